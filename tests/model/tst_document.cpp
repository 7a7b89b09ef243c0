// Document tests: each mutator changes exactly what it says, bumps exactly the right revisions
// and signals in order; invalid input is refused with the reason, no change and no signal.
#include "model/document/document.h"
#include "model/document/validation.h"
#include "model_fixtures.h"
#include "signallog.h"
#include "tests/support/expected_test_util.h"

#include <QSignalSpy>
#include <QTest>
#include <cmath>
#include <limits>

using namespace kw;
using namespace kw::test;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Document loaded with threeSurfaceScene().
struct Fixture {
    Document doc;
    Fixture() {
        QString error;
        const auto ok = doc.resetScene(threeSurfaceScene());
        if (!ok)
            qFatal("fixture scene invalid: %s", qPrintable(ok.message()));
    }
};

} // namespace

class TestDocument : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void emptyDocument();
    void resetScene();
    void resetSceneRejectsInvalid();
    void validateScene_data();
    void validateScene();
    void insertSurface();
    void insertSurfaceRejects();
    void removeSurface();
    void setName();
    void setControlPoints();
    void setControlPointsRejects();
    void setWeight();
    void setGeometry();
    void setPartitionsAndMaterial();
    void trimLoops();
    void trimLoopsReject();
    void setTrimPoint();
    void lightsAndCamera();
    void revisionsNeverRepeat();
    void revisionMovesWithEveryChange();
    void editedFaceOpensItsSolid();
    void idsNeverReused();
    void refusalsSayWhy();
};

// Surface::solid: a change of a face's shape or trims, or its removal, clears the mark on every
// face of its solid (a seam may be open), with a display revision for each; other changes and
// other solids keep theirs; an inserted surface never carries one. Once every face of an
// opened solid has its loaded shape again (undo), the solid is marked again: the seams are the
// imported ones.
void TestDocument::editedFaceOpensItsSolid() {
    const auto marked = [] {
        Scene scene = threeSurfaceScene();
        scene.surfaces[0].solid = scene.surfaces[1].solid = 4;
        scene.surfaces[1].outsideAlongNormal = false;
        scene.surfaces[2].solid = 5;
        return scene;
    };
    const auto solids = [](const Document& doc) {
        std::vector<int> out;
        for (const Surface& s : doc.scene().surfaces)
            out.push_back(s.solid);
        return out;
    };
    {
        Document doc;
        QVERIFY(doc.resetScene(marked()));
        QCOMPARE(solids(doc), (std::vector<int>{4, 4, 5}));
        // What keeps the shape keeps the solid.
        QVERIFY(doc.setName(SurfaceId{1}, QStringLiteral("A")));
        QVERIFY(doc.setPartitions(SurfaceId{1}, 7, 7));
        Material m = doc.scene().surfaces[0].material;
        m.shininess += 1.0;
        QVERIFY(doc.setMaterial(SurfaceId{1}, m));
        QVERIFY(doc.setHidden(SurfaceId{1}, true));
        QVERIFY(doc.setHidden(SurfaceId{1}, false));
        QCOMPARE(solids(doc), (std::vector<int>{4, 4, 5}));
        // A moved point opens solid 4, both faces, each with a new display revision.
        const std::uint64_t before = doc.revisions(SurfaceId{2}).display;
        const glm::dvec3 p = doc.scene().surfaces[0].geometry.points[0];
        QVERIFY(doc.setControlPoints(SurfaceId{1}, {0}, {p + glm::dvec3(0.1)}));
        QCOMPARE(solids(doc), (std::vector<int>{-1, -1, 5}));
        QVERIFY(doc.revisions(SurfaceId{2}).display > before);
        // Moving it back closes it again, both faces, each with a new display revision, and
        // each on its side; the marks' revision moves with each opening and closing only.
        const std::uint64_t opened = doc.revisions(SurfaceId{2}).display;
        const std::uint64_t marks = doc.marksRevision();
        QSignalSpy changed(&doc, &Document::surfaceChanged);
        QVERIFY(doc.setControlPoints(SurfaceId{1}, {0}, {p}));
        QCOMPARE(solids(doc), (std::vector<int>{4, 4, 5}));
        QVERIFY(doc.revisions(SurfaceId{2}).display > opened);
        QCOMPARE(changed.size(), 3); // the points of 1, then the display of 1 and 2
        QVERIFY(doc.marksRevision() > marks);
        const std::uint64_t closed = doc.marksRevision();
        QVERIFY(doc.setName(SurfaceId{1}, QStringLiteral("B")));
        QVERIFY(doc.setPartitions(SurfaceId{3}, 5, 5));
        QCOMPARE(doc.marksRevision(), closed);
        QVERIFY(doc.scene().surfaces[0].outsideAlongNormal);
        QVERIFY(!doc.scene().surfaces[1].outsideAlongNormal);
        // With two faces changed, only both back close it.
        const glm::dvec3 q = doc.scene().surfaces[1].geometry.points[1];
        QVERIFY(doc.setControlPoints(SurfaceId{1}, {0}, {p + glm::dvec3(0.1)}));
        QVERIFY(doc.setControlPoints(SurfaceId{2}, {1}, {q - glm::dvec3(0.2)}));
        QVERIFY(doc.setControlPoints(SurfaceId{1}, {0}, {p}));
        QCOMPARE(solids(doc), (std::vector<int>{-1, -1, 5}));
        // A shape near the loaded one is not it.
        QVERIFY(doc.setControlPoints(SurfaceId{2}, {1}, {q + glm::dvec3(1e-12, 0.0, 0.0)}));
        QCOMPARE(solids(doc), (std::vector<int>{-1, -1, 5}));
        QVERIFY(doc.setControlPoints(SurfaceId{2}, {1}, {q}));
        QCOMPARE(solids(doc), (std::vector<int>{4, 4, 5}));
        // A new scene forgets the old marks: the same ids and shapes, unmarked, stay so.
        QVERIFY(doc.resetScene(threeSurfaceScene()));
        QVERIFY(doc.setControlPoints(SurfaceId{1}, {0}, {p + glm::dvec3(0.1)}));
        QVERIFY(doc.setControlPoints(SurfaceId{1}, {0}, {p}));
        QCOMPARE(solids(doc), (std::vector<int>{-1, -1, -1}));
    }
    {
        Document doc;
        QVERIFY(doc.resetScene(marked()));
        QVERIFY(doc.setWeight(SurfaceId{2}, 0, 2.0));
        QCOMPARE(solids(doc), (std::vector<int>{-1, -1, 5}));
        const TrimLoop loop = doc.scene().surfaces[2].trims[0];
        QVERIFY(doc.removeTrimLoop(SurfaceId{3}, loop.id));
        QCOMPARE(solids(doc), (std::vector<int>{-1, -1, -1}));
        // Undone in reverse: the loop closes solid 5, the weight solid 4.
        QVERIFY(doc.insertTrimLoop(SurfaceId{3}, 0, loop));
        QCOMPARE(solids(doc), (std::vector<int>{-1, -1, 5}));
        QVERIFY(doc.setWeight(SurfaceId{2}, 0, 1.0));
        QCOMPARE(solids(doc), (std::vector<int>{4, 4, 5}));
    }
    {
        Document doc;
        QVERIFY(doc.resetScene(marked()));
        const Surface removed = doc.scene().surfaces[1];
        QVERIFY(doc.removeSurface(SurfaceId{2}));
        QCOMPARE(solids(doc), (std::vector<int>{-1, 5}));
        QVERIFY(doc.insertSurface(1, removed)); // undo of the removal
        QCOMPARE(solids(doc), (std::vector<int>{4, 4, 5}));
        KW_VERIFY_OK(Document::validate(doc.scene()));
        // A face of another shape under the removed one's id does not close it.
        QVERIFY(doc.removeSurface(SurfaceId{2}));
        Surface other = removed;
        other.geometry.points[0].z += 1.0;
        QVERIFY(doc.insertSurface(1, other));
        QCOMPARE(solids(doc), (std::vector<int>{-1, -1, 5}));
        // Nor does a new surface of the removed one's shape.
        QVERIFY(doc.removeSurface(SurfaceId{2}));
        Surface copy = removed;
        copy.id = doc.allocateSurfaceId();
        QVERIFY(doc.insertSurface(1, copy));
        QCOMPARE(solids(doc), (std::vector<int>{-1, -1, 5}));
    }
}

