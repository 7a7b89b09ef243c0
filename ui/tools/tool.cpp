// ToolRouter: a view's events to its tools, in one place for the 3D view and the UV panel.
#include "ui/tools/tool.h"

#include <QKeyEvent>
#include <QMouseEvent>

namespace kw {

void ToolRouter::add(std::unique_ptr<Tool> tool) {
    if (tool)
        m_tools.push_back(std::move(tool));
}

void ToolRouter::install(Tool* tool) {
    if (m_active && m_active == m_installed && tool != m_installed)
        cancel();
    m_installed = tool;
}

void ToolRouter::settle() {
    if (m_active && !m_active->dragging())
        m_active = nullptr;
}

bool ToolRouter::press(QMouseEvent* event, bool toInstalled) {
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

bool ToolRouter::move(QMouseEvent* event) {
    if (m_active) {
        m_active->move(event);
        settle();
        return true;
    }
    if (m_installed)
        m_installed->hover(event);
    return false;
}

bool ToolRouter::release(QMouseEvent* event) {
    if (!m_active)
        return false;
    m_active->release(event);
    settle();
    return true;
}

bool ToolRouter::doubleClick(QMouseEvent* event) {
    Tool* t = m_active ? m_active : m_installed;
    return t && t->doubleClick(event);
}

bool ToolRouter::key(QKeyEvent* event) {
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

bool ToolRouter::keyRelease(QKeyEvent* event) {
    Tool* t = m_active ? m_active : m_installed;
    const bool used = t && t->keyRelease(event);
    settle();
    return used;
}

void ToolRouter::cancel() {
    if (Tool* t = m_active) {
        m_active = nullptr;
        t->cancel();
    }
}

void ToolRouter::paint(QPainter& painter) {
    if (m_installed)
        m_installed->paint(painter);
    for (const auto& t : m_tools)
        t->paint(painter);
}

} // namespace kw
