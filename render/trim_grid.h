// The hybrid trim mask on the CPU: a grid over a surface's trim loops whose texels are inside,
// outside or edge, with the arc pieces crossing each edge texel, and the exact classification
// of any (u, v) from a texel's parity bit plus crossings counted inside that texel.
#pragma once

#include "model/nurbs/trim_arcs.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace kw {

/// The part of one monotone arc (TrimArcs::arcs[arc]) between t0 < t1 that lies in one texel:
/// arcs are cut where they cross the grid lines. p0 = C(t0), p1 = C(t1); consecutive pieces of
/// a loop share these end points bit for bit.
struct TrimPiece {
    std::uint32_t arc = 0;
    double t0 = 0.0, t1 = 1.0;
    glm::dvec2 p0{0.0}, p1{0.0};
};

/// A width x height grid over `rect` = (u first, u last, v first, v last), texel (i, j) at index
/// j * width + i (row 0 at v first). Texel k lists entries[first[k] .. first[k + 1]); each entry
/// is piece << 2 | left << 1 | right (see trimGridContains). A texel without entries is inside
/// (base 1) or outside (base 0) as a whole; one with entries is an edge texel.
///
/// Classification (the ray rule of trimRegionContains, localised to a texel): for a point q in
/// texel T and a piece P with end points L (smaller u) and R, let
///   h_P(q) = [v of P at u_q > v_q]  if u_q is in [u_L, u_R),
///            left bit = [v_L > v_T]  if u_q < u_L,   right bit = [v_R > v_T]  otherwise,
/// with v_T the v of the texel's centre. The parity of q is base(T) XOR h_P(q) over T's pieces.
/// Why: the ray parity f(q) is the sum over all pieces of g_P(q) = [u_q in [u_L, u_R) and
/// v_P(u_q) > v_q]; a piece that misses T has g_P constant across T except for steps on the
/// vertical lines through its ends, where it steps by [v_E > v_q], and the listed pieces' h_P
/// step there by [v_E > v_T]. Each end E is shared by two pieces. Both listed: their steps cancel.
/// Neither: likewise. One listed: E is on T's border, and on the lower (upper) border both steps
/// are 0 (1), even when the cut put E a rounding error off the border, which is why v_T is the
/// centre and not the lower border. So f XOR sum(h_P) is constant on T: that constant is
/// base(T). Only the comparison v_P(u_q) > v_q depends on q, so rounding can only misclassify
/// points next to a curve.
struct TrimGrid {
    glm::dvec4 rect{0.0, 1.0, 0.0, 1.0};
    int width = 0, height = 0;
    std::vector<std::uint32_t> first; ///< width * height + 1 offsets into entries
    std::vector<std::uint8_t> base;   ///< per texel: the parity constant, 0 or 1
    std::vector<std::uint32_t> entries;
    std::vector<TrimPiece> pieces;

    int texelCount() const { return width * height; }
    bool isEdge(int k) const { return first[size_t(k) + 1] > first[size_t(k)]; }
    /// Texel index of a point, clamped to the grid.
    int texelOf(glm::dvec2 uv) const;
};

/// The rectangle a grid over `arcs` spans: their bounds, widened by a small margin on every side
/// so that no arc lies on the rectangle's border. Outside it every point is outside every loop
/// (a vertical ray crosses closed loops an even number of times). Empty arcs: the unit square.
glm::dvec4 trimGridRect(const TrimArcs& arcs);

/// The grid resolution chosen from the loops' complexity, not from the zoom (the grid only sets
/// how many fragments take the exact path): 16 sqrt(arcs) texels a side, a power of two within
/// [kMinTrimGridSize, cap], equal on both sides. A cap below kMinTrimGridSize (a memory budget
/// forcing coarse grids) is the side; cap >= 1.
constexpr int kMinTrimGridSize = 16;
glm::ivec2 trimGridResolution(const TrimArcs& arcs, int cap = 1024);

/// Builds the grid (see TrimGrid): arcs cut at the grid lines by bisection, each piece listed in
/// the texel holding its middle and in every texel its box comes within 1e-3 texel of (so a
/// float lookup that rounds a point across a texel border still classifies it right), and
/// every texel's base from one sweep per column through the texel centres. Preconditions: size >= 1
/// on both sides. Empty arcs: every texel inside.
TrimGrid makeTrimGrid(const TrimArcs& arcs, glm::ivec2 size);

/// Exact even-odd classification of uv through the grid (see TrimGrid). Agrees with
/// trimArcsContain(arcs, uv) except for points within rounding of a curve. No loops: inside.
bool trimGridContains(const TrimGrid& grid, const TrimArcs& arcs, glm::dvec2 uv);

/// What a grid holds, and the bytes its GPU form takes (render/trim_*: 4 bytes per texel word,
/// 4 per entry, 32 per piece, 16 per homogeneous control point and 16 per arc header).
struct TrimGridStats {
    int edgeTexels = 0;
    int maxEntries = 0; ///< longest list of one texel
    std::int64_t entries = 0, pieces = 0, controlPoints = 0, arcs = 0;
    std::int64_t bytes = 0;
};
TrimGridStats trimGridStats(const TrimGrid& grid, const TrimArcs& arcs);

} // namespace kw
