// Edge quality of a frame against a reference: silhouettes, cracks, id/depth, normals.
#include "render/edge_metrics.h"

#include <QJsonDocument>
#include <QJsonObject>
#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

namespace kw {
namespace {

constexpr double kDegrees = 180.0 / 3.14159265358979323846;
/// Neighbouring reference pixels of one surface whose eye depths differ by more than this many
/// pixel footprints are on either side of the surface's own silhouette: a continuous surface
/// only gets there where it is within 3 degrees of edge-on (1 / tan 3 degrees = 19), that is,
/// on a curved surface, within a small fraction of a pixel of its silhouette.
constexpr double kDepthJumpFootprints = 19.0;

bool covered(const AovBuffer& b, int x, int y) {
    return b.pixel(x, y)[0] >= 0.0f;
}

int idAt(const AovBuffer& b, int x, int y) {
    const float id = b.pixel(x, y)[0];
    return id >= 0.0f ? int(std::lround(id)) : -1;
}

/// Marks background pixels of `b` in a run of at most 2 between covered pixels along one axis.
void markCracks(const AovBuffer& b, std::vector<char>& mark) {
    const int w = b.width, h = b.height;
    auto scan = [&](int count, int length, auto at) {
        for (int line = 0; line < count; ++line) {
            int last = -1; // index of the last covered pixel on this line
            for (int k = 0; k < length; ++k) {
                const auto [x, y] = at(line, k);
                if (!covered(b, x, y))
                    continue;
                const int gap = k - last - 1;
                if (last >= 0 && gap >= 1 && gap <= 2)
                    for (int g = last + 1; g < k; ++g) {
                        const auto [gx, gy] = at(line, g);
                        mark[size_t(gy) * size_t(w) + size_t(gx)] = 1;
                    }
                last = k;
            }
        }
    };
    scan(h, w, [](int line, int k) { return std::pair<int, int>(k, line); });
    scan(w, h, [](int line, int k) { return std::pair<int, int>(line, k); });
}

/// Distance from (x, y) to the nearest set pixel of `silhouette` (a w x h mask), searching
/// square rings outwards; the image diagonal when there is none.
double nearestDistance(const std::vector<char>& silhouette, int w, int h, int x, int y) {
    double best = std::hypot(double(w), double(h));
    const int maxR = std::max(w, h);
    for (int r = 0; r <= maxR; ++r) {
        if (double(r) > best)
            break; // every pixel of ring r and beyond is at least r away
        for (int yy = y - r; yy <= y + r; ++yy) {
            if (yy < 0 || yy >= h)
                continue;
            const int step = (yy == y - r || yy == y + r) ? 1 : 2 * r;
            for (int xx = x - r; xx <= x + r; xx += std::max(step, 1)) {
                if (xx < 0 || xx >= w || !silhouette[size_t(yy) * size_t(w) + size_t(xx)])
                    continue;
                best = std::min(best, std::hypot(double(xx - x), double(yy - y)));
            }
        }
    }
    return best;
}

} // namespace

long long crackPixels(const AovBuffer& frame) {
    std::vector<char> mark(size_t(frame.width) * size_t(frame.height), 0);
    markCracks(frame, mark);
    return std::count(mark.begin(), mark.end(), 1);
}

Status sameAovSize(const AovBuffer& frame, const AovBuffer& reference, const QString& who) {
    if (frame.width == reference.width && frame.height == reference.height && frame.width > 0 &&
        frame.height > 0)
        return ok();
    return Error(QStringLiteral("%1 two AOV frames of one non-empty size, got %2x%3 and %4x%5")
                     .arg(who)
                     .arg(frame.width)
                     .arg(frame.height)
                     .arg(reference.width)
                     .arg(reference.height));
}

Status compareWithReference(const AovBuffer& frame, const AovBuffer& reference,
                            double depthTolerance, EdgeMetrics& out, double pixelAngle,
                            const glm::dvec3* eye) {
    out = EdgeMetrics{};
    if (Status sized = sameAovSize(frame, reference, QStringLiteral("edge metrics need")); !sized)
        return sized;
    const int w = frame.width, h = frame.height;
    const size_t n = size_t(w) * size_t(h);
    out.pixels = (long long)n;
    out.depthTolerance = depthTolerance;

    // Reference silhouette and the edge band.
    std::vector<char> silhouette(n, 0), band(n, 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const int id = idAt(reference, x, y);
            out.covered += covered(frame, x, y);
            out.referenceCovered += id >= 0;
            bool idEdge = false, uncoveredNeighbour = false;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int xx = x + dx, yy = y + dy;
                    if (xx < 0 || yy < 0 || xx >= w || yy >= h) {
                        uncoveredNeighbour |= (dx == 0) != (dy == 0);
                        continue;
                    }
                    const int other = idAt(reference, xx, yy);
                    idEdge |= other != id;
                    // A surface's silhouette over itself (a torus's inner rim over its far
                    // side) is an edge too: the same id on both sides, but the depth jumps.
                    if (id >= 0 && other == id) {
                        const double z = double(reference.pixel(x, y)[9]);
                        const double zo = double(reference.pixel(xx, yy)[9]);
                        idEdge |=
                            pixelAngle > 0.0 &&
                            std::abs(z - zo) > kDepthJumpFootprints * pixelAngle * std::min(z, zo);
                    }
                    if ((dx == 0) != (dy == 0))
                        uncoveredNeighbour |= other < 0;
                }
            if (id >= 0 && uncoveredNeighbour)
                silhouette[size_t(y) * size_t(w) + size_t(x)] = 1;
            if (idEdge) // this pixel and its neighbours are within one pixel of an id change
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int xx = x + dx, yy = y + dy;
                        if (xx >= 0 && yy >= 0 && xx < w && yy < h)
                            band[size_t(yy) * size_t(w) + size_t(xx)] = 1;
                    }
        }

    std::vector<char> cracks(n, 0);
    markCracks(frame, cracks);
    std::vector<double> angles;
    double silhouetteSum = 0.0, angleSum = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t k = size_t(y) * size_t(w) + size_t(x);
            const bool cf = covered(frame, x, y), cr = covered(reference, x, y);
            if (cracks[k]) {
                ++out.crackPixels;
                out.crackPixelsCoveredInReference += cr;
            }
            if (cf != cr) {
                ++out.silhouetteMismatched;
                const double d = nearestDistance(silhouette, w, h, x, y);
                silhouetteSum += d;
                out.silhouetteMaxPixels = std::max(out.silhouetteMaxPixels, d);
            }
            const int idF = idAt(frame, x, y), idR = idAt(reference, x, y);
            const float* pf = frame.pixel(x, y);
            const float* pr = reference.pixel(x, y);
            if (eye && idF >= 0 && idF == idR) {
                const glm::dvec3 ray = glm::dvec3(pr[3], pr[4], pr[5]) - *eye;
                const glm::dvec3 nf(pf[6], pf[7], pf[8]), nr(pr[6], pr[7], pr[8]);
                const double cr = glm::dot(nr, ray), cf = glm::dot(nf, ray);
                // The hidden sheet lies behind: a nearer point of the same surface is one the
                // reference's ray casting missed, not the frame's fault.
                out.facingDisagreements +=
                    std::abs(cr) >= 0.01 * glm::length(nr) * glm::length(ray) && cr * cf < 0.0 &&
                    double(pf[9]) >= double(pr[9]) * (1.0 - 1e-6);
            }
            if (band[k]) {
                ++out.edgeBandPixels;
                out.bandBehind += idF >= 0 && idR >= 0 && idF != idR &&
                                  double(pf[9]) > double(pr[9]) + depthTolerance;
                continue;
            }
            if (idF != idR) {
                const bool tie = idF >= 0 && idR >= 0 &&
                                 std::abs(double(pf[9]) - double(pr[9])) <= depthTolerance;
                ++out.idDisagreements;
                out.idCoincident += tie;
                continue;
            }
            if (idR < 0)
                continue;
            if (!(std::abs(double(pf[9]) - double(pr[9])) <= depthTolerance))
                ++out.depthDisagreements;
            const glm::dvec3 nf(pf[6], pf[7], pf[8]), nr(pr[6], pr[7], pr[8]);
            const double lf = glm::length(nf), lr = glm::length(nr);
            double angle = 180.0; // a broken normal must not look good
            if (std::isfinite(lf) && lf > 0.0 && lr > 0.0)
                angle = std::acos(std::clamp(glm::dot(nf / lf, nr / lr), -1.0, 1.0)) * kDegrees;
            angles.push_back(angle);
            angleSum += angle;
            out.normalMaxDegrees = std::max(out.normalMaxDegrees, angle);
        }
    out.silhouetteMeanPixels =
        out.silhouetteMismatched ? silhouetteSum / double(out.silhouetteMismatched) : 0.0;
    out.normalPixels = (long long)angles.size();
    if (!angles.empty()) {
        out.normalMeanDegrees = angleSum / double(angles.size());
        const size_t at = std::min(angles.size() - 1, size_t(0.99 * double(angles.size())));
        std::nth_element(angles.begin(), angles.begin() + std::ptrdiff_t(at), angles.end());
        out.normalP99Degrees = angles[at];
    }
    return ok();
}

