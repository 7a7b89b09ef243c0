// Resolves kw::AntialiasTarget into the host's framebuffer: per sample, the edge pass's
// accumulated premultiplied colour over what the opaque passes drew, then the box filter's
// average of the samples (the MSAA resolve). Coverage summed past 1 (partly covered fragments
// of overlapping edges) is normalised. The depth written is the nearest sample's, so overlays
// drawn afterwards are hidden by the surfaces as without anti-aliasing.
layout(binding = KW_COMPOSITE_COLOUR_UNIT) uniform sampler2DMS uColour;
layout(binding = KW_COMPOSITE_ACCUM_UNIT) uniform sampler2DMS uAccum;
layout(binding = KW_COMPOSITE_DEPTH_UNIT) uniform sampler2DMS uDepth;

layout(location = KW_COLOUR_OUTPUT) out vec4 fragColor;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 sum = vec4(0.0);
    float depth = 0.0; // reversed depth (render/depth_convention.h): the nearest is the greatest
    int samples = textureSamples(uColour);
    for (int s = 0; s < samples; ++s) {
        vec4 below = texelFetch(uColour, pixel, s);
        vec4 edge = texelFetch(uAccum, pixel, s);
        float covered = min(edge.a, 1.0);
        vec4 over = edge.a > 1.0 ? edge / edge.a : edge;
        sum += vec4(over.rgb, covered) + (1.0 - covered) * below;
        depth = max(depth, texelFetch(uDepth, pixel, s).r);
    }
    fragColor = sum / float(samples);
    gl_FragDepth = depth;
}
