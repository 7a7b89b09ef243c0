// ViewSurface: the 3D view's native OpenGL window (or its QOpenGLWidget fallback), and the
// frame policy of its frames.
#include "ui/view_surface.h"

#include "ui/cameracontroller.h"
#include "ui/overlay_bounds.h"

#include <QCoreApplication>
#include <QEvent>
#include <QGuiApplication>
#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QOpenGLExtraFunctions>
#include <QOpenGLFramebufferObject>
#include <QOpenGLFunctions>
#include <QOpenGLPaintDevice>
#include <QOpenGLWidget>
#include <QPaintEvent>
#include <QPainter>
#include <QPointer>
#include <QRegion>
#include <QTimer>
#include <QWidget>
#include <QWindow>
#include <algorithm>

namespace kw {

namespace {

/// A frame read back as QOpenGLWidget::grabFramebuffer reads it (no alpha: opaque RGB).
QImage readFrame(QOpenGLContext* gl, GLuint fbo, QSize pixels, qreal dpr) {
    QOpenGLExtraFunctions* f = gl->extraFunctions();
    f->glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    f->glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    f->glPixelStorei(GL_PACK_ALIGNMENT, 4);
    f->glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    f->glReadBuffer(GL_COLOR_ATTACHMENT0);
    QImage image(pixels, QImage::Format_RGBA8888);
    f->glReadPixels(0, 0, pixels.width(), pixels.height(), GL_RGBA, GL_UNSIGNED_BYTE, image.bits());
    image = image.convertToFormat(QImage::Format_RGBX8888).mirrored();
    image.setDevicePixelRatio(dpr);
    return image;
}

// ---- The native window

class NativeSurface;

/// The window: shows the frames; takes no input (Qt::WindowTransparentForInput), so that the
/// view's widget under it gets the mouse as it would without it; where the platform cannot
/// make a window transparent for input, the view filters what it gets (nativeWindow()).
class ViewWindow : public QWindow {
public:
    explicit ViewWindow(NativeSurface* surface) : m_surface(surface) {
        setSurfaceType(QSurface::OpenGLSurface);
        setFlags(flags() | Qt::WindowTransparentForInput | Qt::WindowDoesNotAcceptFocus);
    }

protected:
    void exposeEvent(QExposeEvent*) override;
    bool event(QEvent* event) override;

private:
    NativeSurface* m_surface;
};

class NativeSurface final : public ViewSurface {
public:
    NativeSurface(QWidget* host, const QSurfaceFormat& format, const ViewState& view,
                  Callbacks callbacks)
        : ViewSurface(host, view, std::move(callbacks)), m_format(format) {
        m_window = new ViewWindow(this);
        m_window->setFormat(format);
        // The container owns the window.
        m_container = QWidget::createWindowContainer(m_window, host);
        m_container->setObjectName(QStringLiteral("viewWindowContainer"));
        m_container->setAttribute(Qt::WA_TransparentForMouseEvents);
        m_container->setFocusPolicy(Qt::NoFocus);
        m_container->installEventFilter(this);
    }

    ~NativeSurface() override {
        if (m_context && m_context->isValid()) {
            makeCurrent();
            m_device.reset();
            m_fbo.reset();
            doneCurrent();
        }
        m_context.reset(); // aboutToBeDestroyed: the view lets its resources go first
        delete m_container.data();
    }

    QWidget* widget() const override { return m_container; }
    bool isNativeWindow() const override { return true; }
    QWindow* nativeWindow() const override { return m_window; }
    QOpenGLContext* context() const override { return m_context.get(); }
    QSurfaceFormat format() const override {
        return m_context && m_context->isValid() ? m_context->format() : m_format;
    }
    unsigned framebuffer() const override { return m_fbo ? m_fbo->handle() : 0u; }

    void makeCurrent() override {
        if (!ensureContext())
            return;
        // The window once it exists, else a hidden surface: frames go to the framebuffer
        // object either way, only the swap needs the window.
        if (!m_context->makeCurrent(surface()))
            return;
        ensureFramebuffer();
        if (m_fbo)
            m_fbo->bind();
    }

