// The shared scene buffers (range allocation, growth, writes) and one surface's uploads into
// them: full, a moved point's texels and polygon vertices, the polygon, the trim split.
#include "render/gpu_pool.h"

#include "render/surface_bound.h"
#include "render/trim_mask_pass.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace kw {

std::int64_t RangeAllocator::allocate(std::int64_t count) {
    for (auto it = m_free.begin(); it != m_free.end(); ++it) {
        if (it->second < count)
            continue;
        const std::int64_t offset = it->first, left = it->second - count;
        m_free.erase(it);
        if (left > 0)
            m_free.emplace(offset + count, left);
        m_used += count;
        return offset;
    }
    const std::int64_t offset = m_end;
    m_end += count;
    m_used += count;
    return offset;
}

void RangeAllocator::free(std::int64_t offset, std::int64_t count) {
    if (count <= 0)
        return;
    m_used -= count;
    // Merge with the free neighbours on both sides.
    auto next = m_free.lower_bound(offset);
    if (next != m_free.end() && next->first == offset + count) {
        count += next->second;
        next = m_free.erase(next);
    }
    if (next != m_free.begin()) {
        auto prev = std::prev(next);
        if (prev->first + prev->second == offset) {
            offset = prev->first;
            count += prev->second;
            m_free.erase(prev);
        }
    }
    if (offset + count == m_end)
        m_end = offset; // the top range: the end moves down instead
    else
        m_free.emplace(offset, count);
}

std::int64_t GpuPool::grownCapacity(std::int64_t capacity, std::int64_t need,
                                    std::int64_t elementBytes, std::int64_t maxBytes) {
    const std::int64_t limit = maxBytes / elementBytes;
    std::int64_t grown = std::max<std::int64_t>(capacity, kMinElements);
    while (grown < need) {
        // Doubling keeps the copies few while the pool is small; past kDoublingBytes a quarter
        // more each time, so a scene of thousands of surfaces does not hold up to twice its
        // data (the slack is at most a quarter; the copies stay linear in the total).
        const bool small = grown * elementBytes < kDoublingBytes;
        grown = small ? grown * 2 : grown + std::max<std::int64_t>(grown / 4, 1);
    }
    return std::min(grown, limit);
}

std::int64_t GpuPool::allocate(std::int64_t count) {
    if (count <= 0)
        return 0;
    const std::int64_t offset = m_ranges.allocate(count);
    const std::int64_t need = m_ranges.end();
    if (need > m_capacity) {
        const std::int64_t capacity = grownCapacity(m_capacity, need, m_elementBytes, m_maxBytes);
        if (capacity < need) {
            m_ranges.free(offset, count);
            return -1;
        }
        GLuint grown = 0;
        m_gl->glCreateBuffers(1, &grown);
        m_gl->glNamedBufferData(grown, GLsizeiptr(capacity * m_elementBytes), nullptr,
                                GL_DYNAMIC_DRAW);
        if (m_buffer) {
            m_gl->glCopyNamedBufferSubData(m_buffer, grown, 0, 0,
                                           GLsizeiptr(m_capacity * m_elementBytes));
            // The copy must have run before the old buffer goes and before the next
            // glNamedBufferSubData into the new one. GL orders them, but NVIDIA 580.159 (H100,
            // GLX) did not: ranges copied here read as zeros in the draws (vertices at the
            // origin, stray triangles on every CAD part; docs/PERFORMANCE.md "On a GPU").
            // A pool grows by at least a quarter of itself, so the wait is rare.
            m_gl->glFinish();
            m_gl->glDeleteBuffers(1, &m_buffer);
        }
        m_buffer = grown;
        m_capacity = capacity;
    }
    return offset;
}

void GpuPool::free(std::int64_t offset, std::int64_t count) {
    if (offset < 0 || count <= 0) // never allocated (a failed allocation leaves -1)
        return;
    m_ranges.free(offset, count);
    if (m_ranges.used() == 0)
        release();
}

