// Second-derivative bounds from derivative control nets, the Filip-Magedson-Markot cell bound,
// its projection to pixels and the partitions it implies.
#include "render/surface_bound.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace kw {
namespace {

/// The NURBS Book A3.3 (CurveDerivCpts), restricted to the p+1 points P[span-p .. span] that
/// act on knot span `span`: after `order` steps, point r of the result is the r-th derivative
/// control point of that span (their basis functions of degree p-order are non-negative and sum
/// to one there). Empty when order > p (the derivative vanishes on the span).
std::vector<glm::dvec4> spanDerivativeNet(std::vector<glm::dvec4> pts, int span, int p,
                                          const std::vector<double>& knots, int order) {
    for (int k = 1; k <= order; ++k) {
        if (k > p)
            return {};
        std::vector<glm::dvec4> next(pts.size() - 1);
        for (size_t r = 0; r + 1 < pts.size(); ++r) {
            const int i = span - p + int(r);
            // U[i+p+1] >= U[span+1] > U[span] >= U[i+k]: positive for a non-empty span.
            const double d = knots[size_t(i + p + 1)] - knots[size_t(i + k)];
            next[r] = double(p - k + 1) * (pts[r + 1] - pts[r]) / d;
        }
        pts = std::move(next);
    }
    return pts;
}

/// Blossom of the degree-p B-spline segment on knot span `span` with control points
/// d[0..p] (global indices span-p .. span): de Boor's algorithm with argument args[r-1] at
/// level r (symmetric in the arguments, Ramshaw 1989). d is overwritten.
glm::dvec4 blossom(glm::dvec4* d, int span, int p, const std::vector<double>& knots,
                   const double* args) {
    for (int r = 1; r <= p; ++r)
        for (int j = p; j >= r; --j) {
            const int i = span - p + j;
            const double a0 = knots[size_t(i)], a1 = knots[size_t(i + p + 1 - r)];
            const double alpha = (args[r - 1] - a0) / (a1 - a0);
            d[j] = (1.0 - alpha) * d[j - 1] + alpha * d[j];
        }
    return d[p];
}

/// The Bezier points of the segment over [t0, t1] inside the span: blossoms at t0^(p-a) t1^a.
std::vector<glm::dvec4> bezierPoints(const std::vector<glm::dvec4>& pts, int span, int p,
                                     const std::vector<double>& knots, double t0, double t1) {
    std::vector<glm::dvec4> out(size_t(p + 1));
    double args[kMaxDegree];
    for (int a = 0; a <= p; ++a) {
        for (int r = 0; r < p; ++r)
            args[r] = r < p - a ? t0 : t1;
        std::vector<glm::dvec4> d = pts;
        out[size_t(a)] = blossom(d.data(), span, p, knots, args);
    }
    return out;
}

struct NetNorms {
    double xyz = 0.0; ///< max |(x, y, z)| over the derivative net
    double w = 0.0;   ///< max |w|
};

/// A Bezier patch (p+1) x (q+1), point (a, b) at b * (p+1) + a, on [u0, u1] x [v0, v1].
struct BezierPatch {
    int p = 1, q = 1;
    std::vector<double> knotsU, knotsV; ///< u0^(p+1) u1^(p+1), likewise v
    std::vector<glm::dvec4> pts;
};

/// Norm bounds of d^(ku+kv) Pw / du^ku dv^kv over the patch, from its tensor derivative net.
NetNorms derivativeNorms(const BezierPatch& bz, int ku, int kv) {
    const int pu = bz.p, pv = bz.q;
    std::vector<std::vector<glm::dvec4>> columns(size_t(pv + 1));
    for (int b = 0; b <= pv; ++b) {
        std::vector<glm::dvec4> col(bz.pts.begin() + b * (pu + 1),
                                    bz.pts.begin() + (b + 1) * (pu + 1));
        columns[size_t(b)] = spanDerivativeNet(std::move(col), pu, pu, bz.knotsU, ku);
        if (columns[size_t(b)].empty())
            return {};
    }
    NetNorms out;
    const size_t rows = columns[0].size();
    for (size_t a = 0; a < rows; ++a) {
        std::vector<glm::dvec4> row(size_t(pv + 1));
        for (int b = 0; b <= pv; ++b)
            row[size_t(b)] = columns[size_t(b)][a];
        for (const glm::dvec4& q : spanDerivativeNet(std::move(row), pv, pv, bz.knotsV, kv)) {
            out.xyz = std::max(out.xyz, glm::length(glm::dvec3(q)));
            out.w = std::max(out.w, std::abs(q.w));
        }
    }
    return out;
}

/// The homogeneous Bezier patch of the rectangle, with its Cartesian control bounds.
BezierPatch extractPatch(const NurbsSurface& s, int spanU, int spanV, double u0, double u1,
                         double v0, double v1, glm::dvec3& lo, glm::dvec3& hi) {
    const int pu = s.degreeU, pv = s.degreeV;
    BezierPatch bz;
    bz.p = pu;
    bz.q = pv;
    bz.knotsU.assign(size_t(pu + 1), u0);
    bz.knotsU.insert(bz.knotsU.end(), size_t(pu + 1), u1);
    bz.knotsV.assign(size_t(pv + 1), v0);
    bz.knotsV.insert(bz.knotsV.end(), size_t(pv + 1), v1);
    // Rows along u first (each v index of the span), then every resulting column along v.
    std::vector<std::vector<glm::dvec4>> rows(size_t(pv + 1));
    for (int b = 0; b <= pv; ++b) {
        std::vector<glm::dvec4> row(size_t(pu + 1));
        for (int a = 0; a <= pu; ++a) {
            const size_t idx = size_t(s.index(spanU - pu + a, spanV - pv + b));
            row[size_t(a)] = glm::dvec4(s.points[idx] * s.weights[idx], s.weights[idx]);
        }
        rows[size_t(b)] = bezierPoints(row, spanU, pu, s.knotsU, u0, u1);
    }
    bz.pts.resize(size_t((pu + 1) * (pv + 1)));
    for (int a = 0; a <= pu; ++a) {
        std::vector<glm::dvec4> col(size_t(pv + 1));
        for (int b = 0; b <= pv; ++b)
            col[size_t(b)] = rows[size_t(b)][size_t(a)];
        const std::vector<glm::dvec4> bzCol = bezierPoints(col, spanV, pv, s.knotsV, v0, v1);
        for (int b = 0; b <= pv; ++b)
            bz.pts[size_t(b * (pu + 1) + a)] = bzCol[size_t(b)];
    }
    for (size_t k = 0; k < bz.pts.size(); ++k) {
        const glm::dvec3 p = glm::dvec3(bz.pts[k]) / bz.pts[k].w;
        lo = k == 0 ? p : glm::min(lo, p);
        hi = k == 0 ? p : glm::max(hi, p);
    }
    return bz;
}

SecondDerivativeBound patchBound(BezierPatch bz, const glm::dvec3& lo, const glm::dvec3& hi) {
    // Translating by the centre c keeps |S - c| (and so the quotient-rule terms) small.
    const glm::dvec3 c = 0.5 * (lo + hi);
    double a0 = 0.0, wMin = 0.0;
    for (size_t k = 0; k < bz.pts.size(); ++k) {
        glm::dvec4& q = bz.pts[k];
        const glm::dvec3 p = glm::dvec3(q) / q.w - c;
        a0 = std::max(a0, glm::length(p));
        wMin = k == 0 ? q.w : std::min(wMin, q.w);
        q = glm::dvec4(p * q.w, q.w);
    }
    const NetNorms hu = derivativeNorms(bz, 1, 0);
    const NetNorms hv = derivativeNorms(bz, 0, 1);
    const NetNorms huu = derivativeNorms(bz, 2, 0);
    const NetNorms huv = derivativeNorms(bz, 1, 1);
    const NetNorms hvv = derivativeNorms(bz, 0, 2);
    const double su = (hu.xyz + hu.w * a0) / wMin;
    const double sv = (hv.xyz + hv.w * a0) / wMin;
    SecondDerivativeBound m;
    m.uu = (huu.xyz + 2.0 * hu.w * su + huu.w * a0) / wMin;
    m.uv = (huv.xyz + hu.w * sv + hv.w * su + huv.w * a0) / wMin;
    m.vv = (hvv.xyz + 2.0 * hv.w * sv + hvv.w * a0) / wMin;
    return m;
}

} // namespace

