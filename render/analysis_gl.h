// GL side of the analysis modes: the environment map texture and the uniforms of analysis.glsl.
#pragma once

#include "model/error.h"
#include "render/analysis.h"
#include "render/render_types.h"

#include <QOpenGLFunctions_4_5_Core>
#include <QString>
#include <vector>

class QOpenGLShaderProgram;

namespace kw {

/// An equirectangular environment image as float RGB, row 0 at the top.
struct EnvironmentImage {
    int width = 0;
    int height = 0;
    std::vector<float> rgb;
};

/// The default environment: environment/studio.png of the data folder (kw::dataDir(): the
/// installed share/knotwork, or build/share/knotwork), made by tools/make_environment.py.
QString defaultEnvironmentPath();

/// Reads `path`: a file through OpenImageIO (EXR, HDR, PNG, JPEG, TIFF, ...: render/image_reader.h;
/// float values above 1 are kept), or a Qt resource path ":/..." (the bundled default) through
/// Qt's PNG reader. Grey images are expanded, alpha is dropped, non-finite or negative values
/// become 0. Returns the error naming the file on failure (missing, unknown format, corrupt,
/// too large, module not loadable).
Expected<EnvironmentImage> loadEnvironmentImage(const QString& path);

/// The environment map texture, (re)loaded when the requested path changes.
class EnvironmentMap {
public:
    void initialize(QOpenGLFunctions_4_5_Core* gl) { m_gl = gl; }
    /// Binds the texture of `path` (empty: the bundled default) to `unit`. A file that cannot
    /// be read returns its error (the previous texture, if any, stays bound).
    Status bind(const QString& path, int unit);
    /// Frees the texture; the initialising context must be current.
    void release();
    /// Texture (re)loads so far, for tests: switching back and forth between modes must not
    /// reload an unchanged image.
    int loads() const { return m_loads; }

private:
    QOpenGLFunctions_4_5_Core* m_gl = nullptr;
    GLuint m_texture = 0;
    QString m_path; ///< what m_texture holds
    QString m_failedPath;
    Error m_failedError;
    int m_loads = 0;
};

/// Sets the uniforms of analysis.glsl for `options` on the bound `program` (built with
/// analysisDefines(options, ...)): the resolved colour range, stripe, isophote, draft and
/// isocurve parameters (directions derived from `camera` where they are view-relative), and
/// the environment sampler on `environmentUnit`.
void setAnalysisUniforms(QOpenGLFunctions_4_5_Core* gl, QOpenGLShaderProgram* program,
                         const AnalysisOptions& options, const ValueRange& range,
                         const FrameCamera& camera, const std::vector<Light>& lights,
                         int environmentUnit);

} // namespace kw
