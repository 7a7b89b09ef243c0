// knotwork convert, run as a process: round trips through OBJ, CAD files in, bad input exits 1.
#include "knotwork_process.h"
#include "model/io/knotfile.h"

#include <QDir>
#include <QProcess>
#include <QTest>

using namespace kw;

namespace {

QString out(const QString& name) {
    return QStringLiteral(KW_TEST_OUTPUT_DIR "/convert_") + name;
}
QString data(const char* name) {
    return QStringLiteral(KW_TEST_DATA_DIR "/") + name;
}

Scene readScene(const QString& path) {
    QString error;
    auto s = readKnotFile(path);
    if (!s)
        qWarning("%s", qPrintable(s.message()));
    return s.value_or(Scene{});
}

// A broken copy of a good file: cut in half, or 400 bytes of garbage in the middle.
QString broken(const QString& source, const QString& name, bool truncate) {
    QFile in(source);
    QByteArray bytes;
    if (in.open(QIODevice::ReadOnly))
        bytes = in.readAll();
    if (truncate)
        bytes.truncate(bytes.size() / 2);
    else
        bytes.replace(bytes.size() / 2, 400, QByteArray(400, '@'));
    const QString path = out(name);
    QFile f(path);
    if (f.open(QIODevice::WriteOnly))
        f.write(bytes);
    return path;
}

} // namespace

class TestConvert : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void knotToObjToKnotIsExact_data();
    void knotToObjToKnotIsExact();
    void meshOutput();
    void cadFiles_data();
    void cadFiles();
    void importedCadRoundTripsThroughObj();
    void badInputExitsOne_data();
    void badInputExitsOne();
    void usageExitsTwo();
};

void TestConvert::knotToObjToKnotIsExact_data() {
    QTest::addColumn<QString>("file");
    const QDir dir(QStringLiteral(KW_SAMPLES_DIR));
    for (const QString& f : dir.entryList({QStringLiteral("*.knot")}, QDir::Files))
        QTest::newRow(qPrintable(f)) << dir.filePath(f);
}

void TestConvert::knotToObjToKnotIsExact() {
    QFETCH(QString, file);
    const QString obj = out(QFileInfo(file).baseName() + QStringLiteral(".obj"));
    const QString back = out(QFileInfo(file).baseName() + QStringLiteral(".knot"));
    QFile::remove(back);
    Run r = knotwork({QStringLiteral("convert"), file, obj});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    r = knotwork({QStringLiteral("convert"), obj, back});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    const Scene original = readScene(file);
    QVERIFY(!original.surfaces.empty());
    QVERIFY(readScene(back) == original);
}

void TestConvert::meshOutput() {
    const QString mesh = out(QStringLiteral("teapot_mesh.obj"));
    const Run r =
        knotwork({QStringLiteral("convert"), QStringLiteral(KW_SAMPLES_DIR "/teapot.knot"), mesh,
                  QStringLiteral("--mesh"), QStringLiteral("--subdivisions"), QStringLiteral("1")});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QFile f(mesh);
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QByteArray text = f.readAll();
    // Untrimmed patches: 2 triangles per partition cell, one object per patch.
    qsizetype cells = 0;
    const Scene teapot = readScene(QStringLiteral(KW_SAMPLES_DIR "/teapot.knot"));
    for (const Surface& s : teapot.surfaces)
        cells += s.partitionsU * s.partitionsV;
    QCOMPARE(text.count("\nf "), 2 * cells);
    QCOMPARE(text.count("\no "), qsizetype(32));
}

void TestConvert::cadFiles_data() {
    QTest::addColumn<QString>("file");
    QTest::addColumn<int>("faces");
    QTest::newRow("teapot.igs") << data("teapot.igs") << 32;
    QTest::newRow("hammer.iges") << data("hammer.iges") << 45;
    QTest::newRow("screw.step") << data("screw.step") << 10;
}

void TestConvert::cadFiles() {
    QFETCH(QString, file);
    QFETCH(int, faces);
    const QString knot = out(QFileInfo(file).completeBaseName() + QStringLiteral("_cad.knot"));
    QFile::remove(knot);
    const Run r = knotwork({QStringLiteral("convert"), file, knot, QStringLiteral("--report")});
#ifdef KW_HAVE_OCCT
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains(QStringLiteral("%1 face(s) imported, 0 skipped").arg(faces)),
             qPrintable(r.out));
    QCOMPARE(readScene(knot).surfaces.size(), size_t(faces));
