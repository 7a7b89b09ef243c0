// Face and model properties on exact shapes: areas and volumes against closed forms, trimmed
// faces by even-odd, surface types, bounding boxes of the trimmed geometry.
#include "model/analysis/mass_properties.h"
#include "model/document/topology.h"
#include "model/nurbs/nurbs_shapes.h"

#include <QTest>
#include <cmath>
#include <numbers>

using namespace kw;

namespace {

constexpr double kPi = std::numbers::pi;

Surface face(const NurbsSurface& g, std::uint32_t id = 1) {
    Surface s;
    s.id = SurfaceId{id};
    s.name = QStringLiteral("face %1").arg(id);
    s.geometry = g;
    return s;
}

TrimLoop loopOf(std::vector<NurbsCurve2> curves, std::uint32_t id) {
    TrimLoop l;
    l.id = TrimLoopId{id};
    l.curves = std::move(curves);
    return l;
}

NurbsCurve2 line(glm::dvec2 a, glm::dvec2 b) {
    NurbsCurve2 c;
    c.degree = 1;
    c.knots = {0, 0, 1, 1};
    c.points = {a, b};
    c.weights = {1, 1};
    return c;
}

/// A square loop [a, b]^2 of four lines, counter-clockwise (or not).
TrimLoop square(double a, double b, std::uint32_t id, bool ccw = true) {
    std::vector<glm::dvec2> p = {{a, a}, {b, a}, {b, b}, {a, b}};
    if (!ccw)
        std::reverse(p.begin(), p.end());
    std::vector<NurbsCurve2> c;
    for (size_t k = 0; k < 4; ++k)
        c.push_back(line(p[k], p[(k + 1) % 4]));
    return loopOf(std::move(c), id);
}

bool relNear(double a, double b, double tol) {
    return std::abs(a - b) <= tol * std::abs(b);
}

} // namespace

class TestMassProperties : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void sphereArea();
    void torusAreaAndType();
    void trimmedPlate();
    void holeByEitherOrientation();
    void cylinderWithHole();
    void closedBoxVolume();
    void sphereVolumeNeedsClosedShell();
    void fluxMovesWithVectorArea();
    void types();
    void boundsOfTrimmedFace();
};

// The unit sphere is 4 pi within 1e-7 relative; a sphere of radius 3 moved off the origin, 36 pi.
void TestMassProperties::sphereArea() {
    const double a = faceIntegrals(face(makeSphere(glm::dvec3(0.0), 1.0))).area;
    QVERIFY2(relNear(a, 4 * kPi, 1e-7), qPrintable(QString::number(a, 'g', 17)));
    const double b = faceIntegrals(face(makeSphere(glm::dvec3(5, -2, 7), 3.0))).area;
    QVERIFY2(relNear(b, 36 * kPi, 1e-10), qPrintable(QString::number(b, 'g', 17)));
    // The flux from the centre is the volume (Su x Sv points outwards on makeSphere).
    const double v =
        faceIntegrals(face(makeSphere(glm::dvec3(5, -2, 7), 3.0)), glm::dvec3(5, -2, 7)).volume;
    QVERIFY2(relNear(std::abs(v), 36 * kPi, 1e-10), qPrintable(QString::number(v, 'g', 17)));
}

void TestMassProperties::torusAreaAndType() {
    const Surface t = face(makeTorus(glm::dvec3(1, 2, 3), 2.0, 0.6));
    const double a = faceIntegrals(t).area;
    QVERIFY2(relNear(a, 4 * kPi * kPi * 2.0 * 0.6, 1e-10), qPrintable(QString::number(a, 'g', 17)));
    QCOMPARE(surfaceType(t), SurfaceType::Torus);
}

// A plane [0, 4] x [0, 2] (uv [0,1]^2) trimmed to an inner square [0.25, 0.75]^2 keeps a quarter.
void TestMassProperties::trimmedPlate() {
    Surface p = face(makePlane(glm::dvec3(0.0), glm::dvec3(4, 0, 0), glm::dvec3(0, 2, 0)));
    QVERIFY(relNear(faceIntegrals(p).area, 8.0, 1e-12));
    p.trims.push_back(square(0.25, 0.75, 1));
    QVERIFY2(relNear(faceIntegrals(p).area, 2.0, 1e-12),
             qPrintable(QString::number(faceIntegrals(p).area, 'g', 17)));
    glm::dvec3 lo, hi;
    QVERIFY(faceBounds(p, lo, hi));
    QVERIFY(glm::length(lo - glm::dvec3(1.0, 0.5, 0.0)) < 1e-12);
    QVERIFY(glm::length(hi - glm::dvec3(3.0, 1.5, 0.0)) < 1e-12);
    QCOMPARE(surfaceType(p), SurfaceType::Plane);
}

