// GL test: the renderer's public interface. The pick query against the AOV of a full frame and
// the kernel; the FrameReport's uploads, draw calls and GPU bytes, which go back to the empty
// document's when every surface is removed; hidden surfaces left out of frames and picks.
#include "expected_test_util.h"
#include "render/gpu_layout.h"
#include "render_test_util.h"

#include <QGuiApplication>
#include <set>

using namespace kw;

class TestRenderScene : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenRenderer> m_renderer;

    FrameReport frame(const Document& doc, const RenderOptions& options = {}) {
        (void)m_renderer->render(doc, fitCamera(doc.scene(), 4.0 / 3.0), options); // reported
        return m_renderer->lastReport();
    }

private Q_SLOTS:
    void initTestCase() {
        QString error;
        auto made = kwtest::offscreenRenderer(QSize(160, 120), true);
        QVERIFY2(made, qPrintable(made.message()));
        m_renderer = std::move(made).value();
    }

    void pickMatchesAov_data() {
        QTest::addColumn<QString>("sample");
        for (const char* name : {"teapot", "trimmed_plate", "torus"})
            QTest::newRow(name) << QString::fromLatin1(name);
    }
    void pickMatchesAov() {
        // Every 4th pixel of a 160x120 frame picked one at a time: the surface, (u, v) and
        // point the full frame's AOV holds there, and the kernel's point at that (u, v).
        QFETCH(QString, sample);
        QString error;
        const auto scene = kwtest::loadSample(sample);
        QVERIFY2(scene, qPrintable(scene.message()));
        Document doc;
        KW_VERIFY_OK(doc.resetScene(*scene));
        const Camera camera = fitCamera(doc.scene(), 4.0 / 3.0);
        KW_VERIFY_OK(m_renderer->render(doc, camera, RenderOptions{}));
        const AovBuffer aov = m_renderer->aov();
        glm::dvec3 lo, hi;
        sceneBounds(doc.scene(), lo, hi);
        const double modelSize = glm::length(hi - lo);
        int hits = 0, misses = 0, disagree = 0;
        double maxUv = 0.0, maxPoint = 0.0;
        for (int y = 1; y < aov.height; y += 4)
            for (int x = 1; x < aov.width; x += 4) {
                const float* px = aov.pixel(x, y);
                const std::optional<PickHit> hit =
                    m_renderer->pick(doc, camera, QPointF(x + 0.5, y + 0.5));
                const bool covered = px[0] >= 0.0f;
                if (bool(hit) != covered || (hit && double(hit->surface.value) != px[0])) {
                    ++disagree;
                    continue;
                }
                if (!hit) {
                    ++misses;
                    continue;
                }
                ++hits;
                maxUv = std::max({maxUv, std::abs(hit->uv.x - px[1]), std::abs(hit->uv.y - px[2])});
                const Surface* s = doc.surface(hit->surface);
                QVERIFY(s);
                // The point is the kernel's at the picked (u, v), and where the frame put it.
                QCOMPARE(hit->point, surfacePoint(s->geometry, hit->uv.x, hit->uv.y));
                maxPoint =
                    std::max(maxPoint, glm::length(hit->point - glm::dvec3(px[3], px[4], px[5])));
            }
        qInfo("%s: %d hits, %d background, %d disagreements; max |uv| diff %.3g, max point diff "
              "%.3g (model size %.3g)",
              qPrintable(sample), hits, misses, disagree, maxUv, maxPoint, modelSize);
        QVERIFY(hits > 100);
        QVERIFY(misses > 10);
        QCOMPARE(disagree, 0);
        // The pick's viewport is the frame's shifted by whole pixels: the same fragments, with
        // interpolation rounding of float window coordinates of another size.
        QVERIFY(maxUv <= 1e-5);
        QVERIFY(maxPoint <= 1e-5 * modelSize);
        // Outside the frame: nothing.
        QVERIFY(!m_renderer->pick(doc, camera, QPointF(-1.0, 10.0)));
        QVERIFY(!m_renderer->pick(doc, camera, QPointF(10.0, 120.0)));
    }

    void pickSeesTrims() {
        // A trimmed-away spot of trimmed_plate is background for pick, as in the frame; with
        // trims off the same pixel hits the plate.
        QString error;
        const auto scene = kwtest::loadSample(QStringLiteral("trimmed_plate"));
        QVERIFY2(scene, qPrintable(scene.message()));
        Document doc;
        KW_VERIFY_OK(doc.resetScene(*scene));
        const Camera camera = fitCamera(doc.scene(), 4.0 / 3.0);
        RenderOptions untrimmed;
        untrimmed.trims = false;
        KW_VERIFY_OK(m_renderer->render(doc, camera, RenderOptions{}));
        const AovBuffer trimmed = m_renderer->aov();
        KW_VERIFY_OK(m_renderer->render(doc, camera, untrimmed));
        const AovBuffer whole = m_renderer->aov();
        int checked = 0;
        for (int y = 0; y < trimmed.height && checked < 5; y += 3)
            for (int x = 0; x < trimmed.width && checked < 5; x += 3)
                if (trimmed.pixel(x, y)[0] < 0.0f && whole.pixel(x, y)[0] >= 0.0f) {
                    const QPointF at(x + 0.5, y + 0.5);
                    QVERIFY(!m_renderer->pick(doc, camera, at));
                    const std::optional<PickHit> h = m_renderer->pick(doc, camera, at, untrimmed);
                    QVERIFY(h);
                    QCOMPARE(double(h->surface.value), double(whole.pixel(x, y)[0]));
                    ++checked;
                }
        QCOMPARE(checked, 5);
    }

    void reportCountsUploadsAndBytes() {
        QString error;
        const auto scene = kwtest::loadSample(QStringLiteral("trimmed_plate"));
        QVERIFY2(scene, qPrintable(scene.message()));
        Document doc;
        KW_VERIFY_OK(doc.resetScene(*scene));
        RenderOptions options;
        options.controlNet = true;
        const FrameReport first = frame(doc, options);
        QVERIFY2(first.ok, qPrintable(first.error));
        const auto n = std::int64_t(doc.scene().surfaces.size());
        QCOMPARE(first.surfaces, int(n));
        QCOMPARE(first.uploads.fullUploads, n);
        QCOMPARE(first.uploads.netBuilds, n);
        QVERIFY(first.masks.redraws >= 1);
        QVERIFY(first.drawCalls >= int(n));
        QVERIFY(first.gpuBytes.controlPoints > 0 && first.gpuBytes.spanTables > 0 &&
                first.gpuBytes.basePolygons > 0 && first.gpuBytes.controlNets > 0 &&
                first.gpuBytes.trimMasks > 0);
        QVERIFY(first.cpuMs.total >= first.cpuMs.surfaces);
        // Thread CPU up to the first surface draw: some, and not more than the call's wall.
        QVERIFY(first.cpuMs.beforeDraws > 0.0);
        QVERIFY(first.cpuMs.beforeDraws <= first.cpuMs.total + 1.0);
        // Nothing changed: the next frame uploads and redraws nothing, holds the same bytes.
        const FrameReport second = frame(doc, options);
        QCOMPARE(second.uploads, UploadStats{});
        QCOMPARE(second.masks.redraws, 0);
        QCOMPARE(second.gpuBytes, first.gpuBytes);
        // A moved point: one texel.
        const Surface& s = doc.scene().surfaces.front();
        QVERIFY(doc.setControlPoints(s.id, {0}, {s.geometry.points[0] + glm::dvec3(0, 0, 0.1)}));
        const FrameReport moved = frame(doc, options);
        QCOMPARE(moved.uploads.subImageUploads, 1);
        QCOMPARE(moved.uploads.texels, 1);
        QCOMPARE(moved.uploads.fullUploads, 0);
        QCOMPARE(moved.gpuBytes, first.gpuBytes);
        // The tessellated mode's meshes are counted too.
        options.mode = RenderMode::Tessellated;
        const FrameReport tess = frame(doc, options);
        QCOMPARE(tess.uploads.meshBuilds, n);
        QVERIFY(tess.gpuBytes.tessellatedMeshes > 0);
    }

    /// Renderer::renderMesh (the bench's comparison meshes through the public interface):
    /// the surfaces' own baseline meshes handed in from outside draw the image the
    /// tessellated mode draws, AOVs included; a mesh of a surface the document lacks is
    /// skipped, an empty slot is an error.
    void externalMeshDrawsAsTheBaseline() {
        const auto scene = kwtest::loadSample(QStringLiteral("teapot"));
        QVERIFY2(scene, qPrintable(scene.message()));
        Document doc;
        KW_VERIFY_OK(doc.resetScene(*scene));
        const Camera camera = fitCamera(doc.scene(), 4.0 / 3.0);
        RenderOptions tessellated;
        tessellated.mode = RenderMode::Tessellated;
        KW_VERIFY_OK(m_renderer->render(doc, camera, tessellated));
        const QImage baseline = m_renderer->colorImage();
        const AovBuffer baselineAov = m_renderer->aov();
        TriangleMesh mesh;
        for (const Surface& s : doc.scene().surfaces) {
            TessellatedMesh t = tessellate(s.geometry, s.partitionsU, s.partitionsV);
            mesh.surfaces.push_back(SurfaceMesh{s.id, std::move(t.positions), std::move(t.normals),
                                                std::move(t.uvs), std::move(t.indices)});
        }
        mesh.surfaces.push_back(mesh.surfaces.front());
        mesh.surfaces.back().id = SurfaceId{999999}; // not in the document: skipped
        QVERIFY(m_renderer->setMesh(1, mesh) > 0);
        KW_VERIFY_OK(m_renderer->renderMesh(doc, 1, camera, RenderOptions{}));
        const FrameReport& r = m_renderer->lastReport();
        QCOMPARE(r.surfaces, int(doc.scene().surfaces.size()));
        QCOMPARE(r.drawCalls, int(doc.scene().surfaces.size()));
        QVERIFY(r.gpuBytes.tessellatedMeshes > 0);
        QVERIFY(m_renderer->colorImage() == baseline);
        const AovBuffer aov = m_renderer->aov();
        QVERIFY(aov.data == baselineAov.data);
        const auto result = m_renderer->renderMesh(doc, 2, camera, RenderOptions{});
        QVERIFY(!result);
        QVERIFY2(result.message().contains(QStringLiteral("no mesh")),
                 qPrintable(result.message()));
        QCOMPARE(m_renderer->setMesh(Renderer::kMeshSlots, mesh), std::int64_t(-1));
    }

    void hiddenSurfacesAreNeitherDrawnNorPicked() {
        // teapot: every pixel the AOV gives to a hidden surface shows the background (or a
        // visible surface that was behind it), pick never returns a hidden surface, and showing
        // them again uploads nothing: their records were kept.
        const auto scene = kwtest::loadSample(QStringLiteral("teapot"));
        QVERIFY2(scene, qPrintable(scene.message()));
        Document doc;
        KW_VERIFY_OK(doc.resetScene(*scene));
        const Camera camera = fitCamera(doc.scene(), 4.0 / 3.0);
        KW_VERIFY_OK(m_renderer->render(doc, camera, RenderOptions{}));
        const AovBuffer all = m_renderer->aov();
        const FrameReport shown = m_renderer->lastReport();
        std::set<std::uint32_t> hidden;
        for (size_t k = 0; k < doc.scene().surfaces.size(); k += 2)
            hidden.insert(doc.scene().surfaces[k].id.value);
        for (std::uint32_t id : hidden)
            QVERIFY(doc.setHidden(SurfaceId{id}, true));
        KW_VERIFY_OK(m_renderer->render(doc, camera, RenderOptions{}));
        const AovBuffer some = m_renderer->aov();
        const FrameReport hiddenReport = m_renderer->lastReport();
        QCOMPARE(hiddenReport.surfaces, shown.surfaces - int(hidden.size()));
        QCOMPARE(hiddenReport.uploads, UploadStats{});
        int uncovered = 0, picked = 0;
        for (int y = 0; y < some.height; ++y)
            for (int x = 0; x < some.width; ++x) {
                const float id = some.pixel(x, y)[0];
                QVERIFY(id < 0.0f || !hidden.count(std::uint32_t(std::lround(id))));
                const float before = all.pixel(x, y)[0];
                if (before >= 0.0f && hidden.count(std::uint32_t(std::lround(before))) && id < 0.0f)
                    ++uncovered;
                if (x % 5 == 2 && y % 5 == 2 && before >= 0.0f) {
                    const std::optional<PickHit> h =
                        m_renderer->pick(doc, camera, QPointF(x + 0.5, y + 0.5));
                    QVERIFY(!h || !hidden.count(h->surface.value));
                    QCOMPARE(bool(h), id >= 0.0f);
                    picked += h ? 1 : 0;
                }
            }
        QVERIFY(uncovered > 100);
        QVERIFY(picked > 50);
        for (std::uint32_t id : hidden)
            QVERIFY(doc.setHidden(SurfaceId{id}, false));
        KW_VERIFY_OK(m_renderer->render(doc, camera, RenderOptions{}));
        QCOMPARE(m_renderer->lastReport().uploads, UploadStats{});
        QCOMPARE(m_renderer->lastReport().surfaces, shown.surfaces);
        const AovBuffer again = m_renderer->aov();
        for (int y = 0; y < again.height; ++y)
            for (int x = 0; x < again.width; ++x)
                QCOMPARE(again.pixel(x, y)[0], all.pixel(x, y)[0]);
    }

    void removingEverySurfaceFreesItsGpuData() {
        QString error;
        RenderOptions options;
        options.controlNet = true;
        Document empty;
        const FrameReport none = frame(empty, options);
        QVERIFY2(none.ok, qPrintable(none.error));
        QCOMPARE(none.gpuBytes, GpuBytes{});
        Document doc;
        const auto scene = kwtest::loadSample(QStringLiteral("trimmed_plate"));
        QVERIFY2(scene, qPrintable(scene.message()));
        KW_VERIFY_OK(doc.resetScene(*scene));
        options.mode = RenderMode::Tessellated;
        QVERIFY(frame(doc, options).gpuBytes.tessellatedMeshes > 0);
        options.mode = RenderMode::Exact;
        const FrameReport full = frame(doc, options);
        QVERIFY(full.gpuBytes.total() > full.gpuBytes.tessellatedMeshes);
        std::vector<SurfaceId> ids;
        for (const Surface& s : doc.scene().surfaces)
            ids.push_back(s.id);
        for (SurfaceId id : ids)
            QVERIFY(doc.removeSurface(id));
        const FrameReport after = frame(doc, options);
        QVERIFY2(after.ok, qPrintable(after.error));
        QCOMPARE(after.surfaces, 0);
        QCOMPARE(after.gpuBytes.controlPoints, none.gpuBytes.controlPoints);
        QCOMPARE(after.gpuBytes.spanTables, none.gpuBytes.spanTables);
        QCOMPARE(after.gpuBytes.basePolygons, none.gpuBytes.basePolygons);
        QCOMPARE(after.gpuBytes.tessellatedMeshes, none.gpuBytes.tessellatedMeshes);
        QCOMPARE(after.gpuBytes.controlNets, none.gpuBytes.controlNets);
        QCOMPARE(after.gpuBytes.trimMasks, none.gpuBytes.trimMasks);
        QCOMPARE(after.gpuBytes, none.gpuBytes);
        QCOMPARE(after.drawCalls, none.drawCalls);
    }
};

QTEST_MAIN(TestRenderScene)
#include "tst_render_scene.moc"
