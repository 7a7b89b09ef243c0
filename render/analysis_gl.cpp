// Environment map loading (OpenImageIO for a chosen file, QImage for the default one) and the
// analysis uniforms.
#include "render/analysis_gl.h"

#include "model/io/install_layout.h"
#include "render/image_reader.h"
#include "render/shader_library.h"

#include <QImage>
#include <QOpenGLShaderProgram>
#include <algorithm>
#include <cmath>
#include <glm/gtc/type_ptr.hpp>

namespace kw {

namespace {

/// A Qt resource (":/...", which OpenImageIO cannot open) or the default PNG, through Qt's PNG
/// reader: the default environment does not load OpenImageIO's libraries.
Expected<EnvironmentImage> loadQtImage(const QString& path) {
    const QImage img = QImage(path).convertToFormat(QImage::Format_RGB888);
    if (img.isNull())
        return Error(QStringLiteral("%1: cannot read the environment image").arg(path), path);
    EnvironmentImage out;
    out.width = img.width();
    out.height = img.height();
    out.rgb.resize(size_t(out.width) * size_t(out.height) * 3);
    for (int y = 0; y < out.height; ++y) {
        const uchar* line = img.constScanLine(y);
        for (int k = 0; k < out.width * 3; ++k)
            out.rgb[size_t(y) * size_t(out.width) * 3 + size_t(k)] = float(line[k]) / 255.0f;
    }
    return out;
}

} // namespace

QString defaultEnvironmentPath() {
    const QString data = dataDir();
    return data.isEmpty() ? QString() : data + QStringLiteral("/environment/studio.png");
}

Expected<EnvironmentImage> loadEnvironmentImage(const QString& path) {
    if (path.startsWith(QLatin1String(":/")))
        return loadQtImage(path);
    const Expected<FloatImage> read = readImageFile(path);
    if (!read)
        return Error(QStringLiteral("cannot read the environment image %1").arg(read.message()),
                     path);
    const FloatImage& img = *read;
    EnvironmentImage out;
    // RGB from 1 (grey), 2 (grey, alpha), 3 or 4 (RGBA) channels. HDR values above 1 are kept
    // (the reflection is as bright as the file says; the framebuffer clamps); NaN, infinite
    // and negative values, which a reflection cannot show, become 0.
    out.width = img.width;
    out.height = img.height;
    out.rgb.resize(size_t(img.width) * size_t(img.height) * 3);
    const size_t pixels = size_t(img.width) * size_t(img.height);
    for (size_t p = 0; p < pixels; ++p) {
        const float* in = img.pixels.data() + p * size_t(img.channels);
        for (int c = 0; c < 3; ++c) {
            const float x = in[img.channels >= 3 ? c : 0];
            out.rgb[p * 3 + size_t(c)] = std::isfinite(x) && x > 0.0f ? x : 0.0f;
        }
    }
    return out;
}

Status EnvironmentMap::bind(const QString& requested, int unit) {
    const bool standard = requested.isEmpty();
    const QString path = standard ? defaultEnvironmentPath() : requested;
    if (path.isEmpty())
        return Error(QStringLiteral("no default environment image: share/knotwork/environment/"
                                    "studio.png is not in the prefix of %1")
                         .arg(executableDir()));
    if (!m_texture || path != m_path) {
        if (path == m_failedPath) // do not retry a bad file every frame
            return m_failedError;
        const Expected<EnvironmentImage> loaded =
            standard ? loadQtImage(path) : loadEnvironmentImage(path);
        if (!loaded) {
            m_failedPath = path;
            m_failedError = loaded.error();
            return loaded.error();
        }
        const EnvironmentImage& img = *loaded;
        release();
        m_gl->glCreateTextures(GL_TEXTURE_2D, 1, &m_texture);
        m_gl->glTextureStorage2D(m_texture, 1, GL_RGB32F, img.width, img.height);
        // Row 0 of the image is the top (latitude +90); GL's t = 0 is the first row uploaded,
        // and analysis.glsl maps latitude +90 to t = 0.
        m_gl->glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        m_gl->glTextureSubImage2D(m_texture, 0, 0, 0, img.width, img.height, GL_RGB, GL_FLOAT,
                                  img.rgb.data());
        // No mipmaps: the longitude seam would pick the coarsest level along a line.
        m_gl->glTextureParameteri(m_texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        m_gl->glTextureParameteri(m_texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        m_gl->glTextureParameteri(m_texture, GL_TEXTURE_WRAP_S, GL_REPEAT);
        m_gl->glTextureParameteri(m_texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        m_path = path;
        m_failedPath.clear();
        ++m_loads;
    }
    m_gl->glBindTextureUnit(GLuint(unit), m_texture);
    return ok();
}

void EnvironmentMap::release() {
    if (m_gl && m_texture)
        m_gl->glDeleteTextures(1, &m_texture);
    m_texture = 0;
    m_path.clear();
}

void setAnalysisUniforms(QOpenGLFunctions_4_5_Core* gl, QOpenGLShaderProgram* program,
                         const AnalysisOptions& o, const ValueRange& range,
                         const FrameCamera& camera, const std::vector<Light>& lights,
                         int environmentUnit) {
    // Locations looked up once per program (ShaderLibrary), not by name on every draw.
    const UniformLocations& u = ShaderLibrary::uniforms(program);
    const float toRad = float(M_PI / 180.0);
    // By the parameters the mode's row names, so a new mode with no new parameters adds no case.
    switch (analysisParameters(o.mode)) {
    case AnalysisParameters::ColourMap:
        gl->glUniform2f(u.analysisRange, float(range.low), float(range.high));
        gl->glUniform1i(u.analysisScale, int(o.scale.value_or(defaultScale(o.mode))));
        break;
    case AnalysisParameters::Stripes: {
        // The stripe axis in the view plane: angle 0 along the camera's right, 90 along its up.
        const glm::mat3 rot = glm::transpose(glm::mat3(camera.view)); // view -> world rotation
        const glm::vec3 right = rot[0], up = rot[1];
        const float a = float(o.stripeAngleDegrees) * toRad;
        const glm::vec3 axis = glm::normalize(std::cos(a) * right + std::sin(a) * up);
        // The tubes go all the way round the axis: 2 count bands per turn must be whole, or
        // the pattern breaks where the reflected angle wraps (behind the viewer, on every
        // silhouette's rim). A count is drawn as the nearest whole number of halves.
        const double count = std::max(0.5, std::round(2.0 * o.stripeCount) / 2.0);
        gl->glUniform1f(u.stripeCount, float(count));
        gl->glUniform3fv(u.stripeAxis, 1, glm::value_ptr(axis));
        break;
    }
    case AnalysisParameters::Isophotes: {
        // The first light's direction (a point light: from the scene centre's side, the eye).
        glm::vec3 L = -camera.forward;
        if (!lights.empty() && lights.front().kind == Light::Kind::Directional &&
            glm::length(lights.front().vector) > 0.0)
            L = glm::vec3(glm::normalize(lights.front().vector));
        gl->glUniform1f(u.isophoteCount, float(o.isophoteCount));
        gl->glUniform3fv(u.isophoteLight, 1, glm::value_ptr(L));
        break;
    }
    case AnalysisParameters::Environment:
        gl->glUniform1i(u.environment, environmentUnit);
        break;
    case AnalysisParameters::Draft: {
        const glm::dvec3 d = glm::length(o.pullDirection) > 0.0 ? glm::normalize(o.pullDirection)
                                                                : glm::dvec3(0.0, 0.0, 1.0);
        gl->glUniform3fv(u.pullDirection, 1, glm::value_ptr(glm::vec3(d)));
        gl->glUniform1f(u.draftAngle, float(o.draftAngleDegrees) * toRad);
        break;
    }
    case AnalysisParameters::None:
        break;
    }
    if (o.principalDirections) {
        gl->glUniform1f(u.dirSpacing, float(std::clamp(o.directionSpacingPixels, 6.0, 512.0)));
    }
    if (o.isocurves) {
        gl->glUniform2f(u.isoCount, float(std::max(o.isoCount.x, 0)),
                        float(std::max(o.isoCount.y, 0)));
        gl->glUniform1f(u.isoWidth, float(o.isoWidthPixels));
        gl->glUniform3f(u.isoColour, 0.08f, 0.08f, 0.08f);
        gl->glUniform3f(u.knotColour, 0.85f, 0.1f, 0.55f);
    }
}

} // namespace kw