void GpuPool::write(std::int64_t offset, std::int64_t count, const void* data) {
    if (count > 0)
        m_gl->glNamedBufferSubData(m_buffer, GLintptr(offset * m_elementBytes),
                                   GLsizeiptr(count * m_elementBytes), data);
}

bool GpuPool::shouldCompact(std::int64_t capacity, std::int64_t used) {
    return used > 0 && capacity > 2 * compactedCapacity(used);
}

std::int64_t GpuPool::compactedCapacity(std::int64_t used) {
    return std::max(used + used / 4, kMinElements);
}

bool GpuPool::compact(std::vector<Range> ranges) {
    const std::int64_t used = m_ranges.used();
    if (!m_buffer || !shouldCompact(m_capacity, used))
        return false;
    std::int64_t total = 0;
    for (const Range& r : ranges) {
        if (!r.offset || *r.offset < 0 || r.count <= 0 || *r.offset + r.count > m_ranges.end())
            return false;
        total += r.count;
    }
    std::sort(ranges.begin(), ranges.end(),
              [](const Range& a, const Range& b) { return *a.offset < *b.offset; });
    for (size_t k = 1; k < ranges.size(); ++k)
        if (*ranges[k - 1].offset + ranges[k - 1].count > *ranges[k].offset)
            return false; // overlapping: not the allocator's ranges
    if (total != used)
        return false; // a range not listed would be lost
    const std::int64_t capacity = compactedCapacity(used);
    GLuint packed = 0;
    m_gl->glCreateBuffers(1, &packed);
    m_gl->glNamedBufferData(packed, GLsizeiptr(capacity * m_elementBytes), nullptr,
                            GL_DYNAMIC_DRAW);
    // Neighbouring ranges stay neighbours: one copy per run of them.
    std::int64_t to = 0;
    for (size_t k = 0; k < ranges.size();) {
        const std::int64_t from = *ranges[k].offset;
        std::int64_t run = 0;
        size_t end = k;
        while (end < ranges.size() && *ranges[end].offset == from + run)
            run += ranges[end++].count;
        m_gl->glCopyNamedBufferSubData(m_buffer, packed, GLintptr(from * m_elementBytes),
                                       GLintptr(to * m_elementBytes),
                                       GLsizeiptr(run * m_elementBytes));
        for (; k < end; ++k) {
            *ranges[k].offset = to;
            to += ranges[k].count;
        }
    }
    // Waited for before the old buffer goes, as when the pool grows (allocate).
    m_gl->glFinish();
    m_gl->glDeleteBuffers(1, &m_buffer);
    m_buffer = packed;
    m_capacity = capacity;
    m_ranges.clear();
    m_ranges.allocate(used); // one live block [0, used): the ranges' new places
    return true;
}

void GpuPool::release() {
    if (m_buffer && m_gl)
        m_gl->glDeleteBuffers(1, &m_buffer);
    m_buffer = 0;
    m_capacity = 0;
    m_ranges.clear();
}

// ---- One surface's uploads

namespace {

void freePolygon(ScenePools& pools, SurfaceGpu& g) {
    pools.vertices.free(g.vertexOffset, g.vertexCount);
    pools.triangles.free(g.triangleOffset, g.triangleIndexCount);
    pools.outlines.free(g.outlineOffset, g.outlineIndexCount);
    pools.skirtVertices.free(g.skirtVertexOffset, g.skirtVertexCount);
    pools.skirtIndices.free(g.skirtIndexOffset, g.skirtIndexCount);
    g.vertexOffset = g.triangleOffset = g.outlineOffset = -1;
    g.skirtVertexOffset = g.skirtIndexOffset = -1;
    g.vertexCount = g.skirtVertexCount = 0;
    g.triangleIndexCount = g.outlineIndexCount = g.skirtIndexCount = 0;
}

// Every polygon and cover rebuilt gets the next: SurfaceGpu::polygonSerial.
std::uint64_t g_polygonSerial = 0;

void freeControl(ScenePools& pools, SurfaceGpu& g) {
    pools.control.free(g.controlOffset, std::int64_t(g.countU) * g.countV);
    pools.spans.free(g.spanOffset, g.spanTexelsU + g.spanTexelsV);
    g.controlOffset = g.spanOffset = -1;
    g.spanTexelsU = g.spanTexelsV = 0;
}

} // namespace

