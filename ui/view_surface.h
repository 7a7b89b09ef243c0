// ViewSurface: where the 3D view's frames are drawn and shown. The view (Viewport) stays a plain
// QWidget; its surface is a child that fills it, asks the renderer for each frame itself (the
// frame policy: previews while moving, progressive anti-aliasing, the still frame, partial
// frames, the bare frame kept for overlays, timing) from the view's state (ViewState), and
// calls the view back to set up, resize and paint the overlays. Two kinds:
// - a native OpenGL window in a window container (the default): a frame is drawn into a
//   framebuffer object, blitted to the window and swapped on its own, so the rest of the main
//   window is not composed through OpenGL at every frame (on llvmpipe that composition cost
//   more than the frame; docs/PERFORMANCE.md "The editor's frame rate");
// - a QOpenGLWidget where the platform has no native child windows (offscreen, eglfs, wasm).
// Both keep the frame in a framebuffer object with depth and stencil that outlives it (the
// probe reads the last frame's pre-pass back), and neither takes input: the view's own widget
// gets the mouse, the wheel, keys and focus, as the tests' events do. Input that reaches the
// native window anyway (a platform that cannot make it transparent for input, events sent to
// it) the view takes through an event filter on nativeWindow(), without a hop through here.
#pragma once

#include "render/renderer.h"
#include "ui/tools/tool.h"

#include <QElapsedTimer>
#include <QImage>
#include <QObject>
#include <QRect>
#include <QSize>
#include <QSurfaceFormat>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

class QOpenGLContext;
class QOpenGLExtraFunctions;
class QOpenGLFramebufferObject;
class QPaintDevice;
class QTimer;
class QWidget;
class QWindow;

namespace kw {

class CameraController;

/// The widget's size in device pixels, at least 1 x 1: the size of the frames drawn for it.
QSize devicePixels(const QWidget& widget);
/// Blits the colour of framebuffer `from` onto framebuffer `to`, both `pixels` in size (no
/// scissor, every channel written).
void blitColour(QOpenGLExtraFunctions* f, unsigned from, unsigned to, QSize pixels);

/// What the view's frames are drawn from: the view (Viewport) owns it and changes it, its
/// surface reads it at every frame. Plain data and inline reads, so that a frame needs no trip
/// back into the view's code on its way to the renderer.
struct ViewState {
    /// Navigation the view runs itself; every other gesture is a tool's.
    enum class Gesture { None, Orbit, Pan };
    static constexpr int kAutoSamples = 0;
    static constexpr int kAutoSamplesCount = 4;
    static constexpr int kStillMs = 250;
    static constexpr double kPreviewScale = 0.5;

    // What is drawn, set once by the view (all outlive the surface).
    const Document* document = nullptr;
    Renderer* renderer = nullptr;
    const CameraController* camera = nullptr;
    const ToolRouter* tools = nullptr;

    /// The view's options, samples resolved (Viewport::renderOptions).
    RenderOptions options;
    bool netForAll = false; ///< nets of every surface, not only the selected ones
    int samplesWanted = kAutoSamples;
    bool softwareGl = false; ///< the context is a software rasteriser (set at initialize)
    double previewScale = kPreviewScale;
    bool partialFrames = true;
    /// Why the renderer could not be set up (ok until it failed).
    Status gl;
    Gesture gesture = Gesture::None;
    QElapsedTimer wheelClock; ///< the last wheel zoom (the view moving without a gesture)

