// Match Surface: exact G0/G1/G2 to an untrimmed neighbour's edge on compatible bases, and a
// least-squares approximation to a trim curve.
#include "model/document/matchsurface.h"

#include <algorithm>
#include <cmath>

namespace kw {

namespace {

using Row = std::vector<glm::dvec4>;

NurbsSurface transposed(const NurbsSurface& s) {
    NurbsSurface t;
    t.degreeU = s.degreeV;
    t.degreeV = s.degreeU;
    t.countU = s.countV;
    t.countV = s.countU;
    t.knotsU = s.knotsV;
    t.knotsV = s.knotsU;
    t.points.resize(s.points.size());
    t.weights.resize(s.weights.size());
    for (int j = 0; j < s.countV; ++j)
        for (int i = 0; i < s.countU; ++i) {
            t.points[size_t(t.index(j, i))] = s.points[size_t(s.index(i, j))];
            t.weights[size_t(t.index(j, i))] = s.weights[size_t(s.index(i, j))];
        }
    return t;
}

std::vector<double> reversedKnots(const std::vector<double>& k) {
    std::vector<double> r(k.size());
    const double sum = k.front() + k.back();
    for (size_t i = 0; i < k.size(); ++i)
        r[i] = sum - k[k.size() - 1 - i];
    return r;
}

/// The same surface with v running the other way (exact: mirrored knots, reversed rows).
NurbsSurface reversedV(const NurbsSurface& s) {
    NurbsSurface r = s;
    r.knotsV = reversedKnots(s.knotsV);
    for (int j = 0; j < s.countV; ++j)
        for (int i = 0; i < s.countU; ++i) {
            r.points[size_t(r.index(i, j))] = s.points[size_t(s.index(i, s.countV - 1 - j))];
            r.weights[size_t(r.index(i, j))] = s.weights[size_t(s.index(i, s.countV - 1 - j))];
        }
    return r;
}

NurbsSurface reversedU(const NurbsSurface& s) {
    return transposed(reversedV(transposed(s)));
}

enum class Turn { ToV0, Back };

/// Turns `s` so that its edge `edge` is v = first with v running into the surface (ToV0), or
/// turns such a result back (Back). Each turn undoes itself except U1's, whose two steps
/// are undone in the other order.
NurbsSurface turned(const NurbsSurface& s, DomainEdge edge, Turn turn) {
    switch (edge) {
    case DomainEdge::V1:
        return reversedV(s);
    case DomainEdge::U0:
        return transposed(s);
    case DomainEdge::U1:
        return turn == Turn::ToV0 ? reversedV(transposed(s)) : transposed(reversedV(s));
    default:
        return s;
    }
}

glm::dvec4 homogeneous(const NurbsSurface& s, int i, int j) {
    const double w = s.weights[size_t(s.index(i, j))];
    return glm::dvec4(s.points[size_t(s.index(i, j))] * w, w);
}

Row row(const NurbsSurface& s, int j) {
    Row r;
    for (int i = 0; i < s.countU; ++i)
        r.push_back(homogeneous(s, i, j));
    return r;
}

bool setRow(NurbsSurface& s, int j, const Row& r) {
    for (int i = 0; i < s.countU; ++i) {
        const double w = r[size_t(i)].w;
        if (!(w > 0.0) || !std::isfinite(w))
            return false;
        s.points[size_t(s.index(i, j))] = glm::dvec3(r[size_t(i)]) / w;
        s.weights[size_t(s.index(i, j))] = w;
    }
    return true;
}

bool clampedAtStart(const std::vector<double>& k, int degree) {
    for (int i = 1; i <= degree; ++i)
        if (k[size_t(i)] != k[0])
            return false;
    return true;
}

/// The first and second derivatives across v = first, per column (homogeneous; A3.3's
/// derivative control points of a clamped start). D2 is zero below degree 2.
void crossDerivatives(const NurbsSurface& s, Row& d1, Row& d2) {
    const int q = s.degreeV;
    const std::vector<double>& V = s.knotsV;
    const Row p0 = row(s, 0), p1 = row(s, 1);
    d1.assign(p0.size(), glm::dvec4(0.0));
    d2.assign(p0.size(), glm::dvec4(0.0));
    for (size_t i = 0; i < p0.size(); ++i)
        d1[i] = double(q) * (p1[i] - p0[i]) / (V[size_t(q + 1)] - V[1]);
    if (q < 2 || s.countV < 3)
        return;
    const Row p2 = row(s, 2);
    for (size_t i = 0; i < p0.size(); ++i) {
        const glm::dvec4 e1 = double(q) * (p2[i] - p1[i]) / (V[size_t(q + 2)] - V[2]);
        d2[i] = double(q - 1) * (e1 - d1[i]) / (V[size_t(q + 1)] - V[2]);
    }
}

/// Inserts knots across (v) at the middle of the widest spans until the surface has at least
/// `rows` rows besides its far edge, so that changing them leaves the opposite edge alone.
NurbsSurface withRowsAcross(NurbsSurface s, int rows) {
    while (s.countV < rows + 1) {
        const Interval d = surfaceDomainV(s);
        double widest = 0.0, at = 0.5 * (d.first + d.last);
        for (size_t k = size_t(s.degreeV); k + 1 < s.knotsV.size(); ++k) {
            const double a = s.knotsV[k], b = s.knotsV[k + 1];
            if (a >= d.first && b <= d.last && b - a > widest) {
                widest = b - a;
                at = 0.5 * (a + b);
            }
        }
        const NurbsSurface next = surfaceInsertKnotV(s, at, 1);
        if (next.countV == s.countV)
            break;
        s = next;
    }
    return s;
}

/// Knot insertion along u so that both surfaces have the same u knots (their u domains equal).
void mergeKnotsU(NurbsSurface& a, NurbsSurface& b) {
    const double eps = 1e-10 * (a.knotsU.back() - a.knotsU.front());
    // Snap b's knots onto a's where they agree within rounding.
    for (double& k : b.knotsU)
        for (double ka : a.knotsU)
            if (std::abs(k - ka) <= eps)
                k = ka;
    const auto multiplicity = [](const std::vector<double>& k, double v) {
        return int(std::count(k.begin(), k.end(), v));
    };
    for (int pass = 0; pass < 2; ++pass) {
        NurbsSurface& to = pass == 0 ? a : b;
        const NurbsSurface& from = pass == 0 ? b : a;
        const Interval d = knotDomain(from.knotsU, from.degreeU);
        std::vector<double> values = from.knotsU;
        values.erase(std::unique(values.begin(), values.end()), values.end());
        for (double v : values) {
            if (v <= d.first || v >= d.last)
                continue;
            const int need = multiplicity(from.knotsU, v) - multiplicity(to.knotsU, v);
            if (need > 0)
                to = surfaceInsertKnotU(to, v, need);
        }
    }
}

double meanLength(const Row& r) {
    double sum = 0.0;
    for (const glm::dvec4& v : r)
        sum += glm::length(glm::dvec3(v));
    return r.empty() ? 0.0 : sum / double(r.size());
}

int rowsFor(MatchContinuity c) {
    return c == MatchContinuity::G0 ? 1 : c == MatchContinuity::G1 ? 2 : 3;
}

/// The exact match of `a` (its edge at v = first) to `b` (likewise): see matchSurface.
std::optional<NurbsSurface> matchExact(NurbsSurface a, NurbsSurface b, MatchContinuity c,
                                       QString* error) {
    // Along the edge, both run the same way.
    const Interval au = surfaceDomainU(a), bu = surfaceDomainU(b);
    const glm::dvec3 aStart = surfacePoint(a, au.first, surfaceDomainV(a).first);
    const glm::dvec3 bStart = surfacePoint(b, bu.first, surfaceDomainV(b).first);
    const glm::dvec3 bEnd = surfacePoint(b, bu.last, surfaceDomainV(b).first);
    if (glm::length(aStart - bEnd) < glm::length(aStart - bStart))
        b = reversedU(b);
    // The same parameter range along (an affine change of b's parameter moves nothing).
    const Interval bd = surfaceDomainU(b);
    for (double& k : b.knotsU)
        k = au.first + (k - bd.first) * (au.last - au.first) / (bd.last - bd.first);
    if (a.degreeU < b.degreeU)
        a = surfaceElevateDegreeU(a, b.degreeU - a.degreeU);
    if (b.degreeU < a.degreeU)
        b = surfaceElevateDegreeU(b, a.degreeU - b.degreeU);
    mergeKnotsU(a, b);
    if (a.countU != b.countU) {
        if (error)
            *error = QStringLiteral("the two edges' knots could not be made compatible");
        return std::nullopt;
    }
    b.knotsU = a.knotsU;
    if (c == MatchContinuity::G2 && a.degreeV < 2)
        a = surfaceElevateDegreeV(a, 2 - a.degreeV);
    a = withRowsAcross(a, rowsFor(c));
    Row dA1, dA2, dB1, dB2;
    crossDerivatives(a, dA1, dA2);
    crossDerivatives(b, dB1, dB2);
    // beta keeps the surface's own mean tangent length across the edge.
    const double lb = meanLength(dB1);
    const double beta = lb > 0.0 ? std::max(meanLength(dA1), 1e-12 * lb) / lb : 1.0;
    const int q = a.degreeV;
    const std::vector<double>& V = a.knotsV;
    Row p0 = row(b, 0), p1(p0.size()), p2(p0.size());
    for (size_t i = 0; i < p0.size(); ++i) {
        const glm::dvec4 d1 = -beta * dB1[i];
        p1[i] = p0[i] + d1 * (V[size_t(q + 1)] - V[1]) / double(q);
        if (c == MatchContinuity::G2) {
            const glm::dvec4 d2 = beta * beta * dB2[i];
            const glm::dvec4 e1 = d1 + d2 * (V[size_t(q + 1)] - V[2]) / double(q - 1);
            p2[i] = p1[i] + e1 * (V[size_t(q + 2)] - V[2]) / double(q);
        }
    }
    const bool ok = setRow(a, 0, p0) && (c == MatchContinuity::G0 || setRow(a, 1, p1)) &&
                    (c != MatchContinuity::G2 || setRow(a, 2, p2));
    if (!ok) {
        if (error)
            *error = QStringLiteral("the match gives weights that are not positive");
        return std::nullopt;
    }
    return a;
}

/// Solves the small dense system m x = r (Gaussian elimination with partial pivoting) for
/// each of the three coordinates; false when singular.
bool solve(std::vector<std::vector<double>> m, std::vector<glm::dvec3>& r) {
    const size_t n = r.size();
    for (size_t c = 0; c < n; ++c) {
        size_t pivot = c;
        for (size_t k = c + 1; k < n; ++k)
            if (std::abs(m[k][c]) > std::abs(m[pivot][c]))
                pivot = k;
        if (!(std::abs(m[pivot][c]) > 1e-300))
            return false;
        std::swap(m[c], m[pivot]);
        std::swap(r[c], r[pivot]);
        for (size_t k = c + 1; k < n; ++k) {
            const double f = m[k][c] / m[c][c];
            for (size_t j = c; j < n; ++j)
                m[k][j] -= f * m[c][j];
            r[k] -= f * r[c];
        }
    }
    for (size_t c = n; c-- > 0;) {
        for (size_t j = c + 1; j < n; ++j)
            r[c] -= m[c][j] * r[j];
        r[c] /= m[c][c];
    }
    return true;
}

/// The approximate match to an edge that is a trim curve: the boundary row by least squares
/// to the edge (by arc length), the next row turned into the neighbour's tangent planes.
std::optional<NurbsSurface> matchToCurve(NurbsSurface a, const SeamSide& edge, MatchContinuity c,
                                         QString* error) {
    // Freedom along: at least 12 control points.
    while (a.countU < 12) {
        const Interval d = surfaceDomainU(a);
        double widest = 0.0, at = 0.5 * (d.first + d.last);
        for (size_t k = size_t(a.degreeU); k + 1 < a.knotsU.size(); ++k)
            if (a.knotsU[k + 1] - a.knotsU[k] > widest) {
                widest = a.knotsU[k + 1] - a.knotsU[k];
                at = 0.5 * (a.knotsU[k] + a.knotsU[k + 1]);
            }
        const NurbsSurface next = surfaceInsertKnotU(a, at, 1);
        if (next.countU == a.countU)
            break;
        a = next;
    }
    a = withRowsAcross(a, rowsFor(c));
    const Interval du = surfaceDomainU(a), dv = surfaceDomainV(a);
    // The edge by arc length, oriented like a's edge.
    std::vector<double> length(edge.at.size(), 0.0);
    for (size_t k = 1; k < edge.at.size(); ++k)
        length[k] = length[k - 1] + glm::length(edge.at[k] - edge.at[k - 1]);
    const bool reversed = glm::length(surfacePoint(a, du.first, dv.first) - edge.at.back()) <
                          glm::length(surfacePoint(a, du.first, dv.first) - edge.at.front());
    const auto edgeAt = [&](double fraction, double& t) {
        const double s = (reversed ? 1.0 - fraction : fraction) * length.back();
        const size_t k = size_t(std::clamp<std::ptrdiff_t>(
            std::lower_bound(length.begin(), length.end(), s) - length.begin(), 1,
            std::ptrdiff_t(length.size()) - 1));
        const double f =
            length[k] > length[k - 1] ? (s - length[k - 1]) / (length[k] - length[k - 1]) : 0.0;
        t = edge.t[k - 1] + f * (edge.t[k] - edge.t[k - 1]);
        return seamSidePoint(edge, t);
    };
    const int n = a.countU;
    const int p = a.degreeU;
    const Row before0 = row(a, 0), before1 = row(a, 1);
    // Least squares with the ends fixed on the edge's ends: sum_i N_i w_i (P_i - E) = 0 at
    // 8 n samples, for the n - 2 inner points.
    std::vector<double> w(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i)
        w[size_t(i)] = a.weights[size_t(a.index(i, 0))];
    double t = 0.0;
    std::vector<glm::dvec3> fixed = {edgeAt(0.0, t), edgeAt(1.0, t)};
    const int inner = n - 2;
    std::vector<std::vector<double>> m(size_t(inner), std::vector<double>(size_t(inner), 0.0));
    std::vector<glm::dvec3> r(size_t(inner), glm::dvec3(0.0));
    std::vector<double> basis(size_t(p + 1));
    const int samples = 8 * n;
    for (int k = 0; k <= samples; ++k) {
        const double f = double(k) / samples;
        const double u = du.first + f * (du.last - du.first);
        const glm::dvec3 e = edgeAt(f, t);
        const int span = findSpan(p, a.knotsU, u);
        basisFunctions(span, u, p, a.knotsU, basis.data());
        std::vector<double> row(size_t(n), 0.0);
        double sum = 0.0;
        for (int j = 0; j <= p; ++j) {
            row[size_t(span - p + j)] = basis[size_t(j)] * w[size_t(span - p + j)];
            sum += row[size_t(span - p + j)];
        }
        // sum_i row_i P_i = sum E, with the ends known.
        glm::dvec3 rhs = sum * e - row[0] * fixed[0] - row[size_t(n - 1)] * fixed[1];
        for (int i = 1; i < n - 1; ++i) {
            if (row[size_t(i)] == 0.0)
                continue;
            for (int j = 1; j < n - 1; ++j)
                m[size_t(i - 1)][size_t(j - 1)] += row[size_t(i)] * row[size_t(j)];
            r[size_t(i - 1)] += row[size_t(i)] * rhs;
        }
    }
    if (!solve(m, r)) {
        if (error)
            *error = QStringLiteral("the edge could not be fitted");
        return std::nullopt;
    }
    a.points[size_t(a.index(0, 0))] = fixed[0];
    a.points[size_t(a.index(n - 1, 0))] = fixed[1];
    for (int i = 1; i < n - 1; ++i)
        a.points[size_t(a.index(i, 0))] = r[size_t(i - 1)];
    if (c == MatchContinuity::G0)
        return a;
    // The next row: its offset from the boundary turned into the neighbour's tangent plane at
    // the edge's point nearest the column's Greville abscissa, keeping its length.
    for (int i = 0; i < n; ++i) {
        const double g = grevilleAbscissa(a.knotsU, p, i);
        edgeAt((g - du.first) / (du.last - du.first), t);
        const glm::dvec2 uv = curvePoint(edge.curve, t);
        const glm::dvec3 normal = surfaceFrame(*edge.surface, uv.x, uv.y).normal;
        const glm::dvec3 offset = glm::dvec3(before1[size_t(i)]) / before1[size_t(i)].w -
                                  glm::dvec3(before0[size_t(i)]) / before0[size_t(i)].w;
        glm::dvec3 inPlane = offset - glm::dot(offset, normal) * normal;
        if (!(glm::length(inPlane) > 0.0))
            continue;
        inPlane *= glm::length(offset) / glm::length(inPlane);
        a.points[size_t(a.index(i, 1))] = a.points[size_t(a.index(i, 0))] + inPlane;
    }
    return a;
}

const Surface* findIn(const Scene& scene, SurfaceId id) {
    for (const Surface& s : scene.surfaces)
        if (s.id == id)
            return &s;
    return nullptr;
}

ContinuityClass asked(MatchContinuity c) {
    return c == MatchContinuity::G0   ? ContinuityClass::G0
           : c == MatchContinuity::G1 ? ContinuityClass::G1
                                      : ContinuityClass::G2;
}

/// G2 ranks above G1 above G0 above open.
int rank(ContinuityClass c) {
    return c == ContinuityClass::G2 ? 3 : c == ContinuityClass::G1 ? 2 : c == ContinuityClass::G0;
}

} // namespace

QString domainEdgeName(DomainEdge edge) {
    switch (edge) {
    case DomainEdge::U0:
        return QStringLiteral("U0");
    case DomainEdge::U1:
        return QStringLiteral("U1");
    case DomainEdge::V0:
        return QStringLiteral("V0");
    case DomainEdge::V1:
        return QStringLiteral("V1");
    case DomainEdge::None:
        break;
    }
    return {};
}

Expected<MatchResult> matchSurface(const Scene& scene, const MatchRequest& request,
                                   const ContinuityTolerances& tolerances) {
    const auto fail = [](const QString& why) {
        return Error(why);
    };
    const Surface* a = findIn(scene, request.surface);
    const Surface* b = findIn(scene, request.target.surface);
    if (!a || !b)
        return fail(QStringLiteral("no surface with id %1")
                        .arg((a ? request.target.surface : request.surface).value));
    if (request.edge == DomainEdge::None)
        return fail(QStringLiteral("name an edge of the surface's domain (U0, U1, V0, V1)"));
    if (!a->trims.empty())
        return fail(QStringLiteral("surface '%1' is trimmed: Match Surface moves an edge of an "
                                   "untrimmed surface")
                        .arg(a->name));
    if (a->id == b->id && request.target.domainEdge == request.edge)
        return fail(QStringLiteral("the edge cannot be matched to itself"));
    const std::optional<SeamSide> target =
        continuitySideCurve(*b, request.target, kContinuitySamples);
    if (!target)
        return fail(QStringLiteral("surface '%1' has no such edge").arg(b->name));
    const NurbsSurface aV0 = turned(a->geometry, request.edge, Turn::ToV0);
    if (!clampedAtStart(aV0.knotsV, aV0.degreeV))
        return fail(QStringLiteral("edge %1 of surface '%2' is not clamped")
                        .arg(domainEdgeName(request.edge), a->name));
    MatchResult result;
    QString why;
    std::optional<NurbsSurface> matched;
    if (request.target.domainEdge != DomainEdge::None && b->trims.empty()) {
        const NurbsSurface bV0 = turned(b->geometry, request.target.domainEdge, Turn::ToV0);
        if (!clampedAtStart(bV0.knotsV, bV0.degreeV))
            return fail(QStringLiteral("edge %1 of surface '%2' is not clamped")
                            .arg(domainEdgeName(request.target.domainEdge), b->name));
        matched = matchExact(aV0, bV0, request.continuity, &why);
        result.exact = true;
    } else {
        matched = matchToCurve(aV0, *target, request.continuity, &why);
    }
    if (!matched)
        return fail(why);
    result.geometry = turned(*matched, request.edge, Turn::Back);
    if (const Status valid = checkNurbsSurface(result.geometry); !valid)
        return fail(valid.message());
    // The kernel's measure of the edge as matched.
    Scene after = scene;
    for (Surface& s : after.surfaces)
        if (s.id == a->id)
            s.geometry = result.geometry;
    ContinuityEdge edge;
    edge.sides = {ContinuitySide{a->id, TrimLoopId{}, -1, request.edge}, request.target};
    result.measured = measureEdgeContinuity(after, edge, tolerances);
    const ContinuityClass want = asked(request.continuity);
    result.reached = rank(result.measured.continuity) >= rank(want);
    const EdgeContinuity& m = result.measured;
    const QString values = QStringLiteral("G0 %1, G1 %2 deg, G2 %3 %")
                               .arg(m.g0, 0, 'g', 3)
                               .arg(m.g1Degrees, 0, 'g', 3)
                               .arg(m.g2Percent, 0, 'g', 3);
    if (result.reached)
        result.summary =
            QStringLiteral("Matched %1: %2 (%3)")
                .arg(continuityClassName(want), continuityClassName(m.continuity), values);
    else
        result.summary =
            QStringLiteral("%1 not reached%2: the edge is %3 (%4)")
                .arg(continuityClassName(want),
                     result.exact ? QString()
                                  : QStringLiteral(" across a trimmed edge (approximated)"),
                     continuityClassName(m.continuity), values);
    return result;
}

std::optional<ContinuitySide> nearestSide(const Scene& scene, SurfaceId surface, DomainEdge edge,
                                          SurfaceId target) {
    const Surface* a = findIn(scene, surface);
    const Surface* b = findIn(scene, target);
    if (!a || !b)
        return std::nullopt;
    const std::optional<SeamSide> mine =
        continuitySideCurve(*a, ContinuitySide{surface, TrimLoopId{}, -1, edge}, 16);
    if (!mine)
        return std::nullopt;
    std::optional<ContinuitySide> best;
    double bestDistance = 0.0;
    for (const ContinuitySide& side : continuityBoundaries(*b)) {
        if (side.surface == surface && side.domainEdge == edge)
            continue;
        const std::optional<SeamSide> other = continuitySideCurve(*b, side, 16);
        if (!other)
            continue;
        double d = 0.0;
        for (const glm::dvec3& p : mine->at)
            d += nearestOnSeamSide(*other, p).distance;
        if (!best || d < bestDistance) {
            best = side;
            bestDistance = d;
        }
    }
    return best;
}

} // namespace kw
