// Triangle meshes built on the CPU for the benchmark's comparison passes (GLU, fine mesh).
#pragma once

#include "model/scene.h"

#include <glm/glm.hpp>
#include <vector>

namespace kw::bench {

/// One surface's triangles: per-vertex position, unit normal and (u, v); GL_TRIANGLES indices.
struct SurfaceMesh {
    SurfaceId id;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> uvs;
    std::vector<unsigned> indices;
};

/// Triangles over every surface of a scene, one SurfaceMesh per surface in scene order.
struct SceneMesh {
    std::vector<SurfaceMesh> surfaces;
    long long triangleCount() const;
    long long vertexCount() const;
};

/// The uniform nu x nv tessellation of every surface (kw::tessellate: kernel points and
/// normals at the grid vertices), the "prebuilt fine mesh". nu, nv >= 1 (clamped).
SceneMesh uniformSceneMesh(const Scene& scene, int nu, int nv);

} // namespace kw::bench
