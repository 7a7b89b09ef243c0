// Helpers for the editor GUI tests: a main window with scripted dialogs, sample paths and
// widget-event shortcuts.
#pragma once

#include "ui/mainwindow.h"
#include "ui/viewport.h"

#include <QImage>
#include <QTest>
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

/// Pixels that differ between two same-sized images.
inline int differingPixels(const QImage& a, const QImage& b) {
    if (a.size() != b.size())
        return a.width() * a.height();
    const QImage x = a.convertToFormat(QImage::Format_RGBA8888);
    const QImage y = b.convertToFormat(QImage::Format_RGBA8888);
    int n = 0;
    for (int r = 0; r < x.height(); ++r) {
        const auto* p = reinterpret_cast<const quint32*>(x.constScanLine(r));
        const auto* q = reinterpret_cast<const quint32*>(y.constScanLine(r));
        for (int c = 0; c < x.width(); ++c)
            n += p[c] != q[c];
    }
    return n;
}

} // namespace kwtest
