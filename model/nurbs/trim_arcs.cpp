// Monotone rational Bezier arcs from trim curves, and exact even-odd classification against them.
#include "model/nurbs/trim_arcs.h"

#include "model/nurbs/trim.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace kw {
namespace {

constexpr int kMaxRootDepth = 64;
// Turning points closer than this to an arc's end (in t) are that end: no arc is cut there.
constexpr double kEndSlack = 1e-9;
constexpr int kBisectionSteps = 60;

double binomial(int n, int k) {
    double r = 1.0;
    for (int i = 1; i <= k; ++i)
        r = r * double(n - k + i) / double(i);
    return r;
}

// Splits Bernstein coefficients at s (de Casteljau): left gets [0, s], right [s, 1].
template <class T>
void splitBezier(const std::vector<T>& c, double s, std::vector<T>& left, std::vector<T>& right) {
    std::vector<T> work = c;
    const size_t n = c.size();
    left.resize(n);
    right.resize(n);
    for (size_t r = 0; r < n; ++r) {
        left[r] = work.front();
        right[n - 1 - r] = work[n - 1 - r];
        for (size_t i = 0; i + 1 < n - r; ++i)
            work[i] = (1.0 - s) * work[i] + s * work[i + 1];
    }
}

double bernsteinValue(std::vector<double> c, double t) {
    for (size_t r = c.size(); r > 1; --r)
        for (size_t i = 0; i + 1 < r; ++i)
            c[i] = (1.0 - t) * c[i] + t * c[i + 1];
    return c.front();
}

// Roots in (lo, hi) of the polynomial with Bernstein coefficients c on [lo, hi] (see
// trimArcTurningPoints). Coefficients within `eps` of zero count as zero.
void bernsteinRoots(const std::vector<double>& c, double lo, double hi, double eps, int depth,
                    std::vector<double>& out) {
    int changes = 0, last = 0;
    for (double x : c) {
        const int s = x > eps ? 1 : (x < -eps ? -1 : 0);
        if (s != 0 && last != 0 && s != last)
            ++changes;
        if (s != 0)
            last = s;
    }
    if (changes == 0)
        return;
    const double f0 = c.front(), f1 = c.back();
    if (changes == 1 && std::abs(f0) > eps && std::abs(f1) > eps && (f0 > 0) != (f1 > 0)) {
        // Exactly one root (Descartes' rule of signs in Bernstein form): bisect on it.
        double a = 0.0, b = 1.0;
        for (int k = 0; k < kBisectionSteps && b - a > 1e-16; ++k) {
            const double m = 0.5 * (a + b);
            if ((bernsteinValue(c, m) > 0) == (f0 > 0))
                a = m;
            else
                b = m;
        }
        out.push_back(lo + (hi - lo) * 0.5 * (a + b));
        return;
    }
    if (depth >= kMaxRootDepth || hi - lo < 1e-13) {
        out.push_back(0.5 * (lo + hi)); // a double root (tangent inflection): cut anyway
        return;
    }
    std::vector<double> left, right;
    splitBezier(c, 0.5, left, right);
    const double mid = 0.5 * (lo + hi);
    bernsteinRoots(left, lo, mid, eps, depth + 1, out);
    bernsteinRoots(right, mid, hi, eps, depth + 1, out);
}

TrimArc arcOf(std::vector<glm::dvec3> hw, glm::dvec2 start, glm::dvec2 end) {
    TrimArc a;
    a.degree = int(hw.size()) - 1;
    a.hw = std::move(hw);
    a.start = start;
    a.end = end;
    return a;
}

} // namespace

glm::dvec2 trimArcPoint(const TrimArc& arc, double t) {
    std::array<glm::dvec3, kMaxDegree + 1> w;
    const int n = arc.degree + 1;
    std::copy(arc.hw.begin(), arc.hw.end(), w.begin());
    for (int r = n; r > 1; --r)
        for (int i = 0; i + 1 < r; ++i)
            w[i] = (1.0 - t) * w[i] + t * w[i + 1];
    return glm::dvec2(w[0]) / w[0].z;
}