void TestDocument::emptyDocument() {
    Document doc;
    QVERIFY(doc.scene().surfaces.empty());
    QCOMPARE(doc.scene().lights.size(), size_t(2));
    KW_VERIFY_OK(Document::validate(doc.scene()));
    QVERIFY(!doc.surface(SurfaceId{1}));
    QCOMPARE(doc.indexOf(SurfaceId{1}), -1);
    QCOMPARE(doc.revisions(SurfaceId{1}), Revisions{});
}

void TestDocument::resetScene() {
    Document doc;
    SignalLog log(&doc);
    QSignalSpy reset(&doc, &Document::sceneReset);
    Scene scene = threeSurfaceScene();
    scene.nextId = 1; // below the ids in use: resetScene raises it
    const Status done = doc.resetScene(scene);
    QVERIFY(done);
    QCOMPARE(done.message(), QString());
    QCOMPARE(reset.count(), 1);
    QCOMPARE(log.take(), QStringList({"aboutToReset", "reset"}));
    QCOMPARE(doc.scene().nextId, 13u);
    QVERIFY(sameContent(doc.scene(), scene));
    QCOMPARE(doc.indexOf(SurfaceId{3}), 2);
    QCOMPARE(doc.surface(SurfaceId{2})->name, QStringLiteral("Beta"));
    const Revisions r = doc.revisions(SurfaceId{1});
    QVERIFY(r.points > 0 && r.knots > 0 && r.trims > 0 && r.display > 0);
    QVERIFY(doc.lightsRevision() > 0);
    QVERIFY(doc.cameraRevision() > 0);
}

void TestDocument::resetSceneRejectsInvalid() {
    Fixture f;
    SignalLog log(&f.doc);
    const Scene before = f.doc.scene();
    Scene bad = threeSurfaceScene();
    bad.surfaces[1].id = SurfaceId{1};
    QString error;
    const auto result = f.doc.resetScene(bad);
    QVERIFY(!result);
    QVERIFY2(result.message().contains(QStringLiteral("used twice")), qPrintable(result.message()));
    QCOMPARE(f.doc.scene(), before);
    QVERIFY(log.entries.isEmpty());
    QVERIFY(!f.doc.resetScene(bad)); // no error pointer: still no crash
}

