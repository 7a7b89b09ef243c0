// knotwork info / eval, run as a process: outputs agree with the kernel, and bad input or bad
// usage exits 1 or 2 with a one-line message.
#include "knotwork_process.h"
#include "model/io/knotfile.h"

#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTest>
#include <cstring>

using namespace kw;

namespace {

QStringList samples() {
    QStringList paths;
    const QDir dir(QStringLiteral(KW_SAMPLES_DIR));
    for (const QString& f : dir.entryList({QStringLiteral("*.knot")}, QDir::Files))
        paths << dir.filePath(f);
    return paths;
}

bool sameBits(double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

/// Parses "x y z" (text output) into a vector; false unless exactly three numbers.
bool parseVec(const QString& line, glm::dvec3& v) {
    const QStringList f = line.split(QLatin1Char(' '), Qt::SkipEmptyParts);
    if (f.size() != 4)
        return false;
    bool ok[3];
    for (int k = 0; k < 3; ++k)
        v[k] = f[k + 1].toDouble(&ok[k]);
    return ok[0] && ok[1] && ok[2];
}

bool sameVec(const glm::dvec3& a, const glm::dvec3& b) {
    return sameBits(a.x, b.x) && sameBits(a.y, b.y) && sameBits(a.z, b.z);
}

glm::dvec3 jsonVec(const QJsonValue& v) {
    const QJsonArray a = v.toArray();
    return {a[0].toDouble(), a[1].toDouble(), a[2].toDouble()};
}

/// Parameters to probe: corners, edge midpoints (poles, seams) and an interior point.
std::vector<glm::dvec2> probes(const NurbsSurface& g) {
    const Interval du = surfaceDomainU(g), dv = surfaceDomainV(g);
    std::vector<glm::dvec2> uv;
    for (double a : {0.0, 0.37, 1.0})
        for (double b : {0.0, 0.61, 1.0})
            uv.emplace_back(du.first + a * (du.last - du.first),
                            dv.first + b * (dv.last - dv.first));
    return uv;
}

QString uvArg(glm::dvec2 uv) {
    return QString::asprintf("%.17g,%.17g", uv.x, uv.y);
}

} // namespace

class TestCli : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void helpAndVersion();
    void infoOnEverySample();
    void infoJsonMatchesScene();
    void infoOnCadFile();
    void fileAloneOpensEditor();
    void evalMatchesKernel();
    void evalJsonMatchesKernel();
    void evalByName();
    void badInputExitsOne_data();
    void badInputExitsOne();
    void usageErrorsExitTwo_data();
    void usageErrorsExitTwo();
};

void TestCli::helpAndVersion() {
    const Run help = knotwork({QStringLiteral("--help")});
    QCOMPARE(help.code, 0);
    QVERIFY(help.out.contains(QStringLiteral("info")));
    QVERIFY(help.out.contains(QStringLiteral("eval")));
    QVERIFY(help.out.contains(QStringLiteral("knotwork FILE")));
    const Run version = knotwork({QStringLiteral("--version")});
    QCOMPARE(version.code, 0);
    QVERIFY(version.out.startsWith(QStringLiteral("knotwork ")));
    const Run evalHelp = knotwork({QStringLiteral("eval"), QStringLiteral("--help")});
    QCOMPARE(evalHelp.code, 0);
    QVERIFY(evalHelp.out.contains(QStringLiteral("--surface")));
}

void TestCli::infoOnEverySample() {
    QVERIFY(samples().size() >= 5);
    for (const QString& path : samples()) {
        const auto scene = readKnotFile(path);
        QVERIFY(scene);
        const Run r = knotwork({QStringLiteral("info"), path});
        QVERIFY2(r.code == 0, qPrintable(r.err));
        QVERIFY(r.err.isEmpty());
        for (const Surface& s : scene->surfaces) {
            const QString line =
                QStringLiteral("surface %1 \"%2\": degree %3 x %4, %5 x %6 control points")
                    .arg(s.id.value)
                    .arg(s.name)
                    .arg(s.geometry.degreeU)
                    .arg(s.geometry.degreeV)
                    .arg(s.geometry.countU)
                    .arg(s.geometry.countV);
            QVERIFY2(r.out.contains(line), qPrintable(path + QStringLiteral(": ") + line));
        }
    }
}

