// The partial frame's bookkeeping without GL (render/partial_frame.h): which rectangle a frame
// redraws after the remembered one, when it must be drawn whole, and when the kept camera
// planes still hold the scene.
#include "render/edge_bands.h"
#include "render/partial_frame.h"

#include <QTest>

using namespace kw;

namespace {

constexpr int kSide = 100;

PartialFrameView view() {
    PartialFrameView v;
    v.drawnSize = v.targetSize = QSize(kSide, kSide);
    v.viewport = glm::ivec2(kSide);
    v.options.frameReuse = RenderOptions::FrameReuse::Partial;
    return v;
}

SurfaceFootprint surface(std::uint32_t id, glm::ivec4 rect) {
    SurfaceFootprint f;
    f.id = id;
    f.slot = int(id);
    f.revisions.points = id;
    f.drawn = f.bounded = true;
    f.rect = rect;
    return f;
}

/// The identity: normalised device coordinates are the points' x and y.
const glm::mat4 kIdentity(1.0f);

} // namespace

class TestPartialFrameDamage : public QObject {
    Q_OBJECT
    const int pad = PartialFrames::reachPixels(view().options);

private Q_SLOTS:
    void nothingRememberedIsWhole() {
        PartialFrames p;
        QVERIFY(!p.damage(view(), 0, {surface(1, {10, 10, 20, 20})}, kIdentity, nullptr));
    }

    void changedSurfacesOldAndNew() {
        PartialFrames p;
        const std::vector<SurfaceFootprint> before{surface(1, {10, 10, 20, 20}),
                                                   surface(2, {60, 60, 70, 70})};
        p.remember(Camera{}, FrameCamera{}, view(), 7, before, nullptr, {}, true);
        // Nothing changed: an empty rectangle.
        const auto same = p.damage(view(), 7, before, kIdentity, nullptr);
        QVERIFY(same && same->z <= same->x);
        // Surface 1 moved and changed revision: its old and new rectangles, grown by the reach.
        std::vector<SurfaceFootprint> after = before;
        after[0].revisions.points = 99;
        after[0].rect = {30, 12, 40, 22};
        const auto moved = p.damage(view(), 7, after, kIdentity, nullptr);
        QVERIFY(moved);
        QCOMPARE(*moved, glm::ivec4(10 - pad, 10 - pad, 40 + pad, 22 + pad));
        // A new polygon without a revision (cells chosen again) counts too.
        after = before;
        after[1].polygon = 5;
        QCOMPARE(*p.damage(view(), 7, after, kIdentity, nullptr),
                 glm::ivec4(60 - pad, 60 - pad, 70 + pad, 70 + pad));
        // Hidden (gone from the list): its old rectangle. Shown: its new one.
        QCOMPARE(*p.damage(view(), 7, {before[0]}, kIdentity, nullptr),
                 glm::ivec4(60 - pad, 60 - pad, 70 + pad, 70 + pad));
        after = before;
        after.push_back(surface(3, {80, 5, 90, 15}));
        QCOMPARE(*p.damage(view(), 7, after, kIdentity, nullptr),
                 glm::ivec4(80 - pad, 5 - pad, std::min(90 + pad, kSide), 15 + pad));
    }

    void wholeWhereItCannotBound() {
        PartialFrames p;
        const std::vector<SurfaceFootprint> before{surface(1, {10, 10, 20, 20})};
        p.remember(Camera{}, FrameCamera{}, view(), 7, before, nullptr, {}, true);
        // Another frame wrote the pre-pass data since.
        QVERIFY(!p.damage(view(), 8, before, kIdentity, nullptr));
        // Another option.
        PartialFrameView other = view();
        other.options.pixelTolerance = 1.0;
        QVERIFY(!p.damage(other, 7, before, kIdentity, nullptr));
        // A colour map's range moved.
        other = view();
        other.analysisRange.high = 2.0;
        QVERIFY(!p.damage(other, 7, before, kIdentity, nullptr));
        // A changed surface that may draw anywhere.
        std::vector<SurfaceFootprint> after = before;
        after[0].revisions.points = 99;
        after[0].bounded = false;
        QVERIFY(!p.damage(view(), 7, after, kIdentity, nullptr));
        // More than half the view.
        after = before;
        after[0].revisions.points = 99;
        after[0].rect = {0, 0, 90, 90};
        QVERIFY(!p.damage(view(), 7, after, kIdentity, nullptr));
        p.forget();
        QVERIFY(!p.damage(view(), 7, before, kIdentity, nullptr));
    }

