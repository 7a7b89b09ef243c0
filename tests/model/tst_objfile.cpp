// OBJ free-form reader/writer and mesh export (model/io/objfile.h): round trips, foreign files,
// errors.
#include "model/analysis/mass_properties.h"
#include "model/document/document.h"
#include "model/io/knotfile.h"
#include "model/io/objfile.h"
#include "model/nurbs/trim.h"
#include "model_fixtures.h"
#include "tests/support/expected_test_util.h"

#include <QDir>
#include <QRandomGenerator>
#include <QtTest>
#include <cmath>

using namespace kw;
using namespace kw::test;

namespace {

Scene sample(const char* name) {
    auto s = readKnotFile(QStringLiteral(KW_SAMPLES_DIR "/") + name);
    if (!s)
        qFatal("%s", qPrintable(s.message()));
    return *s;
}

bool parse(const QByteArray& text, Scene& scene, ImportReport& report, QString& error) {
    const Status parsed = parseObj(text, QStringLiteral("t.obj"), scene, report);
    error = parsed.message();
    return bool(parsed);
}

} // namespace

class TestObjFile : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void roundTripSamples_data();
    void roundTripSamples();
    void roundTripEveryField();
    void foreignFreeForm();
    void bezierSurface();
    void unsupportedAndPolygonsAreReported();
    void errors_data();
    void errors();
    void truncatedFile();
    void meshExport();
    void randomDamageNeverCrashes();
};

void TestObjFile::roundTripSamples_data() {
    QTest::addColumn<QString>("file");
    const QStringList files = QDir(QStringLiteral(KW_SAMPLES_DIR)).entryList({"*.knot"});
    QVERIFY(files.size() >= 5);
    for (const QString& f : files)
        QTest::newRow(qPrintable(f)) << f;
}

void TestObjFile::roundTripSamples() {
    QFETCH(QString, file);
    const Scene original = sample(file.toUtf8().constData());
    const QByteArray obj = writeObj(original);
    Scene back;
    ImportReport report;
    QString error;
    QVERIFY2(parse(obj, back, report, error), qPrintable(error));
    QVERIFY(back == original); // every field, bit for bit
    QVERIFY(report.skipped.isEmpty() && report.warnings.isEmpty());
    // Knotwork's own comments are optional: without them the geometry and trims still read.
    QByteArray plain;
    for (const QByteArray& line : obj.split('\n'))
        if (!line.startsWith("# knotwork"))
            plain += line + '\n';
    Scene foreign;
    QVERIFY2(parse(plain, foreign, report, error), qPrintable(error));
    QCOMPARE(foreign.surfaces.size(), original.surfaces.size());
    for (size_t k = 0; k < original.surfaces.size(); ++k) {
        QCOMPARE(foreign.surfaces[k].geometry, original.surfaces[k].geometry);
        QCOMPARE(foreign.surfaces[k].trims.size(), original.surfaces[k].trims.size());
        for (size_t l = 0; l < original.surfaces[k].trims.size(); ++l)
            QCOMPARE(foreign.surfaces[k].trims[l].curves, original.surfaces[k].trims[l].curves);
    }
    KW_VERIFY_OK(Document::validate(foreign));
}

void TestObjFile::roundTripEveryField() {
    Scene s = threeSurfaceScene();
    s.surfaces[0].name = QStringLiteral("  odd name: é, 100%\nsecond line ");
    s.surfaces[1].name = QString();
    s.surfaces[1].partitionsU = 37;
    s.surfaces[1].material.color = {0.1, 0.2, 0.3};
    s.surfaces[1].material.shininess = 7.25;
    s.surfaces[2].geometry.weights[5] = 0.3; // rational
    s.surfaces[0].trims[1].curves[2].weights[1] = 1.0 / 3.0;
    s.camera = {{1e-300, -5, 3}, {0.1, 0.2, 0.3}, {0, 0, 1}, 42.5, true};
    s.display = {QStringLiteral("uniform"), 0.3, QStringLiteral("light"), {}, true,
                 {1.0, 0.0, -0.5},          2.5};
    s.surfaces[0].solid = s.surfaces[2].solid = 6; // a face of a closed solid (.knot 1.2)
    s.surfaces[2].outsideAlongNormal = false;
    Light point;
    point.kind = Light::Kind::Point;
    point.vector = {1, 2, 3};
    s.lights.push_back(point);
    s.nextId = 99;
    KW_VERIFY_OK(Document::validate(s));
    Scene back;
    ImportReport report;
    QString error;
    QVERIFY2(parse(writeObj(s), back, report, error), qPrintable(error));
    QVERIFY(back == s);
}

