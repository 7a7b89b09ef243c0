// Depth pre-pass: no colour, the rasteriser writes the base polygon's depth. With KW_TRIM it
// discards exactly as exact_surface.frag does, or trimmed holes would keep their depth and hide
// what lies behind them under GL_EQUAL.
#include "surface_data.glsl"
#include "trim_sample.glsl"

in vec2 vUv;
flat in int vSurface;
#ifdef KW_GBUFFER
// With the deferred exact pass (kw::ExactSurfacePass): the polygon's (u, v), the surface's
// row and facing, and the cell's provoking vertex, for exact_surface.frag's KW_DEFERRED.
flat in int vVertex;
layout(location = KW_PREPASS_OUTPUT) out uvec4 kwPrepassOut;
#endif

void main() {
    kwSurface = vSurface;
    KW_DISCARD_TRIMMED(vUv);
#ifdef KW_GBUFFER
    kwPrepassOut = kwPrepassWords(vUv, vSurface, gl_FrontFacing, vVertex);
#endif
}
