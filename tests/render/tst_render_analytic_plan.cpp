// The exact pass's planner (no GL) with faces that kept an analytic form: they batch apart
// (variant bit 14), never with the gather, in every pass that shades them and in their own
// deferred route; only in adaptive frames, only with RenderOptions::analyticFaces; an affine
// polygon keeps its cheaper way; and a touched record whose form an edit dropped is planned
// again the NURBS way.
#include "render/exact_planner.h"
#include "render/gpu_scene.h"

#include <QtTest>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>

using namespace kw;

namespace {

/// A cylinder's form (the planner only asks whether it is usable).
AnalyticForm cylinderForm() {
    AnalyticForm f;
    f.kind = AnalyticForm::Kind::Cylinder;
    f.radius = 1.0;
    f.u = AnalyticParamMap{AnalyticParamMap::Kind::HalfAngle, 0.0, 6.283185307179586};
    f.v = AnalyticParamMap{AnalyticParamMap::Kind::Linear, 0.0, 2.0};
    return f;
}

/// Records with exact data and no GL objects, as GpuScene holds them after a sync.
struct Records {
    std::vector<std::unique_ptr<SurfaceRecord>> owned;
    std::vector<std::unique_ptr<Surface>> surfaces;
    std::vector<SurfaceRecord*> order, touched;

    SurfaceRecord& add(int p, int q, bool analytic, glm::vec3 at = glm::vec3(0.0f)) {
        auto s = std::make_unique<Surface>();
        if (analytic)
            s->analytic = cylinderForm();
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
        order.push_back(r.get());
        surfaces.push_back(std::move(s));
        owned.push_back(std::move(r));
        return *order.back();
    }
    ExactPlanScene scene() const {
        return ExactPlanScene{this, 1, 0, &order, &touched, [](int) {
                                  return 0;
                              }};
    }
};

FrameCamera camera() {
    FrameCamera c;
    c.eye = glm::vec3(0.0f, 0.0f, 10.0f);
    c.view = glm::lookAt(c.eye, glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    c.projection = glm::perspective(glm::radians(45.0f), 1.0f, 0.1f, 100.0f);
    c.viewProjection = c.projection * c.view;
    c.viewport = glm::ivec2(100, 100);
    return c;
}

} // namespace

class TestRenderAnalyticPlan : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void analyticFacesBatchApart() {
        Records rs;
        SurfaceRecord& cylinder = rs.add(2, 1, true);
        rs.add(2, 1, false, glm::vec3(1.0f, 0.0f, 0.0f));
        SurfaceRecord& plane = rs.add(1, 1, true, glm::vec3(-1.0f, 0.0f, 0.0f));
        plane.exact->affine = true;
        RenderOptions o;
        o.partitioning = RenderOptions::Partitioning::Adaptive;
        o.gatherMinCellPixels = 0.0; // the gather wherever allowed
        const FrameCamera cam = camera();
        ExactPlanner plan;
        std::vector<ExactPlanner::CommandWrite> writes;
        plan.update(rs.scene(), ExactPlanner::keyFor(rs.scene(), cam, o, false, false, true), cam,
                    writes);
        // The cylinder alone: the affine plane keeps its polygon's (u, v).
        QCOMPARE(plan.analyticSurfaces(), 1);
        QCOMPARE(plan.affineSurfaces(), 1);
        const ExactPlace* p = plan.place(&cylinder);
        QVERIFY(p && ((p->variant >> 14) & 1));
        const ExactBatch& b = plan.variants().at(p->variant);
        QVERIFY(b.analytic && !b.gather && b.commands.size() == 1);
        // Its own route: the NURBS one of the same degrees, the affine one, the analytic one.
        QCOMPARE(int(plan.routes().size()), 3);
        QVERIFY(plan.routes().count(p->route()));
        QCOMPARE(int(plan.plain().size()), 3);
        // Off: the same surfaces the NURBS way.
        o.analyticFaces = false;
        plan.update(rs.scene(), ExactPlanner::keyFor(rs.scene(), cam, o, false, false, true), cam,
                    writes);
        QCOMPARE(plan.analyticSurfaces(), 0);
        QCOMPARE(int(plan.routes().size()), 2);
        // Uniform partitions: the paper's (u, v), no ray, no closed form either.
        o.analyticFaces = true;
        o.partitioning = RenderOptions::Partitioning::Uniform;
        plan.update(rs.scene(), ExactPlanner::keyFor(rs.scene(), cam, o, false, false, false), cam,
                    writes);
        QCOMPARE(plan.analyticSurfaces(), 0);
    }

