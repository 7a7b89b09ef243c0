// Builds without OpenCASCADE: the IGES/STEP/BREP entry point reports the formats unavailable.
#include "model/cad/cadimport.h"

namespace kw {

bool occtAvailable() {
    return false;
}

std::optional<ImportResult> importOcctFile(const QString& path, CadFormat format, QString& error,
                                           const ImportProgress&) {
    error = QStringLiteral("%1: cannot read %2: %3")
                .arg(path, cadFormatName(format), occtUnavailableMessage());
    return std::nullopt;
}

} // namespace kw
