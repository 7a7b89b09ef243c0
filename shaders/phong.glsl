// Phong shading (paper eq. 3.8), two-sided: the normal is turned towards the viewer.
// I = (ka * sum ia + sum kd (L.N) id) * colour + sum ks (R.V)^alpha is, each term clamped at 0.

const int kMaxLights = 8;
uniform int uLightCount;
uniform vec4 uLightVector[kMaxLights];   // xyz: direction towards the light (w = 0) or position (w = 1)
uniform vec3 uLightAmbient[kMaxLights];
uniform vec3 uLightDiffuse[kMaxLights];
uniform vec3 uLightSpecular[kMaxLights];
uniform vec3 uColor;
uniform vec4 uMaterial; // ka, kd, ks, shininess
uniform vec3 uEye;

vec3 phong(vec3 point, vec3 normal) {
    vec3 V = normalize(uEye - point);
    vec3 N = dot(normal, V) < 0.0 ? -normal : normal;
    vec3 ambient = vec3(0.0), diffuse = vec3(0.0), specular = vec3(0.0);
    for (int k = 0; k < uLightCount; ++k) {
        vec3 L = uLightVector[k].w == 0.0 ? uLightVector[k].xyz
                                          : normalize(uLightVector[k].xyz - point);
        float ln = dot(L, N);
        ambient += uLightAmbient[k];
        if (ln > 0.0) {
            diffuse += ln * uLightDiffuse[k];
            vec3 R = 2.0 * ln * N - L;
            specular += pow(max(dot(R, V), 0.0), uMaterial.w) * uLightSpecular[k];
        }
    }
    return (uMaterial.x * ambient + uMaterial.y * diffuse) * uColor + uMaterial.z * specular;
}
