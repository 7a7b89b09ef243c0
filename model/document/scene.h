// Scene: the authored data of a Knotwork document as plain values (no derived data, no Qt objects).
#pragma once

#include "model/document/ids.h"
#include "model/document/topology.h"
#include "model/document/units.h"
#include "model/error.h"
#include "model/nurbs/analytic.h"
#include "model/nurbs/nurbs.h"

#include <QString>
#include <compare>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace kw {

/// One control point of one surface: (i, j) as in NurbsSurface::index.
struct ControlPointRef {
    SurfaceId surface;
    int i = 0;
    int j = 0;
    auto operator<=>(const ControlPointRef&) const = default;
};

/// One control point of one trim curve.
struct TrimPointRef {
    SurfaceId surface;
    TrimLoopId loop;
    int curve = 0;
    int index = 0;
    auto operator<=>(const TrimPointRef&) const = default;
};

/// Phong material (paper eq. 3.8): I = ka*ia + sum(kd (L.N) id + ks (R.V)^shininess is) * color.
struct Material {
    glm::dvec3 color{0.80, 0.82, 0.86};
    double ka = 0.15;
    double kd = 0.75;
    double ks = 0.35;
    double shininess = 40.0;
    bool operator==(const Material&) const = default;
};

/// A closed loop of 2D NURBS curves in the surface's (u, v) space, each curve starting where
/// the previous one ends. Outer boundaries, holes and islands are distinguished by nesting,
/// not by orientation: the trim mask combines loops by parity.
struct TrimLoop {
    TrimLoopId id;
    std::vector<NurbsCurve2> curves;
    bool operator==(const TrimLoop&) const = default;
};

/// Tessellation partitions of the base polygon (paper 3.1): the domain cut into nu x nv cells.
constexpr int kMinPartitions = 1;
constexpr int kMaxPartitions = 256;

struct Surface {
    SurfaceId id;
    QString name;
    NurbsSurface geometry;
    std::vector<TrimLoop> trims;
    int partitionsU = 10;
    int partitionsV = 10;
    Material material;
    /// Hidden by the user (View > Hide): not drawn and not pickable, still part of the
    /// document (saved, exported, counted). An edit like any other: undoable, marks modified.
    bool hidden = false;
    /// A face of a closed solid, all of whose faces were imported (kw::importOcctFile): the
    /// solid's number (>= 0), and whether the solid's outside lies on the side S_u x S_v
    /// points to (false: the other side). While the eye sees the solid from outside, the
    /// renderer skips the base polygon's triangles that turn their inside to the eye: the
    /// solid's own faces in front hide them (docs/RENDERING.md, "Back faces of closed
    /// solids"). -1: not known to bound a solid. A change of any of its faces' shape or trims,
    /// or the removal of one, may open the solid: Document then clears the mark on all of
    /// them, and marks them again once every face has the shape it had when the scene was
    /// loaded (undo); a surface inserted into a document carries none but as such a face.
    int solid = -1;
    bool outsideAlongNormal = true;
    /// The closed form the source file gave this face (kw::AnalyticForm), while `geometry` is
    /// still the NURBS made from it; Kind::None for created, free-form or edited faces.
    AnalyticForm analytic;
    bool operator==(const Surface&) const = default;
};

/// A light of the Phong model: directional (vector = direction the light travels *from*,
/// i.e. towards the light, in world space) or point (vector = position).
struct Light {
    enum class Kind { Directional, Point };
    Kind kind = Kind::Directional;
    glm::dvec3 vector{0.0, 0.0, 1.0};
    glm::dvec3 ambient{0.2};  ///< i_a
    glm::dvec3 diffuse{0.8};  ///< i_d
    glm::dvec3 specular{0.6}; ///< i_s
    bool operator==(const Light&) const = default;
};

constexpr int kMaxLights = 8;

/// The two lights a new scene starts with: a key light from the upper left front and a
/// dimmer fill light from the right.
std::vector<Light> defaultLights();

/// Adaptive partitions' screen tolerance limits in pixels (DisplaySettings,
/// RenderOptions::pixelTolerance).
constexpr double kMinPixelTolerance = 0.05;
constexpr double kMaxPixelTolerance = 16.0;

/// A section plane: it removes the half-space its normal points into, so that what is left
/// faces the eye with the plane's normal as its outward normal (the cap's). `flip` keeps the
/// other half instead. The normal need not be unit length but must not be zero
/// (checkSectionPlane).
struct SectionPlane {
    glm::dvec3 position{0.0};
    glm::dvec3 normal{1.0, 0.0, 0.0};
    bool flip = false;
    /// The unit normal of the removed side (flip applied); zero for a zero normal.
    glm::dvec3 removedSide() const {
        const double l = glm::length(normal);
        return l > 0.0 ? (flip ? -normal : normal) / l : glm::dvec3(0.0);
    }
    bool operator==(const SectionPlane&) const = default;
};
/// At most this many section planes cut a view at once (the exact pass's uniform array).
constexpr int kMaxSectionPlanes = 3;
/// ok() when `plane` can cut, else an Error saying why not (a zero or non-finite normal, a
/// non-finite position).
Status checkSectionPlane(const SectionPlane& plane);

