// The scale table: tiling a part keeps every face, renumbers ids and separates the
// copies (label model: tileScene alone), and `knotwork bench --tables scale` on hammer.iges
// at N = 1 and 10 copies writes a well-formed report (label gl). No timing is asserted.
#include "bench/scale_scene.h"
#include "model/document/document.h"
#include "model/io/knotfile.h"
#include "tests/support/expected_test_util.h"

#include <QDir>
#include <QFile>
#include <QImage>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTest>
#include <cmath>
#include <set>

#ifdef KW_BENCH_RUN
#include "knotwork_process.h"
#endif

using namespace kw;

namespace {

[[maybe_unused]] bool finiteNonNegative(const QJsonValue& v) {
    return v.isDouble() && std::isfinite(v.toDouble()) && v.toDouble() >= 0.0;
}

} // namespace

class TestBenchScale : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void tilingKeepsFacesAndSeparatesCopies();
    void smokeRunWritesWellFormedReport();
};

void TestBenchScale::tilingKeepsFacesAndSeparatesCopies() {
    QString error;
    const auto unit = readKnotFile(QStringLiteral(KW_SAMPLES_DIR "/trimmed_plate.knot"));
    QVERIFY2(unit, qPrintable(unit.message()));
    const size_t n = unit->surfaces.size();
    QCOMPARE(bench::copiesForFaces(int(n), 1), 1);
    QCOMPARE(bench::copiesForFaces(45, 10000), 223);
    QCOMPARE(bench::copiesForFaces(45, 450), 10);
    const Scene tiled = bench::tileScene(*unit, 10);
    QCOMPARE(tiled.surfaces.size(), 10 * n);
    // A valid document: unique ids, nextId above them.
    KW_VERIFY_OK(Document::validate(tiled));
    std::set<std::uint32_t> ids;
    for (const Surface& s : tiled.surfaces) {
        ids.insert(s.id.value);
        for (const TrimLoop& l : s.trims)
            ids.insert(l.id.value);
    }
    QVERIFY(*ids.rbegin() < tiled.nextId);
    // Copy k is the unit moved by one offset: same knots, trims and weights, and the copies'
    // bounds do not overlap.
    std::vector<std::pair<glm::dvec3, glm::dvec3>> boxes;
    for (size_t k = 0; k < 10; ++k) {
        const glm::dvec3 offset =
            tiled.surfaces[k * n].geometry.points[0] - unit->surfaces[0].geometry.points[0];
        glm::dvec3 lo(1e300), hi(-1e300);
        for (size_t s = 0; s < n; ++s) {
            const Surface& a = unit->surfaces[s];
            const Surface& b = tiled.surfaces[k * n + s];
            QCOMPARE(b.geometry.knotsU, a.geometry.knotsU);
            QCOMPARE(b.geometry.weights, a.geometry.weights);
            QCOMPARE(b.trims.size(), a.trims.size());
            for (size_t t = 0; t < a.trims.size(); ++t)
                QVERIFY(b.trims[t].curves == a.trims[t].curves);
            for (size_t p = 0; p < a.geometry.points.size(); ++p) {
                QVERIFY(glm::length(b.geometry.points[p] - a.geometry.points[p] - offset) < 1e-9);
                lo = glm::min(lo, b.geometry.points[p]);
                hi = glm::max(hi, b.geometry.points[p]);
            }
        }
        for (const auto& [blo, bhi] : boxes)
            QVERIFY(glm::any(glm::lessThan(hi, blo)) || glm::any(glm::lessThan(bhi, lo)));
        boxes.emplace_back(lo, hi);
    }
}

