// MainWindow: the editor window — viewport, scene tree, property, lights and UV panels, File /
// Edit / View menus, undo stack, file state, recent files and window layout.
#pragma once

#include "model/document/selection.h"
#include "model/error.h"
#include "ui/cameracontroller.h"

#include <QMainWindow>
#include <QMessageBox>
#include <atomic>
#include <functional>
#include <memory>
#include <optional>

class QLabel;
class QMenu;
class QProgressDialog;
class QThread;
class QTreeView;
class QUndoStack;

namespace kw {

class Autosave;
class DesktopActions;
class LightsPanel;
class ModelingTools;
class PropertyPanel;
class UvPanel;
class Viewport;

/// What an import or export on a worker thread shares with the progress dialog.
struct ExchangeJob {
    std::atomic<int> done{0};
    std::atomic<int> total{0};
    std::atomic<bool> cancel{false};
};

/// The file dialog filter of File ▸ Import…; without OpenCASCADE (`occt` false) the IGES,
/// STEP and BREP entries say they are unavailable.
QString importFileFilter(bool occt);
/// The samples folder, share/knotwork/samples of the running program's prefix (kw::dataDir);
/// empty when there is none.
QString samplesDir();
/// Labels for File ▸ Open Recent: each file's name, followed by as many of its parent folders
/// as it takes to tell it from the other paths ("model.knot — a/b").
QStringList recentLabels(const QStringList& paths);

class MainWindow : public QMainWindow {
    Q_OBJECT
public:
    /// The dialogs the window asks through; tests replace them to run without user input.
    struct Dialogs {
        /// Returns a path, or an empty string when the user cancels.
        std::function<QString(QWidget*, const QString& title, const QString& filter)> openFile;
        std::function<QString(QWidget*, const QString& title, const QString& filter,
                              const QString& suggested)>
            saveFile;
        std::function<void(QWidget*, const QString& title, const QString& text)> error;
        /// Unsaved changes: Save, Discard or Cancel.
        std::function<QMessageBox::StandardButton(QWidget*, const QString& text)> askSave;
        /// File ▸ Import…: returns a path, or an empty string when the user cancels.
        std::function<QString(QWidget*, const QString& title, const QString& filter)> importFile;
        /// The import report (warnings, skipped entities) after a successful import.
        std::function<void(QWidget*, const QString& title, const QString& text)> information;
        /// Called on the UI thread when the import's progress dialog is set up and after each
        /// update of its value (about every 30 ms); tests read it or press its Cancel button.
        /// May be empty.
        std::function<void(QProgressDialog*)> importProgress;
        /// After a crash: offer the autosaved edits. Yes restores them, Discard deletes the
        /// recovery file, anything else keeps it for the next start. May be empty (keep).
        std::function<QMessageBox::StandardButton(QWidget*, const QString& text)> askRecover;
        /// File ▸ Export Image…, after the path: the image size (starting at the view's) and
        /// whether to write the AOV EXR next to it. Empty: the view's size, no AOVs.
        struct ExportOptions {
            QSize size;
            bool aov = false;
        };
        std::function<std::optional<ExportOptions>(QWidget*, const ExportOptions&)> exportOptions;
        /// Edit ▸ Units…: the unit to set, and whether to convert (scale every length so the
        /// part keeps its size) or only relabel the numbers. nullopt when cancelled.
        struct UnitsChoice {
            LengthUnit unit = LengthUnit::Millimetre;
            bool convert = true;
        };
        std::function<std::optional<UnitsChoice>(QWidget*, LengthUnit current)> units;
        static Dialogs standard();
    };

    explicit MainWindow(QWidget* parent = nullptr);
    ~MainWindow() override;

    void setDialogs(Dialogs dialogs) { m_dialogs = std::move(dialogs); }

    // The file actions below show their own failure (status bar and error dialog, through
    // showError) and return it too, for callers that stop on it (the command line).

    /// Opens a .knot file, replacing the document. On failure shows and returns the loader's
    /// Error and keeps the current document. Does not ask about unsaved changes.
    Status openFile(const QString& path);
    /// Imports IGES, STEP, BREP or OBJ (model/cad importFile) on a worker thread behind a
    /// progress dialog whose Cancel stops the import. On success the imported scene replaces
    /// the document, which is then unsaved and has no .knot path (Save asks where), the report's
    /// warnings and skipped entities are shown. On failure shows and returns the importer's
    /// Error; on cancel says why in the status bar and returns that; both keep the current
    /// document. Does not ask about unsaved changes; refused while another exchange runs.
    Status importFile(const QString& path);
    /// File ▸ Open Sample: asks about unsaved changes, then opens the sample `path` (a file of
    /// samplesDir()) as an unsaved copy with no .knot path (Save asks where), or imports a CAD
    /// sample as importFile does. On failure shows and returns the Error; declined (the user
    /// kept the unsaved changes), returns an Error saying so without showing it.
    Status openSample(const QString& path);
    bool isImporting() const { return m_importProgress != nullptr; }
    /// File ▸ Export… (`selectedOnly`: Export Selected…): writes the document, or its selected
    /// surfaces, as STEP or IGES (kw::exportCadFile, in the CAD child process, on a worker thread
    /// behind a progress dialog whose Cancel stops it) or OBJ. The document keeps its path and
    /// its modified state. Open seams and other remarks are shown in a report when done. On
    /// failure shows and returns the Error (nothing is written); on cancel says so in the
    /// status bar and returns that. Refused while another exchange runs.
    Status exportModel(const QString& path, bool selectedOnly = false);
    /// Writes the document to `path` (atomic); on failure shows and returns the Error. A STEP,
    /// IGES or OBJ name is exported instead (exportModel), a BREP name refused: a project is
    /// never written under another format's name.
    Status saveFile(const QString& path);
    /// Offers the recovery files of editors that crashed (Autosave::orphans, newest first)
    /// through Dialogs::askRecover. Restoring replaces the document with the autosaved scene,
    /// remembers its original path (Save writes there) and marks it modified; the restored
    /// edits are autosaved again at once under this session before the old file is deleted.
    /// Returns true when a recovery was restored. Does not ask about unsaved changes.
    bool offerRecovery();
    Autosave* autosave() const { return m_autosave; }
    /// Makes `id` the current surface (tree row and panels).
    void selectSurface(SurfaceId id);

