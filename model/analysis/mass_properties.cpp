// Area, volume flux and bounds of trimmed faces by quadrature on the exact geometry.
#include "model/analysis/mass_properties.h"

#include "model/document/seamgaps.h"
#include "model/nurbs/trim.h"
#include "model/nurbs/trim_arcs.h"
#include "model/nurbs/visible_bounds.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>
#include <thread>

namespace kw {
namespace {

// 8-point Gauss-Legendre on [-1, 1] (Abramowitz & Stegun 25.4.30): exact for degree 15.
constexpr std::array<double, 4> kGaussX = {0.1834346424956498, 0.5255324099163290,
                                           0.7966664774136267, 0.9602898564975363};
constexpr std::array<double, 4> kGaussW = {0.3626837833783620, 0.3137066458778873,
                                           0.2223810344533745, 0.1012285362903763};
constexpr int kMaxDepth = 30;

/// A fixed number of integrals computed together (the quadrature's value type).
template <int N> struct Sums {
    std::array<double, N> v{};
    Sums() = default;
    explicit Sums(double x) { v.fill(x); }
    static constexpr int length() { return N; }
    double& operator[](int k) { return v[size_t(k)]; }
    double operator[](int k) const { return v[size_t(k)]; }
    Sums& operator+=(const Sums& o) {
        for (int k = 0; k < N; ++k)
            v[size_t(k)] += o.v[size_t(k)];
        return *this;
    }
    friend Sums operator+(Sums a, const Sums& b) { return a += b; }
    friend Sums operator*(double s, Sums a) {
        for (double& x : a.v)
            x *= s;
        return a;
    }
};

template <class V, class F> V gauss8(const F& f, double a, double b) {
    const double h = 0.5 * (b - a), m = 0.5 * (a + b);
    V sum(0.0);
    for (size_t k = 0; k < kGaussX.size(); ++k)
        sum += kGaussW[k] * (f(m - h * kGaussX[k]) + f(m + h * kGaussX[k]));
    return h * sum;
}

/// The shared state of one face's quadratures: evaluations spent, and whether refinement was
/// cut short by the budget.
struct Quadrature {
    long evaluations = 0;
    long limit = 0;
    bool cut = false;
    bool spent() {
        if (evaluations < limit)
            return false;
        cut = true;
        return true;
    }
};

// Halves [a, b] until the two halves' sum agrees with the whole within `relative` of itself or
// `floor` (absolute, shared out over the halves), component by component, or the budget is spent.
template <class V, class F>
V adaptive(const F& f, double a, double b, const V& whole, const V& floor, double relative,
           int depth, Quadrature& q) {
    const double m = 0.5 * (a + b);
    const V left = gauss8<V>(f, a, m), right = gauss8<V>(f, m, b);
    const V sum = left + right;
    bool good = depth <= 0 || !(m > a && m < b);
    if (!good) {
        good = true;
        for (int k = 0; k < V::length(); ++k)
            if (std::abs(sum[k] - whole[k]) > std::max(relative * std::abs(sum[k]), floor[k]))
                good = false;
    }
    if (good)
        return sum;
    if (q.spent())
        return sum;
    return adaptive<V>(f, a, m, left, 0.5 * floor, relative, depth - 1, q) +
           adaptive<V>(f, m, b, right, 0.5 * floor, relative, depth - 1, q);
}

template <class V, class F>
V integrate(const F& f, double a, double b, const V& floor, double relative, Quadrature& q) {
    if (!(b > a))
        return V(0.0);
    if (q.spent()) // past the budget: one rule over the whole interval, no halving
        return gauss8<V>(f, a, b);
    return adaptive<V>(f, a, b, gauss8<V>(f, a, b), floor, relative, kMaxDepth, q);
}

/// S, Su and Sv: A3.6 to order 1 on homogeneous points, then the rational quotient (A4.4);
/// the integrands need no second derivatives, and this runs at every quadrature node.
/// Preconditions: a valid surface, (u, v) in its domain.
struct FirstOrder {
    glm::dvec3 s, su, sv;
};
FirstOrder firstOrder(const NurbsSurface& g, double u, double v) {
    const int pu = g.degreeU, pv = g.degreeV;
    const int spanU = findSpan(pu, g.knotsU, u), spanV = findSpan(pv, g.knotsV, v);
    double nu[2 * (kMaxDegree + 1)], nv[2 * (kMaxDegree + 1)];
    basisFunctionDerivatives(spanU, u, pu, 1, g.knotsU, nu);
    basisFunctionDerivatives(spanV, v, pv, 1, g.knotsV, nv);
    glm::dvec4 a(0.0), au(0.0), av(0.0);
    for (int l = 0; l <= pv; ++l) {
        glm::dvec4 t0(0.0), t1(0.0);
        for (int r = 0; r <= pu; ++r) {
            const size_t idx = size_t(g.index(spanU - pu + r, spanV - pv + l));
            const glm::dvec4 pw(g.points[idx] * g.weights[idx], g.weights[idx]);
            t0 += nu[r] * pw;
            t1 += nu[pu + 1 + r] * pw;
        }
        a += nv[l] * t0;
        au += nv[l] * t1;
        av += nv[pv + 1 + l] * t0;
    }
    FirstOrder f;
    f.s = glm::dvec3(a) / a.w;
    f.su = (glm::dvec3(au) - au.w * f.s) / a.w;
    f.sv = (glm::dvec3(av) - av.w * f.s) / a.w;
    return f;
}

// One piece of a loop's boundary in (u, v): a span of a trim curve, or a straight segment.
struct Piece {
    const NurbsCurve2* curve = nullptr; // nullptr: straight from p to q over t in [0, 1]
    double t0 = 0.0, t1 = 1.0;
    glm::dvec2 p{0.0}, q{0.0};
};

void pointAndTangent(const Piece& piece, double t, glm::dvec2& point, glm::dvec2& d1) {
    if (!piece.curve) {
        point = piece.p + t * (piece.q - piece.p);
        d1 = piece.q - piece.p;
        return;
    }
    const CurveDerivatives2 d = curveDerivatives(*piece.curve, t);
    point = d.point, d1 = d.d1;
}

// A loop as pieces: each valid curve split at its distinct knots, gaps bridged by straight
// segments (as makeTrimRegion draws them), and a flattened copy for nesting tests.
struct LoopPieces {
    std::vector<Piece> pieces;
    TrimPolygon polygon;
    double vLow = 0.0;
};

LoopPieces loopPieces(const TrimLoop& loop, double tolerance) {
    LoopPieces out;
    std::vector<const NurbsCurve2*> curves;
    for (const NurbsCurve2& c : loop.curves)
        if (checkNurbsCurve(c).has_value())
            curves.push_back(&c);
    if (curves.empty())
        return out;
    for (size_t k = 0; k < curves.size(); ++k) {
        const NurbsCurve2& c = *curves[k];
        const Interval d = curveDomain(c);
        double t = d.first;
        for (double knot : c.knots)
            if (knot > t && knot < d.last) {
                out.pieces.push_back({&c, t, knot, {}, {}});
                t = knot;
            }
        out.pieces.push_back({&c, t, d.last, {}, {}});
        const glm::dvec2 end = curvePoint(c, d.last);
        const NurbsCurve2& next = *curves[(k + 1) % curves.size()];
        const glm::dvec2 start = curvePoint(next, curveDomain(next).first);
        if (end != start)
            out.pieces.push_back({nullptr, 0.0, 1.0, end, start});
    }
    for (const NurbsCurve2* c : curves) {
        const std::vector<glm::dvec2> pts = tessellateTrimCurve(*c, tolerance);
        out.polygon.insert(out.polygon.end(), pts.begin(), pts.end());
    }
    out.vLow = std::numeric_limits<double>::infinity();
    for (const glm::dvec2& p : out.polygon)
        out.vLow = std::min(out.vLow, p.y);
    return out;
}

LoopPieces domainLoop(const NurbsSurface& s) {
    const Interval u = surfaceDomainU(s), v = surfaceDomainV(s);
    const glm::dvec2 c[4] = {
        {u.first, v.first}, {u.last, v.first}, {u.last, v.last}, {u.first, v.last}};
    LoopPieces out;
    for (int k = 0; k < 4; ++k) {
        out.pieces.push_back({nullptr, 0.0, 1.0, c[k], c[(k + 1) % 4]});
        out.polygon.push_back(c[k]);
    }
    out.vLow = v.first;
    return out;
}

bool polygonContains(const TrimPolygon& poly, glm::dvec2 p) {
    bool inside = false;
    for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
        const glm::dvec2 a = poly[i], b = poly[j];
        if ((a.x > p.x) != (b.x > p.x) && p.y < a.y + (p.x - a.x) * (b.y - a.y) / (b.x - a.x))
            inside = !inside;
    }
    return inside;
}

double diagonal(const NurbsSurface& s) {
    glm::dvec3 lo, hi;
    surfaceControlBounds(s, lo, hi);
    return std::max(glm::length(hi - lo), 1e-300);
}

// The trimmed face's sample points: a grid over the trims' parameter box (those kept) and the
// trim curves (or the domain's edges), with the curve each boundary sample lies on.
struct Samples {
    std::vector<glm::dvec2> inside;
    struct OnCurve {
        const Piece* piece;
        double t;
        double dt;
    };
    std::vector<OnCurve> boundary;
    std::vector<LoopPieces> loops;
    TrimArcs arcs;
};

Samples faceSamples(const Surface& surface, int grid) {
    Samples s;
    const NurbsSurface& g = surface.geometry;
    const double tol = trimTolerance(g);
    for (const TrimLoop& loop : surface.trims) {
        LoopPieces lp = loopPieces(loop, tol);
        if (!lp.pieces.empty())
            s.loops.push_back(std::move(lp));
    }
    if (s.loops.empty())
        s.loops.push_back(domainLoop(g));
    else
        s.arcs = makeTrimArcs(surface.trims, tol);
    const ParameterBox box = trimParameterBox(surface);
    for (int j = 0; j <= grid; ++j)
        for (int i = 0; i <= grid; ++i) {
            const glm::dvec2 uv(box.u.first + (box.u.last - box.u.first) * i / grid,
                                box.v.first + (box.v.last - box.v.first) * j / grid);
            if (s.arcs.empty() || trimArcsContain(s.arcs, uv))
                s.inside.push_back(uv);
        }
    constexpr int kPerPiece = 8;
    for (const LoopPieces& lp : s.loops)
        for (const Piece& p : lp.pieces) {
            const double dt = (p.t1 - p.t0) / kPerPiece;
            for (int k = 0; k <= kPerPiece; ++k)
                s.boundary.push_back({&p, p.t0 + dt * k, dt});
        }
    return s;
}

glm::dvec3 boundaryPoint(const NurbsSurface& g, const Piece& piece, double t) {
    glm::dvec2 uv, d1;
    pointAndTangent(piece, std::clamp(t, piece.t0, piece.t1), uv, d1);
    return surfacePoint(g, uv.x, uv.y);
}

// Golden-section search for the largest sign * coordinate along a piece within [t0, t1].
double refineAlongCurve(const NurbsSurface& g, const Piece& piece, int axis, double sign, double t0,
                        double t1) {
    const double r = 0.5 * (std::sqrt(5.0) - 1.0);
    const auto f = [&](double t) {
        return sign * boundaryPoint(g, piece, t)[axis];
    };
    double a = std::max(t0, piece.t0), b = std::min(t1, piece.t1);
    double c = b - r * (b - a), d = a + r * (b - a);
    double fc = f(c), fd = f(d);
    for (int k = 0; k < 60 && b - a > 1e-15 * (std::abs(a) + std::abs(b) + 1e-300); ++k) {
        if (fc > fd)
            b = d, d = c, fd = fc, c = b - r * (b - a), fc = f(c);
        else
            a = c, c = d, fc = fd, d = a + r * (b - a), fd = f(d);
    }
    return std::max({fc, fd, f(a), f(b)});
}

// Newton's iteration towards a stationary point of sign * coordinate inside the trims,
// climbing only: returns the best value seen.
double refineInside(const Surface& surface, const Samples& s, glm::dvec2 uv, int axis,
                    double sign) {
    const NurbsSurface& g = surface.geometry;
    const Interval du = surfaceDomainU(g), dv = surfaceDomainV(g);
    double best = sign * surfacePoint(g, uv.x, uv.y)[axis];
    for (int k = 0; k < 12; ++k) {
        const SurfaceDerivatives d = surfaceDerivatives(g, uv.x, uv.y);
        const glm::dvec2 grad(sign * d.su[axis], sign * d.sv[axis]);
        const double a = sign * d.suu[axis], b = sign * d.suv[axis], c = sign * d.svv[axis];
        const double det = a * c - b * b;
        if (!(det > 0.0 && a < 0.0)) // not concave here: no maximum to head for
            break;
        const glm::dvec2 step(-(c * grad.x - b * grad.y) / det, -(a * grad.y - b * grad.x) / det);
        const glm::dvec2 next(std::clamp(uv.x + step.x, du.first, du.last),
                              std::clamp(uv.y + step.y, dv.first, dv.last));
        if (!s.arcs.empty() && !trimArcsContain(s.arcs, next))
            break;
        const double value = sign * surfacePoint(g, next.x, next.y)[axis];
        if (!(value >= best))
            break;
        best = value;
        if (next == uv)
            break;
        uv = next;
    }
    return best;
}

// ---- Trims that cross, fold or reach past the domain ----
// Green's theorem holds for any region whose boundary is a set of closed curves each of which
// keeps the region on its left. For the even-odd region R of arbitrary loops clipped to the
// domain D, that boundary is made of the pieces of the trim arcs inside D (cut where arcs cross
// one another or the domain's edges), each oriented by which of its sides R holds, and the
// pieces of D's edges that lie inside R. Pieces with R on both sides or on neither (coincident
// curves, curves outside D) are no boundary at all.

/// The point and first derivative of a monotone arc at t: de Casteljau on the homogeneous
/// points down to two (The NURBS Book A1.5), then the rational quotient's derivative.
void arcPointAndTangent(const TrimArc& arc, double t, glm::dvec2& point, glm::dvec2& d1) {
    const int n = int(arc.hw.size()) - 1;
    std::array<glm::dvec3, kMaxDegree + 2> w;
    std::copy(arc.hw.begin(), arc.hw.end(), w.begin());
    if (n <= 0) {
        point = glm::dvec2(w[0]) / w[0].z;
        d1 = glm::dvec2(0.0);
        return;
    }
    for (int r = 1; r < n; ++r)
        for (int i = 0; i <= n - r; ++i)
            w[size_t(i)] = (1.0 - t) * w[size_t(i)] + t * w[size_t(i + 1)];
    const glm::dvec3 p = (1.0 - t) * w[0] + t * w[1], dp = double(n) * (w[1] - w[0]);
    point = glm::dvec2(p) / p.z;
    d1 = (glm::dvec2(dp) - dp.z * point) / p.z;
}

/// A span [t0, t1] of one arc with its end points (a monotone arc lies in their box).
struct ArcSpan {
    double t0 = 0.0, t1 = 1.0;
    glm::dvec2 a{0.0}, b{0.0};
};

/// Where the arcs meet one another: per arc the parameters of the meetings found.
struct Meetings {
    std::vector<std::vector<double>> at;
    double resolution = 0.0;
    long work = 0;
    /// Box tests one face may spend: coincident arcs subdivide without end; past it the search
    /// stops and the result is flagged approximate.
    long limit = 150'000;
    bool cut = false;
    bool crossing = false; ///< a meeting other than consecutive arcs' shared end points
    glm::dvec2 clipLo{0.0}, clipHi{0.0}; ///< the box meetings are looked for in
};

// Newton's iteration on A(t) = B(s) from the meeting found by subdivision; kept when it stays in
// the spans and converges, as the subdivision's box then holds the one meeting.
void refineMeeting(const TrimArc& A, const ArcSpan& sa, const TrimArc& B, const ArcSpan& sb,
                   double& t, double& s) {
    double tt = t, ss = s;
    for (int k = 0; k < 8; ++k) {
        glm::dvec2 pa, da, pb, db;
        arcPointAndTangent(A, tt, pa, da);
        arcPointAndTangent(B, ss, pb, db);
        const glm::dvec2 r = pa - pb;
        const double det = -da.x * db.y + da.y * db.x;
        if (!(std::abs(det) > 0.0) || !std::isfinite(det))
            return;
        const double dt = (-r.x * db.y + r.y * db.x) / det, ds = (da.x * r.y - da.y * r.x) / det;
        tt -= dt, ss -= ds;
        if (!(tt >= sa.t0 && tt <= sa.t1 && ss >= sb.t0 && ss <= sb.t1))
            return;
    }
    t = tt, s = ss;
}

void meet(const TrimArcs& arcs, int ia, const ArcSpan& A, int ib, const ArcSpan& B, Meetings& m) {
    if (m.cut)
        return;
    if (++m.work > m.limit) {
        m.cut = true;
        return;
    }
    const glm::dvec2 loA = glm::min(A.a, A.b), hiA = glm::max(A.a, A.b);
    const glm::dvec2 loB = glm::min(B.a, B.b), hiB = glm::max(B.a, B.b);
    if (!(loA.x <= hiB.x && loB.x <= hiA.x && loA.y <= hiB.y && loB.y <= hiA.y))
        return;
    // Meetings outside the domain bound no piece that counts.
    const glm::dvec2 lo = glm::max(loA, loB), hi = glm::min(hiA, hiB);
    if (!(lo.x <= m.clipHi.x && lo.y <= m.clipHi.y && hi.x >= m.clipLo.x && hi.y >= m.clipLo.y))
        return;
    const TrimArc& arcA = arcs.arcs[size_t(ia)];
    const TrimArc& arcB = arcs.arcs[size_t(ib)];
    // Consecutive arcs at their shared end point: boxes that only touch (no common area) hold
    // no other meeting, since each arc lies in its box.
    const bool joint = (A.t1 == 1.0 && B.t0 == 0.0 && arcA.end == arcB.start) ||
                       (A.t0 == 0.0 && B.t1 == 1.0 && arcA.start == arcB.end);
    const glm::dvec2 common = glm::min(hiA, hiB) - glm::max(loA, loB);
    if (joint && (common.x <= 0.0 || common.y <= 0.0))
        return;
    const double sizeA = std::max(hiA.x - loA.x, hiA.y - loA.y);
    const double sizeB = std::max(hiB.x - loB.x, hiB.y - loB.y);
    const double midA = 0.5 * (A.t0 + A.t1), midB = 0.5 * (B.t0 + B.t1);
    const bool splitA = sizeA > m.resolution && midA > A.t0 && midA < A.t1;
    const bool splitB = sizeB > m.resolution && midB > B.t0 && midB < B.t1;
    if (!splitA && !splitB) {
        double t = midA, s = midB;
        refineMeeting(arcA, A, arcB, B, t, s);
        m.at[size_t(ia)].push_back(t);
        m.at[size_t(ib)].push_back(s);
        const glm::dvec2 shared = A.t1 == 1.0 ? arcA.end : arcA.start;
        if (!joint || glm::length(0.5 * (A.a + A.b) - shared) > 1e3 * m.resolution)
            m.crossing = true;
        return;
    }
    if (splitA && (sizeA >= sizeB || !splitB)) {
        const glm::dvec2 pm = trimArcPoint(arcA, midA);
        meet(arcs, ia, {A.t0, midA, A.a, pm}, ib, B, m);
        meet(arcs, ia, {midA, A.t1, pm, A.b}, ib, B, m);
    } else {
        const glm::dvec2 pm = trimArcPoint(arcB, midB);
        meet(arcs, ia, A, ib, {B.t0, midB, B.a, pm}, m);
        meet(arcs, ia, A, ib, {midB, B.t1, pm, B.b}, m);
    }
}

Meetings arcMeetings(const TrimArcs& arcs, double resolution, glm::dvec2 clipLo,
                     glm::dvec2 clipHi) {
    Meetings m;
    m.at.resize(arcs.arcs.size());
    m.resolution = resolution;
    m.clipLo = clipLo;
    m.clipHi = clipHi;
    std::vector<int> order(arcs.arcs.size());
    std::iota(order.begin(), order.end(), 0);
    const auto lowU = [&](int k) {
        return std::min(arcs.arcs[size_t(k)].start.x, arcs.arcs[size_t(k)].end.x);
    };
    std::sort(order.begin(), order.end(), [&](int a, int b) { return lowU(a) < lowU(b); });
    for (size_t i = 0; i < order.size() && !m.cut; ++i) {
        const TrimArc& a = arcs.arcs[size_t(order[i])];
        const double hiU = std::max(a.start.x, a.end.x);
        for (size_t j = i + 1; j < order.size() && lowU(order[j]) <= hiU && !m.cut; ++j) {
            const TrimArc& b = arcs.arcs[size_t(order[j])];
            meet(arcs, order[i], {0.0, 1.0, a.start, a.end}, order[j], {0.0, 1.0, b.start, b.end},
                 m);
        }
    }
    return m;
}

/// One boundary piece of the clipped even-odd region: a span of an arc, or a straight segment
/// from p to q over [0, 1], with the orientation that keeps the region on its left.
struct SignedPiece {
    const TrimArc* arc = nullptr;
    double t0 = 0.0, t1 = 1.0;
    glm::dvec2 p{0.0}, q{0.0};
    double sign = 1.0;
};

void signedPointAndTangent(const SignedPiece& piece, double t, glm::dvec2& point, glm::dvec2& d1) {
    if (!piece.arc) {
        point = piece.p + t * (piece.q - piece.p);
        d1 = piece.q - piece.p;
        return;
    }
    arcPointAndTangent(*piece.arc, t, point, d1);
}

/// The boundary of the even-odd region of `arcs` clipped to the box [lo, hi].
/// Pieces are also cut at u = cutU[0] and cutU[1].
std::vector<SignedPiece> clippedBoundary(const TrimArcs& arcs, const Meetings& meetings,
                                         glm::dvec2 lo, glm::dvec2 hi, std::array<double, 2> cutU) {
    const double size = std::max(hi.x - lo.x, hi.y - lo.y);
    const auto inBox = [&](glm::dvec2 p) {
        return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y;
    };
    const auto contains = [&](glm::dvec2 p) {
        return trimArcsContain(arcs, p);
    };
    std::vector<SignedPiece> out;
    for (size_t k = 0; k < arcs.arcs.size(); ++k) {
        const TrimArc& arc = arcs.arcs[k];
        std::vector<double> cuts = meetings.at[k];
        for (int axis = 0; axis < 2; ++axis)
            for (double value : {lo[axis], hi[axis], cutU[0], cutU[1]})
                if ((axis == 0 || value == lo[axis] || value == hi[axis]) &&
                    std::min(arc.start[axis], arc.end[axis]) <= value &&
                    value <= std::max(arc.start[axis], arc.end[axis]))
                    cuts.push_back(trimArcSolve(arc, axis, value, 0.0, 1.0));
        cuts.push_back(0.0);
        cuts.push_back(1.0);
        std::sort(cuts.begin(), cuts.end());
        for (size_t c = 0; c + 1 < cuts.size(); ++c) {
            const double t0 = std::max(cuts[c], 0.0), t1 = std::min(cuts[c + 1], 1.0);
            if (!(t1 > t0))
                continue;
            glm::dvec2 mid, d1;
            arcPointAndTangent(arc, 0.5 * (t0 + t1), mid, d1);
            if (!inBox(mid))
                continue;
            const glm::dvec2 chord = trimArcPoint(arc, t1) - trimArcPoint(arc, t0);
            glm::dvec2 along = glm::length(d1) > 0.0 ? d1 / glm::length(d1) : glm::dvec2(0.0);
            if (!std::isfinite(along.x) || !std::isfinite(along.y) || along == glm::dvec2(0.0))
                along = glm::length(chord) > 0.0 ? chord / glm::length(chord) : glm::dvec2(0.0);
            const double eps = std::min(1e-9 * size, 0.25 * glm::length(chord));
            if (!(eps > 0.0) || along == glm::dvec2(0.0))
                continue;
            const glm::dvec2 left(-along.y, along.x);
            const double sign =
                double(contains(mid + eps * left)) - double(contains(mid - eps * left));
            if (sign != 0.0)
                out.push_back({&arc, t0, t1, {}, {}, sign});
        }
    }
    // The box's lower and upper edges (its vertical ones add nothing to -F du), counter-clockwise,
    // cut where arcs cross them; a part is boundary where the region holds both of its sides.
    for (const auto& [from, to] :
         {std::pair{lo, glm::dvec2(hi.x, lo.y)}, std::pair{hi, glm::dvec2(lo.x, hi.y)}}) {
        std::vector<double> cuts{0.0, 1.0};
        for (double u : cutU)
            if ((u - from.x) / (to.x - from.x) > 0.0 && (u - from.x) / (to.x - from.x) < 1.0)
                cuts.push_back((u - from.x) / (to.x - from.x));
        for (const TrimArc& arc : arcs.arcs)
            if (std::min(arc.start.y, arc.end.y) <= from.y &&
                from.y <= std::max(arc.start.y, arc.end.y)) {
                const double u = trimArcPoint(arc, trimArcSolve(arc, 1, from.y, 0.0, 1.0)).x;
                const double s = (u - from.x) / (to.x - from.x);
                if (s > 0.0 && s < 1.0)
                    cuts.push_back(s);
            }
        std::sort(cuts.begin(), cuts.end());
        const glm::dvec2 along = (to - from) / glm::length(to - from);
        const glm::dvec2 inward(-along.y, along.x);
        for (size_t c = 0; c + 1 < cuts.size(); ++c) {
            if (!(cuts[c + 1] > cuts[c]))
                continue;
            const glm::dvec2 a = from + cuts[c] * (to - from), b = from + cuts[c + 1] * (to - from);
            const glm::dvec2 mid = 0.5 * (a + b);
            const double eps = std::min(1e-9 * size, 0.25 * glm::length(b - a));
            if (eps > 0.0 && contains(mid + eps * inward) && contains(mid - eps * inward))
                out.push_back({nullptr, 0.0, 1.0, a, b, 1.0});
        }
    }
    return out;
}

} // namespace