void TestObjFile::foreignFreeForm() {
    // A rational biquadratic B-spline patch with an outer trim made of two pieces of one
    // curv2 (a sub-range each), and a hole given backwards (u1 > u0), continuation lines,
    // relative indices, normals/texture data and a group name.
    const QByteArray text =
        "# made by hand\n"
        "g my patch\n"
        "vp 0.1 0.1\nvp 0.9 0.1\nvp 0.9 0.9\nvp 0.1 0.9\nvp 0.1 0.1\n"
        "cstype bspline\ndeg 1\n"
        "curv2 -5 -4 -3 -2 -1\nparm u 0 0 1 2 3 4 4\nend\n"
        "vp 0.4 0.4 1\nvp 0.7 0.4 0.5\nvp 0.7 0.7 1\nvp 0.4 0.7 0.5\nvp 0.4 0.4 1\n"
        "cstype rat bspline\ndeg 2\n"
        "curv2 6 7 8 9 -1\nparm u 0 0 0 1 2 3 3 3\nend\n"
        "v 0 0 0\nv 1 0 0 2\nv 2 0 0\nv 0 1 0\nv 1 1 1 0.5\nv 2 1 0\nv 0 2 0\nv 1 2 0\n"
        "v 2 2 0\nvn 0 0 1\nvt 0 0\n"
        "cstype rat bspline\ndeg 2 2\n"
        "surf 0 1 0 1 1/1/1 2 3 4 5 6 \\\n 7 8 9\n"
        "parm u 0 0 0 1 1 1\nparm v 0 0 0 1 1 1\n"
        "trim 0 2 1 2 4 1\n"
        "hole 3 0 2\n"
        "end\n";
    Scene s;
    ImportReport report;
    QString error;
    QVERIFY2(parse(text, s, report, error), qPrintable(error));
    QCOMPARE(s.surfaces.size(), size_t(1));
    const Surface& surf = s.surfaces[0];
    QCOMPARE(surf.name, QStringLiteral("my patch"));
    QCOMPARE(surf.geometry.weights[1], 2.0);
    QCOMPARE(surf.geometry.weights[4], 0.5);
    QCOMPARE(surf.geometry.points[4], glm::dvec3(1, 1, 1));
    QCOMPARE(surf.trims.size(), size_t(2));
    QCOMPARE(surf.trims[0].curves.size(), size_t(2));
    // The sub-ranges [0, 2] and [2, 4] of the polyline: (0.1,0.1)-(0.9,0.1)-(0.9,0.9), etc.
    const NurbsCurve2& first = surf.trims[0].curves[0];
    QCOMPARE(curvePoint(first, curveDomain(first).first), glm::dvec2(0.1, 0.1));
    QCOMPARE(curvePoint(first, curveDomain(first).last), glm::dvec2(0.9, 0.9));
    QVERIFY(glm::length(curvePoint(first, 1.0) - glm::dvec2(0.9, 0.1)) < 1e-15);
    // The hole runs backwards: it starts where the curve ends.
    const NurbsCurve2& hole = surf.trims[1].curves[0];
    NurbsCurve2 source;
    source.degree = 2;
    source.knots = {0, 0, 0, 1, 2, 3, 3, 3};
    source.points = {{0.4, 0.4}, {0.7, 0.4}, {0.7, 0.7}, {0.4, 0.7}, {0.4, 0.4}};
    source.weights = {1, 0.5, 1, 0.5, 1};
    QCOMPARE(curveDomain(hole), (Interval{-3.0, 0.0})); // trimCurveReversed negates
    for (double t : {0.0, 0.25, 0.5, 1.8, 3.0})
        QVERIFY(glm::length(curvePoint(hole, -t) - curvePoint(source, t)) < 1e-15);
    QVERIFY(surf.id.isValid() && surf.trims[0].id.isValid() && surf.trims[1].id.isValid());
    KW_VERIFY_OK(Document::validate(s));
    // Trim semantics: the hole removes its inside.
    const TrimRegion r = makeTrimRegion(surf.trims, 1e-6);
    QVERIFY(trimRegionContains(r, {0.2, 0.2}));
    QVERIFY(!trimRegionContains(r, {0.55, 0.55}));
    QVERIFY(!trimRegionContains(r, {0.05, 0.5}));
}

