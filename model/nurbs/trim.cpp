// Trim loops: flattening to polylines, even-odd classification and trimmed surface area.
#include "model/nurbs/trim.h"

#include "model/document/validation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace kw {
namespace {

constexpr int kMinPiecesPerKnotSpan = 4;
constexpr int kMaxBisectionDepth = 18;
// Bound on the points of one flattened curve. Without it a curve far outside its domain's scale
// (points at 1e6 with a tolerance of 1e-9, as a hostile file can have) bisects every piece to
// the depth limit: 4 * 2^18 points per knot span, seconds per curve (found by fuzz_trim). 2^14
// points flatten a curve of 1000 knot spans to 16 points per span, plenty for a trim.
constexpr std::int64_t kMaxFlattenedPoints = std::int64_t(1) << 14;

double distanceToSegment(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b) {
    const glm::dvec2 ab = b - a;
    const double len2 = glm::dot(ab, ab);
    if (!std::isfinite(len2) && std::isfinite(ab.x) && std::isfinite(ab.y)) {
        // Finite points so far apart that the squared length overflows: the same at a
        // power-of-two scale (exact), then scaled back.
        constexpr int k = 600;
        const auto down = [](glm::dvec2 v) {
            return glm::dvec2(std::ldexp(v.x, -k), std::ldexp(v.y, -k));
        };
        return std::ldexp(distanceToSegment(down(p), down(a), down(b)), k);
    }
    if (len2 <= 0.0)
        return glm::length(p - a);
    const double t = std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0);
    return glm::length(p - (a + t * ab));
}

// Where the edge a-b meets the vertical line x = u, for a.x and b.x on either side of it (the
// parity tests below). The textbook a.y + (u - a.x) (b.y - a.y) / (b.x - a.x) overflows for
// finite but huge coordinates (fuzz_trim: an edge from (1, 1) to (-2.5e305, 94709) gave a cut
// at -inf, so trimRegionSpans and trimRegionContains disagreed). The fraction along the edge
// first (in [0, 1]; at half scale if b.x - a.x overflows), then std::lerp, which stays between
// a.y and b.y: a cut never leaves the edge's box, so contains' box test cannot change a parity.
double crossingV(glm::dvec2 a, glm::dvec2 b, double u) {
    const double width = b.x - a.x;
    const double t =
        std::isfinite(width) ? (u - a.x) / width : (0.5 * u - 0.5 * a.x) / (0.5 * b.x - 0.5 * a.x);
    return std::lerp(a.y, b.y, std::clamp(t, 0.0, 1.0));
}

// Appends the points of (t0, t1] to out, bisecting while the curve strays from the chord.
void flattenPiece(const NurbsCurve2& c, double t0, glm::dvec2 p0, double t1, glm::dvec2 p1,
                  double tolerance, int depth, int maxDepth, std::vector<glm::dvec2>& out) {
    const double tm = 0.5 * (t0 + t1);
    const glm::dvec2 pm = curvePoint(c, tm);
    if (depth < maxDepth && distanceToSegment(pm, p0, p1) > tolerance) {
        flattenPiece(c, t0, p0, tm, pm, tolerance, depth + 1, maxDepth, out);
        flattenPiece(c, tm, pm, t1, p1, tolerance, depth + 1, maxDepth, out);
        return;
    }
    out.push_back(p1);
}

// Distinct knot values inside the domain, both ends included.
std::vector<double> breakpoints(const std::vector<double>& knots, int degree) {
    const Interval d = knotDomain(knots, degree);
    std::vector<double> out{d.first};
    for (double k : knots)
        if (k > out.back() && k < d.last)
            out.push_back(k);
    out.push_back(d.last);
    return out;
}