FaceIntegrals faceIntegrals(const Surface& surface, const glm::dvec3& origin, double relative,
                            long budget) {
    const NurbsSurface& g = surface.geometry;
    if (!checkNurbsSurface(g))
        return {};
    const double tol = trimTolerance(g);
    const Interval du = surfaceDomainU(g), dv = surfaceDomainV(g);
    const glm::dvec2 domainLo(du.first, dv.first), domainHi(du.last, dv.last);
    const double domainSize = std::max(du.last - du.first, dv.last - dv.first);

    // Trims that cross one another or themselves, or reach past the domain, are measured by
    // their clipped even-odd boundary (clippedBoundary); disjoint loops inside the domain, as
    // every well-formed face has, by their loops as wholes, signed by orientation and nesting.
    TrimArcs arcs;
    Meetings meetings;
    bool general = false;
    if (!surface.trims.empty()) {
        // Loops the mask leaves out (invalid, overflowing or degenerate) are left out here too;
        // with none left, every point is inside, as for the mask.
        arcs = makeTrimArcs(surface.trims, tol);
        general = arcs.empty();
        if (!arcs.empty()) {
            // CAD systems write p-curves that stray past the domain within their tolerance (the
            // parts in tests/data up to ~3e-6 of it); OpenCASCADE measures such loops whole, and
            // so do we: within the trim tolerance (the mask's) a loop counts as inside. Meetings
            // are sought near the domain only, at a resolution of its size (arcs may reach
            // 1e300 away).
            const double margin = tol;
            meetings = arcMeetings(arcs, 1e-13 * domainSize, domainLo - 2.0 * margin,
                                   domainHi + 2.0 * margin);
            const bool inside =
                arcs.lo.x >= domainLo.x - margin && arcs.lo.y >= domainLo.y - margin &&
                arcs.hi.x <= domainHi.x + margin && arcs.hi.y <= domainHi.y + margin;
            general = meetings.crossing || meetings.cut || !inside;
        }
    }

    glm::dvec3 lo, hi;
    surfaceControlBounds(g, lo, hi);
    const double size = diagonal(g);
    const double reach = size + glm::length(0.5 * (lo + hi) - origin);
    // Inner: area, flux, the vector area's x y z; outer: the same and the loop's (u, v) area.
    using Inner = Sums<5>;
    using Outer = Sums<6>;
    Inner floorIn(relative * size * size);
    floorIn[1] *= reach;
    Outer floorOut;
    for (int k = 0; k < 5; ++k)
        floorOut[k] = floorIn[k];
    floorOut[5] = relative;

    std::vector<double> vKnots;
    for (double k : g.knotsV)
        if (k > dv.first && k < dv.last && (vKnots.empty() || k != vKnots.back()))
            vKnots.push_back(k);

    Quadrature q;
    q.limit = budget;
    // |Su x Sv|, (P - origin) . (Su x Sv) / 3 and Su x Sv at (u, v), clamped to the domain: loops
    // inside the domain only reach past it by rounding.
    const auto density = [&](double u, double v) {
        ++q.evaluations;
        const FirstOrder d =
            firstOrder(g, std::clamp(u, du.first, du.last), std::clamp(v, dv.first, dv.last));
        const glm::dvec3 n = glm::cross(d.su, d.sv);
        Inner r;
        r.v = {glm::length(n), glm::dot(d.s - origin, n) / 3.0, n.x, n.y, n.z};
        return r;
    };
    // F(u, v): the integral of the density along v from v0 to v, cut at the v knots.
    const auto strip = [&](double u, double v0, double v) {
        const double sign = v >= v0 ? 1.0 : -1.0;
        const double a = std::min(v0, v), b = std::max(v0, v);
        Inner sum(0.0);
        double from = a;
        const auto f = [&](double t) {
            return density(u, t);
        };
        for (double k : q.spent() ? std::vector<double>{} : vKnots)
            if (k > from && k < b) {
                sum += integrate<Inner>(f, from, k, floorIn, relative, q);
                from = k;
            }
        sum += integrate<Inner>(f, from, b, floorIn, relative, q);
        return sign * sum;
    };

    FaceIntegrals out;
    // Arcs reaching a million domains away (hostile files reach 1e300) are solved for a u or v
    // of the domain only to their own scale's precision: no exact boundary either.
    // So are arcs whose weights differ by more than double precision can follow: the point
    // stays at one end for all but the last few ulps of the parameter, and the quadrature along
    // the arc never sees it move.
    const auto extremeWeights = [](const TrimArc& a) {
        double lo = a.hw.front().z, hi = lo;
        for (const glm::dvec3& h : a.hw) {
            lo = std::min(lo, h.z);
            hi = std::max(hi, h.z);
        }
        return !(hi <= 1e12 * lo);
    };
    const bool wild = !arcs.empty() &&
                      (std::max(arcs.hi.x - arcs.lo.x, arcs.hi.y - arcs.lo.y) > 1e6 * domainSize ||
                       std::any_of(arcs.arcs.begin(), arcs.arcs.end(), extremeWeights));
    // Arcs that meet without end (coincident or cusped stretches), or wild ones: no exact
    // boundary. The estimate integrates the density over the even-odd spans of columns of the
    // domain, so it stays in [0, the untrimmed area]; flagged approximate below.
    const auto columnEstimate = [&] {
        Inner total(0.0);
        constexpr int kColumns = 16;
        const double width = (du.last - du.first) / kColumns;
        for (int c = 0; c < kColumns; ++c) {
            const auto column = [&](double u) {
                std::vector<double> at;
                for (const TrimArc& a : arcs.arcs)
                    if ((a.start.x <= u) != (a.end.x <= u))
                        at.push_back(trimArcPoint(a, trimArcSolve(a, 0, u, 0.0, 1.0)).y);
                std::sort(at.begin(), at.end());
                Inner sum(0.0);
                const auto f = [&](double v) {
                    return density(u, v);
                };
                for (size_t k = 0; k + 1 < at.size(); k += 2) {
                    const double a = std::max(at[k], dv.first), b = std::min(at[k + 1], dv.last);
                    if (b > a)
                        sum += gauss8<Inner>(f, a, b);
                }
                return sum;
            };
            const double a = du.first + c * width;
            total += gauss8<Inner>(column, a, c + 1 == kColumns ? du.last : a + width);
        }
        return total;
    };
    bool estimated = false;
    const auto keep = [&](const Inner& total) {
        out.area = total[0];
        out.volume = total[1];
        out.vectorArea = glm::dvec3(total[2], total[3], total[4]);
    };
    if (general && (meetings.cut || wild)) {
        keep(columnEstimate());
        estimated = true;
    } else if (general) {
        // One F for every piece, from the domain's lower edge: the pieces form closed curves
        // only together, so no piece may have its own reference.
        const double hair = 1e-10 * domainSize;
        const glm::dvec2 boxLo = domainLo - hair, boxHi = domainHi + hair;
        Inner total(0.0);
        for (const SignedPiece& piece :
             clippedBoundary(arcs, meetings, boxLo, boxHi, {du.first, du.last})) {
            // The hair holds no surface: F is zero left and right of the domain and constant
            // above and below it (pieces are cut at the domain's edges, so no step falls inside
            // one).
            const auto h = [&](double t) {
                glm::dvec2 uv, d1;
                signedPointAndTangent(piece, t, uv, d1);
                if (d1.x == 0.0 || !(uv.x >= du.first && uv.x <= du.last))
                    return Inner(0.0);
                return (-d1.x) * strip(uv.x, dv.first, std::clamp(uv.y, dv.first, dv.last));
            };
            total += piece.sign * integrate<Inner>(h, piece.t0, piece.t1, floorIn, relative, q);
        }
        keep(total);
        // An area below zero means the boundary was not followed (an arc the quadrature could
        // not resolve): the bounded estimate instead, flagged approximate.
        if (!(out.area >= -relative * size * size)) {
            keep(columnEstimate());
            estimated = true;
        }
    } else {
        std::vector<LoopPieces> loops;
        for (const TrimLoop& loop : surface.trims) {
            LoopPieces lp = loopPieces(loop, tol);
            if (!lp.pieces.empty() && lp.polygon.size() >= 3)
                loops.push_back(std::move(lp));
        }
        if (loops.empty())
            loops.push_back(domainLoop(g));
        std::vector<Outer> loopSums;
        for (const LoopPieces& lp : loops) {
            Outer sum(0.0);
            for (const Piece& piece : lp.pieces) {
                const auto h = [&](double t) {
                    glm::dvec2 uv, d1;
                    pointAndTangent(piece, t, uv, d1);
                    Outer r(0.0);
                    if (d1.x == 0.0)
                        return r;
                    const Inner F = strip(uv.x, lp.vLow, uv.y);
                    for (int k = 0; k < 5; ++k)
                        r[k] = -F[k] * d1.x;
                    r[5] = -(uv.y - lp.vLow) * d1.x;
                    return r;
                };
                sum += integrate<Outer>(h, piece.t0, piece.t1, floorOut, relative, q);
            }
            loopSums.push_back(sum);
        }
        // Even-odd: a loop inside an odd number of others is a hole; each loop's own interior
        // integral is its line integral times its orientation (counter-clockwise positive).
        for (size_t k = 0; k < loops.size(); ++k) {
            int depth = 0;
            for (size_t j = 0; j < loops.size(); ++j)
                if (j != k && polygonContains(loops[j].polygon, loops[k].polygon.front()))
                    ++depth;
            const double sign =
                (loopSums[k][5] >= 0.0 ? 1.0 : -1.0) * (depth % 2 == 0 ? 1.0 : -1.0);
            out.area += sign * loopSums[k][0];
            out.volume += sign * loopSums[k][1];
            out.vectorArea += sign * glm::dvec3(loopSums[k][2], loopSums[k][3], loopSums[k][4]);
        }
    }
    out.approximate = q.cut || estimated;
    out.evaluations = q.evaluations;
    // Trims whose points or tangents overflow double precision (hostile files reach 1e300)
    // give inf - inf: such a face has no measurable area, and none is reported.
    if (!std::isfinite(out.area) || !std::isfinite(out.volume) ||
        !std::isfinite(glm::length(out.vectorArea)))
        return {};
    return out;
}

