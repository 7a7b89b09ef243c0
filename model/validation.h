// Validation of authored data, shared by Document and by the edit commands that check an edit
// before it is pushed. Each function returns an empty string when valid, else the reason.
#pragma once

#include "model/scene.h"

#include <QString>
#include <vector>

namespace kw {

/// Both counts in [kMinPartitions, kMaxPartitions].
QString partitionsError(int nu, int nv);
/// Colour and coefficients finite and >= 0.
QString materialError(const Material& material);
/// Known kind; vector finite (non-zero for a directional light); intensities finite and >= 0.
QString lightError(const Light& light);
/// 1..kMaxLights lights, each valid.
QString lightsError(const std::vector<Light>& lights);
/// Finite eye, target and up; eye != target; up not parallel to the view direction;
/// fovYDegrees in (0, 180).
QString cameraError(const Camera& camera);
/// A valid id and at least one curve, each valid (kw::curveValidationError).
QString trimLoopError(const TrimLoop& loop);
/// A valid id, geometry valid (kw::surfaceValidationError), partitions in range, material
/// valid, every trim loop valid and loop ids unique within the surface. Ids against other
/// surfaces are the document's business.
QString surfaceError(const Surface& surface);

} // namespace kw
