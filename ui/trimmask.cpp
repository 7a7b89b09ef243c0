// Trim polylines and the scanline-parity classification image of a surface's domain.
#include "ui/trimmask.h"

#include <algorithm>
#include <cmath>

namespace kw {

std::vector<std::vector<glm::dvec2>> trimPolylines(const Surface& surface, int samplesPerSpan) {
    samplesPerSpan = std::clamp(samplesPerSpan, 2, 512);
    std::vector<std::vector<glm::dvec2>> out;
    for (const TrimLoop& loop : surface.trims) {
        std::vector<glm::dvec2> line;
        for (const NurbsCurve2& c : loop.curves) {
            if (!curveValidationError(c).empty())
                continue;
            if (c.degree == 1) {
                line.insert(line.end(), c.points.begin(), c.points.end());
                continue;
            }
            const Interval dom = curveDomain(c);
            // Sample every non-empty span so corners at knots are hit exactly.
            for (size_t k = size_t(c.degree); k + 1 < c.knots.size() - size_t(c.degree); ++k) {
                const double a = c.knots[k], b = c.knots[k + 1];
                if (!(b > a) || a < dom.first || b > dom.last)
                    continue;
                for (int s = 0; s < samplesPerSpan; ++s)
                    line.push_back(curvePoint(c, a + (b - a) * s / samplesPerSpan));
            }
            line.push_back(curvePoint(c, dom.last));
        }
        if (line.size() >= 2)
            out.push_back(std::move(line));
    }
    return out;
}

QImage trimMaskImage(const Surface& surface, QSize size) {
    if (size.isEmpty())
        return {};
    QImage image(size, QImage::Format_Grayscale8);
    const auto lines = trimPolylines(surface);
    if (lines.empty()) {
        image.fill(255);
        return image;
    }
    const Interval du = surfaceDomainU(surface.geometry), dv = surfaceDomainV(surface.geometry);
    const int w = size.width(), h = size.height();
    std::vector<double> crossings;
    for (int y = 0; y < h; ++y) {
        const double v = dv.last - (y + 0.5) / h * (dv.last - dv.first);
        crossings.clear();
        // Each loop is closed implicitly (last point back to first). Half-open rule on the
        // edge's v range so a vertex on the scanline counts once.
        for (const auto& line : lines)
            for (size_t k = 0; k < line.size(); ++k) {
                const glm::dvec2& a = line[k];
                const glm::dvec2& b = line[(k + 1) % line.size()];
                if ((a.y <= v) == (b.y <= v))
                    continue;
                crossings.push_back(a.x + (v - a.y) / (b.y - a.y) * (b.x - a.x));
            }
        std::sort(crossings.begin(), crossings.end());
        uchar* row = image.scanLine(y);
        size_t next = 0;
        bool inside = false;
        for (int x = 0; x < w; ++x) {
            const double u = du.first + (x + 0.5) / w * (du.last - du.first);
            while (next < crossings.size() && crossings[next] <= u) {
                inside = !inside;
                ++next;
            }
            row[x] = inside ? 255 : 0;
        }
    }
    return image;
}

double keptFraction(const QImage& mask) {
    if (mask.isNull())
        return 0.0;
    std::int64_t kept = 0;
    for (int y = 0; y < mask.height(); ++y) {
        const uchar* row = mask.constScanLine(y);
        for (int x = 0; x < mask.width(); ++x)
            kept += row[x] > 127;
    }
    return double(kept) / (double(mask.width()) * mask.height());
}

} // namespace kw