bool uploadSurface(ScenePools& pools, SurfaceGpu& g, const Surface& s, const PolygonCut& cut,
                   const ParameterBox& box, bool skirt, bool outlines, UploadStats& stats) {
    const NurbsSurface& geo = s.geometry;
    freeControl(pools, g);
    g.degreeU = geo.degreeU;
    g.degreeV = geo.degreeV;
    g.countU = geo.countU;
    g.countV = geo.countV;
    const Interval du = surfaceDomainU(geo), dv = surfaceDomainV(geo);
    g.domain = glm::vec4(float(du.first), float(du.last), float(dv.first), float(dv.last));

    g.origin = controlOrigin(geo);
    g.control = packControlPoints(geo, g.origin);
    g.affine = surfaceIsAffine(geo);
    const std::vector<glm::vec4> su = packSpanTable(geo.knotsU, geo.degreeU, geo.countU);
    const std::vector<glm::vec4> sv = packSpanTable(geo.knotsV, geo.degreeV, geo.countV);
    const std::int64_t texels = std::int64_t(g.control.size());
    g.controlOffset = pools.control.allocate(texels);
    g.spanOffset =
        g.controlOffset < 0 ? -1 : pools.spans.allocate(std::int64_t(su.size() + sv.size()));
    if (g.controlOffset < 0 || g.spanOffset < 0) {
        if (g.controlOffset >= 0)
            pools.control.free(g.controlOffset, texels);
        g.controlOffset = g.spanOffset = -1;
        freePolygon(pools, g);
        return false;
    }
    g.spanTexelsU = std::int64_t(su.size());
    g.spanTexelsV = std::int64_t(sv.size());
    pools.control.write(g.controlOffset, texels, g.control.data());
    stats.fullUploads += 1;
    stats.texels += texels;
    stats.bytes += texels * std::int64_t(sizeof(glm::vec4));

    pools.spans.write(g.spanOffset, g.spanTexelsU, su.data());
    pools.spans.write(g.spanOffset + g.spanTexelsU, g.spanTexelsV, sv.data());
    stats.spanTableUploads += 2;
    stats.bytes += std::int64_t((su.size() + sv.size()) * sizeof(glm::vec4));
    if (!rebuildPolygon(pools, g, s, cut, box, skirt, outlines, stats)) {
        freeControl(pools, g);
        return false;
    }
    return true;
}