void TestCli::infoJsonMatchesScene() {
    for (const QString& path : samples()) {
        const auto scene = readKnotFile(path);
        QVERIFY(scene);
        const Run r = knotwork({QStringLiteral("info"), path, QStringLiteral("--json")});
        QCOMPARE(r.code, 0);
        QJsonParseError pe;
        const QJsonObject root = QJsonDocument::fromJson(r.out.toUtf8(), &pe).object();
        QVERIFY2(pe.error == QJsonParseError::NoError, qPrintable(pe.errorString()));
        const QJsonArray surfaces = root.value(QStringLiteral("surfaces")).toArray();
        QCOMPARE(surfaces.size(), qsizetype(scene->surfaces.size()));
        for (qsizetype k = 0; k < surfaces.size(); ++k) {
            const Surface& s = scene->surfaces[size_t(k)];
            const QJsonObject o = surfaces[k].toObject();
            QCOMPARE(o.value(QStringLiteral("id")).toInteger(), qint64(s.id.value));
            QCOMPARE(o.value(QStringLiteral("name")).toString(), s.name);
            QCOMPARE(o.value(QStringLiteral("degreeU")).toInt(), s.geometry.degreeU);
            QCOMPARE(o.value(QStringLiteral("countV")).toInt(), s.geometry.countV);
            const QJsonObject ku = o.value(QStringLiteral("knotsU")).toObject();
            QCOMPARE(ku.value(QStringLiteral("first")).toDouble(),
                     surfaceDomainU(s.geometry).first);
            QCOMPARE(ku.value(QStringLiteral("last")).toDouble(), surfaceDomainU(s.geometry).last);
            const QJsonArray loops = o.value(QStringLiteral("trimLoops")).toArray();
            QCOMPARE(loops.size(), qsizetype(s.trims.size()));
            for (qsizetype l = 0; l < loops.size(); ++l)
                QCOMPARE(loops[l].toObject().value(QStringLiteral("curves")).toInt(),
                         int(s.trims[size_t(l)].curves.size()));
            QCOMPARE(o.value(QStringLiteral("partitions")).toArray().at(0).toInt(), s.partitionsU);
            // The solid mark as the file has it (the sphere and torus samples), else none.
            const QJsonObject solid = o.value(QStringLiteral("solid")).toObject();
            QCOMPARE(o.contains(QStringLiteral("solid")), s.solid >= 0);
            if (s.solid >= 0) {
                QCOMPARE(solid.value(QStringLiteral("index")).toInt(), s.solid);
                QCOMPARE(solid.value(QStringLiteral("outside")).toString(),
                         s.outsideAlongNormal ? QStringLiteral("normal")
                                              : QStringLiteral("reversed"));
            }
        }
        QCOMPARE(root.value(QStringLiteral("lights")).toArray().size(),
                 qsizetype(scene->lights.size()));
        QVERIFY(root.value(QStringLiteral("camera")).isNull());
    }
    // The bicubic sample's u knots: a double interior knot plus ... distinct interior values.
    const Run r = knotwork({QStringLiteral("info"), QStringLiteral(KW_SAMPLES_DIR "/bicubic.knot"),
                            QStringLiteral("--json")});
    const QJsonObject ku = QJsonDocument::fromJson(r.out.toUtf8())
                               .object()[QStringLiteral("surfaces")][0][QStringLiteral("knotsU")]
                               .toObject();
    QCOMPARE(ku.value(QStringLiteral("distinctInterior")).toInt(), 1);
    QCOMPARE(ku.value(QStringLiteral("count")).toInt(), 10);
}

// info reads what render reads: a CAD file is imported (as convert does) and summarised.
void TestCli::infoOnCadFile() {
    const QString step = QStringLiteral(KW_TEST_DATA_DIR "/screw.step");
    const Run r = knotwork({QStringLiteral("info"), step});
    if (r.err.contains(QStringLiteral("built without OpenCASCADE")))
        QSKIP("built without OpenCASCADE");
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QVERIFY2(r.out.startsWith(step + QStringLiteral(": 10 surface(s)")), qPrintable(r.out));
    // The screw is one closed solid: every face says so (docs/IMPORT.md item 8).
    QCOMPARE(r.out.count(QStringLiteral("  face of closed solid 0, outside ")), 10);
    QVERIFY2(r.out.contains(QStringLiteral("camera: none")), qPrintable(r.out));
    QVERIFY2(r.err.isEmpty(), qPrintable(r.err)); // a clean import says nothing on stderr
}

