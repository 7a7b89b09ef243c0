// The background saved with the project (DisplaySettings::background, docs/FILE_FORMAT.md
// ## Display): written and read back, refused when it is neither "dark" nor "light", named
// to the renderer's options by kw::backgroundNamed. No GL.
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
        const std::optional<Scene> back =
            sceneFromJson(sceneToJson(scene), QStringLiteral("a.knot"), &error);
        QVERIFY2(back, qPrintable(error));
        QCOMPARE(back->display.background, QStringLiteral("light"));
        RenderOptions o;
        QVERIFY(backgroundNamed(back->display.background, o));
        QVERIFY(o.backgroundTop.has_value());

        // Without one: the dark default, and a file without the member reads as before.
        scene.display.background.clear();
        const QByteArray plain = sceneToJson(scene);
        QVERIFY(!plain.contains("\"background\""));
        QVERIFY(sceneFromJson(plain, QStringLiteral("a.knot"), &error));

        QByteArray bad = sceneToJson(scene);
        bad.replace("\"partitionMode\"", "\"background\": \"purple\", \"partitionMode\"");
        QVERIFY(!sceneFromJson(bad, QStringLiteral("a.knot"), &error));
        QVERIFY2(error.startsWith(QStringLiteral("a.knot: $.display.background: ")),
                 qPrintable(error));
        scene.display.background = QStringLiteral("purple");
        QVERIFY(!displayError(scene.display).isEmpty());
        QVERIFY(!sceneError(scene).isEmpty());

        // A background without a partition mode is kept too, in .knot and in OBJ.
        scene.display = DisplaySettings{};
        scene.display.background = QStringLiteral("light");
        const std::optional<Scene> alone =
            sceneFromJson(sceneToJson(scene), QStringLiteral("b.knot"), &error);
        QVERIFY2(alone, qPrintable(error));
        QCOMPARE(alone->display, scene.display);
        const QString obj = QStringLiteral(KW_TEST_OUTPUT_DIR "/background_alone.obj");
        QVERIFY2(writeObjFile(obj, scene, error), qPrintable(error));
        Scene fromObj;
        ImportReport report;
        QVERIFY2(readObjFile(obj, fromObj, report, error), qPrintable(error));
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
        QString error;
        const QByteArray json = sceneToJson(scene);
        QVERIFY(json.contains("\"pullDirection\"") && json.contains("\"draftAngle\""));
        const std::optional<Scene> back = sceneFromJson(json, QStringLiteral("d.knot"), &error);
        QVERIFY2(back, qPrintable(error));
        QCOMPARE(back->display, scene.display);
        const QString obj = QStringLiteral(KW_TEST_OUTPUT_DIR "/draft_alone.obj");
        QVERIFY2(writeObjFile(obj, scene, error), qPrintable(error));
        Scene fromObj;
        ImportReport report;
        QVERIFY2(readObjFile(obj, fromObj, report, error), qPrintable(error));
        QCOMPARE(fromObj.display, scene.display);

        QJsonObject root = QJsonDocument::fromJson(json).object();
        QJsonObject display = root[QStringLiteral("display")].toObject();
        display[QStringLiteral("pullDirection")] = QJsonArray{0, 0, 0};
        root[QStringLiteral("display")] = display;
        QVERIFY(!sceneFromJson(QJsonDocument(root).toJson(), QStringLiteral("d.knot"), &error));
        QVERIFY2(error.startsWith(QStringLiteral("d.knot: $.display.pullDirection: ")),
                 qPrintable(error));
        QByteArray steep = json;
        steep.replace("\"draftAngle\": 7.25", "\"draftAngle\": 95");
        QVERIFY(!sceneFromJson(steep, QStringLiteral("d.knot"), &error));
        QVERIFY2(error.startsWith(QStringLiteral("d.knot: $.display.draftAngle: ")),
                 qPrintable(error));
        scene.display.pullDirection = glm::dvec3(0.0);
        QVERIFY(!displayError(scene.display).isEmpty());
    }
};

QTEST_APPLESS_MAIN(TestBackgroundSetting)
#include "tst_background_setting.moc"
