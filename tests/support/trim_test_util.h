// Helpers shared by the trim tests: trim curves built in code, a messy-input surface, and the
// comparison of a trimmed AOV render with the CPU classification of model/nurbs/trim.h.
#pragma once

#include "model/document/scene.h"
#include "model/nurbs/trim.h"

#include <cmath>
#include <map>
#include <vector>

namespace kwtest {

/// A degree-1 curve through `pts` with uniform interior knots.
inline kw::NurbsCurve2 polylineCurve(const std::vector<glm::dvec2>& pts) {
    kw::NurbsCurve2 c;
    c.degree = 1;
    c.points = pts;
    c.weights.assign(pts.size(), 1.0);
    c.knots = {0.0};
    for (size_t k = 0; k < pts.size(); ++k)
        c.knots.push_back(double(k) / double(pts.size() - 1));
    c.knots.push_back(1.0);
    return c;
}

/// A clamped degree-`degree` curve whose control points go once round an ellipse (centre c,
/// radii r) and back to the start: a closed smooth-ish loop of any degree 1..15.
inline kw::NurbsCurve2 ellipseCurve(int degree, glm::dvec2 c, glm::dvec2 r, int count,
                                    bool clockwise = false) {
    kw::NurbsCurve2 curve;
    curve.degree = degree;
    for (int k = 0; k < count; ++k) {
        const double a = (clockwise ? -1.0 : 1.0) * 2.0 * M_PI * k / (count - 1);
        curve.points.push_back(c + r * glm::dvec2(std::cos(a), std::sin(a)));
    }
    curve.weights.assign(size_t(count), 1.0);
    for (int k = 0; k <= degree; ++k)
        curve.knots.push_back(0.0);
    const int interior = count - degree - 1;
    for (int k = 1; k <= interior; ++k)
        curve.knots.push_back(double(k) / (interior + 1));
    for (int k = 0; k <= degree; ++k)
        curve.knots.push_back(1.0);
    return curve;
}

inline kw::TrimLoop loopOf(std::uint32_t id, std::vector<kw::NurbsCurve2> curves) {
    kw::TrimLoop l;
    l.id = kw::TrimLoopId{id};
    l.curves = std::move(curves);
    return l;
}

/// Loops of messy input over the unit domain, ids from `firstId`: an outer loop on the domain
/// boundary made of four separate edges, one of them reversed in direction (so the curves do
/// not join head to tail: a gap) and the loop left open at the end; a clockwise degree-15
/// ellipse hole; a counter-clockwise degree-3 ellipse island inside it; a degenerate loop (a
/// line walked there and back); and a loop of three collinear points.
inline std::vector<kw::TrimLoop> messyLoops(std::uint32_t firstId) {
    std::vector<kw::TrimLoop> loops;
    loops.push_back(loopOf(firstId, {polylineCurve({{0, 0}, {1, 0}}),
                                     polylineCurve({{1, 1}, {1, 0}}), // reversed
                                     polylineCurve({{1, 1}, {0, 1}}),
                                     polylineCurve({{0, 1}, {0, 0.02}})})); // open: 0.02 short
    loops.push_back(
        loopOf(firstId + 1, {ellipseCurve(15, {0.5, 0.5}, {0.35, 0.3}, 24, /*clockwise=*/true)}));
    loops.push_back(loopOf(firstId + 2, {ellipseCurve(3, {0.5, 0.5}, {0.12, 0.1}, 9)}));
    loops.push_back(loopOf(firstId + 3, {polylineCurve({{0.1, 0.1}, {0.3, 0.2}, {0.1, 0.1}})}));
    loops.push_back(loopOf(firstId + 4, {polylineCurve({{0.2, 0.8}, {0.3, 0.85}, {0.4, 0.9}})}));
    return loops;
}

/// How a trimmed render agrees with the CPU classification (model/nurbs/trim.h) at each pixel.
struct TrimAgreement {
    long checked = 0;       ///< pixels showing a trimmed surface in either render
    long agree = 0;         ///< of those, the trimmed render shows what the CPU says it should
    long far = 0;           ///< disagreements further than `texels` mask texels from a curve
    double worstTexels = 0; ///< largest distance of a disagreement from a curve, in mask texels
    double fraction() const { return checked ? double(agree) / double(checked) : 0.0; }
};

/// Per pixel: where the untrimmed render shows trimmed surface s at (u, v), the trimmed render
/// must show s at the same (u, v) exactly when trimRegionContains(s, (u, v)); where the trimmed
/// render shows a trimmed surface that the untrimmed one hid, the CPU must say inside.
/// `texelOf` gives the mask texel size (parameter units) of a surface. Disagreements are
/// measured by trimRegionDistance and counted as far beyond `texels` texels.
template <class Aov, class TexelOf>
TrimAgreement compareTrimmedRender(const kw::Scene& scene, const Aov& trimmed, const Aov& whole,
                                   TexelOf texelOf, double texels = 1.0) {
    std::map<float, const kw::Surface*> byId;
    std::map<float, kw::TrimRegion> regions;
    for (const kw::Surface& s : scene.surfaces)
        if (!s.trims.empty()) {
            byId[float(s.id.value)] = &s;
            regions[float(s.id.value)] =
                kw::makeTrimRegion(s.trims, kw::trimTolerance(s.geometry, 1e-6));
        }
    TrimAgreement r;
    for (int y = 0; y < trimmed.height; ++y)
        for (int x = 0; x < trimmed.width; ++x) {
            const float* t = trimmed.pixel(x, y);
            const float* w = whole.pixel(x, y);
            const bool wholeTrimmed = byId.count(w[0]) > 0;
            const bool shownTrimmed = byId.count(t[0]) > 0;
            if (!wholeTrimmed && !shownTrimmed)
                continue;
            ++r.checked;
            const bool same =
                t[0] == w[0] && std::abs(t[1] - w[1]) < 1e-6f && std::abs(t[2] - w[2]) < 1e-6f;
            double distance = -1.0; // of a disagreement, in texels
            auto check = [&](const float* px, bool visible) {
                const kw::TrimRegion& region = regions[px[0]];
                const glm::dvec2 uv(px[1], px[2]);
                if (kw::trimRegionContains(region, uv) != visible)
                    distance = std::max(distance, kw::trimRegionDistance(region, uv) /
                                                      texelOf(byId[px[0]]->id));
            };
            if (wholeTrimmed)
                check(w, same);
            if (shownTrimmed && !same)
                check(t, true);
            if (distance < 0.0) {
                ++r.agree;
                continue;
            }
            r.worstTexels = std::max(r.worstTexels, distance);
            if (distance > texels)
                ++r.far;
        }
    return r;
}

} // namespace kwtest