    void doneCurrent() override {
        if (m_context)
            m_context->doneCurrent();
    }

    QPaintDevice* frameDevice() override {
        if (!m_fbo)
            return nullptr;
        if (!m_device)
            m_device = std::make_unique<Device>(this);
        m_device->setSize(m_fbo->size());
        m_device->setDevicePixelRatio(devicePixelRatio());
        return m_device.get();
    }

    void bindFramebuffer() {
        if (m_fbo)
            m_fbo->bind();
    }

protected:
    // The framebuffer object is the view's own: only its frames and overlays draw into it.
    bool keepsPixels() const override { return true; }

public:
    void exposed() {
        if (m_window->isExposed())
            show(m_paintPending || !m_drawn);
    }

    void updateRequested() {
        m_posted = false;
        if (m_paintPending || m_presentPending)
            show(m_paintPending || !m_drawn);
    }

protected:
    void requestFrame() override {
        m_paintPending = true;
        post();
    }

    QImage grab() override {
        if (!ensureContext())
            return {};
        makeCurrent();
        if (!m_fbo)
            return {};
        paint();
        m_drawn = true;
        makeCurrent();
        const QImage image =
            readFrame(m_context.get(), m_fbo->handle(), m_fbo->size(), devicePixelRatio());
        // The window shows what was grabbed, as a QOpenGLWidget would at its next composition.
        m_presentPending = true;
        post();
        return image;
    }

    bool eventFilter(QObject* watched, QEvent* event) override {
        // As QOpenGLWidget::resizeEvent: the context made, the framebuffer resized (which
        // tells the view), a frame asked for.
        if (watched == m_container && event->type() == QEvent::Resize &&
            !m_container->size().isEmpty()) {
            if (ensureContext())
                makeCurrent();
            requestFrame();
        }
        return false;
    }

private:
    /// QPainter on the framebuffer object (QOpenGLWidget paints the same way on its own).
    class Device : public QOpenGLPaintDevice {
    public:
        explicit Device(NativeSurface* surface) : m_surface(surface) {}
        void ensureActiveTarget() override { m_surface->bindFramebuffer(); }

    private:
        NativeSurface* m_surface;
    };

    QSurface* surface() const {
        return m_window->handle() ? static_cast<QSurface*>(m_window)
                                  : static_cast<QSurface*>(m_offscreen.get());
    }

    qreal devicePixelRatio() const { return m_container->devicePixelRatioF(); }

    QSize framePixels() const { return devicePixels(*m_container); }

    void post() {
        if (m_posted)
            return;
        m_posted = true;
        // Low priority, as a widget's update: waiting input (the next mouse move) comes first.
        QCoreApplication::postEvent(m_window, new QEvent(QEvent::UpdateRequest),
                                    Qt::LowEventPriority);
    }

    bool ensureContext() {
        if (m_context)
            return m_context->isValid();
        m_context = std::make_unique<QOpenGLContext>();
        m_context->setFormat(m_format);
        if (QOpenGLContext* share = QOpenGLContext::globalShareContext())
            m_context->setShareContext(share);
        m_context->setScreen(m_window->screen());
        if (!m_context->create())
            return false;
        m_offscreen = std::make_unique<QOffscreenSurface>(m_window->screen());
        m_offscreen->setFormat(m_context->format());
        m_offscreen->create();
        // As QOpenGLWidget: set up first, then the framebuffer's size (resize), then frames.
        if (!m_context->makeCurrent(surface()))
            return false;
        m_callbacks.initialize();
        return true;
    }

    /// The framebuffer object at the widget's size: depth and stencil as QOpenGLWidget's.
    void ensureFramebuffer() {
        const QSize pixels = framePixels();
        if (m_fbo && m_fbo->size() == pixels)
            return;
        QOpenGLFramebufferObjectFormat f;
        f.setAttachment(QOpenGLFramebufferObject::CombinedDepthStencil);
        f.setSamples(0);
        m_fbo = std::make_unique<QOpenGLFramebufferObject>(pixels, f);
        m_drawn = false;
        m_fbo->bind();
        resized(m_container->width(), m_container->height());
    }

