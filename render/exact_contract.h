// The constants C++ and the shaders share, declared once. ShaderLibrary writes every one of
// them into each program as a #define (shaderPreamble), so no GLSL file repeats a literal.
#pragma once

#include "model/scene.h"
#include "render/analysis.h"

#include <array>
#include <cstddef>

namespace kw {

/// Texture units and buffer bindings. The GLSL name of each is in kShaderConstants.
/// The analysis-free passes' own units (their programs bind nothing else):
constexpr int kCompositeColourUnit = 0;  ///< aa_composite.frag: the multisampled colour
constexpr int kCompositeAccumUnit = 1;   ///< aa_composite.frag: the edge pass's accumulation
constexpr int kCompositeDepthUnit = 2;   ///< aa_composite.frag: the multisampled depth
constexpr int kAccumulateSampleUnit = 0; ///< accumulate_add.frag / accumulate_resolve.frag
constexpr int kAccumulateDepthUnit = 1;  ///< accumulate_resolve.frag
/// The exact pass's:
constexpr int kTrimMaskUnit = 3;      ///< trim_sample.glsl's uTrimMask (TrimMaskPass::bindArray)
constexpr int kEnvironmentUnit = 4;   ///< analysis.glsl's uEnvironment
constexpr int kSurfaceTableUnit = 5;  ///< surface_data.glsl kwSurfaceTable (RGBA32F rows)
constexpr int kSurfaceIntsUnit = 6;   ///< the same rows as RGBA32I (kwSurfaceInts)
constexpr int kControlUnit = 7;       ///< the control texel pool (kwControl)
constexpr int kSpanUnit = 8;          ///< the span-table pool (kwSpans)
constexpr int kTrimGridUnit = 9;      ///< trim_exact.glsl kwTrimGrid (R32UI words)
constexpr int kTrimGridQuadUnit = 10; ///< the same words 4 at a time (kwTrimQuads)
constexpr int kPrepassUnit = 11;      ///< the deferred pass's input (exact_surface.frag kwPrepass)
constexpr int kVertexStorageBinding = 1; ///< the deferred pass's vertex pool (KwVertices SSBO)
/// GpuScene's four surface-data views, bound in this order from kSurfaceTableUnit.
constexpr int kSurfaceDataViews = 4;
static_assert(kSurfaceIntsUnit == kSurfaceTableUnit + 1 && kControlUnit == kSurfaceTableUnit + 2 &&
              kSpanUnit == kSurfaceTableUnit + 3);

/// Texel layouts. The surface table: RGBA texels per surface row (kw::SurfaceTableEntry), and
/// the integer texels among them (read through the RGBA32I view).
constexpr int kSurfaceTableTexels = 8;
constexpr int kSurfaceTableDomainTexel = 0;   ///< u first, u last, v first, v last
constexpr int kSurfaceTableOriginTexel = 1;   ///< the control texels' origin
constexpr int kSurfaceTableColourTexel = 2;   ///< material colour
constexpr int kSurfaceTableMaterialTexel = 3; ///< ka, kd, ks, shininess
constexpr int kSurfaceTableTrimRectTexel = 4; ///< the trims' (u, v) rectangle
constexpr int kSurfaceTableTrimSizeTexel = 5; ///< the trims' size and layer
constexpr int kSurfaceTableDataTexel = 6;     ///< control offset, countU, span-table offsets
constexpr int kSurfaceTableIdsTexel = 7;      ///< surface id, exact trim grid's first word
/// kw::BaseVertex as 32-bit words (the deferred pass reads the pool as words): its size and
/// where its knot span and span scale start.
constexpr int kBaseVertexWords = 8;
constexpr int kBaseVertexSpanWord = 5;
constexpr int kBaseVertexSpanScaleWord = 7;

/// A constant as the shaders see it.
struct ShaderConstant {
    const char* name;
    int value;
};

/// Every constant above that a shader reads, and the light count and analysis modes, under
/// their GLSL names. The span-table width depends on the degree, so it is a per-variant
/// define (ExactSurfacePass::degreeDefines: KW_SPAN_TEXELS_U/V from kw::spanTableTexels).
inline constexpr std::array kShaderConstants{
    ShaderConstant{"KW_MAX_LIGHTS", kMaxLights},
    ShaderConstant{"KW_COMPOSITE_COLOUR_UNIT", kCompositeColourUnit},
    ShaderConstant{"KW_COMPOSITE_ACCUM_UNIT", kCompositeAccumUnit},
    ShaderConstant{"KW_COMPOSITE_DEPTH_UNIT", kCompositeDepthUnit},
    ShaderConstant{"KW_ACCUMULATE_SAMPLE_UNIT", kAccumulateSampleUnit},
    ShaderConstant{"KW_ACCUMULATE_DEPTH_UNIT", kAccumulateDepthUnit},
    ShaderConstant{"KW_TRIM_MASK_UNIT", kTrimMaskUnit},
    ShaderConstant{"KW_ENVIRONMENT_UNIT", kEnvironmentUnit},
    ShaderConstant{"KW_SURFACE_TABLE_UNIT", kSurfaceTableUnit},
    ShaderConstant{"KW_SURFACE_INTS_UNIT", kSurfaceIntsUnit},
    ShaderConstant{"KW_CONTROL_UNIT", kControlUnit},
    ShaderConstant{"KW_SPAN_UNIT", kSpanUnit},
    ShaderConstant{"KW_TRIM_GRID_UNIT", kTrimGridUnit},
    ShaderConstant{"KW_TRIM_QUAD_UNIT", kTrimGridQuadUnit},
    ShaderConstant{"KW_PREPASS_UNIT", kPrepassUnit},
    ShaderConstant{"KW_VERTEX_STORAGE_BINDING", kVertexStorageBinding},
    ShaderConstant{"KW_TABLE_TEXELS", kSurfaceTableTexels},
    ShaderConstant{"KW_TABLE_DOMAIN_TEXEL", kSurfaceTableDomainTexel},
    ShaderConstant{"KW_TABLE_ORIGIN_TEXEL", kSurfaceTableOriginTexel},
    ShaderConstant{"KW_TABLE_COLOUR_TEXEL", kSurfaceTableColourTexel},
    ShaderConstant{"KW_TABLE_MATERIAL_TEXEL", kSurfaceTableMaterialTexel},
    ShaderConstant{"KW_TABLE_TRIM_RECT_TEXEL", kSurfaceTableTrimRectTexel},
    ShaderConstant{"KW_TABLE_TRIM_SIZE_TEXEL", kSurfaceTableTrimSizeTexel},
    ShaderConstant{"KW_TABLE_DATA_TEXEL", kSurfaceTableDataTexel},
    ShaderConstant{"KW_TABLE_IDS_TEXEL", kSurfaceTableIdsTexel},
    ShaderConstant{"KW_VERTEX_WORDS", kBaseVertexWords},
    ShaderConstant{"KW_VERTEX_SPAN_WORD", kBaseVertexSpanWord},
    ShaderConstant{"KW_VERTEX_SPAN_SCALE_WORD", kBaseVertexSpanScaleWord},
    ShaderConstant{"KW_ANALYSIS_PHONG", int(AnalysisMode::Phong)},
    ShaderConstant{"KW_ANALYSIS_GAUSSIAN", int(AnalysisMode::Gaussian)},
    ShaderConstant{"KW_ANALYSIS_MEAN", int(AnalysisMode::Mean)},
    ShaderConstant{"KW_ANALYSIS_MAX_CURVATURE", int(AnalysisMode::MaxCurvature)},
    ShaderConstant{"KW_ANALYSIS_MIN_RADIUS", int(AnalysisMode::MinRadius)},
    ShaderConstant{"KW_ANALYSIS_ZEBRA", int(AnalysisMode::Zebra)},
    ShaderConstant{"KW_ANALYSIS_ISOPHOTES", int(AnalysisMode::Isophotes)},
    ShaderConstant{"KW_ANALYSIS_ENVIRONMENT", int(AnalysisMode::Environment)},
    ShaderConstant{"KW_ANALYSIS_DRAFT", int(AnalysisMode::Draft)},
    ShaderConstant{"KW_SCALE_LINEAR", int(ColourScale::Linear)},
    ShaderConstant{"KW_SCALE_SYMMETRIC", int(ColourScale::Symmetric)},
    ShaderConstant{"KW_SCALE_LOG", int(ColourScale::Log)},
};

} // namespace kw
