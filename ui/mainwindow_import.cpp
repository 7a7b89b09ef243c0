// MainWindow: File ▸ Import… — IGES, STEP, BREP and OBJ read on a worker thread behind a
// progress dialog whose Cancel stops the importer through its progress callback.
#include "model/cad/cadimport.h"
#include "model/document/naming.h"
#include "ui/mainwindow.h"
#include "ui/preferences.h"

#include <QEventLoop>
#include <QFileInfo>
#include <QProgressDialog>
#include <QStatusBar>
#include <QThread>
#include <QTimer>
#include <QUndoStack>
#include <algorithm>
#include <atomic>
#include <memory>

namespace kw {

namespace {

// Shared by the UI thread and the worker: the worker writes progress and the outcome, the UI
// thread writes `cancel`; the outcome is read only after the thread has finished.
struct ImportJob : ExchangeJob {
    std::optional<ImportResult> result;
    Error error; ///< without a result: why
};

// How often the UI thread looks at the worker's progress.
constexpr int kTickMs = 30;

} // namespace

QString importFileFilter(bool occt) {
    const QString off =
        occt ? QString() : QObject::tr(" — unavailable, Knotwork was built without OpenCASCADE");
    QStringList filters;
    filters << (occt ? QObject::tr("All importable files (*.igs *.iges *.stp *.step *.brep *.brp "
                                   "*.obj)")
                     : QObject::tr("All importable files (*.obj)"));
    filters << QObject::tr("IGES%1 (*.igs *.iges)").arg(off)
            << QObject::tr("STEP%1 (*.stp *.step)").arg(off)
            << QObject::tr("BREP%1 (*.brep *.brp)").arg(off) << QObject::tr("OBJ (*.obj)")
            << QObject::tr("All files (*)");
    return filters.join(QStringLiteral(";;"));
}

void MainWindow::importDialog() {
    if (m_importProgress || !maybeSave())
        return;
    const auto ask = m_dialogs.importFile ? m_dialogs.importFile : m_dialogs.openFile;
    const QString path = ask(this, tr("Import"), importFileFilter(occtAvailable()));
    if (!path.isEmpty())
        (void)importFile(path); // a failure is shown there
}

void MainWindow::runWithProgress(const QString& title, const QString& label, ExchangeJob& job,
                                 std::unique_ptr<QThread> worker,
                                 const std::function<bool()>& succeeded) {
    // Owned so it can be destroyed before any message: its minimum-duration timer could
    // otherwise show it, window-modal, over the error box of a fast failed exchange.
    auto progressOwner = std::make_unique<QProgressDialog>(label, tr("Cancel"), 0, 0, this);
    QProgressDialog& progress = *progressOwner;
    progress.setWindowTitle(title);
    progress.setWindowModality(Qt::WindowModal);
    progress.setMinimumDuration(300);
    progress.setAutoReset(false);
    progress.setAutoClose(false);
    m_importProgress = &progress; // one exchange at a time: Import and Export both wait
    connect(&progress, &QProgressDialog::canceled, this, [&job] { job.cancel = true; });

    QEventLoop loop;
    QTimer tick;
    tick.setInterval(kTickMs);
    const auto update = [&] {
        if (progress.wasCanceled())
            job.cancel = true; // also a programmatic cancel(), which emits no canceled()
        const int total = job.total;
        if (total > 0 && !progress.wasCanceled()) {
            progress.setMaximum(total);
            progress.setValue(std::clamp(job.done.load(), 0, total));
        }
        if (m_dialogs.importProgress)
            m_dialogs.importProgress(&progress);
        if (worker->isFinished())
            loop.quit();
    };
    connect(&tick, &QTimer::timeout, &loop, update);
    connect(worker.get(), &QThread::finished, &loop, &QEventLoop::quit);
    worker->start();
    tick.start();
    update();
    // Re-checked after each exit: a quit delivered before exec() must not leave us waiting.
    while (!worker->isFinished())
        loop.exec();
    worker->wait();
    tick.stop();
    if (progress.wasCanceled())
        job.cancel = true;
    if (!job.cancel && succeeded()) { // done: a full bar (OBJ and .knot report no progress)
        progress.setRange(0, 1);
        progress.setValue(1);
        if (m_dialogs.importProgress)
            m_dialogs.importProgress(&progress);
    }
    m_importProgress = nullptr;
    progress.hide();
}

Status MainWindow::importFile(const QString& path) {
    if (m_importProgress) // one exchange at a time; its own dialog is up
        return Error(tr("Cannot import %1 while another import or export runs").arg(path), path);
    const QString name = QFileInfo(path).fileName();
    auto job = std::make_shared<ImportJob>();
    // importFile is reentrant (plain data out; OCCT sets up its signal handling per thread).
    std::unique_ptr<QThread> worker(QThread::create([job, path] {
        Expected<ImportResult> read = kw::importFile(path, [job](int done, int total) {
            job->done = done;
            job->total = total;
            return !job->cancel.load();
        });
        if (read)
            job->result = std::move(*read);
        else
            job->error = std::move(read).error();
    }));

    runWithProgress(tr("Import"), tr("Importing %1…").arg(name), *job, std::move(worker),
                    [job] { return job->result.has_value(); });

    if (job->cancel) {
        // The importer's own Error when it stopped; otherwise it had finished first. Asked
        // for by the user: the status bar says so, no error dialog.
        const Error cancelled =
            job->result
                ? Error(tr("Import of %1 cancelled; the document is unchanged").arg(name), path)
                : job->error;
        statusBar()->showMessage(cancelled.message, 10000);
        return cancelled;
    }
    if (!job->result)
        return showError(tr("Cannot import file"), job->error);
    // "Face" x 200 in one file: "Face 1" .. "Face 200" in the tree.
    makeSurfaceNamesDistinct(job->result->scene, QFileInfo(path).completeBaseName());
    // A CAD or mesh file carries no continuity tolerances: the user's defaults apply.
    job->result->scene.continuity = Preferences::load().continuity;
    if (const Status reset = m_doc->resetScene(std::move(job->result->scene)); !reset)
        return showError(tr("Cannot import file"), reset.error());
    m_stack->clear();
    m_stack->resetClean(); // unsaved until written as .knot: the title is marked, Save asks where
    setFilePath(QString());
    m_importedPath = path;
    updateTitle();
    if (!m_doc->scene().surfaces.empty())
        selectSurface(m_doc->scene().surfaces.front().id);

    const ImportReport& report = job->result->report;
    const QString summary =
        tr("Imported %1: %n surface(s)", nullptr, static_cast<int>(m_doc->scene().surfaces.size()))
            .arg(name);
    if ((!report.warnings.isEmpty() || !report.skipped.isEmpty()) && m_dialogs.information)
        m_dialogs.information(
            this, tr("Import report"),
            tr("%1 was imported with remarks:\n\n%2").arg(name, report.summary()));
    statusBar()->showMessage(summary, 10000);
    return ok();
}

} // namespace kw
