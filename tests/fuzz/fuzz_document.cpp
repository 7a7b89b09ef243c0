// libFuzzer harness: the whole Document command set. The input is a sequence of mutator calls
// (insert/remove surfaces and loops, rename, move control and trim points, weights, geometry from
// the kernel's knot insertion and degree elevation or made up, partitions, material, lights,
// camera, reset, id allocation) with valid, invalid and absurd arguments. After each call:
//  - the scene is valid (Document::validate);
//  - a refused call (false) changed nothing and emitted nothing;
//  - a call that changed nothing emitted nothing (no-ops never cost an upload);
//  - every surface whose authored data changed has a fresh revision for exactly those aspects
//    (never an old value), and an untouched surface keeps its revisions;
//  - the item signals balance: inserted/removed surfaces and loops match the scene's counts.
// At the end, what Save writes (.knot) reopens as the same scene.
#include "fuzz_roundtrip.h"
#include "model/nurbs/nurbs_shapes.h"

#include <map>
#include <set>

using namespace kw;
using kw::fuzz::Input;

namespace {

struct SignalLog {
    int total = 0;
    int surfacesIn = 0, surfacesOut = 0, loopsIn = 0, loopsOut = 0, resets = 0;
    std::map<std::uint32_t, Aspects> changed;

    void connect(Document& doc) {
        QObject::connect(&doc, &Document::sceneReset, [this] { ++total, ++resets; });
        QObject::connect(&doc, &Document::sceneAboutToBeReset, [this] { ++total; });
        QObject::connect(&doc, &Document::surfaceAboutToBeInserted, [this] { ++total; });
        QObject::connect(&doc, &Document::surfaceInserted, [this] { ++total, ++surfacesIn; });
        QObject::connect(&doc, &Document::surfaceAboutToBeRemoved, [this] { ++total; });
        QObject::connect(&doc, &Document::surfaceRemoved, [this] { ++total, ++surfacesOut; });
        QObject::connect(&doc, &Document::surfaceChanged, [this](SurfaceId id, Aspects a) {
            ++total;
            changed[id.value] |= a;
        });
        QObject::connect(&doc, &Document::trimLoopAboutToBeInserted, [this] { ++total; });
        QObject::connect(&doc, &Document::trimLoopInserted, [this] { ++total, ++loopsIn; });
        QObject::connect(&doc, &Document::trimLoopAboutToBeRemoved, [this] { ++total; });
        QObject::connect(&doc, &Document::trimLoopRemoved, [this] { ++total, ++loopsOut; });
        QObject::connect(&doc, &Document::lightsChanged, [this] { ++total; });
        QObject::connect(&doc, &Document::cameraChanged, [this] { ++total; });
    }
    void clear() { *this = SignalLog{}; }
};

glm::dvec3 vec3(Input& in, double lo, double hi) {
    return {in.wild(lo, hi), in.wild(lo, hi), in.wild(lo, hi)};
}

NurbsCurve2 segment(glm::dvec2 a, glm::dvec2 b) {
    NurbsCurve2 c;
    c.knots = {0, 0, 1, 1};
    c.points = {a, b};
    c.weights = {1, 1};
    return c;
}

/// Mostly a valid closed polygon loop inside [0, 1]^2, sometimes a broken one.
TrimLoop makeLoop(Input& in, TrimLoopId id) {
    TrimLoop loop;
    loop.id = id;
    const int corners = in.integer(0, 5);
    std::vector<glm::dvec2> p;
    for (int i = 0; i < corners; ++i)
        p.push_back({in.wild(0, 1), in.wild(0, 1)}); // braces: read left to right
    for (int i = 0; i < corners; ++i)
        loop.curves.push_back(segment(p[size_t(i)], p[size_t((i + 1) % corners)]));
    if (in.byte() == 0 && !loop.curves.empty())
        loop.curves.back().degree = in.integer(-1, 20); // a broken curve
    if (in.byte() == 0) {
        const glm::dvec2 centre{in.real(0, 1), in.real(0, 1)};
        loop.curves.push_back(makeCircle2(centre, in.wild(0, 0.5)));
    }
    return loop;
}

NurbsSurface makeGeometry(Input& in) {
    NurbsSurface g;
    // One value per statement: the evaluation order of call arguments is unspecified.
    switch (in.integer(0, 4)) {
    case 0: {
        const glm::dvec3 c = vec3(in, -5, 5);
        g = makeSphere(c, in.wild(0.1, 3));
        break;
    }
    case 1: {
        const glm::dvec3 c = vec3(in, -5, 5);
        const double major = in.wild(1, 3);
        g = makeTorus(c, major, in.wild(0.1, 1));
        break;
    }
    case 2: {
        const glm::dvec3 c = vec3(in, -5, 5);
        const double radius = in.wild(0.1, 3);
        g = makeCylinder(c, radius, in.wild(0.1, 3));
        break;
    }
    case 3: {
        const glm::dvec3 p[4] = {vec3(in, -5, 5), vec3(in, -5, 5), vec3(in, -5, 5),
                                 vec3(in, -5, 5)};
        g = makeBilinear(p[0], p[1], p[2], p[3]);
        break;
    }
    default: {
        const glm::dvec3 p[3] = {vec3(in, -5, 5), vec3(in, -5, 5), vec3(in, -5, 5)};
        g = makePlane(p[0], p[1], p[2]);
        break;
    }
    }
    if (in.byte() < 8) { // corrupt one field
        switch (in.integer(0, 5)) {
        case 0:
            g.degreeU = in.integer(-2, 20);
            break;
        case 1:
            g.countV = in.integer(-2, 20);
            break;
        case 2:
            if (!g.knotsU.empty())
                g.knotsU[in.integer(0, int(g.knotsU.size()) - 1)] = in.wild(-1, 2);
            break;
        case 3:
            if (!g.weights.empty())
                g.weights[in.integer(0, int(g.weights.size()) - 1)] = in.wild(-1, 1);
            break;
        case 4:
            g.points.pop_back();
            break;
        default:
            g.knotsV.push_back(1.0);
            break;
        }
    }
    return g;
}

class Driver {
public:
    explicit Driver(Input& in) : in(in) { log.connect(doc); }