// An outer loop and a circular hole: parity, not orientation, makes the hole.
void TestMassProperties::holeByEitherOrientation() {
    for (bool ccw : {true, false})
        for (bool holeCw : {true, false}) {
            Surface p = face(makePlane(glm::dvec3(0.0), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0)));
            p.trims.push_back(square(0.0, 1.0, 1, ccw));
            p.trims.push_back(loopOf({makeCircle2({0.5, 0.5}, 0.25, holeCw)}, 2));
            const double a = faceIntegrals(p).area;
            QVERIFY2(relNear(a, 1.0 - kPi / 16.0, 1e-11), qPrintable(QString::number(a, 'g', 17)));
        }
}

// A cylinder of radius 2 and height 3 with a uv-square hole: 12 pi (1 - 1/4).
void TestMassProperties::cylinderWithHole() {
    Surface c = face(makeCylinder(glm::dvec3(0.0), 2.0, 3.0));
    QCOMPARE(surfaceType(c), SurfaceType::Cylinder);
    QVERIFY(relNear(faceIntegrals(c).area, 12 * kPi, 1e-11));
    c.trims.push_back(square(0.0, 1.0, 1));
    c.trims.push_back(square(0.25, 0.75, 2));
    const double a = faceIntegrals(c).area;
    QVERIFY2(relNear(a, 12 * kPi * 0.75, 1e-11), qPrintable(QString::number(a, 'g', 17)));
}

// Six planes bounding a 1 x 2 x 3 box, recorded as one closed shell: volume 6, area 22; without
// the closed record no volume.
void TestMassProperties::closedBoxVolume() {
    Scene scene;
    const glm::dvec3 e[3] = {{1, 0, 0}, {0, 2, 0}, {0, 0, 3}};
    std::uint32_t id = 1;
    Shell shell;
    shell.id = ShellId{1};
    shell.closed = true;
    shell.solid = 0;
    for (int axis = 0; axis < 3; ++axis) {
        const glm::dvec3 a = e[(axis + 1) % 3], b = e[(axis + 2) % 3];
        // The face at 0 with a x b pointing into the box, the one at e[axis] out of it.
        Surface lowFace = face(makePlane(glm::dvec3(0.0), a, b), id++);
        lowFace.outsideAlongNormal = false;
        Surface highFace = face(makePlane(e[axis], a, b), id++);
        for (Surface* s : {&lowFace, &highFace}) {
            s->solid = 0;
            shell.faces.push_back(s->id);
            scene.surfaces.push_back(*s);
        }
    }
    scene.topology.shells.push_back(shell);
    scene.nextId = id;
    ModelProperties m = modelProperties(scene);
    QVERIFY2(relNear(m.area, 22.0, 1e-12), qPrintable(QString::number(m.area, 'g', 17)));
    QVERIFY(m.volume.has_value());
    QVERIFY2(relNear(*m.volume, 6.0, 1e-12), qPrintable(QString::number(*m.volume, 'g', 17)));
    QVERIFY(m.hasBounds);
    QVERIFY(glm::length(m.lo) < 1e-12 && glm::length(m.hi - glm::dvec3(1, 2, 3)) < 1e-12);
    // Measured once, the faces give the same totals again (what the Properties panel caches).
    const std::vector<FaceMeasure> faces = measureFaces(scene);
    QCOMPARE(faces.size(), scene.surfaces.size());
    const ModelProperties again = modelProperties(scene, faces);
    QCOMPARE(again.area, m.area);
    QVERIFY(again.volume && std::abs(*again.volume - *m.volume) < 1e-15);
    // A face turned inside out (its outside mark flipped) no longer closes the volume.
    scene.surfaces[0].outsideAlongNormal = !scene.surfaces[0].outsideAlongNormal;
    QVERIFY(std::abs(*modelProperties(scene, faces).volume - 6.0) > 0.1);
    scene.surfaces[0].outsideAlongNormal = !scene.surfaces[0].outsideAlongNormal;
    scene.topology.shells[0].closed = false;
    QVERIFY(!modelProperties(scene).volume.has_value());
}

void TestMassProperties::sphereVolumeNeedsClosedShell() {
    Scene scene;
    scene.surfaces.push_back(face(makeSphere(glm::dvec3(0.0), 1.0)));
    const ModelProperties m = modelProperties(scene);
    QVERIFY(!m.volume.has_value());
    QVERIFY(relNear(m.area, 4 * kPi, 1e-7));
    QVERIFY(glm::length(m.lo + glm::dvec3(1.0)) < 1e-9 &&
            glm::length(m.hi - glm::dvec3(1.0)) < 1e-9);
}

