// Document: the one place the scene changes; validates, counts revisions and signals.
#include "model/document/document.h"

#include "model/analysis/continuity.h"
#include "model/document/edit_checks.h"
#include "model/document/seamkeeper.h"
#include "model/document/validation.h"
#include "model/nurbs/analytic_eval.h"

#include <QHashFunctions>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <set>
#include <utility>

// A valid call that would change nothing (same name, same positions, same lights...) is ok()
// and emits nothing, so a no-op never costs an upload.

namespace kw {

namespace {

// splitmix64's finaliser (Steele, Lea and Flood 2014): every input bit reaches every output bit.
std::uint64_t mix64(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

std::uint64_t bitsOf(double d) {
    d += 0.0; // -0 and +0 compare equal, so they digest alike
    std::uint64_t b;
    std::memcpy(&b, &d, sizeof b);
    return b;
}

// One control point's share of Document::NetDigest::points: the net's digest is the sum (mod
// 2^64) of these, so moving a point changes it by two terms.
std::uint64_t pointDigest(int index, const glm::dvec3& p, double w) {
    std::uint64_t h = mix64(std::uint64_t(index));
    for (double x : {p.x, p.y, p.z, w})
        h = mix64(h ^ bitsOf(x));
    return h;
}

Document::NetDigest netDigest(const NurbsSurface& g) {
    Document::NetDigest d;
    std::uint64_t h = mix64(std::uint64_t(g.degreeU) << 32 | std::uint32_t(g.degreeV));
    h = mix64(h ^ (std::uint64_t(std::uint32_t(g.countU)) << 32 | std::uint32_t(g.countV)));
    for (const std::vector<double>* knots : {&g.knotsU, &g.knotsV}) {
        h = mix64(h ^ knots->size());
        for (double k : *knots)
            h = mix64(h ^ bitsOf(k));
    }
    d.shape = h;
    for (size_t i = 0; i < g.points.size(); ++i)
        d.points += pointDigest(int(i), g.points[i], g.weights[i]);
    return d;
}

constexpr std::uint32_t kMaxId = std::numeric_limits<std::uint32_t>::max();

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Surface and loop ids come from one counter (docs/FILE_FORMAT.md), so a new id must differ
// from every surface and loop id in use.
bool idUsed(const Scene& scene, std::uint32_t id) {
    for (const Surface& s : scene.surfaces) {
        if (s.id.value == id)
            return true;
        for (const TrimLoop& l : s.trims)
            if (l.id.value == id)
                return true;
    }
    return false;
}

// Revisions come from one counter shared by every Document of the process, so no value is handed
// out twice, not even by two documents: a cache keyed by a document's address and revision (the
// renderer's accumulated frame, its analysis range) cannot mistake a new document at the old
// address for the old one.
std::uint64_t processRevision() {
    static std::atomic<std::uint64_t> counter{0};
    return ++counter;
}

Error noSurface(SurfaceId id) {
    return Error(QStringLiteral("no surface with id %1").arg(id.value));
}

int loopIndex(const Surface& s, TrimLoopId id) {
    for (size_t i = 0; i < s.trims.size(); ++i)
        if (s.trims[i].id == id)
            return int(i);
    return -1;
}

// A 64-bit digest of a surface's shape: degrees, knots, control points, weights and trim
// curves, as their bytes (an undo restores the very values). Names, ids, display and marks are
// left out. It is taken on every edit of a face of an opened solid (closeSolid), once per drag
// step, so a fast hash (qHashBits, chained through the seed): SHA-1 cost 0.29 ms per step on a
// 100 x 100 surface, qHashBits 0.04 ms. A collision would only mark an opened solid again.
size_t shapeDigest(const Surface& s) {
    size_t seed = 0;
    const auto ints = [&seed](std::initializer_list<std::int64_t> values) {
        for (std::int64_t v : values)
            seed = qHashBits(&v, sizeof v, seed);
    };
    const auto bytes = [&seed, &ints](const auto& values) {
        ints({std::int64_t(values.size())});
        seed = qHashBits(values.data(), values.size() * sizeof(values[0]), seed);
    };
    const NurbsSurface& g = s.geometry;
    ints({g.degreeU, g.degreeV, g.countU, g.countV});
    bytes(g.knotsU);
    bytes(g.knotsV);
    bytes(g.points);
    bytes(g.weights);
    ints({std::int64_t(s.trims.size())});
    for (const TrimLoop& loop : s.trims) {
        ints({std::int64_t(loop.curves.size())});
        for (const NurbsCurve2& c : loop.curves) {
            ints({c.degree});
            bytes(c.knots);
            bytes(c.points);
            bytes(c.weights);
        }
    }
    return seed;
}

} // namespace

// ---- The edit checks (edit_checks.h)

Status checkInsertSurface(const Scene& scene, int index, const Surface& surface) {
    if (index < 0 || size_t(index) > scene.surfaces.size())
        return Error(QStringLiteral("surface index %1 out of range").arg(index));
    if (Status valid = checkSurface(surface); !valid)
        return valid;
    if (idUsed(scene, surface.id.value))
        return Error(QStringLiteral("surface id %1 already used").arg(surface.id.value));
    if (surface.id.value == kMaxId)
        return Error(QStringLiteral("id %1 leaves no room for new ids").arg(kMaxId));
    if (scene.surfaces.size() >= size_t(kMaxSurfaces))
        return Error(QStringLiteral("%1 surfaces, more than the limit %2")
                         .arg(scene.surfaces.size() + 1)
                         .arg(kMaxSurfaces));
    for (const TrimLoop& l : surface.trims) {
        if (l.id.value == kMaxId)
            return Error(QStringLiteral("id %1 leaves no room for new ids").arg(kMaxId));
        if (l.id == TrimLoopId{surface.id.value} || idUsed(scene, l.id.value))
            return Error(QStringLiteral("trim loop id %1 already used").arg(l.id.value));
    }
    return ok();
}

Status checkInsertTrimLoop(const Scene& scene, const Surface& target, int index,
                           const TrimLoop& loop) {
    if (index < 0 || size_t(index) > target.trims.size())
        return Error(QStringLiteral("trim loop index %1 out of range").arg(index));
    if (Status valid = checkTrimLoop(loop); !valid)
        return valid;
    if (loop.id.value == kMaxId)
        return Error(QStringLiteral("id %1 leaves no room for new ids").arg(kMaxId));
    if (idUsed(scene, loop.id.value))
        return Error(QStringLiteral("trim loop id %1 already used").arg(loop.id.value));
    if (target.trims.size() >= size_t(kMaxTrimLoops))
        return Error(QStringLiteral("%1 trim loops, more than the limit %2")
                         .arg(target.trims.size() + 1)
                         .arg(kMaxTrimLoops));
    return ok();
}

Status checkSurfaceName(const QString& name) {
    if (name.trimmed().isEmpty())
        return Error(QStringLiteral("a surface name needs a visible character"));
    return ok();
}

Document::Document(QObject* parent) : QObject(parent), m_walkFrom(processRevision()) {
    qRegisterMetaType<kw::SurfaceId>();
    qRegisterMetaType<kw::Aspects>();
}

const Surface* Document::surface(SurfaceId id) const {
    const int i = indexOf(id);
    return i < 0 ? nullptr : &m_scene.surfaces[size_t(i)];
}

int Document::indexOf(SurfaceId id) const {
    if (!id.isValid())
        return -1;
    for (size_t i = 0; i < m_scene.surfaces.size(); ++i)
        if (m_scene.surfaces[i].id == id)
            return int(i);
    return -1;
}

Revisions Document::revisions(SurfaceId id) const {
    const int i = indexOf(id);
    return i < 0 ? Revisions{} : m_revisions[size_t(i)];
}

// Ids come from nextId and are never handed out twice; an undone AddSurface keeps its id, so
// undo never lowers nextId. Returns an invalid id only if the 32-bit space is exhausted.
SurfaceId Document::allocateSurfaceId() {
    if (m_scene.nextId == kMaxId)
        return {};
    return SurfaceId{m_scene.nextId++};
}

TrimLoopId Document::allocateTrimLoopId() {
    if (m_scene.nextId == kMaxId)
        return {};
    return TrimLoopId{m_scene.nextId++};
}

Status Document::resetScene(Scene scene) {
    std::uint32_t maxId = 0;
    for (const Surface& s : scene.surfaces) {
        maxId = std::max(maxId, s.id.value);
        for (const TrimLoop& l : s.trims)
            maxId = std::max(maxId, l.id.value);
    }
    if (maxId == kMaxId)
        return Error(QStringLiteral("id %1 leaves no room for new ids").arg(maxId));
    scene.nextId = std::max(scene.nextId, maxId + 1);
    if (Status valid = validate(scene); !valid)
        return valid;
    Q_EMIT sceneAboutToBeReset();
    m_scene = std::move(scene);
    m_markedFaces.clear();
    m_takenWithSurface.clear();
    m_takenWithLoop.clear();
    for (const Surface& s : m_scene.surfaces)
        if (s.solid >= 0)
            m_markedFaces.insert(s.id, MarkedFace{s.solid, shapeDigest(s)});
    m_analyticOrigins.clear();
    for (const Surface& s : m_scene.surfaces)
        if (s.analytic.kind != AnalyticForm::Kind::None) {
            const NetDigest net = netDigest(s.geometry);
            m_analyticOrigins.insert(s.id, AnalyticOrigin{net, s.analytic, {}, {}, net});
        }
    const std::uint64_t rev = nextRevision();
    m_revisions.assign(m_scene.surfaces.size(), Revisions{rev, rev, rev, rev});
    m_lightsRevision = rev;
    m_cameraRevision = rev;
    m_marksRevision = rev;
    changedStructure();
    Q_EMIT sceneReset();
    return ok();
}

Status Document::insertSurface(int index, Surface surface) {
    if (Status allowed = checkInsertSurface(m_scene, index, surface); !allowed)
        return allowed;
    std::uint32_t maxId = surface.id.value;
    for (const TrimLoop& l : surface.trims)
        maxId = std::max(maxId, l.id.value);
    const SurfaceId id = surface.id;
    surface.solid = -1; // joins no solid: its siblings' marks may have been cleared meanwhile
    if (const auto origin = m_analyticOrigins.find(surface.id); origin != m_analyticOrigins.end())
        origin->current = netDigest(surface.geometry); // the undo of its removal
    else if (surface.analytic.kind != AnalyticForm::Kind::None) {
        const NetDigest net = netDigest(surface.geometry);
        m_analyticOrigins.insert(surface.id, AnalyticOrigin{net, surface.analytic, {}, {}, net});
    }
    Q_EMIT surfaceAboutToBeInserted(index);
    m_scene.surfaces.insert(m_scene.surfaces.begin() + index, std::move(surface));
    const std::uint64_t rev = nextRevision();
    m_revisions.insert(m_revisions.begin() + index, Revisions{rev, rev, rev, rev});
    m_scene.nextId = std::max(m_scene.nextId, maxId + 1);
    if (const auto taken = m_takenWithSurface.constFind(id); taken != m_takenWithSurface.cend()) {
        restoreTopology(m_scene, *taken); // the undo of the surface's removal
        m_takenWithSurface.erase(taken);
    }
    changedStructure();
    Q_EMIT surfaceInserted(id, index);
    closeSolid(id); // the undo of a face's removal
    return ok();
}

Status Document::removeSurface(SurfaceId id) {
    const int index = indexOf(id);
    if (index < 0)
        return noSurface(id);
    const int solid = m_scene.surfaces[size_t(index)].solid;
    Q_EMIT surfaceAboutToBeRemoved(id, index);
    if (TopologyPiece taken = takeSurfaceTopology(m_scene.topology, id); !taken.empty())
        m_takenWithSurface.insert(id, std::move(taken));
    m_scene.surfaces.erase(m_scene.surfaces.begin() + index);
    m_revisions.erase(m_revisions.begin() + index);
    nextRevision(); // the scene changed, though no surface's revisions did
    changedStructure();
    Q_EMIT surfaceRemoved(id);
    openSolid(solid);
    return ok();
}

Status Document::setName(SurfaceId id, const QString& name) {
    Surface* s = mutableSurface(id);
    if (!s)
        return noSurface(id);
    if (Status valid = checkSurfaceName(name); !valid)
        return valid;
    if (s->name == name)
        return ok();
    s->name = name;
    bump(id, Aspect::Name);
    return ok();
}

Status Document::checkControlPoints(SurfaceId id, const std::vector<int>& indices,
                                    const std::vector<glm::dvec3>& positions) const {
    const Surface* s = surface(id);
    if (!s)
        return noSurface(id);
    if (indices.empty() || indices.size() != positions.size())
        return Error(QStringLiteral("need one position per control point"));
    std::set<int> seen;
    for (size_t k = 0; k < indices.size(); ++k) {
        const int i = indices[k];
        if (i < 0 || size_t(i) >= s->geometry.points.size())
            return Error(QStringLiteral("control point index %1 out of range").arg(i));
        if (!seen.insert(i).second)
            return Error(QStringLiteral("control point %1 listed twice").arg(i));
        if (!finite(positions[k]))
            return Error(QStringLiteral("control point positions must be finite"));
    }
    return ok();
}

Status Document::setControlPoints(SurfaceId id, const std::vector<int>& indices,
                                  const std::vector<glm::dvec3>& positions) {
    return setControlPoints(id, indices, positions, m_seamLink);
}

Status Document::setControlPoints(SurfaceId id, const std::vector<int>& indices,
                                  const std::vector<glm::dvec3>& positions, SeamLink link) {
    return moveControlPoints(id, indices, positions, link, false);
}

Status Document::placeControlPoints(SurfaceId id, const std::vector<glm::dvec3>& positions) {
    std::vector<int> indices(positions.size());
    for (size_t k = 0; k < indices.size(); ++k)
        indices[k] = int(k);
    const Surface* s = surface(id);
    if (!s)
        return noSurface(id);
    if (positions.size() != s->geometry.points.size())
        return Error(QStringLiteral("need %1 positions, one per control point of surface %2")
                         .arg(s->geometry.points.size())
                         .arg(id.value));
    return moveControlPoints(id, indices, positions, m_seamLink, true);
}

Status Document::moveControlPoints(SurfaceId id, const std::vector<int>& indices,
                                   const std::vector<glm::dvec3>& positions, SeamLink link,
                                   bool placement) {
    if (Status valid = checkControlPoints(id, indices, positions); !valid)
        return valid;
    Surface* s = mutableSurface(id);
    // The net before a placement, for the form to follow: the only copy, and only then.
    std::optional<NurbsSurface> before;
    if (placement && s->analytic.kind != AnalyticForm::Kind::None)
        before = s->geometry;
    // The neighbours' points that move with these, from the positions before the move.
    const std::vector<LinkedMove> linked =
        link == SeamLink::Off
            ? std::vector<LinkedMove>{}
            : linkedMoves(m_scene, id, indices, positions, link == SeamLink::Tangency);
    bool changed = false;
    for (size_t k = 0; k < indices.size(); ++k) {
        glm::dvec3& p = s->geometry.points[size_t(indices[k])];
        if (p == positions[k])
            continue;
        changed = true;
        const double w = s->geometry.weights[size_t(indices[k])];
        digestPoint(id, indices[k], p, w, positions[k], w);
        p = positions[k];
    }
    std::vector<SurfaceId> others;
    for (const LinkedMove& m : linked) {
        Surface* o = mutableSurface(m.surface);
        glm::dvec3& p = o->geometry.points[size_t(m.index)];
        if (p == m.position)
            continue;
        const double w = o->geometry.weights[size_t(m.index)];
        digestPoint(m.surface, m.index, p, w, m.position, w);
        p = m.position;
        if (m.surface == id)
            changed = true;
        else if (std::find(others.begin(), others.end(), m.surface) == others.end())
            others.push_back(m.surface);
    }
    if (changed)
        bump(id, Aspect::Points, before ? &*before : nullptr);
    for (SurfaceId o : others)
        bump(o, Aspect::Points);
    return ok();
}

Status Document::checkWeight(SurfaceId id, int index, double weight) const {
    const Surface* s = surface(id);
    if (!s)
        return noSurface(id);
    if (index < 0 || size_t(index) >= s->geometry.weights.size())
        return Error(QStringLiteral("control point index %1 out of range").arg(index));
    if (!std::isfinite(weight) || weight <= 0)
        return Error(QStringLiteral("weight %1 must be finite and > 0").arg(weight));
    return ok();
}

Status Document::setWeight(SurfaceId id, int index, double weight) {
    if (Status valid = checkWeight(id, index, weight); !valid)
        return valid;
    Surface* s = mutableSurface(id);
    double& w = s->geometry.weights[size_t(index)];
    if (w == weight)
        return ok();
    digestPoint(id, index, s->geometry.points[size_t(index)], w, s->geometry.points[size_t(index)],
                weight);
    w = weight;
    bump(id, Aspect::Points);
    return ok();
}

Status Document::setGeometry(SurfaceId id, const NurbsSurface& geometry) {
    Surface* s = mutableSurface(id);
    if (!s)
        return noSurface(id);
    if (Status valid = checkNurbsSurface(geometry); !valid)
        return valid;
    const NurbsSurface& old = s->geometry;
    Aspects aspects;
    if (old.degreeU != geometry.degreeU || old.degreeV != geometry.degreeV ||
        old.countU != geometry.countU || old.countV != geometry.countV ||
        old.knotsU != geometry.knotsU || old.knotsV != geometry.knotsV)
        aspects |= Aspect::Knots;
    if (old.points != geometry.points || old.weights != geometry.weights)
        aspects |= Aspect::Points;
    if (!aspects)
        return ok();
    s->geometry = geometry;
    digestNet(id, geometry);
    bump(id, aspects);
    return ok();
}

Status Document::setPartitions(SurfaceId id, int nu, int nv) {
    Surface* s = mutableSurface(id);
    if (!s)
        return noSurface(id);
    if (Status valid = checkPartitions(nu, nv); !valid)
        return valid;
    if (s->partitionsU == nu && s->partitionsV == nv)
        return ok();
    s->partitionsU = nu;
    s->partitionsV = nv;
    bump(id, Aspect::Display);
    return ok();
}

Status Document::setMaterial(SurfaceId id, const Material& material) {
    Surface* s = mutableSurface(id);
    if (!s)
        return noSurface(id);
    if (Status valid = checkMaterial(material); !valid)
        return valid;
    if (s->material == material)
        return ok();
    s->material = material;
    bump(id, Aspect::Display);
    return ok();
}

Status Document::setHidden(SurfaceId id, bool hidden) {
    Surface* s = mutableSurface(id);
    if (!s)
        return noSurface(id);
    if (s->hidden == hidden)
        return ok();
    s->hidden = hidden;
    bump(id, Aspect::Display);
    return ok();
}

Status Document::insertTrimLoop(SurfaceId id, int index, TrimLoop loop) {
    Surface* s = mutableSurface(id);
    if (!s)
        return noSurface(id);
    if (Status allowed = checkInsertTrimLoop(m_scene, *s, index, loop); !allowed)
        return allowed;
    Q_EMIT trimLoopAboutToBeInserted(id, index);
    const TrimLoopId loopId = loop.id;
    const int curves = int(loop.curves.size());
    s->trims.insert(s->trims.begin() + index, std::move(loop));
    if (const auto taken = m_takenWithLoop.constFind(loopId);
        taken != m_takenWithLoop.cend() && taken->loopCurves == curves) {
        restoreTopology(m_scene, *taken);
        m_takenWithLoop.erase(taken);
    }
    m_scene.nextId = std::max(m_scene.nextId, loopId.value + 1);
    m_revisions[size_t(indexOf(id))].trims = nextRevision();
    const int solid = std::exchange(s->solid, -1);
    Q_EMIT trimLoopInserted(id, index);
    changed(id, Aspect::Trims);
    openSolid(solid);
    closeSolid(id);
    return ok();
}

Status Document::removeTrimLoop(SurfaceId id, TrimLoopId loop) {
    Surface* s = mutableSurface(id);
    if (!s)
        return noSurface(id);
    const int index = loopIndex(*s, loop);
    if (index < 0)
        return Error(
            QStringLiteral("no trim loop with id %1 on surface %2").arg(loop.value).arg(id.value));
    Q_EMIT trimLoopAboutToBeRemoved(id, index);
    // A removal that takes no edge keeps what an earlier one took: ReplaceTrimLoop's undo
    // removes the edited loop (no edges, when its curve count differed) before it inserts the
    // original, which gets its edges back.
    if (TopologyPiece taken = takeLoopTopology(m_scene.topology, id, loop,
                                               int(s->trims[size_t(index)].curves.size()));
        !taken.edges.empty())
        m_takenWithLoop.insert(loop, std::move(taken));
    s->trims.erase(s->trims.begin() + index);
    m_revisions[size_t(indexOf(id))].trims = nextRevision();
    const int solid = std::exchange(s->solid, -1);
    Q_EMIT trimLoopRemoved(id, index);
    changed(id, Aspect::Trims);
    openSolid(solid);
    closeSolid(id);
    return ok();
}

Status Document::setTrimPoint(const TrimPointRef& ref, glm::dvec2 position) {
    return setTrimPoints({ref}, {position});
}

// All points move first, then each touched loop must still be closed (checkTrimLoop): a curve
// end moves together with the coinciding end of its neighbour in one call.
Status Document::movedTrims(const std::vector<TrimPointRef>& refs,
                            const std::vector<glm::dvec2>& positions, std::vector<TrimLoop>& trims,
                            std::set<int>& touched) const {
    if (refs.empty() || refs.size() != positions.size())
        return Error(QStringLiteral("need one position per trim point"));
    const SurfaceId id = refs.front().surface;
    const Surface* s = surface(id);
    if (!s)
        return noSurface(id);
    trims = s->trims;
    std::set<TrimPointRef> seen;
    for (size_t k = 0; k < refs.size(); ++k) {
        const TrimPointRef& ref = refs[k];
        const int li = ref.surface == id ? loopIndex(*s, ref.loop) : -1;
        const std::vector<NurbsCurve2>* curves = li >= 0 ? &trims[size_t(li)].curves : nullptr;
        if (ref.surface != id)
            return Error(QStringLiteral("trim points of one surface at a time"));
        if (!curves || ref.curve < 0 || size_t(ref.curve) >= curves->size() || ref.index < 0 ||
            size_t(ref.index) >= (*curves)[size_t(ref.curve)].points.size())
            return Error(QStringLiteral("no trim point %1 of curve %2 in loop %3 of surface %4")
                             .arg(ref.index)
                             .arg(ref.curve)
                             .arg(ref.loop.value)
                             .arg(ref.surface.value));
        if (!seen.insert(ref).second)
            return Error(QStringLiteral("trim point listed twice"));
        if (!std::isfinite(positions[k].x) || !std::isfinite(positions[k].y))
            return Error(QStringLiteral("trim point positions must be finite"));
        trims[size_t(li)].curves[size_t(ref.curve)].points[size_t(ref.index)] = positions[k];
        touched.insert(li);
    }
    for (int li : touched)
        if (Status closed = checkTrimLoop(trims[size_t(li)]); !closed)
            return closed;
    return ok();
}

Status Document::checkTrimPoints(const std::vector<TrimPointRef>& refs,
                                 const std::vector<glm::dvec2>& positions) const {
    std::vector<TrimLoop> trims;
    std::set<int> touched;
    return movedTrims(refs, positions, trims, touched);
}

Status Document::setTrimPoints(const std::vector<TrimPointRef>& refs,
                               const std::vector<glm::dvec2>& positions) {
    std::vector<TrimLoop> trims;
    std::set<int> touched;
    if (Status valid = movedTrims(refs, positions, trims, touched); !valid)
        return valid;
    Surface* s = mutableSurface(refs.front().surface);
    if (trims == s->trims)
        return ok();
    s->trims = std::move(trims);
    bump(s->id, Aspect::Trims);
    return ok();
}

Status Document::setLights(std::vector<Light> lights) {
    if (Status valid = checkLights(lights); !valid)
        return valid;
    if (m_scene.lights == lights)
        return ok();
    m_scene.lights = std::move(lights);
    m_lightsRevision = nextRevision();
    Q_EMIT lightsChanged();
    return ok();
}

Status Document::setCamera(const Camera& camera) {
    if (Status valid = checkCamera(camera); !valid)
        return valid;
    if (m_scene.camera == camera)
        return ok();
    m_scene.camera = camera;
    m_cameraRevision = nextRevision();
    Q_EMIT cameraChanged();
    return ok();
}

Status Document::setDisplay(const DisplaySettings& display) {
    if (Status valid = checkDisplay(display); !valid)
        return valid;
    if (m_scene.display == display)
        return ok();
    m_scene.display = display;
    nextRevision(); // no surface or signal: the scene's content changed all the same
    return ok();
}

Status Document::setContinuityTolerances(const ContinuityTolerances& tolerances) {
    if (Status valid = checkContinuityTolerances(tolerances); !valid)
        return valid;
    if (m_scene.continuity == tolerances)
        return ok();
    m_scene.continuity = tolerances;
    nextRevision();
    Q_EMIT continuityTolerancesChanged();
    return ok();
}

Document::Lengths Document::lengths() const {
    Lengths out;
    out.unit = m_scene.unit;
    for (const Surface& s : m_scene.surfaces)
        out.points.insert(out.points.end(), s.geometry.points.begin(), s.geometry.points.end());
    for (const SharedEdge& e : m_scene.topology.edges)
        out.tolerances.push_back(e.tolerance);
    out.camera = m_scene.camera;
    out.lights = m_scene.lights;
    return out;
}

Document::Lengths Document::scaledLengths(const Lengths& from, LengthUnit unit, double factor) {
    Lengths out = from;
    out.unit = unit;
    if (factor == 1.0)
        return out;
    for (glm::dvec3& p : out.points)
        p *= factor;
    for (double& t : out.tolerances)
        t *= factor;
    // The view keeps its direction and framing: eye and target scale about the origin.
    out.camera.eye *= factor;
    out.camera.target *= factor;
    for (Light& l : out.lights)
        if (l.kind == Light::Kind::Point)
            l.vector *= factor;
    return out;
}

Status Document::setLengths(const Lengths& lengths) {
    size_t points = 0;
    for (const Surface& s : m_scene.surfaces)
        points += s.geometry.points.size();
    if (lengths.points.size() != points)
        return Error(QStringLiteral("%1 control points for the %2 of the scene")
                         .arg(lengths.points.size())
                         .arg(points));
    if (lengths.tolerances.size() != m_scene.topology.edges.size())
        return Error(QStringLiteral("%1 edge tolerances for the %2 edges of the scene")
                         .arg(lengths.tolerances.size())
                         .arg(m_scene.topology.edges.size()));
    for (const glm::dvec3& p : lengths.points)
        if (!finite(p))
            return Error(QStringLiteral("control point positions must be finite"));
    for (double t : lengths.tolerances)
        if (!std::isfinite(t) || t < 0)
            return Error(QStringLiteral("edge tolerance %1 must be finite and >= 0").arg(t));
    if (Status valid = checkCamera(lengths.camera); !valid)
        return valid;
    if (Status valid = checkLights(lengths.lights); !valid)
        return valid;
    size_t at = 0;
    std::vector<SurfaceId> moved;
    // A unit conversion scales every net: a placement, which analytic forms follow.
    std::vector<NurbsSurface> before;
    for (Surface& s : m_scene.surfaces) {
        const bool follow = s.analytic.kind != AnalyticForm::Kind::None;
        const bool changed = !std::equal(s.geometry.points.begin(), s.geometry.points.end(),
                                         lengths.points.begin() + std::ptrdiff_t(at));
        if (changed && follow)
            before.push_back(s.geometry);
        for (glm::dvec3& p : s.geometry.points)
            p = lengths.points[at++];
        if (changed) {
            moved.push_back(s.id);
            digestNet(s.id, s.geometry);
        }
    }
    for (size_t k = 0; k < lengths.tolerances.size(); ++k)
        m_scene.topology.edges[k].tolerance = lengths.tolerances[k];
    size_t placed = 0;
    for (SurfaceId id : moved) {
        const bool follow = surface(id)->analytic.kind != AnalyticForm::Kind::None;
        bump(id, Aspect::Points, follow ? &before[placed++] : nullptr);
    }
    // Both checked above: they cannot be refused here.
    static_cast<void>(setCamera(lengths.camera));
    static_cast<void>(setLights(lengths.lights));
    if (m_scene.unit != lengths.unit) {
        m_scene.unit = lengths.unit;
        nextRevision();
        Q_EMIT unitChanged();
    }
    return ok();
}

Status Document::validate(const Scene& scene) {
    return checkScene(scene);
}

std::uint64_t Document::nextRevision() {
    m_counter = processRevision();
    return m_counter;
}

Surface* Document::mutableSurface(SurfaceId id) {
    const int i = indexOf(id);
    return i < 0 ? nullptr : &m_scene.surfaces[size_t(i)];
}

// Gives every changed aspect one fresh value of the document-wide counter, then signals.
// Name has no revision: nothing is uploaded for it.
void Document::bump(SurfaceId id, Aspects aspects, const NurbsSurface* placedFrom) {
    const size_t index = size_t(indexOf(id));
    Revisions& r = m_revisions[index];
    const std::uint64_t rev = nextRevision();
    if (aspects & Aspect::Points)
        r.points = rev;
    if (aspects & Aspect::Knots)
        r.knots = rev;
    if (aspects & Aspect::Trims)
        r.trims = rev;
    if (aspects & Aspect::Display)
        r.display = rev;
    Surface& s = m_scene.surfaces[index];
    if (aspects & (Aspect::Points | Aspect::Knots))
        reviewAnalytic(s, placedFrom);
    const int solid = aspects & (Aspect::Points | Aspect::Knots | Aspect::Trims)
                          ? std::exchange(s.solid, -1)
                          : -1;
    changed(id, aspects);
    openSolid(solid);
    if (aspects & (Aspect::Points | Aspect::Knots | Aspect::Trims))
        closeSolid(id);
}

// The form `s` has after a change of its geometry (AnalyticOrigin): O(1) but for a placement,
// which fits the similarity that moved the net.
void Document::reviewAnalytic(Surface& s, const NurbsSurface* placedFrom) {
    const auto origin = m_analyticOrigins.find(s.id);
    if (origin == m_analyticOrigins.end()) {
        s.analytic = {};
    } else if (origin->current == origin->imported) {
        s.analytic = origin->form;
    } else if (placedFrom && s.analytic.kind != AnalyticForm::Kind::None) {
        ++m_analyticFits;
        s.analytic = analyticFollow(s.analytic, *placedFrom, s.geometry).value_or(AnalyticForm{});
        if (s.analytic.kind != AnalyticForm::Kind::None) {
            origin->placed = origin->current;
            origin->placedForm = s.analytic;
        }
    } else if (origin->placedForm.kind != AnalyticForm::Kind::None &&
               origin->current == origin->placed) {
        s.analytic = origin->placedForm;
    } else {
        s.analytic = {};
    }
}

void Document::digestPoint(SurfaceId id, int index, const glm::dvec3& from, double fromWeight,
                           const glm::dvec3& to, double toWeight) {
    if (const auto origin = m_analyticOrigins.find(id); origin != m_analyticOrigins.end())
        origin->current.points +=
            pointDigest(index, to, toWeight) - pointDigest(index, from, fromWeight);
}

void Document::digestNet(SurfaceId id, const NurbsSurface& net) {
    if (const auto origin = m_analyticOrigins.find(id); origin != m_analyticOrigins.end())
        origin->current = netDigest(net);
}

void Document::changed(SurfaceId id, Aspects aspects) {
    if (aspects & (Aspect::Points | Aspect::Knots | Aspect::Trims | Aspect::Display)) {
        if (m_changes.size() >= kMaxChanges) {
            // A reader this far behind walks everything once, as after a reset.
            const auto half = m_changes.begin() + std::ptrdiff_t(m_changes.size() / 2);
            m_walkFrom = std::max(m_walkFrom, std::prev(half)->revision);
            m_changes.erase(m_changes.begin(), half);
        }
        m_changes.push_back({m_counter, id});
    }
    Q_EMIT surfaceChanged(id, aspects);
}

void Document::changedStructure() {
    m_walkFrom = m_counter;
    m_changes.clear();
}

// A face of `solid` changed shape or went away: a seam may be open, and through it the other
// faces' insides may show, so none of them is marked any more (Surface::solid).
void Document::openSolid(int solid) {
    if (solid < 0)
        return;
    m_marksRevision = nextRevision();
    for (size_t i = 0; i < m_scene.surfaces.size(); ++i)
        if (m_scene.surfaces[i].solid == solid) {
            m_scene.surfaces[i].solid = -1;
            m_revisions[i].display = nextRevision();
            changed(m_scene.surfaces[i].id, Aspect::Display);
        }
}

// `id`'s shape changed or it came back: where it was a face of a solid that an edit opened and
// every face of that solid now has its marked shape again (the seams are the imported ones),
// the solid is marked again, with a display revision for each face.
void Document::closeSolid(SurfaceId id) {
    const auto marked = m_markedFaces.constFind(id);
    const Surface* s = surface(id);
    if (marked == m_markedFaces.cend() || !s || s->solid >= 0 || shapeDigest(*s) != marked->shape)
        return;
    const int solid = marked->solid;
    std::vector<size_t> faces;
    for (size_t i = 0; i < m_scene.surfaces.size(); ++i) {
        const Surface& face = m_scene.surfaces[i];
        const auto f = m_markedFaces.constFind(face.id);
        if (f == m_markedFaces.cend() || f->solid != solid)
            continue;
        if (face.solid >= 0 || (face.id != id && shapeDigest(face) != f->shape))
            return;
        faces.push_back(i);
    }
    if (faces.size() !=
        size_t(std::count_if(m_markedFaces.cbegin(), m_markedFaces.cend(),
                             [solid](const MarkedFace& f) { return f.solid == solid; })))
        return; // a face is missing
    m_marksRevision = nextRevision();
    for (size_t i : faces) {
        m_scene.surfaces[i].solid = solid;
        m_revisions[i].display = nextRevision();
        changed(m_scene.surfaces[i].id, Aspect::Display);
    }
}

} // namespace kw