void TestDocument::validateScene_data() {
    QTest::addColumn<int>("which");
    QTest::addColumn<QString>("expected");
    QTest::newRow("valid") << 0 << QString();
    QTest::newRow("duplicate surface id") << 1 << QStringLiteral("surface id 1 used twice");
    QTest::newRow("invalid surface id") << 2 << QStringLiteral("surface has no id");
    QTest::newRow("duplicate loop id across surfaces")
        << 3 << QStringLiteral("trim loop id 10 used twice");
    QTest::newRow("nextId not above ids") << 4 << QStringLiteral("nextId 12");
    QTest::newRow("bad geometry") << 5 << QStringLiteral("surface 2");
    QTest::newRow("bad trim curve") << 6 << QStringLiteral("trim loop 12, curve 1");
    QTest::newRow("partitions 0") << 7 << QStringLiteral("partitions 0 x 10");
    QTest::newRow("partitions 257") << 8 << QStringLiteral("partitions 10 x 257");
    QTest::newRow("no lights (unlit)") << 9 << QString();
    QTest::newRow("nine lights") << 10 << QStringLiteral("9 lights");
    QTest::newRow("NaN light") << 11 << QStringLiteral("light 2");
    QTest::newRow("empty trim loop") << 12 << QStringLiteral("has no curves");
    QTest::newRow("loop id used twice in one surface") << 13 << QStringLiteral("used twice");
}

void TestDocument::validateScene() {
    QFETCH(int, which);
    QFETCH(QString, expected);
    Scene s = threeSurfaceScene();
    switch (which) {
    case 1:
        s.surfaces[2].id = SurfaceId{1};
        break;
    case 2:
        s.surfaces[0].id = SurfaceId{};
        break;
    case 3:
        s.surfaces[2].trims[0].id = TrimLoopId{10};
        break;
    case 4:
        s.nextId = 12;
        break;
    case 5:
        s.surfaces[1].geometry.knotsU.pop_back();
        break;
    case 6:
        s.surfaces[2].trims[0].curves[0].weights[0] = -1;
        break;
    case 7:
        s.surfaces[0].partitionsU = 0;
        break;
    case 8:
        s.surfaces[0].partitionsV = 257;
        break;
    case 9:
        s.lights.clear();
        break;
    case 10:
        s.lights.assign(9, Light{});
        break;
    case 11:
        s.lights[1].diffuse.y = kNaN;
        break;
    case 12:
        s.surfaces[0].trims[1].curves.clear();
        break;
    case 13:
        s.surfaces[0].trims[1].id = TrimLoopId{10};
        break;
    default:
        break;
    }
    const QString error = kwtest::refusal(Document::validate(s));
    if (expected.isEmpty())
        QCOMPARE(error, QString());
    else
        QVERIFY2(error.contains(expected), qPrintable(error));
}

void TestDocument::insertSurface() {
    Fixture f;
    SignalLog log(&f.doc);
    QSignalSpy inserted(&f.doc, &Document::surfaceInserted);
    Surface s = makeSurface(20, QStringLiteral("Delta"), patch(4, 5));
    s.trims.push_back(rectLoop(TrimLoopId{30}, 0.2, 0.2, 0.8, 0.8));
    QVERIFY(f.doc.insertSurface(1, s));
    QCOMPARE(log.take(), QStringList({"aboutToInsert @1", "inserted 20 @1"}));
    QCOMPARE(inserted.count(), 1);
    QCOMPARE(inserted.at(0).at(0).value<SurfaceId>(), SurfaceId{20});
    QCOMPARE(f.doc.scene().surfaces.size(), size_t(4));
    QCOMPARE(f.doc.scene().surfaces[1], s);
    QCOMPARE(f.doc.indexOf(SurfaceId{2}), 2);
    QCOMPARE(f.doc.scene().nextId, 31u); // raised above the loop id
    const Revisions r = f.doc.revisions(SurfaceId{20});
    QVERIFY(r.points > f.doc.revisions(SurfaceId{1}).points);
    QCOMPARE(r.knots, r.points);
    // Append at the end.
    QVERIFY(f.doc.insertSurface(4, makeSurface(40, QStringLiteral("End"), patch())));
    QCOMPARE(f.doc.indexOf(SurfaceId{40}), 4);
}

void TestDocument::insertSurfaceRejects() {
    Fixture f;
    SignalLog log(&f.doc);
    const Scene before = f.doc.scene();
    const Surface good = makeSurface(20, QStringLiteral("Delta"), patch());
    QVERIFY(!f.doc.insertSurface(-1, good));
    QVERIFY(!f.doc.insertSurface(4, good));
    Surface s = good;
    s.id = SurfaceId{};
    QVERIFY(!f.doc.insertSurface(0, s)); // invalid id
    s.id = SurfaceId{2};
    QVERIFY(!f.doc.insertSurface(0, s)); // id in use
    s = good;
    s.geometry.weights[3] = 0.0;
    QVERIFY(!f.doc.insertSurface(0, s)); // zero weight
    s = good;
    s.geometry.points.pop_back();
    QVERIFY(!f.doc.insertSurface(0, s)); // net size mismatch
    s = good;
    s.partitionsU = 0;
    QVERIFY(!f.doc.insertSurface(0, s));
    s = good;
    s.trims.push_back(rectLoop(TrimLoopId{10}, 0.1, 0.1, 0.2, 0.2)); // loop id of surface 1
    QVERIFY(!f.doc.insertSurface(0, s));
    s = good;
    s.material.kd = -1;
    QVERIFY(!f.doc.insertSurface(0, s));
    s = good;
    s.id = SurfaceId{std::numeric_limits<std::uint32_t>::max()}; // would overflow nextId
    QVERIFY(!f.doc.insertSurface(0, s));
    QCOMPARE(f.doc.scene(), before);
    QVERIFY(log.entries.isEmpty());
}

