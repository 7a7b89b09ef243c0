// GpuScene: the one sync per frame (drop removed surfaces, compare revisions once, rebuild the
// stale parts the frame needs) and the per-record bookkeeping.
#include "render/gpu_scene.h"

#include "model/nurbs/visible_bounds.h"
#include "render/exact_planner.h"
#include "render/gpu_layout.h"

#include <QElapsedTimer>
#include <algorithm>
#include <atomic>

namespace kw {

void GpuScene::initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders) {
    m_gl = gl;
    m_masks.initialize(gl, shaders);
    gl->glGetIntegerv(GL_MAX_TEXTURE_SIZE, &m_maxTextureSize);
    GLint64 texels = 0;
    gl->glGetInteger64v(GL_MAX_TEXTURE_BUFFER_SIZE, &texels);
    m_glBufferLimit = std::int64_t(texels) * std::int64_t(sizeof(glm::vec4));
    const std::int64_t max = bufferLimit();
    m_pools.control.initialize(gl, sizeof(glm::vec4), max);
    m_pools.spans.initialize(gl, sizeof(glm::vec4), max);
    m_pools.vertices.initialize(gl, sizeof(BaseVertex), max);
    m_pools.triangles.initialize(gl, sizeof(unsigned), max);
    m_pools.outlines.initialize(gl, sizeof(unsigned), max);
    m_pools.skirtVertices.initialize(gl, sizeof(SkirtVertex), max);
    m_pools.skirtIndices.initialize(gl, sizeof(unsigned), max);
}

namespace {
std::atomic<std::int64_t> g_bufferLimitForTests{0};
} // namespace

void GpuScene::setBufferLimitForTests(std::int64_t bytes) {
    g_bufferLimitForTests = bytes;
}

std::int64_t GpuScene::bufferLimit() const {
    const std::int64_t lowered = g_bufferLimitForTests;
    return lowered > 0 ? std::min<std::int64_t>(lowered, m_glBufferLimit) : m_glBufferLimit;
}

void GpuScene::dropExact(SurfaceRecord& r) {
    if (r.exact)
        destroySurfaceGpu(m_pools, *r.exact);
    r.exact.reset();
    r.bounded = false;
    if (r.slot >= 0) {
        m_table.rows[size_t(r.slot)] = SurfaceTableEntry{};
        m_table.freeSlots.push_back(r.slot);
        --m_table.used;
        r.slot = -1;
    }
}

struct GpuScene::Pass {
    Pass(const Document& d, const FrameCamera& c, const RenderOptions& o)
        : doc(d), camera(c), options(o) {}
    const Document& doc;
    const FrameCamera& camera;
    const RenderOptions& options;
    bool adaptive = false;
    ScreenScale scale;
    std::int64_t limit = 0;
    UploadStats frame;
    /// Surfaces whose data did not fit, and the first of them described (the error names the
    /// count and that one: a scene of thousands must not get a line per surface).
    int tooLarge = 0;
    QString firstTooLarge;
    int examined = 0;
    int choicesEvaluated = 0;
};

void GpuScene::prepare(const Document& doc) {
    // Ids and revisions are per document: another document's data is never reused.
    if (m_document != &doc) {
        release();
        m_document = &doc;
    }
    m_changes.pull(doc);
    m_changes.updateBounds(doc);
}

bool coversAllowed(const RenderOptions& options) {
    // Adaptive exact frames whose faces are drawn from their analytic form, aliased or
    // accumulated (MSAA frames cover silhouettes and trims by the polygon's samples), without
    // the wireframe (the polygon's cells) and without section planes (a cover shows its face's
    // first meeting with the ray, which a plane may cut where a later one is kept).
    return options.partitioning == RenderOptions::Partitioning::Adaptive &&
           options.mode == RenderMode::Exact && options.analyticFaces && !options.wireframe &&
           options.sections.empty() &&
           !(options.samples > 1 && options.antialiasing == RenderOptions::Antialiasing::Coverage);
}