// The Boehm / A5.1 knot insertion on a 2D rational curve, in homogeneous coordinates.
NurbsCurve2 insertCurveKnot(const NurbsCurve2& c, double t) {
    const int p = c.degree;
    const int k = findSpan(p, c.knots, t);
    std::vector<glm::dvec3> hw(c.points.size());
    for (size_t i = 0; i < hw.size(); ++i)
        hw[i] = glm::dvec3(c.points[i] * c.weights[i], c.weights[i]);
    std::vector<glm::dvec3> q(hw.size() + 1);
    for (int i = 0; i < static_cast<int>(q.size()); ++i) {
        if (i <= k - p)
            q[i] = hw[i];
        else if (i > k)
            q[i] = hw[i - 1];
        else {
            const double a = (t - c.knots[i]) / (c.knots[i + p] - c.knots[i]);
            q[i] = a * hw[i] + (1.0 - a) * hw[i - 1];
        }
    }
    NurbsCurve2 out;
    out.degree = p;
    out.knots = c.knots;
    out.knots.insert(out.knots.begin() + k + 1, t);
    for (const glm::dvec3& h : q) {
        out.points.push_back(glm::dvec2(h) / h.z);
        out.weights.push_back(h.z);
    }
    return out;
}

} // namespace

NurbsCurve2 trimCurveSegment(NurbsCurve2 c, double a, double b) {
    const int p = c.degree;
    for (double t : {a, b}) {
        const int have = static_cast<int>(std::count(c.knots.begin(), c.knots.end(), t));
        for (int m = have; m < p; ++m)
            c = insertCurveKnot(c, t);
    }
    const auto first = std::lower_bound(c.knots.begin(), c.knots.end(), a) - c.knots.begin();
    const auto last = std::upper_bound(c.knots.begin(), c.knots.end(), b) - c.knots.begin();
    NurbsCurve2 out;
    out.degree = p;
    // Keep multiplicity p at each end, plus one more knot each side to clamp: take the knots
    // from the first a (p+1 of them, a repeated) to the last b.
    out.knots.assign(p + 1, a);
    for (auto i = first; i < last; ++i)
        if (c.knots[i] > a && c.knots[i] < b)
            out.knots.push_back(c.knots[i]);
    out.knots.insert(out.knots.end(), p + 1, b);
    const int count = static_cast<int>(out.knots.size()) - p - 1;
    // With a of multiplicity m >= p at knots[first ..], the segment starts at control point
    // first + m - p - 1 (the one C(a+) equals).
    const int multA = static_cast<int>(std::count(c.knots.begin(), c.knots.end(), a));
    const int start = static_cast<int>(first) + multA - p - 1;
    out.points.assign(c.points.begin() + start, c.points.begin() + start + count);
    out.weights.assign(c.weights.begin() + start, c.weights.begin() + start + count);
    return out;
}

NurbsCurve2 trimCurveReversed(const NurbsCurve2& c) {
    NurbsCurve2 r = c;
    std::reverse(r.points.begin(), r.points.end());
    std::reverse(r.weights.begin(), r.weights.end());
    // Negate the knots: exact in floating point, so every valid curve stays valid with the same
    // multiplicities and the same shape. Reflecting about the domain middle (a + b - k) rounds:
    // for a domain like [-1.5, 1e308] it merged distinct knots into one of multiplicity above
    // degree + 1 (fuzz_trim, tests/fuzz/repro/trim/reversed-invalid). 0.0 - k, not -k, so that
    // a knot 0 stays +0 in files.
    for (size_t i = 0; i < c.knots.size(); ++i)
        r.knots[i] = 0.0 - c.knots[c.knots.size() - 1 - i];
    return r;
}

std::vector<glm::dvec2> tessellateTrimCurve(const NurbsCurve2& curve, double tolerance) {
    const std::vector<double> t = breakpoints(curve.knots, curve.degree);
    std::vector<glm::dvec2> out{curvePoint(curve, t.front())};
    const std::int64_t pieces = std::int64_t(t.size() - 1) * kMinPiecesPerKnotSpan;
    int maxDepth = kMaxBisectionDepth;
    while (maxDepth > 0 && (pieces << maxDepth) > kMaxFlattenedPoints)
        --maxDepth;
    for (size_t k = 0; k + 1 < t.size(); ++k) {
        for (int p = 0; p < kMinPiecesPerKnotSpan; ++p) {
            const double a = t[k] + (t[k + 1] - t[k]) * p / kMinPiecesPerKnotSpan;
            const double b = p + 1 == kMinPiecesPerKnotSpan
                                 ? t[k + 1]
                                 : t[k] + (t[k + 1] - t[k]) * (p + 1) / kMinPiecesPerKnotSpan;
            flattenPiece(curve, a, out.back(), b, curvePoint(curve, b), tolerance, 0, maxDepth,
                         out);
        }
    }
    return out;
}

