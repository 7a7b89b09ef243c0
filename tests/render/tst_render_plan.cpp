// The exact pass's planner (render/exact_planner.h) without GL: surfaces grouped by variant
// into batches whose commands are laid out in one buffer, culling outside the view, trimmed
// surfaces in the pre-pass and edge batches, closed solids' back faces, and a moved record
// patched in place while a changed variant or key builds the plan again.
#include "render/exact_planner.h"
#include "render/gpu_scene.h"

#include <QtTest>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>

using namespace kw;

namespace {

/// Records with exact data but no GL objects, as GpuScene would hold them after a sync.
struct Records {
    std::vector<std::unique_ptr<SurfaceRecord>> owned;
    std::vector<std::unique_ptr<Surface>> surfaces;
    std::vector<SurfaceRecord*> order, touched;
    std::map<int, int> members;
    std::uint64_t layout = 1;

    /// A record of degrees (p, q) whose 10 triangles start at `first` and whose control bounds
    /// are the unit box at `at`.
    SurfaceRecord& add(int p, int q, glm::vec3 at = glm::vec3(0.0f), int solid = -1) {
        auto s = std::make_unique<Surface>();
        s->solid = solid;
        auto r = std::make_unique<SurfaceRecord>();
        r->surface = s.get();
        r->exact = std::make_unique<SurfaceGpu>();
        r->exact->degreeU = p;
        r->exact->degreeV = q;
        r->exact->triangleIndexCount = 30;
        r->exact->triangleOffset = std::int64_t(owned.size()) * 30;
        r->exact->vertexOffset = std::int64_t(owned.size()) * 16;
        r->slot = int(owned.size());
        r->bounded = true;
        r->boundsLo = at - glm::vec3(0.5f);
        r->boundsHi = at + glm::vec3(0.5f);
        if (solid >= 0)
            ++members[solid];
        order.push_back(r.get());
        surfaces.push_back(std::move(s));
        owned.push_back(std::move(r));
        return *order.back();
    }
    ExactPlanScene scene() const {
        return ExactPlanScene{this, layout, 0, &order, &touched, [this](int solid) {
                                  const auto it = members.find(solid);
                                  return it == members.end() ? 0 : it->second;
                              }};
    }
};

/// Looking down -z at the origin from 10 units, 100 x 100 pixels.
FrameCamera camera() {
    FrameCamera c;
    c.eye = glm::vec3(0.0f, 0.0f, 10.0f);
    c.view = glm::lookAt(c.eye, glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    c.nearPlane = 0.1f;
    c.farPlane = 100.0f;
    c.projection = glm::perspective(glm::radians(45.0f), 1.0f, c.nearPlane, c.farPlane);
    c.viewProjection = c.projection * c.view;
    c.viewport = glm::ivec2(100, 100);
    return c;
}

int commandsIn(const std::map<int, ExactBatch>& batches) {
    int n = 0;
    for (const auto& [k, b] : batches)
        n += int(b.commands.size());
    return n;
}

/// Every batch's commands are where its `first` says in the plan's buffer.
bool laidOut(const ExactPlanner& plan) {
    for (const auto* batches : {&plan.plain(), &plan.trimmedPrepass(), &plan.variants(),
                                &plan.edges(), &plan.skirts(), &plan.backFaces()})
        for (const auto& [k, b] : *batches)
            for (size_t i = 0; i < b.commands.size(); ++i)
                if (!(plan.commands().at(size_t(b.first) + i) == b.commands[i]))
                    return false;
    return true;
}

} // namespace

class TestRenderPlan : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void surfacesGroupByVariant() {
        Records rs;
        for (int k = 0; k < 3; ++k)
            rs.add(3, 3);
        rs.add(1, 2);
        rs.add(1, 2);
        RenderOptions o; // depth pre-pass, uniform partitions
        const FrameCamera cam = camera();
        const ExactPlanKey key = ExactPlanner::keyFor(rs.scene(), cam, o, false, false, false);
        ExactPlanner plan;
        std::vector<ExactPlanner::CommandWrite> writes;
        QVERIFY(plan.update(rs.scene(), key, cam, writes)); // the first plan is built
        QCOMPARE(int(plan.variants().size()), 2);           // two degree pairs
        QCOMPARE(commandsIn(plan.variants()), 5);
        QCOMPARE(int(plan.plain().size()), 1); // one untrimmed pre-pass batch for all
        QCOMPARE(commandsIn(plan.plain()), 5);
        QCOMPARE(int(plan.commands().size()), 10);
        QVERIFY(laidOut(plan));
        for (const auto& [k, b] : plan.variants()) {
            QVERIFY(!b.trimmed);
            // Document order within a batch, each command the record's range and table row.
            std::uint32_t last = 0;
            for (const IndirectCommand& c : b.commands) {
                QCOMPARE(c.count, 30u);
                QVERIFY(c.firstIndex == 0 || c.firstIndex > last);
                QCOMPARE(c.firstIndex, c.baseInstance * 30u);
                last = c.firstIndex;
            }
        }
        QVERIFY(plan.edges().empty() && plan.skirts().empty() && plan.trimmedPrepass().empty());
        // Exact depth: no pre-pass batches.
        o.shading = RenderOptions::Shading::ExactDepth;
        QVERIFY(plan.update(rs.scene(),
                            ExactPlanner::keyFor(rs.scene(), cam, o, false, false, false), cam,
                            writes));
        QVERIFY(plan.plain().empty());
        QCOMPARE(commandsIn(plan.variants()), 5);
    }