bool faceBounds(const Surface& surface, glm::dvec3& lo, glm::dvec3& hi) {
    const NurbsSurface& g = surface.geometry;
    if (!checkNurbsSurface(g))
        return false;
    const Samples s = faceSamples(surface, 16);
    if (s.inside.empty() && s.boundary.empty())
        return false;
    for (int axis = 0; axis < 3; ++axis)
        for (double sign : {1.0, -1.0}) {
            // The best samples inside and on the boundary, each climbed to its local extreme.
            double best = -std::numeric_limits<double>::infinity();
            const glm::dvec2* bestInside = nullptr;
            for (const glm::dvec2& uv : s.inside) {
                const double value = sign * surfacePoint(g, uv.x, uv.y)[axis];
                if (value > best)
                    best = value, bestInside = &uv;
            }
            std::vector<std::pair<double, const Samples::OnCurve*>> edge;
            for (const Samples::OnCurve& b : s.boundary)
                edge.push_back({sign * boundaryPoint(g, *b.piece, b.t)[axis], &b});
            const size_t keep = std::min<size_t>(3, edge.size());
            std::partial_sort(edge.begin(), edge.begin() + long(keep), edge.end(),
                              [](const auto& x, const auto& y) { return x.first > y.first; });
            if (bestInside)
                best = std::max(best, refineInside(surface, s, *bestInside, axis, sign));
            for (size_t k = 0; k < keep; ++k) {
                const Samples::OnCurve& b = *edge[k].second;
                best = std::max(best,
                                refineAlongCurve(g, *b.piece, axis, sign, b.t - b.dt, b.t + b.dt));
            }
            (sign > 0 ? hi : lo)[axis] = sign * best;
        }
    return true;
}

