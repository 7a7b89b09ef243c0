// The partial frame (docs/RENDERING.md, "The partial frame"): what a frame drawn into the
// renderer's own framebuffer leaves for the next one, and the rectangle the next one must
// redraw when only some surfaces' data changed. Plain data and arithmetic, no GL: the renderer
// (render/renderer.cpp) decides, scissors and draws.
#pragma once

#include "model/document/document.h"
#include "render/analysis.h"
#include "render/render_types.h"

#include <QSize>
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <set>
#include <unordered_map>
#include <vector>

namespace kw {

struct EdgeBands;

/// Everything of a frame besides the surfaces' own data that decides its pixels: any
/// difference draws the next frame whole.
struct PartialFrameView {
    const Document* document = nullptr;
    std::uint64_t target = 0; ///< the own framebuffer's FloatDepthTarget::serial
    QSize drawnSize;          ///< the pixels drawn (a preview's fewer)
    QSize targetSize;         ///< the host's, which the drawn frame is copied (magnified) into
    /// The frame camera's matrices and viewport: the near and far planes follow the scene's
    /// bounds, so an edit that grows them changes every depth.
    glm::mat4 view{1.0f}, projection{1.0f};
    glm::ivec2 viewport{0};
    std::vector<Light> lights;
    RenderOptions options;    ///< with frameReuse set to Partial, so Full and Partial frames match
    ValueRange analysisRange; ///< a colour map's range over the whole scene
    std::uint64_t marks = 0;  ///< GpuScene::marksRevision: which solids skip their back faces
    bool operator==(const PartialFrameView&) const = default;
};

/// One drawn surface as the frame saw it: what its pixels depend on, and where they can be.
struct SurfaceFootprint {
    std::uint32_t id = 0;
    int slot = -1; ///< its surface table row (the pre-pass data's, Renderer::pickInLastFrame)
    Revisions revisions;
    /// Its polygon (SurfaceGpu::polygonSerial) and trim mask's size: an unchanged surface's
    /// cells or mask chosen again (another view drawn between, a pick) may move its pixels.
    std::uint64_t polygon = 0;
    int maskWidth = 0, maskHeight = 0;
    bool drawn = false;   ///< has exact data
    bool bounded = false; ///< `rect` holds what it draws (else it may draw anywhere)
    /// Window pixels (x0, y0, x1, y1 exclusive, GL rows) its polygon, or its control points,
    /// project to; what it draws past them is PartialFrames::reachPixels.
    glm::ivec4 rect{0};
    /// The damage tiles (render/damage_tiles.h) its cells touch, grown by
    /// PartialFrames::reachPixels, when known (taken for the surfaces a partial frame redraws);
    /// else its rectangle's. What it holds, not part of what it is: left out of ==.
    std::shared_ptr<const std::vector<std::int32_t>> tiles;
    bool operator==(const SurfaceFootprint& o) const {
        return id == o.id && slot == o.slot && revisions == o.revisions && polygon == o.polygon &&
               maskWidth == o.maskWidth && maskHeight == o.maskHeight && drawn == o.drawn &&
               bounded == o.bounded && rect == o.rect;
    }
};

/// A surface whose pixels a partial frame redraws: as the remembered frame drew it (`before`)
/// or as this one will (`index` into the frame's footprints).
struct DamagedSurface {
    SurfaceFootprint footprint;
    bool before = false;
    int index = -1; ///< this frame's footprint; -1 for one before
};

class PartialFrames {
public:
    /// How far past its projected control bounds a surface may change pixels in a frame with
    /// `options`: its polygon lies inside them, its skirts and silhouette fins reach
    /// pixelTolerance + ExactSurfacePass::kSkirtMarginPixels past its polygon's edge, control
    /// points are drawn as squares, edge bands are lines of their width; plus two pixels for
    /// the rasteriser's rounding.
    static int reachPixels(const RenderOptions& options);
    /// `lo`..`hi` projected by `viewProjection` into window pixels of `viewport` (x0, y0, x1,
    /// y1 exclusive, GL rows), grown by `pad` and clamped to the view; nullopt when a corner
    /// lies behind the eye (it may reach any pixel).
    static std::optional<glm::ivec4> windowRect(const glm::vec3& lo, const glm::vec3& hi,
                                                const glm::mat4& viewProjection,
                                                glm::ivec2 viewport, int pad);
    /// `rect` grown by `pad` and clamped to `viewport` (x1 <= x0: off the view).
    static glm::ivec4 grown(const glm::ivec4& rect, int pad, glm::ivec2 viewport);
    /// Grows `into` (x1 <= x0: empty) to hold `r` (an empty `r` adds nothing).
    static void unite(glm::ivec4& into, const glm::ivec4& r);

