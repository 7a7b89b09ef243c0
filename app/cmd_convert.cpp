// knotwork convert IN OUT: IGES/STEP/BREP/OBJ/.knot in; .knot, OBJ (free-form or mesh), STEP or
// IGES (B-rep, written by OpenCASCADE in a child process) out.
#include "app/commands.h"
#include "model/cad/cadexport.h"
#include "model/cad/cadimport.h"
#include "model/io/knotfile.h"
#include "model/io/objfile.h"

#include <QCommandLineParser>
#include <QFileInfo>

namespace kw::cli {

int runConvert(const QStringList& args) {
    QCommandLineParser parser;
    parser.setApplicationDescription(QStringLiteral(
        "Convert IN (.igs/.iges, .stp/.step, .brep, .obj or .knot) to OUT (.knot; .obj: free-form\n"
        "surfaces with trims, or a triangle mesh with --mesh; .step/.stp or .iges/.igs: a B-rep\n"
        "of the exact surfaces, closed shells as solids, docs/EXCHANGE.md). Faces that cannot be\n"
        "imported are counted on stderr; --report lists each one and every warning. A STEP or\n"
        "IGES export warns on stderr about every open seam (the two faces, the largest gap)."));
    parser.addPositionalArgument(QStringLiteral("IN"), QStringLiteral("File to import."));
    parser.addPositionalArgument(QStringLiteral("OUT"), QStringLiteral("File to write."));
    const QCommandLineOption report(QStringLiteral("report"),
                                    QStringLiteral("Print the import report on stdout."));
    const QCommandLineOption mesh(QStringLiteral("mesh"),
                                  QStringLiteral("Write OUT (.obj) as a triangle mesh."));
    const QCommandLineOption subdivisions(
        QStringLiteral("subdivisions"),
        QStringLiteral("With --mesh: quads per partition cell and direction (default 4)."),
        QStringLiteral("N"), QStringLiteral("4"));
    const QCommandLineOption maxMesh(
        QStringLiteral("max-mesh-mb"),
        QStringLiteral("With --mesh: refuse to write more than N MB (default %1).")
            .arg(kDefaultMaxMeshBytes >> 20),
        QStringLiteral("N"), QString::number(kDefaultMaxMeshBytes >> 20));
    const QCommandLineOption stepSchema(
        QStringLiteral("step-schema"),
        QStringLiteral("STEP application protocol: ap203, ap214 (default) or ap242."),
        QStringLiteral("SCHEMA"), QStringLiteral("ap214"));
    const QCommandLineOption igesMode(
        QStringLiteral("iges-mode"),
        QStringLiteral("IGES: brep (default; MSBO solids, type 186) or faces (trimmed surfaces, "
                       "type 144)."),
        QStringLiteral("MODE"), QStringLiteral("brep"));
    const QCommandLineOption requireClosed(
        QStringLiteral("require-closed"),
        QStringLiteral("STEP/IGES: write nothing and exit 1 unless every face ends in a closed "
                       "solid."));
    parser.addOption(report);
    parser.addOption(stepSchema);
    parser.addOption(igesMode);
    parser.addOption(requireClosed);
    parser.addOption(mesh);
    parser.addOption(subdivisions);
    parser.addOption(maxMesh);
    if (const int code = parseOrExit(parser, args); code >= 0)
        return code;
    const QStringList pos = parser.positionalArguments();
    const QString command = args.value(0);
    if (pos.size() != 2) {
        printError(QStringLiteral("%1: expected IN and OUT (see --help)").arg(command));
        return kExitUsage;
    }
    const QString in = pos[0], out = pos[1];
    const CadFormat outFormat = cadFormatFromPath(out);
    const bool cadOut = outFormat == CadFormat::Step || outFormat == CadFormat::Iges;
    if (outFormat != CadFormat::Knot && outFormat != CadFormat::Obj && !cadOut) {
        // A bad name is bad input like a bad file: it names the file, exit 1.
        printError(
            QStringLiteral("%1: cannot tell what to write from %2 (expected .knot, .obj, "
                           ".step, .stp, .iges or .igs)")
                .arg(out, QFileInfo(out).suffix().isEmpty()
                              ? QStringLiteral("a name without an extension")
                              : QStringLiteral("the extension .") + QFileInfo(out).suffix()));
        return kExitBadInput;
    }
    ExportOptions exportOptions;
    exportOptions.stepSchema = parser.value(stepSchema).toLower();
    exportOptions.requireClosed = parser.isSet(requireClosed);
    const QString mode = parser.value(igesMode).toLower();
    if (mode != QLatin1String("brep") && mode != QLatin1String("faces")) {
        printError(QStringLiteral("%1: --iges-mode must be brep or faces").arg(command));
        return kExitUsage;
    }
    exportOptions.igesFaces = mode == QLatin1String("faces");
    if (const QString bad = checkExportOptions(exportOptions).message(); !bad.isEmpty()) {
        printError(QStringLiteral("%1: --step-schema: %2").arg(command, bad));
        return kExitUsage;
    }
    if (!cadOut &&
        (parser.isSet(stepSchema) || parser.isSet(igesMode) || parser.isSet(requireClosed))) {
        printError(QStringLiteral("%1: --step-schema, --iges-mode and --require-closed need a "
                                  "STEP or IGES OUT")
                       .arg(command));
        return kExitUsage;
    }
    bool ok = false;
    ObjMeshOptions meshOptions;
    meshOptions.subdivisions = parser.value(subdivisions).toInt(&ok);
    if (!ok || meshOptions.subdivisions < 1 || meshOptions.subdivisions > 64) {
        printError(QStringLiteral("%1: --subdivisions must be an integer in [1, 64]").arg(command));
        return kExitUsage;
    }
    const long long maxMeshMb = parser.value(maxMesh).toLongLong(&ok);
    if (!ok || maxMeshMb < 1 || maxMeshMb > (1LL << 40)) {
        printError(QStringLiteral("%1: --max-mesh-mb must be a positive integer").arg(command));
        return kExitUsage;
    }
    meshOptions.maxBytes = maxMeshMb << 20;
    if (parser.isSet(mesh) && outFormat != CadFormat::Obj) {
        printError(QStringLiteral("%1: --mesh needs an .obj OUT").arg(command));
        return kExitUsage;
    }

    const CadFormat inFormat = cadFormatFromPath(in);
    if (cadOut && (inFormat == CadFormat::Iges || inFormat == CadFormat::Step ||
                   inFormat == CadFormat::Brep)) {
        // CAD to CAD: read and written by one child, which loads OpenCASCADE once.
        ImportReport imported;
        ExportReport exported;
        const Status written = convertCadFile(in, out, exportOptions, imported, exported);
        if (parser.isSet(report) && imported.facesImported > 0)
            printOut(QStringLiteral("%1: %2").arg(in, imported.summary()));
        else if (imported.facesSkipped() > 0)
            printError(QStringLiteral("%1: %2 face(s) skipped, %3 imported (--report lists why)")
                           .arg(in)
                           .arg(imported.facesSkipped())
                           .arg(imported.facesImported));
        for (const QString& w : exported.warnings)
            printError(QStringLiteral("%1: warning: %2").arg(out, w));
        if (!written) {
            printError(written.message());
            return kExitBadInput;
        }
        if (parser.isSet(report))
            printOut(QStringLiteral("%1: %2").arg(out, exported.summary()));
        return kExitOk;
    }
    const Expected<ImportResult> result = importFile(in);
    if (!result) {
        printError(result.message());
        return kExitBadInput;
    }
    if (parser.isSet(report))
        printOut(QStringLiteral("%1: %2").arg(in, result->report.summary()));
    else if (result->report.facesSkipped() > 0)
        printError(QStringLiteral("%1: %2 face(s) skipped, %3 imported (--report lists why)")
                       .arg(in)
                       .arg(result->report.facesSkipped())
                       .arg(result->report.facesImported));

    QString error;
    const auto take = [&error](const Status& status) {
        error = status.message();
        return bool(status);
    };
    bool written = false;
    if (cadOut) {
        ExportReport exported;
        written = take(exportCadFile(result->scene, out, exportOptions, exported));
        for (const QString& w : exported.warnings)
            printError(QStringLiteral("%1: warning: %2").arg(out, w));
        if (written && parser.isSet(report))
            printOut(QStringLiteral("%1: %2").arg(out, exported.summary()));
    } else if (outFormat == CadFormat::Knot)
        written = take(writeKnotFile(out, result->scene));
    else if (parser.isSet(mesh))
        written = take(writeObjMeshFile(out, result->scene, meshOptions));
    else
        written = take(writeObjFile(out, result->scene));
    if (!written) {
        printError(error);
        return kExitBadInput;
    }
    return kExitOk;
}

} // namespace kw::cli
