// Adds one accumulated sample's colour into the sum (kw::AccumulateTarget::add; blended with
// GL_ONE, GL_ONE after the first sample).
layout(binding = KW_ACCUMULATE_SAMPLE_UNIT) uniform sampler2D uSample;

layout(location = KW_COLOUR_OUTPUT) out vec4 fragColor;

void main() {
    fragColor = texelFetch(uSample, ivec2(gl_FragCoord.xy), 0);
}