bool coverable(const Surface& s) {
    using Kind = AnalyticForm::Kind;
    const Kind k = s.analytic.kind;
    if ((k != Kind::Cylinder && k != Kind::Cone && k != Kind::Sphere) ||
        !analyticUsable(s.analytic))
        return false;
    // The convex hull property holds for positive weights.
    return std::all_of(s.geometry.weights.begin(), s.geometry.weights.end(),
                       [](double w) { return w > 0.0; });
}

void GpuScene::syncSurface(Entry& e, const Surface& s, int index, Pass& pass) {
    const RenderOptions& options = pass.options;
    ++pass.examined;
    SurfaceRecord& r = e.record;
    r.id = s.id;
    r.surface = &s;
    // The sliders' partitions (or the override): the paper's uniform grid, the minimum in
    // adaptive mode, and always the tessellated baseline's.
    const int sliderU = options.partitionsU > 0 ? options.partitionsU : s.partitionsU;
    const int sliderV = options.partitionsV > 0 ? options.partitionsV : s.partitionsV;
    // By index: a search by id per surface made each frame quadratic in the surfaces.
    const Revisions rev = pass.doc.revisionsAt(index);
    r.revisions = rev;
    const NurbsSurface& geo = s.geometry;
    UploadStats up;
    std::unique_ptr<SurfaceGpu>& g = r.exact;
    bool fits = true;
    // The polygon spans the trims' (u, v) box (a small face on a large domain gets its
    // partitions) or, with polygonOverTrims off, the domain. The box is recomputed only
    // when the trims or that option changed.
    const auto boxFor = [&] {
        return options.polygonOverTrims ? trimParameterBox(s)
                                        : ParameterBox{surfaceDomainU(geo), surfaceDomainV(geo)};
    };
    const bool fresh = !g || g->revisions.knots != rev.knots || g->degreeU != geo.degreeU ||
                       g->degreeV != geo.degreeV || g->countU != geo.countU ||
                       g->countV != geo.countV;
    const bool boxStale = fresh || g->polygonTrimmed != options.polygonOverTrims ||
                          (options.polygonOverTrims && g->revisions.trims != rev.trims);
    const ParameterBox box = boxStale ? boxFor() : g->polygonBox;
    // Skirts are drawn only in adaptive exact frames (ExactSurfacePass::skirtPass): built only
    // then, so the paper's mode uploads what it did.
    const bool skirt = pass.adaptive && options.edgeSkirts;
    // Outlines once a frame drew the wireframe, and from then on with every polygon rebuilt.
    const bool outlines = options.wireframe || (g && g->outlineOffset >= 0);
    // Adaptive mode: the cached choice's breaks (AdaptivePartitions::cut), not copied.
    const PolygonCut uniformCut{sliderU, sliderV, {}, {}};
    const PolygonCut* chosenCut = &uniformCut;
    r.boundPixels = 0.0;
    m_unmet.erase(index);
    if (pass.adaptive) {
        bool evaluated = false;
        const PartitionChoice& c =
            e.adaptive.choose(s, rev, box, pass.scale, m_viewStamp, options.pixelTolerance, sliderU,
                              sliderV, &evaluated, options.polygonsInView);
        chosenCut = &e.adaptive.cut();
        pass.choicesEvaluated += evaluated;
        r.boundPixels = c.boundPixels;
        if (!c.met)
            m_unmet.insert(index);
    }
    const PolygonCut& cut = *chosenCut;
    // A closed-form face whose polygon in view would take many cells (a close-up beside it)
    // gets its cover instead: one box, whatever the view (docs/RENDERING.md, "Covers of
    // closed-form faces").
    std::optional<CoverBox> cover;
    if (pass.adaptive && coversAllowed(options) && coverable(s)) {
        const auto inView = std::int64_t(std::max<size_t>(cut.breaksU.size(), 2) - 1) *
                            std::int64_t(std::max<size_t>(cut.breaksV.size(), 2) - 1);
        if (double(inView) > options.coverMinCells && inView > 1) {
            cover = coverBox(e.adaptive.spans(s, rev), box);
            if (cover) {
                r.boundPixels = 0.0; // no chords: no tolerance to meet
                m_unmet.erase(index);
            }
        }
    }
    if (fresh) {
        if (!g) {
            g = std::make_unique<SurfaceGpu>();
            g->id = s.id;
        }
        fits = uploadSurface(m_pools, *g, s, cut, box, skirt, outlines, up);
        if (fits && cover)
            fits = rebuildCover(m_pools, *g, buildCover(geo, *cover), cut, box, up);
    } else if (cover) {
        if (!g->cover || box != g->polygonBox || g->revisions.points != rev.points) {
            if (g->revisions.points != rev.points)
                uploadChangedPoints(m_pools, *g, s, up); // the texels; the cover is rebuilt
            fits = rebuildCover(m_pools, *g, buildCover(geo, *cover), cut, box, up);
        }
    } else {
        if (g->cover || g->cut != cut || box != g->polygonBox ||
            (g->skirtVertexOffset >= 0) != skirt) {
            // The polygon is rebuilt from the current points; pick up a point change.
            if (g->revisions.points != rev.points)
                uploadChangedPoints(m_pools, *g, s, up);
            fits = rebuildPolygon(m_pools, *g, s, cut, box, skirt, outlines, up);
        } else if (g->revisions.points != rev.points) {
            uploadChangedPoints(m_pools, *g, s, up);
        }
    }
    if (fits && options.wireframe)
        fits = addOutlines(m_pools, *g, up);
    g->polygonTrimmed = options.polygonOverTrims;
    m_tooLarge.erase(index);
    if (fits) {
        g->choiceCells = pass.adaptive ? e.adaptive.choiceCells() : g->polygon.cellCount();
        g->revisions = rev;
        if (r.slot < 0) {
            if (!m_table.freeSlots.empty()) {
                r.slot = m_table.freeSlots.back();
                m_table.freeSlots.pop_back();
            } else {
                r.slot = int(m_table.rows.size());
                m_table.rows.emplace_back();
            }
            ++m_table.used;
        }
        if (!r.bounded || r.boundsOf.points != rev.points || r.boundsOf.knots != rev.knots) {
            r.bounded = controlBounds(*g, r.boundsLo, r.boundsHi);
            r.boundsOf = rev;
        }
    } else {
        // Not drawn: its data does not fit the shared buffers. Retried (as a full upload)
        // on the next frame, since other surfaces may have been removed meanwhile.
        dropExact(r);
        m_tooLarge.insert(index);
        if (pass.tooLarge++ == 0)
            pass.firstTooLarge =
                QStringLiteral("surface %1 (\"%2\") with %3 x %4 control points")
                    .arg(s.id.value)
                    .arg(s.name.size() > 40 ? s.name.left(39) + QChar(0x2026) : s.name)
                    .arg(geo.countU)
                    .arg(geo.countV);
    }
    r.cells = !g ? 0 : g->cover ? g->coverBoxes : std::int64_t(g->triangleIndexCount / 6);
    if (options.mode == RenderMode::Tessellated)
        syncMesh(r, rev, sliderU, sliderV, up);
    if (options.controlNet)
        syncNet(r, rev, up);
    e.stats += up;
    pass.frame += up;
}

