// FaceMesher: the parent side of `knotwork __mesh-faces` (facemesher.h).
#include "model/cad/facemesher.h"

#include "model/cad/cadprocess.h"
#include "model/cad/cadtempdir.h"
#include "model/cad/handover.h"
#include "model/io/savefile.h"

#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QProcess>
#include <algorithm>
#include <csignal>
#include <sys/prctl.h>
#include <unistd.h>

namespace kw {

struct FaceMesher::Impl {
    QProcess child;
    QString dir;
    int requests = 0;
    pid_t pid = 0;

    void stop() {
        if (child.state() != QProcess::NotRunning) {
            child.closeWriteChannel();
            if (!child.waitForFinished(2000)) {
                child.kill();
                child.waitForFinished(-1);
            }
        }
        if (pid)
            unregisterCadChild(pid);
        pid = 0;
        if (!dir.isEmpty())
            removeCadTempDir(dir);
        dir.clear();
    }
};

FaceMesher::FaceMesher() : d(std::make_unique<Impl>()) {}

FaceMesher::~FaceMesher() {
    d->stop();
}

Status FaceMesher::start() {
    if (d->child.state() == QProcess::Running)
        return ok();
    d->stop();
    Expected<QString> made = makeCadTempDir();
    if (!made)
        return Error(QStringLiteral("cannot make a temporary folder for the face mesher: %1")
                         .arg(made.message()));
    d->dir = *made;
    d->child.setProgram(cadReaderExecutable());
    d->child.setArguments({QString::fromLatin1(kMeshFacesVerb), d->dir,
                           QStringLiteral("--max-memory-mb"),
                           QString::number(cadMemoryLimitBytes() >> 20)});
    // The child dies with this process, as the CAD reader's does (cadprocess.cpp).
    const pid_t parent = ::getpid();
    d->child.setChildProcessModifier([parent] {
        ::prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (::getppid() != parent)
            ::_exit(127);
    });
    d->child.start(QIODevice::ReadWrite);
    if (!d->child.waitForStarted(30000)) {
        Error failed(QStringLiteral("cannot start the face mesher (%1): %2")
                         .arg(d->child.program(), d->child.errorString()));
        d->stop();
        return failed;
    }
    d->pid = pid_t(d->child.processId());
    registerCadChild(d->pid);
    return ok();
}

Status FaceMesher::mesh(const std::vector<Surface>& surfaces, double tolerance, double linear,
                        double angularDegrees, TaggedMeshSet& out, FaceMeshCost& cost,
                        double seconds) {
    if (Status started = start(); !started)
        return started;
    ImportResult request;
    request.scene.surfaces = surfaces;
    std::uint32_t next = 1;
    for (const Surface& s : surfaces) {
        next = std::max(next, s.id.value + 1);
        for (const TrimLoop& l : s.trims)
            next = std::max(next, l.id.value + 1);
    }
    request.scene.nextId = next;
    for (int k = 0; k < int(surfaces.size()); ++k)
        request.sourceFaces.push_back(k + 1);
    const QString name = QStringLiteral("request%1.kwi").arg(++d->requests);
    const QString path = QDir(d->dir).filePath(name);
    if (const Status saved = saveBytesAtomically(path, encodeImportHandover(request)); !saved)
        return Error(
            QStringLiteral("cannot hand the faces to the face mesher: %1").arg(saved.message()));
    const QByteArray line = "mesh " + name.toUtf8() + ' ' + QByteArray::number(tolerance, 'g', 17) +
                            ' ' + QByteArray::number(linear, 'g', 17) + ' ' +
                            QByteArray::number(angularDegrees, 'g', 17) + '\n';
    d->child.write(line);
    d->child.waitForBytesWritten(5000);
    QElapsedTimer clock;
    clock.start();
    QByteArray answer;
    while (!d->child.canReadLine()) {
        if (d->child.state() != QProcess::Running) {
            const QList<QByteArray> err = d->child.readAllStandardError().trimmed().split('\n');
            Error ended(QStringLiteral("the face mesher ended (%1)%2")
                            .arg(d->child.exitStatus() == QProcess::CrashExit
                                     ? QStringLiteral("crashed")
                                     : QStringLiteral("exit code %1").arg(d->child.exitCode()),
                                 err.back().isEmpty()
                                     ? QString()
                                     : QStringLiteral(": ") + QString::fromLocal8Bit(err.back())));
            d->stop();
            return ended;
        }
        if (clock.elapsed() > seconds * 1000.0) {
            d->child.kill();
            d->stop();
            return Error(QStringLiteral("the face mesher did not answer within %1 s").arg(seconds));
        }
        d->child.waitForReadyRead(50);
    }
    answer = d->child.readLine().trimmed();
    QFile::remove(path);
    const QList<QByteArray> t = answer.split(' ');
    if (t.value(0) != "ok" || t.size() != 3) {
        return Error(answer.startsWith("error ") ? QString::fromUtf8(answer.mid(6))
                                                 : QStringLiteral("the face mesher answered '%1'")
                                                       .arg(QString::fromUtf8(answer.left(200))));
    }
    cost.wallMs = t[1].toDouble();
    cost.cpuMs = t[2].toDouble();
    const QString obj = path + QStringLiteral(".obj");
    Expected<TaggedMeshSet> read = readTaggedMeshObjFile(obj);
    QFile::remove(obj);
    if (!read)
        return Error(
            QStringLiteral("the face mesher's triangles are unreadable: %1").arg(read.message()));
    out = std::move(read).value();
    return ok();
}

} // namespace kw
