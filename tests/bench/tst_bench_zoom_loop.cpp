// `knotwork bench FILE --zoom-loop`: a close-up of screw.step (a closed solid with a shared-edge
// record) at 64 x 64 and 4x writes one "zoomLoop" row: the close-up looks at a contour of a face,
// the fitted view's mesh is measured at the zoom, the peer re-meshes only the faces in view, and
// both methods' times and memory are there. No timing is compared.
#include "knotwork_process.h"

#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTest>
#include <cmath>

class TestBenchZoomLoop : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void writesTheRows();
    void refusesBadLevels();
};

void TestBenchZoomLoop::writesTheRows() {
    const QString dir = QStringLiteral(KW_TEST_OUTPUT_DIR "/bench_zoom_loop");
    QDir(dir).removeRecursively();
    QDir().mkpath(dir);
    const QString json = dir + QStringLiteral("/zoom.json");
    const Run r = knotwork({QStringLiteral("bench"), QStringLiteral(KW_TEST_DATA_DIR "/screw.step"),
                            QStringLiteral("--zoom-loop"), QStringLiteral("--zoom-levels"),
                            QStringLiteral("4"), QStringLiteral("--zoom-repeats"),
                            QStringLiteral("1"), QStringLiteral("--edit-size"),
                            QStringLiteral("64"), QStringLiteral("--json"), json});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains(QStringLiteral("### Close-up: fitted view to zoom, 1 transitions at "
                                           "64 x 64")),
             qPrintable(r.out));
    QFile f(json);
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QJsonObject root = QJsonDocument::fromJson(f.readAll()).object();
    QVERIFY(root.value(QStringLiteral("table1")).toArray().isEmpty());
    const QJsonArray rows = root.value(QStringLiteral("zoomLoop")).toArray();
    QCOMPARE(rows.size(), 1);
    const QJsonObject row = rows.at(0).toObject();
    QCOMPARE(row.value(QStringLiteral("model")).toString(), QStringLiteral("screw.step"));
    QCOMPARE(row.value(QStringLiteral("zoom")).toDouble(), 4.0);
    QVERIFY2(
        row.value(QStringLiteral("target")).toString().startsWith(QStringLiteral("contour of ")),
        qPrintable(row.value(QStringLiteral("target")).toString()));
    for (const char* key :
         {"knotworkMs", "knotworkCpuMs", "knotworkAgainMs", "knotworkAgainCpuMs", "peerMs",
          "peerCpuMs", "peerMeshMs", "knotworkGpuMiB", "knotworkCpuMiB", "peerGpuMiB", "peerCpuMiB",
          "peerLinearDeflection", "peerAngularDeflection"}) {
        const QJsonValue v = row.value(QLatin1String(key));
        QVERIFY2(v.isDouble() && std::isfinite(v.toDouble()) && v.toDouble() > 0.0, key);
    }
    // The floor beside the first frame: the close-up drawn again, and its ratio to the peer.
    QVERIFY2(r.out.contains(QStringLiteral("drawn again / peer")), qPrintable(r.out));
    // The peer's close-up holds its re-mesh of the faces in view, a part of the model.
    QVERIFY(row.value(QStringLiteral("peerMs")).toDouble() >=
            row.value(QStringLiteral("peerMeshMs")).toDouble());
    const int inView = row.value(QStringLiteral("facesInView")).toInt();
    QVERIFY2(inView >= 1 && inView < 19, qPrintable(QString::number(inView)));
    QVERIFY(row.value(QStringLiteral("peerTriangles")).toDouble() > 0.0);
    QVERIFY(row.value(QStringLiteral("fittedTriangles")).toDouble() > 0.0);
    QVERIFY(row.value(QStringLiteral("fittedMeshNormalP99")).toDouble() > 0.0);
}

void TestBenchZoomLoop::refusesBadLevels() {
    const Run r = knotwork({QStringLiteral("bench"), QStringLiteral(KW_TEST_DATA_DIR "/screw.step"),
                            QStringLiteral("--zoom-loop"), QStringLiteral("--zoom-levels"),
                            QStringLiteral("1")});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains(QStringLiteral("--zoom-levels")), qPrintable(r.err));
}

QTEST_GUILESS_MAIN(TestBenchZoomLoop)
#include "tst_bench_zoom_loop.moc"
