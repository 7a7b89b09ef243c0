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
/// nu x nv are then kMaxPartitions where the bound fell short). Breaks always set. The
/// renderer's silhouette fins cover what the polygon's silhouette leaves out.
PartitionChoice chooseCut(const NurbsSurface& s, const std::vector<SpanBound>& spans,
                          const ParameterBox& box, const ScreenScale& scale, double tolerance,
                          int minU, int minV);

/// One surface's cached adaptive choice. The span bounds depend on the geometry only (points
/// and knots revisions); the choice on them, the polygon's box, the minimum and the view.
class AdaptivePartitions {
public:
    /// The partitions for `surface` (valid) over `box` seen with `scale`; `viewStamp` changes
    /// whenever the camera, viewport or tolerance does. Recomputes only what is stale; sets
    /// `recomputed` when the choice was evaluated again (not when it was reused). The choice
    /// returned holds the counts, bound and whether it was met; its breaks are in cut().
    const PartitionChoice& choose(const Surface& surface, const Revisions& rev,
                                  const ParameterBox& box, const ScreenScale& scale,
                                  std::uint64_t viewStamp, double tolerance, int minU, int minV,
                                  bool* recomputed = nullptr);
    /// The last choice as a polygon cut (its breaks).
    const PolygonCut& cut() const { return m_cut; }
    /// The bounds of all of `surface`'s non-empty spans (kw::surfaceSpanBounds at gridFor),
    /// taken again only when its points or knots changed (the section planes' cell bounds
    /// use them in either partitioning).
    const std::vector<SpanBound>& spans(const Surface& surface, const Revisions& rev);

    /// Sub-rectangles per span side: 4, fewer for surfaces of many spans so that the bounds
    /// of one surface cost at most ~256 Bezier extractions (measured: 0.27 ms per hammer.iges
    /// face at 4, 1 ms at 8).
    static int gridFor(int spans);

private:
    Revisions m_geometry; ///< points and knots the spans were built from
    bool m_haveSpans = false;
    std::vector<SpanBound> m_spans; ///< all non-empty spans
    ParameterBox m_box;
    std::vector<SpanBound> m_inBox; ///< the spans meeting m_box
    std::uint64_t m_viewStamp = 0;
    int m_minU = 0, m_minV = 0;
    bool m_haveChoice = false;
    PartitionChoice m_choice;
    PolygonCut m_cut;
};

} // namespace kw
