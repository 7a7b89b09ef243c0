// Triangle meshes built outside the renderer (the benchmark's comparison rows: libGLU's NURBS
// tessellation and a prebuilt fine mesh), which Renderer::renderMesh draws with the tessellated
// baseline's shading. Plain data, no GL.
#pragma once

#include "model/document/scene.h"

#include <glm/glm.hpp>
#include <vector>

namespace kw {

/// One surface's triangles: per-vertex position, unit normal and (u, v); GL_TRIANGLES indices.
struct SurfaceMesh {
    SurfaceId id;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> uvs;
    std::vector<unsigned> indices;
};

/// Triangles over the surfaces of a scene, one SurfaceMesh per surface.
struct TriangleMesh {
    std::vector<SurfaceMesh> surfaces;
    long long triangleCount() const;
    long long vertexCount() const;
};

} // namespace kw
