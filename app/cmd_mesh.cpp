// knotwork mesh IN -o OUT.obj: a CAD file triangulated by OpenCASCADE's BRepMesh, the mesh an
// OCCT-based viewer draws (the mesh peer), tagged with the surface ids `knotwork
// convert` gives the same file, so `knotwork render MODEL.knot --peer-mesh OUT.obj` can draw it
// and compare it with the exact surfaces pixel by pixel.
#include "app/commands.h"
#include "model/cad/cadprocess.h"
#include "model/io/knotfile.h"
#include "model/io/savefile.h"

#include <QCommandLineParser>
#include <cmath>

namespace kw::cli {

int runMesh(const QStringList& args) {
    QCommandLineParser parser;
    parser.setApplicationDescription(QStringLiteral(
        "Triangulate IN (.igs/.iges, .stp/.step, .brep) with OpenCASCADE's\n"
        "BRepMesh_IncrementalMesh (absolute linear deflection, angular deflection, one thread)\n"
        "and write the triangles with OCCT viewers' vertex normals as OBJ: one group\n"
        "surface_<id> per face, with the ids 'knotwork convert IN MODEL.knot' gives the faces,\n"
        "for 'knotwork render MODEL.knot --peer-mesh OUT.obj'."));
    parser.addPositionalArgument(QStringLiteral("IN"), QStringLiteral("CAD file to mesh."));
    const QCommandLineOption out({QStringLiteral("o"), QStringLiteral("output")},
                                 QStringLiteral("The OBJ to write."), QStringLiteral("OUT.obj"));
    const QCommandLineOption linear(
        QStringLiteral("linear-deflection"),
        QStringLiteral("Largest distance between a triangle and the surface, in model units "
                       "(default: OCCT viewers' 0.004 x the largest side of the bounding box)."),
        QStringLiteral("D"));
    const QCommandLineOption angular(
        QStringLiteral("angular-deflection"),
        QStringLiteral("Largest angle between the normals of adjacent triangles, degrees "
                       "(default 20, OCCT viewers' default)."),
        QStringLiteral("DEG"), QStringLiteral("20"));
    const QCommandLineOption knot(
        QStringLiteral("knot"),
        QStringLiteral("Also write the converted scene (as 'knotwork convert') from the same "
                       "read."),
        QStringLiteral("MODEL.knot"));
    parser.addOptions({out, linear, angular, knot});
    if (const int code = parseOrExit(parser, args); code >= 0)
        return code;
    const QString command = args.value(0);
    const QStringList pos = parser.positionalArguments();
    if (pos.size() != 1 || !parser.isSet(out)) {
        printError(QStringLiteral("%1: expected IN and -o OUT.obj (see --help)").arg(command));
        return kExitUsage;
    }
    const QString in = pos[0], outPath = parser.value(out);
    if (cadFormatFromPath(outPath) != CadFormat::Obj) {
        printError(QStringLiteral("%1: OUT must end in .obj: %2").arg(command, outPath));
        return kExitUsage;
    }
    if (parser.isSet(knot) && cadFormatFromPath(parser.value(knot)) != CadFormat::Knot) {
        printError(
            QStringLiteral("%1: --knot must end in .knot: %2").arg(command, parser.value(knot)));
        return kExitUsage;
    }
    MeshDeflection deflection;
    bool ok = true;
    if (parser.isSet(linear)) {
        deflection.linear = parser.value(linear).toDouble(&ok);
        if (!ok || !std::isfinite(deflection.linear) || deflection.linear <= 0.0) {
            printError(QStringLiteral("%1: --linear-deflection '%2' is not a positive number")
                           .arg(command, parser.value(linear)));
            return kExitUsage;
        }
    }
    deflection.angularDegrees = parser.value(angular).toDouble(&ok);
    if (!ok || !(deflection.angularDegrees > 0.0) || deflection.angularDegrees > 180.0) {
        printError(QStringLiteral("%1: --angular-deflection '%2' is not in (0, 180]")
                       .arg(command, parser.value(angular)));
        return kExitUsage;
    }
    const CadFormat format = cadFormatFromPath(in);
    if (format != CadFormat::Iges && format != CadFormat::Step && format != CadFormat::Brep) {
        printError(
            QStringLiteral("%1: IN must be an IGES, STEP or BREP file: %2").arg(command, in));
        return kExitUsage;
    }
    TaggedMeshSet mesh;
    const Expected<ImportResult> result = importInChildProcess(in, format, {}, &deflection, &mesh);
    if (!result) {
        printError(result.message());
        return kExitBadInput;
    }
    for (const QString& w : result->report.warnings)
        if (w.contains(QLatin1String("BRepMesh")))
            printError(QStringLiteral("%1: warning: %2").arg(in, w));
    Status written = saveBytesAtomically(outPath, writeTaggedMeshObj(mesh));
    if (written && parser.isSet(knot))
        written = writeKnotFile(parser.value(knot), result->scene);
    if (!written) {
        printError(written.message());
        return kExitBadInput;
    }
    printOut(QStringLiteral("%1: %2 of %3 face(s) meshed, %4 triangles, %5 vertices (BRepMesh "
                            "linear deflection %6, angular %7 deg) -> %8\n")
                 .arg(in)
                 .arg(mesh.faces.size())
                 .arg(result->scene.surfaces.size())
                 .arg(mesh.triangleCount())
                 .arg(mesh.vertexCount())
                 .arg(mesh.linearDeflection, 0, 'g', 6)
                 .arg(mesh.angularDeflectionDegrees, 0, 'g', 6)
                 .arg(outPath));
    return kExitOk;
}

} // namespace kw::cli
