// CAD import and export entry points: IGES, STEP and BREP (OpenCASCADE), OBJ and .knot files.
#pragma once

#include "model/document/scene.h"
#include "model/error.h"
#include "model/io/importreport.h"

#include <QString>
#include <optional>
#include <vector>

namespace kw {

enum class CadFormat { Unknown, Iges, Step, Brep, Obj, Knot };

/// The format named by a path's extension (case-insensitive): .igs/.iges, .stp/.step,
/// .brep/.brp, .obj, .knot; Unknown otherwise.
CadFormat cadFormatFromPath(const QString& path);
/// "IGES", "STEP", "BREP", "OBJ", ".knot" or "unknown".
QString cadFormatName(CadFormat format);

/// True when this build reads IGES, STEP and BREP (it was built with OpenCASCADE).
bool occtAvailable();

/// What an import produced. `sourceFaces[k]` is, for scene.surfaces[k], the 1-based index of
/// the face it came from in TopExp::MapShapes(shape, TopAbs_FACE) of the shape the reader
/// transferred (IGES, STEP, BREP), or the 1-based surface number in the file (OBJ, .knot).
struct ImportResult {
    Scene scene;
    ImportReport report;
    std::vector<int> sourceFaces;
};

/// Reads any supported file into a new, complete, valid Scene (kw::checkScene passes).
/// IGES, STEP, BREP: every face becomes a surface (analytic ones converted to exact rational
/// B-splines) with its wires as trim loops; faces that cannot be converted are listed in
/// report.skipped. These three are read by OpenCASCADE in a child process (cadprocess.h:
/// crash, time limit, memory limit, Cancel). `progress`, if set, is called during long imports
/// (for the child, also every 50 ms while it works); returning false cancels.
/// Returns an Error "<path>: <reason>" (or "<path>:<line>: <reason>" for OBJ; file = path) when
/// the file cannot be read, is truncated or corrupt, holds no importable surface, the format is
/// unknown or unavailable in this build, the reader crashed or ran out of time or memory, or
/// the import was cancelled. Never a partial scene.
Expected<ImportResult> importFile(const QString& path, const ImportProgress& progress = {});

/// What the tools that take any model file open (`knotwork render` and `info`, the editor's
/// command line): a .knot project as saved (readKnotFile: its camera, lights and display settings,
/// nothing repaired; also any path whose extension names no format), IGES, STEP, BREP and OBJ
/// through importFile. Errors as readKnotFile's and importFile's, naming the file.
Expected<ImportResult> openModelFile(const QString& path, const ImportProgress& progress = {});

/// The last step of every import: trim loops with gaps are closed (kw::closeSceneTrimLoops: snapped
/// within 1e-5 of the domain's diagonal, else bridged by a straight segment), each gap reported
/// in result.report.warnings, so the scene saves closed and reopens; then the scene is checked
/// with kw::checkScene. An Error "<path>: <reason>" when it is not valid.
Status finishImport(ImportResult& result, const QString& path);

/// How `knotwork mesh` asks OpenCASCADE to triangulate a CAD file (BRepMesh_IncrementalMesh's
/// absolute linear deflection in model units and angular deflection in degrees). linear 0:
/// OCCT viewers' default (0.004 times the largest side of the shape's bounding box).
struct MeshDeflection {
    double linear = 0.0;
    double angularDegrees = 20.0; ///< AIS_Shape's default deviation angle
};

/// Message for OCCT formats in a build without OpenCASCADE.
QString occtUnavailableMessage();

} // namespace kw
