// DesktopActions: preferences, help pages and view toggles.
#include "ui/desktopactions.h"

#include "model/document/document.h"
#include "ui/edit/modelcommands.h"
#include "ui/sectiondialog.h"
#include "ui/viewport.h"

#include <QAction>
#include <QCoreApplication>
#include <QDialog>
#include <QDialogButtonBox>
#include <QMainWindow>
#include <QMenu>
#include <QMenuBar>
#include <QSettings>
#include <QSignalBlocker>
#include <QStatusBar>
#include <QTextBrowser>
#include <QUndoStack>
#include <QVBoxLayout>
#include <algorithm>

namespace kw {

DesktopActions::Prompts DesktopActions::Prompts::standard() {
    Prompts p;
    p.preferences = [](QWidget* parent, const PreferencesEdit& init,
                       bool focusContinuity) -> std::optional<PreferencesEdit> {
        PreferencesDialog d(init, parent);
        if (focusContinuity)
            d.focusContinuity();
        if (d.exec() != QDialog::Accepted)
            return std::nullopt;
        return d.edit();
    };
    p.show = [](QWidget* parent, const QString& title, const QString& html) {
        QDialog d(parent);
        d.setWindowTitle(title);
        d.resize(560, 520);
        auto* layout = new QVBoxLayout(&d);
        auto* text = new QTextBrowser;
        text->setOpenExternalLinks(true);
        text->setHtml(html);
        layout->addWidget(text);
        auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close);
        QObject::connect(buttons, &QDialogButtonBox::rejected, &d, &QDialog::reject);
        layout->addWidget(buttons);
        d.exec();
    };
    return p;
}

DesktopActions::DesktopActions(QMainWindow* window, Viewport* viewport, QUndoStack* stack)
    : QObject(window), m_window(window), m_viewport(viewport), m_stack(stack),
      m_prompts(Prompts::standard()) {}

void DesktopActions::applyPreferences() {
    const Preferences p = Preferences::load();
    m_viewport->setBackground(p.background);
    m_viewport->setHeadlight(p.headlight);
    m_viewport->setTrimMaskCap(p.trimMaskCap);
    m_viewport->setSamples(p.samples);
    m_viewport->setAntialiasing(
        antialiasingNamed(p.aaMethod).value_or(RenderOptions::Antialiasing::Accumulate));
    m_viewport->setTrimMode(trimModeNamed(p.trimMode).value_or(RenderOptions::TrimMode::Exact),
                            std::int64_t(p.trimBudgetMiB) << 20);
    showPartitions(p.partitionMode, p.pixelTolerance);
}

void DesktopActions::applyDisplay(const DisplaySettings& display) {
    applyPreferences();
    if (!display.partitionMode.isEmpty())
        showPartitions(display.partitionMode, display.pixelTolerance);
    // The project's background, or the dark default (a project saved without one).
    const bool light = display.background == QLatin1String("light");
    m_viewport->setLightBackground(light);
    if (m_lightBackground) {
        const QSignalBlocker quiet(m_lightBackground);
        m_lightBackground->setChecked(light);
    }
    // The project's sections, or none (a project saved without them).
    m_viewport->setSections(display.sections, display.sectionCaps);
    if (m_sections)
        m_sections->setSections(m_viewport->sections(), m_viewport->sectionCaps());
    // The project's draft settings (the defaults for a project saved without them).
    AnalysisOptions a = m_viewport->renderOptions().analysis;
    a.pullDirection = display.pullDirection;
    a.draftAngleDegrees = display.draftAngleDegrees;
    m_viewport->setAnalysis(a);
}

void DesktopActions::showPartitions(const QString& mode, double pixelTolerance) {
    m_viewport->setPartitioning(partitioningNamed(mode), pixelTolerance);
    if (m_adaptive) {
        const QSignalBlocker quiet(m_adaptive);
        m_adaptive->setChecked(m_viewport->partitioning() == RenderOptions::Partitioning::Adaptive);
    }
}

void DesktopActions::showSections() {
    if (!m_sections) {
        m_sections = new SectionDialog(
            [this] {
                glm::dvec3 lo(0.0), hi(0.0);
                sceneBounds(m_viewport->document()->scene(), lo, hi, true);
                return 0.5 * (lo + hi);
            },
            m_window);
        connect(m_sections, &SectionDialog::sectionsChanged, m_viewport, &Viewport::setSections);
        // A plane's handle dragged in the view: the fields follow (setSections emits nothing).
        connect(m_viewport, &Viewport::sectionsMoved, m_sections, &SectionDialog::setSections);
    }
    m_sections->setSections(m_viewport->sections(), m_viewport->sectionCaps());
    m_sections->show();
    m_sections->raise();
    m_sections->activateWindow();
}

