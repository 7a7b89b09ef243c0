// Window coordinates (pixels, as gl_FragCoord) of clip-space points and of world tangents, for
// the surface passes. Needs uViewProjection declared first. uViewport is glViewport's x, y,
// width and height (kw::setFrameUniforms; a pick shifts it onto its one pixel).
#ifndef KW_WINDOW_GLSL
#define KW_WINDOW_GLSL
uniform vec4 uViewport;

vec2 kwWindow(vec4 clip) {
    return uViewport.xy + (clip.xy / clip.w + 1.0) * 0.5 * uViewport.zw;
}

// The window-space image of the world tangent t at the point whose clip position is clip: the
// derivative of the perspective division, d(xy / w) = (dxy - xy / w dw) / w.
vec2 kwWindowTangent(vec4 clip, vec3 t) {
    vec4 ct = uViewProjection * vec4(t, 0.0);
    return (ct.xy - clip.xy / clip.w * ct.w) / clip.w * 0.5 * uViewport.zw;
}
#endif
