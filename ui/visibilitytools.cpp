// VisibilityTools: hide / show / isolate actions, the tree's context menu and greyed rows.
#include "ui/visibilitytools.h"

#include "ui/edit/modelcommands.h"

#include <QAbstractItemView>
#include <QAction>
#include <QMenu>
#include <QStyledItemDelegate>
#include <QUndoStack>
#include <set>

namespace kw {

namespace {

/// Greys and italicises the rows of hidden surfaces (and the rows below them).
class HiddenRowDelegate : public QStyledItemDelegate {
public:
    HiddenRowDelegate(const Document* doc, QObject* parent)
        : QStyledItemDelegate(parent), m_doc(doc) {}

protected:
    void initStyleOption(QStyleOptionViewItem* option, const QModelIndex& index) const override {
        QStyledItemDelegate::initStyleOption(option, index);
        const QVariant id = index.data(SceneModel::SurfaceIdRole);
        const Surface* s = id.isValid() ? m_doc->surface(id.value<SurfaceId>()) : nullptr;
        if (s && s->hidden) {
            option->font.setItalic(true);
            option->palette.setColor(QPalette::Text,
                                     option->palette.color(QPalette::Disabled, QPalette::Text));
        }
    }

private:
    const Document* m_doc;
};

QString surfaces(int n) {
    return n == 1 ? QObject::tr("surface") : QObject::tr("%1 surfaces").arg(n);
}

} // namespace

VisibilityTools::VisibilityTools(QObject* parent, Document* document, Selection* selection,
                                 QUndoStack* stack)
    : QObject(parent), m_doc(document), m_selection(selection), m_stack(stack) {}

bool VisibilityTools::apply(const std::vector<std::pair<SurfaceId, bool>>& states,
                            const QString& verb, int count) {
    auto c = SetSurfacesHidden::create(m_doc, states, QString());
    if (!c) {
        Q_EMIT message(tr("%1: %2").arg(verb, c.message()));
        return false;
    }
    (*c)->setText(
        QStringLiteral("%1 %2").arg(verb, surfaces(count >= 0 ? count : (*c)->changed())));
    Q_EMIT message((*c)->text());
    pushCommand(m_stack, std::move(*c));
    return true;
}

bool VisibilityTools::hideSelected() {
    const std::vector<SurfaceId> ids = m_selection->selectedSurfaces();
    if (ids.empty()) {
        Q_EMIT message(tr("Select the surfaces to hide."));
        return false;
    }
    std::vector<std::pair<SurfaceId, bool>> states;
    for (SurfaceId id : ids)
        states.emplace_back(id, true);
    if (!apply(states, tr("Hide")))
        return false;
    // What is hidden cannot stay selected: a drag or Delete would act on what is not seen.
    // That includes trim points picked in the UV editor, not only rows and control points.
    m_selection->clear();
    return true;
}

bool VisibilityTools::showSelected() {
    std::vector<std::pair<SurfaceId, bool>> states;
    for (SurfaceId id : m_selection->selectedSurfaces())
        states.emplace_back(id, false);
    if (states.empty()) {
        Q_EMIT message(tr("Select the hidden surfaces to show in the scene tree."));
        return false;
    }
    return apply(states, tr("Show"));
}

bool VisibilityTools::isolateSelected() {
    const std::vector<SurfaceId> ids = m_selection->selectedSurfaces();
    if (ids.empty()) {
        Q_EMIT message(tr("Select the surfaces to isolate."));
        return false;
    }
    const std::set<SurfaceId> keep(ids.begin(), ids.end());
    std::vector<std::pair<SurfaceId, bool>> states;
    for (const Surface& s : m_doc->scene().surfaces)
        states.emplace_back(s.id, !keep.count(s.id));
    return apply(states, tr("Isolate"), int(ids.size()));
}

bool VisibilityTools::showAll() {
    std::vector<std::pair<SurfaceId, bool>> states;
    for (const Surface& s : m_doc->scene().surfaces)
        states.emplace_back(s.id, false);
    return apply(states, tr("Show"));
}

void VisibilityTools::install(QMenu* menu, QAbstractItemView* tree) {
    auto make = [this, menu](const char* name, const QString& text, const QKeySequence& key,
                             bool (VisibilityTools::*slot)()) {
        QAction* a = menu->addAction(text);
        a->setObjectName(QLatin1String(name));
        a->setShortcut(key);
        connect(a, &QAction::triggered, this, [this, slot] { (this->*slot)(); });
        return a;
    };
    const QList<QAction*> actions = {
        make("actionHide", tr("&Hide Selected"), QKeySequence(Qt::Key_H),
             &VisibilityTools::hideSelected),
        make("actionIsolate", tr("&Isolate Selected"), QKeySequence(Qt::SHIFT | Qt::Key_H),
             &VisibilityTools::isolateSelected),
        make("actionShowSelected", tr("Show &Selected"), QKeySequence(),
             &VisibilityTools::showSelected),
        // Not Alt+H: that is the Help menu's mnemonic. Ctrl+Alt+H is Rhino's Show.
        make("actionShowAll", tr("Show &All"), QKeySequence(Qt::CTRL | Qt::ALT | Qt::Key_H),
             &VisibilityTools::showAll)};
    actions.front()->setStatusTip(tr("Hidden surfaces are not drawn or picked; they stay in the "
                                     "document and are saved hidden"));
    tree->setContextMenuPolicy(Qt::ActionsContextMenu);
    tree->addActions(actions);
    tree->setItemDelegate(new HiddenRowDelegate(m_doc, tree));
    // The model reports display changes of no row; repaint the rows when visibility changes.
    connect(m_doc, &Document::surfaceChanged, tree, [tree](SurfaceId, Aspects aspects) {
        if (aspects & Aspect::Display)
            tree->viewport()->update();
    });
}

} // namespace kw
