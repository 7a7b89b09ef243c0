// CPU reference frame: a bound-driven fine tessellation rasterised with depth test and trim
// classification finds each pixel's surface, then Newton's method puts it on the exact ray hit.
#include "render/reference_render.h"

#include "model/nurbs/trim.h"
#include "render/render_types.h"
#include "render/surface_bound.h"

#include <QElapsedTimer>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <thread>

namespace kw {
namespace {

/// What the rasteriser keeps per pixel: the nearest trimmed-in fragment.
struct Fragment {
    double depth = std::numeric_limits<double>::infinity(); ///< eye depth
    int surface = -1;                                       ///< index into Scene::surfaces
    double u = 0.0, v = 0.0;
    double cellU = 0.0, cellV = 0.0; ///< cell size there, to bound Newton's travel
};

struct Vertex {
    double x = 0.0, y = 0.0; ///< pixels, y down (row 0 at the top, as AovBuffer)
    double z = 0.0;          ///< eye depth
    double u = 0.0, v = 0.0;
    glm::dvec3 p{0.0}; ///< world position, for clipping at the near plane
};

struct Raster {
    int width = 0, height = 0;
    std::vector<Fragment> frags;
    ReferenceStats* stats = nullptr;
};

/// Rasterises one triangle, wholly in front of the near plane, at pixel centres with
/// perspective-correct (u, v) and eye depth. Centres on an edge belong to both triangles
/// (harmless: neighbours share the surface).
void rasteriseInFront(Raster& r, const Vertex& a, const Vertex& b, const Vertex& c, int surface,
                      const TrimRegion& trims, double cellU, double cellV) {
    const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if (!(std::abs(area) > 1e-12))
        return;
    ++r.stats->triangles;
    const int x0 = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}) - 0.5)));
    const int x1 = std::min(r.width - 1, int(std::ceil(std::max({a.x, b.x, c.x}) - 0.5)));
    const int y0 = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}) - 0.5)));
    const int y1 = std::min(r.height - 1, int(std::ceil(std::max({a.y, b.y, c.y}) - 0.5)));
    const double inv = 1.0 / area;
    for (int py = y0; py <= y1; ++py) {
        const double cy = py + 0.5;
        for (int px = x0; px <= x1; ++px) {
            const double cx = px + 0.5;
            const double l0 = ((b.x - cx) * (c.y - cy) - (b.y - cy) * (c.x - cx)) * inv;
            const double l1 = ((c.x - cx) * (a.y - cy) - (c.y - cy) * (a.x - cx)) * inv;
            const double l2 = 1.0 - l0 - l1;
            if (l0 < 0.0 || l1 < 0.0 || l2 < 0.0)
                continue;
            ++r.stats->fragments;
            const double q0 = l0 / a.z, q1 = l1 / b.z, q2 = l2 / c.z;
            const double z = 1.0 / (q0 + q1 + q2);
            Fragment& f = r.frags[size_t(py) * size_t(r.width) + size_t(px)];
            if (!(z < f.depth))
                continue;
            const double u = (q0 * a.u + q1 * b.u + q2 * c.u) * z;
            const double v = (q0 * a.v + q1 * b.v + q2 * c.v) * z;
            if (!trims.empty() && !trimRegionContains(trims, {u, v}))
                continue;
            f = {z, surface, u, v, cellU, cellV};
        }
    }
}

struct View {
    glm::dmat4 viewProjection{1.0};
    glm::dmat4 inverse{1.0};
    glm::dvec3 eye{0.0}, forward{0.0, 0.0, -1.0};
    double nearDepth = 0.01;
    int width = 1, height = 1;