void TestCli::fileAloneOpensEditor() {
    // `knotwork [FILE]` is the editor. This test runs on the offscreen platform, which has no
    // desktop OpenGL: the editor must say so and exit 1, not crash.
    // DISPLAY is removed too: with an X server reachable (ctest under xvfb-run) the offscreen
    // plugin would reach GLX through it and the editor would open.
    const QString path = QStringLiteral(KW_SAMPLES_DIR "/torus.knot");
    QProcessEnvironment offscreen = QProcessEnvironment::systemEnvironment();
    offscreen.insert(QStringLiteral("QT_QPA_PLATFORM"), QStringLiteral("offscreen"));
    offscreen.remove(QStringLiteral("DISPLAY"));
    offscreen.remove(QStringLiteral("WAYLAND_DISPLAY"));
    for (const QStringList& args : {QStringList{path}, QStringList{}}) {
        const Run r = knotwork(args, offscreen);
        QCOMPARE(r.code, 1);
        QVERIFY(r.out.isEmpty());
        QVERIFY2(r.err.contains(QStringLiteral("needs OpenGL 4.5")), qPrintable(r.err));
    }
    // Without any display the editor refuses before Qt's platform plugin can abort.
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    for (const char* name : {"QT_QPA_PLATFORM", "DISPLAY", "WAYLAND_DISPLAY"})
        env.remove(QLatin1String(name));
    const Run r = knotwork({path}, env);
    QCOMPARE(r.code, 1);
    QVERIFY2(r.err.contains(QStringLiteral("no display")), qPrintable(r.err));
}

void TestCli::evalMatchesKernel() {
    for (const QString& path : samples()) {
        const auto scene = readKnotFile(path);
        QVERIFY(scene);
        // Every surface of the small samples; every fourth teapot patch (process start-up costs).
        const size_t step = scene->surfaces.size() > 4 ? 4 : 1;
        for (size_t k = 0; k < scene->surfaces.size(); k += step) {
            const Surface& s = scene->surfaces[k];
            for (const glm::dvec2& uv : probes(s.geometry)) {
                const Run r =
                    knotwork({QStringLiteral("eval"), path, QStringLiteral("--surface"),
                              QString::number(s.id.value), QStringLiteral("--uv"), uvArg(uv)});
                QVERIFY2(r.code == 0, qPrintable(r.err));
                const QStringList lines = r.out.split(QLatin1Char('\n'), Qt::SkipEmptyParts);
                QCOMPARE(lines.size(), 5);
                const SurfaceFrame f = surfaceFrame(s.geometry, uv.x, uv.y);
                glm::dvec3 point, du, dv, normal;
                QVERIFY(lines[1].startsWith(QStringLiteral("point ")) && parseVec(lines[1], point));
                QVERIFY(lines[2].startsWith(QStringLiteral("du ")) && parseVec(lines[2], du));
                QVERIFY(lines[3].startsWith(QStringLiteral("dv ")) && parseVec(lines[3], dv));
                QVERIFY(lines[4].startsWith(QStringLiteral("normal ")) &&
                        parseVec(lines[4], normal));
                // %.17g round-trips, so the printed numbers are the kernel's doubles exactly.
                QVERIFY2(sameVec(point, f.point), qPrintable(path + QLatin1Char(' ') + lines[1]));
                QVERIFY(sameVec(du, f.du));
                QVERIFY(sameVec(dv, f.dv));
                QVERIFY2(sameVec(normal, f.normal),
                         qPrintable(path + QLatin1Char(' ') + uvArg(uv) + QLatin1Char(' ') +
                                    lines[4] +
                                    QString::asprintf(" kernel %.17g %.17g %.17g", f.normal.x,
                                                      f.normal.y, f.normal.z)));
                QVERIFY(std::abs(glm::length(normal) - 1.0) < 1e-12);
            }
        }
    }
}