QString edgeMetricsJson(const EdgeMetrics& m) {
    QJsonObject o;
    o[QStringLiteral("pixels")] = double(m.pixels);
    o[QStringLiteral("covered")] = double(m.covered);
    o[QStringLiteral("referenceCovered")] = double(m.referenceCovered);
    o[QStringLiteral("silhouetteMismatched")] = double(m.silhouetteMismatched);
    o[QStringLiteral("silhouetteMeanPixels")] = m.silhouetteMeanPixels;
    o[QStringLiteral("silhouetteMaxPixels")] = m.silhouetteMaxPixels;
    o[QStringLiteral("crackPixels")] = double(m.crackPixels);
    o[QStringLiteral("crackPixelsCoveredInReference")] = double(m.crackPixelsCoveredInReference);
    o[QStringLiteral("edgeBandPixels")] = double(m.edgeBandPixels);
    o[QStringLiteral("idDisagreements")] = double(m.idDisagreements);
    o[QStringLiteral("idCoincident")] = double(m.idCoincident);
    o[QStringLiteral("depthDisagreements")] = double(m.depthDisagreements);
    o[QStringLiteral("depthTolerance")] = m.depthTolerance;
    o[QStringLiteral("normalPixels")] = double(m.normalPixels);
    o[QStringLiteral("normalMeanDegrees")] = m.normalMeanDegrees;
    o[QStringLiteral("normalP99Degrees")] = m.normalP99Degrees;
    o[QStringLiteral("normalMaxDegrees")] = m.normalMaxDegrees;
    o[QStringLiteral("facingDisagreements")] = double(m.facingDisagreements);
    o[QStringLiteral("bandBehind")] = double(m.bandBehind);
    return QString::fromUtf8(QJsonDocument(o).toJson(QJsonDocument::Indented));
}

} // namespace kw