// The flux about one origin follows from the flux about another and the vector area, which for
// a closed surface is zero; a box measured face by face once gives the same totals later.
void TestMassProperties::fluxMovesWithVectorArea() {
    Surface c = face(makeCylinder(glm::dvec3(1, 2, 3), 2.0, 3.0));
    c.trims.push_back(square(0.1, 0.8, 1));
    const glm::dvec3 o1(0.0), o2(7, -4, 2);
    const FaceIntegrals a = faceIntegrals(c, o1), b = faceIntegrals(c, o2);
    QVERIFY(glm::length(a.vectorArea) > 1.0);
    QVERIFY(glm::length(a.vectorArea - b.vectorArea) < 1e-12 * glm::length(a.vectorArea));
    const double moved = b.volume + glm::dot(o2 - o1, b.vectorArea) / 3.0;
    QVERIFY2(
        std::abs(moved - a.volume) < 1e-11 * std::abs(a.volume),
        qPrintable(QStringLiteral("%1 vs %2").arg(moved, 0, 'g', 17).arg(a.volume, 0, 'g', 17)));
    const FaceIntegrals sphere = faceIntegrals(face(makeSphere(glm::dvec3(1.0), 2.0)));
    QVERIFY(glm::length(sphere.vectorArea) < 1e-11);
}

void TestMassProperties::types() {
    QCOMPARE(surfaceType(face(makeSphere(glm::dvec3(1, 2, 3), 0.5))), SurfaceType::Sphere);
    QCOMPARE(surfaceType(face(makeCylinder(glm::dvec3(1, 2, 3), 0.5, 4))), SurfaceType::Cylinder);
    // A cone: the profile line from (r 1, z 0) to (r 0.2, z 2) revolved.
    const NurbsSurface cone = makeRevolution(glm::dvec3(0.0), [] {
        NurbsCurve2 c = line({1.0, 0.0}, {0.2, 2.0});
        return c;
    }());
    QCOMPARE(surfaceType(face(cone)), SurfaceType::Cone);
    // A bent plane is free-form; so is a sphere with one control point moved.
    NurbsSurface bent = makePlane(glm::dvec3(0.0), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0));
    bent = surfaceElevateDegreeU(surfaceElevateDegreeV(bent));
    bent.points[size_t(bent.index(1, 1))].z = 0.1;
    QCOMPARE(surfaceType(face(bent)), SurfaceType::FreeForm);
    NurbsSurface dented = makeSphere(glm::dvec3(0.0), 1.0);
    dented.points[size_t(dented.index(2, 2))] *= 1.01;
    QCOMPARE(surfaceType(face(dented)), SurfaceType::FreeForm);
    QCOMPARE(surfaceTypeName(SurfaceType::FreeForm), QStringLiteral("free-form"));
}

// A sphere trimmed to the uv band v in [0.25, 0.75] (the equator half) is bounded in z by
// +-sin(pi/4); its x extremes lie inside the face, on the equator.
void TestMassProperties::boundsOfTrimmedFace() {
    Surface s = face(makeSphere(glm::dvec3(0.0), 2.0));
    TrimLoop band;
    band.id = TrimLoopId{1};
    band.curves = {line({0, 0.25}, {1, 0.25}), line({1, 0.25}, {1, 0.75}),
                   line({1, 0.75}, {0, 0.75}), line({0, 0.75}, {0, 0.25})};
    s.trims.push_back(band);
    glm::dvec3 lo, hi;
    QVERIFY(faceBounds(s, lo, hi));
    const glm::dvec3 p = surfacePoint(s.geometry, 0.3, 0.75);
    QVERIFY2(std::abs(hi.z - p.z) < 1e-9, qPrintable(QString::number(hi.z - p.z)));
    QVERIFY2(std::abs(lo.z + p.z) < 1e-9, qPrintable(QString::number(lo.z + p.z)));
    QVERIFY2(std::abs(hi.x - 2.0) < 1e-9 && std::abs(lo.x + 2.0) < 1e-9,
             qPrintable(QString("%1 %2").arg(hi.x).arg(lo.x)));
    QVERIFY(std::abs(hi.y - 2.0) < 1e-9 && std::abs(lo.y + 2.0) < 1e-9);
}

QTEST_GUILESS_MAIN(TestMassProperties)
#include "tst_mass_properties.moc"
