// Modifying operations: knot insertion (A5.3) and degree elevation (A5.9-equivalent, by
// blossoming, in one pass for any t) in u or v.
#include "model/nurbs/nurbs_internal.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/type_ptr.hpp>

namespace kw {

std::uint64_t& detail::elevationWork() {
    static thread_local std::uint64_t work = 0;
    return work;
}

namespace {

using Line = std::vector<glm::dvec4>;

/// The control net seen along one direction: a family of curves ("lines") that share one knot
/// vector and degree. For direction u there is one line per j (countV lines of countU points);
/// for v one line per i. Surface algorithms of Chapter 5 are exactly the curve algorithms
/// applied to every line with the same knot bookkeeping.
///
/// A point is kept Cartesian with its weight, (P, w); the algorithms combine the homogeneous
/// (w P, w) (blend(), elevateBy()) but never round-trip a point they do not change, and equal
/// points combine to exactly that point. Stored as (w P, w), w P / w rounded the collapsed row
/// of a sphere's pole or a cone's apex apart by ~1e-16 of its distance from the origin, and the
/// evaluator saw a non-zero Su at the pole.
struct Lines {
    int degree = 1;
    std::vector<double> knots;
    std::vector<Line> lines;
};

Lines extract(const NurbsSurface& s, bool alongU) {
    Lines out;
    out.degree = alongU ? s.degreeU : s.degreeV;
    out.knots = alongU ? s.knotsU : s.knotsV;
    const int nLines = alongU ? s.countV : s.countU;
    const int nPts = alongU ? s.countU : s.countV;
    out.lines.assign(size_t(nLines), Line(size_t(nPts)));
    for (int l = 0; l < nLines; ++l) {
        for (int k = 0; k < nPts; ++k) {
            const size_t idx = size_t(alongU ? s.index(k, l) : s.index(l, k));
            const double w = s.weights[idx];
            out.lines[size_t(l)][size_t(k)] = glm::dvec4(s.points[idx], w);
        }
    }
    return out;
}

NurbsSurface rebuild(const NurbsSurface& s, const Lines& ls, bool alongU) {
    NurbsSurface out = s;
    const int nPts = int(ls.lines.front().size());
    if (alongU) {
        out.degreeU = ls.degree;
        out.knotsU = ls.knots;
        out.countU = nPts;
    } else {
        out.degreeV = ls.degree;
        out.knotsV = ls.knots;
        out.countV = nPts;
    }
    out.points.assign(size_t(out.countU) * size_t(out.countV), glm::dvec3(0.0));
    out.weights.assign(out.points.size(), 1.0);
    for (size_t l = 0; l < ls.lines.size(); ++l) {
        for (int k = 0; k < nPts; ++k) {
            const size_t idx = size_t(alongU ? out.index(k, int(l)) : out.index(int(l), k));
            const glm::dvec4& pw = ls.lines[l][size_t(k)];
            out.points[idx] = glm::dvec3(pw);
            out.weights[idx] = pw.w;
        }
    }
    return out;
}

/// (1 - a) x + a y of two (P, w) points taken in homogeneous space, as knot insertion combines
/// them (The NURBS Book, Eq. 5.15 on Pw), written as x + t (y - x) with the weighted ratio
/// t = a w_y / ((1 - a) w_x + a w_y): equal points give exactly that point, and the rounding
/// is relative to |y - x| rather than to |P|.
glm::dvec4 blend(double a, const glm::dvec4& x, const glm::dvec4& y) {
    const double wy = a * y.w;
    const double w = (1.0 - a) * x.w + wy;
    const glm::dvec3 px(x), py(y);
    return glm::dvec4(px + (wy / w) * (py - px), w);
}

// The NURBS Book, A5.3 (SurfaceKnotIns), written for the family of lines: insert u r times
// into span k (knots[k] <= u < knots[k+1]) where u already has multiplicity s, r + s <= p.
// The alphas depend only on the knots, so they are computed once and applied to every line.
void insertKnot(Lines& ls, double u, int k, int s, int r) {
    const int p = ls.degree;
    const std::vector<double>& up = ls.knots;
    const int np = int(up.size()) - p - 2; // last control point index
    std::vector<double> uq(up.size() + size_t(r));
    for (int i = 0; i <= k; ++i)
        uq[size_t(i)] = up[size_t(i)];
    for (int i = 1; i <= r; ++i)
        uq[size_t(k + i)] = u;
    for (int i = k + 1; i <= np + p + 1; ++i)
        uq[size_t(i + r)] = up[size_t(i)];

    double alpha[kMaxDegree + 1][kMaxDegree + 1];
    for (int j = 1; j <= r; ++j) {
        const int L = k - p + j;
        for (int i = 0; i <= p - j - s; ++i)
            alpha[i][j] = (u - up[size_t(L + i)]) / (up[size_t(i + k + 1)] - up[size_t(L + i)]);
    }
    glm::dvec4 rw[kMaxDegree + 1];
    for (Line& pw : ls.lines) {
        Line qw(pw.size() + size_t(r));
        for (int i = 0; i <= k - p; ++i)
            qw[size_t(i)] = pw[size_t(i)];
        for (int i = k - s; i <= np; ++i)
            qw[size_t(i + r)] = pw[size_t(i)];
        for (int i = 0; i <= p - s; ++i)
            rw[i] = pw[size_t(k - p + i)];
        int L = k - p;
        for (int j = 1; j <= r; ++j) {
            L = k - p + j;
            for (int i = 0; i <= p - j - s; ++i)
                rw[i] = blend(alpha[i][j], rw[i], rw[i + 1]);
            qw[size_t(L)] = rw[0];
            qw[size_t(k + r - j - s)] = rw[p - j - s];
        }
        for (int i = L + 1; i < k - s; ++i)
            qw[size_t(i)] = rw[i - L];
        pw = std::move(qw);
    }
    ls.knots = std::move(uq);
}

/// Number of knots equal to u.
int multiplicity(const std::vector<double>& knots, double u) {
    return int(std::count(knots.begin(), knots.end(), u));
}

/// Reverses the parameterisation (t -> -t): knots negated and reversed, points reversed.
/// Exact, and lets the clamping below treat both ends with one routine.
void reverse(Lines& ls) {
    std::reverse(ls.knots.begin(), ls.knots.end());
    for (double& k : ls.knots)
        k = -k;
    for (Line& l : ls.lines)
        std::reverse(l.begin(), l.end());
}

/// Makes the start clamped (first p + 1 knots equal to the domain start a) without moving the
/// curves on their domain: insert a until it has multiplicity p, after which C(a) is the
/// control point P[k-p] (k the last index of a); drop what lies before it. The knot before the
/// p copies of a only shapes basis functions that vanish on the domain, so it can become a.
void clampStart(Lines& ls) {
    const int p = ls.degree;
    const double a = ls.knots[size_t(p)];
    if (multiplicity(ls.knots, a) == p + 1 && ls.knots.front() == a)
        return;
    const int s = multiplicity(ls.knots, a);
    if (s < p)
        insertKnot(ls, a, findSpan(p, ls.knots, a), s, p - s);
    const int k = int(std::upper_bound(ls.knots.begin(), ls.knots.end(), a) - ls.knots.begin()) - 1;
    const int drop = k - p; // control points (and knots) before P[k-p]
    std::vector<double> knots;
    knots.push_back(a);
    knots.insert(knots.end(), ls.knots.begin() + (k - p + 1), ls.knots.end());
    ls.knots = std::move(knots);
    for (Line& l : ls.lines)
        l.erase(l.begin(), l.begin() + drop);
}

// Degree elevation by t in one go, exactly equivalent to The NURBS Book A5.9 (same knots, same
// control points in exact arithmetic) but computed by blossoming instead of Bezier
// decomposition and knot removal: A5.9's removal step extrapolates, and as printed it lost up
// to 1e-2 of the model size for degrees >= 10 (a simple knot followed by a triple knot, t = 1)
// in our tests. Each distinct knot gains multiplicity t and the new control points are the
// blossom values (Ramshaw's blossoming; The NURBS Book Sec. 5.5)
//   Q_j = B'(u'_{j+1}, ..., u'_{j+ph}),   B'(x_1..x_ph) = 1/C(ph, p) sum_{|S| = p} B(x_S),
// the symmetric average over the p-subsets S of the ph = p + t arguments that defines the
// degree-ph blossom of a degree-p polynomial (Eq. 5.36 is the Bezier special case). B is the
// blossom of the polynomial piece on a non-empty span k inside Q_j's support, the one nearest
// its middle, by de Boor's algorithm with one argument per level: level r (1..p) with argument
// y maps d[r-1..p] to d'[i] = (1 - a) d[i-1] + a d[i], a = (y - U[g]) / (U[g+p+1-r] - U[g]),
// g = k - p + i, i = r..p. With all arguments u it is C(u).
//
// Every level is linear in d, so the sum over subsets runs as one pass over the arguments:
// D[r] = sum, over the subsets of the arguments seen so far that chose r of them, of the
// triangle after those r levels; argument x_i adds level r applied to D[r - 1] to D[r]
// (chosen) or leaves D[r] (skipped). Only r >= i - t can still be completed (at most t
// arguments are skipped), so each argument touches at most t + 1 levels: O(ph min(t+1, p) p)
// point operations per new control point. The same operations on the same kind of values as
// the elevation by one that was repeated t times before (which made a surface elevated from 3
// to 15 cost about 11 times as much, a fuzzer input 5 to 15 s under AddressSanitizer), but
// with no intermediate rounding. The span's points are lifted about its first point O,
// (w (P - O), w), and the result is O + (sum) / w: equal points stay exactly equal, and the
// rounding is relative to the span's size. The end points of a clamped curve do not move under
// elevation, so they are copied. Precondition: clamped knot vector without interior knots of
// multiplicity p + 1 (see elevate()).
void elevateBy(Lines& ls, int t) {
    const int p = ls.degree;
    const int ph = p + t;
    const std::vector<double>& U = ls.knots;
    std::vector<double> uh;
    uh.reserve(U.size() + size_t(t) * U.size() + 2);
    for (size_t i = 0; i < U.size(); ++i) {
        uh.push_back(U[i]);
        if (i + 1 == U.size() || U[i + 1] != U[i])
            uh.insert(uh.end(), size_t(t), U[i]); // t more copies of each distinct knot
    }
    double binomial = 1.0; // C(ph, p), exact in double for ph <= kMaxDegree
    for (int q = 1; q <= t; ++q)
        binomial = binomial * double(p + q) / double(q);
    const int count = int(uh.size()) - ph - 1;
    std::vector<Line> out(ls.lines.size(), Line(size_t(count)));
    static_assert(sizeof(glm::dvec4) == 4 * sizeof(double)); // rows read as plain doubles
    // alpha[i][r][m]: the coefficient a of level r, row m, for argument i (0-based).
    static thread_local double alpha[kMaxDegree][kMaxDegree + 1][kMaxDegree + 1];
    glm::dvec4 d[kMaxDegree + 1][kMaxDegree + 1]; // d[r][m]: D[r], rows r..p
    glm::dvec4 d0[kMaxDegree + 1];                 // D[0]: the span's points, lifted about O
    std::uint64_t work = 0;
    for (int j = 0; j < count; ++j) {
        // The non-empty span of the new knots inside [u'_j, u'_{j+ph+1}) nearest its middle.
        int best = -1;
        for (int k = j; k <= j + ph; ++k)
            if (uh[size_t(k)] < uh[size_t(k + 1)] &&
                (best < 0 || std::abs(2 * k - (2 * j + ph)) < std::abs(2 * best - (2 * j + ph))))
                best = k;
        const int k = findSpan(p, U, uh[size_t(best)]); // the same interval in the old knots
        for (int i = 0; i < ph; ++i) {
            const double y = uh[size_t(j + 1 + i)];
            for (int r = std::max(1, i + 1 - t); r <= std::min(i + 1, p); ++r)
                for (int m = r; m <= p; ++m) {
                    const int g = k - p + m;
                    alpha[i][r][m] = (y - U[size_t(g)]) / (U[size_t(g + p + 1 - r)] - U[size_t(g)]);
                }
        }
        for (size_t l = 0; l < ls.lines.size(); ++l) {
            const glm::dvec4* span = ls.lines[l].data() + (k - p);
            const glm::dvec3 o(span[0]);
            for (int m = 0; m <= p; ++m)
                d0[m] = glm::dvec4((glm::dvec3(span[m]) - o) * span[m].w, span[m].w);
            for (int i = 0; i < ph; ++i) {
                // Downwards in r, so that D[r - 1] is still the sum before argument i.
                for (int r = std::min(i + 1, p); r >= std::max(1, i + 1 - t); --r) {
                    // Plain doubles: the same products and sums as glm's operators, without
                    // the 4-vector temporaries that AddressSanitizer checks copy by copy.
                    const double* src = glm::value_ptr(r == 1 ? d0[0] : d[r - 1][0]);
                    const double* a = alpha[i][r];
                    double* dst = glm::value_ptr(d[r][0]);
                    const bool first = r == i + 1; // first reached: every argument so far chosen
                    for (int m = r; m <= p; ++m) {
                        const double b = a[m], c = 1.0 - b;
                        const double* x = src + 4 * (m - 1);
                        const double* y = src + 4 * m;
                        double* o = dst + 4 * m;
                        for (int q = 0; q < 4; ++q)
                            o[q] = first ? c * x[q] + b * y[q] : o[q] + (c * x[q] + b * y[q]);
                    }
                    work += std::uint64_t(p + 1 - r);
                }
            }
            const glm::dvec4 q = d[p][p] / binomial;
            out[l][size_t(j)] = glm::dvec4(o + glm::dvec3(q) / q.w, q.w);
        }
    }
    for (size_t l = 0; l < ls.lines.size(); ++l) {
        out[l].front() = ls.lines[l].front();
        out[l].back() = ls.lines[l].back();
    }
    detail::elevationWork() += work;
    ls.knots = std::move(uh);
    ls.lines = std::move(out);
    ls.degree = ph;
}

/// Degree elevation of any valid knot vector: clamp both ends (exact, see clampStart), split at
/// interior knots of multiplicity p + 1 (where the curves may jump), elevate each clamped piece
/// by t (elevateBy) and join the pieces again (the join knot gets multiplicity
/// ph + 1).
void elevate(Lines& ls, int t) {
    clampStart(ls);
    reverse(ls);
    clampStart(ls);
    reverse(ls);
    const int p = ls.degree;
    const int ph = p + t;
    Lines result;
    size_t firstKnot = 0; // piece = knots [firstKnot, k], points [firstKnot, k - p - 1]
    const size_t m = ls.knots.size() - 1;
    size_t i = size_t(p) + 1;
    while (i <= m) {
        size_t e = i;
        while (e + 1 <= m && ls.knots[e + 1] == ls.knots[i])
            ++e;
        const bool split = e < m - size_t(p) && e - i + 1 == size_t(p) + 1;
        if (split || e == m) {
            Lines piece;
            piece.degree = p;
            piece.knots.assign(ls.knots.begin() + long(firstKnot), ls.knots.begin() + long(e) + 1);
            const size_t nPts = piece.knots.size() - size_t(p) - 1;
            for (const Line& l : ls.lines)
                piece.lines.emplace_back(l.begin() + long(firstKnot),
                                         l.begin() + long(firstKnot + nPts));
            elevateBy(piece, t);
            if (result.lines.empty()) {
                result = std::move(piece);
            } else {
                result.knots.insert(result.knots.end(), piece.knots.begin() + ph + 1,
                                    piece.knots.end());
                for (size_t l = 0; l < result.lines.size(); ++l)
                    result.lines[l].insert(result.lines[l].end(), piece.lines[l].begin(),
                                           piece.lines[l].end());
            }
            firstKnot = i; // the next piece starts with the p + 1 copies of this knot
        }
        i = e + 1;
    }
    ls = std::move(result);
}

/// Contract (beyond nurbs.h): an invalid surface (checkNurbsSurface) or times <= 0 also
/// returns the input unchanged.
NurbsSurface insertKnot(const NurbsSurface& s, double u, int times, bool alongU) {
    if (times <= 0 || !checkNurbsSurface(s))
        return s;
    const int p = alongU ? s.degreeU : s.degreeV;
    const std::vector<double>& knots = alongU ? s.knotsU : s.knotsV;
    const Interval d = knotDomain(knots, p);
    if (!(u > d.first && u < d.last))
        return s;
    const int mult = multiplicity(knots, u);
    if (times > p - mult) // written so that a huge `times` cannot overflow
        return s;
    Lines ls = extract(s, alongU);
    insertKnot(ls, u, findSpan(p, knots, u), mult, times);
    return rebuild(s, ls, alongU);
}

/// Contract (beyond nurbs.h): an invalid surface or t <= 0 also returns the input unchanged.
/// An unclamped knot vector comes back clamped at the domain ends (same surface, same domain).
NurbsSurface elevateDegree(const NurbsSurface& s, int t, bool alongU) {
    if (t <= 0 || !checkNurbsSurface(s))
        return s;
    const int p = alongU ? s.degreeU : s.degreeV;
    if (t > kMaxDegree - p) // written so that a huge t cannot overflow
        return s;
    Lines ls = extract(s, alongU);
    elevate(ls, t);
    return rebuild(s, ls, alongU);
}

} // namespace

NurbsSurface surfaceInsertKnotU(const NurbsSurface& s, double u, int times) {
    return insertKnot(s, u, times, true);
}

NurbsSurface surfaceInsertKnotV(const NurbsSurface& s, double v, int times) {
    return insertKnot(s, v, times, false);
}

NurbsSurface surfaceElevateDegreeU(const NurbsSurface& s, int t) {
    return elevateDegree(s, t, true);
}

NurbsSurface surfaceElevateDegreeV(const NurbsSurface& s, int t) {
    return elevateDegree(s, t, false);
}

} // namespace kw
