// Tool: one gesture of a view (a drag, a rubber band, a drawing) behind one interface, and
// ToolRouter, which decides which tool gets a view's events and lets them draw (the 3D view and
// the UV panel both use it). A drag's moves go from the host straight to the gesture's tool
// (active()), the hottest path of the editor, read in the host and the tool alone.
#pragma once

#include <QKeyEvent>
#include <QMouseEvent>
#include <algorithm>
#include <memory>
#include <vector>

class QPainter;

namespace kw {

/// A gesture. The host view keeps navigation (orbit, pan, zoom) and routes everything else
/// through a ToolRouter: a press goes to the installed tool, then to the registered ones in
/// order, and the first that takes it owns the gesture (move / release / keys) until it stops
/// dragging(). A tool that edits the document does so through a LiveEdit, so that Esc
/// (cancel()) puts the document back and the release is one undo step.
class Tool {
public:
    virtual ~Tool() = default;
    /// A press the host did not use for navigation; true when the tool took it.
    virtual bool press(QMouseEvent* event) = 0;
    /// A move or release during the tool's own gesture (dragging() after press()).
    virtual void move(QMouseEvent*) {}
    virtual void release(QMouseEvent*) {}
    /// A move with no gesture running (every tool gets it, the installed one first; the
    /// host tracks the mouse). A tool that shows something on hover calls its host's update().
    virtual void hover(QMouseEvent*) {}
    virtual bool doubleClick(QMouseEvent*) { return false; }
    /// Keys while the tool's gesture runs, or for the installed tool; true when used.
    virtual bool key(QKeyEvent*) { return false; }
    virtual bool keyRelease(QKeyEvent*) { return false; }
    /// Esc during the gesture, or the host dropping it: the gesture ends and the document is
    /// as it was at the press.
    virtual void cancel() {}
    /// A press-move-release gesture of this tool is running.
    virtual bool dragging() const { return false; }
    /// A live edit of the document is running (the renderer holds its colour range).
    virtual bool editing() const { return false; }
    /// Draws over the view, in widget pixels: what it draws and nothing else (it may be called
    /// twice a frame, once on a device that only measures, ViewSurface::paintOverlays).
    virtual void paint(QPainter&) {}
    /// A key this tool wants ahead of the window's shortcuts (the host's ShortcutOverride),
    /// such as Ctrl+C over the view copying the tool's values rather than the selection.
    virtual bool overridesShortcut(const QKeyEvent*) const { return false; }
    /// The pointer left the host; the host lost the keyboard focus (a held key's release will
    /// not come).
    virtual void leave() {}
    virtual void focusOut() {}
    /// Another tool (or none) was installed in this one's place.
    virtual void uninstalled() {}
};

/// Routes one host widget's events to its tools: the installed tool (a mode the user picked,
/// such as the curve tool; not owned) first, then the registered tools (owned) in order, then
/// the listening ones (not owned).
class ToolRouter {
public:
    void add(std::unique_ptr<Tool> tool);
    /// A tool the host does not own (a QObject of the window, say) that listens while it is
    /// not installed: it gets hover moves, the keys listenKey offers, the pointer or focus
    /// leaving, and paints; presses only once installed. Such a tool shows what a held key
    /// asks for (the probe under held P) without being the view's mode. It must outlive the
    /// host's events.
    void listen(Tool* tool);
    /// Installs a tool (nullptr removes it), cancelling the gesture of the one it replaces.
    void install(Tool* tool);
    Tool* installed() const { return m_installed; }
    /// The tool whose gesture runs, or nullptr: the host hands it a drag's moves itself
    /// (`if (Tool* t = active()) t->move(event); else hover(event);`).
    Tool* active() const { return m_active && m_active->dragging() ? m_active : nullptr; }
    /// The registered tool of type T, or nullptr.
    template <class T> T* find() const {
        for (const auto& t : m_tools)
            if (auto* found = dynamic_cast<T*>(t.get()))
                return found;
        return nullptr;
    }