TrimPolygon tessellateTrimLoop(const TrimLoop& loop, double tolerance) {
    TrimPolygon poly;
    for (const NurbsCurve2& c : loop.curves) {
        for (glm::dvec2 p : tessellateTrimCurve(c, tolerance))
            if (poly.empty() || p != poly.back())
                poly.push_back(p);
    }
    while (poly.size() > 1 && poly.back() == poly.front())
        poly.pop_back();
    return poly;
}

namespace {

bool clampedStart(const NurbsCurve2& c) {
    return std::all_of(c.knots.begin(), c.knots.begin() + c.degree + 1,
                       [&](double k) { return k == c.knots.front(); });
}

NurbsCurve2 straightCurve(glm::dvec2 from, glm::dvec2 to) {
    NurbsCurve2 c;
    c.degree = 1;
    c.knots = {0.0, 0.0, 1.0, 1.0};
    c.points = {from, to};
    c.weights = {1.0, 1.0};
    return c;
}

} // namespace

QStringList closeSceneTrimLoops(Scene& scene) {
    QStringList lines;
    for (Surface& s : scene.surfaces)
        for (TrimLoop& loop : s.trims) {
            const bool valid =
                std::all_of(loop.curves.begin(), loop.curves.end(),
                            [](const NurbsCurve2& c) { return checkNurbsCurve(c).has_value(); });
            if (!valid)
                continue;
            std::vector<int> newIndex;
            const QStringList closed = closeTrimLoop(loop, trimTolerance(s.geometry), &newIndex);
            // A bridge inserted before curve k renumbers it and those after it; the topology's
            // sides must keep naming the same curves.
            renumberLoopCurves(scene.topology, s.id, loop.id, newIndex);
            for (const QString& line : closed)
                lines << QStringLiteral("surface '%1', trim loop %2: %3")
                             .arg(s.name)
                             .arg(loop.id.value)
                             .arg(line);
        }
    return lines;
}

std::vector<TrimPointRef> trimPointWithCoincidentEnds(const Surface& surface,
                                                      const TrimPointRef& hit) {
    std::vector<TrimPointRef> refs{hit};
    const auto loop = std::find_if(surface.trims.begin(), surface.trims.end(),
                                   [&](const TrimLoop& l) { return l.id == hit.loop; });
    if (hit.surface != surface.id || loop == surface.trims.end() || hit.curve < 0 ||
        size_t(hit.curve) >= loop->curves.size())
        return refs;
    const std::vector<glm::dvec2>& own = loop->curves[size_t(hit.curve)].points;
    const int last = int(own.size()) - 1;
    if (hit.index < 0 || hit.index > last || (hit.index != 0 && hit.index != last))
        return refs;
    const glm::dvec2 at = own[size_t(hit.index)];
    // Within the tolerance the loop is closed by, not exactly: files and imports close loops
    // to the last bit or two (0.04 against 0.04000000000000001 in the trimmed_plate sample).
    const double tolerance = trimLoopClosureTolerance(*loop);
    for (size_t c = 0; c < loop->curves.size(); ++c) {
        const std::vector<glm::dvec2>& pts = loop->curves[c].points;
        for (int k : {0, int(pts.size()) - 1}) {
            const TrimPointRef ref{hit.surface, hit.loop, int(c), k};
            if (glm::length(pts[size_t(k)] - at) <= tolerance &&
                std::find(refs.begin(), refs.end(), ref) == refs.end())
                refs.push_back(ref);
        }
    }
    return refs;
}

