// MainWindow: File ▸ Export… and Export Selected… — STEP and IGES written by OpenCASCADE in the
// CAD child process on a worker thread behind a progress dialog (Cancel kills the child), OBJ
// written here; the open-seam report shown when it is done. The document stays what it is.
#include "model/cad/cadexport.h"
#include "model/io/objfile.h"
#include "ui/mainwindow.h"

#include <QEventLoop>
#include <QFileInfo>
#include <QProgressDialog>
#include <QStatusBar>
#include <QThread>
#include <QTimer>
#include <algorithm>
#include <atomic>
#include <memory>
#include <set>

namespace kw {

namespace {

struct ExportJob : ExchangeJob {
    ExportReport report;
    std::optional<Error> error; ///< set when the export failed or was cancelled
};

// The scene with only `keep`'s surfaces, and the part of the import's record among them: edges
// with both sides kept, shells with their kept faces (no longer closed when a face is left out).
Scene sceneOf(const Scene& all, std::vector<SurfaceId> keep) {
    std::sort(keep.begin(), keep.end());
    Scene s = all;
    s.surfaces.clear();
    for (const Surface& x : all.surfaces)
        if (std::binary_search(keep.begin(), keep.end(), x.id))
            s.surfaces.push_back(x);
    s.topology = topologyOfFaces(all.topology, keep);
    return s;
}

} // namespace

QString exportFileFilter(bool occt) {
    QStringList filters;
    if (occt)
        filters << QObject::tr("STEP (*.step *.stp)") << QObject::tr("IGES (*.iges *.igs)");
    filters << QObject::tr("OBJ, free-form surfaces (*.obj)");
    return filters.join(QStringLiteral(";;"));
}

bool isExportPath(const QString& path) {
    const CadFormat f = cadFormatFromPath(path);
    return f == CadFormat::Step || f == CadFormat::Iges || f == CadFormat::Obj;
}

void MainWindow::exportDialog(bool selectedOnly) {
    if (m_importProgress)
        return;
    if (selectedOnly && m_selection->selectedSurfaces().empty()) {
        showError(tr("Cannot export"), tr("No surface is selected."));
        return;
    }
    const QString named = m_path.isEmpty() ? m_importedPath : m_path;
    const QString suggested =
        (named.isEmpty() ? tr("untitled") : QFileInfo(named).completeBaseName()) +
        QStringLiteral(".step");
    const QString path =
        m_dialogs.saveFile(this, selectedOnly ? tr("Export selected surfaces") : tr("Export"),
                           exportFileFilter(occtAvailable()), suggested);
    if (!path.isEmpty())
        (void)exportModel(path, selectedOnly); // a failure is shown there
}

Status MainWindow::exportModel(const QString& path, bool selectedOnly) {
    if (m_importProgress) // one exchange at a time; its own dialog is up
        return Error(tr("Cannot export %1 while another import or export runs").arg(path), path);
    const CadFormat format = cadFormatFromPath(path);
    const QString name = QFileInfo(path).fileName();
    if (!isExportPath(path))
        return showError(
            tr("Cannot export"),
            Error(tr("%1: Knotwork exports STEP (.step, .stp), IGES (.iges, .igs) and OBJ (.obj)")
                      .arg(path),
                  path));
    const Scene scene =
        selectedOnly ? sceneOf(m_doc->scene(), m_selection->selectedSurfaces()) : m_doc->scene();
    if (format == CadFormat::Obj) {
        if (scene.surfaces.empty())
            return showError(
                tr("Cannot export"),
                Error(tr("%1: nothing to export: the document has no surfaces").arg(path), path));
        if (const Status written = writeObjFile(path, scene); !written)
            return showError(tr("Cannot export"), written.error());
        statusBar()->showMessage(
            tr("Exported %1; the document is still %2").arg(name, displayName()), 10000);
        return ok();
    }

    auto job = std::make_shared<ExportJob>();
    std::unique_ptr<QThread> worker(QThread::create([job, scene, path] {
        const Status written =
            exportCadFile(scene, path, ExportOptions{}, job->report, [job](int done, int total) {
                job->done = done;
                job->total = total;
                return !job->cancel.load();
            });
        if (!written)
            job->error = written.error();
    }));
    runWithProgress(tr("Export"), tr("Exporting %1…").arg(name), *job, std::move(worker),
                    [job] { return !job->error; });

    if (job->error) {
        if (job->cancel) { // asked for by the user: the status bar says so, no error dialog
            const Error cancelled(tr("Export of %1 cancelled; nothing was written").arg(name),
                                  path);
            statusBar()->showMessage(cancelled.message, 10000);
            return cancelled;
        }
        Error failed = *job->error;
        if (!job->report.warnings.isEmpty())
            failed.message += QStringLiteral("\n\n") + job->report.summary();
        return showError(tr("Cannot export"), std::move(failed));
    }
    const QString summary = tr("Exported %1: %2 face(s), %3 solid(s); the document is still %4")
                                .arg(name)
                                .arg(job->report.faces)
                                .arg(job->report.solids)
                                .arg(displayName());
    // The open seams an edit made, by face and gap, as `convert` prints them.
    if (!job->report.warnings.isEmpty() && m_dialogs.information)
        m_dialogs.information(
            this, tr("Export report"),
            tr("%1 was written with remarks:\n\n%2").arg(name, job->report.summary()));
    statusBar()->showMessage(summary, 10000);
    return ok();
}

} // namespace kw
