// In-process IGES, STEP and BREP reading through OpenCASCADE (target knotwork_occt_read).
// Knotwork itself reads these formats in a child process (cadprocess.h) that loads this code
// as a module; tests that compare with OCCT call it directly.
#pragma once

#include "model/cad/cadimport.h"
#include "model/io/meshobj.h"

namespace kw {

/// Reads an IGES, STEP or BREP file in this process: same contract as importFile, except that
/// the scene is not yet finished (finishImport closes trim loops and validates). OCCT faults
/// that raise exceptions or signals become errors; a stack overflow or an endless loop inside
/// OCCT cannot be caught here, which is why Knotwork runs it in a child process.
Expected<ImportResult> importOcctFile(const QString& path, CadFormat format,
                                      const ImportProgress& progress = {});

/// importOcctFile, then the shape triangulated by OpenCASCADE (occt::meshFaces): `mesh` gets
/// one TaggedMesh per imported surface, tagged with its id. A meshing failure is an error;
/// faces left without triangles are warnings in the report.
Expected<ImportResult> importAndMeshOcctFile(const QString& path, CadFormat format,
                                             const MeshDeflection& deflection, TaggedMeshSet& mesh,
                                             const ImportProgress& progress = {});

/// The exported entry point of the OCCT modules (QLibrary resolves it by this name): calls
/// importOcctFile. The module is built with the executable that loads it (same compiler, same
/// kw types: it already takes QString and ImportResult), so it returns the Expected itself.
using OcctImportFunction = Expected<ImportResult> (*)(const QString& path, CadFormat format,
                                                      const ImportProgress* progress);
constexpr const char* kOcctImportSymbol = "knotwork_occt_import";
/// The module's second entry point: importAndMeshOcctFile.
using OcctMeshFunction = Expected<ImportResult> (*)(const QString& path, CadFormat format,
                                                    const MeshDeflection* deflection,
                                                    TaggedMeshSet* mesh,
                                                    const ImportProgress* progress);
constexpr const char* kOcctMeshSymbol = "knotwork_occt_mesh";
/// The module's third entry point: each surface of a scene built as a face and meshed alone
/// (occt::meshBuiltFaces), for `knotwork __mesh-faces`.
using OcctMeshFacesFunction = Status (*)(const Scene* scene, double tolerance, double linear,
                                         double angularDegrees, TaggedMeshSet* mesh);
constexpr const char* kOcctMeshFacesSymbol = "knotwork_occt_mesh_faces";
/// The module with every format and the mesher (all entry points): `knotwork mesh`.
constexpr const char* kOcctModuleName = "knotwork_occt";

/// The module a child process loads to read `format` without meshing: knotwork_occt_iges,
/// knotwork_occt_step or knotwork_occt_brep (kOcctImportSymbol only). Each links only the
/// toolkits of its format, so reading one file does not relocate the others' symbols
/// (docs/IMPORT.md). kOcctModuleName for any other format.
inline const char* occtReadModuleName(CadFormat format) {
    switch (format) {
    case CadFormat::Iges:
        return "knotwork_occt_iges";
    case CadFormat::Step:
        return "knotwork_occt_step";
    case CadFormat::Brep:
        return "knotwork_occt_brep";
    default:
        return kOcctModuleName;
    }
}

} // namespace kw