double trimArcSolve(const TrimArc& arc, int axis, double value, double t0, double t1) {
    const double c0 = trimArcPoint(arc, t0)[axis], c1 = trimArcPoint(arc, t1)[axis];
    const bool rising = c1 >= c0;
    if (rising ? value <= c0 : value >= c0)
        return t0;
    if (rising ? value >= c1 : value <= c1)
        return t1;
    // Illinois (modified regula falsi, Dowell & Jarratt 1971) on the bracket, halving the stale
    // end's value when one end stays twice; a bisection step whenever the bracket shrinks too
    // slowly. The coordinate is monotone, so the bracket always holds the one root.
    double a = t0, b = t1, fa = c0 - value, fb = c1 - value;
    const double tiny = 4e-16 * (std::abs(c0) + std::abs(c1) + std::abs(value));
    int side = 0;
    bool bisect = false;
    for (int k = 0; k < 2 * kBisectionSteps; ++k) {
        const double width = b - a;
        double m = bisect ? 0.5 * (a + b) : (a * fb - b * fa) / (fb - fa);
        if (!(m > a && m < b))
            m = 0.5 * (a + b);
        if (m <= a || m >= b)
            break;
        const double fm = trimArcPoint(arc, m)[axis] - value;
        if (std::abs(fm) <= tiny)
            return m;
        if ((fm < 0) == (fa < 0)) {
            a = m, fa = fm;
            if (side == -1)
                fb *= 0.5;
            side = -1;
        } else {
            b = m, fb = fm;
            if (side == 1)
                fa *= 0.5;
            side = 1;
        }
        bisect = b - a > 0.75 * width; // slow progress: bisect next
    }
    return std::abs(fa) < std::abs(fb) ? a : b;
}

std::vector<double> trimArcTurningPoints(const std::vector<glm::dvec3>& hw) {
    const int p = int(hw.size()) - 1;
    std::vector<double> roots;
    if (p < 1)
        return roots;
    for (int axis = 0; axis < 2; ++axis) {
        // N = X'W - XW' = p sum_{i<p, j<=p} (dX_i W_j - dW_i X_j) B_i^{p-1} B_j^p, and
        // B_i^m B_j^n = C(m,i) C(n,j) / C(m+n, i+j) B_{i+j}^{m+n} (Farin, Curves and Surfaces for
        // CAGD, 5.2). The factor p > 0 does not move the roots.
        std::vector<double> c(size_t(2 * p), 0.0);
        double scale = 0.0;
        for (int i = 0; i < p; ++i)
            for (int j = 0; j <= p; ++j) {
                const double dX = hw[i + 1][axis] - hw[i][axis], dW = hw[i + 1].z - hw[i].z;
                const double term = (dX * hw[j].z - dW * hw[j][axis]) * binomial(p - 1, i) *
                                    binomial(p, j) / binomial(2 * p - 1, i + j);
                c[size_t(i + j)] += term;
                scale = std::max(scale, std::abs(term));
            }
        std::vector<double> found;
        bernsteinRoots(c, 0.0, 1.0, scale * 1e-12, 0, found);
        for (double t : found)
            if (t > kEndSlack && t < 1.0 - kEndSlack)
                roots.push_back(t);
    }
    std::sort(roots.begin(), roots.end());
    roots.erase(std::unique(roots.begin(), roots.end(),
                            [](double a, double b) { return b - a < kEndSlack; }),
                roots.end());
    return roots;
}

