// GL test: a closed solid shows no background between its faces while the
// view moves and while a control point is dragged, drawn as the editor draws those frames, and
// each frame is measured against the CPU reference of the same pose and scene
// (render/reference_render.h, render/edge_metrics.h).
//
// How the editor draws them (ui/view_surface.cpp): one kw::Renderer for the widget's life,
// synced incrementally frame to frame (docs/RENDERING.md, "What a frame looks at"); adaptive
// partitions re-chosen per view and per changed surface; on a software rasteriser a frame drawn
// while the view moves or points are dragged is aliased (Viewport::aliasedWhileMoving) into
// QOpenGLWidget's default framebuffer, whose depth is 24-bit integer. So here: one renderer kept
// across every frame of a sequence, the editor's options (adaptive, 0.5 px, headlight, exact
// trims, 1 sample), frames with AOVs into a float-depth framebuffer measured against the
// reference, and the editor's colour-only frame into an RGBA8 + DEPTH24_STENCIL8 framebuffer
// like the widget's, which must equal the float-depth host's frame pixel for pixel: the renderer
// draws aliased frames for such hosts through its own float-depth target
// (render/float_depth_target.h). Before that, this test measured the 24-bit frames showing the
// wrong one of two touching faces in close-ups (up to 2,460 pixels of a frame on
// Axis_of_bearing; docs/PERFORMANCE.md ## Edges). The camera moves through
// CameraController::orbit and the wheel's zoom towards the cursor (Viewport::wheelEvent's
// arithmetic); the drag goes through Document::setControlPoints with the editor's view-plane
// delta (ui/tools/pointdragtool.cpp) and ends with the MoveControlPoints command its LiveEdit
// pushes on release, then undo and redo.
//
// What is held:
// - no crack the reference covers. Where a face's trim loop runs along its polygon's edge (the
//   domain's edge on these solids), that edge is a chord within 0.5 px of the exact one, and a
//   pixel centre between the two was drawn by no polygon: 1 pinhole in each orbit and 4 in
//   Pump_Nut's drag before the edge skirts (RenderOptions::edgeSkirts, docs/RENDERING.md
//   "Skirts") filled them; Axis_of_bearing's needed their quarter pixel of reach past the
//   domain (its faces miss each other by 0.1-0.15 px there). The drag runs a control without
//   skirts that must still show Pump_Nut's. The same chord at a periodic face's own seam, and a
//   skirt's edge point where the reference has the point just past the edge, give depth
//   disagreements, allowed only at a polygon boundary;
// - silhouettes within 1 px in frames without such a pinhole (which also scores as a covered
//   pixel far from any silhouette);
// - no pixel showing another face than the reference's beyond twice the depth tolerance
//   (touching faces are decided by the polygon's depth, within 0.5 px).
// Checked by hand that it fails: the drag drawn with the paper's uniform partitions fails on
// Pump_Nut (28 cracks away from a polygon boundary, 42 the reference covers) and on
// Axis_of_bearing (depth disagreements); with the partial vertex update after a moved point
// skipped (uploadChangedPoints: a stale base polygon) both drags fail (16,034 and 880 pixels of
// another face beyond the depth tolerance, 20,494 and 1,976 depth disagreements); without the
// float-depth target the editor's frames differ. The orbit asserts its own control: the same
// poses in uniform mode show > 1000 disagreements.
#include "expected_test_util.h"
#include "cad_test_util.h"
#include "model/nurbs/visible_bounds.h"
#include "render/edge_metrics.h"
#include "render/reference_render.h"
#include "render_test_util.h"
#include "ui/cameracontroller.h"
#include "ui/edit/commands.h"

#include <QOpenGLContext>
#include <QOpenGLFunctions_4_5_Core>
#include <QOpenGLVersionFunctionsFactory>
#include <QUndoStack>
#include <algorithm>
#include <cmath>
#include <map>

using namespace kw;

