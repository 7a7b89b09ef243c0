// Surface curvature from the exact derivatives to order 2 (kernel, double precision).
#pragma once

#include "model/nurbs/nurbs.h"

namespace kw {

/// Differential geometry at a surface point, in double precision. Signs: the second fundamental
/// form is taken against `normal` (surfaceFrame's, the Su x Sv side): L = Suu.n, M = Suv.n,
/// N = Svv.n. Curvatures are positive where the surface bends away from the normal, i.e. is
/// convex seen from the side the normal points to: a sphere with outward normal has
/// H = k1 = k2 = +1/r, a cylinder k1 = 1/r, k2 = 0, H = 1/(2r). K does not depend on the sign.
struct SurfaceCurvature {
    glm::dvec3 point{0.0};
    glm::dvec3 normal{0.0, 0.0, 1.0}; ///< surfaceFrame's unit normal
    double E = 0.0, F = 0.0, G = 0.0; ///< first fundamental form (Su.Su, Su.Sv, Sv.Sv)
    double L = 0.0, M = 0.0, N = 0.0; ///< second fundamental form against `normal`
    double gaussian = 0.0;            ///< K = k1 k2 = (LN - M^2) / (EG - F^2)
    double mean = 0.0;                ///< H = (k1 + k2) / 2
    double k1 = 0.0;                  ///< larger principal curvature (k1 >= k2)
    double k2 = 0.0;
    glm::dvec3 dir1{1.0, 0.0, 0.0}; ///< unit tangent direction of k1
    glm::dvec3 dir2{0.0, 1.0, 0.0}; ///< unit tangent direction of k2, normal x dir1
    /// Where the values were computed: (u, v) itself, or the interior point of the rule below.
    bool regular = true;
};

/// K, H, principal curvatures and directions from the exact derivatives to order 2 (Do Carmo,
/// Differential Geometry of Curves and Surfaces, 3.3: the eigenvalues of the Weingarten map
/// I^-1 II). Never NaN, by the rule of surfaceFrame's normal: where the plain normal Su x Sv is
/// unusable (step 1 fails: a collapsed edge such as a sphere pole), the curvature is the one
/// at surfaceFrame's step-3 point (kInteriorStep of the domain towards its centre), the limit
/// on a geometrically smooth surface (within O(kInteriorStep) times the curvature's gradient,
/// and about 1e-8 relative from rounding: the normal part of Suu is O(step^2) there); if that point
/// is degenerate too, every curvature is 0 and the directions are any orthonormal tangent pair. The
/// first and second forms are those of the point actually used. The GPU shader implements the same
/// rule. Non-finite results (e.g. a surface with huge coordinates overflowing) also give the zero
/// answer.
SurfaceCurvature surfaceCurvature(const NurbsSurface& s, double u, double v);

} // namespace kw
