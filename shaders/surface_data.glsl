// The scene's shared per-surface data (kw::GpuScene, kw::ScenePools): one
// table row per surface and pools of control texels and span-table rows, addressed by the
// draw's surface index (surface.vert's aSurface, fed by the draw's base instance), so surfaces
// of one shader variant are drawn by one multi-draw with no per-surface uniforms.
// Defines the per-surface values under the names the per-draw uniforms had (uDomain, uOrigin,
// uColor, uMaterial, uSurfaceId, uTrimRect, uTrimSize, uTrimLayer, uTrimBlock) for the shared
// includes.
#ifndef KW_SURFACE_DATA
#define KW_SURFACE_DATA

// Texture buffers, not SSBOs: llvmpipe (Mesa 22.3) returns 0 from an SSBO load in a helper
// invocation, which broke the screen derivatives (fwidth) of the zebra and isophote bands along
// every triangle edge; texel fetches run in helper invocations too. Units match
// kw::GpuScene::bindSurfaceData.
// The table: KW_TABLE_TEXELS RGBA32F texels per surface (kw::SurfaceTableEntry), read as floats for texels
// 0-5 (domain; origin; colour; ka, kd, ks, shininess; trim rectangle; trim size and layer) and
// through an RGBA32I view for texels 6-7 (control offset, countU, u and v span-table offsets;
// surface id, exact trim grid's first word, closed solid's side).
layout(binding = KW_SURFACE_TABLE_UNIT) uniform samplerBuffer kwSurfaceTable;
layout(binding = KW_SURFACE_INTS_UNIT) uniform isamplerBuffer kwSurfaceInts;
layout(binding = KW_CONTROL_UNIT) uniform samplerBuffer kwControl; // RGBA32F (w (P - origin), w)
layout(binding = KW_SPAN_UNIT) uniform samplerBuffer kwSpans; // RGBA32F span-table rows

// The row of the surface being drawn; each stage's main() sets it first.
int kwSurface = 0;

#define KW_ROW(k) texelFetch(kwSurfaceTable, kwSurface * KW_TABLE_TEXELS + (k))
#define KW_DATA texelFetch(kwSurfaceInts, kwSurface * KW_TABLE_TEXELS + KW_TABLE_DATA_TEXEL)
#define uDomain KW_ROW(KW_TABLE_DOMAIN_TEXEL)
#define uOrigin (KW_ROW(KW_TABLE_ORIGIN_TEXEL).xyz)
#define uColor (KW_ROW(KW_TABLE_COLOUR_TEXEL).rgb)
#define uMaterial KW_ROW(KW_TABLE_MATERIAL_TEXEL)
#define uSurfaceId float(texelFetch(kwSurfaceInts, kwSurface * KW_TABLE_TEXELS + KW_TABLE_IDS_TEXEL).x)
#define uTrimRect KW_ROW(KW_TABLE_TRIM_RECT_TEXEL)
#define uTrimSize (KW_ROW(KW_TABLE_TRIM_SIZE_TEXEL).xy)
#define uTrimLayer (KW_ROW(KW_TABLE_TRIM_SIZE_TEXEL).z)
#define uTrimBlock uint(texelFetch(kwSurfaceInts, kwSurface * KW_TABLE_TEXELS + KW_TABLE_IDS_TEXEL).y)
// 1: a face of a closed solid whose outside is along S_u x S_v, -1: against it, 0: no solid.
#define uSolidSide texelFetch(kwSurfaceInts, kwSurface * KW_TABLE_TEXELS + KW_TABLE_IDS_TEXEL).z

// Control texel (i, j) and texel x of span-table row `row` of the current surface.
#define KW_CONTROL(ij) texelFetch(kwControl, KW_DATA.x + (ij).y * KW_DATA.y + (ij).x)
#define KW_SPAN_U(x, row) texelFetch(kwSpans, KW_DATA.z + (row) * KW_SPAN_TEXELS_U + (x))
#define KW_SPAN_V(x, row) texelFetch(kwSpans, KW_DATA.w + (row) * KW_SPAN_TEXELS_V + (x))

#ifdef KW_GBUFFER
// The deferred exact pass's input, as the pre-pass writes it (exact_surface.frag's
// kwReadPrepass reads it back): the polygon's (u, v), the surface's row with the facing bit,
// and the cell's provoking vertex.
uvec4 kwPrepassWords(vec2 uv, int surface, bool front, int vertex) {
    return uvec4(floatBitsToUint(uv), uint(surface) | (front ? 0x80000000u : 0u), uint(vertex));
}
#endif

#endif // KW_SURFACE_DATA
