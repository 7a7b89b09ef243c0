// STEP files whose names are `$` (unset), as Rhino 8 writes them, import with a warning as
// OpenCASCADE reads them; a file whose geometry is damaged is still refused, and a file that is
// not STEP at all says so instead of calling itself truncated.
#include "model/cad/cadimport.h"
#include "tests/support/expected_test_util.h"

#include <QFile>
#include <QRegularExpression>
#include <QTest>

using namespace kw;

namespace {

QByteArray readAll(const QString& path) {
    QFile f(path);
    return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

QString writeCopy(const QByteArray& bytes, const QString& name) {
    const QString path = QStringLiteral(KW_TEST_OUTPUT_DIR "/lenient_") + name;
    QFile f(path);
    if (!f.open(QIODevice::WriteOnly) || f.write(bytes) != bytes.size())
        qFatal("cannot write %s", qPrintable(path));
    return path;
}

const QString kRhino = QStringLiteral(KW_TEST_DATA_DIR "/rhino_unset_names.step");

} // namespace

class TestStepLenient : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void unsetNamesImportWithAWarning() {
        QVERIFY(readAll(kRhino).contains("AXIS2_PLACEMENT_3D($,"));
        const auto result = importFile(kRhino);
        QVERIFY2(result, qPrintable(result.message()));
        QCOMPARE(result->scene.surfaces.size(), size_t(3));
        QCOMPARE(result->report.skipped.size(), 0);
        // The warning says what was lenient, once.
        int named = 0;
        for (const QString& w : result->report.warnings)
            named += w.contains(QStringLiteral("not a string")) ? 1 : 0;
        QCOMPARE(named, 1);
        // The geometry is whole: the cone and its two discs still close one solid.
        for (const Surface& s : result->scene.surfaces)
            QCOMPARE(s.solid, 0);
    }

    // A name replaced by an entity reference, a number or garbage that is not `$` is still a
    // string failure only, and as harmless; but a point without its coordinates is not.
    void damagedGeometryIsStillRefused() {
        QByteArray bytes = readAll(kRhino);
        const int at = bytes.indexOf("CARTESIAN_POINT($,(");
        QVERIFY(at > 0);
        const int open = bytes.indexOf('(', at + 16);
        const int close = bytes.indexOf(')', open);
        bytes.replace(open + 1, close - open - 1, "'x','y'");
        const auto refused = importFile(writeCopy(bytes, QStringLiteral("bad_point.step")));
        QVERIFY(!refused);
        const QString error = refused.message();
        QVERIFY2(error.contains(QStringLiteral("corrupt STEP file")), qPrintable(error));
    }

    void aFileWithOnlyGoodNamesHasNoWarning() {
        QString text = QString::fromLatin1(readAll(kRhino));
        text.replace(QStringLiteral("PRODUCT_DEFINITION_SHAPE($,"),
                     QStringLiteral("PRODUCT_DEFINITION_SHAPE('',"));
        text.replace(QRegularExpression(QStringLiteral(
                         "(AXIS2_PLACEMENT_3D|CARTESIAN_POINT|DIRECTION|CIRCLE)\\(\\$,")),
                     QStringLiteral("\\1('',"));
        const QByteArray bytes = text.toLatin1();
        QVERIFY(!bytes.contains("AXIS2_PLACEMENT_3D($,") && !bytes.contains("SHAPE($,"));
        const auto result = importFile(writeCopy(bytes, QStringLiteral("named.step")));
        QVERIFY2(result, qPrintable(result.message()));
        for (const QString& w : result->report.warnings)
            QVERIFY2(!w.contains(QStringLiteral("not a string")), qPrintable(w));
    }

    // Garbage named .step: the error says it is not STEP and what the first line holds, never
    // "truncated" (what a file without its last line is told).
    void garbageSaysWhatIsWrong_data() {
        QTest::addColumn<QByteArray>("bytes");
        QTest::newRow("text") << QByteArray("hello, this is not a model\nat all\n");
        QTest::newRow("binary") << QByteArray("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16);
        QTest::newRow("json") << QByteArray("{\"format\": \"knotwork\"}\n");
    }
    void garbageSaysWhatIsWrong() {
        QFETCH(QByteArray, bytes);
        const QString path =
            writeCopy(bytes, QStringLiteral("garbage_%1.step").arg(QTest::currentDataTag()));
        const auto refused = importFile(path);
        QVERIFY(!refused);
        const QString error = refused.message();
        QVERIFY2(error.startsWith(path + QStringLiteral(": ")), qPrintable(error));
        QVERIFY2(error.contains(QStringLiteral("not a STEP file")), qPrintable(error));
        QVERIFY2(error.contains(QStringLiteral("ISO-10303-21;")), qPrintable(error));
        QVERIFY2(!error.contains(QStringLiteral("truncated")), qPrintable(error));
        QVERIFY2(!error.contains(QLatin1Char('\n')), qPrintable(error));
    }

    // A STEP file cut short is the one told it is truncated.
    void truncatedStepSaysTruncated() {
        QByteArray bytes = readAll(kRhino);
        bytes.truncate(bytes.size() / 2);
        const auto refused = importFile(writeCopy(bytes, QStringLiteral("half.step")));
        QVERIFY(!refused);
        const QString error = refused.message();
        QVERIFY2(error.contains(QStringLiteral("truncated STEP file")), qPrintable(error));
    }
};

QTEST_GUILESS_MAIN(TestStepLenient)
#include "tst_step_lenient.moc"
