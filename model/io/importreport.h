// ImportReport: what an importer converted, skipped (and why) and warned about.
#pragma once

#include <QString>
#include <QStringList>
#include <functional>

namespace kw {

/// Filled by every importer. Nothing a file contains is dropped silently: each entity that
/// did not become a surface or trim is listed in `skipped` with its reason.
struct ImportReport {
    int facesImported = 0;
    QStringList skipped;  ///< one line per face/entity not imported: "<what>: <reason>"
    QStringList warnings; ///< imported, but something was adjusted or ignored
    double seconds = 0.0; ///< wall time of the import

    int facesSkipped() const { return static_cast<int>(skipped.size()); }
    /// A multi-line human-readable summary (counts, then every skipped entity and warning).
    QString summary() const {
        QString out = QStringLiteral("%1 face(s) imported, %2 skipped, %3 warning(s), %4 s\n")
                          .arg(facesImported)
                          .arg(facesSkipped())
                          .arg(warnings.size())
                          .arg(seconds, 0, 'f', 3);
        for (const QString& s : skipped)
            out += QStringLiteral("skipped: ") + s + QLatin1Char('\n');
        for (const QString& w : warnings)
            out += QStringLiteral("warning: ") + w + QLatin1Char('\n');
        return out;
    }
};

/// Progress callback of long imports: `done` of `total` steps; return false to cancel.
using ImportProgress = std::function<bool(int done, int total)>;

} // namespace kw
