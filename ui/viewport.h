// Viewport: the 3D view of the document: orbit, pan, zoom, standard views, picking and the
// overlays; every other gesture is a tool's (ui/tools/). A plain widget: a ViewSurface that
// fills it (a native OpenGL window, ui/view_surface.h) draws its frames from its state
// (ViewState) with the render module and shows them.
#pragma once

#include "model/document/selection.h"
#include "render/renderer.h"
#include "ui/cameracontroller.h"
#include "ui/controlpointpicker.h"
#include "ui/tools/tool.h"
#include "ui/view_surface.h"

#include <QImage>
#include <QOpenGLDebugLogger>
#include <QPointer>
#include <QSurfaceFormat>
#include <QWidget>
#include <functional>
#include <map>
#include <memory>
#include <vector>

class QKeyEvent;
class QMouseEvent;
class QOpenGLContext;
class QPainter;
class QUndoStack;

namespace kw {

/// Mouse: middle drag or Alt+left drag orbits, right drag or Shift+middle drag pans, the wheel
/// zooms; every other press goes to the tools (ui/tools/tool.h), the installed one first, then
/// those of ui/tools/viewtools.cpp in order: a left drag on a section plane's handle (an arrow
/// along its normal) moves the plane along it, Ctrl+Shift drag on a point sets its weight, Ctrl
/// drag moves, rotates or scales the selected surfaces, a left click picks the nearest control
/// point within a few pixels (Shift adds or removes) and a drag from it moves the picked
/// points in the view plane (hold X, Y or Z to move along that world axis), a left drag
/// elsewhere draws a rubber band. Esc cancels a drag. A drag edits the document live through
/// a LiveEdit and its release is one undo step; a refused step's reason goes to message().
class Viewport : public QWidget {
    Q_OBJECT
public:
    /// All pointers must outlive the viewport; `model` is the one `selection` was built on.
    Viewport(Document* document, SceneModel* model, Selection* selection, QUndoStack* stack,
             QWidget* parent = nullptr);
    ~Viewport() override;

    const CameraController& cameraController() const { return m_camera; }
    void setCamera(const Camera& camera);
    /// The camera of the document if it has one, else a fitted one.
    void resetCamera();
    void fitToView();
    void setStandardView(StandardView view);
    /// The mapping the picker and the tools use for the current camera and size (here, so that
    /// a drag step reads it without a trip back into the view's code).
    ViewProjection viewProjection() const {
        return ViewProjection(m_camera.camera(), m_doc->scene(), size());
    }