void TestObjFile::bezierSurface() {
    // Two bicubic Bezier pieces along u (7 x 4 points), parm u 0 1 2: knots 0000 111 2222.
    QByteArray text = "cstype bezier\ndeg 3 3\n";
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 7; ++i)
            text += QStringLiteral("v %1 %2 %3\n").arg(i).arg(j).arg((i * j) % 3).toUtf8();
    text += "surf 0 2 0 1";
    for (int k = 1; k <= 28; ++k)
        text += ' ' + QByteArray::number(k);
    text += "\nparm u 0 1 2\nparm v 0 1\nend\n";
    Scene s;
    ImportReport report;
    QString error;
    QVERIFY2(parse(text, s, report, error), qPrintable(error));
    const NurbsSurface& g = s.surfaces.at(0).geometry;
    QCOMPARE(g.knotsU, (std::vector<double>{0, 0, 0, 0, 1, 1, 1, 2, 2, 2, 2}));
    QCOMPARE(g.knotsV, (std::vector<double>{0, 0, 0, 0, 1, 1, 1, 1}));
    QCOMPARE(g.countU, 7);
    // The pieces meet at the shared control point, as Bezier pieces do.
    QCOMPARE(surfacePoint(g, 1.0, 0.0), glm::dvec3(3, 0, 0));
    QCOMPARE(s.surfaces[0].name, QStringLiteral("Surface 1"));

    // The same patch with surf 0.5 1.5 0.25 1: cut exactly to that range, same parameters.
    QByteArray cut = text;
    cut.replace("surf 0 2 0 1", "surf 0.5 1.5 0.25 1");
    Scene part;
    QVERIFY2(parse(cut, part, report, error), qPrintable(error));
    const NurbsSurface& h = part.surfaces.at(0).geometry;
    QCOMPARE(surfaceDomainU(h).first, 0.5);
    QCOMPARE(surfaceDomainU(h).last, 1.5);
    QCOMPARE(surfaceDomainV(h).first, 0.25);
    QCOMPARE(surfaceDomainV(h).last, 1.0);
    QVERIFY(checkNurbsSurface(h).has_value());
    for (double u = 0.5; u <= 1.5; u += 0.125)
        for (double v = 0.25; v <= 1.0; v += 0.125)
            QVERIFY(glm::length(surfacePoint(h, u, v) - surfacePoint(g, u, v)) < 1e-13);
    cut.replace("surf 0.5 1.5 0.25 1", "surf 0 3 0 1");
    QVERIFY(!parse(cut, part, report, error));
    QVERIFY2(error.contains(QLatin1String("outside the knot domain")), qPrintable(error));
}

void TestObjFile::unsupportedAndPolygonsAreReported() {
    const QByteArray text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n"
                            "cstype cardinal\ndeg 3 3\nsurf 0 1 0 1 1 2 3 4\nend\n"
                            "cstype bspline\ndeg 1 1\nsurf 0 1 0 1 1 2 3 4\n"
                            "parm u 0 0 1 1\nparm v 0 0 1 1\nend\n";
    Scene s;
    ImportReport report;
    QString error;
    QVERIFY2(parse(text, s, report, error), qPrintable(error));
    QCOMPARE(s.surfaces.size(), size_t(1));
    QCOMPARE(report.facesImported, 1);
    QCOMPARE(report.skipped.size(), 1);
    QVERIFY2(report.skipped[0].contains(QLatin1String("cardinal")), qPrintable(report.skipped[0]));
    QVERIFY2(report.skipped[0].startsWith(QLatin1String("t.obj:9:")),
             qPrintable(report.skipped[0]));
    QCOMPARE(report.warnings.size(), 1);
    QVERIFY(report.warnings[0].contains(QLatin1String("2 polygon")));
}

