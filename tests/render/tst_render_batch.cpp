// GL test: batched drawing. Surfaces of one shader variant are drawn by one
// multi-draw per pass, so 300 surfaces take as many draw calls as 3 of the same variants; the
// image equals the one-draw-per-surface path's and the kernel's; a moved point is still one
// texel in a scene of 300 surfaces.
#include "expected_test_util.h"
#include "render/renderer_test_hook.h"
#include "render_test_util.h"

#include <QScopeGuard>

using namespace kw;

namespace {

/// `n` wavy patches of two variants (render_test_util.h).
Scene grid(int n) {
    return kwtest::variantGrid(n);
}

/// The gather choice depends on each surface's size on screen; fixed here so that each degree
/// pair is one variant at every size. `multiDraw` false: one draw per surface.
RenderOptions batchOptions(bool multiDraw = true) {
    RenderOptions o;
    o.gatherMinCellPixels = 0.0;
    o.multiDraw = multiDraw;
    return o;
}

} // namespace

class TestRenderBatch : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenRenderer> m_renderer;

    /// The report of the second frame of `doc` (the first uploads everything).
    FrameReport steadyFrame(const Document& doc, const RenderOptions& options = batchOptions()) {
        const Camera camera = fitCamera(doc.scene(), 4.0 / 3.0);
        (void)m_renderer->render(doc, camera, options); // the report says how it went
        (void)m_renderer->render(doc, camera, options);
        return m_renderer->lastReport();
    }

