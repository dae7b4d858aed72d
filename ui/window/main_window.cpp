#include "window/main_window.h"

#include "panels/collision_groups_dialog.h"

#include "import/mesh_import_job.h"

#include "document/body_keys.h"
#include "document/document.h"
#include "document/joint_presets.h"
#include "editor_main.h"
#include "panels/plots_dock.h"
#include "panels/property_dock.h"
#include "panels/scene_tree_dock.h"
#include "panels/settings_dock.h"
#include "timeline/timeline.h"
#include "timeline/timeline_dock.h"
#include "viewport/viewport.h"
#include "window/autosave.h"
#include "window/manual_dialog.h"
#include "window/sample_scenes.h"
#include "window/shortcuts_dialog.h"
#include "window/sticky_menu.h"

#include <tumble/io/atomic_file.h>
#include <tumble/io/mesh_import.h>
#include <tumble/io/scene_file.h>

#include <QAbstractButton>
#include <QAction>
#include <QActionGroup>
#include <QApplication>
#include <QCloseEvent>
#include <QDir>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QLocale>
#include <QMenuBar>
#include <QMessageBox>
#include <QMetaEnum>
#include <QMimeData>
#include <QProcess>
#include <QPushButton>
#include <QSettings>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTimer>
#include <QUndoStack>
#include <QUndoView>

#include <malloc.h>