void TestDocument::removeSurface() {
    Fixture f;
    SignalLog log(&f.doc);
    QSignalSpy removed(&f.doc, &Document::surfaceRemoved);
    QVERIFY(!f.doc.removeSurface(SurfaceId{99}));
    QVERIFY(!f.doc.removeSurface(SurfaceId{}));
    QVERIFY(log.entries.isEmpty());
    QVERIFY(f.doc.removeSurface(SurfaceId{2}));
    QCOMPARE(log.take(), QStringList({"aboutToRemove 2 @1", "removed 2"}));
    QCOMPARE(removed.count(), 1);
    QCOMPARE(f.doc.scene().surfaces.size(), size_t(2));
    QCOMPARE(f.doc.indexOf(SurfaceId{3}), 1);
    QCOMPARE(f.doc.revisions(SurfaceId{2}), Revisions{});
    QVERIFY(!f.doc.removeSurface(SurfaceId{2}));
}

void TestDocument::setName() {
    Fixture f;
    SignalLog log(&f.doc);
    const Revisions before = f.doc.revisions(SurfaceId{1});
    QVERIFY(f.doc.setName(SurfaceId{1}, QStringLiteral("Hood")));
    QCOMPARE(f.doc.surface(SurfaceId{1})->name, QStringLiteral("Hood"));
    QCOMPARE(log.take(), QStringList({"changed 1 Name"}));
    QCOMPARE(f.doc.revisions(SurfaceId{1}), before);              // names are not uploaded
    QVERIFY(f.doc.setName(SurfaceId{1}, QStringLiteral("Hood"))); // no-op: silent
    QVERIFY(log.entries.isEmpty());
    QVERIFY(!f.doc.setName(SurfaceId{1}, QString()));
    QVERIFY(!f.doc.setName(SurfaceId{1}, QStringLiteral("   ")));
    QVERIFY(!f.doc.setName(SurfaceId{42}, QStringLiteral("x")));
    QVERIFY(log.entries.isEmpty());
    QCOMPARE(f.doc.surface(SurfaceId{1})->name, QStringLiteral("Hood"));
}

void TestDocument::setControlPoints() {
    Fixture f;
    SignalLog log(&f.doc);
    QSignalSpy changed(&f.doc, &Document::surfaceChanged);
    const Revisions before = f.doc.revisions(SurfaceId{2});
    const Revisions other = f.doc.revisions(SurfaceId{1});
    QVERIFY(f.doc.setControlPoints(SurfaceId{2}, {0, 7}, {{9, 9, 9}, {-1, -2, -3}}));
    const NurbsSurface& g = f.doc.surface(SurfaceId{2})->geometry;
    QCOMPARE(g.points[0], glm::dvec3(9, 9, 9));
    QCOMPARE(g.points[7], glm::dvec3(-1, -2, -3));
    QCOMPARE(changed.count(), 1);
    QCOMPARE(changed.at(0).at(1).value<Aspects>(), Aspects(Aspect::Points));
    QCOMPARE(log.take(), QStringList({"changed 2 Points"}));
    const Revisions after = f.doc.revisions(SurfaceId{2});
    QVERIFY(after.points > before.points);
    QCOMPARE(after.knots, before.knots);
    QCOMPARE(after.trims, before.trims);
    QCOMPARE(after.display, before.display);
    QCOMPARE(f.doc.revisions(SurfaceId{1}), other);
    // Same positions again: valid, silent, no bump.
    QVERIFY(f.doc.setControlPoints(SurfaceId{2}, {0}, {{9, 9, 9}}));
    QVERIFY(log.entries.isEmpty());
    QCOMPARE(f.doc.revisions(SurfaceId{2}), after);
}

void TestDocument::setControlPointsRejects() {
    Fixture f;
    SignalLog log(&f.doc);
    const Scene before = f.doc.scene();
    const SurfaceId id{2}; // 5 x 4 = 20 points
    QVERIFY(!f.doc.setControlPoints(id, {}, {}));
    QVERIFY(!f.doc.setControlPoints(id, {0, 1}, {{0, 0, 0}}));
    QVERIFY(!f.doc.setControlPoints(id, {20}, {{0, 0, 0}}));
    QVERIFY(!f.doc.setControlPoints(id, {-1}, {{0, 0, 0}}));
    QVERIFY(!f.doc.setControlPoints(id, {3, 3}, {{0, 0, 0}, {1, 1, 1}}));
    QVERIFY(!f.doc.setControlPoints(id, {0, 1}, {{5, 5, 5}, {kNaN, 0, 0}})); // no partial move
    QVERIFY(!f.doc.setControlPoints(SurfaceId{9}, {0}, {{0, 0, 0}}));
    QCOMPARE(f.doc.scene(), before);
    QVERIFY(log.entries.isEmpty());
}

void TestDocument::setWeight() {
    Fixture f;
    SignalLog log(&f.doc);
    const Revisions before = f.doc.revisions(SurfaceId{1});
    QVERIFY(f.doc.setWeight(SurfaceId{1}, 5, 2.5));
    QCOMPARE(f.doc.surface(SurfaceId{1})->geometry.weights[5], 2.5);
    QCOMPARE(log.take(), QStringList({"changed 1 Points"}));
    const Revisions after = f.doc.revisions(SurfaceId{1});
    QVERIFY(after.points > before.points);
    QCOMPARE(after.knots, before.knots);
    const Scene s = f.doc.scene();
    QVERIFY(!f.doc.setWeight(SurfaceId{1}, 5, 0.0));
    QVERIFY(!f.doc.setWeight(SurfaceId{1}, 5, -1.0));
    QVERIFY(!f.doc.setWeight(SurfaceId{1}, 5, kNaN));
    QVERIFY(!f.doc.setWeight(SurfaceId{1}, 16, 1.0));
    QVERIFY(!f.doc.setWeight(SurfaceId{7}, 0, 1.0));
    QCOMPARE(f.doc.scene(), s);
    QVERIFY(log.entries.isEmpty());
}

