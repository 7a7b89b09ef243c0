// `knotwork bench FILE --drag-step`: two drag steps of the teapot sample's face with the most
// shared edges, as read and tiled to 100 faces, at 64 x 64, write one "dragStep" row per model
// with the overlay on and off measured and the edge counts of the model and the face. No timing
// is compared.
#include "knotwork_process.h"

#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTest>
#include <cmath>

class TestBenchDragStep : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void writesTheRows();
    void overlayOffAlone();
    void refusesABadOverlayState();

private:
    QJsonObject run(const QStringList& extra, QString* out = nullptr);
};

QJsonObject TestBenchDragStep::run(const QStringList& extra, QString* out) {
    const QString dir = QStringLiteral(KW_TEST_OUTPUT_DIR "/bench_drag_step");
    QDir().mkpath(dir);
    const QString json = dir + QStringLiteral("/drag.json");
    QFile::remove(json);
    const Run r =
        knotwork(QStringList{QStringLiteral("bench"), QStringLiteral(KW_SAMPLES_DIR "/teapot.knot"),
                             QStringLiteral("--drag-step"), QStringLiteral("--drag-steps"),
                             QStringLiteral("2"), QStringLiteral("--drag-size"),
                             QStringLiteral("64"), QStringLiteral("--json"), json} +
                 extra);
    if (r.code != 0) {
        qWarning("%s", qPrintable(r.err));
        return {};
    }
    if (out)
        *out = r.out;
    QFile f(json);
    if (!f.open(QIODevice::ReadOnly))
        return {};
    return QJsonDocument::fromJson(f.readAll()).object();
}

void TestBenchDragStep::writesTheRows() {
    QString out;
    const QJsonObject root = run({QStringLiteral("--drag-faces"), QStringLiteral("0,100")}, &out);
    QVERIFY(!root.isEmpty());
    QVERIFY2(out.contains(QStringLiteral("### Drag step, Edge Continuity overlay on / off: 2 "
                                         "steps each at 64 x 64")),
             qPrintable(out));
    QVERIFY(root.value(QStringLiteral("table1")).toArray().isEmpty()); // the drag step alone
    const QJsonArray rows = root.value(QStringLiteral("dragStep")).toArray();
    QCOMPARE(rows.size(), 2);
    const QJsonObject one = rows.at(0).toObject(), tiled = rows.at(1).toObject();
    QCOMPARE(one.value(QStringLiteral("model")).toString(), QStringLiteral("teapot.knot"));
    QCOMPARE(one.value(QStringLiteral("surfaces")).toInt(), 32);
    QCOMPARE(one.value(QStringLiteral("copies")).toInt(), 1);
    QCOMPARE(tiled.value(QStringLiteral("copies")).toInt(), 4); // 4 x 32 >= 100
    QCOMPARE(tiled.value(QStringLiteral("surfaces")).toInt(), 128);
    // Edges found by matching each copy's boundaries; the copies lie apart, so 4 times one's.
    const int edges = one.value(QStringLiteral("edges")).toInt();
    QVERIFY(edges > 32);
    QCOMPARE(tiled.value(QStringLiteral("edges")).toInt(), 4 * edges);
    for (const QJsonObject& row : {one, tiled}) {
        QCOMPARE(row.value(QStringLiteral("steps")).toInt(), 2);
        // A bicubic teapot patch meets four others; its middle control point moves no boundary.
        QVERIFY(row.value(QStringLiteral("faceEdges")).toInt() >= 3);
        QCOMPARE(row.value(QStringLiteral("opens")).toString(), QString());
        for (const char* state : {"overlayOn", "overlayOff"}) {
            const QJsonObject t = row.value(QLatin1String(state)).toObject();
            for (const char* key : {"ms", "cpuMs", "continuityMs"}) {
                const QJsonValue v = t.value(QLatin1String(key));
                QVERIFY2(v.isDouble() && std::isfinite(v.toDouble()) && v.toDouble() > 0.0, key);
            }
        }
        const QJsonObject on = row.value(QStringLiteral("overlayOn")).toObject();
        QVERIFY(on.value(QStringLiteral("bandVertices")).toDouble() > 0.0);
        QVERIFY(row.value(QStringLiteral("overlayOff"))
                    .toObject()
                    .value(QStringLiteral("bandVertices"))
                    .toDouble() == 0.0);
        QVERIFY(row.value(QStringLiteral("ratio")).toDouble() > 0.0);
        QVERIFY(row.value(QStringLiteral("setupMs")).toDouble() > 0.0);
    }
    // The tiled model's bands are every copy's.
    QVERIFY(tiled.value(QStringLiteral("overlayOn"))
                .toObject()
                .value(QStringLiteral("bandVertices"))
                .toDouble() > 3.0 * one.value(QStringLiteral("overlayOn"))
                                        .toObject()
                                        .value(QStringLiteral("bandVertices"))
                                        .toDouble());
}

void TestBenchDragStep::overlayOffAlone() {
    const QJsonObject root = run({QStringLiteral("--drag-faces"), QStringLiteral("0"),
                                  QStringLiteral("--continuity-overlay"), QStringLiteral("off")});
    const QJsonArray rows = root.value(QStringLiteral("dragStep")).toArray();
    QCOMPARE(rows.size(), 1);
    const QJsonObject row = rows.at(0).toObject();
    QVERIFY(!row.contains(QStringLiteral("overlayOn")));
    QVERIFY(
        row.value(QStringLiteral("overlayOff")).toObject().value(QStringLiteral("ms")).toDouble() >
        0.0);
    QCOMPARE(row.value(QStringLiteral("ratio")).toDouble(), 0.0);
}

void TestBenchDragStep::refusesABadOverlayState() {
    const Run r = knotwork({QStringLiteral("bench"), QStringLiteral(KW_SAMPLES_DIR "/teapot.knot"),
                            QStringLiteral("--drag-step"), QStringLiteral("--continuity-overlay"),
                            QStringLiteral("maybe")});
    QCOMPARE(r.code, 2);
    QVERIFY2(r.err.contains(QStringLiteral("--continuity-overlay")), qPrintable(r.err));
}

QTEST_GUILESS_MAIN(TestBenchDragStep)
#include "tst_bench_drag_step.moc"
