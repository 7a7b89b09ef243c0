// `knotwork info FILE --json` reports the model's area, enclosed volume (null without a closed
// solid) and bounding box, and each surface's type, area and bounds.
#include "knotwork_process.h"

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTest>
#include <cmath>
#include <numbers>

class TestInfoProperties : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void sphere();
    void closedSolid();
};

namespace {

QJsonObject info(const QString& file) {
    const Run r = knotwork({QStringLiteral("info"), file, QStringLiteral("--json")});
    if (r.code != 0)
        qWarning("%s", qPrintable(r.err));
    return QJsonDocument::fromJson(r.out.toUtf8()).object();
}

} // namespace

void TestInfoProperties::sphere() {
    const QJsonObject o = info(QStringLiteral(KW_SAMPLES_DIR "/sphere.knot"));
    QVERIFY(!o.isEmpty());
    const double area = o.value(QStringLiteral("area")).toDouble();
    QVERIFY2(std::abs(area - 4 * std::numbers::pi) <= 1e-7 * 4 * std::numbers::pi,
             qPrintable(QString::number(area, 'g', 17)));
    QVERIFY(o.contains(QStringLiteral("volume")));
    QVERIFY(o.value(QStringLiteral("volume")).isNull());
    const QJsonObject box = o.value(QStringLiteral("bbox")).toObject();
    for (int k = 0; k < 3; ++k) {
        QVERIFY(std::abs(box[QStringLiteral("min")].toArray()[k].toDouble() + 1.0) < 1e-9);
        QVERIFY(std::abs(box[QStringLiteral("max")].toArray()[k].toDouble() - 1.0) < 1e-9);
    }
    const QJsonObject s = o.value(QStringLiteral("surfaces")).toArray()[0].toObject();
    QCOMPARE(s.value(QStringLiteral("type")).toString(), QStringLiteral("sphere"));
    QVERIFY(std::abs(s.value(QStringLiteral("area")).toDouble() - area) < 1e-12);
}

// A closed B-rep solid: its volume inside its box, equal to BRepGProp's (computed once with
// OpenCASCADE 7.6, tst_mass_occt checks every part live), and the text output says the same.
void TestInfoProperties::closedSolid() {
#ifndef KW_TEST_HAVE_OCCT
    QSKIP("built without OpenCASCADE: no B-rep to read");
#endif
    const QString file = QStringLiteral(KW_TEST_DATA_DIR "/Pump_Nut.brep");
    const QJsonObject o = info(file);
    QVERIFY(!o.isEmpty());
    QVERIFY(o.value(QStringLiteral("volume")).isDouble());
    const double volume = o.value(QStringLiteral("volume")).toDouble();
    const QJsonObject box = o.value(QStringLiteral("bbox")).toObject();
    double boxVolume = 1.0;
    for (int k = 0; k < 3; ++k)
        boxVolume *= box[QStringLiteral("max")].toArray()[k].toDouble() -
                     box[QStringLiteral("min")].toArray()[k].toDouble();
    QVERIFY2(volume > 0.0 && volume < boxVolume, qPrintable(QString::number(volume)));
    QVERIFY2(std::abs(volume - 24130.3105554028) < 1e-6 * 24130.3105554028,
             qPrintable(QString::number(volume, 'g', 15)));
    const Run text = knotwork({QStringLiteral("info"), file});
    QCOMPARE(text.code, 0);
    QVERIFY2(text.out.contains(QStringLiteral("volume: 24130.31055")), qPrintable(text.out));
}

QTEST_GUILESS_MAIN(TestInfoProperties)
#include "tst_info_properties.moc"