void TestDocument::setGeometry() {
    Fixture f;
    SignalLog log(&f.doc);
    const SurfaceId id{3};
    Revisions r0 = f.doc.revisions(id);
    // Knots only (an interior knot moves): Knots aspect only.
    NurbsSurface g = f.doc.surface(id)->geometry;
    QCOMPARE(g.knotsV.size(), size_t(10)); // 6 points, degree 3: interior 1/3, 2/3
    g.knotsV[4] = 0.25;
    QVERIFY(f.doc.setGeometry(id, g));
    QCOMPARE(log.take(), QStringList({"changed 3 Knots"}));
    Revisions r1 = f.doc.revisions(id);
    QVERIFY(r1.knots > r0.knots);
    QCOMPARE(r1.points, r0.points);
    QCOMPARE(r1.trims, r0.trims);
    // A larger net (as after knot insertion): Points and Knots.
    NurbsSurface bigger = patch(5, 6, 10.0, 2.0);
    QVERIFY(f.doc.setGeometry(id, bigger));
    QCOMPARE(log.take(), QStringList({"changed 3 Points|Knots"}));
    Revisions r2 = f.doc.revisions(id);
    QVERIFY(r2.points > r1.points && r2.knots > r1.knots);
    QCOMPARE(r2.points, r2.knots);
    QCOMPARE(r2.display, r0.display);
    QCOMPARE(f.doc.surface(id)->geometry, bigger);
    // Invalid: decreasing knots, wrong point count.
    NurbsSurface bad = bigger;
    bad.knotsU[4] = 2.0;
    QVERIFY(!f.doc.setGeometry(id, bad));
    bad = bigger;
    bad.countU = 4;
    QVERIFY(!f.doc.setGeometry(id, bad));
    QVERIFY(!f.doc.setGeometry(SurfaceId{77}, bigger));
    QVERIFY(log.entries.isEmpty());
    QCOMPARE(f.doc.surface(id)->geometry, bigger);
}

void TestDocument::setPartitionsAndMaterial() {
    Fixture f;
    SignalLog log(&f.doc);
    const Revisions r0 = f.doc.revisions(SurfaceId{1});
    QVERIFY(f.doc.setPartitions(SurfaceId{1}, 1, 256));
    QCOMPARE(f.doc.surface(SurfaceId{1})->partitionsU, 1);
    QCOMPARE(f.doc.surface(SurfaceId{1})->partitionsV, 256);
    QCOMPARE(log.take(), QStringList({"changed 1 Display"}));
    const Revisions r1 = f.doc.revisions(SurfaceId{1});
    QVERIFY(r1.display > r0.display);
    QCOMPARE(r1.points, r0.points);
    QVERIFY(!f.doc.setPartitions(SurfaceId{1}, 0, 5));
    QVERIFY(!f.doc.setPartitions(SurfaceId{1}, 5, 257));
    QVERIFY(!f.doc.setPartitions(SurfaceId{5}, 5, 5));
    QVERIFY(log.entries.isEmpty());

    Material m;
    m.color = {1, 0, 0};
    m.shininess = 8;
    QVERIFY(f.doc.setMaterial(SurfaceId{1}, m));
    QCOMPARE(f.doc.surface(SurfaceId{1})->material, m);
    QCOMPARE(log.take(), QStringList({"changed 1 Display"}));
    QVERIFY(f.doc.revisions(SurfaceId{1}).display > r1.display);
    Material bad = m;
    bad.ks = -0.1;
    QVERIFY(!f.doc.setMaterial(SurfaceId{1}, bad));
    bad = m;
    bad.color.z = kNaN;
    QVERIFY(!f.doc.setMaterial(SurfaceId{1}, bad));
    QVERIFY(log.entries.isEmpty());
    QCOMPARE(f.doc.surface(SurfaceId{1})->material, m);

    // Hidden: a display change; setting the same value again changes and emits nothing.
    const Revisions r2 = f.doc.revisions(SurfaceId{1});
    QVERIFY(f.doc.setHidden(SurfaceId{1}, true));
    QVERIFY(f.doc.surface(SurfaceId{1})->hidden);
    QCOMPARE(log.take(), QStringList({"changed 1 Display"}));
    QVERIFY(f.doc.revisions(SurfaceId{1}).display > r2.display);
    QCOMPARE(f.doc.revisions(SurfaceId{1}).points, r2.points);
    QVERIFY(f.doc.setHidden(SurfaceId{1}, true));
    QVERIFY(log.entries.isEmpty());
    QVERIFY(!f.doc.setHidden(SurfaceId{5}, false));
    QVERIFY(f.doc.setHidden(SurfaceId{1}, false));
    QVERIFY(!f.doc.surface(SurfaceId{1})->hidden);
    QCOMPARE(log.take(), QStringList({"changed 1 Display"}));
}

void TestDocument::trimLoops() {
    Fixture f;
    SignalLog log(&f.doc);
    const Revisions r0 = f.doc.revisions(SurfaceId{1});
    const TrimLoop loop = rectLoop(TrimLoopId{50}, 0.4, 0.4, 0.5, 0.5);
    QVERIFY(f.doc.insertTrimLoop(SurfaceId{1}, 1, loop));
    QCOMPARE(log.take(),
             QStringList({"aboutToInsertLoop 1 @1", "insertedLoop 1 @1", "changed 1 Trims"}));
    const auto& trims = f.doc.surface(SurfaceId{1})->trims;
    QCOMPARE(trims.size(), size_t(3));
    QCOMPARE(trims[1], loop);
    QCOMPARE(trims[2].id, TrimLoopId{11});
    QCOMPARE(f.doc.scene().nextId, 51u);
    const Revisions r1 = f.doc.revisions(SurfaceId{1});
    QVERIFY(r1.trims > r0.trims);
    QCOMPARE(r1.points, r0.points);
    QCOMPARE(r1.display, r0.display);

    QVERIFY(f.doc.removeTrimLoop(SurfaceId{1}, TrimLoopId{10}));
    QCOMPARE(log.take(),
             QStringList({"aboutToRemoveLoop 1 @0", "removedLoop 1 @0", "changed 1 Trims"}));
    QCOMPARE(f.doc.surface(SurfaceId{1})->trims.front().id, TrimLoopId{50});
    QVERIFY(f.doc.revisions(SurfaceId{1}).trims > r1.trims);
}

