// Exact trim classification on the GPU: the hybrid trim grid of render/trim_grid.h,
// packed by kw::packTrimGrid (render/trim_grid_store.h) into one R32UI texture buffer. A
// fragment in a texel without pieces takes the texel's parity bit; one in an edge texel adds
// the crossings of the texel's few monotone arc pieces (Schollmeyer & Froehlich 2009), each
// found by regula falsi on the exact rational Bezier arc. Included by trim_sample.glsl, which
// declares uTrimRect, uTrimSize (the grid's texels along u and v) and uTrimBlock (the
// surface's first word), per draw or from the surface table.
// A texture buffer, not an SSBO: llvmpipe (Mesa 22.3) returns 0 from SSBO loads in helper
// invocations (shaders/surface_data.glsl). Its unit is kw::kTrimGridUnit.
layout(binding = KW_TRIM_GRID_UNIT) uniform usamplerBuffer kwTrimGrid;
// The same words 4 at a time (RGBA32UI, unit kw::kTrimGridQuadUnit), for the pieces and
// points, which start on a multiple of 4 words (render/trim_grid_store.h): a point or a piece's
// half in one fetch instead of 3 or 4. On llvmpipe each fetch is a gather per lane with its own
// bounds check, and the root find's arc points were most of the exact trim test's cost.
layout(binding = KW_TRIM_QUAD_UNIT) uniform usamplerBuffer kwTrimQuads;

uint kwTrimWord(uint i) { return texelFetch(kwTrimGrid, int(i)).x; }
// The 4 words from word i, a multiple of 4.
uvec4 kwTrimQuad(uint i) { return texelFetch(kwTrimQuads, int(i >> 2)); }
vec4 kwTrimQuadFloats(uint i) { return uintBitsToFloat(kwTrimQuad(i)); }

// The arc's point at t by Horner's rule for the Bernstein form (Farin, "Curves and Surfaces
// for CAGD", 5.3) on its homogeneous control points (degree <= 15), read from the buffer as it
// goes: no local array, which llvmpipe kept in scratch memory for every fragment of the
// variant (a tenth of the frame on trimmed_plate, docs/PERFORMANCE.md ## Trims). `first` is
// the word of its first control point (kwTrimPieceV looks it and the degree up once), each
// point one quad (kwTrimQuad).
vec2 kwTrimArcPoint(uint first, int degree, float t) {
    uint k = first;
    float s = 1.0 - t, tn = 1.0, binomial = 1.0;
    vec3 sum = kwTrimQuadFloats(k).xyz;
    if (degree == 0)
        return sum.xy / sum.z;
    sum *= s;
    for (int i = 1; i < degree; ++i) {
        k += 4u;
        tn *= t;
        binomial *= float(degree - i + 1) / float(i);
        sum = (sum + tn * binomial * kwTrimQuadFloats(k).xyz) * s;
    }
    k += 4u;
    vec3 h = sum + tn * t * kwTrimQuadFloats(k).xyz;
    return h.xy / h.z;
}

// The point of the piece where its coordinate `axis` (0: u, 1: v) equals `value`, strictly
// inside the range of the piece's ends (else the nearer end), and its parameter *t: the
// Illinois variant of regula falsi (Dowell & Jarratt 1971), as trimArcSolve does on the CPU.
// The piece is monotone in u and in v, so there is one such point.
vec2 kwTrimPieceSolve(uint arc, int axis, float value, float t0, float t1, vec2 p0, vec2 p1,
                      out float t) {
    // At an end the answer is that end: the bracket's sign test below would take fa == 0 for
    // the wrong side (a fragment whose u is an end's u to the last bit, as at a loop vertex).
    float c0 = p0[axis], c1 = p1[axis];
    bool rising = c1 >= c0;
    t = t0;
    if (rising ? value <= c0 : value >= c0)
        return p0;
    t = t1;
    if (rising ? value >= c1 : value <= c1)
        return p1;
    // The arc's header, once per piece rather than once per evaluation below.
    uint header = uTrimBlock + kwTrimWord(uTrimBlock + 2u) + 2u * arc;
    uint first = uTrimBlock + kwTrimWord(uTrimBlock + 3u) + 4u * kwTrimWord(header);
    int degree = int(kwTrimWord(header + 1u));
    float a = t0, b = t1, fa = c0 - value, fb = c1 - value;
    vec2 pa = p0, pb = p1;
    int side = 0;
    bool bisect = false;
    for (int k = 0; k < 80; ++k) {
        float width = b - a;
        float m = bisect ? 0.5 * (a + b) : (a * fb - b * fa) / (fb - fa);
        if (!(m > a && m < b))
            m = 0.5 * (a + b);
        if (m <= a || m >= b)
            break;
        vec2 pm = kwTrimArcPoint(first, degree, m);
        float fm = pm[axis] - value;
        if (fm == 0.0) {
            t = m;
            return pm;
        }
        if ((fm < 0.0) == (fa < 0.0)) {
            a = m, fa = fm, pa = pm;
            if (side == -1)
                fb *= 0.5;
            side = -1;
        } else {
            b = m, fb = fm, pb = pm;
            if (side == 1)
                fa *= 0.5;
            side = 1;
        }
        bisect = b - a > 0.75 * width; // slow progress: bisect next
    }
    bool atA = abs(fa) < abs(fb);
    t = atA ? a : b;
    return atA ? pa : pb;
}

