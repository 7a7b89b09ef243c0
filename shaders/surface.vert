// Base polygon vertex stage (paper 3.4.1): exact vertex positions, (u, v) and the cell's knot span.
// Attributes match kw::BaseVertex (render/gpu_layout.h). The flat outputs are those of the
// cell whose lower-left corner this vertex is (the provoking vertex of its triangles).
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec2 aUv;
layout(location = 2) in ivec2 aSpan;
layout(location = 3) in float aSpanScale;
layout(location = 4) in int aSurface; // per instance: the draw's base instance, a table row

uniform mat4 uViewProjection;

// The depth pre-pass and the exact pass must produce bit-identical depths for GL_EQUAL.
invariant gl_Position;

out vec2 vUv;
flat out ivec2 vSpan;
flat out float vSpanScale;
flat out int vSurface;

#include "surface_data.glsl"
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
#ifdef KW_CELL_GATHER
    ivec2 first = aSpan - ivec2(DEGREE_U, DEGREE_V);
    for (int j = 0; j <= DEGREE_V; ++j)
        for (int i = 0; i <= DEGREE_U; ++i)
            vCellControl[j * (DEGREE_U + 1) + i] = KW_CONTROL(first + ivec2(i, j));
    for (int x = 0; x < KW_SPAN_TEXELS(DEGREE_U); ++x)
        vCellSpanU[x] = KW_SPAN_U(x, first.x);
    for (int x = 0; x < KW_SPAN_TEXELS(DEGREE_V); ++x)
        vCellSpanV[x] = KW_SPAN_V(x, first.y);
#endif
    gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
