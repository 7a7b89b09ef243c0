// GL test: a render of an imported CAD model shows its faces where
// OpenCASCADE's trims say they are. Every pixel of a trimmed face in the trimmed or untrimmed
// AOV is checked against the CPU classification (model/nurbs/trim.h) at that pixel's (id, u, v).
#include "expected_test_util.h"
#include "model/cad/cadimport.h"
#include "render/renderer_test_hook.h"
#include "render_test_util.h"
#include "trim_test_util.h"

#include <QtTest>

using namespace kw;
using namespace kwtest;

class TestRenderCadCoverage : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenRenderer> m_renderer;

private Q_SLOTS:
    void initTestCase() {
#ifndef KW_HAVE_OCCT
        QSKIP("built without OpenCASCADE (KW_HAVE_OCCT): IGES and STEP cannot be imported");
#endif
        auto made = kwtest::offscreenRenderer(QSize(1024, 1024), true);
        QVERIFY2(made, qPrintable(made.message()));
        m_renderer = std::move(made).value();
    }

    void facesAppearWhereTheTrimsSay_data() {
        QTest::addColumn<QString>("file");
        QTest::newRow("hammer.iges") << QStringLiteral("hammer.iges");
        QTest::newRow("screw.step") << QStringLiteral("screw.step");
    }

    void facesAppearWhereTheTrimsSay() {
        QFETCH(QString, file);
        const Expected<ImportResult> imported =
            importFile(QStringLiteral(KW_TEST_DATA_DIR "/") + file);
        QVERIFY2(imported, qPrintable(imported.message()));
        const Scene& scene = imported->scene;
        int trimmedFaces = 0;
        for (const Surface& s : scene.surfaces)
            trimmedFaces += !s.trims.empty();
        QVERIFY(trimmedFaces > 0);
        Document doc;
        KW_VERIFY_OK(doc.resetScene(scene));
        const Camera cam = fitCamera(scene, 1.0);
        RenderOptions opt;
        opt.trims = false;
        KW_VERIFY_OK(m_renderer->render(doc, cam, opt));
        const AovBuffer whole = m_renderer->aov();
        opt.trims = true;
        KW_VERIFY_OK(m_renderer->render(doc, cam, opt));
        const AovBuffer trimmed = m_renderer->aov();
        const GpuScene& masks = RendererTestHook::scene(m_renderer->renderer());
        const auto texelOf = [&](SurfaceId id) {
            const TrimMask* m = masks.mask(id);
            return m ? std::max((m->rect.y - m->rect.x) / m->width,
                                (m->rect.w - m->rect.z) / m->height)
                     : 0.0; // no mask: any disagreement is far
        };
        const TrimAgreement a = compareTrimmedRender(scene, trimmed, whole, texelOf);
        qInfo("%s: %zu faces (%d trimmed), %ld pixels checked, %.4f%% agree, worst disagreement "
              "%.2f mask texels from a trim curve; %lld masks drawn",
              qPrintable(file), scene.surfaces.size(), trimmedFaces, a.checked,
              100.0 * a.fraction(), a.worstTexels,
              static_cast<long long>(masks.totalMaskStats().redraws));
        QVERIFY(a.checked > 10000);
        // Every disagreement must lie within a mask texel of a trim curve (`far` below): that is
        // the mask's resolution. How many pixels fall there depends on the view's
        // scale against the mask cap: with fitCamera framing the trimmed geometry, hammer.iges
        // fills more of the frame and 0.10% of its pixels lie within half a texel of a curve.
        QVERIFY2(a.fraction() >= 0.998, qPrintable(QString::number(a.fraction())));
        QCOMPARE(a.far, 0L);
    }
};

QTEST_MAIN(TestRenderCadCoverage)
#include "tst_render_cad_coverage.moc"