// v of the piece where its u equals u (kwTrimPieceSolve along u).
float kwTrimPieceV(uint arc, float u, float t0, float t1, vec2 p0, vec2 p1) {
    float t;
    return kwTrimPieceSolve(arc, 0, u, t0, t1, p0, p1, t).y;
}

// True where the grid says (u, v) is outside the trimmed surface; unit is (u, v) mapped to the
// grid's rectangle, inside [0, 1]^2.
bool kwTrimmedAwayExact(vec2 uv, vec2 unit) {
    ivec2 size = ivec2(uTrimSize);
    ivec2 cell = clamp(ivec2(floor(unit * vec2(size))), ivec2(0), size - 1);
    uint k = uTrimBlock + 4u + uint(cell.y * size.x + cell.x);
    uint word = kwTrimWord(k);
    bool inside = (word & 1u) != 0u;
    uint last = kwTrimWord(k + 1u) >> 2;
    if (last == word >> 2)
        return !inside; // no piece in this texel: its parity alone decides
    uint entries = uTrimBlock + kwTrimWord(uTrimBlock);
    uint pieces = uTrimBlock + kwTrimWord(uTrimBlock + 1u);
    for (uint e = word >> 2; e < last; ++e) {
        uint entry = kwTrimWord(entries + e);
        uint p = pieces + 8u * (entry >> 2);
        vec4 ends = kwTrimQuadFloats(p);
        vec2 p0 = ends.xy, p1 = ends.zw;
        bool h;
        if (uv.x < min(p0.x, p1.x))
            h = (entry & 2u) != 0u;
        else if (uv.x >= max(p0.x, p1.x))
            h = (entry & 1u) != 0u;
        // The piece is monotone in u and v, so it lies in the box of its ends: below the box it
        // is above the point at every u, above the box below it. Only a point inside the box
        // needs the root find (most fragments of an edge texel are not).
        else if (uv.y < min(p0.y, p1.y))
            h = true;
        else if (uv.y >= max(p0.y, p1.y))
            h = false;
        else {
            uvec4 rest = kwTrimQuad(p + 4u); // t0, t1, arc
            h = kwTrimPieceV(rest.z, uv.x, uintBitsToFloat(rest.x), uintBitsToFloat(rest.y), p0,
                             p1) > uv.y;
        }
        inside = inside != h;
    }
    return !inside;
}

#ifdef KW_TRIM_AA
#define KW_TRIM_AA_MAX_TEXELS 4
// Anti-aliasing: the fraction of the fragment's pixel that lies inside the
// trimmed surface, from the exact distance to the nearest trim curve in screen pixels (after
// Schollmeyer & Froehlich 2019); see kwTrimCoverageExact.

// True where `point` (on screen, from the fragment) lies on the line whose nearest point to the
// fragment is `foot`, to a fiftieth of a pixel.
bool kwTrimOnLine(vec2 point, vec2 foot) {
    float f = length(foot);
    return f > 1e-6 && abs(dot(point, foot) / f - f) < 0.02;
}