    /// A press: to the installed tool when `toInstalled`, then to the registered ones. True
    /// when a tool took it.
    bool press(QMouseEvent* event, bool toInstalled = true);
    /// A move with no gesture running, to every tool.
    void hover(QMouseEvent* event);
    bool release(QMouseEvent* event);
    bool doubleClick(QMouseEvent* event);
    /// Esc cancels a running gesture; other keys go to it, else to the installed tool.
    bool key(QKeyEvent* event);
    bool keyRelease(QKeyEvent* event);
    /// A key (or its release) that no gesture and no installed tool used, offered to the
    /// listening tools (they repaint what they show themselves); true when one used it.
    bool listenKey(QKeyEvent* event);
    bool listenKeyRelease(QKeyEvent* event);
    /// Whether the installed or a listening tool wants `event` ahead of the shortcuts.
    bool overridesShortcut(const QKeyEvent* event) const;
    /// The pointer left the host / the host lost the focus: every tool is told.
    void leave();
    void focusOut();
    /// Cancels the running gesture, if any.
    void cancel();
    /// The installed tool, then the registered ones, then the listeners.
    void paint(QPainter& painter);

private:
    void settle();
    /// Calls f on every tool once: the installed one, the registered ones, the listeners.
    template <class F> void each(F f) const;

    std::vector<std::unique_ptr<Tool>> m_tools;
    std::vector<Tool*> m_listeners;
    Tool* m_installed = nullptr;
    Tool* m_active = nullptr;
};

// ---- ToolRouter

inline void ToolRouter::add(std::unique_ptr<Tool> tool) {
    if (tool)
        m_tools.push_back(std::move(tool));
}

inline void ToolRouter::listen(Tool* tool) {
    if (tool && std::find(m_listeners.begin(), m_listeners.end(), tool) == m_listeners.end())
        m_listeners.push_back(tool);
}

template <class F> void ToolRouter::each(F f) const {
    if (m_installed)
        f(m_installed);
    for (const auto& t : m_tools)
        f(t.get());
    for (Tool* t : m_listeners)
        if (t != m_installed)
            f(t);
}

inline void ToolRouter::install(Tool* tool) {
    if (active() && m_active == m_installed && tool != m_installed)
        cancel();
    Tool* was = m_installed;
    m_installed = tool;
    if (was && was != tool)
        was->uninstalled();
}

inline void ToolRouter::settle() {
    m_active = active();
}

inline bool ToolRouter::press(QMouseEvent* event, bool toInstalled) {
    settle();
    if (m_active)
        return true; // a second button during a gesture: the gesture keeps the mouse
    if (toInstalled && m_installed && m_installed->press(event)) {
        m_active = m_installed;
        settle();
        return true;
    }
    for (const auto& t : m_tools)
        if (t->press(event)) {
            m_active = t.get();
            settle();
            return true;
        }
    return false;
}

inline void ToolRouter::hover(QMouseEvent* event) {
    each([event](Tool* t) { t->hover(event); });
}

inline bool ToolRouter::release(QMouseEvent* event) {
    settle();
    if (!m_active)
        return false;
    m_active->release(event);
    settle();
    return true;
}

inline bool ToolRouter::doubleClick(QMouseEvent* event) {
    settle();
    Tool* t = m_active ? m_active : m_installed;
    return t && t->doubleClick(event);
}

inline bool ToolRouter::key(QKeyEvent* event) {
    settle();
    if (m_active) {
        if (event->key() == Qt::Key_Escape) {
            cancel();
            return true;
        }
        const bool used = m_active->key(event);
        settle();
        return used;
    }
    return m_installed && m_installed->key(event);
}

inline bool ToolRouter::keyRelease(QKeyEvent* event) {
    settle();
    Tool* t = m_active ? m_active : m_installed;
    const bool used = t && t->keyRelease(event);
    settle();
    return used;
}

inline bool ToolRouter::listenKey(QKeyEvent* event) {
    if (active())
        return false;
    for (Tool* t : m_listeners)
        if (t != m_installed && t->key(event))
            return true;
    return false;
}

inline bool ToolRouter::listenKeyRelease(QKeyEvent* event) {
    if (active())
        return false;
    for (Tool* t : m_listeners)
        if (t != m_installed && t->keyRelease(event))
            return true;
    return false;
}

inline bool ToolRouter::overridesShortcut(const QKeyEvent* event) const {
    if (m_installed && m_installed->overridesShortcut(event))
        return true;
    for (Tool* t : m_listeners)
        if (t->overridesShortcut(event))
            return true;
    return false;
}

inline void ToolRouter::leave() {
    each([](Tool* t) { t->leave(); });
}

inline void ToolRouter::focusOut() {
    each([](Tool* t) { t->focusOut(); });
}

inline void ToolRouter::cancel() {
    if (Tool* t = active()) {
        m_active = nullptr;
        t->cancel();
    }
}

inline void ToolRouter::paint(QPainter& painter) {
    each([&painter](Tool* t) { t->paint(painter); });
}

} // namespace kw
