// Shader loading with #include expansion and variant defines; programs cached per variant.
#include "render/shader_library.h"

#include "render/exact_contract.h"

#include <QFile>
#include <QOpenGLShaderProgram>
#include <QRegularExpression>

namespace kw {

namespace {

Status expand(const QString& file, int depth, QString& out) {
    if (depth > 8)
        return Error(QStringLiteral("shader includes nested too deeply at %1").arg(file), file);
    const QString dir = ShaderLibrary::sourceDirectory();
    QFile f(dir + QLatin1Char('/') + file);
    if (!f.open(QIODevice::ReadOnly | QIODevice::Text))
        return Error(QStringLiteral("shader file %1/%2 not found").arg(dir, file), file);
    static const QRegularExpression include(QStringLiteral("^\\s*#include\\s+\"([^\"]+)\"\\s*$"));
    const QStringList lines = QString::fromUtf8(f.readAll()).split(QLatin1Char('\n'));
    for (const QString& line : lines) {
        const QRegularExpressionMatch m = include.match(line);
        if (m.hasMatch()) {
            if (Status included = expand(m.captured(1), depth + 1, out); !included)
                return included;
        } else {
            out += line;
            out += QLatin1Char('\n');
        }
    }
    return ok();
}

} // namespace

namespace {
QString& sourceDirectoryOverride() {
    static QString dir;
    return dir;
}
} // namespace

void ShaderLibrary::setSourceDirectory(const QString& dir) {
    sourceDirectoryOverride() = dir;
}

QString ShaderLibrary::sourceDirectory() {
    const QString& dir = sourceDirectoryOverride();
    return dir.isEmpty() ? QStringLiteral(":/shaders") : dir;
}

ShaderLibrary::ShaderLibrary() = default;

QString ShaderLibrary::preamble() {
    QString out;
    for (const ShaderConstant& c : kShaderConstants)
        out += QStringLiteral("#define %1 %2\n").arg(QLatin1String(c.name)).arg(c.value);
    for (const AnalysisMode m : analysisModes())
        out += QStringLiteral("#define %1 %2\n").arg(analysisModeDefine(m)).arg(int(m));
    return out;
}
ShaderLibrary::~ShaderLibrary() = default;

Expected<QString> ShaderLibrary::expandedSource(const QString& file) {
    QString out;
    if (Status expanded = expand(file, 0, out); !expanded)
        return std::move(expanded).error();
    return out;
}

namespace {

/// A program with its uniform locations (ShaderLibrary::uniforms).
class Program : public QOpenGLShaderProgram {
public:
    void lookUpUniforms() {
        UniformLocations& u = locations;
        const std::pair<int*, const char*> names[] = {{&u.viewProjection, "uViewProjection"},
                                                      {&u.eye, "uEye"},
                                                      {&u.forward, "uForward"},
                                                      {&u.viewport, "uViewport"},
                                                      {&u.ambient, "uAmbient"},
                                                      {&u.fill, "uFill"},
                                                      {&u.backgroundBottom, "uBackgroundBottom"},
                                                      {&u.backgroundTop, "uBackgroundTop"},
                                                      {&u.lightVector, "uLightVector"},
                                                      {&u.lightDiffuse, "uLightDiffuse"},
                                                      {&u.lightSpecular, "uLightSpecular"},
                                                      {&u.color, "uColor"},
                                                      {&u.material, "uMaterial"},
                                                      {&u.surfaceId, "uSurfaceId"},
                                                      {&u.trimMask, "uTrimMask"},
                                                      {&u.trimRect, "uTrimRect"},
                                                      {&u.trimSize, "uTrimSize"},
                                                      {&u.trimLayerScale, "uTrimLayerScale"},
                                                      {&u.trimLayer, "uTrimLayer"},
                                                      {&u.trimBlock, "uTrimBlock"},
                                                      {&u.skirtPixels, "uSkirtPixels"},
                                                      {&u.skirtReach, "uSkirtReach"},
                                                      {&u.skirtDepthScale, "uSkirtDepthScale"},
                                                      {&u.sectionPlanes, "uSectionPlanes"},
                                                      {&u.sectionCount, "uSectionCount"},
                                                      {&u.sectionCaps, "uSectionCaps"},
                                                      {&u.solidSide, "uSolidSide"},
                                                      {&u.depthBias, "uDepthBias"},
                                                      {&u.pointSize, "uPointSize"},
                                                      {&u.lineColor, "uLineColor"},
                                                      {&u.analysisRange, "uAnalysisRange"},
                                                      {&u.analysisScale, "uAnalysisScale"},
                                                      {&u.stripeCount, "uStripeCount"},
                                                      {&u.stripeAxis, "uStripeAxis"},
                                                      {&u.isophoteCount, "uIsophoteCount"},
                                                      {&u.isophoteLight, "uIsophoteLight"},
                                                      {&u.environment, "uEnvironment"},
                                                      {&u.pullDirection, "uPullDirection"},
                                                      {&u.draftAngle, "uDraftAngle"},
                                                      {&u.dirSpacing, "uDirSpacing"},
                                                      {&u.isoCount, "uIsoCount"},
                                                      {&u.isoWidth, "uIsoWidth"},
                                                      {&u.isoColour, "uIsoColour"},
                                                      {&u.knotColour, "uKnotColour"}};
        for (const auto& [slot, name] : names)
            *slot = uniformLocation(name);
    }
    UniformLocations locations;
};

} // namespace

const UniformLocations& ShaderLibrary::uniforms(const QOpenGLShaderProgram* program) {
    return static_cast<const Program*>(program)->locations;
}

Expected<QOpenGLShaderProgram*>
ShaderLibrary::program(const QString& vertex, const QString& fragment, const QStringList& defines) {
    const QString key =
        vertex + QLatin1Char('|') + fragment + QLatin1Char('|') + defines.join(QLatin1Char(','));
    auto it = m_programs.find(key);
    if (it != m_programs.end()) {
        if (!it.value())
            return m_failures.value(key);
        return it.value().get();
    }
    static const QString shared = preamble();
    QString header = QStringLiteral("#version 450 core\n") + shared;
    for (const QString& d : defines)
        header += QStringLiteral("#define ") + d + QLatin1Char('\n');

    auto prog = std::make_shared<Program>();
    QString error, file;
    const Expected<QString> vs = expandedSource(vertex);
    const Expected<QString> fs = vs ? expandedSource(fragment) : Expected<QString>(vs.error());
    bool ok = vs && fs;
    if (!ok)
        error = fs.message(), file = fs.error().file;
    // Cacheable: link() first looks for a program binary in Qt's disk cache
    // (QStandardPaths::CacheLocation/qtshadercache-*, keyed by a SHA-1 of the full sources, so
    // of the defines too; each entry records GL_VENDOR/RENDERER/VERSION and is ignored when
    // they differ) and compiles only on a miss, then stores the binary (glGetProgramBinary)
    // where the driver offers a binary format. QT_DISABLE_SHADER_DISK_CACHE=1 turns it off.
    if (ok && !prog->addCacheableShaderFromSourceCode(QOpenGLShader::Vertex, header + *vs))
        ok = false, error = QStringLiteral("%1: %2").arg(vertex, prog->log()), file = vertex;
    if (ok && !prog->addCacheableShaderFromSourceCode(QOpenGLShader::Fragment, header + *fs))
        ok = false, error = QStringLiteral("%1: %2").arg(fragment, prog->log()), file = fragment;
    if (ok && !prog->link())
        ok = false,
        error = QStringLiteral("linking %1 + %2: %3").arg(vertex, fragment, prog->log());
    if (!ok) {
        const Error failed(
            QStringLiteral("shader variant [%1]: %2").arg(defines.join(QLatin1Char(' ')), error),
            file, defines.join(QLatin1Char(' ')));
        m_programs.insert(key, nullptr);
        m_failures.insert(key, failed);
        return failed;
    }
    prog->lookUpUniforms();
    m_programs.insert(key, prog);
    return prog.get();
}

void ShaderLibrary::clear() {
    m_programs.clear();
    m_failures.clear();
}

} // namespace kw
