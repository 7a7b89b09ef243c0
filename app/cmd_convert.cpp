// knotwork convert IN OUT: IGES/STEP/BREP/OBJ/.knot in, .knot or OBJ (free-form or mesh) out.
#include "app/commands.h"
#include "model/cad/cadimport.h"
#include "model/knotfile.h"
#include "model/objfile.h"

#include <QCommandLineParser>
#include <QFileInfo>

namespace kw::cli {

int runConvert(const QStringList& args) {
    QCommandLineParser parser;
    parser.setApplicationDescription(QStringLiteral(
        "Convert IN (.igs/.iges, .stp/.step, .brep, .obj or .knot) to OUT (.knot, or .obj:\n"
        "free-form surfaces with trims, or a triangle mesh with --mesh). Faces that cannot be\n"
        "imported are counted on stderr; --report lists each one and every warning."));
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
    parser.addOption(report);
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
    if (outFormat != CadFormat::Knot && outFormat != CadFormat::Obj) {
        printError(QStringLiteral("%1: OUT must end in .knot or .obj: %2").arg(command, out));
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

    QString error;
    const std::optional<ImportResult> result = importFile(in, error);
    if (!result) {
        printError(error);
        return kExitBadInput;
    }
    if (parser.isSet(report))
        printOut(QStringLiteral("%1: %2").arg(in, result->report.summary()));
    else if (result->report.facesSkipped() > 0)
        printError(QStringLiteral("%1: %2 face(s) skipped, %3 imported (--report lists why)")
                       .arg(in)
                       .arg(result->report.facesSkipped())
                       .arg(result->report.facesImported));

    bool written = false;
    if (outFormat == CadFormat::Knot)
        written = writeKnotFile(out, result->scene, &error);
    else if (parser.isSet(mesh))
        written = writeObjMeshFile(out, result->scene, meshOptions, error);
    else
        written = writeObjFile(out, result->scene, error);
    if (!written) {
        printError(error);
        return kExitBadInput;
    }
    return kExitOk;
}

} // namespace kw::cli