void TestBenchScale::smokeRunWritesWellFormedReport() {
#ifndef KW_BENCH_RUN
    QSKIP("the bench run needs the knotwork binary (label gl)");
#else
    const QString dir = QStringLiteral(KW_TEST_OUTPUT_DIR "/bench_scale");
    QDir(dir).removeRecursively();
    QDir().mkpath(dir);
    const QString json = dir + QStringLiteral("/scale.json");
    const QString md = dir + QStringLiteral("/scale.md");
    // 1 and 450 faces of the 45-face hammer: N = 1 and N = 10 copies.
    const Run r =
        knotwork({QStringLiteral("bench"), QStringLiteral("--tables"), QStringLiteral("scale"),
                  QStringLiteral("--smoke"), QStringLiteral("--scale-faces"),
                  QStringLiteral("1,450"), QStringLiteral("--scale-size"), QStringLiteral("64"),
                  QStringLiteral("--json"), json, QStringLiteral("--markdown"), md});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QFile f(json);
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QJsonObject root = QJsonDocument::fromJson(f.readAll()).object();
    QVERIFY(root.value(QStringLiteral("table1")).toArray().isEmpty());
    const QJsonObject scale = root.value(QStringLiteral("scale")).toObject();
    QCOMPARE(scale.value(QStringLiteral("model")).toString(), QStringLiteral("hammer.iges"));
    QCOMPARE(scale.value(QStringLiteral("unitFaces")).toInt(), 45);
    QVERIFY(scale.value(QStringLiteral("unitTrimmed")).toInt() > 0);
    QCOMPARE(scale.value(QStringLiteral("width")).toInt(), 64);
    QCOMPARE(scale.value(QStringLiteral("partitioning")).toString(),
             QStringLiteral("uniform partitions, each surface's own"));
    const QJsonArray rows = scale.value(QStringLiteral("rows")).toArray();
    QCOMPARE(rows.size(), 2);
    const int copies[] = {1, 10};
    for (int k = 0; k < 2; ++k) {
        const QJsonObject row = rows.at(k).toObject();
        QCOMPARE(row.value(QStringLiteral("copies")).toInt(), copies[k]);
        QCOMPARE(row.value(QStringLiteral("faces")).toInt(), 45 * copies[k]);
        for (const char* key :
             {"loadSeconds", "firstFrameSeconds", "residentMiB", "dragStepMs", "dragToDrawMs"})
            QVERIFY2(finiteNonNegative(row.value(QLatin1String(key))), key);
        // Edit to draw call is a part of each step: its median cannot exceed the step's.
        QVERIFY(row.value(QStringLiteral("dragToDrawMs")).toDouble() > 0.0);
        QVERIFY(row.value(QStringLiteral("dragToDrawMs")).toDouble() <=
                row.value(QStringLiteral("dragStepMs")).toDouble());
        QVERIFY(row.value(QStringLiteral("loadSeconds")).toDouble() > 0.0);
        QVERIFY(row.value(QStringLiteral("residentMiB")).toDouble() > 1.0);
        // From FrameReport: a frame of trimmed faces holds GPU data and issues draws.
        QVERIFY(row.value(QStringLiteral("gpuBytes")).toDouble() > 0.0);
        QVERIFY(row.value(QStringLiteral("drawCalls")).toInt() > 0);
        for (const char* view : {"fitted", "closeUp"}) {
            const QJsonObject v = row.value(QLatin1String(view)).toObject();
            for (const char* key : {"fps", "msMedian", "cpuMsPerFrame", "renderCallMs"})
                QVERIFY2(finiteNonNegative(v.value(QLatin1String(key))),
                         qPrintable(
                             QStringLiteral("%1.%2").arg(QLatin1String(view), QLatin1String(key))));
            QVERIFY(v.value(QStringLiteral("fps")).toDouble() > 0.0);
        }
    }
    QFile mdFile(md);
    QVERIFY(mdFile.open(QIODevice::ReadOnly));
    const QString text = QString::fromUtf8(mdFile.readAll());
    QVERIFY2(text.contains(QStringLiteral("### Scale: hammer.iges (45 faces")), qPrintable(text));
    QVERIFY(text.contains(QStringLiteral("| 10 | 450 |")));
    QVERIFY(text.contains(QStringLiteral("Targets, 450 faces against 45")));
    const QImage plot(dir + QStringLiteral("/scale.png"));
    QVERIFY(!plot.isNull() && plot.width() > 100);

    // The editor's adaptive mode from a 1 x 1 minimum, in an analysis shading, as the report
    // says; a bad mode or shading is a usage error.
    const Run a =
        knotwork({QStringLiteral("bench"), QStringLiteral("--tables"), QStringLiteral("scale"),
                  QStringLiteral("--smoke"), QStringLiteral("--scale-faces"), QStringLiteral("1"),
                  QStringLiteral("--scale-size"), QStringLiteral("64"), QStringLiteral("--json"),
                  json, QStringLiteral("--scale-partition-mode"), QStringLiteral("adaptive"),
                  QStringLiteral("--scale-partitions"), QStringLiteral("1"),
                  QStringLiteral("--scale-shading"), QStringLiteral("mean")});
    QVERIFY2(a.code == 0, qPrintable(a.err));
    QFile f2(json);
    QVERIFY(f2.open(QIODevice::ReadOnly));
    const QJsonObject adaptive =
        QJsonDocument::fromJson(f2.readAll()).object().value(QStringLiteral("scale")).toObject();
    QCOMPARE(adaptive.value(QStringLiteral("partitioning")).toString(),
             QStringLiteral("adaptive partitions from 1 x 1"));
    QCOMPARE(adaptive.value(QStringLiteral("shading")).toString(), QStringLiteral("mean"));
    const Run badShading =
        knotwork({QStringLiteral("bench"), QStringLiteral("--tables"), QStringLiteral("scale"),
                  QStringLiteral("--scale-shading"), QStringLiteral("shiny")});
    QCOMPARE(badShading.code, 2);
    QVERIFY2(badShading.err.contains(QStringLiteral("--scale-shading 'shiny'")),
             qPrintable(badShading.err));
    const Run bad =
        knotwork({QStringLiteral("bench"), QStringLiteral("--tables"), QStringLiteral("scale"),
                  QStringLiteral("--scale-partition-mode"), QStringLiteral("fine")});
    QCOMPARE(bad.code, 2);
    QVERIFY2(bad.err.contains(QStringLiteral("--scale-partition-mode 'fine'")),
             qPrintable(bad.err));
#endif
}

QTEST_GUILESS_MAIN(TestBenchScale)
#include "tst_bench_scale.moc"