QStringList closeTrimLoop(TrimLoop& loop, double snap, std::vector<int>* newIndex) {
    QStringList done;
    if (newIndex)
        newIndex->clear();
    if (loop.curves.empty())
        return done;
    const double tolerance = trimLoopClosureTolerance(loop);
    std::vector<NurbsCurve2> out;
    out.reserve(loop.curves.size());
    // Joins `next` after `prev`: snaps or bridges the gap between prev's end and next's start.
    // `bridge` receives a straight curve when one is needed; `label` names the later curve.
    auto join = [&](const NurbsCurve2& prev, NurbsCurve2& next, std::vector<NurbsCurve2>& bridge,
                    size_t label) {
        const glm::dvec2 end = curvePoint(prev, curveDomain(prev).last);
        const double gap = glm::length(curvePoint(next, curveDomain(next).first) - end);
        if (gap <= tolerance)
            return;
        if (gap <= snap && clampedStart(next)) {
            next.points.front() = end;
            if (glm::length(curvePoint(next, curveDomain(next).first) - end) <= tolerance) {
                done << QStringLiteral("gap of %1 before curve %2 closed by moving its first point")
                            .arg(gap, 0, 'g', 3)
                            .arg(label);
                return;
            }
        }
        bridge.push_back(straightCurve(end, curvePoint(next, curveDomain(next).first)));
        done << QStringLiteral("gap of %1 before curve %2 bridged by a straight segment")
                    .arg(gap, 0, 'g', 3)
                    .arg(label);
    };
    for (size_t k = 0; k < loop.curves.size(); ++k) {
        NurbsCurve2 cur = loop.curves[k];
        if (!out.empty()) {
            std::vector<NurbsCurve2> bridge;
            join(out.back(), cur, bridge, k + 1);
            out.insert(out.end(), bridge.begin(), bridge.end());
        }
        if (newIndex)
            newIndex->push_back(int(out.size()));
        out.push_back(std::move(cur));
    }
    std::vector<NurbsCurve2> bridge;
    NurbsCurve2 first = out.front();
    join(out.back(), first, bridge, 1);
    if (bridge.empty())
        out.front() = std::move(first);
    else
        out.insert(out.end(), bridge.begin(), bridge.end());
    loop.curves = std::move(out);
    return done;
}

TrimRegion makeTrimRegion(const std::vector<TrimLoop>& trims, double tolerance,
                          QStringList* warnings) {
    auto warn = [&](const QString& text) {
        if (warnings)
            warnings->append(text);
    };
    TrimRegion region;
    for (size_t l = 0; l < trims.size(); ++l) {
        const TrimLoop& loop = trims[l];
        const QString name = QStringLiteral("trim loop %1").arg(loop.id.value);
        TrimPolygon poly;
        bool haveCurve = false;
        glm::dvec2 lastEnd{0.0};
        for (size_t c = 0; c < loop.curves.size(); ++c) {
            const NurbsCurve2& curve = loop.curves[c];
            if (const Status e = checkNurbsCurve(curve); !e) {
                warn(QStringLiteral("%1: curve %2 is invalid (%3); left out")
                         .arg(name)
                         .arg(c + 1)
                         .arg(e.message()));
                continue;
            }
            const std::vector<glm::dvec2> pts = tessellateTrimCurve(curve, tolerance);
            // Finite points and weights can still overflow in evaluation (1e300 * 1e10); a
            // polygon with infinities would poison every parity test (found by fuzz_trim).
            if (std::any_of(pts.begin(), pts.end(), [](glm::dvec2 p) {
                    return !std::isfinite(p.x) || !std::isfinite(p.y);
                })) {
                warn(QStringLiteral("%1: curve %2 evaluates beyond the range of doubles; left out")
                         .arg(name)
                         .arg(c + 1));
                continue;
            }
            if (haveCurve && glm::length(pts.front() - lastEnd) > tolerance)
                warn(QStringLiteral("%1: gap of %2 before curve %3; bridged by a straight segment")
                         .arg(name)
                         .arg(glm::length(pts.front() - lastEnd), 0, 'g', 3)
                         .arg(c + 1));
            for (glm::dvec2 p : pts)
                if (poly.empty() || p != poly.back())
                    poly.push_back(p);
            haveCurve = true;
            lastEnd = pts.back();
        }
        if (poly.size() >= 2 && glm::length(lastEnd - poly.front()) > tolerance)
            warn(QStringLiteral("%1 does not close (gap of %2); closed by a straight segment")
                     .arg(name)
                     .arg(glm::length(lastEnd - poly.front()), 0, 'g', 3));
        while (poly.size() > 1 && poly.back() == poly.front())
            poly.pop_back();
        // Unsigned area of the fan from the first point (what the GPU mask rasterises): zero
        // only when every point lies on one line through it. The signed area would wrongly call
        // a figure eight degenerate.
        double fanArea = 0.0;
        for (size_t i = 1; i + 1 < poly.size(); ++i) {
            const glm::dvec2 a = poly[i] - poly[0], b = poly[i + 1] - poly[0];
            fanArea += 0.5 * std::abs(a.x * b.y - a.y * b.x);
        }
        if (poly.size() < 3 || fanArea < tolerance * tolerance) {
            warn(QStringLiteral("%1 is degenerate (encloses no area); ignored").arg(name));
            continue;
        }
        glm::dvec2 lo = poly.front(), hi = poly.front();
        for (glm::dvec2 p : poly) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        region.loops.push_back(std::move(poly));
        region.lo.push_back(lo);
        region.hi.push_back(hi);
    }
    return region;
}

