// GpuScene: the one sync per frame (drop removed surfaces, compare revisions once, rebuild the
// stale parts the frame needs) and the per-record bookkeeping.
#include "render/gpu_scene.h"

#include "model/visible_bounds.h"
#include "render/gpu_layout.h"

#include <QElapsedTimer>

namespace kw {

void GpuScene::initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders) {
    m_gl = gl;
    m_masks.initialize(gl, shaders);
}

bool GpuScene::sync(const Document& doc, const FrameCamera& camera, const RenderOptions& options,
                    FrameReport& report, QString* error) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    QElapsedTimer timer;
    timer.start();
    // Ids and revisions are per document: another document's data is never reused.
    if (m_document != &doc) {
        release();
        m_document = &doc;
    }
    // The one place removed surfaces are dropped, with every part they hold.
    for (auto it = m_entries.begin(); it != m_entries.end();) {
        if (!doc.surface(it->first)) {
            drop(it->second);
            it = m_entries.erase(it);
        } else {
            ++it;
        }
    }
    const Scene& scene = doc.scene();
    GLint maxSize = 0;
    gl->glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    QStringList tooLarge;
    m_order.clear();
    m_order.reserve(scene.surfaces.size());
    UploadStats frame;
    for (const Surface& s : scene.surfaces) {
        Entry& e = m_entries[s.id];
        SurfaceRecord& r = e.record;
        r.id = s.id;
        r.surface = &s;
        const int nu = options.partitionsU > 0 ? options.partitionsU : s.partitionsU;
        const int nv = options.partitionsV > 0 ? options.partitionsV : s.partitionsV;
        const Revisions rev = doc.revisions(s.id);
        const NurbsSurface& geo = s.geometry;
        UploadStats up;
        if (geo.countU > maxSize || geo.countV > maxSize) {
            // Not drawn: its control net does not fit one texture.
            if (r.exact) {
                destroySurfaceGpu(gl, *r.exact);
                r.exact.reset();
            }
            tooLarge << QStringLiteral("surface %1 (\"%2\") has %3 x %4 control points, more "
                                       "than the GPU's texture size limit %5")
                            .arg(s.id.value)
                            .arg(s.name)
                            .arg(geo.countU)
                            .arg(geo.countV)
                            .arg(maxSize);
        } else {
            std::unique_ptr<SurfaceGpu>& g = r.exact;
            // The polygon spans the trims' (u, v) box (a small face on a large domain gets its
            // partitions) or, with polygonOverTrims off, the domain. The box is recomputed only
            // when the trims or that option changed.
            const auto boxFor = [&] {
                return options.polygonOverTrims
                           ? trimParameterBox(s)
                           : ParameterBox{surfaceDomainU(geo), surfaceDomainV(geo)};
            };
            if (!g || g->revisions.knots != rev.knots || g->degreeU != geo.degreeU ||
                g->degreeV != geo.degreeV || g->countU != geo.countU || g->countV != geo.countV) {
                if (!g) {
                    g = std::make_unique<SurfaceGpu>();
                    g->id = s.id;
                }
                uploadSurface(gl, *g, s, nu, nv, boxFor(), up);
            } else {
                const bool boxStale = g->polygonTrimmed != options.polygonOverTrims ||
                                      (options.polygonOverTrims && g->revisions.trims != rev.trims);
                const ParameterBox box = boxStale ? boxFor() : g->polygonBox;
                if (g->partitionsU != nu || g->partitionsV != nv || box != g->polygonBox) {
                    // The polygon is rebuilt from the current points; pick up a point change.
                    if (g->revisions.points != rev.points)
                        uploadChangedPoints(gl, *g, s, up);
                    rebuildPolygon(gl, *g, s, nu, nv, box, up);
                } else if (g->revisions.points != rev.points) {
                    uploadChangedPoints(gl, *g, s, up);
                }
            }
            g->polygonTrimmed = options.polygonOverTrims;
            g->revisions = rev;
        }
        if (options.mode == RenderMode::Tessellated)
            syncMesh(r, rev, nu, nv, up);
        if (options.controlNet)
            syncNet(r, rev, up);
        e.stats += up;
        frame += up;
        m_order.push_back(&r);
    }
    report.uploads += frame;
    report.cpuMs.sync += double(timer.nsecsElapsed()) * 1e-6;

    bool ok = tooLarge.isEmpty();
    if (!ok) {
        *error = tooLarge.join(QStringLiteral("; "));
        report.warnings << tooLarge;
    }
    if (options.trims) {
        timer.restart();
        QString maskError;
        if (!m_masks.sync(doc, m_order, camera, options, &maskError)) {
            if (ok)
                *error = maskError;
            ok = false;
        }
        report.masks += m_masks.frameStats();
        report.drawCalls += m_masks.drawCalls;
        report.warnings << maskWarnings();
        report.cpuMs.masks += double(timer.nsecsElapsed()) * 1e-6;
    }
    return ok;
}

