// Surface analysis options (curvature colour maps, zebra, isophotes, environment, draft,
// isocurves), their shader defines, the colour scale shared by the shader and the legend, and
// the automatic colour range from the CPU kernel. No GL here (the uniforms are set in
// render/analysis_uniforms.cpp).
#pragma once

#include "model/document/scene.h"
#include "model/nurbs/nurbs_curvature.h"

#include <QString>
#include <QStringList>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

namespace kw {

/// What the exact pass shows. The numeric values are the shader's KW_ANALYSIS (analysis.glsl).
/// Each mode has a row in analysis.cpp's table, in this order: its names, its parameters and
/// its default scale. A new mode is a value here, its row and its colour in analysis.glsl.
enum class AnalysisMode {
    Phong = 0,        ///< plain shading (paper eq. 3.8)
    Gaussian = 1,     ///< K, colour map
    Mean = 2,         ///< H, colour map
    MaxCurvature = 3, ///< max(|k1|, |k2|), colour map
    MinRadius = 4,    ///< 1 / max(|k1|, |k2|), colour map (a plane: the scale's top)
    Zebra = 5,        ///< reflected parallel stripes
    Isophotes = 6,    ///< bands of N.L
    Environment = 7,  ///< reflection of an equirectangular environment image
    Draft = 8,        ///< draft angle against a pull direction, three colours
};

/// The parameters of AnalysisOptions that a mode's shader reads; setAnalysisUniforms
/// (render/analysis_gl.cpp) sets them by this group, so a mode that reads an existing group
/// needs no GL code.
enum class AnalysisParameters {
    None,        ///< Phong: nothing
    ColourMap,   ///< the colour range and scale: the mode is a colour map (ramp, legend)
    Stripes,     ///< zebra: the stripe count and axis
    Isophotes,   ///< the band count and the light's direction
    Environment, ///< the environment image's unit
    Draft,       ///< the pull direction and the draft angle
};

/// How a colour-map value maps to the colour scale.
enum class ColourScale {
    Linear = 0,    ///< low .. high
    Symmetric = 1, ///< -m .. m with m = max(|low|, |high|): zero in the middle
    Log = 2,       ///< signed log: linear within 1e-3 m of zero, logarithmic beyond
};

struct ValueRange {
    double low = 0.0;
    double high = 1.0;
    bool operator==(const ValueRange&) const = default;
};

/// Options of the analysis modes. Defaults are what `knotwork render --shading MODE` uses.
struct AnalysisOptions {
    AnalysisMode mode = AnalysisMode::Phong;
    bool isocurves = false; ///< knot and iso-parameter lines over any mode
    /// Colour maps: a user range, or none for the automatic one (percentiles, see autoRange).
    std::optional<ValueRange> range;
    /// Colour maps: the scale, or none for the mode's default (defaultScale).
    std::optional<ColourScale> scale;
    /// Zebra: stripe pairs per 180 degrees of reflection, drawn to the nearest 0.5 (the tubes
    /// must close around the axis).
    double stripeCount = 8.0;
    double stripeAngleDegrees = 90; ///< zebra: stripe direction in the view plane (90: vertical)
    double isophoteCount = 10.0;    ///< isophotes: bands across N.L in [-1, 1]
    glm::dvec3 pullDirection{0.0, 0.0, 1.0}; ///< draft: world direction (normalised when used)
    double draftAngleDegrees = 3.0;          ///< draft: threshold
    glm::ivec2 isoCount{8, 8};               ///< isocurves: lines per direction, i / (n + 1)
    double isoWidthPixels = 1.5;             ///< isocurves: line width
    /// Short line marks of the principal directions (k1 dark red, k2 dark blue) on a screen
    /// grid, over any mode (KW_DIRECTIONS; needs the second derivatives).
    bool principalDirections = false;
    double directionSpacingPixels = 24.0; ///< principal directions: grid spacing
    /// Environment: an image file read through OpenImageIO (equirectangular, z up; EXR, HDR,
    /// PNG, JPEG, ...); empty for the default (share/knotwork/environment/studio.png, made
    /// by tools/make_environment.py).
    QString environmentMap;
    /// Keep the last automatic range instead of recomputing it (the editor sets it during
    /// drags so the colours do not swim; the range follows again on release).
    bool holdRange = false;

