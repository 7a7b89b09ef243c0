// NURBS constructions: patches, cones, revolution (A8.1), extrusion, skinning (Sec. 10.3 with
// A9.1), iso-curves and knot removal (A5.8).
#include "model/nurbs/nurbs_construct.h"

#include "model/nurbs/nurbs_shapes.h"

#include <algorithm>
#include <cmath>

namespace kw {
namespace {

const double kHalfSqrt2 = std::sqrt(0.5);
/// Control points of the unit 9-point circle (Ex. 7.2), counter-clockwise from (1, 0).
const glm::dvec2 kUnitSquare[9] = {{1, 0},   {1, 1},  {0, 1},  {-1, 1}, {-1, 0},
                                   {-1, -1}, {0, -1}, {1, -1}, {1, 0}};

using Line = std::vector<glm::dvec4>;

/// A curve as the v = 0 row of a surface whose two rows are equal (degree 1 in v). The surface
/// algorithms of Chapter 5 (knot insertion, degree elevation, evaluation) then apply to the
/// curve unchanged: every row of the lifted net is the curve's control polygon.
NurbsSurface lift(const NurbsCurve3& c) {
    NurbsSurface s;
    s.degreeU = c.degree;
    s.degreeV = 1;
    s.countU = int(c.points.size());
    s.countV = 2;
    s.knotsU = c.knots;
    s.knotsV = {0, 0, 1, 1};
    for (int j = 0; j < 2; ++j) {
        s.points.insert(s.points.end(), c.points.begin(), c.points.end());
        s.weights.insert(s.weights.end(), c.weights.begin(), c.weights.end());
    }
    return s;
}

NurbsCurve3 row0(const NurbsSurface& s) {
    NurbsCurve3 c;
    c.degree = s.degreeU;
    c.knots = s.knotsU;
    c.points.assign(s.points.begin(), s.points.begin() + s.countU);
    c.weights.assign(s.weights.begin(), s.weights.begin() + s.countU);
    return c;
}

bool clampedKnots(const std::vector<double>& k, int p) {
    return std::all_of(k.begin(), k.begin() + p + 1, [&](double x) { return x == k.front(); }) &&
           std::all_of(k.end() - p - 1, k.end(), [&](double x) { return x == k.back(); });
}

/// Solves A x = b for several right-hand sides by Gaussian elimination with partial pivoting.
/// A is n x n row-major; b is n rows of m columns. Returns false when A is singular.
bool solve(std::vector<double> a, std::vector<glm::dvec4>& b, int n) {
    const size_t N = size_t(n);
    for (size_t c = 0; c < N; ++c) {
        size_t piv = c;
        for (size_t r = c + 1; r < N; ++r)
            if (std::abs(a[r * N + c]) > std::abs(a[piv * N + c]))
                piv = r;
        if (std::abs(a[piv * N + c]) < 1e-14)
            return false;
        if (piv != c) {
            for (size_t k = 0; k < N; ++k)
                std::swap(a[c * N + k], a[piv * N + k]);
            std::swap(b[c], b[piv]);
        }
        for (size_t r = c + 1; r < N; ++r) {
            const double f = a[r * N + c] / a[c * N + c];
            if (f == 0.0)
                continue;
            for (size_t k = c; k < N; ++k)
                a[r * N + k] -= f * a[c * N + k];
            b[r] -= f * b[c];
        }
    }
    for (size_t c = N; c-- > 0;) {
        for (size_t k = c + 1; k < N; ++k)
            b[c] -= a[c * N + k] * b[k];
        b[c] /= a[c * N + c];
    }
    return true;
}

/// A5.8 with num = 1 on one homogeneous line: removes the knot U[r] (multiplicity s, r its last
/// index) once if the two estimates of the new control points agree within tol (4D distance).
bool removeOnce(const Line& pw, const std::vector<double>& U, int p, int r, int s, double tol,
                Line& out, double& distanceOut) {
    const double u = U[size_t(r)];
    const int first = r - p, last = r - s;
    const int off = first - 1;
    std::vector<glm::dvec4> temp(size_t(last + 2 - off));
    temp[0] = pw[size_t(off)];
    temp[size_t(last + 1 - off)] = pw[size_t(last + 1)];
    int i = first, j = last, ii = 1, jj = last - off;
    while (j - i > 0) {
        const double alfi = (u - U[size_t(i)]) / (U[size_t(i + p + 1)] - U[size_t(i)]);
        const double alfj = (u - U[size_t(j)]) / (U[size_t(j + p + 1)] - U[size_t(j)]);
        temp[size_t(ii)] = (pw[size_t(i)] - (1.0 - alfi) * temp[size_t(ii - 1)]) / alfi;
        temp[size_t(jj)] = (pw[size_t(j)] - alfj * temp[size_t(jj + 1)]) / (1.0 - alfj);
        ++i, ++ii, --j, --jj;
    }
    double distance = 0.0;
    if (j - i < 0) {
        distance = glm::length(temp[size_t(ii - 1)] - temp[size_t(jj + 1)]);
    } else {
        const double alfi = (u - U[size_t(i)]) / (U[size_t(i + p + 1)] - U[size_t(i)]);
        distance = glm::length(pw[size_t(i)] -
                               (alfi * temp[size_t(ii + 1)] + (1.0 - alfi) * temp[size_t(ii - 1)]));
    }
    if (!(distance <= tol))
        return false;
    distanceOut = distance;
    out = pw;
    i = first, j = last;
    while (j - i > 0) {
        out[size_t(i)] = temp[size_t(i - off)];
        out[size_t(j)] = temp[size_t(j - off)];
        ++i, --j;
    }
    out.erase(out.begin() + (2 * r - s - p) / 2); // fout: the point that drops out
    return true;
}

} // namespace

Status checkNurbsCurve3(const NurbsCurve3& c) {
    if (Status knots = checkKnotVector(c.knots, c.degree, int(c.points.size())); !knots)
        return knots;
    if (c.weights.size() != c.points.size())
        return Error("weights and points differ in count");
    for (size_t i = 0; i < c.points.size(); ++i) {
        const glm::dvec3& p = c.points[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return Error(QStringLiteral("control point %1 is not finite").arg(i));
        if (!(c.weights[i] > 0.0) || !std::isfinite(c.weights[i]))
            return Error(QStringLiteral("weight %1 is not a finite positive number").arg(i));
    }
    return ok();
}

glm::dvec3 curve3Point(const NurbsCurve3& c, double t) {
    return surfacePoint(lift(c), t, 0.0);
}

std::vector<double> clampedUniformKnots(int degree, int count) {
    std::vector<double> k(size_t(degree + 1), 0.0);
    const int interior = count - degree - 1;
    for (int i = 1; i <= interior; ++i)
        k.push_back(double(i) / double(interior + 1));
    k.insert(k.end(), size_t(degree + 1), 1.0);
    return k;
}

NurbsSurface makePatch(const glm::dvec3& center, int degreeU, int degreeV, int countU, int countV,
                       double sizeU, double sizeV) {
    NurbsSurface s;
    s.degreeU = degreeU;
    s.degreeV = degreeV;
    s.countU = countU;
    s.countV = countV;
    s.knotsU = clampedUniformKnots(degreeU, countU);
    s.knotsV = clampedUniformKnots(degreeV, countV);
    for (int j = 0; j < countV; ++j)
        for (int i = 0; i < countU; ++i) {
            const double x = sizeU * (double(i) / double(std::max(1, countU - 1)) - 0.5);
            const double y = sizeV * (double(j) / double(std::max(1, countV - 1)) - 0.5);
            s.points.push_back(center + glm::dvec3(x, y, 0.0));
            s.weights.push_back(1.0);
        }
    return s;
}

NurbsSurface makeCone(const glm::dvec3& baseCenter, double baseRadius, double height,
                      double topRadius) {
    NurbsCurve2 line;
    line.degree = 1;
    line.knots = {0, 0, 1, 1};
    line.points = {{baseRadius, 0.0}, {topRadius, height}};
    line.weights = {1, 1};
    return makeRevolution(baseCenter, line);
}

NurbsSurface makeRevolution3(const NurbsCurve3& profile, const glm::dvec3& axisPoint,
                             const glm::dvec3& axisDirection) {
    const glm::dvec3 a = glm::normalize(axisDirection);
    NurbsSurface s;
    s.degreeU = 2;
    s.degreeV = profile.degree;
    s.countU = 9;
    s.countV = int(profile.points.size());
    s.knotsU = {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1};
    s.knotsV = profile.knots;
    for (int j = 0; j < s.countV; ++j) {
        const glm::dvec3 p = profile.points[size_t(j)];
        const glm::dvec3 o = axisPoint + glm::dot(p - axisPoint, a) * a; // foot on the axis
        const glm::dvec3 x = p - o;
        const glm::dvec3 y = glm::cross(a, x);
        for (int i = 0; i < 9; ++i) {
            s.points.push_back(o + kUnitSquare[i].x * x + kUnitSquare[i].y * y);
            s.weights.push_back((i % 2 == 0 ? 1.0 : kHalfSqrt2) * profile.weights[size_t(j)]);
        }
    }
    return s;
}

NurbsSurface makeExtrusion(const NurbsCurve3& curve, const glm::dvec3& direction) {
    NurbsSurface s = lift(curve);
    for (int i = 0; i < s.countU; ++i)
        s.points[size_t(s.index(i, 1))] += direction;
    return s;
}

Expected<NurbsSurface> makeLoft(std::vector<NurbsCurve3> sections, int maxDegreeV,
                                std::vector<double>* sectionParameters) {
    auto fail = [](const std::string& why) {
        return Error(QString::fromStdString(why));
    };
    const int K = int(sections.size());
    if (K < 2)
        return fail("a loft needs at least two curves");
    if (maxDegreeV < 1)
        return fail("the loft degree must be at least 1");
    // 1. Same parameter range [0, 1], highest degree, clamped ends.
    int P = 1;
    for (int k = 0; k < K; ++k) {
        NurbsCurve3& c = sections[size_t(k)];
        if (const Status valid = checkNurbsCurve3(c); !valid)
            return Error(QStringLiteral("curve %1: %2").arg(k + 1).arg(valid.message()));
        const Interval d = knotDomain(c.knots, c.degree);
        for (double& x : c.knots)
            x = (x - d.first) / (d.last - d.first);
        P = std::max(P, c.degree);
    }
    for (NurbsCurve3& c : sections) {
        // Degree elevation clamps unclamped ends; an unclamped curve already at the top degree
        // is elevated once more by all (knot union needs equal, clamped ends).
        if (c.degree == P && !clampedKnots(c.knots, c.degree))
            P = std::min(kMaxDegree, P + 1);
    }
    for (NurbsCurve3& c : sections)
        if (c.degree < P)
            c = row0(surfaceElevateDegreeU(lift(c), P - c.degree));
    for (const NurbsCurve3& c : sections)
        if (c.degree != P || !clampedKnots(c.knots, P))
            return fail("the curves could not be made compatible (unclamped at degree " +
                        std::to_string(kMaxDegree) + ")");
    // 2. Knot union: every interior knot with its highest multiplicity among the sections.
    std::vector<std::pair<double, int>> unionKnots;
    for (const NurbsCurve3& c : sections)
        for (size_t i = size_t(P) + 1; i + size_t(P) + 1 < c.knots.size();) {
            size_t e = i;
            while (e + 1 + size_t(P) + 1 < c.knots.size() && c.knots[e + 1] == c.knots[i])
                ++e;
            const int m = int(e - i + 1);
            auto it = std::find_if(unionKnots.begin(), unionKnots.end(), [&](const auto& q) {
                return std::abs(q.first - c.knots[i]) <= 1e-12;
            });
            if (it == unionKnots.end())
                unionKnots.push_back({c.knots[i], m});
            else
                it->second = std::max(it->second, m);
            i = e + 1;
        }
    for (NurbsCurve3& c : sections) {
        NurbsSurface s = lift(c);
        for (const auto& [x, m] : unionKnots) {
            int own = 0;
            for (double& k : s.knotsU)
                if (std::abs(k - x) <= 1e-12) {
                    k = x; // snap near-equal knots so the vectors become identical
                    ++own;
                }
            if (m > own)
                s = surfaceInsertKnotU(s, x, m - own);
        }
        c = row0(s);
    }
    const int n = int(sections.front().points.size());
    for (const NurbsCurve3& c : sections)
        if (c.knots != sections.front().knots)
            return fail("the curves could not be made compatible");
    // 3. Parameters v_k: chord lengths between sections averaged over the columns (Sec. 10.3).
    std::vector<double> v(size_t(K), 0.0);
    int columns = 0;
    for (int i = 0; i < n; ++i) {
        std::vector<double> chord(size_t(K), 0.0);
        for (int k = 1; k < K; ++k)
            chord[size_t(k)] =
                chord[size_t(k - 1)] + glm::length(sections[size_t(k)].points[size_t(i)] -
                                                   sections[size_t(k - 1)].points[size_t(i)]);
        if (chord.back() <= 0.0)
            continue;
        ++columns;
        for (int k = 0; k < K; ++k)
            v[size_t(k)] += chord[size_t(k)] / chord.back();
    }
    if (columns == 0)
        return fail("the curves coincide");
    for (double& x : v)
        x /= double(columns);
    v.front() = 0.0;
    v.back() = 1.0;
    for (int k = 1; k < K; ++k)
        if (!(v[size_t(k)] > v[size_t(k - 1)]))
            return fail("two consecutive curves coincide");
    // 4. Knots in v by averaging (Eq. 9.8) and the interpolation matrix N_j(v_k) (A9.1).
    const int q = std::min(maxDegreeV, K - 1);
    std::vector<double> kv(size_t(q + 1), 0.0);
    for (int j = 1; j <= K - 1 - q; ++j) {
        double sum = 0.0;
        for (int i = j; i < j + q; ++i)
            sum += v[size_t(i)];
        kv.push_back(sum / double(q));
    }
    kv.insert(kv.end(), size_t(q + 1), 1.0);
    std::vector<double> a(size_t(K) * size_t(K), 0.0);
    double basis[kMaxDegree + 1];
    for (int k = 0; k < K; ++k) {
        const int span = findSpan(q, kv, v[size_t(k)]);
        basisFunctions(span, v[size_t(k)], q, kv, basis);
        for (int j = 0; j <= q; ++j)
            a[size_t(k) * size_t(K) + size_t(span - q + j)] = basis[j];
    }
    NurbsSurface s;
    s.degreeU = P;
    s.degreeV = q;
    s.countU = n;
    s.countV = K;
    s.knotsU = sections.front().knots;
    s.knotsV = kv;
    s.points.assign(size_t(n) * size_t(K), glm::dvec3(0.0));
    s.weights.assign(s.points.size(), 1.0);
    for (int i = 0; i < n; ++i) {
        std::vector<glm::dvec4> b(static_cast<size_t>(K));
        for (int k = 0; k < K; ++k) {
            const NurbsCurve3& c = sections[size_t(k)];
            b[size_t(k)] =
                glm::dvec4(c.points[size_t(i)] * c.weights[size_t(i)], c.weights[size_t(i)]);
        }
        if (!solve(a, b, K))
            return fail("the interpolation through the curves is singular");
        for (int j = 0; j < K; ++j) {
            const glm::dvec4 pw = b[size_t(j)];
            if (!(pw.w > 1e-12))
                return fail("the curves' weights give a loft with non-positive weights");
            s.points[size_t(s.index(i, j))] = glm::dvec3(pw) / pw.w;
            s.weights[size_t(s.index(i, j))] = pw.w;
        }
    }
    if (const Status valid = checkNurbsSurface(s); !valid)
        return Error(QStringLiteral("the loft is invalid: %1").arg(valid.message()));
    if (sectionParameters)
        *sectionParameters = v;
    return s;
}

Expected<NurbsCurve3> interpolateCurve3(const std::vector<glm::dvec3>& q, int maxDegree,
                                        std::vector<double>* parameters) {
    const auto fail = [](const char* why) {
        return Error(why);
    };
    const int n = int(q.size());
    if (n < 2)
        return fail("at least two points are needed");
    for (const glm::dvec3& x : q)
        if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z))
            return fail("a point is not finite");
    // Chord-length parameters (Eq. 9.5).
    std::vector<double> t(size_t(n), 0.0);
    for (int k = 1; k < n; ++k) {
        const double d = glm::length(q[size_t(k)] - q[size_t(k - 1)]);
        if (!(d > 0.0))
            return fail("two consecutive points coincide");
        t[size_t(k)] = t[size_t(k - 1)] + d;
    }
    const double total = t.back();
    for (double& x : t)
        x /= total;
    t.front() = 0.0;
    t.back() = 1.0;
    // Knots by averaging (Eq. 9.8).
    const int p = std::clamp(maxDegree, 1, std::min(n - 1, kMaxDegree));
    std::vector<double> knots(size_t(p + 1), 0.0);
    for (int j = 1; j <= n - 1 - p; ++j) {
        double sum = 0.0;
        for (int i = j; i < j + p; ++i)
            sum += t[size_t(i)];
        knots.push_back(sum / double(p));
    }
    knots.insert(knots.end(), size_t(p + 1), 1.0);
    // A9.1: the n x n system N_i(t_k) P_i = Q_k.
    std::vector<double> a(size_t(n) * size_t(n), 0.0);
    double basis[kMaxDegree + 1];
    for (int k = 0; k < n; ++k) {
        const int span = findSpan(p, knots, t[size_t(k)]);
        basisFunctions(span, t[size_t(k)], p, knots, basis);
        for (int j = 0; j <= p; ++j)
            a[size_t(k) * size_t(n) + size_t(span - p + j)] = basis[j];
    }
    std::vector<glm::dvec4> b(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k)
        b[size_t(k)] = glm::dvec4(q[size_t(k)], 1.0);
    if (!solve(a, b, n))
        return fail("the interpolation is singular");
    NurbsCurve3 c;
    c.degree = p;
    c.knots = std::move(knots);
    for (const glm::dvec4& x : b)
        c.points.emplace_back(x);
    c.weights.assign(size_t(n), 1.0);
    if (parameters)
        *parameters = t;
    return c;
}

