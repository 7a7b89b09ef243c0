// DesktopActions: Preferences, Help (keyboard shortcuts, about) and the View toggles of the
// modeling editor (nets of all surfaces, ground grid, axis indicator, headlight).
#pragma once

#include "model/document/scene.h"
#include "ui/preferences.h"

#include <QObject>

class QAction;
class QUndoStack;

namespace kw {
class SectionDialog;
}
#include <functional>
#include <optional>

class QMainWindow;
class QMenu;
class QMenuBar;

namespace kw {

class Viewport;

class DesktopActions : public QObject {
    Q_OBJECT
public:
    /// Dialogs, replaceable by tests. `preferences` returns the edited values (the preferences
    /// and the open project's continuity tolerances) or nullopt;
    /// `show` presents a page of rich text (shortcuts, about).
    struct Prompts {
        std::function<std::optional<PreferencesEdit>(QWidget*, const PreferencesEdit&,
                                                     bool focusContinuity)>
            preferences;
        std::function<void(QWidget*, const QString& title, const QString& html)> show;
        static Prompts standard();
    };

    /// A change of the project's continuity tolerances is pushed on `stack` (one undo step).
    DesktopActions(QMainWindow* window, Viewport* viewport, QUndoStack* stack);
    void setPrompts(Prompts p) { m_prompts = std::move(p); }

    void addEditEntries(QMenu* edit);
    void addViewEntries(QMenu* view);
    void addHelpMenu(QMenuBar* bar);

    /// Reads the preferences and applies the view ones to the viewport.
    void applyPreferences();
    /// The opened project's display settings (Scene::display) when it has them, else the
    /// preferences; the View menu follows.
    void applyDisplay(const DisplaySettings& display);
    /// What the view shows now, for the project file.
    DisplaySettings currentDisplay() const;
    /// Opens the Preferences dialog; on OK saves and applies the preferences, and sets the
    /// project's continuity tolerances (an undoable edit) when they changed. With
    /// `focusContinuity` the dialog opens on the project's tolerances (View > Analysis >
    /// Continuity Tolerances).
    void editPreferences(bool focusContinuity = false);
    /// View › Section…: the section dialog, modeless, made on first use; it shows and sets
    /// the view's planes.
    void showSections();
    /// Every action of the window with a shortcut, and the mouse gestures, as an HTML table.
    QString shortcutsHtml() const;

private:
    /// The view draws `mode` ("adaptive" or "uniform") within `pixelTolerance`; the View
    /// menu's check follows.
    void showPartitions(const QString& mode, double pixelTolerance);

    QMainWindow* m_window;
    Viewport* m_viewport;
    QUndoStack* m_stack;
    QAction* m_adaptive = nullptr;        ///< View › Adaptive Partitions
    QAction* m_lightBackground = nullptr; ///< View › Light Background
    SectionDialog* m_sections = nullptr;  ///< View › Section…, made when first asked for
    Prompts m_prompts;
};

} // namespace kw
