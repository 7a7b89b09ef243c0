// The exact pass's data per surface stays within budget at scale, without GL: the bytes the pools
// hold per cell do not grow with the degree, outlines cost nothing until asked for, and a grown
// pool holds at most a quarter more than its data once it is large. Together: 10,000 faces of
// degree 10 x 5 at the paper's 30 x 30 fit the budget below.
#include "render/gpu_layout.h"
#include "render/gpu_pool.h"

#include <QtTest/QtTest>

using namespace kw;

namespace {

/// A Bezier patch of degree (p, q): (p + 1) x (q + 1) points on a gently curved sheet.
NurbsSurface bezier(int p, int q) {
    NurbsSurface s;
    s.degreeU = p, s.degreeV = q, s.countU = p + 1, s.countV = q + 1;
    s.knotsU.assign(size_t(p + 1), 0.0);
    s.knotsU.resize(size_t(2 * p + 2), 1.0);
    s.knotsV.assign(size_t(q + 1), 0.0);
    s.knotsV.resize(size_t(2 * q + 2), 1.0);
    for (int j = 0; j <= q; ++j)
        for (int i = 0; i <= p; ++i) {
            const double x = double(i) / p, y = double(j) / q;
            s.points.emplace_back(x, y, 0.2 * std::sin(3.0 * x) * std::cos(2.0 * y));
        }
    s.weights.assign(s.points.size(), 1.0);
    return s;
}

/// Bytes one surface takes in the pools as GpuScene uploads it for a frame without the
/// wireframe and without skirts (the paper's uniform mode): the per-surface part (control
/// texels, span tables) and the polygon's.
struct SurfaceBytes {
    std::int64_t perSurface = 0, polygon = 0;
};
SurfaceBytes surfaceBytes(const NurbsSurface& s, int parts) {
    const ParameterBox box{surfaceDomainU(s), surfaceDomainV(s)};
    const PolygonUpload u =
        buildPolygonUpload(s, box, PolygonCut{parts, parts, {}, {}}, false, false);
    const std::int64_t control =
        std::int64_t(packControlPoints(s, controlOrigin(s)).size() * sizeof(glm::vec4));
    const std::int64_t spans = std::int64_t((packSpanTable(s.knotsU, s.degreeU, s.countU).size() +
                                             packSpanTable(s.knotsV, s.degreeV, s.countV).size()) *
                                            sizeof(glm::vec4));
    return {control + spans, u.bytes()};
}

/// The capacity a pool reaches when `total` elements arrive in pieces of `piece`.
std::int64_t capacityAfter(std::int64_t total, std::int64_t piece, std::int64_t elementBytes) {
    std::int64_t capacity = 0;
    for (std::int64_t used = piece; used <= total; used += piece)
        if (used > capacity)
            capacity = GpuPool::grownCapacity(capacity, used, elementBytes, std::int64_t(1) << 40);
    return capacity;
}

} // namespace

class TestGpuBudget : public QObject {
    Q_OBJECT
private Q_SLOTS:
    // Per-cell data is the polygon's: a vertex and six triangle indices a cell (32 + 24 bytes),
    // whatever the degree. What grows with the degree (control texels, span tables) is per
    // surface: the same at 10 x 10 as at 30 x 30.
    void perCellBytesDoNotGrowWithDegree() {
        const SurfaceBytes low = surfaceBytes(bezier(3, 3), 30);
        const SurfaceBytes high = surfaceBytes(bezier(10, 5), 30);
        QCOMPARE(high.polygon, low.polygon);
        QVERIFY(high.perSurface > low.perSurface);
        QCOMPARE(surfaceBytes(bezier(10, 5), 10).perSurface, high.perSurface);
        QVERIFY2(high.polygon <= 900 * 64,
                 qPrintable(QStringLiteral("%1 bytes for 900 cells").arg(high.polygon)));
    }

