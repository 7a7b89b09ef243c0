// Render data layouts without GL: span tables reproduce the kernel's basis functions, base
// polygon cells lie in one knot span each, partial vertex updates equal a rebuild,
// the pixels-per-cell estimate behind the per-cell gather choice.
#include "model/nurbs/nurbs_shapes.h"
#include "render/exact_planner.h"
#include "render/gpu_layout.h"
#include "render/gpu_pool.h"
#include "render_test_util.h"

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>

using namespace kw;

namespace {

// The algorithm of shaders/basis.glsl, in double, reading a packSpanTable row.
void basisFromTable(const std::vector<glm::vec4>& table, int p, int row, double u, double* N,
                    double* dN) {
    const int texels = spanTableTexels(p);
    std::vector<double> t;
    for (int x = 0; x < texels; ++x)
        for (int c = 0; c < 4; ++c)
            t.push_back(table[size_t(row * texels + x)][c]);
    std::vector<double> left(size_t(p) + 1), right(size_t(p) + 1), lower(size_t(p) + 1);
    for (int j = 1; j <= p; ++j) {
        left[size_t(j)] = u - t[size_t(j - 1)];
        right[size_t(j)] = t[size_t(p + j - 1)] - u;
    }
    N[0] = 1.0;
    int inv = 2 * p;
    for (int j = 1; j <= p; ++j) {
        double saved = 0.0;
        for (int r = 0; r < j; ++r) {
            if (j == p)
                lower[size_t(r)] = N[r];
            const double temp = N[r] * t[size_t(inv + r)];
            N[r] = saved + right[size_t(r + 1)] * temp;
            saved = left[size_t(j - r)] * temp;
        }
        N[j] = saved;
        if (j < p)
            inv += j;
    }
    dN[0] = -p * lower[0] * t[size_t(inv)];
    for (int r = 1; r < p; ++r)
        dN[r] = p * (lower[size_t(r - 1)] * t[size_t(inv + r - 1)] -
                     lower[size_t(r)] * t[size_t(inv + r)]);
    dN[p] = p * lower[size_t(p - 1)] * t[size_t(inv + p - 1)];
}

} // namespace

