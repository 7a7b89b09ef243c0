// MainWindow: File ▸ Open Sample — the projects and CAD part in share/knotwork/samples (of the
// installed prefix, or build/share/knotwork in the build tree), opened as copies to start from.
#include "model/cad/cadimport.h"
#include "model/io/install_layout.h"
#include "model/io/knotfile.h"
#include "ui/desktopactions.h"
#include "ui/mainwindow.h"

#include <QDir>
#include <QFileInfo>
#include <QMenu>
#include <QStatusBar>
#include <QUndoStack>
#include <algorithm>

namespace kw {

QString samplesDir() {
    const QString data = dataDir();
    return data.isEmpty() ? QString() : data + QStringLiteral("/samples");
}

void MainWindow::addSamplesMenu(QMenu* file) {
    QMenu* menu = file->addMenu(tr("Open &Sample"));
    menu->setObjectName(QStringLiteral("menuSamples"));
    const QString dir = samplesDir();
    const QStringList patterns{QStringLiteral("*.knot"), QStringLiteral("*.igs"),
                               QStringLiteral("*.iges"), QStringLiteral("*.stp"),
                               QStringLiteral("*.step"), QStringLiteral("*.brep")};
    // Projects first, then the CAD parts (imported), each group by name.
    QFileInfoList files = QDir(dir).entryInfoList(patterns, QDir::Files, QDir::Name);
    std::stable_partition(files.begin(), files.end(), [](const QFileInfo& f) {
        return cadFormatFromPath(f.fileName()) == CadFormat::Knot;
    });
    for (const QFileInfo& f : files) {
        QAction* a = menu->addAction(f.fileName(), this, [this, path = f.absoluteFilePath()] {
            (void)openSample(path); // a failure is shown there
        });
        a->setObjectName(QStringLiteral("actionSample_") + f.completeBaseName());
    }
    if (files.isEmpty()) {
        menu->addAction(dir.isEmpty() ? tr("(no share/knotwork folder next to the program)")
                                      : tr("(no samples in %1)").arg(dir))
            ->setEnabled(false);
    }
}

Status MainWindow::openSample(const QString& path) {
    if (!maybeSave()) // the user's own answer: nothing to show
        return Error(
            tr("%1 was not opened: the unsaved changes were kept").arg(QFileInfo(path).fileName()),
            path);
    // A CAD part is imported as File ▸ Import does (no .knot path; Save asks where).
    if (cadFormatFromPath(path) != CadFormat::Knot)
        return importFile(path);
    Expected<Scene> scene = readKnotFile(path);
    const Status reset = scene ? m_doc->resetScene(std::move(*scene)) : Status(scene.error());
    if (!reset)
        return showError(tr("Cannot open sample"), reset.error());
    m_stack->clear();
    m_stack->setClean();
    // A copy to start from, not the file: the installed samples are read-only, so Save asks
    // where (as after an import), and the sample stays out of the recent files.
    setFilePath(QString());
    m_importedPath = path;
    updateTitle();
    m_desktop->applyDisplay(m_doc->scene().display);
    if (!m_doc->scene().surfaces.empty())
        selectSurface(m_doc->scene().surfaces.front().id);
    statusBar()->showMessage(tr("Opened the sample %1").arg(QFileInfo(path).fileName()), 5000);
    return ok();
}

} // namespace kw