    int samples() const {
        return samplesWanted == kAutoSamples ? kAutoSamplesCount : samplesWanted;
    }
    bool aliasedWhileMoving() const { return samplesWanted == kAutoSamples && softwareGl; }
    bool previewWhileMoving() const { return softwareGl && previewScale < 1.0; }
    /// A wheel zoom less than kStillMs ago.
    bool wheeling() const { return wheelClock.isValid() && wheelClock.elapsed() < kStillMs; }
    /// A tool's drag is editing the document (points, surfaces or a weight).
    bool dragging() const { return tools->active() && tools->active()->editing(); }
    /// The view moves: navigation, a tool's gesture or a recent wheel zoom.
    bool moving() const { return gesture != Gesture::None || tools->active() || wheeling(); }
    /// The camera or the document moves: the next frame comes anyway.
    bool changing() const { return gesture != Gesture::None || dragging() || wheeling(); }
};

/// Where a frame's time went in the frame and after it (wall ms): the render call, the
/// QPainter overlays (selection outline, nets, legend) and the frame's way to the screen up to
/// frameSwapped (0 until it comes): the native window's blit and swap, or the fallback
/// QOpenGLWidget's composition of the whole main window and swap.
struct FrameTiming {
    double renderMs = 0.0;
    double painterMs = 0.0;
    double swapMs = 0.0;
    bool moving = false; ///< drawn while the view moved (a preview when previewWhileMoving)
};

/// Responsiveness during drags: for each drag step that reached a frame, the wall time from
/// the mouse-move event to the start of the next frame (the draw call), and that frame's
/// FrameReport (its CPU time by phase, uploads and draw calls).
struct DragMetrics {
    std::vector<double> moveToDrawMs;
    std::vector<double> handlerMs; ///< of moveToDrawMs: the mouse-move handler itself
    std::vector<FrameReport> frames;
};

class ViewSurface : public QObject {
    Q_OBJECT
public:
    /// The view's side: each called with the context current; paintOverlays with
    /// framebuffer() bound, over a frame just drawn or restored.
    struct Callbacks {
        std::function<void()> initialize;
        std::function<void(int width, int height)> resize; ///< logical pixels
        std::function<void()> paintOverlays;
    };
    /// A native window's surface where the platform has child windows, else a QOpenGLWidget's;
    /// its widget() is a child of `host`, which lays it out. Frames are drawn from `view`,
    /// which must outlive the surface.
    static std::unique_ptr<ViewSurface> create(QWidget* host, const QSurfaceFormat& format,
                                               const ViewState& view, Callbacks callbacks);
    /// Whether create() gives a native window on this platform.
    static bool nativeWindowsAvailable();
    ~ViewSurface() override;

    /// Draws a new frame soon (many calls, one frame).
    void update();
    /// Paints the overlays again over the last frame without drawing a new one (a hover's
    /// probe marker, a rubber band); a new frame when the last one was drawn while moving.
    void updateOverlays();
    /// Paints a frame now and returns it (QOpenGLWidget::grabFramebuffer); null without GL.
    QImage grabFramebuffer();

    /// The widget that shows the frames (the window container or the QOpenGLWidget).
    virtual QWidget* widget() const = 0;
    virtual bool isNativeWindow() const = 0;
    /// The native window that shows the frames, null for the fallback. It asks for no input;
    /// what it gets all the same is the host's to filter (its positions are the host's: the
    /// window fills it from its corner).
    virtual QWindow* nativeWindow() const { return nullptr; }
    /// The context current with the frame's framebuffer bound, as QOpenGLWidget::makeCurrent.
    virtual void makeCurrent() = 0;
    virtual void doneCurrent() = 0;
    /// Null until the first frame or grab made it.
    virtual QOpenGLContext* context() const = 0;
    virtual QSurfaceFormat format() const = 0;
    /// The framebuffer the frame is drawn into (valid inside paint).
    virtual unsigned framebuffer() const = 0;
    /// For QPainter over the frame, inside paint only (while the overlays' bounds are taken, a
    /// device that keeps them, ui/overlay_bounds.h).
    QPaintDevice* paintDevice();

    /// The frame's own GL objects (the bare frame kept for overlays): whether there are any,
    /// and letting them go with the context current.
    bool holdsGl() const { return m_cleanFrame != nullptr; }
    void releaseGl();

