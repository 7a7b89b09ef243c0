// The exact pass's C++/GLSL contract without GL: ShaderLibrary's preamble defines every shared
// constant (render/exact_contract.h) with its C++ value, the degree defines carry the span-table
// widths of kw::spanTableTexels, and no shader file repeats one of them as a literal.
#include "render/exact_contract.h"
#include "render/exact_surface_pass.h"
#include "render/gpu_layout.h"
#include "render/shader_library.h"

#include <QDir>
#include <QFile>
#include <QRegularExpression>
#include <QSet>
#include <QtTest>

using namespace kw;

namespace {

/// Lines of `source` that write a shared constant as a number instead of its name: any layout
/// qualifier's number (texture and buffer bindings, vertex attribute and fragment output
/// locations), the light array's size, analysis modes and colour scales, the surface
/// table's and the vertex pool's layouts, the span-table formula.
QStringList literalViolations(const QString& source) {
    static const QRegularExpression patterns[] = {
        QRegularExpression(QStringLiteral(
            "layout\\s*\\([^)]*\\b(binding|location|index|component)\\s*=\\s*[-+(]*\\d")),
        QRegularExpression(QStringLiteral("uniform\\s+\\w+\\s+\\w+\\s*\\[\\s*\\d")),
        QRegularExpression(QStringLiteral("\\bkMaxLights\\b")),
        QRegularExpression(QStringLiteral("KW_ANALYSIS\\s*(==|!=|>=|<=|>|<)\\s*\\d")),
        QRegularExpression(QStringLiteral("#define\\s+KW_ANALYSIS\\s+\\d")),
        QRegularExpression(QStringLiteral("uAnalysisScale\\s*(==|!=)\\s*\\d")),
        QRegularExpression(QStringLiteral("kwSurface\\s*\\*\\s*\\d")),
        QRegularExpression(QStringLiteral("KW_ROW\\(\\s*\\d")),
        QRegularExpression(QStringLiteral("KW_SPAN_TEXELS\\s*\\(")),
        QRegularExpression(QStringLiteral("kwVertexWord\\(\\s*at\\s*\\+\\s*\\d")),
        QRegularExpression(QStringLiteral("\\bg\\.w\\s*\\*\\s*\\d")),
    };
    QStringList out;
    const QStringList lines = source.split(QLatin1Char('\n'));
    for (int k = 0; k < lines.size(); ++k) {
        // Comments may name the values (they explain them).
        const QString code = lines[k].section(QStringLiteral("//"), 0, 0);
        for (const QRegularExpression& p : patterns)
            if (p.match(code).hasMatch()) {
                out << QStringLiteral("line %1: %2").arg(k + 1).arg(lines[k].trimmed());
                break;
            }
    }
    return out;
}

/// Declarations of `source` (a .vert's inputs when `vertexInputs`, else a .frag's outputs) that
/// leave their location to the linker or give it as something other than a contract name.
QStringList unnamedLocations(const QString& source, bool vertexInputs) {
    static const QRegularExpression input(
        QStringLiteral("^\\s*(layout\\s*\\(([^)]*)\\)\\s*)?(flat\\s+)?in\\s+\\w+\\s+\\w+"));
    static const QRegularExpression output(
        QStringLiteral("^\\s*(layout\\s*\\(([^)]*)\\)\\s*)?(flat\\s+)?out\\s+\\w+\\s+\\w+"));
    static const QRegularExpression named(QStringLiteral("^\\s*location\\s*=\\s*KW_\\w+\\s*$"));
    QStringList out;
    const QStringList lines = source.split(QLatin1Char('\n'));
    for (int k = 0; k < lines.size(); ++k) {
        const QRegularExpressionMatch m = (vertexInputs ? input : output).match(lines[k]);
        if (m.hasMatch() && !named.match(m.captured(2)).hasMatch())
            out << QStringLiteral("line %1: %2").arg(k + 1).arg(lines[k].trimmed());
    }
    return out;
}

/// Lines of a C++ source that give a vertex attribute's location as a number: the vertex
/// array calls whose second argument is the attribute.
QStringList numericAttributes(const QString& source) {
    static const QRegularExpression call(QStringLiteral(
        "gl(?:EnableVertexArrayAttrib|DisableVertexArrayAttrib|VertexArrayAttrib[IL]?Format|"
        "VertexArrayAttribBinding)\\s*\\(\\s*[^,()]+,\\s*\\d"));
    QStringList out;
    const QStringList lines = source.split(QLatin1Char('\n'));
    for (int k = 0; k < lines.size(); ++k)
        if (call.match(lines[k].section(QStringLiteral("//"), 0, 0)).hasMatch())
            out << QStringLiteral("line %1: %2").arg(k + 1).arg(lines[k].trimmed());
    return out;
}

QStringList shaderFiles() {
    const QDir dir(QStringLiteral(KW_SOURCE_DIR "/shaders"));
    return dir.entryList(
        {QStringLiteral("*.glsl"), QStringLiteral("*.vert"), QStringLiteral("*.frag")}, QDir::Files,
        QDir::Name);
}

QString readShader(const QString& name) {
    QFile f(QStringLiteral(KW_SOURCE_DIR "/shaders/") + name);
    if (!f.open(QIODevice::ReadOnly | QIODevice::Text))
        return {};
    return QString::fromUtf8(f.readAll());
}

} // namespace