void TestDocument::trimLoopsReject() {
    Fixture f;
    SignalLog log(&f.doc);
    const Scene before = f.doc.scene();
    const TrimLoop good = rectLoop(TrimLoopId{50}, 0.4, 0.4, 0.5, 0.5);
    QVERIFY(!f.doc.insertTrimLoop(SurfaceId{1}, 3, good));  // index past the end
    QVERIFY(!f.doc.insertTrimLoop(SurfaceId{1}, -1, good)); // negative index
    QVERIFY(!f.doc.insertTrimLoop(SurfaceId{8}, 0, good));  // unknown surface
    TrimLoop l = good;
    l.id = TrimLoopId{12}; // used by surface 3
    QVERIFY(!f.doc.insertTrimLoop(SurfaceId{1}, 0, l));
    l.id = TrimLoopId{};
    QVERIFY(!f.doc.insertTrimLoop(SurfaceId{1}, 0, l));
    l = good;
    l.curves.clear();
    QVERIFY(!f.doc.insertTrimLoop(SurfaceId{1}, 0, l));
    l = good;
    l.curves[2].knots = {0, 1, 0, 1}; // decreasing
    QVERIFY(!f.doc.insertTrimLoop(SurfaceId{1}, 0, l));
    QVERIFY(!f.doc.removeTrimLoop(SurfaceId{1}, TrimLoopId{12})); // loop of another surface
    QVERIFY(!f.doc.removeTrimLoop(SurfaceId{9}, TrimLoopId{10}));
    QCOMPARE(f.doc.scene(), before);
    QVERIFY(log.entries.isEmpty());
}

void TestDocument::setTrimPoint() {
    Fixture f;
    SignalLog log(&f.doc);
    const Revisions r0 = f.doc.revisions(SurfaceId{1});
    const TrimPointRef ref{SurfaceId{1}, TrimLoopId{11}, 2, 1}; // the arc's middle point
    QVERIFY(f.doc.setTrimPoint(ref, {0.45, 0.7}));
    QCOMPARE(f.doc.surface(SurfaceId{1})->trims[1].curves[2].points[1], glm::dvec2(0.45, 0.7));
    QCOMPARE(log.take(), QStringList({"changed 1 Trims"}));
    const Revisions r1 = f.doc.revisions(SurfaceId{1});
    QVERIFY(r1.trims > r0.trims);
    QCOMPARE(r1.points, r0.points);
    const Scene before = f.doc.scene();
    QVERIFY(!f.doc.setTrimPoint({SurfaceId{1}, TrimLoopId{11}, 2, 3}, {0, 0})); // index
    QVERIFY(!f.doc.setTrimPoint({SurfaceId{1}, TrimLoopId{11}, 4, 0}, {0, 0})); // curve
    QVERIFY(!f.doc.setTrimPoint({SurfaceId{1}, TrimLoopId{12}, 0, 0}, {0, 0})); // loop
    QVERIFY(!f.doc.setTrimPoint({SurfaceId{6}, TrimLoopId{11}, 0, 0}, {0, 0})); // surface
    QVERIFY(!f.doc.setTrimPoint(ref, {kNaN, 0}));
    // A curve end alone would open the loop (the file could not be reopened): refused...
    const int last = int(f.doc.surface(SurfaceId{1})->trims[1].curves[0].points.size()) - 1;
    const TrimPointRef end{SurfaceId{1}, TrimLoopId{11}, 0, last};
    const TrimPointRef start{SurfaceId{1}, TrimLoopId{11}, 1, 0};
    QVERIFY(!f.doc.setTrimPoint(end, {0.31, 0.29}));
    QVERIFY(!f.doc.setTrimPoints({end, end}, {{0.31, 0.29}, {0.31, 0.29}})); // listed twice
    QCOMPARE(f.doc.scene(), before);
    QVERIFY(log.entries.isEmpty());
    // ...together with the coinciding start of the next curve it is one valid step.
    QVERIFY(f.doc.setTrimPoints({end, start}, {{0.31, 0.29}, {0.31, 0.29}}));
    QCOMPARE(log.take(), QStringList({"changed 1 Trims"}));
    KW_VERIFY_OK(checkScene(f.doc.scene()));
}