void TestCli::evalJsonMatchesKernel() {
    const QString path = QStringLiteral(KW_SAMPLES_DIR "/sphere.knot");
    const auto scene = readKnotFile(path);
    QVERIFY(scene);
    const NurbsSurface& g = scene->surfaces[0].geometry;
    const Run r = knotwork({QStringLiteral("eval"), path, QStringLiteral("--surface=1"),
                            QStringLiteral("--uv=0.1,0.3"), QStringLiteral("--json")});
    QVERIFY2(r.code == 0, qPrintable(r.err));
    QJsonParseError pe;
    const QJsonObject o = QJsonDocument::fromJson(r.out.toUtf8(), &pe).object();
    QVERIFY2(pe.error == QJsonParseError::NoError, qPrintable(pe.errorString() + r.out));
    const SurfaceFrame f = surfaceFrame(g, 0.1, 0.3);
    QVERIFY(sameVec(jsonVec(o[QStringLiteral("point")]), f.point));
    QVERIFY(sameVec(jsonVec(o[QStringLiteral("du")]), f.du));
    QVERIFY(sameVec(jsonVec(o[QStringLiteral("dv")]), f.dv));
    QVERIFY(sameVec(jsonVec(o[QStringLiteral("normal")]), f.normal));
    QCOMPARE(o[QStringLiteral("name")].toString(), QStringLiteral("Unit sphere"));
    // On the unit sphere the outward normal is the point itself.
    QVERIFY(glm::length(f.normal - f.point) < 1e-12);
}

void TestCli::evalByName() {
    const QString path = QStringLiteral(KW_SAMPLES_DIR "/teapot.knot");
    const Run byName =
        knotwork({QStringLiteral("eval"), path, QStringLiteral("--surface"),
                  QStringLiteral("spout 2"), QStringLiteral("--uv"), QStringLiteral("0.5,0.5")});
    QVERIFY2(byName.code == 0, qPrintable(byName.err));
    const auto scene = readKnotFile(path);
    QVERIFY(scene);
    const Surface* spout = nullptr;
    for (const Surface& s : scene->surfaces)
        if (s.name == QLatin1String("spout 2"))
            spout = &s;
    QVERIFY(spout);
    const Run byId = knotwork({QStringLiteral("eval"), path, QStringLiteral("--surface"),
                               QString::number(spout->id.value), QStringLiteral("--uv"),
                               QStringLiteral("0.5,0.5")});
    QCOMPARE(byId.code, 0);
    QCOMPARE(byName.out, byId.out);
}

void TestCli::badInputExitsOne_data() {
    QTest::addColumn<QStringList>("args");
    QTest::addColumn<QString>("file");
    QTest::addColumn<QString>("mentions");
    const QString broken = QStringLiteral(KW_TEST_DATA_DIR "/broken/");
    const QString sphere = QStringLiteral(KW_SAMPLES_DIR "/sphere.knot");
    for (const char* f :
         {"truncated.knot", "decreasing_knot.knot", "future_version.knot", "nan_string.knot"}) {
        const QString path = broken + QLatin1String(f);
        QTest::newRow(f) << QStringList{QStringLiteral("info"), path} << path
                         << QStringLiteral("$");
        QTest::newRow(qPrintable(QStringLiteral("eval ") + QLatin1String(f)))
            << QStringList{QStringLiteral("eval"),      path,
                           QStringLiteral("--surface"), QStringLiteral("1"),
                           QStringLiteral("--uv"),      QStringLiteral("0.5,0.5")}
            << path << QStringLiteral("$");
    }
    // A file that only claims to be IGES: the importer's one-line error, naming it.
    const QString notIges = QStringLiteral(KW_TEST_OUTPUT_DIR "/not iges.igs");
    QFile f(notIges);
    QVERIFY(f.open(QIODevice::WriteOnly) && f.write("not an IGES file\n") > 0);
    f.close();
    QTest::newRow("info not IGES")
        << QStringList{QStringLiteral("info"), notIges} << notIges << QString();
    // The editor imports a CAD file named on its command line; one that cannot be opened is
    // refused before any window, naming the file.
    const QString step = QStringLiteral(KW_TEST_OUTPUT_DIR "/no such part.step");
    QTest::newRow("missing CAD file alone")
        << QStringList{step} << step << QStringLiteral("no such file");
    const QString missing = QStringLiteral(KW_TEST_OUTPUT_DIR "/no such file.knot");
    QTest::newRow("missing file") << QStringList{QStringLiteral("info"), missing} << missing
                                  << QStringLiteral("cannot open");
    QTest::newRow("missing file alone")
        << QStringList{missing} << missing << QStringLiteral("cannot open");
    QTest::newRow("u outside domain")
        << QStringList{QStringLiteral("eval"),      sphere,
                       QStringLiteral("--surface"), QStringLiteral("1"),
                       QStringLiteral("--uv"),      QStringLiteral("1.5,0.5")}
        << sphere << QStringLiteral("u in [0, 1]");
    QTest::newRow("v outside domain")
        << QStringList{QStringLiteral("eval"),      sphere,
                       QStringLiteral("--surface"), QStringLiteral("1"),
                       QStringLiteral("--uv"),      QStringLiteral("0.5,-0.25")}
        << sphere << QStringLiteral("v in [0, 1]");
    QTest::newRow("unknown surface")
        << QStringList{QStringLiteral("eval"),      sphere,
                       QStringLiteral("--surface"), QStringLiteral("42"),
                       QStringLiteral("--uv"),      QStringLiteral("0.5,0.5")}
        << sphere << QStringLiteral("no surface has the id or name \"42\"");
}

