// TrimMaskPass in exact mode: the hybrid trim grids of every trimmed surface in one
// texture buffer, each rebuilt and re-sent only when its surface's trims or knots change.
#include "model/nurbs/trim.h"
#include "render/exact_planner.h"
#include "render/gpu_scene.h"
#include "render/trim_mask_pass.h"

#include <QElapsedTimer>
#include <algorithm>

namespace kw {

void TrimMaskPass::freeGrids() {
    if (m_gl) {
        if (m_gridView)
            m_gl->glDeleteTextures(1, &m_gridView);
        if (m_gridQuads)
            m_gl->glDeleteTextures(1, &m_gridQuads);
        if (m_gridBuffer)
            m_gl->glDeleteBuffers(1, &m_gridBuffer);
    }
    m_gridView = m_gridQuads = m_gridBuffer = 0;
    m_gridBufferBytes = 0;
    m_grids.clear();
    m_gridCap = kMaxTrimGridSide;
    m_gridBudget = 0;
    m_gridOptionCap = 0;
    m_budgetWarning.clear();
}

/// A surface's arcs: loops repaired as makeTrimRegion repairs them, at the same tolerance as
/// the CPU classification (model/nurbs/trim_arcs.h).
struct TrimSurfaceArcs {
    TrimArcs arcs;
    QStringList warnings;
    std::int64_t nanoseconds = 0;
};

namespace {

std::uint64_t nextClassSerial() {
    static std::uint64_t serial = 0;
    return ++serial;
}

TrimSurfaceArcs arcsOf(const Surface& s) {
    QElapsedTimer timer;
    timer.start();
    TrimSurfaceArcs a;
    a.arcs = makeTrimArcs(s.trims, trimTolerance(s.geometry), &a.warnings);
    a.nanoseconds = timer.nsecsElapsed();
    return a;
}

/// About the words a grid of `arcs` takes under `cap` (packTrimGrid's layout): texels exactly,
/// arcs and points exactly, pieces and entries from the crossings of about four grid lines per
/// texel row, plus at most 6 words that start the pieces and points on a multiple of 4. Used to
/// choose the cap before building (the builds then confirm it).
std::int64_t estimatedWords(const TrimArcs& arcs, int cap) {
    const std::int64_t side = trimGridResolution(arcs, cap).x;
    std::int64_t points = 0;
    for (const TrimArc& a : arcs.arcs)
        points += std::int64_t(a.hw.size());
    const std::int64_t n = std::int64_t(arcs.arcs.size());
    const std::int64_t pieces = n + 4 * side;
    return 5 + side * side + 2 * n + 4 * points + 8 * pieces + (3 * pieces) / 2 + 6;
}

} // namespace

void TrimMaskPass::buildGrid(TrimMask& m, const Surface& s, const Revisions& rev, bool* grew) {
    buildGrid(m, arcsOf(s), rev, grew);
}

void TrimMaskPass::buildGrid(TrimMask& m, const TrimSurfaceArcs& a, const Revisions& rev,
                             bool* grew) {
    QElapsedTimer timer;
    timer.start();
    const TrimArcs& arcs = a.arcs;
    m.warnings = a.warnings;
    m.active = !arcs.empty();
    m.layer = -1;
    m.trimsRevision = rev.trims;
    m.knotsRevision = rev.knots;
    TrimMaskStats d;
    d.redraws = 1;
    if (m.active) {
        const TrimGrid grid = makeTrimGrid(arcs, trimGridResolution(arcs, m_gridCap));
        if (!m_grids.place(m.grid, packTrimGrid(grid, arcs), grew)) {
            // Never a wrong picture: a surface whose trims cannot be addressed is left out of
            // the trimmed draws (drawn untrimmed) and says so.
            m.active = false;
            m.warnings << QStringLiteral("its trim grid does not fit the 16 GiB the trim "
                                         "buffer can address; drawn untrimmed");
        }
        m.rect = grid.rect;
        m.width = grid.width;
        m.height = grid.height;
        m.texelClass.resize(size_t(grid.texelCount()));
        for (int k = 0; k < grid.texelCount(); ++k)
            m.texelClass[size_t(k)] = grid.isEdge(k) ? 2 : grid.base[size_t(k)];
        m.classSerial = nextClassSerial();
        d.loops = arcs.loops;
        d.texels = std::int64_t(grid.width) * grid.height;
        d.largestSide = std::max(grid.width, grid.height);
    } else {
        m_grids.release(m.grid);
        m.width = m.height = 0;
        m.texelClass.clear();
        m.classSerial = nextClassSerial();
    }
    m.grid.cap = m_gridCap;
    d.cpuNanoseconds = timer.nsecsElapsed() + a.nanoseconds;
    m.stats += d;
    m_frame += d;
}

void TrimMaskPass::dropGrid(TrimMask& m) {
    if (!m.grid.words && !m.grid.cap && !m.active)
        return;
    m_grids.release(m.grid);
    const TrimMaskStats stats = m.stats;
    const QStringList warnings = m.warnings;
    m = TrimMask{};
    m.stats = stats;
    m.warnings = warnings;
    m.classSerial = nextClassSerial();
}

Status TrimMaskPass::syncExact(const std::vector<SurfaceRecord*>& records,
                               const FrameCamera& camera, const RenderOptions& options) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    // What mask mode held goes: the records' layers, then the array.
    for (SurfaceRecord* r : records)
        if (r->mask.layer >= 0)
            freeLayer(r->mask);
    freeArray();

