// VisibilityTools: View ▸ Hide / Show / Isolate / Show All and the scene tree's context menu.
// Hiding is a document edit (Surface::hidden): one undo step, saved in the project, as Hide is
// in Rhino and Blender; the renderer leaves hidden surfaces out of frames and picks.
#pragma once

#include "model/document/selection.h"

#include <QObject>
#include <vector>

class QAbstractItemView;
class QMenu;
class QUndoStack;

namespace kw {

class VisibilityTools : public QObject {
    Q_OBJECT
public:
    /// All pointers must outlive the tools (`parent` owns them and their actions).
    VisibilityTools(QObject* parent, Document* document, Selection* selection, QUndoStack* stack);

    /// Adds the actions to `menu` (H, Shift+H, Ctrl+Alt+H) and as the context menu of `tree`;
    /// hidden rows of the tree are drawn greyed and in italics.
    void install(QMenu* menu, QAbstractItemView* tree);

    // One undo step each; false with message() when nothing changes.
    /// Hides the selected surfaces and clears the selection, trim points included ("Hide 2
    /// surfaces").
    bool hideSelected();
    /// Shows the selected surfaces (hidden ones can be selected in the tree).
    bool showSelected();
    /// Hides every surface that is not selected and shows the selected ones.
    bool isolateSelected();
    bool showAll();

Q_SIGNALS:
    void message(const QString& text);

private:
    /// Pushes one SetSurfacesHidden step named "<verb> N surfaces", N the surfaces it changes
    /// or `count` when given.
    bool apply(const std::vector<std::pair<SurfaceId, bool>>& states, const QString& verb,
               int count = -1);

    Document* m_doc;
    Selection* m_selection;
    QUndoStack* m_stack;
};

} // namespace kw