    /// The view's options, samples resolved (automatic: kAutoSamplesCount); what a frame
    /// changes while the view moves (fewer samples, progressive) is not in them.
    const RenderOptions& renderOptions() const { return m_view.options; }
    void setRenderMode(RenderMode mode);
    void setWireframe(bool on);
    /// Control nets on or off; while on, only the selected surfaces' nets are drawn and
    /// pickable unless setControlNetForAll(true).
    void setControlNet(bool on);
    /// The Edge Continuity overlay's bands (null: none) and its legend.
    void setEdgeBands(std::shared_ptr<const EdgeBands> bands);
    /// Analysis colouring (View ▸ Analysis). While a drag runs the automatic colour range is
    /// held (AnalysisOptions::holdRange), so colours do not swim; it follows on release.
    void setAnalysis(const AnalysisOptions& analysis);
    bool controlNetForAll() const { return m_view.netForAll; }
    void setControlNetForAll(bool on);
    bool groundGrid() const { return m_grid; }
    void setGroundGrid(bool on);
    bool axisIndicator() const { return m_axes; }
    void setAxisIndicator(bool on);
    void setBackground(const QColor& color);
    /// The light gradient (kw::backgroundNamed "light") instead of the flat colour above.
    void setLightBackground(bool on);
    bool lightBackground() const { return m_lightBackground; }
    void setHeadlight(bool on);
    /// Section planes (at most kMaxSectionPlanes; invalid ones, a zero normal, are left out)
    /// and caps: view state saved with the project (DisplaySettings), not an edit.
    void setSections(const std::vector<SectionPlane>& planes, bool caps);
    const std::vector<SectionPlane>& sections() const { return m_view.options.sections; }
    /// setSections from the view itself (a plane's handle dragged): the caps stay, and
    /// sectionsMoved() tells the Section dialog.
    void moveSections(const std::vector<SectionPlane>& planes);
    bool sectionCaps() const { return m_view.options.sectionCaps; }
    /// Trim mask budget (RenderOptions::trimMaskCap), clamped to what the renderer accepts.
    void setTrimMaskCap(int texels);
    /// How trims cut (RenderOptions::trimMode) and exact trims' memory budget in bytes.
    void setTrimMode(RenderOptions::TrimMode mode, std::int64_t budgetBytes);
    /// Anti-aliasing samples per pixel (RenderOptions::samples), clamped to 1..kMaxSamples;
    /// 0 (kAutoSamples, the default) draws kAutoSamplesCount, except that on a software
    /// rasteriser (llvmpipe), where 4 samples cost several times the frame (docs/PERFORMANCE.md
    /// ## Trims), frames drawn while the view moves or points are dragged are aliased: with
    /// accumulation (the default method) each frame draws one sample, the first of a new image
    /// or the next of a still one (RenderOptions::progressive), and a still view is drawn
    /// again until all its samples are in; with MSAA the still frame kStillMs later draws all
    /// of them at once.
    void setSamples(int samples);
    /// How frames with samples > 1 are anti-aliased (RenderOptions::antialiasing).
    void setAntialiasing(RenderOptions::Antialiasing method);
    static constexpr int kAutoSamples = ViewState::kAutoSamples;
    static constexpr int kAutoSamplesCount = ViewState::kAutoSamplesCount;
    static constexpr int kStillMs = ViewState::kStillMs;
    /// The samples of a still frame (setSamples' choice, automatic resolved).
    int samples() const { return m_view.samples(); }
    /// Whether frames drawn while the view moves are aliased (automatic on software OpenGL;
    /// known once the context exists). With accumulation, still frames are then drawn a sample
    /// at a time (FrameReport::samplesInImage, refining).
    bool aliasedWhileMoving() const { return m_view.aliasedWhileMoving(); }
    /// While the view moves (orbit, pan, a wheel zoom, a tool's drag) on a software rasteriser,
    /// frames are previews (RenderOptions::previewScale): aliased, at previewScale() of the
    /// view's width and height, magnified; the still frame kStillMs after the last move is the
    /// full anti-aliased image, the same pixels as without the previews. 1 turns them off.
    bool previewWhileMoving() const { return m_view.previewWhileMoving(); }
    double previewScale() const { return m_view.previewScale; }
    void setPreviewScale(double scale);
    /// At 0.5 a preview draws a quarter of the pixels: an orbit of a 223-face part at the
    /// default window runs at ~15 FPS on two CPU cores (docs/PERFORMANCE.md ## Editing).
    static constexpr double kPreviewScale = ViewState::kPreviewScale;
    /// Aliased frames after an edit redraw only the rectangle the changed surfaces covered
    /// before and cover now, the rest kept from the last frame (RenderOptions::FrameReuse::
    /// Partial; on by default). Off draws every frame whole, as before (for measuring).
    void setPartialFrames(bool on) { m_view.partialFrames = on; }
    bool partialFrames() const { return m_view.partialFrames; }
    /// Adaptive partitions within `pixelTolerance` (clamped to kMin..kMaxPixelTolerance), the
    /// sliders then being the minimum, or the paper's uniform sliders' grid.
    void setPartitioning(RenderOptions::Partitioning mode, double pixelTolerance);
    RenderOptions::Partitioning partitioning() const { return m_view.options.partitioning; }
    double pixelTolerance() const { return m_view.options.pixelTolerance; }
    /// The surfaces whose nets are drawn and pickable now.
    std::vector<SurfaceId> netSurfaces() const;

