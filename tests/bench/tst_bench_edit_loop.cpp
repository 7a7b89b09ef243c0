// `knotwork bench FILE --edit-loop`: a short drag of teapot.igs's largest free-form face at
// 64 x 64, with the peer's deflections given (no search), writes one "editLoop" row whose
// Knotwork and peer timings are there and whose peer re-meshed the face in the child. No timing
// is compared.
#include "knotwork_process.h"

#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTest>
#include <cmath>

namespace {

// Two drag steps of teapot.igs at 64 x 64, the peer's deflections given, JSON to `json`.
Run shortDrag(const QString& json, const QStringList& more = {}) {
    return knotwork(QStringList{QStringLiteral("bench"),
                                QStringLiteral(KW_TEST_DATA_DIR "/teapot.igs"),
                                QStringLiteral("--edit-loop"), QStringLiteral("--edit-steps"),
                                QStringLiteral("2"), QStringLiteral("--edit-size"),
                                QStringLiteral("64"), QStringLiteral("--peer-deflections"),
                                QStringLiteral("0.05,10"), QStringLiteral("--json"), json} +
                    more);
}

} // namespace

class TestBenchEditLoop : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void writesTheRows();
    void reportsPassTimes();
    void refusesBadDeflections();
};

void TestBenchEditLoop::writesTheRows() {
    const QString dir = QStringLiteral(KW_TEST_OUTPUT_DIR "/bench_edit_loop");
    QDir(dir).removeRecursively();
    QDir().mkpath(dir);
    const QString json = dir + QStringLiteral("/edit.json");
    const Run r = shortDrag(json);
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains(QStringLiteral("### Edit loop: 2 drag steps at 64 x 64")),
             qPrintable(r.out));
    QFile f(json);
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QJsonObject root = QJsonDocument::fromJson(f.readAll()).object();
    // The edit loop alone: no Table 1 or 2 rows.
    QVERIFY(root.value(QStringLiteral("table1")).toArray().isEmpty());
    const QJsonArray rows = root.value(QStringLiteral("editLoop")).toArray();
    QCOMPARE(rows.size(), 1);
    const QJsonObject row = rows.at(0).toObject();
    QCOMPARE(row.value(QStringLiteral("model")).toString(), QStringLiteral("teapot.igs"));
    QCOMPARE(row.value(QStringLiteral("steps")).toInt(), 2);
    QVERIFY(row.value(QStringLiteral("freeForm")).toBool()); // bicubic patches
    for (const char* key : {"knotworkMs", "knotworkStillMs", "peerMs", "peerDefaultMs",
                            "peerMeshMs", "peerDefaultMeshMs", "knotworkCpuMs", "peerCpuMs"}) {
        const QJsonValue v = row.value(QLatin1String(key));
        QVERIFY2(v.isDouble() && std::isfinite(v.toDouble()) && v.toDouble() > 0.0, key);
    }
    // The peer's step holds its re-mesh; its frame draws the whole model at the deflections
    // given, of which the edited face is a part.
    QVERIFY(row.value(QStringLiteral("peerMs")).toDouble() >=
            row.value(QStringLiteral("peerMeshMs")).toDouble());
    QVERIFY(row.value(QStringLiteral("deflectionsGiven")).toBool());
    QCOMPARE(row.value(QStringLiteral("peerLinearDeflection")).toDouble(), 0.05);
    QCOMPARE(row.value(QStringLiteral("peerAngularDeflection")).toDouble(), 10.0);
    const double tris = row.value(QStringLiteral("peerTriangles")).toDouble();
    const double face = row.value(QStringLiteral("peerFaceTriangles")).toDouble();
    QVERIFY(face > 0.0 && face < tris);
    QVERIFY(row.value(QStringLiteral("peerDefaultTriangles")).toDouble() > 0.0);
    QVERIFY(!row.contains(QStringLiteral("partialPasses"))); // only with --pass-times
}

// --pass-times: the editor's aliased frames pass by pass, each pass's time within the frame's.
void TestBenchEditLoop::reportsPassTimes() {
    const QString dir = QStringLiteral(KW_TEST_OUTPUT_DIR "/bench_edit_loop_passes");
    QDir(dir).removeRecursively();
    QDir().mkpath(dir);
    const QString json = dir + QStringLiteral("/edit.json");
    const Run r = shortDrag(json, {QStringLiteral("--pass-times")});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.err.contains(QStringLiteral("teapot.igs: the editor's aliased frame by pass")),
             qPrintable(r.err));
    QFile f(json);
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QJsonObject row = QJsonDocument::fromJson(f.readAll())
                                .object()
                                .value(QStringLiteral("editLoop"))
                                .toArray()
                                .at(0)
                                .toObject();
    const QJsonObject passes = row.value(QStringLiteral("partialPasses")).toObject();
    double sum = 0.0;
    for (const char* pass : {"sync", "prepass", "exact", "skirts", "present"}) {
        const QJsonObject p = passes.value(QLatin1String(pass)).toObject();
        const double wall = p.value(QStringLiteral("wallMs")).toDouble(-1.0);
        QVERIFY2(wall > 0.0 && p.value(QStringLiteral("cpuMs")).toDouble(-1.0) >= 0.0, pass);
        sum += wall;
    }
    // Medians per pass, each frame's passes within its edit-to-frame time.
    QVERIFY2(sum <= 2.0 * row.value(QStringLiteral("knotworkMs")).toDouble(),
             qPrintable(QString::number(sum)));
}

void TestBenchEditLoop::refusesBadDeflections() {
    const Run r = knotwork({QStringLiteral("bench"), QStringLiteral(KW_TEST_DATA_DIR "/teapot.igs"),
                            QStringLiteral("--edit-loop"), QStringLiteral("--peer-deflections"),
                            QStringLiteral("0.05")});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains(QStringLiteral("--peer-deflections '0.05'")), qPrintable(r.err));
}

QTEST_GUILESS_MAIN(TestBenchEditLoop)
#include "tst_bench_edit_loop.moc"