void uploadChangedPoints(ScenePools& pools, SurfaceGpu& g, const Surface& s, UploadStats& stats) {
    const std::vector<glm::vec4> now = packControlPoints(s.geometry, g.origin);
    int i0 = g.countU, i1 = -1, j0 = g.countV, j1 = -1;
    for (int j = 0; j < g.countV; ++j)
        for (int i = 0; i < g.countU; ++i) {
            const size_t k = size_t(j * g.countU + i);
            if (now[k] != g.control[k]) {
                i0 = std::min(i0, i), i1 = std::max(i1, i);
                j0 = std::min(j0, j), j1 = std::max(j1, j);
            }
        }
    if (i1 < 0)
        return; // revision moved (e.g. undo then redo) but the texels are identical
    g.control = now;
    g.affine = surfaceIsAffine(s.geometry);
    const int w = i1 - i0 + 1, h = j1 - j0 + 1;
    // Rows are contiguous in the pool: one write per row of the rectangle (one in a drag).
    for (int j = j0; j <= j1; ++j) {
        const std::int64_t k = std::int64_t(j) * g.countU + i0;
        pools.control.write(g.controlOffset + k, w, g.control.data() + k);
    }
    stats.subImageUploads += 1;
    stats.texels += std::int64_t(w) * h;
    stats.bytes += std::int64_t(w) * h * std::int64_t(sizeof(glm::vec4));

    // The vertices' CPU copy went after the upload (rebuildPolygon): the first change of the
    // surface's points brings it back whole, from the new points. The nodes outside the moved
    // points' support come out as they are on the GPU (the same points, the same sums), so
    // only the support's range is written, as with the copy kept.
    if (g.cover)
        return; // a cover is rebuilt from the new bounds (GpuScene::syncSurface)
    if (g.polygon.vertices.empty() && g.vertexCount > 0)
        g.polygon.vertices = buildBasePolygon(s.geometry, g.polygonBox, g.cut).vertices;
    int first = 0, last = -1;
    if (updateBasePolygon(g.polygon, s.geometry, i0, i1, j0, j1, first, last)) {
        const std::int64_t count = last - first + 1;
        pools.vertices.write(g.vertexOffset + first, count,
                             g.polygon.vertices.data() + size_t(first));
        const std::int64_t size = count * std::int64_t(sizeof(BaseVertex));
        stats.vertexUpdates += 1;
        stats.vertexBytes += size;
        stats.bytes += size;
        if (g.skirtVertexOffset < 0)
            return;
        // The skirt repeats the outline's nodes, two vertices each, side by side (bottom,
        // right, top, left; kw::skirtVertices): rewrite the runs of the sides that pass
        // through the rectangle of nodes updateBasePolygon re-evaluated (first and last are
        // its corners), a few per boundary node a moved point reaches.
        const int nu = g.polygon.nodesU(), nv = int(g.polygon.breaksV.size());
        const int gu0 = first % nu, gv0 = first / nu, gu1 = last % nu, gv1 = last / nu;
        const std::vector<SkirtVertex> skirt = skirtVertices(g.polygon);
        const auto run = [&](std::int64_t side, int k0, int k1) {
            const std::int64_t at = side + 2 * std::int64_t(k0);
            const std::int64_t n = 2 * std::int64_t(k1 - k0 + 1);
            if (at < 0 || at + n > std::int64_t(skirt.size()))
                return;
            pools.skirtVertices.write(g.skirtVertexOffset + at, n, skirt.data() + at);
            stats.vertexBytes += n * std::int64_t(sizeof(SkirtVertex));
            stats.bytes += n * std::int64_t(sizeof(SkirtVertex));
        };
        const std::int64_t right = 2 * std::int64_t(nu), top = right + 2 * std::int64_t(nv),
                           left = top + 2 * std::int64_t(nu);
        if (gv0 == 0)
            run(0, gu0, gu1);
        if (gu1 == nu - 1)
            run(right, gv0, gv1);
        if (gv1 == nv - 1)
            run(top, gu0, gu1);
        if (gu0 == 0)
            run(left, gv0, gv1);
    }
}

std::int64_t PolygonUpload::bytes() const {
    return std::int64_t(
        polygon.vertices.size() * sizeof(BaseVertex) + skirt.size() * sizeof(SkirtVertex) +
        (triangles.size() + outlines.size() + skirtIndices.size()) * sizeof(unsigned));
}

PolygonUpload buildPolygonUpload(const NurbsSurface& geo, const ParameterBox& box,
                                 const PolygonCut& cut, bool withSkirt, bool withOutlines) {
    PolygonUpload u;
    u.polygon = buildBasePolygon(geo, box, cut);
    u.triangles = basePolygonTriangles(u.polygon);
    if (withOutlines)
        u.outlines = basePolygonOutlines(u.polygon);
    if (withSkirt)
        buildSkirt(u.polygon, u.skirt, u.skirtIndices);
    return u;
}

namespace {

/// A new polygon (or cover) in `g`'s ranges: what was derived from the old one goes.
void newPolygon(SurfaceGpu& g) {
    g.polygonSerial = ++g_polygonSerial;
    g.insideIndexCount = -1;
    g.edgeIndexCount = 0;
    g.splitPolygon = g.splitClasses = g.splitSections = 0;
    g.keptIndexCount = g.crossedIndexCount = 0;
    std::vector<std::uint8_t>().swap(g.cellBuckets);
}

} // namespace

