// Base polygon vertex stage (paper 3.4.1): exact vertex positions, (u, v) and the cell's knot span.
// Attributes match kw::BaseVertex (render/gpu_layout.h). The flat outputs are those of the
// cell whose lower-left corner this vertex is (the provoking vertex of its triangles).
layout(location = KW_ATTR_POSITION) in vec3 aPosition;
layout(location = KW_ATTR_UV) in vec2 aUv;
layout(location = KW_ATTR_SPAN) in ivec2 aSpan;
layout(location = KW_ATTR_SPAN_SCALE) in float aSpanScale;
layout(location = KW_ATTR_SURFACE) in int aSurface; // per instance: the draw's base instance, a table row

uniform mat4 uViewProjection;

// The depth pre-pass and the exact pass must produce bit-identical depths for GL_EQUAL.
invariant gl_Position;

out vec2 vUv;
flat out ivec2 vSpan;
flat out float vSpanScale;
flat out int vSurface;
#ifdef KW_GBUFFER
flat out int vVertex; // the provoking vertex: the cell's span and span scale (KW_DEFERRED)
#endif

#include "surface_data.glsl"
#ifdef KW_SKIRT
// The edge skirt (kw::buildSkirt, kw::ExactSurfacePass::skirtPass): the outline's nodes, those
// marked with an outward (u, v) direction pushed uSkirtPixels across the edge on screen.
layout(location = KW_ATTR_OUTWARD) in vec2 aOutward;
uniform float uSkirtPixels;
uniform float uSkirtDepthScale; // clip z factor: the strip lies kSkirtDepthPixels behind
#include "nurbs_surface.glsl"
#include "window.glsl"
#endif
#ifdef KW_CELL_GATHER
#define KW_CELL_IO flat out
#include "cell_data.glsl"
#endif

void main() {
    vUv = aUv;
    vSpan = aSpan;
    vSpanScale = aSpanScale;
    vSurface = aSurface;
    kwSurface = aSurface;
#ifdef KW_GBUFFER
    vVertex = gl_VertexID;
#endif
#ifdef KW_CELL_GATHER
    ivec2 first = aSpan - ivec2(DEGREE_U, DEGREE_V);
    for (int j = 0; j <= DEGREE_V; ++j)
        for (int i = 0; i <= DEGREE_U; ++i)
            vCellControl[j * (DEGREE_U + 1) + i] = KW_CONTROL(first + ivec2(i, j));
    for (int x = 0; x < KW_SPAN_TEXELS_U; ++x)
        vCellSpanU[x] = KW_SPAN_U(x, first.x);
    for (int x = 0; x < KW_SPAN_TEXELS_V; ++x)
        vCellSpanV[x] = KW_SPAN_V(x, first.y);
#endif
    gl_Position = uViewProjection * vec4(aPosition, 1.0);
#ifdef KW_SKIRT
    if (aOutward != vec2(0.0) && gl_Position.w > 0.0) {
        // The screen images of the tangents across the edge (outward) and along it.
        SurfacePartials d = surfacePartials(clamp(aUv, uDomain.xz, uDomain.yw), aSpan);
        vec2 across = kwWindowTangent(gl_Position, aOutward.x * d.su + aOutward.y * d.sv);
        vec2 along = kwWindowTangent(gl_Position, aOutward.y * d.su + aOutward.x * d.sv);
        float rate = length(across);
        // The strip must reach uSkirtPixels from the edge measured square to it on screen: the
        // push along `across` is longer where it runs obliquely to the edge, up to 4 times.
        float square = length(along) > 0.0 ? abs(determinant(mat2(across, along))) / length(along)
                                            : rate;
        square = max(square, 0.25 * rate);
        if (square > 0.0) {
            // (u, v) moves with the point to first order; at most a quarter of the domain across
            // (an edge seen end on, or collapsed, has no gap to cover).
            vec2 extent = uDomain.yw - uDomain.xz;
            float du = min(uSkirtPixels / square, 0.25 * abs(dot(extent, aOutward)));
            // Where the surface folds (a silhouette) between the edge and du inside it, the
            // edge is a hidden sliver's and the outward tangent's image points back under the
            // face: the strip would lie under its own face while the pixel centres between the
            // edge and the exact outline, outside the polygon and with no polygon silhouette
            // edge to carry a fin, showed the background. The fold turns the tangent's image
            // across the edge (square to the edge's image) round, and the edge's sheet is the
            // hidden one when the surface past the fold is nearer the eye (across a fold the
            // depth changes to first order, the screen position to second; where the edge's
            // sheet is in front, its own outline is the face's and the strip stays outside).
            // The strip then goes the other way on screen, its (u, v) into the domain, towards
            // the fold.
            vec2 inner = clamp(aUv - aOutward * du, uDomain.xz, uDomain.yw);
            SurfacePartials e = surfacePartials(inner, aSpan);
            vec4 innerClip = uViewProjection * vec4(e.s + uOrigin, 1.0);
            float side = 1.0;
            vec2 innerAcross = kwWindowTangent(innerClip, aOutward.x * e.su + aOutward.y * e.sv);
            if (innerClip.w > 0.0 && innerClip.w < gl_Position.w &&
                determinant(mat2(across, along)) * determinant(mat2(innerAcross, along)) < 0.0)
                side = -1.0;
            vUv = aUv + side * aOutward * du;
            gl_Position.xy += side * across * du * 2.0 / uViewport.zw * gl_Position.w;
        }
    }
    // Behind its own polygon by a few pixels' worth of distance along the ray (reversed depth:
    // smaller is farther), so the face's own pixels, a neighbour's polygon (within the
    // tolerance of the same surface in 3D, by the adaptive bound) and anything in front reject
    // the strip before it is shaded: it fills only gaps, over the background or a face far
    // behind.
    gl_Position.z *= uSkirtDepthScale;
#endif
}