class TestRenderContract : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void preambleDefinesEveryConstant() {
        const QString preamble = ShaderLibrary::preamble();
        QSet<QString> names;
        for (const ShaderConstant& c : kShaderConstants) {
            const QString name = QLatin1String(c.name);
            QVERIFY2(!names.contains(name), qPrintable(name + QStringLiteral(" twice")));
            names.insert(name);
            const QString line = QStringLiteral("#define %1 %2\n").arg(name).arg(c.value);
            QVERIFY2(preamble.contains(line), qPrintable(line));
        }
        // Each analysis mode's number, named from its table entry: a new mode needs no
        // contract line.
        for (const AnalysisMode m : analysisModes()) {
            const QString name = analysisModeDefine(m);
            QVERIFY2(!names.contains(name), qPrintable(name + QStringLiteral(" twice")));
            names.insert(name);
            QVERIFY2(preamble.contains(QStringLiteral("#define %1 %2\n").arg(name).arg(int(m))),
                     qPrintable(name));
        }
        QCOMPARE(preamble.count(QStringLiteral("#define ")),
                 int(kShaderConstants.size() + analysisModes().size()));
        // The values are C++'s own, not copies.
        QVERIFY(preamble.contains(QStringLiteral("#define KW_MAX_LIGHTS %1\n").arg(kMaxLights)));
        QVERIFY(preamble.contains(
            QStringLiteral("#define KW_ANALYSIS_DRAFT %1\n").arg(int(AnalysisMode::Draft))));
        QVERIFY(preamble.contains(
            QStringLiteral("#define KW_SCALE_LOG %1\n").arg(int(ColourScale::Log))));
        QVERIFY(preamble.contains(
            QStringLiteral("#define KW_SPAN_UNIT %1\n").arg(kSurfaceTableUnit + 3)));
        QVERIFY(
            preamble.contains(QStringLiteral("#define KW_TRIM_GRID_UNIT %1\n").arg(kTrimGridUnit)));
        // The section planes' array size and the caps' AOV id.
        QVERIFY(preamble.contains(
            QStringLiteral("#define KW_MAX_SECTIONS %1\n").arg(kMaxSectionPlanes)));
        QVERIFY(
            preamble.contains(QStringLiteral("#define KW_SECTION_CAP_ID %1\n").arg(kSectionCapId)));
        QCOMPARE(featureDefines(ExactFeature::Section), QStringList{QStringLiteral("KW_SECTION")});
        // Attribute and output locations.
        QVERIFY(
            preamble.contains(QStringLiteral("#define KW_ATTR_OUTWARD %1\n").arg(kAttrOutward)));
        QVERIFY(preamble.contains(
            QStringLiteral("#define KW_AOV_CURVATURE_OUTPUT %1\n").arg(kAovCurvatureOutput)));
    }

    void degreeDefinesCarrySpanTableWidths() {
        for (int p = 1; p <= 15; ++p)
            for (int q : {1, 3, 15}) {
                const QStringList d = ExactVariant{p, q, 2, AnalysisMode::Phong, {}}.defines();
                QVERIFY(d.contains(QStringLiteral("KW_SPAN_TEXELS_U %1").arg(spanTableTexels(p))));
                QVERIFY(d.contains(QStringLiteral("KW_SPAN_TEXELS_V %1").arg(spanTableTexels(q))));
                QVERIFY(d.contains(QStringLiteral("DEGREE_U %1").arg(p)));
                QVERIFY(d.contains(QStringLiteral("LIGHT_COUNT 2")));
            }
    }

    void variantDefinesOneLinePerBit() {
        // Every feature has its own define, and a variant lists exactly its bits' defines.
        QSet<QString> names;
        ExactFeatures all;
        for (const ExactFeatureDefine& f : kExactFeatureDefines) {
            QVERIFY(!names.contains(QLatin1String(f.define)));
            names.insert(QLatin1String(f.define));
            QVERIFY(!all.testFlag(f.feature));
            all |= f.feature;
            QCOMPARE(featureDefines(f.feature), QStringList{QLatin1String(f.define)});
        }
        QCOMPARE(int(names.size()), 20);
        const ExactVariant none{2, 3, 1, AnalysisMode::Phong, {}};
        QCOMPARE(none.defines().size(), 5); // degrees, span widths, lights
        ExactVariant v = none;
        v.features = ExactFeature::Trim | ExactFeature::TrimExact | ExactFeature::RayNewton;
        const QStringList d = v.defines();
        QCOMPARE(d.size(), 8);
        QVERIFY(d.contains(QStringLiteral("KW_TRIM")) &&
                d.contains(QStringLiteral("KW_TRIM_EXACT")) &&
                d.contains(QStringLiteral("KW_RAY_NEWTON")));
        v.analysis = AnalysisMode::Gaussian;
        QVERIFY(v.defines().contains(
            QStringLiteral("KW_ANALYSIS %1").arg(int(AnalysisMode::Gaussian))));
        QVERIFY(v.defines().contains(QStringLiteral("KW_RAMP_STOPS %1").arg(colourRamp().size())));
        // A program without degrees (depth_only.frag) gets only its features.
        QCOMPARE(ExactVariant({0, 0, 1, AnalysisMode::Phong, ExactFeature::GBuffer}).defines(),
                 QStringList{QStringLiteral("KW_GBUFFER")});
    }

    void passVariantsFollowOptions() {
        RenderOptions o;
        o.partitioning = RenderOptions::Partitioning::Adaptive;
        o.shading = RenderOptions::Shading::DepthPrepass;
        o.trimMode = RenderOptions::TrimMode::Mask;
        using TrimAa = ExactSurfacePass::TrimAa;
        ExactVariant v = ExactSurfacePass::variant(3, 3, 2, o, true, true, TrimAa::Edge);
        QCOMPARE(v.features, ExactFeature::CellGather | ExactFeature::RayNewton |
                                 ExactFeature::Trim | ExactFeature::TrimAa |
                                 ExactFeature::TrimEdge);
        // Degree 5 x 5 does not fit the varyings: no gather. Affine: no Newton step.
        v = ExactSurfacePass::variant(5, 5, 2, o, false, true, TrimAa::Off, false, true);
        QCOMPARE(v.features, ExactFeatures());
        // The skirt's program: no gather, no Newton step, never exact depth.
        o.shading = RenderOptions::Shading::ExactDepth;
        o.writeAov = true;
        v = ExactSurfacePass::variant(1, 1, 1, o, false, true, TrimAa::Off, true);
        QCOMPARE(v.features, ExactFeature::Skirt | ExactFeature::Aov);
        v = ExactSurfacePass::variant(1, 1, 1, o);
        QVERIFY(v.features.testFlag(ExactFeature::ExactDepth));
        o.trimMode = RenderOptions::TrimMode::Exact;
        QVERIFY(
            ExactSurfacePass::variant(1, 1, 1, o, true).features.testFlag(ExactFeature::TrimExact));
        QVERIFY(!ExactSurfacePass::variant(1, 1, 1, o, false)
                     .features.testFlag(ExactFeature::TrimExact));
        // The deferred pass's program: its route's degrees and affine bit.
        o = RenderOptions{};
        o.partitioning = RenderOptions::Partitioning::Adaptive;
        v = ExactSurfacePass::deferredVariant(2 | 3 << 4 | 1 << 12, 1, o);
        QCOMPARE(v.degreeU, 2);
        QCOMPARE(v.degreeV, 3);
        QVERIFY(v.features.testFlag(ExactFeature::Deferred));
        QVERIFY(!v.features.testFlag(ExactFeature::RayNewton));
        QVERIFY(!v.features.testFlag(ExactFeature::CellGather));
    }

    void checkFindsLiterals() {
        // The check itself: each kind of repeated literal is caught, comments are not.
        QVERIFY(!literalViolations(QStringLiteral("layout(binding = 5) uniform x;")).isEmpty());
        QVERIFY(!literalViolations(QStringLiteral("layout(location = 0) in vec3 aPosition;"))
                     .isEmpty());
        QVERIFY(!literalViolations(QStringLiteral("layout(location=4) out vec4 aovCurvature;"))
                     .isEmpty());
        QVERIFY(!literalViolations(QStringLiteral("layout(std140, binding = 2) uniform B {"))
                     .isEmpty());
        QVERIFY(!literalViolations(QStringLiteral("layout(location = 1, index = 1) out vec4 c;"))
                     .isEmpty());
        QVERIFY(literalViolations(
                    QStringLiteral("layout(location = KW_ATTR_POSITION) in vec3 aPosition;"))
                    .isEmpty());
        QVERIFY(literalViolations(QStringLiteral("int location = 0;")).isEmpty());
        QVERIFY(!literalViolations(QStringLiteral("uniform vec3 uL[8];")).isEmpty());
        QVERIFY(!literalViolations(QStringLiteral("#if KW_ANALYSIS == 8")).isEmpty());
        QVERIFY(!literalViolations(QStringLiteral("#define KW_ANALYSIS 0")).isEmpty());
        QVERIFY(!literalViolations(QStringLiteral("if (uAnalysisScale == 1) {")).isEmpty());
        QVERIFY(!literalViolations(QStringLiteral("texelFetch(t, kwSurface * 8 + 6)")).isEmpty());
        QVERIFY(!literalViolations(QStringLiteral("#define uDomain KW_ROW(0)")).isEmpty());
        QVERIFY(!literalViolations(QStringLiteral("vec4 a[KW_SPAN_TEXELS(DEGREE_U)];")).isEmpty());
        QVERIFY(!literalViolations(QStringLiteral("uint at = g.w * 8u;")).isEmpty());
        QVERIFY(literalViolations(QStringLiteral("float x = 1.0; // binding = 5")).isEmpty());
        QVERIFY(literalViolations(
                    QStringLiteral("layout(binding = KW_SPAN_UNIT) uniform samplerBuffer s;"))
                    .isEmpty());
    }

    void shadersRepeatNoSharedLiteral() {
        const QStringList files = shaderFiles();
        QVERIFY(files.size() > 10);
        for (const QString& f : files) {
            const QString source = readShader(f);
            QVERIFY2(!source.isEmpty(), qPrintable(f));
            const QStringList bad = literalViolations(source);
            QVERIFY2(bad.isEmpty(),
                     qPrintable(f + QStringLiteral(": ") + bad.join(QLatin1Char('\n'))));
        }
    }

    void locationsAreContractNames() {
        // The check: a number, a missing layout and a name are told apart.
        QVERIFY(!unnamedLocations(QStringLiteral("in vec3 aPosition;"), true).isEmpty());
        QVERIFY(
            !unnamedLocations(QStringLiteral("layout(location = 2) in vec2 aUv;"), true).isEmpty());
        QVERIFY(unnamedLocations(QStringLiteral("layout(location = KW_ATTR_UV) in vec2 aUv;"), true)
                    .isEmpty());
        QVERIFY(!unnamedLocations(QStringLiteral("out vec4 fragColor;"), false).isEmpty());
        QVERIFY(unnamedLocations(QStringLiteral("flat in int vSurface;"), false).isEmpty());
        QVERIFY(unnamedLocations(QStringLiteral("layout(location = KW_COLOUR_OUTPUT) out vec4 c;"),
                                 false)
                    .isEmpty());
        // Every vertex input and fragment output names its location from the contract.
        int named = 0;
        for (const QString& f : shaderFiles()) {
            const bool vertex = f.endsWith(QLatin1String(".vert"));
            if (!vertex && !f.endsWith(QLatin1String(".frag")))
                continue;
            const QString source = readShader(f);
            const QStringList bad = unnamedLocations(source, vertex);
            QVERIFY2(bad.isEmpty(),
                     qPrintable(f + QStringLiteral(": ") + bad.join(QLatin1Char('\n'))));
            named += int(source.count(QStringLiteral("location = KW_")));
        }
        QVERIFY(named >= 32);
        // And the C++ side: the vertex arrays set their attributes by the same names.
        QVERIFY(
            !numericAttributes(QStringLiteral("gl->glEnableVertexArrayAttrib(vao, 4);")).isEmpty());
        QVERIFY(!numericAttributes(
                     QStringLiteral("glVertexArrayAttribIFormat(m.vao, 2, 2, GL_INT, 0);"))
                     .isEmpty());
        QVERIFY(numericAttributes(QStringLiteral("glVertexArrayAttribBinding(vao, kAttrUv, 0);"))
                    .isEmpty());
        const QDir render(QStringLiteral(KW_SOURCE_DIR "/render"));
        const QStringList sources =
            render.entryList({QStringLiteral("*.cpp"), QStringLiteral("*.h")}, QDir::Files);
        QVERIFY(sources.size() > 20);
        for (const QString& name : sources) {
            QFile f(render.filePath(name));
            QVERIFY(f.open(QIODevice::ReadOnly | QIODevice::Text));
            const QStringList bad = numericAttributes(QString::fromUtf8(f.readAll()));
            QVERIFY2(bad.isEmpty(),
                     qPrintable(name + QStringLiteral(": ") + bad.join(QLatin1Char('\n'))));
        }
    }

    void everyModeHasItsRowAndColour() {
        // The mode table is the one list of modes: each row's define is used by the
        // analysis shader (its colour), and the colour maps are the rows that say so, not a
        // range of numbers.
        const QString analysis = readShader(QStringLiteral("analysis.glsl"));
        QVERIFY(!analysis.isEmpty());
        QCOMPARE(analysisModes().front(), AnalysisMode::Phong);
        QCOMPARE(analysisModeNames().size(), int(analysisModes().size()));
        for (const AnalysisMode m : analysisModes()) {
            QCOMPARE(analysisModeNames().at(int(m)), analysisModeName(m));
            QCOMPARE(parseAnalysisMode(analysisModeName(m)), std::optional<AnalysisMode>(m));
            QCOMPARE(isColourMap(m), analysisParameters(m) == AnalysisParameters::ColourMap);
            QCOMPARE(needsCurvature(m), isColourMap(m));
            if (m != AnalysisMode::Phong)
                QVERIFY2(analysis.contains(analysisModeDefine(m)),
                         qPrintable(analysisModeDefine(m)));
        }
        QCOMPARE(analysisParameters(AnalysisMode::Zebra), AnalysisParameters::Stripes);
        QCOMPARE(defaultScale(AnalysisMode::Gaussian), ColourScale::Symmetric);
        QCOMPARE(defaultScale(AnalysisMode::MaxCurvature), ColourScale::Linear);
        QVERIFY(!analysis.contains(
            QRegularExpression(QStringLiteral("KW_ANALYSIS\\s*(>=|<=|>|<)\\s*KW_ANALYSIS_"))));
    }

    void shadersUseOnlyDeclaredConstants() {
        // A contract name a shader uses and the preamble lacks would fail only when that
        // variant is built; every one must be declared.
        QSet<QString> declared;
        for (const ShaderConstant& c : kShaderConstants)
            declared.insert(QLatin1String(c.name));
        for (const AnalysisMode m : analysisModes())
            declared.insert(analysisModeDefine(m));
        const QRegularExpression name(QStringLiteral(
            "\\bKW_(?:\\w+_(?:UNIT|BINDING|TEXEL|TEXELS|WORD|WORDS|OUTPUT)|ANALYSIS_\\w+|"
            "SCALE_\\w+|ATTR_\\w+|MAX_LIGHTS)\\b"));
        // Names a shader defines for itself are its own, not shared with C++.
        const QRegularExpression own(QStringLiteral("#define\\s+(\\w+)"));
        for (const QString& f : shaderFiles()) {
            auto it = own.globalMatch(readShader(f));
            while (it.hasNext())
                declared.insert(it.next().captured(1));
        }
        int uses = 0;
        for (const QString& f : shaderFiles()) {
            auto it = name.globalMatch(readShader(f));
            while (it.hasNext()) {
                const QString n = it.next().captured(0);
                if (n == QLatin1String("KW_SPAN_TEXELS_U") ||
                    n == QLatin1String("KW_SPAN_TEXELS_V"))
                    continue; // per variant (ExactVariant::defines)
                QVERIFY2(declared.contains(n), qPrintable(f + QStringLiteral(": ") + n));
                ++uses;
            }
        }
        QVERIFY(uses > 20);
    }
};

QTEST_GUILESS_MAIN(TestRenderContract)
#include "tst_render_contract.moc"