bool rebuildPolygon(ScenePools& pools, SurfaceGpu& g, const Surface& s, const PolygonCut& cut,
                    const ParameterBox& box, bool withSkirt, bool withOutlines,
                    UploadStats& stats) {
    freePolygon(pools, g);
    g.cut = cut;
    g.polygonBox = box;
    PolygonUpload u = buildPolygonUpload(s.geometry, box, cut, withSkirt, withOutlines);
    const std::int64_t vertices = std::int64_t(u.polygon.vertices.size());
    const std::int64_t triangles = std::int64_t(u.triangles.size());
    const std::int64_t lines = std::int64_t(u.outlines.size());
    const std::int64_t skirtVertices = std::int64_t(u.skirt.size());
    const std::int64_t skirtIndices = std::int64_t(u.skirtIndices.size());
    const std::int64_t v = pools.vertices.allocate(vertices);
    const std::int64_t t = v < 0 ? -1 : pools.triangles.allocate(triangles);
    const std::int64_t o = t < 0 || !withOutlines ? -1 : pools.outlines.allocate(lines);
    std::int64_t sv = -1, si = -1; // -1: no skirt
    bool fits = t >= 0 && (!withOutlines || o >= 0);
    if (fits && withSkirt) {
        sv = pools.skirtVertices.allocate(skirtVertices);
        si = sv < 0 ? -1 : pools.skirtIndices.allocate(skirtIndices);
        fits = si >= 0;
    }
    if (!fits) {
        if (v >= 0)
            pools.vertices.free(v, vertices);
        if (t >= 0)
            pools.triangles.free(t, triangles);
        if (o >= 0)
            pools.outlines.free(o, lines);
        if (sv >= 0)
            pools.skirtVertices.free(sv, skirtVertices);
        return false;
    }
    g.polygon = std::move(u.polygon);
    g.vertexOffset = v, g.vertexCount = vertices;
    g.triangleOffset = t, g.triangleIndexCount = int(triangles);
    g.outlineOffset = o, g.outlineIndexCount = int(lines);
    g.skirtVertexOffset = sv, g.skirtVertexCount = skirtVertices;
    g.skirtIndexOffset = si, g.skirtIndexCount = int(skirtIndices);
    newPolygon(g);
    g.cover = false;
    g.coverBoxes = 0;
    pools.vertices.write(v, vertices, g.polygon.vertices.data());
    pools.triangles.write(t, triangles, u.triangles.data());
    if (withOutlines)
        pools.outlines.write(o, lines, u.outlines.data());
    if (withSkirt) {
        pools.skirtVertices.write(sv, skirtVertices, u.skirt.data());
        pools.skirtIndices.write(si, skirtIndices, u.skirtIndices.data());
    }
    stats.basePolygonBuilds += 1;
    stats.bytes += u.bytes();
    // The vertices' CPU copy serves a skirted polygon's fins and skirt, rebuilt from it as the
    // view moves; without a skirt only a later point change reads it (uploadChangedPoints
    // brings it back then). Not kept: at 30 x 30 it is 30 KB a surface, 300 MB over 10,000.
    if (!withSkirt)
        std::vector<BaseVertex>().swap(g.polygon.vertices); // `= {}` would keep the capacity
    return true;
}

bool rebuildCover(ScenePools& pools, SurfaceGpu& g, const CoverMesh& cover, const PolygonCut& cut,
                  const ParameterBox& box, UploadStats& stats) {
    freePolygon(pools, g);
    g.cut = cut;
    g.polygonBox = box;
    const std::int64_t vertices = std::int64_t(cover.vertices.size());
    const std::int64_t triangles = std::int64_t(cover.triangles.size());
    const std::int64_t v = pools.vertices.allocate(vertices);
    const std::int64_t t = v < 0 ? -1 : pools.triangles.allocate(triangles);
    if (t < 0) {
        if (v >= 0)
            pools.vertices.free(v, vertices);
        return false;
    }
    g.polygon = BasePolygon{};
    g.vertexOffset = v, g.vertexCount = vertices;
    g.triangleOffset = t, g.triangleIndexCount = int(triangles);
    g.outlineOffset = -1, g.outlineIndexCount = 0;
    g.skirtVertexOffset = -1, g.skirtVertexCount = 0;
    g.skirtIndexOffset = -1, g.skirtIndexCount = 0;
    newPolygon(g);
    g.cover = true;
    g.coverBoxes = cover.boxes();
    pools.vertices.write(v, vertices, cover.vertices.data());
    pools.triangles.write(t, triangles, cover.triangles.data());
    stats.basePolygonBuilds += 1;
    stats.bytes += std::int64_t(vertices * std::int64_t(sizeof(BaseVertex)) +
                                triangles * std::int64_t(sizeof(unsigned)));
    return true;
}

