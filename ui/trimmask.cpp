// Trim polylines and the parity classification image of a surface's domain, both from
// model/nurbs/trim.h (one flattening and one point-in-loop rule for the whole program).
#include "ui/trimmask.h"

#include "model/nurbs/trim.h"

#include <algorithm>
#include <cmath>

namespace kw {

namespace {

// Flattening tolerance for the panel: a thousandth of the domain diagonal is well under a
// panel pixel at any size the panel is shown.
double panelTolerance(const Surface& surface) {
    return trimTolerance(surface.geometry, 1e-3);
}

} // namespace

std::vector<std::vector<glm::dvec2>> trimPolylines(const Surface& surface, int samplesPerSpan) {
    // model/nurbs/trim.h flattens adaptively; samplesPerSpan sets a tolerance finer than that many
    // chords per span of the domain would give.
    const double tolerance =
        panelTolerance(surface) * 24.0 / double(std::clamp(samplesPerSpan, 2, 512));
    return makeTrimRegion(surface.trims, tolerance).loops;
}

QImage trimMaskImage(const Surface& surface, QSize size) {
    if (size.isEmpty())
        return {};
    QImage image(size, QImage::Format_Grayscale8);
    const TrimRegion region = makeTrimRegion(surface.trims, panelTolerance(surface));
    if (region.empty()) {
        image.fill(255);
        return image;
    }
    image.fill(0);
    const Interval du = surfaceDomainU(surface.geometry), dv = surfaceDomainV(surface.geometry);
    const int w = size.width(), h = size.height();
    // Column by column: the kept v intervals of u = column centre (model/nurbs/trim.h's parity
    // rule), then the rows whose centres fall inside them. Row 0 is v = last.
    for (int x = 0; x < w; ++x) {
        const double u = du.first + (x + 0.5) / w * (du.last - du.first);
        for (const Interval& span : trimRegionSpans(region, u, dv.first, dv.last)) {
            // Rows y with v(y) = last - (y + 0.5)/h (last - first) inside [span.first, span.last].
            const double scale = h / (dv.last - dv.first);
            const int y0 = std::max(0, int(std::ceil((dv.last - span.last) * scale - 0.5)));
            const int y1 = std::min(h - 1, int(std::floor((dv.last - span.first) * scale - 0.5)));
            for (int y = y0; y <= y1; ++y)
                image.scanLine(y)[x] = 255;
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