bool GpuScene::maskStale(const SurfaceRecord& r, const FrameCamera& camera,
                         const RenderOptions& options) const {
    const TrimMask& m = r.mask;
    if (r.surface->trims.empty() || !r.exact) // a layer or grid block to give back
        return m.layer >= 0 || m.active || !m.warnings.isEmpty() || m.grid.words || m.grid.cap;
    if (m.trimsRevision != r.revisions.trims || m.knotsRevision != r.revisions.knots)
        return true;
    // Exact grids follow the view only by which surfaces are in it (a new view walks every
    // record); one dropped out of view has no grid (cap 0).
    if (options.trimMode == RenderOptions::TrimMode::Exact)
        return m.grid.cap == 0 || m.layer >= 0;
    if (m.layer < 0)
        return true;
    const int cap = std::clamp(options.trimMaskCap, kMinTrimMaskSize, m_maxTextureSize);
    return TrimMaskPass::maskResolution(*r.surface, camera, cap) != glm::ivec2(m.width, m.height);
}

Status GpuScene::sync(const Document& doc, const FrameCamera& camera, const RenderOptions& options,
                      FrameReport& report) {
    QElapsedTimer timer;
    timer.start();
    prepare(doc); // a no-op when the renderer already called it this frame
    const Scene& scene = doc.scene();
    Pass pass(doc, camera, options);
    beginPass(pass);
    std::vector<int> work;
    const bool full = needsFullWalk(scene, camera, options, work);
    m_touched.clear();
    if (full)
        syncAll(scene, pass);
    else
        syncChanged(scene, work, pass);
    countSolidMembers(doc, full);
    compactPools();
    m_changes.clear();
    Status status = reportPass(scene, pass, double(timer.nsecsElapsed()) * 1e-6, report);
    const bool masksRan = options.trims && syncMasks(doc, camera, options, full, status, report);
    orderCells(masksRan, camera, options);
    timer.restart();
    syncTable(masksRan ? m_order : m_touched);
    report.cpuMs.sync += double(timer.nsecsElapsed()) * 1e-6;
    return status;
}

