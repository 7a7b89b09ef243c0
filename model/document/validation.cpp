// Validation of authored data: plain-English reasons shared by Document, the .knot reader, the
// importers and the writers (one notion of a valid scene).
#include "model/document/validation.h"

#include "model/analysis/continuity.h"
#include "model/nurbs/analytic_eval.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace kw {

namespace {

bool finite(double x) {
    return std::isfinite(x);
}
bool finite(const glm::dvec3& v) {
    return finite(v.x) && finite(v.y) && finite(v.z);
}
bool in(double x, double lo, double hi) {
    return finite(x) && x >= lo && x <= hi;
}
bool in(const glm::dvec3& v, double lo, double hi) {
    return in(v.x, lo, hi) && in(v.y, lo, hi) && in(v.z, lo, hi);
}

// A reason, empty when valid, as a Status.
Status asStatus(const QString& reason) {
    if (reason.isEmpty())
        return ok();
    return Error(reason);
}

} // namespace

static QString partitionsReason(int nu, int nv) {
    if (nu < kMinPartitions || nu > kMaxPartitions || nv < kMinPartitions || nv > kMaxPartitions)
        return QStringLiteral("partitions %1 x %2 outside [%3, %4]")
            .arg(nu)
            .arg(nv)
            .arg(kMinPartitions)
            .arg(kMaxPartitions);
    return {};
}

static QString materialReason(const Material& m) {
    if (!in(m.color, 0.0, 1.0))
        return QStringLiteral("material colour components must be in [0, 1]");
    if (!in(m.ka, 0.0, 1.0) || !in(m.kd, 0.0, 1.0) || !in(m.ks, 0.0, 1.0))
        return QStringLiteral("material coefficients ka, kd, ks must be in [0, 1]");
    if (!in(m.shininess, 0.0, kMaxShininess))
        return QStringLiteral("material shininess must be in [0, %1]").arg(kMaxShininess);
    return {};
}

static QString lightReason(const Light& l) {
    if (l.kind != Light::Kind::Directional && l.kind != Light::Kind::Point)
        return QStringLiteral("unknown light kind");
    if (!finite(l.vector))
        return QStringLiteral("light direction or position must be finite");
    if (l.kind == Light::Kind::Directional && glm::length(l.vector) == 0.0)
        return QStringLiteral("directional light needs a non-zero direction");
    if (!in(l.ambient, 0.0, kMaxLightIntensity) || !in(l.diffuse, 0.0, kMaxLightIntensity) ||
        !in(l.specular, 0.0, kMaxLightIntensity))
        return QStringLiteral("light intensities must be in [0, %1]").arg(kMaxLightIntensity);
    return {};
}

static QString lightsReason(const std::vector<Light>& lights) {
    if (lights.size() > size_t(kMaxLights))
        return QStringLiteral("%1 lights, more than the limit %2")
            .arg(lights.size())
            .arg(kMaxLights);
    for (size_t i = 0; i < lights.size(); ++i) {
        const QString e = lightReason(lights[i]);
        if (!e.isEmpty())
            return QStringLiteral("light %1: %2").arg(i + 1).arg(e);
    }
    return {};
}

static QString cameraReason(const Camera& c) {
    if (!finite(c.eye) || !finite(c.target) || !finite(c.up))
        return QStringLiteral("camera vectors must be finite");
    const glm::dvec3 view = c.target - c.eye;
    if (glm::length(view) == 0.0)
        return QStringLiteral("camera eye and target coincide");
    if (glm::length(glm::cross(view, c.up)) <= 1e-12 * glm::length(view) * glm::length(c.up))
        return QStringLiteral("camera up vector is zero or parallel to the view direction");
    if (!(finite(c.fovYDegrees) && c.fovYDegrees > 0 && c.fovYDegrees < 180))
        return QStringLiteral("camera field of view must be in (0, 180) degrees");
    return {};
}

double trimLoopClosureTolerance(const TrimLoop& loop) {
    double extent = 1.0;
    for (const NurbsCurve2& c : loop.curves)
        for (const glm::dvec2& p : c.points)
            extent = std::max({extent, std::abs(p.x), std::abs(p.y)});
    return 1e-9 * extent;
}

