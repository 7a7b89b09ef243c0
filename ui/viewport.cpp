// Viewport: GL lifetime, camera gestures, picking and routing to the tools; its surface draws
// the frames (ui/view_surface.cpp).
#include "ui/viewport.h"

#include "render/edge_bands.h"
#include "render/gl_context.h"
#include "ui/analysiscontrols.h"
#include "ui/tools/viewtools.h"
#include "ui/view_surface.h"

#include <QCoreApplication>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QOpenGLContext>
#include <QPaintEvent>
#include <QPainter>
#include <QUndoStack>
#include <QVBoxLayout>
#include <QWheelEvent>
#include <QWindow>
#include <algorithm>
#include <cmath>

namespace kw {

Viewport::Viewport(Document* document, SceneModel* model, Selection* selection, QUndoStack* stack,
                   QWidget* parent)
    : QWidget(parent), m_doc(document), m_model(model), m_selection(selection), m_stack(stack) {
    setFocusPolicy(Qt::StrongFocus);
    setMouseTracking(true); // hover moves for the tools
    // The frames cover the widget: nothing of its own to paint under them.
    setAttribute(Qt::WA_OpaquePaintEvent);
    setAttribute(Qt::WA_NoSystemBackground);
    // KW_GL_DEBUG=1: a debug context whatever the application's default format (initializeGL
    // starts its log).
    QSurfaceFormat format = QSurfaceFormat::defaultFormat();
    if (glDebugRequested())
        format.setOption(QSurfaceFormat::DebugContext);
    m_view.document = m_doc;
    m_view.renderer = &m_renderer;
    m_view.camera = &m_camera;
    m_view.tools = &m_tools;
    m_surface =
        ViewSurface::create(this, format, m_view,
                            {[this] { initializeGL(); }, [this](int w, int h) { resizeGL(w, h); },
                             [this] {
                                 paintOverlays();
                             }});
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(m_surface->widget());
    if (QWindow* window = m_surface->nativeWindow())
        window->installEventFilter(this);
    setMinimumSize(160, 120);
    m_view.options.controlNet = true;
    m_view.options.samples = samples(); // the automatic count: kept resolved, as setSamples does
    // A document change only asks the surface for a frame; nothing renders inside a signal.
    ViewSurface* frames = m_surface.get();
    connect(m_doc, &Document::surfaceChanged, frames, &ViewSurface::update);
    connect(m_doc, &Document::surfaceInserted, frames, &ViewSurface::update);
    connect(m_doc, &Document::surfaceRemoved, frames, &ViewSurface::update);
    connect(m_doc, &Document::lightsChanged, frames, &ViewSurface::update);
    for (auto& tool : makeViewTools(this))
        m_tools.add(std::move(tool));
    connect(m_doc, &Document::sceneReset, this, [this] {
        m_tools.cancel(); // the live edit has already let go of the old scene's points
        m_view.gesture = Gesture::None;
        resetCamera();
    });
    connect(m_selection, &Selection::changed, frames, &ViewSurface::update);
    connect(frames, &ViewSurface::frameSwapped, this, &Viewport::frameSwapped);
    connect(frames, &ViewSurface::frameDrawn, this, &Viewport::frameDrawn);
    connect(frames, &ViewSurface::framesPerSecond, this, &Viewport::framesPerSecond);
    connect(frames, &ViewSurface::renderError, this, &Viewport::renderError);
    resetCamera();
}

Viewport::~Viewport() {
    // The surface's destructor destroys the context: its aboutToBeDestroyed must not call
    // releaseGl() on this already destroyed Viewport.
    if (QOpenGLContext* gl = context())
        disconnect(gl, &QOpenGLContext::aboutToBeDestroyed, this, &Viewport::releaseGl);
    releaseGl();
    m_surface.reset();
}

void Viewport::releaseGl() {
    if (!m_renderer.isInitialized() && !m_glDebug && !m_surface->holdsGl())
        return;
    makeCurrent();
    m_renderer.release();
    m_surface->releaseGl();
    m_glDebug.reset(); // stops logging while its context is current
    doneCurrent();
}

void Viewport::update() {
    m_surface->update();
}

void Viewport::updateOverlays() {
    m_surface->updateOverlays();
}

void Viewport::addOverlay(QObject* owner, std::function<void(QPainter&)> paint) {
    m_overlays.emplace_back(owner, std::move(paint));
}

void Viewport::makeCurrent() {
    m_surface->makeCurrent();
}

void Viewport::doneCurrent() {
    m_surface->doneCurrent();
}

QOpenGLContext* Viewport::context() const {
    return m_surface->context();
}

QSurfaceFormat Viewport::format() const {
    return m_surface->format();
}

unsigned Viewport::defaultFramebufferObject() const {
    return m_surface->framebuffer();
}

QImage Viewport::grabFramebuffer() {
    return m_surface->grabFramebuffer();
}

bool Viewport::isNativeWindow() const {
    return m_surface->isNativeWindow();
}

QSize Viewport::framePixels() const {
    return devicePixels(*this);
}

double Viewport::aspect() const {
    return height() > 0 ? double(width()) / double(height()) : 1.0;
}

void Viewport::setCamera(const Camera& camera) {
    m_autoFit = false;
    m_camera.setCamera(camera);
    update();
}

void Viewport::resetCamera() {
    const Camera& authored = m_doc->scene().camera;
    m_camera.setCamera(authored.authored ? authored : fitCamera(m_doc->scene(), aspect()));
    m_autoFit = !authored.authored;
    update();
}

void Viewport::fitToView() {
    m_camera.fit(m_doc->scene(), aspect());
    update();
}

void Viewport::setStandardView(StandardView view) {
    m_autoFit = false;
    m_camera.setStandardView(view, m_doc->scene(), aspect());
    update();
}

void Viewport::setRenderMode(RenderMode mode) {
    m_view.options.mode = mode;
    update();
}

void Viewport::setWireframe(bool on) {
    m_view.options.wireframe = on;
    update();
}

void Viewport::setAnalysis(const AnalysisOptions& analysis) {
    m_view.options.analysis = analysis;
    update();
}

void Viewport::drawLegend(QPainter& p) {
    if (m_view.options.edgeBands) {
        // The Edge Continuity overlay's classes, bottom right.
        const std::pair<glm::vec4, QString> rows[] = {
            {continuityColor(ContinuityClass::G2), tr("G2")},
            {continuityColor(ContinuityClass::G1), tr("G1")},
            {continuityColor(ContinuityClass::G0), tr("G0")},
            {continuityColor(ContinuityClass::Open), tr("open")},
            {freeEdgeColor(), tr("free")}};
        const int rowHeight = 18;
        QRect box(width() - 90, height() - 16 - 5 * rowHeight - 8, 76, 5 * rowHeight + 8);
        p.fillRect(box, QColor(0, 0, 0, 140));
        for (int k = 0; k < 5; ++k) {
            const glm::vec4 c = rows[k].first;
            const QRect swatch(box.left() + 6, box.top() + 4 + k * rowHeight + 4, 20, 8);
            p.fillRect(swatch, QColor::fromRgbF(c.r, c.g, c.b));
            p.setPen(Qt::white);
            p.drawText(QRect(swatch.right() + 8, box.top() + 4 + k * rowHeight, 40, rowHeight),
                       Qt::AlignVCenter | Qt::AlignLeft, rows[k].second);
        }
    }
    const AnalysisOptions& a = m_view.options.analysis;
    if (m_view.options.mode == RenderMode::Exact && a.mode == AnalysisMode::Draft) {
        drawDraftLegend(p, QRect(width() - 190, 16, 170, 100), a.pullDirection,
                        a.draftAngleDegrees);
        return;
    }
    if (m_view.options.mode != RenderMode::Exact || !isColourMap(a.mode))
        return;
    const QRect area(width() - 150, 16, 130, std::min(260, height() - 32));
    drawColourLegend(p, area, a.mode, lastFrameReport().analysisRange,
                     a.scale.value_or(defaultScale(a.mode)), !a.range);
}

void Viewport::setEdgeBands(std::shared_ptr<const EdgeBands> bands) {
    m_view.options.edgeBands = std::move(bands);
    update();
}

void Viewport::setControlNet(bool on) {
    m_view.options.controlNet = on;
    update();
}

void Viewport::setTool(Tool* tool) {
    m_tools.install(tool);
    update();
}

void Viewport::showMessage(const QString& text) {
    Q_EMIT message(text);
}

glm::dmat4 Viewport::surfaceDragMatrix(double* amount) const {
    return m_tools.find<SurfaceDragTool>()->matrix(amount);
}

std::optional<ControlPointRef> Viewport::controlPointAt(QPointF pixel) {
    const std::vector<SurfaceId> nets = netSurfaces();
    if (nets.empty())
        return std::nullopt;
    m_picker.update(*m_doc, viewProjection(), &nets);
    return m_picker.nearest(pixel);
}

std::vector<ControlPointRef> Viewport::controlPointsIn(const QRectF& rect) {
    const std::vector<SurfaceId> nets = netSurfaces();
    if (nets.empty())
        return {};
    m_picker.update(*m_doc, viewProjection(), &nets);
    return m_picker.inRect(rect);
}

void Viewport::setControlNetForAll(bool on) {
    m_view.netForAll = on;
    update();
}

void Viewport::setGroundGrid(bool on) {
    m_grid = on;
    update();
}

void Viewport::setAxisIndicator(bool on) {
    m_axes = on;
    update();
}

void Viewport::setBackground(const QColor& c) {
    m_flatBackground = glm::vec4(float(c.redF()), float(c.greenF()), float(c.blueF()), 1.0f);
    setLightBackground(m_lightBackground);
}

void Viewport::setLightBackground(bool on) {
    m_lightBackground = on;
    if (on) {
        backgroundNamed(QStringLiteral("light"), m_view.options);
    } else {
        m_view.options.background = m_flatBackground;
        m_view.options.backgroundTop.reset();
    }
    update();
}

void Viewport::setHeadlight(bool on) {
    m_view.options.headlight = on;
    update();
}

void Viewport::setSections(const std::vector<SectionPlane>& planes, bool caps) {
    std::vector<SectionPlane> kept;
    for (const SectionPlane& p : planes)
        if (int(kept.size()) < kMaxSectionPlanes && checkSectionPlane(p))
            kept.push_back(p);
    if (kept == m_view.options.sections && caps == m_view.options.sectionCaps)
        return;
    m_view.options.sections = std::move(kept);
    m_view.options.sectionCaps = caps;
    update();
}

void Viewport::moveSections(const std::vector<SectionPlane>& planes) {
    setSections(planes, m_view.options.sectionCaps);
    Q_EMIT sectionsMoved(m_view.options.sections, m_view.options.sectionCaps);
}

void Viewport::setTrimMaskCap(int texels) {
    m_view.options.trimMaskCap = std::clamp(texels, kMinTrimMaskSize, 16384);
    update();
}

void Viewport::setTrimMode(RenderOptions::TrimMode mode, std::int64_t budgetBytes) {
    m_view.options.trimMode = mode;
    m_view.options.trimBudgetBytes =
        std::clamp(budgetBytes, kMinTrimBudgetBytes, kMaxTrimBudgetBytes);
    update();
}

void Viewport::setSamples(int samples) {
    m_view.samplesWanted =
        samples == kAutoSamples ? kAutoSamples : std::clamp(samples, 1, kMaxSamples);
    m_view.options.samples = this->samples();
    update();
}

void Viewport::setAntialiasing(RenderOptions::Antialiasing method) {
    m_view.options.antialiasing = method;
    update();
}

void Viewport::setPreviewScale(double scale) {
    m_view.previewScale = std::clamp(scale, 0.125, 1.0);
}

void Viewport::setPassProfiling(bool on) {
    m_renderer.setPassProfiling(on);
}

void Viewport::setPartitioning(RenderOptions::Partitioning mode, double pixelTolerance) {
    m_view.options.partitioning = mode;
    m_view.options.pixelTolerance =
        std::clamp(pixelTolerance, kMinPixelTolerance, kMaxPixelTolerance);
    update();
}

std::vector<SurfaceId> Viewport::netSurfaces() const {
    if (!m_view.options.controlNet)
        return {};
    return shownSurfaces(!m_view.netForAll); // a hidden surface's points cannot be picked either
}

std::vector<SurfaceId> Viewport::shownSurfaces(bool selectedOnly) const {
    std::vector<SurfaceId> shown;
    if (selectedOnly) {
        for (SurfaceId id : m_selection->selectedSurfaces())
            if (const Surface* s = m_doc->surface(id); s && !s->hidden)
                shown.push_back(id);
        return shown;
    }
    for (const Surface& s : m_doc->scene().surfaces)
        if (!s.hidden)
            shown.push_back(s.id);
    return shown;
}

// ---- GL

void Viewport::initializeGL() {
    connect(context(), &QOpenGLContext::aboutToBeDestroyed, this, &Viewport::releaseGl,
            Qt::DirectConnection);
    m_glDebug = startDebugLog(); // KW_GL_DEBUG=1 only
    if (const Status initialized = m_renderer.initialize(); !initialized) {
        m_view.gl = initialized;
        Q_EMIT renderError(QStringLiteral("Renderer unavailable: %1").arg(m_view.gl.message()));
        return;
    }
    // Software OpenGL rasterises every sample on the CPU (aliasedWhileMoving).
    static const QStringList software{QStringLiteral("llvmpipe"), QStringLiteral("softpipe"),
                                      QStringLiteral("SwiftShader"), QStringLiteral("swrast")};
    const QString gl = m_renderer.glDescription();
    m_view.softwareGl = std::any_of(software.begin(), software.end(), [&](const QString& s) {
        return gl.contains(s, Qt::CaseInsensitive);
    });
}

void Viewport::resizeGL(int, int) {
    // A fitted camera was fitted for the old aspect; fit again until the user moves it.
    if (m_autoFit)
        m_camera.setCamera(fitCamera(m_doc->scene(), aspect()));
}

void Viewport::paintEvent(QPaintEvent*) {
    // Nothing of the widget's own: the surface over it draws and shows the frames (a first
    // frame, a resize and an expose are its own), and a frame comes through update().
}

void Viewport::paintOverlays() {
    QPaintDevice* device = m_surface->paintDevice();
    if (!device)
        return;
    std::erase_if(m_overlays, [](const auto& overlay) { return overlay.first.isNull(); });
    // One painter for them all: the surface may paint them first on a device that keeps their
    // bounds (ViewSurface::paintOverlays). Each starts from the painter's defaults.
    QPainter p(device);
    const auto paint = [&p](const auto& draw) {
        p.save();
        draw();
        p.restore();
    };
    paint([&] { drawSelection(p); });
    paint([&] { drawLegend(p); });
    for (const auto& overlay : m_overlays)
        paint([&] { overlay.second(p); });
}

std::optional<PickHit> Viewport::pickSurface(QPointF position) {
    // The frame on screen answers most pixels from what its pre-pass left; a new render of the
    // pixel only where it cannot tell.
    const Renderer::FramePick shown = pickFromFrame(position);
    return shown.known ? shown.hit : pickByDrawing(position);
}

Renderer::FramePick Viewport::pickFromFrame(QPointF position) {
    if (!m_renderer.isInitialized())
        return {};
    makeCurrent();
    const Renderer::FramePick shown = m_renderer.pickInLastFrame(
        *m_doc, m_camera.camera(), framePixels(), position * devicePixelRatioF());
    doneCurrent();
    return shown;
}

std::optional<PickHit> Viewport::pickByDrawing(QPointF position) {
    if (!m_renderer.isInitialized())
        return std::nullopt;
    RenderOptions options = m_view.options;
    options.lightCount = std::clamp(int(m_doc->scene().lights.size()), 1, kMaxLights);
    makeCurrent();
    std::optional<PickHit> hit = m_renderer.pick(*m_doc, m_camera.camera(), framePixels(),
                                                 position * devicePixelRatioF(), options);
    doneCurrent();
    return hit;
}

void Viewport::selectClickedSurface(SurfaceId id, bool additive) {
    const QModelIndex row = m_model->surfaceIndex(id);
    if (!row.isValid())
        return;
    QItemSelectionModel* items = m_selection->itemSelection();
    if (additive) {
        // Shift toggles the surface in the selection, as Ctrl does in the tree.
        items->select(row, QItemSelectionModel::Toggle | QItemSelectionModel::Rows);
        items->setCurrentIndex(row, QItemSelectionModel::NoUpdate);
        return;
    }
    m_selection->setControlPoints({});
    items->setCurrentIndex(row, QItemSelectionModel::ClearAndSelect | QItemSelectionModel::Rows);
}

// ---- Mouse and keys: navigation here, every other gesture to the tools

void Viewport::mousePressEvent(QMouseEvent* event) {
    setFocus(Qt::MouseFocusReason);
    event->accept();
    if (m_view.gesture != Gesture::None || m_tools.active())
        return;
    m_lastPixel = event->position();
    const Qt::KeyboardModifiers mods = event->modifiers();
    if (event->button() == Qt::MiddleButton && (mods & Qt::ShiftModifier))
        m_view.gesture = Gesture::Pan;
    else if (event->button() == Qt::MiddleButton ||
             (event->button() == Qt::LeftButton && (mods & Qt::AltModifier)))
        m_view.gesture = Gesture::Orbit;
    else if (event->button() == Qt::RightButton)
        m_view.gesture = Gesture::Pan;
    else if (event->button() == Qt::LeftButton &&
             m_tools.press(event, !(mods & (Qt::ControlModifier | Qt::AltModifier))))
        update();
}

void Viewport::mouseMoveEvent(QMouseEvent* event) {
    const QPointF pixel = event->position();
    const QPointF delta = pixel - m_lastPixel;
    m_lastPixel = pixel;
    event->accept();
    if (m_view.gesture == Gesture::Orbit || m_view.gesture == Gesture::Pan) {
        m_autoFit = false;
        if (m_view.gesture == Gesture::Orbit)
            m_camera.orbit(delta.x(), delta.y());
        else
            m_camera.pan(delta.x(), delta.y(), size());
        update();
        return;
    }
    // A drag step's time from this event to the frame that shows it (dragMetrics).
    m_surface->moveStarted();
    Tool* gesture = m_tools.active();
    if (!gesture) {
        m_tools.hover(event);
        return;
    }
    gesture->move(event);
    if (isDragging())
        m_surface->moveHandled();
}

void Viewport::mouseReleaseEvent(QMouseEvent* event) {
    event->accept();
    if (m_view.gesture != Gesture::None) {
        m_view.gesture = Gesture::None;
        return;
    }
    if (m_tools.release(event))
        update();
}

void Viewport::mouseDoubleClickEvent(QMouseEvent* event) {
    if (!m_tools.doubleClick(event))
        QWidget::mouseDoubleClickEvent(event);
}

void Viewport::wheelEvent(QWheelEvent* event) {
    m_autoFit = false;
    m_view.wheelClock.start();
    // Toward the cursor: the point under it on the target's view plane stays under it, so
    // eye and target both move toward that point by the zoom's fraction.
    const ViewProjection view = viewProjection();
    const Camera before = m_camera.camera();
    const glm::dvec3 under = view.onViewPlane(event->position(), before.target);
    const double steps = event->angleDelta().y() / 120.0;
    m_camera.zoom(steps);
    Camera after = m_camera.camera();
    const double kept = glm::length(after.eye - after.target) /
                        glm::length(before.eye - before.target); // distance factor
    const glm::dvec3 shift = (1.0 - kept) * (under - before.target);
    after.eye += shift;
    after.target += shift;
    m_camera.setCamera(after);
    update();
    event->accept();
}

void Viewport::keyPressEvent(QKeyEvent* event) {
    const int key = event->key();
    const bool axisKey = key == Qt::Key_X || key == Qt::Key_Y || key == Qt::Key_Z;
    // Held X, Y or Z constrains a drag to that world axis; the drag's tool then steps again.
    if (axisKey && !event->isAutoRepeat())
        m_axis = key - Qt::Key_X;
    if (m_tools.key(event) || axisKey) {
        update();
        event->accept();
        return;
    }
    // A listening tool repaints what it shows itself (the probe's panel): no frame here.
    if (m_tools.listenKey(event)) {
        event->accept();
        return;
    }
    QWidget::keyPressEvent(event);
}

void Viewport::keyReleaseEvent(QKeyEvent* event) {
    const int key = event->key();
    if ((key == Qt::Key_X || key == Qt::Key_Y || key == Qt::Key_Z) && !event->isAutoRepeat()) {
        if (m_axis == key - Qt::Key_X) {
            m_axis = -1;
            m_tools.keyRelease(event);
            update();
        }
        event->accept();
        return;
    }
    if (m_tools.keyRelease(event) || m_tools.listenKeyRelease(event)) {
        event->accept();
        return;
    }
    QWidget::keyReleaseEvent(event);
}

void Viewport::focusOutEvent(QFocusEvent* event) {
    m_axis = -1;
    m_tools.focusOut();
    QWidget::focusOutEvent(event);
}

void Viewport::leaveEvent(QEvent* event) {
    m_tools.leave();
    QWidget::leaveEvent(event);
}

bool Viewport::event(QEvent* event) {
    // A key a tool wants over the view comes to keyPressEvent, not to a window shortcut.
    if (event->type() == QEvent::ShortcutOverride &&
        m_tools.overridesShortcut(static_cast<QKeyEvent*>(event))) {
        event->accept();
        return true;
    }
    return QWidget::event(event);
}

bool Viewport::eventFilter(QObject* watched, QEvent* event) {
    // (No surface while the destructor lets it go.)
    if (!m_surface || watched != m_surface->nativeWindow())
        return QWidget::eventFilter(watched, event);
    // The native window asks for no input, but a platform that cannot make it transparent for
    // input (or a test's events sent to it) gives it some: it is the view's, at the view's
    // positions (the window fills it from its corner). Mouse and wheel go straight to the
    // handlers, so that a drag step enters no file twice; the rest through QWidget's own
    // dispatch (Tab's focus move, the context-menu policy, enter and leave), which hands what
    // the view ignores to its parents. Disabled, the view takes none of it, as QWidget.
    const bool enabled = isEnabled();
    switch (event->type()) {
    case QEvent::MouseButtonPress:
        if (enabled)
            mousePressEvent(static_cast<QMouseEvent*>(event));
        return true;
    case QEvent::MouseButtonRelease:
        if (enabled)
            mouseReleaseEvent(static_cast<QMouseEvent*>(event));
        return true;
    case QEvent::MouseButtonDblClick:
        if (enabled)
            mouseDoubleClickEvent(static_cast<QMouseEvent*>(event));
        return true;
    case QEvent::MouseMove:
        if (enabled)
            mouseMoveEvent(static_cast<QMouseEvent*>(event));
        return true;
    case QEvent::Wheel:
        if (enabled)
            wheelEvent(static_cast<QWheelEvent*>(event));
        return true;
    case QEvent::KeyPress:
    case QEvent::KeyRelease:
    case QEvent::TabletPress:
    case QEvent::TabletMove:
    case QEvent::TabletRelease:
    case QEvent::ContextMenu:
    case QEvent::Enter:
    case QEvent::Leave:
        QCoreApplication::sendEvent(this, event);
        return true;
    default:
        return false;
    }
}

} // namespace kw
