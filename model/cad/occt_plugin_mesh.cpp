// The mesh entry point of libknotwork_occt.so (`knotwork mesh`), kept out of the one-format
// modules so that they do not link TKMesh.
#include "model/cad/occtimport.h"

#include <QtGlobal>

extern "C" Q_DECL_EXPORT bool knotwork_occt_mesh(const QString& path, kw::CadFormat format,
                                                 const kw::MeshDeflection* deflection,
                                                 kw::ImportResult* result, kw::TaggedMeshSet* mesh,
                                                 QString* error,
                                                 const kw::ImportProgress* progress) {
    auto r = kw::importAndMeshOcctFile(path, format, *deflection, *mesh, *error,
                                       progress ? *progress : kw::ImportProgress{});
    if (!r)
        return false;
    *result = std::move(*r);
    return true;
}
