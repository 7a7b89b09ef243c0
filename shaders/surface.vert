// Base polygon vertex stage (paper 3.4.1): exact vertex positions, (u, v) and the cell's knot span.
// Attributes match kw::BaseVertex (render/gpu_layout.h).
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec2 aUv;
layout(location = 2) in ivec2 aSpan;
layout(location = 3) in float aSpanScale;

uniform mat4 uViewProjection;

// The depth pre-pass and the exact pass must produce bit-identical depths for GL_EQUAL.
invariant gl_Position;

out vec2 vUv;
flat out ivec2 vSpan;
flat out float vSpanScale;

void main() {
    vUv = aUv;
    vSpan = aSpan;
    vSpanScale = aSpanScale;
    gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
