// A partial frame's damage tiles without GL (render/damage_tiles.h): the tiles a rectangle and a
// polygon's cells touch, and the rectangles covering a tile set, merged while cheap or too many.
#include "render/damage_tiles.h"

#include <QtTest>
#include <limits>
#include <set>

using namespace kw;

namespace {

/// A flat polygon of `cells` x `cells` cells over [lo, hi] in normalised device coordinates:
/// under the identity its cell (i, j) covers the window pixels it maps to.
BasePolygon flat(int cells, glm::vec2 lo, glm::vec2 hi) {
    BasePolygon p;
    for (int k = 0; k <= cells; ++k) {
        p.breaksU.push_back(double(k) / cells);
        p.breaksV.push_back(double(k) / cells);
    }
    p.spanU.assign(size_t(cells), 3);
    p.spanV.assign(size_t(cells), 3);
    for (int j = 0; j <= cells; ++j)
        for (int i = 0; i <= cells; ++i) {
            BaseVertex v{};
            const glm::vec2 t(float(i) / float(cells), float(j) / float(cells));
            v.position = glm::vec3(lo + (hi - lo) * t, 0.0f);
            p.vertices.push_back(v);
        }
    return p;
}

/// Whether the pixel (x, y) lies in one of `rects`.
bool covered(const std::vector<glm::ivec4>& rects, int x, int y) {
    for (const glm::ivec4& r : rects)
        if (x >= r.x && x < r.z && y >= r.y && y < r.w)
            return true;
    return false;
}

/// TileGrid::rects' merging as a scan of every pair per merge (O(n^3) in the runs): the
/// cheapest union, of two equal the first pair in order, while cheap enough or too many.
std::vector<glm::ivec4> mergedByScan(std::vector<glm::ivec4> out, int maxRects,
                                     std::int64_t mergePixels) {
    const auto united = [](const glm::ivec4& a, const glm::ivec4& b) {
        return glm::ivec4(glm::min(glm::ivec2(a), glm::ivec2(b)),
                          glm::max(glm::ivec2(a.z, a.w), glm::ivec2(b.z, b.w)));
    };
    while (out.size() > 1) {
        std::int64_t best = std::numeric_limits<std::int64_t>::max();
        size_t bi = 0, bj = 0;
        for (size_t i = 0; i < out.size(); ++i)
            for (size_t j = i + 1; j < out.size(); ++j) {
                const std::int64_t added =
                    rectPixels(united(out[i], out[j])) - rectPixels(out[i]) - rectPixels(out[j]);
                if (added < best) {
                    best = added;
                    bi = i;
                    bj = j;
                }
            }
        if (best > mergePixels && int(out.size()) <= std::max(maxRects, 1))
            break;
        out[bi] = united(out[bi], out[bj]);
        out.erase(out.begin() + std::ptrdiff_t(bj));
    }
    return out;
}

} // namespace

class TestDamageTiles : public QObject {
    Q_OBJECT

private Q_SLOTS:
    void rectTouchesItsTiles() {
        TileGrid g(glm::ivec2(100, 60), 16); // 7 x 4 tiles, the last ones clipped
        QCOMPARE(g.columns(), 7);
        QCOMPARE(g.rows(), 4);
        g.addRect({15, 0, 17, 1}); // across the first tile boundary: tiles 0 and 1
        QCOMPARE(g.tiles(), (std::vector<std::int32_t>{0, 1}));
        g.addRect({32, 32, 48, 48}); // exactly tile (2, 2): exclusive ends
        QCOMPARE(g.tiles(), (std::vector<std::int32_t>{0, 1, 16}));
        g.addRect({96, 48, 500, 500}); // clamped to the view: the corner tile only
        QVERIFY(g.has(6, 3));
        QCOMPARE(g.count(), 4);
        g.addRect({40, 40, 40, 50});   // empty
        g.addRect({-30, -30, -1, -1}); // off the view
        QCOMPARE(g.count(), 4);
        g.addTiles({27, 1000, -1}); // out of the grid: ignored
        QCOMPARE(g.count(), 4);
    }

    void runsAndMerges() {
        // An L of tiles: a column of three at x = 0 and a row to its right at the bottom.
        TileGrid g(glm::ivec2(160, 160), 10);
        for (int ty = 0; ty < 3; ++ty)
            g.addRect({0, ty * 10, 10, ty * 10 + 10});
        g.addRect({10, 0, 40, 10});
        // Unmerged: the bottom row's run (4 tiles) and the column's two tiles above it.
        const std::vector<glm::ivec4> runs = g.rects(64, 0);
        QCOMPARE(runs.size(), size_t(2));
        QVERIFY(runs[0] == glm::ivec4(0, 0, 40, 10));
        QVERIFY(runs[1] == glm::ivec4(0, 10, 10, 30));
        // Their union (4 x 3 tiles) adds 6 tiles (600 pixels): merged at 600, not at 599.
        QCOMPARE(g.rects(64, 599).size(), size_t(2));
        const std::vector<glm::ivec4> one = g.rects(64, 600);
        QCOMPARE(one.size(), size_t(1));
        QVERIFY(one[0] == glm::ivec4(0, 0, 40, 30));
        // Too many: merged whatever it adds.
        QCOMPARE(g.rects(1, 0).size(), size_t(1));
        // Clamped to the view: a tile at the edge of a 155-pixel view.
        TileGrid edge(glm::ivec2(155, 155), 10);
        edge.addRect({150, 150, 155, 155});
        QVERIFY(edge.rects(8, 0).front() == glm::ivec4(150, 150, 155, 155));
        QCOMPARE(rectPixels({0, 0, 3, 4}), std::int64_t(12));
        QCOMPARE(rectPixels({5, 0, 3, 4}), std::int64_t(0));
    }

