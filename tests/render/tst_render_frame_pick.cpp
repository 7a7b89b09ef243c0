// GL test: the frame on screen answers a pick (Renderer::pickInLastFrame) on the pixels the
// forward pass drew as well as on the deferred pass's: a plane whose one cell covers thousands
// of pixels (drawn the forward way, RenderOptions::deferMaxCellPixels) beside the torus sample
// (deferred). Each answer is checked against an AOV frame of the same view.
#include "expected_test_util.h"
#include "model/nurbs/nurbs_shapes.h"
#include "render_test_util.h"

#include <QGuiApplication>

using namespace kw;

class TestRenderFramePick : public QObject {
    Q_OBJECT
    static constexpr int kSize = 256;
    std::unique_ptr<OffscreenRenderer> m_frame; ///< no AOV: its frames are the ones picked
    std::unique_ptr<OffscreenRenderer> m_aov;   ///< the reference

private Q_SLOTS:
    void initTestCase() {
        auto frame = kwtest::offscreenRenderer(QSize(kSize, kSize), false);
        QVERIFY2(frame, qPrintable(frame.message()));
        m_frame = std::move(frame).value();
        auto aov = kwtest::offscreenRenderer(QSize(kSize, kSize), true);
        QVERIFY2(aov, qPrintable(aov.message()));
        m_aov = std::move(aov).value();
    }

    void cleanupTestCase() {
        m_frame.reset();
        m_aov.reset();
    }

    void forwardPixelsAreRead() {
        auto s = kwtest::loadSample(QStringLiteral("torus"));
        QVERIFY2(s, qPrintable(s.message()));
        const std::uint32_t planeId = s->nextId++;
        s->surfaces.insert(
            s->surfaces.begin(),
            kwtest::makeSurface(planeId,
                                makePlane(glm::dvec3(-2.0, -0.6, 0.9), glm::dvec3(1.6, 0.0, 0.0),
                                          glm::dvec3(0.0, 1.6, 0.0)),
                                1));
        Document doc;
        QVERIFY(doc.resetScene(*s));
        const Camera cam = fitCamera(doc.scene(), 1.0);
        RenderOptions opt;
        opt.partitioning = RenderOptions::Partitioning::Adaptive;
        KW_VERIFY_OK(m_aov->render(doc, cam, opt));
        const AovBuffer aov = m_aov->aov();
        KW_VERIFY_OK(m_frame->render(doc, cam, opt));
        // Mixed: the torus deferred, the plane forward.
        const int deferred = m_frame->lastReport().partitions.deferredSurfaces;
        QVERIFY2(deferred >= 1 && deferred < int(doc.scene().surfaces.size()),
                 qPrintable(QString::number(deferred)));
        QVERIFY(m_frame->makeCurrent());
        const double diagonal = 6.0; // about the scene's
        int planePixels = 0, planeRead = 0, torusPixels = 0, torusRead = 0, background = 0,
            otherSurface = 0, farOnTorus = 0;
        for (int y = 1; y < kSize; y += 2)
            for (int x = 1; x < kSize; x += 2) {
                const float* a = aov.pixel(x, y);
                const Renderer::FramePick p = m_frame->renderer().pickInLastFrame(
                    doc, cam, QSize(kSize, kSize), QPointF(x + 0.5, y + 0.5));
                if (a[0] <= 0.0f) { // background in the AOV frame
                    if (p.known && !p.hit)
                        ++background;
                    continue;
                }
                const bool plane = std::uint32_t(a[0]) == planeId;
                (plane ? planePixels : torusPixels) += 1;
                if (!p.known)
                    continue; // a skirt's or fin's pixel: pick() draws it
                QVERIFY2(p.hit, qPrintable(QStringLiteral("%1,%2: no hit").arg(x).arg(y)));
                if (p.hit->surface.value != std::uint32_t(a[0])) {
                    // Where the plane cuts the torus the AOV frame (the forward way) and this
                    // one may see different sheets by a fraction of a pixel's depth.
                    ++otherSurface;
                    continue;
                }
                // The polygon's (u, v), not yet refined onto the ray (the probe does that): the
                // plane's polygon is the plane, so its point is the exact one; the torus's lies
                // within the pixel tolerance on screen, more along a grazing ray.
                const double off = glm::distance(p.hit->point, glm::dvec3(a[3], a[4], a[5]));
                if (plane)
                    QVERIFY2(off < 1e-4 * diagonal,
                             qPrintable(QStringLiteral("%1,%2: %3").arg(x).arg(y).arg(off)));
                else
                    farOnTorus += off > 5e-3 * diagonal ? 1 : 0;
                (plane ? planeRead : torusRead) += 1;
            }
        qInfo("plane %d of %d pixels read, torus %d of %d, background %d, %d another surface",
              planeRead, planePixels, torusRead, torusPixels, background, otherSurface);
        QVERIFY(otherSurface * 100 <= planePixels + torusPixels);
        QVERIFY2(farOnTorus * 50 <= torusPixels, qPrintable(QString::number(farOnTorus)));
        QVERIFY(planePixels > 200 && torusPixels > 200 && background > 200);
        QVERIFY2(planeRead * 100 >= planePixels * 90, // its edges' skirts are not read
                 qPrintable(QStringLiteral("%1 of %2").arg(planeRead).arg(planePixels)));
        QVERIFY2(torusRead * 100 >= torusPixels * 95,
                 qPrintable(QStringLiteral("%1 of %2").arg(torusRead).arg(torusPixels)));
    }
};

QTEST_MAIN(TestRenderFramePick)
#include "tst_render_frame_pick.moc"