void GpuScene::syncMesh(SurfaceRecord& r, const Revisions& rev, int nu, int nv, UploadStats& up) {
    MeshGpu& m = r.mesh;
    if (m.vao && m.revisions.points == rev.points && m.revisions.knots == rev.knots && m.nu == nu &&
        m.nv == nv)
        return;
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    const TessellatedMesh t = tessellate(r.surface->geometry, nu, nv);
    if (!m.vao) {
        gl->glCreateVertexArrays(1, &m.vao);
        GLuint* bufs[] = {&m.positions, &m.normals, &m.uvs, &m.indices};
        for (GLuint* b : bufs)
            gl->glCreateBuffers(1, b);
        const GLuint attrBuf[] = {m.positions, m.normals, m.uvs};
        const int sizes[] = {3, 3, 2};
        for (GLuint a = 0; a < 3; ++a) {
            gl->glVertexArrayVertexBuffer(m.vao, a, attrBuf[a], 0,
                                          GLsizei(sizes[a] * sizeof(float)));
            gl->glEnableVertexArrayAttrib(m.vao, a);
            gl->glVertexArrayAttribFormat(m.vao, a, sizes[a], GL_FLOAT, GL_FALSE, 0);
            gl->glVertexArrayAttribBinding(m.vao, a, a);
        }
        gl->glVertexArrayElementBuffer(m.vao, m.indices);
    }
    gl->glNamedBufferData(m.positions, GLsizeiptr(t.positions.size() * sizeof(glm::vec3)),
                          t.positions.data(), GL_DYNAMIC_DRAW);
    gl->glNamedBufferData(m.normals, GLsizeiptr(t.normals.size() * sizeof(glm::vec3)),
                          t.normals.data(), GL_DYNAMIC_DRAW);
    gl->glNamedBufferData(m.uvs, GLsizeiptr(t.uvs.size() * sizeof(glm::vec2)), t.uvs.data(),
                          GL_DYNAMIC_DRAW);
    gl->glNamedBufferData(m.indices, GLsizeiptr(t.indices.size() * sizeof(unsigned)),
                          t.indices.data(), GL_DYNAMIC_DRAW);
    m.indexCount = int(t.indices.size());
    m.bytes =
        std::int64_t(t.positions.size() * sizeof(glm::vec3) + t.normals.size() * sizeof(glm::vec3) +
                     t.uvs.size() * sizeof(glm::vec2) + t.indices.size() * sizeof(unsigned));
    m.revisions = rev;
    m.nu = nu;
    m.nv = nv;
    up.meshBuilds += 1;
    up.bytes += m.bytes;
}

void GpuScene::syncNet(SurfaceRecord& r, const Revisions& rev, UploadStats& up) {
    NetGpu& n = r.net;
    if (n.vao && n.revisions.points == rev.points && n.revisions.knots == rev.knots)
        return;
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    const NurbsSurface& s = r.surface->geometry;
    if (!n.vao) {
        gl->glCreateVertexArrays(1, &n.vao);
        gl->glCreateBuffers(1, &n.points);
        gl->glCreateBuffers(1, &n.lines);
        gl->glVertexArrayVertexBuffer(n.vao, 0, n.points, 0, sizeof(glm::vec3));
        gl->glEnableVertexArrayAttrib(n.vao, 0);
        gl->glVertexArrayAttribFormat(n.vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
        gl->glVertexArrayAttribBinding(n.vao, 0, 0);
        gl->glVertexArrayElementBuffer(n.vao, n.lines);
    }
    std::vector<glm::vec3> pts(s.points.begin(), s.points.end());
    std::vector<unsigned> idx;
    for (int j = 0; j < s.countV; ++j)
        for (int i = 0; i < s.countU; ++i) {
            if (i + 1 < s.countU)
                idx.insert(idx.end(), {unsigned(s.index(i, j)), unsigned(s.index(i + 1, j))});
            if (j + 1 < s.countV)
                idx.insert(idx.end(), {unsigned(s.index(i, j)), unsigned(s.index(i, j + 1))});
        }
    gl->glNamedBufferData(n.points, GLsizeiptr(pts.size() * sizeof(glm::vec3)), pts.data(),
                          GL_DYNAMIC_DRAW);
    gl->glNamedBufferData(n.lines, GLsizeiptr(idx.size() * sizeof(unsigned)), idx.data(),
                          GL_DYNAMIC_DRAW);
    n.pointCount = int(pts.size());
    n.lineIndexCount = int(idx.size());
    n.bytes = std::int64_t(pts.size() * sizeof(glm::vec3) + idx.size() * sizeof(unsigned));
    n.revisions = rev;
    up.netBuilds += 1;
    up.bytes += n.bytes;
}

void GpuScene::drop(Entry& e) {
    QOpenGLFunctions_4_5_Core* gl = m_gl;
    SurfaceRecord& r = e.record;
    if (r.exact)
        destroySurfaceGpu(gl, *r.exact);
    r.exact.reset();
    MeshGpu& m = r.mesh;
    for (GLuint* b : {&m.positions, &m.normals, &m.uvs, &m.indices})
        if (*b)
            gl->glDeleteBuffers(1, b), *b = 0;
    if (m.vao)
        gl->glDeleteVertexArrays(1, &m.vao), m.vao = 0;
    NetGpu& n = r.net;
    for (GLuint* b : {&n.points, &n.lines})
        if (*b)
            gl->glDeleteBuffers(1, b), *b = 0;
    if (n.vao)
        gl->glDeleteVertexArrays(1, &n.vao), n.vao = 0;
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
    return r && r->mask.active && r->mask.layer >= 0 ? &r->mask : nullptr;
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
    for (const auto& [id, e] : m_entries) {
        if (e.record.exact)
            addResidentBytes(*e.record.exact, out);
        out.tessellatedMeshes += e.record.mesh.bytes;
        out.controlNets += e.record.net.bytes;
    }
    out.trimMasks += m_masks.residentBytes();
}

void GpuScene::release() {
    if (m_gl)
        for (auto& [id, e] : m_entries)
            drop(e);
    m_entries.clear();
    m_order.clear();
    if (m_gl)
        m_masks.release();
    m_document = nullptr;
}

} // namespace kw
