// Section planes (KW_SECTION; kw::SectionPlane, set by kw::setSectionUniforms): a pixel is cut
// by its exact point, the caps close what a cut opens in a closed solid, and the section curve
// is drawn where a kept surface meets a plane. Needs uEye (phong.glsl).
#ifndef KW_SECTION_GLSL
#define KW_SECTION_GLSL

// xyz: unit normal pointing into the removed half-space, w: -dot(normal, a point of the
// plane); a point x is removed where dot(xyz, x) + w > 0 for any of the first uSectionCount.
uniform vec4 uSectionPlanes[KW_MAX_SECTIONS];
uniform int uSectionCount;
uniform int uSectionCaps; // 1: cap closed solids
// How far past the plane each point is: > 0 removed. The largest over the planes.
float kwSectionBeyond(vec3 point) {
    float beyond = -1e30;
    for (int k = 0; k < uSectionCount; ++k)
        beyond = max(beyond, dot(uSectionPlanes[k].xyz, point) + uSectionPlanes[k].w);
    return beyond;
}

// The section curve's line on a kept surface: 1 within a pixel and a half of a plane (on
// screen, from the distance's screen rate), fading out over the next half pixel. Call it in
// uniform control flow, before kwSectionCut's discard (it takes screen derivatives).
float kwSectionLine(vec3 point) {
    float line = 0.0;
    for (int k = 0; k < uSectionCount; ++k) {
        float d = dot(uSectionPlanes[k].xyz, point) + uSectionPlanes[k].w;
        float rate = fwidth(d);
        if (rate > 0.0)
            line = max(line, 1.0 - smoothstep(1.5, 2.0, -d / rate));
    }
    return line;
}

// True where the point lies on a removed side.
bool kwSectionCut(vec3 point) {
    return uSectionCount > 0 && kwSectionBeyond(point) > 0.0;
}

// The cap in front of a kept `point` of a closed solid's face seen from inside (its outward
// normal `outward` turned away from the eye): the ray from the eye entered the kept region
// through the plane returned (-1: none, the eye is inside every kept half-space, and the face
// is seen from inside the solid itself), at `capPoint`. Where this face is the first kept
// surface on the ray (the depth test decides: the cap keeps the face's depth), the ray
// crosses no kept surface between that point and `point`, and leaves the solid at `point`, so
// the segment lies inside the solid: the cap is solid material.
int kwSectionCap(vec3 point, vec3 outward, out vec3 capPoint) {
    capPoint = point;
    vec3 ray = point - uEye;
    if (uSectionCaps == 0 || !(dot(outward, ray) > 0.0))
        return -1;
    float enter = 0.0;
    int plane = -1;
    for (int k = 0; k < uSectionCount; ++k) {
        float atEye = dot(uSectionPlanes[k].xyz, uEye) + uSectionPlanes[k].w;
        float along = dot(uSectionPlanes[k].xyz, ray);
        if (atEye > 0.0 && along < 0.0 && -atEye / along > enter) {
            enter = -atEye / along;
            plane = k;
        }
    }
    if (plane >= 0)
        capPoint = uEye + min(enter, 1.0) * ray;
    return plane;
}

// A cap's colour: the solid's, lit with the plane's normal, with dark hatching at 45 degrees
// every 8 pixels on screen (the same density at any zoom).
vec3 kwCapColour(vec3 lit) {
    float band = mod(gl_FragCoord.x + gl_FragCoord.y, 8.0);
    return band < 1.5 ? lit * 0.45 : lit;
}

// The section curve's line colour over a kept surface.
vec3 kwSectionLineColour(vec3 colour, float line) {
    return mix(colour, vec3(0.05, 0.05, 0.06), line);
}

#endif // KW_SECTION_GLSL
