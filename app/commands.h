// Command-line subcommands of the knotwork executable: one cmd_<name>.cpp per subcommand.
#pragma once

#include <QString>
#include <QStringList>
#include <functional>
#include <vector>

class QCommandLineParser;

namespace kw::cli {

/// Exit codes shared by every subcommand.
enum ExitCode : int {
    kExitOk = 0,
    kExitBadInput = 1, ///< unreadable or invalid file, unknown surface, (u, v) outside the domain
    kExitUsage = 2,    ///< unknown subcommand or option, missing or malformed argument
};

/// One subcommand. `run` receives the arguments after the subcommand name (argv[0] is
/// "knotwork <name>"), runs inside a QCoreApplication, prints results on stdout and one-line
/// errors on stderr, and returns an ExitCode.
struct Command {
    QString name;
    QString summary;
    std::function<int(const QStringList& args)> run;
    /// Runs in a QGuiApplication (OpenGL) with OffscreenRenderer::requiredFormat() as the
    /// default surface format, instead of a QCoreApplication.
    bool gui = false;
};

/// Every subcommand, in the order --help lists them. Add yours in main.cpp's table.
const std::vector<Command>& commands();

int runInfo(const QStringList& args);
int runEval(const QStringList& args);
int runConvert(const QStringList& args);
int runRender(const QStringList& args);
int runBench(const QStringList& args);
/// The hidden child-process verb model/cad/cadprocess.h runs (kw::kReadCadVerb).
int runReadCad(const QStringList& args);

// ---- Helpers shared by subcommands (main.cpp).

/// Writes one line to stderr (a newline is appended).
void printError(const QString& line);
/// Writes text to stdout as is.
void printOut(const QString& text);
/// Parses args with parser (which gets --help added). Returns -1 to go on, or the exit code to
/// return at once: kExitOk after printing help, kExitUsage after printing the parse error.
int parseOrExit(QCommandLineParser& parser, const QStringList& args);
/// "%.17g": the shortest printf form that reads back as the same double.
QString fullPrecision(double value);

} // namespace kw::cli
