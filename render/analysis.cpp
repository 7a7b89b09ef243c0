// Analysis mode names, the colour scale (shared by the shader and the legend), shader defines
// and the automatic colour range from kernel curvature samples.
#include "render/analysis.h"

#include "render/exact_contract.h"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace kw {

namespace {
/// A mode's row: everything C++ knows of it besides a colour map's value (analysisValue). Its
/// name gives the `--shading` parser, the View › Analysis menu and the toolbar list
/// (analysisModes) and the shaders' define of its number (analysisModeDefine); its parameters
/// say which uniforms setAnalysisUniforms sets and whether it is a colour map.
struct ModeInfo {
    AnalysisMode mode;
    const char* name;
    const char* title;
    AnalysisParameters parameters;
    ColourScale scale; ///< a colour map's default scale
};
using P = AnalysisParameters;
constexpr ModeInfo kModes[] = {
    {AnalysisMode::Phong, "phong", "Shaded (Phong)", P::None, ColourScale::Linear},
    {AnalysisMode::Gaussian, "gaussian", "Gaussian curvature", P::ColourMap,
     ColourScale::Symmetric},
    {AnalysisMode::Mean, "mean", "Mean curvature", P::ColourMap, ColourScale::Symmetric},
    {AnalysisMode::MaxCurvature, "max-curvature", "Maximum curvature |k|", P::ColourMap,
     ColourScale::Linear},
    {AnalysisMode::MinRadius, "min-radius", "Minimum radius", P::ColourMap, ColourScale::Linear},
    {AnalysisMode::Zebra, "zebra", "Zebra stripes", P::Stripes, ColourScale::Linear},
    {AnalysisMode::Isophotes, "isophotes", "Isophotes", P::Isophotes, ColourScale::Linear},
    {AnalysisMode::Environment, "environment", "Environment map", P::Environment,
     ColourScale::Linear},
    {AnalysisMode::Draft, "draft", "Draft angle", P::Draft, ColourScale::Linear},
};

/// Row k is mode k: a mode's row is found by its number, and a row out of order or a gap
/// does not compile. (A mode with no row at the end is unnamed: no parser, menu or shader
/// define knows it, and tst_render_contract finds its GLSL name undeclared.)
constexpr bool rowsInModeOrder() {
    for (size_t k = 0; k < std::size(kModes); ++k)
        if (int(kModes[k].mode) != int(k))
            return false;
    return true;
}
static_assert(rowsInModeOrder(), "kModes: one row per AnalysisMode, in its order");

const ModeInfo& row(AnalysisMode mode) {
    const auto k = size_t(mode);
    return k < std::size(kModes) ? kModes[k] : kModes[0];
}

/// Signed-log scale: linear within kLogLinearFraction * m of zero.
constexpr double kLogLinearFraction = 1e-3;

double maxAbs(const ValueRange& r) {
    return std::max({std::abs(r.low), std::abs(r.high), 1e-30});
}
} // namespace

QString analysisModeName(AnalysisMode mode) {
    return QString::fromLatin1(row(mode).name);
}

QStringList analysisModeNames() {
    QStringList out;
    for (const ModeInfo& m : kModes)
        out << QString::fromLatin1(m.name);
    return out;
}

QString analysisModeTitle(AnalysisMode mode) {
    return QString::fromLatin1(row(mode).title);
}

QString analysisModeDefine(AnalysisMode mode) {
    return QStringLiteral("KW_ANALYSIS_") +
           analysisModeName(mode).toUpper().replace(QLatin1Char('-'), QLatin1Char('_'));
}

std::vector<AnalysisMode> analysisModes() {
    std::vector<AnalysisMode> out;
    for (const ModeInfo& m : kModes)
        out.push_back(m.mode);
    return out;
}

std::optional<AnalysisMode> parseAnalysisMode(const QString& name) {
    for (const ModeInfo& m : kModes)
        if (name == QLatin1String(m.name))
            return m.mode;
    return std::nullopt;
}

AnalysisParameters analysisParameters(AnalysisMode mode) {
    return row(mode).parameters;
}

bool isColourMap(AnalysisMode mode) {
    return analysisParameters(mode) == AnalysisParameters::ColourMap;
}

bool needsCurvature(AnalysisMode mode) {
    return isColourMap(mode);
}

ColourScale defaultScale(AnalysisMode mode) {
    return row(mode).scale;
}

QString colourScaleName(ColourScale scale) {
    switch (scale) {
    case ColourScale::Symmetric:
        return QStringLiteral("symmetric");
    case ColourScale::Log:
        return QStringLiteral("log");
    case ColourScale::Linear:
        break;
    }
    return QStringLiteral("linear");
}

std::optional<ColourScale> parseColourScale(const QString& name) {
    for (ColourScale s : {ColourScale::Linear, ColourScale::Symmetric, ColourScale::Log})
        if (name == colourScaleName(s))
            return s;
    return std::nullopt;
}

const std::vector<glm::vec3>& colourRamp() {
    static const std::vector<glm::vec3> ramp = {{0.10f, 0.20f, 0.85f},
                                                {0.10f, 0.65f, 0.95f},
                                                {0.15f, 0.80f, 0.35f},
                                                {0.95f, 0.90f, 0.20f},
                                                {0.90f, 0.20f, 0.12f}};
    return ramp;
}