int trimLoopOpenAt(const TrimLoop& loop, glm::dvec2* start, glm::dvec2* end) {
    const double tolerance = trimLoopClosureTolerance(loop);
    const size_t n = loop.curves.size();
    for (size_t k = 0; k < n; ++k) {
        const NurbsCurve2& prev = loop.curves[(k + n - 1) % n];
        const NurbsCurve2& cur = loop.curves[k];
        const glm::dvec2 e = curvePoint(prev, curveDomain(prev).last);
        const glm::dvec2 s = curvePoint(cur, curveDomain(cur).first);
        if (!(glm::length(e - s) <= tolerance)) {
            if (start)
                *start = s;
            if (end)
                *end = e;
            return int(k);
        }
    }
    return -1;
}

static QString trimLoopReason(const TrimLoop& loop) {
    if (!loop.id.isValid())
        return QStringLiteral("trim loop has no id");
    if (loop.curves.empty())
        return QStringLiteral("trim loop %1 has no curves").arg(loop.id.value);
    if (loop.curves.size() > size_t(kMaxLoopCurves))
        return QStringLiteral("trim loop %1 has %2 curves, more than the limit %3")
            .arg(loop.id.value)
            .arg(loop.curves.size())
            .arg(kMaxLoopCurves);
    for (size_t i = 0; i < loop.curves.size(); ++i) {
        QString e = checkNurbsCurve(loop.curves[i]).message();
        if (e.isEmpty() && loop.curves[i].points.size() > size_t(kMaxCurvePoints))
            e = QStringLiteral("more than %1 control points").arg(kMaxCurvePoints);
        if (!e.isEmpty())
            return QStringLiteral("trim loop %1, curve %2: %3")
                .arg(loop.id.value)
                .arg(i + 1)
                .arg(e);
    }
    glm::dvec2 start, end;
    if (const int k = trimLoopOpenAt(loop, &start, &end); k >= 0)
        return QStringLiteral("trim loop %1 is not closed: curve %2 starts at (%3, %4) but the "
                              "previous curve ends at (%5, %6)")
            .arg(loop.id.value)
            .arg(k + 1)
            .arg(start.x, 0, 'g', 17)
            .arg(start.y, 0, 'g', 17)
            .arg(end.x, 0, 'g', 17)
            .arg(end.y, 0, 'g', 17);
    return {};
}

static QString surfaceReason(const Surface& s) {
    if (!s.id.isValid())
        return QStringLiteral("surface has no id");
    const QString who = QStringLiteral("surface %1").arg(s.id.value);
    const Status geometry = checkNurbsSurface(s.geometry);
    if (!geometry)
        return who + QStringLiteral(": ") + geometry.message();
    QString e;
    if ((long long)s.geometry.countU * s.geometry.countV > kMaxControlPoints)
        e = QStringLiteral("%1 x %2 control points, more than the limit %3")
                .arg(s.geometry.countU)
                .arg(s.geometry.countV)
                .arg(kMaxControlPoints);
    if (e.isEmpty())
        e = partitionsReason(s.partitionsU, s.partitionsV);
    if (e.isEmpty())
        e = materialReason(s.material);
    if (e.isEmpty())
        if (const Status a = checkAnalyticForm(s.analytic, s.geometry); !a)
            e = QStringLiteral("analytic form: ") + a.message();
    if (e.isEmpty() && s.solid < -1)
        e = QStringLiteral("solid number %1 is negative").arg(s.solid);
    if (e.isEmpty() && s.trims.size() > size_t(kMaxTrimLoops))
        e = QStringLiteral("%1 trim loops, more than the limit %2")
                .arg(s.trims.size())
                .arg(kMaxTrimLoops);
    std::set<std::uint32_t> loops;
    for (size_t i = 0; e.isEmpty() && i < s.trims.size(); ++i) {
        e = trimLoopReason(s.trims[i]);
        if (e.isEmpty() && !loops.insert(s.trims[i].id.value).second)
            e = QStringLiteral("trim loop id %1 used twice").arg(s.trims[i].id.value);
    }
    return e.isEmpty() ? QString() : who + QStringLiteral(": ") + e;
}

