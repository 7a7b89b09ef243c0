// Per-cell data passed flat from the provoking vertex in KW_CELL_GATHER variants: the cell's
// (p+1)(q+1) control texels and its two span-table rows, fetched once per vertex instead of
// once per fragment (on llvmpipe a texelFetch is a per-lane gather even when all lanes read
// the same texel; a flat input is a broadcast). KW_CELL_IO is "flat out" in the vertex stage
// and "flat in" in the fragment stage. The renderer picks this variant only when the data
// fits the 32 varying vectors (kw::ExactSurfacePass::variantDefines).
#define KW_CTRL_COUNT ((DEGREE_U + 1) * (DEGREE_V + 1))
KW_CELL_IO vec4 vCellControl[KW_CTRL_COUNT];
KW_CELL_IO vec4 vCellSpanU[KW_SPAN_TEXELS_U];
KW_CELL_IO vec4 vCellSpanV[KW_SPAN_TEXELS_V];
