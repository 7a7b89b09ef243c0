// Loads GLSL from the bundled /shaders resources, expands #include, injects variant #defines
// and caches linked programs by (files, defines), in memory and as program binaries on disk.
#pragma once

#include <QMap>
#include <QString>
#include <QStringList>
#include <memory>

class QOpenGLShaderProgram;

namespace kw {

class ShaderLibrary {
public:
    ShaderLibrary();
    ~ShaderLibrary();
    ShaderLibrary(const ShaderLibrary&) = delete;
    ShaderLibrary& operator=(const ShaderLibrary&) = delete;

    /// The program linked from the resource files `vertex` and `fragment` (names under
    /// :/shaders, or under $KW_SHADER_DIR when set, for shader development) with `defines` ("NAME"
    /// or "NAME VALUE") inserted after the #version line. Needs a current OpenGL 4.5 core context.
    /// Returns nullptr and sets lastError() when a file is missing or compiling/linking fails;
    /// failures are cached too (no retry storms).
    QOpenGLShaderProgram* program(const QString& vertex, const QString& fragment,
                                  const QStringList& defines = {});
    QString lastError() const { return m_lastError; }
    /// Deletes every program; needs the context that created them to be current.
    void clear();

    /// The source of `file` with #include "x" lines replaced by the files (recursively, at
    /// most 8 deep), or an empty string with *error set.
    static QString expandedSource(const QString& file, QString* error);

private:
    QMap<QString, std::shared_ptr<QOpenGLShaderProgram>> m_programs;
    QString m_lastError;
};

} // namespace kw
