// GL test: the GPU frame measured against the CPU reference (knotwork render --reference and
// --edge-report, render/edge_metrics.h). Fine partitions agree with the reference outside the
// edge band; the paper's coarse base polygon shows a silhouette error the metrics catch.
#include "knotwork_process.h"

#include <QDir>
#include <QFile>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTest>

namespace {

QString sample(const char* name) {
    return QStringLiteral(KW_SAMPLES_DIR "/%1.knot").arg(QString::fromLatin1(name));
}

QString output(const QString& name) {
    QDir(QStringLiteral(KW_TEST_OUTPUT_DIR)).mkpath(QStringLiteral("."));
    return QStringLiteral(KW_TEST_OUTPUT_DIR "/") + name;
}

/// Runs render --edge-report on a sample at `partitions` and returns the report.
QJsonObject edgeReport(const char* name, const QString& partitions) {
    const QString json = output(QStringLiteral("edges_%1_%2.json").arg(name, partitions));
    QFile::remove(json);
    const Run r =
        knotwork({QStringLiteral("render"), sample(name), QStringLiteral("-o"),
                  output(QStringLiteral("edges_%1.png").arg(name)), QStringLiteral("--size"),
                  QStringLiteral("256x192"), QStringLiteral("--partitions"), partitions,
                  QStringLiteral("--edge-report"), json});
    if (r.code != 0)
        qWarning("%s", qPrintable(r.err));
    QFile f(json);
    if (!f.open(QIODevice::ReadOnly))
        return {};
    return QJsonDocument::fromJson(f.readAll()).object();
}

} // namespace

class TestRenderEdges : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void referenceWritesImageAndAov() {
        const QString png = output(QStringLiteral("edges_ref_torus.png"));
        const QString exr = output(QStringLiteral("edges_ref_torus.exr"));
        QFile::remove(png);
        QFile::remove(exr);
        const Run r = knotwork({QStringLiteral("render"), sample("torus"), QStringLiteral("-o"),
                                png, QStringLiteral("--size"), QStringLiteral("160x120"),
                                QStringLiteral("--reference"), QStringLiteral("--aov"), exr});
        QVERIFY2(r.code == 0, qPrintable(r.err));
        QVERIFY2(r.out.contains(QStringLiteral("reference: ")), qPrintable(r.out));
        QVERIFY(QFile::exists(png));
        QVERIFY(QFile::exists(exr));
    }

    void finePartitionsAgreeWithTheReference_data() {
        QTest::addColumn<QString>("name");
        QTest::newRow("sphere") << QStringLiteral("sphere");
        QTest::newRow("torus") << QStringLiteral("torus");
        QTest::newRow("teapot") << QStringLiteral("teapot");
    }
    void finePartitionsAgreeWithTheReference() {
        QFETCH(QString, name);
        const QJsonObject fine = edgeReport(qPrintable(name), QStringLiteral("96"));
        QVERIFY(!fine.isEmpty());
        qInfo("%s at 96: silhouette max %.2f px, id %g, normal p99 %.4f max %.3f deg",
              qPrintable(name), fine[QStringLiteral("silhouetteMaxPixels")].toDouble(),
              fine[QStringLiteral("idDisagreements")].toDouble(),
              fine[QStringLiteral("normalP99Degrees")].toDouble(),
              fine[QStringLiteral("normalMaxDegrees")].toDouble());
        QVERIFY(fine[QStringLiteral("referenceCovered")].toDouble() > 3000);
        QVERIFY(fine[QStringLiteral("silhouetteMaxPixels")].toDouble() <= 1.5);
        // Narrow true gaps (the torus hole's rim, the teapot's handle) are not cracks: count
        // only the gap pixels the reference covers.
        QCOMPARE(fine[QStringLiteral("crackPixelsCoveredInReference")].toDouble(), 0.0);
        QVERIFY(fine[QStringLiteral("normalP99Degrees")].toDouble() < 0.5);
        // The paper's coarse grid: the metrics see the polygonal silhouette.
        const QJsonObject coarse = edgeReport(qPrintable(name), QStringLiteral("2"));
        qInfo("%s at 2: silhouette max %.2f px, normal p99 %.3f deg", qPrintable(name),
              coarse[QStringLiteral("silhouetteMaxPixels")].toDouble(),
              coarse[QStringLiteral("normalP99Degrees")].toDouble());
        QVERIFY(coarse[QStringLiteral("silhouetteMaxPixels")].toDouble() > 2.0);
        QVERIFY(coarse[QStringLiteral("normalP99Degrees")].toDouble() >
                fine[QStringLiteral("normalP99Degrees")].toDouble());
    }

    void referenceAndReportExcludeEachOther() {
        const Run r = knotwork({QStringLiteral("render"), sample("sphere"), QStringLiteral("-o"),
                                output(QStringLiteral("x.png")), QStringLiteral("--reference"),
                                QStringLiteral("--edge-report"), QStringLiteral("-")});
        QCOMPARE(r.code, 2);
        QVERIFY(r.err.contains(QStringLiteral("exclude")));
    }
};

QTEST_GUILESS_MAIN(TestRenderEdges)
#include "tst_render_edges.moc"