void GpuScene::beginPass(Pass& pass) {
    pass.limit = bufferLimit();
    for (GpuPool* p : {&m_pools.control, &m_pools.spans, &m_pools.vertices, &m_pools.triangles,
                       &m_pools.outlines, &m_pools.skirtVertices, &m_pools.skirtIndices})
        p->initialize(m_gl,
                      p == &m_pools.control || p == &m_pools.spans ? sizeof(glm::vec4)
                      : p == &m_pools.vertices                     ? sizeof(BaseVertex)
                      : p == &m_pools.skirtVertices                ? sizeof(SkirtVertex)
                                                                   : sizeof(unsigned),
                      pass.limit);
    const RenderOptions& options = pass.options;
    pass.adaptive = options.partitioning == RenderOptions::Partitioning::Adaptive &&
                    options.mode == RenderMode::Exact;
    if (pass.adaptive) {
        const ViewKey key{pass.camera.viewProjection, pass.camera.viewport, options.pixelTolerance};
        if (!(key == m_viewKey)) {
            m_viewKey = key;
            ++m_viewStamp;
        }
        pass.scale = frameScreenScale(pass.camera);
    }
}

bool GpuScene::needsFullWalk(const Scene& scene, const FrameCamera& camera,
                             const RenderOptions& options, std::vector<int>& work) {
    // Everything a record depends on besides its own surface: when one of these changed,
    // every record is compared (each still rebuilds only what is stale).
    const FrameKey key{camera.viewProjection,   camera.viewport,        options.mode,
                       options.partitioning,    options.pixelTolerance, options.partitionsU,
                       options.partitionsV,     options.trimMaskCap,    options.polygonOverTrims,
                       options.controlNet,      options.trims,          options.trimMode,
                       options.trimBudgetBytes, options.trimGridCap,    options.splitCellsByTrims,
                       options.edgeSkirts,      options.polygonsInView, options.wireframe,
                       options.cullOutsideView, coversAllowed(options), options.coverMinCells};
    const bool full = m_changes.structureChanged() || !m_haveFrameKey || !(key == m_frameKey);
    m_frameKey = key;
    m_haveFrameKey = true;
    if (full)
        return true;
    // The incremental way: the surfaces the document reported changed, and those retried.
    for (const SurfaceId id : m_changes.changed()) {
        const int index = m_changes.indexOf(id);
        if (index < 0 || scene.surfaces[size_t(index)].id != id)
            return true; // not where the last structural walk put it
        const Surface& s = scene.surfaces[size_t(index)];
        const auto it = m_entries.find(id);
        const bool listed = it != m_entries.end() && it->second.record.inOrder;
        if (s.hidden != !listed)
            return true; // shown or hidden: the draw list changes
        if (!s.hidden)
            work.push_back(index);
    }
    work.insert(work.end(), m_tooLarge.begin(), m_tooLarge.end());
    std::sort(work.begin(), work.end());
    work.erase(std::unique(work.begin(), work.end()), work.end());
    return false;
}

