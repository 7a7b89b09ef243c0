// Command-line subcommands of the knotwork executables: one cmd_<name>.cpp per subcommand.
// `knotwork` itself (Qt6::Core + model) runs info, eval and convert; it replaces itself with
// knotwork-gl (editor, render) or knotwork-bench (bench) for the commands that draw, so those
// that do not never load Qt's GUI, OpenGL or OpenImageIO libraries.
#pragma once

#include "model/io/importreport.h"

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
    /// Null when `program` runs the command.
    std::function<int(const QStringList& args)> run;
    /// The executable next to `knotwork` that runs this command in a QGuiApplication with
    /// OpenGL (app/gl_command.h), or null when `run` does, in `knotwork` itself.
    const char* program = nullptr;
};

/// Every subcommand, in the order --help lists them. Add yours in main.cpp's table.
const std::vector<Command>& commands();

int runInfo(const QStringList& args);    ///< knotwork
int runEval(const QStringList& args);    ///< knotwork
int runConvert(const QStringList& args); ///< knotwork
int runMesh(const QStringList& args);    ///< knotwork
/// knotwork-gl and knotwork-bench: they call `startGui` (app/gl_command.h) once their
/// arguments are valid and return kExitBadInput when it returns false.
int runRender(const QStringList& args, const std::function<bool()>& startGui);
int runBench(const QStringList& args, const std::function<bool()>& startGui);
/// knotwork, hidden: the child process model/cad/cadprocess.h runs (kw::kReadCadVerb).
int runReadCad(const QStringList& args);
/// knotwork, hidden: the CAD writer's child process (kw::kWriteCadVerb).
int runWriteCad(const QStringList& args);
/// The hidden `knotwork __mesh-faces` child (model/cad/facemesher.h).
int runMeshFaces(const QStringList& args);

// ---- Helpers shared by subcommands (cli_util.cpp, in every executable).

/// Writes one line to stderr (a newline is appended).
void printError(const QString& line);
/// Writes text to stdout as is.
void printOut(const QString& text);
/// Parses args with parser (which gets --help added). Returns -1 to go on, or the exit code to
/// return at once: kExitOk after printing help, kExitUsage after printing the parse error.
int parseOrExit(QCommandLineParser& parser, const QStringList& args);
/// Prints on stderr what an import skipped and warned about, each line led by `file`:
/// "FILE: N face(s) skipped, M imported", then "FILE: skipped: ..." and "FILE: warning: ...".
/// Nothing for a clean import. (`render` and `info` on a CAD file; `convert --report` lists the
/// same on stdout.)
void printImportRemarks(const QString& file, const ImportReport& report);
/// "%.17g": the shortest printf form that reads back as the same double.
QString fullPrecision(double value);

} // namespace kw::cli
