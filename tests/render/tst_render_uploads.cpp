// GL test: the renderer uploads only what the document's revisions say is stale.
#include "expected_test_util.h"
#include "render/gl_context.h"
#include "render/renderer_test_hook.h"
#include "render_test_util.h"

#include <QScopeGuard>
#include <cstring>
#include <glm/gtc/type_ptr.hpp>

using namespace kw;

class TestRenderUploads : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenRenderer> m_renderer;
    Document m_doc;
    SurfaceId m_bicubic, m_sphere;

    Status renderOnce() {
        return m_renderer->render(m_doc, fitCamera(m_doc.scene(), 1.0), RenderOptions{});
    }

    // The surface's control texels as stored in the scene's shared control buffer.
    std::vector<glm::vec4> gpuTexels(SurfaceId id) {
        const GpuScene& scene = RendererTestHook::scene(m_renderer->renderer());
        const SurfaceGpu* g = scene.surfaceGpu(id);
        std::vector<glm::vec4> out(size_t(g->countU * g->countV));
        m_renderer->makeCurrent();
        RendererTestHook::gl(m_renderer->renderer())
            ->glGetNamedBufferSubData(scene.pools().control.buffer(),
                                      GLintptr(g->controlOffset * 16),
                                      GLsizeiptr(out.size() * sizeof(glm::vec4)), out.data());
        return out;
    }