static QString displayReason(const DisplaySettings& d) {
    if (!d.partitionMode.isEmpty() && d.partitionMode != QLatin1String("adaptive") &&
        d.partitionMode != QLatin1String("uniform"))
        return QStringLiteral("partition mode \"%1\" is neither \"adaptive\" nor \"uniform\"")
            .arg(d.partitionMode);
    if (!d.background.isEmpty() && d.background != QLatin1String("dark") &&
        d.background != QLatin1String("light"))
        return QStringLiteral("background \"%1\" is neither \"dark\" nor \"light\"")
            .arg(d.background);
    if (!(glm::length(d.pullDirection) > 0.0) || !std::isfinite(glm::length(d.pullDirection)))
        return QStringLiteral("the draft pull direction is zero or not finite");
    if (!(d.draftAngleDegrees >= 0.0 && d.draftAngleDegrees <= 90.0))
        return QStringLiteral("draft angle %1 is outside 0..90").arg(d.draftAngleDegrees);
    if (!(d.pixelTolerance >= kMinPixelTolerance && d.pixelTolerance <= kMaxPixelTolerance))
        return QStringLiteral("pixel tolerance %1 is outside %2..%3")
            .arg(d.pixelTolerance)
            .arg(kMinPixelTolerance)
            .arg(kMaxPixelTolerance);
    if (d.sections.size() > size_t(kMaxSectionPlanes))
        return QStringLiteral("%1 section planes, at most %2")
            .arg(d.sections.size())
            .arg(kMaxSectionPlanes);
    for (size_t k = 0; k < d.sections.size(); ++k)
        if (const QString why = checkSectionPlane(d.sections[k]).message(); !why.isEmpty())
            return QStringLiteral("section %1: %2").arg(k + 1).arg(why);
    return QString();
}

static QString sceneReason(const Scene& scene) {
    if (scene.surfaces.size() > size_t(kMaxSurfaces))
        return QStringLiteral("%1 surfaces, more than the limit %2")
            .arg(scene.surfaces.size())
            .arg(kMaxSurfaces);
    std::set<std::uint32_t> ids;
    std::uint32_t maxId = 0;
    for (const Surface& s : scene.surfaces) {
        const QString e = surfaceReason(s);
        if (!e.isEmpty())
            return e;
        // Surface and loop ids come from one counter, so all of them differ.
        if (!ids.insert(s.id.value).second)
            return QStringLiteral("surface id %1 used twice").arg(s.id.value);
        maxId = std::max(maxId, s.id.value);
        for (const TrimLoop& l : s.trims) {
            if (!ids.insert(l.id.value).second)
                return QStringLiteral("trim loop id %1 used twice").arg(l.id.value);
            maxId = std::max(maxId, l.id.value);
        }
    }
    if (scene.nextId <= maxId)
        return QStringLiteral("nextId %1 is not above the largest id %2")
            .arg(scene.nextId)
            .arg(maxId);
    QString e = lightsReason(scene.lights);
    if (e.isEmpty())
        e = checkTopology(scene).message();
    if (e.isEmpty())
        e = cameraReason(scene.camera);
    if (e.isEmpty())
        e = displayReason(scene.display);
    if (e.isEmpty())
        if (const QString why = checkContinuityTolerances(scene.continuity).message();
            !why.isEmpty())
            e = QStringLiteral("continuity: ") + why;
    return e;
}

// The checks as the public interface states them: the reason above becomes the Error.

Status checkPartitions(int nu, int nv) {
    return asStatus(partitionsReason(nu, nv));
}

Status checkMaterial(const Material& material) {
    return asStatus(materialReason(material));
}

Status checkLight(const Light& light) {
    return asStatus(lightReason(light));
}

Status checkLights(const std::vector<Light>& lights) {
    return asStatus(lightsReason(lights));
}

Status checkCamera(const Camera& camera) {
    return asStatus(cameraReason(camera));
}

Status checkDisplay(const DisplaySettings& display) {
    return asStatus(displayReason(display));
}

Status checkTrimLoop(const TrimLoop& loop) {
    return asStatus(trimLoopReason(loop));
}

Status checkSurface(const Surface& surface) {
    return asStatus(surfaceReason(surface));
}

Status checkScene(const Scene& scene) {
    return asStatus(sceneReason(scene));
}

} // namespace kw