QStringList trimWarnings(const Surface& surface) {
    QStringList warnings;
    makeTrimRegion(surface.trims, trimTolerance(surface.geometry), &warnings);
    return warnings;
}

double trimRegionDistance(const TrimRegion& region, glm::dvec2 uv) {
    double best = std::numeric_limits<double>::infinity();
    for (const TrimPolygon& poly : region.loops)
        for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
            best = std::min(best, distanceToSegment(uv, poly[j], poly[i]));
    return best;
}

double trimTolerance(const NurbsSurface& surface, double relative) {
    const Interval u = surfaceDomainU(surface);
    const Interval v = surfaceDomainV(surface);
    return relative * std::hypot(u.last - u.first, v.last - v.first);
}

bool trimRegionContains(const TrimRegion& region, glm::dvec2 uv) {
    if (region.empty())
        return true;
    bool inside = false;
    for (size_t l = 0; l < region.loops.size(); ++l) {
        if (uv.x < region.lo[l].x || uv.x > region.hi[l].x || uv.y < region.lo[l].y ||
            uv.y > region.hi[l].y)
            continue;
        const TrimPolygon& poly = region.loops[l];
        // Crossing number of the ray from uv towards +v (half-open rule on u for vertices).
        for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
            const glm::dvec2 a = poly[j], b = poly[i];
            if ((a.x <= uv.x) == (b.x <= uv.x))
                continue;
            if (crossingV(a, b, uv.x) > uv.y)
                inside = !inside;
        }
    }
    return inside;
}

void trimRegionContainsColumn(const TrimRegion& region, double u, const double* v, int count,
                              bool* inside) {
    std::fill(inside, inside + count, region.empty());
    std::vector<double> crossings;
    for (size_t l = 0; l < region.loops.size(); ++l) {
        if (u < region.lo[l].x || u > region.hi[l].x)
            continue;
        // The edges trimRegionContains counts for any point of this column, same rule.
        crossings.clear();
        const TrimPolygon& poly = region.loops[l];
        for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
            const glm::dvec2 a = poly[j], b = poly[i];
            if ((a.x <= u) != (b.x <= u))
                crossings.push_back(crossingV(a, b, u));
        }
        for (int k = 0; k < count; ++k) {
            if (v[k] < region.lo[l].y || v[k] > region.hi[l].y)
                continue;
            for (double c : crossings)
                if (c > v[k])
                    inside[k] = !inside[k];
        }
    }
}

std::vector<Interval> trimRegionSpans(const TrimRegion& region, double u, double v0, double v1) {
    if (region.empty())
        return {Interval{v0, v1}};
    std::vector<double> cuts;
    for (size_t l = 0; l < region.loops.size(); ++l) {
        if (u < region.lo[l].x || u > region.hi[l].x)
            continue;
        const TrimPolygon& poly = region.loops[l];
        for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
            const glm::dvec2 a = poly[j], b = poly[i];
            if ((a.x <= u) == (b.x <= u))
                continue;
            cuts.push_back(crossingV(a, b, u));
        }
    }
    std::sort(cuts.begin(), cuts.end());
    std::vector<Interval> spans;
    for (size_t k = 0; k + 1 < cuts.size(); k += 2) {
        const double a = std::max(cuts[k], v0), b = std::min(cuts[k + 1], v1);
        if (b > a)
            spans.push_back({a, b});
    }
    return spans;
}

} // namespace kw
