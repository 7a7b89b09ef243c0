// convertCadFile reads and writes in one child, yet each stage's failure is its own kw::Error:
// the read's names IN (message and Error::file), the write's names OUT, and a refused
// conversion leaves no OUT behind.
#include "model/cad/cadexport.h"
#include "tests/support/expected_test_util.h"
#include "tests/support/model_fixtures.h"

#include <QDir>
#include <QFile>
#include <QTemporaryDir>
#include <QTest>

using namespace kw;

class TestConvertErrors : public QObject {
    Q_OBJECT

    QTemporaryDir m_dir;

    QString out(const char* name) const { return m_dir.filePath(QLatin1String(name)); }
    static QString data(const char* name) {
        return QStringLiteral(KW_TEST_DATA_DIR "/") + QLatin1String(name);
    }
    static Status convert(const QString& in, const QString& path, bool requireClosed = false) {
        ExportOptions options;
        options.requireClosed = requireClosed;
        ImportReport imported;
        ExportReport report;
        return convertCadFile(in, path, options, imported, report);
    }
    static void write(const QString& path, const QByteArray& bytes) {
        QFile f(path);
        QVERIFY(f.open(QIODevice::WriteOnly | QIODevice::Truncate));
        QCOMPARE(f.write(bytes), bytes.size());
    }
    // The failure names `file` as its Error::file and at the start of its message, and
    // `target` was not written.
    static void failsNaming(const Status& result, const QString& file, const QString& target) {
        QVERIFY(!result);
        QCOMPARE(result.error().file, file);
        QVERIFY2(result.message().startsWith(file + QLatin1Char(':')),
                 qPrintable(result.message()));
        QVERIFY(!QFileInfo::exists(target));
    }

private Q_SLOTS:
    void initTestCase() { QVERIFY(m_dir.isValid()); }

    void inputNotCadNamesInput() {
        const QString in = out("notes.txt");
        write(in, "not a model\n");
        const Status r = convert(in, out("a.step"));
        failsNaming(r, in, out("a.step"));
        QCOMPARE(r.message(), in + QStringLiteral(": not an IGES, STEP or BREP file"));
    }

    void inputFolderNamesInput() {
        const QString in = out("folder.step");
        QVERIFY(QDir().mkpath(in));
        const Status r = convert(in, out("b.step"));
        failsNaming(r, in, out("b.step"));
        QVERIFY2(r.message().contains(QLatin1String("not a regular file")),
                 qPrintable(r.message()));
    }

    void inputHeadNamesInput() {
        const QString in = out("text.step");
        write(in, "hello, not STEP\n");
        failsNaming(convert(in, out("c.step")), in, out("c.step"));
    }

    void outputNameNamesOutput() {
        const QString in = data("product_named.step");
        const QString path = out("d.obj");
        const Status r = convert(in, path);
        failsNaming(r, path, path);
        QVERIFY2(r.message().contains(QLatin1String("not a STEP or IGES name")),
                 qPrintable(r.message()));
    }

    void outputFolderNamesOutput() {
        const QString path = out("missing/e.step");
        failsNaming(convert(data("product_named.step"), path), path, path);
    }

    // The head passes, the child's reader finds nothing to import: the read's failure, IN.
    void childReadFailureNamesInput() {
        const QString in = out("empty.step");
        write(in, "ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\nENDSEC;\nEND-ISO-10303-21;\n");
        failsNaming(convert(in, out("f.step")), in, out("f.step"));
    }

    // The read succeeds, the writer refuses open faces: the write's failure, OUT.
    void childWriteFailureNamesOutput() {
        const QString open = out("open.step");
        ExportReport report;
        KW_VERIFY_OK(exportCadFile(test::threeSurfaceScene(), open, {}, report));
        const QString path = out("g.step");
        const Status r = convert(open, path, true);
        failsNaming(r, path, path);
        QVERIFY2(r.message().contains(QLatin1String("closed")), qPrintable(r.message()));
        // Without the requirement the same file converts.
        KW_VERIFY_OK(convert(open, path));
        QVERIFY(QFileInfo(path).size() > 0);
    }
};

QTEST_GUILESS_MAIN(TestConvertErrors)
#include "tst_convert_errors.moc"