bool addOutlines(ScenePools& pools, SurfaceGpu& g, UploadStats& stats) {
    if (g.outlineOffset >= 0 || g.vertexOffset < 0)
        return true;
    const std::vector<unsigned> lines = basePolygonOutlines(g.polygon);
    const std::int64_t o = pools.outlines.allocate(std::int64_t(lines.size()));
    if (o < 0)
        return false;
    g.outlineOffset = o, g.outlineIndexCount = int(lines.size());
    pools.outlines.write(o, std::int64_t(lines.size()), lines.data());
    stats.bytes += std::int64_t(lines.size() * sizeof(unsigned));
    return true;
}

void destroySurfaceGpu(ScenePools& pools, SurfaceGpu& g) {
    freeControl(pools, g);
    freePolygon(pools, g);
}

bool controlBounds(const SurfaceGpu& g, glm::vec3& lo, glm::vec3& hi) {
    lo = glm::vec3(std::numeric_limits<float>::max());
    hi = glm::vec3(-std::numeric_limits<float>::max());
    for (const glm::vec4& t : g.control) {
        if (!(t.w > 0.0f))
            continue;
        const glm::vec3 p = glm::vec3(t) / t.w;
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    if (lo.x > hi.x)
        return false;
    const glm::vec3 o(g.origin);
    lo += o;
    hi += o;
    return true;
}

namespace {

/// 0 trimmed away, 1 inside, 2 near an edge, for the (u, v) rectangle [u0, u1] x [v0, v1].
int cellTrimClass(const TrimMask& m, double u0, double u1, double v0, double v1) {
    const double sx = double(m.width) / (m.rect.y - m.rect.x);
    const double sy = double(m.height) / (m.rect.w - m.rect.z);
    // The texels the rectangle overlaps, grown by one; beyond the grid everything is outside
    // every loop (trimGridRect).
    const double fx0 = std::floor((u0 - m.rect.x) * sx) - 1,
                 fx1 = std::floor((u1 - m.rect.x) * sx) + 1;
    const double fy0 = std::floor((v0 - m.rect.z) * sy) - 1,
                 fy1 = std::floor((v1 - m.rect.z) * sy) + 1;
    bool in = false, out = false;
    if (fx0 < 0 || fy0 < 0 || fx1 >= m.width || fy1 >= m.height)
        out = true;
    const int i0 = int(std::clamp(fx0, 0.0, double(m.width - 1)));
    const int i1 = int(std::clamp(fx1, 0.0, double(m.width - 1)));
    const int j0 = int(std::clamp(fy0, 0.0, double(m.height - 1)));
    const int j1 = int(std::clamp(fy1, 0.0, double(m.height - 1)));
    if (fx1 < 0 || fy1 < 0 || fx0 >= m.width || fy0 >= m.height)
        return 0; // wholly beside the grid
    for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
            const std::uint8_t c = m.texelClass[size_t(j * m.width + i)];
            if (c == 2)
                return 2;
            (c ? in : out) = true;
            if (in && out)
                return 2;
        }
    return in ? 1 : 0;
}

} // namespace