std::vector<TrimArc> monotoneTrimArcs(const NurbsCurve2& curve) {
    std::vector<TrimArc> out;
    const Interval d = curveDomain(curve);
    std::vector<double> breaks{d.first};
    for (double k : curve.knots)
        if (k > breaks.back() && k < d.last)
            breaks.push_back(k);
    breaks.push_back(d.last);
    glm::dvec2 from = curvePoint(curve, d.first);
    for (size_t s = 0; s + 1 < breaks.size(); ++s) {
        // One Bezier piece per knot span: knots inserted to full multiplicity at both ends.
        const NurbsCurve2 bez = trimCurveSegment(curve, breaks[s], breaks[s + 1]);
        std::vector<glm::dvec3> hw(bez.points.size());
        for (size_t i = 0; i < hw.size(); ++i)
            hw[i] = glm::dvec3(bez.points[i] * bez.weights[i], bez.weights[i]);
        const glm::dvec2 to = s + 2 == breaks.size() ? curvePoint(curve, d.last)
                                                     : glm::dvec2(hw.back()) / hw.back().z;
        // A knot of multiplicity degree + 1 may break the curve: bridge the jump by a straight
        // arc so the loop stays closed (anything but rounding apart counts as a jump).
        const glm::dvec2 begin = glm::dvec2(hw.front()) / hw.front().z;
        if (s > 0 && glm::length(begin - from) > 1e-12 * (1.0 + glm::length(from))) {
            out.push_back(arcOf({glm::dvec3(from, 1.0), glm::dvec3(begin, 1.0)}, from, begin));
            from = begin;
        }
        double done = 0.0; // the part of the span already emitted, in the span's t
        for (double r : trimArcTurningPoints(hw)) {
            std::vector<glm::dvec3> left, right;
            splitBezier(hw, (r - done) / (1.0 - done), left, right);
            const glm::dvec2 mid = glm::dvec2(left.back()) / left.back().z;
            out.push_back(arcOf(std::move(left), from, mid));
            from = mid;
            hw = std::move(right);
            done = r;
        }
        out.push_back(arcOf(std::move(hw), from, to));
        from = to;
    }
    return out;
}

TrimArcs makeTrimArcs(const std::vector<TrimLoop>& trims, double tolerance, QStringList* warnings) {
    TrimArcs result;
    auto line = [](glm::dvec2 a, glm::dvec2 b) {
        return arcOf({glm::dvec3(a, 1.0), glm::dvec3(b, 1.0)}, a, b);
    };
    for (const TrimLoop& loop : trims) {
        // The same repairs and warnings as makeTrimRegion, loop by loop: a loop it drops as
        // degenerate is dropped here too.
        if (makeTrimRegion({loop}, tolerance, warnings).empty())
            continue;
        std::vector<TrimArc> arcs;
        for (const NurbsCurve2& curve : loop.curves) {
            if (!checkNurbsCurve(curve))
                continue;
            std::vector<TrimArc> pieces = monotoneTrimArcs(curve);
            // makeTrimRegion leaves out a curve whose evaluation overflows; so do the arcs.
            const auto finite = [](glm::dvec2 p) {
                return std::isfinite(p.x) && std::isfinite(p.y);
            };
            if (std::any_of(pieces.begin(), pieces.end(), [&](const TrimArc& a) {
                    return !finite(a.start) || !finite(a.end) ||
                           std::any_of(a.hw.begin(), a.hw.end(), [&](const glm::dvec3& h) {
                               return !finite(glm::dvec2(h)) || !std::isfinite(h.z);
                           });
                }))
                continue;
            if (!arcs.empty() && arcs.back().end != pieces.front().start)
                arcs.push_back(line(arcs.back().end, pieces.front().start));
            arcs.insert(arcs.end(), pieces.begin(), pieces.end());
        }
        if (arcs.empty())
            continue;
        if (arcs.back().end != arcs.front().start)
            arcs.push_back(line(arcs.back().end, arcs.front().start));
        for (TrimArc& a : arcs) {
            a.loop = result.loops;
            if (result.arcs.empty() && &a == &arcs.front())
                result.lo = result.hi = a.start;
            result.lo = glm::min(result.lo, glm::min(a.start, a.end));
            result.hi = glm::max(result.hi, glm::max(a.start, a.end));
        }
        result.arcs.insert(result.arcs.end(), arcs.begin(), arcs.end());
        ++result.loops;
    }
    return result;
}

bool trimArcsContain(const TrimArcs& arcs, glm::dvec2 uv) {
    if (arcs.empty())
        return true;
    bool inside = false;
    for (const TrimArc& a : arcs.arcs) {
        if ((a.start.x <= uv.x) == (a.end.x <= uv.x))
            continue; // the half-open rule of trimRegionContains
        const double vLo = std::min(a.start.y, a.end.y), vHi = std::max(a.start.y, a.end.y);
        if (uv.y >= vHi)
            continue;
        if (uv.y < vLo || trimArcPoint(a, trimArcSolve(a, 0, uv.x, 0.0, 1.0)).y > uv.y)
            inside = !inside;
    }
    return inside;
}

} // namespace kw
