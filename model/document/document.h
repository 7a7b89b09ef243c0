// Document: owns the Scene, applies validated mutations, counts revisions and signals changes.
#pragma once

#include "model/document/scene.h"
#include "model/error.h"

#include <QFlags>
#include <QHash>
#include <QObject>
#include <QString>
#include <algorithm>
#include <cstdint>
#include <set>
#include <span>
#include <vector>

namespace kw {

/// What part of a surface changed; the renderer re-uploads only stale aspects.
enum class Aspect : unsigned {
    Points = 1 << 0,  ///< control point positions or weights (same counts)
    Knots = 1 << 1,   ///< degrees, knot vectors, or control-net size
    Trims = 1 << 2,   ///< trim loops
    Display = 1 << 3, ///< partitions, material, hidden, the solid mark
    Name = 1 << 4,
};
Q_DECLARE_FLAGS(Aspects, Aspect)
Q_DECLARE_OPERATORS_FOR_FLAGS(Aspects)

/// Per-surface revision of each aspect. Values come from one counter shared by every document
/// (Document::revision), so every change (undo included) yields a value never seen before.
struct Revisions {
    std::uint64_t points = 0;
    std::uint64_t knots = 0;
    std::uint64_t trims = 0;
    std::uint64_t display = 0;
    bool operator==(const Revisions&) const = default;
};

/// A surface whose drawn data (points, knots, trims or display) changed, at `revision`.
struct SurfaceChange {
    std::uint64_t revision = 0;
    SurfaceId id;
};

/// The one place the scene changes. Every mutator validates its input and, when it is invalid
/// or names an unknown id, returns an Error saying why (the validator's words: checkSurface,
/// checkControlPoints, checkDisplay...), changing nothing and emitting nothing; on success it
/// bumps the revisions and emits the matching signals. A valid call that changes nothing (the
/// same name, positions, lights...) is ok() and emits nothing. Undo commands (ui/edit) call
/// these; views and the renderer only read and listen.
class Document : public QObject {
    Q_OBJECT
public:
    explicit Document(QObject* parent = nullptr);

    /// Edit > Keep Seams Closed: how a control point move carries the coincident points of
    /// neighbouring untrimmed faces with it (model/document/seamkeeper.h). Off: alone.
    enum class SeamLink { Off, Position, Tangency };

    const Scene& scene() const { return m_scene; }
    /// nullptr when no surface has this id.
    const Surface* surface(SurfaceId id) const;
    /// Position in scene().surfaces, or -1.
    int indexOf(SurfaceId id) const;
    /// Zero revisions for an unknown id.
    Revisions revisions(SurfaceId id) const;
    /// The revisions of scene().surfaces[index] (0 <= index < surface count), without the id
    /// search: for passes over every surface (the renderer's per-frame sync).
    Revisions revisionsAt(int index) const { return m_revisions[size_t(index)]; }
    std::uint64_t lightsRevision() const { return m_lightsRevision; }
    /// Changes with every change of the scene (a surface inserted, removed or edited, the
    /// lights, the camera, a reset) and never takes a value twice, in any document of the
    /// process: "nothing changed" is `revision()` unchanged (the renderer's progressive
    /// anti-aliasing keys its sum by it).
    std::uint64_t revision() const { return m_counter; }
    std::uint64_t cameraRevision() const { return m_cameraRevision; }
    /// Changes whenever some surface's Surface::solid mark is set or cleared (a reset, an edit
    /// that opens a solid, an undo that closes it again), and only then.
    std::uint64_t marksRevision() const { return m_marksRevision; }

    /// What a reader that last looked at revision `since` has to look at again. `structural`:
    /// every surface (a reset, an insert or a removal came since, or `since` is older than
    /// what the document keeps: a reader's first look, another document at the old address).
    /// Else `surfaces`: those whose points, knots, trims or display changed since, oldest
    /// first, once per change. The next look passes `through` as `since`. The renderer pulls
    /// this at frame time, so an edit reaches the GPU scene by the frame alone, not by a
    /// signal.
    struct Changes {
        bool structural = false;
        std::span<const SurfaceChange> surfaces;
        std::uint64_t through = 0;
    };
    Changes changesSince(std::uint64_t since) const;