    std::vector<SurfaceRecord*> trimmed;
    for (SurfaceRecord* r : records) {
        if (r->surface->trims.empty() || !r->exact) {
            freeLayer(r->mask); // no longer trimmed (or not drawn)
        } else if (options.cullOutsideView && r->bounded &&
                   ExactPlanner::outsideView(r->boundsLo, r->boundsHi, camera.viewProjection)) {
            // Wholly outside the view: the exact passes cull it by the same test, so no
            // fragment reads its grid. A close-up then holds the grids of what it shows;
            // the grid is built again when the surface comes back into view.
            dropGrid(r->mask);
        } else {
            trimmed.push_back(r);
        }
    }
    if (trimmed.empty()) {
        // No trimmed surface left: an emptied scene holds no trim memory.
        freeGrids();
        return ok();
    }
    GLint maxTexels = 0;
    gl->glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
    const std::int64_t budget =
        std::min(std::clamp(options.trimBudgetBytes, kMinTrimBudgetBytes, kMaxTrimBudgetBytes),
                 4 * std::int64_t(maxTexels));
    const int optionCap = std::clamp(options.trimGridCap, 1, kMaxTrimGridSide);
    if (budget != m_gridBudget || optionCap != m_gridOptionCap) {
        // A new budget or cap: start again from the largest grids the options allow (the loop
        // below coarsens them again if they still do not fit).
        m_gridBudget = budget;
        m_gridOptionCap = optionCap;
        m_gridCap = optionCap;
        m_budgetWarning.clear();
    }