void GpuScene::syncAll(const Scene& scene, Pass& pass) {
    m_order.clear();
    m_order.reserve(scene.surfaces.size());
    m_unmet.clear();
    m_tooLarge.clear();
    ++m_syncs;
    ++m_layoutStamp;
    for (int index = 0; index < int(scene.surfaces.size()); ++index) {
        const Surface& s = scene.surfaces[size_t(index)];
        // The draw list: a hidden surface is left out of the frame (every pass and the
        // pick query draw records() only) but keeps its record, so showing it again
        // uploads only what changed meanwhile. Its trim mask layer is given back: the
        // mask pass reassigns layers among the records it sees, so a kept layer could go
        // to another surface.
        if (s.hidden) {
            if (const auto it = m_entries.find(s.id); it != m_entries.end()) {
                it->second.seen = m_syncs; // kept, not dropped
                it->second.record.inOrder = false;
                m_masks.freeLayer(it->second.record.mask);
            }
            continue;
        }
        Entry& e = m_entries[s.id];
        e.seen = m_syncs;
        e.record.inOrder = true;
        syncSurface(e, s, index, pass);
        m_order.push_back(&e.record);
    }
    // The one place removed surfaces are dropped, with every part they hold: those the
    // loop above did not see.
    for (auto it = m_entries.begin(); it != m_entries.end();) {
        if (it->second.seen != m_syncs) {
            drop(it->second);
            it = m_entries.erase(it);
        } else {
            ++it;
        }
    }
    m_touched = m_order;
    // The frame's figures over every drawn record, summed again after a full walk.
    m_drawn = 0;
    m_cells = 0;
    m_worstBound = 0.0;
    for (const SurfaceRecord* r : m_order) {
        m_drawn += r->exact ? 1 : 0;
        m_cells += r->cells;
        m_worstBound = std::max(m_worstBound, r->boundPixels);
    }
}

void GpuScene::syncChanged(const Scene& scene, const std::vector<int>& work, Pass& pass) {
    // A changed record's share is replaced; the worst bound is looked for again only when
    // the record that held it got better.
    bool lowered = false;
    for (const int index : work) {
        const Surface& s = scene.surfaces[size_t(index)];
        Entry& e = m_entries.at(s.id);
        SurfaceRecord& r = e.record;
        const int drawn = r.exact ? 1 : 0;
        const std::int64_t cells = r.cells;
        const double bound = r.boundPixels;
        syncSurface(e, s, index, pass);
        m_touched.push_back(&r);
        m_drawn += (r.exact ? 1 : 0) - drawn;
        m_cells += r.cells - cells;
        if (r.boundPixels >= m_worstBound)
            m_worstBound = r.boundPixels;
        else if (bound >= m_worstBound)
            lowered = true;
    }
    if (lowered) {
        m_worstBound = 0.0;
        for (const SurfaceRecord* r : m_order)
            m_worstBound = std::max(m_worstBound, r->boundPixels);
    }
}

void GpuScene::countSolidMembers(const Document& doc, bool full) {
    // Marks are cleared and set again by edits of their faces (Document::openSolid,
    // closeSolid), hidden ones included, between full walks too: counted again when they did.
    if (!full && doc.marksRevision() == m_marksRevision)
        return;
    m_marksRevision = doc.marksRevision();
    m_solidMembers.clear();
    for (const Surface& s : doc.scene().surfaces)
        if (s.solid >= 0)
            ++m_solidMembers[s.solid];
}