namespace {

constexpr int kSide = 256;

/// A framebuffer like QOpenGLWidget's default one (RGBA8 colour, GL_DEPTH24_STENCIL8) or, with
/// GL_DEPTH32F_STENCIL8, like Knotwork's own targets, with or without the three AOV attachments
/// of OffscreenRenderer (id, u, v, Z / P / N). Needs the renderer's context current.
class EditorTarget {
public:
    bool create(QSize size, GLenum depthFormat, bool withAov, QString* error) {
        gl = QOpenGLVersionFunctionsFactory::get<QOpenGLFunctions_4_5_Core>(
            QOpenGLContext::currentContext());
        if (!gl) {
            *error = QStringLiteral("no OpenGL 4.5 functions");
            return false;
        }
        m_size = size;
        m_withAov = withAov;
        auto texture = [&](GLenum format) {
            GLuint t = 0;
            gl->glCreateTextures(GL_TEXTURE_2D, 1, &t);
            gl->glTextureStorage2D(t, 1, format, size.width(), size.height());
            return t;
        };
        gl->glCreateFramebuffers(1, &m_fbo);
        m_tex[0] = texture(GL_RGBA8);
        m_tex[1] = texture(depthFormat);
        gl->glNamedFramebufferTexture(m_fbo, GL_COLOR_ATTACHMENT0, m_tex[0], 0);
        gl->glNamedFramebufferTexture(m_fbo, GL_DEPTH_STENCIL_ATTACHMENT, m_tex[1], 0);
        for (int k = 0; k < (withAov ? 3 : 0); ++k) {
            m_tex[2 + k] = texture(GL_RGBA32F);
            gl->glNamedFramebufferTexture(m_fbo, GL_COLOR_ATTACHMENT1 + GLenum(k), m_tex[2 + k], 0);
        }
        const GLenum buffers[4] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                                   GL_COLOR_ATTACHMENT3};
        gl->glNamedFramebufferDrawBuffers(m_fbo, withAov ? 4 : 1, buffers);
        if (gl->glCheckNamedFramebufferStatus(m_fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            *error = QStringLiteral("the editor-like framebuffer is incomplete");
            return false;
        }
        return true;
    }
    void destroy() {
        if (!gl)
            return;
        gl->glDeleteFramebuffers(1, &m_fbo);
        gl->glDeleteTextures(5, m_tex);
        gl = nullptr;
    }
    RenderTarget target() const { return {m_fbo, m_size, m_withAov, false, std::nullopt}; }

    /// The colour, top row first.
    QImage colour() const {
        QImage img(m_size, QImage::Format_RGBA8888);
        gl->glPixelStorei(GL_PACK_ALIGNMENT, 4);
        gl->glGetTextureImage(m_tex[0], 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(img.sizeInBytes()),
                              img.bits());
        return img.mirrored(false, true);
    }

    /// The AOVs, top row first (OffscreenRenderer::aov's layout).
    AovBuffer aov() const {
        AovBuffer out;
        const int w = m_size.width(), h = m_size.height();
        out.width = w;
        out.height = h;
        out.data.resize(size_t(w) * size_t(h) * AovBuffer::kChannels);
        std::vector<float> planes[3];
        for (int k = 0; k < 3; ++k) {
            planes[k].resize(size_t(w) * size_t(h) * 4);
            gl->glGetTextureImage(m_tex[2 + k], 0, GL_RGBA, GL_FLOAT,
                                  GLsizei(planes[k].size() * sizeof(float)), planes[k].data());
        }
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const size_t src = (size_t(h - 1 - y) * size_t(w) + size_t(x)) * 4;
                const float* a = &planes[0][src];
                const float* p = &planes[1][src];
                const float* n = &planes[2][src];
                const float values[AovBuffer::kChannels] = {a[0], a[1], a[2], p[0], p[1],
                                                            p[2], n[0], n[1], n[2], a[3]};
                std::copy(values, values + AovBuffer::kChannels,
                          out.data.data() +
                              (size_t(y) * size_t(w) + size_t(x)) * AovBuffer::kChannels);
            }
        return out;
    }

private:
    QOpenGLFunctions_4_5_Core* gl = nullptr;
    QSize m_size;
    bool m_withAov = true;
    GLuint m_fbo = 0;
    GLuint m_tex[5] = {0, 0, 0, 0, 0};
};

/// The options of the editor's frames while the view moves or a point is dragged on llvmpipe:
/// Preferences' defaults (adaptive at 0.5 px, headlight, exact trims) and one sample.
RenderOptions movingFrameOptions(const Scene& scene, RenderOptions::Partitioning partitioning) {
    RenderOptions o;
    o.partitioning = partitioning;
    o.pixelTolerance = 0.5;
    o.headlight = true;
    o.samples = 1;
    o.lightCount = std::clamp(int(scene.lights.size()), 1, kMaxLights);
    return o;
}

/// The editor's wheel zoom (Viewport::wheelEvent): `steps` notches towards `cursor`, whose
/// point on the target's view plane stays under it.
Camera wheelZoom(const Camera& before, const Scene& scene, QPointF cursor, double steps) {
    const ViewProjection view(before, scene, QSize(kSide, kSide));
    const glm::dvec3 under = view.onViewPlane(cursor, before.target);
    CameraController c;
    c.setCamera(before);
    c.zoom(steps);
    Camera after = c.camera();
    const double kept =
        glm::length(after.eye - after.target) / glm::length(before.eye - before.target);
    const glm::dvec3 shift = (1.0 - kept) * (under - before.target);
    after.eye += shift;
    after.target += shift;
    return after;
}

