// Test fixtures for document, item model and command tests: valid surfaces, trim loops, scenes.
#pragma once

#include "model/document/scene.h"

#include <QString>
#include <algorithm>

namespace kw::test {

/// Clamped uniform knot vector for `count` points of `degree` on [0, 1].
inline std::vector<double> clampedKnots(int degree, int count) {
    std::vector<double> k(size_t(degree + 1), 0.0);
    const int interior = count - degree - 1;
    for (int i = 1; i <= interior; ++i)
        k.push_back(double(i) / (interior + 1));
    k.insert(k.end(), size_t(degree + 1), 1.0);
    return k;
}

/// A bicubic (degree clamped to count - 1) patch over the grid [0, nu-1] x [0, nv-1] with a
/// bump whose height is `height`, shifted along x by `offset`; weights 1.
inline NurbsSurface patch(int nu = 4, int nv = 4, double offset = 0.0, double height = 1.0) {
    NurbsSurface s;
    s.degreeU = std::min(3, nu - 1);
    s.degreeV = std::min(3, nv - 1);
    s.countU = nu;
    s.countV = nv;
    s.knotsU = clampedKnots(s.degreeU, nu);
    s.knotsV = clampedKnots(s.degreeV, nv);
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const double bump = (i > 0 && i < nu - 1 && j > 0 && j < nv - 1) ? height : 0.0;
            s.points.emplace_back(offset + i, j, bump);
        }
    s.weights.assign(size_t(nu * nv), 1.0);
    return s;
}

/// A degree-1 segment from a to b.
inline NurbsCurve2 segment(glm::dvec2 a, glm::dvec2 b) {
    NurbsCurve2 c;
    c.degree = 1;
    c.knots = {0, 0, 1, 1};
    c.points = {a, b};
    c.weights = {1, 1};
    return c;
}

/// A closed rectangle [u0, u1] x [v0, v1] of four segments, plus (if `withArc`) a quadratic
/// replacing the top edge so loops have curves of different degrees.
inline TrimLoop rectLoop(TrimLoopId id, double u0, double v0, double u1, double v1,
                         bool withArc = false) {
    TrimLoop l;
    l.id = id;
    l.curves.push_back(segment({u0, v0}, {u1, v0}));
    l.curves.push_back(segment({u1, v0}, {u1, v1}));
    if (withArc) {
        NurbsCurve2 arc;
        arc.degree = 2;
        arc.knots = {0, 0, 0, 1, 1, 1};
        arc.points = {{u1, v1}, {0.5 * (u0 + u1), v1 + 0.1 * (v1 - v0)}, {u0, v1}};
        arc.weights = {1, 0.8, 1};
        l.curves.push_back(arc);
    } else {
        l.curves.push_back(segment({u1, v1}, {u0, v1}));
    }
    l.curves.push_back(segment({u0, v1}, {u0, v0}));
    return l;
}

inline Surface makeSurface(std::uint32_t id, const QString& name, NurbsSurface g) {
    Surface s;
    s.id = SurfaceId{id};
    s.name = name;
    s.geometry = std::move(g);
    return s;
}

/// Three surfaces (ids 1, 2, 3; 4x4, 5x4, 4x6) — the first with two trim loops (ids 10, 11),
/// the third with one (id 12). nextId 13.
inline Scene threeSurfaceScene() {
    Scene scene;
    Surface a = makeSurface(1, QStringLiteral("Alpha"), patch(4, 4));
    a.trims.push_back(rectLoop(TrimLoopId{10}, 0.1, 0.1, 0.9, 0.9));
    a.trims.push_back(rectLoop(TrimLoopId{11}, 0.3, 0.3, 0.6, 0.6, true));
    Surface b = makeSurface(2, QStringLiteral("Beta"), patch(5, 4, 5.0));
    Surface c = makeSurface(3, QStringLiteral("Gamma"), patch(4, 6, 10.0, 2.0));
    c.trims.push_back(rectLoop(TrimLoopId{12}, 0.2, 0.2, 0.4, 0.7));
    scene.surfaces = {a, b, c};
    scene.nextId = 13;
    return scene;
}

/// One degree-1 surface (id 1, "big") on an n x n net of gently varying heights: a file that
/// takes a while to write (n = 250: about 8 MB as .knot; n = 400: about 22 MB). nextId 2.
inline Scene bigFlatScene(int n) {
    Scene scene;
    Surface s;
    s.id = SurfaceId{1};
    s.name = QStringLiteral("big");
    NurbsSurface& g = s.geometry;
    g.degreeU = g.degreeV = 1;
    g.countU = g.countV = n;
    g.knotsU = {0.0};
    for (int k = 0; k < n; ++k)
        g.knotsU.push_back(double(k) / (n - 1));
    g.knotsU.push_back(1.0);
    g.knotsV = g.knotsU;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            g.points.push_back({i * 0.01, j * 0.01, 0.001 * ((i * 7 + j * 13) % 17)});
            g.weights.push_back(1.0);
        }
    scene.surfaces.push_back(s);
    scene.nextId = 2;
    return scene;
}

/// Scenes compared as authored content: nextId only ever grows (ids are never reused in a
/// session, so undo does not lower it) and is left out.
inline bool sameContent(Scene a, const Scene& b) {
    a.nextId = b.nextId;
    return a == b;
}

} // namespace kw::test
