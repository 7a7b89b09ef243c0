// The B-rep topology a CAD import keeps: which trim curves are one edge, which faces one shell.
#pragma once

#include "model/document/ids.h"
#include "model/error.h"

#include <QString>
#include <array>
#include <optional>
#include <vector>

namespace kw {

struct Scene;

/// Most shared edges and shells one document holds (docs/FILE_FORMAT.md, ## Limits).
constexpr int kMaxSharedEdges = 4'000'000;
constexpr int kMaxShells = 100'000;

/// One face's side of a shared edge: curve `curve` (its index in the loop's curves) of trim loop
/// `loop` of surface `surface`. `reversed`: the trim curve runs against the edge's own
/// direction (the face's wire uses the B-rep edge REVERSED); in a consistently oriented shell
/// the two sides of an edge run opposite ways.
struct EdgeUse {
    SurfaceId surface;
    TrimLoopId loop;
    int curve = 0;
    bool reversed = false;
    auto operator<=>(const EdgeUse&) const = default;
};

/// A B-rep edge that two trim curves are: in the source both curves, mapped through their
/// surfaces, were one edge within `tolerance` (model units, the source's edge tolerance: the
/// farthest its curves on either face may lie from one another). Both sides may lie on one
/// surface (the seam of a closed surface, such as a cylinder's).
struct SharedEdge {
    EdgeId id;
    double tolerance = 0.0;
    std::array<EdgeUse, 2> sides;
    bool operator==(const SharedEdge&) const = default;
};

/// Faces that formed one shell in the source, `faces` in ascending id order. `closed`: when
/// recorded, the shell had no free boundary (every edge of it shared by two of its faces, and
/// each such edge recorded); the removal of one of its faces, or of a loop holding one of its
/// edges, clears it and its undo sets it again (Document). Whether the seams still meet after
/// edits of shape is a measurement, not a flag: kw::closedShells (model/document/seamgaps.h).
/// `solid`: the Surface::solid number the import gave its faces when the shell bounds a closed
/// solid (a solid with a cavity has several shells with one number), -1 when it bounds none.
struct Shell {
    ShellId id;
    bool closed = false;
    int solid = -1;
    std::vector<SurfaceId> faces;
    bool operator==(const Shell&) const = default;
};

/// The topology of a scene, both lists in ascending id order. Empty for created surfaces, OBJ
/// imports and files without it: such scenes are simply loose faces.
struct Topology {
    std::vector<SharedEdge> edges;
    std::vector<Shell> shells;
    bool empty() const { return edges.empty() && shells.empty(); }
    bool operator==(const Topology&) const = default;
};

/// Where a topology refers to what is not there, and why.
struct TopologyProblem {
    QString place;  ///< relative to the topology: "edges[3].sides[1].loop", "shells[0].faces[2]"
    QString reason; ///< plain English, naming the ids
};

/// Checks scene.topology against the scene: edge and shell ids valid, unique and ascending, at
/// most kMaxSharedEdges edges and kMaxShells shells; every tolerance finite and >= 0; every
/// side naming a surface, a loop of that surface and a curve index of that loop; the two sides
/// of an edge two different curves, and no curve a side of two edges; every shell face an
/// existing surface, ascending, and in no other shell; solid >= -1. nullopt when valid.
std::optional<TopologyProblem> topologyProblem(const Scene& scene);

/// topologyProblem as an Error of one line, "topology: PLACE: REASON"; ok() when valid
/// (kw::checkScene's).
Status checkTopology(const Scene& scene);

/// The edge with this id, nullptr for none.
const SharedEdge* findSharedEdge(const Topology& topology, EdgeId id);
/// The shell holding `surface`, nullptr for none.
const Shell* shellOfSurface(const Topology& topology, SurfaceId surface);
/// True when a side of `edge` is a curve of `surface`.
bool edgeTouches(const SharedEdge& edge, SurfaceId surface);

/// The record of a part of the scene (Export Selected): the edges both of whose sides lie on
/// `faces` (ascending ids), and every shell with a face among them, holding only those; a
/// shell that lost a face is not closed.
Topology topologyOfFaces(const Topology& topology, const std::vector<SurfaceId>& faces);

/// What the removal of a surface or of a trim loop takes out of the topology, kept by Document
/// so that the undo which brings the part back restores the record exactly.
struct TopologyPiece {
    std::vector<SharedEdge> edges; ///< the edges that had a side on the part
    /// The shells whose `closed` the removal cleared, with the value it had before.
    std::vector<std::pair<ShellId, bool>> closedBefore;
    SurfaceId surface;   ///< the removed surface (invalid for a loop's removal)
    ShellId shell;       ///< the removed surface's shell (invalid: none, or a loop's removal)
    int loopCurves = -1; ///< a removed loop's curve count (-1 for a surface)
    bool empty() const { return edges.empty() && !shell.isValid(); }
};

/// Removes `surface` from the topology: the edges with a side on it and its place in its shell;
/// the shells concerned are no longer closed. Returns what was removed.
TopologyPiece takeSurfaceTopology(Topology& topology, SurfaceId surface);
/// Removes the edges with a side on loop `loop` of `surface` (its shell, and the other sides'
/// shells, are no longer closed); `loopCurves` is the loop's curve count, for the restore.
TopologyPiece takeLoopTopology(Topology& topology, SurfaceId surface, TrimLoopId loop,
                               int loopCurves);
/// Puts back what a take removed, into scene.topology: the surface's place in its shell, and
/// every edge whose sides all exist again in `scene` (each in its place by id); when all of it
/// came back, the shells get their `closed` back. Returns how many of the pieces (edges, shell
/// place) could not be put back (0 after an undo of the take's edit).
int restoreTopology(Scene& scene, const TopologyPiece& piece);

/// After the curves of loop `loop` of `surface` were renumbered (a curve inserted to close a
/// gap), moves every side on that loop from curve k to `newIndex[k]`.
void renumberLoopCurves(Topology& topology, SurfaceId surface, TrimLoopId loop,
                        const std::vector<int>& newIndex);

} // namespace kw
