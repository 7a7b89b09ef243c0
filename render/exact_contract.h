// The exact pass's contract with its shaders, declared once: the constants C++ and GLSL share
// (ShaderLibrary writes each into every program as a #define, so no GLSL file repeats a
// literal) and the program variant as a typed bit set with one GLSL define per bit.
#pragma once

#include "model/document/scene.h"
#include "render/analysis.h"

#include <QFlags>
#include <QStringList>
#include <array>
#include <cstddef>
#include <cstdint>

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
/// The deferred pass's vertex pool as RGBA32UI texels (exact_surface.frag kwVertexPool): a
/// texture buffer, not a storage buffer, as the surface data (surface_data.glsl).
constexpr int kVertexPoolUnit = 12;
/// The analytic forms' rows (analytic.glsl kwAnalytic, RGBA32F texels; kw::AnalyticTable),
/// read only by the KW_ANALYTIC programs.
constexpr int kAnalyticUnit = 13;
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
/// The analytic table: RGBA texels per surface row (kw::AnalyticEntry), by the same slot as the
/// surface table.
constexpr int kAnalyticTexels = 6;
/// kw::BaseVertex as 32-bit words (the deferred pass reads the pool as words): its size and
/// where its knot span and span scale start.
constexpr int kBaseVertexWords = 8;
constexpr int kBaseVertexSpanWord = 5;
constexpr int kBaseVertexSpanScaleWord = 7;

/// Vertex attribute locations: the `in`s of the vertex shaders and the vertex arrays that feed
/// them. Every layout has its position at kAttrPosition, so lines.vert draws the base polygon's
/// outline (kw::BaseVertex) and the control net (plain points) alike.
constexpr int kAttrPosition = 0;
/// surface.vert: kw::BaseVertex (render/gpu_layout.h) from binding 0, the table row per instance
/// from binding 1, and SkirtVertex's outward (u, v) direction (the skirts and fins only).
constexpr int kAttrUv = 1;
constexpr int kAttrSpan = 2;
constexpr int kAttrSpanScale = 3;
constexpr int kAttrSurface = 4;
constexpr int kAttrOutward = 5;
/// tessellated.vert: the tessellated meshes' normal and (u, v), one buffer per attribute.
constexpr int kAttrMeshNormal = 1;
constexpr int kAttrMeshUv = 2;
/// edge_bands.vert: kw::EdgeBandVertex's colour.
constexpr int kAttrBandColour = 1;
/// trim_mask.vert: a trim loop's vertex in the unit square of the surface's domain.
constexpr int kAttrTrimCorner = 0;

/// Fragment output locations. A location is the draw-buffer index the output writes (its place
/// in glNamedFramebufferDrawBuffers' list, glClearBuffer's drawbuffer); a frame with AOVs
/// attaches each target at GL_COLOR_ATTACHMENT0 + its output, so outputs and attachments agree.
constexpr int kColourOutput = 0;       ///< every colour-writing shader's fragColor
constexpr int kAovIdUvDepthOutput = 1; ///< surface id, u, v, eye-space depth
constexpr int kAovPositionOutput = 2;  ///< the exact point, w = 1
constexpr int kAovNormalOutput = 3;    ///< the unit normal, w = 0
constexpr int kAovCurvatureOutput = 4; ///< K, H, k1, k2 (the curvature AOV only)
constexpr int kAovDirectionOutput = 5; ///< the principal direction of k1 (the curvature AOV only)
/// The draw buffers of a frame with AOVs: colour and the three AOVs, then the curvature's two.
constexpr int kAovDrawBuffers = kAovNormalOutput + 1;
constexpr int kCurvatureAovDrawBuffers = kAovDirectionOutput + 1;
/// The deferred pass's pre-pass writes one target, its only draw buffer
/// (ExactSurfacePass::attachPrepassTexture): depth_only.frag, exact_surface.frag's KW_GBUFFER.
constexpr int kPrepassOutput = 0;
/// trim_mask.frag: the mask layer, the trim framebuffer's only colour attachment.
constexpr int kTrimMaskOutput = 0;

/// The AOV id of a section cap's pixels (surface ids are positive, the background -1).
constexpr int kSectionCapId = -2;

/// A constant as the shaders see it.
struct ShaderConstant {
    const char* name;
    int value;
};