std::optional<CoverBox> coverBox(const std::vector<SpanBound>& spans, const ParameterBox& box) {
    CoverBox c;
    bool any = false;
    for (const SpanBound& b : spans)
        for (int j = 0; j < b.grid; ++j)
            for (int i = 0; i < b.grid; ++i) {
                const double a0 = std::max(b.sideU(i), box.u.first);
                const double a1 = std::min(b.sideU(i + 1), box.u.last);
                const double c0 = std::max(b.sideV(j), box.v.first);
                const double c1 = std::min(b.sideV(j + 1), box.v.last);
                if (!(a0 <= a1 && c0 <= c1))
                    continue;
                const SpanBound::Sub& sub = b.subs[size_t(j * b.grid + i)];
                c.bounds.lo = any ? glm::min(c.bounds.lo, sub.lo) : sub.lo;
                c.bounds.hi = any ? glm::max(c.bounds.hi, sub.hi) : sub.hi;
                c.u0 = any ? std::min(c.u0, a0) : a0;
                c.u1 = any ? std::max(c.u1, a1) : a1;
                c.v0 = any ? std::min(c.v0, c0) : c0;
                c.v1 = any ? std::max(c.v1, c1) : c1;
                any = true;
            }
    if (!any)
        return std::nullopt;
    // The span nearest the middle (holding it, unless the box's spans leave a gap there).
    const glm::dvec2 mid(0.5 * (c.u0 + c.u1), 0.5 * (c.v0 + c.v1));
    double best = std::numeric_limits<double>::infinity();
    for (const SpanBound& b : spans) {
        const double du = std::max({b.u0 - mid.x, mid.x - b.u1, 0.0});
        const double dv = std::max({b.v0 - mid.y, mid.y - b.v1, 0.0});
        if (du + dv < best)
            best = du + dv, c.span = &b;
    }
    return c;
}