    void edgeBandsByRange() {
        auto bands = std::make_shared<EdgeBands>();
        bands->revision = bands->layoutRevision = 1;
        EdgeBandRange a, b;
        a.lo = glm::vec3(-0.8f, -0.8f, 0.0f), a.hi = glm::vec3(-0.6f, -0.6f, 0.0f);
        b.lo = glm::vec3(0.6f, 0.6f, 0.0f), b.hi = glm::vec3(0.8f, 0.8f, 0.0f);
        a.revision = b.revision = 1;
        bands->ranges = {a, b};
        PartialFrameView v = view();
        v.options.edgeBands = bands;
        PartialFrames p;
        const std::vector<SurfaceFootprint> surfaces{surface(1, {45, 45, 55, 55})};
        p.remember(Camera{}, FrameCamera{}, v, 7, surfaces, bands.get(), {}, true);
        // Range b re-made in place (a drag step): its old and new places.
        bands->revision = 2;
        bands->ranges[1].revision = 2;
        bands->ranges[1].lo = glm::vec3(0.4f, 0.6f, 0.0f);
        const int reach = PartialFrames::reachPixels(v.options);
        const auto r = p.damage(v, 7, surfaces, kIdentity, bands.get());
        QVERIFY(r);
        QCOMPARE(*r, glm::ivec4(70 - reach, 80 - reach, std::min(90 + reach, kSide),
                                std::min(90 + reach, kSide)));
        // Ranges changed in number: whole.
        bands->layoutRevision = 2;
        QVERIFY(!p.damage(v, 7, surfaces, kIdentity, bands.get()));
    }

    void keptPlanesWhileTheyHoldTheScene() {
        Camera cam;
        cam.eye = glm::dvec3(0.0, -10.0, 0.0);
        cam.target = glm::dvec3(0.0);
        glm::dvec3 box[2] = {glm::dvec3(-1.0), glm::dvec3(1.0)};
        const FrameCamera fc = frameCamera(cam, &box, 1.0);
        PartialFrames p;
        p.remember(cam, fc, view(), 7, {}, nullptr, {}, true);
        // The bounds a little larger: the planes (10 % beyond them) still hold them.
        glm::dvec3 grown[2] = {glm::dvec3(-1.05), glm::dvec3(1.05)};
        const std::optional<FrameCamera> kept =
            p.keptCamera(cam, QSize(kSide, kSide), QSize(kSide, kSide), &grown);
        QVERIFY(kept);
        QVERIFY(kept->projection == fc.projection);
        // Far past the far plane, another camera, another size: fresh planes.
        glm::dvec3 far[2] = {glm::dvec3(-1.0), glm::dvec3(1.0, 8.0, 1.0)};
        QVERIFY(!p.keptCamera(cam, QSize(kSide, kSide), QSize(kSide, kSide), &far));
        Camera moved = cam;
        moved.eye.x += 0.1;
        QVERIFY(!p.keptCamera(moved, QSize(kSide, kSide), QSize(kSide, kSide), &grown));
        QVERIFY(!p.keptCamera(cam, QSize(kSide, kSide / 2), QSize(kSide, kSide / 2), &grown));
    }
};

QTEST_GUILESS_MAIN(TestPartialFrameDamage)
#include "tst_partial_frame_damage.moc"