double trimmedSurfaceArea(const NurbsSurface& surface, const std::vector<TrimLoop>& trims) {
    Surface s;
    s.geometry = surface;
    s.trims = trims;
    return faceIntegrals(s).area;
}

FaceProperties faceProperties(const Surface& surface) {
    FaceProperties p;
    p.type = surfaceType(surface);
    p.degreeU = surface.geometry.degreeU;
    p.degreeV = surface.geometry.degreeV;
    const FaceIntegrals f = faceIntegrals(surface);
    p.area = f.area;
    p.approximate = f.approximate;
    p.hasBounds = faceBounds(surface, p.lo, p.hi);
    return p;
}

FaceMeasure measureFace(const Surface& surface) {
    FaceMeasure m;
    glm::dvec3 lo, hi;
    surfaceControlBounds(surface.geometry, lo, hi);
    m.centre = 0.5 * (lo + hi);
    m.props.type = surfaceType(surface);
    m.props.degreeU = surface.geometry.degreeU;
    m.props.degreeV = surface.geometry.degreeV;
    const FaceIntegrals f = faceIntegrals(surface, m.centre);
    m.props.area = f.area;
    m.props.approximate = f.approximate;
    m.flux = f.volume;
    m.vectorArea = f.vectorArea;
    m.props.hasBounds = faceBounds(surface, m.props.lo, m.props.hi);
    return m;
}

