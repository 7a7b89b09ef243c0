// GL test: the partial frame (RenderOptions::FrameReuse::Partial; render/partial_frame.h). On
// hammer.iges and Motor-c.brep, a control point of the largest free-form face is dragged in
// steps, the whole face moved past its old bounds and put back, another face is edited, hidden
// and shown again: each frame after an edit is partial, and its pixels are byte for
// byte those of the same frame drawn whole (FrameReuse::Full, following the same edits), and
// those of a fresh renderer's whole frame but for depth ties of a few pixels, while it sends only
// the cells of the reached faces that reach its rectangle; the pre-pass data
// that Renderer::pickInLastFrame reads answers as the whole frame's; likewise with a section
// plane (caps), the wireframe and the control nets on. With the damage tiles unmerged (one
// rectangle per run of tiles, render/damage_tiles.h), the same, and the rectangles redraw fewer
// pixels than the one bounding them. A new camera, a colour map whose range the edit moved,
// and an anti-aliased frame are drawn whole.
#include "cad_test_util.h"
#include "expected_test_util.h"
#include "image_test_util.h"
#include "render_test_util.h"

#include <algorithm>
#include <cmath>
#include <map>

using namespace kw;

namespace {

constexpr int kSide = 320;

/// The largest free-form face (polynomial, degree >= 2, by control bounds) and its middle
/// control point, moved along the surface normal there (the bench's drag, bench/edit_loop.cpp).
struct Drag {
    SurfaceId id;
    int index = 0;
    glm::dvec3 home{0.0}, direction{0.0};
    double size = 0.0;
};

Drag chooseDrag(const Scene& scene, SurfaceId skip = {}) {
    Drag d;
    for (const Surface& s : scene.surfaces) {
        const NurbsSurface& g = s.geometry;
        const bool polynomial = std::all_of(g.weights.begin(), g.weights.end(),
                                            [&](double w) { return w == g.weights.front(); });
        if (!polynomial || std::max(g.degreeU, g.degreeV) < 2 || s.id == skip)
            continue;
        glm::dvec3 lo, hi;
        surfaceControlBounds(g, lo, hi);
        if (glm::length(hi - lo) > d.size) {
            d.size = glm::length(hi - lo);
            d.id = s.id;
        }
    }
    const Surface* s = nullptr;
    for (const Surface& t : scene.surfaces)
        if (t.id == d.id)
            s = &t;
    if (!s)
        return d;
    const NurbsSurface& g = s->geometry;
    d.index = g.index(g.countU / 2, g.countV / 2);
    d.home = g.points[size_t(d.index)];
    const Interval du = surfaceDomainU(g), dv = surfaceDomainV(g);
    d.direction = surfaceFrame(g, 0.5 * (du.first + du.last), 0.5 * (dv.first + dv.last)).normal;
    return d;
}

} // namespace

class TestRenderPartialFrame : public QObject {
    Q_OBJECT
    std::unique_ptr<OffscreenRenderer> m_partial; ///< FrameReuse::Partial: under test
    std::unique_ptr<OffscreenRenderer> m_whole;   ///< FrameReuse::Full: the same frames whole
    std::unique_ptr<OffscreenRenderer> m_fresh;   ///< FrameReuse::None: main's way
    std::uint64_t m_drawnRevision = 0;            ///< the document's at the last frame
    /// Over the partial frames since the last reset: the cells of the surfaces that reached
    /// their rectangles, and those of them the frames sent (the ones reaching it).
    std::int64_t m_surfaceCells = 0, m_sentCells = 0;
    /// Over the same frames: the pixels their rectangles (the damage tiles' covers) redrew,
    /// the pixels of the rectangles bounding them, and the frames drawn as several.
    std::int64_t m_regionPixels = 0, m_boundPixels = 0;
    int m_multiRegion = 0;

    RenderOptions m_base;             ///< what every frame draws besides the defaults
    std::map<QString, Scene> m_parts; ///< imported once (the CAD reader takes seconds)