    /// What Ctrl + drag does to the selected surfaces (Modify ▸ Ctrl+Drag Moves / Rotates /
    /// Scales). Rotation is about the centre of their control-point bounds, about the held
    /// axis (X, Y, Z) or else the view direction, by the angle the cursor turns about that
    /// centre (on the plane through it across the axis); scale is about the same centre by the
    /// ratio of the cursor's distances from it, along the held axis only or uniformly. Shift
    /// snaps to 15° or to steps of 0.1. The release pushes one TransformSurfaces step, the
    /// exact affine map applied to the press-time points.
    enum class SurfaceDrag { Move, Rotate, Scale };
    void setSurfaceDrag(SurfaceDrag mode) { m_surfaceDrag = mode; }
    SurfaceDrag surfaceDrag() const { return m_surfaceDrag; }
    /// The map the running rotate or scale drag applies (identity otherwise), and its angle in
    /// radians or its factor through `amount`.
    glm::dmat4 surfaceDragMatrix(double* amount = nullptr) const;
    /// Draws a new frame soon (QWidget::update of the view; many calls, one frame).
    void update();
    /// Paints the overlays again over the last frame without drawing a new one (a hover's
    /// probe marker, a rubber band); a new frame when the last one was drawn while moving.
    void updateOverlays();
    /// Adds a QPainter overlay drawn over every frame after the view's own (the measurements'
    /// dimensions), until `owner` is destroyed. It draws and does nothing else: it may be
    /// called twice a frame, once to measure where it falls (ViewSurface::paintOverlays).
    void addOverlay(QObject* owner, std::function<void(QPainter&)> paint);
    /// As QOpenGLWidget's: the view's context current with its frame's framebuffer bound,
    /// the context (null before the first frame), its format, that framebuffer, and a frame
    /// painted now and read back.
    void makeCurrent();
    void doneCurrent();
    QOpenGLContext* context() const;
    QSurfaceFormat format() const;
    unsigned defaultFramebufferObject() const;
    QImage grabFramebuffer();
    /// Frames go to a native OpenGL window (else, where the platform has no native child
    /// windows or KNOTWORK_VIEW=widget, to a QOpenGLWidget: ui/view_surface.h).
    bool isNativeWindow() const;

    /// Installs a tool (a mode such as the curve tool; nullptr removes it): it sees plain
    /// left presses, hover moves and keys first, and draws over the frame. The tool must
    /// outlive its installation; navigation keeps working under it.
    void setTool(Tool* tool);
    Tool* tool() const { return m_tools.installed(); }
    /// Adds a listening tool (ToolRouter::listen): hover moves, keys no other tool used, and
    /// presses once it is installed with setTool. It must outlive the view's events (a child
    /// QObject of the view does).
    void listen(Tool* tool) { m_tools.listen(tool); }

    // For the tools: the document and what they pick in this view.
    Document* document() const { return m_doc; }
    SceneModel* sceneModel() const { return m_model; }
    Selection* selection() const { return m_selection; }
    QUndoStack* undoStack() const { return m_stack; }
    /// The nearest pickable control point within a few pixels of `pixel`, if any.
    std::optional<ControlPointRef> controlPointAt(QPointF pixel);
    /// The pickable control points inside `rect` (widget pixels).
    std::vector<ControlPointRef> controlPointsIn(const QRectF& rect);
    /// Click selection: the surface alone, or toggled in the selection with `additive`.
    void selectClickedSurface(SurfaceId id, bool additive);
    /// The surfaces that are not hidden, in document order: the selected ones only, or all.
    /// Hidden surfaces show no outline or net, and neither their points nor they can be dragged.
    std::vector<SurfaceId> shownSurfaces(bool selectedOnly) const;
    /// Emits message(text): a tool's word for the status bar.
    void showMessage(const QString& text);

    /// ok when the renderer is ready (or not yet set up); else why it could not be set up
    /// (shown in the view).
    const Status& glError() const { return m_view.gl; }
    /// A tool's drag is editing the document (points, surfaces or a weight).
    bool isDragging() const { return m_view.dragging(); }
    /// World axis a drag is constrained to (0 x, 1 y, 2 z) or -1.
    int axisConstraint() const { return m_axis; }

