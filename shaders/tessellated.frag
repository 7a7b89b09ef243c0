// Baseline pass: Gouraud colour; AOVs are the interpolated tessellation values. KW_TRIM: discard
// where the trim mask says trimmed, at the interpolated (u, v).
#include "trim_sample.glsl"

in vec3 vColor;
in vec2 vUv;
in vec3 vPosition;
in vec3 vNormal;
in float vDepth;

uniform float uSurfaceId;

layout(location = 0) out vec4 fragColor;
#ifdef KW_AOV
layout(location = 1) out vec4 aovIdUvDepth;
layout(location = 2) out vec4 aovPosition;
layout(location = 3) out vec4 aovNormal;
#endif

void main() {
    KW_DISCARD_TRIMMED(vUv);
    fragColor = vec4(vColor, 1.0);
#ifdef KW_AOV
    aovIdUvDepth = vec4(uSurfaceId, vUv, vDepth);
    aovPosition = vec4(vPosition, 1.0);
    aovNormal = vec4(normalize(vNormal), 0.0);
#endif
}
