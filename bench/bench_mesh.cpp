// The benchmark's uniform fine mesh.
#include "bench/bench_mesh.h"

#include "render/gpu_layout.h"

namespace kw::bench {

SceneMesh uniformSceneMesh(const Scene& scene, int nu, int nv) {
    SceneMesh out;
    for (const Surface& s : scene.surfaces) {
        TessellatedMesh t = tessellate(s.geometry, nu, nv);
        out.surfaces.push_back(SurfaceMesh{s.id, std::move(t.positions), std::move(t.normals),
                                           std::move(t.uvs), std::move(t.indices)});
    }
    return out;
}

} // namespace kw::bench