    bool grew = false;
    std::vector<TrimMask*> rebuilt;
    const int capBefore = m_gridCap;
    // Whether a grid built under another cap would come out differently under m_gridCap.
    const auto capMoved = [this](const TrimMask& m) {
        const int side = std::max(m.width, m.height);
        return (m.grid.cap > m_gridCap && side > m_gridCap) ||
               (m.grid.cap < m_gridCap && side >= m.grid.cap);
    };
    std::vector<SurfaceRecord*> stale;
    for (SurfaceRecord* r : trimmed) {
        const TrimMask& m = r->mask;
        const Revisions& rev = r->revisions; // GpuScene::sync's, found by index
        if (m.grid.cap == 0 || m.trimsRevision != rev.trims || m.knotsRevision != rev.knots ||
            (m.active && capMoved(m)))
            stale.push_back(r);
    }
    std::vector<TrimSurfaceArcs> arcs;
    arcs.reserve(stale.size());
    std::int64_t keptWords = m_grids.usedBytes() / 4, staleWords = 0;
    for (SurfaceRecord* r : stale) {
        arcs.push_back(arcsOf(*r->surface));
        keptWords -= r->mask.grid.words;
        staleWords += estimatedWords(arcs.back().arcs, m_gridCap);
    }
    // Over budget: choose the cap from estimates before building, so that opening a large model
    // builds each grid once, not once per halving of the cap.
    std::int64_t wanted = 4 * (keptWords + staleWords);
    if (wanted > budget && !stale.empty()) {
        while (m_gridCap > 1) {
            std::int64_t words = keptWords;
            for (const TrimSurfaceArcs& a : arcs)
                words += estimatedWords(a.arcs, m_gridCap);
            if (4 * words <= budget)
                break;
            m_gridCap /= 2;
        }
    }
    for (size_t k = 0; k < stale.size(); ++k) {
        buildGrid(stale[k]->mask, arcs[k], stale[k]->revisions, &grew);
        rebuilt.push_back(&stale[k]->mask);
    }
    arcs.clear();
    // Still over budget (estimates are estimates, and grids built under a larger cap are
    // kept): halve the cap of the largest grids and rebuild them, until the blocks fit or the
    // grids are one texel (every piece then in one list: still exact, slower).
    wanted = std::max(wanted, m_grids.usedBytes());
    while (m_grids.usedBytes() > budget && m_gridCap > 1) {
        int largest = 0;
        for (const SurfaceRecord* r : trimmed)
            largest = std::max({largest, r->mask.width, r->mask.height});
        m_gridCap = std::max(1, std::min(m_gridCap, largest) / 2);
        for (SurfaceRecord* r : trimmed) {
            TrimMask& m = r->mask;
            if (m.active && (m.width > m_gridCap || m.height > m_gridCap)) {
                buildGrid(m, *r->surface, r->revisions, &grew);
                rebuilt.push_back(&m);
            }
        }
    }
    if (m_gridCap < capBefore) {
        const std::int64_t now = m_grids.usedBytes();
        m_budgetWarning =
            QStringLiteral("trim grids need %1 MiB, over the budget of %2 MiB: grids capped at "
                           "%3 texels a side (%4 MiB; more fragments take the exact path)%5")
                .arg(double(wanted) / (1 << 20), 0, 'f', 1)
                .arg(double(budget) / (1 << 20), 0, 'f', 1)
                .arg(m_gridCap)
                .arg(double(now) / (1 << 20), 0, 'f', 1)
                .arg(now > budget ? QStringLiteral(", still over: the trim curves alone exceed it")
                                  : QString());
    }
    if (m_grids.wantsCompaction(budget)) {
        std::vector<TrimGridBlock*> blocks;
        for (SurfaceRecord* r : trimmed)
            if (r->mask.grid.words)
                blocks.push_back(&r->mask.grid);
        m_grids.compact(blocks);
        grew = true; // blocks moved: the whole array goes up again
    }

    const std::vector<std::uint32_t>& words = m_grids.words();
    const std::int64_t bytes = std::int64_t(words.size()) * 4;
    while (gl->glGetError() != GL_NO_ERROR) {
        // errors of earlier calls are not this upload's
    }
    if (!m_gridBuffer || grew || bytes != m_gridBufferBytes) {
        // New, grown or compacted: the whole array (every block may have moved).
        if (!m_gridBuffer) {
            gl->glCreateBuffers(1, &m_gridBuffer);
            gl->glCreateTextures(GL_TEXTURE_BUFFER, 1, &m_gridView);
            gl->glCreateTextures(GL_TEXTURE_BUFFER, 1, &m_gridQuads);
        }
        gl->glNamedBufferData(m_gridBuffer, GLsizeiptr(std::max<std::int64_t>(bytes, 4)),
                              words.empty() ? nullptr : words.data(), GL_DYNAMIC_DRAW);
        gl->glTextureBuffer(m_gridView, GL_R32UI, m_gridBuffer);
        gl->glTextureBuffer(m_gridQuads, GL_RGBA32UI, m_gridBuffer); // the same words by 4
        m_gridBufferBytes = std::max<std::int64_t>(bytes, 4);
    } else {
        for (const TrimMask* m : rebuilt)
            if (m->grid.words)
                gl->glNamedBufferSubData(m_gridBuffer, GLintptr(m->grid.offset) * 4,
                                         GLsizeiptr(m->grid.words) * 4,
                                         words.data() + m->grid.offset);
    }
    if (const GLenum e = gl->glGetError(); e != GL_NO_ERROR) {
        const Error failed(QStringLiteral("the trim grid buffer of %1 bytes could not be filled "
                                          "(GL error 0x%2); trimmed surfaces are drawn untrimmed")
                               .arg(bytes)
                               .arg(e, 0, 16));
        // Never a wrong picture: nothing classifies by a buffer that did not arrive. Everything
        // is built again on the next frame.
        for (SurfaceRecord* r : trimmed)
            freeLayer(r->mask);
        freeGrids();
        return failed;
    }
    return ok();
}

} // namespace kw