    /// An id that exists most of the time, else 0 or a random one.
    SurfaceId pickSurface() {
        const auto& s = doc.scene().surfaces;
        if (!s.empty() && in.byte() >= 16)
            return s[size_t(in.integer(0, int(s.size()) - 1))].id;
        return SurfaceId{in.flag() ? 0u : in.u32()};
    }
    TrimLoopId pickLoop(SurfaceId id) {
        const Surface* s = doc.surface(id);
        if (s && !s->trims.empty() && in.byte() >= 16)
            return s->trims[size_t(in.integer(0, int(s->trims.size()) - 1))].id;
        return TrimLoopId{in.flag() ? 0u : in.u32()};
    }
    Surface makeSurface() {
        Surface s;
        s.id = in.byte() >= 16 ? doc.allocateSurfaceId() : SurfaceId{in.u32() % 64};
        s.name = QStringLiteral("S%1").arg(s.id.value);
        s.geometry = makeGeometry(in);
        if (in.flag())
            s.trims.push_back(makeLoop(in, doc.allocateTrimLoopId()));
        s.partitionsU = in.integer(-1, 300);
        s.partitionsV = in.integer(1, 20);
        return s;
    }
    Scene makeScene() {
        Scene scene;
        const int n = in.integer(0, 3);
        for (int i = 0; i < n; ++i)
            scene.surfaces.push_back(makeSurface());
        scene.nextId = in.byte() < 16 ? in.u32() : 1;
        if (in.byte() < 16)
            scene.lights.clear();
        return scene;
    }

