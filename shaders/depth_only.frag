// Depth pre-pass: no colour, the rasteriser writes the base polygon's depth. With KW_TRIM it
// discards exactly as exact_surface.frag does, or trimmed holes would keep their depth and hide
// what lies behind them under GL_EQUAL.
#include "surface_data.glsl"
#include "trim_sample.glsl"

in vec2 vUv;
flat in int vSurface;

void main() {
    kwSurface = vSurface;
    KW_DISCARD_TRIMMED(vUv);
}