const DraftColours& draftColours() {
    static const DraftColours colours{
        {0.15f, 0.75f, 0.25f}, {0.95f, 0.85f, 0.20f}, {0.85f, 0.20f, 0.15f}};
    return colours;
}

double colourScalePosition(double x, const ValueRange& range, ColourScale scale) {
    double t = 0.0;
    if (scale == ColourScale::Symmetric) {
        t = 0.5 + 0.5 * x / maxAbs(range);
    } else if (scale == ColourScale::Log) {
        const double m = maxAbs(range), c = kLogLinearFraction * m;
        t = 0.5 + 0.5 * (x < 0 ? -1.0 : (x > 0 ? 1.0 : 0.0)) * std::log1p(std::abs(x) / c) /
                      std::log1p(m / c);
    } else {
        t = (x - range.low) / std::max(range.high - range.low, 1e-30);
    }
    return std::clamp(std::isnan(t) ? 0.0 : t, 0.0, 1.0);
}

double colourScaleValue(double t, const ValueRange& range, ColourScale scale) {
    t = std::clamp(t, 0.0, 1.0);
    if (scale == ColourScale::Symmetric)
        return (2.0 * t - 1.0) * maxAbs(range);
    if (scale == ColourScale::Log) {
        const double m = maxAbs(range), c = kLogLinearFraction * m;
        const double s = 2.0 * t - 1.0;
        const double mag = c * std::expm1(std::abs(s) * std::log1p(m / c));
        return s < 0 ? -mag : mag;
    }
    return range.low + t * (range.high - range.low);
}

glm::vec3 rampColour(double t) {
    const std::vector<glm::vec3>& r = colourRamp();
    const double x = std::clamp(t, 0.0, 1.0) * double(r.size() - 1);
    const int i = std::min(int(x), int(r.size()) - 2);
    return glm::mix(r[size_t(i)], r[size_t(i + 1)], float(x - i));
}

QStringList analysisDefines(const AnalysisOptions& options, bool curvatureAov) {
    return ExactVariant{0, 0, 1, options.mode, analysisFeatures(options, curvatureAov)}.defines();
}

double analysisValue(AnalysisMode mode, const SurfaceCurvature& c) {
    const double kmax = std::max(std::abs(c.k1), std::abs(c.k2));
    switch (mode) {
    case AnalysisMode::Gaussian:
        return c.gaussian;
    case AnalysisMode::Mean:
        return c.mean;
    case AnalysisMode::MaxCurvature:
        return kmax;
    case AnalysisMode::MinRadius:
        return kmax > 0.0 ? 1.0 / kmax : std::numeric_limits<double>::infinity();
    default:
        return 0.0;
    }
}

ValueRange autoRange(const Scene& scene, AnalysisMode mode, int samples, double lowPercentile,
                     double highPercentile) {
    if (!isColourMap(mode) || samples < 1)
        return {};
    // (value, area) of each sample: its cell's area |Su x Sv| du dv. Counted per sample, a
    // small sharp patch (the teapot's rim, spout tip, lid knob: 16 x 16 samples each, like the
    // body's much larger patches) held most of the samples and set the range to +-21.55 of
    // mean curvature, where the body's 0.3 to 1.1 was one colour.
    std::vector<std::pair<double, double>> values;
    values.reserve(scene.surfaces.size() * size_t(samples) * size_t(samples));
    for (const Surface& s : scene.surfaces) {
        if (s.hidden) // the range follows what is drawn (Isolate shows one surface's range)
            continue;
        const Interval du = surfaceDomainU(s.geometry), dv = surfaceDomainV(s.geometry);
        const double cell =
            (du.last - du.first) * (dv.last - dv.first) / (double(samples) * double(samples));
        for (int j = 0; j < samples; ++j)
            for (int i = 0; i < samples; ++i) {
                // Cell centres: no sample sits on a collapsed edge.
                const double u = du.first + (du.last - du.first) * (i + 0.5) / samples;
                const double v = dv.first + (dv.last - dv.first) * (j + 0.5) / samples;
                const SurfaceCurvature c = surfaceCurvature(s.geometry, u, v);
                const double x = analysisValue(mode, c);
                const double area = std::sqrt(std::max(c.E * c.G - c.F * c.F, 0.0)) * cell;
                if (std::isfinite(x) && std::isfinite(area))
                    values.emplace_back(x, area);
            }
    }
    if (values.empty())
        return {};
    std::sort(values.begin(), values.end());
    double total = 0.0;
    for (const auto& v : values)
        total += v.second;
    // The value below which fraction p of the area lies; by count where no sample has area
    // (every surface degenerate).
    const auto at = [&](double p) {
        p = std::clamp(p, 0.0, 1.0);
        if (!(total > 0.0))
            return values[size_t(std::lround(p * double(values.size() - 1)))].first;
        double below = 0.0;
        for (const auto& [x, area] : values) {
            below += area;
            if (below >= p * total)
                return x;
        }
        return values.back().first;
    };
    ValueRange r{at(lowPercentile), at(highPercentile)};
    // A (nearly) constant quantity, e.g. max |k| = 1/r on a torus: rounding noise must not span
    // the whole scale, so the range is at least +-5% of its magnitude around its middle.
    const double mid = 0.5 * (r.low + r.high);
    const double half = std::max(0.05 * std::abs(mid), 1e-12);
    if (r.high - r.low < 2.0 * half)
        r = {mid - half, mid + half};
    return r;
}

} // namespace kw