    /// One mutator call; returns its result (ok() for the id allocators).
    Status step() {
        const int op = in.integer(0, 17);
        switch (op) {
        case 0: {
            const int index = in.integer(-1, int(doc.scene().surfaces.size()) + 1);
            return doc.insertSurface(index, makeSurface());
        }
        case 1:
            return doc.removeSurface(pickSurface());
        case 2: {
            const SurfaceId id = pickSurface();
            return doc.setName(id, in.flag() ? QStringLiteral("  ")
                                             : QStringLiteral("N%1").arg(in.byte()));
        }
        case 3: {
            const SurfaceId id = pickSurface();
            const Surface* s = doc.surface(id);
            const int n = s ? int(s->geometry.points.size()) : 4;
            std::vector<int> idx;
            std::vector<glm::dvec3> pos;
            const int k = in.integer(0, 4);
            for (int i = 0; i < k; ++i) {
                idx.push_back(in.byte() < 8 ? in.integer(-2, n + 2)
                                            : in.integer(0, std::max(n - 1, 0)));
                pos.push_back(vec3(in, -5, 5));
            }
            if (in.byte() < 8 && !pos.empty())
                pos.pop_back(); // sizes differ
            return doc.setControlPoints(id, idx, pos);
        }
        case 4: {
            const SurfaceId id = pickSurface();
            const int index = in.integer(-1, 50);
            return doc.setWeight(id, index, in.wild(-1, 4));
        }
        case 5: {
            const SurfaceId id = pickSurface();
            const Surface* s = doc.surface(id);
            NurbsSurface g = s ? s->geometry : makeGeometry(in);
            switch (in.integer(0, 4)) {
            case 0: {
                const double u = in.wild(-0.5, 1.5);
                g = surfaceInsertKnotU(g, u, in.integer(0, 2));
                break;
            }
            case 1: {
                const double v = in.wild(-0.5, 1.5);
                g = surfaceInsertKnotV(g, v, in.integer(0, 2));
                break;
            }
            case 2:
                g = surfaceElevateDegreeU(g, in.integer(0, 2));
                break;
            case 3:
                g = surfaceElevateDegreeV(g, in.integer(0, 2));
                break;
            default:
                g = makeGeometry(in);
                break;
            }
            return doc.setGeometry(id, g);
        }
        case 6: {
            const SurfaceId id = pickSurface();
            const int nu = in.integer(-1, 300);
            return doc.setPartitions(id, nu, in.integer(-1, 300));
        }
        case 7: {
            Material m;
            m.color = vec3(in, 0, 1);
            m.ka = in.wild(0, 1);
            m.shininess = in.wild(0, 200);
            return doc.setMaterial(pickSurface(), m);
        }
        case 8: {
            const SurfaceId id = pickSurface();
            const Surface* s = doc.surface(id);
            const int index = in.integer(-1, s ? int(s->trims.size()) + 1 : 1);
            const TrimLoopId loopId =
                in.byte() >= 16 ? doc.allocateTrimLoopId() : TrimLoopId{in.u32() % 64};
            return doc.insertTrimLoop(id, index, makeLoop(in, loopId));
        }
        case 9: {
            const SurfaceId id = pickSurface();
            return doc.removeTrimLoop(id, pickLoop(id));
        }
        case 10: {
            TrimPointRef ref;
            ref.surface = pickSurface();
            ref.loop = pickLoop(ref.surface);
            ref.curve = in.integer(-1, 6);
            ref.index = in.integer(-1, 9);
            return doc.setTrimPoint(ref, {in.wild(-0.5, 1.5), in.wild(-0.5, 1.5)});
        }
        case 11: {
            std::vector<Light> lights(size_t(in.integer(0, kMaxLights + 1)));
            for (Light& l : lights) {
                l.kind = in.flag() ? Light::Kind::Point : Light::Kind::Directional;
                l.vector = vec3(in, -1, 1);
                l.diffuse = vec3(in, 0, 1);
            }
            return doc.setLights(std::move(lights));
        }
        case 12: {
            Camera c = doc.scene().camera;
            c.eye = vec3(in, -10, 10);
            c.up = in.flag() ? c.up : vec3(in, -1, 1);
            c.fovYDegrees = in.wild(0, 180);
            c.authored = in.flag();
            return doc.setCamera(c);
        }
        case 13: {
            const Status reset = doc.resetScene(makeScene());
            KW_FUZZ_CHECK(bool(reset) == reset.message().isEmpty(),
                          "resetScene: result and error disagree");
            return reset;
        }
        case 14:
            doc.allocateSurfaceId();
            return ok();
        case 15:
            doc.allocateTrimLoopId();
            return ok();
        default: { // a pure no-op: setting what is already there
            const SurfaceId id = pickSurface();
            const Surface* s = doc.surface(id);
            if (!s)
                return doc.setLights(doc.scene().lights);
            return doc.setPartitions(id, s->partitionsU, s->partitionsV);
        }
        }
    }

