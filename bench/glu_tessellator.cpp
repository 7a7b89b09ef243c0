// gluNurbsSurface in GLU_NURBS_TESSELLATOR mode: callbacks assemble strips and fans into a
// plain triangle list per surface.
#include "bench/glu_tessellator.h"

#include "model/nurbs/nurbs.h"

#include <GL/glu.h>
#include <glm/gtc/type_ptr.hpp>
#include <memory>

namespace kw::bench {

namespace {

/// What the callbacks write into: the surface being built and the primitive in progress.
struct Collector {
    SurfaceMesh* mesh = nullptr;
    GLenum primitive = 0;
    std::vector<unsigned> current; ///< vertex indices of the primitive so far
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
    glm::vec2 uv{0.0f};
    GLenum error = 0;
};

void emitPrimitive(Collector& c) {
    std::vector<unsigned>& idx = c.mesh->indices;
    const std::vector<unsigned>& v = c.current;
    const size_t n = v.size();
    switch (c.primitive) {
    case GL_TRIANGLES:
        for (size_t k = 0; k + 2 < n; k += 3)
            idx.insert(idx.end(), {v[k], v[k + 1], v[k + 2]});
        break;
    case GL_TRIANGLE_STRIP:
        for (size_t k = 0; k + 2 < n; ++k)
            if (k % 2 == 0)
                idx.insert(idx.end(), {v[k], v[k + 1], v[k + 2]});
            else
                idx.insert(idx.end(), {v[k + 1], v[k], v[k + 2]});
        break;
    case GL_TRIANGLE_FAN:
        for (size_t k = 1; k + 1 < n; ++k)
            idx.insert(idx.end(), {v[0], v[k], v[k + 1]});
        break;
    case GL_QUAD_STRIP:
        for (size_t k = 0; k + 3 < n; k += 2)
            idx.insert(idx.end(), {v[k], v[k + 1], v[k + 3], v[k], v[k + 3], v[k + 2]});
        break;
    case GL_QUADS:
        for (size_t k = 0; k + 3 < n; k += 4)
            idx.insert(idx.end(), {v[k], v[k + 1], v[k + 2], v[k], v[k + 2], v[k + 3]});
        break;
    default: // points and lines (outline display modes) carry no area
        break;
    }
}

void GLAPIENTRY onBegin(GLenum type, void* data) {
    auto* c = static_cast<Collector*>(data);
    c->primitive = type;
    c->current.clear();
}

void GLAPIENTRY onNormal(GLfloat* n, void* data) {
    auto* c = static_cast<Collector*>(data);
    const glm::vec3 v(n[0], n[1], n[2]);
    const float len = glm::length(v);
    c->normal = len > 0.0f ? v / len : glm::vec3(0.0f, 0.0f, 1.0f);
}

void GLAPIENTRY onTexCoord(GLfloat* t, void* data) {
    static_cast<Collector*>(data)->uv = glm::vec2(t[0], t[1]);
}

void GLAPIENTRY onVertex(GLfloat* p, void* data) {
    auto* c = static_cast<Collector*>(data);
    SurfaceMesh& m = *c->mesh;
    c->current.push_back(unsigned(m.positions.size()));
    m.positions.emplace_back(p[0], p[1], p[2]);
    m.normals.push_back(c->normal);
    m.uvs.push_back(c->uv);
}

void GLAPIENTRY onEnd(void* data) {
    auto* c = static_cast<Collector*>(data);
    emitPrimitive(*c);
    c->current.clear();
}

/// The error callback has no user-data form; the tessellator runs on one thread at a time.
thread_local GLenum t_gluError = 0;
void GLAPIENTRY onError(GLenum code) {
    t_gluError = code;
}

struct NurbsDeleter {
    void operator()(GLUnurbs* n) const { gluDeleteNurbsRenderer(n); }
};

} // namespace

Status gluTessellate(const Scene& scene, const FrameCamera& camera, double tolerancePixels,
                     SceneMesh& out) {
    out.surfaces.clear();
    if (!(tolerancePixels > 0.0))
        return Error(QStringLiteral("GLU sampling tolerance must be > 0 pixels, got %1")
                         .arg(tolerancePixels));
    std::unique_ptr<GLUnurbs, NurbsDeleter> nurbs(gluNewNurbsRenderer());
    if (!nurbs)
        return Error(QStringLiteral("gluNewNurbsRenderer failed"));
    GLUnurbs* n = nurbs.get();
    gluNurbsProperty(n, GLU_NURBS_MODE, GLU_NURBS_TESSELLATOR);
    gluNurbsProperty(n, GLU_DISPLAY_MODE, GLU_FILL);
    gluNurbsProperty(n, GLU_CULLING, GL_FALSE);
    gluNurbsProperty(n, GLU_SAMPLING_METHOD, GLU_PATH_LENGTH);
    gluNurbsProperty(n, GLU_SAMPLING_TOLERANCE, GLfloat(tolerancePixels));
    gluNurbsProperty(n, GLU_AUTO_LOAD_MATRIX, GL_FALSE);
    const GLint viewport[4] = {0, 0, camera.viewport.x, camera.viewport.y};
    gluLoadSamplingMatrices(n, glm::value_ptr(camera.view), glm::value_ptr(camera.projection),
                            viewport);
    gluNurbsCallback(n, GLU_NURBS_BEGIN_DATA, reinterpret_cast<_GLUfuncptr>(&onBegin));
    gluNurbsCallback(n, GLU_NURBS_NORMAL_DATA, reinterpret_cast<_GLUfuncptr>(&onNormal));
    gluNurbsCallback(n, GLU_NURBS_TEXTURE_COORD_DATA, reinterpret_cast<_GLUfuncptr>(&onTexCoord));
    gluNurbsCallback(n, GLU_NURBS_VERTEX_DATA, reinterpret_cast<_GLUfuncptr>(&onVertex));
    gluNurbsCallback(n, GLU_NURBS_END_DATA, reinterpret_cast<_GLUfuncptr>(&onEnd));
    gluNurbsCallback(n, GLU_NURBS_ERROR, reinterpret_cast<_GLUfuncptr>(&onError));

    Collector collector;
    gluNurbsCallbackData(n, &collector);
    std::vector<GLfloat> knotsU, knotsV, control;
    for (const Surface& s : scene.surfaces) {
        const NurbsSurface& g = s.geometry;
        out.surfaces.push_back(SurfaceMesh{s.id, {}, {}, {}, {}});
        collector.mesh = &out.surfaces.back();
        knotsU.assign(g.knotsU.begin(), g.knotsU.end());
        knotsV.assign(g.knotsV.begin(), g.knotsV.end());
        control.resize(size_t(g.countU) * size_t(g.countV) * 4);
        for (size_t k = 0; k < g.points.size(); ++k) {
            const double w = g.weights[k];
            const glm::dvec3 p = g.points[k] * w; // homogeneous (wP, w)
            control[4 * k + 0] = GLfloat(p.x);
            control[4 * k + 1] = GLfloat(p.y);
            control[4 * k + 2] = GLfloat(p.z);
            control[4 * k + 3] = GLfloat(w);
        }
        // (u, v) as a second, bilinear map over the same domain.
        const Interval du = surfaceDomainU(g), dv = surfaceDomainV(g);
        GLfloat linU[4] = {GLfloat(du.first), GLfloat(du.first), GLfloat(du.last),
                           GLfloat(du.last)};
        GLfloat linV[4] = {GLfloat(dv.first), GLfloat(dv.first), GLfloat(dv.last),
                           GLfloat(dv.last)};
        GLfloat uvNet[8] = {linU[0], linV[0], linU[2], linV[0], linU[0], linV[2], linU[2], linV[2]};
        t_gluError = 0;
        gluBeginSurface(n);
        gluNurbsSurface(n, GLint(knotsU.size()), knotsU.data(), GLint(knotsV.size()), knotsV.data(),
                        4, 4 * g.countU, control.data(), g.degreeU + 1, g.degreeV + 1,
                        GL_MAP2_VERTEX_4);
        gluNurbsSurface(n, 4, linU, 4, linV, 2, 4, uvNet, 2, 2, GL_MAP2_TEXTURE_COORD_2);
        gluEndSurface(n);
        if (t_gluError != 0)
            return Error(QStringLiteral("GLU NURBS error on surface %1: %2")
                             .arg(s.id.value)
                             .arg(QString::fromLatin1(
                                 reinterpret_cast<const char*>(gluErrorString(t_gluError)))));
    }
    return ok();
}

} // namespace kw::bench