private Q_SLOTS:
    void initTestCase() {
        QString error;
        auto made = kwtest::offscreenRenderer(QSize(320, 240), true);
        QVERIFY2(made, qPrintable(made.message()));
        m_renderer = std::move(made).value();
    }

    void drawCallsFollowVariantsNotSurfaces() {
        QString error;
        Document few, many;
        KW_VERIFY_OK(few.resetScene(grid(3)));
        KW_VERIFY_OK(many.resetScene(grid(300)));
        for (auto shading :
             {RenderOptions::Shading::DepthPrepass, RenderOptions::Shading::ExactDepth}) {
            RenderOptions options = batchOptions();
            options.shading = shading;
            const FrameReport a = steadyFrame(few, options);
            const FrameReport b = steadyFrame(many, options);
            QVERIFY2(a.ok && b.ok, qPrintable(a.error + b.error));
            QCOMPARE(a.surfaces, 3);
            QCOMPARE(b.surfaces, 300);
            // Two variants: with the pre-pass one depth draw (nothing trimmed) and one exact
            // draw per variant; exact depth has no pre-pass.
            const int expected = shading == RenderOptions::Shading::DepthPrepass ? 3 : 2;
            QCOMPARE(a.drawCalls, expected);
            QCOMPARE(b.drawCalls, expected);
        }
        // The per-surface path draws each surface (twice with the pre-pass): the count is real.
        QCOMPARE(steadyFrame(many, batchOptions(false)).drawCalls, 600);
    }

    void batchedImageEqualsPerSurfaceImage() {
        QString error;
        Document doc;
        const Scene scene = grid(300);
        KW_VERIFY_OK(doc.resetScene(scene));
        const FrameReport batched = steadyFrame(doc);
        QVERIFY2(batched.ok, qPrintable(batched.error));
        const QImage colour = m_renderer->colorImage();
        const AovBuffer aov = m_renderer->aov();
        QVERIFY(steadyFrame(doc, batchOptions(false)).ok);
        const QImage colourPerSurface = m_renderer->colorImage();
        const AovBuffer aovPerSurface = m_renderer->aov();

        QCOMPARE(colour.size(), colourPerSurface.size());
        int covered = 0, worstColour = 0;
        double worstPosition = 0.0;
        for (int y = 0; y < aov.height; ++y)
            for (int x = 0; x < aov.width; ++x) {
                const float* a = aov.pixel(x, y);
                const float* b = aovPerSurface.pixel(x, y);
                QCOMPARE(a[0], b[0]); // the same surface (or none) at every pixel
                if (a[0] < 0.0f)
                    continue;
                ++covered;
                for (int c = 3; c < 6; ++c)
                    worstPosition = std::max(worstPosition, double(std::abs(a[c] - b[c])));
            }
        for (int y = 0; y < colour.height(); ++y)
            for (int x = 0; x < colour.width(); ++x) {
                const QRgb p = colour.pixel(x, y), q = colourPerSurface.pixel(x, y);
                worstColour =
                    std::max({worstColour, std::abs(qRed(p) - qRed(q)),
                              std::abs(qGreen(p) - qGreen(q)), std::abs(qBlue(p) - qBlue(q))});
            }
        qInfo("%d covered pixels; batched vs per-surface: worst colour difference %d/255, worst "
              "position difference %g",
              covered, worstColour, worstPosition);
        QVERIFY2(covered > 10000, qPrintable(QString::number(covered)));
        QVERIFY2(worstColour <= 1, qPrintable(QString::number(worstColour)));
        QVERIFY2(worstPosition <= 1e-6 * 100.0, qPrintable(QString::number(worstPosition)));
        // And the batched frame against the kernel, with the usual bounds.
        const kwtest::AovComparison r = kwtest::compareAovWithKernel(scene, aov, 3);
        qInfo("batched vs kernel: %d pixels compared, worst position %g (model size %g), worst "
              "normal angle %g deg",
              r.compared, r.maxPosition, r.modelSize, r.maxAngleDeg);
        QCOMPARE(r.unknownIds, 0);
        QVERIFY(r.compared > 3000);
        QVERIFY2(r.maxPosition <= 1e-5 * r.modelSize, qPrintable(QString::number(r.maxPosition)));
        QVERIFY2(r.maxAngleDeg <= 0.05, qPrintable(QString::number(r.maxAngleDeg)));
    }

    void movedPointInManySurfacesIsOneTexel() {
        QString error;
        Document doc;
        KW_VERIFY_OK(doc.resetScene(grid(300)));
        const FrameReport before = steadyFrame(doc);
        const Surface& s = doc.scene().surfaces.at(150);
        const int index = s.geometry.index(2, 2);
        QVERIFY(doc.setControlPoints(s.id, {index},
                                     {s.geometry.points[size_t(index)] + glm::dvec3(0, 0, 0.3)}));
        QVERIFY(m_renderer->render(doc, fitCamera(doc.scene(), 4.0 / 3.0), batchOptions()));
        const FrameReport moved = m_renderer->lastReport();
        QCOMPARE(moved.uploads.fullUploads, 0);
        QCOMPARE(moved.uploads.subImageUploads, 1);
        QCOMPARE(moved.uploads.texels, 1);
        QCOMPARE(moved.uploads.basePolygonBuilds, 0);
        QCOMPARE(moved.uploads.vertexUpdates, 1);
        QCOMPARE(moved.drawCalls, before.drawCalls);
        QCOMPARE(moved.gpuBytes, before.gpuBytes);
        const kwtest::AovComparison r =
            kwtest::compareAovWithKernel(doc.scene(), m_renderer->aov(), 3);
        QVERIFY2(r.maxPosition <= 1e-5 * r.modelSize, qPrintable(QString::number(r.maxPosition)));
    }

    void cleanupTestCase() { m_renderer.reset(); }

    // A close-up sends no triangle of the surfaces wholly outside the view, and changes no
    // pixel: the same frame without culling is bit-identical.
    void closeUpCullsWhatIsOutsideTheView() {
        QString error;
        Document doc;
        KW_VERIFY_OK(doc.resetScene(grid(300)));
        Camera close;
        close.target = glm::dvec3(2.5, 2.0, 0.0); // between the first four patches
        close.eye = close.target + glm::dvec3(0.0, -4.0, 6.0);
        close.authored = true;
        RenderOptions options = batchOptions();
        const auto frame = [&](bool cull) {
            options.cullOutsideView = cull;
            (void)m_renderer->render(doc, close, options); // the report says how it went
            return std::pair(m_renderer->lastReport(), m_renderer->colorImage());
        };
        const auto [uncut, uncutImage] = frame(false);
        const auto [cut, cutImage] = frame(true);
        QVERIFY2(cut.ok && uncut.ok, qPrintable(cut.error + uncut.error));
        QCOMPARE(uncut.culled, 0);
        qInfo("close-up of 300 patches: %d culled, draw CPU %.2f -> %.2f ms", cut.culled,
              uncut.cpuMs.surfaces, cut.cpuMs.surfaces);
        QVERIFY(cut.culled >= 250);
        QVERIFY(cut.culled <= 296); // the four patches around the target are drawn
        QVERIFY(!uncutImage.isNull());
        QCOMPARE(cutImage, uncutImage);
        // The fitted view sees every patch: nothing is culled.
        options.cullOutsideView = true;
        KW_VERIFY_OK(m_renderer->render(doc, fitCamera(doc.scene(), 4.0 / 3.0), options));
        QCOMPARE(m_renderer->lastReport().culled, 0);
    }
};

QTEST_MAIN(TestRenderBatch)
#include "tst_render_batch.moc"
