// GL test: the polygon pools are packed when they hold more than twice what the polygons need.
// A fitted view of fine polygons leaves the pools far above what a close-up (one patch's cells
// in view) needs: after each frame no polygon pool keeps that slack, and every frame of the
// sequence (close-ups, views back out, fine again) draws the same bytes (colour and AOV) as a
// fresh renderer drawing that view alone.
#include "expected_test_util.h"
#include "render/offscreen_renderer.h"
#include "render/renderer_test_hook.h"
#include "render_test_util.h"

using namespace kw;

namespace {

constexpr QSize kSize(256, 192);

using Frame = kwtest::DrawnFrame;

/// Drawn in a renderer of its own: no pool history.
Expected<Frame> fresh(const Document& doc, const Camera& cam, const RenderOptions& opt) {
    auto made = kwtest::offscreenRenderer(kSize, true);
    if (!made)
        return made.error();
    return kwtest::drawFrame(**made, doc, cam, opt);
}

struct PoolState {
    const char* name;
    std::int64_t capacity, used;
};

std::vector<PoolState> polygonPools(OffscreenRenderer& r) {
    const ScenePools& p = RendererTestHook::scene(r.renderer()).pools();
    std::vector<PoolState> out;
    for (const auto& [name, pool] : {std::pair{"vertices", &p.vertices},
                                     {"triangles", &p.triangles},
                                     {"skirt vertices", &p.skirtVertices},
                                     {"skirt indices", &p.skirtIndices}})
        out.push_back({name, pool->residentBytes() / pool->elementBytes(), pool->usedElements()});
    return out;
}

} // namespace

class TestRenderPoolCompaction : public QObject {
    Q_OBJECT

private Q_SLOTS:
    void policy() {
        // More than twice the packed size is due; a pool just grown by doubling is not.
        QVERIFY(!GpuPool::shouldCompact(0, 0));
        QVERIFY(!GpuPool::shouldCompact(2048, 0));
        QVERIFY(!GpuPool::shouldCompact(2 * 1024, 1000)); // 1000 pack into 1250
        QVERIFY(GpuPool::shouldCompact(32768, 12360));    // the screw's close-up vertices
        QVERIFY(!GpuPool::shouldCompact(131072, 72588));  // doubled for what it holds
        QCOMPARE(GpuPool::compactedCapacity(12360), std::int64_t(15450));
        QCOMPARE(GpuPool::compactedCapacity(10), GpuPool::kMinElements);
        QVERIFY(!GpuPool::shouldCompact(2 * GpuPool::compactedCapacity(5000), 5000));
        QVERIFY(GpuPool::shouldCompact(2 * GpuPool::compactedCapacity(5000) + 1, 5000));
    }

    void closeUpGivesTheSlackBack() {
        auto made = kwtest::offscreenRenderer(kSize, true);
        QVERIFY2(made, qPrintable(made.message()));
        OffscreenRenderer& r = **made;
        Document doc;
        KW_VERIFY_OK(doc.resetScene(kwtest::variantGrid(12)));
        RenderOptions fine;
        fine.partitioning = RenderOptions::Partitioning::Adaptive;
        fine.pixelTolerance = kMinPixelTolerance; // every patch's polygon fine: a high-water mark
        RenderOptions opt = fine;
        opt.pixelTolerance = 0.5;
        const double aspect = double(kSize.width()) / kSize.height();
        const Camera fit = fitCamera(doc.scene(), aspect);
        // Close-ups on the last patch: the others keep one cell, its polygon is rebuilt.
        const Surface& patch = doc.scene().surfaces.back();
        const Camera near = kwtest::zoomedOn(fit, patch, {0.4, 0.6}, 6.0);
        const Camera nearer = kwtest::zoomedOn(fit, patch, {0.4, 0.6}, 40.0);
        const std::pair<const Camera*, const RenderOptions*> views[] = {
            {&fit, &fine}, {&near, &opt}, {&fit, &opt}, {&nearer, &opt}, {&fit, &fine}};
        std::vector<Frame> frames;
        std::vector<std::int64_t> vertexCapacity;
        for (const auto& [cam, o] : views) {
            auto f = kwtest::drawFrame(r, doc, *cam, *o);
            QVERIFY2(f, qPrintable(f.message()));
            frames.push_back(*f);
            for (const PoolState& p : polygonPools(r)) {
                qInfo("%s: capacity %lld, used %lld", p.name, (long long)p.capacity,
                      (long long)p.used);
                QVERIFY2(!GpuPool::shouldCompact(p.capacity, p.used), p.name);
            }
            vertexCapacity.push_back(polygonPools(r)[0].capacity);
        }
        // The fine polygons' pools were given back at the close-up.
        QVERIFY(2 * vertexCapacity[1] < vertexCapacity[0]);
        // Every frame as a renderer without that history draws it.
        for (size_t k = 0; k < std::size(views); ++k) {
            auto alone = fresh(doc, *views[k].first, *views[k].second);
            QVERIFY2(alone, qPrintable(alone.message()));
            QCOMPARE(kwtest::differingPixels(frames[k], *alone), 0);
        }
    }

    void editGivesTheSlackBack() {
        // One view throughout: a patch's slider minimum falls from fine to coarse, so its
        // polygon shrinks in an incremental sync and the packing moves the other patches'
        // polygons too: their draw commands must follow (the layout stamp), though none of
        // them changed.
        auto made = kwtest::offscreenRenderer(kSize, true);
        QVERIFY2(made, qPrintable(made.message()));
        OffscreenRenderer& r = **made;
        Document doc;
        KW_VERIFY_OK(doc.resetScene(kwtest::variantGrid(12)));
        const SurfaceId first = doc.scene().surfaces.front().id;
        KW_VERIFY_OK(doc.setPartitions(first, 120, 120));
        RenderOptions opt;
        opt.partitioning = RenderOptions::Partitioning::Adaptive;
        const Camera fit = fitCamera(doc.scene(), double(kSize.width()) / kSize.height());
        auto before = kwtest::drawFrame(r, doc, fit, opt);
        QVERIFY2(before, qPrintable(before.message()));
        const std::int64_t grown = polygonPools(r)[0].capacity;
        KW_VERIFY_OK(doc.setPartitions(first, 6, 6));
        auto after = kwtest::drawFrame(r, doc, fit, opt);
        QVERIFY2(after, qPrintable(after.message()));
        qInfo("vertex pool: %lld elements, then %lld (%lld used)", (long long)grown,
              (long long)polygonPools(r)[0].capacity, (long long)polygonPools(r)[0].used);
        QVERIFY(2 * polygonPools(r)[0].capacity < grown);
        auto alone = fresh(doc, fit, opt);
        QVERIFY2(alone, qPrintable(alone.message()));
        QCOMPARE(kwtest::differingPixels(*after, *alone), 0);
    }
};

QTEST_MAIN(TestRenderPoolCompaction)
#include "tst_render_pool_compaction.moc"
