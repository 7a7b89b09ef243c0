// Validation of authored data: plain-English reasons for Document and the edit commands.
#include "model/validation.h"

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
bool nonNegative(const glm::dvec3& v) {
    return finite(v) && v.x >= 0 && v.y >= 0 && v.z >= 0;
}

} // namespace

QString partitionsError(int nu, int nv) {
    if (nu < kMinPartitions || nu > kMaxPartitions || nv < kMinPartitions || nv > kMaxPartitions)
        return QStringLiteral("partitions %1 x %2 outside [%3, %4]")
            .arg(nu)
            .arg(nv)
            .arg(kMinPartitions)
            .arg(kMaxPartitions);
    return {};
}

QString materialError(const Material& m) {
    if (!nonNegative(m.color))
        return QStringLiteral("material colour must be finite and non-negative");
    if (!(finite(m.ka) && m.ka >= 0) || !(finite(m.kd) && m.kd >= 0) ||
        !(finite(m.ks) && m.ks >= 0))
        return QStringLiteral("material coefficients ka, kd, ks must be finite and non-negative");
    if (!(finite(m.shininess) && m.shininess >= 0))
        return QStringLiteral("material shininess must be finite and non-negative");
    return {};
}

QString lightError(const Light& l) {
    if (l.kind != Light::Kind::Directional && l.kind != Light::Kind::Point)
        return QStringLiteral("unknown light kind");
    if (!finite(l.vector))
        return QStringLiteral("light direction or position must be finite");
    if (l.kind == Light::Kind::Directional && glm::length(l.vector) <= 1e-12)
        return QStringLiteral("directional light needs a non-zero direction");
    if (!nonNegative(l.ambient) || !nonNegative(l.diffuse) || !nonNegative(l.specular))
        return QStringLiteral("light intensities must be finite and non-negative");
    return {};
}

QString lightsError(const std::vector<Light>& lights) {
    if (lights.empty() || lights.size() > size_t(kMaxLights))
        return QStringLiteral("%1 lights; a scene needs 1 to %2")
            .arg(lights.size())
            .arg(kMaxLights);
    for (size_t i = 0; i < lights.size(); ++i) {
        const QString e = lightError(lights[i]);
        if (!e.isEmpty())
            return QStringLiteral("light %1: %2").arg(i + 1).arg(e);
    }
    return {};
}

QString cameraError(const Camera& c) {
    if (!finite(c.eye) || !finite(c.target) || !finite(c.up))
        return QStringLiteral("camera vectors must be finite");
    const glm::dvec3 view = c.target - c.eye;
    if (glm::length(view) <= 1e-12)
        return QStringLiteral("camera eye and target coincide");
    if (glm::length(glm::cross(view, c.up)) <= 1e-12 * glm::length(view))
        return QStringLiteral("camera up vector is zero or parallel to the view direction");
    if (!(finite(c.fovYDegrees) && c.fovYDegrees > 0 && c.fovYDegrees < 180))
        return QStringLiteral("camera field of view must be in (0, 180) degrees");
    return {};
}

QString trimLoopError(const TrimLoop& loop) {
    if (!loop.id.isValid())
        return QStringLiteral("trim loop has no id");
    if (loop.curves.empty())
        return QStringLiteral("trim loop %1 has no curves").arg(loop.id.value);
    for (size_t i = 0; i < loop.curves.size(); ++i) {
        const std::string e = curveValidationError(loop.curves[i]);
        if (!e.empty())
            return QStringLiteral("trim loop %1, curve %2: %3")
                .arg(loop.id.value)
                .arg(i + 1)
                .arg(QString::fromStdString(e));
    }
    return {};
}

QString surfaceError(const Surface& s) {
    if (!s.id.isValid())
        return QStringLiteral("surface has no id");
    const QString who = QStringLiteral("surface %1").arg(s.id.value);
    const std::string g = surfaceValidationError(s.geometry);
    if (!g.empty())
        return who + QStringLiteral(": ") + QString::fromStdString(g);
    QString e = partitionsError(s.partitionsU, s.partitionsV);
    if (e.isEmpty())
        e = materialError(s.material);
    std::set<std::uint32_t> loops;
    for (size_t i = 0; e.isEmpty() && i < s.trims.size(); ++i) {
        e = trimLoopError(s.trims[i]);
        if (e.isEmpty() && !loops.insert(s.trims[i].id.value).second)
            e = QStringLiteral("trim loop id %1 used twice").arg(s.trims[i].id.value);
    }
    return e.isEmpty() ? QString() : who + QStringLiteral(": ") + e;
}

} // namespace kw
