// Baseline pass ("OpenGL API" column of the paper's Table 2): CPU tessellation, per-vertex
// normals, Gouraud shading (lighting per vertex, colour interpolated).
#include "phong.glsl"

layout(location = KW_ATTR_POSITION) in vec3 aPosition;
layout(location = KW_ATTR_MESH_NORMAL) in vec3 aNormal;
layout(location = KW_ATTR_MESH_UV) in vec2 aUv;

uniform mat4 uViewProjection;
uniform vec3 uForward;

out vec3 vColor;
out vec2 vUv;
out vec3 vPosition;
out vec3 vNormal;
out float vDepth;

void main() {
    vColor = phong(aPosition, aNormal);
    vUv = aUv;
    vPosition = aPosition;
    vNormal = aNormal;
    vDepth = dot(aPosition - uEye, uForward);
    gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