    // Crossed by a section plane, an analytic face and a NURBS face of the same degrees go to
    // two section batches: a batch's program takes its closed form from its first record.
    void crossedAnalyticFacesBatchApart() {
        Records rs;
        SurfaceRecord& cylinder = rs.add(2, 1, true);
        SurfaceRecord& nurbs = rs.add(2, 1, false, glm::vec3(1.0f, 0.0f, 0.0f));
        RenderOptions o;
        o.partitioning = RenderOptions::Partitioning::Adaptive;
        o.sections = {SectionPlane{glm::dvec3(0.0), glm::dvec3(0.0, 1.0, 0.0), false}};
        const FrameCamera cam = camera();
        ExactPlanner plan;
        std::vector<ExactPlanner::CommandWrite> writes;
        plan.update(rs.scene(), ExactPlanner::keyFor(rs.scene(), cam, o, false, false, true), cam,
                    writes);
        const ExactPlace* pc = plan.place(&cylinder);
        const ExactPlace* pn = plan.place(&nurbs);
        QVERIFY(pc && pn && pc->sectionVariant >= 0 && pn->sectionVariant >= 0);
        QVERIFY(pc->sectionVariant != pn->sectionVariant);
        QCOMPARE(int(plan.sections().size()), 2);
        QVERIFY(plan.sections().at(pc->sectionVariant).analytic);
        QVERIFY(!plan.sections().at(pn->sectionVariant).analytic);
    }

    // A face drawn by its cover (SurfaceGpu::cover) is sent once, to the exact-depth pass of
    // sections(), its boxes' inside faces only: no pre-pass (its boxes are no chords of it), no
    // shading, skirt or route; a touched record keeps its place, patched in place.
    void coversGoToTheExactDepthPass() {
        Records rs;
        SurfaceRecord& cylinder = rs.add(2, 1, true);
        SurfaceRecord& nurbs = rs.add(2, 1, false, glm::vec3(1.0f, 0.0f, 0.0f));
        cylinder.exact->cover = true;
        cylinder.exact->coverBoxes = 4;
        cylinder.exact->skirtIndexOffset = nurbs.exact->skirtIndexOffset = 0;
        cylinder.exact->skirtIndexCount = nurbs.exact->skirtIndexCount = 12;
        RenderOptions o;
        o.partitioning = RenderOptions::Partitioning::Adaptive;
        const FrameCamera cam = camera();
        ExactPlanner plan;
        std::vector<ExactPlanner::CommandWrite> writes;
        const ExactPlanKey key = ExactPlanner::keyFor(rs.scene(), cam, o, false, false, true);
        QVERIFY(plan.update(rs.scene(), key, cam, writes));
        QCOMPARE(plan.coverSurfaces(), 1);
        QCOMPARE(plan.analyticSurfaces(), 1);
        QCOMPARE(plan.deferredSurfaces(), 1); // the NURBS face alone
        const ExactPlace* p = plan.place(&cylinder);
        QVERIFY(p && p->cover && p->sectionVariant >= 0 && p->skirtVariant < 0 && p->index < 0 &&
                p->prepassIndex < 0);
        QCOMPARE(p->cells, std::int64_t(4));
        QCOMPARE(int(plan.sections().size()), 1);
        const ExactBatch& b = plan.sections().at(p->sectionVariant);
        QVERIFY(b.cover && b.analytic && b.face == 1 && b.commands.size() == 1);
        QCOMPARE(b.commands[0].count, 30u);
        QCOMPARE(plan.sectionCells(), std::int64_t(0)); // no plane crosses anything
        QCOMPARE(int(plan.routes().size()), 1);
        QCOMPARE(int(plan.variants().size()), 1);
        QCOMPARE(int(plan.skirts().size()), 1);
        for (const auto& [k, batch] : plan.plain())
            for (const IndirectCommand& c : batch.commands)
                QVERIFY(c.baseInstance != std::uint32_t(cylinder.slot));
        // Touched with its cover re-made elsewhere: patched, one write.
        cylinder.exact->triangleOffset = 600;
        rs.touched = {&cylinder};
        QVERIFY(!plan.update(rs.scene(), key, cam, writes));
        QCOMPARE(int(writes.size()), 1);
        QCOMPARE(writes[0].command.firstIndex, 600u);
        // Back to a polygon: planned again, the NURBS face's way with the closed form.
        cylinder.exact->cover = false;
        QVERIFY(plan.update(rs.scene(), key, cam, writes));
        QCOMPARE(plan.coverSurfaces(), 0);
        QVERIFY(plan.sections().empty());
        QCOMPARE(plan.analyticSurfaces(), 1);
    }

    void droppedFormIsPlannedAgain() {
        Records rs;
        SurfaceRecord& cylinder = rs.add(2, 1, true);
        rs.add(2, 1, false, glm::vec3(1.0f, 0.0f, 0.0f));
        RenderOptions o;
        o.partitioning = RenderOptions::Partitioning::Adaptive;
        const FrameCamera cam = camera();
        ExactPlanner plan;
        std::vector<ExactPlanner::CommandWrite> writes;
        const ExactPlanKey key = ExactPlanner::keyFor(rs.scene(), cam, o, false, false, false);
        QVERIFY(plan.update(rs.scene(), key, cam, writes));
        QCOMPARE(int(plan.variants().size()), 2);
        QCOMPARE(plan.analyticSurfaces(), 1);
        // An edit dropped the form (the document's rule) and touched the record: the plan is
        // built again, with both surfaces in one batch.
        rs.surfaces[0]->analytic = AnalyticForm{};
        rs.touched = {&cylinder};
        QVERIFY(plan.update(rs.scene(), key, cam, writes));
        QCOMPARE(plan.analyticSurfaces(), 0);
        QCOMPARE(int(plan.variants().size()), 1);
    }
};

QTEST_GUILESS_MAIN(TestRenderAnalyticPlan)
#include "tst_render_analytic_plan.moc"