namespace tumble::ui {

namespace {

bool isSceneFile(const QString& path) {
    return path.endsWith(".json", Qt::CaseInsensitive);
}

}  // namespace

MainWindow::MainWindow(QWidget* parent) : QMainWindow(parent), doc_(new Document(this)) {
    setObjectName("MainWindow");
    timeline_ = new Timeline(doc_, this);
    viewport_ = new Viewport(doc_, this);
    viewport_->setTimeline(timeline_);
    setCentralWidget(viewport_);

    tree_ = new SceneTreeDock(doc_, this);
    auto* tree = tree_;
    tree->setObjectName("SceneTreeDock");
    addDockWidget(Qt::LeftDockWidgetArea, tree);
    connect(tree, &SceneTreeDock::importMeshRequested, this, &MainWindow::importDialog);

    auto* properties = new PropertyDock(doc_, this);
    properties->setObjectName("PropertyDock");
    properties->setTimeline(timeline_);
    addDockWidget(Qt::RightDockWidgetArea, properties);

    auto* settings = new SettingsDock(doc_, this);
    settings->setObjectName("SettingsDock");
    addDockWidget(Qt::RightDockWidgetArea, settings);
    tabifyDockWidget(properties, settings);

    auto* history = new QDockWidget(tr("Undo History"), this);
    history->setObjectName("UndoHistoryDock");
    history->setWidget(new QUndoView(doc_->undoStack(), history));
    addDockWidget(Qt::LeftDockWidgetArea, history);

    timelineDock_ = new TimelineDock(timeline_, this);
    addDockWidget(Qt::BottomDockWidgetArea, timelineDock_);
    auto* plots = new PlotsDock(timeline_, this);
    plots->setObjectName("PlotsDock");
    addDockWidget(Qt::RightDockWidgetArea, plots);
    tabifyDockWidget(settings, plots);
    properties->raise();

    buildMenus();
    setAcceptDrops(true);
    connect(doc_, &Document::fileStateChanged, this, &MainWindow::updateTitle);
    statusBar();

    autosave_ = std::make_unique<Autosave>();
    startEditor = [](const QStringList& args) {
        return QProcess::startDetached(QCoreApplication::applicationFilePath(), args);
    };
    autosaveTimer_ = new QTimer(this);
    autosaveTimer_->setInterval(60 * 1000);
    connect(autosaveTimer_, &QTimer::timeout, this, &MainWindow::autosave);
    autosaveTimer_->start();

    resize(1280, 800);
    // Room for three-component fields with their units in the properties.
    resizeDocks({properties, tree}, {440, 260}, Qt::Horizontal);
    QSettings s;
    restoreGeometry(s.value("window/geometry").toByteArray());
    restoreState(s.value("window/state").toByteArray());
    updateTitle();
}

MainWindow::~MainWindow() {
    delete importJob_;  // stops a read still running before the document goes
    // A field closed with the window commits its edit (its focus out) while the widgets go:
    // the document's signals must not reach this half-destroyed window then (UBSan: a
    // rename typed and not entered, the window closed).
    doc_->disconnect(this);
    if (timeline_) timeline_->disconnect(this);
}

const SceneDesc& MainWindow::scene() const {
    return doc_->scene();
}

QString MainWindow::defaultScenePath() {
    return QStringLiteral(":/scenes/tumbling-box.json");
}

void MainWindow::buildMenus() {
    QMenu* file = menuBar()->addMenu(tr("&File"));
    file->addAction(tr("&New"), QKeySequence::New, this, &MainWindow::newScene);
    file->addAction(tr("&Open..."), QKeySequence::Open, this, &MainWindow::openDialog);
    recentMenu_ = file->addMenu(tr("Open &Recent"));
    connect(recentMenu_, &QMenu::aboutToShow, this, &MainWindow::fillRecentMenu);
    QMenu* samples = file->addMenu(tr("&Samples"));
    // The compiled-in samples, then the installed ones with meshes beside them (sample_scenes.h).
    samples->setObjectName("samplesMenu");
    bool compiled = true;
    for (const SampleScene& sample : sampleScenes()) {
        if (compiled && !sample.path.startsWith(':')) samples->addSeparator();
        compiled = sample.path.startsWith(':');
        samples->addAction(sample.name, this, [this, path = sample.path] { openPath(path); })->setData(sample.path);
    }
    file->addSeparator();
    file->addAction(tr("&Save"), QKeySequence::Save, this, &MainWindow::save)->setObjectName("fileSave");
    file->addAction(tr("Save &As..."), QKeySequence::SaveAs, this, &MainWindow::saveAsDialog);
    file->addAction(tr("Save with &Meshes..."), this, &MainWindow::saveWithMeshesDialog);
    file->addAction(tr("Re&vert"), this, &MainWindow::revert);
    file->addSeparator();
    file->addAction(tr("&Import Mesh..."), QKeySequence(tr("Ctrl+I")), this, &MainWindow::importDialog);
    file->addAction(tr("&Export..."), QKeySequence(tr("Ctrl+E")), this, &MainWindow::exportDialog);
    file->addSeparator();
    file->addAction(tr("&Quit"), QKeySequence::Quit, this, &QWidget::close);

    QMenu* edit = menuBar()->addMenu(tr("&Edit"));
    QAction* undo = doc_->undoStack()->createUndoAction(this, tr("&Undo"));
    undo->setShortcut(QKeySequence::Undo);
    QAction* redo = doc_->undoStack()->createRedoAction(this, tr("&Redo"));
    redo->setShortcut(QKeySequence::Redo);
    edit->addAction(undo);
    edit->addAction(redo);
    edit->addSeparator();
    // The scene tree's own actions (their shortcuts live there; a second action with the
    // same key would make both ambiguous).
    edit->addMenu(tree_->addMenu());
    edit->addMenu(tree_->partMenu());
    edit->addAction(tree_->duplicateAction());
    edit->addAction(tree_->deleteAction());
    edit->addAction(tree_->renameAction());
    edit->addAction(tree_->groupAction());
    edit->addAction(tree_->ungroupAction());
    edit->addAction(tree_->splitAction());
    edit->addMenu(tree_->jointMenu());
    // Pairs of single bodies kept apart (the file's no_collide), for two or more selected.
    QAction* apart = edit->addAction(tr("&Keep Selected Apart"), this,
                                     [this] { doc_->keepApart(doc_->selection(), true); });
    apart->setObjectName("keepApart");
    QAction* collide = edit->addAction(tr("&Let Selected Collide"), this,
                                       [this] { doc_->keepApart(doc_->selection(), false); });
    collide->setObjectName("letCollide");
    auto enablePairs = [this, apart, collide] {
        apart->setEnabled(doc_->selection().size() >= 2);
        collide->setEnabled(doc_->selection().size() >= 2);
    };
    connect(doc_, &Document::selectionChanged, this, enablePairs);
    enablePairs();
    QAction* key = edit->addAction(tr("Insert &Key"), QKeySequence(Qt::Key_I), this, &MainWindow::insertKey);
    key->setObjectName("insertKey");
    key->setToolTip(tr("Key the selected body's pose at the playhead (it becomes animated)"));
    connect(viewport_, &Viewport::insertKeyRequested, this, &MainWindow::insertKey);
    // The selected animated body's keys, ticked on the timeline.
    auto showKeys = [this] {
        const QList<int>& sel = doc_->selection();
        std::vector<double> times;
        QString name;
        if (sel.size() == 1 && doc_->body(sel.front()).motion == Motion::Animated) {
            const BodyDesc& b = doc_->body(sel.front());
            for (const BodyKey& k : b.keys) times.push_back(k.time);
            name = QString::fromStdString(b.name);
        }
        timelineDock_->setKeyTimes(times, name);
    };
    for (auto signal : {&Document::selectionChanged, &Document::sceneReset})
        connect(doc_, signal, this, showKeys);
    connect(doc_, &Document::bodyChanged, this, showKeys);
    connect(timeline_, &Timeline::recordingReset, this, showKeys);
    // A key's tick dragged on the timeline moves the key (refused onto another key's time);
    // a right click deletes it (the last key stays).
    auto keyedBody = [this]() -> int {
        const QList<int>& sel = doc_->selection();
        return sel.size() == 1 && doc_->body(sel.front()).motion == Motion::Animated ? sel.front() : -1;
    };
    connect(timelineDock_, &TimelineDock::keyMoved, this, [this, keyedBody, showKeys](int key, double time) {
        const int i = keyedBody();
        if (i < 0 || key >= int(doc_->body(i).keys.size())) return;
        BodyDesc b = doc_->body(i);
        if (!moveKey(b, key, time)) {
            statusBar()->showMessage(tr("A key is already at t = %1 s").arg(time, 0, 'g', 6), 4000);
            showKeys();  // the tick back where its key is
            return;
        }
        doc_->setBody(i, b, tr("Move key"));
    });
    connect(timelineDock_, &TimelineDock::keyDeleteRequested, this, [this, keyedBody](int key) {
        const int i = keyedBody();
        if (i < 0) return;
        BodyDesc b = doc_->body(i);
        if (!removeKey(b, key)) {
            statusBar()->showMessage(tr("An animated body keeps at least one key"), 4000);
            return;
        }
        doc_->setBody(i, b, tr("Delete key"));
    });
    edit->addAction(tr("Select &All"), QKeySequence::SelectAll, this, [this] {
        QList<int> all;
        for (int i = 0; i < doc_->bodyCount(); ++i) all.append(i);
        doc_->setSelection(all);
    });

    buildSceneMenu(edit);  // and Copy, Paste (main_window_build.cpp)

    // The timeline's keys (Space, Left, Right, Home, Ctrl+End) work anywhere in the window; a
    // text field that has the focus keeps its own use of them.
    QMenu* simulation = menuBar()->addMenu(tr("&Simulation"));
    simulation->addAction(timelineDock_->simulateAction());
    simulation->addAction(timelineDock_->cancelAction());
    simulation->addSeparator();
    for (QAction* a :
         {timelineDock_->playAction(), timelineDock_->stepBackAction(), timelineDock_->stepForwardAction(),
          timelineDock_->toStartAction(), timelineDock_->toEndAction(), timelineDock_->loopAction()})
        simulation->addAction(a);
    simulation->addSeparator();
    simulation->addAction(timelineDock_->useFrameAction());
    simulation->addSeparator();
    simulation
        ->addAction(tr("Collision &Groups..."), this,
                    [this] {
                        CollisionGroupsDialog dialog(doc_, this);
                        dialog.exec();
                    })
        ->setObjectName("collisionGroups");

    QMenu* view = menuBar()->addMenu(tr("&View"));
    // The viewport's keys (F, A, W, E; I in the Edit menu) as window shortcuts: they work
    // wherever the focus is in the window (after a click in the Scene list, an Add, a
    // click on a body), except in a text or number field, which takes a letter for its
    // text first (its ShortcutOverride).
    view->addAction(tr("&Frame Selection"), QKeySequence(Qt::Key_F), this, [this] { viewport_->frameSelection(); })
        ->setObjectName("frameSelection");
    view->addAction(tr("Frame &All"), QKeySequence(Qt::Key_A), this, [this] { viewport_->frameAll(); })
        ->setObjectName("frameAll");
    addStandardViews(view);  // Front, Right, Top and their opposites (main_window_build.cpp)
    view->addSeparator();
    auto* modes = new QActionGroup(this);
    QAction* move = view->addAction(tr("&Move Handles"), QKeySequence(Qt::Key_W), this,
                                    [this] { viewport_->setTransformMode(Viewport::TransformMode::Move); });
    move->setObjectName("moveHandles");
    QAction* rotate = view->addAction(tr("&Rotate Handles"), QKeySequence(Qt::Key_E), this, [this] {
        viewport_->setTransformMode(Viewport::TransformMode::Rotate);
    });
    rotate->setObjectName("rotateHandles");
    for (QAction* a : {move, rotate}) a->setCheckable(true), modes->addAction(a);
    move->setChecked(viewport_->transformMode() == Viewport::TransformMode::Move);
    rotate->setChecked(!move->isChecked());
    connect(viewport_, &Viewport::transformModeChanged, this, [move, rotate](Viewport::TransformMode m) {
        move->setChecked(m == Viewport::TransformMode::Move);
        rotate->setChecked(m == Viewport::TransformMode::Rotate);
    });
    QAction* snap = view->addAction(tr("S&nap Handles (0.1 m, 15°)"));
    snap->setCheckable(true);
    snap->setChecked(viewport_->snapping());
    connect(snap, &QAction::toggled, viewport_, &Viewport::setSnapping);
    QAction* shapes = view->addAction(tr("Show &Collision Shapes"));
    shapes->setCheckable(true);
    shapes->setChecked(viewport_->showCollisionShapes());
    connect(shapes, &QAction::toggled, viewport_, &Viewport::setShowCollisionShapes);
    // Overlays of the simulation at the playhead, each computed only while shown; the menu
    // stays open while they are ticked, and Alt+1 ... Alt+8 switch them from anywhere.
    auto* overlays = new StickyMenu(tr("&Overlays"), view);
    view->addMenu(overlays);
    for (int i = 0; i < Viewport::kOverlayCount; ++i) {
        const auto which = static_cast<Viewport::Overlay>(i);
        QAction* a = overlays->addAction(Viewport::overlayText(which));
        a->setObjectName(QStringLiteral("overlay%1").arg(i));
        a->setCheckable(true);
        a->setShortcut(QKeySequence(Qt::ALT | Qt::Key(Qt::Key_1 + i)));
        const QString key =
            QStringLiteral("view/overlay/%1").arg(QMetaEnum::fromType<Viewport::Overlay>().key(i));
        viewport_->setOverlay(which, QSettings().value(key, viewport_->overlay(which)).toBool());
        a->setChecked(viewport_->overlay(which));
        connect(a, &QAction::toggled, viewport_, [this, which, key](bool on) {
            viewport_->setOverlay(which, on);
            QSettings().setValue(key, on);  // the user's choice for the next session
        });
        connect(viewport_, &Viewport::overlayChanged, a, [a, which](Viewport::Overlay o, bool on) {
            if (o == which) a->setChecked(on);
        });
    }
    view->addSeparator();
    for (QDockWidget* dock : findChildren<QDockWidget*>()) view->addAction(dock->toggleViewAction());

    QMenu* help = menuBar()->addMenu(tr("&Help"));
    help->addAction(tr("&Keyboard Shortcuts"), QKeySequence::HelpContents, this, &MainWindow::showShortcuts)
        ->setObjectName(QStringLiteral("helpShortcuts"));
    help->addAction(tr("&Manual"), this, [this] { (new ManualDialog(this))->show(); })->setObjectName("manual");
    help->addAction(tr("&About Tumble"), this, [this] {
        QMessageBox::about(this, tr("About Tumble"),
                           tr("<b>Tumble %1</b><p>A rigid-body dynamics editor: place bodies, tune them, "
                              "simulate, play and export.</p><p>docs/editor.md describes the window.</p>")
                               .arg(QApplication::applicationVersion()));
    });
}

QList<ShortcutRow> MainWindow::shortcuts() const {
    QList<ShortcutRow> rows = shortcutRows(menuBar());
    // The viewport's camera keys, which no menu holds (viewport.cpp, handleKey).
    const QString viewport = tr("Viewport");
    rows.append({viewport, tr("Orbit"), tr("Shift+Arrow keys (Up and Down alone too)")});
    rows.append({viewport, tr("Zoom in / out"), tr("+ / -")});
    rows.append({viewport, tr("Cancel a handle drag"), tr("Esc")});
    return rows;
}

void MainWindow::showShortcuts() {
    ShortcutsDialog dialog(shortcuts(), this);
    dialog.exec();
}

QString MainWindow::sceneName() const {
    if (doc_->filePath().isEmpty() && source_.startsWith(":/")) return QFileInfo(source_).fileName();
    return doc_->displayName();
}

void MainWindow::updateTitle() {
    setWindowTitle(tr("%1[*] - Tumble").arg(sceneName()));
    setWindowModified(doc_->isModified());
}

bool MainWindow::openScene(const QString& path, QString* error) {
    if (!doc_->open(path, error)) return false;
    source_ = path;
    if (!path.startsWith(":/")) addRecent(path);
    updateTitle();
    viewport_->frameAll();
    return true;
}

void MainWindow::insertKey() {
    if (const int joint = doc_->selectedJoint(); joint >= 0) {  // a servo's target
        JointDesc j = doc_->joint(joint);
        const double time = timeline_->currentFrame() / doc_->scene().settings.frameRate;
        if (!insertServoKey(j, time)) {
            statusBar()->showMessage(tr("Insert Key: this joint has no servo to key"), 4000);
            return;
        }
        doc_->setJoint(joint, j, tr("Insert servo key"));
        statusBar()->showMessage(
            tr("Keyed %1's servo at t = %2 s").arg(QString::fromStdString(j.name)).arg(time, 0, 'g', 6), 3000);
        return;
    }
    const QList<int>& selection = doc_->selection();
    if (selection.size() != 1) {
        statusBar()->showMessage(tr("Insert Key: select one body"), 4000);
        return;
    }
    const int index = selection.front();
    BodyDesc body = doc_->body(index);
    if (body.shape.type == ShapeType::Plane) {
        statusBar()->showMessage(tr("Insert Key: a plane cannot move"), 4000);
        return;
    }
    double time = 0.0;
    Vec3 position = body.position;
    Quat orientation = body.orientation;
    const int frame = timeline_->currentFrame();
    if (frame > 0) {
        // The pose the run has at the playhead: of this scene's run, recorded that far.
        State state;
        const auto model = timeline_->model();
        if (timeline_->isStale() || !model || !timeline_->frameState(frame, &state) ||
            index >= int(state.bodies.size())) {
            statusBar()->showMessage(tr("Insert Key: the run has not reached frame %1 since the last edit; "
                                        "key it when the timeline has it")
                                         .arg(frame),
                                     5000);
            return;
        }
        time = state.time;
        position = bodyFramePosition(model->bodies[size_t(index)], state.bodies[size_t(index)]);
        orientation = state.bodies[size_t(index)].q;
        // A body made animated here starts where it was placed: its first key at t = 0.
        if (body.motion != Motion::Animated) ui::insertKey(body, 0.0, body.position, body.orientation);
    }
    ui::insertKey(body, time, position, orientation);
    doc_->setBody(index, body, tr("Insert key"));
    statusBar()->showMessage(
        tr("Keyed %1 at t = %2 s").arg(QString::fromStdString(body.name)).arg(time, 0, 'g', 6), 3000);
}

void MainWindow::openPath(const QString& path) {
    if (!maybeSave()) return;
    QString error;
    if (!openScene(path, &error))
        QMessageBox::warning(this, tr("Open scene"), error);
    else if (!doc_->openWarnings().isEmpty())
        QMessageBox::warning(
            this, tr("Open scene"),
            tr("The scene opened, but these meshes could not be read; their bodies are marked in "
               "red in the scene tree and the scene cannot be simulated until they are back:\n\n%1")
                .arg(doc_->openWarnings().join("\n")));
}

bool MainWindow::maybeSave() {
    if (!doc_->isModified()) return true;
    const auto answer = QMessageBox::warning(
        this, tr("Unsaved changes"), tr("%1 has unsaved changes. Save them?").arg(sceneName()),
        QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel, QMessageBox::Save);
    if (answer == QMessageBox::Cancel) return false;
    if (answer == QMessageBox::Save) return save();
    return true;
}

void MainWindow::newScene() {
    if (!maybeSave()) return;
    doc_->newScene();
    source_.clear();
    updateTitle();
}

void MainWindow::openDialog() {
    const QString path =
        QFileDialog::getOpenFileName(this, tr("Open scene"), QString(), tr("Tumble scenes (*.json)"));
    if (!path.isEmpty()) openPath(path);
}

bool MainWindow::save() {
    if (doc_->filePath().isEmpty()) return saveAsDialog();
    QString error;
    if (!doc_->saveAs(doc_->filePath(), &error)) {
        QMessageBox::warning(this, tr("Save"), error);
        return false;
    }
    autosave_->remove();
    statusBar()->showMessage(tr("Saved %1").arg(doc_->filePath()), 3000);
    warnOfChangedMeshes();
    return true;
}

void MainWindow::warnOfChangedMeshes() {
    const QStringList changed = doc_->meshFilesChangedOnDisk();
    if (changed.isEmpty()) return;
    QMessageBox::warning(
        this, tr("Save"),
        tr("%1 was saved, but these mesh files are gone or changed on disk since the scene read "
           "them:\n\n%2\n\n"
           "While it is open the scene keeps the meshes as it read them. The saved file refers to the files, "
           "so opened again it reads them as they are now (a removed one will be missing). Put the files "
           "back "
           "to keep the meshes you see.")
            .arg(QFileInfo(doc_->filePath()).fileName(), changed.join('\n')));
}

QString MainWindow::askSceneFile(const QString& title) {
    // A name typed without an extension gets ".json" (the Open dialog's filter hid a scene
    // saved as "my-scene"), and the dialog asks before replacing the file of that name.
    QFileDialog dialog(this, title, doc_->filePath(), tr("Tumble scenes (*.json)"));
    dialog.setAcceptMode(QFileDialog::AcceptSave);
    dialog.setDefaultSuffix(QStringLiteral("json"));
    if (dialog.exec() != QDialog::Accepted || dialog.selectedFiles().isEmpty()) return QString();
    return dialog.selectedFiles().first();
}

bool MainWindow::saveAsDialog() {
    const QString path = askSceneFile(tr("Save scene as"));
    if (path.isEmpty()) return false;
    QString error;
    if (!doc_->saveAs(path, &error)) {
        QMessageBox::warning(this, tr("Save"), error);
        return false;
    }
    source_ = path;
    addRecent(path);
    autosave_->remove();
    updateTitle();
    warnOfChangedMeshes();
    return true;
}

void MainWindow::revert() {
    if (source_.isEmpty() || !doc_->isModified()) return;
    if (QMessageBox::question(this, tr("Revert"), tr("Discard the changes and reload %1?").arg(source_)) !=
        QMessageBox::Yes)
        return;
    QString error;
    if (!openScene(source_, &error)) QMessageBox::warning(this, tr("Revert"), error);
}

void MainWindow::addRecent(const QString& path) {
    QSettings s;
    QStringList recent = s.value("recentFiles").toStringList();
    recent.removeAll(path);
    recent.prepend(path);
    while (recent.size() > 10) recent.removeLast();
    s.setValue("recentFiles", recent);
}

void MainWindow::fillRecentMenu() {
    recentMenu_->clear();
    const QStringList recent = QSettings().value("recentFiles").toStringList();
    for (const QString& path : recent) recentMenu_->addAction(path, this, [this, path] { openPath(path); });
    recentMenu_->setEnabled(!recent.isEmpty());
}

QString MainWindow::autosavePath() const {
    return autosave_->file();
}

void MainWindow::autosave() {
    if (!doc_->isModified()) {
        autosave_->remove();
        return;
    }
    // A failed write keeps the previous autosave; the user is told, and the message stays
    // until an autosave succeeds again (their work is not protected meanwhile).
    QString error;
    if (!autosave_->write(doc_->scene(), doc_->filePath(), &error)) {
        autosaveFailure_ =
            tr("Autosave failed: %1. Save your work: unsaved changes would be lost in a crash.").arg(error);
        statusBar()->showMessage(autosaveFailure_);
    } else if (!autosaveFailure_.isEmpty()) {
        if (statusBar()->currentMessage() == autosaveFailure_) statusBar()->clearMessage();
        autosaveFailure_.clear();
    }
}

void MainWindow::offerRecovery() {
    for (const AutosaveLeftover& l : Autosave::leftovers()) {
        const QString when = QLocale().toString(l.savedAt, QLocale::ShortFormat);
        const QString what =
            l.scenePath.isEmpty()
                ? tr("Tumble did not close cleanly. Unsaved changes to an untitled scene were autosaved on "
                     "%1.")
                      .arg(when)
                : tr("Tumble did not close cleanly. Unsaved changes to %1 (in %2) were autosaved on %3.")
                      .arg(QFileInfo(l.scenePath).fileName(),
                           QDir::toNativeSeparators(QFileInfo(l.scenePath).absolutePath()), when);
        QMessageBox box(QMessageBox::Question, tr("Recover"), what, QMessageBox::NoButton, this);
        box.setInformativeText(
            tr("Recover opens them as that scene, unsaved (in a new window if this one holds another scene). "
               "Discard deletes them. Later keeps them and asks again at the next start."));
        QAbstractButton* recoverButton = box.addButton(tr("Recover"), QMessageBox::AcceptRole);
        QAbstractButton* discardButton = box.addButton(tr("Discard"), QMessageBox::DestructiveRole);
        box.addButton(tr("Later"), QMessageBox::RejectRole);
        box.setDefaultButton(qobject_cast<QPushButton*>(recoverButton));
        box.exec();
        QString error;
        if (box.clickedButton() == recoverButton && !recover(l, &error))
            QMessageBox::warning(this, tr("Recover"), error);
        else if (box.clickedButton() == discardButton)
            Autosave::discard(l);
    }
}

namespace {

bool sameFile(const QString& a, const QString& b) {
    return !a.isEmpty() && !b.isEmpty() && QFileInfo(a).absoluteFilePath() == QFileInfo(b).absoluteFilePath();
}

}  // namespace

bool MainWindow::recover(const AutosaveLeftover& leftover, QString* error) {
    const bool here =
        !doc_->isModified() && (doc_->filePath().isEmpty() || sameFile(doc_->filePath(), leftover.scenePath));
    if (here) return recoverHere(leftover, error);
    if (!startEditor({QStringLiteral("--recover"), leftover.file})) {
        if (error) *error = tr("%1: another editor could not be started to recover it").arg(leftover.file);
        return false;
    }
    return true;  // that editor takes the leftover (and removes it once it holds it)
}

bool MainWindow::recoverHere(const AutosaveLeftover& leftover, QString* error) {
    SceneDesc scene;
    if (!Autosave::read(leftover, &scene, error)) return false;
    // The file as it is on disk first, so that undo goes back to it; untitled, or that path
    // without its content if the file is gone.
    QString ignored;
    if (leftover.scenePath.isEmpty() || !doc_->open(leftover.scenePath, &ignored)) {
        doc_->newScene();
        doc_->setFilePath(leftover.scenePath);
    }
    source_ = leftover.scenePath;
    doc_->replaceScene(scene, tr("Recover unsaved scene"), true);
    updateTitle();
    autosave();  // this editor's own autosave holds it now
    Autosave::discard(leftover);
    return true;
}

bool MainWindow::recoverAutosave(QString* error) {
    const QList<AutosaveLeftover> all = Autosave::leftovers();
    if (all.isEmpty()) {
        if (error) *error = tr("No autosave to recover");
        return false;
    }
    return recover(all.first(), error);
}

bool MainWindow::recoverFile(const QString& file, QString* error) {
    AutosaveLeftover leftover;
    return Autosave::describe(file, &leftover, error) && recoverHere(leftover, error);
}

void MainWindow::closeEvent(QCloseEvent* event) {
    if (!maybeSave()) {
        event->ignore();
        return;
    }
    autosave_->remove();  // a clean end: nothing to recover
    QSettings s;
    s.setValue("window/geometry", saveGeometry());
    s.setValue("window/state", saveState());
    event->accept();
}

// Only local scene and mesh files are taken; anything else shows no drop cursor.
void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
    for (const QUrl& url : event->mimeData()->urls()) {
        const QString path = url.toLocalFile();
        if (!path.isEmpty() && (isSceneFile(path) || isMeshFile(path))) {
            event->acceptProposedAction();
            return;
        }
    }
}

