// Overlays (base polygon wireframe, control net): positions pulled slightly towards the camera
// in clip space so lines on the surface win the depth test.
layout(location = KW_ATTR_POSITION) in vec3 aPosition;
out vec3 vWorld; // for KW_SECTION's cut (lines.frag)

uniform mat4 uViewProjection;
uniform float uDepthBias; // fraction of clip w
uniform float uPointSize;

void main() {
    vWorld = aPosition;
    gl_Position = uViewProjection * vec4(aPosition, 1.0);
    // Reversed depth (render/depth_convention.h): nearer is greater. Half the bias in the
    // zero-to-one range moves a line as far as the full bias did in GL's -1..1 range.
    gl_Position.z += 0.5 * uDepthBias * gl_Position.w;
    gl_PointSize = uPointSize;
}
