// ProbeTool: probe values under the cursor and measure clicks, a tool of the viewport.
#include "ui/probe_tool.h"

#include "model/analysis/mass_properties.h"
#include "model/document/document.h"
#include "model/document/units.h"
#include "render/thread_clock.h"
#include "ui/viewport.h"

#include <QAction>
#include <QActionGroup>
#include <QApplication>
#include <QClipboard>
#include <QElapsedTimer>
#include <QFrame>
#include <QKeyEvent>
#include <QLabel>
#include <QMenu>
#include <QMenuBar>
#include <QMouseEvent>
#include <QToolButton>
#include <QVBoxLayout>
#include <cmath>

namespace kw {

ProbeTool::ProbeTool(Document* document, Viewport* viewport)
    : QObject(viewport), m_doc(document), m_view(viewport), m_measure(new MeasureTool(viewport)) {
    makePanel();
    if (viewport->isNativeWindow())
        viewport->installEventFilter(this);
    viewport->listen(this);
    // Dimensions and the probe belong to the geometry they were taken on: a new or opened
    // document starts without them.
    connect(document, &Document::sceneReset, this, [this] {
        m_measure->clear();
        hideProbe();
    });
}

void ProbeTool::makePanel() {
    m_panel = new QFrame(m_view);
    m_panel->setObjectName(QStringLiteral("probePanel"));
    m_panel->setFrameShape(QFrame::StyledPanel);
    m_panel->setAutoFillBackground(true);
    if (m_view->isNativeWindow()) {
        // Over the view's native window only a native window shows: the panel is one, a child
        // of the main window's placed over the view (its ancestors and siblings stay alien:
        // Qt::AA_DontCreateNativeWidgetSiblings, set with the view's window).
        m_panel->setAttribute(Qt::WA_DontCreateNativeAncestors);
        m_panel->setAttribute(Qt::WA_NativeWindow);
    }
    auto* layout = new QVBoxLayout(m_panel);
    layout->setContentsMargins(6, 4, 6, 4);
    m_text = new QLabel;
    m_text->setObjectName(QStringLiteral("probeText"));
    m_text->setTextInteractionFlags(Qt::TextSelectableByMouse);
    m_text->setTextFormat(Qt::PlainText);
    layout->addWidget(m_text);
    auto* copy = new QToolButton;
    copy->setObjectName(QStringLiteral("probeCopy"));
    copy->setText(tr("Copy"));
    copy->setToolTip(tr("Copy the probe values as text"));
    layout->addWidget(copy, 0, Qt::AlignRight);
    connect(copy, &QToolButton::clicked, this, [this] { copyProbe(); });
    m_panel->hide();
}

bool ProbeTool::eventFilter(QObject* watched, QEvent* event) {
    // A native panel whose view moves to another window would keep a native window of the old
    // one (gone with it): a new panel, made in the new window when next shown.
    if (watched == m_view && event->type() == QEvent::ParentAboutToChange) {
        hideProbe();
        delete m_panel;
        makePanel();
    }
    return QObject::eventFilter(watched, event);
}

void ProbeTool::buildMenu(QMenuBar* bar) {
    QMenu* menu = bar->addMenu(tr("&Measure"));
    menu->setObjectName(QStringLiteral("menuMeasure"));
    auto* group = new QActionGroup(this);
    group->setExclusionPolicy(QActionGroup::ExclusionPolicy::ExclusiveOptional);
    const struct {
        const char* name;
        QString text;
        QString tip;
        Mode mode;
    } entries[] = {
        {"actionProbe", tr("&Probe"),
         tr("Show the exact point under the cursor: surface, (u, v), x y z, normal and curvature "
            "(or hold P over the view)"),
         Mode::Probe},
        {"actionMeasureDistance", tr("&Distance"),
         tr("Click two points: their distance with dx, dy, dz"), Mode::Distance},
        {"actionMeasureAngle", tr("&Angle"),
         tr("Click two points: the angle between their normals"), Mode::Angle},
        {"actionMeasureRadius", tr("&Radius"),
         tr("Click a point: its smallest radius of curvature"), Mode::Radius},
    };
    int k = 0;
    for (const auto& e : entries) {
        QAction* a = menu->addAction(e.text);
        a->setObjectName(QLatin1String(e.name));
        a->setStatusTip(e.tip);
        a->setCheckable(true);
        group->addAction(a);
        const Mode mode = e.mode;
        connect(a, &QAction::toggled, this, [this, mode](bool on) {
            if (on)
                setMode(mode);
            else if (m_mode == mode)
                setMode(Mode::Off);
        });
        m_actions[k++] = a;
    }
    menu->addSeparator();
    QAction* copy = menu->addAction(tr("&Copy Probe Values"));
    copy->setObjectName(QStringLiteral("actionCopyProbe"));
    connect(copy, &QAction::triggered, this, [this] { copyProbe(); });
    QAction* clear = menu->addAction(tr("C&lear Measurements"));
    clear->setObjectName(QStringLiteral("actionClearMeasurements"));
    connect(clear, &QAction::triggered, this, [this] { m_measure->clear(); });
}

void ProbeTool::setMode(Mode mode) {
    if (mode == m_mode)
        return;
    m_mode = mode;
    switch (mode) {
    case Mode::Distance:
        m_measure->setKind(Measurement::Kind::Distance);
        break;
    case Mode::Angle:
        m_measure->setKind(Measurement::Kind::Angle);
        break;
    case Mode::Radius:
        m_measure->setKind(Measurement::Kind::Radius);
        break;
    case Mode::Off:
    case Mode::Probe:
        m_measure->cancelPending();
        break;
    }
    for (int k = 0; k < 4; ++k)
        if (m_actions[k]) {
            const QSignalBlocker b(m_actions[k]);
            m_actions[k]->setChecked(int(mode) == k + 1);
        }
    // A mode is the view's installed tool (it sees plain clicks before selection does);
    // Off gives the view back, unless another tool took it already (uninstalled()).
    if (mode != Mode::Off)
        m_view->setTool(this);
    else if (m_view->tool() == this)
        m_view->setTool(nullptr);
    if (!probing())
        hideProbe();
    static const char* const hints[] = {
        "", "Probe: move over a surface; Copy puts the values on the clipboard",
        "Distance: click two points", "Angle: click two points", "Radius: click a point"};
    if (mode != Mode::Off)
        Q_EMIT message(tr(hints[int(mode)]));
}

void ProbeTool::hideProbe() {
    m_probe.reset();
    m_text->clear();
    m_panel->hide();
    m_measure->setProbeMarker(std::nullopt);
}

std::optional<ProbePoint> ProbeTool::refine(const PickHit& hit, QPointF position) const {
    const Surface* s = m_doc->surface(hit.surface);
    if (!s)
        return std::nullopt;
    // The pick's (u, v) is the fragment at the centre of the device pixel under the cursor:
    // refine it onto the ray through that centre.
    const qreal dpr = m_view->devicePixelRatioF();
    const QPointF centre((std::floor(position.x() * dpr) + 0.5) / dpr,
                         (std::floor(position.y() * dpr) + 0.5) / dpr);
    glm::dvec3 origin, direction;
    m_view->viewProjection().ray(centre, origin, direction);
    return probeOnRay(*s, hit.uv, origin, direction);
}

std::optional<ProbePoint> ProbeTool::probePoint(QPointF position) {
    const std::optional<PickHit> hit = m_view->pickSurface(position);
    return hit ? refine(*hit, position) : std::nullopt;
}

std::optional<ProbePoint> ProbeTool::probeAt(QPointF position) {
    QElapsedTimer clock;
    clock.start();
    const double cpuStart = threadCpuMs();
    const std::optional<PickHit> hit = m_view->pickSurface(position);
    const qint64 picked = clock.nsecsElapsed();
    m_probe = hit ? refine(*hit, position) : std::nullopt;
    if (!m_probe) {
        hideProbe();
        m_updateMs = clock.nsecsElapsed() * 1e-6;
        m_updateCpuMs = threadCpuMs() - cpuStart;
        m_refineMs = 0.0;
        Q_EMIT probed();
        return std::nullopt;
    }
    m_text->setText(probeText(*m_probe, lengthUnitKey(m_doc->scene().unit)));
    m_refineMs = (clock.nsecsElapsed() - picked) * 1e-6;
    // Grown only, from a width most values fit: a panel that changed size at every move would
    // make the view under it draw its frame again (Viewport::paintEvent), at every hover.
    const int wide = m_panel->fontMetrics().horizontalAdvance(QLatin1Char('0')) * 44;
    const QSize want = m_panel->sizeHint().expandedTo(QSize(wide, 0));
    if (want.width() > m_panel->width() || want.height() > m_panel->height())
        m_panel->resize(m_panel->size().expandedTo(want));
    // A fixed place in the top left corner (the colour legend takes the top right): a panel that
    // followed or fled the cursor could not be reached for Copy. Over the panel the view gets no
    // moves, so the values stay while the cursor goes to its button.
    constexpr int kMargin = 8;
    m_panel->move(kMargin, kMargin);
    m_panel->show();
    m_panel->raise();
    m_measure->setProbeMarker(m_probe->point);
    m_updateMs = clock.nsecsElapsed() * 1e-6;
    m_updateCpuMs = threadCpuMs() - cpuStart;
    Q_EMIT probed();
    return m_probe;
}

bool ProbeTool::measureAt(QPointF position) {
    const std::optional<ProbePoint> p = probePoint(position);
    if (!p) {
        Q_EMIT message(tr("Nothing to measure there: click a surface"));
        return false;
    }
    const auto planes = [this](const ProbePoint& a, const ProbePoint& b) {
        const Surface* sa = m_doc->surface(a.surface);
        const Surface* sb = m_doc->surface(b.surface);
        return sa && sb && surfaceType(*sa) == SurfaceType::Plane &&
               surfaceType(*sb) == SurfaceType::Plane;
    };
    if (const std::optional<Measurement> m = m_measure->addPoint(*p, planes)) {
        Q_EMIT message(measurementText(*m, 8, lengthUnitKey(m_doc->scene().unit)));
        Q_EMIT measured(*m);
    } else {
        Q_EMIT message(tr("First point on %1; click the second").arg(p->name));
    }
    return true;
}

QString ProbeTool::panelText() const {
    return m_probe ? m_text->text() : QString();
}

bool ProbeTool::copyProbe() {
    if (!m_probe)
        return false;
    QApplication::clipboard()->setText(m_text->text());
    Q_EMIT message(tr("Probe values copied"));
    return true;
}

bool ProbeTool::overridesShortcut(const QKeyEvent* k) const {
    // Ctrl+C over the view copies the probe, ahead of any window-wide Copy; P is ours too.
    return (k->matches(QKeySequence::Copy) && probing() && m_probe) ||
           (k->key() == Qt::Key_P && k->modifiers() == Qt::NoModifier);
}

bool ProbeTool::key(QKeyEvent* k) {
    if (k->key() == Qt::Key_P && k->modifiers() == Qt::NoModifier) {
        if (k->isAutoRepeat())
            return false; // held: nothing new (and no frame for the host to draw)
        if (!m_held) {
            m_held = true;
            probeAt(m_view->mapFromGlobal(QCursor::pos()));
        }
        return true;
    }
    if (k->key() == Qt::Key_Escape && m_mode != Mode::Off) {
        if (!m_measure->cancelPending())
            setMode(Mode::Off);
        return true;
    }
    if (k->matches(QKeySequence::Copy) && probing() && m_probe)
        return copyProbe();
    return false;
}

bool ProbeTool::keyRelease(QKeyEvent* k) {
    if (k->key() != Qt::Key_P || k->isAutoRepeat() || !m_held)
        return false;
    m_held = false;
    if (!probing())
        hideProbe();
    return true;
}

void ProbeTool::focusOut() {
    if (m_held) { // the release will not come to the view
        m_held = false;
        if (!probing())
            hideProbe();
    }
}

void ProbeTool::leave() {
    if (probing())
        hideProbe();
}

void ProbeTool::hover(QMouseEvent* m) {
    if (probing() && m->buttons() == Qt::NoButton)
        probeAt(m->position());
}

bool ProbeTool::press(QMouseEvent* m) {
    const bool measuring =
        m_mode == Mode::Distance || m_mode == Mode::Angle || m_mode == Mode::Radius;
    if (!measuring || m->button() != Qt::LeftButton || m->modifiers() != Qt::NoModifier)
        return false; // Probe: clicks select as usual
    measureAt(m->position());
    return true; // no drag: the release goes nowhere
}

void ProbeTool::uninstalled() {
    setMode(Mode::Off);
}

} // namespace kw