/// How the project asks to be drawn, saved with it like the camera (not an edit). An empty
/// mode leaves it to the viewer (the editor's preference, render's --partition-mode).
struct DisplaySettings {
    QString partitionMode;       ///< "", "adaptive" or "uniform"
    double pixelTolerance = 0.5; ///< adaptive mode's, kMinPixelTolerance..kMaxPixelTolerance
    QString background;          ///< "", "dark" or "light" (kw::backgroundNamed)
    /// Section planes (at most kMaxSectionPlanes) and whether closed solids get caps.
    std::vector<SectionPlane> sections;
    bool sectionCaps = true;
    /// Draft analysis: the pull direction (world, non-zero; normalised when used) and the
    /// minimum draft angle in degrees (0..90), as View > Analysis > Draft Settings sets them.
    glm::dvec3 pullDirection{0.0, 0.0, 1.0};
    double draftAngleDegrees = 3.0;
    /// True when the draft members differ from their defaults (files then write them).
    bool customDraft() const {
        return pullDirection != glm::dvec3(0.0, 0.0, 1.0) || draftAngleDegrees != 3.0;
    }
    bool operator==(const DisplaySettings&) const = default;
};

/// Thresholds of the classes, in the units CATIA's checker uses. An edge is G0 when its gap is
/// within g0 (or within its own recorded tolerance, when larger), G1 when moreover its normals
/// agree within g1Degrees, G2 when moreover the normal curvatures across it agree within
/// g2Percent of the larger. `match`: how close the boundaries of faces without a record must
/// lie to be found as one edge (model units, >= g0); farther apart they are two free edges.
struct ContinuityTolerances {
    double g0 = 0.001;
    double g1Degrees = 0.5;
    double g2Percent = 5.0;
    double match = 0.01;
    bool operator==(const ContinuityTolerances&) const = default;
};

/// Perspective camera. `authored` false means none was set by the user or file: views fit one
/// to the scene (fitCamera) and files omit it.
struct Camera {
    glm::dvec3 eye{0.0, -5.0, 3.0};
    glm::dvec3 target{0.0};
    glm::dvec3 up{0.0, 0.0, 1.0};
    double fovYDegrees = 35.0;
    bool authored = false;
    bool operator==(const Camera&) const = default;
};

/// The whole authored document. Ids are unique; nextId is above every id in use.
struct Scene {
    std::vector<Surface> surfaces;
    /// Which trim curves are one B-rep edge and which faces one shell, as a CAD import found
    /// them (model/document/topology.h); empty for anything else.
    Topology topology;
    std::vector<Light> lights = defaultLights();
    Camera camera;
    DisplaySettings display;
    /// The edge continuity classes' thresholds (model/analysis/continuity.h), saved with the
    /// project like the display settings (not an edit).
    ContinuityTolerances continuity;
    std::uint32_t nextId = 1;
    /// The unit of every length: coordinates, tolerances, gaps (model/document/units.h). An import
    /// keeps the source file's; everything else starts in millimetres.
    LengthUnit unit = LengthUnit::Millimetre;
    bool operator==(const Scene&) const = default;
};

/// Axis-aligned bounds of all control points (with `shownOnly`, of the surfaces not hidden);
/// false when there are none.
bool sceneBounds(const Scene& scene, glm::dvec3& lo, glm::dvec3& hi, bool shownOnly = false);
/// A camera that looks at the whole scene from the front-right-above, for views without one.
/// It frames the exact trimmed geometry (sceneVisibleBounds, model/nurbs/visible_bounds.h), or the
/// control points when that gives no bounds, of the surfaces shown; of all surfaces when every
/// one is hidden.
Camera fitCamera(const Scene& scene, double aspect);
/// `camera` magnified `factor` (>= 1) times about the point of its target plane that shows at
/// `at` in an image of width / height `aspect` (fractions of the image, (0, 0) its top left,
/// (0.5, 0.5) its centre, the target): it turns to that point, which becomes the target, and
/// narrows its field of view; the eye stays, so a close-up never puts it inside the part. The
/// close-ups of `knotwork render --zoom`.
Camera zoomedCamera(const Camera& camera, double factor, glm::dvec2 at, double aspect);

} // namespace kw
