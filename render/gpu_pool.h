// The GPU side of every surface's exact data, and how an edit reaches it: shared buffers (one
// per kind: control points, span tables, base polygon vertices and indices), each surface's ranges
// in them (SurfaceGpu), and the uploads that fill those ranges, down to the one write per row of
// a moved point's texels. GpuScene::sync decides per surface which upload is due.
#pragma once

#include "model/document/document.h"
#include "render/frame_report.h"
#include "render/gpu_layout.h"
#include "render/render_types.h"
#include "render/surface_bound.h"

#include <QOpenGLFunctions_4_5_Core>
#include <QString>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

namespace kw {

/// First-fit allocator of element ranges in [0, end()) with coalescing free ranges (no GL, so
/// it is testable alone). Ranges are in elements; freeing the last range lowers end().
class RangeAllocator {
public:
    /// Offset of `count` free elements (count > 0): the first free range that fits, or the end.
    std::int64_t allocate(std::int64_t count);
    /// Returns [offset, offset + count) to the free ranges (must have come from allocate).
    void free(std::int64_t offset, std::int64_t count);
    /// One past the highest allocated element.
    std::int64_t end() const { return m_end; }
    /// Elements in live ranges.
    std::int64_t used() const { return m_used; }
    void clear() { m_free.clear(), m_end = 0, m_used = 0; }

private:
    std::map<std::int64_t, std::int64_t> m_free; ///< offset -> count, below m_end
    std::int64_t m_end = 0;
    std::int64_t m_used = 0;
};

/// One GL buffer holding elements of `elementBytes` each, sub-allocated by a RangeAllocator.
/// It grows (grownCapacity; the old contents copied on the GPU, waited for: see allocate) and is
/// deleted when its last range is freed, so an empty scene holds no pool memory. Growth replaces
/// the buffer name: users re-bind buffer() after every allocate (GpuScene does, once per sync).
class GpuPool {
public:
    void initialize(QOpenGLFunctions_4_5_Core* gl, std::int64_t elementBytes,
                    std::int64_t maxBytes) {
        m_gl = gl, m_elementBytes = elementBytes, m_maxBytes = maxBytes;
    }
    /// Offset (in elements) of `count` elements, or -1 when the buffer would exceed maxBytes.
    std::int64_t allocate(std::int64_t count);
    void free(std::int64_t offset, std::int64_t count);
    /// Writes `count` elements at `offset` (glNamedBufferSubData).
    void write(std::int64_t offset, std::int64_t count, const void* data);
    GLuint buffer() const { return m_buffer; }
    /// Bytes of the GL buffer (capacity, not only the live ranges).
    std::int64_t residentBytes() const { return m_capacity * m_elementBytes; }
    std::int64_t usedElements() const { return m_ranges.used(); }
    std::int64_t elementBytes() const { return m_elementBytes; }
    std::int64_t maxBytes() const { return m_maxBytes; }
    /// Frees the GL buffer and every range.
    void release();

    /// One live range of the pool and where its owner keeps the offset (compact moves it).
    struct Range {
        std::int64_t* offset = nullptr; ///< elements; compact writes the new place here
        std::int64_t count = 0;
    };
    /// Packs `ranges` (every live range of the pool, each once) to the front of a new buffer
    /// of compactedCapacity(used) elements, in the order of their offsets, copying their
    /// contents on the GPU, and writes each range's new offset to its owner. Due only when the
    /// buffer holds more than twice what the ranges need (shouldCompact): a pool keeps the
    /// high-water mark of a view's polygons (a close-up's rebuilt polygon allocated past the
    /// fitted view's). False, with nothing moved, when not due or when `ranges` are not
    /// exactly the pool's live elements. Users re-bind buffer() afterwards, as after allocate.
    bool compact(std::vector<Range> ranges);
    /// Whether a pool of `capacity` elements holding `used` is worth packing: more than twice
    /// compactedCapacity(used). No GL: the policy is testable alone.
    static bool shouldCompact(std::int64_t capacity, std::int64_t used);
    /// The capacity a pack leaves for `used` elements: a quarter of room to grow (a view that
    /// needs a few more cells then re-uses it, without a copy), at least kMinElements.
    static std::int64_t compactedCapacity(std::int64_t used);