NurbsCurve3 controlPointCurve3(const std::vector<glm::dvec3>& points, int maxDegree) {
    const int n = int(points.size());
    if (n < 2)
        return {};
    NurbsCurve3 c;
    c.degree = std::clamp(maxDegree, 1, std::min(n - 1, kMaxDegree));
    c.knots = clampedUniformKnots(c.degree, n);
    c.points = points;
    c.weights.assign(size_t(n), 1.0);
    return c;
}

NurbsCurve3 surfaceIsoCurve(const NurbsSurface& s, bool alongU, double parameter) {
    // C(t) = sum_i N_i(t) [ sum_j N_j(t0) Pw_ij ]: the fixed direction's basis functions at t0
    // combine each row of the homogeneous net into one control point of the iso-curve.
    const int q = alongU ? s.degreeV : s.degreeU;
    const std::vector<double>& fixedKnots = alongU ? s.knotsV : s.knotsU;
    const Interval d = knotDomain(fixedKnots, q);
    const double t0 = std::clamp(parameter, d.first, d.last);
    const int span = findSpan(q, fixedKnots, t0);
    double basis[kMaxDegree + 1];
    basisFunctions(span, t0, q, fixedKnots, basis);
    NurbsCurve3 c;
    c.degree = alongU ? s.degreeU : s.degreeV;
    c.knots = alongU ? s.knotsU : s.knotsV;
    const int count = alongU ? s.countU : s.countV;
    for (int i = 0; i < count; ++i) {
        glm::dvec4 sum(0.0);
        for (int j = 0; j <= q; ++j) {
            const int fixedIndex = span - q + j;
            const size_t idx = size_t(alongU ? s.index(i, fixedIndex) : s.index(fixedIndex, i));
            sum += basis[j] * glm::dvec4(s.points[idx] * s.weights[idx], s.weights[idx]);
        }
        c.points.push_back(glm::dvec3(sum) / sum.w);
        c.weights.push_back(sum.w);
    }
    return c;
}