/// Every constant above that a shader reads (units, layouts, attribute and output locations),
/// the light count and the colour scales, under their GLSL names. The span-table width depends
/// on the degree, so it is a per-variant define (ExactVariant::defines: KW_SPAN_TEXELS_U/V from
/// kw::spanTableTexels). The analysis modes' numbers come from their table
/// (kw::analysisModeDefine), so a new mode adds no line.
inline constexpr std::array kShaderConstants{
    ShaderConstant{"KW_MAX_LIGHTS", kMaxLights},
    ShaderConstant{"KW_MAX_SECTIONS", kMaxSectionPlanes},
    ShaderConstant{"KW_SECTION_CAP_ID", kSectionCapId},
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
    ShaderConstant{"KW_VERTEX_POOL_UNIT", kVertexPoolUnit},
    ShaderConstant{"KW_ANALYTIC_UNIT", kAnalyticUnit},
    ShaderConstant{"KW_ANALYTIC_TEXELS", kAnalyticTexels},
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
    ShaderConstant{"KW_ATTR_POSITION", kAttrPosition},
    ShaderConstant{"KW_ATTR_UV", kAttrUv},
    ShaderConstant{"KW_ATTR_SPAN", kAttrSpan},
    ShaderConstant{"KW_ATTR_SPAN_SCALE", kAttrSpanScale},
    ShaderConstant{"KW_ATTR_SURFACE", kAttrSurface},
    ShaderConstant{"KW_ATTR_OUTWARD", kAttrOutward},
    ShaderConstant{"KW_ATTR_MESH_NORMAL", kAttrMeshNormal},
    ShaderConstant{"KW_ATTR_MESH_UV", kAttrMeshUv},
    ShaderConstant{"KW_ATTR_BAND_COLOUR", kAttrBandColour},
    ShaderConstant{"KW_ATTR_TRIM_CORNER", kAttrTrimCorner},
    ShaderConstant{"KW_COLOUR_OUTPUT", kColourOutput},
    ShaderConstant{"KW_AOV_ID_UV_DEPTH_OUTPUT", kAovIdUvDepthOutput},
    ShaderConstant{"KW_AOV_POSITION_OUTPUT", kAovPositionOutput},
    ShaderConstant{"KW_AOV_NORMAL_OUTPUT", kAovNormalOutput},
    ShaderConstant{"KW_AOV_CURVATURE_OUTPUT", kAovCurvatureOutput},
    ShaderConstant{"KW_AOV_DIRECTION_OUTPUT", kAovDirectionOutput},
    ShaderConstant{"KW_PREPASS_OUTPUT", kPrepassOutput},
    ShaderConstant{"KW_TRIM_MASK_OUTPUT", kTrimMaskOutput},
    ShaderConstant{"KW_FORM_PLANE", int(AnalyticForm::Kind::Plane)},
    ShaderConstant{"KW_FORM_CYLINDER", int(AnalyticForm::Kind::Cylinder)},
    ShaderConstant{"KW_FORM_CONE", int(AnalyticForm::Kind::Cone)},
    ShaderConstant{"KW_FORM_SPHERE", int(AnalyticForm::Kind::Sphere)},
    ShaderConstant{"KW_FORM_TORUS", int(AnalyticForm::Kind::Torus)},
    ShaderConstant{"KW_SCALE_LINEAR", int(ColourScale::Linear)},
    ShaderConstant{"KW_SCALE_SYMMETRIC", int(ColourScale::Symmetric)},
    ShaderConstant{"KW_SCALE_LOG", int(ColourScale::Log)},
};

/// One feature of an exact-pass program: a bit of ExactFeatures and one #define of
/// exact_surface.frag (and of depth_only.frag for the trim and output bits), named in
/// kExactFeatureDefines. The shaders' header comments say what each does.
enum class ExactFeature : std::uint32_t {
    Aov = 1u << 0,           ///< KW_AOV: write the AOV targets
    CellGather = 1u << 1,    ///< KW_CELL_GATHER: per-cell data as flat inputs (cell_data.glsl)
    RayNewton = 1u << 2,     ///< KW_RAY_NEWTON: adaptive partitions, the point under the pixel
    ExactDepth = 1u << 3,    ///< KW_EXACT_DEPTH: one pass writing gl_FragDepth, no pre-pass
    Skirt = 1u << 4,         ///< KW_SKIRT: the edge skirts' program
    Trim = 1u << 5,          ///< KW_TRIM: discard trimmed fragments
    TrimExact = 1u << 6,     ///< KW_TRIM_EXACT: by the exact trim grid instead of the mask
    TrimAa = 1u << 7,        ///< KW_TRIM_AA: keep only wholly covered fragments
    TrimEdge = 1u << 8,      ///< KW_TRIM_EDGE: the anti-aliased frame's edge pass
    DepthOnly = 1u << 9,     ///< KW_DEPTH_ONLY: the pre-pass at the point under the pixel
    GBuffer = 1u << 10,      ///< KW_GBUFFER: the pre-pass writes the deferred pass's input
    Deferred = 1u << 11,     ///< KW_DEFERRED: the deferred pass, one triangle per route
    Isocurves = 1u << 12,    ///< KW_ISOCURVES: knot and iso-parameter lines
    Directions = 1u << 13,   ///< KW_DIRECTIONS: principal-direction marks
    SecondOrder = 1u << 14,  ///< KW_SECOND_ORDER: second derivatives and curvature
    AovCurvature = 1u << 15, ///< KW_AOV_CURVATURE: the curvature AOV targets
    Section = 1u << 16,      ///< KW_SECTION: section planes cut at the exact point, caps
    BackFill = 1u << 17,     ///< KW_BACK_FILL: a solid's skipped side, where nothing covered
    /// KW_ANALYTIC (with KW_RAY_NEWTON): the point under the pixel from the face's analytic
    /// form in closed form (analytic.glsl), instead of the Newton step onto the NURBS
    Analytic = 1u << 18,
    /// KW_COVER (with KW_ANALYTIC and KW_EXACT_DEPTH): a closed-form face drawn by its cover's
    /// boxes (SurfaceGpu::cover): the ray's first meeting with the face in its domain, beyond
    /// the near plane and not trimmed away, or the fragment is discarded
    Cover = 1u << 19,
};
using ExactFeatures = QFlags<ExactFeature>;

