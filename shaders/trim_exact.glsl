// Exact trim classification on the GPU (issue 11): the hybrid trim grid of model/trim_grid.h,
// packed by kw::packTrimGrid (render/trim_grid_store.h) into one R32UI texture buffer. A
// fragment in a texel without pieces takes the texel's parity bit; one in an edge texel adds
// the crossings of the texel's few monotone arc pieces (Schollmeyer & Froehlich 2009), each
// found by regula falsi on the exact rational Bezier arc. Included by trim_sample.glsl, which
// declares uTrimRect, uTrimSize (the grid's texels along u and v) and uTrimBlock (the
// surface's first word), per draw or from the surface table.
// A texture buffer, not an SSBO: llvmpipe (Mesa 22.3) returns 0 from SSBO loads in helper
// invocations (shaders/surface_data.glsl). Unit 9 is kw::kTrimGridUnit.
layout(binding = 9) uniform usamplerBuffer kwTrimGrid;

uint kwTrimWord(uint i) { return texelFetch(kwTrimGrid, int(i)).x; }
float kwTrimFloat(uint i) { return uintBitsToFloat(kwTrimWord(i)); }

// The arc's point at t by Horner's rule for the Bernstein form (Farin, "Curves and Surfaces
// for CAGD", 5.3) on its homogeneous control points (degree <= 15), read from the buffer as it
// goes: no local array, which llvmpipe kept in scratch memory for every fragment of the
// variant (a tenth of the frame on trimmed_plate, docs/PERFORMANCE.md ## Trims). `first` is
// the word of its first control point (kwTrimPieceV looks it and the degree up once).
vec2 kwTrimArcPoint(uint first, int degree, float t) {
    uint k = first;
    float s = 1.0 - t, tn = 1.0, binomial = 1.0;
    vec3 sum = vec3(kwTrimFloat(k), kwTrimFloat(k + 1u), kwTrimFloat(k + 2u));
    if (degree == 0)
        return sum.xy / sum.z;
    sum *= s;
    for (int i = 1; i < degree; ++i) {
        k += 3u;
        tn *= t;
        binomial *= float(degree - i + 1) / float(i);
        sum = (sum + tn * binomial * vec3(kwTrimFloat(k), kwTrimFloat(k + 1u),
                                          kwTrimFloat(k + 2u))) * s;
    }
    k += 3u;
    vec3 h = sum + tn * t * vec3(kwTrimFloat(k), kwTrimFloat(k + 1u), kwTrimFloat(k + 2u));
    return h.xy / h.z;
}

// v of the piece where its u equals u, u strictly inside [u0, u1) of the piece's ends: the
// Illinois variant of regula falsi (Dowell & Jarratt 1971), as trimArcSolve does on the CPU.
float kwTrimPieceV(uint arc, float u, float t0, float t1, vec2 p0, vec2 p1) {
    // At an end the answer is that end: the bracket's sign test below would take fa == 0 for
    // the wrong side (a fragment whose u is an end's u to the last bit, as at a loop vertex).
    bool rising = p1.x >= p0.x;
    if (rising ? u <= p0.x : u >= p0.x)
        return p0.y;
    if (rising ? u >= p1.x : u <= p1.x)
        return p1.y;
    // The arc's header, once per piece rather than once per evaluation below.
    uint header = uTrimBlock + kwTrimWord(uTrimBlock + 2u) + 2u * arc;
    uint first = uTrimBlock + kwTrimWord(uTrimBlock + 3u) + 3u * kwTrimWord(header);
    int degree = int(kwTrimWord(header + 1u));
    float a = t0, b = t1, fa = p0.x - u, fb = p1.x - u;
    float va = p0.y, vb = p1.y;
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
        float fm = pm.x - u;
        if (fm == 0.0)
            return pm.y;
        if ((fm < 0.0) == (fa < 0.0)) {
            a = m, fa = fm, va = pm.y;
            if (side == -1)
                fb *= 0.5;
            side = -1;
        } else {
            b = m, fb = fm, vb = pm.y;
            if (side == 1)
                fa *= 0.5;
            side = 1;
        }
        bisect = b - a > 0.75 * width; // slow progress: bisect next
    }
    return abs(fa) < abs(fb) ? va : vb;
}

// True where the grid says (u, v) is outside the trimmed surface; unit is (u, v) mapped to the
// grid's rectangle, inside [0, 1]^2.
bool kwTrimmedAwayExact(vec2 uv, vec2 unit) {
    ivec2 size = ivec2(uTrimSize);
    ivec2 cell = clamp(ivec2(floor(unit * vec2(size))), ivec2(0), size - 1);
    uint k = uTrimBlock + 4u + uint(cell.y * size.x + cell.x);
    uint word = kwTrimWord(k);
    bool inside = (word & 1u) != 0u;
    uint last = kwTrimWord(k + 1u) >> 1;
    if (last == word >> 1)
        return !inside; // no piece in this texel: its parity alone decides
    uint entries = uTrimBlock + kwTrimWord(uTrimBlock);
    uint pieces = uTrimBlock + kwTrimWord(uTrimBlock + 1u);
    for (uint e = word >> 1; e < last; ++e) {
        uint entry = kwTrimWord(entries + e);
        uint p = pieces + 8u * (entry >> 2);
        vec2 p0 = vec2(kwTrimFloat(p), kwTrimFloat(p + 1u));
        vec2 p1 = vec2(kwTrimFloat(p + 2u), kwTrimFloat(p + 3u));
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
        else
            h = kwTrimPieceV(kwTrimWord(p + 6u), uv.x, kwTrimFloat(p + 4u), kwTrimFloat(p + 5u),
                             p0, p1) > uv.y;
        inside = inside != h;
    }
    return !inside;
}