    /// A drag step's mouse move starts, and its handler is done: the time from the move to
    /// the frame that shows it goes to dragMetrics().
    void moveStarted() { m_moveClock.start(); }
    void moveHandled() {
        m_moveTimed = true;
        m_handlerMs = double(m_moveClock.nsecsElapsed()) * 1e-6;
    }
    const DragMetrics& dragMetrics() const { return m_metrics; }
    void resetDragMetrics() { m_metrics = {}; }
    /// The report of the last frame drawn (empty before the first).
    const FrameReport& lastFrameReport() const { return m_lastReport; }
    const FrameTiming& lastFrameTiming() const { return m_timing; }
    /// Frames drawn since construction.
    std::int64_t framesDrawn() const { return m_framesDrawn; }

Q_SIGNALS:
    /// A frame is on screen (QOpenGLWidget::frameSwapped).
    void frameSwapped();
    /// Once a second while frames are drawn: frames in the last second and the last frame's
    /// report.
    void framesPerSecond(double fps, const kw::FrameReport& lastFrame);
    /// After every frame, with its report.
    void frameDrawn(const kw::FrameReport& frame);
    /// A frame failed (once per new message, for the status bar).
    void renderError(const QString& message);

protected:
    ViewSurface(QWidget* host, const ViewState& view, Callbacks callbacks);
    /// Paints a frame soon (coalesced: one frame for many requests).
    virtual void requestFrame() = 0;
    /// Paints a frame now into framebuffer() (with its context current) and reads it back.
    virtual QImage grab() = 0;
    /// The frame's framebuffer as a QPainter device.
    virtual QPaintDevice* frameDevice() = 0;
    /// Whether framebuffer() keeps its pixels from one frame to the next, with nothing but
    /// this view drawing into it: a partial frame then copies only what changed
    /// (RenderTarget::drawnOver). Not a QOpenGLWidget's, which Qt may discard.
    virtual bool keepsPixels() const { return false; }
    /// The kinds' calls: the frame's framebuffer was made at a new size; paint a frame into it
    /// (the frame policy, then the view's overlays); the frame is on screen.
    void resized(int width, int height);
    void paint();
    void swapped();

    Callbacks m_callbacks;

private:
    /// The frame: the view's options made this frame's (previews while moving, progressive
    /// anti-aliasing, partial frames), drawn, its error reported, its overlays painted, timed.
    void drawFrame(QSize pixels);
    RenderOptions frameOptions(bool moving);
    void paintUnavailable();
    void reportError();
    /// The next sample of a refining image: now, or when still.
    void refine(bool moving);
    /// Frames per second, drag metrics.
    void count(double moveToDrawMs, bool timed);
    /// Draws again kStillMs from now (restarted by every call): the still frame after a move.
    void drawAgainWhenStill();
    /// The frame before its overlays, kept after still frames (updateOverlays): copy, restore.
    void keepCleanFrame(QSize pixels);
    bool restoreCleanFrame(QSize pixels);
    /// The view's overlays over the frame; while m_drawnOver is kept, their bounds (painted
    /// first on OverlayBounds) join it.
    void paintOverlays(QSize pixels);

    QWidget* m_host;
    const ViewState& m_view;
    std::unique_ptr<QOpenGLFramebufferObject> m_cleanFrame; ///< the last still frame, bare
    bool m_cleanFrameValid = false;
    /// What was painted over framebuffer() since the renderer's last frame into it (GL pixels;
    /// RenderTarget::drawnOver); unset when not known or not needed (a framebuffer that does
    /// not keep its pixels or is new, a last frame the next one copies whole anyway).
    std::optional<QRect> m_drawnOver;
    QPaintDevice* m_recording = nullptr; ///< the overlays' bounds device while they are taken
    bool m_framePending = false;    ///< update() since the last frame
    bool m_overlaysOnly = false;    ///< updateOverlays() since the last frame
    QTimer* m_stillTimer = nullptr; ///< draws the anti-aliased still frame after moving
    int m_stillRestarts = 0; ///< consecutive still frames that were a new image's first sample
    FrameTiming m_timing;
    QElapsedTimer m_paintEnd; ///< from the end of the frame to frameSwapped
    QString m_lastRenderError;
    FrameReport m_lastReport;
    QElapsedTimer m_moveClock; ///< started by a drag's mouse move, read by the next frame
    bool m_moveTimed = false;
    double m_handlerMs = 0.0; ///< duration of the last timed mouse-move handler
    DragMetrics m_metrics;
    QElapsedTimer m_fpsClock; ///< frames per second: frames drawn over wall time
    int m_frames = 0;
    std::int64_t m_framesDrawn = 0;
};

} // namespace kw