    /// The capacity (elements) a pool of `capacity` grows to for `need` elements: at least
    /// kMinElements, doubled while under kDoublingBytes, then a quarter more at a time, capped
    /// at maxBytes (then below `need` when it does not fit). No GL: the growth is testable alone.
    static std::int64_t grownCapacity(std::int64_t capacity, std::int64_t need,
                                      std::int64_t elementBytes, std::int64_t maxBytes);
    /// The least capacity a pool holds: a few dozen cells. A close-up of a few faces (the
    /// screw's at 64x, drawn by a cover and 9 cells) held 1024 elements in each of four pools,
    /// 0.08 MiB for 0.002 MiB of data, a quarter of Knotwork's memory for that view.
    static constexpr std::int64_t kMinElements = 64;
    static constexpr std::int64_t kDoublingBytes = std::int64_t(64) << 20;

private:
    QOpenGLFunctions_4_5_Core* m_gl = nullptr;
    std::int64_t m_elementBytes = 1;
    std::int64_t m_maxBytes = 0;
    std::int64_t m_capacity = 0; ///< elements
    GLuint m_buffer = 0;
    RangeAllocator m_ranges;
};

/// Where a closed-form face's cover goes: the union of the Bezier control bounds of the
/// sub-rectangles of `spans` meeting `box` (with positive weights each patch lies in their
/// convex hull), their (u, v) rectangle cut to the box, and the span nearest its middle.
struct CoverBox {
    const SpanBound* span = nullptr;
    SpanBound::Sub bounds;
    double u0 = 0.0, u1 = 0.0, v0 = 0.0, v1 = 0.0;
};
/// The cover's box over `box`, or nullopt when no span meets it. One box for the face, not one
/// a span or a sub-rectangle: boxes overlap on screen (near the eye each covers much of the
/// view) and every box's fragment solves the face again (the screw's 64x close-up: 334 ms a
/// frame with a box a sub-rectangle, 171 ms with one a span), while a solve needs no start near
/// the point. A pixel inside the box but off the face costs one solve and its discard.
std::optional<CoverBox> coverBox(const std::vector<SpanBound>& spans, const ParameterBox& box);

/// A closed-form face's cover (docs/RENDERING.md, "Covers of closed-form faces"): `box` grown by
/// a float margin, as 8 BaseVertex: its corners, each with the (u, v) of the middle of its
/// rectangle, its span and that span's scale; 12 triangles, each face wound counter-clockwise
/// seen from inside, so that with GL_BACK culled a pixel is drawn once, by the face where its
/// ray leaves the box, whether the eye is outside or inside it (and the part of the box past
/// the near plane is what rays beyond it cross).
struct CoverMesh {
    std::vector<BaseVertex> vertices;
    std::vector<unsigned> triangles;
    int boxes() const { return int(vertices.size() / 8); }
};
CoverMesh buildCover(const NurbsSurface& s, const CoverBox& box);

// ---- One surface's ranges in the pools, and its uploads

/// The shared buffers of every surface's exact data (shaders/surface_data.glsl reads them):
/// control texels (w (P - origin), w) row by row (v outer), span-table rows
/// (kw::packSpanTable; a surface's u table then its v table), base polygon vertices
/// (kw::BaseVertex) and its triangle and outline indices, relative to the surface's first
/// vertex (drawn with a base vertex), and its skirt's vertices (kw::SkirtVertex) and triangle
/// indices, relative to the skirt's first vertex.
struct ScenePools {
    GpuPool control, spans, vertices, triangles, outlines, skirtVertices, skirtIndices;
};

/// Where one surface's data lies in the pools, and the CPU copies the partial updates compare
/// against. Offsets are in elements of each pool; -1 while not allocated.
struct SurfaceGpu {
    SurfaceId id;
    Revisions revisions; ///< what is on the GPU
    PolygonCut cut;      ///< how the polygon now on the GPU was cut
    int degreeU = 1, degreeV = 1, countU = 0, countV = 0;
    glm::vec4 domain{0.0f, 1.0f, 0.0f, 1.0f};
    glm::dvec3 origin{0.0};          ///< control texels are relative to it (packControlPoints)
    std::int64_t controlOffset = -1; ///< countU x countV texels
    std::int64_t spanOffset = -1;    ///< spanTexelsU texels of the u table, then the v table's
    std::int64_t spanTexelsU = 0, spanTexelsV = 0;
    std::int64_t vertexOffset = -1, vertexCount = 0;
    std::int64_t triangleOffset = -1, outlineOffset = -1;
    int triangleIndexCount = 0, outlineIndexCount = 0;
    /// The polygon's skirt (kw::buildSkirt): built and freed with the polygon; offset -1 when
    /// the polygon has none (rebuildPolygon's `skirt`).
    std::int64_t skirtVertexOffset = -1, skirtVertexCount = 0;
    std::int64_t skirtIndexOffset = -1;
    int skirtIndexCount = 0;
    std::vector<glm::vec4> control; ///< the texels now on the GPU
    /// The polygon on the GPU: its breaks and spans always; its vertices while the polygon has
    /// a skirt or since its points changed (rebuildPolygon, uploadChangedPoints), else none.
    BasePolygon polygon;
    ParameterBox polygonBox;         ///< the (u, v) box the polygon spans
    bool polygonTrimmed = false;     ///< polygonBox is trimParameterBox, not the domain
    std::uint64_t polygonSerial = 0; ///< changes whenever the polygon is rebuilt
    /// Cells of the partition choice over polygonBox, in view or not (the polygon holds only
    /// those in view: RenderOptions::polygonsInView); the exact planner's cell size estimate.
    std::int64_t choiceCells = 0;
    /// splitByTrims: the triangle range holds the cells wholly inside the trims first
    /// (insideIndexCount indices), then those near a trim curve (edgeIndexCount), then those
    /// wholly trimmed away. insideIndexCount < 0: not split (one range, every cell).
    int insideIndexCount = -1, edgeIndexCount = 0;
    std::uint64_t splitPolygon = 0, splitClasses = 0; ///< what the split was made for
    /// splitCells with section classes (splitSections != 0, their serial): the cells a plane
    /// keeps wholly first (keptIndexCount indices; split by the trims too, they are the inside
    /// then the near-edge cells above, keptIndexCount = insideIndexCount + edgeIndexCount),
    /// then those a plane crosses (crossedIndexCount; near an edge first), then those removed
    /// or trimmed away.
    int keptIndexCount = 0, crossedIndexCount = 0;
    std::uint64_t splitSections = 0;
    /// The order of the cells in the triangle range as the last split wrote it: per cell (row
    /// by row, v outer) its bucket, the range holding bucket 0's cells row by row, then bucket
    /// 1's, and so on (kw::splitCells). Empty: row by row, as rebuildPolygon wrote them. A
    /// partial frame draws sub-ranges of it (render/partial_cells.h).
    std::vector<std::uint8_t> cellBuckets;
    /// kw::surfaceIsAffine of the geometry now on the GPU: the base polygon is the surface, so
    /// adaptive frames draw it without the Newton step onto the pixel's ray (ExactSurfacePass).
    bool affine = false;
    /// The triangle range holds the face's cover (kw::buildCover, rebuildCover), not a base
    /// polygon: `polygon` is then empty (no cells, no breaks), and the exact planner draws the
    /// range with the closed form's exact depth only (docs/RENDERING.md, "Covers of
    /// closed-form faces"). `coverBoxes` counts its boxes.
    bool cover = false;
    int coverBoxes = 0;
};

/// Full upload of a new surface, or after its knots, degrees or counts changed: ranges
/// (re)allocated and filled, base polygon rebuilt cut as `cut` over `box`. Counts into
/// `stats`. Returns false (and holds no ranges) when a pool would exceed its GPU limit.
/// `skirt` and `outlines` as rebuildPolygon's.
bool uploadSurface(ScenePools& pools, SurfaceGpu& g, const Surface& s, const PolygonCut& cut,
                   const ParameterBox& box, bool skirt, bool outlines, UploadStats& stats);
/// After a Points revision change: the texels of the bounding rectangle of those that differ
/// (one sub-range write per row of it, counted as one sub-image upload), and only the base
/// polygon vertices in the support of those points (and the polygon's skirt vertices, a few
/// per boundary node).
void uploadChangedPoints(ScenePools& pools, SurfaceGpu& g, const Surface& s, UploadStats& stats);
/// What rebuildPolygon writes to the pools for one surface, built on the CPU (no GL): the base
/// polygon, its triangle indices, and its outline indices and skirt when asked for.
struct PolygonUpload {
    BasePolygon polygon;
    std::vector<unsigned> triangles, outlines;
    std::vector<SkirtVertex> skirt;
    std::vector<unsigned> skirtIndices;
    /// Bytes of all of it in the pools.
    std::int64_t bytes() const;
};
PolygonUpload buildPolygonUpload(const NurbsSurface& geo, const ParameterBox& box,
                                 const PolygonCut& cut, bool skirt, bool outlines);
/// The base polygon cut as `cut` over `box` (a rectangle of the domain: GpuScene
/// passes trimParameterBox unless RenderOptions::polygonOverTrims is off, so a trimmed face's
/// cells go where its trims keep the surface) from the current points;
/// control data untouched. Returns false (the polygon's ranges freed) when a pool would
/// exceed its limit. With `skirt`, the polygon's skirt too (kw::buildSkirt; adaptive frames
/// draw it), else none. With `outlines`, the cells' outline indices too (the wireframe's),
/// else none: at 8 indices a cell they would be a third of the polygon's bytes, for an
/// overlay most frames do not draw (addOutlines brings them when one does).
bool rebuildPolygon(ScenePools& pools, SurfaceGpu& g, const Surface& s, const PolygonCut& cut,
                    const ParameterBox& box, bool skirt, bool outlines, UploadStats& stats);
/// Replaces the polygon's ranges with `cover`'s (kw::buildCover): no skirt, no outlines, an
/// empty `polygon`; `box` and `cut` recorded as rebuildPolygon records them. Returns false (the
/// ranges freed) when a pool would exceed its limit.
bool rebuildCover(ScenePools& pools, SurfaceGpu& g, const CoverMesh& cover, const PolygonCut& cut,
                  const ParameterBox& box, UploadStats& stats);
/// The outline indices of the polygon on the GPU, when it has none yet (a frame that draws the
/// wireframe). Returns false when the outline pool would exceed its limit (nothing changed).
bool addOutlines(ScenePools& pools, SurfaceGpu& g, UploadStats& stats);
struct TrimMask;
/// Orders the polygon's triangles by how the trims cut their cells (SurfaceGpu's
/// insideIndexCount and edgeIndexCount), from the mask's texel classes: a cell is inside (or
/// trimmed away) when every grid texel it overlaps, and every texel next to those, is inside
/// (outside) with no curve; else it is near an edge. The one-texel ring keeps a margin for
/// float (u, v) rounding at cell borders. Without classes (mask mode, untrimmed) the polygon
/// is left one range. Rewrites the triangle indices in place (same count); a cell's two
/// triangles stay together, starting at its provoking vertex. Returns true when the split
/// changed. Why: the depth pre-pass then tests the trims only on cells near a curve and draws
/// no cell the trims remove (docs/PERFORMANCE.md ## Trims).
bool splitByTrims(ScenePools& pools, SurfaceGpu& g, const TrimMask* mask);
/// splitByTrims, and with `sections` (one kw::CellSection per cell, row by row, v outer; null
/// or empty: none) also by the section planes, in SurfaceGpu::keptIndexCount and
/// crossedIndexCount's order; `sectionSerial` (non-zero) names those classes, so the same
/// serial again rewrites nothing. Why: a cut frame's kept cells draw with the pre-pass as an
/// uncut frame's, only the crossed ones with exact depth and the section test, and the removed
/// ones not at all (docs/RENDERING.md, "Section planes").
bool splitCells(ScenePools& pools, SurfaceGpu& g, const TrimMask* mask,
                const std::vector<std::uint8_t>* sections, std::uint64_t sectionSerial);

/// World-space bounds of the control points of `g` as on the GPU (texels plus origin; they
/// hold the surface and its base polygon); false without a point of positive weight.
bool controlBounds(const SurfaceGpu& g, glm::vec3& lo, glm::vec3& hi);
/// Returns the surface's ranges to the pools.
void destroySurfaceGpu(ScenePools& pools, SurfaceGpu& g);

} // namespace kw
