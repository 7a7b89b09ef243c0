// The section split's cell classes without GL (render/section_cells.h): every cell's bounds
// hold the exact surface over it; a cell called kept has every exact point of it and of its
// neighbours on the kept side of every plane, by more than the margin; one called removed has
// every point on a removed side; a plane through the middle of a surface leaves cells of all
// three classes; without bounds for its cells nothing is classified.
#include "model/nurbs/nurbs_shapes.h"
#include "render/adaptive_partitions.h"
#include "render/section_cells.h"
#include "render_test_util.h"

#include <QtTest>

using namespace kw;

namespace {

/// The camera of these checks: looking at the origin from (0, -8, 3), 1024 pixels high.
ScreenScale testScale() {
    ScreenScale s;
    s.eye = glm::dvec3(0.0, -8.0, 3.0);
    s.forward = glm::normalize(-s.eye);
    s.focalPixels = 512.0 / std::tan(glm::radians(20.0));
    s.tanHalfDiagonal = std::tan(glm::radians(20.0)) * std::sqrt(2.0);
    s.nearDepth = 0.01;
    return s;
}

} // namespace

class TestSectionCells : public QObject {
    Q_OBJECT

private Q_SLOTS:
    void classesAreConservative_data() {
        QTest::addColumn<int>("shape"); // 0 sphere, 1 torus, 2 wavy rational patch
        QTest::addColumn<int>("parts");
        QTest::addRow("sphere 12") << 0 << 12;
        QTest::addRow("torus 24") << 1 << 24;
        QTest::addRow("wavy patch 16") << 2 << 16;
    }
    void classesAreConservative() {
        QFETCH(int, shape);
        QFETCH(int, parts);
        const NurbsSurface g =
            shape == 0   ? makeSphere(glm::dvec3(0.0), 1.0)
            : shape == 1 ? makeTorus(glm::dvec3(0.0), 1.5, 0.5)
                         : kwtest::wavyPatch(3, 2, kwtest::clampedUniform(3, 7),
                                             kwtest::clampedUniform(2, 6));
        const BasePolygon poly = buildBasePolygon(g, parts, parts);
        const std::vector<SpanBound> spans = surfaceSpanBounds(g, 4);
        const std::vector<CellBox> boxes = polygonCellBoxes(g, poly, spans);
        QCOMPARE(boxes.size(), size_t(poly.cellCount()));
        const std::vector<SectionPlane> planes{
            SectionPlane{glm::dvec3(0.1, 0.0, 0.05), glm::dvec3(0.3, -1.0, 0.2), false},
            SectionPlane{glm::dvec3(0.0, 0.0, 0.4), glm::dvec3(0.0, 0.2, 1.0), false}};
        const double marginPixels = 3.0;
        const std::vector<CellSection> classes =
            sectionCellClasses(poly, boxes, planes, testScale(), marginPixels);
        QCOMPARE(classes.size(), boxes.size());
        int counts[3] = {0, 0, 0};
        const int cu = poly.cellsU();
        constexpr int kSamples = 6;
        for (int j = 0; j < poly.cellsV(); ++j)
            for (int i = 0; i < cu; ++i) {
                const CellSection c = classes[size_t(j * cu + i)];
                ++counts[int(c)];
                const CellBox& box = boxes[size_t(j * cu + i)];
                // Every sample of the cell's rectangle: inside its box, and on the side its
                // class says.
                for (int b = 0; b <= kSamples; ++b)
                    for (int a = 0; a <= kSamples; ++a) {
                        const double u = poly.breaksU[size_t(i)] +
                                         (poly.breaksU[size_t(i + 1)] - poly.breaksU[size_t(i)]) *
                                             a / kSamples;
                        const double v = poly.breaksV[size_t(j)] +
                                         (poly.breaksV[size_t(j + 1)] - poly.breaksV[size_t(j)]) *
                                             b / kSamples;
                        const glm::dvec3 p = surfacePoint(g, u, v);
                        const double slack = 1e-9 * (1.0 + glm::length(p));
                        QVERIFY2(glm::all(glm::greaterThanEqual(p, box.lo - slack)) &&
                                     glm::all(glm::lessThanEqual(p, box.hi + slack)),
                                 qPrintable(QStringLiteral("cell (%1, %2)").arg(i).arg(j)));
                        double beyond = -1e300; // the largest over the planes
                        for (const SectionPlane& s : planes)
                            beyond = std::max(beyond, glm::dot(p - s.position, s.removedSide()));
                        if (c == CellSection::Kept)
                            QVERIFY2(beyond < 0.0, qPrintable(QString::number(beyond)));
                        if (c == CellSection::Removed) {
                            bool removed = false;
                            for (const SectionPlane& s : planes)
                                removed = removed ||
                                          glm::dot(p - s.position, s.removedSide()) > 0.0;
                            QVERIFY(removed);
                        }
                    }
                // A kept cell's neighbours are kept or crossed, never removed: the margin and
                // the ring keep the Newton step's point on the kept side.
                if (c == CellSection::Kept)
                    for (int dj = -1; dj <= 1; ++dj)
                        for (int di = -1; di <= 1; ++di) {
                            const int ni = i + di, nj = j + dj;
                            if (ni >= 0 && nj >= 0 && ni < cu && nj < poly.cellsV())
                                QVERIFY(classes[size_t(nj * cu + ni)] != CellSection::Removed);
                        }
            }
        qInfo("%d kept, %d crossed, %d removed of %d cells", counts[0], counts[1], counts[2],
              poly.cellCount());
        QVERIFY(counts[0] > 0 && counts[1] > 0 && counts[2] > 0);
        // No planes: every cell kept. Bounds from another surface's spans: none.
        const std::vector<CellSection> none =
            sectionCellClasses(poly, boxes, {}, testScale(), marginPixels);
        QCOMPARE(int(std::count(none.begin(), none.end(), CellSection::Kept)), poly.cellCount());
        QVERIFY(sectionCellClasses(poly, {}, planes, testScale(), marginPixels).empty());
    }

    /// The margin is pixels at the cell's depth: a far view calls more cells crossed.
    void marginGrowsWithDistance() {
        const NurbsSurface g = makeSphere(glm::dvec3(0.0), 1.0);
        const BasePolygon poly = buildBasePolygon(g, 24, 24);
        const std::vector<CellBox> boxes = polygonCellBoxes(g, poly, surfaceSpanBounds(g, 4));
        const std::vector<SectionPlane> planes{
            SectionPlane{glm::dvec3(0.0), glm::dvec3(0.0, 0.0, 1.0), false}};
        ScreenScale nearBy = testScale(), far = testScale();
        far.eye *= 400.0;
        const auto crossed = [&](const ScreenScale& s) {
            const std::vector<CellSection> c = sectionCellClasses(poly, boxes, planes, s, 3.0);
            return std::count(c.begin(), c.end(), CellSection::Crossed);
        };
        QVERIFY2(crossed(far) > crossed(nearBy),
                 qPrintable(QStringLiteral("%1 vs %2").arg(crossed(far)).arg(crossed(nearBy))));
    }
};

QTEST_GUILESS_MAIN(TestSectionCells)
#include "tst_section_cells.moc"
