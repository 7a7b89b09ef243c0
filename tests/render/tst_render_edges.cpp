// GL test: the GPU frame measured against the CPU reference (knotwork render --reference and
// --edge-report, render/edge_metrics.h). Fine partitions agree with the reference outside the
// edge band; the paper's coarse base polygon shows a silhouette error the metrics catch.
#include "knotwork_process.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QImage>
#include <QJsonDocument>
#include <QJsonObject>
#include <QRegularExpression>
#include <QSet>
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

/// tests/data/NAME.brep converted to a project in the test output (once per run).
QString convertedPart(const char* name) {
    const QString knot = output(QStringLiteral("%1.knot").arg(QLatin1String(name)));
    // Converted once per run, never reused from an earlier build: a file an older importer
    // wrote lacks what this one keeps (the analytic forms), and would be drawn another way.
    static QSet<QString> converted;
    if (!converted.contains(knot)) {
        converted.insert(knot);
        const Run r =
            knotwork({QStringLiteral("convert"),
                      QStringLiteral(KW_TEST_DATA_DIR "/%1.brep").arg(QLatin1String(name)), knot});
        if (r.code != 0)
            qWarning("%s", qPrintable(r.err));
    }
    return knot;
}

/// render --edge-report of `knot` at `side` x `side` in adaptive mode (the default), the fitted
/// view moved by --zoom `zoom` ("1" keeps it).
QJsonObject partReport(const QString& knot, const QString& zoom, int side = 256) {
    const QString json =
        output(QStringLiteral("edges_part_%1_%2_%3.json")
                   .arg(QFileInfo(knot).baseName(), zoom)
                   .arg(side)
                   .replace(QRegularExpression(QStringLiteral("[@,]")), QStringLiteral("_")));
    QFile::remove(json);
    const Run r = knotwork({QStringLiteral("render"), knot, QStringLiteral("-o"),
                            output(QStringLiteral("edges_part.png")), QStringLiteral("--size"),
                            QStringLiteral("%1x%1").arg(side), QStringLiteral("--zoom"), zoom,
                            QStringLiteral("--edge-report"), json});
    if (r.code != 0)
        qWarning("%s", qPrintable(r.err));
    QFile f(json);
    if (!f.open(QIODevice::ReadOnly))
        return {};
    return QJsonDocument::fromJson(f.readAll()).object();
}

/// render --edge-report of sample `name` at 256 x 192 from 1 x 1 partitions at a coarse 2 px
/// tolerance (the polygon's silhouette up to 2 px inside the exact one), with the silhouette
/// fins on or off (KW_FINS).
QJsonObject coarseReport(const QString& name, bool fins) {
    const QString json = output(QStringLiteral("edges_coarse_%1_%2.json").arg(name).arg(fins));
    QFile::remove(json);
    const Run r = knotwork(
        {QStringLiteral("render"), sample(qPrintable(name)), QStringLiteral("-o"),
         output(QStringLiteral("edges_coarse_%1_%2.png").arg(name).arg(fins)),
         QStringLiteral("--size"), QStringLiteral("256x192"), QStringLiteral("--partitions"),
         QStringLiteral("1"), QStringLiteral("--pixel-tolerance"), QStringLiteral("2"),
         QStringLiteral("--edge-report"), json},
        environmentWith(QStringLiteral("KW_FINS"),
                        fins ? QStringLiteral("1") : QStringLiteral("0")));
    if (r.code != 0)
        qWarning("%s", qPrintable(r.err));
    QFile f(json);
    return f.open(QIODevice::ReadOnly) ? QJsonDocument::fromJson(f.readAll()).object()
                                       : QJsonObject{};
}

