// View-adaptive partitions: per surface and view, the fewest uniform
// partitions at or above the sliders' for which the base polygon lies within a pixel tolerance
// of the exact surface on screen, by the guaranteed bound of render/surface_bound.h.
#pragma once

#include "model/document/document.h"
#include "model/nurbs/visible_bounds.h"
#include "render/gpu_layout.h"
#include "render/render_types.h"
#include "render/surface_bound.h"

#include <cstdint>
#include <vector>

namespace kw {

/// The screen scale of a frame's camera (focal length and frustum from its projection), with
/// culling of what lies outside the view.
ScreenScale frameScreenScale(const FrameCamera& camera);

/// The adaptive cut of `s` over `box` (spans: those meeting it): whichever of the uniform
/// partitions (choosePartitions, its breaks from cellBreaks) and the tensor-product breaks
/// (chooseBreaks) meets the tolerance with fewer cells; both are proven bounds, and neither is
/// always smaller (uniform wins where the sliders' minimum decides, since the tensor grid
/// rounds it up per sub-rectangle column). When neither meets it, the uniform one (its
/// nu x nv are then kMaxPartitions where the bound fell short). When neither meets it and
/// some control bounds reach past the near plane, the tensor grid is tried again on finer
/// bounds of the same spans (up to 16 x 16 a span, 4096 sub-rectangles): near the eye coarse
/// bounds can hold the eye's surroundings though the surface keeps away. Breaks always set. The
/// renderer's silhouette fins cover what the polygon's silhouette leaves out.
PartitionChoice chooseCut(const NurbsSurface& s, const std::vector<SpanBound>& spans,
                          const ParameterBox& box, const ScreenScale& scale, double tolerance,
                          int minU, int minV);

/// How far past the view's edges, in pixels, cells are kept (cutInView): past what a kept
/// polygon's skirts and silhouette fins reach on screen (the tolerance plus
/// ExactSurfacePass::kSkirtMarginPixels), with room to spare.
double viewMarginPixels(double tolerance);

/// The cells of `cut` (breaks set, each cell inside one span, and inside one sub-rectangle of
/// `spans` when `cellsInOneSub`) that may reach the view: the smallest block of its rows and
/// columns holding every cell over a sub-rectangle (over a span, when cells may straddle its
/// sub-rectangles) whose control bounds reach `scale`'s frustum grown by `marginPixels` on
/// each side. A cell left out lies, triangles and all, inside such bounds wholly outside one
/// plane of that frustum (the convex hull property: its corners are surface points there),
/// so it, its skirt and its fins cover no pixel; the kept cells are the cut's own, so every
/// pixel is drawn from the same triangle as with the whole cut. With nothing in view, one
/// cell. Without scale.cullOutsideView, `cut` as it is.
PolygonCut cutInView(const PolygonCut& cut, const std::vector<SpanBound>& spans,
                     bool cellsInOneSub, const ScreenScale& scale, double marginPixels);

/// One surface's cached adaptive choice. The span bounds depend on the geometry only (points
/// and knots revisions); the choice on them, the polygon's box, the minimum and the view.
class AdaptivePartitions {
public:
    /// The partitions for `surface` (valid) over `box` seen with `scale`; `viewStamp` changes
    /// whenever the camera, viewport or tolerance does. Recomputes only what is stale; sets
    /// `recomputed` when the choice was evaluated again (not when it was reused). The choice
    /// returned holds the counts, bound and whether it was met; its breaks are in cut(),
    /// which keeps only the cells in view with `inView` (RenderOptions::polygonsInView).
    const PartitionChoice& choose(const Surface& surface, const Revisions& rev,
                                  const ParameterBox& box, const ScreenScale& scale,
                                  std::uint64_t viewStamp, double tolerance, int minU, int minV,
                                  bool* recomputed = nullptr, bool inView = true);
    /// The last choice as a polygon cut (its breaks), with `inView` (choose) only the cells
    /// that may reach the view (cutInView).
    const PolygonCut& cut() const { return m_cut; }
    /// Cells of the last choice over the whole box, in view or not: the cell size the exact
    /// planner estimates from the surface's whole screen box.
    std::int64_t choiceCells() const { return m_choiceCells; }
    /// The bounds of all of `surface`'s non-empty spans (kw::surfaceSpanBounds at gridFor),
    /// taken again only when its points or knots changed (the section planes' cell bounds
    /// use them in either partitioning).
    const std::vector<SpanBound>& spans(const Surface& surface, const Revisions& rev);

    /// Sub-rectangles per span side: 4, fewer for surfaces of many spans so that the bounds
    /// of one surface cost at most ~256 Bezier extractions (measured: 0.27 ms per hammer.iges
    /// face at 4, 1 ms at 8).
    static int gridFor(int spans);
    /// Bytes of the span bounds and the cut kept here (FrameReport::hostCopyBytes).
    std::int64_t hostBytes() const;

private:
    Revisions m_geometry; ///< points and knots the spans were built from
    bool m_haveSpans = false;
    std::vector<SpanBound> m_spans; ///< all non-empty spans
    ParameterBox m_box;
    /// The spans meeting m_box: empty while they are all of m_spans (inBox), so that the
    /// common case (an untrimmed face, or trims over every span) keeps one copy of its bounds.
    std::vector<SpanBound> m_inBox;
    bool m_allInBox = false;
    const std::vector<SpanBound>& inBox() const { return m_allInBox ? m_spans : m_inBox; }
    std::uint64_t m_viewStamp = 0;
    int m_minU = 0, m_minV = 0;
    bool m_inView = true;
    bool m_haveChoice = false;
    std::int64_t m_choiceCells = 0;
    PartitionChoice m_choice;
    PolygonCut m_cut;
};

} // namespace kw
