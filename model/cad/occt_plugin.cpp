// The module libknotwork_occt.so: OpenCASCADE reading, loaded on demand by `knotwork
// __read-cad` only (the executables do not link OCCT).
#include "model/cad/occtimport.h"

#include <QtGlobal>

extern "C" Q_DECL_EXPORT bool knotwork_occt_import(const QString& path, kw::CadFormat format,
                                                   kw::ImportResult* result, QString* error,
                                                   const kw::ImportProgress* progress) {
    auto r = kw::importOcctFile(path, format, *error, progress ? *progress : kw::ImportProgress{});
    if (!r)
        return false;
    *result = std::move(*r);
    return true;
}

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
