// Resolves kw::AccumulateTarget into the host's framebuffer: the mean of the samples' colours,
// and the last sample's depth, so overlays drawn afterwards are hidden by the surfaces as
// without anti-aliasing.
layout(binding = KW_ACCUMULATE_SAMPLE_UNIT) uniform sampler2D uSum;
layout(binding = KW_ACCUMULATE_DEPTH_UNIT) uniform sampler2D uDepth;
uniform float uScale; // 1 / samples

layout(location = KW_COLOUR_OUTPUT) out vec4 fragColor;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    fragColor = texelFetch(uSum, pixel, 0) * uScale;
    gl_FragDepth = texelFetch(uDepth, pixel, 0).r;
}
