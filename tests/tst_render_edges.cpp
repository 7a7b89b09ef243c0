// GL test: the GPU frame measured against the CPU reference (knotwork render --reference and
// --edge-report, render/edge_metrics.h). Fine partitions agree with the reference outside the
// edge band; the paper's coarse base polygon shows a silhouette error the metrics catch.
#include "knotwork_process.h"

#include <QDir>
#include <QFile>
#include <QJsonDocument>
#include <QJsonObject>
#include <QRegularExpression>
#include <QTest>

namespace {

QString sample(const char* name) {
    return QStringLiteral(KW_SAMPLES_DIR "/%1.knot").arg(QString::fromLatin1(name));
}

QString output(const QString& name) {
    QDir(QStringLiteral(KW_TEST_OUTPUT_DIR)).mkpath(QStringLiteral("."));
    return QStringLiteral(KW_TEST_OUTPUT_DIR "/") + name;
}

/// Runs render --edge-report on a sample at `partitions` (the minimum in adaptive mode) and
/// returns the report; `stdoutText` gets what render printed.
QJsonObject edgeReport(const char* name, const QString& partitions,
                       const QString& mode = QStringLiteral("uniform"),
                       QString* stdoutText = nullptr) {
    const QString json =
        output(QStringLiteral("edges_%1_%2_%3.json").arg(QLatin1String(name), partitions, mode));
    QFile::remove(json);
    const Run r =
        knotwork({QStringLiteral("render"), sample(name), QStringLiteral("-o"),
                  output(QStringLiteral("edges_%1.png").arg(name)), QStringLiteral("--size"),
                  QStringLiteral("256x192"), QStringLiteral("--partitions"), partitions,
                  QStringLiteral("--partition-mode"), mode, QStringLiteral("--edge-report"), json});
    if (r.code != 0)
        qWarning("%s", qPrintable(r.err));
    if (stdoutText)
        *stdoutText = r.out;
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

    // Adaptive partitions from a 1 x 1 minimum (issue 10 item 2): the guaranteed 0.5 px bound
    // puts the silhouette where the reference has it (the metric counts whole pixels, as for
    // the fine grid above) and the normals as close as 96 x 96, with far fewer cells.
    void adaptiveFromOneCellAgreesWithTheReference_data() {
        finePartitionsAgreeWithTheReference_data();
    }
    void adaptiveFromOneCellAgreesWithTheReference() {
        QFETCH(QString, name);
        QString out;
        const QJsonObject adaptive =
            edgeReport(qPrintable(name), QStringLiteral("1"), QStringLiteral("adaptive"), &out);
        QVERIFY(!adaptive.isEmpty());
        const QRegularExpression line(
            QStringLiteral("adaptive partitions: (\\d+) cells, screen bound ([0-9.]+) px"));
        const QRegularExpressionMatch m = line.match(out);
        QVERIFY2(m.hasMatch(), qPrintable(out));
        const qint64 cells = m.captured(1).toLongLong();
        const double bound = m.captured(2).toDouble();
        qInfo("%s adaptive from 1: %lld cells, bound %.3f px, silhouette max %.2f px, normal "
              "p99 %.4f deg",
              qPrintable(name), cells, bound,
              adaptive[QStringLiteral("silhouetteMaxPixels")].toDouble(),
              adaptive[QStringLiteral("normalP99Degrees")].toDouble());
        QVERIFY(bound <= 0.5);
        QVERIFY(cells > 0);
        QVERIFY(adaptive[QStringLiteral("silhouetteMaxPixels")].toDouble() <= 1.0);
        QCOMPARE(adaptive[QStringLiteral("crackPixelsCoveredInReference")].toDouble(), 0.0);
        // The normal shown is exact at the polygon's (u, v), which lies within the tolerance
        // of the point truly under the pixel: the error scales with the tolerance (teapot p99
        // 1.08 deg at 0.5 px, 0.55 at 0.25, 0.22 at 0.1; measured 2026-11-22).
        QVERIFY(adaptive[QStringLiteral("normalP99Degrees")].toDouble() < 1.5);
        // Fewer cells than the uniform 96 x 96 grid per surface that reaches the same.
        const QString uniformOut =
            knotwork({QStringLiteral("render"), sample(qPrintable(name)), QStringLiteral("-o"),
                      output(QStringLiteral("edges_u96.png")), QStringLiteral("--size"),
                      QStringLiteral("256x192"), QStringLiteral("--partitions"),
                      QStringLiteral("96"), QStringLiteral("--partition-mode"),
                      QStringLiteral("uniform")})
                .out;
        const QRegularExpressionMatch u =
            QRegularExpression(QStringLiteral("uniform partitions: (\\d+) cells"))
                .match(uniformOut);
        QVERIFY2(u.hasMatch(), qPrintable(uniformOut));
        QVERIFY(cells < u.captured(1).toLongLong());
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
