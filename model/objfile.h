// Wavefront OBJ: free-form surfaces with trims (OBJ 3.0) in and out, and triangle-mesh export.
#pragma once

#include "model/importreport.h"
#include "model/scene.h"

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
/// Returns true and sets `scene` on success; on malformed input returns false with
/// `error` = "<fileName>:<line>: <reason>" and leaves `scene` untouched.
bool parseObj(const QByteArray& text, const QString& fileName, Scene& scene, ImportReport& report,
              QString& error);
/// Reads a file and parses it as above; an unreadable file is an error naming the file.
bool readObjFile(const QString& path, Scene& scene, ImportReport& report, QString& error);

/// The whole scene as free-form OBJ: every surface as `cstype [rat] bspline` with its trims
/// as curv2 + trim/hole (hole for loops nested inside an odd number of others), numbers in
/// %.17g so parseObj(writeObj(s)) == s. Precondition: a valid scene (Document::validate).
QByteArray writeObj(const Scene& scene);

struct ObjMeshOptions {
    int subdivisions = 4; ///< each partition cell is cut into subdivisions x subdivisions quads
};

/// A triangle mesh for tools without NURBS: each surface is sampled on its partition grid
/// refined by options.subdivisions, with unit normals (surfaceFrame); a triangle whose
/// centroid the trims remove (trim.h, even-odd) is dropped. One `o` per surface.
QByteArray writeObjMesh(const Scene& scene, const ObjMeshOptions& options = {});

/// Writes bytes to a file; false with `error` naming the file when it cannot be written.
bool writeFileBytes(const QString& path, const QByteArray& bytes, QString& error);

} // namespace kw
