// knotwork: entry point; dispatches to a command-line subcommand or the editor.
#include "app/commands.h"
#include "app/editor.h"
#include "render/offscreen_renderer.h"

#include <QCommandLineParser>
#include <QCoreApplication>
#include <QGuiApplication>
#include <QSurfaceFormat>
#include <cstdio>
#include <memory>

namespace kw::cli {

const std::vector<Command>& commands() {
    // One row per subcommand; each lives in its own cmd_<name>.cpp.
    static const std::vector<Command> table = {
        {QStringLiteral("info"),
         QStringLiteral("Summarise a .knot project (surfaces, lights, camera)."), runInfo},
        {QStringLiteral("eval"),
         QStringLiteral("Evaluate a surface's point, partials and normal at (u, v)."), runEval},
        {QStringLiteral("convert"),
         QStringLiteral("Convert IGES/STEP/BREP/OBJ/.knot to .knot or OBJ (free-form or mesh)."),
         runConvert},
        {QStringLiteral("render"),
         QStringLiteral("Render a project off-screen to an image (and AOVs)."), runRender, true},
        {QStringLiteral("bench"), QStringLiteral("Measure off-screen frame rates per image size."),
         runBench, true},
    };
    return table;
}

void printError(const QString& line) {
    std::fprintf(stderr, "%s\n", line.toLocal8Bit().constData());
    std::fflush(stderr);
}

void printOut(const QString& text) {
    std::fputs(text.toUtf8().constData(), stdout);
    std::fflush(stdout);
}

int parseOrExit(QCommandLineParser& parser, const QStringList& args) {
    const QCommandLineOption help = parser.addHelpOption();
    if (!parser.parse(args)) {
        printError(QStringLiteral("%1: %2 (see --help)").arg(args.value(0), parser.errorText()));
        return kExitUsage;
    }
    if (parser.isSet(help) || parser.isSet(QStringLiteral("help-all"))) {
        // Qt names the binary's full path in the usage line; show the subcommand instead.
        QString text = parser.helpText();
        const qsizetype eol = text.indexOf(QLatin1Char('\n'));
        const QString usage = text.left(eol);
        text = QStringLiteral("Usage: %1%2")
                   .arg(args.value(0), usage.mid(usage.indexOf(QLatin1Char(' '), 7))) +
               text.mid(eol);
        printOut(text);
        return kExitOk;
    }
    return -1;
}

QString fullPrecision(double value) {
    // C's printf, not QString::asprintf, which drops the sign of -0.0.
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", value);
    return QString::fromLatin1(buf);
}

} // namespace kw::cli

namespace {

using namespace kw::cli;

QString globalHelp() {
    QString text = QStringLiteral("Usage: knotwork <subcommand> [options] [arguments]\n"
                                  "       knotwork FILE.knot      (the editor; FILE is optional)\n"
                                  "       knotwork --screenshot OUT [--size WxH] [--demo] [FILE.knot]\n"
                                  "\n"
                                  "Knotwork NURBS surface editor and command-line tools.\n"
                                  "\n"
                                  "Subcommands:\n");
    for (const Command& c : commands())
        text += QStringLiteral("  %1  %2\n").arg(c.name.leftJustified(8), c.summary);
    text += QStringLiteral(
        "\n"
        "knotwork [FILE] opens the editor (it needs a display and OpenGL 4.5 core); a FILE\n"
        "that cannot be read is reported on stderr with exit code 1 before any window opens.\n"
        "--screenshot OUT opens FILE with its first surface selected, saves a picture of the\n"
        "window to OUT and exits; --size WxH sets the window size. --demo starts with a scene\n"
        "made by the editor's Create and trim tools.\n"
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

} // namespace

int main(int argc, char** argv) {
    if (kw::app::isEditorInvocation(argc, argv))
        return kw::app::runEditor(argc, argv);
    // GL subcommands need a QGuiApplication, and the default format must be set before it.
    const Command* early = argc > 1 ? findCommand(QString::fromLocal8Bit(argv[1])) : nullptr;
    std::unique_ptr<QCoreApplication> app;
    if (early && early->gui) {
        // Without a display Qt's xcb platform aborts the process; say what to do instead.
        const QByteArray platform = qgetenv("QT_QPA_PLATFORM");
        if ((platform.isEmpty() || platform.startsWith("xcb")) &&
            qEnvironmentVariableIsEmpty("DISPLAY")) {
            printError(
                QStringLiteral("knotwork %1: no OpenGL 4.5 context can be made: no X display "
                               "(DISPLAY is not set). Run under xvfb-run -a -s \"-screen 0 "
                               "1280x1024x24\" with QT_QPA_PLATFORM=xcb.")
                    .arg(early->name));
            return kExitBadInput;
        }
        QSurfaceFormat::setDefaultFormat(kw::OffscreenRenderer::requiredFormat());
        app = std::make_unique<QGuiApplication>(argc, argv);
    } else {
        app = std::make_unique<QCoreApplication>(argc, argv);
    }
    QCoreApplication::setApplicationName(QStringLiteral("knotwork"));
    QCoreApplication::setApplicationVersion(QStringLiteral(KW_VERSION));
    const QStringList args = QCoreApplication::arguments();

    const QString first = args[1];
    if (first == QLatin1String("-h") || first == QLatin1String("--help")) {
        printOut(globalHelp());
        return kExitOk;
    }
    if (first == QLatin1String("-v") || first == QLatin1String("--version")) {
        printOut(QStringLiteral("knotwork %1\n").arg(QStringLiteral(KW_VERSION)));
        return kExitOk;
    }
    QStringList rest = args.mid(2);
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