DisplaySettings DesktopActions::currentDisplay() const {
    DisplaySettings d;
    d.partitionMode = m_viewport->partitioning() == RenderOptions::Partitioning::Uniform
                          ? QStringLiteral("uniform")
                          : QStringLiteral("adaptive");
    d.pixelTolerance = m_viewport->pixelTolerance();
    d.background = m_viewport->lightBackground() ? QStringLiteral("light") : QStringLiteral("dark");
    d.sections = m_viewport->sections();
    d.sectionCaps = m_viewport->sectionCaps();
    d.pullDirection = m_viewport->renderOptions().analysis.pullDirection;
    d.draftAngleDegrees = m_viewport->renderOptions().analysis.draftAngleDegrees;
    return d;
}

void DesktopActions::editPreferences(bool focusContinuity) {
    Document* doc = m_viewport->document();
    const PreferencesEdit initial{Preferences::load(), doc->scene().continuity};
    const std::optional<PreferencesEdit> e =
        m_prompts.preferences(m_window, initial, focusContinuity);
    if (!e)
        return;
    e->preferences.save();
    applyPreferences();
    if (!e->project || *e->project == doc->scene().continuity)
        return;
    // The project's tolerances are authored data saved with it: an edit like any other.
    auto command = SetContinuityTolerances::create(doc, *e->project);
    if (!command)
        m_window->statusBar()->showMessage(
            tr("Continuity tolerances not set: %1").arg(command.message()), 8000);
    else
        m_stack->push(command->release());
}

void DesktopActions::addEditEntries(QMenu* edit) {
    edit->addSeparator();
    QAction* prefs = edit->addAction(tr("&Preferences…"), this, [this] { editPreferences(); });
    prefs->setObjectName(QStringLiteral("actionPreferences"));
    prefs->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_Comma));
    prefs->setMenuRole(QAction::PreferencesRole);
}

void DesktopActions::addViewEntries(QMenu* view) {
    QSettings settings;
    auto toggle = [&](const char* name, const QString& text, const char* key, bool initial,
                      void (Viewport::*set)(bool)) {
        QAction* a = view->addAction(text);
        a->setObjectName(QLatin1String(name));
        a->setCheckable(true);
        const QString k = QLatin1String(key);
        a->setChecked(settings.value(k, initial).toBool());
        (m_viewport->*set)(a->isChecked());
        connect(a, &QAction::toggled, this, [this, k, set](bool on) {
            (m_viewport->*set)(on);
            QSettings().setValue(k, on);
        });
        return a;
    };
    view->addSeparator();
    toggle("actionNetForAll", tr("Control Nets of &All Surfaces"), "view/controlNetForAll", false,
           &Viewport::setControlNetForAll);
    toggle("actionGroundGrid", tr("&Ground Grid"), "view/groundGrid", false,
           &Viewport::setGroundGrid);
    toggle("actionAxisIndicator", tr("A&xis Indicator"), "view/axisIndicator", true,
           &Viewport::setAxisIndicator);
    // The paper's uniform grid or view-adaptive partitions: a preference, so it
    // holds for every document and the next start.
    m_adaptive = view->addAction(tr("Ada&ptive Partitions (within the pixel tolerance)"));
    m_adaptive->setObjectName(QStringLiteral("actionAdaptivePartitions"));
    m_adaptive->setCheckable(true);
    m_adaptive->setChecked(Preferences::load().partitionMode != QLatin1String("uniform"));
    m_adaptive->setToolTip(tr("On: each surface gets the fewest partitions (at least the "
                              "sliders') that keep its base polygon within the Preferences' "
                              "pixel tolerance of the exact surface. Off: the sliders' grid, "
                              "as in the paper."));
    connect(m_adaptive, &QAction::toggled, this, [this](bool on) {
        Preferences p = Preferences::load();
        p.partitionMode = on ? QStringLiteral("adaptive") : QStringLiteral("uniform");
        p.save();
        applyPreferences();
    });
    // The light gradient CAD viewers offer; saved with the project, as the partition mode.
    m_lightBackground = view->addAction(tr("&Light Background (gradient)"));
    m_lightBackground->setObjectName(QStringLiteral("actionLightBackground"));
    m_lightBackground->setCheckable(true);
    m_lightBackground->setChecked(m_viewport->lightBackground());
    connect(m_lightBackground, &QAction::toggled, m_viewport, &Viewport::setLightBackground);
    // Section planes: view state saved with the project, as the background.
    QAction* section = view->addAction(tr("&Section…"));
    section->setObjectName(QStringLiteral("actionSection"));
    section->setToolTip(tr("Up to three planes that cut the view at the exact surface, with "
                           "caps on closed solids"));
    connect(section, &QAction::triggered, this, [this] { showSections(); });
    QAction* head = view->addAction(tr("&Headlight (lights follow the camera)"));
    head->setObjectName(QStringLiteral("actionHeadlight"));
    head->setCheckable(true);
    head->setChecked(Preferences::load().headlight);
    connect(head, &QAction::toggled, this, [this](bool on) {
        Preferences p = Preferences::load();
        p.headlight = on;
        p.save();
        applyPreferences();
    });
}