    const Scene* part(const QString& file) {
        if (!m_parts.count(file))
            if (std::optional<Scene> imported = kwtest::importedPart(file))
                m_parts.emplace(file, std::move(*imported));
        const auto it = m_parts.find(file);
        return it == m_parts.end() ? nullptr : &it->second;
    }

    RenderOptions options(RenderOptions::FrameReuse reuse) const {
        RenderOptions o = m_base;
        o.partitioning = RenderOptions::Partitioning::Adaptive; // the editor's
        o.frameReuse = reuse;
        return o;
    }

    /// Draws `doc` with all three and checks them; `partial` 1: the frame must be partial, 0:
    /// whole, -1: either.
    void drawAndCompare(const Document& doc, const Camera& cam, const QString& step, int partial,
                        QRect* rect = nullptr) {
        KW_VERIFY_OK(m_partial->render(doc, cam, options(RenderOptions::FrameReuse::Partial)));
        const FrameReport report = m_partial->lastReport();
        KW_VERIFY_OK(m_whole->render(doc, cam, options(RenderOptions::FrameReuse::Full)));
        QVERIFY2(!m_whole->lastReport().partial, qPrintable(step));
        KW_VERIFY_OK(m_fresh->render(doc, cam, options(RenderOptions::FrameReuse::None)));
        QVERIFY2(partial < 0 || report.partial == (partial == 1), qPrintable(step));
        if (report.partial && partial == 1 && doc.revision() != m_drawnRevision) {
            QVERIFY2(!report.partialRect.isEmpty() &&
                         report.partialRect.width() * report.partialRect.height() <
                             kSide * kSide / 2,
                     qPrintable(step));
            QVERIFY2(report.partialSurfaces >= 1 &&
                         report.partialSurfaces <= int(doc.scene().surfaces.size()),
                     qPrintable(step));
            // A cell reaching two of the frame's rectangles is sent for each.
            QVERIFY2(report.partialCells >= 1 &&
                         report.partialCells <=
                             report.partialSurfaceCells * std::max(report.partialRegions, 1),
                     qPrintable(step));
            const std::int64_t bound =
                std::int64_t(report.partialRect.width()) * report.partialRect.height();
            QVERIFY2(report.partialRegions >= 1 && report.partialPixels >= 1 &&
                         report.partialPixels <= bound * report.partialRegions,
                     qPrintable(step));
            if (report.partialRegions == 1) {
                m_surfaceCells += report.partialSurfaceCells;
                m_sentCells += report.partialCells;
            }
            m_regionPixels += report.partialPixels;
            m_boundPixels += bound;
            m_multiRegion += report.partialRegions > 1;
        }
        m_drawnRevision = doc.revision();
        if (rect)
            *rect = report.partialRect;
        const QImage got = m_partial->colorImage(), whole = m_whole->colorImage(),
                     fresh = m_fresh->colorImage();
        const int vsWhole = kwtest::differingPixels(got, whole);
        const int vsFresh = kwtest::differingPixels(got, fresh);
        qInfo("%s: partial %d, rectangle %d,%d %dx%d (%d rectangles, %lld pixels), surfaces %d, "
              "cells %lld of %lld; %d pixels differ from a fresh whole frame",
              qPrintable(step), report.partial, report.partialRect.x(), report.partialRect.y(),
              report.partialRect.width(), report.partialRect.height(), report.partialRegions,
              (long long)report.partialPixels, report.partialSurfaces,
              (long long)report.partialCells, (long long)report.partialSurfaceCells, vsFresh);
        if (vsWhole != 0) {
            got.save(kwtest::outputDir().filePath(QStringLiteral("partial_%1.png").arg(step)));
            whole.save(kwtest::outputDir().filePath(QStringLiteral("whole_%1.png").arg(step)));
        }
        QVERIFY2(vsWhole == 0, qPrintable(QStringLiteral("%1: %2 pixels differ from the whole "
                                                         "frame")
                                              .arg(step)
                                              .arg(vsWhole)));
        // The fresh renderer's planes follow the bounds at every edit, the kept ones not
        // (PartialFrames::keptCamera): depth ties between touching faces may fall otherwise.
        QVERIFY2(vsFresh <= kSide * kSide / 2000,
                 qPrintable(QStringLiteral("%1: %2 pixels differ from a fresh whole frame")
                                .arg(step)
                                .arg(vsFresh)));
    }