SecondDerivativeBound rectSecondDerivativeBound(const NurbsSurface& s, int spanU, int spanV,
                                                double u0, double u1, double v0, double v1) {
    glm::dvec3 lo, hi;
    const BezierPatch bz = extractPatch(s, spanU, spanV, u0, u1, v0, v1, lo, hi);
    return patchBound(bz, lo, hi);
}

SecondDerivativeBound spanSecondDerivativeBound(const NurbsSurface& s, int spanU, int spanV) {
    return rectSecondDerivativeBound(s, spanU, spanV, s.knotsU[size_t(spanU)],
                                     s.knotsU[size_t(spanU + 1)], s.knotsV[size_t(spanV)],
                                     s.knotsV[size_t(spanV + 1)]);
}

double cellDeviationBound(const SecondDerivativeBound& m, double du, double dv) {
    return (m.uu * du * du + 2.0 * m.uv * du * dv + m.vv * dv * dv) / 8.0;
}

ScreenScale screenScale(const Camera& camera, int width, int height, double nearDepth) {
    ScreenScale sc;
    sc.eye = camera.eye;
    glm::dvec3 forward = camera.target - camera.eye;
    if (glm::length(forward) < 1e-300)
        forward = glm::dvec3(0.0, 1.0, 0.0);
    sc.forward = glm::normalize(forward);
    const double tanHalfY =
        std::tan(glm::radians(std::clamp(camera.fovYDegrees, 1.0, 170.0)) * 0.5);
    const double aspect = double(std::max(width, 1)) / double(std::max(height, 1));
    sc.focalPixels = 0.5 * double(std::max(height, 1)) / tanHalfY;
    sc.tanHalfDiagonal = tanHalfY * std::sqrt(1.0 + aspect * aspect);
    sc.nearDepth = std::max(nearDepth, 1e-300);
    return sc;
}

