// knotwork __mesh-faces DIR [--max-memory-mb N]: the persistent child process that builds
// Knotwork surfaces as OpenCASCADE faces and meshes them alone for a parent (FaceMesher,
// model/cad/facemesher.h), with OCCT loaded only here, from libknotwork_occt.so. Hidden from
// --help.
#include "app/commands.h"
#include "app/plugin.h"
#include "model/cad/facemesher.h"
#include "model/cad/handover.h"
#include "model/cad/occtimport.h"
#include "model/io/savefile.h"

#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QFileInfo>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <string>
#include <sys/resource.h>

namespace kw::cli {

namespace {

double processCpuMs() {
    timespec t{};
    ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

void answer(const QByteArray& line) {
    std::fwrite(line.constData(), 1, size_t(line.size()), stdout);
    std::fputc('\n', stdout);
    std::fflush(stdout);
}

// One request: "mesh NAME TOL LIN ANG". The answer line, "ok WALL CPU" or "error REASON".
QByteArray serve(const QString& dir, const QByteArray& request, OcctMeshFacesFunction meshFaces) {
    const QList<QByteArray> t = request.split(' ');
    bool okTol = false, okLin = false, okAng = false;
    const double tolerance = t.value(2).toDouble(&okTol);
    const double linear = t.value(3).toDouble(&okLin);
    const double angular = t.value(4).toDouble(&okAng);
    const QString name = QString::fromUtf8(t.value(1));
    // The parent names files in DIR only.
    if (t.size() != 5 || t[0] != "mesh" || !okTol || !okLin || !okAng || !(tolerance > 0.0) ||
        !(linear > 0.0) || !(angular > 0.0) || name.contains(QLatin1Char('/')) || name.isEmpty())
        return "error malformed request: " + request.left(200);
    QFile in(QDir(dir).filePath(name));
    const Expected<ImportResult> scene = in.open(QIODevice::ReadOnly)
                                             ? decodeImportHandover(in.readAll())
                                             : Expected<ImportResult>(Error(in.errorString()));
    if (!scene)
        return "error cannot read the faces to mesh: " + scene.message().toUtf8();
    // The build and the mesh alone are timed: what a viewer holding the face would pay.
    QElapsedTimer wall;
    const double cpu0 = processCpuMs();
    wall.start();
    TaggedMeshSet mesh;
    const Status meshed = meshFaces(&scene->scene, tolerance, linear, angular, &mesh);
    const double wallMs = double(wall.nsecsElapsed()) * 1e-6;
    const double cpuMs = processCpuMs() - cpu0;
    if (!meshed)
        return "error " + meshed.message().simplified().toUtf8();
    if (const Status left = saveBytesAtomically(QDir(dir).filePath(name + QStringLiteral(".obj")),
                                                writeTaggedMeshObj(mesh));
        !left)
        return "error cannot leave the triangles for the parent: " +
               left.message().simplified().toUtf8();
    return "ok " + QByteArray::number(wallMs, 'f', 4) + ' ' + QByteArray::number(cpuMs, 'f', 4);
}

} // namespace

int runMeshFaces(const QStringList& args) {
    // args[0] is "knotwork __mesh-faces"; FaceMesher builds the line.
    long long memoryMb = 0;
    bool usage = args.size() < 2;
    for (qsizetype k = 2; k < args.size() && !usage; k += 2) {
        bool ok = false;
        if (args[k] == QLatin1String("--max-memory-mb") && k + 1 < args.size())
            memoryMb = args[k + 1].toLongLong(&ok);
        usage = !ok;
    }
    if (usage || !QFileInfo(args.value(1)).isDir()) {
        printError(QStringLiteral("%1: expected DIR [--max-memory-mb N] (used by knotwork itself "
                                  "to mesh faces in a child process)")
                       .arg(args.value(0)));
        return kExitUsage;
    }
    if (memoryMb > 0) {
        const rlim_t bytes = rlim_t(memoryMb) << 20;
        const rlimit limit{bytes, bytes};
        if (::setrlimit(RLIMIT_AS, &limit) != 0)
            printError(QStringLiteral("%1: cannot set the memory limit").arg(args.value(0)));
    }
    const Expected<QFunctionPointer> resolved =
        app::resolveModuleSymbol(QString::fromLatin1(kOcctModuleName), kOcctMeshFacesSymbol);
    if (!resolved) {
        printError(QStringLiteral("%1: %2").arg(args.value(0), resolved.message()));
        return kExitBadInput;
    }
    const auto meshFaces = reinterpret_cast<OcctMeshFacesFunction>(*resolved);
    for (std::string line; std::getline(std::cin, line);) {
        const QByteArray request = QByteArray::fromStdString(line).trimmed();
        if (!request.isEmpty())
            answer(serve(args[1], request, meshFaces));
    }
    return kExitOk;
}

} // namespace kw::cli
