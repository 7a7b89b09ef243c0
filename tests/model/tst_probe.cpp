// The probe's refinement onto a pixel's ray and the values it shows: exact curvature on spheres
// of several radii, the point on the ray, distances and angles between probed points, and the
// cost of one probe.
#include "model/analysis/probe.h"
#include "model/nurbs/nurbs_shapes.h"

#include <QElapsedTimer>
#include <QRandomGenerator>
#include <QTest>
#include <algorithm>
#include <cmath>
#include <numbers>

using namespace kw;

class TestProbe : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void sphereCurvature_data();
    void sphereCurvature();
    void cylinderAndPlane();
    void distanceAndAngle();
    void silhouetteDoesNotDiverge();
    void cost();
};

namespace {

Surface sphere(const glm::dvec3& c, double r) {
    Surface s;
    s.id = SurfaceId{7};
    s.name = QStringLiteral("ball");
    s.geometry = makeSphere(c, r);
    return s;
}

/// The first hit of the ray o + t d (d unit) with the sphere (c, r), or false.
bool raySphere(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& c, double r,
               glm::dvec3& hit) {
    const glm::dvec3 oc = o - c;
    const double b = glm::dot(oc, d), q = glm::dot(oc, oc) - r * r, disc = b * b - q;
    if (disc < 0.0)
        return false;
    hit = o + (-b - std::sqrt(disc)) * d;
    return true;
}

/// (u, v) of a point of makeSphere's surface near `p`, by a coarse search then a small error as
/// a float pick has.
glm::dvec2 roughUv(const Surface& s, const glm::dvec3& p) {
    glm::dvec2 best(0.5);
    double bestD = 1e300;
    for (int j = 1; j < 64; ++j)
        for (int i = 0; i <= 128; ++i) {
            const glm::dvec2 uv(i / 128.0, j / 64.0);
            const double d = glm::distance(surfacePoint(s.geometry, uv.x, uv.y), p);
            if (d < bestD)
                bestD = d, best = uv;
        }
    return best;
}

} // namespace

void TestProbe::sphereCurvature_data() {
    QTest::addColumn<double>("radius");
    QTest::newRow("r 0.01") << 0.01;
    QTest::newRow("r 1") << 1.0;
    QTest::newRow("r 37.5") << 37.5;
    QTest::newRow("r 2500") << 2500.0;
}

// K = 1/r^2 and k1 = k2 = 1/r within 1e-9 relative at points all over a sphere, each refined
// from a rough (u, v) onto the ray, which it lies on to rounding.
void TestProbe::sphereCurvature() {
    QFETCH(double, radius);
    const glm::dvec3 c(3.0 * radius, -radius, 0.5 * radius);
    const Surface s = sphere(c, radius);
    QRandomGenerator rng(42);
    int probed = 0;
    for (int k = 0; k < 40; ++k) {
        // Eyes all around, rays through random points of the sphere's disc.
        glm::dvec3 eye(rng.generateDouble() - 0.5, rng.generateDouble() - 0.5,
                       rng.generateDouble() - 0.5);
        eye = c + 6.0 * radius * glm::normalize(eye);
        const glm::dvec3 aim =
            c + 0.9 * radius *
                    glm::dvec3(rng.generateDouble() - 0.5, rng.generateDouble() - 0.5,
                               rng.generateDouble() - 0.5);
        const glm::dvec3 d = glm::normalize(aim - eye);
        glm::dvec3 exact;
        if (!raySphere(eye, d, c, radius, exact))
            continue;
        const std::optional<ProbePoint> p = probeOnRay(s, roughUv(s, exact), eye, d);
        QVERIFY(p.has_value());
        ++probed;
        const QString where =
            QStringLiteral("ray %1, uv (%2, %3)").arg(k).arg(p->uv.x).arg(p->uv.y);
        QVERIFY2(glm::distance(p->point, exact) <= 1e-11 * radius, qPrintable(where));
        QVERIFY2(p->rayDistance <= 1e-12 * radius, qPrintable(where));
        QVERIFY2(std::abs(p->gaussian * radius * radius - 1.0) <= 1e-9,
                 qPrintable(where + QStringLiteral(" K %1").arg(p->gaussian, 0, 'g', 17)));
        QVERIFY2(std::abs(p->k1 * radius - 1.0) <= 1e-9 && std::abs(p->k2 * radius - 1.0) <= 1e-9,
                 qPrintable(where + QStringLiteral(" k1 %1 k2 %2").arg(p->k1).arg(p->k2)));
        QVERIFY2(std::abs(p->mean * radius - 1.0) <= 1e-9, qPrintable(where));
        QVERIFY(glm::distance(p->normal, (exact - c) / radius) <= 1e-9);
        QVERIFY(std::abs(curvatureRadius(p->k1) / radius - 1.0) <= 1e-9);
    }
    QVERIFY(probed >= 20);
}

