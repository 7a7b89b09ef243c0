// The OCCT writer module's entry point: libknotwork_occt_write.so, loaded on demand by
// `knotwork __write-cad` only (the executables do not link OCCT).
#include "model/cad/occtexport.h"

#include <QtGlobal>

extern "C" Q_DECL_EXPORT bool knotwork_occt_export(const kw::Scene* scene, const QString& path,
                                                   const kw::ExportOptions* options,
                                                   QByteArray* bytes, kw::ExportReport* report,
                                                   QString* error,
                                                   const kw::ImportProgress* progress) {
    auto r = kw::exportOcctBytes(*scene, path, *options, *report, *error,
                                 progress ? *progress : kw::ImportProgress{});
    if (!r)
        return false;
    *bytes = std::move(*r);
    return true;
}
