// CAD export: a scene written as STEP or IGES by OpenCASCADE in a child process
// (`knotwork __write-cad`, docs/EXCHANGE.md), the same way IGES/STEP/BREP are read.
#pragma once

#include "model/cad/cadimport.h"
#include "model/document/scene.h"
#include "model/error.h"

#include <QString>
#include <QStringList>

namespace kw {

/// How a scene is written.
struct ExportOptions {
    /// STEP application protocol: "ap203", "ap214" (default) or "ap242".
    QString stepSchema = QStringLiteral("ap214");
    /// IGES: false writes a B-rep (MSBO, type 186, with shells and faces 514/510), true writes
    /// every face as a trimmed surface (type 144).
    bool igesFaces = false;
    /// Refuse to write (an error, no file) when any face does not end in a closed solid.
    bool requireClosed = false;
    /// Sewing tolerance in model units; 0: the largest edge tolerance the import recorded
    /// (Scene::topology), at least 1e-5 of the scene's diagonal (and 1e-7).
    double tolerance = 0.0;
};

/// What an export wrote and found.
struct ExportReport {
    int faces = 0;      ///< faces written
    int solids = 0;     ///< closed shells written as solids
    int openShells = 0; ///< shells written open
    int looseFaces = 0; ///< faces sewn to no other face
    int freeEdges = 0;  ///< edges used by one face only (0 for a model of closed solids)
    /// One line per open seam: "seam between face 'A' and face 'B' is open: largest gap G
    /// (model units)", then other remarks (faces written as loose faces, ...).
    QStringList warnings;
    double seconds = 0.0; ///< in the writer's child, from the scene to the file's bytes
    /// Of `seconds`, the time in OpenCASCADE's writer alone (STEPControl_Writer /
    /// IGESControl_Writer: transfer of the built shape, then the text): the floor an export
    /// cannot go below whatever it does before.
    double writerSeconds = 0.0;
    /// Multi-line summary: counts, then every warning.
    QString summary() const;
    /// The report as lines for the child's hand-over, and back. fromText returns false on a
    /// malformed block.
    QByteArray toText() const;
    bool fromText(const QByteArray& text);
};

/// Checks `options` (schema name); ok() when valid, else an Error with the reason.
Status checkExportOptions(const ExportOptions& options);

/// Writes `scene` to `path` (.step/.stp or .iges/.igs) through OpenCASCADE in a child process
/// (the parent hands the scene over as a binary block in a temporary folder; a crash, the time
/// limit or Cancel in OCCT never reaches the caller). Every surface becomes a face with its
/// exact B-spline surface and trims (occtbuild.h); faces are sewn so that an edge two faces
/// share is written once; closed shells become solids, the rest open shells or loose faces.
/// The file is written under a temporary name and renamed: on any failure `path` is untouched.
/// Returns an Error "<path>: <reason>" (file = path) when the scene is empty, a surface is
/// refused, options.requireClosed and a face is not in a closed solid, the writer fails, crashes,
/// runs out of time or is cancelled ("<path>: export cancelled").
Status exportCadFile(const Scene& scene, const QString& path, const ExportOptions& options,
                     ExportReport& report, const ImportProgress& progress = {});

/// `knotwork convert IN.step|.iges|.brep OUT.step|.iges`: what importFile then exportCadFile do,
/// in one child process (`knotwork __write-cad IN OUT DIR --read-cad`), which loads
/// OpenCASCADE once: the read with its format's module, the import finished as importFile
/// finishes it (`imported` gets its report, also when the write then fails), the write as
/// exportCadFile writes. Errors as importFile's ("<IN>: <reason>", file = IN) for the read and
/// as exportCadFile's (file = OUT) for the write; the time limit is the read's plus the write's for
/// a file of IN's size.
Status convertCadFile(const QString& in, const QString& path, const ExportOptions& options,
                      ImportReport& imported, ExportReport& report,
                      const ImportProgress& progress = {});

} // namespace kw