void TestCli::badInputExitsOne() {
    QFETCH(QStringList, args);
    QFETCH(QString, file);
    QFETCH(QString, mentions);
    const Run r = knotwork(args);
    QCOMPARE(r.code, 1);
    QVERIFY(r.out.isEmpty());
    QVERIFY2(r.err.endsWith(QLatin1Char('\n')) && r.err.count(QLatin1Char('\n')) == 1,
             qPrintable(r.err));
    QVERIFY2(r.err.startsWith(file + QStringLiteral(": ")), qPrintable(r.err));
    QVERIFY2(r.err.contains(mentions), qPrintable(r.err));
}

void TestCli::usageErrorsExitTwo_data() {
    QTest::addColumn<QStringList>("args");
    const QString sphere = QStringLiteral(KW_SAMPLES_DIR "/sphere.knot");
    QTest::newRow("unknown subcommand") << QStringList{QStringLiteral("frobnicate")};
    QTest::newRow("unknown global option") << QStringList{QStringLiteral("--frob")};
    QTest::newRow("info without file") << QStringList{QStringLiteral("info")};
    QTest::newRow("info two files") << QStringList{QStringLiteral("info"), sphere, sphere};
    QTest::newRow("info unknown option")
        << QStringList{QStringLiteral("info"), sphere, QStringLiteral("--bogus")};
    QTest::newRow("eval without surface") << QStringList{
        QStringLiteral("eval"), sphere, QStringLiteral("--uv"), QStringLiteral("0.5,0.5")};
    QTest::newRow("eval without uv") << QStringList{
        QStringLiteral("eval"), sphere, QStringLiteral("--surface"), QStringLiteral("1")};
    QTest::newRow("eval uv one number")
        << QStringList{QStringLiteral("eval"),      sphere,
                       QStringLiteral("--surface"), QStringLiteral("1"),
                       QStringLiteral("--uv"),      QStringLiteral("0.5")};
    QTest::newRow("eval uv not numbers")
        << QStringList{QStringLiteral("eval"),      sphere,
                       QStringLiteral("--surface"), QStringLiteral("1"),
                       QStringLiteral("--uv"),      QStringLiteral("a,b")};
    QTest::newRow("eval uv nan") << QStringList{
        QStringLiteral("eval"),      sphere,
        QStringLiteral("--surface"), QStringLiteral("1"),
        QStringLiteral("--uv"),      QStringLiteral("nan,0")};
    QTest::newRow("editor unknown shading")
        << QStringList{QStringLiteral("--shading"), QStringLiteral("nope"), sphere};
    QTest::newRow("eval uv missing value")
        << QStringList{QStringLiteral("eval"), sphere, QStringLiteral("--surface"),
                       QStringLiteral("1"), QStringLiteral("--uv")};
}

void TestCli::usageErrorsExitTwo() {
    QFETCH(QStringList, args);
    const Run r = knotwork(args);
    QCOMPARE(r.code, 2);
    QVERIFY(r.out.isEmpty());
    QVERIFY2(r.err.count(QLatin1Char('\n')) == 1, qPrintable(r.err));
    QVERIFY2(r.err.startsWith(QStringLiteral("knotwork")), qPrintable(r.err));
}

QTEST_GUILESS_MAIN(TestCli)
#include "tst_cli.moc"