    void outsideTheViewIsCulled() {
        Records rs;
        rs.add(2, 2);
        SurfaceRecord& far = rs.add(2, 2, glm::vec3(200.0f, 0.0f, 0.0f));
        RenderOptions o;
        const FrameCamera cam = camera();
        ExactPlanner plan;
        std::vector<ExactPlanner::CommandWrite> writes;
        plan.update(rs.scene(), ExactPlanner::keyFor(rs.scene(), cam, o, false, false, false), cam,
                    writes);
        QCOMPARE(plan.culled(), 1);
        QCOMPARE(commandsIn(plan.variants()), 1);
        QVERIFY(plan.place(&far)->culled);
        o.cullOutsideView = false;
        plan.update(rs.scene(), ExactPlanner::keyFor(rs.scene(), cam, o, false, false, false), cam,
                    writes);
        QCOMPARE(plan.culled(), 0);
        QCOMPARE(commandsIn(plan.variants()), 2);
    }

    void trimmedSurfacesTestTheirTrims() {
        Records rs;
        rs.add(3, 3);
        SurfaceRecord& trimmed = rs.add(3, 3);
        trimmed.mask.active = true;
        trimmed.mask.layer = 0;
        RenderOptions o;
        const FrameCamera cam = camera();
        ExactPlanner plan;
        std::vector<ExactPlanner::CommandWrite> writes;
        // With the pre-pass the trims are tested there: the shading variant needs no lookup.
        plan.update(rs.scene(), ExactPlanner::keyFor(rs.scene(), cam, o, true, false, false), cam,
                    writes);
        QCOMPARE(commandsIn(plan.trimmedPrepass()), 1);
        QCOMPARE(commandsIn(plan.plain()), 1);
        QCOMPARE(int(plan.variants().size()), 1);
        QVERIFY(!plan.variants().begin()->second.trimmed);
        QCOMPARE(commandsIn(plan.edges()), 1); // the anti-aliased edge pass's batch
        QVERIFY(plan.edges().begin()->second.trimmed);
        // Exact depth looks the trims up in the shading pass: a trimmed variant of its own.
        o.shading = RenderOptions::Shading::ExactDepth;
        plan.update(rs.scene(), ExactPlanner::keyFor(rs.scene(), cam, o, true, false, false), cam,
                    writes);
        QCOMPARE(int(plan.variants().size()), 2);
        QVERIFY(plan.variants().at(plan.place(&trimmed)->variant).trimmed);
        // Trims off: one variant again.
        plan.update(rs.scene(), ExactPlanner::keyFor(rs.scene(), cam, o, false, false, false), cam,
                    writes);
        QCOMPARE(int(plan.variants().size()), 1);
    }