Status GpuScene::reportPass(const Scene& scene, const Pass& pass, double cpuMs,
                            FrameReport& report) const {
    report.recordsSynced += pass.examined;
    report.uploads += pass.frame;
    FrameReport::Partitions& parts = report.partitions;
    parts.choicesEvaluated += pass.choicesEvaluated;
    parts.cells += m_cells;
    parts.worstBoundPixels = std::max(parts.worstBoundPixels, m_worstBound);
    parts.unmet += int(m_unmet.size());
    report.cpuMs.sync += cpuMs;
    if (!m_unmet.empty()) {
        QStringList unmet;
        for (const int index : m_unmet) {
            if (unmet.size() == 8) {
                unmet << QStringLiteral("... (%1 in all)").arg(m_unmet.size());
                break;
            }
            unmet << QString::number(scene.surfaces[size_t(index)].id.value);
        }
        report.warnings << QStringLiteral("surfaces %1: the base polygon could not be brought "
                                          "within %2 px of the surface at %3 x %3 partitions "
                                          "(too close to the eye); drawn at %3 x %3")
                               .arg(unmet.join(QStringLiteral(", ")))
                               .arg(pass.options.pixelTolerance)
                               .arg(kMaxPartitions);
    }
    // The frame is drawn without what failed; the first failure is the frame's error.
    if (pass.tooLarge == 0)
        return ok();
    // One line with the totals, however many surfaces it is about.
    std::int64_t resident = 0;
    for (const GpuPool* p :
         {&m_pools.control, &m_pools.spans, &m_pools.vertices, &m_pools.triangles,
          &m_pools.outlines, &m_pools.skirtVertices, &m_pools.skirtIndices})
        resident += p->residentBytes();
    const Error error(QStringLiteral("%1 of %2 surfaces do not fit the GPU's buffer limit of %3 "
                                     "bytes (%4 MiB of surface data resident; the first: %5) and "
                                     "are not drawn")
                          .arg(m_tooLarge.size())
                          .arg(scene.surfaces.size())
                          .arg(pass.limit)
                          .arg(double(resident) / double(1 << 20), 0, 'f', 1)
                          .arg(pass.firstTooLarge));
    report.warnings << error.message;
    return error;
}

bool GpuScene::syncMasks(const Document& doc, const FrameCamera& camera,
                         const RenderOptions& options, bool full, Status& status,
                         FrameReport& report) {
    QElapsedTimer timer;
    timer.start();
    // The mask pass looks at every record; a frame whose changed records need no new mask
    // skips it and repeats its last answer.
    bool stale = full;
    for (size_t k = 0; !stale && k < m_touched.size(); ++k)
        stale = maskStale(*m_touched[k], camera, options);
    if (stale) {
        ++m_layoutStamp;
        m_maskError = m_masks.sync(doc, m_order, camera, options).message();
        m_maskWarnings = maskWarnings();
        report.masks += m_masks.frameStats();
        report.drawCalls += m_masks.drawCalls;
    }
    if (!m_maskError.isEmpty() && status)
        status = Error(m_maskError);
    report.warnings << m_maskWarnings;
    report.cpuMs.masks += double(timer.nsecsElapsed()) * 1e-6;
    return stale;
}

void GpuScene::orderCells(bool masksRan, const FrameCamera& camera, const RenderOptions& options) {
    // Cells ordered by how the trims cut them (inside, near a curve, trimmed away), for the
    // pre-pass's split draws: after the masks, whose grids classify them.
    const bool split = options.splitCellsByTrims && options.trims &&
                       options.trimMode == RenderOptions::TrimMode::Exact &&
                       options.mode == RenderMode::Exact;
    // And by the section planes: every record again when the planes or the view changed.
    const SectionKey sectionKey{options.splitCellsBySections && options.mode == RenderMode::Exact
                                    ? options.sections
                                    : std::vector<SectionPlane>{},
                                camera.viewProjection, camera.viewport};
    const bool sectionsMoved = !(sectionKey == m_sectionKey);
    m_sectionKey = sectionKey;
    splitRecords(masksRan || sectionsMoved ? m_order : m_touched, split, camera, options);
}