    /// Responsiveness during drags (kw::DragMetrics, ui/view_surface.h).
    using DragMetrics = kw::DragMetrics;
    const DragMetrics& dragMetrics() const { return m_surface->dragMetrics(); }
    void resetDragMetrics() { m_surface->resetDragMetrics(); }
    /// The report of the last frame drawn (empty before the first).
    const FrameReport& lastFrameReport() const { return m_surface->lastFrameReport(); }
    /// Renderer::pick at a widget position (logical pixels) of the current view; makes the
    /// view's context current. nullopt when nothing is there or GL is unavailable.
    std::optional<PickHit> pickSurface(QPointF position);
    /// pickSurface's two ways: the frame on screen read back at the pixel
    /// (Renderer::pickInLastFrame: a few bytes, nothing drawn; not known where that frame
    /// cannot tell), and a render of the pixel (Renderer::pick), which pickSurface draws only
    /// where the first does not know.
    Renderer::FramePick pickFromFrame(QPointF position);
    std::optional<PickHit> pickByDrawing(QPointF position);
    /// Frames painted since construction.
    std::int64_t framesDrawn() const { return m_surface->framesDrawn(); }
    /// Where the last frame's time went (kw::FrameTiming, ui/view_surface.h).
    using FrameTiming = kw::FrameTiming;
    const FrameTiming& lastFrameTiming() const { return m_surface->lastFrameTiming(); }
    /// Renderer::setPassProfiling for this view's frames (FrameReport::passes), the QPainter
    /// overlays' GL work finished too; for measuring only.
    void setPassProfiling(bool on);

Q_SIGNALS:
    /// Once a second while frames are drawn: frames in the last second and the last frame's
    /// report (its cpuMs.total is the render call's CPU time).
    void framesPerSecond(double fps, const kw::FrameReport& lastFrame);
    /// After every frame, with its report: the status bar shows the last frame's time even
    /// when idle, when framesPerSecond is quiet.
    void frameDrawn(const kw::FrameReport& frame);
    /// The renderer could not be set up or a frame failed (message for the status bar).
    void renderError(const QString& message);
    /// A tool's message for the status bar, such as why a drag step was refused.
    void message(const QString& text);
    /// The section planes moved in the view (moveSections), as now drawn.
    void sectionsMoved(const std::vector<kw::SectionPlane>& planes, bool caps);
    /// A frame is on screen (QOpenGLWidget::frameSwapped).
    void frameSwapped();

protected:
    void initializeGL();
    void resizeGL(int w, int h);
    void paintEvent(QPaintEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;
    void mouseDoubleClickEvent(QMouseEvent* event) override;
    void wheelEvent(QWheelEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;
    void keyReleaseEvent(QKeyEvent* event) override;
    void focusOutEvent(QFocusEvent* event) override;
    void leaveEvent(QEvent* event) override;
    bool event(QEvent* event) override;
    /// What reaches the native window (nativeWindow()) is the view's input (see the .cpp).
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    using Gesture = ViewState::Gesture;
    void releaseGl();
    void drawSelection(QPainter& p);
    void drawLegend(QPainter& p);
    /// QPainter overlays: highlighted selected surfaces, their control nets, grid, axes.
    void drawOverlays(class QPainter& p, const ViewProjection& view);
    /// All the QPainter work over a frame: selection, nets, tools, legend, added overlays.
    void paintOverlays();
    QSize framePixels() const;
    double aspect() const;

    /// What the frames are drawn from; the surface draws them (the frame policy).
    ViewState m_view;
    std::unique_ptr<ViewSurface> m_surface;
    std::vector<std::pair<QPointer<QObject>, std::function<void(QPainter&)>>> m_overlays;
    Document* m_doc;
    SceneModel* m_model;
    Selection* m_selection;
    QUndoStack* m_stack;
    Renderer m_renderer;
    CameraController m_camera;
    ControlPointPicker m_picker;
    std::unique_ptr<QOpenGLDebugLogger> m_glDebug; ///< KW_GL_DEBUG=1: the driver's messages

    QPointF m_lastPixel;
    int m_axis = -1;
    SurfaceDrag m_surfaceDrag = SurfaceDrag::Move;
    ToolRouter m_tools;
    bool m_grid = false;
    bool m_axes = true;
    bool m_lightBackground = false;
    glm::vec4 m_flatBackground = RenderOptions{}.background; ///< setBackground's colour
    bool m_autoFit = true; ///< refit on resize until the user moves the camera
};

} // namespace kw
