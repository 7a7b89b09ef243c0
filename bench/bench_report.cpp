// JSON and markdown of a BenchReport.
#include "bench/bench_report.h"

#include <QJsonArray>

namespace kw::bench {

namespace {

QJsonObject timingJson(const Timing& t) {
    return QJsonObject{{QStringLiteral("fps"), t.fps()},
                       {QStringLiteral("fpsMin"), t.fpsMin()},
                       {QStringLiteral("fpsMax"), t.fpsMax()},
                       {QStringLiteral("msMedian"), t.medianMs},
                       {QStringLiteral("cpuMsPerFrame"), t.cpuMs}};
}

QJsonObject qualityJson(const Quality& q) {
    const NormalError& n = q.normal;
    const SilhouetteError& s = q.silhouette;
    return QJsonObject{
        {QStringLiteral("normalError"), QJsonObject{{QStringLiteral("meanDegrees"), n.meanDegrees},
                                                    {QStringLiteral("maxDegrees"), n.maxDegrees},
                                                    {QStringLiteral("pixels"), double(n.pixels)}}},
        {QStringLiteral("silhouetteError"),
         QJsonObject{{QStringLiteral("mismatched"), double(s.mismatched)},
                     {QStringLiteral("silhouettePixels"), double(s.silhouettePixels)},
                     {QStringLiteral("meanPixels"), s.meanPixels},
                     {QStringLiteral("maxPixels"), s.maxPixels},
                     {QStringLiteral("perSilhouettePixel"), s.perSilhouettePixel}}}};
}

QJsonObject methodJson(const MethodResult& r) {
    QJsonObject o = timingJson(r.timing);
    const QJsonObject q = qualityJson(r.quality);
    for (auto it = q.begin(); it != q.end(); ++it)
        o.insert(it.key(), it.value());
    o.insert(QStringLiteral("parameter"), r.parameter);
    o.insert(QStringLiteral("matched"), r.matched);
    o.insert(QStringLiteral("triangles"), double(r.triangles));
    return o;
}

double ratio(const MethodResult& a, const MethodResult& b) {
    return b.timing.fps() > 0.0 ? a.timing.fps() / b.timing.fps() : 0.0;
}

QJsonArray intArray(const std::vector<int>& v) {
    QJsonArray a;
    for (int x : v)
        a.append(x);
    return a;
}

QString num(double v, int decimals = 1) {
    return QString::number(v, 'f', decimals);
}

/// Small angles need significant digits, not decimals.
QString deg(double v) {
    return QString::number(v, 'g', 3);
}

/// "NxN", as 'knotwork render --size' spells sizes.
QString sq(int n) {
    return QStringLiteral("%1x%1").arg(n);
}

QString mark(const MethodResult& r) {
    return r.matched ? QString() : QStringLiteral(" †");
}

/// Table 1's trim drag cells: none without --trim-drag, '-' where the file has no trims.
QString dragCells(const BenchConfig& c, const std::optional<TrimDrag>& d) {
    if (!c.trimDrag)
        return {};
    if (!d)
        return QStringLiteral(" - | - | - |");
    return QStringLiteral(" %1 | %2 | %3 |")
        .arg(num(d->medianMs, 2), num(d->maskCpuMs, 2), QString::number(d->maskSide));
}

} // namespace

QJsonObject reportJson(const BenchReport& report, const QString& command) {
    const BenchConfig& c = report.config;
    QJsonArray t1;
    for (const Table1Row& r : report.table1) {
        QJsonObject o = timingJson(r.timing);
        o.insert(QStringLiteral("model"), r.model);
        o.insert(QStringLiteral("surfaces"), r.surfaces);
        o.insert(QStringLiteral("width"), r.side);
        o.insert(QStringLiteral("height"), r.side);
        o.insert(QStringLiteral("partitions"), c.table1Partitions);
        o.insert(QStringLiteral("coverage"), r.coverage);
        const QJsonObject q = qualityJson(r.quality);
        for (auto it = q.begin(); it != q.end(); ++it)
            o.insert(it.key(), it.value());
        if (c.trimDrag) { // null where the file has no trimmed surface
            const std::optional<TrimDrag>& d = r.drag;
            o.insert(QStringLiteral("trimDragMsMedian"),
                     d ? QJsonValue(d->medianMs) : QJsonValue());
            o.insert(QStringLiteral("maskRedrawCpuMs"),
                     d ? QJsonValue(d->maskCpuMs) : QJsonValue());
            o.insert(QStringLiteral("maskSide"), d ? QJsonValue(d->maskSide) : QJsonValue());
        }
        t1.append(o);
    }
    QJsonArray t2;
    for (const Table2Row& r : report.table2)
        t2.append(QJsonObject{
            {QStringLiteral("model"), r.model},
            {QStringLiteral("surfaces"), r.surfaces},
            {QStringLiteral("partitions"), r.partitions},
            {QStringLiteral("targetMaxNormalDegrees"), r.targetMaxDegrees},
            {QStringLiteral("width"), c.table2Size.width()},
            {QStringLiteral("height"), c.table2Size.height()},
            {QStringLiteral("exact"), methodJson(r.exact)},
            {QStringLiteral("baseline"), methodJson(r.baseline)},
            {QStringLiteral("fineMesh"), methodJson(r.fine)},
            {QStringLiteral("glu"), methodJson(r.glu)},
            {QStringLiteral("ratios"),
             QJsonObject{{QStringLiteral("exactOverBaseline"), ratio(r.exact, r.baseline)},
                         {QStringLiteral("exactOverFineMesh"), ratio(r.exact, r.fine)},
                         {QStringLiteral("exactOverGlu"), ratio(r.exact, r.glu)}}}});
    return QJsonObject{
        {QStringLiteral("command"), command},
        {QStringLiteral("machine"), QJsonObject{{QStringLiteral("cpu"), report.cpu},
                                                {QStringLiteral("threads"), report.threads},
                                                {QStringLiteral("gl"), report.gl}}},
        {QStringLiteral("settings"),
         QJsonObject{
             {QStringLiteral("frames"), c.frames},
             {QStringLiteral("warmup"), c.warmup},
             {QStringLiteral("lights"), c.lights},
             {QStringLiteral("sizes"), intArray(c.sizes)},
             {QStringLiteral("table1Partitions"), c.table1Partitions},
             {QStringLiteral("partitions"), intArray(c.partitions)},
             {QStringLiteral("table2Width"), c.table2Size.width()},
             {QStringLiteral("table2Height"), c.table2Size.height()},
             {QStringLiteral("referencePartitions"), c.referencePartitions},
             {QStringLiteral("fineMaxVertices"), double(c.fineMaxVertices)},
             {QStringLiteral("gluMinTolerance"), c.gluMinTolerance},
             {QStringLiteral("normalFloorDegrees"), c.normalFloorDegrees},
             {QStringLiteral("table1Mode"), c.table1Mode == RenderMode::Exact
                                                ? QStringLiteral("exact")
                                                : QStringLiteral("tessellated")},
             {QStringLiteral("exactShading"), c.shading == RenderOptions::Shading::DepthPrepass
                                                  ? QStringLiteral("prepass")
                                                  : QStringLiteral("exact-depth")},
             {QStringLiteral("trims"), c.trims},
             {QStringLiteral("trimDrag"), c.trimDrag},
             {QStringLiteral("gluMaxVertices"), double(c.gluMaxVertices)}}},
        {QStringLiteral("table1"), t1},
        {QStringLiteral("table2"), t2}};
}

QString reportMarkdown(const BenchReport& report, const QString& command,
                       const QStringList& plotFiles) {
    const BenchConfig& c = report.config;
    QString md;
    md += QStringLiteral("Machine: %1, %2 threads; %3. Frames: median of %4 after %5 warm-up, "
                         "glFinish per frame; %6 light(s).\n\n")
              .arg(report.cpu)
              .arg(report.threads)
              .arg(report.gl)
              .arg(c.frames)
              .arg(c.warmup)
              .arg(c.lights);
    md += QStringLiteral("Command: `%1`\n\n").arg(command);
    if (!report.table1.empty()) {
        md +=
            QStringLiteral("### Table 1: %2 mode, %1 × %1 partitions%3\n\n"
                           "| model | patches | resolution | covered | FPS | FPS min | FPS max | "
                           "CPU ms/frame | normal error mean / max (°) | silhouette error mean "
                           "/ max (px) |%4\n|---|---|---|---|---|---|---|---|---|---|%5\n")
                .arg(c.table1Partitions)
                .arg(c.table1Mode == RenderMode::Exact ? QStringLiteral("exact")
                                                       : QStringLiteral("tessellated"),
                     c.trims ? QString() : QStringLiteral(", trims off"),
                     c.trimDrag
                         ? QStringLiteral(" trim drag ms/frame | mask redraw CPU ms | mask side |")
                         : QString(),
                     c.trimDrag ? QStringLiteral("---|---|---|") : QString());
        for (const Table1Row& r : report.table1)
            md += QStringLiteral("| %1 | %2 | %3 | %4 % | %5 | %6 | %7 | %8 | %9 / %10 | %11 / "
                                 "%12 |%13\n")
                      .arg(r.model)
                      .arg(r.surfaces)
                      .arg(sq(r.side), num(100.0 * r.coverage), num(r.timing.fps()),
                           num(r.timing.fpsMin()), num(r.timing.fpsMax()), num(r.timing.cpuMs),
                           deg(r.quality.normal.meanDegrees), deg(r.quality.normal.maxDegrees))
                      .arg(num(r.quality.silhouette.meanPixels, 2),
                           num(r.quality.silhouette.maxPixels, 2), dragCells(c, r.drag));
        md += QLatin1Char('\n');
    }
    if (!report.table2.empty()) {
        md += QStringLiteral(
                  "### Table 2: speed at %1 × %2\n\n"
                  "| model | partitions | exact FPS | baseline FPS | exact / baseline | fine mesh "
                  "n × n | fine FPS | exact / fine | GLU tolerance (px) | GLU FPS | exact / GLU "
                  "|\n|---|---|---|---|---|---|---|---|---|---|---|\n")
                  .arg(c.table2Size.width())
                  .arg(c.table2Size.height());
        for (const Table2Row& r : report.table2)
            md += QStringLiteral("| %1 | %2 | %3 | %4 | %5 | %6%7 | %8 | %9 | %10%11 | %12 | "
                                 "%13 |\n")
                      .arg(r.model, sq(r.partitions), num(r.exact.timing.fps()),
                           num(r.baseline.timing.fps()), num(ratio(r.exact, r.baseline), 2),
                           sq(int(r.fine.parameter)), mark(r.fine), num(r.fine.timing.fps()),
                           num(ratio(r.exact, r.fine), 2), QString::number(r.glu.parameter),
                           mark(r.glu), num(r.glu.timing.fps()), num(ratio(r.exact, r.glu), 2));
        md += QStringLiteral("\nEqual quality: max normal error ≤ max(exact mode's, %1°). † not "
                             "reached: the search stopped at its limit (fine mesh: %2 vertices; "
                             "GLU: %3 px or %4 vertices) and this is the finest setting tried.\n\n")
                  .arg(c.normalFloorDegrees)
                  .arg(c.fineMaxVertices)
                  .arg(c.gluMinTolerance)
                  .arg(c.gluMaxVertices);
        md += QStringLiteral(
            "### Table 2: quality at the same settings\n\n"
            "| model | partitions | method | setting | triangles | normal error mean (°) | "
            "normal error max (°) | mismatched pixels | per silhouette pixel | silhouette error "
            "mean / max (px) |\n|---|---|---|---|---|---|---|---|---|---|\n");
        for (const Table2Row& r : report.table2) {
            const std::pair<QString, const MethodResult*> methods[] = {
                {QStringLiteral("exact"), &r.exact},
                {QStringLiteral("baseline"), &r.baseline},
                {QStringLiteral("fine mesh"), &r.fine},
                {QStringLiteral("GLU"), &r.glu}};
            for (const auto& [name, m] : methods) {
                const QString setting =
                    m == &r.glu ? QStringLiteral("%1 px").arg(m->parameter) : sq(int(m->parameter));
                md +=
                    QStringLiteral("| %1 | %2 | %3 | %4%5 | %6 | %7 | %8 | %9 | %10 | %11 / "
                                   "%12 |\n")
                        .arg(r.model, sq(r.partitions), name, setting, mark(*m))
                        .arg(m->triangles)
                        .arg(deg(m->quality.normal.meanDegrees), deg(m->quality.normal.maxDegrees))
                        .arg(m->quality.silhouette.mismatched)
                        .arg(num(m->quality.silhouette.perSilhouettePixel, 3),
                             num(m->quality.silhouette.meanPixels, 2),
                             num(m->quality.silhouette.maxPixels, 2));
            }
        }
        md += QLatin1Char('\n');
    }
    for (const QString& f : plotFiles)
        md += QStringLiteral("![%1](%1)\n\n").arg(f);
    return md;
}

} // namespace kw::bench
