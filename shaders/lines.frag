// Overlays: one flat colour. AOV targets are left untouched (draw buffer 0 only). KW_SECTION:
// the section planes cut the lines as they cut the surfaces (section.glsl).
uniform vec4 uLineColor;
layout(location = KW_COLOUR_OUTPUT) out vec4 fragColor;
in vec3 vWorld;
#ifdef KW_SECTION
uniform vec3 uEye; // section.glsl's caps read it; lines draw none
#include "section.glsl"
#endif

void main() {
#ifdef KW_SECTION
    if (kwSectionCut(vWorld))
        discard;
#endif
    fragColor = uLineColor;
}