void TestProbe::cylinderAndPlane() {
    Surface cyl;
    cyl.id = SurfaceId{2};
    cyl.geometry = makeCylinder(glm::dvec3(0.0), 4.0, 10.0);
    // A ray along -x at height 5 hits the cylinder at (4, 0, 5).
    const auto p = probeOnRay(cyl, {0.02, 0.45}, glm::dvec3(20, 0, 5), glm::dvec3(-1, 0, 0));
    QVERIFY(p);
    QVERIFY(glm::distance(p->point, glm::dvec3(4, 0, 5)) < 1e-12);
    QVERIFY(std::abs(p->gaussian) < 1e-12);
    const Measurement r{Measurement::Kind::Radius, *p, {}};
    QVERIFY2(std::abs(measurementValue(r) - 4.0) < 1e-12, qPrintable(measurementText(r)));
    QVERIFY(measurementText(r).startsWith(QStringLiteral("radius 4 (principal radii 4, ∞)")));
    Surface plane;
    plane.geometry = makePlane(glm::dvec3(0.0), glm::dvec3(2, 0, 0), glm::dvec3(0, 2, 0));
    const auto q = probeOnRay(plane, {0.1, 0.9}, glm::dvec3(0.5, 0.25, 3), glm::dvec3(0, 0, -1));
    QVERIFY(q);
    QVERIFY(glm::distance(q->point, glm::dvec3(0.5, 0.25, 0)) < 1e-14);
    QVERIFY(std::isinf(measurementValue({Measurement::Kind::Radius, *q, {}})));
    QVERIFY(probeText(*q).contains(QStringLiteral("radii: ∞, ∞")));
}

