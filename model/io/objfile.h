// Wavefront OBJ: free-form surfaces with trims (OBJ 3.0) in and out, and triangle-mesh export.
#pragma once

#include "model/document/scene.h"
#include "model/error.h"
#include "model/io/importreport.h"

#include <QByteArray>
#include <QString>

namespace kw {

/// Parses free-form OBJ text: v (with optional weight), vp, cstype [rat] bspline|bezier, deg,
/// surf, parm u|v, curv2, trim, hole, end, o/g names; continuation lines ending in '\'. A surf
/// range inside the knot domain cuts the surface to that range exactly (same parameters).
/// Polygons (f, l, p), 3D curves and other statements that carry no surface are counted in
/// report.warnings; surfaces of unsupported kinds (cardinal, taylor, bmatrix, degree above
/// kMaxDegree) are listed in report.skipped. Knotwork's own "# knotwork ..." comment lines,
/// written by writeObj, restore ids, names, partitions, materials, lights and camera exactly.
/// Gaps between the pieces of a trim loop are closed (kw::closeSceneTrimLoops) and reported in
/// report.warnings, and the scene must pass kw::checkScene, so an accepted file saves and
/// reopens. Sets `scene` and `report` on success; on malformed input returns the error
/// "<fileName>:<line>: <reason>" (Error::location "line N" where there is one) and leaves
/// `scene` and `report` untouched.
Status parseObj(const QByteArray& text, const QString& fileName, Scene& scene,
                ImportReport& report);
/// Reads a file and parses it as above; an unreadable file is an error naming the file.
Status readObjFile(const QString& path, Scene& scene, ImportReport& report);

/// The whole scene as free-form OBJ: every surface as `cstype [rat] bspline` with its trims
/// as curv2 + trim/hole (hole for loops nested inside an odd number of others), numbers in
/// %.17g so parseObj(writeObj(s)) == s. Precondition: a valid scene (Document::validate).
QByteArray writeObj(const Scene& scene);

/// Default cap of a --mesh file: 1 GiB (the command line raises it with --max-mesh-mb).
constexpr long long kDefaultMaxMeshBytes = 1LL << 30;

struct ObjMeshOptions {
    int subdivisions = 4; ///< each partition cell is cut into subdivisions x subdivisions quads
    long long maxBytes = kDefaultMaxMeshBytes; ///< writeObjMeshFile refuses a larger mesh
};

/// A triangle mesh for tools without NURBS: each surface is sampled on its partition grid
/// refined by options.subdivisions, with unit normals (surfaceFrame); a triangle whose
/// centroid the trims remove (trim.h, even-odd) is dropped. One `o` per surface. In memory,
/// without the size cap (for small scenes and tests).
QByteArray writeObjMesh(const Scene& scene, const ObjMeshOptions& options = {});
/// The same mesh streamed into `path` atomically, surface by surface. Refused with the error
/// "<path>: the mesh would be larger than the limit ..." (and the previous file untouched)
/// as soon as it is clear the file would exceed options.maxBytes: at once when the vertex
/// count alone cannot fit, else when a surface's lines pass the cap.
Status writeObjMeshFile(const QString& path, const Scene& scene, const ObjMeshOptions& options);

/// Writes bytes to a file atomically (kw::saveBytesAtomically: QSaveFile, flush checked);
/// an error naming the file when it cannot be written; the old file is then kept.
Status writeFileBytes(const QString& path, const QByteArray& bytes);
/// writeObj into `path` atomically; an invalid scene (kw::checkScene) is refused first.
Status writeObjFile(const QString& path, const Scene& scene);

} // namespace kw