NurbsSurface surfaceRemoveKnots(const NurbsSurface& s, bool alongU, double tolerance,
                                int* removed) {
    if (removed)
        *removed = 0;
    if (!(tolerance >= 0.0) || !checkNurbsSurface(s))
        return s;
    // Eq. 5.30: a homogeneous deviation below tol * wmin / (1 + |P|max) keeps the rational
    // surface within tol. The net is lifted about the centre c of its bounds, (w (P - c), w):
    // the deviation does not change under a translation, and |P - c|max is the net's half
    // diagonal. Lifted about the model's origin, |P|max grew with the distance from it, and a
    // surface moved 100 units away lost every removal that a tolerance allowed at the origin.
    glm::dvec3 lo, hi;
    surfaceControlBounds(s, lo, hi);
    const glm::dvec3 c = 0.5 * (lo + hi);
    double wmin = s.weights.front(), pmax = 0.0;
    for (size_t k = 0; k < s.points.size(); ++k) {
        wmin = std::min(wmin, s.weights[k]);
        pmax = std::max(pmax, glm::length(s.points[k] - c));
    }
    const double tol4 = tolerance * wmin / (1.0 + pmax);
    const int p = alongU ? s.degreeU : s.degreeV;
    std::vector<double> U = alongU ? s.knotsU : s.knotsV;
    const int nLines = alongU ? s.countV : s.countU;
    const int nPts = alongU ? s.countU : s.countV;
    std::vector<Line> lines(static_cast<size_t>(nLines), Line(static_cast<size_t>(nPts)));
    for (int l = 0; l < nLines; ++l)
        for (int k = 0; k < nPts; ++k) {
            const size_t idx = size_t(alongU ? s.index(k, l) : s.index(l, k));
            lines[size_t(l)][size_t(k)] =
                glm::dvec4((s.points[idx] - c) * s.weights[idx], s.weights[idx]);
        }
    // Each removal moves the surface by at most its A5.8 distance; their sum stays within the
    // budget so that the removals together keep the surface within tolerance.
    double budget = tol4;
    int count = 0;
    for (bool progress = true; progress;) {
        progress = false;
        const Interval d = knotDomain(U, p);
        for (int r = p + 1; r + p + 1 < int(U.size()); ++r) {
            if (U[size_t(r)] == U[size_t(r + 1)] ||
                !(U[size_t(r)] > d.first && U[size_t(r)] < d.last))
                continue; // r must be the last index of an interior knot
            const int mult = int(std::count(U.begin(), U.end(), U[size_t(r)]));
            if (mult > p)
                continue;
            std::vector<Line> next(lines.size());
            bool all = true;
            double worst = 0.0;
            for (size_t l = 0; l < lines.size() && all; ++l) {
                double distance = 0.0;
                all = removeOnce(lines[l], U, p, r, mult, budget, next[l], distance);
                worst = std::max(worst, distance);
            }
            if (!all)
                continue;
            budget -= worst;
            lines = std::move(next);
            U.erase(U.begin() + r);
            ++count;
            progress = true;
            break;
        }
    }
    if (count == 0)
        return s;
    NurbsSurface out = s;
    const int newPts = int(lines.front().size());
    (alongU ? out.knotsU : out.knotsV) = U;
    (alongU ? out.countU : out.countV) = newPts;
    out.points.assign(size_t(out.countU) * size_t(out.countV), glm::dvec3(0.0));
    out.weights.assign(out.points.size(), 1.0);
    for (int l = 0; l < nLines; ++l)
        for (int k = 0; k < newPts; ++k) {
            const size_t idx = size_t(alongU ? out.index(k, l) : out.index(l, k));
            const glm::dvec4& pw = lines[size_t(l)][size_t(k)];
            out.points[idx] = c + glm::dvec3(pw) / pw.w;
            out.weights[idx] = pw.w;
        }
    if (!checkNurbsSurface(out) || !(out.weights == out.weights))
        return s;
    for (double w : out.weights)
        if (!(w > 0.0))
            return s;
    if (removed)
        *removed = count;
    return out;
}

