// The exact pass's program variants turned into GLSL defines, in one place.
#include "render/exact_contract.h"

#include "render/gpu_layout.h"

namespace kw {

QStringList featureDefines(ExactFeatures features) {
    QStringList d;
    for (const ExactFeatureDefine& f : kExactFeatureDefines)
        if (features.testFlag(f.feature))
            d << QLatin1String(f.define);
    return d;
}

ExactFeatures analysisFeatures(const AnalysisOptions& options, bool curvatureAov) {
    ExactFeatures f;
    f.setFlag(ExactFeature::Isocurves, options.isocurves);
    f.setFlag(ExactFeature::Directions, options.principalDirections);
    // Curvature for the curvature maps, the curvature AOV and the principal directions.
    f.setFlag(ExactFeature::SecondOrder,
              needsCurvature(options.mode) || curvatureAov || options.principalDirections);
    f.setFlag(ExactFeature::AovCurvature, curvatureAov);
    return f;
}

QStringList ExactVariant::defines() const {
    QStringList d;
    if (degreeU > 0)
        d << QStringLiteral("DEGREE_U %1").arg(degreeU)
          << QStringLiteral("DEGREE_V %1").arg(degreeV)
          << QStringLiteral("KW_SPAN_TEXELS_U %1").arg(spanTableTexels(degreeU))
          << QStringLiteral("KW_SPAN_TEXELS_V %1").arg(spanTableTexels(degreeV))
          << QStringLiteral("LIGHT_COUNT %1").arg(lightCount);
    d << featureDefines(features);
    if (analysis != AnalysisMode::Phong)
        d << QStringLiteral("KW_ANALYSIS %1").arg(int(analysis));
    if (isColourMap(analysis)) {
        const std::vector<glm::vec3>& r = colourRamp();
        QStringList stops;
        for (const glm::vec3& c : r)
            stops << QStringLiteral("vec3(%1, %2, %3)").arg(c.x).arg(c.y).arg(c.z);
        d << QStringLiteral("KW_RAMP_STOPS %1").arg(r.size())
          << QStringLiteral("KW_RAMP vec3[](%1)").arg(stops.join(QStringLiteral(", ")));
    }
    if (analysis == AnalysisMode::Draft) {
        const auto vec = [](const glm::vec3& c) {
            return QStringLiteral("vec3(%1, %2, %3)").arg(c.x).arg(c.y).arg(c.z);
        };
        const DraftColours& c = draftColours();
        d << QStringLiteral("KW_DRAFT_OK ") + vec(c.draft)
          << QStringLiteral("KW_DRAFT_INSUFFICIENT ") + vec(c.insufficient)
          << QStringLiteral("KW_DRAFT_UNDERCUT ") + vec(c.undercut);
    }
    return d;
}

} // namespace kw