class TestRenderLayout : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void spanTableReproducesBasis_data() {
        QTest::addColumn<int>("degree");
        QTest::addColumn<std::vector<double>>("knots");
        for (int p = 1; p <= kMaxDegree; ++p)
            QTest::addRow("uniform p=%d", p) << p << kwtest::clampedUniform(p, p + 4);
        QTest::newRow("multiplicities p=3")
            << 3 << std::vector<double>{0, 0, 0, 0, 0.2, 0.2, 0.5, 0.5, 0.5, 0.9, 1, 1, 1, 1};
        QTest::newRow("non-uniform p=2 scaled domain")
            << 2 << std::vector<double>{-3, -3, -3, -1, 0.5, 0.5, 4, 4, 4};
    }
    void spanTableReproducesBasis() {
        QFETCH(int, degree);
        QFETCH(std::vector<double>, knots);
        const int count = int(knots.size()) - degree - 1;
        QVERIFY(checkKnotVector(knots, degree, count).has_value());
        const std::vector<glm::vec4> table = packSpanTable(knots, degree, count);
        QCOMPARE(int(table.size()), (count - degree) * spanTableTexels(degree));
        const Interval dom = knotDomain(knots, degree);
        double N[kMaxDegree + 1], dN[kMaxDegree + 1], ref[2 * (kMaxDegree + 1)];
        for (int s = 0; s <= 200; ++s) {
            const double u = dom.first + (dom.last - dom.first) * s / 200.0;
            const int span = findSpan(degree, knots, u);
            basisFromTable(table, degree, span - degree, u, N, dN);
            basisFunctionDerivatives(span, u, degree, 1, knots, ref);
            const double scale = dom.last - dom.first;
            for (int k = 0; k <= degree; ++k) {
                // float knots and reciprocals: relative accuracy ~1e-6
                QVERIFY2(std::abs(N[k] - ref[k]) < 1e-5, qPrintable(QString::number(u)));
                QVERIFY(std::abs(dN[k] - ref[degree + 1 + k]) * scale <
                        1e-4 * (degree + 1) * degree);
            }
        }
    }

    void cellsLieInOneSpan() {
        const NurbsSurface s = kwtest::wavyPatch(
            3, 2, {0, 0, 0, 0, 0.3, 0.3, 0.3, 0.61, 1, 1, 1, 1}, {0, 0, 0, 0.5, 1, 1, 1});
        const BasePolygon poly = buildBasePolygon(s, 7, 3);
        // 7 uniform cells + the distinct interior knots 0.3 and 0.61 (0.3 and 0.61 are not on
        // the uniform grid); v: 3 cells + 0.5.
        QCOMPARE(poly.cellsU(), 9);
        QCOMPARE(poly.cellsV(), 4);
        for (double k : {0.3, 0.61})
            QVERIFY(std::find(poly.breaksU.begin(), poly.breaksU.end(), k) != poly.breaksU.end());
        for (int c = 0; c < poly.cellsU(); ++c) {
            const int k = poly.spanU[size_t(c)];
            QVERIFY(s.knotsU[size_t(k)] <= poly.breaksU[size_t(c)]);
            QVERIFY(poly.breaksU[size_t(c + 1)] <= s.knotsU[size_t(k + 1)]);
        }
        QCOMPARE(int(poly.vertices.size()), (poly.cellsU() + 1) * (poly.cellsV() + 1));
        for (const BaseVertex& v : poly.vertices) {
            const glm::dvec3 p = surfacePoint(s, v.uv.x, v.uv.y);
            QVERIFY(glm::length(glm::dvec3(v.position) - p) < 1e-5);
            QVERIFY(v.spanScale > 0.0f);
        }
        // The first (provoking) vertex of every triangle carries a span containing the
        // whole triangle.
        const std::vector<unsigned> tri = basePolygonTriangles(poly);
        QCOMPARE(int(tri.size()), poly.cellCount() * 6);
        for (size_t t = 0; t < tri.size(); t += 3) {
            const glm::ivec2 span = poly.vertices[tri[t]].span;
            for (size_t k = 0; k < 3; ++k) {
                const glm::vec2 uv = poly.vertices[tri[t + k]].uv;
                QVERIFY(float(s.knotsU[size_t(span.x)]) <= uv.x &&
                        uv.x <= float(s.knotsU[size_t(span.x + 1)]));
                QVERIFY(float(s.knotsV[size_t(span.y)]) <= uv.y &&
                        uv.y <= float(s.knotsV[size_t(span.y + 1)]));
            }
        }
    }

    void partialUpdateEqualsRebuild() {
        NurbsSurface s =
            kwtest::wavyPatch(3, 3, kwtest::clampedUniform(3, 9), kwtest::clampedUniform(3, 8));
        BasePolygon poly = buildBasePolygon(s, 20, 20);
        s.points[size_t(s.index(4, 3))] += glm::dvec3(0.1, -0.2, 0.7);
        int first = -1, last = -1;
        QVERIFY(updateBasePolygon(poly, s, 4, 4, 3, 3, first, last));
        QVERIFY(first >= 0 && last < int(poly.vertices.size()) && first <= last);
        QVERIFY(last - first + 1 < int(poly.vertices.size())); // local support: not all
        const BasePolygon fresh = buildBasePolygon(s, 20, 20);
        for (size_t k = 0; k < poly.vertices.size(); ++k) {
            QVERIFY(glm::length(poly.vertices[k].position - fresh.vertices[k].position) < 1e-6f);
            QCOMPARE(poly.vertices[k].spanScale, fresh.vertices[k].spanScale);
        }
    }

    /// Silhouette fins: one quad per polygon edge whose triangles face opposite ways, around
    /// the edge on screen; none on a patch whose triangles all face the eye.
    void finsFollowTheSilhouette() {
        const NurbsSurface sphere = makeSphere({0, 0, 0}, 1.0);
        const BasePolygon poly = buildBasePolygon(sphere, 16, 8);
        const glm::dvec3 eye(0.3, -5.0, 0.8);
        const glm::ivec2 viewport(512, 512);
        const glm::dmat4 vp = glm::perspective(glm::radians(40.0), 1.0, 0.1, 100.0) *
                              glm::lookAt(eye, glm::dvec3(0.0), glm::dvec3(0, 0, 1));
        const auto window = [&](const glm::vec3& p) {
            return kwtest::windowPixels(vp, glm::dvec3(p), glm::dvec2(viewport));
        };
        std::vector<SkirtVertex> vertices;
        std::vector<unsigned> indices;
        const double pixels = 1.5;
        buildFins(poly, vp, eye, viewport, pixels, vertices, indices);
        QCOMPARE(vertices.size() % 4, size_t(0));
        QCOMPARE(indices.size(), vertices.size() / 4 * 6);
        // The outline of 16 x 8 cells around the sphere: at least one fin per column.
        QVERIFY2(vertices.size() / 4 >= 16, qPrintable(QString::number(vertices.size() / 4)));
        for (size_t f = 0; f < vertices.size(); f += 4) {
            const SkirtVertex &aUp = vertices[f], &aDown = vertices[f + 1];
            const SkirtVertex &bUp = vertices[f + 2], &bDown = vertices[f + 3];
            QCOMPARE(indices[f / 4 * 6], unsigned(f));
            for (const SkirtVertex* v : {&aUp, &aDown, &bUp, &bDown})
                QCOMPARE(v->outward, glm::vec2(0.0f));
            QCOMPARE(aUp.base.uv, aDown.base.uv);
            QCOMPARE(bUp.base.uv, bDown.base.uv);
            // The edge's ends lie where the view grazes the sphere: the normal (the point,
            // on a unit sphere at the origin) nearly square to the ray (cells of 22.5 deg).
            for (const SkirtVertex* v : {&aUp, &bUp}) {
                const glm::dvec3 p = surfacePoint(sphere, v->base.uv.x, v->base.uv.y);
                QVERIFY(std::abs(glm::dot(glm::normalize(p - eye), glm::normalize(p))) < 0.45);
            }
            // 2 x pixels apart across the edge, and pushed `pixels` past each end.
            QVERIFY(std::abs(glm::length(window(aUp.base.position) - window(aDown.base.position)) -
                             2.0 * pixels) < 1e-2);
            const glm::dvec2 a = 0.5 * (window(aUp.base.position) + window(aDown.base.position));
            const glm::dvec2 b = 0.5 * (window(bUp.base.position) + window(bDown.base.position));
            const glm::dvec3 pa = surfacePoint(sphere, aUp.base.uv.x, aUp.base.uv.y);
            const glm::dvec3 pb = surfacePoint(sphere, bUp.base.uv.x, bUp.base.uv.y);
            const double edge = glm::length(window(glm::vec3(pb)) - window(glm::vec3(pa)));
            QVERIFY(std::abs(glm::length(b - a) - (edge + 2.0 * pixels)) < 1e-2);
        }
        // A flat patch seen from above: every triangle faces the eye, no fin.
        NurbsSurface flat =
            kwtest::wavyPatch(3, 2, kwtest::clampedUniform(3, 6), kwtest::clampedUniform(2, 4));
        for (glm::dvec3& p : flat.points)
            p.z = 0.0;
        vertices.clear();
        indices.clear();
        buildFins(buildBasePolygon(flat, 9, 7),
                  glm::perspective(glm::radians(40.0), 1.0, 0.1, 100.0) *
                      glm::lookAt(glm::dvec3(0.5, 0.4, 3.0), glm::dvec3(0.5, 0.5, 0.0),
                                  glm::dvec3(0, 1, 0)),
                  glm::dvec3(0.5, 0.4, 3.0), viewport, pixels, vertices, indices);
        QVERIFY(vertices.empty() && indices.empty());
    }

    /// The skirt: one quad per boundary segment of the outline, inner nodes
    /// unmarked and outer ones marked with the side's outward direction, both triangles of a
    /// quad starting at a vertex whose span holds the whole segment.
    void skirtRingsTheOutline() {
        const NurbsSurface s = kwtest::wavyPatch(
            3, 2, {0, 0, 0, 0, 0.3, 0.3, 0.3, 0.61, 1, 1, 1, 1}, {0, 0, 0, 0.5, 1, 1, 1});
        const BasePolygon poly = buildBasePolygon(s, 7, 3);
        std::vector<SkirtVertex> vertices;
        std::vector<unsigned> indices;
        buildSkirt(poly, vertices, indices);
        const int nu = poly.nodesU(), nv = poly.cellsV() + 1;
        QCOMPARE(int(vertices.size()), 2 * (2 * nu + 2 * nv));
        const int segments = 2 * poly.cellsU() + 2 * poly.cellsV();
        QCOMPARE(int(indices.size()), 6 * segments + 4 * 3);
        const glm::vec2 lo(0.0f), hi(1.0f);
        int perSide[4] = {0, 0, 0, 0};
        const size_t quads = size_t(6 * segments);
        for (size_t t = 0; t < quads; t += 6) {
            // a, b, bOut, a, bOut, aOut: a and b inner, the outer copies at the same nodes.
            const SkirtVertex& a = vertices[indices[t]];
            const SkirtVertex& b = vertices[indices[t + 1]];
            const SkirtVertex& bOut = vertices[indices[t + 2]];
            const SkirtVertex& aOut = vertices[indices[t + 5]];
            QCOMPARE(indices[t + 3], indices[t]);
            QCOMPARE(indices[t + 4], indices[t + 2]);
            QCOMPARE(a.outward, glm::vec2(0.0f));
            QCOMPARE(b.outward, glm::vec2(0.0f));
            QVERIFY(aOut.outward != glm::vec2(0.0f));
            QCOMPARE(aOut.outward, bOut.outward);
            QCOMPARE(aOut.base.uv, a.base.uv);
            QCOMPARE(bOut.base.uv, b.base.uv);
            QCOMPARE(aOut.base.position, a.base.position);
            QCOMPARE(aOut.base.span, a.base.span);
            // On the side the direction points out of, and along it.
            const glm::vec2 n = aOut.outward;
            const float edge = n.x + n.y > 0.0f ? 1.0f : 0.0f;
            const float across = n.x != 0.0f ? a.base.uv.x : a.base.uv.y;
            QCOMPARE(across, edge);
            QCOMPARE(n.x != 0.0f ? b.base.uv.x : b.base.uv.y, edge);
            const int side = n.y < 0.0f ? 0 : n.x > 0.0f ? 1 : n.y > 0.0f ? 2 : 3;
            ++perSide[side];
            // The provoking vertex's span holds the whole segment (its cell borders it).
            const glm::ivec2 span = a.base.span;
            for (const SkirtVertex* v : {&a, &b}) {
                QVERIFY(float(s.knotsU[size_t(span.x)]) <= v->base.uv.x &&
                        v->base.uv.x <= float(s.knotsU[size_t(span.x + 1)]));
                QVERIFY(float(s.knotsV[size_t(span.y)]) <= v->base.uv.y &&
                        v->base.uv.y <= float(s.knotsV[size_t(span.y + 1)]));
            }
            QVERIFY(glm::all(glm::greaterThanEqual(a.base.uv, lo)) &&
                    glm::all(glm::lessThanEqual(a.base.uv, hi)));
        }
        QCOMPARE(perSide[0], poly.cellsU());
        QCOMPARE(perSide[1], poly.cellsV());
        QCOMPARE(perSide[2], poly.cellsU());
        QCOMPARE(perSide[3], poly.cellsV());
        // The corners: from the corner's inner copy to two outer copies of it pushed across the
        // two sides meeting there; every corner of the domain once.
        std::vector<glm::vec2> cornersSeen;
        for (size_t t = quads; t < indices.size(); t += 3) {
            const SkirtVertex& c = vertices[indices[t]];
            const SkirtVertex& a = vertices[indices[t + 1]];
            const SkirtVertex& b = vertices[indices[t + 2]];
            QCOMPARE(c.outward, glm::vec2(0.0f));
            QVERIFY(a.outward != glm::vec2(0.0f) && b.outward != glm::vec2(0.0f));
            QCOMPARE(glm::dot(a.outward, b.outward), 0.0f);
            QCOMPARE(a.base.uv, c.base.uv);
            QCOMPARE(b.base.uv, c.base.uv);
            QVERIFY(c.base.uv.x == 0.0f || c.base.uv.x == 1.0f);
            QVERIFY(c.base.uv.y == 0.0f || c.base.uv.y == 1.0f);
            // Each outward direction points away from the corner's side of the domain.
            for (const SkirtVertex* o : {&a, &b}) {
                const glm::vec2 n = o->outward;
                QCOMPARE(n.x != 0.0f ? c.base.uv.x : c.base.uv.y, n.x + n.y > 0.0f ? 1.0f : 0.0f);
            }
            cornersSeen.push_back(c.base.uv);
        }
        QCOMPARE(int(cornersSeen.size()), 4);
        for (const glm::vec2 corner :
             {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)})
            QVERIFY(std::count(cornersSeen.begin(), cornersSeen.end(), corner) == 1);
        // A moved node moves its skirt copies (skirtVertices after updateBasePolygon).
        NurbsSurface moved = s;
        moved.points[0] += glm::dvec3(0.0, 0.0, 0.5);
        BasePolygon updated = poly;
        int first = -1, last = -1;
        QVERIFY(updateBasePolygon(updated, moved, 0, 0, 0, 0, first, last));
        const std::vector<SkirtVertex> now = skirtVertices(updated);
        QCOMPARE(now.size(), vertices.size());
        QVERIFY(now[0].base.position != vertices[0].base.position); // corner (0, 0)
        QCOMPARE(now[0].base.position, updated.vertices[0].position);
    }

    void controlPointsAreHomogeneousAroundOrigin() {
        NurbsSurface s =
            kwtest::wavyPatch(2, 2, kwtest::clampedUniform(2, 4), kwtest::clampedUniform(2, 3));
        const glm::dvec3 o = controlOrigin(s);
        const std::vector<glm::vec4> t = packControlPoints(s, o);
        for (size_t k = 0; k < t.size(); ++k) {
            QCOMPARE(double(t[k].w), double(float(s.weights[k])));
            const glm::dvec3 back = glm::dvec3(t[k]) / double(t[k].w) + o;
            QVERIFY(glm::length(back - s.points[k]) < 1e-6);
        }
    }

    // The gather choice's estimate: projected control bounds (clamped to the viewport) per cell.
    void projectedPixelsPerCellFromControlBounds() {
        const NurbsSurface s =
            kwtest::wavyPatch(3, 3, kwtest::clampedUniform(3, 4), kwtest::clampedUniform(3, 5));
        SurfaceGpu g;
        g.origin = controlOrigin(s);
        g.control = packControlPoints(s, g.origin);
        g.polygon = buildBasePolygon(s, 10, 10);
        glm::dvec3 lo(1e300), hi(-1e300);
        for (const glm::dvec3& p : s.points) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        const glm::dvec3 size = hi - lo, centre = 0.5 * (lo + hi);
        const double scale = 1.0 / std::max(size.x, size.y); // box spans at most NDC [-0.5, 0.5]
        FrameCamera cam;
        cam.viewport = glm::ivec2(400, 300);
        cam.viewProjection = glm::mat4(glm::scale(glm::dmat4(1.0), glm::dvec3(scale)) *
                                       glm::translate(glm::dmat4(1.0), -centre));
        const double expected =
            (size.x * scale * 200.0) * (size.y * scale * 150.0) / double(g.polygon.cellCount());
        const double got = ExactPlanner::projectedPixelsPerCell(g, cam);
        QVERIFY2(std::abs(got - expected) < 1e-3 * expected, qPrintable(QString::number(got)));
        // Eight times the scale: the box is clamped to the viewport (4 NDC units squared).
        cam.viewProjection = glm::mat4(glm::scale(glm::dmat4(1.0), glm::dvec3(8.0 * scale)) *
                                       glm::translate(glm::dmat4(1.0), -centre));
        QVERIFY(ExactPlanner::projectedPixelsPerCell(g, cam) <=
                400.0 * 300.0 / double(g.polygon.cellCount()) * (1.0 + 1e-6));
        // A corner behind the eye (clip w <= 0): treated as large.
        cam.viewProjection = glm::mat4(1.0f);
        cam.viewProjection[3][3] = -1.0f;
        QVERIFY(std::isinf(ExactPlanner::projectedPixelsPerCell(g, cam)));
        // Nothing uploaded: no estimate.
        QCOMPARE(ExactPlanner::projectedPixelsPerCell(SurfaceGpu{}, cam), 0.0);
    }

    // The shared scene buffers' ranges: first fit, neighbours merged, the end lowered when the
    // top range goes, no overlap between live ranges.
    void rangeAllocatorReusesFreedRanges() {
        RangeAllocator a;
        const std::int64_t r0 = a.allocate(10), r1 = a.allocate(5), r2 = a.allocate(7);
        QCOMPARE(r0, 0);
        QCOMPARE(r1, 10);
        QCOMPARE(r2, 15);
        QCOMPARE(a.end(), 22);
        a.free(r1, 5);
        QCOMPARE(a.allocate(6), 22); // does not fit the hole of 5
        QCOMPARE(a.allocate(3), 10); // first fit
        QCOMPARE(a.allocate(2), 13); // the rest of the hole
        QCOMPARE(a.used(), 28);
        a.free(r0, 10);
        a.free(10, 3); // merges with [0, 10)
        QCOMPARE(a.allocate(13), 0);
        a.free(0, 13);
        a.free(13, 2); // [0, 15) free again
        a.free(22, 6); // the top range: end falls to 22, then the hole below it stays
        QCOMPARE(a.end(), 22);
        a.free(r2, 7); // everything free: end falls through the merged hole to 0
        QCOMPARE(a.end(), 0);
        QCOMPARE(a.used(), 0);
        // Random churn: live ranges never overlap and stay below end().
        std::vector<std::pair<std::int64_t, std::int64_t>> live;
        std::uint32_t seed = 12345;
        auto next = [&seed]() {
            return seed = seed * 1664525u + 1013904223u;
        };
        for (int step = 0; step < 2000; ++step) {
            if (!live.empty() && next() % 3 == 0) {
                const size_t k = next() % live.size();
                a.free(live[k].first, live[k].second);
                live.erase(live.begin() + std::ptrdiff_t(k));
            } else {
                const std::int64_t n = 1 + next() % 40;
                live.emplace_back(a.allocate(n), n);
            }
            std::vector<std::pair<std::int64_t, std::int64_t>> sorted = live;
            std::sort(sorted.begin(), sorted.end());
            std::int64_t used = 0;
            for (size_t k = 0; k < sorted.size(); ++k) {
                used += sorted[k].second;
                QVERIFY(sorted[k].first + sorted[k].second <= a.end());
                if (k > 0)
                    QVERIFY(sorted[k - 1].first + sorted[k - 1].second <= sorted[k].first);
            }
            QCOMPARE(a.used(), used);
        }
    }
};

QTEST_MAIN(TestRenderLayout)
#include "tst_render_layout.moc"
