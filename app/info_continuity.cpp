// The continuity report of `knotwork info --continuity`, as JSON and as a table.
#include "app/info_continuity.h"

#include <QJsonArray>

namespace kw::cli {

QJsonObject continuityJson(const ContinuityReport& report) {
    QJsonArray edges;
    for (const EdgeContinuity& e : report.edges)
        edges.append(QJsonObject{
            {QStringLiteral("faces"), QJsonArray{qint64(e.edge.sides[0].surface.value),
                                                 qint64(e.edge.sides[1].surface.value)}},
            {QStringLiteral("g0"), e.g0},
            {QStringLiteral("g1Degrees"), e.g1Degrees},
            {QStringLiteral("g2Percent"), e.g2Percent},
            {QStringLiteral("continuity"), continuityClassName(e.continuity)}});
    const ContinuityTolerances& t = report.tolerances;
    return QJsonObject{
        {QStringLiteral("edges"), edges},
        {QStringLiteral("freeEdges"), int(report.topology.freeSides.size())},
        {QStringLiteral("tolerances"), QJsonObject{{QStringLiteral("g0"), t.g0},
                                                   {QStringLiteral("g1Degrees"), t.g1Degrees},
                                                   {QStringLiteral("g2Percent"), t.g2Percent},
                                                   {QStringLiteral("match"), t.match}}}};
}

QString continuitySummary(const ContinuityReport& report) {
    const ContinuityTopology& t = report.topology;
    QString line = QStringLiteral("%1 shared edge(s): %2 G2, %3 G1, %4 G0, %5 open; %6 free "
                                  "edge(s)")
                       .arg(report.edges.size())
                       .arg(report.count(ContinuityClass::G2))
                       .arg(report.count(ContinuityClass::G1))
                       .arg(report.count(ContinuityClass::G0))
                       .arg(report.count(ContinuityClass::Open))
                       .arg(t.freeSides.size());
    if (!t.degenerateSides.empty())
        line += QStringLiteral("; %1 degenerate side(s) (poles, collapsed edges) not measured")
                    .arg(t.degenerateSides.size());
    if (t.matchedFaces > 0)
        line += QStringLiteral("; %1 face(s) without a shared-edge record, matched by boundary")
                    .arg(t.matchedFaces);
    if (t.unresolvedSides > 0)
        line += QStringLiteral("; %1 recorded side(s) naming a missing face, loop or curve")
                    .arg(t.unresolvedSides);
    return line;
}

QString continuityText(const QString& file, const ContinuityReport& report) {
    const ContinuityTolerances& t = report.tolerances;
    QString out = QStringLiteral("%1: continuity (G0 %2, G1 %3 deg, G2 %4 %)\n")
                      .arg(file)
                      .arg(t.g0)
                      .arg(t.g1Degrees)
                      .arg(t.g2Percent);
    out += QStringLiteral("%1 %2 %3 %4 %5  %6\n")
               .arg(QStringLiteral("edge"), 8)
               .arg(QStringLiteral("faces"), 13)
               .arg(QStringLiteral("G0 gap"), 11)
               .arg(QStringLiteral("G1 deg"), 10)
               .arg(QStringLiteral("G2 %"), 10)
               .arg(QStringLiteral("class"));
    for (const EdgeContinuity& e : report.edges) {
        const QString id = e.edge.recorded.isValid() ? QString::number(e.edge.recorded.value)
                                                     : QStringLiteral("-");
        const QString faces = QStringLiteral("%1/%2")
                                  .arg(e.edge.sides[0].surface.value)
                                  .arg(e.edge.sides[1].surface.value);
        out += QStringLiteral("%1 %2 %3 %4 %5  %6\n")
                   .arg(id, 8)
                   .arg(faces, 13)
                   .arg(e.g0, 11, 'g', 3)
                   .arg(e.g1Degrees, 10, 'f', 4)
                   .arg(e.g2Percent, 10, 'f', 2)
                   .arg(continuityClassName(e.continuity));
    }
    return out + continuitySummary(report) + QLatin1Char('\n');
}

} // namespace kw::cli