    /// The rectangle a frame of `view` over `surfaces` must redraw after the remembered one,
    /// in window pixels (x0, y0, x1, y1 exclusive, GL rows; x1 <= x0: none, the kept frame
    /// is the image), or nullopt when it must be drawn whole: nothing remembered, another view
    /// or options, another frame wrote the pre-pass data since (`prepassWrites`,
    /// ExactSurfacePass::prepassWrites), a changed surface with no bounds in front of the eye,
    /// edge bands changed in number, or a rectangle over more than kMaxFraction of the view.
    /// A surface changed when its revisions, table row or bounds did, or it came or went
    /// (shown, hidden, added, removed); its old and new rectangles both count. `bands`: the
    /// frame's edge bands (RenderOptions::edgeBands), whose changed ranges count likewise.
    /// `changed`, when given, receives the changed surfaces counted, each as it was and as it
    /// is (the renderer narrows the rectangle to their tiles); `bandsChanged` whether edge
    /// bands added to it.
    std::optional<glm::ivec4> damage(const PartialFrameView& view, std::uint64_t prepassWrites,
                                     const std::vector<SurfaceFootprint>& surfaces,
                                     const glm::mat4& viewProjection, const EdgeBands* bands,
                                     std::vector<DamagedSurface>* changed = nullptr,
                                     bool* bandsChanged = nullptr) const;
    /// A partial frame costs about its share of the view's pixels; past this share of the
    /// view the whole frame is drawn (it costs the same, and is the simpler path).
    static constexpr double kMaxFraction = 0.5;

    /// Keeps what the frame just drawn left: its view, the surfaces, the edge bands' ranges,
    /// the solids whose back faces it skipped and whether Renderer::pickInLastFrame may read
    /// its pre-pass data (`pickable`).
    void remember(const Camera& camera, const FrameCamera& frame, const PartialFrameView& view,
                  std::uint64_t prepassWrites, const std::vector<SurfaceFootprint>& surfaces,
                  const EdgeBands* bands, const std::set<int>& backCulled, bool pickable);
    /// The remembered frame's camera for a frame of `camera` into `drawnSize` pixels of a
    /// `targetSize` target whose scene's control bounds are `bounds`, while its near and far
    /// planes still hold what fresh ones would (the far plane beyond the bounds, the near one
    /// clipping nothing fresh ones keep, and at least half as far as theirs, for depth
    /// precision): an edit that moves the bounds a little then keeps every depth, and the frame
    /// can be partial. Else nullopt (the frame's own planes, kw::frameCamera).
    std::optional<FrameCamera> keptCamera(const Camera& camera, QSize drawnSize, QSize targetSize,
                                          const glm::dvec3 (*bounds)[2]) const;
    void forget() { m_have = false; }
    bool remembered() const { return m_have; }
    /// The remembered frame's solids with their back faces skipped: a partial frame whose plan
    /// skips others is drawn again whole (the change reaches every face of those solids).
    const std::set<int>& backCulled() const { return m_backCulled; }
    /// Whether the remembered frame's pre-pass data could be read by pickInLastFrame; a partial
    /// frame's can then too (its rectangle's is new, the rest is that frame's).
    bool pickable() const { return m_pickable; }

private:
    bool m_have = false;
    PartialFrameView m_view;
    Camera m_camera;
    FrameCamera m_frame; ///< without a partial frame's reach
    std::uint64_t m_prepassWrites = 0;
    std::unordered_map<std::uint32_t, SurfaceFootprint> m_surfaces;
    /// The bands' revision and layout as drawn, and each range's bounds then.
    const EdgeBands* m_bands = nullptr;
    std::uint64_t m_bandsRevision = 0, m_bandsLayout = 0;
    std::vector<std::pair<glm::vec3, glm::vec3>> m_bandBounds;
    std::set<int> m_backCulled;
    bool m_pickable = false;
};

} // namespace kw
