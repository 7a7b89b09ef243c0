// The exact pass's planner: variants, culling and batches from the records, no GL.
#include "render/exact_planner.h"

#include "render/analytic_table.h"
#include "render/exact_surface_pass.h"
#include "render/gpu_scene.h"
#include "render/surface_bound.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace kw {

namespace {
const TrimMask* maskOf(const SurfaceRecord& r) {
    return r.mask.usable() ? &r.mask : nullptr;
}
} // namespace

bool ExactPlanner::outsideView(const glm::vec3& lo, const glm::vec3& hi,
                               const glm::mat4& viewProjection) {
    // Grown a little so that rounding in the transform never culls a surface whose edge
    // touches the view.
    const glm::vec3 margin(1e-4f * (glm::length(hi - lo) + glm::length(hi) + glm::length(lo)));
    return boxOutsideFrustum(glm::dmat4(viewProjection), glm::dvec3(lo - margin),
                             glm::dvec3(hi + margin));
}

ExactPlanner::SectionSide ExactPlanner::sectionSide(const glm::vec3& lo, const glm::vec3& hi,
                                                    const std::vector<SectionPlane>& planes) {
    bool crossed = false;
    for (const SectionPlane& plane : planes) {
        const glm::dvec3 n = plane.removedSide();
        if (n == glm::dvec3(0.0))
            continue; // refused before drawing (checkSectionPlane)
        // The shader compares a float distance: a margin of the float resolution of the
        // coordinates involved keeps a point the shader might keep out of Removed.
        const double margin =
            1e-5 * (glm::length(glm::dvec3(hi - lo)) + glm::length(glm::dvec3(hi)) +
                    glm::length(glm::dvec3(lo)) + glm::length(plane.position));
        double nearest = std::numeric_limits<double>::infinity();
        double farthest = -nearest;
        for (int c = 0; c < 8; ++c) {
            const glm::dvec3 p(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z);
            const double d = glm::dot(n, p - plane.position);
            nearest = std::min(nearest, d);
            farthest = std::max(farthest, d);
        }
        if (nearest > margin)
            return SectionSide::Removed;
        crossed = crossed || farthest > -margin;
    }
    return crossed ? SectionSide::Crossed : SectionSide::Kept;
}

namespace {
/// The cells the partition choice cut the surface's polygon box into, whether or not the
/// polygon keeps them all (RenderOptions::polygonsInView): the cell size over the surface's
/// whole screen box, as before the off-screen cells were left out.
int cellsOver(const SurfaceGpu& g) {
    return int(std::max<std::int64_t>(g.choiceCells, g.polygon.cellCount()));
}
} // namespace

double ExactPlanner::projectedPixelsPerCell(const SurfaceGpu& g, const FrameCamera& camera) {
    glm::vec3 lo, hi;
    if (!kw::controlBounds(g, lo, hi))
        return 0.0;
    return pixelsPerCell(screenBox(lo, hi, camera.viewProjection), cellsOver(g), camera.viewport,
                         true);
}