// Keeps the three nearest feet (nearest points of lines on screen, from the fragment) of
// different lines in order: a, b, c. Empty slots hold vec2(1e15). A line found again (by its
// chord and its tangents, or by the pieces of another texel) is one line.
void kwTrimKeepFoot(vec2 f, inout vec2 a, inout vec2 b, inout vec2 c) {
    if (kwTrimOnLine(f, a) && kwTrimOnLine(a, f))
        return;
    if (kwTrimOnLine(f, b) && kwTrimOnLine(b, f))
        return;
    if (kwTrimOnLine(f, c) && kwTrimOnLine(c, f))
        return;
    float d = dot(f, f);
    if (d < dot(a, a)) {
        c = b, b = a, a = f;
    } else if (d < dot(b, b)) {
        c = b, b = f;
    } else if (d < dot(c, c)) {
        c = f;
    }
}

// The same for piece ends with their piece's chord direction (xy: the end, zw: the chord).
void kwTrimKeepEnd(vec4 e, inout vec4 a, inout vec4 b, inout vec4 c) {
    float d = dot(e.xy, e.xy);
    if (d < dot(a.xy, a.xy)) {
        c = b, b = a, a = e;
    } else if (d < dot(b.xy, b.xy)) {
        c = b, b = e;
    } else if (d < dot(c.xy, c.xy)) {
        c = e;
    }
}

// Whether the piece end e (xy) is within reach of the pixel and not a mere cut of the edge
// whose foot is f: off that line, or its piece (chord zw) turned away from it by more than
// 5 degrees (a vertex of the loop lies on both its edges' lines). No foot counts as off.
bool kwTrimOffLine(vec4 e, vec2 f) {
    if (!(dot(e.xy, e.xy) < 0.5625))
        return false;
    if (!(dot(f, f) < 1e29) || !kwTrimOnLine(e.xy, f))
        return true;
    float chord = length(e.zw), foot = length(f);
    return !(chord > 0.0 && foot > 1e-6) || abs(dot(e.zw, f)) > 0.09 * chord * foot;
}

// Whether foot g, within reach of the pixel, is on another edge than foot f: neither is on the
// other's line (the same line found twice, by its chord and by its tangent, is one edge; the
// two sides of a sliver thinner than a pixel, or of a corner, are two).
bool kwTrimOtherEdge(vec2 f, vec2 g) {
    return dot(g, g) < 0.5625 && !kwTrimOnLine(g, f) && !kwTrimOnLine(f, g);
}

// The ends of the piece at word p (exact points of its arc), and whether the box of the piece
// (which holds it: a piece is monotone in u and v) meets the box [boxLo, boxHi].
bool kwTrimPieceMeets(uint p, vec2 boxLo, vec2 boxHi, out vec2 p0, out vec2 p1) {
    vec4 ends = kwTrimQuadFloats(p);
    p0 = ends.xy;
    p1 = ends.zw;
    return !(any(greaterThan(min(p0, p1), boxHi)) || any(lessThan(max(p0, p1), boxLo)));
}

