// The background saved with the project (DisplaySettings::background, docs/FILE_FORMAT.md
// ## Display): written and read back, refused when it is neither "dark" nor "light", named
// to the renderer's options by kw::backgroundNamed. No GL.
#include "expected_test_util.h"
#include "model/document/validation.h"
#include "model/io/knotfile.h"
#include "model/io/objfile.h"
#include "model/nurbs/nurbs_shapes.h"
#include "render/render_types.h"

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTest>

using namespace kw;

class TestBackgroundSetting : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void roundTripsAndRefusesOthers() {
        Scene scene;
        Surface s;
        s.id = SurfaceId{1};
        s.geometry = makeSphere(glm::dvec3(0.0), 1.0);
        scene.surfaces.push_back(s);
        scene.nextId = 2;
        scene.display.partitionMode = QStringLiteral("adaptive");
        scene.display.background = QStringLiteral("light");
        QString error;
        const auto back = sceneFromJson(sceneToJson(scene), QStringLiteral("a.knot"));
        QVERIFY2(back, qPrintable(back.message()));
        QCOMPARE(back->display.background, QStringLiteral("light"));
        RenderOptions o;
        QVERIFY(backgroundNamed(back->display.background, o));
        QVERIFY(o.backgroundTop.has_value());

        // Without one: the dark default, and a file without the member reads as before.
        scene.display.background.clear();
        const QByteArray plain = sceneToJson(scene);
        QVERIFY(!plain.contains("\"background\""));
        QVERIFY(sceneFromJson(plain, QStringLiteral("a.knot")));

        QByteArray bad = sceneToJson(scene);
        bad.replace("\"partitionMode\"", "\"background\": \"purple\", \"partitionMode\"");
        const auto result = sceneFromJson(bad, QStringLiteral("a.knot"));
        QVERIFY(!result);
        QVERIFY2(result.message().startsWith(QStringLiteral("a.knot: $.display.background: ")),
                 qPrintable(result.message()));
        scene.display.background = QStringLiteral("purple");
        QVERIFY(!checkDisplay(scene.display));
        QVERIFY(!checkScene(scene));

        // A background without a partition mode is kept too, in .knot and in OBJ.
        scene.display = DisplaySettings{};
        scene.display.background = QStringLiteral("light");
        const auto alone = sceneFromJson(sceneToJson(scene), QStringLiteral("b.knot"));
        QVERIFY2(alone, qPrintable(alone.message()));
        QCOMPARE(alone->display, scene.display);
        const QString obj = QStringLiteral(KW_TEST_OUTPUT_DIR "/background_alone.obj");
        KW_VERIFY_OK(writeObjFile(obj, scene));
        Scene fromObj;
        ImportReport report;
        KW_VERIFY_OK(readObjFile(obj, fromObj, report));
        QCOMPARE(fromObj.display, scene.display);
    }

    // The draft analysis's pull direction and angle (View > Analysis > Draft Settings): kept
    // alone in .knot and OBJ, defaults written as nothing, zero pull and > 90 degrees refused.
    void draftSettingsRoundTripAndRefuseOthers() {
        Scene scene;
        Surface s;
        s.id = SurfaceId{1};
        s.geometry = makeSphere(glm::dvec3(0.0), 1.0);
        scene.surfaces.push_back(s);
        scene.nextId = 2;
        QVERIFY(!sceneToJson(scene).contains("\"pullDirection\""));
        scene.display.pullDirection = glm::dvec3(1.0, -2.0, 0.5);
        scene.display.draftAngleDegrees = 7.25;
        const QByteArray json = sceneToJson(scene);
        QVERIFY(json.contains("\"pullDirection\"") && json.contains("\"draftAngle\""));
        const auto back = sceneFromJson(json, QStringLiteral("d.knot"));
        QVERIFY2(back, qPrintable(back.message()));
        QCOMPARE(back->display, scene.display);
        const QString obj = QStringLiteral(KW_TEST_OUTPUT_DIR "/draft_alone.obj");
        KW_VERIFY_OK(writeObjFile(obj, scene));
        Scene fromObj;
        ImportReport report;
        KW_VERIFY_OK(readObjFile(obj, fromObj, report));
        QCOMPARE(fromObj.display, scene.display);

        QJsonObject root = QJsonDocument::fromJson(json).object();
        QJsonObject display = root[QStringLiteral("display")].toObject();
        display[QStringLiteral("pullDirection")] = QJsonArray{0, 0, 0};
        root[QStringLiteral("display")] = display;
        const auto zeroPull = sceneFromJson(QJsonDocument(root).toJson(), QStringLiteral("d.knot"));
        QVERIFY(!zeroPull);
        QVERIFY2(zeroPull.message().startsWith(QStringLiteral("d.knot: $.display.pullDirection: ")),
                 qPrintable(zeroPull.message()));
        QByteArray steep = json;
        steep.replace("\"draftAngle\": 7.25", "\"draftAngle\": 95");
        const auto tooSteep = sceneFromJson(steep, QStringLiteral("d.knot"));
        QVERIFY(!tooSteep);
        QVERIFY2(tooSteep.message().startsWith(QStringLiteral("d.knot: $.display.draftAngle: ")),
                 qPrintable(tooSteep.message()));
        scene.display.pullDirection = glm::dvec3(0.0);
        QVERIFY(!checkDisplay(scene.display));
    }
};

QTEST_APPLESS_MAIN(TestBackgroundSetting)
#include "tst_background_setting.moc"
#include "expected_test_util.h"
