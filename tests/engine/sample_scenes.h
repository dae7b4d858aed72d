// The sample scenes of resources/scenes that the tests run (each in every pose, with every
// integrator, through the energy ledger): every scene file there but the sidecars beside
// them (NAME.convex-parts.json: a scene's kept convex parts, not a scene).
#pragma once

#include <QDir>
#include <QString>
#include <QStringList>

namespace tumble::test {

inline QStringList sampleSceneFiles() {
    QStringList out;
    for (const QString& f : QDir(TUMBLE_SCENES_DIR).entryList({"*.json"}, QDir::Files, QDir::Name))
        if (!f.endsWith(".convex-parts.json")) out << f;
    return out;
}

}  // namespace tumble::test