    /// Paints a frame if asked (else shows the last one again), blits it to the window and
    /// swaps.
    void show(bool paint) {
        if (!m_window->isExposed() || !ensureContext())
            return;
        makeCurrent();
        if (!m_fbo || QOpenGLContext::currentContext() != m_context.get())
            return;
        if (paint || !m_drawn) {
            m_paintPending = false;
            ViewSurface::paint();
            m_drawn = true;
            makeCurrent(); // the view may have let it go (a pick)
        }
        m_presentPending = false;
        QOpenGLExtraFunctions* f = m_context->extraFunctions();
        const QSize pixels = m_fbo->size();
        blitColour(f, m_fbo->handle(), m_context->defaultFramebufferObject(), pixels);
        m_context->swapBuffers(m_window);
        m_fbo->bind();
        swapped();
    }

    QSurfaceFormat m_format;
    ViewWindow* m_window = nullptr;
    QPointer<QWidget> m_container;
    std::unique_ptr<QOpenGLContext> m_context;
    std::unique_ptr<QOffscreenSurface> m_offscreen;
    std::unique_ptr<QOpenGLFramebufferObject> m_fbo;
    std::unique_ptr<Device> m_device;
    bool m_posted = false;         ///< an UpdateRequest is on its way
    bool m_paintPending = true;    ///< requestFrame since the last frame
    bool m_presentPending = false; ///< the frame object changed outside a frame (a grab)
    bool m_drawn = false;          ///< the frame object holds a frame of its size
};

void ViewWindow::exposeEvent(QExposeEvent*) {
    m_surface->exposed();
}

bool ViewWindow::event(QEvent* event) {
    if (event->type() == QEvent::UpdateRequest) {
        m_surface->updateRequested();
        return true;
    }
    return QWindow::event(event);
}

// ---- The fallback: a QOpenGLWidget

class WidgetSurface;

class ViewWidget : public QOpenGLWidget {
public:
    ViewWidget(WidgetSurface* surface, QWidget* parent)
        : QOpenGLWidget(parent), m_surface(surface) {}

protected:
    void initializeGL() override;
    void resizeGL(int w, int h) override;
    void paintGL() override;
    void paintEvent(QPaintEvent* event) override {
        // QOpenGLWidget draws its frame again at every paint event, and a child widget's
        // repaint sends one for the part under it: that part is the last frame composed
        // again, no new frame.
        if (m_painted && !QRegion(rect()).subtracted(event->region()).isEmpty())
            return;
        QOpenGLWidget::paintEvent(event);
    }

private:
    WidgetSurface* m_surface;
    bool m_painted = false;
};

class WidgetSurface final : public ViewSurface {
public:
    WidgetSurface(QWidget* host, const QSurfaceFormat& format, const ViewState& view,
                  Callbacks callbacks)
        : ViewSurface(host, view, std::move(callbacks)) {
        m_widget = new ViewWidget(this, host);
        m_widget->setObjectName(QStringLiteral("viewWidget"));
        m_widget->setFormat(format);
        m_widget->setAttribute(Qt::WA_TransparentForMouseEvents);
        m_widget->setFocusPolicy(Qt::NoFocus);
        connect(m_widget, &QOpenGLWidget::frameSwapped, this, [this] { swapped(); });
    }
    ~WidgetSurface() override { delete m_widget.data(); }

    QWidget* widget() const override { return m_widget; }
    bool isNativeWindow() const override { return false; }
    void makeCurrent() override { m_widget->makeCurrent(); }
    void doneCurrent() override { m_widget->doneCurrent(); }
    QOpenGLContext* context() const override { return m_widget->context(); }
    QSurfaceFormat format() const override { return m_widget->format(); }
    unsigned framebuffer() const override { return m_widget->defaultFramebufferObject(); }
    QPaintDevice* frameDevice() override { return m_widget; }

