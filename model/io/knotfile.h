// Knotwork project files (.knot): the whole Scene as versioned JSON, see docs/FILE_FORMAT.md.
#pragma once

#include "model/document/scene.h"
#include "model/document/validation.h"
#include "model/error.h"

#include <QByteArray>
#include <QString>

namespace kw {

/// Format written by this build. Readers accept any file with the same major version (unknown
/// members of a newer minor version are ignored) and reject a newer major version.
constexpr int kKnotFormatMajor = 1;
/// 1.1 added the optional "display", 1.2 "solid", 1.3 "topology", 1.4 the display's
/// "sections" and "sectionCaps" the optional "continuity" and "unit", 1.5 a surface's "analytic"
constexpr int kKnotFormatMinor = 5;

/// Limits a file must respect (those of a valid scene, model/document/validation.h); larger values
/// are rejected as corrupt, not attempted.
constexpr long long kMaxKnotControlPoints = kMaxControlPoints; ///< countU * countV of one surface
constexpr int kMaxKnotCurvePoints = kMaxCurvePoints;           ///< control points of one curve
constexpr int kMaxKnotTrimLoops = kMaxTrimLoops;               ///< loops of one surface
constexpr int kMaxKnotLoopCurves = kMaxLoopCurves;             ///< curves of one loop
constexpr int kMaxKnotSurfaces = kMaxSurfaces;
/// Files larger than this are refused before they are read.
constexpr long long kMaxKnotFileBytes = 1LL << 30;

/// The scene as UTF-8 JSON in the current format (indented). Every double is written in its
/// shortest exact form, so it reads back bit for bit, except that the sign of a zero is lost
/// (QJsonDocument writes -0.0 as 0). The camera is omitted when !scene.camera.authored.
QByteArray sceneToJson(const Scene& scene);

/// Parses and validates a scene. On success ids are those of the file and nextId is raised
/// above every surface and loop id. On any problem returns an error whose message is ONE line
/// "<sourceName>: <JSON path>: <reason>", e.g.
/// "a.knot: $.surfaces[2].knotsU[5]: knot 0.25 is smaller than the previous knot 0.5",
/// with Error::file = sourceName and Error::location = the JSON path.
/// Never returns a partial scene; never crashes on any input.
Expected<Scene> sceneFromJson(const QByteArray& json, const QString& sourceName);

/// Writes the scene atomically (QSaveFile, flush checked): on failure the previous file at
/// `path` is left untouched and the error names the file and the reason. An invalid scene
/// (kw::checkScene) is refused before anything is written, so every file written reads back.
Status writeKnotFile(const QString& path, const Scene& scene);

/// Reads a .knot file; errors as for sceneFromJson, with the path as the source name (also
/// for a file that cannot be opened or is larger than 1 GiB).
Expected<Scene> readKnotFile(const QString& path);

} // namespace kw
