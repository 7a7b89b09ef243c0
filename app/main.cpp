// knotwork: entry point. Runs the command-line tools that need no display here (Qt6::Core and
// the model only, so --version, --help, info and eval start in a few milliseconds) and hands
// the editor, render and bench to knotwork-gl / knotwork-bench (app/launch.h).
#include "app/commands.h"
#include "app/launch.h"
#include "app/version.h"
#include "model/cad/cadimport.h"
#include "model/cad/cadprestart.h"
#include "model/cad/cadprocess.h"
#include "model/cad/facemesher.h"

#include <QCoreApplication>
#include <QFileInfo>

namespace kw::cli {

namespace {
constexpr const char* kGlProgram = "knotwork-gl";       // editor and render (app/gl_main.cpp)
constexpr const char* kBenchProgram = "knotwork-bench"; // bench (bench/main.cpp)
} // namespace

const std::vector<Command>& commands() {
    // One row per subcommand; each lives in its own cmd_<name>.cpp.
    static const std::vector<Command> table = {
        {QStringLiteral("info"),
         QStringLiteral("Summarise a project or CAD file (surfaces, lights, camera)."), runInfo},
        {QStringLiteral("eval"),
         QStringLiteral("Evaluate a surface's point, partials and normal at (u, v)."), runEval},
        {QStringLiteral("convert"),
         QStringLiteral("Convert IGES/STEP/BREP/OBJ/.knot to .knot or OBJ (free-form or mesh)."),
         runConvert},
        {QStringLiteral("mesh"),
         QStringLiteral("Triangulate IGES/STEP/BREP with OpenCASCADE (the viewers' mesh) to OBJ."),
         runMesh},
        {QStringLiteral("render"),
         QStringLiteral("Render a project or CAD file off-screen to an image (and AOVs)."), nullptr,
         kGlProgram},
        {QStringLiteral("bench"), QStringLiteral("Measure off-screen frame rates per image size."),
         nullptr, kBenchProgram},
    };
    return table;
}

} // namespace kw::cli

namespace {

using namespace kw::cli;

QString globalHelp() {
    QString text =
        QStringLiteral("Usage: knotwork <subcommand> [options] [arguments]\n"
                       "       knotwork FILE           (the editor; FILE is optional)\n"
                       "       knotwork --screenshot OUT [--size WxH] [--demo] [--shading MODE] "
                       "[FILE.knot]\n"
                       "\n"
                       "Knotwork NURBS surface editor and command-line tools.\n"
                       "\n"
                       "Subcommands:\n");
    for (const Command& c : commands())
        text += QStringLiteral("  %1  %2\n").arg(c.name.leftJustified(8), c.summary);
    text += QStringLiteral(
        "\n"
        "knotwork [FILE] opens the editor (it needs a display and OpenGL 4.5 core) on a .knot\n"
        "project, or imports an IGES, STEP, BREP or OBJ FILE into a new one; a FILE that\n"
        "cannot be read is reported on stderr with exit code 1 before any window opens.\n"
        "--screenshot OUT opens FILE with its first surface selected, saves a picture of the\n"
        "window to OUT and exits; --size WxH sets the window size. --demo starts with a scene\n"
        "made by the editor's Create and trim tools; --shading MODE starts with that View ›\n"
        "Analysis mode (the modes of 'knotwork render --shading').\n"
        "'knotwork <subcommand> --help' describes a subcommand.\n"
        "\n"
        "Options:\n"
        "  -h, --help     Show this help.\n"
        "  -v, --version  Show the version.\n"
        "\n"
        "Exit codes: 0 success, 1 bad input (the message names the file), 2 usage error.\n");
    return text;
}

const Command* findCommand(const QString& name) {
    for (const Command& c : commands())
        if (c.name == name)
            return &c;
    return nullptr;
}

/// True when argv[1] names something the editor handles (a FILE or an editor option) rather
/// than a subcommand or a global option of the command-line tools.
bool isEditorInvocation(int argc, char** argv) {
    if (argc < 2)
        return true;
    const QString first = QString::fromLocal8Bit(argv[1]);
    if (first == QLatin1String("--screenshot") ||
        first.startsWith(QLatin1String("--screenshot=")) || first == QLatin1String("--size") ||
        first == QLatin1String("--demo") || first == QLatin1String("--shading") ||
        first.startsWith(QLatin1String("--shading=")))
        return true;
    if (first.startsWith(QLatin1Char('-')))
        return false;
    if (findCommand(first) || first == QLatin1String(kw::kReadCadVerb) ||
        first == QLatin1String(kw::kWriteCadVerb) || first == QLatin1String(kw::kMeshFacesVerb))
        return false;
    // A model file by its name (the editor then says when it is missing).
    return QFileInfo::exists(first) || kw::cadFormatFromPath(first) != kw::CadFormat::Unknown;
}

/// Replaces this process with `program`; returns the exit code only when that fails.
int runElsewhere(const char* program, char** argv) {
    printError(kw::app::execSibling(program, argv));
    return kExitBadInput;
}

} // namespace

