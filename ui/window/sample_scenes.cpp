#include "window/sample_scenes.h"

#include <QCoreApplication>
#include <QDir>
#include <QFile>
#include <QRegularExpression>

#include <algorithm>

namespace tumble::ui {

namespace {

const char* const kCompiledIn[] = {"tumbling-box",
                                   "spring-pendulum",
                                   "projectile",
                                   "bouncing-ball",
                                   "head-on",
                                   "tilted-box-impact",
                                   "newtons-cradle",
                                   "newtons-cradle-strings",
                                   "chain",
                                   "hinged-door",
                                   "ragdoll",
                                   "sliding-block",
                                   "incline",
                                   "rolling-sphere",
                                   "tower-20",
                                   "pyramid-15",
                                   "mass-ratio-stack",
                                   "sleeping-wake",
                                   "table",
                                   "chair",
                                   "hammer",
                                   "cart",
                                   "chair-pile",
                                   "sieve",
                                   "paddle-dominoes",
                                   "lift",
                                   "turntable",
                                   "ragdoll-stairs",
                                   "robot-arm",
                                   "suspension-cart",
                                   "tilt-platform"};

bool isScene(const QString& path) {
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly)) return false;
    static const QRegularExpression format(R"re("format"\s*:\s*"tumble-scene")re");
    return format.match(QString::fromUtf8(f.read(4096))).hasMatch();
}

}  // namespace

QString samplesFolder() {
    // (ui/CMakeLists.txt: the installed folder relative to bin/, and the source tree's.)
    const QDir installed(QCoreApplication::applicationDirPath() + "/" + TUMBLE_SCENES_FROM_BIN);
    if (installed.exists()) return installed.canonicalPath();
    const QDir source(TUMBLE_SOURCE_SCENES);
    return source.exists() ? source.canonicalPath() : QString();
}

std::vector<SampleScene> sampleScenes() {
    std::vector<SampleScene> out;
    for (const char* name : kCompiledIn) out.push_back({name, QStringLiteral(":/scenes/%1.json").arg(name)});
    const QString folder = samplesFolder();
    if (folder.isEmpty()) return out;
    const auto compiled = std::size_t(std::size(kCompiledIn));
    const QFileInfoList files = QDir(folder).entryInfoList({"*.json"}, QDir::Files, QDir::Name);
    for (const QFileInfo& f : files) {
        QString name = f.fileName();
        name.chop(5);  // ".json"
        const bool known = std::any_of(out.begin(), out.begin() + compiled,
                                       [&](const SampleScene& s) { return s.name == name; });
        if (!known && isScene(f.filePath())) out.push_back({name, f.filePath()});
    }
    return out;
}

}  // namespace tumble::ui