void TestDocument::lightsAndCamera() {
    Fixture f;
    SignalLog log(&f.doc);
    QSignalSpy lights(&f.doc, &Document::lightsChanged);
    const auto l0 = f.doc.lightsRevision();
    std::vector<Light> ls = f.doc.scene().lights;
    ls.push_back(
        Light{Light::Kind::Point, {1, 2, 3}, glm::dvec3(0), glm::dvec3(0.5), glm::dvec3(0.5)});
    QVERIFY(f.doc.setLights(ls));
    QCOMPARE(f.doc.scene().lights, ls);
    QCOMPARE(lights.count(), 1);
    QVERIFY(f.doc.lightsRevision() > l0);
    QCOMPARE(log.take(), QStringList({"lights"}));
    const auto l1 = f.doc.lightsRevision();
    QVERIFY(!f.doc.setLights(std::vector<Light>(size_t(kMaxLights + 1))));
    std::vector<Light> tooBright = ls;
    tooBright[1].diffuse.y = 1001; // intensities in [0, 1000], as the .knot reader says
    QVERIFY(!f.doc.setLights(tooBright));
    std::vector<Light> bad = ls;
    bad[0].vector = glm::dvec3(0);
    QVERIFY(!f.doc.setLights(bad)); // directional light with no direction
    bad = ls;
    bad[2].specular.x = -1;
    QVERIFY(!f.doc.setLights(bad));
    QVERIFY(f.doc.setLights(std::vector<Light>(size_t(kMaxLights)))); // the maximum is fine
    QCOMPARE(log.take(), QStringList({"lights"}));
    QVERIFY(f.doc.lightsRevision() > l1);

    const auto c0 = f.doc.cameraRevision();
    Camera cam;
    cam.eye = {1, 2, 3};
    cam.authored = true;
    QVERIFY(f.doc.setCamera(cam));
    QCOMPARE(f.doc.scene().camera, cam);
    QCOMPARE(log.take(), QStringList({"camera"}));
    QVERIFY(f.doc.cameraRevision() > c0);
    Camera badCam = cam;
    badCam.target = badCam.eye;
    QVERIFY(!f.doc.setCamera(badCam));
    badCam = cam;
    badCam.fovYDegrees = 180;
    QVERIFY(!f.doc.setCamera(badCam));
    badCam = cam;
    badCam.up = glm::normalize(cam.target - cam.eye);
    QVERIFY(!f.doc.setCamera(badCam));
    QVERIFY(log.entries.isEmpty());
    QCOMPARE(f.doc.scene().camera, cam);
}

void TestDocument::revisionsNeverRepeat() {
    // Moving a point away and back (as undo does) must give a new revision, not the old one,
    // so a renderer that cached the first upload still re-uploads.
    Fixture f;
    const SurfaceId id{1};
    const glm::dvec3 p = f.doc.surface(id)->geometry.points[5];
    const auto r0 = f.doc.revisions(id).points;
    QVERIFY(f.doc.setControlPoints(id, {5}, {p + glm::dvec3(1)}));
    const auto r1 = f.doc.revisions(id).points;
    QVERIFY(f.doc.setControlPoints(id, {5}, {p}));
    const auto r2 = f.doc.revisions(id).points;
    QVERIFY(r0 < r1 && r1 < r2);
    // A surface removed and re-inserted with the same id gets fresh revisions too.
    const Surface s = *f.doc.surface(id);
    const Revisions before = f.doc.revisions(id);
    QVERIFY(f.doc.removeSurface(id));
    QVERIFY(f.doc.insertSurface(0, s));
    const Revisions after = f.doc.revisions(id);
    QVERIFY(after.points > before.points && after.knots > before.knots &&
            after.trims > before.trims && after.display > before.display);
}

void TestDocument::revisionMovesWithEveryChange() {
    // revision() is "has anything changed": the renderer adds samples of one anti-aliased image
    // while it stays (Renderer's progressive accumulation), so a change it missed would leave a
    // stale image on screen.
    Fixture f;
    std::uint64_t last = f.doc.revision();
    QVERIFY(last > 0);
    auto moved = [&](bool changed) {
        const std::uint64_t now = f.doc.revision();
        const bool ok = changed ? now > last : now == last;
        last = now;
        return ok;
    };
    const SurfaceId id{1};
    const glm::dvec3 p = f.doc.surface(id)->geometry.points[5];
    QVERIFY(f.doc.setControlPoints(id, {5}, {p + glm::dvec3(1)}));
    QVERIFY(moved(true));
    QVERIFY(f.doc.setControlPoints(id, {5}, {p + glm::dvec3(1)})); // the same positions
    QVERIFY(moved(false));
    QVERIFY(f.doc.setWeight(id, 5, 2.0));
    QVERIFY(moved(true));
    QVERIFY(f.doc.setPartitions(id, 7, 9));
    QVERIFY(moved(true));
    QVERIFY(f.doc.setHidden(id, true));
    QVERIFY(moved(true));
    QVERIFY(f.doc.setName(id, QStringLiteral("renamed")));
    QVERIFY(moved(true));
    // A removal bumps no surface's revisions (the surface is gone), but the scene changed.
    QVERIFY(f.doc.removeSurface(SurfaceId{2}));
    QVERIFY(moved(true));
    QVERIFY(!f.doc.removeSurface(SurfaceId{2}));
    QVERIFY(moved(false));
    std::vector<Light> lights = f.doc.scene().lights;
    lights.push_back(Light{});
    QVERIFY(f.doc.setLights(lights));
    QVERIFY(moved(true));
    Camera camera = f.doc.scene().camera;
    camera.fovYDegrees += 5.0;
    QVERIFY(f.doc.setCamera(camera));
    QVERIFY(moved(true));
    DisplaySettings display = f.doc.scene().display;
    display.partitionMode = QStringLiteral("uniform");
    QVERIFY(f.doc.setDisplay(display));
    QVERIFY(moved(true));
    QVERIFY(f.doc.setDisplay(display));
    QVERIFY(moved(false));
    QVERIFY(f.doc.resetScene(threeSurfaceScene()));
    QVERIFY(moved(true));
    // Two documents never hand out the same value, so a new document at an old one's address
    // with the same number of edits is not taken for the old one.
    Fixture g;
    QVERIFY(g.doc.revision() > f.doc.revision());
    QVERIFY(f.doc.setHidden(id, true));
    QVERIFY(f.doc.revision() > g.doc.revision());
}

