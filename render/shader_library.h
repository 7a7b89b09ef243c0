// Loads GLSL from the bundled /shaders resources, expands #include, injects variant #defines
// and caches linked programs by (files, defines), in memory and as program binaries on disk.
#pragma once

#include "model/error.h"

#include <QMap>
#include <QString>
#include <QStringList>
#include <memory>

class QOpenGLShaderProgram;

namespace kw {

/// Uniform locations of one program, looked up once when it is linked (-1 where the program
/// does not use the uniform), so no draw asks the driver by name. Names are the shaders'.
struct UniformLocations {
    int viewProjection = -1, eye = -1, forward = -1, viewport = -1;            // camera
    int ambient = -1, lightVector = -1, lightDiffuse = -1, lightSpecular = -1; // phong.glsl
    int fill = -1;                                                             // phong.glsl
    int color = -1, material = -1, surfaceId = -1;                             // per surface
    int trimMask = -1, trimRect = -1, trimSize = -1, trimLayerScale = -1, trimLayer = -1;
    int trimBlock = -1;
    int skirtPixels = -1, skirtReach = -1, skirtDepthScale = -1; // the edge skirts' (KW_SKIRT)
    int sectionPlanes = -1, sectionCount = -1, sectionCaps = -1; // section.glsl (KW_SECTION)
    int solidSide = -1; // tessellated.frag's (the exact pass reads the surface table's)
    int depthBias = -1, pointSize = -1, lineColor = -1; // lines.vert/.frag
    // analysis.glsl (render/analysis_gl.cpp), by mode
    int analysisRange = -1, analysisScale = -1, stripeCount = -1, stripeAxis = -1;
    int isophoteCount = -1, isophoteLight = -1, environment = -1, pullDirection = -1;
    int draftAngle = -1, dirSpacing = -1, isoCount = -1, isoWidth = -1;
    int isoColour = -1, knotColour = -1;
    int backgroundBottom = -1, backgroundTop = -1; // background.frag
};

class ShaderLibrary {
public:
    ShaderLibrary();
    ~ShaderLibrary();
    ShaderLibrary(const ShaderLibrary&) = delete;
    ShaderLibrary& operator=(const ShaderLibrary&) = delete;

    /// Where shader files are read from: the bundled :/shaders, or `dir` (not empty) for shader
    /// development and measurements with modified shaders (the executables set it from
    /// KW_SHADER_DIR, kw::cli::applyDevelopmentSwitches; tools/speed_floor.py relies on it).
    /// Process-wide; set it before the first program is built (programs are cached).
    static void setSourceDirectory(const QString& dir);
    static QString sourceDirectory();

    /// The program linked from the files `vertex` and `fragment` (names under
    /// sourceDirectory()) with the preamble
    /// and `defines` ("NAME" or "NAME VALUE") inserted after the #version line. Needs a current
    /// OpenGL 4.5 core context. Returns the error when a file is missing or compiling/linking
    /// fails (Error::file the shader file, Error::location the variant's defines); failures are
    /// cached too (no retry storms), and a cached failure returns the same error. The program
    /// is never null on success.
    Expected<QOpenGLShaderProgram*> program(const QString& vertex, const QString& fragment,
                                            const QStringList& defines = {});
    /// Deletes every program; needs the context that created them to be current.
    void clear();
    /// The locations of a program returned by any ShaderLibrary's program().
    static const UniformLocations& uniforms(const QOpenGLShaderProgram* program);

    /// The #define line of every constant C++ and the shaders share (kw::kShaderConstants,
    /// render/exact_contract.h, and each analysis mode's kw::analysisModeDefine), which
    /// program() puts after the #version line of each stage.
    static QString preamble();

    /// The source of `file` with #include "x" lines replaced by the files (recursively, at
    /// most 8 deep), or the error naming the file that is missing or nested too deeply.
    static Expected<QString> expandedSource(const QString& file);

private:
    QMap<QString, std::shared_ptr<QOpenGLShaderProgram>> m_programs;
    /// The build error of each variant that failed, repeated on every later request so the
    /// message stays the compiler's (and the same each frame) rather than "failed earlier".
    QMap<QString, Error> m_failures;
};

} // namespace kw
