// Section planes in the project file and the scene's validation: every field reads back, a file
// of an older minor version (no sections) reads with none, a zero normal or too many planes are
// refused with the JSON path, and validation names the plane.
#include "model/document/validation.h"
#include "model/io/knotfile.h"
#include "model_fixtures.h"
#include "tests/support/expected_test_util.h"

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QtTest>

using namespace kw;
using kw::test::threeSurfaceScene;

class TestSectionFile : public QObject {
    Q_OBJECT

    static Scene withSections() {
        Scene scene = threeSurfaceScene();
        scene.display.sections = {
            SectionPlane{glm::dvec3(0.1, -0.25, 1.0 / 3.0), glm::dvec3(0.0, 0.6, 0.8), false},
            SectionPlane{glm::dvec3(2.0, 0.0, 0.0), glm::dvec3(-1.0, 1e-7, 0.0), true}};
        scene.display.sectionCaps = false;
        return scene;
    }

private Q_SLOTS:
    void roundTrip() {
        const Scene scene = withSections();
        KW_VERIFY_OK(checkScene(scene));
        QString error;
        const auto back = sceneFromJson(sceneToJson(scene), QStringLiteral("mem"));
        QVERIFY2(back, qPrintable(back.message()));
        QVERIFY(back->display == scene.display);
        QCOMPARE(QJsonDocument::fromJson(sceneToJson(scene))
                     .object()[QStringLiteral("version")]
                     .toString(),
                 QStringLiteral("%1.%2").arg(kKnotFormatMajor).arg(kKnotFormatMinor));
        // Sections alone (no partition mode) are enough for a display object.
        Scene alone = threeSurfaceScene();
        alone.display.sections = {SectionPlane{}};
        const auto aloneBack = sceneFromJson(sceneToJson(alone), QStringLiteral("mem"));
        QVERIFY2(aloneBack, qPrintable(aloneBack.message()));
        QVERIFY(aloneBack->display == alone.display);
        QVERIFY(aloneBack->display.sectionCaps);
    }

    void olderFileReadsWithNone() {
        QJsonObject root = QJsonDocument::fromJson(sceneToJson(threeSurfaceScene())).object();
        root.insert(QStringLiteral("version"), QStringLiteral("1.3"));
        root.insert(QStringLiteral("display"),
                    QJsonObject{{QStringLiteral("partitionMode"), QStringLiteral("uniform")}});
        const auto back = sceneFromJson(QJsonDocument(root).toJson(), QStringLiteral("old.knot"));
        QVERIFY2(back, qPrintable(back.message()));
        QVERIFY(back->display.sections.empty());
        QVERIFY(back->display.sectionCaps);
    }

    void badPlanesRefused() {
        QJsonObject root = QJsonDocument::fromJson(sceneToJson(withSections())).object();
        QJsonObject display = root[QStringLiteral("display")].toObject();
        QJsonArray planes = display[QStringLiteral("sections")].toArray();
        QJsonObject zero = planes[1].toObject();
        zero.insert(QStringLiteral("normal"), QJsonArray{0.0, 0.0, 0.0});
        planes[1] = zero;
        display.insert(QStringLiteral("sections"), planes);
        root.insert(QStringLiteral("display"), display);
        const auto result = sceneFromJson(QJsonDocument(root).toJson(), QStringLiteral("bad.knot"));
        QVERIFY(!result);
        QVERIFY2(result.message().startsWith(
                     QStringLiteral("bad.knot: $.display.sections[1].normal: ")) &&
                     result.message().contains(QStringLiteral("zero length")) &&
                     !result.message().contains('\n'),
                 qPrintable(result.message()));
        planes[1] = planes[0];
        planes.append(planes[0]);
        planes.append(planes[0]);
        display.insert(QStringLiteral("sections"), planes);
        root.insert(QStringLiteral("display"), display);
        const auto failed = sceneFromJson(QJsonDocument(root).toJson(), QStringLiteral("bad.knot"));
        QVERIFY(!failed);
        QVERIFY2(failed.message().contains(QStringLiteral("$.display.sections")) &&
                     failed.message().contains(QStringLiteral("4 section planes")),
                 qPrintable(failed.message()));

        Scene scene = withSections();
        scene.display.sections[1].normal = glm::dvec3(0.0);
        QVERIFY2(checkScene(scene).message().contains(QStringLiteral("section 2")),
                 qPrintable(checkScene(scene).message()));
        scene.display.sections[1].normal = glm::dvec3(std::nan(""), 0.0, 1.0);
        QVERIFY(!checkScene(scene));
    }

    void removedSide() {
        const SectionPlane p{glm::dvec3(1.0), glm::dvec3(0.0, 0.0, 2.0), false};
        QCOMPARE(p.removedSide(), glm::dvec3(0.0, 0.0, 1.0));
        SectionPlane f = p;
        f.flip = true;
        QCOMPARE(f.removedSide(), glm::dvec3(0.0, 0.0, -1.0));
    }
};

QTEST_APPLESS_MAIN(TestSectionFile)
#include "tst_section_file.moc"
