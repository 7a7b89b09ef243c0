// MainWindow: construction of the window, docks, menus, actions and status bar.
#include "ui/mainwindow.h"

#include "ui/analysiscontrols.h"
#include "ui/autosave.h"
#include "ui/desktopactions.h"
#include "ui/edgecontinuity.h"
#include "ui/edit/commands.h"
#include "ui/lightspanel.h"
#include "ui/modelingtools.h"
#include "ui/probe_tool.h"
#include "ui/propertypanel.h"
#include "ui/uvpanel.h"
#include "ui/viewport.h"
#include "ui/visibilitytools.h"

#include <QActionGroup>
#include <QCheckBox>
#include <QCloseEvent>
#include <QDialogButtonBox>
#include <QDockWidget>
#include <QFileDialog>
#include <QFormLayout>
#include <QHeaderView>
#include <QLabel>
#include <QMenuBar>
#include <QProgressDialog>
#include <QPushButton>
#include <QScreen>
#include <QScrollArea>
#include <QSettings>
#include <QShowEvent>
#include <QSpinBox>
#include <QStatusBar>
#include <QTimer>
#include <QToolBar>
#include <QTreeView>
#include <QUndoStack>
#include <algorithm>

namespace kw {

// Edit ▸ Units… (mainwindow_units.cpp).
std::optional<MainWindow::Dialogs::UnitsChoice> unitsDialogStandard(QWidget* parent,
                                                                    LengthUnit current);

MainWindow::Dialogs MainWindow::Dialogs::standard() {
    Dialogs d;
    d.openFile = [](QWidget* parent, const QString& title, const QString& filter) {
        return QFileDialog::getOpenFileName(parent, title, QString(), filter);
    };
    d.saveFile = [](QWidget* parent, const QString& title, const QString& filter,
                    const QString& suggested) {
        return QFileDialog::getSaveFileName(parent, title, suggested, filter);
    };
    d.error = [](QWidget* parent, const QString& title, const QString& text) {
        QMessageBox::critical(parent, title, text);
    };
    d.askSave = [](QWidget* parent, const QString& text) {
        return QMessageBox::warning(parent, QObject::tr("Unsaved changes"), text,
                                    QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel,
                                    QMessageBox::Save);
    };
    d.importFile = d.openFile;
    d.exportOptions = [](QWidget* parent,
                         const ExportOptions& init) -> std::optional<ExportOptions> {
        QDialog dialog(parent);
        dialog.setWindowTitle(QObject::tr("Export image"));
        auto* form = new QFormLayout(&dialog);
        auto* w = new QSpinBox;
        auto* h = new QSpinBox;
        for (QSpinBox* b : {w, h})
            b->setRange(16, 16384);
        w->setValue(init.size.width());
        h->setValue(init.size.height());
        auto* aov = new QCheckBox(QObject::tr("Also write the AOVs (id, u, v, P, N, Z) as "
                                              "NAME_aov.exr"));
        aov->setChecked(init.aov);
        form->addRow(QObject::tr("Width"), w);
        form->addRow(QObject::tr("Height"), h);
        form->addRow(aov);
        auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
        QObject::connect(buttons, &QDialogButtonBox::accepted, &dialog, &QDialog::accept);
        QObject::connect(buttons, &QDialogButtonBox::rejected, &dialog, &QDialog::reject);
        form->addRow(buttons);
        if (dialog.exec() != QDialog::Accepted)
            return std::nullopt;
        return ExportOptions{QSize(w->value(), h->value()), aov->isChecked()};
    };
    d.information = [](QWidget* parent, const QString& title, const QString& text) {
        QMessageBox::information(parent, title, text);
    };
    d.units = unitsDialogStandard;
    d.askRecover = [](QWidget* parent, const QString& text) {
        QMessageBox box(QMessageBox::Question, QObject::tr("Recover unsaved changes"), text,
                        QMessageBox::Yes | QMessageBox::Discard | QMessageBox::Cancel, parent);
        box.button(QMessageBox::Yes)->setText(QObject::tr("Restore"));
        box.button(QMessageBox::Cancel)->setText(QObject::tr("Later"));
        box.setDefaultButton(QMessageBox::Yes);
        return QMessageBox::StandardButton(box.exec());
    };
    return d;
}

MainWindow::MainWindow(QWidget* parent)
    : QMainWindow(parent), m_doc(new Document(this)), m_model(new SceneModel(*m_doc, this)),
      m_selection(new Selection(*m_model, this)), m_stack(new QUndoStack(this)),
      m_dialogs(Dialogs::standard()) {
    setObjectName(QStringLiteral("KnotworkMainWindow"));
    // The untitled project the window starts with is a new one: the user's default tolerances.
    // Preferences::load keeps the defaults in place of invalid tolerances: never refused.
    (void)m_doc->setContinuityTolerances(Preferences::load().continuity);
    setAcceptDrops(true);
    setDockNestingEnabled(true);
    m_model->setRenameHandler([this](SurfaceId id, const QString& name) {
        if (const Status pushed = pushCommand(m_stack, RenameSurface::create(m_doc, id, name));
            !pushed)
            statusBar()->showMessage(pushed.message(), 5000);
    });

    m_viewport = new Viewport(m_doc, m_model, m_selection, m_stack, this);
    setCentralWidget(m_viewport);
    buildDocks();
    buildMenus();

    m_fpsLabel = new QLabel;
    m_fpsLabel->setMinimumWidth(170);
    statusBar()->addPermanentWidget(m_fpsLabel);
    m_unitLabel = new QLabel;
    m_unitLabel->setObjectName(QStringLiteral("unitLabel"));
    m_unitLabel->setToolTip(tr("The document's length unit (Edit ▸ Units…)"));
    statusBar()->addPermanentWidget(m_unitLabel);
    connect(m_doc, &Document::unitChanged, this, &MainWindow::showUnit);
    connect(m_doc, &Document::sceneReset, this, &MainWindow::showUnit);
    showUnit();
    // While frames come, frames per second and the last frame's report; a second after the
    // last frame, "idle" with that frame's time, rather than a stale rate.
    auto* idle = new QTimer(this);
    idle->setSingleShot(true);
    idle->setInterval(1200);
    connect(m_viewport, &Viewport::framesPerSecond, this,
            [this](double fps, const FrameReport& frame) {
                m_fpsLabel->setText(tr("%1 fps, frame %2 ms CPU, %3 draws")
                                        .arg(fps, 0, 'f', 1)
                                        .arg(frame.cpuMs.total, 0, 'f', 1)
                                        .arg(frame.drawCalls));
            });
    connect(m_viewport, &Viewport::frameDrawn, this, [this, idle](const FrameReport& frame) {
        m_lastFrameMs = frame.cpuMs.total;
        idle->start();
    });
    connect(idle, &QTimer::timeout, this, [this] {
        m_fpsLabel->setText(tr("idle, last frame %1 ms CPU").arg(m_lastFrameMs, 0, 'f', 1));
    });
    connect(m_viewport, &Viewport::renderError, this,
            [this](const QString& message) { statusBar()->showMessage(message); });
    connect(m_viewport, &Viewport::message, this,
            [this](const QString& m) { statusBar()->showMessage(m, 5000); });
    connect(m_properties, &PropertyPanel::editRejected, this,
            [this](const QString& m) { statusBar()->showMessage(m, 5000); });
    connect(m_lights, &LightsPanel::editRejected, this,
            [this](const QString& m) { statusBar()->showMessage(m, 5000); });
    connect(m_stack, &QUndoStack::cleanChanged, this, &MainWindow::updateTitle);
    m_autosave = new Autosave(
        m_doc, m_stack,
        [this] {
            return Autosave::Origin{m_path, m_importedPath};
        },
        this);
    connect(m_autosave, &Autosave::failed, this, [this](const QString& message) {
        statusBar()->showMessage(tr("Autosave failed: %1").arg(message));
    });

    QSettings settings;
    sizeFirstStart();
    restoreGeometry(settings.value(QStringLiteral("window/geometry")).toByteArray());
    rebuildRecentMenu();
    updateTitle();
}

MainWindow::~MainWindow() = default;

namespace {
// The first widths of the left (scene, UV domain) and right (properties, lights) docks.
constexpr double kLeftDockFraction = 0.18;
constexpr double kRightDockFraction = 0.2;
} // namespace

// The first start, before any saved layout: most of the screen, as CAD viewers open.
void MainWindow::sizeFirstStart() {
    const QRect screen = this->screen() ? this->screen()->availableGeometry() : QRect();
    if (screen.isEmpty()) {
        resize(1100, 720);
        return;
    }
    const int w = std::clamp(int(screen.width() * 0.9), std::min(1100, screen.width()), 1800);
    const int h = std::clamp(int(screen.height() * 0.9), std::min(720, screen.height()), 1100);
    resize(w, h);
}

// At the first show: the saved layout, or else the docks' first widths as fractions of the
// window, so that the 3D view takes most of it (about 60 %) at any window size.
void MainWindow::showEvent(QShowEvent* event) {
    QMainWindow::showEvent(event);
    if (m_docksSized)
        return;
    m_docksSized = true;
    // The saved docks and toolbars, restored once the window has its size: restored before,
    // the docks' widths came back tens of pixels off.
    if (restoreState(QSettings().value(QStringLiteral("window/state")).toByteArray()))
        return;
    QList<QDockWidget*> left, right;
    for (QDockWidget* d : findChildren<QDockWidget*>()) {
        if (dockWidgetArea(d) == Qt::LeftDockWidgetArea)
            left << d;
        else if (dockWidgetArea(d) == Qt::RightDockWidgetArea)
            right << d;
    }
    QList<QDockWidget*> docks;
    QList<int> widths;
    if (!left.isEmpty()) {
        docks << left.first();
        widths << int(width() * kLeftDockFraction);
    }
    if (!right.isEmpty()) {
        docks << right.first();
        widths << int(width() * kRightDockFraction);
    }
    resizeDocks(docks, widths, Qt::Horizontal);
    // The scene tree above, the UV domain below it: the domain square gets the larger share.
    if (left.size() > 1)
        resizeDocks({left[0], left[1]}, {height() * 2 / 5, height() * 3 / 5}, Qt::Vertical);
}

void MainWindow::buildDocks() {
    auto dock = [this](const QString& title, const QString& name, QWidget* content,
                       Qt::DockWidgetArea area) {
        auto* d = new QDockWidget(title, this);
        d->setObjectName(name); // saveState() keys docks by object name
        d->setWidget(content);
        addDockWidget(area, d);
        return d;
    };
    m_tree = new QTreeView;
    m_tree->setModel(m_model);
    m_tree->setSelectionModel(m_selection->itemSelection());
    m_tree->setEditTriggers(QAbstractItemView::EditKeyPressed | QAbstractItemView::DoubleClicked);
    m_tree->setSelectionMode(QAbstractItemView::ExtendedSelection); // Ctrl / Shift add
    m_tree->header()->setStretchLastSection(true);
    dock(tr("Scene"), QStringLiteral("dockScene"), m_tree, Qt::LeftDockWidgetArea);

    m_uv = new UvPanel(m_doc, m_selection, m_stack);
    dock(tr("UV domain and trims"), QStringLiteral("dockUv"),
         makeUvEditor(m_uv, m_selection, m_doc), Qt::LeftDockWidgetArea);
    connect(m_uv, &UvPanel::message, this,
            [this](const QString& m) { statusBar()->showMessage(m, 8000); });

    m_properties = new PropertyPanel(m_doc, m_selection, m_stack);
    auto* scroll = new QScrollArea;
    scroll->setWidgetResizable(true);
    scroll->setWidget(m_properties);
    QDockWidget* props =
        dock(tr("Properties"), QStringLiteral("dockProperties"), scroll, Qt::RightDockWidgetArea);
    m_lights = new LightsPanel(m_doc, m_stack);
    // Scrolled like the properties, so that its width does not set the tabbed docks' minimum.
    auto* lightsScroll = new QScrollArea;
    lightsScroll->setWidgetResizable(true);
    lightsScroll->setWidget(m_lights);
    QDockWidget* lights =
        dock(tr("Lights"), QStringLiteral("dockLights"), lightsScroll, Qt::RightDockWidgetArea);
    tabifyDockWidget(props, lights);
    props->raise();
}

QAction* MainWindow::addAction(QMenu* menu, const QString& name, const QString& text,
                               const QKeySequence& key, std::function<void()> slot) {
    auto* a = menu->addAction(text);
    a->setObjectName(name);
    if (!key.isEmpty())
        a->setShortcut(key);
    connect(a, &QAction::triggered, this, std::move(slot));
    return a;
}

QAction* MainWindow::action(const QString& objectName) const {
    return findChild<QAction*>(objectName);
}

void MainWindow::buildMenus() {
    buildFileMenu();
    buildEditMenu();
    buildViewMenu();
    m_tools = new ModelingTools(this, m_doc, m_model, m_selection, m_stack, m_viewport);
    connect(m_tools, &ModelingTools::message, this,
            [this](const QString& m) { statusBar()->showMessage(m, 5000); });
    // A row of its own: beside the Analysis toolbar it ran out of room in the first window.
    addToolBarBreak();
    QToolBar* toolbar = addToolBar(tr("Create"));
    toolbar->setObjectName(QStringLiteral("toolbarCreate")); // saveState() keys by name
    toolbar->setToolButtonStyle(Qt::ToolButtonTextOnly);
    m_tools->buildMenus(menuBar(), toolbar);
    auto* probe = new ProbeTool(m_doc, m_viewport); // Measure menu: probe and measurements
    probe->buildMenu(menuBar());
    connect(probe, &ProbeTool::message, this,
            [this](const QString& m) { statusBar()->showMessage(m, 8000); });
    m_desktop = new DesktopActions(this, m_viewport, m_stack);
    m_desktop->addEditEntries(findChild<QMenu*>(QStringLiteral("menuEdit")));
    m_desktop->addViewEntries(findChild<QMenu*>(QStringLiteral("menuView")));
    m_desktop->addHelpMenu(menuBar());
    m_desktop->applyPreferences();
    auto* visibility = new VisibilityTools(this, m_doc, m_selection, m_stack);
    QMenu* view = findChild<QMenu*>(QStringLiteral("menuView"));
    view->addSeparator();
    visibility->install(view, m_tree);
    connect(visibility, &VisibilityTools::message, this,
            [this](const QString& m) { statusBar()->showMessage(m, 5000); });
}

void MainWindow::buildFileMenu() {
    QMenu* file = menuBar()->addMenu(tr("&File"));
    addAction(file, QStringLiteral("actionNew"), tr("&New"), QKeySequence::New,
              [this] { newDocument(); });
    addAction(file, QStringLiteral("actionOpen"), tr("&Open…"), QKeySequence::Open,
              [this] { openDialog(); });
    m_recentMenu = file->addMenu(tr("Open &Recent"));
    m_recentMenu->setObjectName(QStringLiteral("menuRecent"));
    // Import right after the recent files, as the other CAD tools place it; then the samples.
    addAction(file, QStringLiteral("actionImport"), tr("&Import…"), QKeySequence(),
              [this] { importDialog(); });
    addSamplesMenu(file);
    file->addSeparator();
    addAction(file, QStringLiteral("actionSave"), tr("&Save"), QKeySequence::Save,
              [this] { save(); });
    // Explicit: QKeySequence::SaveAs is empty on some X11 desktops.
    addAction(file, QStringLiteral("actionSaveAs"), tr("Save &As…"),
              QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_S), [this] { saveAs(); });
    addAction(file, QStringLiteral("actionExport"), tr("E&xport…"), QKeySequence(),
              [this] { exportDialog(false); });
    addAction(file, QStringLiteral("actionExportSelected"), tr("Export Se&lected…"), QKeySequence(),
              [this] { exportDialog(true); });
    addAction(file, QStringLiteral("actionExportImage"), tr("&Export Image…"),
              QKeySequence(Qt::CTRL | Qt::Key_E), [this] { exportImage(); });
    file->addSeparator();
    QAction* quit = addAction(file, QStringLiteral("actionQuit"), tr("&Quit"), QKeySequence::Quit,
                              [this] { close(); });
    quit->setMenuRole(QAction::QuitRole);
}