ExactPlanner::ScreenBox ExactPlanner::screenBox(const glm::vec3& lo, const glm::vec3& hi,
                                                const glm::mat4& viewProjection) {
    ScreenBox box{glm::vec2(std::numeric_limits<float>::max()),
                  glm::vec2(-std::numeric_limits<float>::max()), false};
    for (int k = 0; k < 8; ++k) {
        const glm::vec3 c(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
        const glm::vec4 clip = viewProjection * glm::vec4(c, 1.0f);
        if (!(clip.w > 0.0f)) {
            box.behind = true;
            return box;
        }
        const glm::vec2 ndc = glm::vec2(clip) / clip.w;
        box.lo = glm::min(box.lo, ndc);
        box.hi = glm::max(box.hi, ndc);
    }
    return box;
}

glm::ivec4 ExactPlanner::pixelRect(const ScreenBox& box, glm::ivec2 viewport) {
    // Clamped a little past the view first: a corner near the eye projects far out, and only
    // the part on screen matters.
    const glm::vec2 size(viewport);
    const glm::vec2 lo = (glm::clamp(box.lo, -2.0f, 2.0f) * 0.5f + 0.5f) * size;
    const glm::vec2 hi = (glm::clamp(box.hi, -2.0f, 2.0f) * 0.5f + 0.5f) * size;
    return glm::ivec4(int(std::floor(lo.x)), int(std::floor(lo.y)), int(std::ceil(hi.x)),
                      int(std::ceil(hi.y)));
}

double ExactPlanner::pixelsPerCell(const ScreenBox& box, int cells, glm::ivec2 viewport,
                                   bool clampToView) {
    if (cells <= 0)
        return 0.0;
    if (box.behind) // a corner behind the eye: treat the surface as large
        return std::numeric_limits<double>::infinity();
    glm::vec2 lo = box.lo, hi = box.hi;
    if (clampToView) {
        lo = glm::clamp(lo, glm::vec2(-1.0f), glm::vec2(1.0f));
        hi = glm::clamp(hi, glm::vec2(-1.0f), glm::vec2(1.0f));
    }
    const glm::vec2 extent = glm::max(hi - lo, glm::vec2(0.0f)) * 0.5f * glm::vec2(viewport);
    return double(extent.x) * double(extent.y) / double(cells);
}

ExactPlanKey ExactPlanner::keyFor(const ExactPlanScene& scene, const FrameCamera& camera,
                                  const RenderOptions& options, bool trims, bool antialiased,
                                  bool deferred) {
    const bool adaptive = options.partitioning == RenderOptions::Partitioning::Adaptive;
    PlanFlags f;
    f.setFlag(PlanFlag::Trims, trims);
    f.setFlag(PlanFlag::Prepass, options.shading == RenderOptions::Shading::DepthPrepass);
    f.setFlag(PlanFlag::Cull, options.cullOutsideView);
    f.setFlag(PlanFlag::Antialiased, antialiased);
    // Skirts close the gap between an adaptive polygon's edge chords and the true edges; the
    // paper's uniform mode stays as it was. Not in anti-aliased frames: their trimmed
    // surfaces' partly covered pixels belong to the edge pass (docs/RENDERING.md, "Skirts").
    f.setFlag(PlanFlag::Skirts, options.edgeSkirts && !antialiased && adaptive);
    f.setFlag(PlanFlag::SkipBackFaces, options.skipBackFaces);
    f.setFlag(PlanFlag::Adaptive, adaptive);
    f.setFlag(PlanFlag::AffineNoNewton, options.affineWithoutNewton);
    f.setFlag(PlanFlag::Deferred, deferred);
    f.setFlag(PlanFlag::Analytic, options.analyticFaces);
    f.setFlag(PlanFlag::SectionSplit, !options.sections.empty() && options.splitCellsBySections &&
                                          options.shading == RenderOptions::Shading::DepthPrepass &&
                                          !antialiased);
    const bool partial = camera.reach.z > camera.reach.x;
    const int skirtPush =
        partial ? int(std::ceil(skirtPushPixels(options.pixelTolerance +
                                                double(ExactSurfacePass::kSkirtMarginPixels))))
                : 0;
    return ExactPlanKey{scene.identity,
                        scene.layout,
                        scene.marks,
                        camera.viewProjection,
                        camera.viewport,
                        f,
                        options.gatherMinCellPixels,
                        options.deferMaxCellPixels,
                        options.sections,
                        camera.pickPixel,
                        camera.reach,
                        skirtPush};
}

void ExactPlanner::clear() {
    m_have = false;
    m_places.clear();
    m_commands.clear();
}

const ExactPlace* ExactPlanner::place(const SurfaceRecord* r) const {
    const auto it = m_places.find(r);
    return it == m_places.end() ? nullptr : &it->second;
}

int ExactPlanner::stencilOf(const ExactBatch& b) const {
    return b.route >= 0 ? m_routes.at(b.route).stencil : kForwardStencil;
}

std::int64_t ExactPlanner::trimTestedCells() const {
    std::int64_t cells = 0;
    for (const auto& [k, b] : m_trimmedPre)
        for (const IndirectCommand& c : b.commands)
            cells += c.count / 6;
    return cells;
}

std::int64_t ExactPlanner::sectionCells() const {
    std::int64_t cells = 0;
    for (const auto& [k, b] : m_sections)
        if (!b.cover)
            for (const IndirectCommand& c : b.commands)
                cells += c.count / 6;
    return cells;
}

int ExactPlanner::affineSurfaces() const {
    return m_affine;
}

int ExactPlanner::analyticSurfaces() const {
    return m_analytic;
}

int ExactPlanner::deferredSurfaces() const {
    return m_deferred;
}

bool ExactPlanner::update(const ExactPlanScene& scene, const ExactPlanKey& key,
                          const FrameCamera& camera, std::vector<CommandWrite>& writes) {
    writes.clear();
    if (m_have && key == m_key && patch(scene, key, camera, writes))
        return false;
    writes.clear();
    build(scene, key, camera);
    return true;
}

ExactPlace ExactPlanner::classify(const SurfaceRecord& r, const ExactPlanKey& key,
                                  const FrameCamera& camera, Commands& commands) const {
    ExactPlace p;
    const SurfaceGpu* g = r.exact.get();
    if (!g || r.slot < 0)
        return p;
    p.drawn = true;
    // Wholly outside the view (its control bounds hold it): no triangle of it is sent, so a
    // close-up costs what is visible, not the whole scene. The bounds are kept with the record
    // (GpuScene), not taken from its points per frame.
    if (key.has(PlanFlag::Cull) && r.bounded &&
        outsideView(r.boundsLo, r.boundsHi, camera.viewProjection)) {
        p.culled = true;
        return p;
    }
    // A pick draws one pixel: a surface whose projected bounds (two pixels wider, for rounding
    // and the skirts' reach) miss it sends no triangle (a probe's hover costs what is under
    // the cursor, not the scene).
    if (key.pickPixel.x >= 0 && r.bounded) {
        const ScreenBox box = screenBox(r.boundsLo, r.boundsHi, camera.viewProjection);
        const glm::vec2 pixel = (glm::vec2(key.pickPixel) + 0.5f) / glm::vec2(camera.viewport);
        const glm::vec2 at = pixel * 2.0f - 1.0f, margin = 4.0f / glm::vec2(camera.viewport);
        if (!box.behind && (glm::any(glm::lessThan(at, box.lo - margin)) ||
                            glm::any(glm::greaterThan(at, box.hi + margin)))) {
            p.culled = true;
            return p;
        }
    }
    // A partial frame redraws one rectangle: a surface whose projected polygon (or control)
    // bounds miss its reach has no pixel in it (the reach is already grown by what a surface
    // draws past them).
    if (key.reach.z > key.reach.x) {
        const bool polygon = r.drawnBounded && r.drawnView == camera.viewProjection &&
                             r.drawnViewport == camera.viewport;
        ScreenBox box;
        box.behind = !polygon && !r.bounded;
        if (!polygon && r.bounded)
            box = screenBox(r.boundsLo, r.boundsHi, camera.viewProjection);
        // The skirts and fins draw up to the skirts' push past the polygon.
        const glm::ivec4 at =
            (polygon ? r.drawnRect : pixelRect(box, camera.viewport)) +
            glm::ivec4(-key.skirtPush, -key.skirtPush, key.skirtPush, key.skirtPush);
        if (!box.behind && (at.z <= key.reach.x || at.x >= key.reach.z || at.w <= key.reach.y ||
                            at.y >= key.reach.w)) {
            p.culled = true;
            return p;
        }
        // Of a surface that reaches it, the cells that do: a face at the rectangle's corner
        // sends the few cells there through every pass, not all of them. A cover has no
        // cells: its few boxes are sent whole, the scissor keeps their pixels in the rectangle.
        const std::vector<std::uint8_t> keep =
            g->cover ? std::vector<std::uint8_t>{}
                     : cellsReaching(g->polygon, camera.viewProjection, camera.viewport, key.reach,
                                     key.skirtPush);
        if (!keep.empty() && std::int64_t(keep.size()) * 6 == g->triangleIndexCount) {
            std::int64_t cells = 0, skirted = 0; // cells with each bit, in one pass
            for (const std::uint8_t k : keep) {
                cells += (k & kCellTriangles) != 0;
                skirted += (k & kCellSkirt) != 0;
            }
            if (cells == 0 && skirted == 0) {
                p.culled = true;
                return p;
            }
            if (cells < std::int64_t(keep.size()) || skirted < std::int64_t(keep.size())) {
                p.pieces = true;
                commands.cells = cellRuns(*g, keep, kCellTriangles, kCellRunGap);
                commands.skirtRuns = skirtRuns(*g, keep, kCellRunGap, commands.skirtWhole);
                commands.triangles = std::uint32_t(g->triangleOffset);
                commands.skirtIndices =
                    std::uint32_t(std::max<std::int64_t>(g->skirtIndexOffset, 0));
            }
        }
    }
    // Wholly on a section plane's removed side: every fragment would be evaluated, then
    // discarded.
    const SectionSide side = !key.sections.empty() && r.bounded
                                 ? sectionSide(r.boundsLo, r.boundsHi, key.sections)
                                 : SectionSide::Kept;
    if (side == SectionSide::Removed) {
        p.culled = true;
        return p;
    }
    commands.all =
        IndirectCommand{std::uint32_t(g->triangleIndexCount), 1, std::uint32_t(g->triangleOffset),
                        std::int32_t(g->vertexOffset), std::uint32_t(r.slot)};
    p.cells = g->triangleIndexCount / 6;
    if (p.pieces) {
        p.cells = 0;
        for (const CellRun& run : commands.cells)
            p.cells += run.count;
    }
    const bool prepass = key.has(PlanFlag::Prepass);
    const TrimMask* mask = key.has(PlanFlag::Trims) ? maskOf(r) : nullptr;
    // Batch keys: degrees (1..15, 4 bits each), then the variant's flags.
    const int degrees = g->degreeU | g->degreeV << 4;
    // A closed-form face's cover (docs/RENDERING.md, "Covers of closed-form faces"): its
    // boxes are no chords of the face, so no pre-pass depth, skirt or fin; drawn once, after
    // the shading, with the closed form's exact depth as the cells a section plane crosses
    // are (their pass), each box's inside faces only (culled as face 1: wound counter-
    // clockwise seen from inside), testing its trims itself.
    if (g->cover && key.has(PlanFlag::Adaptive) && key.has(PlanFlag::Analytic) && r.surface &&
        analyticUsable(r.surface->analytic)) {
        p.cover = true;
        p.cells = g->coverBoxes;
        p.face = 1;
        commands.section = commands.all;
        p.sectionVariant = degrees | int(mask != nullptr) << 8 | 1 << 10 | 1 << 14 | 1 << 16;
        return p;
    }
    p.prepassTrimmed = mask != nullptr;
    // Split by the trims: the pre-pass tests them only on the cells near a curve (a discard
    // costs llvmpipe its early depth test), and no pass draws the cells they remove.
    p.split = mask && prepass && !key.has(PlanFlag::Antialiased) && g->insideIndexCount >= 0 &&
              g->splitClasses == mask->classSerial;
    if (p.split) {
        const auto inside = std::uint32_t(g->insideIndexCount);
        const auto edge = std::uint32_t(g->edgeIndexCount);
        p.awayCells = (g->triangleIndexCount - std::int64_t(inside) - std::int64_t(edge)) / 6;
        commands.inside = commands.all;
        commands.inside.count = inside;
        commands.edge = commands.all;
        commands.edge.count = edge;
        commands.edge.firstIndex += inside;
        commands.all.count = inside + edge;
    }
    // With the depth pre-pass, a trimmed fragment left no depth there, so GL_EQUAL rejects it
    // before shading and early-z stays on: no lookup needed here. A discard in this shader
    // costs llvmpipe 5x (docs/PERFORMANCE.md, ## Trims), so only the exact-depth way, which
    // has no pre-pass, looks the mask up.
    const bool lookUp = mask && !prepass;
    // The gather pays only where a cell covers many fragments: on small cells its flat
    // varyings cost llvmpipe's triangle setup more than the fetches it saves.
    ScreenBox box;
    box.behind = true;
    if (r.bounded)
        box = screenBox(r.boundsLo, r.boundsHi, camera.viewProjection);
    const int cells = cellsOver(*g);
    // A face that kept its analytic form (unedited) has the point under the pixel in closed
    // form, where the Newton step onto the NURBS would be taken; an affine polygon needs
    // neither. Its program evaluates no NURBS, so the gather's per-cell data would be unused.
    const bool analytic = key.has(PlanFlag::Adaptive) && key.has(PlanFlag::Analytic) &&
                          !(key.has(PlanFlag::AffineNoNewton) && g->affine) && r.surface &&
                          analyticUsable(r.surface->analytic);
    const bool gather = !analytic && r.bounded &&
                        pixelsPerCell(box, cells, camera.viewport, true) >= key.minCellPixels;
    // Large cells the forward way (RenderOptions::deferMaxCellPixels). The cells' size on
    // screen, not clamped to the view: in a close-up most of them lie outside it, and those
    // inside are the large ones.
    const bool deferred = key.has(PlanFlag::Deferred);
    const bool forward =
        deferred && pixelsPerCell(box, cells, camera.viewport, false) >= key.deferMaxCellPixels;
    if (deferred && !box.behind)
        p.window = glm::vec4(glm::clamp(box.lo, -1.0f, 1.0f), glm::clamp(box.hi, -1.0f, 1.0f));
    // A closed solid seen from outside: the triangles facing away from the eye are hidden by
    // its faces in front (chooseBackCulled).
    const int solid = r.surface ? r.surface->solid : -1;
    if (solid >= 0 && m_backCulled.count(solid))
        p.face = r.surface->outsideAlongNormal ? 1 : 2;
    // The polygon is the surface (planes): in adaptive mode its (u, v) is already the point
    // under the pixel, and the Newton step would only evaluate the surface once more.
    const bool affine =
        key.has(PlanFlag::Adaptive) && key.has(PlanFlag::AffineNoNewton) && g->affine;
    // The section test on the cells drawn here: every cell in a frame without the split; with
    // it these are cells every plane keeps (with a margin: kw::sectionCellClasses), which need
    // it only for a closed solid's caps, seen through a cut of the solid's other faces.
    const bool sectionTest =
        !key.sections.empty() && (!key.has(PlanFlag::SectionSplit) || (solid >= 0 && p.face == 0));
    p.variant = degrees | int(lookUp) << 8 | int(gather) << 9 | p.face << 10 | int(affine) << 12 |
                int(forward) << 13 | int(analytic) << 14 | int(sectionTest) << 15;
    if (mask)
        p.edgeVariant =
            degrees | int(gather) << 9 | p.face << 10 | int(affine) << 12 | int(analytic) << 14;
    if (key.has(PlanFlag::Skirts) && g->skirtIndexOffset >= 0) {
        commands.skirt = IndirectCommand{std::uint32_t(g->skirtIndexCount), 1,
                                         std::uint32_t(g->skirtIndexOffset),
                                         std::int32_t(g->skirtVertexOffset), std::uint32_t(r.slot)};
        p.skirtVariant = degrees | int(mask != nullptr) << 8;
    }
    // The skipped side again, drawn last where nothing nearer covered a pixel (seams' sub-pixel
    // gaps): no pre-pass tests these triangles' trims, so their programs do, but only on the
    // cells near a curve when split (a trimmed program costs every fragment of its triangles,
    // rejected ones too: 1.15x Pump_Nut's frame unsplit). Never the gather: its vertex fetches
    // and flat inputs cost every triangle, and few fragments are shaded.
    if (p.face != 0 && !key.has(PlanFlag::Antialiased))
        p.backVariant = degrees | int(mask != nullptr) << 8 | p.face << 10 | int(affine) << 12 |
                        int(analytic) << 14;
    // Crossed by a section plane: its pre-pass depth would be the polygon's where the shader
    // then discards, hiding what lies behind. The cells a plane crosses go to their own pass
    // with exact depth; those every plane keeps stay in the commands above, drawn as an uncut
    // surface's (kw::splitCells ordered them: kept, crossed, then removed or trimmed away).
    if (key.has(PlanFlag::SectionSplit) && side == SectionSide::Crossed) {
        commands.section = commands.all; // the inside and near-edge cells when split by trims
        if (g->splitSections != 0) {
            const auto kept = std::uint32_t(g->keptIndexCount);
            commands.section.firstIndex += kept;
            commands.section.count = std::uint32_t(g->crossedIndexCount);
            commands.all.count = kept; // split by the trims too: inside + edge already
            if (p.split)               // not trimmed away: drawn by the section pass
                p.awayCells -= g->crossedIndexCount / 6;
        } else {
            // Cells not split by the planes (no bounds for them): every one is crossed.
            commands.all.count = commands.inside.count = commands.edge.count = 0;
        }
        // The analytic bit too: a batch takes its program's features from its first record.
        p.sectionVariant = degrees | int(mask != nullptr) << 8 | int(gather) << 9 | p.face << 10 |
                           int(affine) << 12 | int(analytic) << 14;
    }
    return p;
}

void ExactPlanner::chooseBackCulled(const ExactPlanScene& scene, const ExactPlanKey& key,
                                    const FrameCamera& camera) {
    m_backCulled.clear();
    if (!key.has(PlanFlag::SkipBackFaces))
        return;
    struct Solid {
        int drawn = 0;
        bool complete = true;
        glm::vec3 lo{0.0f}, hi{0.0f};
    };
    std::map<int, Solid> solids;
    for (const SurfaceRecord* r : *scene.records) {
        const int k = r->surface ? r->surface->solid : -1;
        if (k < 0)
            continue;
        Solid& s = solids[k];
        if (!r->exact || r->slot < 0 || !r->bounded) {
            s.complete = false; // a member not drawn: a hole
            continue;
        }
        s.lo = s.drawn ? glm::min(s.lo, r->boundsLo) : r->boundsLo;
        s.hi = s.drawn ? glm::max(s.hi, r->boundsHi) : r->boundsHi;
        ++s.drawn;
    }
    const glm::dmat4 view(camera.view);
    // A little past the near plane: the bounds hold the polygon, rounding aside.
    const double nearest = double(camera.nearPlane) * (1.0 + 1e-3);
    for (const auto& [k, s] : solids) {
        if (!s.complete || s.drawn != scene.solidMembers(k) ||
            sectionSide(s.lo, s.hi, key.sections) != SectionSide::Kept)
            continue;
        bool beyond = true;
        for (int c = 0; c < 8 && beyond; ++c) {
            const glm::dvec3 p(c & 1 ? s.hi.x : s.lo.x, c & 2 ? s.hi.y : s.lo.y,
                               c & 4 ? s.hi.z : s.lo.z);
            beyond = -(view * glm::dvec4(p, 1.0)).z > nearest;
        }
        if (beyond)
            m_backCulled.insert(k);
    }
}

int ExactPlanner::addCommand(ExactBatch& b, const IndirectCommand& command, const ExactPlace& p,
                             const Commands& cs, bool skirt) {
    const int at = int(b.commands.size());
    if (!p.pieces || (skirt && cs.skirtWhole)) {
        b.commands.push_back(command);
        return at;
    }
    // The command's part of each run: a run may cross from one of the range's parts (inside,
    // near an edge, crossed by a plane) into the next.
    const std::uint32_t unit = skirt ? 1 : 6, start = skirt ? cs.skirtIndices : cs.triangles;
    const std::uint32_t lo = command.firstIndex, hi = command.firstIndex + command.count;
    for (const CellRun& run : skirt ? cs.skirtRuns : cs.cells) {
        const std::uint32_t first = std::max(lo, start + std::uint32_t(run.first) * unit);
        const std::uint32_t end = std::min(hi, start + std::uint32_t(run.first + run.count) * unit);
        if (end > first)
            b.commands.push_back(IndirectCommand{end - first, command.instanceCount, first,
                                                 command.baseVertex, command.baseInstance});
    }
    return at;
}

void ExactPlanner::addToBatches(const SurfaceRecord& r, ExactPlace& p, const Commands& cs,
                                const ExactPlanKey& key) {
    if (p.cover) {
        ExactBatch& k = m_sections[p.sectionVariant];
        if (k.commands.empty()) {
            k.degreeU = r.exact->degreeU;
            k.degreeV = r.exact->degreeV;
            k.trimmed = (p.sectionVariant >> 8) & 1;
            k.analytic = true;
            k.section = true;
            k.cover = true;
            k.face = p.face;
        }
        p.sectionIndex = addCommand(k, cs.section, p, cs);
        return;
    }
    const IndirectCommand& c = cs.all;
    const bool deferred = key.has(PlanFlag::Deferred);
    if (key.has(PlanFlag::Prepass)) {
        const auto plain = [&]() -> ExactBatch& {
            ExactBatch& b = m_plain[p.plainKey(deferred)];
            b.face = p.face;
            b.route = p.route();
            return b;
        };
        ExactBatch& pre = p.prepassTrimmed ? m_trimmedPre[p.trimmedPreKey(deferred)] : plain();
        if (p.prepassTrimmed && pre.commands.empty()) {
            pre.trimmed = true;
            pre.face = p.face;
            pre.degreeU = r.exact->degreeU;
            pre.degreeV = r.exact->degreeV;
            pre.affine = (p.variant >> 12) & 1;
            pre.analytic = (p.variant >> 14) & 1;
            pre.route = p.route();
        }
        p.prepassIndex = addCommand(pre, p.split ? cs.edge : c, p, cs);
        if (p.split)
            p.insideIndex = addCommand(plain(), cs.inside, p, cs);
        if (deferred && p.route() >= 0)
            addToRoute(p);
    }
    ExactBatch& b = m_variants[p.variant];
    if (b.commands.empty()) {
        b.degreeU = r.exact->degreeU;
        b.degreeV = r.exact->degreeV;
        b.trimmed = (p.variant >> 8) & 1;
        b.gather = (p.variant >> 9) & 1;
        b.affine = (p.variant >> 12) & 1;
        b.analytic = (p.variant >> 14) & 1;
        b.section = (p.variant >> 15) & 1;
        b.face = p.face;
    }
    p.index = addCommand(b, c, p, cs);
    if (p.edgeVariant >= 0) {
        ExactBatch& e = m_edges[p.edgeVariant];
        if (e.commands.empty()) {
            e = b;
            e.commands.clear();
            e.trimmed = true;
            e.section = true;
        }
        p.edgeIndex = addCommand(e, c, p, cs); // with anti-aliasing: never split
    }
    if (p.skirtVariant >= 0) {
        ExactBatch& k = m_skirts[p.skirtVariant];
        if (k.commands.empty()) {
            k.degreeU = b.degreeU;
            k.degreeV = b.degreeV;
            k.trimmed = (p.skirtVariant >> 8) & 1;
        }
        p.skirtIndex = addCommand(k, cs.skirt, p, cs, true);
    }
    const auto addBack = [&](int key, const IndirectCommand& command) {
        ExactBatch& k = m_backFaces[key];
        if (k.commands.empty()) {
            k = b;
            k.commands.clear();
            k.trimmed = (key >> 8) & 1;
            k.gather = false;
            k.section = true;
        }
        return addCommand(k, command, p, cs);
    };
    if (p.backVariant >= 0)
        p.backIndex = addBack(p.backVariant, p.split ? cs.edge : c);
    if (p.backVariant >= 0 && p.split)
        p.backInsideIndex = addBack(p.backVariant & ~(1 << 8), cs.inside);
    if (p.sectionVariant >= 0) {
        ExactBatch& k = m_sections[p.sectionVariant];
        if (k.commands.empty()) {
            k = b;
            k.commands.clear();
            k.trimmed = (p.sectionVariant >> 8) & 1;
            k.section = true;
        }
        p.sectionIndex = addCommand(k, cs.section, p, cs);
    }
}

void ExactPlanner::build(const ExactPlanScene& scene, const ExactPlanKey& key,
                         const FrameCamera& camera) {
    // Group the surfaces by variant (document order within a group).
    for (auto* batches :
         {&m_plain, &m_trimmedPre, &m_variants, &m_edges, &m_skirts, &m_backFaces, &m_sections})
        batches->clear();
    m_routes.clear();
    chooseBackCulled(scene, key, camera);
    m_places.clear();
    m_places.reserve(scene.records->size());
    m_culled = 0;
    m_trimmedAway = 0;
    m_cellsSent = 0;
    m_affine = m_analytic = m_deferred = m_cover = 0;
    for (const SurfaceRecord* r : *scene.records) {
        Commands cs;
        ExactPlace p = classify(*r, key, camera, cs);
        if (p.drawn && !p.culled) {
            addToBatches(*r, p, cs, key);
            m_cellsSent += p.cells;
            m_affine += p.cover ? 0 : (p.variant >> 12) & 1;
            m_analytic += p.cover ? 1 : (p.variant >> 14) & 1;
            m_deferred += p.cover || (p.variant >> 13) & 1 ? 0 : 1;
            m_cover += p.cover;
        }
        m_culled += p.culled ? 1 : 0;
        m_trimmedAway += p.awayCells;
        m_places[r] = p;
    }
    int stencil = 0;
    for (auto& [k, route] : m_routes)
        route.stencil = ++stencil;
    m_commands.clear();
    for (auto* batches :
         {&m_plain, &m_trimmedPre, &m_variants, &m_edges, &m_skirts, &m_backFaces, &m_sections})
        for (auto& [k, b] : *batches) {
            b.first = std::int64_t(m_commands.size());
            m_commands.insert(m_commands.end(), b.commands.begin(), b.commands.end());
        }
    m_key = key;
    m_have = true;
}

bool ExactPlanner::patch(const ExactPlanScene& scene, const ExactPlanKey& key,
                         const FrameCamera& camera, std::vector<CommandWrite>& writes) {
    const bool deferred = key.has(PlanFlag::Deferred);
    for (const SurfaceRecord* r : *scene.touched) {
        const auto it = m_places.find(r);
        if (it == m_places.end())
            return false;
        const ExactPlace& was = it->second;
        Commands cs;
        const ExactPlace now = classify(*r, key, camera, cs);
        const IndirectCommand& c = cs.all;
        if (now.drawn != was.drawn || now.culled != was.culled || now.pieces || was.pieces)
            return false;
        if (!now.drawn || now.culled)
            continue;
        if (now.cover != was.cover)
            return false;
        if (now.cover) {
            if (now.sectionVariant != was.sectionVariant)
                return false;
            IndirectCommand& old =
                m_sections.at(was.sectionVariant).commands[size_t(was.sectionIndex)];
            if (!(old == cs.section)) {
                old = cs.section;
                const std::int64_t at = m_sections.at(was.sectionVariant).first + was.sectionIndex;
                m_commands[size_t(at)] = cs.section;
                writes.push_back({at, cs.section});
            }
            m_cellsSent += now.cells - was.cells;
            it->second.cells = now.cells;
            continue;
        }
        if (now.variant != was.variant || now.prepassTrimmed != was.prepassTrimmed ||
            now.edgeVariant != was.edgeVariant || now.split != was.split ||
            now.skirtVariant != was.skirtVariant || now.backVariant != was.backVariant ||
            now.sectionVariant != was.sectionVariant)
            return false;
        const auto patchOne = [&](ExactBatch& b, int index, const IndirectCommand& command) {
            IndirectCommand& old = b.commands[size_t(index)];
            if (!(old == command)) {
                old = command;
                m_commands[size_t(b.first + index)] = command;
                writes.push_back({b.first + index, command});
            }
        };
        patchOne(m_variants.at(now.variant), was.index, c);
        if (key.has(PlanFlag::Prepass))
            patchOne(was.prepassTrimmed ? m_trimmedPre.at(was.trimmedPreKey(deferred))
                                        : m_plain.at(was.plainKey(deferred)),
                     was.prepassIndex, was.split ? cs.edge : c);
        if (was.split)
            patchOne(m_plain.at(was.plainKey(deferred)), was.insideIndex, cs.inside);
        if (was.edgeVariant >= 0)
            patchOne(m_edges.at(was.edgeVariant), was.edgeIndex, c);
        if (was.skirtVariant >= 0)
            patchOne(m_skirts.at(was.skirtVariant), was.skirtIndex, cs.skirt);
        if (was.backVariant >= 0)
            patchOne(m_backFaces.at(was.backVariant), was.backIndex, was.split ? cs.edge : c);
        if (was.backVariant >= 0 && was.split)
            patchOne(m_backFaces.at(was.backVariant & ~(1 << 8)), was.backInsideIndex, cs.inside);
        if (was.sectionVariant >= 0)
            patchOne(m_sections.at(was.sectionVariant), was.sectionIndex, cs.section);
        if (deferred && now.route() >= 0) {
            it->second.window = now.window;
            addToRoute(now); // grown only: it may have moved
        }
        m_trimmedAway += now.awayCells - was.awayCells;
        it->second.awayCells = now.awayCells;
        m_cellsSent += now.cells - was.cells;
        it->second.cells = now.cells;
    }
    return true;
}

void ExactPlanner::addToRoute(const ExactPlace& p) {
    const auto [it, added] = m_routes.try_emplace(p.route(), Route{0, p.window});
    glm::vec4& w = it->second.window;
    if (!added)
        w = glm::vec4(glm::min(glm::vec2(w), glm::vec2(p.window)),
                      glm::max(glm::vec2(w.z, w.w), glm::vec2(p.window.z, p.window.w)));
}

} // namespace kw