float idAt(const AovBuffer& b, int x, int y) {
    return b.pixel(x, y)[0];
}

/// The reference pixel on a seam (its right or lower neighbour shows another face) nearest to
/// `near`, or `near` itself when the frame shows no seam: where the user zooms in.
QPointF seamNear(const AovBuffer& ref, QPointF near) {
    double best = 1e300;
    QPointF at = near;
    for (int y = 0; y + 1 < ref.height; ++y)
        for (int x = 0; x + 1 < ref.width; ++x) {
            const float id = idAt(ref, x, y), right = idAt(ref, x + 1, y),
                        down = idAt(ref, x, y + 1);
            if (id < 0.0f || !((right >= 0.0f && right != id) || (down >= 0.0f && down != id)))
                continue;
            const double d = std::hypot(x + 0.5 - near.x(), y + 0.5 - near.y());
            if (d < best) {
                best = d;
                at = QPointF(x + 0.5, y + 0.5);
            }
        }
    return at;
}

/// The pixels EdgeMetrics::crackPixelsCoveredInReference counts: background in `gpu` in a
/// horizontal or vertical run of at most 2 between covered pixels, covered in `ref`.
std::vector<QPoint> crackPixelsCovered(const AovBuffer& gpu, const AovBuffer& ref) {
    std::vector<QPoint> out;
    const auto background = [&](int x, int y) {
        return idAt(gpu, x, y) < 0.0f;
    };
    for (int y = 0; y < gpu.height; ++y)
        for (int x = 0; x < gpu.width; ++x) {
            if (!background(x, y) || idAt(ref, x, y) < 0.0f)
                continue;
            for (const QPoint step : {QPoint(1, 0), QPoint(0, 1)}) {
                QPoint a(x, y), b(x, y);
                int run = 1;
                const auto inside = [&](QPoint p) {
                    return p.x() >= 0 && p.y() >= 0 && p.x() < gpu.width && p.y() < gpu.height;
                };
                while (inside(a - step) && background((a - step).x(), (a - step).y()))
                    a -= step, ++run;
                while (inside(b + step) && background((b + step).x(), (b + step).y()))
                    b += step, ++run;
                if (run <= 2 && inside(a - step) && inside(b + step)) {
                    out.emplace_back(x, y);
                    break;
                }
            }
        }
    return out;
}

/// Screen distance (pixels) from the centre of pixel `px` to the boundary of the base polygon
/// of `s` (the edges of its trim loops' (u, v) box, trimParameterBox, which for the faces of
/// these solids is the domain), as projected by `view`: the nearest of 4 x 256 samples per edge,
/// refined 256 times between its neighbours.
double toPolygonBoundary(const Surface& s, const ViewProjection& view, QPoint px) {
    const ParameterBox box = trimParameterBox(s);
    const QPointF centre(px.x() + 0.5, px.y() + 0.5);
    double best = 1e300;
    for (int edge = 0; edge < 4; ++edge) {
        const auto at = [&](double t) {
            const double u = edge == 0   ? box.u.first
                             : edge == 1 ? box.u.last
                                         : box.u.first + t * (box.u.last - box.u.first);
            const double v = edge == 2   ? box.v.first
                             : edge == 3 ? box.v.last
                                         : box.v.first + t * (box.v.last - box.v.first);
            const std::optional<QPointF> p = view.project(surfacePoint(s.geometry, u, v));
            return p ? std::hypot(p->x() - centre.x(), p->y() - centre.y()) : 1e300;
        };
        double lo = 0.0, hi = 1.0;
        for (int level = 0; level < 2; ++level) {
            const int n = 256;
            int nearest = 0;
            double d = 1e300;
            for (int k = 0; k <= n; ++k)
                if (const double dk = at(lo + (hi - lo) * k / n); dk < d)
                    d = dk, nearest = k;
            best = std::min(best, d);
            const double width = (hi - lo) / n;
            lo = std::max(0.0, lo + nearest * width - width);
            hi = std::min(1.0, lo + 2.0 * width);
        }
    }
    return best;
}

/// One way of drawing the moving frames: its own renderer kept across a whole sequence, a
/// target and options, and the sums over the sequence's frames.
struct Pipeline {
    Pipeline(const char* n, GLenum depth, RenderOptions::Partitioning mode, bool withAov = true)
        : name(n), depthFormat(depth), partitioning(mode), aov(withAov) {}
    const char* name;
    GLenum depthFormat;
    RenderOptions::Partitioning partitioning;
    bool aov;           ///< frames with AOVs, compared with the reference; else colour only
    bool skirts = true; ///< RenderOptions::edgeSkirts (off only for the control)
    Renderer renderer;
    EditorTarget target;
    RenderOptions options;
    int frames = 0;
    long long covered = 0, cracks = 0, cracksCovered = 0, boundaryCracks = 0, otherCracks = 0,
              idOff = 0, idCoincident = 0, depthOff = 0, worstFrameCracks = 0, depthAtBoundary = 0,
              otherDepth = 0, idFar = 0;
    double silhouetteMaxWithoutPinholes = 0.0; ///< over frames with no crack the reference covers
    double silhouetteMax = 0.0;
    FrameReport last;
};

} // namespace

