// MainWindow: file handling — New, Open, Save, Save As (also of imported scenes), recent files,
// export, drops, title.
#include "model/cad/cadimport.h"
#include "model/io/knotfile.h"
#include "render/image_writer.h"
#include "render/offscreen_renderer.h"
#include "ui/autosave.h"
#include "ui/desktopactions.h"
#include "ui/mainwindow.h"
#include "ui/viewport.h"

#include <QDir>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileInfo>
#include <QLocale>
#include <QMenu>
#include <QMimeData>
#include <QSettings>
#include <QStatusBar>
#include <QUndoStack>

namespace kw {

namespace {

constexpr int kMaxRecent = 8;
const QString kKnotFilter = QStringLiteral("Knotwork projects (*.knot);;All files (*)");

QString knotPathOf(const QMimeData* mime) {
    if (!mime || !mime->hasUrls())
        return {};
    for (const QUrl& url : mime->urls())
        if (url.isLocalFile() &&
            url.toLocalFile().endsWith(QLatin1String(".knot"), Qt::CaseInsensitive))
            return url.toLocalFile();
    return {};
}

/// "dir/name.knot" for an imported "dir/name.igs".
QString knotPathNextTo(const QString& imported) {
    const QFileInfo info(imported);
    return info.dir().filePath(info.completeBaseName() + QStringLiteral(".knot"));
}

} // namespace

Status MainWindow::openFile(const QString& path) {
    Expected<Scene> scene = readKnotFile(path);
    const Status reset = scene ? m_doc->resetScene(std::move(*scene)) : Status(scene.error());
    if (!reset)
        return showError(tr("Cannot open file"), reset.error());
    m_stack->clear();
    m_stack->setClean();
    setFilePath(path);
    addRecent(path);
    // A project saved with a partition mode is shown so; one without, as the preferences say.
    m_desktop->applyDisplay(m_doc->scene().display);
    if (!m_doc->scene().surfaces.empty())
        selectSurface(m_doc->scene().surfaces.front().id);
    statusBar()->showMessage(tr("Opened %1").arg(QFileInfo(path).fileName()), 5000);
    return ok();
}

bool isExportPath(const QString& path); // mainwindow_export.cpp

Status MainWindow::saveFile(const QString& path) {
    // A project is JSON: never under a CAD or mesh name, which other programs would misread.
    if (isExportPath(path)) {
        if (Status exported = exportModel(path); !exported)
            return exported; // shown by exportModel
        statusBar()->showMessage(tr("Exported %1 (Save As with a %2 name exports); the document "
                                    "is still the project %3")
                                     .arg(QFileInfo(path).fileName(),
                                          cadFormatName(cadFormatFromPath(path)), displayName()),
                                 10000);
        return ok();
    }
    if (const CadFormat f = cadFormatFromPath(path);
        f != CadFormat::Knot && f != CadFormat::Unknown)
        return showError(tr("Cannot save file"),
                         Error(tr("%1: Knotwork does not write %2 files; save the project as "
                                  ".knot, or export STEP, IGES or OBJ")
                                   .arg(path, cadFormatName(f)),
                               path));
    // The view's camera goes into the file; it is not an edit (no undo step, not "modified"),
    // as in other editors, so it is copied into the document only here.
    Camera camera = m_viewport->cameraController().camera();
    camera.authored = true;
    Scene scene = m_doc->scene();
    scene.camera = camera;
    // So is the partition mode the view draws (as the camera, not an edit).
    scene.display = m_desktop->currentDisplay();
    // The previous version becomes FILE.bak. A failed copy does not stop the save; it is said.
    const Status backup =
        QSettings().value(kKeepBackupKey, true).toBool() ? keepBackup(path) : ok();
    if (!backup)
        statusBar()->showMessage(tr("No backup kept: %1").arg(backup.message()), 10000);
    if (const Status written = writeKnotFile(path, scene); !written)
        return showError(tr("Cannot save file"), written.error());
    // Both were written, so both passed the writer's checkScene: neither can be refused.
    (void)m_doc->setCamera(camera);
    (void)m_doc->setDisplay(scene.display);
    m_stack->setClean();
    setFilePath(path);
    addRecent(path);
    if (backup)
        statusBar()->showMessage(tr("Saved %1").arg(QFileInfo(path).fileName()), 5000);
    return ok();
}

bool MainWindow::offerRecovery() {
    for (const Recovery& r : Autosave::orphans()) {
        const QString name = !r.originalPath.isEmpty()   ? QFileInfo(r.originalPath).fileName()
                             : !r.importedFrom.isEmpty() ? QFileInfo(r.importedFrom).fileName()
                                                         : tr("an untitled document");
        const QString text =
            tr("Knotwork did not close normally. Unsaved changes to %1 were "
               "autosaved at %2. Restore them?")
                .arg(name, QLocale().toString(r.savedAt.toLocalTime(), QLocale::ShortFormat));
        const QMessageBox::StandardButton answer =
            m_dialogs.askRecover ? m_dialogs.askRecover(this, text) : QMessageBox::Cancel;
        if (answer == QMessageBox::Discard) {
            Autosave::discard(r);
            continue;
        }
        if (answer != QMessageBox::Yes)
            continue;
        Expected<Scene> scene = Autosave::load(r);
        const Status restored = scene ? m_doc->resetScene(std::move(*scene)) : scene.error();
        if (!restored) {
            showError(tr("Cannot restore the unsaved changes"), restored.error());
            continue; // kept: the file may be opened by hand
        }
        m_stack->clear();
        setFilePath(r.originalPath);
        m_importedPath = r.importedFrom;
        m_stack->resetClean(); // modified: the edits are not in any saved file
        updateTitle();
        if (!m_doc->scene().surfaces.empty())
            selectSurface(m_doc->scene().surfaces.front().id);
        // Ours first, then the old one goes: a crash in between still leaves a copy.
        statusBar()->showMessage(tr("Restored the unsaved changes to %1").arg(name), 10000);
        if (const Status saved = m_autosave->writeNow())
            Autosave::discard(r);
        else
            statusBar()->showMessage(tr("Autosave failed: %1").arg(saved.message()));
        return true;
    }
    return false;
}

void MainWindow::newDocument() {
    if (!maybeSave())
        return;
    Scene scene;
    scene.continuity = Preferences::load().continuity; // the user's defaults for new projects
    const Status reset = m_doc->resetScene(std::move(scene));
    Q_ASSERT(reset); // an empty scene with validated tolerances (Preferences::load) is valid
    m_stack->clear();
    m_stack->setClean();
    setFilePath(QString());
}

void MainWindow::openDialog() {
    if (!maybeSave())
        return;
    const QString path = m_dialogs.openFile(this, tr("Open project"), kKnotFilter);
    if (!path.isEmpty())
        (void)openFile(path); // a failure is shown there
}

bool MainWindow::save() {
    return m_path.isEmpty() ? saveAs() : bool(saveFile(m_path));
}

bool MainWindow::saveAs() {
    const QString suggested = !m_path.isEmpty()           ? m_path
                              : !m_importedPath.isEmpty() ? knotPathNextTo(m_importedPath)
                                                          : tr("untitled.knot");
    QString path = m_dialogs.saveFile(this, tr("Save project as"), kKnotFilter, suggested);
    if (path.isEmpty())
        return false;
    if (QFileInfo(path).suffix().isEmpty())
        path += QStringLiteral(".knot");
    return bool(saveFile(path));
}

void MainWindow::exportImage() {
    const QString named = m_path.isEmpty() ? m_importedPath : m_path;
    const QString suggested =
        named.isEmpty() ? tr("untitled.png") : QFileInfo(named).completeBaseName() + ".png";
    const QString path =
        m_dialogs.saveFile(this, tr("Export image"),
                           tr("Images (*.png *.jpg *.tif *.exr);;EXR, float (*.exr)"), suggested);
    if (path.isEmpty())
        return;
    if (!isSupportedImagePath(path)) {
        showError(tr("Cannot export image"),
                  tr("%1: unsupported image type (use .png, .jpg, .tif or .exr)").arg(path));
        return;
    }
    Dialogs::ExportOptions options{m_viewport->size(), false};
    if (m_dialogs.exportOptions) {
        const auto chosen = m_dialogs.exportOptions(this, options);
        if (!chosen)
            return;
        options = *chosen;
    }
    // Rendered again off screen at the chosen size with the view's camera and options, and
    // written through OpenImageIO, as `knotwork render` does. The picture is anti-aliased as
    // the view is (its options carry the samples; all at once); AOV frames are exact samples,
    // so they are a second, aliased frame.
    const QString aovPath = QFileInfo(path).dir().filePath(QFileInfo(path).completeBaseName() +
                                                           QStringLiteral("_aov.exr"));
    OffscreenRenderer renderer;
    RenderOptions render = m_viewport->renderOptions();
    render.lightCount = std::clamp(int(m_doc->scene().lights.size()), 1, kMaxLights);
    render.controlNet = false; // the picture of the surfaces, not of the editing aids
    const Camera camera = m_viewport->cameraController().camera();
    // Each step runs while the ones before succeeded; the first failure is shown.
    Status done = renderer.create();
    if (done)
        done = renderer.setSize(options.size, false);
    if (done)
        done = renderer.render(*m_doc, camera, render);
    if (done)
        done = writeColorImage(renderer.colorImage(), path);
    if (done && options.aov)
        done = renderer.setSize(options.size, true);
    if (done && options.aov)
        done = renderer.render(*m_doc, camera, render);
    if (done && options.aov)
        done = writeAovImage(renderer.aov(), aovPath);
    if (!done) {
        showError(tr("Cannot export image"), done.message());
        return;
    }
    statusBar()->showMessage(
        options.aov ? tr("Exported %1 and %2")
                          .arg(QFileInfo(path).fileName(), QFileInfo(aovPath).fileName())
                    : tr("Exported %1").arg(QFileInfo(path).fileName()),
        5000);
}

bool MainWindow::maybeSave() {
    if (m_stack->isClean())
        return true;
    switch (m_dialogs.askSave(this, tr("%1 has unsaved changes. Save them?").arg(displayName()))) {
    case QMessageBox::Save:
        return save();
    case QMessageBox::Discard:
        return true;
    default:
        return false;
    }
}

void MainWindow::setFilePath(const QString& path) {
    m_path = path;
    m_importedPath.clear();
    updateTitle();
}

QString MainWindow::displayName() const {
    const QString named = m_path.isEmpty() ? m_importedPath : m_path;
    return named.isEmpty() ? tr("Untitled") : QFileInfo(named).fileName();
}

void MainWindow::updateTitle() {
    setWindowFilePath(m_path);
    setWindowTitle(tr("%1[*] — Knotwork").arg(displayName()));
    setWindowModified(!m_stack->isClean());
}

QStringList MainWindow::recentFiles() const {
    return QSettings().value(QStringLiteral("recentFiles")).toStringList();
}

void MainWindow::addRecent(const QString& path) {
    const QString absolute = QFileInfo(path).absoluteFilePath();
    QStringList list = recentFiles();
    list.removeAll(absolute);
    list.prepend(absolute);
    while (list.size() > kMaxRecent)
        list.removeLast();
    QSettings().setValue(QStringLiteral("recentFiles"), list);
    rebuildRecentMenu();
}

QStringList recentLabels(const QStringList& paths) {
    // The file name, with as many parent folders as it takes to tell it from the others
    // ("a/model.knot", "b/model.knot").
    QStringList labels;
    for (const QString& path : paths) {
        const QStringList parts =
            QDir::fromNativeSeparators(path).split(QLatin1Char('/'), Qt::SkipEmptyParts);
        int depth = 1;
        auto tail = [](const QStringList& p, int n) {
            return p.mid(std::max(0, int(p.size()) - n)).join(QLatin1Char('/'));
        };
        for (; depth < parts.size(); ++depth) {
            bool unique = true;
            for (const QString& other : paths) {
                if (other == path)
                    continue;
                const QStringList o =
                    QDir::fromNativeSeparators(other).split(QLatin1Char('/'), Qt::SkipEmptyParts);
                if (tail(o, depth) == tail(parts, depth))
                    unique = false;
            }
            if (unique)
                break;
        }
        const QString name = parts.value(parts.size() - 1);
        labels << (depth <= 1 ? name
                              : QStringLiteral("%1 — %2").arg(
                                    name, tail(parts, depth).section(QLatin1Char('/'), 0, -2)));
    }
    return labels;
}

void MainWindow::rebuildRecentMenu() {
    m_recentMenu->clear();
    const QStringList list = recentFiles();
    const QStringList labels = recentLabels(list);
    for (int k = 0; k < list.size(); ++k) {
        const QString path = list[k];
        QAction* a = m_recentMenu->addAction(labels[k]);
        a->setToolTip(path);
        a->setData(path);
        connect(a, &QAction::triggered, this, [this, path] {
            if (maybeSave())
                (void)openFile(path); // a failure is shown there
        });
    }
    if (list.isEmpty())
        m_recentMenu->addAction(tr("(none)"))->setEnabled(false);
    else {
        m_recentMenu->addSeparator();
        m_recentMenu->addAction(tr("Clear Menu"), this, [this] {
            QSettings().remove(QStringLiteral("recentFiles"));
            rebuildRecentMenu();
        });
    }
}

void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
    if (!knotPathOf(event->mimeData()).isEmpty())
        event->acceptProposedAction();
}

void MainWindow::dropEvent(QDropEvent* event) {
    const QString path = knotPathOf(event->mimeData());
    if (path.isEmpty())
        return;
    event->acceptProposedAction();
    if (maybeSave())
        (void)openFile(path); // a failure is shown there
}

} // namespace kw