int main(int argc, char** argv) {
    // Decided before any Q*Application exists: the editor makes its own QApplication.
    if (isEditorInvocation(argc, argv))
        return runElsewhere(kGlProgram, argv);
    if (const Command* c = findCommand(QString::fromLocal8Bit(argv[1])); c && c->program) {
        // `render FILE.iges ...`: the CAD reader's child starts now and reads while knotwork-gl
        // starts; knotwork-gl takes it over (model/cad/cadprestart.h). Only for FILE right after
        // the verb, the form --help shows; any other form reads the file as usual.
        if (c->name == QLatin1String("render") && argc > 2 && argv[2][0] != '-') {
            const QString reader = qEnvironmentVariable("KNOTWORK_CAD_READER");
            kw::prestartCadRead(reader.isEmpty() ? kw::app::siblingPath("knotwork") : reader,
                                QString::fromLocal8Bit(argv[2]));
        }
        return runElsewhere(c->program, argv);
    }
    QCoreApplication app(argc, argv);
    QCoreApplication::setApplicationName(QStringLiteral("knotwork"));
    QCoreApplication::setApplicationVersion(kw::versionString());
    const QStringList args = QCoreApplication::arguments();

    const QString first = args[1];
    if (first == QLatin1String("-h") || first == QLatin1String("--help")) {
        printOut(globalHelp());
        return kExitOk;
    }
    if (first == QLatin1String("-v") || first == QLatin1String("--version")) {
        printOut(QStringLiteral("knotwork %1\n").arg(kw::versionString()));
        return kExitOk;
    }
    QStringList rest = args.mid(2);
    if (first == QLatin1String(kw::kReadCadVerb)) { // hidden: the CAD reader's child process
        rest.prepend(QStringLiteral("knotwork ") + first);
        return runReadCad(rest);
    }
    if (first == QLatin1String(kw::kWriteCadVerb)) { // hidden: the CAD writer's child process
        rest.prepend(QStringLiteral("knotwork ") + first);
        return runWriteCad(rest);
    }
    if (first == QLatin1String(kw::kMeshFacesVerb)) { // hidden: the face mesher's child process
        rest.prepend(QStringLiteral("knotwork ") + first);
        return runMeshFaces(rest);
    }
    if (const Command* command = findCommand(first)) {
        rest.prepend(QStringLiteral("knotwork ") + command->name);
        return command->run(rest);
    }
    if (first.startsWith(QLatin1Char('-'))) {
        printError(
            QStringLiteral("knotwork: unknown option '%1' (see knotwork --help)").arg(first));
        return kExitUsage;
    }
    printError(
        QStringLiteral("knotwork: unknown subcommand '%1' (see knotwork --help)").arg(first));
    return kExitUsage;
}
