// Helpers for the editor GUI tests: a main window with scripted dialogs, sample paths and
// widget-event shortcuts.
#pragma once

#include "image_test_util.h"
#include "ui/mainwindow.h"
#include "ui/viewport.h"

#include <QApplication>
#include <QImage>
#include <QTest>
#include <QUndoStack>
#include <memory>

namespace kwtest {

inline QString samplePath(const char* name) {
    return QStringLiteral(KW_SAMPLES_DIR "/") + QLatin1String(name) + QStringLiteral(".knot");
}

/// What the scripted dialogs answered and were told.
struct DialogScript {
    QString openPath;
    QString savePath;
    QMessageBox::StandardButton askAnswer = QMessageBox::Discard;
    QStringList errors;
    int opens = 0;
    int asks = 0;
};

inline void scriptDialogs(kw::MainWindow& w, DialogScript& s) {
    kw::MainWindow::Dialogs d;
    d.openFile = [&s](QWidget*, const QString&, const QString&) {
        ++s.opens;
        return s.openPath;
    };
    d.saveFile = [&s](QWidget*, const QString&, const QString&, const QString&) {
        return s.savePath;
    };
    d.error = [&s](QWidget*, const QString&, const QString& text) {
        s.errors << text;
    };
    d.askSave = [&s](QWidget*, const QString&) {
        ++s.asks;
        return s.askAnswer;
    };
    w.setDialogs(std::move(d));
}

/// Base of the editor GUI test classes: a fresh main window per test with scripted dialogs.
/// Derived classes declare Q_OBJECT and their own slots (call closeWindow() from cleanup()).
class EditorTestBase : public QObject {
protected:
    std::unique_ptr<kw::MainWindow> m_window;
    DialogScript m_script;

    /// Opens a fresh window of `size`, on `sample` when given, shows it and waits for its
    /// first frame; fails the test when the 3D view reports a GL error.
    void openWindow(const char* sample = nullptr, QSize size = QSize(960, 640)) {
        m_window = std::make_unique<kw::MainWindow>();
        scriptDialogs(*m_window, m_script);
        m_window->resize(size);
        m_window->show();
        QVERIFY(QTest::qWaitForWindowExposed(m_window.get()));
        if (sample)
            QVERIFY(m_window->openFile(samplePath(sample)));
        QTest::qWait(50);
        QVERIFY2(m_window->viewport()->glError(),
                 qPrintable(m_window->viewport()->glError().message()));
    }
    /// Closes the window without the unsaved-changes question and forgets the script.
    void closeWindow() {
        if (m_window) {
            m_window->undoStack()->setClean();
            m_window->close();
        }
        m_window.reset();
        m_script = {};
    }
    /// Makes the window the active one, so that its shortcuts and focus work. Xvfb has no
    /// window manager: the X server grants the focus request, but under load the activation
    /// may not arrive in time, so after a short wait Qt is told directly (what a window
    /// manager's answer would do).
    void activate() {
        m_window->activateWindow();
        if (!QTest::qWaitFor([&] { return m_window->isActiveWindow(); }, 1000))
            QApplication::setActiveWindow(m_window.get());
        QTRY_VERIFY(m_window->isActiveWindow());
    }
    /// Until the view draws no more frames for `quietMs` and its image has all its samples.
    void waitStill(int quietMs = 400) {
        kw::Viewport* vp = m_window->viewport();
        std::int64_t drawn = -1;
        for (int k = 0; k < 100; ++k) {
            if (drawn == vp->framesDrawn() && !vp->lastFrameReport().refining)
                return;
            drawn = vp->framesDrawn();
            QTest::qWait(quietMs);
        }
        QFAIL("the view did not come to rest");
    }
    const kw::Scene& scene() const { return m_window->document()->scene(); }
    /// The window's action by object name (a warning names a missing one).
    QAction* act(const char* name) const {
        QAction* a = m_window->action(QLatin1String(name));
        if (!a)
            qWarning("no action %s", name);
        return a;
    }
};

} // namespace kwtest
