// Baseline pass: Gouraud colour; AOVs are the interpolated tessellation values. KW_TRIM: discard
// where the trim mask says trimmed, at the interpolated (u, v). KW_SECTION: section planes cut
// at the interpolated point (the mesh's), caps where a closed solid is seen from inside
// (section.glsl; the depth stays the face's, as in exact_surface.frag).
#include "trim_sample.glsl"
#ifdef KW_SECTION
#include "phong.glsl"
#include "section.glsl"
uniform vec3 uForward;
uniform int uSolidSide; // 1: a closed solid's outside is along the normal, -1: against, 0: none
#endif

in vec3 vColor;
in vec2 vUv;
in vec3 vPosition;
in vec3 vNormal;
in float vDepth;

uniform float uSurfaceId;

layout(location = KW_COLOUR_OUTPUT) out vec4 fragColor;
#ifdef KW_AOV
layout(location = KW_AOV_ID_UV_DEPTH_OUTPUT) out vec4 aovIdUvDepth;
layout(location = KW_AOV_POSITION_OUTPUT) out vec4 aovPosition;
layout(location = KW_AOV_NORMAL_OUTPUT) out vec4 aovNormal;
#endif

void main() {
    KW_DISCARD_TRIMMED(vUv);
    fragColor = vec4(vColor, 1.0);
    vec3 point = vPosition, normal = normalize(vNormal);
    float id = uSurfaceId, depth = vDepth;
    int capPlane = -1;
#ifdef KW_SECTION
    float line = kwSectionLine(point);
    if (kwSectionCut(point))
        discard;
    vec3 capPoint;
    capPlane = uSolidSide == 0 ? -1 : kwSectionCap(point, normal * float(uSolidSide), capPoint);
    if (capPlane >= 0) {
        point = capPoint;
        normal = uSectionPlanes[capPlane].xyz;
        id = float(KW_SECTION_CAP_ID);
        depth = dot(point - uEye, uForward);
        fragColor = vec4(kwCapColour(phong(point, normal)), 1.0);
    } else {
        fragColor.rgb = kwSectionLineColour(fragColor.rgb, line);
    }
#endif
#ifdef KW_AOV
    aovIdUvDepth = vec4(id, capPlane >= 0 ? vec2(0.0) : vUv, depth);
    aovPosition = vec4(point, 1.0);
    aovNormal = vec4(normal, 0.0);
#endif
}