    /// pickInLastFrame over a grid of pixels, partial against whole.
    void comparePicks(const Document& doc, const Camera& cam) {
        int known = 0;
        for (int y = 2; y < kSide; y += 9)
            for (int x = 2; x < kSide; x += 9) {
                const QPointF at(x + 0.5, y + 0.5);
                QVERIFY(m_partial->makeCurrent());
                const Renderer::FramePick p =
                    m_partial->renderer().pickInLastFrame(doc, cam, QSize(kSide, kSide), at);
                QVERIFY(m_whole->makeCurrent());
                const Renderer::FramePick w =
                    m_whole->renderer().pickInLastFrame(doc, cam, QSize(kSide, kSide), at);
                QVERIFY2(p.known == w.known, qPrintable(QStringLiteral("%1,%2").arg(x).arg(y)));
                if (!p.known)
                    continue;
                ++known;
                QVERIFY(bool(p.hit) == bool(w.hit));
                if (p.hit) {
                    QCOMPARE(p.hit->surface.value, w.hit->surface.value);
                    QVERIFY(p.hit->uv == w.hit->uv);
                }
            }
        QVERIFY2(known > 100, qPrintable(QString::number(known)));
    }

    /// `grown`: the face's move past its old bounds, in face sizes (Motor-c's face is a few
    /// pixels wide).
    /// `solid`: the faces edited bound closed solids, whose marks an edit, a hide or a show
    /// changes (every face's back faces then: a whole frame). `grows`: the move leaves the
    /// face's damage tiles (Motor-c's face is a few pixels wide: it stays in its tiles).
    void editSequence(const QString& file, double grown, bool solid, bool grows) {
        const Scene* scene = part(file);
        QVERIFY2(scene, qPrintable(file));
        Document doc;
        QVERIFY(doc.resetScene(*scene));
        const Camera cam = fitCamera(doc.scene(), 1.0);
        const Drag drag = chooseDrag(doc.scene());
        QVERIFY2(drag.size > 0.0, qPrintable(file));
        m_surfaceCells = m_sentCells = m_regionPixels = m_boundPixels = 0;
        m_multiRegion = 0;
        drawAndCompare(doc, cam, file + QStringLiteral("-first"), 0);
        QRect first, grownRect;
        const NurbsSurface homeGeometry = doc.surface(drag.id)->geometry;
        // Sideways on screen too, so that the face's rectangle grows with the amount.
        const glm::dvec3 right = glm::normalize(glm::cross(cam.target - cam.eye, cam.up));
        const auto moveTo = [&](double amount) {
            return doc.setControlPoints(
                drag.id, {drag.index},
                {drag.home + (drag.direction + right) * (amount * drag.size)});
        };
        // Two warm-up steps: the first edit of a face of a closed solid opens it (the marks
        // change, a whole frame).
        QVERIFY(moveTo(0.01));
        drawAndCompare(doc, cam, file + QStringLiteral("-open"), -1);
        QVERIFY(moveTo(0.02));
        drawAndCompare(doc, cam, file + QStringLiteral("-small"), 1, &first);
        // A pick between two frames (the probe's hover) draws its own pixel with its own plan.
        m_partial->pick(doc, cam, QPointF(kSide / 2 + 0.5, kSide / 2 + 0.5),
                        options(RenderOptions::FrameReuse::Partial));
        // A whole frame between two partial ones (the bench alternates them): the next partial
        // frame redraws the face's tiles as that frame drew it.
        QVERIFY(moveTo(0.03));
        KW_VERIFY_OK(m_partial->render(doc, cam, options(RenderOptions::FrameReuse::Full)));
        QVERIFY(!m_partial->lastReport().partial);
        QVERIFY(moveTo(0.04));
        drawAndCompare(doc, cam, file + QStringLiteral("-more"), 1);
        // The whole face moved sideways past its old bounds: the rectangle must hold both.
        {
            const Surface* face = doc.surface(drag.id);
            QVERIFY(face);
            std::vector<int> all;
            std::vector<glm::dvec3> moved;
            for (int k = 0; k < int(face->geometry.points.size()); ++k) {
                all.push_back(k);
                moved.push_back(face->geometry.points[size_t(k)] + right * (grown * drag.size));
            }
            QVERIFY(doc.setControlPoints(drag.id, all, moved));
        }
        drawAndCompare(doc, cam, file + QStringLiteral("-grown"), 1, &grownRect);
        QVERIFY2(!grows || !first.contains(grownRect),
                 qPrintable(QStringLiteral("%1: %2x%3 after %4x%5")
                                .arg(file)
                                .arg(grownRect.width())
                                .arg(grownRect.height())
                                .arg(first.width())
                                .arg(first.height())));
        comparePicks(doc, cam);
        QVERIFY(doc.setGeometry(drag.id, homeGeometry));
        drawAndCompare(doc, cam, file + QStringLiteral("-back"), solid ? -1 : 1);
        // Nothing changed: the kept frame again.
        drawAndCompare(doc, cam, file + QStringLiteral("-same"), 1);
        QVERIFY(m_partial->lastReport().partialRect.isEmpty());
        // Another face: hidden, shown, edited.
        const Drag other = chooseDrag(doc.scene(), drag.id);
        QVERIFY(other.size > 0.0);
        QVERIFY(doc.setHidden(other.id, true));
        drawAndCompare(doc, cam, file + QStringLiteral("-hidden"), solid ? -1 : 1);
        QVERIFY(doc.setHidden(other.id, false));
        drawAndCompare(doc, cam, file + QStringLiteral("-shown"), solid ? -1 : 1);
        QVERIFY(doc.setControlPoints(other.id, {other.index},
                                     {other.home + other.direction * (0.05 * other.size)}));
        drawAndCompare(doc, cam, file + QStringLiteral("-other"), solid ? -1 : 1);
        comparePicks(doc, cam);
        // Another view: whole.
        Camera turned = cam;
        turned.eye += 0.05 * (cam.target - cam.eye);
        drawAndCompare(doc, turned, file + QStringLiteral("-camera"), 0);
        // The faces reaching a rectangle sent only their cells that reach it: on both parts
        // the rectangles cut through faces, whose cells outside were left out.
        qInfo("%s: partial frames sent %lld of their surfaces' %lld cells", qPrintable(file),
              (long long)m_sentCells, (long long)m_surfaceCells);
        qInfo("%s: the damage tiles' rectangles redrew %lld of their bounds' %lld pixels, %d "
              "frames as several rectangles",
              qPrintable(file), (long long)m_regionPixels, (long long)m_boundPixels, m_multiRegion);
        if (m_surfaceCells == 0)
            return; // every partial frame was drawn as several rectangles
        QVERIFY2(m_sentCells < m_surfaceCells * 9 / 10,
                 qPrintable(QStringLiteral("%1: %2 of %3 cells")
                                .arg(file)
                                .arg(m_sentCells)
                                .arg(m_surfaceCells)));
    }

private Q_SLOTS:
    void initTestCase() {
        for (auto* r : {&m_partial, &m_whole, &m_fresh}) {
            auto made = kwtest::offscreenRenderer(QSize(kSide, kSide), 0);
            QVERIFY2(made, qPrintable(made.message()));
            *r = std::move(made).value();
        }
    }