    void adaptiveFramesGetSkirtsAndRoutes() {
        Records rs;
        SurfaceRecord& a = rs.add(2, 2);
        a.exact->skirtIndexOffset = 1000;
        a.exact->skirtIndexCount = 12;
        rs.add(1, 1, glm::vec3(1.0f, 0.0f, 0.0f)).exact->affine = true;
        RenderOptions o;
        o.partitioning = RenderOptions::Partitioning::Adaptive;
        const FrameCamera cam = camera();
        ExactPlanner plan;
        std::vector<ExactPlanner::CommandWrite> writes;
        plan.update(rs.scene(), ExactPlanner::keyFor(rs.scene(), cam, o, false, false, true), cam,
                    writes);
        QCOMPARE(commandsIn(plan.skirts()), 1);
        QCOMPARE(plan.skirts().begin()->second.commands[0].count, 12u);
        QCOMPARE(plan.affineSurfaces(), 1);
        // Two routes (degrees and affine), stencil values 1 and 2, both shaded deferred.
        QCOMPARE(int(plan.routes().size()), 2);
        int stencil = 0;
        for (const auto& [k, r] : plan.routes())
            QCOMPARE(r.stencil, ++stencil);
        QCOMPARE(plan.deferredSurfaces(), 2);
        QCOMPARE(int(plan.plain().size()), 2); // one pre-pass batch per route
        // Anti-aliased (coverage) frames have no skirts; affine without the step only when on.
        o.affineWithoutNewton = false;
        plan.update(rs.scene(), ExactPlanner::keyFor(rs.scene(), cam, o, false, true, false), cam,
                    writes);
        QVERIFY(plan.skirts().empty());
        QCOMPARE(plan.affineSurfaces(), 0);
        // Every surface's cells large: none deferred.
        o.deferMaxCellPixels = 0.0;
        plan.update(rs.scene(), ExactPlanner::keyFor(rs.scene(), cam, o, false, false, true), cam,
                    writes);
        QCOMPARE(plan.deferredSurfaces(), 0);
        QVERIFY(plan.routes().empty());
    }

    void closedSolidsSkipTheirBackFaces() {
        Records rs;
        rs.add(2, 2, glm::vec3(0.0f), 7);
        rs.add(2, 2, glm::vec3(0.5f, 0.0f, 0.0f), 7);
        rs.surfaces[1]->outsideAlongNormal = false;
        RenderOptions o;
        const FrameCamera cam = camera();
        ExactPlanner plan;
        std::vector<ExactPlanner::CommandWrite> writes;
        plan.update(rs.scene(), ExactPlanner::keyFor(rs.scene(), cam, o, false, false, false), cam,
                    writes);
        QVERIFY(plan.backCulled() == std::set<int>{7});
        QCOMPARE(plan.place(rs.order[0])->face, 1); // the back ones
        QCOMPARE(plan.place(rs.order[1])->face, 2); // turned: the front ones
        // A member missing (hidden, or too large for the GPU): a hole, every face drawn.
        rs.members[7] = 3;
        ++rs.layout;
        plan.update(rs.scene(), ExactPlanner::keyFor(rs.scene(), cam, o, false, false, false), cam,
                    writes);
        QVERIFY(plan.backCulled().empty());
        QCOMPARE(plan.place(rs.order[0])->face, 0);
        QVERIFY(plan.backFaces().empty());
    }