    Vertex project(const glm::dvec3& p, double u, double v) const {
        const glm::dvec4 c = viewProjection * glm::dvec4(p, 1.0);
        Vertex out;
        out.p = p;
        out.z = glm::dot(p - eye, forward);
        const double w = c.w != 0.0 ? c.w : 1e-300;
        out.x = (c.x / w * 0.5 + 0.5) * width;
        out.y = (0.5 - c.y / w * 0.5) * height;
        out.u = u;
        out.v = v;
        return out;
    }
    /// Unit direction of the ray through the centre of pixel (px, py).
    glm::dvec3 ray(int px, int py) const {
        const double nx = 2.0 * (px + 0.5) / width - 1.0;
        const double ny = 1.0 - 2.0 * (py + 0.5) / height;
        const glm::dvec4 q = inverse * glm::dvec4(nx, ny, 0.0, 1.0);
        return glm::normalize(glm::dvec3(q) / q.w - eye);
    }
    /// True when the box [lo, hi] lies wholly outside one side of the frustum (by its corners'
    /// clip coordinates), so nothing in it can be drawn.
    bool culled(const glm::dvec3& lo, const glm::dvec3& hi) const {
        int outside[5] = {0, 0, 0, 0, 0};
        for (int k = 0; k < 8; ++k) {
            const glm::dvec3 p((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
            const glm::dvec4 c = viewProjection * glm::dvec4(p, 1.0);
            outside[0] += c.x < -c.w;
            outside[1] += c.x > c.w;
            outside[2] += c.y < -c.w;
            outside[3] += c.y > c.w;
            outside[4] += glm::dot(p - eye, forward) < nearDepth;
        }
        return std::any_of(outside, outside + 5, [](int n) { return n == 8; });
    }
};

/// Rasterises one triangle clipped to the near plane, as the GPU clips its base polygon:
/// a close-up's large faces reach behind the eye and must still cover the pixels they cover.
/// (u, v) are affine on the planar triangle, so they are clipped with the world position.
void rasterise(Raster& r, const View& view, const Vertex& a, const Vertex& b, const Vertex& c,
               int surface, const TrimRegion& trims, double cellU, double cellV) {
    const double nearDepth = view.nearDepth;
    if (a.z > nearDepth && b.z > nearDepth && c.z > nearDepth) {
        rasteriseInFront(r, a, b, c, surface, trims, cellU, cellV);
        return;
    }
    // Sutherland-Hodgman against the one plane z = nearDepth: at most 4 vertices.
    const Vertex* in[3] = {&a, &b, &c};
    Vertex out[4];
    int n = 0;
    for (int k = 0; k < 3; ++k) {
        const Vertex& s = *in[k];
        const Vertex& e = *in[(k + 1) % 3];
        const bool sIn = s.z > nearDepth, eIn = e.z > nearDepth;
        if (sIn)
            out[n++] = s;
        if (sIn != eIn) {
            const double t = (nearDepth - s.z) / (e.z - s.z);
            out[n++] =
                view.project(glm::mix(s.p, e.p, t), s.u + (e.u - s.u) * t, s.v + (e.v - s.v) * t);
        }
    }
    if (n >= 3)
        rasteriseInFront(r, out[0], out[1], out[2], surface, trims, cellU, cellV);
    if (n == 4)
        rasteriseInFront(r, out[0], out[2], out[3], surface, trims, cellU, cellV);
}

/// Tessellates one surface span by span, each as finely as its bound requires, and rasterises.
void rasteriseSurface(Raster& r, const View& view, const ScreenScale& scale, const Surface& surf,
                      int index, const ReferenceOptions& options) {
    const NurbsSurface& g = surf.geometry;
    TrimRegion trims;
    if (options.trims && !surf.trims.empty())
        trims = makeTrimRegion(surf.trims, trimTolerance(g));
    for (const SpanBound& span : surfaceSpanBounds(g, 4)) {
        glm::dvec3 lo = span.subs[0].lo, hi = span.subs[0].hi;
        for (const SpanBound::Sub& sub : span.subs) {
            lo = glm::min(lo, sub.lo);
            hi = glm::max(hi, sub.hi);
        }
        if (view.culled(lo, hi))
            continue;
        const PartitionChoice c = choosePartitions({span}, {span.u0, span.u1}, {span.v0, span.v1},
                                                   scale, options.pixelTolerance, 1, 1);
        if (!c.met)
            ++r.stats->unmetSpans;
        const int nu = std::min(c.nu, options.maxCellsPerSpan);
        const int nv = std::min(c.nv, options.maxCellsPerSpan);
        const double du = (span.u1 - span.u0) / nu, dv = (span.v1 - span.v0) / nv;
        std::vector<Vertex> grid(size_t((nu + 1) * (nv + 1)));
        for (int j = 0; j <= nv; ++j)
            for (int i = 0; i <= nu; ++i) {
                const double u = i == nu ? span.u1 : span.u0 + du * i;
                const double v = j == nv ? span.v1 : span.v0 + dv * j;
                grid[size_t(j * (nu + 1) + i)] = view.project(surfacePoint(g, u, v), u, v);
            }
        for (int j = 0; j < nv; ++j)
            for (int i = 0; i < nu; ++i) {
                const Vertex& ll = grid[size_t(j * (nu + 1) + i)];
                const Vertex& lr = grid[size_t(j * (nu + 1) + i + 1)];
                const Vertex& ul = grid[size_t((j + 1) * (nu + 1) + i)];
                const Vertex& ur = grid[size_t((j + 1) * (nu + 1) + i + 1)];
                rasterise(r, view, ll, lr, ur, index, trims, du, dv);
                rasterise(r, view, ll, ur, ul, index, trims, du, dv);
            }
    }
}

/// Newton's method for the ray hit near (u, v): F = (a.(S - E), b.(S - E)) with a, b
/// orthonormal to the ray direction d. Converged when |F| <= eps and the parameters moved at
/// most two cells (so it stays on the sheet the rasteriser found).
bool refine(const NurbsSurface& g, const glm::dvec3& eye, const glm::dvec3& d, double eps,
            const Fragment& f, double& u, double& v) {
    const glm::dvec3 helper = std::abs(d.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 a = glm::normalize(glm::cross(d, helper));
    const glm::dvec3 b = glm::cross(d, a);
    const Interval du = surfaceDomainU(g), dv = surfaceDomainV(g);
    u = f.u;
    v = f.v;
    auto residual = [&](double uu, double vv) {
        const glm::dvec3 r = surfacePoint(g, uu, vv) - eye;
        return std::hypot(glm::dot(a, r), glm::dot(b, r));
    };
    for (int it = 0; it < 24; ++it) {
        const SurfaceDerivatives s = surfaceDerivatives(g, u, v);
        const glm::dvec3 r = s.s - eye;
        const double f0 = glm::dot(a, r), f1 = glm::dot(b, r);
        const double norm = std::hypot(f0, f1);
        if (norm <= eps)
            return std::abs(u - f.u) <= 2.0 * f.cellU && std::abs(v - f.v) <= 2.0 * f.cellV &&
                   glm::dot(r, d) > 0.0;
        const double j00 = glm::dot(a, s.su), j01 = glm::dot(a, s.sv);
        const double j10 = glm::dot(b, s.su), j11 = glm::dot(b, s.sv);
        const double det = j00 * j11 - j01 * j10;
        if (!(std::abs(det) > 1e-300))
            return false;
        const double stepU = -(j11 * f0 - j01 * f1) / det;
        const double stepV = -(-j10 * f0 + j00 * f1) / det;
        // Halve the step until the residual falls (near a silhouette the full step overshoots).
        double t = 1.0;
        double nu = u, nv = v;
        for (int k = 0; k < 20; ++k, t *= 0.5) {
            nu = std::clamp(u + t * stepU, du.first, du.last);
            nv = std::clamp(v + t * stepV, dv.first, dv.last);
            if (residual(nu, nv) < norm)
                break;
        }
        if (nu == u && nv == v)
            return false;
        u = nu;
        v = nv;
    }
    return false;
}

} // namespace

AovBuffer renderReference(const Scene& scene, const Camera& camera, int width, int height,
                          const ReferenceOptions& options, ReferenceStats* stats) {
    QElapsedTimer timer;
    timer.start();
    ReferenceStats local;
    ReferenceStats& st = stats ? *stats : local;
    st = ReferenceStats{};
    width = std::max(width, 1);
    height = std::max(height, 1);
    const CameraMatrices m = cameraMatrices(camera, scene, double(width) / double(height));
    View view;
    view.viewProjection = m.projection * m.view;
    view.inverse = glm::inverse(view.viewProjection);
    view.eye = m.eye;
    view.forward = m.forward;
    view.nearDepth = m.nearPlane;
    view.width = width;
    view.height = height;
    ScreenScale scale = screenScale(camera, width, height, m.nearPlane);
    scale.eye = m.eye;
    scale.forward = m.forward;

    Raster raster;
    raster.width = width;
    raster.height = height;
    raster.frags.resize(size_t(width) * size_t(height));
    raster.stats = &st;
    for (size_t k = 0; k < scene.surfaces.size(); ++k) {
        const Surface& s = scene.surfaces[k];
        if (s.hidden || !checkNurbsSurface(s.geometry)) // as the GPU frame
            continue;
        rasteriseSurface(raster, view, scale, s, int(k), options);
    }

    glm::dvec3 lo(-1.0), hi(1.0);
    sceneBounds(scene, lo, hi);
    const double eps = 1e-10 * std::max(glm::length(hi - lo), 1e-300);
    AovBuffer out;
    out.width = width;
    out.height = height;
    out.data.assign(size_t(width) * size_t(height) * AovBuffer::kChannels, 0.0f);
    std::vector<long long> failures(2, 0);
    auto work = [&](int part, int parts) {
        for (int py = part; py < height; py += parts)
            for (int px = 0; px < width; ++px) {
                const Fragment& f = raster.frags[size_t(py) * size_t(width) + size_t(px)];
                float* o = out.data.data() +
                           (size_t(py) * size_t(width) + size_t(px)) * AovBuffer::kChannels;
                if (f.surface < 0) {
                    o[0] = -1.0f;
                    continue;
                }
                const Surface& s = scene.surfaces[size_t(f.surface)];
                double u = f.u, v = f.v;
                if (!refine(s.geometry, view.eye, view.ray(px, py), eps, f, u, v)) {
                    ++failures[size_t(part)];
                    u = f.u;
                    v = f.v;
                }
                const SurfaceFrame fr = surfaceFrame(s.geometry, u, v);
                const float values[AovBuffer::kChannels] = {
                    float(s.id.value),  float(u),
                    float(v),           float(fr.point.x),
                    float(fr.point.y),  float(fr.point.z),
                    float(fr.normal.x), float(fr.normal.y),
                    float(fr.normal.z), float(glm::dot(fr.point - view.eye, view.forward))};
                std::copy(values, values + AovBuffer::kChannels, o);
            }
    };
    std::thread helper(work, 1, 2);
    work(0, 2);
    helper.join();
    st.newtonFailures = failures[0] + failures[1];
    for (const Fragment& f : raster.frags)
        st.pixels += f.surface >= 0;
    st.milliseconds = double(timer.nsecsElapsed()) * 1e-6;
    return out;
}

QImage shadeReference(const Scene& scene, const Camera& camera, const AovBuffer& aov,
                      const ReferenceOptions& options) {
    QImage img(std::max(aov.width, 1), std::max(aov.height, 1), QImage::Format_RGBA8888);
    const std::vector<Light> lights = lightsFor(scene, camera, options.lightCount);
    glm::dvec3 ambient(0.0);
    for (const Light& l : lights)
        ambient += l.ambient;
    auto toByte = [](double x) {
        return int(std::lround(std::clamp(x, 0.0, 1.0) * 255.0));
    };
    const glm::vec4 bg = options.background;
    std::map<std::uint32_t, const Surface*> byId;
    for (const Surface& s : scene.surfaces)
        byId[s.id.value] = &s;
    for (int y = 0; y < aov.height; ++y)
        for (int x = 0; x < aov.width; ++x) {
            const float* p = aov.pixel(x, y);
            const auto it = p[0] >= 0.0f ? byId.find(std::uint32_t(std::lround(p[0]))) : byId.end();
            const Surface* surf = it != byId.end() ? it->second : nullptr;
            if (!surf) {
                img.setPixel(x, y, qRgba(toByte(bg.r), toByte(bg.g), toByte(bg.b), 255));
                continue;
            }
            // shaders/phong.glsl, in double precision.
            const glm::dvec3 point(p[3], p[4], p[5]);
            const glm::dvec3 vdir = glm::normalize(camera.eye - point);
            glm::dvec3 n(p[6], p[7], p[8]);
            double nv = glm::dot(n, vdir);
            if (nv < 0.0)
                n = -n;
            nv = std::abs(nv);
            const Material& mat = surf->material;
            glm::dvec3 diffuse(0.0), specular(0.0);
            for (const Light& l : lights) {
                const glm::dvec3 ldir = l.kind == Light::Kind::Directional
                                            ? glm::normalize(l.vector)
                                            : glm::normalize(l.vector - point);
                const double ln = glm::dot(ldir, n);
                const double rv = std::max(2.0 * ln * nv - glm::dot(ldir, vdir), 0.0);
                diffuse += std::max(ln, 0.0) * l.diffuse;
                if (ln > 0.0)
                    specular += std::pow(rv, std::max(mat.shininess, 1e-3)) * l.specular;
            }
            diffuse += glm::dvec3(kViewerFill.base + kViewerFill.facing * nv);
            const glm::dvec3 c =
                (mat.ka * ambient + mat.kd * diffuse) * mat.color + mat.ks * specular;
            img.setPixel(x, y, qRgba(toByte(c.r), toByte(c.g), toByte(c.b), 255));
        }
    return img;
}

} // namespace kw
