// The continuity kernel: which boundaries meet (record or matching) and G0/G1/G2 along them.
#include "model/analysis/continuity.h"

#include "model/nurbs/nurbs_curvature.h"

#include <QHash>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <set>

namespace kw {

namespace {

constexpr double kPi = 3.14159265358979323846;

const Surface* findSurface(const QHash<SurfaceId, const Surface*>& surfaces, SurfaceId id) {
    return surfaces.value(id, nullptr);
}

QHash<SurfaceId, const Surface*> surfaceIndex(const Scene& scene) {
    QHash<SurfaceId, const Surface*> out;
    for (const Surface& s : scene.surfaces)
        out.insert(s.id, &s);
    return out;
}

/// The straight line of a domain edge as a degree-1 curve whose parameter is the surface's
/// own parameter along it.
NurbsCurve2 domainEdgeCurve(const NurbsSurface& g, DomainEdge edge) {
    const Interval du = surfaceDomainU(g), dv = surfaceDomainV(g);
    NurbsCurve2 c;
    c.degree = 1;
    c.weights = {1.0, 1.0};
    switch (edge) {
    case DomainEdge::U0:
    case DomainEdge::U1: {
        const double u = edge == DomainEdge::U0 ? du.first : du.last;
        c.knots = {dv.first, dv.first, dv.last, dv.last};
        c.points = {{u, dv.first}, {u, dv.last}};
        break;
    }
    default: {
        const double v = edge == DomainEdge::V0 ? dv.first : dv.last;
        c.knots = {du.first, du.first, du.last, du.last};
        c.points = {{du.first, v}, {du.last, v}};
        break;
    }
    }
    return c;
}

double polylineLength(const SeamSide& s) {
    double length = 0.0;
    for (size_t k = 1; k < s.at.size(); ++k)
        length += glm::length(s.at[k] - s.at[k - 1]);
    return length;
}

/// The unit normal from first derivatives, and whether it is a plain one (Su x Sv usable);
/// where it is not (a pole, a collapsed edge), surfaceFrame's limit normal.
glm::dvec3 normalAt(const NurbsSurface& g, const SurfaceDerivatives& sd, glm::dvec2 uv,
                    bool& regular) {
    const glm::dvec3 n = glm::cross(sd.su, sd.sv);
    const double scale = glm::length(sd.su) * glm::length(sd.sv);
    regular = glm::length(n) > 1e-10 * scale && scale > 0.0;
    if (regular)
        return glm::normalize(n);
    return surfaceFrame(g, uv.x, uv.y).normal;
}

/// Normal curvature of the surface in tangent direction d against normal n: II(d) / I(d), with
/// d = a Su + b Sv solved from the first fundamental form.
std::optional<double> normalCurvature(const SurfaceDerivatives& sd, const glm::dvec3& n,
                                      const glm::dvec3& d) {
    const double E = glm::dot(sd.su, sd.su), F = glm::dot(sd.su, sd.sv), G = glm::dot(sd.sv, sd.sv);
    const double det = E * G - F * F;
    if (!(det > 1e-20 * E * G))
        return std::nullopt;
    const double pu = glm::dot(sd.su, d), pv = glm::dot(sd.sv, d);
    const double a = (G * pu - F * pv) / det, b = (E * pv - F * pu) / det;
    const double first = E * a * a + 2.0 * F * a * b + G * b * b;
    if (!(first > 0.0))
        return std::nullopt;
    const double second = glm::dot(sd.suu, n) * a * a + 2.0 * glm::dot(sd.suv, n) * a * b +
                          glm::dot(sd.svv, n) * b * b;
    const double k = second / first;
    return std::isfinite(k) ? std::optional<double>(k) : std::nullopt;
}

/// A boundary of a face without a record, sampled for matching.
struct Piece {
    ContinuitySide side;
    SeamSide curve;
    glm::dvec3 lo{0.0}, hi{0.0};
    double length = 0.0;
};

/// Samples of a piece for the match test: enough to see a piece leave the other on a bend.
constexpr int kMatchSamples = 17;

bool liesOn(const Piece& a, const Piece& b, double tolerance) {
    for (const glm::dvec3& p : a.curve.at)
        if (nearestOnSeamSide(b.curve, p).distance > tolerance)
            return false;
    return true;
}

bool boxesMeet(const Piece& a, const Piece& b, double tolerance) {
    for (int k = 0; k < 3; ++k)
        if (a.lo[k] > b.hi[k] + tolerance || b.lo[k] > a.hi[k] + tolerance)
            return false;
    return true;
}

/// Pairs the pieces whose samples all lie within tolerance of another piece (sweep over x).
void matchPieces(std::vector<Piece>& pieces, const ContinuityTolerances& tol,
                 ContinuityTopology& out) {
    std::sort(pieces.begin(), pieces.end(),
              [](const Piece& a, const Piece& b) { return a.lo.x < b.lo.x; });
    std::vector<bool> matched(pieces.size(), false);
    for (size_t i = 0; i < pieces.size(); ++i)
        for (size_t j = i + 1; j < pieces.size() && pieces[j].lo.x <= pieces[i].hi.x + tol.match;
             ++j) {
            if (!boxesMeet(pieces[i], pieces[j], tol.match))
                continue;
            const bool iOnJ = liesOn(pieces[i], pieces[j], tol.match);
            const bool jOnI = liesOn(pieces[j], pieces[i], tol.match);
            if (!iOnJ && !jOnI)
                continue;
            ContinuityEdge e;
            e.sides = {pieces[i].side, pieces[j].side};
            e.covers = {iOnJ, jOnI};
            if (e.sides[1] < e.sides[0]) {
                std::swap(e.sides[0], e.sides[1]);
                std::swap(e.covers[0], e.covers[1]);
            }
            out.edges.push_back(e);
            matched[i] = matched[j] = true;
        }
    for (size_t i = 0; i < pieces.size(); ++i)
        if (!matched[i])
            out.freeSides.push_back(pieces[i].side);
}

std::optional<Piece> makePiece(const Surface& s, const ContinuitySide& side) {
    std::optional<SeamSide> curve = continuitySideCurve(s, side, kMatchSamples);
    if (!curve)
        return std::nullopt;
    Piece p;
    p.side = side;
    p.curve = std::move(*curve);
    p.lo = p.hi = p.curve.at.front();
    for (const glm::dvec3& q : p.curve.at) {
        p.lo = glm::min(p.lo, q);
        p.hi = glm::max(p.hi, q);
    }
    p.length = polylineLength(p.curve);
    return p;
}

} // namespace

static QString continuityTolerancesReason(const ContinuityTolerances& t) {
    for (const auto& [value, name] : {std::pair{t.g0, "g0"},
                                      {t.g1Degrees, "g1Degrees"},
                                      {t.g2Percent, "g2Percent"},
                                      {t.match, "match"}})
        if (!std::isfinite(value) || value <= 0.0)
            return QStringLiteral("%1 must be a finite number above 0, not %2")
                .arg(QLatin1String(name))
                .arg(value);
    if (t.match < t.g0)
        return QStringLiteral("match (%1) must not be below g0 (%2)").arg(t.match).arg(t.g0);
    return {};
}

Status checkContinuityTolerances(const ContinuityTolerances& t) {
    if (const QString why = continuityTolerancesReason(t); !why.isEmpty())
        return Error(why);
    return ok();
}

QString continuityClassName(ContinuityClass c) {
    switch (c) {
    case ContinuityClass::G2:
        return QStringLiteral("G2");
    case ContinuityClass::G1:
        return QStringLiteral("G1");
    case ContinuityClass::G0:
        return QStringLiteral("G0");
    case ContinuityClass::Open:
        break;
    }
    return QStringLiteral("open");
}

std::optional<SeamSide> continuitySideCurve(const Surface& surface, const ContinuitySide& side,
                                            int samples) {
    if (side.surface != surface.id)
        return std::nullopt;
    const NurbsSurface& g = surface.geometry;
    if (side.domainEdge != DomainEdge::None) {
        const bool alongV = side.domainEdge == DomainEdge::U0 || side.domainEdge == DomainEdge::U1;
        return makeSeamSide(g, domainEdgeCurve(g, side.domainEdge), samples,
                            alongV ? g.knotsV : g.knotsU);
    }
    for (const TrimLoop& loop : surface.trims)
        if (loop.id == side.loop) {
            if (side.curve < 0 || size_t(side.curve) >= loop.curves.size())
                return std::nullopt;
            return makeSeamSide(g, loop.curves[size_t(side.curve)], samples);
        }
    return std::nullopt;
}

std::vector<ContinuitySide> continuityBoundaries(const Surface& s) {
    std::vector<ContinuitySide> out;
    if (s.trims.empty()) {
        for (DomainEdge e : {DomainEdge::U0, DomainEdge::U1, DomainEdge::V0, DomainEdge::V1})
            out.push_back(ContinuitySide{s.id, TrimLoopId{}, -1, e});
        return out;
    }
    for (const TrimLoop& loop : s.trims)
        for (int c = 0; c < int(loop.curves.size()); ++c)
            out.push_back(ContinuitySide{s.id, loop.id, c, DomainEdge::None});
    return out;
}

ContinuityTopology continuityTopology(const Scene& scene, const ContinuityTolerances& tol) {
    ContinuityTopology out;
    const QHash<SurfaceId, const Surface*> surfaces = surfaceIndex(scene);
    std::set<SurfaceId> recordedFaces;
    std::set<ContinuitySide> recordedSides;
    for (const SharedEdge& shared : scene.topology.edges) {
        ContinuityEdge e;
        e.recorded = shared.id;
        e.tolerance = shared.tolerance;
        bool resolved = true, degenerate = false;
        for (size_t k = 0; k < 2; ++k) {
            const EdgeUse& use = shared.sides[k];
            e.sides[k] = ContinuitySide{use.surface, use.loop, use.curve, DomainEdge::None};
            recordedFaces.insert(use.surface);
            const Surface* s = findSurface(surfaces, use.surface);
            const std::optional<SeamSide> curve =
                s ? continuitySideCurve(*s, e.sides[k], kMatchSamples) : std::nullopt;
            if (!curve) {
                ++out.unresolvedSides;
                resolved = false;
            } else if (polylineLength(*curve) <= tol.g0) {
                degenerate = true;
            }
        }
        // The sides of an edge that cannot be measured meet nothing: free if they exist.
        if (!resolved)
            continue;
        recordedSides.insert(e.sides.begin(), e.sides.end());
        if (degenerate)
            out.degenerateSides.insert(out.degenerateSides.end(), e.sides.begin(), e.sides.end());
        else
            out.edges.push_back(e);
    }
    std::vector<Piece> pieces;
    for (const Surface& s : scene.surfaces) {
        const bool recorded = recordedFaces.count(s.id) > 0;
        if (!recorded)
            ++out.matchedFaces;
        for (const ContinuitySide& side : continuityBoundaries(s)) {
            if (recorded && recordedSides.count(side))
                continue;
            std::optional<Piece> piece = makePiece(s, side);
            if (!piece)
                continue;
            if (piece->length <= tol.g0)
                out.degenerateSides.push_back(side);
            else if (recorded)
                out.freeSides.push_back(side); // the record names every edge its faces share
            else
                pieces.push_back(std::move(*piece));
        }
    }
    matchPieces(pieces, tol, out);
    std::sort(out.freeSides.begin(), out.freeSides.end());
    return out;
}

namespace {

EdgeContinuity measureEdge(const QHash<SurfaceId, const Surface*>& surfaces,
                           const ContinuityEdge& edge, const ContinuityTolerances& tol,
                           int samples) {
    EdgeContinuity r;
    r.edge = edge;
    samples = std::max(samples, 64);
    const Surface* faces[2] = {nullptr, nullptr};
    std::optional<SeamSide> sides[2];
    for (size_t k = 0; k < 2; ++k) {
        faces[k] = findSurface(surfaces, edge.sides[k].surface);
        if (faces[k])
            sides[k] = continuitySideCurve(*faces[k], edge.sides[k], samples);
        if (!sides[k]) {
            r.g0 = std::numeric_limits<double>::infinity();
            r.continuity = ContinuityClass::Open;
            return r;
        }
    }
    // Curvatures are compared against the larger one, or against a flat floor relative to the
    // edge's size, so rounding on two flat faces is no jump.
    glm::dvec3 lo = sides[0]->at.front(), hi = lo;
    for (const glm::dvec3& p : sides[0]->at) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    const double flat = kFlatCurvature / std::max(glm::length(hi - lo), 1e-300);
    bool first = true;
    // One sample of side `from`: its foot on `to`, the gap, the angle and the curvature jump.
    const auto measureAt = [&](const SeamSide& from, const SeamSide& to, size_t i) {
        const glm::dvec3& p = from.at[i];
        const SeamFoot foot = nearestOnSeamSide(to, p);
        ++r.samples;
        if (foot.distance > r.g0 || first) {
            r.g0 = std::max(r.g0, foot.distance);
            r.g0At = p;
        }
        const CurveDerivatives2 c = curveDerivatives(from.curve, from.t[i]);
        const SurfaceDerivatives a = surfaceDerivatives(*from.surface, c.point.x, c.point.y);
        const SurfaceDerivatives& b = foot.derivatives;
        bool regularA = false, regularB = false;
        const glm::dvec3 na = normalAt(*from.surface, a, c.point, regularA);
        const glm::dvec3 nb = normalAt(*to.surface, b, foot.uv, regularB);
        const double angle =
            std::atan2(glm::length(glm::cross(na, nb)), std::abs(glm::dot(na, nb))) * 180.0 / kPi;
        if (angle > r.g1Degrees || first) {
            r.g1Degrees = std::max(r.g1Degrees, angle);
            r.g1At = p;
        }
        first = false;
        const glm::dvec3 tangent = a.su * c.d1.x + a.sv * c.d1.y;
        if (!regularA || !regularB || !(glm::length(tangent) > 0.0))
            return foot.t;
        const glm::dvec3 acrossA = glm::cross(na, tangent), acrossB = glm::cross(nb, tangent);
        if (!(glm::length(acrossA) > 0.0) || !(glm::length(acrossB) > 0.0))
            return foot.t;
        const std::optional<double> ka = normalCurvature(a, na, glm::normalize(acrossA));
        std::optional<double> kb = normalCurvature(b, nb, glm::normalize(acrossB));
        if (!ka || !kb)
            return foot.t;
        // Against the same normal: a face whose normal points the other way bends the same
        // way with the opposite sign.
        if (glm::dot(na, nb) < 0.0)
            *kb = -*kb;
        ++r.g2Samples;
        const double scale = std::max({std::abs(*ka), std::abs(*kb), flat});
        const double jump = 100.0 * std::abs(*ka - *kb) / scale;
        if (jump > r.g2Percent) {
            r.g2Percent = jump;
            r.g2At = p;
        }
        return foot.t;
    };
    // Every sample of the first covering side; of the other (when it covers too), the samples
    // beyond the stretch the first side's feet reached (where it is longer, or was pulled
    // along itself), its ends and every eighth: seen from close curves the largest distance is
    // nearly the same both ways, and this halves the cost of a drag step.
    const size_t k0 = edge.covers[0] ? 0 : 1;
    const SeamSide& a = *sides[k0];
    const SeamSide& b = *sides[1 - k0];
    double reachedFirst = b.domain.last, reachedLast = b.domain.first;
    for (size_t i = 0; i < a.t.size(); ++i) {
        const double t = measureAt(a, b, i);
        reachedFirst = std::min(reachedFirst, t);
        reachedLast = std::max(reachedLast, t);
    }
    if (edge.covers[0] && edge.covers[1]) {
        const double margin = 1e-9 * (b.domain.last - b.domain.first);
        for (size_t i = 0; i < b.t.size(); ++i)
            if (i % 8 == 0 || i + 1 == b.t.size() || b.t[i] < reachedFirst - margin ||
                b.t[i] > reachedLast + margin)
                measureAt(b, a, i);
    }
    r.continuity = classifyContinuity(r, tol);
    return r;
}

} // namespace

EdgeContinuity measureEdgeContinuity(const Scene& scene, const ContinuityEdge& edge,
                                     const ContinuityTolerances& tol, int samples) {
    return measureEdge(surfaceIndex(scene), edge, tol, samples);
}

ContinuityClass classifyContinuity(const EdgeContinuity& e, const ContinuityTolerances& t) {
    if (!(e.g0 <= std::max(t.g0, e.edge.tolerance)))
        return ContinuityClass::Open;
    if (!(e.g1Degrees <= t.g1Degrees))
        return ContinuityClass::G0;
    if (!(e.g2Percent <= t.g2Percent))
        return ContinuityClass::G1;
    return ContinuityClass::G2;
}

int ContinuityReport::count(ContinuityClass c) const {
    return int(std::count_if(edges.begin(), edges.end(),
                             [c](const EdgeContinuity& e) { return e.continuity == c; }));
}

ContinuityReport continuityReport(const Scene& scene, const ContinuityTolerances& tol) {
    ContinuityReport report;
    report.tolerances = tol;
    report.topology = continuityTopology(scene, tol);
    const std::vector<ContinuityEdge>& edges = report.topology.edges;
    report.edges.resize(edges.size());
    const QHash<SurfaceId, const Surface*> surfaces = surfaceIndex(scene);
    const auto measure = [&](size_t from, size_t to) {
        for (size_t k = from; k < to; ++k)
            report.edges[k] = measureEdge(surfaces, edges[k], tol, kContinuitySamples);
    };
    // Edges are independent, ~1 ms each: thousands are shared out over the cores, each thread
    // writing its own range.
    constexpr size_t kEdgesPerThread = 32;
    forEachRange(edges.size(), kEdgesPerThread, measure);
    return report;
}

bool measureContinuity(ContinuityReport& report, const Scene& scene,
                       const std::function<bool(size_t done, size_t total)>& progress) {
    const std::vector<ContinuityEdge>& edges = report.topology.edges;
    report.edges.resize(edges.size());
    const QHash<SurfaceId, const Surface*> surfaces = surfaceIndex(scene);
    const ContinuityTolerances tol = report.tolerances;
    // Blocks of ~0.1-0.3 s on two cores: progress often enough to read and a cancel that
    // takes effect soon, few enough that the threads' start costs nothing.
    constexpr size_t kBlock = 256, kEdgesPerThread = 32;
    for (size_t from = 0; from < edges.size(); from += kBlock) {
        if (progress && !progress(from, edges.size()))
            return false;
        const size_t to = std::min(edges.size(), from + kBlock);
        forEachRange(to - from, kEdgesPerThread, [&](size_t a, size_t b) {
            for (size_t k = from + a; k < from + b; ++k)
                report.edges[k] = measureEdge(surfaces, edges[k], tol, kContinuitySamples);
        });
    }
    return !progress || progress(edges.size(), edges.size());
}

ContinuityReport continuityWatch(const Scene& scene, const ContinuityTolerances& tol) {
    ContinuityReport report;
    report.tolerances = tol;
    report.topology = continuityTopology(scene, tol);
    report.edges.resize(report.topology.edges.size());
    for (size_t k = 0; k < report.edges.size(); ++k)
        report.edges[k].edge = report.topology.edges[k];
    return report;
}

SeamOpening seamsOpenAt(const ContinuityReport& report, const std::vector<SurfaceId>& faces) {
    SeamOpening out;
    for (const EdgeContinuity& e : report.edges) {
        if (e.continuity != ContinuityClass::Open)
            continue;
        if (!std::binary_search(faces.begin(), faces.end(), e.edge.sides[0].surface) &&
            !std::binary_search(faces.begin(), faces.end(), e.edge.sides[1].surface))
            continue;
        ++out.open;
        out.largestGap = std::max(out.largestGap, e.g0);
    }
    return out;
}

QString seamOpeningText(const SeamOpening& o, const QString& unit) {
    if (o.open == 0)
        return {};
    return QStringLiteral("opens %1 seam%2, max gap %3%4")
        .arg(o.open)
        .arg(o.open == 1 ? QString() : QStringLiteral("s"))
        .arg(o.largestGap, 0, 'g', 3)
        .arg(unit.isEmpty() ? QString() : QLatin1Char(' ') + unit);
}

std::vector<size_t> edgesOfFace(const ContinuityTopology& topology, SurfaceId surface) {
    std::vector<size_t> out;
    for (size_t k = 0; k < topology.edges.size(); ++k)
        if (topology.edges[k].sides[0].surface == surface ||
            topology.edges[k].sides[1].surface == surface)
            out.push_back(k);
    return out;
}

int updateContinuity(ContinuityReport& report, const Scene& scene,
                     const std::vector<SurfaceId>& faces) {
    int measured = 0;
    QHash<SurfaceId, const Surface*> surfaces;
    for (const Surface& s : scene.surfaces)
        if (std::binary_search(faces.begin(), faces.end(), s.id))
            surfaces.insert(s.id, &s);
    for (size_t k = 0; k < report.topology.edges.size(); ++k) {
        const ContinuityEdge& e = report.topology.edges[k];
        if (!std::binary_search(faces.begin(), faces.end(), e.sides[0].surface) &&
            !std::binary_search(faces.begin(), faces.end(), e.sides[1].surface))
            continue;
        // The other side of an edge may lie on a face that did not change.
        for (const ContinuitySide& side : e.sides)
            if (!surfaces.contains(side.surface))
                for (const Surface& s : scene.surfaces)
                    if (s.id == side.surface)
                        surfaces.insert(s.id, &s);
        report.edges[k] = measureEdge(surfaces, e, report.tolerances, kContinuitySamples);
        ++measured;
    }
    return measured;
}

} // namespace kw
