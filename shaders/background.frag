// The background's vertical gradient (RenderOptions::backgroundTop, kw::Renderer): the bottom
// colour along the view's bottom edge, the top colour along its top edge, drawn over the clear
// before the scene. Writes the colour target only (the renderer masks the AOV targets).
uniform vec4 uViewport;         // the view's origin and size in window pixels
uniform vec4 uBackgroundBottom; // RenderOptions::background
uniform vec4 uBackgroundTop;    // RenderOptions::backgroundTop

layout(location = KW_COLOUR_OUTPUT) out vec4 fragColor;

void main() {
    float t = clamp((gl_FragCoord.y - uViewport.y) / max(uViewport.w, 1.0), 0.0, 1.0);
    fragColor = mix(uBackgroundBottom, uBackgroundTop, t);
}