#else
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains(QLatin1String("unavailable")), qPrintable(r.err));
    QVERIFY(!QFile::exists(knot));
    Q_UNUSED(faces);
#endif
}

void TestConvert::importedCadRoundTripsThroughObj() {
#ifndef KW_HAVE_OCCT
    QSKIP("built without OpenCASCADE");
#else
    // Real trimmed data: hammer.iges -> .knot -> OBJ -> .knot keeps every bit.
    const QString a = out(QStringLiteral("hammer_a.knot"));
    const QString obj = out(QStringLiteral("hammer.obj"));
    const QString b = out(QStringLiteral("hammer_b.knot"));
    QCOMPARE(knotwork({QStringLiteral("convert"), data("hammer.iges"), a}).code, 0);
    QCOMPARE(knotwork({QStringLiteral("convert"), a, obj}).code, 0);
    QCOMPARE(knotwork({QStringLiteral("convert"), obj, b}).code, 0);
    const Scene first = readScene(a);
    QCOMPARE(first.surfaces.size(), size_t(45));
    QVERIFY(readScene(b) == first);
#endif
}

void TestConvert::badInputExitsOne_data() {
    QTest::addColumn<QString>("path");
    QTest::addColumn<QString>("expected");
    const QString obj = out(QStringLiteral("good.obj"));
    knotwork(
        {QStringLiteral("convert"), QStringLiteral(KW_SAMPLES_DIR "/trimmed_plate.knot"), obj});
    QTest::newRow("iges truncated") << broken(data("hammer.iges"), "t.iges", true) << "truncated";
    QTest::newRow("iges corrupt") << broken(data("hammer.iges"), "c.iges", false) << "corrupt";
    QTest::newRow("step truncated") << broken(data("screw.step"), "t.step", true) << "truncated";
    QTest::newRow("step corrupt") << broken(data("screw.step"), "c.step", false) << "corrupt";
    QTest::newRow("obj truncated") << broken(obj, "t.obj", true) << ":";
    QTest::newRow("obj corrupt") << broken(obj, "c.obj", false) << ":";
    QTest::newRow("missing") << out(QStringLiteral("missing.step")) << "no such file";
    const QString unsupported = out(QStringLiteral("cardinal.obj"));
    QFile f(unsupported);
    if (f.open(QIODevice::WriteOnly))
        f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\ncstype cardinal\ndeg 3 3\n"
                "surf 0 1 0 1 1 2 3 4\nend\n");
    f.close();
    QTest::newRow("obj nothing importable") << unsupported << "no surface could be imported";
    QTest::newRow("unknown type") << data("SOURCES.md") << "unknown file type";
}

void TestConvert::badInputExitsOne() {
    QFETCH(QString, path);
    QFETCH(QString, expected);
    const QString target = out(QStringLiteral("never.knot"));
    QFile::remove(target);
    const Run r = knotwork({QStringLiteral("convert"), path, target});
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.startsWith(path + QLatin1Char(':')), qPrintable(r.err)); // names the file
#ifdef KW_HAVE_OCCT
    QVERIFY2(r.err.contains(expected), qPrintable(r.err));
#endif
    QCOMPARE(r.err.count(QLatin1Char('\n')), 1); // one line
    QVERIFY(!QFile::exists(target));             // nothing half-written
}

void TestConvert::usageExitsTwo() {
    const QString knot = QStringLiteral(KW_SAMPLES_DIR "/bicubic.knot");
    QCOMPARE(knotwork({QStringLiteral("convert")}).code, 2);
    QCOMPARE(knotwork({QStringLiteral("convert"), knot}).code, 2);
    // An OUT whose name says no format is bad input, named in the message: exit 1.
    QCOMPARE(knotwork({QStringLiteral("convert"), knot, out(QStringLiteral("x.png"))}).code, 1);
    QCOMPARE(knotwork({QStringLiteral("convert"), knot, out(QStringLiteral("x.knot")),
                       QStringLiteral("--mesh")})
                 .code,
             2);
    QCOMPARE(knotwork({QStringLiteral("convert"), knot, out(QStringLiteral("x.obj")),
                       QStringLiteral("--subdivisions"), QStringLiteral("0")})
                 .code,
             2);
    QCOMPARE(knotwork({QStringLiteral("convert"), QStringLiteral("--frobnicate")}).code, 2);
    const Run help = knotwork({QStringLiteral("convert"), QStringLiteral("--help")});
    QCOMPARE(help.code, 0);
    QVERIFY(help.out.contains(QLatin1String("--report")));
}

QTEST_GUILESS_MAIN(TestConvert)
#include "tst_convert.moc"