    /// Random tile sets: the rectangles cover every marked tile and, unmerged, no other.
    void rectsCoverTheTiles() {
        std::uint32_t seed = 12345;
        const auto next = [&seed] {
            seed = seed * 1664525u + 1013904223u;
            return seed >> 8;
        };
        for (int round = 0; round < 20; ++round) {
            TileGrid g(glm::ivec2(200, 120), 16);
            for (int k = 0; k < 12; ++k)
                g.addTiles({std::int32_t(next() % std::uint32_t(g.columns() * g.rows()))});
            const std::vector<glm::ivec4> exact = g.rects(1000, 0);
            const std::vector<glm::ivec4> merged = g.rects(3, 2048);
            QVERIFY(merged.size() <= 3);
            for (int ty = 0; ty < g.rows(); ++ty)
                for (int tx = 0; tx < g.columns(); ++tx) {
                    const int x = tx * 16 + 7, y = ty * 16 + 7; // a pixel inside the tile
                    QCOMPARE(covered(exact, x, y), g.has(tx, ty));
                    if (g.has(tx, ty))
                        QVERIFY(covered(merged, x, y));
                }
        }
    }

    /// The queue of pair costs merges as a scan of every pair would, ties and overlaps
    /// (merged rectangles may overlap: a negative cost) included, on random tile sets.
    void mergesAsAScanOfPairs() {
        std::uint32_t seed = 777;
        const auto next = [&seed] {
            seed = seed * 1664525u + 1013904223u;
            return seed >> 8;
        };
        int merged = 0;
        for (int round = 0; round < 60; ++round) {
            TileGrid g(glm::ivec2(320, 240), 8);
            const int marks = 5 + int(next() % 60u);
            for (int k = 0; k < marks; ++k) {
                const int x = int(next() % 320u), y = int(next() % 240u);
                g.addRect({x, y, x + int(next() % 40u), y + int(next() % 24u)});
            }
            const std::vector<glm::ivec4> runs = g.rects(1 << 20, -(1 << 30));
            const int maxRects = 1 + int(next() % 8u);
            const std::int64_t mergePixels = std::int64_t(next() % 4096u) - 256;
            const std::vector<glm::ivec4> got = g.rects(maxRects, mergePixels);
            const std::vector<glm::ivec4> want = mergedByScan(runs, maxRects, mergePixels);
            QCOMPARE(got.size(), want.size());
            for (size_t k = 0; k < got.size(); ++k)
                QVERIFY2(got[k] == want[k],
                         qPrintable(QStringLiteral("round %1, rectangle %2").arg(round).arg(k)));
            merged += int(runs.size() - got.size());
        }
        QVERIFY2(merged > 100, qPrintable(QString::number(merged)));
    }

    /// A polygon's cells: the tiles their rectangles grown by the pad touch, not all of its
    /// rectangle's (a diagonal strip of cells leaves most of its box out).
    void cellTilesOfAPolygon() {
        const glm::ivec2 view(160, 160);
        TileGrid g(view, 16);
        // A 4 x 4 polygon over pixels [40, 120) in both directions: cells of 20 pixels.
        const BasePolygon square = flat(4, glm::vec2(-0.5f), glm::vec2(0.5f));
        const std::optional<std::vector<std::int32_t>> all =
            cellTiles(square, glm::mat4(1.0f), g, 0);
        QVERIFY(all);
        TileGrid expect(view, 16);
        expect.addRect({40, 40, 120, 120});
        QCOMPARE(*all, expect.tiles());
        // Grown by 9 pixels: [31, 129), one more tile on every side.
        TileGrid grown(view, 16);
        grown.addRect({31, 31, 129, 129});
        QCOMPARE(*cellTiles(square, glm::mat4(1.0f), g, 9), grown.tiles());
        // Sheared into a diagonal strip: row j of cells moves right by j cells, so the
        // polygon's box is twice as wide as the strip.
        BasePolygon strip = square;
        for (int j = 0; j <= 4; ++j)
            for (int i = 0; i <= 4; ++i)
                strip.vertices[size_t(j * 5 + i)].position.x += 0.25f * float(j);
        const std::vector<std::int32_t> tiles = *cellTiles(strip, glm::mat4(1.0f), g, 0);
        TileGrid box(view, 16);
        box.addRect({40, 40, 160, 120});
        QVERIFY2(tiles.size() < size_t(box.count()),
                 qPrintable(QStringLiteral("%1 of %2").arg(tiles.size()).arg(box.count())));
        // Every cell's own rectangle still lies in its tiles.
        TileGrid marked(view, 16);
        marked.addTiles(tiles);
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) {
                const int x0 = 40 + 20 * i + 20 * j, y0 = 40 + 20 * j;
                for (int y = y0; y < y0 + 20; y += 19)
                    for (int x = x0; x < std::min(x0 + 40, 160); x += 13)
                        if (x < 40 + 20 * (i + 1) + 20 * (j + 1))
                            QVERIFY(marked.has(x / 16, y / 16));
            }
        // A node behind the eye: unknown (the rectangle's tiles are taken instead).
        const glm::mat4 behind(glm::vec4(1, 0, 0, 0), glm::vec4(0, 1, 0, 0), glm::vec4(0, 0, 1, 0),
                               glm::vec4(0, 0, 0, -1));
        QVERIFY(!cellTiles(square, behind, g, 0));
        QVERIFY(!cellTiles(BasePolygon{}, glm::mat4(1.0f), g, 0));
    }
};

QTEST_GUILESS_MAIN(TestDamageTiles)
#include "tst_damage_tiles.moc"
