// Analysis options without GL: mode names, colour scales (the legend inverts the shader's
// mapping), shader defines per mode, and the automatic colour range from kernel samples.
#include "model/nurbs/nurbs_shapes.h"
#include "render/analysis.h"

#include <QTest>

using namespace kw;

class TestAnalysisOptions : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void namesRoundTrip() {
        QCOMPARE(int(analysisModes().size()), 9);
        for (AnalysisMode m : analysisModes()) {
            QCOMPARE(parseAnalysisMode(analysisModeName(m)), std::optional<AnalysisMode>(m));
            QVERIFY(!analysisModeTitle(m).isEmpty());
        }
        QVERIFY(!parseAnalysisMode(QStringLiteral("isocurves"))); // an overlay, not a mode
        QVERIFY(!parseAnalysisMode(QStringLiteral("prepass")));
        for (ColourScale s : {ColourScale::Linear, ColourScale::Symmetric, ColourScale::Log})
            QCOMPARE(parseColourScale(colourScaleName(s)), std::optional<ColourScale>(s));
    }

    void scalesInvert() {
        const ValueRange r{-0.3, 2.0};
        for (ColourScale s : {ColourScale::Linear, ColourScale::Symmetric, ColourScale::Log}) {
            for (int k = 0; k <= 20; ++k) {
                const double t = k / 20.0;
                const double x = colourScaleValue(t, r, s);
                QVERIFY2(std::abs(colourScalePosition(x, r, s) - t) < 1e-12,
                         qPrintable(QStringLiteral("%1 at t = %2").arg(colourScaleName(s)).arg(t)));
            }
        }
        // Symmetric and log put zero in the middle and clamp outside.
        QCOMPARE(colourScalePosition(0.0, r, ColourScale::Symmetric), 0.5);
        QCOMPARE(colourScalePosition(0.0, r, ColourScale::Log), 0.5);
        QCOMPARE(colourScalePosition(-5.0, r, ColourScale::Symmetric), 0.0);
        QCOMPARE(colourScalePosition(5.0, r, ColourScale::Linear), 1.0);
        QCOMPARE(colourScalePosition(std::nan(""), r, ColourScale::Linear), 0.0);
        // The log scale spreads small magnitudes: 1e-3 of the range's magnitude is already well
        // off the middle, where the symmetric scale barely moves.
        QVERIFY(colourScalePosition(2e-3, r, ColourScale::Log) > 0.55);
        QVERIFY(colourScalePosition(2e-3, r, ColourScale::Symmetric) < 0.501);
        // The ramp runs blue to red.
        QVERIFY(rampColour(0.0).b > rampColour(0.0).r);
        QVERIFY(rampColour(1.0).r > rampColour(1.0).b);
        QCOMPARE(rampColour(0.5), colourRamp()[2]);
    }

    void definesPerMode() {
        AnalysisOptions o;
        QVERIFY(analysisDefines(o, false).isEmpty()); // plain Phong: the unchanged shader
        o.mode = AnalysisMode::Gaussian;
        QStringList d = analysisDefines(o, false);
        QVERIFY(d.contains(QStringLiteral("KW_ANALYSIS 1")));
        QVERIFY(d.contains(QStringLiteral("KW_SECOND_ORDER")));
        QVERIFY(d.contains(QStringLiteral("KW_RAMP_STOPS 5")));
        o.mode = AnalysisMode::Zebra;
        o.isocurves = true;
        d = analysisDefines(o, false);
        QVERIFY(!d.contains(QStringLiteral("KW_SECOND_ORDER"))); // zebra needs the normal only
        QVERIFY(d.contains(QStringLiteral("KW_ISOCURVES")));
        d = analysisDefines(o, true);
        QVERIFY(d.contains(QStringLiteral("KW_SECOND_ORDER")));
        QVERIFY(d.contains(QStringLiteral("KW_AOV_CURVATURE")));
    }

    void autoRangeFromKernel() {
        Scene scene;
        Surface s;
        s.id = SurfaceId{1};
        s.geometry = makeTorus(glm::dvec3(0.0), 3.0, 1.0);
        scene.surfaces.push_back(s);
        // Gaussian curvature of a torus: cos v / (r (R + r cos v)) in [-1/2, 1/4], over an area
        // element proportional to R + r cos v: 10 % of the area lies below cos v = -0.8947
        // (K = -0.4250) and 10 % above cos v = 0.9722 (K = 0.2448), to the value of a
        // neighbouring sample of the 16 along v (there K steps by up to 0.045).
        const ValueRange k = autoRange(scene, AnalysisMode::Gaussian);
        QVERIFY2(std::abs(k.low + 0.4250) < 0.045 && std::abs(k.high - 0.2448) < 0.01,
                 qPrintable(QStringLiteral("%1 .. %2").arg(k.low).arg(k.high)));
        // max |k| is 1/r everywhere: a constant, widened to +-5%.
        const ValueRange m = autoRange(scene, AnalysisMode::MaxCurvature);
        QVERIFY(std::abs(m.low - 0.95) < 1e-9 && std::abs(m.high - 1.05) < 1e-9);
        QCOMPARE(autoRange(scene, AnalysisMode::Zebra), ValueRange{});
        QCOMPARE(autoRange(Scene{}, AnalysisMode::Mean), ValueRange{});
        // Percentiles, not extremes: a tiny, sharply curved sphere among large ones.
        for (int k2 = 0; k2 < 60; ++k2) {
            Surface big;
            big.id = SurfaceId{std::uint32_t(10 + k2)};
            big.geometry = makeSphere(glm::dvec3(10.0 * k2, 0.0, 0.0), 2.0);
            scene.surfaces.push_back(big);
        }
        Surface tiny;
        tiny.id = SurfaceId{100};
        tiny.geometry = makeSphere(glm::dvec3(0.0, 50.0, 0.0), 1e-3);
        scene.surfaces.push_back(tiny);
        QVERIFY(autoRange(scene, AnalysisMode::Mean).high < 2.0);
    }
};

QTEST_APPLESS_MAIN(TestAnalysisOptions)
#include "tst_analysis_options.moc"