    void cleanupTestCase() {
        m_partial.reset();
        m_whole.reset();
        m_fresh.reset();
    }

    void hammerEdits() { editSequence(QStringLiteral("hammer.iges"), 0.25, false, true); }
    void motorEdits() { editSequence(QStringLiteral("Motor-c.brep"), 0.5, true, false); }

    /// The damage tiles unmerged and of 8 pixels, one rectangle per run of tiles (at this size
    /// the default merges hammer's into one): each drawn as the whole frame draws it, and together
    /// fewer pixels than the rectangle bounding them.
    void hammerEditsByTiles() {
        m_base.damageTiles = {8, 64, 0};
        editSequence(QStringLiteral("hammer.iges"), 0.25, false, true);
        m_base = RenderOptions{};
        QVERIFY2(m_multiRegion >= 4, qPrintable(QString::number(m_multiRegion)));
        QVERIFY2(m_regionPixels < m_boundPixels * 9 / 10,
                 qPrintable(QStringLiteral("%1 of %2").arg(m_regionPixels).arg(m_boundPixels)));
    }

    /// A section plane through Motor-c (caps on its closed solids), the wireframe and the
    /// control nets: the partial frames still draw the whole frame's pixels.
    void sectionsAndOverlays() {
        const Scene* scene = part(QStringLiteral("Motor-c.brep"));
        QVERIFY(scene);
        Document doc;
        QVERIFY(doc.resetScene(*scene));
        const Camera cam = fitCamera(doc.scene(), 1.0);
        const Drag drag = chooseDrag(doc.scene());
        glm::dvec3 lo, hi;
        QVERIFY(sceneBounds(doc.scene(), lo, hi));
        SectionPlane plane;
        plane.position = 0.5 * (lo + hi);
        plane.normal = glm::dvec3(1.0, 0.0, 0.0);
        m_base.sections = {plane};
        m_base.wireframe = m_base.controlNet = true;
        int partial = 0;
        for (int k = 0; k <= 4; ++k) {
            QVERIFY(doc.setControlPoints(drag.id, {drag.index},
                                         {drag.home + drag.direction * (0.02 * k * drag.size)}));
            drawAndCompare(doc, cam, QStringLiteral("sections-%1").arg(k), -1);
            partial += m_partial->lastReport().partial;
        }
        m_base = RenderOptions{};
        QVERIFY2(partial >= 3, qPrintable(QString::number(partial)));
    }

