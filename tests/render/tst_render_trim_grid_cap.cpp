// GL test: RenderOptions::trimGridCap (set by `knotwork render` from the image size) changes what
// the exact trim grids cost, not which pixels they keep.
#include "expected_test_util.h"
#include "model/document/scene.h"
#include "render_test_util.h"

#include <QTest>

using namespace kw;

class TestTrimGridCap : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenRenderer> m_renderer;
    static constexpr int kW = 160, kH = 120;

    struct Frame {
        QImage color;
        AovBuffer aov;
        int largestGrid = 0;         ///< the largest trim grid side built in the frame
        std::int64_t gridsBuilt = 0; ///< trim grids built in the frame
    };
    Frame draw(const Document& doc, const Camera& camera, int cap) {
        RenderOptions options; // exact mode, exact trims: the editor's defaults
        options.trimGridCap = cap;
        Frame f;
        if (const Status drawn = m_renderer->render(doc, camera, options); !drawn) {
            qWarning("%s", qPrintable(drawn.message()));
            return f;
        }
        f.color = m_renderer->colorImage();
        f.aov = m_renderer->aov();
        f.largestGrid = m_renderer->lastReport().masks.largestSide;
        f.gridsBuilt = m_renderer->lastReport().masks.redraws;
        return f;
    }

private Q_SLOTS:
    void initTestCase() {
        QString error;
        auto made = kwtest::offscreenRenderer(QSize(kW, kH), true);
        QVERIFY2(made, qPrintable(made.message()));
        m_renderer = std::move(made).value();
    }

    void capChangesNoPixel_data() {
        QTest::addColumn<QString>("sample");
        QTest::addColumn<int>("cap");
        for (const char* s : {"trimmed_plate", "star_island", "plate beside star"})
            for (int cap : {16, 1}) // 1: one texel holding every curve piece
                QTest::addRow("%s, cap %d", s, cap) << QString::fromLatin1(s) << cap;
    }
    void capChangesNoPixel() {
        QFETCH(QString, sample);
        QFETCH(int, cap);
        QString error;
        const auto scene = sample == QLatin1String("plate beside star")
                               ? kwtest::plateBesideStar(1.2)
                               : kwtest::loadSample(sample);
        QVERIFY2(scene, qPrintable(scene.message()));
        Document doc;
        KW_VERIFY_OK(doc.resetScene(*scene));
        const Camera camera = fitCamera(doc.scene(), double(kW) / kH);
        const Frame full = draw(doc, camera, kMaxTrimGridSide);
        const Frame capped = draw(doc, camera, cap);
        const Frame again = draw(doc, camera, kMaxTrimGridSide); // the cap is not sticky
        QVERIFY(!full.color.isNull() && !capped.color.isNull() && !again.color.isNull());
        // The cap took effect: the grids were built again, smaller, and again at full size after.
        QVERIFY2(full.largestGrid > cap, qPrintable(QString::number(full.largestGrid)));
        QVERIFY(capped.gridsBuilt > 0 && again.gridsBuilt > 0);
        QCOMPARE(capped.largestGrid, cap);
        QCOMPARE(again.largestGrid, full.largestGrid);
        QCOMPARE(again.color, full.color);
        // Tolerance: a pixel whose centre lies within rounding error of a trim curve may be
        // classified either way (render/trim_grid.h); allow 0.1% of the pixels, no more.
        int differ = 0, trimmedSurface = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const float* a = full.aov.pixel(x, y);
                const float* b = capped.aov.pixel(x, y);
                trimmedSurface += a[0] >= 0.0f;
                differ += a[0] != b[0] || full.color.pixel(x, y) != capped.color.pixel(x, y);
            }
        QVERIFY2(trimmedSurface > kW * kH / 20, "the sample fills too little of the frame");
        QVERIFY2(differ <= kW * kH / 1000,
                 qPrintable(QStringLiteral("%1 pixels differ").arg(differ)));
    }
};

QTEST_MAIN(TestTrimGridCap)
#include "tst_render_trim_grid_cap.moc"