void MainWindow::buildEditMenu() {
    QMenu* edit = menuBar()->addMenu(tr("&Edit"));
    edit->setObjectName(QStringLiteral("menuEdit"));
    // The stack's actions show the command's text ("Undo Move control point").
    QAction* undo = m_stack->createUndoAction(this, tr("&Undo"));
    undo->setObjectName(QStringLiteral("actionUndo"));
    undo->setShortcut(QKeySequence::Undo);
    QAction* redo = m_stack->createRedoAction(this, tr("&Redo"));
    redo->setObjectName(QStringLiteral("actionRedo"));
    // Both redo keys on every platform: QKeySequence::Redo is only Ctrl+Shift+Z on X11.
    redo->setShortcuts(
        {QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_Z), QKeySequence(Qt::CTRL | Qt::Key_Y)});
    edit->addAction(undo);
    edit->addAction(redo);
    edit->addSeparator();
    addAction(edit, QStringLiteral("actionSelectAll"), tr("Select &All"), QKeySequence::SelectAll,
              [this] { selectAll(); });
    addAction(edit, QStringLiteral("actionDelete"), tr("&Delete"), QKeySequence::Delete,
              [this] { deleteSelection(); });
    edit->addSeparator();
    // A control point dragged on a boundary another untrimmed face shares carries that face's
    // coincident point (and, keeping tangency, the next rows on both sides): the document
    // applies it to every move, live drags and undo alike (model/document/seamkeeper.h).
    QSettings settings;
    QAction* seams = addAction(edit, QStringLiteral("actionKeepSeamsClosed"),
                               tr("Keep Seams &Closed"), QKeySequence(), [] {});
    seams->setCheckable(true);
    seams->setChecked(settings.value(QStringLiteral("edit/keepSeamsClosed"), true).toBool());
    seams->setStatusTip(tr("Moving a control point on a shared boundary moves the neighbouring "
                           "face's coincident point too"));
    QAction* tangency = addAction(edit, QStringLiteral("actionKeepTangency"), tr("Keep &Tangency"),
                                  QKeySequence(), [] {});
    tangency->setCheckable(true);
    tangency->setChecked(settings.value(QStringLiteral("edit/keepTangency"), false).toBool());
    tangency->setStatusTip(tr("With Keep Seams Closed: the rows next to a shared boundary move "
                              "with it on both sides, so a tangent seam stays tangent"));
    const auto apply = [this, seams, tangency] {
        tangency->setEnabled(seams->isChecked());
        m_doc->setSeamLink(!seams->isChecked()     ? Document::SeamLink::Off
                           : tangency->isChecked() ? Document::SeamLink::Tangency
                                                   : Document::SeamLink::Position);
        QSettings s;
        s.setValue(QStringLiteral("edit/keepSeamsClosed"), seams->isChecked());
        s.setValue(QStringLiteral("edit/keepTangency"), tangency->isChecked());
    };
    connect(seams, &QAction::toggled, this, apply);
    connect(tangency, &QAction::toggled, this, apply);
    apply();
    addAction(edit, QStringLiteral("actionUnits"), tr("&Units…"), {}, [this] { unitsDialog(); });
}