void GpuScene::splitRecords(const std::vector<SurfaceRecord*>& records, bool splitTrims,
                            const FrameCamera& camera, const RenderOptions& options) {
    const std::vector<SectionPlane>& planes = m_sectionKey.planes;
    const ScreenScale scale = frameScreenScale(camera);
    for (SurfaceRecord* r : records) {
        if (!r->exact)
            continue;
        SurfaceGpu& g = *r->exact;
        const TrimMask* mask = splitTrims ? &r->mask : nullptr;
        // Only a surface a plane crosses is split by the planes; one wholly removed is not
        // drawn (ExactPlanner), and its cells keep whatever order they have.
        const ExactPlanner::SectionSide side =
            planes.empty() || !r->bounded
                ? ExactPlanner::SectionSide::Kept
                : ExactPlanner::sectionSide(r->boundsLo, r->boundsHi, planes);
        if (side == ExactPlanner::SectionSide::Removed)
            continue;
        const auto it = side == ExactPlanner::SectionSide::Crossed ? m_entries.find(r->id)
                                                                   : m_entries.end();
        if (it == m_entries.end() || !r->surface || g.cover) {
            splitCells(m_pools, g, mask, nullptr, 0); // a cover has no cells to split
            continue;
        }
        Entry::Sections& cells = it->second.sections;
        if (cells.polygonSerial != g.polygonSerial || cells.points != g.revisions.points ||
            cells.knots != g.revisions.knots) {
            cells.boxes =
                polygonCellBoxes(r->surface->geometry, g.polygon,
                                 it->second.adaptive.spans(*r->surface, r->revisions));
            cells.polygonSerial = g.polygonSerial;
            cells.points = g.revisions.points;
            cells.knots = g.revisions.knots;
            cells.serial = 0;
        }
        const std::vector<CellSection> classes =
            sectionCellClasses(g.polygon, cells.boxes, planes, scale,
                               kSectionLinePixels + options.pixelTolerance + 0.5);
        std::vector<std::uint8_t> bytes(classes.size());
        std::transform(classes.begin(), classes.end(), bytes.begin(),
                       [](CellSection c) { return std::uint8_t(c); });
        if (bytes.empty()) {
            // No bounds for its cells: the whole surface is drawn as crossed (ExactPlanner).
            splitCells(m_pools, g, mask, nullptr, 0);
            continue;
        }
        if (cells.serial == 0 || bytes != cells.classes) {
            cells.classes = std::move(bytes);
            cells.serial = ++m_sectionSerial;
        }
        splitCells(m_pools, g, mask, &cells.classes, cells.serial);
    }
}

void GpuScene::drop(Entry& e) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    SurfaceRecord& r = e.record;
    dropExact(r);
    MeshGpu& m = r.mesh;
    for (GLuint* b : {&m.positions, &m.normals, &m.uvs, &m.indices})
        if (*b)
            gl->glDeleteBuffers(1, b), *b = 0;
    if (m.vao)
        gl->glDeleteVertexArrays(1, &m.vao), m.vao = 0;
    m_meshBytes -= m.bytes;
    m.bytes = 0;
    NetGpu& n = r.net;
    for (GLuint* b : {&n.points, &n.lines})
        if (*b)
            gl->glDeleteBuffers(1, b), *b = 0;
    if (n.vao)
        gl->glDeleteVertexArrays(1, &n.vao), n.vao = 0;
    m_netBytes -= n.bytes;
    n.bytes = 0;
    m_masks.freeLayer(r.mask);
    m_removedStats += e.stats;
    m_removedMaskStats += r.mask.stats;
}

const SurfaceRecord* GpuScene::find(SurfaceId id) const {
    const auto it = m_entries.find(id);
    return it == m_entries.end() ? nullptr : &it->second.record;
}

const SurfaceGpu* GpuScene::surfaceGpu(SurfaceId id) const {
    const SurfaceRecord* r = find(id);
    return r ? r->exact.get() : nullptr;
}

const TrimMask* GpuScene::mask(SurfaceId id) const {
    const SurfaceRecord* r = find(id);
    return r && r->mask.usable() ? &r->mask : nullptr;
}

UploadStats GpuScene::stats(SurfaceId id) const {
    const auto it = m_entries.find(id);
    return it == m_entries.end() ? UploadStats{} : it->second.stats;
}

UploadStats GpuScene::totalStats() const {
    UploadStats total = m_removedStats;
    for (const auto& [id, e] : m_entries)
        total += e.stats;
    return total;
}

TrimMaskStats GpuScene::maskStats(SurfaceId id) const {
    const SurfaceRecord* r = find(id);
    return r ? r->mask.stats : TrimMaskStats{};
}

