// Helpers shared by the GL render tests: an off-screen renderer per test run, sample loading,
// scenes built in code, and the AOV-vs-kernel comparison.
#pragma once

#include "model/document/document.h"
#include "model/io/knotfile.h"
#include "model/nurbs/nurbs_shapes.h"
#include "render/offscreen_renderer.h"
#include "trim_test_util.h"

#include <QDir>
#include <QString>
#include <QTest>
#include <cmath>
#include <cstring>
#include <memory>
#include <optional>

Q_DECLARE_METATYPE(kw::Scene)

namespace kwtest {

inline QDir outputDir() {
    QDir d(QStringLiteral(KW_TEST_OUTPUT_DIR));
    d.mkpath(QStringLiteral("."));
    return d;
}

/// An off-screen renderer with a current OpenGL 4.5 context and a target of `size` (with the
/// AOV attachments, and the curvature one, when asked), or the error of creating it. The
/// render tests' initTestCase: `auto made = offscreenRenderer(...); QVERIFY2(made, ...)`.
inline kw::Expected<std::unique_ptr<kw::OffscreenRenderer>>
offscreenRenderer(QSize size, bool aov, bool curvature = false) {
    auto r = std::make_unique<kw::OffscreenRenderer>();
    if (kw::Status made = r->create(); !made)
        return std::move(made).error();
    if (kw::Status sized = r->setSize(size, aov, curvature); !sized)
        return std::move(sized).error();
    return kw::Expected<std::unique_ptr<kw::OffscreenRenderer>>(std::move(r));
}

/// One drawn frame as the renderer left it: its report, the colour image and the AOV.
struct DrawnFrame {
    kw::FrameReport report;
    QImage colour;
    kw::AovBuffer aov;
};

/// Renders `doc` from `camera` into `r` and reads the frame back, or the render's error.
inline kw::Expected<DrawnFrame> drawFrame(kw::OffscreenRenderer& r, const kw::Document& doc,
                                          const kw::Camera& camera,
                                          const kw::RenderOptions& options) {
    if (kw::Status drawn = r.render(doc, camera, options); !drawn)
        return drawn.error();
    return DrawnFrame{r.lastReport(), r.colorImage(), r.aov()};
}

/// Pixels whose colour or AOV differ between two frames of the same size.
inline int differingPixels(const DrawnFrame& a, const DrawnFrame& b) {
    int n = 0;
    for (int y = 0; y < a.aov.height; ++y)
        for (int x = 0; x < a.aov.width; ++x)
            n += a.colour.pixel(x, y) != b.colour.pixel(x, y) ||
                 std::memcmp(a.aov.pixel(x, y), b.aov.pixel(x, y),
                             sizeof(float) * size_t(kw::AovBuffer::kChannels)) != 0;
    return n;
}

inline kw::Expected<kw::Scene> loadSample(const QString& name) {
    return kw::readKnotFile(QStringLiteral(KW_SAMPLES_DIR "/") + name + QStringLiteral(".knot"));
}

/// trimmed_plate with star_island beside it, moved by `shift` along x: the star's surface gets
/// id 20 and its loops' ids 20 more; the scene's nextId is 40.
inline kw::Expected<kw::Scene> plateBesideStar(double shift) {
    const auto plate = loadSample(QStringLiteral("trimmed_plate"));
    if (!plate)
        return plate.error();
    const auto star = loadSample(QStringLiteral("star_island"));
    if (!star)
        return star.error();
    kw::Scene scene = *plate;
    kw::Surface second = star->surfaces.front();
    second.id = kw::SurfaceId{20};
    for (kw::TrimLoop& l : second.trims)
        l.id.value += 20;
    for (glm::dvec3& p : second.geometry.points)
        p.x += shift;
    scene.surfaces.push_back(second);
    scene.nextId = 40;
    return scene;
}

inline kw::Surface makeSurface(std::uint32_t id, const kw::NurbsSurface& g, int parts = 10) {
    kw::Surface s;
    s.id = kw::SurfaceId{id};
    s.name = QStringLiteral("surface %1").arg(id);
    s.geometry = g;
    s.partitionsU = parts;
    s.partitionsV = parts;
    return s;
}

/// A wavy rational patch of degrees (p, q) with the given knot vectors (count from the knots).
inline kw::NurbsSurface wavyPatch(int p, int q, std::vector<double> ku, std::vector<double> kv) {
    kw::NurbsSurface s;
    s.degreeU = p;
    s.degreeV = q;
    s.countU = int(ku.size()) - p - 1;
    s.countV = int(kv.size()) - q - 1;
    s.knotsU = std::move(ku);
    s.knotsV = std::move(kv);
    for (int j = 0; j < s.countV; ++j)
        for (int i = 0; i < s.countU; ++i) {
            const double x = 4.0 * i / (s.countU - 1) - 2.0, y = 3.0 * j / (s.countV - 1) - 1.5;
            s.points.emplace_back(x, y, 0.5 * std::sin(1.7 * x + 0.4) * std::cos(1.3 * y));
            s.weights.push_back(1.0 +
                                0.4 * std::sin(0.9 * i + 1.7 * j) * std::sin(0.9 * i + 1.7 * j));
        }
    return s;
}

inline std::vector<double> clampedUniform(int p, int count) {
    std::vector<double> k;
    for (int i = 0; i <= p; ++i)
        k.push_back(0.0);
    const int interior = count - p - 1;
    for (int i = 1; i <= interior; ++i)
        k.push_back(double(i) / (interior + 1));
    for (int i = 0; i <= p; ++i)
        k.push_back(1.0);
    return k;
}

/// Comparison of an AOV render with the kernel at every compared pixel's (u, v).
struct AovComparison {
    int covered = 0;        ///< pixels with a surface id
    int compared = 0;       ///< pixels checked against the kernel
    int unknownIds = 0;     ///< pixels whose id names no surface
    double maxPosition = 0; ///< largest |P_gpu - P_cpu|, model units
    double maxAngleDeg = 0; ///< largest angle between the normals, degrees
    double modelSize = 0;   ///< diagonal of the scene's control bounds
    int worstX = -1, worstY = -1;
};

/// Compares every `stride`-th covered pixel. Pixels within `creaseBand` (parameter units) of a
/// C0 crease (interior knot of multiplicity >= degree), where the normal has two values, are
/// counted as covered but not compared.
inline AovComparison compareAovWithKernel(const kw::Scene& scene, const kw::AovBuffer& aov,
                                          int stride = 1, double creaseBand = 1e-5) {
    AovComparison r;
    glm::dvec3 lo, hi;
    kw::sceneBounds(scene, lo, hi);
    r.modelSize = glm::length(hi - lo);
    int seen = 0;
    for (int y = 0; y < aov.height; ++y)
        for (int x = 0; x < aov.width; ++x) {
            const float* px = aov.pixel(x, y);
            if (px[0] < 0.0f)
                continue;
            ++r.covered;
            if (seen++ % stride != 0)
                continue;
            const kw::Surface* surf = nullptr;
            for (const kw::Surface& s : scene.surfaces)
                if (double(s.id.value) == double(px[0]))
                    surf = &s;
            if (!surf) {
                ++r.unknownIds;
                continue;
            }
            const kw::NurbsSurface& g = surf->geometry;
            const double u = px[1], v = px[2];
            bool onCrease = false;
            auto crease = [&](const std::vector<double>& k, int p, double t) {
                for (size_t a = 0; a < k.size(); ++a) {
                    const size_t m = size_t(std::count(k.begin(), k.end(), k[a]));
                    if (m >= size_t(p) && k[a] > k.front() && k[a] < k.back() &&
                        std::abs(t - k[a]) < creaseBand)
                        return true;
                }
                return false;
            };
            onCrease = crease(g.knotsU, g.degreeU, u) || crease(g.knotsV, g.degreeV, v);
            if (onCrease)
                continue;
            const kw::SurfaceFrame f = kw::surfaceFrame(g, u, v);
            const glm::dvec3 p(px[3], px[4], px[5]), n(px[6], px[7], px[8]);
            const double dp = glm::length(p - f.point);
            const double c = glm::clamp(glm::dot(glm::normalize(n), f.normal), -1.0, 1.0);
            const double angle = glm::degrees(std::acos(c));
            ++r.compared;
            if (dp > r.maxPosition)
                r.maxPosition = dp;
            if (angle > r.maxAngleDeg || std::isnan(angle)) {
                r.maxAngleDeg = std::isnan(angle) ? 180.0 : angle;
                r.worstX = x;
                r.worstY = y;
            }
        }
    return r;
}

/// Window position in pixels (OpenGL conventions: y up, pixel centres at + 0.5) of the model
/// point `p` under `viewProjection` in a viewport of `size` pixels.
inline glm::dvec2 windowPixels(const glm::dmat4& viewProjection, const glm::dvec3& p,
                               glm::dvec2 size) {
    const glm::dvec4 c = viewProjection * glm::dvec4(p, 1.0);
    return (glm::dvec2(c) / c.w * 0.5 + 0.5) * size;
}

/// How far in pixels the point a covered AOV pixel (x, y) shows (its position channels)
/// projects from the pixel's centre under `viewProjection`: 0 for the point truly under it.
/// (AOV rows run top-down, window y up.)
inline double rayOffsetPixels(const kw::AovBuffer& aov, int x, int y,
                              const glm::dmat4& viewProjection) {
    const float* a = aov.pixel(x, y);
    const glm::dvec2 at = windowPixels(viewProjection, glm::dvec3(a[3], a[4], a[5]),
                                       glm::dvec2(aov.width, aov.height));
    return glm::length(at - glm::dvec2(x + 0.5, aov.height - y - 0.5));
}

/// The camera of `fit` moved towards the surface point at (u, v) of `s`, `zoom` times closer.
inline kw::Camera zoomedOn(const kw::Camera& fit, const kw::Surface& s, glm::dvec2 uv,
                           double zoom) {
    kw::Camera c = fit;
    c.target = kw::surfacePoint(s.geometry, uv.x, uv.y);
    const glm::dvec3 away = fit.eye - fit.target;
    c.eye = c.target + away / zoom;
    c.authored = true;
    return c;
}

/// A closed 24-gon loop inside (u, v) in [0.1, 0.9] x [0.15, 0.85] (an ellipse of radii 0.4 and
/// 0.35 about the middle), its first corner turned by `turn` radians.
inline kw::TrimLoop discLoop(std::uint32_t id, double turn) {
    std::vector<glm::dvec2> disc;
    for (int i = 0; i <= 24; ++i) {
        const double a = 2.0 * M_PI * (i % 24) / 24.0 + turn;
        disc.emplace_back(0.5 + 0.4 * std::cos(a), 0.5 + 0.35 * std::sin(a));
    }
    return loopOf(id, {polylineCurve(disc)});
}

/// `n` wavy patches in rows of 20, of two shader variants (bicubic and biquadratic) in a
/// checkerboard; with `trimEveryOther`, every other one is trimmed by a disc. Ids count up from
/// 1 over the surfaces and their loops in order.
inline kw::Scene variantGrid(int n, bool trimEveryOther = false) {
    kw::Scene scene;
    const int columns = 20;
    std::uint32_t next = 1;
    for (int k = 0; k < n; ++k) {
        const bool cubic = (k + k / columns) % 2 == 0;
        kw::NurbsSurface g = cubic ? wavyPatch(3, 3, clampedUniform(3, 5), clampedUniform(3, 6))
                                   : wavyPatch(2, 2, clampedUniform(2, 4), clampedUniform(2, 5));
        for (glm::dvec3& p : g.points)
            p += glm::dvec3(5.0 * (k % columns), 4.0 * (k / columns), 0.0);
        kw::Surface s = makeSurface(next++, g, 6);
        if (trimEveryOther && k % 2 == 1)
            s.trims.push_back(discLoop(next++, 0.1 * k));
        scene.surfaces.push_back(s);
    }
    scene.nextId = next;
    return scene;
}

} // namespace kwtest
