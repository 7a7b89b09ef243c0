// The mesh entry point of libknotwork_occt.so (`knotwork mesh`), kept out of the one-format
// modules so that they do not link TKMesh.
#include "model/cad/occt_internal.h"
#include "model/cad/occtimport.h"

#include <QtGlobal>
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>

extern "C" Q_DECL_EXPORT kw::Expected<kw::ImportResult>
knotwork_occt_mesh(const QString& path, kw::CadFormat format, const kw::MeshDeflection* deflection,
                   kw::TaggedMeshSet* mesh, const kw::ImportProgress* progress) {
    return kw::importAndMeshOcctFile(path, format, *deflection, *mesh,
                                     progress ? *progress : kw::ImportProgress{});
}

// `knotwork __mesh-faces`: each surface of `scene` built as a face and meshed alone
// (occt::meshBuiltFaces), OCCT faults caught.
extern "C" Q_DECL_EXPORT kw::Status knotwork_occt_mesh_faces(const kw::Scene* scene,
                                                             double tolerance, double linear,
                                                             double angularDegrees,
                                                             kw::TaggedMeshSet* mesh) {
    try {
        OCC_CATCH_SIGNALS
        return kw::occt::meshBuiltFaces(*scene, tolerance, linear, angularDegrees, *mesh);
    } catch (const Standard_Failure& e) {
        return kw::Error(QStringLiteral("OpenCASCADE failed meshing a face: %1 (%2)")
                             .arg(QString::fromUtf8(e.GetMessageString()),
                                  QString::fromLatin1(e.DynamicType()->Name())));
    }
}