void TestDocument::idsNeverReused() {
    Fixture f;
    const SurfaceId a = f.doc.allocateSurfaceId();
    const TrimLoopId b = f.doc.allocateTrimLoopId();
    QCOMPARE(a.value, 13u);
    QCOMPARE(b.value, 14u);
    QVERIFY(f.doc.insertSurface(0, makeSurface(a.value, QStringLiteral("New"), patch())));
    QVERIFY(f.doc.removeSurface(a));
    QCOMPARE(f.doc.allocateSurfaceId().value, 15u);
}

// Every refusal carries the validator's reason, or names the unknown id; nothing changes and
// nothing is signalled.
void TestDocument::refusalsSayWhy() {
    using kwtest::refusal;
    Fixture f;
    SignalLog log(&f.doc);
    const Scene before = f.doc.scene();

    DisplaySettings display = before.display;
    display.partitionMode = QStringLiteral("sideways");
    QCOMPARE(refusal(f.doc.setDisplay(display)),
             QStringLiteral("partition mode \"sideways\" is neither \"adaptive\" nor \"uniform\""));
    display = before.display;
    display.draftAngleDegrees = 95.0;
    QCOMPARE(refusal(f.doc.setDisplay(display)), QStringLiteral("draft angle 95 is outside 0..90"));
    ContinuityTolerances tolerances = before.continuity;
    tolerances.g1Degrees = -1.0;
    QCOMPARE(refusal(f.doc.setContinuityTolerances(tolerances)),
             QStringLiteral("g1Degrees must be a finite number above 0, not -1"));
    QCOMPARE(
        refusal(f.doc.setLights(std::vector<Light>(size_t(kMaxLights + 1)))),
        QStringLiteral("%1 lights, more than the limit %2").arg(kMaxLights + 1).arg(kMaxLights));
    Camera camera = before.camera;
    camera.target = camera.eye;
    QCOMPARE(refusal(f.doc.setCamera(camera)), QStringLiteral("camera eye and target coincide"));

    // An unknown id is named.
    QCOMPARE(refusal(f.doc.removeSurface(SurfaceId{99})), QStringLiteral("no surface with id 99"));
    QCOMPARE(refusal(f.doc.setHidden(SurfaceId{98}, true)),
             QStringLiteral("no surface with id 98"));
    QCOMPARE(refusal(f.doc.setName(SurfaceId{97}, QStringLiteral("x"))),
             QStringLiteral("no surface with id 97"));
    QCOMPARE(refusal(f.doc.setGeometry(SurfaceId{96}, before.surfaces[0].geometry)),
             QStringLiteral("no surface with id 96"));
    QCOMPARE(refusal(f.doc.removeTrimLoop(SurfaceId{1}, TrimLoopId{12})),
             QStringLiteral("no trim loop with id 12 on surface 1"));
    QCOMPARE(refusal(f.doc.placeControlPoints(SurfaceId{1}, {glm::dvec3(0.0)})),
             QStringLiteral("need 16 positions, one per control point of surface 1"));

    // The validators' words, through the mutators.
    QCOMPARE(refusal(f.doc.setName(SurfaceId{1}, QStringLiteral("  "))),
             QStringLiteral("a surface name needs a visible character"));
    QCOMPARE(refusal(f.doc.setWeight(SurfaceId{1}, 5, -1.0)),
             QStringLiteral("weight -1 must be finite and > 0"));
    QCOMPARE(refusal(f.doc.setControlPoints(SurfaceId{1}, {3, 3}, {{0, 0, 0}, {1, 1, 1}})),
             QStringLiteral("control point 3 listed twice"));
    QCOMPARE(refusal(f.doc.setPartitions(SurfaceId{1}, 0, 5)), refusal(checkPartitions(0, 5)));
    QVERIFY(refusal(f.doc.setPartitions(SurfaceId{1}, 0, 5))
                .startsWith(QStringLiteral("partitions 0 x 5")));
    QCOMPARE(refusal(f.doc.insertSurface(-1, makeSurface(20, QStringLiteral("D"), patch()))),
             QStringLiteral("surface index -1 out of range"));
    QCOMPARE(refusal(f.doc.insertSurface(0, makeSurface(2, QStringLiteral("D"), patch()))),
             QStringLiteral("surface id 2 already used"));
    QCOMPARE(refusal(f.doc.insertTrimLoop(SurfaceId{1}, 9,
                                          rectLoop(TrimLoopId{40}, 0.1, 0.1, 0.2, 0.2))),
             QStringLiteral("trim loop index 9 out of range"));
    QCOMPARE(refusal(f.doc.insertTrimLoop(SurfaceId{1}, 0,
                                          rectLoop(TrimLoopId{12}, 0.1, 0.1, 0.2, 0.2))),
             QStringLiteral("trim loop id 12 already used"));
    Document::Lengths lengths = f.doc.lengths();
    lengths.points.pop_back();
    QVERIFY(
        refusal(f.doc.setLengths(lengths))
            .startsWith(QStringLiteral("%1 control points for the ").arg(lengths.points.size())));
    lengths = f.doc.lengths();
    lengths.camera = camera;
    QCOMPARE(refusal(f.doc.setLengths(lengths)), QStringLiteral("camera eye and target coincide"));

    QCOMPARE(f.doc.scene(), before);
    QVERIFY(log.entries.isEmpty());
    // A no-op is no refusal.
    KW_VERIFY_OK(f.doc.setDisplay(before.display));
    KW_VERIFY_OK(f.doc.setHidden(SurfaceId{1}, before.surfaces[0].hidden));
    QVERIFY(log.entries.isEmpty());
}

QTEST_GUILESS_MAIN(TestDocument)
#include "tst_document.moc"
