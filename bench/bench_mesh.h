// Triangle meshes built on the CPU for the benchmark's comparison passes (GLU, fine mesh).
#pragma once

#include "model/document/scene.h"
#include "render/triangle_mesh.h"

#include <glm/glm.hpp>
#include <vector>

namespace kw::bench {

/// The renderer's public mesh types (render/triangle_mesh.h): the GLU and fine meshes are
/// handed to it (Renderer::setMesh) and drawn through its public interface.
using SurfaceMesh = kw::SurfaceMesh;
using SceneMesh = kw::TriangleMesh;

/// The uniform nu x nv tessellation of every surface (kw::tessellate: kernel points and
/// normals at the grid vertices), the "prebuilt fine mesh". nu, nv >= 1 (clamped).
SceneMesh uniformSceneMesh(const Scene& scene, int nu, int nv);

} // namespace kw::bench