// A dropped scene opens (the first one; meshes beside it are ignored). Dropped meshes are
// imported together as one undo step.
void MainWindow::dropEvent(QDropEvent* event) {
    QStringList meshes;
    for (const QUrl& url : event->mimeData()->urls()) {
        const QString path = url.toLocalFile();
        if (path.isEmpty()) continue;
        if (isSceneFile(path)) {
            event->acceptProposedAction();
            openPath(path);
            return;
        }
        if (isMeshFile(path)) meshes << path;
    }
    if (meshes.isEmpty()) return;
    event->acceptProposedAction();
    startImport(meshes, true, 1.0);
}

void keepFrameMemory() {
    // Below 32 MB from the heap, and up to 64 MB freed at its top kept (glibc's own
    // thresholds rise to these only after the first large free).
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 64 << 20);
}

int runEditor(int argc, char** argv) {
    keepFrameMemory();
    QApplication app(argc, argv);
    QApplication::setApplicationName("Tumble");
    QApplication::setOrganizationName("Tumble");
    MainWindow window;
    const QStringList args = QApplication::arguments();
    QString error;
    if (args.size() > 2 && args[1] == QStringLiteral("--recover")) {
        // Another editor's Recover: the autosave opens here as the scene it was.
        if (!window.recoverFile(args[2], &error)) {
            QMessageBox::critical(nullptr, QObject::tr("Tumble"), error);
            if (!window.openScene(MainWindow::defaultScenePath(), &error)) return 1;
        }
    } else {
        const QString path = args.size() > 1 ? args[1] : MainWindow::defaultScenePath();
        if (!window.openScene(path, &error)) {
            QMessageBox::critical(nullptr, QObject::tr("Tumble"), error);
            if (!window.openScene(MainWindow::defaultScenePath(), &error)) return 1;
        }
    }
    window.show();
    window.offerRecovery();
    return app.exec();
}

}  // namespace tumble::ui