    void checkAfter(const Scene& before, const std::map<std::uint32_t, Revisions>& revsBefore,
                    bool ok) {
        const Scene& now = doc.scene();
        // Validation is a function of the scene alone and `before` passed it (after the previous
        // call; the empty scene is valid), so an unchanged scene needs no second run.
        const bool unchanged = now == before;
        if (!unchanged) {
            const QString why = Document::validate(now).message();
            KW_FUZZ_CHECK(why.isEmpty(), why);
        }
        // The content is all but nextId, which id allocation moves; a copy only when it moved.
        const bool sameContent = unchanged || (now.nextId != before.nextId && [&] {
                                     Scene content = now;
                                     content.nextId = before.nextId;
                                     return content == before;
                                 }());
        // The document's revision moves exactly when the content does (or on a reset).
        KW_FUZZ_CHECK((doc.revision() != revisionBefore) == (!sameContent || log.resets > 0),
                      QStringLiteral("revision %1 -> %2 with the content %3")
                          .arg(revisionBefore)
                          .arg(doc.revision())
                          .arg(sameContent ? "unchanged" : "changed"));
        KW_FUZZ_CHECK(doc.revision() == revisionBefore || doc.revision() > maxRevision,
                      "a new document revision was handed out before");
        if (!ok) {
            KW_FUZZ_CHECK(sameContent, "a refused call changed the scene");
            KW_FUZZ_CHECK(log.total == 0, "a refused call emitted signals");
            return;
        }
        KW_FUZZ_CHECK(now.nextId >= before.nextId || log.resets > 0, "nextId went down");
        if (sameContent && log.resets == 0)
            KW_FUZZ_CHECK(log.total == 0, "a call that changed nothing emitted signals");
        KW_FUZZ_CHECK(int(before.surfaces.size()) + log.surfacesIn - log.surfacesOut ==
                              int(now.surfaces.size()) ||
                          log.resets > 0,
                      "surface insert/remove signals do not match the surface count");
        if (log.resets > 0)
            return; // every revision is new after a reset
        std::map<std::uint32_t, const Surface*> old;
        for (const Surface& s : before.surfaces)
            old[s.id.value] = &s;
        int loopsBefore = 0, loopsNow = 0;
        for (const Surface& s : before.surfaces)
            loopsBefore += int(s.trims.size());
        for (const Surface& s : now.surfaces) {
            loopsNow += int(s.trims.size());
            const auto o = old.find(s.id.value);
            if (o == old.end())
                continue; // inserted by this call
            const Surface& b = *o->second;
            const Revisions r0 = revsBefore.at(s.id.value), r1 = doc.revisions(s.id);
            const NurbsSurface &g0 = b.geometry, &g1 = s.geometry;
            const bool points = g0.points != g1.points || g0.weights != g1.weights;
            const bool knots = g0.degreeU != g1.degreeU || g0.degreeV != g1.degreeV ||
                               g0.countU != g1.countU || g0.countV != g1.countV ||
                               g0.knotsU != g1.knotsU || g0.knotsV != g1.knotsV;
            const bool trims = b.trims != s.trims;
            const bool display = b.partitionsU != s.partitionsU || b.partitionsV != s.partitionsV ||
                                 b.material != s.material;
            auto fresh = [&](std::uint64_t was, std::uint64_t is, bool changed, const char* what) {
                KW_FUZZ_CHECK(changed ? is > maxRevision : is == was,
                              QStringLiteral("%1 revision of surface %2: %3 -> %4, changed %5")
                                  .arg(QLatin1String(what))
                                  .arg(s.id.value)
                                  .arg(was)
                                  .arg(is)
                                  .arg(changed));
            };
            fresh(r0.points, r1.points, points, "points");
            fresh(r0.knots, r1.knots, knots, "knots");
            fresh(r0.trims, r1.trims, trims, "trims");
            fresh(r0.display, r1.display, display, "display");
            const Aspects signalled =
                log.changed.count(s.id.value) ? log.changed[s.id.value] : Aspects{};
            KW_FUZZ_CHECK(bool(signalled & Aspect::Points) == points &&
                              bool(signalled & Aspect::Knots) == knots &&
                              bool(signalled & Aspect::Trims) == trims &&
                              bool(signalled & Aspect::Display) == display &&
                              bool(signalled & Aspect::Name) == (b.name != s.name),
                          QStringLiteral("surface %1 signalled aspects %2")
                              .arg(s.id.value)
                              .arg(int(signalled)));
        }
        KW_FUZZ_CHECK(
            loopsBefore + log.loopsIn - log.loopsOut ==
                loopsNow +
                    [&] {
                        int gone = 0; // loops that left with a removed surface
                        for (const Surface& s : before.surfaces)
                            if (!doc.surface(s.id))
                                gone += int(s.trims.size());
                        return gone;
                    }() -
                    [&] {
                        int came = 0; // loops that came with an inserted surface
                        for (const Surface& s : now.surfaces)
                            if (!old.count(s.id.value))
                                came += int(s.trims.size());
                        return came;
                    }(),
            "trim loop insert/remove signals do not match the loop count");
    }

    void run() {
        KW_FUZZ_CHECK(bool(Document::validate(doc.scene())), "a new document is invalid");
        for (int n = 0; n < 32 && !in.empty(); ++n) {
            const Scene before = doc.scene();
            std::map<std::uint32_t, Revisions> revs;
            for (const Surface& s : before.surfaces) {
                revs[s.id.value] = doc.revisions(s.id);
                const Revisions r = revs[s.id.value];
                maxRevision = std::max({maxRevision, r.points, r.knots, r.trims, r.display});
            }
            maxRevision =
                std::max({maxRevision, doc.lightsRevision(), doc.cameraRevision(), doc.revision()});
            revisionBefore = doc.revision();
            log.clear();
            const Status done = step();
            // A refusal says why; a success says nothing.
            KW_FUZZ_CHECK(bool(done) == done.message().isEmpty(),
                          "a mutator's result and its reason disagree");
            checkAfter(before, revs, bool(done));
        }
        kw::fuzz::checkAcceptedScene(doc.scene());
    }

    Input& in;
    Document doc;
    SignalLog log;
    std::uint64_t maxRevision = 0;    ///< the largest revision seen before the current call
    std::uint64_t revisionBefore = 0; ///< doc.revision() before the current call
};

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
    Input in(data, size);
    Driver driver(in);
    driver.run();
    return 0;
}