CoverMesh buildCover(const NurbsSurface& s, const CoverBox& box) {
    // The faces of the unit box, corner k at (k & 1, k >> 1 & 1, k >> 2 & 1), each as a quad
    // turned so that its normal (by the right-hand rule) points into the box.
    struct Quad {
        unsigned c[4];
    };
    std::vector<Quad> faces;
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            const int b = (axis + 1) % 3, c = (axis + 2) % 3;
            Quad q{};
            const int order[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
            for (int k = 0; k < 4; ++k)
                q.c[k] = unsigned(side << axis | order[k][0] << b | order[k][1] << c);
            const auto at = [](unsigned k) {
                return glm::dvec3(k & 1, k >> 1 & 1, k >> 2 & 1);
            };
            const glm::dvec3 n = glm::cross(at(q.c[1]) - at(q.c[0]), at(q.c[2]) - at(q.c[0]));
            const glm::dvec3 inward = glm::dvec3(0.5) - at(q.c[0]);
            if (glm::dot(n, inward) < 0.0)
                std::swap(q.c[1], q.c[3]);
            faces.push_back(q);
        }
    CoverMesh m;
    // The corners are floats: grown by their rounding and then some, so the box still holds
    // the patch as the GPU sees it.
    const SpanBound::Sub& sub = box.bounds;
    const double margin =
        1e-6 * (glm::length(sub.hi - sub.lo) + glm::length(sub.lo) + glm::length(sub.hi));
    const glm::dvec3 lo = sub.lo - margin, hi = sub.hi + margin;
    BaseVertex v{};
    v.uv = glm::vec2(float(0.5 * (box.u0 + box.u1)), float(0.5 * (box.v0 + box.v1)));
    v.span = glm::ivec2(box.span->spanU, box.span->spanV);
    v.spanScale = spanScale(s, box.span->spanU, box.span->spanV);
    for (unsigned k = 0; k < 8; ++k) {
        v.position = glm::vec3(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
        m.vertices.push_back(v);
    }
    for (const Quad& q : faces)
        m.triangles.insert(m.triangles.end(), {q.c[0], q.c[1], q.c[2], q.c[0], q.c[2], q.c[3]});
    return m;
}

bool splitByTrims(ScenePools& pools, SurfaceGpu& g, const TrimMask* mask) {
    return splitCells(pools, g, mask, nullptr, 0);
}

bool splitCells(ScenePools& pools, SurfaceGpu& g, const TrimMask* mask,
                const std::vector<std::uint8_t>* sections, std::uint64_t sectionSerial) {
    const bool usable = mask && mask->usable() && !mask->texelClass.empty() && mask->width > 0 &&
                        mask->height > 0 && g.triangleOffset >= 0;
    const std::uint64_t classes = usable ? mask->classSerial : 0;
    if (g.cover)
        return false; // one range, drawn with exact depth: nothing to split
    const BasePolygon& poly = g.polygon;
    const bool cut = sections && sectionSerial != 0 && g.triangleOffset >= 0 &&
                     sections->size() == size_t(poly.cellCount());
    const std::uint64_t planes = cut ? sectionSerial : 0;
    if (g.splitPolygon == g.polygonSerial && g.splitClasses == classes &&
        g.splitSections == planes)
        return false;
    g.splitPolygon = g.polygonSerial;
    g.splitClasses = classes;
    g.splitSections = planes;
    const bool wasSplit = g.insideIndexCount >= 0 || g.keptIndexCount > 0 ||
                          g.crossedIndexCount > 0;
    g.keptIndexCount = g.crossedIndexCount = 0;
    if (!usable && !cut) {
        // One range of every cell, in whatever order the last split left them.
        g.insideIndexCount = -1;
        g.edgeIndexCount = 0;
        return wasSplit;
    }
    // Buckets in drawing order: kept and inside, kept near an edge, crossed near an edge,
    // crossed inside, then the rest (trimmed away or removed).
    std::vector<unsigned> byClass[5];
    std::vector<std::uint8_t> buckets(size_t(poly.cellCount()));
    const unsigned row = unsigned(poly.nodesU());
    for (int cv = 0; cv < poly.cellsV(); ++cv)
        for (int cu = 0; cu < poly.cellsU(); ++cu) {
            const int trim =
                usable ? cellTrimClass(*mask, poly.breaksU[size_t(cu)],
                                       poly.breaksU[size_t(cu + 1)], poly.breaksV[size_t(cv)],
                                       poly.breaksV[size_t(cv + 1)])
                       : 1;
            const std::uint8_t side =
                cut ? (*sections)[size_t(cv) * size_t(poly.cellsU()) + size_t(cu)] : 0;
            const int bucket = trim == 0 || side == 2 ? 4
                               : side == 1            ? (trim == 2 ? 2 : 3)
                                                      : (trim == 2 ? 1 : 0);
            buckets[size_t(cv) * size_t(poly.cellsU()) + size_t(cu)] = std::uint8_t(bucket);
            const unsigned ll = unsigned(cv) * row + unsigned(cu), lr = ll + 1, ul = ll + row,
                           ur = ul + 1;
            byClass[bucket].insert(byClass[bucket].end(), {ll, lr, ur, ll, ur, ul});
        }
    const int sizes[5] = {int(byClass[0].size()), int(byClass[1].size()), int(byClass[2].size()),
                          int(byClass[3].size()), int(byClass[4].size())};
    std::vector<unsigned> tri = std::move(byClass[0]);
    for (int k = 1; k < 5; ++k)
        tri.insert(tri.end(), byClass[k].begin(), byClass[k].end());
    if (int(tri.size()) != g.triangleIndexCount) {
        // Not this polygon's cells (cannot happen: built from g.polygon): stay one range.
        g.insideIndexCount = -1;
        g.edgeIndexCount = 0;
        g.splitSections = 0;
        return wasSplit;
    }
    pools.triangles.write(g.triangleOffset, std::int64_t(tri.size()), tri.data());
    g.cellBuckets = std::move(buckets);
    if (usable) {
        g.insideIndexCount = sizes[0];
        g.edgeIndexCount = sizes[1];
    } else {
        g.insideIndexCount = -1; // not split by the trims: the kept cells are one range
        g.edgeIndexCount = 0;
    }
    if (cut) {
        g.keptIndexCount = sizes[0] + sizes[1];
        g.crossedIndexCount = sizes[2] + sizes[3];
    }
    return true;
}

} // namespace kw
