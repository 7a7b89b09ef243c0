// Edge Continuity overlay: line segments in their class colour, drawn several times shifted by
// a few pixels (uOffset, in clip units per w) to make a band, pulled towards the camera.
layout(location = KW_ATTR_POSITION) in vec3 aPosition;
layout(location = KW_ATTR_BAND_COLOUR) in vec4 aColor;

uniform mat4 uViewProjection;
uniform vec2 uOffset;
uniform float uDepthBias; // fraction of clip w

out vec4 vColor;

void main() {
    gl_Position = uViewProjection * vec4(aPosition, 1.0);
    gl_Position.xy += uOffset * gl_Position.w;
    // Reversed depth (render/depth_convention.h): nearer is greater.
    gl_Position.z += 0.5 * uDepthBias * gl_Position.w;
    vColor = aColor;
}
