// A partial frame's cells without GL (render/partial_cells.h, ExactPlanner): which cells of a
// base polygon its rectangle reaches, their runs in the triangle range whether or not the
// trims reordered it, the skirt segments and fins along them, and the planner's commands
// holding exactly those runs.
#include "render/exact_planner.h"
#include "render/gpu_scene.h"
#include "render/partial_cells.h"

#include <QtTest>
#include <memory>

using namespace kw;

namespace {

constexpr int kSide = 100; ///< the view, in pixels
constexpr int kCells = 10; ///< cells per side: each 10 x 10 pixels under the identity

/// A flat polygon of kCells x kCells cells over the whole view: with the identity as the
/// view-projection, cell (i, j) covers window pixels [10 i, 10 i + 10) x [10 j, 10 j + 10).
BasePolygon grid() {
    BasePolygon p;
    for (int k = 0; k <= kCells; ++k) {
        p.breaksU.push_back(double(k) / kCells);
        p.breaksV.push_back(double(k) / kCells);
    }
    p.spanU.assign(kCells, 3);
    p.spanV.assign(kCells, 3);
    for (int j = 0; j <= kCells; ++j)
        for (int i = 0; i <= kCells; ++i) {
            BaseVertex v{};
            v.position =
                glm::vec3(-1.0f + 2.0f * float(i) / kCells, -1.0f + 2.0f * float(j) / kCells, 0.0f);
            p.vertices.push_back(v);
        }
    return p;
}

/// The cells (i, j) with `bit` in `keep`, as i + kCells * j.
std::vector<int> cellsWith(const std::vector<std::uint8_t>& keep, std::uint8_t bit) {
    std::vector<int> out;
    for (int c = 0; c < int(keep.size()); ++c)
        if (keep[size_t(c)] & bit)
            out.push_back(c);
    return out;
}

/// Cells 2..3 across, 2..4 up: the rectangle (25, 25) - (35, 45).
const glm::ivec4 kReach(25, 25, 35, 45);
const std::vector<int> kReached = {22, 23, 32, 33, 42, 43};

SurfaceGpu surfaceOf(const BasePolygon& poly) {
    SurfaceGpu g;
    g.polygon = poly;
    g.degreeU = g.degreeV = 3;
    g.vertexOffset = 500;
    g.triangleOffset = 6000;
    g.triangleIndexCount = 6 * poly.cellCount();
    g.skirtVertexOffset = 9000;
    g.skirtIndexOffset = 7000;
    g.skirtIndexCount = 6 * (4 * kCells) + 12;
    return g;
}

} // namespace