QString DesktopActions::shortcutsHtml() const {
    QList<QAction*> actions = m_window->findChildren<QAction*>();
    std::sort(actions.begin(), actions.end(), [](QAction* a, QAction* b) {
        return a->text().remove(QLatin1Char('&')) < b->text().remove(QLatin1Char('&'));
    });
    QString rows;
    for (QAction* a : actions) {
        QStringList keys;
        for (const QKeySequence& k : a->shortcuts())
            keys << k.toString(QKeySequence::NativeText);
        if (keys.isEmpty())
            continue;
        rows += QStringLiteral("<tr><td><b>%1</b></td><td>%2</td></tr>")
                    .arg(keys.join(QStringLiteral(", ")).toHtmlEscaped(),
                         a->text().remove(QLatin1Char('&')).toHtmlEscaped());
    }
    const QString mouse =
        tr("<tr><td><b>Left click</b></td><td>pick a control point of a selected surface (Shift "
           "adds)</td></tr>"
           "<tr><td><b>Left drag on a point</b></td><td>move the picked points (hold X, Y or Z to "
           "lock an axis; Esc cancels)</td></tr>"
           "<tr><td><b>Ctrl + left drag</b></td><td>move the selected surfaces (X, Y, Z lock an "
           "axis)</td></tr>"
           "<tr><td><b>Ctrl + Shift + drag on a point</b></td><td>change its weight (up "
           "raises)</td></tr>"
           "<tr><td><b>Middle drag, Alt + left drag</b></td><td>orbit</td></tr>"
           "<tr><td><b>Right drag, Shift + middle drag</b></td><td>pan</td></tr>"
           "<tr><td><b>Wheel</b></td><td>zoom toward the cursor</td></tr>"
           "<tr><td><b>Hold P</b></td><td>probe the exact point under the cursor (Measure "
           "menu: probe, distance, angle, radius)</td></tr>");
    return tr("<h3>Keys</h3><table cellspacing=4>%1</table><h3>Mouse in the 3D view</h3>"
              "<table cellspacing=4>%2</table>")
        .arg(rows, mouse);
}

void DesktopActions::addHelpMenu(QMenuBar* bar) {
    QMenu* help = bar->addMenu(tr("&Help"));
    QAction* keys = help->addAction(tr("&Keyboard Shortcuts"), this, [this] {
        m_prompts.show(m_window, tr("Keyboard shortcuts"), shortcutsHtml());
    });
    keys->setObjectName(QStringLiteral("actionShortcuts"));
    keys->setShortcut(QKeySequence(Qt::Key_F1));
    QAction* about = help->addAction(tr("&About Knotwork"), this, [this] {
        m_prompts.show(
            m_window, tr("About Knotwork"),
            tr("<h3>Knotwork %1</h3><p>A NURBS surface editor that draws the true surface: each "
               "pixel is evaluated exactly on the GPU, after Yau, Lin and Yeh (2009), <i>A New "
               "Approach to Accelerate NURBS Surface Rendering on GPU</i>.</p><p>Qt %2.</p>")
                .arg(QCoreApplication::applicationVersion().isEmpty()
                         ? tr("(development build)")
                         : QCoreApplication::applicationVersion(),
                     QString::fromLatin1(qVersion())));
    });
    about->setObjectName(QStringLiteral("actionAbout"));
    about->setMenuRole(QAction::AboutRole);
}

} // namespace kw
