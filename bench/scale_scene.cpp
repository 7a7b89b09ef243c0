// The scale table's models: one part tiled in a grid (see bench/scale_scene.h).
#include "bench/scale_scene.h"

#include <algorithm>
#include <cmath>

namespace kw::bench {

namespace {

/// The two axes of the largest extents of `size`, largest first.
std::pair<int, int> gridAxes(const glm::dvec3& size) {
    int axes[3] = {0, 1, 2};
    std::sort(axes, axes + 3, [&](int a, int b) { return size[a] > size[b]; });
    return {axes[0], axes[1]};
}

} // namespace

int copiesForFaces(int unitFaces, int faces) {
    if (unitFaces <= 0)
        return 1;
    return std::max(1, (faces + unitFaces - 1) / unitFaces);
}

Scene tileScene(const Scene& unit, int copies) {
    Scene out;
    out.lights = unit.lights;
    glm::dvec3 lo, hi;
    if (!sceneBounds(unit, lo, hi) || copies < 1)
        return out;
    const glm::dvec3 size = hi - lo;
    const double gap = 0.25 * std::max({size.x, size.y, size.z, 1e-9});
    const auto [a, b] = gridAxes(size);
    const int columns = int(std::ceil(std::sqrt(double(copies))));
    std::uint32_t next = 1;
    out.surfaces.reserve(size_t(copies) * unit.surfaces.size());
    for (int k = 0; k < copies; ++k) {
        glm::dvec3 offset(0.0);
        offset[a] = (k % columns) * (size[a] + gap);
        offset[b] = (k / columns) * (size[b] + gap);
        for (const Surface& s : unit.surfaces) {
            Surface c = s;
            c.id = SurfaceId{next++};
            for (glm::dvec3& p : c.geometry.points)
                p += offset;
            for (TrimLoop& loop : c.trims)
                loop.id = TrimLoopId{next++};
            out.surfaces.push_back(std::move(c));
        }
    }
    out.nextId = next;
    return out;
}

Camera closeUpCamera(const Scene& unit, double aspect) {
    // The first copy sits where the unit does (offset 0), so the unit's fitted camera frames it.
    Scene first = unit;
    first.camera.authored = false;
    Camera c = fitCamera(first, aspect);
    // Half the distance: the part fills the view and its far ends leave it.
    c.eye = c.target + 0.5 * (c.eye - c.target);
    c.authored = true;
    return c;
}

} // namespace kw::bench
