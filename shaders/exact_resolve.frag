// Deferred exact shading, pass 2 (paper 3.4.1): for each pixel the G-buffer assigns to this
// surface, evaluate the exact NURBS point and normal at its (u, v) and shade it, once.
// Variants as exact_surface.frag: DEGREE_U/DEGREE_V, LIGHT_COUNT, KW_AOV.
#include "nurbs_surface.glsl"
#include "phong.glsl"

uniform sampler2D uUvSpan;  // G-buffer attachment 0
uniform sampler2D uSurface; // G-buffer attachment 1
uniform float uSlot;
uniform float uSurfaceId;
uniform vec3 uForward;

layout(location = 0) out vec4 fragColor;
#ifdef KW_AOV
layout(location = 1) out vec4 aovIdUvDepth; // surface id, u, v, eye-space depth
layout(location = 2) out vec4 aovPosition;  // exact point, w = 1
layout(location = 3) out vec4 aovNormal;    // unit normal (Su x Sv side, not flipped), w = 0
#endif

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 g1 = texelFetch(uSurface, pixel, 0);
    if (g1.x != uSlot)
        discard;
    vec4 g0 = texelFetch(uUvSpan, pixel, 0);
    // Trimming (later issue) samples the surface's trim mask at g0.xy here and discards.
    SurfaceSample s = evaluateSurface(g0.xy, ivec2(g0.zw), g1.y);
    gl_FragDepth = g1.z; // the base polygon's depth, so overlays test against the surfaces
    fragColor = vec4(phong(s.point, s.normal), 1.0);
#ifdef KW_AOV
    aovIdUvDepth = vec4(uSurfaceId, g0.xy, dot(s.point - uEye, uForward));
    aovPosition = vec4(s.point, 1.0);
    aovNormal = vec4(s.normal, 0.0);
#endif
}