void TestObjFile::errors_data() {
    QTest::addColumn<QByteArray>("text");
    QTest::addColumn<QString>("expected"); // start of the error message
    const QByteArray quad = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\ncstype bspline\ndeg 1 1\n";
    QTest::newRow("bad number") << QByteArray("v 0 x 0\n") << "t.obj:1: 'x' is not";
    QTest::newRow("nan") << QByteArray("v 0 nan 0\n") << "t.obj:1: 'nan' is not";
    QTest::newRow("short v") << QByteArray("\nv 0 0\n") << "t.obj:2: 'v' needs";
    QTest::newRow("index") << quad + "surf 0 1 0 1 1 2 3 9\n"
                           << "t.obj:7: vertex index 9";
    QTest::newRow("no end") << quad + "surf 0 1 0 1 1 2 3 4\nparm u 0 0 1 1\n"
                            << "t.obj:7: element is not closed";
    QTest::newRow("knot count") << quad + "surf 0 1 0 1 1 2 3 4\nparm u 0 0 1 1\nparm v 0 1\nend\n"
                                << "t.obj:7: surf has 4 control points";
    QTest::newRow("decreasing") << quad +
                                       "surf 0 1 0 1 1 2 3 4\nparm u 0 0 1 1\nparm v 1 1 0 0\nend\n"
                                << "t.obj:7: invalid surface";
    QTest::newRow("zero weight") << QByteArray("v 0 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                                               "cstype rat bspline\ndeg 1 1\n"
                                               "surf 0 1 0 1 1 2 3 4\nparm u 0 0 1 1\n"
                                               "parm v 0 0 1 1\nend\n")
                                 << "t.obj:7: invalid surface";
    QTest::newRow("trim curve") << quad + "surf 0 1 0 1 1 2 3 4\ntrim 0 1 1\n"
                                << "t.obj:8: curv2 index 1";
    QTest::newRow("unknown") << QByteArray("v 0 0 0\nfoo 1\n")
                             << "t.obj:2: unknown statement 'foo'";
    QTest::newRow("stray end") << QByteArray("end\n") << "t.obj:1: 'end' without";
    QTest::newRow("no surfaces") << QByteArray("v 0 0 0\n") << "t.obj: no free-form surfaces";
    QTest::newRow("bad cstype") << QByteArray("cstype nurbs\n") << "t.obj:1: unknown cstype";
    QTest::newRow("solid side") << QByteArray("# knotwork solid 2 inward\n")
                                << "t.obj:1: knotwork solid: expected normal or reversed";
    QTest::newRow("solid number") << QByteArray("# knotwork solid -1 normal\n")
                                  << "t.obj:1: knotwork solid: -1 is not an integer";
}

void TestObjFile::errors() {
    QFETCH(QByteArray, text);
    QFETCH(QString, expected);
    Scene s = threeSurfaceScene();
    const Scene before = s;
    ImportReport report;
    QString error;
    QVERIFY(!parse(text, s, report, error));
    QVERIFY2(error.startsWith(expected), qPrintable(error));
    QVERIFY(s == before); // untouched: no half-built scene
}

void TestObjFile::truncatedFile() {
    const QByteArray obj = writeObj(sample("teapot.knot"));
    for (double cut : {0.25, 0.5, 0.9, 0.999}) {
        Scene s;
        ImportReport report;
        QString error;
        QVERIFY2(!parse(obj.left(qsizetype(obj.size() * cut)), s, report, error),
                 qPrintable(QString::number(cut)));
        QVERIFY2(error.startsWith(QLatin1String("t.obj:")), qPrintable(error));
        QVERIFY(s.surfaces.empty());
    }
}