void MainWindow::buildViewMenu() {
    QMenu* view = menuBar()->addMenu(tr("&View"));
    view->setObjectName(QStringLiteral("menuView"));
    addAction(view, QStringLiteral("actionFit"), tr("&Fit to View"), QKeySequence(Qt::Key_F),
              [this] { m_viewport->fitToView(); });
    QMenu* standard = view->addMenu(tr("Standard &Views"));
    const struct {
        const char* name;
        const char* text;
        Qt::Key key;
        StandardView view;
    } views[] = {{"actionViewFront", "&Front", Qt::Key_1, StandardView::Front},
                 {"actionViewBack", "&Back", Qt::Key_2, StandardView::Back},
                 {"actionViewRight", "&Right", Qt::Key_3, StandardView::Right},
                 {"actionViewLeft", "&Left", Qt::Key_4, StandardView::Left},
                 {"actionViewTop", "&Top", Qt::Key_7, StandardView::Top},
                 {"actionViewBottom", "B&ottom", Qt::Key_8, StandardView::Bottom},
                 {"actionViewIso", "&Oblique", Qt::Key_0, StandardView::Iso}};
    for (const auto& v : views) {
        const StandardView which = v.view;
        addAction(standard, QLatin1String(v.name), tr(v.text), QKeySequence(v.key),
                  [this, which] { m_viewport->setStandardView(which); });
    }
    view->addSeparator();
    auto* modes = new QActionGroup(this);
    QAction* exact = addAction(view, QStringLiteral("actionShadeExact"), tr("&Exact Surface"),
                               QKeySequence(Qt::Key_E),
                               [this] { m_viewport->setRenderMode(RenderMode::Exact); });
    QAction* tess = addAction(view, QStringLiteral("actionShadeTessellated"),
                              tr("&Tessellated Baseline"), QKeySequence(Qt::Key_T),
                              [this] { m_viewport->setRenderMode(RenderMode::Tessellated); });
    for (QAction* a : {exact, tess}) {
        a->setCheckable(true);
        modes->addAction(a);
    }
    exact->setChecked(true);
    view->addSeparator();
    QAction* wire = addAction(view, QStringLiteral("actionWireframe"),
                              tr("Base Polygon &Wireframe"), QKeySequence(Qt::Key_W), [] {});
    wire->setCheckable(true);
    connect(wire, &QAction::toggled, m_viewport, &Viewport::setWireframe);
    QAction* net = addAction(view, QStringLiteral("actionControlNet"), tr("&Control Net"),
                             QKeySequence(Qt::Key_N), [] {});
    net->setCheckable(true);
    net->setChecked(m_viewport->renderOptions().controlNet);
    connect(net, &QAction::toggled, m_viewport, &Viewport::setControlNet);
    auto* analysis = new AnalysisControls(this, view, m_viewport); // View ▸ Analysis, toolbar
    // An overlay over any shading mode (zebra across a seam is the classic G1/G2 check).
    analysis->menu()->addSeparator();
    m_edgeContinuity = new EdgeContinuityOverlay(m_doc, m_viewport, this);
    QAction* edges = analysis->menu()->addAction(tr("Edge &Continuity"));
    edges->setObjectName(QStringLiteral("actionEdgeContinuity"));
    edges->setCheckable(true);
    edges->setStatusTip(tr("Colour every edge where faces meet by its continuity (G2, G1, G0, "
                           "open) and mark free edges; tolerances in Preferences"));
    connect(edges, &QAction::toggled, m_edgeContinuity, &EdgeContinuityOverlay::setEnabled);
    QAction* tolerances = analysis->menu()->addAction(tr("Continuity &Tolerances…"));
    tolerances->setObjectName(QStringLiteral("actionContinuityTolerances"));
    tolerances->setStatusTip(tr("The G0, G1 and G2 thresholds of Edge Continuity, Match Surface "
                                "and 'knotwork info --continuity': the project's (saved with it) "
                                "and the defaults for new projects, in Preferences"));
    // One place edits them: Preferences, opened on the project's tolerances.
    connect(tolerances, &QAction::triggered, this, [this] { m_desktop->editPreferences(true); });
    // The first measure of a large model runs in the background: its progress stays in the
    // status bar until it ends, and is cleared then unless another message took its place.
    connect(m_edgeContinuity, &EdgeContinuityOverlay::measureStatus, this,
            [this, shown = QString()](const QString& text) mutable {
                if (!text.isEmpty())
                    statusBar()->showMessage(text);
                else if (statusBar()->currentMessage() == shown)
                    statusBar()->clearMessage();
                shown = text;
            });
    connect(m_edgeContinuity, &EdgeContinuityOverlay::seamMessage, this, [this](const QString& m) {
        if (!m.isEmpty())
            statusBar()->showMessage(tr("This edit %1").arg(m), 4000);
    });
    view->addSeparator();
    QMenu* panels = view->addMenu(tr("&Panels"));
    for (QDockWidget* d : findChildren<QDockWidget*>())
        panels->addAction(d->toggleViewAction());
}