// The coverage of the pixel by the trimmed surface (KW_WHOLLY where no curve is in reach and
// the centre is inside), or -1 where the pixel holds more than one straight edge can stand for.
// `jacobian` holds d(u, v)/dx and d(u, v)/dy (screen pixels); `inside` is the exact
// classification of the pixel's centre.
//
// Candidates: the pieces of the texels under the pixel's footprint (the box in (u, v) holding
// the image of the screen square of half-size 0.75 px), at most KW_TRIM_AA_MAX_TEXELS a side:
// past that the pixel is aliased (see below). A footprint within one texel of a texel without the near bit
// (no edge texel about it) has none, known from one word. For each piece whose box meets the
// footprint: its chord (the segment between its ends) where the arc is straight or the piece
// within a pixel, else its nearer end; on curved arcs, the tangent where the fragment's u and v
// lines cross it, when that crossing lies within 2 px and the tangent's nearest point lies on
// the piece (so that a tangent taken far along a curved piece, or past a corner, cannot pass
// near the fragment). What is kept is the nearest point ("foot") of each line and the nearest
// piece ends.
//
// One line in reach: the pixel is covered as the box filter covers it on the inside of that
// straight edge (kwEdgeCoverage). Two faces sharing a trim curve cut it into pieces at different
// places (their grids differ) and still find the same line, so their coverages add up to the
// pixel (no seam, tst_render_trims_aa). -1, for the caller to count samples (trimCoverage):
// a second line in reach (the far side of a sliver thinner than a pixel, the other edge of a
// corner), or a piece end in reach that is not a mere cut of the nearest line (a vertex).
float kwTrimCoverageExact(vec2 uv, vec2 unit, mat2 jacobian, bool inside) {
    float det = determinant(jacobian);
    if (!(abs(det) > 0.0))
        return inside ? KW_WHOLLY : 0.0; // degenerate (edge-on) pixel: no area to share
    vec2 size = uTrimSize;
    vec2 span = uTrimRect.yw - uTrimRect.xz;
    // The footprint: the box in (u, v) holding the screen square of half-size 0.75 about the
    // fragment, so that the nearest point of any curve that reaches into the pixel (within
    // 0.71 px of its centre) is inside it, with the piece that holds it.
    vec2 reach = 0.75 * (abs(jacobian[0]) + abs(jacobian[1]));
    vec2 boxLo = uv - reach, boxHi = uv + reach;
    ivec2 isize = ivec2(size);
    ivec2 lo = clamp(ivec2(floor((boxLo - uTrimRect.xz) / span * size)), ivec2(0), isize - 1);
    ivec2 hi = clamp(ivec2(floor((boxHi - uTrimRect.xz) / span * size)), ivec2(0), isize - 1);
    // A footprint within a texel of the fragment's texel, which has no edge texel about it:
    // no curve in reach, known from one word (most fragments).
    ivec2 cell = clamp(ivec2(floor(unit * size)), ivec2(0), isize - 1);
    if (all(lessThanEqual(hi - cell, ivec2(1))) && all(lessThanEqual(cell - lo, ivec2(1))) &&
        (kwTrimWord(uTrimBlock + 4u + uint(cell.y * isize.x + cell.x)) & 2u) == 0u)
        return inside ? KW_WHOLLY : 0.0;
    // A grid much finer than the pixel (small faces seen from afar: the grid's resolution
    // follows the loops' complexity, not the screen): walking every texel under the footprint
    // would cost each fragment dozens of lists, so such pixels keep the exact classification of
    // their centre, aliased (MSAA still smooths the silhouettes).
    if (any(greaterThan(hi - lo, ivec2(KW_TRIM_AA_MAX_TEXELS - 1))))
        return inside ? KW_WHOLLY : 0.0;
    uint entries = uTrimBlock + kwTrimWord(uTrimBlock);
    uint pieces = uTrimBlock + kwTrimWord(uTrimBlock + 1u);
    // First only the pieces' boxes: most fragments that get here (within a texel of an edge
    // texel) have no piece whose box meets their footprint, and the full walk below does
    // nothing for such a piece, so they end here. The rest walk only the texels whose pieces
    // do (in the same order: the answer is the same). On a SIMD machine (llvmpipe's lanes, a
    // GPU's warps) the walk's body runs for every lane while any lane needs it, so keeping the
    // lanes without work out of it is what saves (docs/PERFORMANCE.md, "The trim coverage
    // walk").
    ivec2 hitLo = hi + 1, hitHi = lo - 1;
    for (int j = lo.y; j <= hi.y; ++j) {
        for (int i = lo.x; i <= hi.x; ++i) {
            uint k = uTrimBlock + 4u + uint(j * isize.x + i);
            uint last = kwTrimWord(k + 1u) >> 2;
            for (uint e = kwTrimWord(k) >> 2; e < last; ++e) {
                vec2 p0, p1;
                if (kwTrimPieceMeets(pieces + 8u * (kwTrimWord(entries + e) >> 2), boxLo, boxHi,
                                     p0, p1)) {
                    hitLo = min(hitLo, ivec2(i, j));
                    hitHi = max(hitHi, ivec2(i, j));
                }
            }
        }
    }
    if (any(greaterThan(hitLo, hitHi)))
        return inside ? KW_WHOLLY : 0.0;
    lo = hitLo;
    hi = hitHi;
    mat2 toScreen = inverse(jacobian); // only for the few fragments near a curve
    vec2 foot0 = vec2(1e15), foot1 = vec2(1e15), foot2 = vec2(1e15);
    vec4 end0 = vec4(1e15), end1 = vec4(1e15), end2 = vec4(1e15); // the nearest piece ends
    for (int j = lo.y; j <= hi.y; ++j) {
        for (int i = lo.x; i <= hi.x; ++i) {
            uint k = uTrimBlock + 4u + uint(j * isize.x + i);
            uint last = kwTrimWord(k + 1u) >> 2;
            for (uint e = kwTrimWord(k) >> 2; e < last; ++e) {
                uint p = pieces + 8u * (kwTrimWord(entries + e) >> 2);
                vec2 p0, p1;
                if (!kwTrimPieceMeets(p, boxLo, boxHi, p0, p1))
                    continue;
                vec2 pieceLo = min(p0, p1), pieceHi = max(p0, p1);
                uvec4 rest = kwTrimQuad(p + 4u);
                uint arc = rest.z;
                float t0 = uintBitsToFloat(rest.x), t1 = uintBitsToFloat(rest.y);
                uint header = uTrimBlock + kwTrimWord(uTrimBlock + 2u) + 2u * arc;
                uint first = uTrimBlock + kwTrimWord(uTrimBlock + 3u) + 4u * kwTrimWord(header);
                int degree = int(kwTrimWord(header + 1u));
                // The piece's ends, exact points of the curve, and its chord on screen where
                // that is the curve: a straight arc, or a piece within a pixel (its sagitta a
                // small part of that).
                vec2 s0 = toScreen * (p0 - uv), s1 = toScreen * (p1 - uv);
                vec2 chord = s1 - s0;
                float along = 0.0;
                if ((degree <= 1 || dot(chord, chord) <= 1.0) && dot(chord, chord) > 0.0)
                    along = clamp(-dot(s0, chord) / dot(chord, chord), 0.0, 1.0);
                else if (dot(s1, s1) < dot(s0, s0))
                    along = 1.0;
                vec2 q = s0 + along * chord;
                if (along > 0.0 && along < 1.0)
                    kwTrimKeepFoot(q, foot0, foot1, foot2);
                else
                    kwTrimKeepEnd(vec4(q, chord), end0, end1, end2);
                // A straight arc's chord is exact; a curved one's tangents where the
                // fragment's u and v lines cross it.
                for (int axis = 0; axis < (degree > 1 ? 2 : 0); ++axis) {
                    if (!(uv[axis] > pieceLo[axis] && uv[axis] < pieceHi[axis]))
                        continue;
                    float t;
                    vec2 c = kwTrimPieceSolve(arc, axis, uv[axis], t0, t1, p0, p1, t);
                    vec2 sc = toScreen * (c - uv);
                    if (dot(sc, sc) > 4.0)
                        continue;
                    // The tangent by a central difference inside the piece (the exact
                    // derivative would need the arc's hodograph; a direction is all we use).
                    float h = 1e-3 * (t1 - t0);
                    vec2 tangent = kwTrimArcPoint(first, degree, min(t + h, t1)) -
                                   kwTrimArcPoint(first, degree, max(t - h, t0));
                    if (!(dot(tangent, tangent) > 0.0))
                        tangent = p1 - p0;
                    // The tangent line's nearest point to the fragment, on screen (the
                    // screen's metric, not the (u, v) one, decides what is near).
                    vec2 ts = toScreen * tangent;
                    if (!(dot(ts, ts) > 0.0))
                        continue;
                    vec2 foot = sc - ts * (dot(sc, ts) / dot(ts, ts));
                    // Only where that point is on this piece: past the piece's end (a corner
                    // of the loop) the line would come nearer than the curve, and the face on
                    // the other side, whose pieces end elsewhere, would not see that line.
                    vec2 footUv = uv + jacobian * foot;
                    vec2 slack = 0.05 * reach; // a twentieth of a pixel: rounding, not corners
                    if (any(lessThan(footUv, pieceLo - slack)) ||
                        any(greaterThan(footUv, pieceHi + slack)))
                        continue;
                    kwTrimKeepFoot(foot, foot0, foot1, foot2);
                }
            }
        }
    }
    float best = length(foot0);
    if (min(best, length(end0.xy)) >= 0.75) // no curve reaches into the pixel (0.71 px at most)
        return inside ? KW_WHOLLY : 0.0;
    // An end in reach that is off the nearest line: a vertex of the loop (a piece's end where
    // the curve goes on is on its line), or two edges in different directions.
    if (kwTrimOffLine(end0, foot0) || kwTrimOffLine(end1, foot0) ||
        kwTrimOffLine(end2, foot0) || kwTrimOtherEdge(foot0, foot1) ||
        kwTrimOtherEdge(foot0, foot2))
        return -1.0;
    if (!(best > 1e-6)) // the curve through the pixel's centre
        return 0.5;
    return kwEdgeCoverage(inside ? best : -best, foot0 / best);
}
#endif
