// The mesh peer's side of the bench's loops (--edit-loop, --zoom-loop): a model loaded as
// `render` loads it, its CPU reference frame, and the search for the peer's deflections at
// equal quality on screen (as tools/peer_search.py searches them).
#pragma once

#include "model/cad/facemesher.h"
#include "model/document/document.h"
#include "model/error.h"
#include "render/aov_buffer.h"
#include "render/render_types.h"
#include "render/triangle_mesh.h"

#include <QString>
#include <functional>
#include <vector>

namespace kw {
class OffscreenRenderer;
}

namespace kw::bench {

/// Process CPU time in milliseconds (CLOCK_PROCESS_CPUTIME_ID).
double processCpuMs();
/// Resident set of this process, MiB (/proc/self/statm).
double residentMiB();
double median(std::vector<double> v);
/// The CPU's model name from /proc/cpuinfo.
QString cpuModel();

/// The faces of `set` whose id is `only` (except false) or all but it (except true).
TriangleMesh toTriangleMesh(const TaggedMeshSet& set, SurfaceId only, bool except);

/// How far a frame is from the CPU reference: normal error p99 (degrees) and the silhouette's
/// largest distance (pixels).
struct ScreenQuality {
    double normalP99 = 0.0, silhouetteMax = 0.0;
};

/// The peer's deflection steps: from OCCT viewers' default (0.004 of the largest side, 20
/// degrees) down by 2x in distance and about 1.4x in angle per step.
constexpr int kDeflectionSteps = 16;
double linearStep(int k);  ///< fraction of the model's largest side
double angularStep(int k); ///< degrees

/// The search's result: the coarsest deflections found at equal quality.
struct PeerChoice {
    int linearIndex = 0, angularIndex = 0;
    double linear = 0.0, angular = 0.0; ///< model units, degrees
    bool matched = false;               ///< equal quality was reached
    ScreenQuality quality;
    long long triangles = 0;
};

/// One model, its camera and its reference frame; the peer's meshes are drawn in mesh slot 0.
class PeerModel {
public:
    struct Limits {
        int lights = 2;
        /// Equal quality: normal error p99 no worse than max(Knotwork's, this) degrees and
        /// silhouette max no worse than max(Knotwork's, 1) px (peer_search.py's bar).
        double normalP99Floor = 0.1;
        long long maxTriangles = 4'000'000; ///< the search stops refining past this
    };
    PeerModel(OffscreenRenderer& renderer, FaceMesher& mesher, Limits limits,
              std::function<void(const QString&)> progress);

    /// Reads `file` as `render` does; sets the fitted (or authored) camera, the model's size and
    /// the faces' tolerance as the STEP/IGES writer builds them.
    Status load(const QString& file);

    /// Renders the CPU reference at `camera` (side x side) and Knotwork's aliased frame with
    /// `options`, and measures Knotwork's quality, the bar the peer must reach.
    Status measureKnotwork(int side, const RenderOptions& options);
    /// The last frame drawn (any method) against the reference.
    Status compare(ScreenQuality& q);
    bool good(const ScreenQuality& q) const {
        return q.normalP99 <= std::max(knotwork.normalP99, limits.normalP99Floor) &&
               q.silhouetteMax <= std::max(knotwork.silhouetteMax, 1.0);
    }

    /// The whole model meshed at the deflections: a CAD file as its B-rep (shared edges, as a
    /// viewer that opened it meshes it), a project's surfaces face by face.
    Status staticMesh(double linear, double angular, TaggedMeshSet& out);
    /// Makes the peer's mesh at (linear, angular) for the search; `triangles` counts it.
    using MeshMaker = std::function<Status(double linear, double angular, TriangleMesh& out,
                                           long long& triangles)>;
    /// The search: from the step (linearIndex, angularIndex), finer in both until equal quality
    /// (or the triangle limit, or a mesh the child refuses), then coarser in one at a time
    /// while the quality holds and the triangles drop. Draws each candidate in slot 0.
    Status search(const MeshMaker& make, int linearIndex, int angularIndex, PeerChoice& out);
    /// The search over whole-model meshes (staticMesh) from OCCT's defaults.
    Status searchStatic(PeerChoice& out);

    OffscreenRenderer& renderer;
    FaceMesher& mesher;
    Limits limits;
    std::function<void(const QString&)> progress;
    QString path;
    Document doc;
    Camera camera;
    double side = 1.0;       ///< the model's largest side (model units)
    double tolerance = 1e-7; ///< the faces' tolerance (model units)
    AovBuffer reference;
    ScreenQuality knotwork;
};

} // namespace kw::bench
