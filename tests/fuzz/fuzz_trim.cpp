// libFuzzer harness: trim-loop repair and flattening (model/nurbs/trim.h) on loops built from the
// input: curves of any degree with valid, unsorted or miscounted knots, any weights, points
// anywhere (NaN and infinities included), loops that close, have gaps or are empty. Checks:
// makeTrimRegion only keeps finite closed polygons inside their boxes; spans are sorted,
// disjoint and agree with point classification; curve splitting and reversal keep the shape;
// the trimmed area of a unit square lies in [0, 1] (the trim tolerance's band aside), quickly.
#include "fuzz_util.h"
#include "model/analysis/mass_properties.h"
#include "model/nurbs/trim.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

using namespace kw;
using kw::fuzz::Input;

namespace {

bool finite2(glm::dvec2 p) {
    return std::isfinite(p.x) && std::isfinite(p.y);
}

std::vector<double> makeKnots(Input& in, int degree, int count) {
    const int mode = in.integer(0, 7);
    int n = count + degree + 1;
    if (mode == 7)
        n += in.integer(-2, 2); // a miscounted vector
    std::vector<double> k;
    if (mode <= 3) { // clamped, uniform or random interior, sometimes repeated knots
        const double a = mode == 3 ? in.wild(-4, 4) : 0.0;
        const double b = mode == 3 ? a + in.wild(0, 8) : 1.0;
        k.assign(size_t(degree + 1), a);
        const int interior = count - degree - 1;
        std::vector<double> mid;
        for (int i = 1; i <= interior; ++i)
            mid.push_back(mode == 0 ? a + (b - a) * i / (interior + 1) : in.real(a, b));
        std::sort(mid.begin(), mid.end());
        k.insert(k.end(), mid.begin(), mid.end());
        k.insert(k.end(), size_t(degree + 1), b);
    } else { // arbitrary values, sorted or not
        for (int i = 0; i < n && i < 64; ++i)
            k.push_back(in.wild(-2, 2));
        if (mode != 6)
            std::sort(k.begin(), k.end());
    }
    return k;
}

NurbsCurve2 makeCurve(Input& in, glm::dvec2 start) {
    NurbsCurve2 c;
    c.degree = in.byte() == 255 ? in.integer(-1, kMaxDegree + 2) : in.integer(1, 4);
    const int count = std::max(1, c.degree + in.integer(0, 6));
    c.knots = makeKnots(in, c.degree, std::min(count, 40));
    // Mostly curves at the scale of their domain, as in files; sometimes far larger.
    const double scale = in.byte() < 240 ? 1.0 : in.wild(0, 1e6);
    for (int i = 0; i < count && i < 40; ++i) {
        c.points.push_back(
            i == 0 && in.flag() ? start : glm::dvec2{in.wild(-1, 1), in.wild(-1, 1)} * scale);
        c.weights.push_back(in.flag() ? 1.0 : in.wild(0.05, 5));
    }
    if (in.byte() == 0 && !c.weights.empty())
        c.weights.pop_back(); // a weight missing
    return c;
}

/// Loops whose curves mostly chain end to start and close; the input decides where not.
std::vector<TrimLoop> makeLoops(Input& in) {
    std::vector<TrimLoop> loops;
    const int nLoops = in.integer(0, 4);
    for (int l = 0; l < nLoops; ++l) {
        TrimLoop loop;
        loop.id = TrimLoopId{std::uint32_t(l + 1)};
        const int nCurves = in.integer(0, 4);
        glm::dvec2 end{in.real(-1, 1), in.real(-1, 1)};
        const glm::dvec2 first = end;
        for (int c = 0; c < nCurves; ++c) {
            NurbsCurve2 curve = makeCurve(in, end);
            if (c + 1 == nCurves && in.flag() && !curve.points.empty())
                curve.points.back() = first; // close the loop
            if (!curve.points.empty())
                end = curve.points.back();
            loop.curves.push_back(std::move(curve));
        }
        loops.push_back(std::move(loop));
    }
    return loops;
}

void checkRegion(const TrimRegion& r, Input& in) {
    KW_FUZZ_CHECK(r.lo.size() == r.loops.size() && r.hi.size() == r.loops.size(), "");
    for (size_t l = 0; l < r.loops.size(); ++l) {
        KW_FUZZ_CHECK(r.loops[l].size() >= 3,
                      QStringLiteral("loop %1 kept with %2 points").arg(l).arg(r.loops[l].size()));
        for (glm::dvec2 p : r.loops[l]) {
            KW_FUZZ_CHECK(finite2(p), "a kept polygon has a non-finite point");
            KW_FUZZ_CHECK(p.x >= r.lo[l].x && p.y >= r.lo[l].y && p.x <= r.hi[l].x &&
                              p.y <= r.hi[l].y,
                          "a polygon point lies outside its box");
        }
    }
    // Vertical lines: spans sorted, disjoint, clipped, and their midpoints inside, whenever the
    // midpoint is clear of every edge (on an edge the parity of a point is a matter of rounding).
    for (int k = 0; k < 4; ++k) {
        const double u = in.real(-1.5, 1.5);
        const double v0 = in.real(-2, 0), v1 = v0 + in.real(0, 4);
        const std::vector<Interval> spans = trimRegionSpans(r, u, v0, v1);
        double prev = -std::numeric_limits<double>::infinity();
        for (const Interval& s : spans) {
            KW_FUZZ_CHECK(s.first >= v0 && s.last <= v1 && s.first >= prev &&
                              (s.first < s.last || (r.empty() && s.first == s.last)),
                          QStringLiteral("span [%1, %2] in [%3, %4] after %5")
                              .arg(s.first)
                              .arg(s.last)
                              .arg(v0)
                              .arg(v1)
                              .arg(prev));
            prev = s.last;
            const glm::dvec2 mid{u, 0.5 * (s.first + s.last)};
            if (trimRegionDistance(r, mid) > 1e-9)
                KW_FUZZ_CHECK(trimRegionContains(r, mid), "a span midpoint is classified outside");
        }
    }
}

QString knotText(const NurbsCurve2& c) {
    QString s = QStringLiteral(" knots");
    for (double k : c.knots)
        s += QStringLiteral(" %1").arg(k, 0, 'g', 17);
    s += QStringLiteral(" points");
    for (glm::dvec2 p : c.points)
        s += QStringLiteral(" (%1 %2)").arg(p.x, 0, 'g', 17).arg(p.y, 0, 'g', 17);
    return s;
}

void checkCurve(const NurbsCurve2& c, double tolerance, Input& in) {
    if (!checkNurbsCurve(c))
        return; // the functions below require a valid curve
    const Interval d = curveDomain(c);
    glm::dvec2 lo{std::numeric_limits<double>::max()}, hi{-std::numeric_limits<double>::max()};
    for (glm::dvec2 p : c.points) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    const double size = std::max(glm::length(hi - lo), 1.0);
    if (!std::isfinite(size))
        return; // the checks below measure distances
    const std::vector<glm::dvec2> pts = tessellateTrimCurve(c, tolerance);
    KW_FUZZ_CHECK(pts.size() >= 2, "a curve flattened to fewer than 2 points");
    if (!std::all_of(pts.begin(), pts.end(), finite2))
        return; // overflows in evaluation (tiny weights): makeTrimRegion leaves it out
    KW_FUZZ_CHECK(glm::length(pts.front() - curvePoint(c, d.first)) <= 1e-9 * size, "start");
    KW_FUZZ_CHECK(glm::length(pts.back() - curvePoint(c, d.last)) <= 1e-9 * size,
                  QStringLiteral("end (%1, %2) vs (%3, %4)")
                          .arg(pts.back().x)
                          .arg(pts.back().y)
                          .arg(curvePoint(c, d.last).x)
                          .arg(curvePoint(c, d.last).y) +
                      knotText(c));

    const double t = in.real(d.first, d.last);
    const glm::dvec2 at = curvePoint(c, t);
    const NurbsCurve2 r = trimCurveReversed(c);
    KW_FUZZ_CHECK(
        checkNurbsCurve(r).has_value(),
        QStringLiteral("the reversed curve is invalid: %1").arg(checkNurbsCurve(r).message()) +
            knotText(c) + knotText(r));
    // An interior knot of multiplicity degree + 1 (allowed, docs/FILE_FORMAT.md) is a break:
    // there evaluation takes the right-hand piece, which the reversed curve has on its left.
    const bool atBreak =
        t > d.first && t < d.last &&
        std::count(c.knots.begin(), c.knots.end(), t) > static_cast<std::ptrdiff_t>(c.degree);
    KW_FUZZ_CHECK(curveDomain(r) == (Interval{-d.last, -d.first}), "the reversed domain");
    KW_FUZZ_CHECK(atBreak || glm::length(curvePoint(r, -t) - at) <= 1e-7 * size,
                  QStringLiteral("the reversed curve has another shape at t = %1 in [%2, %3]: "
                                 "(%4, %5) vs (%6, %7), degree %8")
                          .arg(t)
                          .arg(d.first)
                          .arg(d.last)
                          .arg(at.x)
                          .arg(at.y)
                          .arg(curvePoint(r, -t).x)
                          .arg(curvePoint(r, -t).y)
                          .arg(c.degree) +
                      knotText(c) + knotText(r));

    const double a = in.real(d.first, d.last), b = in.real(d.first, d.last);
    if (a < b && !(a > d.first && a - d.first < 1e-9) && !(b < d.last && d.last - b < 1e-9)) {
        const NurbsCurve2 s = trimCurveSegment(c, a, b);
        KW_FUZZ_CHECK(
            checkNurbsCurve(s).has_value(),
            QStringLiteral("segment [%1, %2]: %3").arg(a).arg(b).arg(checkNurbsCurve(s).message()));
        KW_FUZZ_CHECK(curveDomain(s) == (Interval{a, b}), "the segment has another domain");
        // Not 0.5 * (a + b): that overflows to inf for a domain near 1e308 (which a file can
        // hold), and evaluation clamps inf to each curve's own end.
        const double m = std::midpoint(a, b);
        KW_FUZZ_CHECK(glm::length(curvePoint(s, m) - curvePoint(c, m)) <= 1e-6 * size,
                      QStringLiteral("the segment [%1, %2] has another shape at %3: (%4, %5) vs "
                                     "(%6, %7), degree %8")
                              .arg(a, 0, 'g', 17)
                              .arg(b, 0, 'g', 17)
                              .arg(m, 0, 'g', 17)
                              .arg(curvePoint(s, m).x)
                              .arg(curvePoint(s, m).y)
                              .arg(curvePoint(c, m).x)
                              .arg(curvePoint(c, m).y)
                              .arg(c.degree) +
                          knotText(c) + knotText(s));
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
    Input in(data, size);
    // trimTolerance's 1e-5 of the domain diagonal first, then coarser and finer ones.
    static const double kTolerances[] = {1e-5, 1e-4, 1e-3, 1e-2, 0.1, 0.5, 1e-6, 1e-9};
    const double tolerance = kTolerances[in.integer(0, 7)];
    const std::vector<TrimLoop> loops = makeLoops(in);

    QStringList warnings;
    const TrimRegion region = makeTrimRegion(loops, tolerance, &warnings);
    checkRegion(region, in);
    for (const TrimLoop& loop : loops)
        for (const NurbsCurve2& c : loop.curves)
            checkCurve(c, tolerance, in);

    // Area of the unit square with these trims: the exact measure clips the loops to the domain,
    // takes them even-odd and stops refining at its budget, so any trims give an area in [0, 1],
    // but for loops that stray past the domain by less than the trim tolerance, which it takes
    // whole as CAD files mean them: at most the domain widened by that band.
    const NurbsSurface square = [] {
        NurbsSurface s;
        s.countU = s.countV = 2;
        s.knotsU = s.knotsV = {0, 0, 1, 1};
        s.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
        s.weights = {1, 1, 1, 1};
        return s;
    }();
    const double area = trimmedSurfaceArea(square, loops);
    const double band = 1.0 + 2.0 * trimTolerance(square);
    KW_FUZZ_CHECK(area >= -1e-9 && area <= band * band + 1e-9,
                  QStringLiteral("area %1").arg(area, 0, 'g', 17));
    return 0;
}
