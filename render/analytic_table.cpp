// The analytic forms' rows on the GPU: validation, packing and the diffed upload.
#include "render/analytic_table.h"

#include "render/gpu_scene.h"

#include <algorithm>
#include <cmath>

namespace kw {

namespace {
bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool mapUsable(const AnalyticParamMap& m) {
    return std::isfinite(m.offset) && std::isfinite(m.scale) && m.scale != 0.0;
}
} // namespace

bool analyticUsable(const AnalyticForm& f) {
    using Kind = AnalyticForm::Kind;
    if (f.kind == Kind::None || !finite(f.origin) || !finite(f.xAxis) || !finite(f.yAxis) ||
        !finite(f.zAxis) || !mapUsable(f.u) || !mapUsable(f.v))
        return false;
    // The shader works in the frame's coordinates by dot products: the axes must be a frame.
    const double tol = 1e-9;
    for (const glm::dvec3& a : {f.xAxis, f.yAxis, f.zAxis})
        if (std::abs(glm::length(a) - 1.0) > tol)
            return false;
    if (std::abs(glm::dot(f.xAxis, f.yAxis)) > tol || std::abs(glm::dot(f.yAxis, f.zAxis)) > tol ||
        std::abs(glm::dot(f.zAxis, f.xAxis)) > tol)
        return false;
    switch (f.kind) {
    case Kind::Plane:
        return true;
    case Kind::Cylinder:
    case Kind::Sphere:
        return std::isfinite(f.radius) && f.radius > 0.0;
    case Kind::Cone:
        // A cone of radius 0 at its origin is its apex there: allowed.
        return std::isfinite(f.radius) && f.radius >= 0.0 && std::isfinite(f.semiAngle) &&
               std::abs(f.semiAngle) < 0.5 * 3.14159265358979323846;
    case Kind::Torus:
        return std::isfinite(f.radius) && std::isfinite(f.minorRadius) && f.radius > 0.0 &&
               f.minorRadius > 0.0;
    case Kind::None:
        break;
    }
    return false;
}

AnalyticEntry packAnalytic(const AnalyticForm& f, const glm::dvec3& controlOrigin) {
    AnalyticEntry e;
    const auto map = [](const AnalyticParamMap& m, float w) {
        return glm::vec4(m.kind == AnalyticParamMap::Kind::HalfAngle ? 1.0f : 0.0f, float(m.offset),
                         float(m.scale), w);
    };
    e.origin = glm::vec4(glm::vec3(f.origin - controlOrigin), float(int(f.kind)));
    e.xAxis = glm::vec4(glm::vec3(f.xAxis), float(f.radius));
    e.yAxis = glm::vec4(glm::vec3(f.yAxis), float(f.minorRadius));
    e.zAxis = glm::vec4(glm::vec3(f.zAxis), float(std::sin(f.semiAngle)));
    e.mapU = map(f.u, f.swapped ? 1.0f : 0.0f);
    e.mapV = map(f.v, float(std::cos(f.semiAngle)));
    return e;
}

void AnalyticTable::sync(QOpenGLFunctions_4_5_Core* gl, const std::vector<SurfaceRecord*>& records,
                         int slots) {
    if (int(m_rows.size()) < slots)
        m_rows.resize(size_t(slots));
    int lo = int(m_rows.size()), hi = -1;
    bool any = m_buffer != 0;
    for (const SurfaceRecord* r : records) {
        if (!r->exact || r->slot < 0 || r->slot >= int(m_rows.size()))
            continue;
        AnalyticEntry e;
        if (r->surface && analyticUsable(r->surface->analytic)) {
            e = packAnalytic(r->surface->analytic, r->exact->origin);
            any = true;
        }
        AnalyticEntry& row = m_rows[size_t(r->slot)];
        if (!(row == e)) {
            row = e;
            lo = std::min(lo, r->slot), hi = std::max(hi, r->slot);
        }
    }
    if (!any)
        return; // no form seen yet: no buffer, no bytes
    if (int(m_rows.size()) > m_capacity) {
        // Grown: a new buffer, every row written (the view points at it again).
        m_capacity = std::max(64, m_capacity);
        while (m_capacity < int(m_rows.size()))
            m_capacity *= 2;
        if (m_buffer)
            gl->glDeleteBuffers(1, &m_buffer);
        gl->glCreateBuffers(1, &m_buffer);
        gl->glNamedBufferData(m_buffer, GLsizeiptr(m_capacity) * GLsizeiptr(sizeof(AnalyticEntry)),
                              nullptr, GL_DYNAMIC_DRAW);
        if (!m_view)
            gl->glCreateTextures(GL_TEXTURE_BUFFER, 1, &m_view);
        gl->glTextureBuffer(m_view, GL_RGBA32F, m_buffer);
        lo = 0, hi = int(m_rows.size()) - 1;
    }
    if (hi >= lo)
        gl->glNamedBufferSubData(m_buffer, GLintptr(lo) * GLintptr(sizeof(AnalyticEntry)),
                                 GLsizeiptr(hi - lo + 1) * GLsizeiptr(sizeof(AnalyticEntry)),
                                 &m_rows[size_t(lo)]);
}

void AnalyticTable::bind(QOpenGLFunctions_4_5_Core* gl) const {
    if (m_view)
        gl->glBindTextureUnit(GLuint(kAnalyticUnit), m_view);
}

void AnalyticTable::release(QOpenGLFunctions_4_5_Core* gl) {
    if (m_view)
        gl->glDeleteTextures(1, &m_view);
    if (m_buffer)
        gl->glDeleteBuffers(1, &m_buffer);
    m_view = m_buffer = 0;
    m_capacity = 0;
    m_rows.clear();
}

} // namespace kw