    bool operator==(const AnalysisOptions&) const = default;
};

/// "phong", "gaussian", "mean", "max-curvature", "min-radius", "zebra", "isophotes",
/// "environment", "draft".
QString analysisModeName(AnalysisMode mode);
/// Every mode's name (analysisModeName) in menu order, for help texts and messages.
QStringList analysisModeNames();
/// The GLSL name of the mode's number (KW_ANALYSIS_ and its name in capitals, '-' as '_':
/// KW_ANALYSIS_MAX_CURVATURE), which the shader preamble defines (ShaderLibrary::preamble).
QString analysisModeDefine(AnalysisMode mode);
/// Every mode, in menu order.
std::vector<AnalysisMode> analysisModes();
/// The mode named `name` (analysisModeName), or nullopt.
std::optional<AnalysisMode> parseAnalysisMode(const QString& name);
/// Menu text, e.g. "Gaussian curvature".
QString analysisModeTitle(AnalysisMode mode);

/// The parameters the mode's shader reads (its row).
AnalysisParameters analysisParameters(AnalysisMode mode);
/// A mode whose parameters are AnalysisParameters::ColourMap.
bool isColourMap(AnalysisMode mode);
/// Colour maps and the curvature AOV need second derivatives (KW_SECOND_ORDER).
bool needsCurvature(AnalysisMode mode);
/// The mode's row's scale: Symmetric for the signed quantities (K, H), Linear otherwise.
ColourScale defaultScale(AnalysisMode mode);
QString colourScaleName(ColourScale scale); ///< "linear", "symmetric", "log"
std::optional<ColourScale> parseColourScale(const QString& name);

/// The colour scale's stops, low to high (a blue-cyan-green-yellow-red rainbow, as CAD
/// curvature maps use); the shader gets them as KW_RAMP through analysisDefines.
const std::vector<glm::vec3>& colourRamp();
/// Draft's three colours, before the headlight's shading: draft of at least the angle along
/// the pull direction, less than the angle either way (insufficient), and at least the angle
/// against it (an undercut). The shader gets them as KW_DRAFT_* through analysisDefines, and
/// the editor's legend shows the same.
struct DraftColours {
    glm::vec3 draft, insufficient, undercut;
};
const DraftColours& draftColours();

/// Position t in [0, 1] of value x on the scale (analysis.glsl's scalePosition).
double colourScalePosition(double x, const ValueRange& range, ColourScale scale);
/// The value at position t (the inverse of colourScalePosition, for legend labels).
double colourScaleValue(double t, const ValueRange& range, ColourScale scale);
/// The ramp's colour at t in [0, 1] (analysis.glsl's rampColour).
glm::vec3 rampColour(double t);

/// Shader defines for the exact pass: KW_ANALYSIS, KW_ISOCURVES, KW_SECOND_ORDER, KW_RAMP,
/// KW_AOV_CURVATURE (the K, H, k1, k2 target at kAovCurvatureOutput).
QStringList analysisDefines(const AnalysisOptions& options, bool curvatureAov);

/// The value a colour map shows at a kernel curvature sample.
double analysisValue(AnalysisMode mode, const SurfaceCurvature& c);

/// Automatic colour range of a colour-map mode: the lowPercentile and highPercentile (0..1)
/// of the mode's value over the surfaces shown, weighted by area, from a samples x samples
/// grid per surface (each sample weighs its cell's area |Su x Sv| du dv), in double precision
/// with kw::surfaceCurvature (trimmed-away samples count too: the mask is a GPU-side raster).
/// Area-weighted percentiles, not extremes nor sample counts, so small sharp regions (fillets,
/// a rim, a knob) saturate at the scale's ends instead of washing out the large faces; 10th
/// to 90th: the teapot's body shows 5 of 10 legend bands of mean curvature.
/// Empty scene or non-colour-map mode: {0, 1}. A range narrower than 10% of its middle's
/// magnitude is widened to +-5% of it (at least +-1e-12), so a constant quantity shows one
/// colour instead of its rounding noise.
ValueRange autoRange(const Scene& scene, AnalysisMode mode, int samples = 16,
                     double lowPercentile = 0.10, double highPercentile = 0.90);

} // namespace kw