    /// What a partial frame cannot bound is drawn whole: a colour map over the whole scene
    /// whose range the edit moved, and anti-aliased frames.
    void wholeWhereItMustBe() {
        const Scene* scene = part(QStringLiteral("hammer.iges"));
        QVERIFY(scene);
        Document doc;
        QVERIFY(doc.resetScene(*scene));
        const Camera cam = fitCamera(doc.scene(), 1.0);
        const Drag drag = chooseDrag(doc.scene());
        RenderOptions map = options(RenderOptions::FrameReuse::Partial);
        map.analysis.mode = AnalysisMode::Mean;
        KW_VERIFY_OK(m_partial->render(doc, cam, map));
        const ValueRange before = m_partial->lastReport().analysisRange;
        QVERIFY(doc.setControlPoints(drag.id, {drag.index},
                                     {drag.home + drag.direction * (0.3 * drag.size)}));
        KW_VERIFY_OK(m_partial->render(doc, cam, map));
        QVERIFY(!(m_partial->lastReport().analysisRange == before));
        QVERIFY(!m_partial->lastReport().partial);
        // Anti-aliased: every sample is a whole frame.
        RenderOptions aa = options(RenderOptions::FrameReuse::Partial);
        aa.samples = 4;
        KW_VERIFY_OK(m_partial->render(doc, cam, aa));
        QVERIFY(doc.setControlPoints(drag.id, {drag.index}, {drag.home}));
        KW_VERIFY_OK(m_partial->render(doc, cam, aa));
        QVERIFY(!m_partial->lastReport().partial);
    }
};

QTEST_MAIN(TestRenderPartialFrame)
#include "tst_render_partial_frame.moc"