    Document* document() const { return m_doc; }
    /// View > Analysis > Edge Continuity's state (report, bands).
    class EdgeContinuityOverlay* edgeContinuity() const {
        return m_edgeContinuity;
    }
    Selection* selection() const { return m_selection; }
    QUndoStack* undoStack() const { return m_stack; }
    Viewport* viewport() const { return m_viewport; }
    PropertyPanel* propertyPanel() const { return m_properties; }
    LightsPanel* lightsPanel() const { return m_lights; }
    UvPanel* uvPanel() const { return m_uv; }
    ModelingTools* modelingTools() const { return m_tools; }
    DesktopActions* desktopActions() const { return m_desktop; }
    QTreeView* sceneTree() const { return m_tree; }
    QString filePath() const { return m_path; }
    /// The file the unsaved document was imported from, or empty (cleared by Save, Open, New).
    QString importedFrom() const { return m_importedPath; }
    QStringList recentFiles() const;

    /// Actions by object name ("actionOpen", "actionSave", ...), for tests and tools.
    QAction* action(const QString& objectName) const;

protected:
    void closeEvent(QCloseEvent* event) override;
    void showEvent(QShowEvent* event) override;
    void dragEnterEvent(QDragEnterEvent* event) override;
    void dropEvent(QDropEvent* event) override;

private:
    void buildDocks();
    void sizeFirstStart();
    void buildMenus();
    void buildFileMenu();
    void buildEditMenu();
    void buildViewMenu();
    QAction* addAction(QMenu* menu, const QString& name, const QString& text,
                       const QKeySequence& key, std::function<void()> slot);
    void newDocument();
    void openDialog();
    void importDialog();
    void exportDialog(bool selectedOnly);
    /// Runs `worker` behind a window-modal progress dialog showing job.done of job.total, until
    /// it has finished; Cancel sets job.cancel. The bar ends full when `succeeded` says so.
    void runWithProgress(const QString& title, const QString& label, ExchangeJob& job,
                         std::unique_ptr<QThread> worker, const std::function<bool()>& succeeded);
    bool save();
    bool saveAs();
    void exportImage();
    void selectAll();
    void deleteSelection();
    /// Edit ▸ Units…: asks Dialogs::units, then pushes one SetUnits command.
    void unitsDialog();
    /// The status bar's unit label and the Properties' suffixes, after the unit changed.
    void showUnit();
    /// True when it is fine to discard the document (saved, discarded or unmodified).
    bool maybeSave();
    void setFilePath(const QString& path);
    void addRecent(const QString& path);
    void rebuildRecentMenu();
    void addSamplesMenu(QMenu* file);
    void updateTitle();
    /// The document's file name for titles and questions ("Untitled" when it has none).
    QString displayName() const;
    /// The one place a file action's failure is shown: the status bar and the error dialog
    /// titled `title`. Returns `error`, so that a failure is shown where it is returned.
    Error showError(const QString& title, Error error);

    Document* m_doc;
    class EdgeContinuityOverlay* m_edgeContinuity = nullptr;
    SceneModel* m_model;
    Selection* m_selection;
    QUndoStack* m_stack;
    Autosave* m_autosave = nullptr;
    Viewport* m_viewport = nullptr;
    QTreeView* m_tree = nullptr;
    PropertyPanel* m_properties = nullptr;
    LightsPanel* m_lights = nullptr;
    UvPanel* m_uv = nullptr;
    ModelingTools* m_tools = nullptr;
    DesktopActions* m_desktop = nullptr;
    QMenu* m_recentMenu = nullptr;
    QLabel* m_fpsLabel = nullptr;
    QLabel* m_unitLabel = nullptr; ///< the document's length unit, in the status bar
    double m_lastFrameMs = 0.0;
    QString m_path;
    QString m_importedPath;
    bool m_docksSized = false;                   ///< the first show restored or set the docks
    QProgressDialog* m_importProgress = nullptr; ///< while an import runs
    Dialogs m_dialogs;
};

} // namespace kw
