// The classic OpenGL 1.x/2.x way to draw NURBS: libGLU's NURBS tessellator, driven through the
// GLU_NURBS_TESSELLATOR callbacks so the triangles come back to the CPU (no fixed function).
#pragma once

#include "bench/bench_mesh.h"
#include "model/error.h"
#include "render/render_types.h"

#include <QString>

namespace kw::bench {

/// Tessellates every surface of `scene` with gluNurbsSurface as seen by `camera` (GLU_PATH_LENGTH
/// sampling: no edge of the result longer than `tolerancePixels` on screen; the sampling
/// matrices are loaded from `camera`, GLU_AUTO_LOAD_MATRIX off, so no GL context is touched).
/// (u, v) per vertex comes from a bilinear GL_MAP2_TEXTURE_COORD_2 map over the surface's domain;
/// normals from GLU's own derivative evaluation. Trim loops are not passed to GLU (the plate is
/// drawn untrimmed). tolerancePixels must be > 0. Returns the GLU error (its string and the
/// surface id) when one occurs.
Status gluTessellate(const Scene& scene, const FrameCamera& camera, double tolerancePixels,
                     SceneMesh& out);

} // namespace kw::bench