// The distance between two probed points equals the distance between the exact ray hits within
// 1e-9 of the model's size; the angle between normals of a sphere is the angle at its centre.
void TestProbe::distanceAndAngle() {
    const double r = 12.0;
    const glm::dvec3 c(100, 200, -50);
    const Surface s = sphere(c, r);
    const glm::dvec3 eye = c + glm::dvec3(0, -100, 0);
    const glm::dvec3 aimA = c + glm::dvec3(5, 0, 3), aimB = c + glm::dvec3(-7, 0, -2);
    glm::dvec3 hitA, hitB;
    QVERIFY(raySphere(eye, glm::normalize(aimA - eye), c, r, hitA));
    QVERIFY(raySphere(eye, glm::normalize(aimB - eye), c, r, hitB));
    const auto a = probeOnRay(s, roughUv(s, hitA), eye, glm::normalize(aimA - eye));
    const auto b = probeOnRay(s, roughUv(s, hitB), eye, glm::normalize(aimB - eye));
    QVERIFY(a && b);
    const Measurement dist{Measurement::Kind::Distance, *a, *b};
    const double size = 2 * r * std::sqrt(3.0);
    QVERIFY2(std::abs(measurementValue(dist) - glm::distance(hitA, hitB)) <= 1e-9 * size,
             qPrintable(measurementText(dist)));
    const glm::dvec3 delta = hitB - hitA;
    QVERIFY(measurementText(dist).startsWith(QStringLiteral("distance %1 (dx %2,")
                                                 .arg(glm::length(delta), 0, 'g', 8)
                                                 .arg(delta.x, 0, 'g', 8)));
    const Measurement angle{Measurement::Kind::Angle, *a, *b};
    const double expected =
        glm::degrees(std::acos(glm::dot(glm::normalize(hitA - c), glm::normalize(hitB - c))));
    QVERIFY2(std::abs(measurementValue(angle) - expected) < 1e-9,
             qPrintable(measurementText(angle)));
    QVERIFY(measurementText(angle).endsWith(QStringLiteral("° between normals")));

    // With the document's unit, every length carries it; angles do not.
    const QString inInches = measurementText(dist, 8, QStringLiteral("in"));
    QVERIFY2(inInches.startsWith(QStringLiteral("distance %1 in (dx %2 in,")
                                     .arg(glm::length(delta), 0, 'g', 8)
                                     .arg(delta.x, 0, 'g', 8)),
             qPrintable(inInches));
    QVERIFY2(inInches.endsWith(QStringLiteral(" in)")), qPrintable(inInches));
    QVERIFY(!measurementText(angle, 8, QStringLiteral("in")).contains(QStringLiteral(" in")));
    const QString probe = probeText(*a, QStringLiteral("mm"));
    const QStringList lines = probe.split(QLatin1Char('\n'));
    QVERIFY2(lines.filter(QStringLiteral("x, y, z: ")).value(0).endsWith(QStringLiteral(" mm")),
             qPrintable(probe));
    QVERIFY2(lines.filter(QStringLiteral("K: ")).value(0).endsWith(QStringLiteral(" 1/mm²")),
             qPrintable(probe));
    QVERIFY2(lines.filter(QStringLiteral("radii: ")).value(0).endsWith(QStringLiteral(" mm")),
             qPrintable(probe));
    QVERIFY(!probeText(*a).contains(QStringLiteral("mm")));
}

// A ray that misses the surface (past its silhouette) ends at the nearest point it found, not
// at NaN or far away, and says how far the ray passes.
void TestProbe::silhouetteDoesNotDiverge() {
    const Surface s = sphere(glm::dvec3(0.0), 1.0);
    const auto p = probeOnRay(s, {0.3, 0.5}, glm::dvec3(-5, 1.2, 0), glm::dvec3(1, 0, 0));
    QVERIFY(p);
    QVERIFY(std::isfinite(p->point.x) && std::isfinite(p->k1));
    QVERIFY(std::abs(glm::length(p->point) - 1.0) < 1e-12);
    QVERIFY2(p->rayDistance >= 0.2 - 1e-9 && p->rayDistance < 0.25,
             qPrintable(QString::number(p->rayDistance)));
}

// A probe update's CPU part (refinement, curvature, text) over rays sweeping the sphere: each
// hits the sphere and gives a text. The time per probe is reported, not asserted: speed is
// measured by the bench, on a machine whose load a test cannot know.
void TestProbe::cost() {
    const Surface s = sphere(glm::dvec3(0.0), 1.0);
    const glm::dvec3 eye(0, -5, 0.3);
    QElapsedTimer t;
    t.start();
    constexpr int kRuns = 2000;
    int hits = 0, texts = 0;
    double worst = 0.0; // the largest distance of a hit from the sphere
    for (int k = 0; k < kRuns; ++k) {
        const double x = -0.5 + k / double(kRuns);
        const auto p = probeOnRay(s, {0.74, 0.55}, eye, glm::normalize(glm::dvec3(x, 5, 0)));
        if (!p)
            continue;
        ++hits;
        worst = std::max(worst, std::abs(glm::length(p->point) - 1.0));
        texts += !probeText(*p).isEmpty();
    }
    qInfo("one probe: %.4f ms", t.nsecsElapsed() * 1e-6 / kRuns);
    QCOMPARE(hits, kRuns);
    QCOMPARE(texts, kRuns);
    QVERIFY2(worst < 1e-9, qPrintable(QString::number(worst)));
}

QTEST_GUILESS_MAIN(TestProbe)
#include "tst_probe.moc"
