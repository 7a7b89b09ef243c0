// knotwork __read-cad IN DIR [--max-memory-mb N]: the child process that reads an IGES, STEP or
// BREP file for a parent (model/cad/cadprocess.h), with OpenCASCADE loaded from the module
// libknotwork_occt.so only here. Hidden from --help.
#include "app/commands.h"
#include "app/plugin.h"
#include "model/cad/cadprocess.h"
#include "model/cad/occtimport.h"

#include <cstdio>
#include <sys/resource.h>

namespace kw::cli {

int runReadCad(const QStringList& args) {
    // args[0] is "knotwork __read-cad"; no QCommandLineParser: the parent builds the line.
    if (args.size() != 3 && !(args.size() == 5 && args[3] == QLatin1String("--max-memory-mb"))) {
        printError(QStringLiteral("%1: expected IN DIR [--max-memory-mb N] (used by knotwork "
                                  "itself to read CAD files in a child process)")
                       .arg(args.value(0)));
        return kExitUsage;
    }
    const QString in = args[1], dir = args[2];
    if (args.size() == 5) {
        // RLIMIT_AS: an allocation beyond it fails (bad_alloc, caught as an error) instead of
        // driving the machine into swap.
        const rlim_t bytes = rlim_t(args[4].toLongLong()) << 20;
        const rlimit limit{bytes, bytes};
        if (bytes > 0 && ::setrlimit(RLIMIT_AS, &limit) != 0)
            printError(QStringLiteral("%1: cannot set the memory limit").arg(args.value(0)));
    }
    const CadFormat format = cadFormatFromPath(in);
    if (format != CadFormat::Iges && format != CadFormat::Step && format != CadFormat::Brep) {
        printError(QStringLiteral("%1: not an IGES, STEP or BREP file").arg(in));
        return kExitUsage;
    }
    QString error;
    const auto read = reinterpret_cast<OcctImportFunction>(
        app::resolveModuleSymbol(QString::fromLatin1(kOcctModuleName), kOcctImportSymbol, &error));
    if (!read) {
        printError(QStringLiteral("%1: cannot read %2: %3").arg(in, cadFormatName(format), error));
        return kExitBadInput;
    }
    const ImportProgress progress = [](int done, int total) {
        const QByteArray line = progressLine(done, total);
        std::fwrite(line.constData(), 1, size_t(line.size()), stdout);
        std::fflush(stdout);
        return true; // the parent cancels by killing this process
    };
    ImportResult result;
    if (!read(in, format, &result, &error, &progress) || !finishImport(result, in, error) ||
        !writeImportForParent(result, dir, error)) {
        printError(error);
        return kExitBadInput;
    }
    return kExitOk;
}

} // namespace kw::cli
