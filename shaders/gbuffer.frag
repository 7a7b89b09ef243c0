// Deferred exact shading, pass 1: the base polygon writes what the exact pass needs per pixel.
in vec2 vUv;
flat in ivec2 vSpan;
flat in float vSpanScale;

uniform float uSlot; // 1 + the surface's index in the frame (0 = background)

layout(location = 0) out vec4 gUvSpan;  // u, v, knot span u, knot span v (exact in float < 2^24)
layout(location = 1) out vec4 gSurface; // slot, span scale, window depth, unused

void main() {
    gUvSpan = vec4(vUv, vec2(vSpan));
    gSurface = vec4(uSlot, vSpanScale, gl_FragCoord.z, 0.0);
}
