// Building a scene quickly (issue 52): new bodies set down where the view looks, Drop to
// Surface, Copy and Paste, Array and Make Stack / Pyramid / Wall, each one undo step.
#include "window/main_window.h"

#include "document/body_presets.h"
#include "document/document.h"
#include "document/placement.h"
#include "panels/scene_tree_dock.h"
#include "viewport/viewport.h"
#include "window/build_dialogs.h"

#include <tumble/io/scene_file.h>
#include <tumble/raycast.h>

#include <QAction>
#include <QClipboard>
#include <QFileInfo>
#include <QGuiApplication>
#include <QMenu>
#include <QMenuBar>
#include <QMimeData>
#include <QSet>
#include <QStatusBar>

#include <algorithm>
#include <functional>
#include <map>

namespace tumble::ui {

namespace {

const QString kBodiesMime = QStringLiteral("application/x-tumble-scene+json");

Vec3 vec(const QVector3D& v) { return Vec3(v.x(), v.y(), v.z()); }

QString nameOf(const BodyDesc& b) { return QString::fromStdString(b.name); }

}  // namespace

void MainWindow::buildSceneMenu(QMenu* edit) {
    // Copy and Paste: window shortcuts; a text field with the focus takes the keys first
    // (its ShortcutOverride), so they copy its text there.
    QAction* copy = edit->addAction(tr("&Copy"), QKeySequence::Copy, this, &MainWindow::copySelection);
    copy->setObjectName("copy");
    QAction* paste = edit->addAction(tr("&Paste"), QKeySequence::Paste, this, &MainWindow::pasteBodies);
    paste->setObjectName("paste");

    QMenu* scene = menuBar()->addMenu(tr("S&cene"));
    scene->setObjectName("sceneMenu");
    scene->addMenu(tree_->addMenu());
    scene->addSeparator();
    QAction* drop = scene->addAction(tr("&Drop to Surface"), QKeySequence(Qt::Key_End), this, &MainWindow::dropSelection);
    drop->setObjectName("dropToSurface");
    drop->setToolTip(tr("Move the selected bodies down along gravity until they touch what is below"));
    QAction* array = scene->addAction(tr("&Array..."), this, &MainWindow::arrayDialog);
    array->setObjectName("array");
    scene->addSeparator();
    const std::pair<Layout, QString> layouts[] = {{Layout::Stack, tr("Make &Stack...")},
                                                  {Layout::Pyramid, tr("Make &Pyramid...")},
                                                  {Layout::Wall, tr("Make &Wall...")}};
    const char* names[] = {"makeStack", "makePyramid", "makeWall"};
    int k = 0;
    for (const auto& [kind, text] : layouts)
        scene->addAction(text, this, [this, kind = kind] { layoutDialog(kind); })->setObjectName(names[k++]);
    // Edit > Box Select: the next drag in the view selects what it encloses.
    QAction* box = edit->addAction(tr("&Box Select"), QKeySequence(Qt::Key_B), this, [this] {
        viewport_->armBoxSelect();
        statusBar()->showMessage(tr("Drag a box in the view to select what it holds (Ctrl adds; Esc gives up)"), 5000);
    });
    box->setObjectName("boxSelect");
    // Edit > Select All of Kind: every body of a shape, or of a motion.
    QMenu* kinds = edit->addMenu(tr("Select All of &Kind"));
    kinds->setObjectName("selectKind");
    const std::pair<ShapeType, QString> shapes[] = {
        {ShapeType::Box, tr("Boxes")},         {ShapeType::Sphere, tr("Spheres")},
        {ShapeType::Capsule, tr("Capsules")},  {ShapeType::Cylinder, tr("Cylinders")},
        {ShapeType::Mesh, tr("Meshes")},       {ShapeType::Compound, tr("Compounds")},
        {ShapeType::Plane, tr("Planes")}};
    auto selectWhere = [this](const std::function<bool(const BodyDesc&)>& kind) {
        QList<int> found;
        for (int i = 0; i < doc_->bodyCount(); ++i)
            if (kind(doc_->body(i))) found.append(i);
        doc_->setSelection(found);
        statusBar()->showMessage(tr("%n bodies selected", nullptr, int(found.size())), 3000);
    };
    for (const auto& [type, text] : shapes)
        kinds->addAction(text, this, [selectWhere, type = type] {
                 selectWhere([type](const BodyDesc& b) { return b.shape.type == type; });
             })->setObjectName(QStringLiteral("select%1").arg(QString::fromUtf8(toString(type))));
    kinds->addSeparator();
    const std::pair<Motion, QString> motions[] = {{Motion::Dynamic, tr("Dynamic Bodies")},
                                                  {Motion::Static, tr("Static Bodies")},
                                                  {Motion::Kinematic, tr("Kinematic Bodies")},
                                                  {Motion::Animated, tr("Animated Bodies")}};
    for (const auto& [motion, text] : motions)
        kinds->addAction(text, this, [selectWhere, motion = motion] {
                 selectWhere([motion](const BodyDesc& b) { return b.motion == motion; });
             })->setObjectName(QStringLiteral("select%1").arg(QString::fromUtf8(toString(motion))));
    auto enable = [this, copy, drop, array] {
        const bool any = !doc_->selection().isEmpty();
        for (QAction* a : {copy, drop, array}) a->setEnabled(any);
    };
    connect(doc_, &Document::selectionChanged, this, enable);
    enable();
    tree_->setPlacement([this](const BodyDesc& b) { return setDownUnderView(b); });
}

void MainWindow::addStandardViews(QMenu* view) {
    QMenu* views = view->addMenu(tr("&Standard Views"));
    struct Side {
        const char* name;
        QString text;
        int key;
        bool opposite;
        float yaw, pitch;  // the camera's place about its target (viewport_camera.h)
    };
    const Side sides[] = {{"viewFront", tr("&Front"), Qt::Key_1, false, 0, 0},
                          {"viewBack", tr("&Back"), Qt::Key_1, true, 180, 0},
                          {"viewRight", tr("&Right"), Qt::Key_3, false, 90, 0},
                          {"viewLeft", tr("&Left"), Qt::Key_3, true, -90, 0},
                          {"viewTop", tr("&Top"), Qt::Key_7, false, 0, 90},
                          {"viewBottom", tr("Botto&m"), Qt::Key_7, true, 0, -90}};
    for (const Side& side : sides) {
        QAction* a = views->addAction(side.text, this, [this, yaw = side.yaw, pitch = side.pitch] {
            viewport_->setCamera(viewport_->cameraTarget(), viewport_->cameraDistance(), yaw, pitch);
        });
        a->setObjectName(side.name);
        const Qt::KeyboardModifiers ctrl = side.opposite ? Qt::ControlModifier : Qt::NoModifier;
        a->setShortcuts({QKeySequence(ctrl | Qt::KeypadModifier | side.key), QKeySequence(ctrl | side.key)});
    }
    views->addSeparator();
    // A parallel projection, toggled (5 on the numpad, as in Blender; or the digit).
    QAction* ortho = views->addAction(tr("&Orthographic"));
    ortho->setObjectName("viewOrthographic");
    ortho->setCheckable(true);
    ortho->setShortcuts({QKeySequence(Qt::KeypadModifier | Qt::Key_5), QKeySequence(Qt::Key_5)});
    ortho->setToolTip(tr("Draw without perspective: parallel lines stay parallel, sizes do not shrink with depth"));
    connect(ortho, &QAction::toggled, viewport_, &Viewport::setOrthographic);
    connect(viewport_, &Viewport::orthographicChanged, ortho, &QAction::setChecked);
}

Vec3 MainWindow::viewPoint(int* hitBody) const {
    const Vec3 eye = vec(viewport_->cameraPosition()), target = vec(viewport_->cameraTarget());
    if (hitBody) *hitBody = -1;
    if ((target - eye).norm() > 0.0) {
        if (const std::optional<RayHit> hit = rayCastScene(doc_->scene(), eye, target - eye)) {
            if (hitBody && doc_->body(hit->body).shape.type != ShapeType::Plane) *hitBody = hit->body;
            return hit->point;
        }
    }
    return target;
}

BodyDesc MainWindow::setDownUnderView(BodyDesc body, const SceneDesc* scene) const {
    int on = -1;
    Vec3 point = viewPoint(&on);
    if (on >= 0) {  // over the body hit, centred on it: adds in a row make a stack
        const Vec3 down = downOf(doc_->scene());
        const Vec3 centre = doc_->body(on).position;
        point = centre + down * down.dot(point - centre);
    }
    return setDownAt(scene ? *scene : doc_->scene(), std::move(body), point);
}

void MainWindow::addBodies(const std::vector<BodyDesc>& bodies, const QString& text) {
    if (bodies.empty()) return;
    QList<int> added;
    doc_->beginMacro(text);
    for (const BodyDesc& b : bodies) added.append(doc_->addBody(b));
    doc_->endMacro();
    doc_->setSelection(added);
}

void MainWindow::dropSelection() {
    const QList<int> selected = doc_->selection();
    if (selected.isEmpty()) return;
    SceneDesc scene = doc_->scene();
    const Vec3 down = downOf(scene);
    std::vector<std::pair<int, BodyDesc>> moved;
    QStringList stayed;
    // The lowest first: a selected body resting on another selected one follows it down.
    std::vector<int> order;
    for (int i : lowestFirst(scene, std::vector<int>(selected.begin(), selected.end()))) {
        const BodyDesc& b = scene.bodies[static_cast<std::size_t>(i)];
        if (b.shape.type == ShapeType::Plane) continue;
        if (b.motion == Motion::Animated) {  // its keys place it; dropping one pose would not
            stayed << tr("%1 is animated (move its keys)").arg(nameOf(b));
            continue;
        }
        order.push_back(i);
    }
    const std::vector<std::optional<double>> falls = dropDistances(scene, order);
    for (std::size_t k = 0; k < order.size(); ++k) {
        BodyDesc& b = scene.bodies[static_cast<std::size_t>(order[k])];
        const std::optional<double>& fall = falls[k];
        if (!fall) {
            stayed << tr("nothing is under %1").arg(nameOf(b));
            continue;
        }
        if (*fall <= 0.0) continue;  // resting already
        b.position += *fall * down;
        moved.emplace_back(order[k], b);
    }
    if (moved.empty()) {
        statusBar()->showMessage(stayed.isEmpty() ? tr("Already resting: nothing to drop")
                                                  : tr("Nothing dropped: %1").arg(stayed.join(tr("; "))),
                                 6000);
        return;
    }
    doc_->beginMacro(moved.size() == 1 ? tr("Drop %1 to surface").arg(nameOf(moved.front().second))
                                       : tr("Drop %n bodies to surface", nullptr, int(moved.size())));
    for (const auto& [i, b] : moved) doc_->setBody(i, b, tr("Drop %1").arg(nameOf(b)));
    doc_->endMacro();
    if (!stayed.isEmpty()) statusBar()->showMessage(tr("Not dropped: %1").arg(stayed.join(tr("; "))), 6000);
}

void MainWindow::copySelection() {
    const QList<int> selected = doc_->selection();
    if (selected.isEmpty()) return;
    const SceneDesc& scene = doc_->scene();
    SceneDesc part;
    part.settings = scene.settings;
    QSet<std::string> names;
    for (int i : selected) {
        part.bodies.push_back(scene.bodies[static_cast<std::size_t>(i)]);
        names.insert(part.bodies.back().name);
    }
    // The joints and kept-apart pairs among them go along (a joint to the world too).
    for (const JointDesc& j : scene.joints)
        if (names.contains(j.bodyA) && (j.bodyB.empty() || names.contains(j.bodyB))) part.joints.push_back(j);
    for (const auto& pair : scene.noCollide)
        if (names.contains(pair[0]) && names.contains(pair[1])) part.noCollide.push_back(pair);
    QString text;
    try {
        text = QString::fromStdString(io::sceneToJson(part));
    } catch (const std::exception& e) {
        statusBar()->showMessage(tr("Cannot copy: %1").arg(QString::fromUtf8(e.what())), 6000);
        return;
    }
    auto* mime = new QMimeData;
    mime->setData(kBodiesMime, text.toUtf8());
    mime->setText(text);
    QGuiApplication::clipboard()->setMimeData(mime);
    copied_ = std::move(part);
    copiedText_ = text;
    statusBar()->showMessage(tr("Copied %n bodies", nullptr, int(selected.size())), 3000);
}

void MainWindow::pasteBodies() {
    const QMimeData* mime = QGuiApplication::clipboard()->mimeData();
    if (!mime) return;
    const QString text = mime->hasFormat(kBodiesMime) ? QString::fromUtf8(mime->data(kBodiesMime)) : mime->text();
    SceneDesc part;
    if (!copiedText_.isEmpty() && text == copiedText_) {
        part = copied_;  // this window's own copy, its meshes' triangles with it
    } else {
        try {  // another window's: its mesh files read beside this scene's
            const QString folder = doc_->filePath().isEmpty() ? QStringLiteral(".") : QFileInfo(doc_->filePath()).absolutePath();
            part = io::parseScene(text.toStdString(), "the clipboard", folder.toStdString());
        } catch (const std::exception& e) {
            statusBar()->showMessage(tr("Nothing to paste: the clipboard holds no Tumble bodies (%1)")
                                         .arg(QString::fromUtf8(e.what())),
                                     6000);
            return;
        }
    }
    if (part.bodies.empty()) return;
    // Beside the originals: moved sideways on the screen by the copies' width and 0.1 m.
    const Vec3 down = downOf(doc_->scene());
    Vec3 right = (vec(viewport_->cameraTarget()) - vec(viewport_->cameraPosition())).cross(-down);
    right = right.norm() > 0.0 ? Vec3(right.normalized()) : Vec3(Vec3::UnitX());
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (const BodyDesc& b : part.bodies) {
        const double at = b.position.dot(right), reach = halfSize(b).cwiseProduct(right.cwiseAbs()).sum();
        lo = std::min(lo, at - reach);
        hi = std::max(hi, at + reach);
    }
    const Vec3 offset = (hi - lo + 0.1) * right;
    // A collision group this scene does not have: the copy goes in "default", and says so.
    QStringList regrouped;
    const std::vector<std::string>& groups = doc_->scene().settings.collisionGroups;
    QList<int> added;
    std::map<std::string, std::string> renamed;
    doc_->beginMacro(tr("Paste %n bodies", nullptr, int(part.bodies.size())));
    for (BodyDesc b : part.bodies) {
        if (b.collisionGroup != "default" && std::find(groups.begin(), groups.end(), b.collisionGroup) == groups.end()) {
            regrouped << QString::fromStdString(b.collisionGroup);
            b.collisionGroup = "default";
        }
        b.position += offset;
        for (BodyKey& key : b.keys) key.position += offset;
        const std::string was = b.name;
        const int index = doc_->addBody(b);
        renamed[was] = doc_->body(index).name;
        added.append(index);
    }
    for (JointDesc j : part.joints) {
        j.bodyA = renamed[j.bodyA];
        if (!j.bodyB.empty()) j.bodyB = renamed[j.bodyB];
        else j.anchorB += offset;  // a world anchor moves with the copies
        doc_->addJoint(j);
    }
    doc_->endMacro();
    doc_->setSelection(added);
    if (!regrouped.isEmpty())
        statusBar()->showMessage(tr("Pasted into the default collision group: this scene has no group %1")
                                     .arg(regrouped.join(", ")),
                                 6000);
}

void MainWindow::arrayDialog() {
    const QList<int> selected = doc_->selection();
    if (selected.isEmpty()) return;
    Vec3 lo = Vec3::Constant(HUGE_VAL), hi = Vec3::Constant(-HUGE_VAL);
    for (int i : selected) {
        const BodyDesc& b = doc_->body(i);
        lo = lo.cwiseMin(b.position - halfSize(b));
        hi = hi.cwiseMax(b.position + halfSize(b));
    }
    ArrayDialog dialog(hi - lo, static_cast<int>(selected.size()), this);
    if (dialog.exec() != QDialog::Accepted) return;
    const std::vector<Vec3> places = arrayPlaces(Vec3::Zero(), dialog.counts(), dialog.steps());
    std::vector<BodyDesc> copies;
    for (std::size_t p = 1; p < places.size(); ++p)
        for (int i : selected) {
            BodyDesc b = doc_->body(i);
            b.position += places[p];
            for (BodyKey& key : b.keys) key.position += places[p];
            copies.push_back(std::move(b));
        }
    addBodies(copies, tr("Array of %n bodies", nullptr, int(copies.size())));
    viewport_->frameSelection();  // (it may reach far past the view)
}

void MainWindow::layoutDialog(Layout kind) {
    LayoutDialog dialog(kind, this);
    if (dialog.exec() != QDialog::Accepted) return;
    const LayoutSpec spec = dialog.spec();
    const Vec3 down = downOf(doc_->scene());
    const Quat upright = uprightFor(down);
    const std::vector<Vec3> centres = layoutCentres(spec);
    if (centres.empty()) return;
    // The layout set down as a whole where the view looks (as one box holding it: on a body,
    // centred on it), then each box in it.
    Vec3 lo = Vec3::Constant(HUGE_VAL), hi = Vec3::Constant(-HUGE_VAL);
    for (const Vec3& c : centres) {
        lo = lo.cwiseMin(c - spec.halfExtents);
        hi = hi.cwiseMax(c + spec.halfExtents);
    }
    BodyDesc whole = presetBody(ShapeType::Box, doc_->scene());
    whole.shape.halfExtents = 0.5 * (hi - lo);
    whole.orientation = upright;
    const Vec3 base = setDownUnderView(whole).position - upright * (0.5 * (hi + lo));
    const char* base_name = kind == Layout::Stack ? "stack" : kind == Layout::Pyramid ? "pyramid" : "wall";
    std::vector<BodyDesc> boxes;
    for (const Vec3& c : centres) {
        BodyDesc b = presetBody(ShapeType::Box, doc_->scene());
        b.name = base_name;
        b.shape.halfExtents = spec.halfExtents;
        b.mass = dialog.mass();
        b.density.reset();
        b.orientation = upright;
        b.position = base + upright * c;
        boxes.push_back(std::move(b));
    }
    addBodies(boxes, dialog.windowTitle().remove("&") + tr(" of %n boxes", nullptr, int(boxes.size())));
    viewport_->frameSelection();
}

}  // namespace tumble::ui