private Q_SLOTS:
    void initTestCase() {
        QString error;
        auto made = kwtest::offscreenRenderer(QSize(128, 128), true);
        QVERIFY2(made, qPrintable(made.message()));
        m_renderer = std::move(made).value();
        auto scene = kwtest::loadSample(QStringLiteral("bicubic"));
        QVERIFY2(scene, qPrintable(scene.message()));
        m_bicubic = scene->surfaces.at(0).id;
        m_sphere = SurfaceId{scene->nextId};
        scene->surfaces.push_back(
            kwtest::makeSurface(m_sphere.value, makeSphere(glm::dvec3(0.0, 0.0, 1.5), 0.8)));
        scene->nextId = m_sphere.value + 1;
        KW_VERIFY_OK(m_doc.resetScene(*scene));
    }

    void glDebugPrintsDriverMessages() {
        // kw::setGlDebug (KW_GL_DEBUG=1 in the executables, docs/PERFORMANCE.md "On a GPU"): a
        // debug context whose driver messages reach stderr, here a GL error on purpose.
        setGlDebug(true);
        auto unset = qScopeGuard([] { setGlDebug(false); });
        auto made = kwtest::offscreenRenderer(QSize(8, 8), false);
        QVERIFY2(made, qPrintable(made.message()));
        std::unique_ptr<OffscreenRenderer> r = std::move(made).value();
        QVERIFY(r->makeCurrent());
        QTest::ignoreMessage(QtWarningMsg, QRegularExpression(QStringLiteral("^GL debug: .+")));
        RendererTestHook::gl(r->renderer())
            ->glBindBuffer(GL_ARRAY_BUFFER, 987654321u); // never created
        QVERIFY(RendererTestHook::gl(r->renderer())->glGetError() != GL_NO_ERROR);
    }

    void poolGrowthKeepsEveryRange() {
        // Ranges written before and after each growth, and into ranges freed before one, all
        // read back. NVIDIA 580.159 lost the copied ranges when the old buffer was deleted
        // right after glCopyNamedBufferSubData (docs/PERFORMANCE.md "On a GPU"); llvmpipe does
        // not, so this guards the copy itself, and the GPU run the wait.
        QVERIFY(m_renderer->makeCurrent());
        QOpenGLFunctions_4_5_Core* gl = RendererTestHook::gl(m_renderer->renderer());
        GpuPool pool;
        pool.initialize(gl, 4, std::int64_t(1) << 30);
        auto release = qScopeGuard([&] { pool.release(); });
        std::vector<std::pair<std::int64_t, std::vector<std::uint32_t>>> live;
        std::uint32_t next = 1;
        std::int64_t grown = 0, last = 0;
        for (int k = 0; k < 40; ++k) {
            std::vector<std::uint32_t> v(size_t(100 + 97 * k));
            for (std::uint32_t& w : v)
                w = next++;
            const std::int64_t at = pool.allocate(std::int64_t(v.size()));
            QVERIFY(at >= 0);
            pool.write(at, std::int64_t(v.size()), v.data());
            grown += pool.residentBytes() != last ? 1 : 0;
            last = pool.residentBytes();
            live.emplace_back(at, std::move(v));
            if (k % 3 == 2) { // a hole that later ranges reuse
                pool.free(live.front().first, std::int64_t(live.front().second.size()));
                live.erase(live.begin());
            }
        }
        QVERIFY2(grown >= 5, "the pool should have grown several times");
        for (const auto& [at, v] : live) {
            std::vector<std::uint32_t> got(v.size());
            gl->glGetNamedBufferSubData(pool.buffer(), GLintptr(at * 4), GLsizeiptr(v.size() * 4),
                                        got.data());
            QCOMPARE(got, v);
        }
    }

    void firstRenderUploadsEverything() {
        QString error;
        KW_VERIFY_OK(renderOnce());
        for (SurfaceId id : {m_bicubic, m_sphere}) {
            const UploadStats s = RendererTestHook::scene(m_renderer->renderer()).stats(id);
            const Surface* surf = m_doc.surface(id);
            QCOMPARE(s.fullUploads, 1);
            QCOMPARE(s.texels, std::int64_t(surf->geometry.countU) * surf->geometry.countV);
            QCOMPARE(s.spanTableUploads, 2);
            QCOMPARE(s.basePolygonBuilds, 1);
        }
        // Nothing changed: a second frame uploads nothing.
        RendererTestHook::scene(m_renderer->renderer()).resetStats();
        KW_VERIFY_OK(renderOnce());
        QCOMPARE(RendererTestHook::scene(m_renderer->renderer()).totalStats(), UploadStats{});
    }

    void movedPointIsOneTexel() {
        QString error;
        RendererTestHook::scene(m_renderer->renderer()).resetStats();
        const Surface* s = m_doc.surface(m_bicubic);
        // Point (1, 0) acts on u in [0, 0.35] and v in [0, 0.3] only (local support).
        const int index = s->geometry.index(1, 0);
        const glm::dvec3 moved = s->geometry.points[size_t(index)] + glm::dvec3(0.1, -0.05, 0.6);
        // Uniform, no skirt: the vertices' CPU copy is not kept (nor its memory) until the
        // points change.
        QCOMPARE(RendererTestHook::scene(m_renderer->renderer())
                     .surfaceGpu(m_bicubic)
                     ->polygon.vertices.capacity(),
                 size_t(0));
        QVERIFY(m_doc.setControlPoints(m_bicubic, {index}, {moved}));
        KW_VERIFY_OK(renderOnce());

        const UploadStats b = RendererTestHook::scene(m_renderer->renderer()).stats(m_bicubic);
        QCOMPARE(b.fullUploads, 0);
        QCOMPARE(b.subImageUploads, 1);
        QCOMPARE(b.texels, 1);
        QCOMPARE(b.spanTableUploads, 0);
        QCOMPARE(b.basePolygonBuilds, 0);
        QCOMPARE(b.vertexUpdates, 1);
        const SurfaceGpu* g = RendererTestHook::scene(m_renderer->renderer()).surfaceGpu(m_bicubic);
        QVERIFY(b.vertexBytes > 0);
        QVERIFY(size_t(b.vertexBytes) < g->polygon.vertices.size() * sizeof(BaseVertex));
        QCOMPARE(RendererTestHook::scene(m_renderer->renderer()).stats(m_sphere), UploadStats{});

        // The GPU texel holds the new point, and the frame matches the kernel.
        const std::vector<glm::vec4> texels = gpuTexels(m_bicubic);
        const std::vector<glm::vec4> expected =
            packControlPoints(m_doc.surface(m_bicubic)->geometry, g->origin);
        QCOMPARE(texels.size(), expected.size());
        for (size_t k = 0; k < texels.size(); ++k)
            QVERIFY2(texels[k] == expected[k], qPrintable(QStringLiteral("texel %1").arg(k)));
        const kwtest::AovComparison r =
            kwtest::compareAovWithKernel(m_doc.scene(), m_renderer->aov());
        QVERIFY(r.compared > 500);
        QVERIFY(r.maxPosition <= 1e-5 * r.modelSize);
        QVERIFY(r.maxAngleDeg <= 0.05);
    }

    void weightChangeIsOneTexel() {
        QString error;
        RendererTestHook::scene(m_renderer->renderer()).resetStats();
        QVERIFY(m_doc.setWeight(m_sphere, 7, 2.5));
        KW_VERIFY_OK(renderOnce());
        const UploadStats s = RendererTestHook::scene(m_renderer->renderer()).stats(m_sphere);
        QCOMPARE(s.subImageUploads, 1);
        QCOMPARE(s.texels, 1);
        QCOMPARE(s.fullUploads, 0);
        QCOMPARE(RendererTestHook::scene(m_renderer->renderer()).stats(m_bicubic), UploadStats{});
    }

    void partitionsRebuildOnlyThatPolygon() {
        QString error;
        RendererTestHook::scene(m_renderer->renderer()).resetStats();
        QVERIFY(m_doc.setPartitions(m_sphere, 17, 5));
        KW_VERIFY_OK(renderOnce());
        const UploadStats s = RendererTestHook::scene(m_renderer->renderer()).stats(m_sphere);
        QCOMPARE(s.basePolygonBuilds, 1);
        QCOMPARE(s.texels, 0);
        QCOMPARE(s.fullUploads, 0);
        QCOMPARE(s.spanTableUploads, 0);
        QCOMPARE(
            RendererTestHook::scene(m_renderer->renderer()).surfaceGpu(m_sphere)->polygon.cellsU(),
            17 + 3); // + 3 interior knots
        QCOMPARE(RendererTestHook::scene(m_renderer->renderer()).stats(m_bicubic), UploadStats{});
    }

    void knotChangeIsFullUploadOfThatSurface() {
        QString error;
        RendererTestHook::scene(m_renderer->renderer()).resetStats();
        // Same counts, a moved interior knot: only the Knots revision tells the cache.
        NurbsSurface refined = m_doc.surface(m_bicubic)->geometry;
        QCOMPARE(refined.knotsV[4], 0.3);
        refined.knotsV[4] = 0.45;
        QVERIFY(m_doc.setGeometry(m_bicubic, refined));
        KW_VERIFY_OK(renderOnce());
        const UploadStats s = RendererTestHook::scene(m_renderer->renderer()).stats(m_bicubic);
        QCOMPARE(s.fullUploads, 1);
        QCOMPARE(s.texels, std::int64_t(refined.countU) * refined.countV);
        QCOMPARE(RendererTestHook::scene(m_renderer->renderer()).stats(m_sphere), UploadStats{});
    }

    void removedSurfaceIsDropped() {
        QString error;
        QVERIFY(m_doc.removeSurface(m_sphere));
        KW_VERIFY_OK(renderOnce());
        QVERIFY(RendererTestHook::scene(m_renderer->renderer()).surfaceGpu(m_sphere) == nullptr);
        QVERIFY(RendererTestHook::scene(m_renderer->renderer()).surfaceGpu(m_bicubic) != nullptr);
    }

    void anotherDocumentIsNotMistakenForThisOne() {
        // Same surface id, same net size, other points: the renderer must not reuse the first
        // document's uploads (in both modes). Revisions come from one counter for the whole
        // process, so the two documents' never coincide (tst_document); the GPU scene also
        // notices the other document by itself.
        QString error;
        Scene a, b;
        NurbsSurface ga = makePlane(glm::dvec3(0.0), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0));
        NurbsSurface gb =
            makePlane(glm::dvec3(0.0, 0.0, 2.0), glm::dvec3(2, 0, 0), glm::dvec3(0, 1, 1));
        a.surfaces.push_back(kwtest::makeSurface(1, ga));
        b.surfaces.push_back(kwtest::makeSurface(1, gb));
        a.nextId = b.nextId = 2;
        for (RenderMode mode : {RenderMode::Exact, RenderMode::Tessellated}) {
            Document da, db;
            QVERIFY(da.resetScene(a));
            QVERIFY(db.resetScene(b));
            QVERIFY(da.revisions(SurfaceId{1}).points != db.revisions(SurfaceId{1}).points);
            RenderOptions opt;
            opt.mode = mode;
            const Camera cam = fitCamera(b, 1.0);
            KW_VERIFY_OK(m_renderer->render(da, cam, opt));
            KW_VERIFY_OK(m_renderer->render(db, cam, opt));
            const kwtest::AovComparison r = kwtest::compareAovWithKernel(b, m_renderer->aov());
            QVERIFY(r.compared > 500);
            QVERIFY2(r.maxPosition <= 1e-4 * r.modelSize,
                     qPrintable(QString::number(r.maxPosition)));
        }
    }

    void oversizedNetIsReportedNotDrawn() {
        // A degree-1 strip with one more control point than the shared control buffer may
        // hold, under a buffer limit lowered to 1 MiB (llvmpipe's real one is 128 MiB).
        GpuScene::setBufferLimitForTests(1048576);
        const auto restore = qScopeGuard([] { GpuScene::setBufferLimitForTests(0); });
        const int maxSize = 1048576;
        NurbsSurface g;
        g.countU = maxSize / 16 / 2 + 1;
        g.countV = 2;
        g.knotsU = kwtest::clampedUniform(1, g.countU);
        g.knotsV = {0, 0, 1, 1};
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < g.countU; ++i) {
                g.points.emplace_back(double(i) / g.countU, double(j), 0.0);
                g.weights.push_back(1.0);
            }
        Scene scene;
        scene.surfaces.push_back(kwtest::makeSurface(3, g, 1));
        scene.surfaces.push_back(
            kwtest::makeSurface(4, makeSphere(glm::dvec3(0.5, 0.5, 0.0), 0.3)));
        scene.nextId = 5;
        Document doc;
        QString error;
        KW_VERIFY_OK(doc.resetScene(scene));
        const auto result = m_renderer->render(doc, fitCamera(scene, 1.0), RenderOptions{});
        QVERIFY(!result);
        QVERIFY2(result.message().contains(QStringLiteral("surface 3")) &&
                     result.message().contains(QString::number(maxSize)),
                 qPrintable(result.message()));
        // The other surface is drawn; the oversized one is not.
        QVERIFY(RendererTestHook::scene(m_renderer->renderer()).surfaceGpu(SurfaceId{3}) ==
                nullptr);
        QVERIFY(RendererTestHook::scene(m_renderer->renderer()).surfaceGpu(SurfaceId{4}) !=
                nullptr);
        const AovBuffer aov = m_renderer->aov();
        int sphere = 0;
        for (int k = 0; k < aov.width * aov.height; ++k) {
            QVERIFY(aov.data[size_t(k) * AovBuffer::kChannels] != 3.0f);
            sphere += aov.data[size_t(k) * AovBuffer::kChannels] == 4.0f;
        }
        QVERIFY(sphere > 100);
    }

    // The edge skirts: built only for adaptive frames, and a moved point
    // brings the GPU's skirt vertices up to date without rebuilding the polygon.
    void skirtFollowsAMovedPointWithoutARebuild() {
        auto scene = kwtest::loadSample(QStringLiteral("bicubic"));
        QVERIFY2(scene, qPrintable(scene.message()));
        Document doc;
        KW_VERIFY_OK(doc.resetScene(*scene));
        const SurfaceId id = doc.scene().surfaces.at(0).id;
        const Camera camera = fitCamera(doc.scene(), 1.0);
        const GpuScene& gpu = RendererTestHook::scene(m_renderer->renderer());
        KW_VERIFY_OK(m_renderer->render(doc, camera, RenderOptions{}));
        QCOMPARE(gpu.surfaceGpu(id)->skirtVertexOffset, std::int64_t(-1)); // uniform: none
        RenderOptions adaptive;
        adaptive.partitioning = RenderOptions::Partitioning::Adaptive;
        KW_VERIFY_OK(m_renderer->render(doc, camera, adaptive));
        QVERIFY(m_renderer->lastReport().partitions.skirtTriangles > 0);
        const auto gpuSkirt = [&] {
            const SurfaceGpu* g = gpu.surfaceGpu(id);
            std::vector<SkirtVertex> out(size_t(g->skirtVertexCount));
            m_renderer->makeCurrent();
            RendererTestHook::gl(m_renderer->renderer())
                ->glGetNamedBufferSubData(
                    gpu.pools().skirtVertices.buffer(),
                    GLintptr(g->skirtVertexOffset * std::int64_t(sizeof(SkirtVertex))),
                    GLsizeiptr(out.size() * sizeof(SkirtVertex)), out.data());
            return out;
        };
        const std::vector<SkirtVertex> before = gpuSkirt();
        QVERIFY(!before.empty());

        // The corner point (0, 0): every skirt copy of the corner node moves.
        const Surface* s = doc.surface(id);
        const glm::dvec3 lo = s->geometry.points.front(), hi = s->geometry.points.back();
        QVERIFY(doc.setControlPoints(id, {0}, {lo + 1e-3 * (hi - lo)}));
        RendererTestHook::scene(m_renderer->renderer()).resetStats();
        KW_VERIFY_OK(m_renderer->render(doc, camera, adaptive));
        const UploadStats st = gpu.stats(id);
        QCOMPARE(st.basePolygonBuilds, 0);
        QCOMPARE(st.vertexUpdates, 1);
        const std::vector<SkirtVertex> after = gpuSkirt();
        const std::vector<SkirtVertex> expected = skirtVertices(gpu.surfaceGpu(id)->polygon);
        QCOMPARE(after.size(), expected.size());
        QVERIFY(std::memcmp(after.data(), expected.data(), after.size() * sizeof(SkirtVertex)) ==
                0);
        QVERIFY(after.front().base.position != before.front().base.position);
        // Only what moved was written: less than the whole skirt.
        QVERIFY(st.vertexBytes <
                std::int64_t(before.size() * sizeof(SkirtVertex)) +
                    std::int64_t(gpu.surfaceGpu(id)->polygon.vertices.size() * sizeof(BaseVertex)));
    }

    void cleanupTestCase() { m_renderer.reset(); }
};

QTEST_MAIN(TestRenderUploads)
#include "tst_render_uploads.moc"