    // ViewWidget's calls.
    void initializeGl() { m_callbacks.initialize(); }
    void resizeGl(int w, int h) { resized(w, h); }
    void paintGl() { paint(); }

protected:
    void requestFrame() override { m_widget->update(); }
    QImage grab() override { return m_widget->grabFramebuffer(); }

private:
    QPointer<ViewWidget> m_widget;
};

void ViewWidget::initializeGL() {
    m_surface->initializeGl();
}

void ViewWidget::resizeGL(int w, int h) {
    m_surface->resizeGl(w, h);
}

void ViewWidget::paintGL() {
    m_surface->paintGl();
    m_painted = true;
}

} // namespace

QSize devicePixels(const QWidget& widget) {
    const qreal dpr = widget.devicePixelRatioF();
    return QSize(qMax(1, qRound(widget.width() * dpr)), qMax(1, qRound(widget.height() * dpr)));
}

void blitColour(QOpenGLExtraFunctions* f, unsigned from, unsigned to, QSize pixels) {
    f->glBindFramebuffer(GL_READ_FRAMEBUFFER, from);
    f->glReadBuffer(GL_COLOR_ATTACHMENT0);
    f->glBindFramebuffer(GL_DRAW_FRAMEBUFFER, to);
    f->glDisable(GL_SCISSOR_TEST);
    f->glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    f->glBlitFramebuffer(0, 0, pixels.width(), pixels.height(), 0, 0, pixels.width(),
                         pixels.height(), GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

bool ViewSurface::nativeWindowsAvailable() {
    // KNOTWORK_VIEW=widget: the QOpenGLWidget, for comparison and for platforms not listed.
    if (qEnvironmentVariable("KNOTWORK_VIEW") == QLatin1String("widget"))
        return false;
    const QString platform = QGuiApplication::platformName();
    return platform == QLatin1String("xcb") || platform.startsWith(QLatin1String("wayland")) ||
           platform == QLatin1String("windows") || platform == QLatin1String("cocoa");
}

std::unique_ptr<ViewSurface> ViewSurface::create(QWidget* host, const QSurfaceFormat& format,
                                                 const ViewState& view, Callbacks callbacks) {
    if (nativeWindowsAvailable()) {
        // A native widget over the view (the probe's panel) would otherwise make its siblings
        // native, and through them the view and every widget of the main window.
        QCoreApplication::setAttribute(Qt::AA_DontCreateNativeWidgetSiblings);
        return std::make_unique<NativeSurface>(host, format, view, std::move(callbacks));
    }
    return std::make_unique<WidgetSurface>(host, format, view, std::move(callbacks));
}

// ---- The frames

ViewSurface::ViewSurface(QWidget* host, const ViewState& view, Callbacks callbacks)
    : m_callbacks(std::move(callbacks)), m_host(host), m_view(view) {}

ViewSurface::~ViewSurface() = default;

void ViewSurface::update() {
    m_framePending = true;
    requestFrame();
}

void ViewSurface::updateOverlays() {
    m_overlaysOnly = true;
    requestFrame();
}

QImage ViewSurface::grabFramebuffer() {
    m_framePending = true;
    return grab();
}

void ViewSurface::releaseGl() {
    m_cleanFrame.reset();
    m_cleanFrameValid = false;
    m_drawnOver.reset();
}

void ViewSurface::resized(int width, int height) {
    m_cleanFrameValid = false; // the framebuffer is new
    m_drawnOver.reset();
    m_callbacks.resize(width, height);
}

void ViewSurface::swapped() {
    // The window's composition and swap of the frame drawn (lastFrameTiming).
    if (m_paintEnd.isValid()) {
        m_timing.swapMs = double(m_paintEnd.nsecsElapsed()) * 1e-6;
        m_paintEnd.invalidate();
    }
    Q_EMIT frameSwapped();
}

void ViewSurface::paint() {
    const bool overlaysOnly = m_overlaysOnly && !m_framePending && m_cleanFrameValid;
    m_overlaysOnly = m_framePending = false;
    // The view's size: the frames cover it.
    const QSize pixels = devicePixels(*m_host);
    if (overlaysOnly && m_view.renderer->isInitialized() && restoreCleanFrame(pixels)) {
        // Only what is painted over the frame changed (a probe marker): the last still frame
        // again, its overlays painted anew; no new frame.
        paintOverlays(pixels);
        return;
    }
    drawFrame(pixels);
}

void ViewSurface::drawFrame(QSize pixels) {
    const bool timed = m_moveTimed;
    const double moveToDraw = timed ? double(m_moveClock.nsecsElapsed()) * 1e-6 : 0.0;
    m_moveTimed = false;
    Renderer& renderer = *m_view.renderer;
    if (!renderer.isInitialized()) {
        paintUnavailable();
        return;
    }
    QElapsedTimer paintClock;
    paintClock.start();
    const bool moving = m_view.moving();
    const RenderOptions options = frameOptions(moving);
    m_lastReport = renderer.render(*m_view.document, m_view.camera->camera(),
                                   {framebuffer(), pixels, false, false, m_drawnOver}, options);
    // The frame alone, until its overlays are painted. Where the next frame copies whole
    // anyway (this one went straight into the framebuffer, a preview, a failed frame), nothing
    // is measured: the overlays are painted once.
    m_drawnOver = keepsPixels() && m_lastReport.ok && m_lastReport.keptInHost
                      ? std::optional<QRect>(QRect())
                      : std::nullopt;
    m_timing.renderMs = double(paintClock.nsecsElapsed()) * 1e-6;
    reportError();
    refine(moving);
    const qint64 painterStart = paintClock.nsecsElapsed();
    // A frame is kept bare, so that its overlays can be painted again alone (the probe's
    // marker, a rubber band), unless the camera or the document is moving: the next frame
    // comes anyway.
    if (!m_view.changing())
        keepCleanFrame(pixels);
    else
        m_cleanFrameValid = false;
    paintOverlays(pixels);
    if (renderer.passProfiling()) {
        // The QPainter overlays' GL work, finished here, as the renderer's passes are.
        makeCurrent();
        context()->functions()->glFinish();
    }
    m_timing.painterMs = double(paintClock.nsecsElapsed() - painterStart) * 1e-6;
    m_timing.swapMs = 0.0;
    m_timing.moving = moving;
    m_paintEnd.start();
    Q_EMIT frameDrawn(m_lastReport);
    count(moveToDraw, timed);
}

RenderOptions ViewSurface::frameOptions(bool moving) {
    RenderOptions options = m_view.options;
    if (moving && m_view.previewWhileMoving()) {
        // A preview: fewer exact pixels, aliased, magnified; the still frame kStillMs after
        // the last move is the full image again (its samples a frame at a time).
        options.previewScale = m_view.previewScale;
        options.samples = 1;
        // The silhouettes' last fraction of a pixel (the fins) is not seen in motion.
        options.silhouetteFins = false;
        drawAgainWhenStill();
    } else if (options.samples > 1 && m_view.aliasedWhileMoving()) {
        if (options.antialiasing == RenderOptions::Antialiasing::Accumulate) {
            // A sample per frame: a moving view draws its first, a still one adds the rest.
            options.progressive = true;
        } else if (moving) { // MSAA: aliased while moving, all samples in the still frame
            options.samples = 1;
            drawAgainWhenStill();
        }
    }
    options.analysis.holdRange = m_view.dragging();
    // A drag step redraws the dragged face's pixels, not the view's; anti-aliased frames are
    // drawn whole anyway.
    options.frameReuse =
        m_view.partialFrames ? RenderOptions::FrameReuse::Partial : RenderOptions::FrameReuse::None;
    // The renderer draws every net; with nets for the selection only, the view's overlays
    // draw them.
    options.controlNet = m_view.options.controlNet && m_view.netForAll;
    options.lightCount = std::clamp(int(m_view.document->scene().lights.size()), 1, kMaxLights);
    return options;
}

void ViewSurface::paintUnavailable() {
    m_drawnOver.reset();
    QPaintDevice* device = paintDevice();
    if (!device)
        return;
    QPainter p(device);
    const QRect rect = m_host->rect();
    p.fillRect(rect, QColor(46, 48, 54));
    p.setPen(Qt::white);
    p.drawText(rect.adjusted(12, 12, -12, -12), Qt::AlignCenter | Qt::TextWordWrap,
               QStringLiteral("The 3D view is unavailable:\n%1").arg(m_view.gl.message()));
}

void ViewSurface::reportError() {
    if (m_lastReport.ok) {
        m_lastRenderError.clear();
        return;
    }
    if (m_lastReport.error != m_lastRenderError) {
        m_lastRenderError = m_lastReport.error;
        Q_EMIT renderError(QStringLiteral("Frame failed: %1").arg(m_lastRenderError));
    }
}

void ViewSurface::refine(bool moving) {
    // Still frames that started their image again, one after the other: each found something
    // changed though the view did not move (a slider held, or something that changes every
    // frame).
    const bool restarted = !moving && m_lastReport.samplesInImage == 1;
    m_stillRestarts = restarted ? m_stillRestarts + 1 : 0;
    if (!m_lastReport.refining)
        return;
    // The next sample: at once when the view is still, else once it has been for kStillMs
    // (a moving view's next frame starts the image again). After two restarts in a row also
    // kStillMs later, so that what changes the image every frame is not drawn again and again
    // as fast as the machine can.
    if (moving || m_stillRestarts >= 2)
        drawAgainWhenStill();
    else
        update();
}

void ViewSurface::count(double moveToDrawMs, bool timed) {
    if (timed) {
        m_metrics.moveToDrawMs.push_back(moveToDrawMs);
        m_metrics.handlerMs.push_back(m_handlerMs);
        m_metrics.frames.push_back(m_lastReport);
    }
    ++m_framesDrawn;
    if (!m_fpsClock.isValid())
        m_fpsClock.start();
    ++m_frames;
    if (m_fpsClock.elapsed() >= 1000) {
        Q_EMIT framesPerSecond(m_frames * 1000.0 / double(m_fpsClock.elapsed()), m_lastReport);
        m_frames = 0;
        m_fpsClock.restart();
    }
}

void ViewSurface::drawAgainWhenStill() {
    if (!m_stillTimer) {
        m_stillTimer = new QTimer(this);
        m_stillTimer->setSingleShot(true);
        connect(m_stillTimer, &QTimer::timeout, this, [this] { update(); });
    }
    m_stillTimer->start(ViewState::kStillMs);
}

QPaintDevice* ViewSurface::paintDevice() {
    return m_recording ? m_recording : frameDevice();
}

void ViewSurface::paintOverlays(QSize pixels) {
    if (m_drawnOver) {
        // Painted once on a device that keeps their bounds: the next partial frame copies its
        // rectangles and these over them, and the rest of the framebuffer is already that
        // frame (RenderTarget::drawnOver).
        if (QPaintDevice* frame = frameDevice()) {
            OverlayBounds bounds(*frame);
            m_recording = &bounds;
            m_callbacks.paintOverlays();
            m_recording = nullptr;
            const QRect b = bounds.bounds();
            // GL rows run bottom-up.
            const QRect gl =
                QRect(b.x(), pixels.height() - b.y() - b.height(), b.width(), b.height())
                    .intersected(QRect(QPoint(0, 0), pixels));
            if (!gl.isEmpty())
                m_drawnOver = m_drawnOver->isEmpty() ? gl : m_drawnOver->united(gl);
        }
    }
    m_callbacks.paintOverlays();
}

void ViewSurface::keepCleanFrame(QSize pixels) {
    if (!m_cleanFrame || m_cleanFrame->size() != pixels)
        m_cleanFrame = std::make_unique<QOpenGLFramebufferObject>(pixels);
    blitColour(context()->extraFunctions(), framebuffer(), m_cleanFrame->handle(), pixels);
    context()->extraFunctions()->glBindFramebuffer(GL_FRAMEBUFFER, framebuffer());
    m_cleanFrameValid = true;
}

bool ViewSurface::restoreCleanFrame(QSize pixels) {
    if (!m_cleanFrameValid || !m_cleanFrame || m_cleanFrame->size() != pixels)
        return false;
    blitColour(context()->extraFunctions(), m_cleanFrame->handle(), framebuffer(), pixels);
    context()->extraFunctions()->glBindFramebuffer(GL_FRAMEBUFFER, framebuffer());
    return true;
}

} // namespace kw