void MainWindow::selectAll() {
    // All control points of the current surface, or of every surface when none is current.
    const SurfaceId current = m_selection->currentSurface();
    std::vector<ControlPointRef> refs;
    for (const Surface& s : m_doc->scene().surfaces) {
        if (current.isValid() && s.id != current)
            continue;
        for (int j = 0; j < s.geometry.countV; ++j)
            for (int i = 0; i < s.geometry.countU; ++i)
                refs.push_back({s.id, i, j});
    }
    m_selection->setControlPoints(refs);
}

void MainWindow::deleteSelection() {
    // Del in the UV panel with a picked trim loop removes the loop, not the surface.
    if (m_uv->hasFocus() && m_uv->deleteSelectedLoops())
        return;
    if (const Status deleted = m_tools->deleteSelected(); !deleted)
        statusBar()->showMessage(deleted.message(), 5000);
}

void MainWindow::selectSurface(SurfaceId id) {
    const QModelIndex row = m_model->surfaceIndex(id);
    m_selection->itemSelection()->setCurrentIndex(row, QItemSelectionModel::ClearAndSelect |
                                                           QItemSelectionModel::Rows);
}

Error MainWindow::showError(const QString& title, Error error) {
    statusBar()->showMessage(error.message, 10000);
    if (m_dialogs.error)
        m_dialogs.error(this, title, error.message);
    return error;
}

void MainWindow::closeEvent(QCloseEvent* event) {
    if (m_importProgress) { // cancel the import first; its dialog's own loop is running
        m_importProgress->cancel();
        event->ignore();
        return;
    }
    if (!maybeSave()) {
        event->ignore();
        return;
    }
    QSettings settings;
    settings.setValue(QStringLiteral("window/geometry"), saveGeometry());
    settings.setValue(QStringLiteral("window/state"), saveState());
    event->accept();
}

} // namespace kw
