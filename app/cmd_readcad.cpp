// knotwork __read-cad IN DIR [--max-memory-mb N] [--mesh LINEAR ANGULAR_DEG]: the child process
// that reads an IGES, STEP or BREP file for a parent (model/cad/cadprocess.h), with OpenCASCADE
// loaded only here, from the module of the file's format (libknotwork_occt_iges.so, ...); with
// --mesh it also triangulates the shape (`knotwork mesh`) into DIR/mesh.obj, with the module
// libknotwork_occt.so (every format and the mesher). Hidden from --help.
#include "app/commands.h"
#include "app/plugin.h"
#include "model/cad/cadprocess.h"
#include "model/cad/occtimport.h"

#include <QFile>
#include <csignal>
#include <optional>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <unistd.h>

namespace kw::cli {

int runReadCad(const QStringList& args) {
    // args[0] is "knotwork __read-cad"; no QCommandLineParser: the parent builds the line.
    bool usage = args.size() < 3;
    long long memoryMb = 0;
    std::optional<MeshDeflection> deflection;
    for (qsizetype k = 3; k < args.size() && !usage;) {
        bool ok1 = false, ok2 = true;
        if (args[k] == QLatin1String("--max-memory-mb") && k + 1 < args.size()) {
            memoryMb = args[k + 1].toLongLong(&ok1);
            k += 2;
        } else if (args[k] == QLatin1String("--die-with-parent")) {
            // Started by the launcher for the program it becomes (cadprestart.h): if that
            // program dies without taking this read over, so does this process.
            ::prctl(PR_SET_PDEATHSIG, SIGKILL);
            ok1 = ::getppid() != 1;
            ++k;
        } else if (args[k] == QLatin1String("--parent-pid") && k + 1 < args.size()) {
            // Dies with the parent (also set between fork and exec); a parent already gone
            // means nobody waits for this read.
            const long long parent = args[k + 1].toLongLong(&ok1);
            ::prctl(PR_SET_PDEATHSIG, SIGKILL);
            if (ok1 && ::getppid() != pid_t(parent))
                return kExitBadInput;
            k += 2;
        } else if (args[k] == QLatin1String("--deadline-s") && k + 1 < args.size()) {
            // Its own deadline, kept even when no parent watches any more: SIGALRM's default
            // action ends the process.
            const int seconds = args[k + 1].toInt(&ok1);
            ok1 = ok1 && seconds > 0;
            if (ok1)
                ::alarm(unsigned(seconds));
            k += 2;
        } else if (args[k] == QLatin1String("--mesh") && k + 2 < args.size()) {
            deflection = MeshDeflection{args[k + 1].toDouble(&ok1), args[k + 2].toDouble(&ok2)};
            k += 3;
        }
        usage = !ok1 || !ok2;
    }
    if (usage) {
        printError(QStringLiteral("%1: expected IN DIR [--max-memory-mb N] [--mesh LINEAR "
                                  "ANGULAR_DEG] (used by knotwork itself to read CAD files in a "
                                  "child process)")
                       .arg(args.value(0)));
        return kExitUsage;
    }
    const QString in = args[1], dir = args[2];
    if (memoryMb != 0) {
        // RLIMIT_AS: an allocation beyond it fails (bad_alloc, caught as an error) instead of
        // driving the machine into swap.
        const rlim_t bytes = rlim_t(memoryMb) << 20;
        const rlimit limit{bytes, bytes};
        if (bytes > 0 && ::setrlimit(RLIMIT_AS, &limit) != 0)
            printError(QStringLiteral("%1: cannot set the memory limit").arg(args.value(0)));
    }
    const CadFormat format = cadFormatFromPath(in);
    if (format != CadFormat::Iges && format != CadFormat::Step && format != CadFormat::Brep) {
        printError(QStringLiteral("%1: not an IGES, STEP or BREP file").arg(in));
        return kExitUsage;
    }
    // Every temporary file of this process (the IGES numbering repair's copy, anything OCCT
    // makes) goes into the parent's folder, which the parent removes even when this process
    // is killed or aborts.
    qputenv("TMPDIR", QFile::encodeName(dir));
    QString error;
    // A plain read loads only its format's toolkits: their symbol relocations are a large part
    // of a small file's read (docs/PERFORMANCE.md, First image of a CAD file).
    const char* module = deflection ? kOcctModuleName : occtReadModuleName(format);
    const auto resolve = [&](const char* symbol) -> QFunctionPointer {
        const Expected<QFunctionPointer> f =
            app::resolveModuleSymbol(QString::fromLatin1(module), symbol);
        if (!f)
            error = f.message();
        return f.value_or(nullptr);
    };
    const auto read = reinterpret_cast<OcctImportFunction>(resolve(kOcctImportSymbol));
    const auto mesh =
        deflection ? reinterpret_cast<OcctMeshFunction>(resolve(kOcctMeshSymbol)) : nullptr;
    if (!read || (deflection && !mesh)) {
        printError(QStringLiteral("%1: cannot read %2: %3").arg(in, cadFormatName(format), error));
        return kExitBadInput;
    }
    const ImportProgress progress = progressToParent();
    TaggedMeshSet triangles;
    Expected<ImportResult> result = deflection
                                        ? mesh(in, format, &*deflection, &triangles, &progress)
                                        : read(in, format, &progress);
    Status done = result ? Status() : Status(result.error());
    if (done && deflection)
        done = writeMeshForParent(triangles, dir);
    if (done)
        done = finishImport(*result, in);
    if (done)
        done = writeImportForParent(*result, dir);
    if (!done) {
        printError(done.message());
        return kExitBadInput;
    }
    return kExitOk;
}

} // namespace kw::cli
