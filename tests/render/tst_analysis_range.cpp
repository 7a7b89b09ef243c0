// The automatic colour range of the curvature maps (kw::autoRange) without GL: set by the
// area the values cover, so the large faces show their variation and small sharp regions
// saturate. On the teapot's body the mean curvature's colours span at least 5 of the legend's
// 10 bands (tenths of the scale), each holding at least 1 % of the body's area; counted by
// sample, the rim, spout tip and the fillet to the bottom set the range to +-21.55 and the
// body was one band.
#include "model/io/knotfile.h"
#include "model/nurbs/nurbs_curvature.h"
#include "model/nurbs/nurbs_shapes.h"
#include "render/analysis.h"

#include <QTest>

using namespace kw;

Q_DECLARE_METATYPE(kw::AnalysisMode)

namespace {

/// Bands of the legend (tenths of the colour scale) that hold at least 1 % of the area of the
/// surfaces `of` picks, sampled on a fine grid independent of autoRange's.
template <class Pick>
int bandsShown(const Scene& scene, AnalysisMode mode, const ValueRange& range, Pick of) {
    const ColourScale scale = defaultScale(mode);
    std::vector<double> area(10, 0.0);
    double total = 0.0;
    for (const Surface& s : scene.surfaces) {
        if (!of(s))
            continue;
        const int n = 61;
        const Interval du = surfaceDomainU(s.geometry), dv = surfaceDomainV(s.geometry);
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const double u = du.first + (du.last - du.first) * (i + 0.5) / n;
                const double v = dv.first + (dv.last - dv.first) * (j + 0.5) / n;
                const SurfaceCurvature c = surfaceCurvature(s.geometry, u, v);
                const double x = analysisValue(mode, c);
                const double a = std::sqrt(std::max(c.E * c.G - c.F * c.F, 0.0));
                if (!std::isfinite(x))
                    continue;
                area[size_t(std::min(9, int(colourScalePosition(x, range, scale) * 10.0)))] += a;
                total += a;
            }
    }
    int bands = 0;
    for (double a : area)
        bands += a >= 0.01 * total;
    return bands;
}

bool isBody(const Surface& s) {
    return s.name.startsWith(QLatin1String("body"));
}

} // namespace

class TestAnalysisRange : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void teapotBodyShowsItsVariation_data() {
        QTest::addColumn<AnalysisMode>("mode");
        QTest::newRow("mean") << AnalysisMode::Mean;
        QTest::newRow("gaussian") << AnalysisMode::Gaussian;
    }

    void teapotBodyShowsItsVariation() {
        QFETCH(AnalysisMode, mode);
        QString error;
        const auto scene = readKnotFile(QStringLiteral(KW_SAMPLES_DIR "/teapot.knot"));
        QVERIFY2(scene, qPrintable(scene.message()));
        const ValueRange r = autoRange(*scene, mode);
        const int bands = bandsShown(*scene, mode, r, isBody);
        qInfo("%s: automatic range %g .. %g, the body spans %d of 10 legend bands",
              qPrintable(analysisModeName(mode)), r.low, r.high, bands);
        QVERIFY2(bands >= 5, qPrintable(QStringLiteral("the body shows %1 bands").arg(bands)));
    }

    /// Weighted by area: a surface's share of the range follows its area, not its sample
    /// count. A large plane (curvature 0) beside a small sphere of radius 0.1 (H = 10): with
    /// the plane 100 times the sphere's area the range's middle part is the plane's 0, however
    /// many samples each gets; with the areas swapped, the sphere's 10.
    void percentilesFollowArea() {
        Scene scene;
        Surface plane;
        plane.id = SurfaceId{1};
        plane.geometry = makePlane(glm::dvec3(-5.0, -5.0, -1.0), glm::dvec3(10.0, 0.0, 0.0),
                                   glm::dvec3(0.0, 10.0, 0.0));
        Surface ball;
        ball.id = SurfaceId{2};
        ball.geometry = makeSphere(glm::dvec3(0.0, 0.0, 1.0), 0.1);
        scene.surfaces = {plane, ball};
        ValueRange r = autoRange(scene, AnalysisMode::MaxCurvature);
        QVERIFY2(
            std::abs(r.high) < 1.0,
            qPrintable(
                QStringLiteral("plane 800x the sphere's area: %1 .. %2").arg(r.low).arg(r.high)));
        // A tiny plane beside a large sphere: the sphere's curvature is the range.
        scene.surfaces[0].geometry = makePlane(
            glm::dvec3(-0.01, -0.01, -1.0), glm::dvec3(0.02, 0.0, 0.0), glm::dvec3(0.0, 0.02, 0.0));
        scene.surfaces[1].geometry = makeSphere(glm::dvec3(0.0, 0.0, 1.0), 2.0);
        r = autoRange(scene, AnalysisMode::MaxCurvature);
        QVERIFY2(r.low > 0.4 && r.high < 0.6,
                 qPrintable(QStringLiteral("sphere of radius 2 beside a speck: %1 .. %2")
                                .arg(r.low)
                                .arg(r.high)));
    }
};

QTEST_MAIN(TestAnalysisRange)
#include "tst_analysis_range.moc"
