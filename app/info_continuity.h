// `knotwork info FILE --continuity [--json]`: the continuity of every edge
// (model/analysis/continuity.h).
#pragma once

#include "model/analysis/continuity.h"

#include <QJsonObject>
#include <QString>

namespace kw::cli {

/// {"edges": [{"faces": [a, b], "g0", "g1Degrees", "g2Percent", "continuity"}], "freeEdges": N,
/// "tolerances": {"g0", "g1Degrees", "g2Percent", "match"}}: exactly these keys.
QJsonObject continuityJson(const ContinuityReport& report);
/// One row per edge (its recorded id or "-", faces, G0, G1, G2, class), then one summary line
/// with the counts of each class, free edges, degenerate sides, faces without a record and
/// recorded sides that name what the scene lacks.
QString continuityText(const QString& file, const ContinuityReport& report);
/// The summary line alone, without a newline (the text's last line; stderr beside --json).
QString continuitySummary(const ContinuityReport& report);

} // namespace kw::cli