    // The skipped side is drawn once more, last, where nothing nearer covered a pixel (a seam's
    // sub-pixel gap between two faces' trims): each culled face in a batch of its own side, a
    // trimmed one with the trim lookup (no pre-pass tests its trims), none in coverage frames.
    void skippedSideFillsTheSeams() {
        Records rs;
        rs.add(2, 2, glm::vec3(0.0f), 7);
        SurfaceRecord& trimmed = rs.add(2, 2, glm::vec3(0.5f, 0.0f, 0.0f), 7);
        trimmed.mask.active = true;
        trimmed.mask.layer = 0;
        rs.add(2, 2, glm::vec3(-0.5f, 0.0f, 0.0f)); // no solid: both sides drawn already
        RenderOptions o;
        const FrameCamera cam = camera();
        ExactPlanner plan;
        std::vector<ExactPlanner::CommandWrite> writes;
        plan.update(rs.scene(), ExactPlanner::keyFor(rs.scene(), cam, o, true, false, false), cam,
                    writes);
        QVERIFY(plan.backCulled() == std::set<int>{7});
        QCOMPARE(commandsIn(plan.backFaces()), 2);
        const ExactPlace* t = plan.place(&trimmed);
        QVERIFY(t->backVariant >= 0 && plan.place(rs.order[2])->backVariant < 0);
        const ExactBatch& b = plan.backFaces().at(t->backVariant);
        QVERIFY(b.trimmed);
        QCOMPARE(b.face, 1);
        QVERIFY(!plan.variants().at(t->variant).trimmed); // the pre-pass tests the others'
        QVERIFY(!plan.backFaces().at(plan.place(rs.order[0])->backVariant).trimmed);
        QVERIFY(laidOut(plan));
        // A moved face's command is patched there too.
        trimmed.exact->triangleIndexCount = 24;
        rs.touched = {&trimmed};
        QVERIFY(!plan.update(
            rs.scene(), ExactPlanner::keyFor(rs.scene(), cam, o, true, false, false), cam, writes));
        QCOMPARE(plan.backFaces().at(t->backVariant).commands.at(size_t(t->backIndex)).count, 24u);
        QVERIFY(laidOut(plan));
        // Anti-aliased by coverage: no skirts and no fill (the edge pass blends what is there).
        plan.update(rs.scene(), ExactPlanner::keyFor(rs.scene(), cam, o, true, true, false), cam,
                    writes);
        QVERIFY(plan.backFaces().empty());
    }

    void movedRecordIsPatchedInPlace() {
        Records rs;
        for (int k = 0; k < 4; ++k)
            rs.add(3, 3);
        RenderOptions o;
        const FrameCamera cam = camera();
        ExactPlanner plan;
        std::vector<ExactPlanner::CommandWrite> writes;
        const ExactPlanKey key = ExactPlanner::keyFor(rs.scene(), cam, o, false, false, false);
        QVERIFY(plan.update(rs.scene(), key, cam, writes));
        // Nothing touched: nothing to write.
        QVERIFY(!plan.update(rs.scene(), key, cam, writes));
        QVERIFY(writes.empty());
        // Its polygon rebuilt with fewer triangles: two commands change (shading, pre-pass).
        SurfaceRecord& moved = *rs.order[2];
        moved.exact->triangleIndexCount = 24;
        rs.touched = {&moved};
        QVERIFY(!plan.update(rs.scene(), key, cam, writes));
        QCOMPARE(int(writes.size()), 2);
        for (const auto& w : writes) {
            QCOMPARE(w.command.count, 24u);
            QCOMPARE(plan.commands().at(size_t(w.at)).count, 24u);
        }
        QVERIFY(laidOut(plan));
        // A new degree is another variant: the plan is built again.
        moved.exact->degreeU = 2;
        QVERIFY(plan.update(rs.scene(), key, cam, writes));
        QCOMPARE(int(plan.variants().size()), 2);
        // So is any change of the key (here the viewport).
        rs.touched.clear();
        FrameCamera wider = cam;
        wider.viewport = glm::ivec2(200, 100);
        QVERIFY(plan.update(rs.scene(),
                            ExactPlanner::keyFor(rs.scene(), wider, o, false, false, false), wider,
                            writes));
        // Forgotten plans are built again.
        plan.clear();
        QVERIFY(plan.update(rs.scene(),
                            ExactPlanner::keyFor(rs.scene(), wider, o, false, false, false), wider,
                            writes));
    }
};

QTEST_GUILESS_MAIN(TestRenderPlan)
#include "tst_render_plan.moc"
