// ViewSurface: the 3D view's native OpenGL window (or its QOpenGLWidget fallback).
#include "ui/view_surface.h"

#include <QCoreApplication>
#include <QEvent>
#include <QGuiApplication>
#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QOpenGLExtraFunctions>
#include <QOpenGLFramebufferObject>
#include <QOpenGLPaintDevice>
#include <QOpenGLWidget>
#include <QPaintEvent>
#include <QPointer>
#include <QRegion>
#include <QWidget>
#include <QWindow>

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
/// make a window transparent for input, what it gets is handed to the view's widget.
class ViewWindow : public QWindow {
public:
    ViewWindow(NativeSurface* surface, QWidget* host) : m_surface(surface), m_host(host) {
        setSurfaceType(QSurface::OpenGLSurface);
        setFlags(flags() | Qt::WindowTransparentForInput | Qt::WindowDoesNotAcceptFocus);
    }

protected:
    void exposeEvent(QExposeEvent*) override;
    bool event(QEvent* event) override;

private:
    NativeSurface* m_surface;
    QPointer<QWidget> m_host;
};

class NativeSurface final : public ViewSurface {
public:
    NativeSurface(QWidget* host, const QSurfaceFormat& format, Callbacks callbacks)
        : ViewSurface(std::move(callbacks)), m_format(format) {
        m_window = new ViewWindow(this, host);
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
    QOpenGLContext* context() const override { return m_context.get(); }
    QSurfaceFormat format() const override {
        return m_context && m_context->isValid() ? m_context->format() : m_format;
    }
    unsigned framebuffer() const override { return m_fbo ? m_fbo->handle() : 0u; }

    void requestFrame() override {
        m_paintPending = true;
        post();
    }

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

    QPaintDevice* paintDevice() override {
        if (!m_fbo)
            return nullptr;
        if (!m_device)
            m_device = std::make_unique<Device>(this);
        m_device->setSize(m_fbo->size());
        m_device->setDevicePixelRatio(devicePixelRatio());
        return m_device.get();
    }

    QImage grabFramebuffer() override {
        if (!ensureContext())
            return {};
        makeCurrent();
        if (!m_fbo)
            return {};
        m_callbacks.paint();
        m_drawn = true;
        makeCurrent();
        const QImage image =
            readFrame(m_context.get(), m_fbo->handle(), m_fbo->size(), devicePixelRatio());
        // The window shows what was grabbed, as a QOpenGLWidget would at its next composition.
        m_presentPending = true;
        post();
        return image;
    }

    void bindFramebuffer() {
        if (m_fbo)
            m_fbo->bind();
    }

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
        m_callbacks.resize(m_container->width(), m_container->height());
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
            m_callbacks.paint();
            m_drawn = true;
            makeCurrent(); // the view may have let it go (a pick)
        }
        m_presentPending = false;
        QOpenGLExtraFunctions* f = m_context->extraFunctions();
        const QSize pixels = m_fbo->size();
        blitColour(f, m_fbo->handle(), m_context->defaultFramebufferObject(), pixels);
        m_context->swapBuffers(m_window);
        m_fbo->bind();
        Q_EMIT frameSwapped();
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
    switch (event->type()) {
    case QEvent::UpdateRequest:
        m_surface->updateRequested();
        return true;
    case QEvent::MouseButtonPress:
    case QEvent::MouseButtonRelease:
    case QEvent::MouseButtonDblClick:
    case QEvent::MouseMove:
    case QEvent::Wheel:
    case QEvent::KeyPress:
    case QEvent::KeyRelease:
    case QEvent::TabletPress:
    case QEvent::TabletMove:
    case QEvent::TabletRelease:
    case QEvent::ContextMenu:
    case QEvent::Enter:
    case QEvent::Leave:
        // The window fills the view's widget from its corner: positions carry over as they
        // are.
        if (m_host) {
            const std::unique_ptr<QEvent> copy(event->clone());
            QCoreApplication::sendEvent(m_host, copy.get());
            event->setAccepted(copy->isAccepted());
            return true;
        }
        break;
    default:
        break;
    }
    return QWindow::event(event);
}

// ---- The fallback: a QOpenGLWidget

class ViewWidget : public QOpenGLWidget {
public:
    ViewWidget(const ViewSurface::Callbacks& callbacks, QWidget* parent)
        : QOpenGLWidget(parent), m_callbacks(callbacks) {}

protected:
    void initializeGL() override { m_callbacks.initialize(); }
    void resizeGL(int w, int h) override { m_callbacks.resize(w, h); }
    void paintGL() override {
        m_callbacks.paint();
        m_painted = true;
    }
    void paintEvent(QPaintEvent* event) override {
        // QOpenGLWidget draws its frame again at every paint event, and a child widget's
        // repaint sends one for the part under it: that part is the last frame composed
        // again, no new frame.
        if (m_painted && !QRegion(rect()).subtracted(event->region()).isEmpty())
            return;
        QOpenGLWidget::paintEvent(event);
    }

private:
    const ViewSurface::Callbacks& m_callbacks;
    bool m_painted = false;
};

class WidgetSurface final : public ViewSurface {
public:
    WidgetSurface(QWidget* host, const QSurfaceFormat& format, Callbacks callbacks)
        : ViewSurface(std::move(callbacks)) {
        m_widget = new ViewWidget(m_callbacks, host);
        m_widget->setObjectName(QStringLiteral("viewWidget"));
        m_widget->setFormat(format);
        m_widget->setAttribute(Qt::WA_TransparentForMouseEvents);
        m_widget->setFocusPolicy(Qt::NoFocus);
        connect(m_widget, &QOpenGLWidget::frameSwapped, this, &ViewSurface::frameSwapped);
    }
    ~WidgetSurface() override { delete m_widget.data(); }

    QWidget* widget() const override { return m_widget; }
    bool isNativeWindow() const override { return false; }
    void requestFrame() override { m_widget->update(); }
    void makeCurrent() override { m_widget->makeCurrent(); }
    void doneCurrent() override { m_widget->doneCurrent(); }
    QOpenGLContext* context() const override { return m_widget->context(); }
    QSurfaceFormat format() const override { return m_widget->format(); }
    unsigned framebuffer() const override { return m_widget->defaultFramebufferObject(); }
    QPaintDevice* paintDevice() override { return m_widget; }
    QImage grabFramebuffer() override { return m_widget->grabFramebuffer(); }

private:
    QPointer<ViewWidget> m_widget;
};

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
                                                 Callbacks callbacks) {
    if (nativeWindowsAvailable()) {
        // A native widget over the view (the probe's panel) would otherwise make its siblings
        // native, and through them the view and every widget of the main window.
        QCoreApplication::setAttribute(Qt::AA_DontCreateNativeWidgetSiblings);
        return std::make_unique<NativeSurface>(host, format, std::move(callbacks));
    }
    return std::make_unique<WidgetSurface>(host, format, std::move(callbacks));
}

} // namespace kw
