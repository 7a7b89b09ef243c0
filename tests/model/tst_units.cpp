// The document's length unit (model/document/units.h): kept by .knot (1.4) and the CAD hand-over,
// old files read as millimetres, bad units refused with their place; converted or relabelled by one
// undoable command that puts every value back bit for bit.
#include "model/cad/handover.h"
#include "model/document/document.h"
#include "model/io/knotfile.h"
#include "model/nurbs/nurbs_shapes.h"
#include "tests/support/expected_test_util.h"
#include "ui/edit/modelcommands.h"

#include <QUndoStack>
#include <QtTest>

using namespace kw;

namespace {

Scene sphereScene() {
    Scene s;
    Surface sphere;
    sphere.id = SurfaceId{1};
    sphere.name = QStringLiteral("sphere");
    sphere.geometry = makeSphere({1.0, 2.0, 3.0}, 2.0);
    s.surfaces.push_back(sphere);
    s.nextId = 2;
    return s;
}

} // namespace

class TestUnits : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void keysRoundTrip() {
        for (LengthUnit u : kLengthUnits) {
            QCOMPARE(lengthUnitFromKey(lengthUnitKey(u)), std::optional<LengthUnit>(u));
            QCOMPARE(lengthUnitFromIgesFlag(igesUnitFlag(u)), std::optional<LengthUnit>(u));
            QVERIFY(millimetresPer(u) > 0);
        }
        QCOMPARE(millimetresPer(LengthUnit::Inch), 25.4);
        QCOMPARE(lengthUnitFromKey(QStringLiteral("IN")), std::optional(LengthUnit::Inch));
        QVERIFY(!lengthUnitFromKey(QStringLiteral("furlong")));
        QVERIFY(!lengthUnitFromIgesFlag(3)); // a unit named in the file, not a flag
    }

    void knotFileKeepsTheUnit() {
        Scene s = sphereScene();
        // Millimetres are the default: no member, and the version is this build's (1.4 added
        // the unit).
        const QJsonObject mm = QJsonDocument::fromJson(sceneToJson(s)).object();
        QVERIFY(!mm.contains(QStringLiteral("unit")));
        QCOMPARE(mm.value(QStringLiteral("version")).toString(),
                 QStringLiteral("%1.%2").arg(kKnotFormatMajor).arg(kKnotFormatMinor));
        QVERIFY(kKnotFormatMajor == 1 && kKnotFormatMinor >= 4);
        s.unit = LengthUnit::Inch;
        const QByteArray json = sceneToJson(s);
        QCOMPARE(QJsonDocument::fromJson(json).object().value(QStringLiteral("unit")).toString(),
                 QStringLiteral("in"));
        const auto back = sceneFromJson(json, QStringLiteral("in.knot"));
        QVERIFY2(back, qPrintable(back.message()));
        QCOMPARE(back->unit, LengthUnit::Inch);
        QVERIFY(*back == s);
    }

    void olderFilesAreMillimetres() {
        QJsonObject o = QJsonDocument::fromJson(sceneToJson(sphereScene())).object();
        o.insert(QStringLiteral("version"), QStringLiteral("1.3"));
        const auto back = sceneFromJson(QJsonDocument(o).toJson(), QStringLiteral("old.knot"));
        QVERIFY2(back, qPrintable(back.message()));
        QCOMPARE(back->unit, LengthUnit::Millimetre);
    }

    void badUnitRefused_data() {
        QTest::addColumn<QJsonValue>("value");
        QTest::newRow("unknown") << QJsonValue(QStringLiteral("furlong"));
        QTest::newRow("not the key's case") << QJsonValue(QStringLiteral("IN"));
        QTest::newRow("number") << QJsonValue(25.4);
    }
    void badUnitRefused() {
        QFETCH(QJsonValue, value);
        QJsonObject o = QJsonDocument::fromJson(sceneToJson(sphereScene())).object();
        o.insert(QStringLiteral("unit"), value);
        const auto result = sceneFromJson(QJsonDocument(o).toJson(), QStringLiteral("bad.knot"));
        QVERIFY(!result);
        QVERIFY2(result.message().startsWith(QStringLiteral("bad.knot: $.unit: ")),
                 qPrintable(result.message()));
        QVERIFY(!result.message().contains(QLatin1Char('\n')));
    }

    void handoverKeepsTheUnit() {
        ImportResult r;
        r.scene = sphereScene();
        r.scene.unit = LengthUnit::Foot;
        r.sourceFaces = {1};
        const auto back = decodeImportHandover(encodeImportHandover(r));
        QVERIFY2(back, qPrintable(back.message()));
        QCOMPARE(back->scene.unit, LengthUnit::Foot);
    }

    // Convert keeps the size (every length scaled, the camera too), relabel keeps the numbers;
    // each is one step whose undo restores every value bit for bit.
    void convertAndRelabelUndo() {
        Document doc;
        Scene s = sphereScene();
        s.camera.authored = true;
        s.camera.eye = {10, -20, 5};
        QVERIFY(doc.resetScene(s));
        QString error;
        QUndoStack stack;
        QSignalSpy unitSpy(&doc, &Document::unitChanged);
        const Document::Lengths before = doc.lengths();

        QVERIFY(pushCommand(&stack, SetUnits::create(&doc, LengthUnit::Inch, true)));
        QCOMPARE(doc.scene().unit, LengthUnit::Inch);
        QCOMPARE(unitSpy.count(), 1);
        const double factor = 1.0 / 25.4;
        QCOMPARE(doc.scene().surfaces[0].geometry.points[3], before.points[3] * factor);
        QCOMPARE(doc.scene().camera.eye, before.camera.eye * factor);

        stack.undo();
        QVERIFY(doc.lengths() == before); // bit for bit, not scaled back
        QCOMPARE(doc.scene().unit, LengthUnit::Millimetre);

        QVERIFY(pushCommand(&stack, SetUnits::create(&doc, LengthUnit::Metre, false)));
        QCOMPARE(doc.scene().unit, LengthUnit::Metre);
        QCOMPARE(doc.lengths().points, before.points);
        stack.undo();
        QVERIFY(doc.lengths() == before);

        // Nothing to change: refused with a reason, nothing pushed.
        error = kwtest::refusal(SetUnits::create(&doc, LengthUnit::Millimetre, true));
        QVERIFY(!error.isNull());
        QVERIFY(error.contains(QStringLiteral("already in mm")));
        // Lengths for another scene (other counts) are refused, changing nothing.
        Document::Lengths wrong = before;
        wrong.points.pop_back();
        QVERIFY(!doc.setLengths(wrong));
        QVERIFY(doc.lengths() == before);
    }
};

QTEST_MAIN(TestUnits)
#include "tst_units.moc"
