// Test fixture for topology tests: a cube of six trimmed bicubic faces with its shared edges
// and its shell recorded as a CAD import records them (model/document/topology.h).
#pragma once

#include "model/document/scene.h"

#include <QString>
#include <algorithm>
#include <map>
#include <utility>

namespace kw::test {

/// A degree-1 segment from a to b.
inline NurbsCurve2 cubeSegment(glm::dvec2 a, glm::dvec2 b) {
    NurbsCurve2 c;
    c.degree = 1;
    c.knots = {0, 0, 1, 1};
    c.points = {a, b};
    c.weights = {1, 1};
    return c;
}

/// The cube [0, size]^3 as six bicubic Bezier faces S(u, v) = O + size (u U + v V) on [0, 1]^2
/// (control points at thirds: S is linear in u and v), each with one trim loop along its domain
/// boundary: curve 0 v = 0 (u: 0 -> 1), 1 u = 1, 2 v = 1 (u: 1 -> 0), 3 u = 0. The 12 cube edges
/// are recorded as shared edges (ids 1.., tolerance 1e-7, the first side not reversed, the other
/// side reversed when it runs the other way) and the six faces as shell 1, closed, solid 0.
/// Surface ids 1..6, loop ids 11..16.
inline Scene cubeScene(double size = 1.0) {
    struct Face {
        glm::dvec3 origin, u, v;
    };
    const glm::dvec3 x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
    // U x V points out of the cube.
    const Face faces[6] = {{{0, 0, 0}, y, x}, {{0, 0, 1}, x, y}, {{0, 0, 0}, x, z},
                           {{0, 1, 0}, z, x}, {{0, 0, 0}, z, y}, {{1, 0, 0}, y, z}};
    Scene scene;
    for (int f = 0; f < 6; ++f) {
        Surface s;
        s.id = SurfaceId{std::uint32_t(f + 1)};
        s.name = QStringLiteral("Face %1").arg(f + 1);
        NurbsSurface& g = s.geometry;
        g.degreeU = g.degreeV = 3;
        g.countU = g.countV = 4;
        g.knotsU = g.knotsV = {0, 0, 0, 0, 1, 1, 1, 1};
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i)
                g.points.push_back(
                    size * (faces[f].origin + (i / 3.0) * faces[f].u + (j / 3.0) * faces[f].v));
        g.weights.assign(16, 1.0);
        TrimLoop loop;
        loop.id = TrimLoopId{std::uint32_t(11 + f)};
        loop.curves = {cubeSegment({0, 0}, {1, 0}), cubeSegment({1, 0}, {1, 1}),
                       cubeSegment({1, 1}, {0, 1}), cubeSegment({0, 1}, {0, 0})};
        s.trims.push_back(loop);
        s.solid = 0;
        scene.surfaces.push_back(s);
    }
    // Curves with the same two end points (in either order) are one edge.
    const auto key = [&](const Surface& s, int c) {
        const NurbsCurve2& curve = s.trims[0].curves[size_t(c)];
        const auto at = [&](glm::dvec2 uv) {
            const glm::dvec3 p = surfacePoint(s.geometry, uv.x, uv.y) / size;
            return std::tuple(std::lround(p.x), std::lround(p.y), std::lround(p.z));
        };
        return std::pair(at(curve.points.front()), at(curve.points.back()));
    };
    std::map<std::pair<std::tuple<long, long, long>, std::tuple<long, long, long>>, size_t> open;
    for (const Surface& s : scene.surfaces)
        for (int c = 0; c < 4; ++c) {
            const auto k = key(s, c);
            const auto reversedKey = std::pair(k.second, k.first);
            const EdgeUse use{s.id, s.trims[0].id, c, false};
            if (const auto it = open.find(k); it != open.end()) {
                scene.topology.edges[it->second].sides[1] = use;
            } else if (const auto r = open.find(reversedKey); r != open.end()) {
                scene.topology.edges[r->second].sides[1] = use;
                scene.topology.edges[r->second].sides[1].reversed = true;
            } else {
                SharedEdge edge;
                edge.id = EdgeId{std::uint32_t(scene.topology.edges.size() + 1)};
                edge.tolerance = 1e-7;
                edge.sides[0] = use;
                open.emplace(k, scene.topology.edges.size());
                scene.topology.edges.push_back(edge);
            }
        }
    Shell shell;
    shell.id = ShellId{1};
    shell.closed = true;
    shell.solid = 0;
    for (const Surface& s : scene.surfaces)
        shell.faces.push_back(s.id);
    scene.topology.shells.push_back(shell);
    scene.nextId = 17;
    return scene;
}

/// `count` cubes of side 1 (cubeScene) in a row along x, 2 apart, each its own shell
/// (ids 1..count, solid 0..count-1): surface k of cube c has id 16 c + k + 1, its loop
/// 16 c + k + 7, edge e of cube c id 12 c + e.
inline Scene cubesScene(int count) {
    Scene out;
    for (int c = 0; c < count; ++c) {
        const Scene cube = cubeScene();
        const std::uint32_t base = std::uint32_t(16 * c);
        for (Surface s : cube.surfaces) {
            s.id.value = base + s.id.value;
            s.trims[0].id.value = s.id.value + 6;
            for (glm::dvec3& p : s.geometry.points)
                p.x += 2.0 * c;
            s.solid = c;
            out.surfaces.push_back(s);
        }
        for (SharedEdge e : cube.topology.edges) {
            e.id.value += std::uint32_t(12 * c);
            for (EdgeUse& side : e.sides) {
                side.surface.value += base;
                side.loop.value = side.surface.value + 6;
            }
            out.topology.edges.push_back(e);
        }
        Shell shell = cube.topology.shells.front();
        shell.id.value = std::uint32_t(c + 1);
        shell.solid = c;
        for (SurfaceId& f : shell.faces)
            f.value += base;
        out.topology.shells.push_back(shell);
    }
    out.nextId = std::uint32_t(16 * count + 1);
    return out;
}

} // namespace kw::test
