// Normal-angle error against kw::surfaceFrame and coverage-mask (silhouette) error.
#include "bench/bench_quality.h"

#include "model/nurbs/nurbs.h"
#include "render/edge_metrics.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace kw::bench {

namespace {

constexpr double kDegrees = 180.0 / 3.14159265358979323846;

bool covered(const AovBuffer& aov, int x, int y) {
    return aov.pixel(x, y)[0] >= 0.0f;
}

} // namespace

NormalError normalError(const Scene& scene, const AovBuffer& aov) {
    std::map<std::uint32_t, const NurbsSurface*> byId;
    for (const Surface& s : scene.surfaces)
        byId[s.id.value] = &s.geometry;
    NormalError e;
    double sum = 0.0;
    for (int y = 0; y < aov.height; ++y)
        for (int x = 0; x < aov.width; ++x) {
            const float* p = aov.pixel(x, y);
            if (p[0] < 0.0f)
                continue;
            ++e.pixels;
            double angle = 180.0;
            const auto it = byId.find(std::uint32_t(std::lround(p[0])));
            const glm::dvec3 shown(p[6], p[7], p[8]);
            const double len = glm::length(shown);
            if (it != byId.end() && std::isfinite(len) && len > 0.0) {
                const SurfaceFrame f = surfaceFrame(*it->second, p[1], p[2]);
                const double c = std::clamp(glm::dot(shown / len, f.normal), -1.0, 1.0);
                angle = std::acos(c) * kDegrees;
            }
            sum += angle;
            e.maxDegrees = std::max(e.maxDegrees, angle);
        }
    e.meanDegrees = e.pixels ? sum / double(e.pixels) : 0.0;
    return e;
}

Status silhouetteError(const AovBuffer& frame, const AovBuffer& reference, SilhouetteError& out) {
    out = SilhouetteError{};
    if (Status sized = sameAovSize(frame, reference, QStringLiteral("silhouette error needs"));
        !sized)
        return sized;
    const int w = reference.width, h = reference.height;
    std::vector<glm::ivec2> silhouette;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!covered(reference, x, y))
                continue;
            const bool edge = x == 0 || y == 0 || x == w - 1 || y == h - 1 ||
                              !covered(reference, x - 1, y) || !covered(reference, x + 1, y) ||
                              !covered(reference, x, y - 1) || !covered(reference, x, y + 1);
            if (edge)
                silhouette.emplace_back(x, y);
        }
    out.silhouettePixels = (long long)silhouette.size();
    // Squared distance to the nearest silhouette pixel, by a brute-force scan over the
    // silhouette (mismatches and silhouette are both O(perimeter), so this stays small).
    double sum = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (covered(frame, x, y) == covered(reference, x, y))
                continue;
            ++out.mismatched;
            double best = std::hypot(double(w), double(h)); // no silhouette: the image diagonal
            long long bestSq = -1;
            for (const glm::ivec2& s : silhouette) {
                const long long dx = s.x - x, dy = s.y - y, d = dx * dx + dy * dy;
                if (bestSq < 0 || d < bestSq)
                    bestSq = d;
            }
            if (bestSq >= 0)
                best = std::sqrt(double(bestSq));
            sum += best;
            out.maxPixels = std::max(out.maxPixels, best);
        }
    out.meanPixels = out.mismatched ? sum / double(out.mismatched) : 0.0;
    out.perSilhouettePixel = out.silhouettePixels
                                 ? double(out.mismatched) / double(out.silhouettePixels)
                                 : (out.mismatched ? double(out.mismatched) : 0.0);
    return ok();
}

} // namespace kw::bench
