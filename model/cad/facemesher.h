// The mesh peer's re-mesh after an edit: Knotwork surfaces built as OpenCASCADE faces
// (occtbuild.h) and triangulated by BRepMesh, one face at a time, in a persistent child process
// (`knotwork __mesh-faces`), so that OCCT stays out of the caller as for every other CAD verb
// and the child's start and module load are paid once, not per edit.
#pragma once

#include "model/document/scene.h"
#include "model/error.h"
#include "model/io/meshobj.h"

#include <QString>
#include <memory>
#include <vector>

namespace kw {

/// The hidden verb of the knotwork executable that serves FaceMesher (not in --help):
/// `knotwork __mesh-faces DIR [--max-memory-mb N]` reads requests "mesh NAME TOL LIN ANG" on
/// stdin, one a line: DIR/NAME is a scene hand-over (handover.h) whose surfaces it builds and
/// meshes alone (occt::meshBuiltFaces); it writes the triangles to DIR/NAME.obj
/// (writeTaggedMeshObj) and answers "ok WALL_MS CPU_MS" on stdout (the build and mesh alone,
/// measured in the child), or "error REASON". It ends at the end of stdin.
constexpr const char* kMeshFacesVerb = "__mesh-faces";

/// What one request cost in the child: wall and process CPU milliseconds of building the faces
/// and meshing them (hand-over and OBJ transfer not included: an in-process viewer has neither).
struct FaceMeshCost {
    double wallMs = 0.0;
    double cpuMs = 0.0;
};

/// Parent side of `knotwork __mesh-faces` (cadReaderExecutable() runs it). Not thread-safe.
class FaceMesher {
public:
    FaceMesher();
    ~FaceMesher(); ///< ends the child (closes its stdin, kills it if it lingers)
    FaceMesher(const FaceMesher&) = delete;
    FaceMesher& operator=(const FaceMesher&) = delete;

    /// Starts the child (once; later calls succeed at once). An Error when it cannot.
    Status start();
    /// Builds each of `surfaces` as a face (tolerance in model units, > 0) and meshes it alone
    /// at the deflections (absolute linear, angular in degrees, both > 0): `out` gets one
    /// TaggedMesh per surface, in order, with its id; `cost` what the child spent. Starts the
    /// child if needed. An Error when a face is refused, the child fails, crashes or takes
    /// longer than `seconds`.
    Status mesh(const std::vector<Surface>& surfaces, double tolerance, double linear,
                double angularDegrees, TaggedMeshSet& out, FaceMeshCost& cost,
                double seconds = 120.0);

private:
    struct Impl;
    std::unique_ptr<Impl> d;
};

} // namespace kw