class TestRenderMotion : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenRenderer> m_gl; ///< the context; its own FBO is not used

    void start(Pipeline& p, const Scene& scene) {
        QString error;
        QVERIFY(m_gl->makeCurrent());
        KW_VERIFY_OK(p.renderer.initialize());
        QVERIFY2(p.target.create(QSize(kSide, kSide), p.depthFormat, p.aov, &error),
                 qPrintable(error));
        p.options = movingFrameOptions(scene, p.partitioning);
        p.options.edgeSkirts = p.skirts;
    }
    void finish(Pipeline& p) {
        QVERIFY(m_gl->makeCurrent());
        p.target.destroy();
        p.renderer.release();
    }

    /// Draws `doc` through `p` and adds its figures against `ref`, the reference of the
    /// document's scene seen by `camera`, to p's sums.
    void frame(Pipeline& p, const Document& doc, const Camera& camera, const AovBuffer& ref) {
        QVERIFY(m_gl->makeCurrent());
        p.last = p.renderer.render(doc, camera, p.target.target(), p.options);
        QVERIFY2(p.last.ok, qPrintable(p.last.error));
        const AovBuffer gpu = p.target.aov();
        glm::dvec3 lo, hi;
        sceneBounds(doc.scene(), lo, hi);
        const double pixelAngle =
            2.0 * std::tan(glm::radians(camera.fovYDegrees) * 0.5) / double(kSide);
        EdgeMetrics m;
        QString error;
        KW_VERIFY_OK(compareWithReference(gpu, ref, 1e-4 * glm::length(hi - lo), m, pixelAngle));
        // Each crack the reference covers: where the reference's face comes within 0.75 px of
        // its base polygon's boundary (a chord within 0.5 px of the exact edge: the pixel
        // centre between them is covered by no polygon), or elsewhere.
        const std::vector<QPoint> sites = crackPixelsCovered(gpu, ref);
        QCOMPARE((long long)sites.size(), m.crackPixelsCoveredInReference);
        const ViewProjection view(camera, doc.scene(), QSize(kSide, kSide));
        QStringList where;
        for (const QPoint& px : sites) {
            // (the boundary distance costs 2 x 4 x 257 evaluations: only for these pixels)
            const Surface* s = doc.surface(SurfaceId{std::uint32_t(idAt(ref, px.x(), px.y()))});
            QVERIFY(s);
            const double d = toPolygonBoundary(*s, view, px);
            (d <= 0.75 ? p.boundaryCracks : p.otherCracks) += 1;
            where << QStringLiteral("(%1, %2) face %3, %4 px from its polygon's boundary")
                         .arg(px.x())
                         .arg(px.y())
                         .arg(s->id.value)
                         .arg(d, 0, 'f', 2);
        }
        // Each depth disagreement (same face, another depth) away from a change of face: the
        // same question, where the boundary chord of a face's seam (u = 0 meeting u = 2 pi of a
        // periodic face) uncovers the face's far side. And each other face shown there: those
        // within twice the depth tolerance of the reference's are the wrong one of two faces
        // that touch (the pre-pass depth is the polygon's, within 0.5 px).
        const double tolerance = 1e-4 * glm::length(hi - lo);
        long long depthAtBoundary = 0;
        for (int y = 1; y + 1 < kSide && p.partitioning == RenderOptions::Partitioning::Adaptive;
             ++y)
            for (int x = 1; x + 1 < kSide; ++x) {
                const float* g = gpu.pixel(x, y);
                const float* r = ref.pixel(x, y);
                if (g[0] < 0.0f || r[0] < 0.0f || std::abs(g[9] - r[9]) <= tolerance)
                    continue;
                bool faceChange = false;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx)
                        faceChange = faceChange || idAt(ref, x + dx, y + dy) != r[0];
                if (faceChange)
                    continue;
                if (g[0] != r[0]) {
                    if (std::abs(g[9] - r[9]) > 2.0 * tolerance) {
                        ++p.idFar;
                        where << QStringLiteral("face %1 for %2 at (%3, %4)")
                                     .arg(g[0])
                                     .arg(r[0])
                                     .arg(x)
                                     .arg(y);
                    }
                    continue;
                }
                const Surface* s = doc.surface(SurfaceId{std::uint32_t(r[0])});
                QVERIFY(s);
                const double d = toPolygonBoundary(*s, view, QPoint(x, y));
                (d <= 0.75 ? depthAtBoundary : p.otherDepth) += 1;
                where << QStringLiteral("depth (%1, %2) face %3, %4 px from its polygon's boundary")
                             .arg(x)
                             .arg(y)
                             .arg(s->id.value)
                             .arg(d, 0, 'f', 2);
            }
        p.depthAtBoundary += depthAtBoundary;
        ++p.frames;
        p.covered += m.covered;
        p.cracks += m.crackPixels;
        p.cracksCovered += m.crackPixelsCoveredInReference;
        p.worstFrameCracks = std::max(p.worstFrameCracks, m.crackPixelsCoveredInReference);
        p.idOff += m.idDisagreements - m.idCoincident;
        p.idCoincident += m.idCoincident;
        p.depthOff += m.depthDisagreements;
        p.silhouetteMax = std::max(p.silhouetteMax, m.silhouetteMaxPixels);
        // A pinhole inside a face is also a covered pixel far from any reference silhouette.
        if (m.crackPixelsCoveredInReference == 0)
            p.silhouetteMaxWithoutPinholes =
                std::max(p.silhouetteMaxWithoutPinholes, m.silhouetteMaxPixels);
        qInfo("  %s: covered %lld, crack px %lld (%lld the reference covers%s%s), id %lld (%lld "
              "at equal depth) / depth %lld, silhouette max %.2f px, cells %lld, records synced "
              "%d",
              p.name, m.covered, m.crackPixels, m.crackPixelsCoveredInReference,
              where.isEmpty() ? "" : ": ", qPrintable(where.join(QStringLiteral("; "))),
              m.idDisagreements, m.idCoincident, m.depthDisagreements, m.silhouetteMaxPixels,
              (long long)p.last.partitions.cells, p.last.recordsSynced);
    }

    static void summary(const QString& what, const Pipeline& p) {
        qInfo("%s, %s: %d frames, %lld covered px, crack px %lld, %lld of them the reference "
              "covers (%lld at a polygon boundary, %lld elsewhere; at most %lld in one frame), id "
              "%lld (+%lld at equal depth; %lld beyond twice the depth tolerance) / depth %lld "
              "disagreements (%lld at a polygon boundary), silhouette max %.2f px (%.2f in "
              "frames without a pinhole)",
              qPrintable(what), p.name, p.frames, p.covered, p.cracks, p.cracksCovered,
              p.boundaryCracks, p.otherCracks, p.worstFrameCracks, p.idOff, p.idCoincident, p.idFar,
              p.depthOff, p.depthAtBoundary, p.silhouetteMax, p.silhouetteMaxWithoutPinholes);
    }

    /// What every sequence must show in the float-depth frames: no
    /// crack the reference covers (see the file's comment), the reference's visible faces and
    /// depths, and edge skirts drawn.
    static void checkAdaptive(const Pipeline& p) {
        QCOMPARE(p.otherCracks, 0LL);
        QCOMPARE(p.cracksCovered, 0LL);
        QVERIFY(p.last.partitions.skirtTriangles > 0);
        QVERIFY(p.silhouetteMaxWithoutPinholes <= 1.0);
        QCOMPARE(p.otherDepth, 0LL);
        QVERIFY(p.depthOff <= p.depthAtBoundary);
        QCOMPARE(p.idFar, 0LL);
    }

    /// The editor's frame, drawn into a 24-bit widget-like framebuffer, against the same frame
    /// into a float-depth one: the renderer draws the former through its float-depth target
    /// (render/float_depth_target.h), so the two must be the same pixel for pixel. Adds the
    /// differing pixels to `differing`.
    void sameAsFloat(Pipeline& editor, Pipeline& floatHost, const Document& doc,
                     const Camera& camera, long long& differing) {
        QVERIFY(m_gl->makeCurrent());
        for (Pipeline* p : {&editor, &floatHost}) {
            p->last = p->renderer.render(doc, camera, p->target.target(), p->options);
            QVERIFY2(p->last.ok, qPrintable(p->last.error));
            ++p->frames;
        }
        QVERIFY(editor.last.gpuBytes.floatDepthTarget > 0);
        QCOMPARE(floatHost.last.gpuBytes.floatDepthTarget, std::int64_t(0));
        const QImage a = editor.target.colour(), b = floatHost.target.colour();
        long long n = 0;
        for (int y = 0; y < kSide; ++y)
            for (int x = 0; x < kSide; ++x)
                n += a.pixel(x, y) != b.pixel(x, y);
        if (n > 0)
            qInfo("  the editor's frame differs from the float-depth frame in %lld pixels", n);
        differing += n;
    }

