// The OCCT modules' import entry point: libknotwork_occt_iges.so, _step.so and _brep.so (one
// format each) and libknotwork_occt.so (every format, with occt_plugin_mesh.cpp), loaded on
// demand by `knotwork __read-cad` only (the executables do not link OCCT).
#include "model/cad/occtimport.h"

#include <QtGlobal>

extern "C" Q_DECL_EXPORT kw::Expected<kw::ImportResult>
knotwork_occt_import(const QString& path, kw::CadFormat format,
                     const kw::ImportProgress* progress) {
    return kw::importOcctFile(path, format, progress ? *progress : kw::ImportProgress{});
}