class TestPartialCells : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void cellsReachingTheRectangle() {
        const BasePolygon poly = grid();
        const std::vector<std::uint8_t> keep =
            cellsReaching(poly, glm::mat4(1.0f), glm::ivec2(kSide), kReach, 6);
        QCOMPARE(int(keep.size()), kCells * kCells);
        QCOMPARE(cellsWith(keep, kCellTriangles), kReached);
        // Grown by the skirts' push of 6 pixels: (19, 19) - (41, 51), cells 1..4 x 1..5.
        std::vector<int> skirt;
        for (int j = 1; j <= 5; ++j)
            for (int i = 1; i <= 4; ++i)
                skirt.push_back(i + kCells * j);
        QCOMPARE(cellsWith(keep, kCellSkirt), skirt);
        // A rectangle that ends where a cell starts does not reach it (exclusive ends).
        const std::vector<std::uint8_t> edge =
            cellsReaching(poly, glm::mat4(1.0f), glm::ivec2(kSide), {20, 20, 30, 30}, 0);
        QCOMPARE(cellsWith(edge, kCellTriangles), std::vector<int>({22}));
        // A node behind the eye: any cell may reach it.
        BasePolygon behind = poly;
        glm::mat4 flip(1.0f);
        flip[3][3] = -1.0f; // w = -1 for every point
        QVERIFY(cellsReaching(behind, flip, glm::ivec2(kSide), kReach, 6).empty());
        // No vertices on the CPU: likewise.
        behind.vertices.clear();
        QVERIFY(cellsReaching(behind, glm::mat4(1.0f), glm::ivec2(kSide), kReach, 6).empty());
    }

    void runsFollowTheDrawingOrder() {
        SurfaceGpu g = surfaceOf(grid());
        const std::vector<std::uint8_t> keep =
            cellsReaching(g.polygon, glm::mat4(1.0f), glm::ivec2(kSide), kReach, 0);
        // Row by row: one run per row of two cells, merged across the rows' gap of 8 cells.
        QCOMPARE(cellRuns(g, keep, kCellTriangles, 0),
                 (std::vector<CellRun>{{22, 2}, {32, 2}, {42, 2}}));
        QCOMPARE(cellRuns(g, keep, kCellTriangles, 8), (std::vector<CellRun>{{22, 22}}));
        QCOMPARE(cellRuns(g, keep, kCellTriangles, 7),
                 (std::vector<CellRun>{{22, 2}, {32, 2}, {42, 2}}));
        // Split (kw::splitCells): the left half's cells first (bucket 0), row by row, then the
        // right half's; cell (i, j) of the left half is at 5 j + i.
        g.cellBuckets.assign(size_t(kCells * kCells), 0);
        for (int j = 0; j < kCells; ++j)
            for (int i = 5; i < kCells; ++i)
                g.cellBuckets[size_t(i + kCells * j)] = 1;
        QCOMPARE(cellRuns(g, keep, kCellTriangles, 0),
                 (std::vector<CellRun>{{12, 2}, {17, 2}, {22, 2}}));
        // A cell of the right half: after all 50 of the left's.
        std::vector<std::uint8_t> right(keep.size(), 0);
        right[size_t(7 + kCells * 1)] = kCellTriangles; // position 50 + 5 + 2
        QCOMPARE(cellRuns(g, right, kCellTriangles, 0), (std::vector<CellRun>{{57, 1}}));
    }

    void skirtSegmentsAlongReachedCells() {
        const SurfaceGpu g = surfaceOf(grid());
        std::vector<std::uint8_t> keep(size_t(kCells * kCells), 0);
        keep[0] = kCellSkirt; // the corner cell (0, 0): its bottom and left segments, corner
        bool whole = true;
        QCOMPARE(skirtRuns(g, keep, 0, whole),
                 (std::vector<CellRun>{{0, 6}, {6 * 30, 6}, {6 * 40, 3}}));
        QVERIFY(!whole);
        // The right side's segment k borders cell (9, k); the top's, cell (k, 9).
        keep.assign(keep.size(), 0);
        keep[size_t(9 + kCells * 4)] = kCellSkirt;
        keep[size_t(3 + kCells * 9)] = kCellSkirt;
        QCOMPARE(skirtRuns(g, keep, 0, whole), (std::vector<CellRun>{{6 * 14, 6}, {6 * 23, 6}}));
        // Triangle bits alone keep no skirt.
        keep.assign(keep.size(), kCellTriangles);
        QVERIFY(skirtRuns(g, keep, 0, whole).empty());
        // Not buildSkirt's layout: drawn whole.
        SurfaceGpu other = g;
        other.skirtIndexCount -= 3;
        QVERIFY(skirtRuns(other, keep, 0, whole).empty());
        QVERIFY(whole);
    }

    void finsReachingTheRectangle() {
        // Two fins as buildFins lays them out: 4 vertices and 6 indices each.
        std::vector<SkirtVertex> vertices;
        std::vector<unsigned> indices;
        for (const glm::vec2 at : {glm::vec2(-0.4f, -0.3f), glm::vec2(0.6f, 0.6f)}) {
            const unsigned first = unsigned(vertices.size());
            for (const glm::vec2 d : {glm::vec2(0.0f), glm::vec2(0.02f, 0.0f),
                                      glm::vec2(0.0f, 0.02f), glm::vec2(0.02f)}) {
                SkirtVertex v{};
                v.base.position = glm::vec3(at + d, 0.0f);
                vertices.push_back(v);
            }
            indices.insert(indices.end(),
                           {first, first + 1, first + 3, first, first + 3, first + 2});
        }
        // The first lies at pixels (30, 35) - (31, 36), in kReach; the second far from it.
        QCOMPARE(finsReaching(vertices, indices, glm::mat4(1.0f), glm::ivec2(kSide), kReach, 0),
                 (std::vector<unsigned>{0, 1, 3, 0, 3, 2}));
        QVERIFY(
            finsReaching(vertices, indices, glm::mat4(1.0f), glm::ivec2(kSide), {0, 0, 10, 10}, 0)
                .empty());
        // Its outer edge may be pushed past its nodes: 3 px right of a rectangle ending at x = 27
        // it reaches it with a push of 4 px, not without.
        const glm::ivec4 left(10, 25, 27, 45);
        QVERIFY(
            finsReaching(vertices, indices, glm::mat4(1.0f), glm::ivec2(kSide), left, 0).empty());
        QCOMPARE(finsReaching(vertices, indices, glm::mat4(1.0f), glm::ivec2(kSide), left, 4),
                 (std::vector<unsigned>{0, 1, 3, 0, 3, 2}));
    }

    /// The planner sends exactly the reached cells' runs, in every batch that draws the
    /// record's triangles, and its skirt's segments along them; a whole frame sends all.
    void plannerSendsTheReachedCells() {
        auto record = std::make_unique<SurfaceRecord>();
        record->exact = std::make_unique<SurfaceGpu>(surfaceOf(grid()));
        record->slot = 4;
        record->bounded = true;
        record->boundsLo = glm::vec3(-1.0f, -1.0f, 0.0f);
        record->boundsHi = glm::vec3(1.0f, 1.0f, 0.0f);
        std::vector<SurfaceRecord*> order{record.get()}, touched;
        const ExactPlanScene scene{this, 1, 0, &order, &touched, [](int) {
                                       return 0;
                                   }};
        RenderOptions o;
        o.partitioning = RenderOptions::Partitioning::Adaptive;
        FrameCamera cam;
        cam.viewProjection = glm::mat4(1.0f);
        cam.viewport = glm::ivec2(kSide);
        ExactPlanner plan;
        std::vector<ExactPlanner::CommandWrite> writes;
        plan.update(scene, ExactPlanner::keyFor(scene, cam, o, false, false, false), cam, writes);
        QCOMPARE(plan.cellsSent(), std::int64_t(kCells * kCells));
        QCOMPARE(plan.variants().begin()->second.commands.size(), size_t(1));

        cam.reach = kReach;
        plan.update(scene, ExactPlanner::keyFor(scene, cam, o, false, false, false), cam, writes);
        // Rows 2, 3 and 4, cells 2 and 3 of each, 8 cells apart: one band from cell 22 to 43
        // (kCellRunGap merges them).
        QVERIFY(kCellRunGap >= 8);
        QCOMPARE(plan.cellsSent(), std::int64_t(22));
        const std::vector<IndirectCommand> rows = {{6 * 22, 1, 6000 + 6 * 22, 500, 4}};
        QCOMPARE(plan.variants().size(), size_t(1));
        QVERIFY(plan.variants().begin()->second.commands == rows);
        QCOMPARE(plan.plain().size(), size_t(1));
        QVERIFY(plan.plain().begin()->second.commands == rows);
        // Skirts: the cells the push reaches border no side of the polygon, so none.
        for (const auto& [k, b] : plan.skirts())
            QVERIFY(b.commands.empty());
        // Near the bottom edge: the bottom side's segments under the reached cells.
        cam.reach = glm::ivec4(25, 0, 35, 5);
        plan.update(scene, ExactPlanner::keyFor(scene, cam, o, false, false, false), cam, writes);
        QCOMPARE(plan.skirts().size(), size_t(1));
        const ExactBatch& skirt = plan.skirts().begin()->second;
        const int push = int(std::ceil(skirtPushPixels(o.pixelTolerance + 0.35)));
        QVERIFY(push > 0 && push < 10);
        // Pushed 4 pixels: (21, -4) - (39, 9), the bottom row's cells 2 and 3 and their
        // bottom segments.
        QCOMPARE(push, 4);
        QVERIFY(skirt.commands == std::vector<IndirectCommand>({{12, 1, 7000 + 6 * 2, 9000, 4}}));
        QVERIFY(plan.variants().begin()->second.commands ==
                std::vector<IndirectCommand>({{12, 1, 6000 + 6 * 2, 500, 4}}));
    }
};

QTEST_MAIN(TestPartialCells)
#include "tst_partial_cells.moc"
