// The OCCT writer module's entry point: libknotwork_occt_write.so, loaded on demand by
// `knotwork __write-cad` only (the executables do not link OCCT).
#include "model/cad/occtexport.h"

#include <QtGlobal>

extern "C" Q_DECL_EXPORT kw::Expected<QByteArray>
knotwork_occt_export(const kw::Scene* scene, const QString& path, const kw::ExportOptions* options,
                     kw::ExportReport* report, const kw::ImportProgress* progress) {
    return kw::exportOcctBytes(*scene, path, *options, *report,
                               progress ? *progress : kw::ImportProgress{});
}
