// Renderer: the render module's one entry point. Draws a Document into a framebuffer of the
// current OpenGL 4.5 core context and answers pick queries; its GPU state lives behind a
// private implementation, so this header needs no GL types (hosts pass framebuffer names).
#pragma once

#include "model/document/document.h"
#include "render/frame_report.h"
#include "render/render_types.h"
#include "render/triangle_mesh.h"

#include <QPointF>
#include <QSize>
#include <QString>
#include <memory>
#include <optional>

namespace kw {

class Renderer {
public:
    Renderer();
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    /// Needs a current OpenGL 4.5 core context (the one every later call uses). Returns the
    /// error when there is no current context or it is not 4.5 core.
    Status initialize();
    bool isInitialized() const;

    /// Draws `doc` as seen by `camera` into `target`, uploading only stale surface data first.
    /// options.writeAov is taken from target.aov. The report's ok is false, with error set, when
    /// a shader does not build (nothing drawn), when a surface's control net exceeds the GPU's
    /// texture size (the frame is drawn without it), or when trim masks exceed the GPU's limits
    /// (those surfaces are drawn untrimmed). Trimmed surfaces are cut by their masks unless
    /// options.trims is false. Surface ids and revisions are per document: drawing another
    /// Document than last time drops every cached upload first. Hidden surfaces
    /// (Surface::hidden) are not drawn. With options.frameReuse an aliased frame is drawn into
    /// the renderer's own framebuffer and copied, and after an edit may redraw only what the
    /// changed surfaces covered (FrameReport::partial; render/partial_frame.h); any other draw
    /// into `target` between frames is then overwritten whole. Leaves the scissor test off.
    FrameReport render(const Document& doc, const Camera& camera, const RenderTarget& target,
                       const RenderOptions& options);

    /// The surface visible at `pixel` (x right, y down, in pixels of a `viewport`-sized frame
    /// drawn with `camera` and `options`), or nullopt for background, a trimmed-away spot or a
    /// pixel outside the viewport; hidden surfaces are never hit. Draws the exact pass with AOVs
    /// into a private framebuffer, scissored to that one pixel, of only the surfaces whose
    /// projected bounds reach it (FrameCamera::pickPixel), and reads it back; the masks and
    /// uploads it needs are the frame's own, so a pick after a frame uploads nothing. Overlays are
    /// ignored. Needs the renderer's context current; leaves the framebuffer binding at 0. A pick
    /// that cannot be made (before initialize(), no pick framebuffer) finds nothing.
    std::optional<PickHit> pick(const Document& doc, const Camera& camera, QSize viewport,
                                QPointF pixel, const RenderOptions& options = {});

    /// pick() answered from the last frame drawn, without drawing: when that frame showed
    /// `doc` at its current revision, from `camera`, at `viewport`'s size, as neither a preview
    /// nor an AOV frame, and its deferred pre-pass wrote the pixel, the surface there and the
    /// polygon's (u, v) under the pixel (within the partition's pixel tolerance of the exact
    /// point, and of the frame's sample offset: refine it onto the pixel's ray, as the probe
    /// does), read back from that frame's buffers (a few bytes); a pixel that frame left
    /// empty is background. `known` is false where the frame cannot tell (another view or
    /// revision, a skirt or fin, a cell a section plane crosses, no deferred pass): then
    /// pick(). The forward pass's surfaces leave their data in the pre-pass as the deferred
    /// pass's do.
    /// Needs the renderer's context current.
    struct FramePick {
        bool known = false;
        std::optional<PickHit> hit;
    };
    FramePick pickInLastFrame(const Document& doc, const Camera& camera, QSize viewport,
                              QPointF pixel);

    /// Meshes built outside the renderer (the benchmark's comparison rows: libGLU's
    /// tessellation, a prebuilt fine mesh) for renderMesh. Sends `mesh` to the GPU as mesh
    /// `slot` (0..kMeshSlots - 1), replacing what it held; returns the bytes sent, or -1 for
    /// a bad slot or before initialize(). Needs the renderer's context current.
    std::int64_t setMesh(int slot, const TriangleMesh& mesh);
    static constexpr int kMeshSlots = 4;
    /// Draws mesh `slot` into `target` instead of the document's surfaces: the target cleared
    /// as render() clears it, the camera's planes and lights from `doc` and `options` as
    /// render() takes them, and each surface's triangles with the tessellated baseline's
    /// Gouraud shading and the material of the surface of `doc` with its id (triangles of
    /// other ids are skipped). Trims, partitions and overlays do not apply. The report has
    /// the draw calls, the surfaces drawn, CPU ms and the bytes resident (the meshes' under
    /// tessellatedMeshes); ok false with error set for an empty slot or a shader that does
    /// not build.
    FrameReport renderMesh(const Document& doc, int slot, const Camera& camera,
                           const RenderTarget& target, const RenderOptions& options);
    /// renderMesh drawing several slots into one frame (cleared once), in the order given: a
    /// mesh kept in one slot and the part that changes in another (the bench's edit loop
    /// re-sends only the edited face). ok false for an empty list or an empty slot.
    FrameReport renderMeshes(const Document& doc, const std::vector<int>& slots,
                             const Camera& camera, const RenderTarget& target,
                             const RenderOptions& options);

    /// Times each pass of every later frame (FrameReport::passes), ending each with glFinish:
    /// for profiling only, since the waits keep the CPU and the GPU from overlapping.
    void setPassProfiling(bool on);
    bool passProfiling() const;
    /// The next RenderOptions::progressive frame starts its image again at the first sample,
    /// though nothing changed (what changes a frame's pixels restarts it by itself).
    void restartProgressive();
    /// Frees all GL objects; the initialising context must be current.
    void release();

    /// GL_RENDERER and GL_VERSION of the context, for reports.
    QString glDescription() const;

private:
    /// Render's tests inspect GPU state through RendererTestHook (render/renderer_test_hook.h).
    friend struct RendererTestHook;
    struct Impl;
    std::unique_ptr<Impl> d;
};

} // namespace kw