    /// Fresh ids that no surface or loop of this document uses (never reused in a session).
    SurfaceId allocateSurfaceId();
    TrimLoopId allocateTrimLoopId();

    /// Replaces the whole scene (New, Open, Import). Ids are kept; nextId is raised above them.
    /// Returns the reason when the scene is invalid (the document is then unchanged).
    Status resetScene(Scene scene);

    /// index in [0, size]; surface.id valid and unused; geometry valid.
    Status insertSurface(int index, Surface surface);
    /// Also takes the surface out of the scene's topology (its edges, its place in its shell);
    /// inserting it again (the undo) puts the record back as it was.
    Status removeSurface(SurfaceId id);
    /// A name with a visible character.
    Status setName(SurfaceId id, const QString& name);
    /// Moves the listed control points (NurbsSurface::index) to new positions.
    Status setControlPoints(SurfaceId id, const std::vector<int>& indices,
                            const std::vector<glm::dvec3>& positions);
    /// The same with the seam link given (an undo step replays the link it was made with);
    /// the plain form uses seamLink(). With a link, the points of neighbouring untrimmed faces
    /// that kw::linkedMoves names move too (each such surface bumped and signalled).
    Status setControlPoints(SurfaceId id, const std::vector<int>& indices,
                            const std::vector<glm::dvec3>& positions, SeamLink link);
    /// Every control point of `id` moved at once by one placement (a move, rotation, mirror or
    /// scale: TransformSurfaces), as setControlPoints on all of them with seamLink(). The one
    /// point edit whose analytic form (Surface::analytic) may follow: where the new net is a
    /// similarity of the old one (analyticFollow). Any other edit of points, weights, knots or
    /// degrees drops the form at once, and gives back the form the face had at those very values.
    Status placeControlPoints(SurfaceId id, const std::vector<glm::dvec3>& positions);

    /// What the document keeps of the closed form a face came in with (a reset, or its first
    /// insertion), in a few words whatever the size of its net. After any change of the face's
    /// geometry the face has that form again where its net has the very values it came in with
    /// (an undo), the form a placement moved it to where its net has the values that placement
    /// left (the undo of a later edit), the form moved along by a placement that is a similarity
    /// (a move, rotation, uniform scale, mirror, unit conversion: analyticFollow, the only fit),
    /// and none otherwise: a point, weight, knot or degree edit drops it at once. Nets are
    /// compared by digest (NetDigest), kept current in O(1) per moved point, so a drag step
    /// costs nothing per control point of the face. The record outlives the face's removal, so
    /// the undo of an edit made before it still finds it.
    struct NetDigest {
        std::uint64_t shape = 0; ///< degrees, counts and knots
        /// The sum over the control points of a hash of (index, point, weight).
        std::uint64_t points = 0;
        bool operator==(const NetDigest&) const = default;
    };
    struct AnalyticOrigin {
        NetDigest imported;
        AnalyticForm form;
        NetDigest placed; ///< the net the last placement left, and the form it gave
        AnalyticForm placedForm;
        NetDigest current;
    };
    /// How many similarity fits (analyticFollow) the document ran to move analytic forms along
    /// with placements and unit conversions: never for other edits. For tests and benchmarks.
    std::uint64_t analyticFits() const { return m_analyticFits; }
    Status setWeight(SurfaceId id, int index, double weight);
    /// Degrees, knots and control net at once (knot edit, knot insertion, degree elevation).
    Status setGeometry(SurfaceId id, const NurbsSurface& geometry);
    /// Both in [kMinPartitions, kMaxPartitions].
    Status setPartitions(SurfaceId id, int nu, int nv);
    Status setMaterial(SurfaceId id, const Material& material);
    /// Hides or shows a surface (Aspect::Display).
    Status setHidden(SurfaceId id, bool hidden);
    /// index in [0, loop count]; loop.id valid and unused; every curve valid.
    Status insertTrimLoop(SurfaceId id, int index, TrimLoop loop);
    /// Also takes the edges with a side on the loop out of the scene's topology; inserting the
    /// loop again with as many curves (an undo, an edit of its curves) puts them back.
    Status removeTrimLoop(SurfaceId id, TrimLoopId loop);
    /// Moves one trim control point; refused when its loop would no longer be closed.
    Status setTrimPoint(const TrimPointRef& ref, glm::dvec2 position);
    /// Moves several trim control points of one surface at once (a curve end together with
    /// the coinciding end of its neighbour); refused, changing nothing, when a ref is unknown
    /// or repeated, a position is not finite or a touched loop would no longer be closed.
    Status setTrimPoints(const std::vector<TrimPointRef>& refs,
                         const std::vector<glm::dvec2>& positions);
    /// The one rule for the point edits above (the mutators, the undo commands and the live
    /// drags all ask it): ok() when the edit would be applied, else an Error saying why it
    /// would be refused. Control points: a known surface, at least one index, one finite position
    /// per index, every index in the net and listed once. Weights: a known point, finite and > 0.
    /// Trim points: known and listed once, all of one surface, finite, and every touched loop
    /// still closed (kw::checkTrimLoop).
    Status checkControlPoints(SurfaceId id, const std::vector<int>& indices,
                              const std::vector<glm::dvec3>& positions) const;
    Status checkWeight(SurfaceId id, int index, double weight) const;
    Status checkTrimPoints(const std::vector<TrimPointRef>& refs,
                           const std::vector<glm::dvec2>& positions) const;
    /// 0..kMaxLights lights (none: unlit), each valid (kw::checkLights).
    Status setLights(std::vector<Light> lights);
    Status setCamera(const Camera& camera);
    /// The display settings saved with the project (as the camera: not an edit, no signal
    /// the views react to); validated by validation.h's checkDisplay.
    Status setDisplay(const DisplaySettings& display);
    /// The continuity tolerances saved with the project (not an edit); emits
    /// continuityTolerancesChanged; validated by checkContinuityTolerances.
    Status setContinuityTolerances(const ContinuityTolerances& tolerances);

