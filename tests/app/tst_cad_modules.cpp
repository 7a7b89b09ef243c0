// The OCCT modules (docs/IMPORT.md): `knotwork __read-cad` loads only the module of its file's
// format, which maps only that format's toolkits, and reads the file; `--mesh` loads the module
// with every format and the mesher; a module asked for a format it was not built with says so.
#include "knotwork_process.h"
#include "model/cad/cadimport.h"
#include "model/cad/occtimport.h"
#include "tests/support/expected_test_util.h"

#include <QDir>
#include <QFileInfo>
#include <QLibrary>
#include <QTemporaryDir>
#include <QTest>

namespace {

QString data(const char* name) {
    return QStringLiteral(KW_TEST_DATA_DIR "/") + QLatin1String(name);
}

// The shared objects the dynamic loader opened in a run (LD_DEBUG=files: "file=NAME [0];").
QStringList loadedFiles(const QString& ldDebug) {
    QStringList files;
    for (const QString& line : ldDebug.split(QLatin1Char('\n'))) {
        const qsizetype at = line.indexOf(QLatin1String("file="));
        if (at < 0)
            continue;
        const QString rest = line.mid(at + 5);
        files << QFileInfo(rest.left(rest.indexOf(QLatin1Char(' ')))).fileName();
    }
    return files;
}

bool anyStartsWith(const QStringList& files, const QString& prefix) {
    for (const QString& f : files)
        if (f.startsWith(prefix))
            return true;
    return false;
}

} // namespace

class TestCadModules : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void eachFormatLoadsOnlyItsModule_data() {
        QTest::addColumn<QString>("file");
        QTest::addColumn<QString>("module");
        QTest::addColumn<QStringList>("absent");
        QTest::newRow("IGES") << data("hammer.iges") << "libknotwork_occt_iges.so"
                              << QStringList{"libTKSTEP", "libTKMesh", "libknotwork_occt.so"};
        QTest::newRow("STEP") << data("screw.step") << "libknotwork_occt_step.so"
                              << QStringList{"libTKIGES", "libTKMesh", "libknotwork_occt.so"};
        QTest::newRow("BREP") << data("Pump_Nut.brep") << "libknotwork_occt_brep.so"
                              << QStringList{"libTKIGES", "libTKSTEP", "libTKMesh",
                                             "libknotwork_occt.so"};
    }
    void eachFormatLoadsOnlyItsModule() {
        QFETCH(QString, file);
        QFETCH(QString, module);
        QFETCH(QStringList, absent);
        QTemporaryDir dir;
        QVERIFY(dir.isValid());
        const Run r =
            knotwork({QStringLiteral("__read-cad"), file, dir.path()},
                     environmentWith(QStringLiteral("LD_DEBUG"), QStringLiteral("files")));
        QCOMPARE(r.code, 0);
        const QStringList files = loadedFiles(r.err);
        QVERIFY2(files.contains(module), qPrintable(files.join(QLatin1Char(' '))));
        QVERIFY(anyStartsWith(files, QStringLiteral("libTKernel")));
        for (const QString& a : absent)
            QVERIFY2(!anyStartsWith(files, a), qPrintable(a + QStringLiteral(" was loaded")));
        // What the module read reaches the parent: the same scene as the in-process reader's.
        const auto viaChild = kw::importFile(file);
        QVERIFY2(viaChild, qPrintable(viaChild.message()));
        QVERIFY(!viaChild->scene.surfaces.empty());
        QVERIFY(QFileInfo(dir.filePath(QStringLiteral("import.kwi"))).size() > 0);
    }

    void meshLoadsTheModuleWithEveryFormat() {
        QTemporaryDir dir;
        QVERIFY(dir.isValid());
        const Run r =
            knotwork({QStringLiteral("__read-cad"), data("hammer.iges"), dir.path(),
                      QStringLiteral("--mesh"), QStringLiteral("0"), QStringLiteral("20")},
                     environmentWith(QStringLiteral("LD_DEBUG"), QStringLiteral("files")));
        QCOMPARE(r.code, 0);
        const QStringList files = loadedFiles(r.err);
        QVERIFY(files.contains(QStringLiteral("libknotwork_occt.so")));
        QVERIFY(anyStartsWith(files, QStringLiteral("libTKMesh")));
        QVERIFY(!files.contains(QStringLiteral("libknotwork_occt_iges.so")));
        QVERIFY(QFileInfo(dir.filePath(QStringLiteral("mesh.obj"))).size() > 0);
    }

    void moduleRefusesAFormatItWasNotBuiltWith() {
        // In this process: the BREP module asked to read an IGES file (cmd_readcad.cpp never
        // does that; a wrong pairing must be an error naming the file, not a crash).
        const QString path = QFileInfo(QStringLiteral(KW_KNOTWORK_BIN))
                                 .dir()
                                 .filePath(QStringLiteral("libknotwork_occt_brep.so"));
        QLibrary library(path);
        const auto read =
            reinterpret_cast<kw::OcctImportFunction>(library.resolve(kw::kOcctImportSymbol));
        QVERIFY2(read, qPrintable(library.errorString()));
        const kw::Expected<kw::ImportResult> result =
            read(data("hammer.iges"), kw::CadFormat::Iges, nullptr);
        QVERIFY(!result);
        const QString error = result.message();
        QVERIFY2(error.startsWith(data("hammer.iges") + QStringLiteral(": ")), qPrintable(error));
        QVERIFY2(error.contains(QStringLiteral("does not read IGES files")), qPrintable(error));
    }
};

QTEST_GUILESS_MAIN(TestCadModules)
#include "tst_cad_modules.moc"
