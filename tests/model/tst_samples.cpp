// Sample projects: each loads, is valid, and has the surfaces, degrees and shape it promises.
#include "model/io/knotfile.h"

#include <QDir>
#include <QTest>
#include <cmath>

using namespace kw;

namespace {

Expected<Scene> loadSample(const char* name) {
    auto scene = readKnotFile(QStringLiteral(KW_SAMPLES_DIR "/") + QLatin1String(name));
    if (!scene)
        qWarning("%s", qPrintable(scene.message()));
    return scene;
}

/// Calls f(point) on an n x n grid over the surface's domain.
template <typename F> void sampleSurface(const NurbsSurface& s, int n, F f) {
    const Interval du = surfaceDomainU(s), dv = surfaceDomainV(s);
    for (int a = 0; a <= n; ++a)
        for (int b = 0; b <= n; ++b)
            f(surfacePoint(s, du.first + (du.last - du.first) * a / n,
                           dv.first + (dv.last - dv.first) * b / n));
}

} // namespace

class TestSamples : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void everySampleIsValid();
    void bicubic();
    void sphereIsExact();
    void torusIsExact();
    void trimmedPlate();
    void teapot();
};

void TestSamples::everySampleIsValid() {
    const QStringList files =
        QDir(QStringLiteral(KW_SAMPLES_DIR)).entryList({QStringLiteral("*.knot")}, QDir::Files);
    QVERIFY(files.size() >= 5);
    for (const QString& f : files) {
        QString error;
        const auto scene = readKnotFile(QStringLiteral(KW_SAMPLES_DIR "/") + f);
        QVERIFY2(scene, qPrintable(scene.message()));
        QVERIFY(!scene->surfaces.empty());
        QVERIFY(!scene->camera.authored); // views fit a camera to the samples
        for (const Surface& s : scene->surfaces) {
            QVERIFY2(checkNurbsSurface(s.geometry).has_value(), qPrintable(f));
            QVERIFY2(!s.name.isEmpty(), qPrintable(f));
            for (const TrimLoop& loop : s.trims)
                for (const NurbsCurve2& c : loop.curves)
                    QVERIFY(checkNurbsCurve(c).has_value());
        }
    }
}

void TestSamples::bicubic() {
    const auto scene = loadSample("bicubic.knot");
    QVERIFY(scene);
    QCOMPARE(scene->surfaces.size(), size_t(1));
    const NurbsSurface& g = scene->surfaces[0].geometry;
    QCOMPARE(g.degreeU, 3);
    QCOMPARE(g.degreeV, 3);
    QVERIFY(g.countU >= 5 && g.countV >= 5);
    // Non-uniform with an interior knot of multiplicity 2.
    int maxInteriorMultiplicity = 0;
    for (int k = g.degreeU + 1; k < g.countU; ++k)
        maxInteriorMultiplicity =
            std::max<int>(maxInteriorMultiplicity,
                          int(std::count(g.knotsU.begin(), g.knotsU.end(), g.knotsU[size_t(k)])));
    QCOMPARE(maxInteriorMultiplicity, 2);
}

void TestSamples::sphereIsExact() {
    const auto scene = loadSample("sphere.knot");
    QVERIFY(scene);
    QCOMPARE(scene->surfaces.size(), size_t(1));
    const NurbsSurface& g = scene->surfaces[0].geometry;
    QCOMPARE(g.degreeU, 2);
    QCOMPARE(g.degreeV, 2);
    QCOMPARE(g.countU, 9);
    double worst = 0.0;
    sampleSurface(g, 40,
                  [&](glm::dvec3 p) { worst = std::max(worst, std::abs(glm::length(p) - 1.0)); });
    QVERIFY2(worst < 1e-12, qPrintable(QString::number(worst)));
}

void TestSamples::torusIsExact() {
    const auto scene = loadSample("torus.knot");
    QVERIFY(scene);
    const NurbsSurface& g = scene->surfaces[0].geometry;
    QCOMPARE(g.degreeU, 2);
    QCOMPARE(g.degreeV, 2);
    double worst = 0.0;
    sampleSurface(g, 40, [&](glm::dvec3 p) {
        const double ring = std::hypot(p.x, p.y) - 2.0; // distance from the core circle R = 2
        worst = std::max(worst, std::abs(std::hypot(ring, p.z) - 0.6));
    });
    QVERIFY2(worst < 1e-12, qPrintable(QString::number(worst)));
}

void TestSamples::trimmedPlate() {
    const auto scene = loadSample("trimmed_plate.knot");
    QVERIFY(scene);
    QCOMPARE(scene->surfaces.size(), size_t(1));
    const Surface& s = scene->surfaces[0];
    QCOMPARE(s.trims.size(), size_t(3));
    // Loops: outer rounded rectangle (8 curves), circle of 4 rational arcs, concave polyline.
    QCOMPARE(s.trims[0].curves.size(), size_t(8));
    QCOMPARE(s.trims[1].curves.size(), size_t(4));
    for (const NurbsCurve2& arc : s.trims[1].curves) {
        QCOMPARE(arc.degree, 2);
        const glm::dvec2 centre(0.3, 0.62);
        for (double t : {0.0, 0.3, 0.5, 0.9})
            QVERIFY(std::abs(glm::length(curvePoint(arc, t) - centre) - 0.14) < 1e-12);
    }
    QCOMPARE(s.trims[2].curves.size(), size_t(1));
    // Every loop lies inside the surface's domain.
    const Interval du = surfaceDomainU(s.geometry), dv = surfaceDomainV(s.geometry);
    for (const TrimLoop& loop : s.trims)
        for (const NurbsCurve2& c : loop.curves)
            for (const glm::dvec2& p : c.points)
                QVERIFY(p.x > du.first && p.x < du.last && p.y > dv.first && p.y < dv.last);
}

void TestSamples::teapot() {
    const auto scene = loadSample("teapot.knot");
    QVERIFY(scene);
    QCOMPARE(scene->surfaces.size(), size_t(32));
    QStringList names;
    for (const Surface& s : scene->surfaces) {
        QCOMPARE(s.geometry.degreeU, 3);
        QCOMPARE(s.geometry.degreeV, 3);
        QCOMPARE(s.geometry.countU, 4);
        QCOMPARE(s.geometry.countV, 4);
        names << s.name;
    }
    names.removeDuplicates();
    QCOMPARE(names.size(), 32);
    glm::dvec3 lo, hi;
    QVERIFY(sceneBounds(*scene, lo, hi));
    // Newell's teapot: spout tip at x 3.525, handle at x -3, lid knob at z 3.15, base at z 0.
    QCOMPARE(hi.x, 3.525);
    QCOMPARE(lo.x, -3.0);
    QCOMPARE(hi.z, 3.15);
    QCOMPARE(lo.z, 0.0);
}

QTEST_GUILESS_MAIN(TestSamples)
#include "tst_samples.moc"