    SeamLink seamLink() const { return m_seamLink; }
    void setSeamLink(SeamLink link) { m_seamLink = link; }

    /// Every number the document holds in its length unit, and the unit: what Edit › Units…
    /// changes in one step (relabelled, or converted by scaling).
    struct Lengths {
        LengthUnit unit = LengthUnit::Millimetre;
        std::vector<glm::dvec3> points; ///< every surface's control points, surfaces in order
        std::vector<double> tolerances; ///< the topology's edge tolerances, edges in order
        Camera camera;
        std::vector<Light> lights; ///< point lights' positions are lengths
        bool operator==(const Lengths&) const = default;
    };
    Lengths lengths() const;
    /// `from` with every length multiplied by `factor` (> 0, finite) and the unit `unit`:
    /// factor 1 relabels, millimetresPer(old) / millimetresPer(unit) converts.
    static Lengths scaledLengths(const Lengths& from, LengthUnit unit, double factor);
    /// Sets what lengths() returns, for the scene as it is (as many points and tolerances);
    /// refused, changing nothing, when the counts differ or a value is not finite or valid.
    /// Emits surfaceChanged (Points) for each surface that moved, cameraChanged, lightsChanged
    /// and unitChanged for what changed.
    Status setLengths(const Lengths& lengths);

    /// Checks a whole scene with kw::checkScene, the rule every reader and writer uses.
    static Status validate(const Scene& scene);

Q_SIGNALS:
    void sceneAboutToBeReset();
    void sceneReset();
    void surfaceAboutToBeInserted(int index);
    void surfaceInserted(kw::SurfaceId id, int index);
    void surfaceAboutToBeRemoved(kw::SurfaceId id, int index);
    void surfaceRemoved(kw::SurfaceId id);
    void surfaceChanged(kw::SurfaceId id, kw::Aspects aspects);
    void trimLoopAboutToBeInserted(kw::SurfaceId id, int index);
    void trimLoopInserted(kw::SurfaceId id, int index);
    void trimLoopAboutToBeRemoved(kw::SurfaceId id, int index);
    void trimLoopRemoved(kw::SurfaceId id, int index);
    void lightsChanged();
    void cameraChanged();
    void continuityTolerancesChanged();
    /// The document's length unit changed (Units…; a reset emits sceneReset instead).
    void unitChanged();

private:
    Surface* mutableSurface(SurfaceId id);
    /// The surface's trims with the moved trim points, and the indices of the touched loops;
    /// checkTrimPoints' Error when it refuses.
    Status movedTrims(const std::vector<TrimPointRef>& refs,
                      const std::vector<glm::dvec2>& positions, std::vector<TrimLoop>& trims,
                      std::set<int>& touched) const;
    /// `placedFrom`: the net before a placement (placeControlPoints, setLengths), for the
    /// analytic form to follow; nullptr for every other edit.
    void bump(SurfaceId id, Aspects aspects, const NurbsSurface* placedFrom = nullptr);
    Status moveControlPoints(SurfaceId id, const std::vector<int>& indices,
                             const std::vector<glm::dvec3>& positions, SeamLink link,
                             bool placement);
    /// Notes a change of the drawn aspects for changesSince(), then emits surfaceChanged.
    void changed(SurfaceId id, Aspects aspects);
    /// A reset, an insert or a removal: every reader walks every surface once.
    void changedStructure();
    void openSolid(int solid);
    void closeSolid(SurfaceId id);

