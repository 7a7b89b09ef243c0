// CAD import and export entry points: IGES, STEP and BREP (OpenCASCADE), OBJ and .knot files.
#pragma once

#include "model/importreport.h"
#include "model/scene.h"

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

/// Reads any supported file into a new, complete, valid Scene (Document::validate is empty).
/// IGES, STEP, BREP: every face becomes a surface (analytic ones converted to exact rational
/// B-splines) with its wires as trim loops; faces that cannot be converted are listed in
/// report.skipped. `progress`, if set, is called during long imports; returning false cancels.
/// Returns nullopt with `error` "<path>: <reason>" (or "<path>:<line>: <reason>" for OBJ) when
/// the file cannot be read, is truncated or corrupt, holds no importable surface, the format is
/// unknown or unavailable in this build, or the import was cancelled. Never a partial scene.
std::optional<ImportResult> importFile(const QString& path, QString& error,
                                       const ImportProgress& progress = {});

/// The OpenCASCADE part of importFile (format Iges, Step or Brep), same contract.
std::optional<ImportResult> importOcctFile(const QString& path, CadFormat format, QString& error,
                                           const ImportProgress& progress = {});

/// Message for OCCT formats in a build without OpenCASCADE.
QString occtUnavailableMessage();

} // namespace kw