NurbsCurve2 curve2InsertKnot(const NurbsCurve2& c, double t) {
    // The curve as the v = 0 row of a lifted surface (x, y, 0): surface knot insertion is A5.3
    // on every row, which for one row is A5.1.
    NurbsCurve3 c3;
    c3.degree = c.degree;
    c3.knots = c.knots;
    c3.weights = c.weights;
    for (const glm::dvec2& p : c.points)
        c3.points.emplace_back(p, 0.0);
    const NurbsSurface s = surfaceInsertKnotU(lift(c3), t, 1);
    if (s.countU == int(c.points.size()))
        return c;
    const NurbsCurve3 r = row0(s);
    NurbsCurve2 out;
    out.degree = r.degree;
    out.knots = r.knots;
    out.weights = r.weights;
    for (const glm::dvec3& p : r.points)
        out.points.emplace_back(p.x, p.y);
    return out;
}

NurbsCurve2 curve2RemovePoint(const NurbsCurve2& c, int index) {
    const int n = int(c.points.size());
    if (index <= 0 || index >= n - 1 || n < 3)
        return c;
    NurbsCurve2 out = c;
    out.points.erase(out.points.begin() + index);
    out.weights.erase(out.weights.begin() + index);
    const int p = c.degree;
    if (n - 1 >= p + 1) {
        // Drop the interior knot nearest the Greville abscissa of the removed point.
        const double greville = grevilleAbscissa(c.knots, p, index);
        int best = -1;
        for (int k = p + 1; k < n; ++k) // interior knots: indices p + 1 .. n - 1
            if (best < 0 || std::abs(c.knots[size_t(k)] - greville) <
                                std::abs(c.knots[size_t(best)] - greville))
                best = k;
        out.knots.erase(out.knots.begin() + best);
    } else {
        // Too few points for the degree: one degree less, clamped uniform on the same domain.
        const Interval d = knotDomain(c.knots, p);
        out.degree = p - 1;
        out.knots = clampedUniformKnots(out.degree, n - 1);
        for (double& k : out.knots)
            k = d.first + k * (d.last - d.first);
    }
    return out;
}

} // namespace kw