TrimMaskStats GpuScene::totalMaskStats() const {
    TrimMaskStats total = m_removedMaskStats;
    for (const auto& [id, e] : m_entries)
        total += e.record.mask.stats;
    total.arrayAllocations = m_masks.arrayAllocations();
    return total;
}

void GpuScene::resetStats() {
    m_removedStats = {};
    m_removedMaskStats = {};
    m_masks.resetArrayAllocations();
    for (auto& [id, e] : m_entries) {
        e.stats = {};
        e.record.mask.stats = {};
    }
}

QStringList GpuScene::maskWarnings() const {
    QStringList out;
    if (!m_masks.budgetWarning().isEmpty())
        out << m_masks.budgetWarning();
    for (const SurfaceRecord* r : m_order)
        for (const QString& w : r->mask.warnings)
            out << QStringLiteral("surface %1: %2").arg(r->id.value).arg(w);
    return out;
}

std::vector<unsigned char> GpuScene::readMask(SurfaceId id) const {
    const TrimMask* m = mask(id);
    return m ? m_masks.readMask(*m) : std::vector<unsigned char>{};
}

void GpuScene::residentBytes(GpuBytes& out) const {
    // The pools' whole buffers (what the GPU holds), not only the live ranges.
    out.controlPoints += m_pools.control.residentBytes();
    out.spanTables += m_pools.spans.residentBytes();
    out.basePolygons += m_pools.vertices.residentBytes() + m_pools.triangles.residentBytes() +
                        m_pools.outlines.residentBytes() + m_pools.skirtVertices.residentBytes() +
                        m_pools.skirtIndices.residentBytes();
    out.perSurface +=
        std::int64_t(m_table.capacity) * std::int64_t(sizeof(SurfaceTableEntry) + sizeof(int)) +
        m_analytic.bytes();
    out.tessellatedMeshes += m_meshBytes; // kept by syncMesh, syncNet and drop
    out.controlNets += m_netBytes;
    out.trimMasks += m_masks.residentBytes();
}

std::int64_t GpuScene::hostCopyBytes() const {
    std::int64_t bytes = 0;
    for (const auto& [id, e] : m_entries) {
        bytes += e.adaptive.hostBytes();
        const SurfaceGpu* g = e.record.exact.get();
        if (!g)
            continue;
        const BasePolygon& p = g->polygon;
        bytes += std::int64_t(
            g->control.size() * sizeof(glm::vec4) + p.vertices.size() * sizeof(BaseVertex) +
            (p.breaksU.size() + p.breaksV.size()) * sizeof(double) +
            (p.spanU.size() + p.spanV.size()) * sizeof(int) + g->cellBuckets.size());
    }
    return bytes;
}

void GpuScene::release() {
    if (m_gl)
        for (auto& [id, e] : m_entries)
            drop(e);
    m_entries.clear();
    m_order.clear();
    m_touched.clear();
    m_meshBytes = m_netBytes = 0;
    m_changes.forget();
    m_haveFrameKey = false;
    ++m_layoutStamp;
    m_drawn = 0;
    m_cells = 0;
    m_worstBound = 0.0;
    m_unmet.clear();
    m_tooLarge.clear();
    m_maskWarnings.clear();
    m_maskError.clear();
    if (m_gl) {
        m_masks.release();
        for (GLuint* b : {&m_table.buffer, &m_table.instances})
            if (*b)
                m_gl->glDeleteBuffers(1, b), *b = 0;
        m_table = Table{};
        m_analytic.release(m_gl);
        for (GpuPool* p : {&m_pools.control, &m_pools.spans, &m_pools.vertices, &m_pools.triangles,
                           &m_pools.outlines, &m_pools.skirtVertices, &m_pools.skirtIndices})
            p->release();
        for (GLuint* a : {&m_triangleVao, &m_outlineVao, &m_skirtVao, &m_finVao})
            if (*a)
                m_gl->glDeleteVertexArrays(1, a), *a = 0;
        for (int k = 0; k < 4; ++k)
            if (m_views[k])
                m_gl->glDeleteTextures(1, &m_views[k]), m_views[k] = 0;
    }
    m_document = nullptr;
}

} // namespace kw
