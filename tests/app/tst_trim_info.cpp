// knotwork info on trimmed files, run as a process: loops per surface with their curve counts,
// and the warnings of messy trims in text and JSON; knotwork render repeats them on stderr.
#include "expected_test_util.h"
#include "knotwork_process.h"
#include "model/io/knotfile.h"
#include "trim_test_util.h"

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QtTest>

using namespace kw;

class TestTrimInfo : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void loopsPerSurface() {
        const Run r =
            knotwork({QStringLiteral("info"), QStringLiteral(KW_SAMPLES_DIR "/star_island.knot")});
        QCOMPARE(r.code, 0);
        QVERIFY2(
            r.out.contains(QStringLiteral("trims: 4 loop(s) (loop 2: 1 curve(s), loop 3: 1 "
                                          "curve(s), loop 4: 4 curve(s), loop 5: 1 curve(s))")),
            qPrintable(r.out));
        QVERIFY(!r.out.contains(QStringLiteral("trim warning")));
    }

    void messyTrimsAreReported() {
        Scene scene;
        Surface s;
        s.id = SurfaceId{1};
        s.name = QStringLiteral("messy");
        s.geometry.degreeU = s.geometry.degreeV = 1;
        s.geometry.countU = s.geometry.countV = 2;
        s.geometry.knotsU = s.geometry.knotsV = {0, 0, 1, 1};
        s.geometry.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
        s.geometry.weights = {1, 1, 1, 1};
        // What a .knot file can hold (its reader refuses loops that do not close): the
        // domain boundary, a clockwise degree-15 hole, and a loop that encloses no area.
        const std::vector<TrimLoop> messy = kwtest::messyLoops(10);
        s.trims = {
            kwtest::loopOf(10, {kwtest::polylineCurve({{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}})}),
            messy[1], messy[3]};
        scene.surfaces.push_back(s);
        scene.nextId = 20;
        QTemporaryDir dir;
        const QString path = dir.filePath(QStringLiteral("messy.knot"));
        QString error;
        KW_VERIFY_OK(writeKnotFile(path, scene));

        const Run text = knotwork({QStringLiteral("info"), path});
        QVERIFY2(text.code == 0, qPrintable(text.err));
        QVERIFY2(text.out.contains(QStringLiteral("trims: 3 loop(s) (loop 10: 1 curve(s), loop 11: "
                                                  "1 curve(s), loop 13: 1 curve(s))")),
                 qPrintable(text.out));
        QCOMPARE(text.out.count(QStringLiteral("  trim warning: ")), 1);
        QVERIFY(text.out.contains(QStringLiteral(
            "trim warning: trim loop 13 is degenerate (encloses no area); ignored")));

        const Run json = knotwork({QStringLiteral("info"), path, QStringLiteral("--json")});
        QCOMPARE(json.code, 0);
        const QJsonObject surface = QJsonDocument::fromJson(json.out.toUtf8())
                                        .object()[QStringLiteral("surfaces")]
                                        .toArray()[0]
                                        .toObject();
        QCOMPARE(surface[QStringLiteral("trimLoops")].toArray().size(), 3);
        QCOMPARE(surface[QStringLiteral("trimLoops")]
                     .toArray()[0]
                     .toObject()[QStringLiteral("curves")]
                     .toInt(),
                 1);
        QCOMPARE(surface[QStringLiteral("trimWarnings")].toArray().size(), 1);

        // knotwork render draws it (exit 0) and says what it ignored.
        const Run render =
            knotwork({QStringLiteral("render"), path, QStringLiteral("-o"),
                      dir.filePath(QStringLiteral("messy.png")), QStringLiteral("--size"),
                      QStringLiteral("64x64")},
                     // the render half needs X (xvfb-run around ctest)
                     environmentWith(QStringLiteral("QT_QPA_PLATFORM"), QStringLiteral("xcb")));
        if (qEnvironmentVariableIsEmpty("DISPLAY")) {
            QVERIFY(render.err.contains(QStringLiteral("xvfb")));
            qInfo("no DISPLAY: the render half needs xvfb-run around ctest");
            return;
        }
        QVERIFY2(render.code == 0, qPrintable(render.err));
        QVERIFY2(
            render.err.contains(QStringLiteral("warning: surface 1: trim loop 13 is degenerate")),
            qPrintable(render.err));
    }
};

QTEST_APPLESS_MAIN(TestTrimInfo)
#include "tst_trim_info.moc"
