// Seam gaps of shared edges on the exact surfaces (kw::seamGaps) and closed shells (closedShells).
#include "model/document/seamgaps.h"

#include <QHash>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <thread>

namespace kw {

glm::dvec3 seamSidePoint(const SeamSide& e, double t) {
    const glm::dvec2 uv = curvePoint(e.curve, t);
    return surfacePoint(*e.surface, uv.x, uv.y);
}

// `samples` parameters evenly over the domain, and every distinct knot inside it: the edge
// may bend sharply at a knot, where a gap also tends to be largest after a control point moved.
SeamSide makeSeamSide(const NurbsSurface& surface, const NurbsCurve2& curve, int samples,
                      const std::vector<double>& extra) {
    SeamSide e;
    e.surface = &surface;
    e.curve = curve;
    e.domain = curveDomain(curve);
    const Interval d = e.domain;
    samples = std::max(samples, 2);
    for (int i = 0; i < samples; ++i)
        e.t.push_back(d.first + (d.last - d.first) * double(i) / double(samples - 1));
    for (const std::vector<double>* knots : {&curve.knots, &extra})
        for (double k : *knots)
            if (k > d.first && k < d.last)
                e.t.push_back(k);
    std::sort(e.t.begin(), e.t.end());
    e.t.erase(std::unique(e.t.begin(), e.t.end()), e.t.end());
    e.at.reserve(e.t.size());
    for (double t : e.t)
        e.at.push_back(seamSidePoint(e, t));
    return e;
}

SeamFoot nearestOnSeamSide(const SeamSide& e, const glm::dvec3& p) {
    size_t nearest = 0;
    double nearestD2 = std::numeric_limits<double>::infinity();
    for (size_t j = 0; j < e.at.size(); ++j) {
        const glm::dvec3 d = e.at[j] - p;
        const double d2 = glm::dot(d, d);
        if (d2 < nearestD2) {
            nearestD2 = d2;
            nearest = j;
        }
    }
    // Newton's start: the foot on the chords to the nearest sample's neighbours, so that a side
    // passing close to p converges in one or two steps.
    double s = e.t[nearest];
    double chordD2 = std::numeric_limits<double>::infinity();
    for (const size_t other : {nearest - 1, nearest + 1}) {
        if (other >= e.at.size()) // also nearest - 1 wrapped below 0
            continue;
        const glm::dvec3 chord = e.at[other] - e.at[nearest];
        const double c2 = glm::dot(chord, chord);
        if (!(c2 > 0.0))
            continue;
        const double lambda = std::clamp(glm::dot(p - e.at[nearest], chord) / c2, 0.0, 1.0);
        const glm::dvec3 r = e.at[nearest] + lambda * chord - p;
        if (glm::dot(r, r) < chordD2) {
            chordD2 = glm::dot(r, r);
            s = e.t[nearest] + lambda * (e.t[other] - e.t[nearest]);
        }
    }
    SeamFoot foot;
    double best = std::numeric_limits<double>::infinity();
    const double length = e.domain.last - e.domain.first;
    bool evaluated = false;
    for (int iteration = 0; iteration < 12; ++iteration) {
        const CurveDerivatives2 c = curveDerivatives(e.curve, s);
        const SurfaceDerivatives sd = surfaceDerivatives(*e.surface, c.point.x, c.point.y);
        const glm::dvec3 r = sd.s - p;
        evaluated = true;
        if (glm::dot(r, r) < best) {
            best = glm::dot(r, r);
            foot.t = s;
            foot.uv = c.point;
            foot.derivatives = sd;
        }
        const glm::dvec3 c1 = sd.su * c.d1.x + sd.sv * c.d1.y;
        const glm::dvec3 c2 = sd.suu * (c.d1.x * c.d1.x) + 2.0 * sd.suv * (c.d1.x * c.d1.y) +
                              sd.svv * (c.d1.y * c.d1.y) + sd.su * c.d2.x + sd.sv * c.d2.y;
        const double f = glm::dot(c1, r);
        const double df = glm::dot(c2, r) + glm::dot(c1, c1);
        if (!(df > 0.0) || !std::isfinite(f / df))
            break;
        const double next = std::clamp(s - f / df, e.domain.first, e.domain.last);
        // Converged: the step left is below what the distance can notice.
        if (std::abs(next - s) <= 1e-12 * length)
            break;
        s = next;
        evaluated = false;
    }
    if (!evaluated) {
        const CurveDerivatives2 c = curveDerivatives(e.curve, s);
        const SurfaceDerivatives sd = surfaceDerivatives(*e.surface, c.point.x, c.point.y);
        const glm::dvec3 r = sd.s - p;
        if (glm::dot(r, r) < best) {
            best = glm::dot(r, r);
            foot.t = s;
            foot.uv = c.point;
            foot.derivatives = sd;
        }
    }
    // The nearest sample itself may be nearer still (Newton left towards another branch).
    if (nearestD2 < best) {
        best = nearestD2;
        foot.t = e.t[nearest];
        const CurveDerivatives2 c = curveDerivatives(e.curve, foot.t);
        foot.uv = c.point;
        foot.derivatives = surfaceDerivatives(*e.surface, c.point.x, c.point.y);
    }
    foot.distance = std::sqrt(best);
    return foot;
}

namespace {

/// The largest distance from a sample of `from` to the edge `to`, and where.
void farthest(const SeamSide& from, SurfaceId fromId, const SeamSide& to, SeamGap& gap) {
    for (const glm::dvec3& p : from.at) {
        const double d = nearestOnSeamSide(to, p).distance;
        if (d > gap.gap || !gap.whereOn.isValid()) {
            gap.gap = std::max(d, gap.gap);
            gap.where = p;
            gap.whereOn = fromId;
        }
    }
}

/// Fewest edges worth a thread of their own.
constexpr size_t kEdgesPerThread = 64;

SeamGap seamGap(const SharedEdge& edge, const QHash<SurfaceId, const Surface*>& surfaces,
                int samples) {
    SeamGap gap;
    gap.edge = edge.id;
    gap.faceA = edge.sides[0].surface;
    gap.faceB = edge.sides[1].surface;
    gap.tolerance = edge.tolerance;
    SeamSide sides[2];
    for (size_t k = 0; k < 2; ++k) {
        const EdgeUse& use = edge.sides[k];
        const Surface* s = surfaces.value(use.surface);
        const auto loop = s ? std::find_if(s->trims.begin(), s->trims.end(),
                                           [&](const TrimLoop& l) { return l.id == use.loop; })
                            : std::vector<TrimLoop>::const_iterator{};
        // Outside the precondition (a side the scene does not have): open, not a crash, so
        // that no export calls such a seam closed.
        if (!s || loop == s->trims.end() || use.curve < 0 ||
            size_t(use.curve) >= loop->curves.size()) {
            gap.gap = std::numeric_limits<double>::infinity();
            gap.whereOn = use.surface;
            return gap;
        }
        sides[k] = makeSeamSide(s->geometry, loop->curves[size_t(use.curve)], samples);
    }
    farthest(sides[0], edge.sides[0].surface, sides[1], gap);
    farthest(sides[1], edge.sides[1].surface, sides[0], gap);
    return gap;
}

} // namespace

void forEachRange(size_t count, size_t perThread,
                  const std::function<void(size_t from, size_t to)>& run) {
    const size_t threads =
        std::min<size_t>(std::max(1u, std::thread::hardware_concurrency()), count / perThread);
    if (threads <= 1) {
        run(0, count);
        return;
    }
    std::vector<std::thread> pool;
    const size_t chunk = (count + threads - 1) / threads;
    for (size_t t = 1; t < threads; ++t)
        pool.emplace_back(run, std::min(t * chunk, count), std::min((t + 1) * chunk, count));
    run(0, std::min(chunk, count));
    for (std::thread& t : pool)
        t.join();
}

std::vector<SeamGap> seamGaps(const Scene& scene, int samples) {
    samples = std::max(samples, kMinSeamSamples);
    QHash<SurfaceId, const Surface*> surfaces;
    for (const Surface& s : scene.surfaces)
        surfaces.insert(s.id, &s);
    const std::vector<SharedEdge>& edges = scene.topology.edges;
    std::vector<SeamGap> out(edges.size());
    const auto measure = [&](size_t from, size_t to) {
        for (size_t k = from; k < to; ++k)
            out[k] = seamGap(edges[k], surfaces, samples);
    };
    // Edges are independent and each costs ~0.3 ms: a model of thousands of edges is split
    // over the cores, each thread writing its own range of `out`.
    forEachRange(edges.size(), kEdgesPerThread, measure);
    return out;
}

std::vector<ShellState> closedShells(const Scene& scene, const std::vector<SeamGap>& gaps) {
    std::vector<ShellState> out;
    QHash<SurfaceId, size_t> shellOf;
    for (const Shell& shell : scene.topology.shells) {
        ShellState state;
        state.shell = shell.id;
        state.solid = shell.solid;
        state.faces = int(shell.faces.size());
        state.closed = shell.closed;
        for (SurfaceId f : shell.faces)
            shellOf.insert(f, out.size());
        out.push_back(state);
    }
    for (const SeamGap& gap : gaps) {
        const auto a = shellOf.constFind(gap.faceA);
        const auto b = shellOf.constFind(gap.faceB);
        for (const auto& it : {a, b}) {
            if (it == shellOf.cend() || (it == b && a != shellOf.cend() && *a == *b))
                continue; // counted once for a shell holding both sides
            ShellState& state = out[*it];
            state.largestGap = std::max(state.largestGap, gap.gap);
            if (gap.open()) {
                ++state.openEdges;
                state.closed = false;
            }
        }
    }
    return out;
}

} // namespace kw
