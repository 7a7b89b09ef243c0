// ViewSurface: where the 3D view's frames are drawn and shown. The view (Viewport) stays a plain
// QWidget; its surface is a child that fills it and calls the view back to set up, resize and
// paint. Two kinds:
// - a native OpenGL window in a window container (the default): a frame is drawn into a
//   framebuffer object, blitted to the window and swapped on its own, so the rest of the main
//   window is not composed through OpenGL at every frame (on llvmpipe that composition cost
//   more than the frame; docs/PERFORMANCE.md "The editor's frame rate");
// - a QOpenGLWidget where the platform has no native child windows (offscreen, eglfs, wasm).
// Both keep the frame in a framebuffer object with depth and stencil that outlives it (the
// probe reads the last frame's pre-pass back), and neither takes input: the view's own widget
// gets the mouse, the wheel, keys and focus, as the tests' events do.
#pragma once

#include <QImage>
#include <QObject>
#include <QSize>
#include <QSurfaceFormat>
#include <functional>
#include <memory>

class QOpenGLContext;
class QOpenGLExtraFunctions;
class QPaintDevice;
class QWidget;

namespace kw {

/// The widget's size in device pixels, at least 1 x 1: the size of the frames drawn for it.
QSize devicePixels(const QWidget& widget);
/// Blits the colour of framebuffer `from` onto framebuffer `to`, both `pixels` in size (no
/// scissor, every channel written).
void blitColour(QOpenGLExtraFunctions* f, unsigned from, unsigned to, QSize pixels);

class ViewSurface : public QObject {
    Q_OBJECT
public:
    /// The view's side: each called with the context current; paint with framebuffer() bound.
    struct Callbacks {
        std::function<void()> initialize;
        std::function<void(int width, int height)> resize; ///< logical pixels
        std::function<void()> paint;
    };
    /// A native window's surface where the platform has child windows, else a QOpenGLWidget's;
    /// its widget() is a child of `host`, which lays it out.
    static std::unique_ptr<ViewSurface> create(QWidget* host, const QSurfaceFormat& format,
                                               Callbacks callbacks);
    /// Whether create() gives a native window on this platform.
    static bool nativeWindowsAvailable();

    /// The widget that shows the frames (the window container or the QOpenGLWidget).
    virtual QWidget* widget() const = 0;
    virtual bool isNativeWindow() const = 0;
    /// Paints a frame soon (coalesced: one frame for many requests).
    virtual void requestFrame() = 0;
    /// The context current with the frame's framebuffer bound, as QOpenGLWidget::makeCurrent.
    virtual void makeCurrent() = 0;
    virtual void doneCurrent() = 0;
    /// Null until the first frame or grab made it.
    virtual QOpenGLContext* context() const = 0;
    virtual QSurfaceFormat format() const = 0;
    /// The framebuffer the frame is drawn into (valid inside paint).
    virtual unsigned framebuffer() const = 0;
    /// For QPainter over the frame, inside paint only.
    virtual QPaintDevice* paintDevice() = 0;
    /// Paints a frame now and returns it (QOpenGLWidget::grabFramebuffer); null without GL.
    virtual QImage grabFramebuffer() = 0;

Q_SIGNALS:
    /// A frame is on screen (QOpenGLWidget::frameSwapped).
    void frameSwapped();

protected:
    explicit ViewSurface(Callbacks callbacks) : m_callbacks(std::move(callbacks)) {}
    Callbacks m_callbacks;
};

} // namespace kw