struct ExactFeatureDefine {
    ExactFeature feature;
    const char* define;
};
/// Each feature's GLSL define, in the order programs list them.
inline constexpr std::array kExactFeatureDefines{
    ExactFeatureDefine{ExactFeature::CellGather, "KW_CELL_GATHER"},
    ExactFeatureDefine{ExactFeature::Aov, "KW_AOV"},
    ExactFeatureDefine{ExactFeature::Skirt, "KW_SKIRT"},
    ExactFeatureDefine{ExactFeature::ExactDepth, "KW_EXACT_DEPTH"},
    ExactFeatureDefine{ExactFeature::RayNewton, "KW_RAY_NEWTON"},
    ExactFeatureDefine{ExactFeature::DepthOnly, "KW_DEPTH_ONLY"},
    ExactFeatureDefine{ExactFeature::Trim, "KW_TRIM"},
    ExactFeatureDefine{ExactFeature::TrimExact, "KW_TRIM_EXACT"},
    ExactFeatureDefine{ExactFeature::TrimAa, "KW_TRIM_AA"},
    ExactFeatureDefine{ExactFeature::TrimEdge, "KW_TRIM_EDGE"},
    ExactFeatureDefine{ExactFeature::GBuffer, "KW_GBUFFER"},
    ExactFeatureDefine{ExactFeature::Deferred, "KW_DEFERRED"},
    ExactFeatureDefine{ExactFeature::Isocurves, "KW_ISOCURVES"},
    ExactFeatureDefine{ExactFeature::Directions, "KW_DIRECTIONS"},
    ExactFeatureDefine{ExactFeature::SecondOrder, "KW_SECOND_ORDER"},
    ExactFeatureDefine{ExactFeature::AovCurvature, "KW_AOV_CURVATURE"},
    ExactFeatureDefine{ExactFeature::Section, "KW_SECTION"},
    ExactFeatureDefine{ExactFeature::BackFill, "KW_BACK_FILL"},
    ExactFeatureDefine{ExactFeature::Analytic, "KW_ANALYTIC"},
    ExactFeatureDefine{ExactFeature::Cover, "KW_COVER"},
};

/// The defines of `features`, one per bit, in kExactFeatureDefines' order.
QStringList featureDefines(ExactFeatures features);
/// The analysis bits a frame with `options` needs (curvatureAov: the curvature AOV targets).
ExactFeatures analysisFeatures(const AnalysisOptions& options, bool curvatureAov);

/// One program of exact_surface.frag: what it is specialised for, turned into its defines in
/// one place (defines()). degreeU == 0: a program without a surface's degrees (the pre-pass's
/// depth_only.frag), whose defines are only the features'.
struct ExactVariant {
    int degreeU = 0, degreeV = 0; ///< 1..15 (DEGREE_U, DEGREE_V)
    int lightCount = 1;           ///< LIGHT_COUNT, 1..kMaxLights
    AnalysisMode analysis = AnalysisMode::Phong;
    ExactFeatures features;
    bool operator==(const ExactVariant&) const = default;
    /// DEGREE_U/V, the span-table widths KW_SPAN_TEXELS_U/V (kw::spanTableTexels) and
    /// LIGHT_COUNT (with degrees), then one define per feature, then KW_ANALYSIS and, for a
    /// colour map, its ramp (KW_RAMP_STOPS, KW_RAMP).
    QStringList defines() const;
};

// In the namespace, so that argument-dependent lookup finds the operators.
Q_DECLARE_OPERATORS_FOR_FLAGS(ExactFeatures)

} // namespace kw
