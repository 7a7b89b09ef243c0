// In-process STEP and IGES writing through OpenCASCADE (target knotwork_occt_write). Knotwork
// itself writes in a child process (`knotwork __write-cad`, cadexport.h) that loads this code as
// the module libknotwork_occt_write.so; tests that check the B-rep call it directly.
#pragma once

#include "model/cad/cadexport.h"

#include <QByteArray>
#include <optional>

namespace kw {

/// Writes `scene` to `path` in this process: the contract of exportCadFile (cadexport.h), with
/// OCCT exceptions and signals caught; a stack overflow or an endless loop inside OCCT is not,
/// which is why Knotwork runs it in a child process. The format comes from the extension.
Status exportOcctFile(const Scene& scene, const QString& path, const ExportOptions& options,
                      ExportReport& report, const ImportProgress& progress = {});

/// exportOcctFile's work without the write: the file's bytes. `path` names the file in errors
/// and in the STEP header, and its extension picks the format.
Expected<QByteArray> exportOcctBytes(const Scene& scene, const QString& path,
                                     const ExportOptions& options, ExportReport& report,
                                     const ImportProgress& progress = {});

/// The module's entry point (QLibrary resolves it by this name): exportOcctBytes. Built with
/// the executable that loads it, so it returns the Expected itself (as OcctImportFunction).
using OcctExportFunction = Expected<QByteArray> (*)(const Scene* scene, const QString& path,
                                                    const ExportOptions* options,
                                                    ExportReport* report,
                                                    const ImportProgress* progress);
constexpr const char* kOcctExportSymbol = "knotwork_occt_export";
/// The module with both writers: libknotwork_occt_write.so.
constexpr const char* kOcctWriteModuleName = "knotwork_occt_write";

} // namespace kw