    // The wireframe's outline indices (8 a cell) are not uploaded for frames that do not draw it.
    void outlinesOnlyWhenAsked() {
        const NurbsSurface s = bezier(10, 5);
        const ParameterBox box{surfaceDomainU(s), surfaceDomainV(s)};
        const PolygonCut cut{30, 30, {}, {}};
        const PolygonUpload without = buildPolygonUpload(s, box, cut, false, false);
        const PolygonUpload with = buildPolygonUpload(s, box, cut, false, true);
        QVERIFY(without.outlines.empty());
        QCOMPARE(with.outlines.size(), size_t(900 * 8));
        QCOMPARE(with.bytes() - without.bytes(), std::int64_t(900 * 8 * sizeof(unsigned)));
        QCOMPARE(with.triangles, without.triangles);
    }

    // Growth: doubling while small, then a quarter at a time, never below the need nor past the
    // limit (then below the need: the caller reports it).
    void poolGrowth() {
        const std::int64_t mib = std::int64_t(1) << 20;
        QCOMPARE(GpuPool::grownCapacity(0, 1, 4, 1 << 30), GpuPool::kMinElements);
        QCOMPARE(GpuPool::grownCapacity(4096, 4097, 4, 1 << 30), std::int64_t(8192));
        const std::int64_t big = 256 * mib / 4; // elements of 4 bytes
        const std::int64_t grown = GpuPool::grownCapacity(big, big + 1, 4, std::int64_t(1) << 40);
        QVERIFY(grown > big && grown <= big + big / 4);
        QCOMPARE(GpuPool::grownCapacity(big, big + 1, 4, 256 * mib + 4), big + 1);
        QVERIFY(GpuPool::grownCapacity(big, 2 * big, 4, 300 * mib) < 2 * big);
        // A large pool filled piece by piece holds at most a quarter more than its data.
        const std::int64_t total = 300 * mib / 32, capacity = capacityAfter(total, 961, 32);
        QVERIFY2(capacity >= total && capacity * 4 <= total * 5,
                 qPrintable(QStringLiteral("%1 elements for %2").arg(capacity).arg(total)));
    }

    // The scale target: 10,000 faces of degree 10 x 5 at 30 x 30 in the uniform mode hold at
    // most 768 MiB of pool memory, growth slack included (it was 1.3 GiB with the outlines
    // always uploaded and pools doubling).
    void tenThousandHighDegreeFacesFitTheBudget() {
        const NurbsSurface s = bezier(10, 5);
        const ParameterBox box{surfaceDomainU(s), surfaceDomainV(s)};
        const PolygonUpload u =
            buildPolygonUpload(s, box, PolygonCut{30, 30, {}, {}}, false, false);
        const std::int64_t faces = 10000;
        std::int64_t bytes = 0;
        bytes += capacityAfter(faces * std::int64_t(u.polygon.vertices.size()),
                               std::int64_t(u.polygon.vertices.size()), sizeof(BaseVertex)) *
                 std::int64_t(sizeof(BaseVertex));
        bytes += capacityAfter(faces * std::int64_t(u.triangles.size()),
                               std::int64_t(u.triangles.size()), sizeof(unsigned)) *
                 std::int64_t(sizeof(unsigned));
        if (!u.outlines.empty())
            bytes += capacityAfter(faces * std::int64_t(u.outlines.size()),
                                   std::int64_t(u.outlines.size()), sizeof(unsigned)) *
                     std::int64_t(sizeof(unsigned));
        const std::int64_t texels = surfaceBytes(s, 30).perSurface;
        bytes += capacityAfter(faces * texels / 16, texels / 16, 16) * 16;
        const std::int64_t budget = std::int64_t(768) << 20;
        QVERIFY2(bytes <= budget, qPrintable(QStringLiteral("%1 MiB of pools for 10,000 faces")
                                                 .arg(double(bytes) / (1 << 20), 0, 'f', 0)));
    }
};

QTEST_APPLESS_MAIN(TestGpuBudget)
#include "tst_gpu_budget.moc"