/// render of `knot` at `side` x `side` (fitted view) with `extra` arguments; the image, or a null
/// one when the run failed.
QImage renderPart(const QString& knot, int side, const QString& tag, const QStringList& extra) {
    const QString png = output(QStringLiteral("aa_%1.png").arg(tag));
    QFile::remove(png);
    const Run r =
        knotwork(QStringList{QStringLiteral("render"), knot, QStringLiteral("-o"), png,
                             QStringLiteral("--size"), QStringLiteral("%1x%1").arg(side)} +
                 extra);
    if (r.code != 0)
        qWarning("%s", qPrintable(r.err));
    return QImage(png).convertToFormat(QImage::Format_RGB32);
}

/// Seams of an anti-aliased frame against the truth (the aliased frame at 4 x the size,
/// box-filtered: 16 samples per pixel): the pixels at least 2 px from the background in the
/// aliased frame (seams and inner outlines, not the part's outline) whose anti-aliased value is
/// darker than the truth's by more than 8 levels (mean of R, G, B), and the mean absolute
/// difference over them.
struct SeamCount {
    int interior = 0, darker = 0;
    double meanDifference = 0.0;
};
SeamCount seams(const QImage& aliased, const QImage& big, const QImage& aa) {
    SeamCount c;
    const int w = aliased.width(), h = aliased.height();
    const QRgb background = aliased.pixel(0, 0);
    double sum = 0.0;
    for (int y = 2; y < h - 2; ++y)
        for (int x = 2; x < w - 2; ++x) {
            bool interior = true;
            for (int dy = -2; dy <= 2 && interior; ++dy)
                for (int dx = -2; dx <= 2; ++dx)
                    if (aliased.pixel(x + dx, y + dy) == background) {
                        interior = false;
                        break;
                    }
            if (!interior)
                continue;
            double truth = 0.0;
            for (int j = 0; j < 4; ++j)
                for (int i = 0; i < 4; ++i) {
                    const QRgb p = big.pixel(4 * x + i, 4 * y + j);
                    truth += (qRed(p) + qGreen(p) + qBlue(p)) / 3.0;
                }
            truth /= 16.0;
            const QRgb p = aa.pixel(x, y);
            const double value = (qRed(p) + qGreen(p) + qBlue(p)) / 3.0;
            ++c.interior;
            sum += std::abs(value - truth);
            c.darker += value < truth - 8.0;
        }
    c.meanDifference = c.interior > 0 ? sum / c.interior : 0.0;
    return c;
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

    // Adaptive partitions from a 1 x 1 minimum: the guaranteed 0.5 px bound
    // puts the silhouette where the reference has it (the metric counts whole pixels, as for
    // the fine grid above) and the normals as close as 96 x 96, with far fewer cells.
    // Silhouette fins (kw::buildFins): at a coarse 2 px tolerance the polygon's silhouette
    // lies inside the exact one by up to 2 px, and the pixel centres between them are covered
    // by the fins' per-pixel solve alone; KW_FINS=0 shows what they cover.
    void finsCoverTheSilhouette_data() { finePartitionsAgreeWithTheReference_data(); }
    void finsCoverTheSilhouette() {
        QFETCH(QString, name);
        // Pixels the reference covers and the frame does not: of the mismatched ones, those
        // not drawn beyond the reference's coverage.
        const auto missed = [](const QJsonObject& o) {
            const double extra = o[QStringLiteral("covered")].toDouble() -
                                 o[QStringLiteral("referenceCovered")].toDouble();
            return (o[QStringLiteral("silhouetteMismatched")].toDouble() - extra) / 2.0;
        };
        const QJsonObject with = coarseReport(name, true), without = coarseReport(name, false);
        QVERIFY(!with.isEmpty() && !without.isEmpty());
        qInfo("%s at 2 px: missed pixels %g with fins, %g without; silhouette max %g px, "
              "mismatched %g",
              qPrintable(name), missed(with), missed(without),
              with[QStringLiteral("silhouetteMaxPixels")].toDouble(),
              with[QStringLiteral("silhouetteMismatched")].toDouble());
        // Measured: sphere 43 -> 1, torus 65 -> 1, teapot 104 -> 5 (where the silhouette runs
        // along a patch's edge, the skirt's job; docs/RENDERING.md "Silhouette fins").
        QVERIFY(missed(without) >= 10.0);
        QVERIFY(missed(with) <= std::max(2.0, 0.1 * missed(without)));
        // (At this coarse tolerance a notch can remain where a patch edge runs along the
        // silhouette: measured 1 on the teapot, 4 without fins; 0 at the default 0.5 px,
        // adaptiveFromOneCellAgreesWithTheReference.)
        const QString crack = QStringLiteral("crackPixelsCoveredInReference");
        QVERIFY(with[crack].toDouble() <= std::min(1.0, without[crack].toDouble()));
        QVERIFY(with[QStringLiteral("silhouetteMaxPixels")].toDouble() <= 1.0);
        // What the fins add beyond the reference lies within 0.002 px of its silhouette (the
        // solve's acceptance), or within the skirts' reach past a seam.
        QVERIFY(with[QStringLiteral("silhouetteMismatched")].toDouble() <=
                0.25 * without[QStringLiteral("silhouetteMismatched")].toDouble() + 4.0);
    }

    // Near a fold the pixel's ray meets the surface twice; the point shown must be on the
    // sheet in front. The skirts' and fins' solve (kwSkirtPoint) and the exact pass (a point
    // facing the eye against its triangle's winding, mirrored about the fold) see to it;
    // before, the hidden sheet showed as black specks along silhouettes. Same settings as
    // above (the polygon's silhouette up to 2 px inside the exact one). Measured, pixels
    // showing the hidden sheet with / without fins: sphere 23 / 12 -> 0 / 0, torus 24 / 3 ->
    // 2 / 1, teapot 78 / 25 -> 1 / 0; what is left lies in the edge band where a fold meets a
    // patch's edge or the solve found no second meeting.
    void silhouettesShowTheFrontSheet_data() { finePartitionsAgreeWithTheReference_data(); }
    void silhouettesShowTheFrontSheet() {
        QFETCH(QString, name);
        for (const bool fins : {true, false}) {
            const QJsonObject o = coarseReport(name, fins);
            QVERIFY(o.contains(QStringLiteral("facingDisagreements")));
            const double facing = o[QStringLiteral("facingDisagreements")].toDouble();
            qInfo("%s %s fins: %g pixels show the hidden sheet", qPrintable(name),
                  fins ? "with" : "without", facing);
            QVERIFY(facing <= 2.0);
        }
    }

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
        // The polygon's (u, v) lies within the tolerance of the point truly under the pixel
        // and one Newton step per pixel moves it there (exact_surface.frag, kwOntoRay): the
        // normal and depth shown are the exact ones (targets: p99 <= 0.1 deg,
        // max <= 1 deg). Without the step the teapot showed p99 1.08 deg at this size.
        QVERIFY(adaptive[QStringLiteral("normalP99Degrees")].toDouble() <= 0.1);
        QVERIFY(adaptive[QStringLiteral("normalMaxDegrees")].toDouble() <= 1.0);
        QCOMPARE(adaptive[QStringLiteral("idDisagreements")].toDouble(), 0.0);
        QVERIFY(adaptive[QStringLiteral("depthDisagreements")].toDouble() * 1000.0 <=
                adaptive[QStringLiteral("normalPixels")].toDouble());
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

    // A closed solid (Pump_Nut from tests/data) shows no background between its faces in the
    // fitted view and in close-ups at 2x and 8x, and the visible faces,
    // depths and normals are the CPU reference's outside the edge band.
    void closedSolidHasNoCracksInCloseUps_data() {
        QTest::addColumn<QString>("zoom");
        QTest::newRow("fitted") << QStringLiteral("1");
        QTest::newRow("2x") << QStringLiteral("2@0.4,0.5");
        QTest::newRow("8x") << QStringLiteral("8@0.3,0.6");
    }
    // Anti-aliased still frames (the editor's) of closed solids: the default accumulated frames
    // (each sample an aliased frame, skirts and fins included) stay within quantisation of the
    // 16-sample truth along seams and inner outlines; the MSAA frame with exact trim coverage
    // showed dark dotted seams there (74 and 105 such pixels at this size, 90 and 142 in the
    // aliased frame itself, docs/PERFORMANCE.md "Anti-aliasing by accumulation").
    void antialiasedSeamsStayClosed_data() {
        QTest::addColumn<QString>("part");
        QTest::addColumn<int>("most");
        QTest::addColumn<double>("meanMost");
        QTest::addRow("Pump_Nut") << QStringLiteral("Pump_Nut") << 32 << 0.15;
        QTest::addRow("Axis_of_bearing") << QStringLiteral("Axis_of_bearing") << 45 << 0.45;
    }
    void antialiasedSeamsStayClosed() {
        QFETCH(QString, part);
        QFETCH(int, most);
        QFETCH(double, meanMost);
        const QString knot = convertedPart(qPrintable(part));
        constexpr int kSide = 256;
        const QImage aliased = renderPart(knot, kSide, part + QStringLiteral("_1"), {});
        const QImage big = renderPart(knot, 4 * kSide, part + QStringLiteral("_big"), {});
        const QImage accumulated = renderPart(knot, kSide, part + QStringLiteral("_acc"),
                                              {QStringLiteral("--samples"), QStringLiteral("4")});
        const QImage coverage =
            renderPart(knot, kSide, part + QStringLiteral("_cov"),
                       {QStringLiteral("--samples"), QStringLiteral("4"),
                        QStringLiteral("--aa-method"), QStringLiteral("coverage")});
        QVERIFY(!aliased.isNull() && !big.isNull() && !accumulated.isNull() && !coverage.isNull());
        const SeamCount acc = seams(aliased, big, accumulated);
        const SeamCount cov = seams(aliased, big, coverage);
        const SeamCount none = seams(aliased, big, aliased);
        qInfo("%s: %d interior pixels; darker than the truth by > 8 levels: accumulated %d "
              "(mean |difference| %.3f), coverage %d (%.3f), aliased %d (%.3f)",
              qPrintable(part), acc.interior, acc.darker, acc.meanDifference, cov.darker,
              cov.meanDifference, none.darker, none.meanDifference);
        QVERIFY(acc.interior > 5000);
        QVERIFY2(acc.darker <= most, qPrintable(QString::number(acc.darker)));
        QVERIFY2(acc.meanDifference <= meanMost, qPrintable(QString::number(acc.meanDifference)));
        // Anti-aliased at all: nearer the truth than the aliased frame.
        QVERIFY(acc.meanDifference < 0.6 * none.meanDifference);
    }

    void closedSolidHasNoCracksInCloseUps() {
        QFETCH(QString, zoom);
        const QJsonObject m = partReport(convertedPart("Pump_Nut"), zoom);
        QVERIFY(!m.isEmpty());
        qInfo("Pump_Nut at %s: %g covered, %g crack pixels, %g id disagreements, normal p99 "
              "%.4f deg",
              qPrintable(zoom), m[QStringLiteral("covered")].toDouble(),
              m[QStringLiteral("crackPixels")].toDouble(),
              m[QStringLiteral("idDisagreements")].toDouble(),
              m[QStringLiteral("normalP99Degrees")].toDouble());
        QVERIFY(m[QStringLiteral("covered")].toDouble() > 20000);
        QCOMPARE(m[QStringLiteral("crackPixels")].toDouble(), 0.0);
        QCOMPARE(m[QStringLiteral("idDisagreements")].toDouble(), 0.0);
        QCOMPARE(m[QStringLiteral("depthDisagreements")].toDouble(), 0.0);
        QVERIFY(m[QStringLiteral("silhouetteMaxPixels")].toDouble() <= 1.0);
        QVERIFY(m[QStringLiteral("normalP99Degrees")].toDouble() <= 0.1);
        // Inside the band: a face behind showing along the edge of the one in front, where the
        // trims were tested at the polygon's (u, v) and dropped pixel centres just inside a
        // trimmed edge. Tested at the point under the pixel: 22 -> 10, 19 -> 8 and 2 -> 1 in
        // these three views (the rest where a skirt's pushed-back depth loses to a face close
        // behind, docs/PERFORMANCE.md "The sheet in front at silhouettes").
        const double behind = m[QStringLiteral("bandBehind")].toDouble();
        qInfo("Pump_Nut at %s: %g band pixels show a face behind the reference's", qPrintable(zoom),
              behind);
        QVERIFY(m.contains(QStringLiteral("bandBehind")));
        QVERIFY(behind <= 12.0);
    }

    // The closed solids at the 1024 x 1024, fitted: no background where the reference
    // shows a face. Axis_of_bearing had one such pixel at (457, 775), on its bore (face 87) next
    // to the seam with face 89, where the skirt's solve ends on the bore's continuation past
    // the rim (the ray meets it before the far wall): the silhouette metric scored it 17 px
    // from the nearest outline. The skirt now solves again from the ray's other meeting with
    // the face and keeps that point when it lies within 2 kSkirtDepthPixels behind the strip
    // (exact_surface.frag, kwSkirtPoint). Without that depth limit the far wall of faces
    // showed over the faces in front of them along their edges: 48 band pixels show a face
    // behind the reference's (17 before the change, 18 with it).
    void closedSolidsAtFullSize_data() {
        QTest::addColumn<QString>("part");
        QTest::addColumn<double>("behindMost");
        // The back-face fill (exact_surface_pass.cpp, backFacePass) shows the solid's inside
        // where two faces' exact trims leave a sub-pixel sliver at a seam: 0 pinholes over the
        // sweep, but in band pixels next to such seams (within a pixel of the outline) the
        // fill's back face shows where the reference sees the front face's edge: 38 and 28
        // band pixels here, 24 and 6 before the fill. A trim overlap of a fraction of a pixel
        // at closed solids' seams would cover them with the front face instead. Axis_of_bearing
        // shows 36 with its faces in closed form (38 by the Newton step); 55 while the closed
        // form took a meeting across the face from the polygon's (u, v) (analytic.glsl,
        // KW_ANALYTIC_NEAR), drawn at the polygon's depth in front of the face hiding it.
        QTest::addRow("Axis_of_bearing") << QStringLiteral("Axis_of_bearing") << 40.0;
        QTest::addRow("Pump_Nut") << QStringLiteral("Pump_Nut") << 30.0;
    }
    void closedSolidsAtFullSize() {
        QFETCH(QString, part);
        QFETCH(double, behindMost);
        const QJsonObject m =
            partReport(convertedPart(qPrintable(part)), QStringLiteral("1"), 1024);
        QVERIFY(!m.isEmpty());
        const double behind = m[QStringLiteral("bandBehind")].toDouble();
        qInfo("%s at 1024 x 1024: %g covered, %g crack pixels (%g the reference covers), "
              "silhouette max %.2f px, %g id disagreements, %g band pixels show a face behind",
              qPrintable(part), m[QStringLiteral("covered")].toDouble(),
              m[QStringLiteral("crackPixels")].toDouble(),
              m[QStringLiteral("crackPixelsCoveredInReference")].toDouble(),
              m[QStringLiteral("silhouetteMaxPixels")].toDouble(),
              m[QStringLiteral("idDisagreements")].toDouble(), behind);
        QVERIFY(m[QStringLiteral("covered")].toDouble() > 100000);
        QCOMPARE(m[QStringLiteral("crackPixelsCoveredInReference")].toDouble(), 0.0);
        QVERIFY(m[QStringLiteral("silhouetteMaxPixels")].toDouble() <= 1.0);
        QCOMPARE(m[QStringLiteral("idDisagreements")].toDouble(), 0.0);
        QVERIFY2(behind <= behindMost, qPrintable(QString::number(behind)));
    }

    // A close-up where a torus fillet (Axis_of_bearing's face 13, surface id 25, seen in this
    // view's id AOV with its neighbours 23, 27 and 29) meets a cylinder and a plane: every pixel
    // outside the edge band shows the face the CPU reference shows, at its depth. The paper's
    // coarse polygons (uniform 10 x 10) do not.
    void filletShowsTheReferenceFaces() {
        const QString knot = convertedPart("Axis_of_bearing");
        const QJsonObject m = partReport(knot, QStringLiteral("8@0.6,0.4"));
        QVERIFY(!m.isEmpty());
        QCOMPARE(m[QStringLiteral("idDisagreements")].toDouble(), 0.0);
        QCOMPARE(m[QStringLiteral("depthDisagreements")].toDouble(), 0.0);
        QVERIFY(m[QStringLiteral("normalPixels")].toDouble() > 20000);
        // The same view from the paper's polygons: the metric sees the wrong faces in front.
        const Run r = knotwork(
            {QStringLiteral("render"), knot, QStringLiteral("-o"),
             output(QStringLiteral("edges_fillet.png")), QStringLiteral("--size"),
             QStringLiteral("256x256"), QStringLiteral("--zoom"), QStringLiteral("8@0.6,0.4"),
             QStringLiteral("--partition-mode"), QStringLiteral("uniform"),
             QStringLiteral("--edge-report"), output(QStringLiteral("edges_fillet_uniform.json"))});
        QVERIFY2(r.code == 0, qPrintable(r.err));
        QFile f(output(QStringLiteral("edges_fillet_uniform.json")));
        QVERIFY(f.open(QIODevice::ReadOnly));
        const QJsonObject u = QJsonDocument::fromJson(f.readAll()).object();
        qInfo("fillet close-up: adaptive %g id / %g depth disagreements, uniform %g / %g",
              m[QStringLiteral("idDisagreements")].toDouble(),
              m[QStringLiteral("depthDisagreements")].toDouble(),
              u[QStringLiteral("idDisagreements")].toDouble(),
              u[QStringLiteral("depthDisagreements")].toDouble());
        QVERIFY(u[QStringLiteral("idDisagreements")].toDouble() +
                    u[QStringLiteral("depthDisagreements")].toDouble() >
                100.0);
    }

    // A project's saved display settings choose the partitioning unless the command line does.
    void projectDisplaySettingsApply() {
        QFile in(sample("bicubic"));
        QVERIFY(in.open(QIODevice::ReadOnly));
        QJsonObject root = QJsonDocument::fromJson(in.readAll()).object();
        root.insert(QStringLiteral("display"),
                    QJsonObject{{QStringLiteral("partitionMode"), QStringLiteral("uniform")}});
        const QString path = output(QStringLiteral("bicubic_uniform.knot"));
        QFile out(path);
        QVERIFY(out.open(QIODevice::WriteOnly | QIODevice::Truncate));
        out.write(QJsonDocument(root).toJson());
        out.close();
        const QStringList base{QStringLiteral("render"), path,
                               QStringLiteral("-o"),     output(QStringLiteral("display.png")),
                               QStringLiteral("--size"), QStringLiteral("64x48")};
        Run r = knotwork(base);
        QVERIFY2(r.code == 0 && r.out.contains(QStringLiteral("uniform partitions: ")),
                 qPrintable(r.out + r.err));
        r = knotwork(base +
                     QStringList{QStringLiteral("--partition-mode"), QStringLiteral("adaptive")});
        QVERIFY2(r.code == 0 && r.out.contains(QStringLiteral("adaptive partitions: ")),
                 qPrintable(r.out + r.err));
        // Without saved settings, adaptive is render's default.
        r = knotwork({QStringLiteral("render"), sample("bicubic"), QStringLiteral("-o"),
                      output(QStringLiteral("display.png")), QStringLiteral("--size"),
                      QStringLiteral("64x48")});
        QVERIFY2(r.code == 0 && r.out.contains(QStringLiteral("adaptive partitions: ")),
                 qPrintable(r.out + r.err));
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
