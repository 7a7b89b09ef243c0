// Shared edges for faces the import recorded none for (loose IGES trimmed surfaces, created
// patches), found by matching boundaries as the continuity kernel does, so that the writers
// build them as recorded edges (each face keeps its own p-curve) instead of sewing them.
#pragma once

#include "model/document/scene.h"

#include <limits>

namespace kw {

/// Edges and shells found for the faces scene.topology does not touch.
struct MatchedTopology {
    /// One per pair of trim curves that lie on one another end to end,
    /// ids above every recorded one; `tolerance` the measured largest gap of the pair
    /// (kw::seamGaps), sides[0] not reversed, sides[1] reversed when it runs the other way.
    std::vector<SharedEdge> edges;
    /// One per connected group of faces built from those edges, ids above every recorded one;
    /// `closed` when every trim curve of the group is a side of one of its edges; solid -1.
    std::vector<Shell> shells;
    int faces = 0; ///< faces in `shells`
    /// Faces left to sewing: groups with a T-junction (one boundary along part of another), a
    /// pairing with an untrimmed face's domain edge, a closed trim curve, or a curve paired
    /// twice; sewing splits and merges edges where one edge per curve pair cannot.
    int leftToSewing = 0;
    /// Pairs that lie on one another within the matching tolerance but further apart than
    /// `maxGap`: not made an edge, so both curves stay free boundaries of their shell (an open
    /// seam, reported with its gap).
    struct FarPair {
        SurfaceId faces[2];
        double gap = 0.0;
    };
    std::vector<FarPair> tooFar;
};

/// The boundaries of the faces no recorded edge or shell touches, paired where every sample of
/// each lies within 4 × `tolerance` (model units, > 0) of the other (kw::continuityTopology;
/// curves shorter than 1e-4 × `tolerance` are points). Where a curve lies near several, it
/// keeps the pairing whose ends meet best. A group of faces joined by pairings is taken whole
/// or not at all, so that no taken face borders one left to sewing. Cost: the continuity
/// kernel's matching plus kw::seamGaps' measure on the pairs found (shared out over the cores).
/// A pair whose measured gap exceeds `maxGap` (model units) is no edge (MatchedTopology::tooFar)
/// and does not join its faces into one shell.
MatchedTopology matchedTopology(const Scene& scene, double tolerance,
                                double maxGap = std::numeric_limits<double>::infinity());

} // namespace kw