private Q_SLOTS:
    void initTestCase() {
        QString error;
        auto made = kwtest::offscreenRenderer(QSize(8, 8), false);
        QVERIFY2(made, qPrintable(made.message()));
        m_gl = std::move(made).value();
    }

    // The editor on a software rasteriser: aliased frames while moving, through the float-depth
    // target (its widget's depth is 24-bit), and an anti-aliased still frame when it stops. The
    // accumulated still frame leaves the float-depth target in place (else every move would
    // allocate it again), draws the same pixels into a 24-bit host as into a float one, and the
    // next aliased frame frees its own framebuffers.
    void stillFramesKeepTheFloatDepthTarget() {
        const std::optional<Scene> loaded = kwtest::importedPart(QStringLiteral("Pump_Nut.brep"));
        QVERIFY(loaded);
        Document doc;
        QVERIFY(doc.resetScene(*loaded));
        Pipeline editor{"editor colour, 24-bit host", GL_DEPTH24_STENCIL8,
                        RenderOptions::Partitioning::Adaptive, false};
        Pipeline floatHost{"colour, float host", GL_DEPTH32F_STENCIL8,
                           RenderOptions::Partitioning::Adaptive, false};
        for (Pipeline* p : {&editor, &floatHost})
            start(*p, doc.scene());
        if (QTest::currentTestFailed())
            return;
        const Camera camera = fitCamera(doc.scene(), 1.0);
        auto draw = [&](Pipeline& p, int samples) {
            p.options.samples = samples;
            p.last = p.renderer.render(doc, camera, p.target.target(), p.options);
            return p.last.ok;
        };
        QVERIFY(m_gl->makeCurrent());
        QVERIFY(draw(editor, 1));
        QVERIFY(editor.last.gpuBytes.floatDepthTarget > 0);
        QCOMPARE(editor.last.gpuBytes.frameTargets, std::int64_t(0));
        QVERIFY(draw(editor, 4));
        QVERIFY(editor.last.gpuBytes.floatDepthTarget > 0);
        QVERIFY(editor.last.gpuBytes.frameTargets > 0);
        QVERIFY(draw(floatHost, 4));
        const QImage a = editor.target.colour(), b = floatHost.target.colour();
        QCOMPARE(a, b);
        QVERIFY(draw(editor, 1));
        QVERIFY(editor.last.gpuBytes.floatDepthTarget > 0);
        QCOMPARE(editor.last.gpuBytes.frameTargets, std::int64_t(0));
        for (Pipeline* p : {&editor, &floatHost})
            finish(*p);
    }

    void orbitAndZoom_data() {
        QTest::addColumn<QString>("file");
        QTest::newRow("Pump_Nut") << QStringLiteral("Pump_Nut.brep");
        QTest::newRow("Axis_of_bearing") << QStringLiteral("Axis_of_bearing.brep");
    }
    void orbitAndZoom() {
        QFETCH(QString, file);
        const std::optional<Scene> loaded = kwtest::importedPart(file);
        QVERIFY(loaded);
        Document doc;
        QVERIFY(doc.resetScene(*loaded));
        const Scene& scene = doc.scene();
        Pipeline floatDepth{"adaptive", GL_DEPTH32F_STENCIL8,
                            RenderOptions::Partitioning::Adaptive};
        Pipeline paper{"uniform (paper)", GL_DEPTH32F_STENCIL8,
                       RenderOptions::Partitioning::Uniform};
        Pipeline editor{"editor colour, 24-bit host", GL_DEPTH24_STENCIL8,
                        RenderOptions::Partitioning::Adaptive, false};
        Pipeline floatHost{"colour, float host", GL_DEPTH32F_STENCIL8,
                           RenderOptions::Partitioning::Adaptive, false};
        long long differing = 0;
        for (Pipeline* p : {&floatDepth, &paper, &editor, &floatHost})
            start(*p, scene);
        if (QTest::currentTestFailed())
            return;

        // The poses: the fitted view, an orbit around the part (30 degrees a step, tilting),
        // then wheel zooms (3 notches: 0.61 of the distance) towards a seam near the cursor with
        // small orbits between them, until the eye is 2 % of the fitted distance from the target.
        struct Move {
            double orbitX, orbitY, wheel; ///< pixels (0.4 deg each), notches
        };
        const Move moves[] = {{0, 0, 0},    {75, 0, 0},   {75, 25, 0}, {75, 25, 0}, {75, -60, 0},
                              {75, -20, 0}, {0, 0, 3},    {20, 10, 3}, {0, 0, 3},   {-20, 5, 3},
                              {0, 0, 3},    {15, -10, 3}, {0, 0, 3},   {10, 10, 3}};
        Camera camera = fitCamera(scene, 1.0);
        const double fitted = glm::length(camera.eye - camera.target);
        AovBuffer previous;
        int pose = 0;
        for (const Move& move : moves) {
            if (move.orbitX != 0.0 || move.orbitY != 0.0) {
                CameraController c;
                c.setCamera(camera);
                c.orbit(move.orbitX, move.orbitY);
                camera = c.camera();
            }
            if (move.wheel != 0.0)
                camera = wheelZoom(camera, scene, seamNear(previous, QPointF(0.45, 0.5) * kSide),
                                   move.wheel);
            const AovBuffer ref = renderReference(scene, camera, kSide, kSide);
            long long referenceCovered = 0;
            for (int y = 0; y < kSide; ++y)
                for (int x = 0; x < kSide; ++x)
                    referenceCovered += idAt(ref, x, y) >= 0.0f;
            qInfo("%s pose %d, eye-target %.3f of the fitted distance, reference covers %lld px",
                  qPrintable(file), ++pose, glm::length(camera.eye - camera.target) / fitted,
                  referenceCovered);
            QVERIFY2(referenceCovered > kSide * kSide / 20, "the pose shows too little");
            for (Pipeline* p : {&floatDepth, &paper}) {
                frame(*p, doc, camera, ref);
                if (QTest::currentTestFailed())
                    return;
            }
            sameAsFloat(editor, floatHost, doc, camera, differing);
            if (QTest::currentTestFailed())
                return;
            previous = ref;
        }
        for (Pipeline* p : {&floatDepth, &paper})
            summary(file + QStringLiteral(" orbit and zoom"), *p);
        for (Pipeline* p : {&floatDepth, &paper, &editor, &floatHost})
            finish(*p);
        qInfo("%s orbit and zoom: the editor's frames differ from the float-depth ones in %lld "
              "pixels",
              qPrintable(file), differing);
        checkAdaptive(floatDepth);
        QCOMPARE(differing, 0LL);
        // The control: the same poses from the paper's polygons, which the metrics catch.
        QVERIFY(paper.idOff + paper.depthOff > 1000);
        QCOMPARE(paper.last.partitions.skirtTriangles, std::int64_t(0)); // the paper's as it was
        QVERIFY(paper.silhouetteMax > 1.0);
    }

    // A drag (PointDragTool through LiveEdit): one control point of the face the
    // fitted view shows most, the one projected nearest that face's pixels' centre, dragged in
    // the view plane 5 px right and 3 px up per mouse move through Document::setControlPoints,
    // then released (the MoveControlPoints command, pushed), undone and redone. Every frame is
    // compared with the reference of the document as it is then: the dragged face may open its
    // seams (the reference shows the same gap), but no crack the reference covers, and the same
    // faces and depths outside the edge band.
    /// `withoutSkirts`: the fewest pinholes the same frames show without the edge skirts (the
    /// control: they are what the skirts close; 4 on Pump_Nut when written), or -1 not to check.
    void dragOnePoint_data() {
        QTest::addColumn<QString>("file");
        QTest::addColumn<int>("withoutSkirts");
        QTest::newRow("Pump_Nut") << QStringLiteral("Pump_Nut.brep") << 1;
        QTest::newRow("Axis_of_bearing") << QStringLiteral("Axis_of_bearing.brep") << -1;
    }
    void dragOnePoint() {
        QFETCH(QString, file);
        QFETCH(int, withoutSkirts);
        const std::optional<Scene> loaded = kwtest::importedPart(file);
        QVERIFY(loaded);
        Document doc;
        QVERIFY(doc.resetScene(*loaded));
        Pipeline floatDepth{"adaptive", GL_DEPTH32F_STENCIL8,
                            RenderOptions::Partitioning::Adaptive};
        Pipeline editor{"editor colour, 24-bit host", GL_DEPTH24_STENCIL8,
                        RenderOptions::Partitioning::Adaptive, false};
        Pipeline floatHost{"colour, float host", GL_DEPTH32F_STENCIL8,
                           RenderOptions::Partitioning::Adaptive, false};
        Pipeline noSkirts{"adaptive without skirts", GL_DEPTH32F_STENCIL8,
                          RenderOptions::Partitioning::Adaptive};
        noSkirts.skirts = false;
        long long differing = 0;
        for (Pipeline* p : {&floatDepth, &editor, &floatHost, &noSkirts})
            start(*p, doc.scene());
        if (QTest::currentTestFailed())
            return;
        const Camera camera = fitCamera(doc.scene(), 1.0);
        const AovBuffer before = renderReference(doc.scene(), camera, kSide, kSide);

        // The face and its point.
        std::map<std::uint32_t, std::pair<long long, glm::dvec2>> pixels; // count, sum of centres
        for (int y = 0; y < kSide; ++y)
            for (int x = 0; x < kSide; ++x)
                if (const float id = idAt(before, x, y); id >= 0.0f) {
                    auto& [n, sum] = pixels[std::uint32_t(id)];
                    ++n;
                    sum += glm::dvec2(x + 0.5, y + 0.5);
                }
        QVERIFY(!pixels.empty());
        const auto most = std::max_element(pixels.begin(), pixels.end(), [](auto& a, auto& b) {
            return a.second.first < b.second.first;
        });
        const SurfaceId face{most->first};
        const glm::dvec2 centre = most->second.second / double(most->second.first);
        const ViewProjection view(camera, doc.scene(), QSize(kSide, kSide));
        const NurbsSurface& g = doc.surface(face)->geometry;
        int index = -1;
        QPointF press;
        for (int k = 0; k < int(g.points.size()); ++k)
            if (const std::optional<QPointF> at = view.project(g.points[size_t(k)])) {
                if (index < 0 || std::hypot(at->x() - centre.x, at->y() - centre.y) <
                                     std::hypot(press.x() - centre.x, press.y() - centre.y)) {
                    index = k;
                    press = *at;
                }
            }
        QVERIFY(index >= 0);
        const glm::dvec3 from = g.points[size_t(index)];
        qInfo("%s: dragging point %d of face %u (%lld px in the fitted view) from pixel (%.1f, "
              "%.1f)",
              qPrintable(file), index, face.value, most->second.first, press.x(), press.y());

        QUndoStack stack;
        const auto drawn = [&](const char* what) {
            const AovBuffer ref = renderReference(doc.scene(), camera, kSide, kSide);
            qInfo("%s %s", qPrintable(file), what);
            frame(floatDepth, doc, camera, ref);
            if (withoutSkirts >= 0 && !QTest::currentTestFailed())
                frame(noSkirts, doc, camera, ref);
            if (!QTest::currentTestFailed())
                sameAsFloat(editor, floatHost, doc, camera, differing);
            return ref;
        };
        drawn("before the drag");
        AovBuffer last;
        glm::dvec3 to = from;
        for (int step = 1; step <= 6 && !QTest::currentTestFailed(); ++step) {
            const QPointF pixel = press + QPointF(5.0 * step, -3.0 * step);
            to = from + view.onViewPlane(pixel, from) - view.onViewPlane(press, from);
            QVERIFY(doc.setControlPoints(face, {index}, {to}));
            last = drawn(qPrintable(QStringLiteral("drag step %1").arg(step)));
            // The editor's path: the moved point is a sub-image upload, nothing is rebuilt.
            for (const Pipeline* p : {&floatDepth, &editor}) {
                QCOMPARE(p->last.uploads.fullUploads, 0);
                QVERIFY(p->last.uploads.subImageUploads >= 1);
            }
        }
        if (QTest::currentTestFailed())
            return;
        auto release = MoveControlPoints::create(&doc, face, {index}, {from}, {to}, MoveKind::Drag);
        QVERIFY2(release, qPrintable(release.message()));
        QVERIFY(pushCommand(&stack, std::move(release)));
        drawn("released");
        stack.undo();
        QCOMPARE(doc.surface(face)->geometry.points[size_t(index)], from);
        drawn("undone");
        stack.redo();
        QCOMPARE(doc.surface(face)->geometry.points[size_t(index)], to);
        drawn("redone");
        if (QTest::currentTestFailed())
            return;
        // The drag changed what is seen.
        long long changed = 0;
        for (int y = 0; y < kSide; ++y)
            for (int x = 0; x < kSide; ++x)
                changed += idAt(before, x, y) != idAt(last, x, y);
        qInfo("%s: the drag changed the visible face of %lld reference pixels", qPrintable(file),
              changed);
        QVERIFY(changed > 50);
        summary(file + QStringLiteral(" drag"), floatDepth);
        if (withoutSkirts >= 0)
            summary(file + QStringLiteral(" drag"), noSkirts);
        for (Pipeline* p : {&floatDepth, &editor, &floatHost, &noSkirts})
            finish(*p);
        checkAdaptive(floatDepth);
        QCOMPARE(differing, 0LL);
        // The control: the skirts are what closes the seams' pinholes.
        if (withoutSkirts >= 0) {
            QVERIFY(noSkirts.cracksCovered >= withoutSkirts);
            QCOMPARE(noSkirts.last.partitions.skirtTriangles, std::int64_t(0));
        }
    }
};

QTEST_MAIN(TestRenderMotion)
#include "tst_render_motion.moc"
