// Counts of a TriangleMesh.
#include "render/triangle_mesh.h"

namespace kw {

long long TriangleMesh::triangleCount() const {
    long long n = 0;
    for (const SurfaceMesh& s : surfaces)
        n += (long long)(s.indices.size() / 3);
    return n;
}

long long TriangleMesh::vertexCount() const {
    long long n = 0;
    for (const SurfaceMesh& s : surfaces)
        n += (long long)s.positions.size();
    return n;
}

} // namespace kw