std::vector<FaceMeasure> measureFaces(const Scene& scene, const std::vector<size_t>& indices) {
    std::vector<size_t> which = indices;
    if (which.empty())
        for (size_t k = 0; k < scene.surfaces.size(); ++k)
            which.push_back(k);
    const size_t n = which.size();
    std::vector<FaceMeasure> out(n);
    std::atomic<size_t> next{0};
    const auto work = [&] {
        for (size_t k; (k = next++) < n;)
            out[k] = measureFace(scene.surfaces[which[k]]);
    };
    const size_t threads = std::min<size_t>(std::max(1u, std::thread::hardware_concurrency()), n);
    std::vector<std::thread> pool;
    for (size_t t = 1; t < threads; ++t)
        pool.emplace_back(work);
    work();
    for (std::thread& t : pool)
        t.join();
    return out;
}

ModelProperties modelProperties(const Scene& scene) {
    return modelProperties(scene, measureFaces(scene));
}

ModelProperties modelProperties(const Scene& scene, const std::vector<FaceMeasure>& faces) {
    ModelProperties m;
    glm::dvec3 clo, chi;
    const glm::dvec3 origin = sceneBounds(scene, clo, chi) ? 0.5 * (clo + chi) : glm::dvec3(0.0);
    const std::vector<ShellState> shells = scene.topology.shells.empty()
                                               ? std::vector<ShellState>{}
                                               : closedShells(scene, seamGaps(scene));
    const size_t n = std::min(scene.surfaces.size(), faces.size());
    std::vector<double> flux(n, 0.0);
    for (size_t k = 0; k < n; ++k) {
        const FaceMeasure& f = faces[k];
        const double about = f.flux + glm::dot(f.centre - origin, f.vectorArea) / 3.0;
        flux[k] = scene.surfaces[k].outsideAlongNormal ? about : -about;
        m.faces.push_back(f.props);
        m.area += f.props.area;
        m.approximate = m.approximate || f.props.approximate;
        if (f.props.hasBounds) {
            m.lo = m.hasBounds ? glm::min(m.lo, f.props.lo) : f.props.lo;
            m.hi = m.hasBounds ? glm::max(m.hi, f.props.hi) : f.props.hi;
            m.hasBounds = true;
        }
    }
    // Signed volume per solid (cavities cancel against their outer shell), per loose shell.
    std::vector<std::pair<int, double>> solids;
    for (size_t k = 0; k < shells.size(); ++k) {
        if (!shells[k].closed)
            continue;
        double volume = 0.0;
        for (SurfaceId id : scene.topology.shells[k].faces)
            for (size_t j = 0; j < scene.surfaces.size(); ++j)
                if (j < n && scene.surfaces[j].id == id)
                    volume += flux[j];
        const int solid = shells[k].solid;
        auto it = std::find_if(solids.begin(), solids.end(),
                               [solid](const auto& p) { return solid >= 0 && p.first == solid; });
        if (it == solids.end())
            solids.push_back({solid, volume});
        else
            it->second += volume;
        ++m.closedShells;
    }
    for (const auto& [solid, volume] : solids)
        m.volume = m.volume.value_or(0.0) + std::abs(volume);
    return m;
}

} // namespace kw
