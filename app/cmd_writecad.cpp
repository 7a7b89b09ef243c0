// knotwork __write-cad SCENE.kwi OUT DIR [options]: the child process that writes a STEP or IGES
// file for a parent (model/cad/cadprocess.h, kWriteCadVerb), with OpenCASCADE loaded only here,
// from libknotwork_occt_write.so. It leaves the bytes in DIR/export.out and the report in
// DIR/export.txt; the parent writes OUT. Hidden from --help.
#include "app/commands.h"
#include "app/plugin.h"
#include "model/cad/cadprocess.h"
#include "model/cad/handover.h"
#include "model/cad/occtexport.h"
#include "model/io/savefile.h"

#include <QDir>
#include <QFile>
#include <sys/resource.h>

namespace kw::cli {

int runWriteCad(const QStringList& args) {
    // args[0] is "knotwork __write-cad"; the parent builds the line.
    bool usage = args.size() < 4;
    long long memoryMb = 0;
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
        } else {
            ok = false;
        }
        usage = !ok;
    }
    if (usage) {
        printError(QStringLiteral("%1: expected SCENE.kwi OUT DIR [--step-schema S] [--iges-faces] "
                                  "[--require-closed] [--tolerance T] [--max-memory-mb N] (used "
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
    QFile in(scenePath);
    const Expected<ImportResult> scene = in.open(QIODevice::ReadOnly)
                                             ? decodeImportHandover(in.readAll())
                                             : Expected<ImportResult>(Error(in.errorString()));
    if (!scene) {
        printError(
            QStringLiteral("%1: cannot read the scene to write: %2").arg(out, scene.message()));
        return kExitBadInput;
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