    /// A face of a closed solid as the last reset marked it (Surface::solid): its solid and a
    /// digest of its shape (shapeDigest: geometry and trims). An edit opens the solid
    /// (openSolid; its side, Surface::outsideAlongNormal, stays); once every one of its faces
    /// has its marked shape again (undo, or a point moved back), closeSolid marks them again.
    struct MarkedFace {
        int solid = -1;
        size_t shape = 0;
    };
    QHash<SurfaceId, MarkedFace> m_markedFaces;
    QHash<SurfaceId, AnalyticOrigin> m_analyticOrigins;
    std::uint64_t m_analyticFits = 0;
    void reviewAnalytic(Surface& s, const NurbsSurface* placedFrom);
    /// Keeps the digest of an analytic face's net current (AnalyticOrigin::current).
    void digestPoint(SurfaceId id, int index, const glm::dvec3& from, double fromWeight,
                     const glm::dvec3& to, double toWeight);
    void digestNet(SurfaceId id, const NurbsSurface& net);
    /// What the removal of a surface or a trim loop took out of the scene's topology (edges
    /// with a side on it, its place in its shell, the shells' `closed`), by the id of what was
    /// removed: ids are never reused, so only the undo of that removal brings the same id back,
    /// and then restoreTopology puts the record back exactly. A loop is put back with its edges
    /// when it has as many curves as the removed one (ReplaceTrimLoop edits a loop by removing
    /// and inserting it: its curves stay the same edges, and kw::seamGaps measures how far
    /// an edit moved them).
    QHash<SurfaceId, TopologyPiece> m_takenWithSurface;
    QHash<TrimLoopId, TopologyPiece> m_takenWithLoop;
    /// A fresh value of the process-wide revision counter, kept as the document's revision().
    std::uint64_t nextRevision();

    Scene m_scene;
    std::vector<Revisions> m_revisions;  // parallel to m_scene.surfaces
    SeamLink m_seamLink = SeamLink::Off; // the editor turns it on (Edit > Keep Seams Closed)
    std::uint64_t m_counter = 0;         ///< revision(): the newest value this document handed out
    std::uint64_t m_lightsRevision = 0;
    std::uint64_t m_cameraRevision = 0;
    std::uint64_t m_marksRevision = 0;
    /// changesSince(): the drawn changes, by revision; a reader from before m_walkFrom walks
    /// everything (the log starts at the last structural change, and is cut by half when
    /// it reaches kMaxChanges between two looks).
    std::vector<SurfaceChange> m_changes;
    std::uint64_t m_walkFrom = 0;
    static constexpr size_t kMaxChanges = size_t(1) << 16;
};

inline Document::Changes Document::changesSince(std::uint64_t since) const {
    const std::uint64_t through = std::max(m_counter, m_walkFrom);
    if (since < m_walkFrom)
        return {true, {}, through};
    const auto first =
        std::upper_bound(m_changes.begin(), m_changes.end(), since,
                         [](std::uint64_t r, const SurfaceChange& c) { return r < c.revision; });
    return {false, {first, m_changes.end()}, through};
}

} // namespace kw

Q_DECLARE_METATYPE(kw::SurfaceId)
Q_DECLARE_METATYPE(kw::Aspects)