double screenDistanceBound(const ScreenScale& scale, double distance, double minDepth) {
    const double z = std::max(minDepth, scale.nearDepth);
    return scale.focalPixels * distance *
           std::sqrt(1.0 + scale.tanHalfDiagonal * scale.tanHalfDiagonal) / z;
}

bool boxOutsideFrustum(const glm::dmat4& viewProjection, const glm::dvec3& lo,
                       const glm::dvec3& hi) {
    int outside[6] = {0, 0, 0, 0, 0, 0};
    for (int k = 0; k < 8; ++k) {
        const glm::dvec4 c =
            viewProjection *
            glm::dvec4((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z, 1.0);
        outside[0] += c.x < -c.w;
        outside[1] += c.x > c.w;
        outside[2] += c.y < -c.w;
        outside[3] += c.y > c.w;
        outside[4] += c.z < -c.w;
        outside[5] += c.z > c.w;
    }
    return std::any_of(outside, outside + 6, [](int n) { return n == 8; });
}

double boxMinDepth(const ScreenScale& scale, const glm::dvec3& lo, const glm::dvec3& hi) {
    double best = 0.0;
    for (int k = 0; k < 8; ++k) {
        const glm::dvec3 p((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
        const double d = glm::dot(p - scale.eye, scale.forward);
        best = k == 0 ? d : std::min(best, d);
    }
    return best;
}

double boxMinDepthInFrustum(const ScreenScale& scale, const glm::dvec3& lo, const glm::dvec3& hi) {
    // The half-spaces n.p + c >= 0 of the four side planes (rows w +- x, w +- y of the clip
    // transform) and of the near plane (depth >= nearDepth).
    const glm::dmat4& m = scale.viewProjection;
    const auto row = [&](int r) {
        return glm::dvec4(m[0][r], m[1][r], m[2][r], m[3][r]);
    };
    const glm::dvec4 planes[5] = {
        row(3) + row(0), row(3) - row(0), row(3) + row(1), row(3) - row(1),
        glm::dvec4(scale.forward, -glm::dot(scale.forward, scale.eye) - scale.nearDepth)};
    const auto side = [](const glm::dvec4& pl, const glm::dvec3& p) {
        return glm::dot(glm::dvec3(pl), p) + pl.w;
    };
    const auto depth = [&](const glm::dvec3& p) {
        return glm::dot(p - scale.eye, scale.forward);
    };
    double best = std::numeric_limits<double>::infinity();
    // The least of a linear function over the convex polytope box & frustum is at one of its
    // vertices: each lies on a face of the box (found by clipping that face to the five
    // half-spaces, Sutherland-Hodgman) or is a corner of the near rectangle inside the box.
    const glm::dvec3 c[2] = {lo, hi};
    for (int axis = 0; axis < 3; ++axis)
        for (int end = 0; end < 2; ++end) {
            const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
            std::vector<glm::dvec3> poly;
            for (int k = 0; k < 4; ++k) {
                glm::dvec3 p;
                p[axis] = c[end][axis];
                p[a1] = c[(k == 1 || k == 2) ? 1 : 0][a1];
                p[a2] = c[k >= 2 ? 1 : 0][a2];
                poly.push_back(p);
            }
            for (const glm::dvec4& pl : planes) {
                std::vector<glm::dvec3> next;
                for (size_t i = 0; i < poly.size(); ++i) {
                    const glm::dvec3 &p = poly[i], &q = poly[(i + 1) % poly.size()];
                    const double sp = side(pl, p), sq = side(pl, q);
                    if (sp >= 0.0)
                        next.push_back(p);
                    if ((sp >= 0.0) != (sq >= 0.0))
                        next.push_back(p + (q - p) * (sp / (sp - sq)));
                }
                poly = std::move(next);
                if (poly.empty())
                    break;
            }
            for (const glm::dvec3& p : poly)
                best = std::min(best, depth(p));
        }
    for (int k = 0; k < 4; ++k) {
        const glm::dvec4 px = planes[k & 1], py = planes[2 + (k >> 1)], pn = planes[4];
        const glm::dmat3 a =
            glm::transpose(glm::dmat3(glm::dvec3(px), glm::dvec3(py), glm::dvec3(pn)));
        if (std::abs(glm::determinant(a)) < 1e-300)
            continue;
        const glm::dvec3 p = glm::inverse(a) * -glm::dvec3(px.w, py.w, pn.w);
        if (glm::all(glm::greaterThanEqual(p, lo)) && glm::all(glm::lessThanEqual(p, hi)))
            best = std::min(best, depth(p));
    }
    return best;
}

bool surfaceIsAffine(const NurbsSurface& s, double relTolerance) {
    const int n = s.countU, m = s.countV;
    if (n < 2 || m < 2 || s.points.size() != size_t(n) * size_t(m) ||
        s.weights.size() != s.points.size())
        return false;
    const double w0 = s.weights[0];
    for (double w : s.weights)
        if (!(std::abs(w - w0) <= relTolerance * std::abs(w0)))
            return false;
    glm::dvec3 lo = s.points[0], hi = s.points[0];
    for (const glm::dvec3& p : s.points)
        lo = glm::min(lo, p), hi = glm::max(hi, p);
    const double extent = glm::length(hi - lo);
    if (!(extent > 0.0) || !std::isfinite(extent))
        return false;
    std::vector<double> xi(static_cast<size_t>(n)), eta(static_cast<size_t>(m));
    for (int i = 0; i < n; ++i)
        xi[size_t(i)] = grevilleAbscissa(s.knotsU, s.degreeU, i);
    for (int j = 0; j < m; ++j)
        eta[size_t(j)] = grevilleAbscissa(s.knotsV, s.degreeV, j);
    const double spanU = xi.back() - xi.front(), spanV = eta.back() - eta.front();
    if (!(spanU > 0.0) || !(spanV > 0.0))
        return false;
    // A, B and C from three corners of the net; every point must then agree.
    const glm::dvec3 p00 = s.points[size_t(s.index(0, 0))];
    const glm::dvec3 b = (s.points[size_t(s.index(n - 1, 0))] - p00) / spanU;
    const glm::dvec3 c = (s.points[size_t(s.index(0, m - 1))] - p00) / spanV;
    const double tolerance = relTolerance * extent;
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < n; ++i) {
            const glm::dvec3 q = p00 + b * (xi[size_t(i)] - xi[0]) + c * (eta[size_t(j)] - eta[0]);
            if (!(glm::length(s.points[size_t(s.index(i, j))] - q) <= tolerance))
                return false;
        }
    return true;
}

std::vector<SpanBound> surfaceSpanBounds(const NurbsSurface& s, int grid) {
    grid = std::clamp(grid, 1, 16);
    std::vector<SpanBound> out;
    const int pu = s.degreeU, pv = s.degreeV;
    for (int ku = pu; ku < s.countU; ++ku) {
        if (!(s.knotsU[size_t(ku)] < s.knotsU[size_t(ku + 1)]))
            continue;
        for (int kv = pv; kv < s.countV; ++kv) {
            if (!(s.knotsV[size_t(kv)] < s.knotsV[size_t(kv + 1)]))
                continue;
            SpanBound b;
            b.spanU = ku;
            b.spanV = kv;
            b.u0 = s.knotsU[size_t(ku)];
            b.u1 = s.knotsU[size_t(ku + 1)];
            b.v0 = s.knotsV[size_t(kv)];
            b.v1 = s.knotsV[size_t(kv + 1)];
            b.grid = grid;
            b.subs.resize(size_t(grid * grid));
            for (int j = 0; j < grid; ++j)
                for (int i = 0; i < grid; ++i) {
                    // The sides chooseBreaks cuts the partition at: a break falls on a bounded
                    // sub-rectangle's edge to the last bit.
                    SpanBound::Sub& sub = b.subs[size_t(j * grid + i)];
                    const BezierPatch bz = extractPatch(s, ku, kv, b.sideU(i), b.sideU(i + 1),
                                                        b.sideV(j), b.sideV(j + 1), sub.lo, sub.hi);
                    sub.m = patchBound(bz, sub.lo, sub.hi);
                }
            out.push_back(std::move(b));
        }
    }
    return out;
}

namespace {

struct SpanScore {
    double pixels = 0.0; ///< screen bound of the worst cell
    double uPart = 0.0;  ///< share of the u terms there (uu du^2 + uv du dv)
    double vPart = 0.0;
    double du = 0.0, dv = 0.0;
};

/// The smallest n in [lo, hi] with ok(n), for ok monotone (false below some n, true from it
/// on) and ok(hi) true.
template <class Ok> int smallestPassing(int lo, int hi, Ok ok) {
    while (lo < hi) {
        const int mid = lo + (hi - lo) / 2;
        if (ok(mid))
            hi = mid;
        else
            lo = mid + 1;
    }
    return hi;
}

double boxMaxDepth(const ScreenScale& scale, const glm::dvec3& lo, const glm::dvec3& hi) {
    ScreenScale backwards = scale;
    backwards.forward = -scale.forward;
    return -boxMinDepth(backwards, lo, hi);
}

/// The worst cell bound of a span at (nu, nv). Cells are at most 1/n of the domain (the
/// uniform breaks) and inside one span, so a cell touching sub-rectangle (a, b) lies inside
/// the sub-rectangles within reach (ceil(du / sub width)) of it: their largest derivative
/// bounds and smallest depth hold over the whole cell. Sub-rectangles whose control bounds lie
/// wholly behind the near plane are never drawn and score 0, and so do those never on screen
/// (ScreenScale::cullOutsideView).
SpanScore scoreSpan(const SpanBound& b, const Interval& domU, const Interval& domV,
                    const ScreenScale& scale, int nu, int nv) {
    SpanScore worst;
    const double du = std::min(b.u1 - b.u0, (domU.last - domU.first) / double(nu));
    const double dv = std::min(b.v1 - b.v0, (domV.last - domV.first) / double(nv));
    const int g = b.grid;
    const int ru = std::min(g, int(std::ceil(du / ((b.u1 - b.u0) / g) - 1e-9)));
    const int rv = std::min(g, int(std::ceil(dv / ((b.v1 - b.v0) / g) - 1e-9)));
    for (int j = 0; j < g; ++j)
        for (int i = 0; i < g; ++i) {
            const SpanBound::Sub& self = b.subs[size_t(j * g + i)];
            if (boxMaxDepth(scale, self.lo, self.hi) < scale.nearDepth)
                continue;
            SecondDerivativeBound m;
            double minDepth = 0.0;
            bool first = true;
            for (int y = std::max(0, j - rv); y <= std::min(g - 1, j + rv); ++y)
                for (int x = std::max(0, i - ru); x <= std::min(g - 1, i + ru); ++x) {
                    const SpanBound::Sub& o = b.subs[size_t(y * g + x)];
                    m.uu = std::max(m.uu, o.m.uu);
                    m.uv = std::max(m.uv, o.m.uv);
                    m.vv = std::max(m.vv, o.m.vv);
                    const double d = boxMinDepth(scale, o.lo, o.hi);
                    minDepth = first ? d : std::min(minDepth, d);
                    first = false;
                }
            const double deviation = cellDeviationBound(m, du, dv);
            // Never on screen: every polygon point over this sub-rectangle lies within
            // `deviation` of the surface there, so inside its bounds grown by that much.
            if (scale.cullOutsideView &&
                boxOutsideFrustum(scale.viewProjection, self.lo - glm::dvec3(deviation),
                                  self.hi + glm::dvec3(deviation)))
                continue;
            if (minDepth < scale.nearDepth && scale.cullOutsideView) {
                // Bounds reaching past the near plane: the depth of what is in view.
                double inView = std::numeric_limits<double>::infinity();
                for (int y = std::max(0, j - rv); y <= std::min(g - 1, j + rv); ++y)
                    for (int x = std::max(0, i - ru); x <= std::min(g - 1, i + ru); ++x) {
                        const SpanBound::Sub& o = b.subs[size_t(y * g + x)];
                        inView = std::min(inView, boxMinDepthInFrustum(scale, o.lo, o.hi));
                    }
                if (inView == std::numeric_limits<double>::infinity())
                    continue;
                minDepth = std::max(minDepth, inView - deviation);
            }
            const double px = screenDistanceBound(scale, deviation, minDepth);
            if (px > worst.pixels) {
                worst.pixels = px;
                worst.uPart = m.uu * du * du + m.uv * du * dv;
                worst.vPart = m.vv * dv * dv + m.uv * du * dv;
                worst.du = du;
                worst.dv = dv;
            }
        }
    return worst;
}

} // namespace

double partitionBoundPixels(const std::vector<SpanBound>& spans, const Interval& domainU,
                            const Interval& domainV, const ScreenScale& scale, int nu, int nv) {
    double worst = 0.0;
    for (const SpanBound& b : spans)
        worst = std::max(worst, scoreSpan(b, domainU, domainV, scale, nu, nv).pixels);
    return worst;
}

PartitionChoice choosePartitions(const std::vector<SpanBound>& spans, const Interval& domainU,
                                 const Interval& domainV, const ScreenScale& scale,
                                 double pixelTolerance, int minU, int minV) {
    PartitionChoice c;
    const int lowU = std::clamp(minU, kMinPartitions, kMaxPartitions);
    const int lowV = std::clamp(minV, kMinPartitions, kMaxPartitions);
    c.nu = lowU;
    c.nv = lowV;
    const double widthU = domainU.last - domainU.first;
    const double widthV = domainV.last - domainV.first;
    auto worstAt = [&](int nu, int nv) {
        SpanScore worst;
        for (const SpanBound& b : spans) {
            const SpanScore sc = scoreSpan(b, domainU, domainV, scale, nu, nv);
            if (sc.pixels > worst.pixels)
                worst = sc;
        }
        return worst;
    };
    // 1. Grow. The bound is quadratic in the cell size: shrinking a direction's cells by
    // sqrt(excess) removes the excess of its own terms; both shrink when both matter.
    for (;;) {
        const SpanScore worst = worstAt(c.nu, c.nv);
        c.boundPixels = worst.pixels;
        if (!(worst.pixels > pixelTolerance))
            break;
        const bool canU = c.nu < kMaxPartitions, canV = c.nv < kMaxPartitions;
        if (!canU && !canV) {
            c.met = false;
            return c;
        }
        const double shrink = std::sqrt(worst.pixels / pixelTolerance);
        const double total = worst.uPart + worst.vPart;
        const bool growU = canU && (worst.uPart >= 0.25 * total || !canV);
        const bool growV = canV && (worst.vPart >= 0.25 * total || !canU);
        if (growU) {
            const double target = std::ceil(widthU / (worst.du / shrink));
            c.nu = int(std::clamp(target, double(c.nu + 1), double(kMaxPartitions)));
        }
        if (growV) {
            const double target = std::ceil(widthV / (worst.dv / shrink));
            c.nv = int(std::clamp(target, double(c.nv + 1), double(kMaxPartitions)));
        }
    }
    // 2. Trim the overshoot: the bound only grows as n falls (cells are min(span, 1/n)), so
    // bisect the smallest nu with nv fixed, then the smallest nv.
    c.nu = smallestPassing(lowU, c.nu,
                           [&](int n) { return worstAt(n, c.nv).pixels <= pixelTolerance; });
    c.nv = smallestPassing(lowV, c.nv,
                           [&](int n) { return worstAt(c.nu, n).pixels <= pixelTolerance; });
    c.boundPixels = worstAt(c.nu, c.nv).pixels;
    c.met = true;
    return c;
}

namespace {
/// The most cells chooseBreaks gives one surface: as many as the uniform choice's largest.
constexpr std::int64_t kMaxCells = std::int64_t(kMaxPartitions) * kMaxPartitions;
} // namespace

PartitionChoice chooseBreaks(const std::vector<SpanBound>& spans, const Interval& boxU,
                             const Interval& boxV, const ScreenScale& scale, double pixelTolerance,
                             int minU, int minV) {
    PartitionChoice c;
    const Interval box[2] = {boxU, boxV};
    const int minimum[2] = {std::clamp(minU, kMinPartitions, kMaxPartitions),
                            std::clamp(minV, kMinPartitions, kMaxPartitions)};
    // 1. Columns (d = 0) and rows (d = 1): the sub-rectangles' sides inside the box
    // (SpanBound::sideU / sideV, as surfaceSpanBounds bounds them).
    std::vector<double> edges[2];
    for (int d = 0; d < 2; ++d) {
        edges[d] = {box[d].first, box[d].last};
        for (const SpanBound& b : spans)
            for (int i = 0; i <= b.grid; ++i) {
                const double t = d == 0 ? b.sideU(i) : b.sideV(i);
                if (t > box[d].first && t < box[d].last)
                    edges[d].push_back(t);
            }
        std::sort(edges[d].begin(), edges[d].end());
        edges[d].erase(std::unique(edges[d].begin(), edges[d].end()), edges[d].end());
    }
    const int lanes[2] = {int(edges[0].size()) - 1, int(edges[1].size()) - 1};
    if (lanes[0] < 1 || lanes[1] < 1 || !(pixelTolerance > 0.0)) {
        c.met = false;
        return c;
    }
    std::vector<double> width[2];
    std::vector<int> count[2], low[2];
    for (int d = 0; d < 2; ++d) {
        const double whole = box[d].last - box[d].first;
        for (int k = 0; k < lanes[d]; ++k) {
            const double w = edges[d][size_t(k + 1)] - edges[d][size_t(k)];
            const int lo = std::max(1, int(std::ceil(w * minimum[d] / whole - 1e-9)));
            width[d].push_back(w); // lo <= minimum[d] <= kMaxPartitions
            low[d].push_back(lo);
        }
        count[d] = low[d];
    }
    // 2. One entry per sub-rectangle inside the box: its column, row, bounds and depth.
    struct Entry {
        int lane[2];
        SecondDerivativeBound m;
        glm::dvec3 lo, hi;
        double minDepth;
        /// The least depth of the part of the bounds in view (boxMinDepthInFrustum), where
        /// they reach past the near plane; else minDepth.
        double inViewDepth;
    };
    std::vector<Entry> entries;
    std::vector<std::vector<int>> byLane[2];
    byLane[0].resize(size_t(lanes[0]));
    byLane[1].resize(size_t(lanes[1]));
    for (const SpanBound& b : spans)
        for (int j = 0; j < b.grid; ++j)
            for (int i = 0; i < b.grid; ++i) {
                const double u0 = std::max(b.sideU(i), box[0].first);
                const double u1 = std::min(b.sideU(i + 1), box[0].last);
                const double v0 = std::max(b.sideV(j), box[1].first);
                const double v1 = std::min(b.sideV(j + 1), box[1].last);
                if (!(u0 < u1 && v0 < v1))
                    continue;
                const SpanBound::Sub& s = b.subs[size_t(j * b.grid + i)];
                if (boxMaxDepth(scale, s.lo, s.hi) < scale.nearDepth)
                    continue; // wholly behind the near plane: never drawn
                Entry e;
                e.lane[0] =
                    int(std::lower_bound(edges[0].begin(), edges[0].end(), u0) - edges[0].begin());
                e.lane[1] =
                    int(std::lower_bound(edges[1].begin(), edges[1].end(), v0) - edges[1].begin());
                e.m = s.m;
                e.lo = s.lo;
                e.hi = s.hi;
                e.minDepth = boxMinDepth(scale, s.lo, s.hi);
                e.inViewDepth = e.minDepth < scale.nearDepth && scale.cullOutsideView
                                    ? boxMinDepthInFrustum(scale, s.lo, s.hi)
                                    : e.minDepth;
                byLane[0][size_t(e.lane[0])].push_back(int(entries.size()));
                byLane[1][size_t(e.lane[1])].push_back(int(entries.size()));
                entries.push_back(e);
            }
    // The screen bound of an entry's cells at the current counts (0 when never on screen).
    struct Score {
        double pixels = 0.0, uPart = 0.0, vPart = 0.0, du = 0.0, dv = 0.0;
        /// The bound at the depth in view itself: the growth's estimate, since near the eye
        /// the bound of coarse cells is far past quadratic (their deviation eats the depth).
        double growPixels = 0.0;
    };
    const auto score = [&](const Entry& e) {
        Score sc;
        sc.du = width[0][size_t(e.lane[0])] / count[0][size_t(e.lane[0])];
        sc.dv = width[1][size_t(e.lane[1])] / count[1][size_t(e.lane[1])];
        const double deviation = cellDeviationBound(e.m, sc.du, sc.dv);
        if (scale.cullOutsideView &&
            boxOutsideFrustum(scale.viewProjection, e.lo - glm::dvec3(deviation),
                              e.hi + glm::dvec3(deviation)))
            return sc;
        // Bounds reaching past the near plane (where minDepth is no bound at all): a polygon
        // point drawn lies in the view, so at inViewDepth or deeper, and the surface point
        // it stands for within `deviation` of it.
        if (e.inViewDepth == std::numeric_limits<double>::infinity())
            return sc;
        sc.pixels =
            screenDistanceBound(scale, deviation, std::max(e.minDepth, e.inViewDepth - deviation));
        sc.growPixels = e.inViewDepth > e.minDepth
                            ? screenDistanceBound(scale, deviation, e.inViewDepth)
                            : sc.pixels;
        sc.uPart = e.m.uu * sc.du * sc.du + e.m.uv * sc.du * sc.dv;
        sc.vPart = e.m.vv * sc.dv * sc.dv + e.m.uv * sc.du * sc.dv;
        return sc;
    };
    // 3. Grow: each cell over the tolerance asks its column and row for cells sqrt(excess)
    // times smaller (the bound is quadratic in the cell size), the direction(s) that matter.
    c.met = true;
    c.cellsInOneSub = true;
    for (;;) {
        std::vector<int> want[2] = {count[0], count[1]};
        bool over = false;
        for (const Entry& e : entries) {
            const Score sc = score(e);
            if (!(sc.pixels > pixelTolerance))
                continue;
            over = true;
            const int ku = e.lane[0], kv = e.lane[1];
            const bool canU = count[0][size_t(ku)] < kMaxPartitions;
            const bool canV = count[1][size_t(kv)] < kMaxPartitions;
            const double shrink = std::max(std::sqrt(sc.growPixels / pixelTolerance), 1.25);
            const double total = sc.uPart + sc.vPart;
            const auto grow = [&](int d, int k, double cell) {
                const double target = std::ceil(width[d][size_t(k)] / (cell / shrink));
                const int n = int(
                    std::clamp(target, double(count[d][size_t(k)] + 1), double(kMaxPartitions)));
                want[d][size_t(k)] = std::max(want[d][size_t(k)], n);
            };
            if (canU && (sc.uPart >= 0.25 * total || !canV))
                grow(0, ku, sc.du);
            if (canV && (sc.vPart >= 0.25 * total || !canU))
                grow(1, kv, sc.dv);
        }
        if (!over)
            break;
        const auto total = [](const std::vector<int>& n) {
            return std::int64_t(std::accumulate(n.begin(), n.end(), 0));
        };
        if ((want[0] == count[0] && want[1] == count[1]) ||
            total(want[0]) * total(want[1]) > kMaxCells) {
            // Every such cell is at kMaxPartitions in both directions, or the grid would pass
            // the uniform choice's largest.
            c.met = false;
            break;
        }
        count[0] = std::move(want[0]);
        count[1] = std::move(want[1]);
    }
    // 4. Trim the overshoot: a lane's bound only grows as its count falls, so bisect each
    // column's smallest count with the rows fixed, then each row's.
    if (c.met)
        for (int d = 0; d < 2; ++d)
            for (int k = 0; k < lanes[d]; ++k) {
                const auto ok = [&](int n) {
                    const int keep = count[d][size_t(k)];
                    count[d][size_t(k)] = n;
                    bool fine = true;
                    for (int i : byLane[d][size_t(k)])
                        if (score(entries[size_t(i)]).pixels > pixelTolerance) {
                            fine = false;
                            break;
                        }
                    count[d][size_t(k)] = keep;
                    return fine;
                };
                count[d][size_t(k)] = smallestPassing(low[d][size_t(k)], count[d][size_t(k)], ok);
            }
    c.boundPixels = 0.0;
    for (const Entry& e : entries)
        c.boundPixels = std::max(c.boundPixels, score(e).pixels);
    // 5. The breaks: each lane cut into its count of equal cells.
    std::vector<double>* out[2] = {&c.breaksU, &c.breaksV};
    for (int d = 0; d < 2; ++d) {
        for (int k = 0; k < lanes[d]; ++k) {
            const double a = edges[d][size_t(k)], w = width[d][size_t(k)];
            const int n = count[d][size_t(k)];
            for (int i = 0; i < n; ++i)
                out[d]->push_back(i == 0 ? a : a + w * i / n);
        }
        out[d]->push_back(box[d].last);
    }
    c.nu = int(c.breaksU.size()) - 1;
    c.nv = int(c.breaksV.size()) - 1;
    return c;
}

} // namespace kw