void TestObjFile::meshExport() {
    const Scene scene = sample("trimmed_plate.knot");
    const Surface& plate = scene.surfaces.front();
    const QByteArray mesh = writeObjMesh(scene, {2});
    std::vector<glm::dvec3> v, n;
    std::vector<std::array<int, 3>> f;
    for (const QByteArray& line : mesh.split('\n')) {
        const QList<QByteArray> t = line.split(' ');
        if (t[0] == "v")
            v.emplace_back(t[1].toDouble(), t[2].toDouble(), t[3].toDouble());
        else if (t[0] == "vn")
            n.emplace_back(t[1].toDouble(), t[2].toDouble(), t[3].toDouble());
        else if (t[0] == "f")
            f.push_back({t[1].split('/')[0].toInt(), t[2].split('/')[0].toInt(),
                         t[3].split('/')[0].toInt()});
    }
    const int nu = plate.partitionsU * 2, nv = plate.partitionsV * 2;
    QCOMPARE(v.size(), size_t((nu + 1) * (nv + 1)));
    QCOMPARE(n.size(), v.size());
    QVERIFY(f.size() < size_t(2 * nu * nv)); // the trims removed triangles
    QVERIFY(f.size() > size_t(nu * nv / 2));
    // Vertices lie on the surface at the grid's (u, v); normals are unit.
    const Interval du = surfaceDomainU(plate.geometry), dv = surfaceDomainV(plate.geometry);
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) {
            const glm::dvec3 p =
                surfacePoint(plate.geometry, du.first + (du.last - du.first) * i / nu,
                             dv.first + (dv.last - dv.first) * j / nv);
            QVERIFY(glm::length(v[j * (nu + 1) + i] - p) < 1e-12);
            QVERIFY(std::abs(glm::length(n[j * (nu + 1) + i]) - 1.0) < 1e-12);
        }
    // The mesh's area approaches the trimmed area (centroid classification, coarse grid).
    double area = 0.0;
    for (const auto& t : f)
        area += 0.5 * glm::length(glm::cross(v[t[1] - 1] - v[t[0] - 1], v[t[2] - 1] - v[t[0] - 1]));
    const double exact = trimmedSurfaceArea(plate.geometry, plate.trims);
    QVERIFY2(std::abs(area - exact) / exact < 0.05,
             qPrintable(QStringLiteral("%1 vs %2").arg(area).arg(exact)));
}

void TestObjFile::randomDamageNeverCrashes() {
    // 400 damaged copies of a file with trims: each either reads into a valid scene or gives a
    // one-line error naming the file and a line; none crashes, none leaves a partial scene.
    const QByteArray good =
        writeObj(sample("trimmed_plate.knot")) + writeObj(sample("bicubic.knot"));
    QRandomGenerator rng(7);
    const char alphabet[] = "0123456789-+.eE \n/#abcdefghijklmnopqrstuvwxyz";
    int refused = 0;
    for (int n = 0; n < 400; ++n) {
        QByteArray bad = good;
        const int edits = 1 + int(rng.bounded(4));
        for (int e = 0; e < edits; ++e) {
            const qsizetype at = rng.bounded(bad.size());
            switch (rng.bounded(3)) {
            case 0:
                bad[at] = alphabet[rng.bounded(int(sizeof alphabet) - 1)];
                break;
            case 1:
                bad.remove(at, rng.bounded(40));
                break;
            default:
                bad.insert(at, bad.mid(rng.bounded(bad.size()), rng.bounded(60)));
            }
        }
        Scene s;
        ImportReport report;
        QString error;
        if (parse(bad, s, report, error)) {
            KW_VERIFY_OK(Document::validate(s));
        } else {
            ++refused;
            QVERIFY2(error.startsWith(QLatin1String("t.obj")), qPrintable(error));
            QVERIFY(!error.contains(QLatin1Char('\n')));
            QVERIFY(s.surfaces.empty());
        }
    }
    QVERIFY(refused > 200); // most damage is caught, not silently read
}

QTEST_GUILESS_MAIN(TestObjFile)
#include "tst_objfile.moc"
