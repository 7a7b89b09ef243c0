// Test data imported as the editor imports it (kw::importFile, through the CAD reader child):
// the tests that use it link knotwork_cad and call kw_use_cad_reader.
#pragma once

#include "model/cad/cadimport.h"

#include <QString>
#include <QtGlobal>
#include <optional>

namespace kwtest {

/// tests/data/`file` imported, or nullopt with the reason logged as a warning.
inline std::optional<kw::Scene> importedPart(const QString& file) {
    kw::Expected<kw::ImportResult> imported =
        kw::importFile(QStringLiteral(KW_TEST_DATA_DIR "/") + file);
    if (!imported) {
        qWarning("%s", qPrintable(imported.message()));
        return std::nullopt;
    }
    return std::move(imported->scene);
}

} // namespace kwtest
