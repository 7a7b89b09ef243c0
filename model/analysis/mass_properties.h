// Exact properties of trimmed faces and of a model: surface type, area, enclosed volume and
// bounding box, in double precision from the NURBS surfaces and their exact trim curves.
#pragma once

#include "model/analysis/surface_type.h"
#include "model/document/scene.h"

#include <QString>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

namespace kw {

/// Density evaluations (|Su x Sv| and its companions at one (u, v)) one face's integrals may
/// spend, about half a second. Well-formed faces need far fewer (the CAD parts in tests/data at
/// most ~60,000); hostile trims (nearly singular rational curves, thousands of knot spans) would
/// otherwise halve to the depth limit everywhere and run for minutes.
constexpr long kAreaEvaluationBudget = 1'500'000;

/// Integrals over the trimmed part of one face.
struct FaceIntegrals {
    double area = 0.0;
    /// (1/3) of the flux of (P - origin) through the face along Su x Sv: summed over a closed
    /// shell with every face's Su x Sv outwards, the volume enclosed (divergence theorem).
    double volume = 0.0;
    /// The integral of Su x Sv (the normal times dA): the flux about another origin o' is
    /// volume + (origin - o') . vectorArea / 3.
    glm::dvec3 vectorArea{0.0};
    /// True when the quadrature or the search for crossing trims ran out of its budget (hostile
    /// trims): the values are then the best estimate reached, not exact to `relative`.
    bool approximate = false;
    long evaluations = 0; ///< density evaluations spent (the budget caps them)
};

/// Area and volume flux of the part of `surface` its trims keep (even-odd, as the trim mask),
/// by Green's theorem in (u, v): the double integral of f over the region is the sum over the
/// loops of the line integral of -F du, F(u, v) the integral of f along v from the loop's lowest
/// v. Both integrals are adaptive Gauss-Legendre (8 points, halved until two levels agree to
/// `relative`), the outer one along the exact trim curves (split at their knots), the inner one
/// split at the surface's v knots, so no flattening error enters. Loops are signed by their
/// orientation and their nesting depth. Without trims the domain's boundary is the loop.
/// Invalid trim curves are left out and gaps bridged straight, as makeTrimRegion does.
/// Trims that cross one another or themselves, or reach past the (u, v) domain, are measured
/// through the boundary of their even-odd region clipped to the domain (the loops cut where they
/// cross), so the area lies in [0, the untrimmed area] for any trims. Past `budget` density
/// evaluations no interval is halved again and the result is flagged approximate.
/// Precondition: a valid surface.
FaceIntegrals faceIntegrals(const Surface& surface, const glm::dvec3& origin = glm::dvec3(0.0),
                            double relative = 1e-11, long budget = kAreaEvaluationBudget);

/// Area of the part of `surface` its trims keep: faceIntegrals' area, the one measure of a
/// trimmed area (the properties panel, `knotwork info` and the tests use it). A measure over
/// flattened trims is not enough to compare two faces at 1e-6: its polygons' chord error
/// (1e-5 of the domain) falls differently on two parameterisations of one boundary.
double trimmedSurfaceArea(const NurbsSurface& surface, const std::vector<TrimLoop>& trims);

/// Axis-aligned bounds of the trimmed face: the surface sampled on a grid of the trims'
/// parameter box (points the trims keep) and along every trim curve, then each extreme refined
/// (Newton on the coordinate inside, golden section along a curve). False when the trims keep
/// no sample.
bool faceBounds(const Surface& surface, glm::dvec3& lo, glm::dvec3& hi);

/// What the properties panel and `knotwork info` show for one face.
struct FaceProperties {
    SurfaceType type = SurfaceType::FreeForm;
    int degreeU = 0, degreeV = 0;
    double area = 0.0;
    /// The area (and the face's flux) is an estimate: hostile trims spent the measure's budget
    /// (FaceIntegrals::approximate). Shown as such, never passed off as exact.
    bool approximate = false;
    bool hasBounds = false;
    glm::dvec3 lo{0.0}, hi{0.0};
};
FaceProperties faceProperties(const Surface& surface);

/// What the model's totals need of one face: its properties, and its flux about its own centre
/// with its vector area, from which the flux about any origin follows (FaceIntegrals), so that
/// a face measured once serves every later total while it keeps its shape and trims.
struct FaceMeasure {
    FaceProperties props;
    glm::dvec3 centre{0.0}; ///< the centre of the control points' bounds: the flux's origin
    double flux = 0.0;      ///< FaceIntegrals::volume about `centre`, along Su x Sv
    glm::dvec3 vectorArea{0.0};
};
FaceMeasure measureFace(const Surface& surface);

/// measureFace of the surfaces at `indices` of scene.surfaces (every one when empty), shared out
/// over the machine's cores (a work queue: face costs differ a thousandfold); the result is in
/// the order of `indices` (or of the surfaces).
std::vector<FaceMeasure> measureFaces(const Scene& scene, const std::vector<size_t>& indices = {});

/// The model's totals.
struct ModelProperties {
    double area = 0.0; ///< every face, hidden or not
    bool approximate = false; ///< some face's area is an estimate (FaceProperties::approximate)
    /// Sum of the volumes of the closed shells (kw::closedShells: recorded closed and every seam
    /// within tolerance), each face oriented by Surface::outsideAlongNormal; nullopt when no shell
    /// is closed. The shells of one solid (Shell::solid: an outer shell and its cavities) are
    /// summed with their orientation, then taken positive; a shell of no solid on its own.
    std::optional<double> volume;
    int closedShells = 0;
    bool hasBounds = false;
    glm::dvec3 lo{0.0}, hi{0.0};
    std::vector<FaceProperties> faces; ///< faceProperties of each surface, in scene order
};
/// The totals from measures already taken: faces[k] is measureFace(scene.surfaces[k]). The
/// volume sums each face's flux moved to one origin, the centre of the control points' bounds.
ModelProperties modelProperties(const Scene& scene, const std::vector<FaceMeasure>& faces);
/// modelProperties(scene, measureFaces(scene)).
ModelProperties modelProperties(const Scene& scene);

} // namespace kw
