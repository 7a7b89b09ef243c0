// knotwork __write-cad SCENE.kwi OUT DIR [options]: the child process that writes a STEP or IGES
// file for a parent (model/cad/cadprocess.h, kWriteCadVerb), with OpenCASCADE loaded only here,
// from libknotwork_occt_write.so. It leaves the bytes in DIR/export.out and the report in
// DIR/export.txt; the parent writes OUT. With --read-cad the first argument is a CAD file,
// read here first with its format's module (as `__read-cad` does, its import left in
// DIR/import.kwi), so that a CAD to CAD convert loads OpenCASCADE once. Hidden from --help.
#include "app/commands.h"
#include "app/plugin.h"
#include "model/cad/cadprocess.h"
#include "model/cad/handover.h"
#include "model/cad/occtexport.h"
#include "model/cad/occtimport.h"
#include "model/io/savefile.h"

#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <sys/resource.h>

namespace kw::cli {
namespace {

// What `__read-cad` does, in this process: `in` read by its format's module and finished, the
// import left for the parent in DIR/import.kwi (its report and face numbers). The writer module
// loaded next shares the OpenCASCADE toolkits already mapped.
Expected<ImportResult> readCadFile(const QString& in, const QString& dir) {
    const CadFormat format = cadFormatFromPath(in);
    if (format != CadFormat::Iges && format != CadFormat::Step && format != CadFormat::Brep)
        return Error(QStringLiteral("%1: not an IGES, STEP or BREP file").arg(in), in);
    // Temporary files (the IGES numbering repair's copy) go into the parent's folder.
    qputenv("TMPDIR", QFile::encodeName(dir));
    const Expected<QFunctionPointer> resolved = app::resolveModuleSymbol(
        QString::fromLatin1(occtReadModuleName(format)), kOcctImportSymbol);
    if (!resolved)
        return Error(QStringLiteral("%1: cannot read %2: %3")
                         .arg(in, cadFormatName(format), resolved.message()),
                     in);
    const auto read = reinterpret_cast<OcctImportFunction>(*resolved);
    // The read's progress is not sent: the parent's bar follows the write, as for an export.
    const ImportProgress none;
    QElapsedTimer timer;
    timer.start();
    Expected<ImportResult> result = read(in, format, &none);
    if (!result)
        return result;
    if (const Status finished = finishImport(*result, in); !finished)
        return finished.error();
    result->report.seconds = timer.elapsed() / 1000.0;
    if (const Status left = writeImportForParent(*result, dir); !left)
        return left.error();
    return result;
}

} // namespace

int runWriteCad(const QStringList& args) {
    // args[0] is "knotwork __write-cad"; the parent builds the line.
    bool usage = args.size() < 4;
    long long memoryMb = 0;
    bool readCad = false;
    ExportOptions options;
    for (qsizetype k = 4; k < args.size() && !usage;) {
        bool ok = true;
        if (args[k] == QLatin1String("--max-memory-mb") && k + 1 < args.size()) {
            memoryMb = args[k + 1].toLongLong(&ok);
            k += 2;
        } else if (args[k] == QLatin1String("--step-schema") && k + 1 < args.size()) {
            options.stepSchema = args[k + 1];
            k += 2;
        } else if (args[k] == QLatin1String("--tolerance") && k + 1 < args.size()) {
            options.tolerance = args[k + 1].toDouble(&ok);
            k += 2;
        } else if (args[k] == QLatin1String("--iges-faces")) {
            options.igesFaces = true;
            ++k;
        } else if (args[k] == QLatin1String("--require-closed")) {
            options.requireClosed = true;
            ++k;
        } else if (args[k] == QLatin1String("--read-cad")) {
            readCad = true;
            ++k;
        } else {
            ok = false;
        }
        usage = !ok;
    }
    if (usage) {
        printError(QStringLiteral(
                       "%1: expected SCENE.kwi OUT DIR [--step-schema S] [--iges-faces] "
                       "[--require-closed] [--tolerance T] [--max-memory-mb N] [--read-cad] (used "
                       "by knotwork itself to write CAD files in a child process)")
                       .arg(args.value(0)));
        return kExitUsage;
    }
    const QString scenePath = args[1], out = args[2], dir = args[3];
    if (memoryMb > 0) {
        const rlim_t bytes = rlim_t(memoryMb) << 20;
        const rlimit limit{bytes, bytes};
        if (::setrlimit(RLIMIT_AS, &limit) != 0)
            printError(QStringLiteral("%1: cannot set the memory limit").arg(args.value(0)));
    }
    Expected<ImportResult> scene = Error(QString());
    if (readCad) {
        scene = readCadFile(scenePath, dir);
        if (!scene) {
            printError(scene.message());
            return kExitBadInput;
        }
    } else {
        QFile in(scenePath);
        scene = in.open(QIODevice::ReadOnly) ? decodeImportHandover(in.readAll())
                                             : Expected<ImportResult>(Error(in.errorString()));
        if (!scene) {
            printError(
                QStringLiteral("%1: cannot read the scene to write: %2").arg(out, scene.message()));
            return kExitBadInput;
        }
    }
    const Expected<QFunctionPointer> resolved =
        app::resolveModuleSymbol(QString::fromLatin1(kOcctWriteModuleName), kOcctExportSymbol);
    if (!resolved) {
        printError(QStringLiteral("%1: cannot write %2: %3")
                       .arg(out, cadFormatName(cadFormatFromPath(out)), resolved.message()));
        return kExitBadInput;
    }
    const auto write = reinterpret_cast<OcctExportFunction>(*resolved);
    const ImportProgress progress = progressToParent();
    ExportReport report;
    const Expected<QByteArray> bytes = write(&scene->scene, out, &options, &report, &progress);
    const bool ok = bool(bytes);
    QString error = bytes.message();
    // The report goes back also when the export is refused (--require-closed lists the seams).
    // A failure to leave the results for the parent (a full disk) still names OUT.
    Status left =
        saveBytesAtomically(QDir(dir).filePath(QStringLiteral("export.txt")), report.toText());
    if (left && ok)
        left = saveBytesAtomically(QDir(dir).filePath(QStringLiteral("export.out")), *bytes);
    if (ok && !left)
        error = QStringLiteral("%1: not written: the writer could not keep the file in the "
                               "temporary folder (%2)")
                    .arg(out, left.message());
    if (!ok || !left) {
        printError(error);
        return kExitBadInput;
    }
    return kExitOk;
}

} // namespace kw::cli
