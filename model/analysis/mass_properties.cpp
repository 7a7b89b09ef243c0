// Area, volume flux and bounds of trimmed faces by quadrature on the exact geometry.
#include "model/analysis/mass_properties.h"

#include "model/document/seamgaps.h"
#include "model/nurbs/trim.h"
#include "model/nurbs/visible_bounds.h"
#include "model/nurbs/trim_arcs.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
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

// Halves [a, b] until the two halves' sum agrees with the whole within `relative` of itself or
// `floor` (absolute, shared out over the halves), component by component.
template <class V, class F>
V adaptive(const F& f, double a, double b, const V& whole, const V& floor, double relative,
           int depth) {
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
    return adaptive<V>(f, a, m, left, 0.5 * floor, relative, depth - 1) +
           adaptive<V>(f, m, b, right, 0.5 * floor, relative, depth - 1);
}

template <class V, class F>
V integrate(const F& f, double a, double b, const V& floor, double relative) {
    if (!(b > a))
        return V(0.0);
    return adaptive<V>(f, a, b, gauss8<V>(f, a, b), floor, relative, kMaxDepth);
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
        if (curveValidationError(c).empty())
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

} // namespace

FaceIntegrals faceIntegrals(const Surface& surface, const glm::dvec3& origin, double relative) {
    const NurbsSurface& g = surface.geometry;
    if (!surfaceValidationError(g).empty())
        return {};
    const double tol = trimTolerance(g);
    std::vector<LoopPieces> loops;
    for (const TrimLoop& loop : surface.trims) {
        LoopPieces lp = loopPieces(loop, tol);
        if (!lp.pieces.empty() && lp.polygon.size() >= 3)
            loops.push_back(std::move(lp));
    }
    if (loops.empty())
        loops.push_back(domainLoop(g));

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
    const Interval dv = surfaceDomainV(g);
    for (double k : g.knotsV)
        if (k > dv.first && k < dv.last && (vKnots.empty() || k != vKnots.back()))
            vKnots.push_back(k);

    // |Su x Sv|, (P - origin) . (Su x Sv) / 3 and Su x Sv at (u, v), clamped to the domain.
    const Interval du = surfaceDomainU(g);
    const auto density = [&](double u, double v) {
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
        for (double k : vKnots)
            if (k > from && k < b) {
                sum += integrate<Inner>(f, from, k, floorIn, relative);
                from = k;
            }
        sum += integrate<Inner>(f, from, b, floorIn, relative);
        return sign * sum;
    };

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
            sum += integrate<Outer>(h, piece.t0, piece.t1, floorOut, relative);
        }
        loopSums.push_back(sum);
    }
    // Even-odd: a loop inside an odd number of others is a hole; each loop's own interior
    // integral is its line integral times its orientation (counter-clockwise positive).
    FaceIntegrals out;
    for (size_t k = 0; k < loops.size(); ++k) {
        int depth = 0;
        for (size_t j = 0; j < loops.size(); ++j)
            if (j != k && polygonContains(loops[j].polygon, loops[k].polygon.front()))
                ++depth;
        const double sign = (loopSums[k][5] >= 0.0 ? 1.0 : -1.0) * (depth % 2 == 0 ? 1.0 : -1.0);
        out.area += sign * loopSums[k][0];
        out.volume += sign * loopSums[k][1];
        out.vectorArea += sign * glm::dvec3(loopSums[k][2], loopSums[k][3], loopSums[k][4]);
    }
    // Trims whose points or tangents overflow double precision (hostile files reach 1e300)
    // give inf - inf: such a face has no measurable area, and none is reported.
    if (!std::isfinite(out.area) || !std::isfinite(out.volume) ||
        !std::isfinite(glm::length(out.vectorArea)))
        return {};
    return out;
}

bool faceBounds(const Surface& surface, glm::dvec3& lo, glm::dvec3& hi) {
    const NurbsSurface& g = surface.geometry;
    if (!surfaceValidationError(g).empty())
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
    p.area = faceIntegrals(surface).area;
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
