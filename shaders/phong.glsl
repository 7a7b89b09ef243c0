// Phong shading (paper eq. 3.8), two-sided: the normal is turned towards the viewer.
// I = (ka * sum ia + kd (sum max(L.N, 0) id + fill)) * colour + sum ks max(R.V, 0)^alpha is,
// fill = uFill.x + uFill.y N.V: the viewer's fill (kw::kViewerFill), so no visible face is black.
// LIGHT_COUNT (1..KW_MAX_LIGHTS) is a compile-time constant so the light loop unrolls: on llvmpipe a
// uniform-bounded loop cost as much as the whole NURBS evaluation (docs/PERFORMANCE.md).

uniform vec4 uLightVector[KW_MAX_LIGHTS];   // xyz: unit direction towards the light (w = 0) or position (w = 1)
uniform vec3 uLightDiffuse[KW_MAX_LIGHTS];
uniform vec3 uLightSpecular[KW_MAX_LIGHTS];
uniform vec3 uAmbient;  // sum of the lights' ambient intensities
uniform vec2 uFill;     // the viewer's fill (kw::kViewerFill): kd (x + y |N.V|) colour
#ifndef KW_SURFACE_DATA // else the surface's row of the surface table (surface_data.glsl)
uniform vec3 uColor;
uniform vec4 uMaterial; // ka, kd, ks, shininess
#endif
uniform vec3 uEye;

vec3 phong(vec3 point, vec3 normal) {
    vec3 V = normalize(uEye - point);
    float nv = dot(normal, V);
    vec3 N = nv < 0.0 ? -normal : normal;
    nv = abs(nv);
    vec3 diffuse = vec3(0.0), specular = vec3(0.0);
    for (int k = 0; k < LIGHT_COUNT; ++k) {
        // w = 0: the direction itself; w = 1: towards the point light (normalize is a no-op
        // on the unit direction).
        vec3 L = normalize(uLightVector[k].xyz - uLightVector[k].w * point);
        float ln = dot(L, N);
        // R.V with R = 2 (L.N) N - L, without forming R.
        float rv = max(2.0 * ln * nv - dot(L, V), 0.0);
        float spec = ln > 0.0 ? pow(rv, uMaterial.w) : 0.0;
        diffuse += max(ln, 0.0) * uLightDiffuse[k];
        specular += spec * uLightSpecular[k];
    }
    diffuse += uFill.x + uFill.y * nv;
    return (uMaterial.x * uAmbient + uMaterial.y * diffuse) * uColor + uMaterial.z * specular;
}
