// Autosave: recovery files for unsaved edits, offered again after a crash, and the .bak copy
// kept on each save.
#pragma once

#include "model/document/scene.h"
#include "model/error.h"

#include <QDateTime>
#include <QObject>
#include <QString>
#include <QTimer>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

class QLockFile;
class QUndoStack;

namespace kw {

class Document;

/// QSettings keys, also shown by the Preferences dialog.
/// Seconds between autosaves while the document is modified; 0 turns autosave off. Default 60.
inline const QString kAutosaveIntervalKey = QStringLiteral("autosave/intervalSeconds");
/// Keep one `FILE.bak`, the previous version, on each save. Default true.
inline const QString kKeepBackupKey = QStringLiteral("save/keepBackup");

/// A recovery file left by an editor that did not close normally.
struct Recovery {
    QString scenePath;    ///< the autosaved scene, a plain .knot file
    QString infoPath;     ///< its sidecar (JSON): where the document came from
    QString originalPath; ///< the document's .knot file when autosaved, or empty (Untitled)
    QString importedFrom; ///< the CAD/OBJ file of an unsaved import, or empty
    QDateTime savedAt;
};

/// Writes the open document to a recovery file every kAutosaveIntervalKey seconds while it has
/// unsaved changes (QSaveFile, so a crash mid-write leaves the previous recovery file). The
/// files live in "recovery/" next to the QSettings file and carry this process's id; a lock
/// file held for the session tells a live editor's files from those of one that crashed. The
/// files are deleted when the document becomes clean (saved, or undone to the saved state)
/// and when the Autosave is destroyed (the window closed normally).
class Autosave : public QObject {
    Q_OBJECT
public:
    /// Where the document came from, written next to the scene.
    struct Origin {
        QString path;
        QString importedFrom;
    };
    Autosave(const Document* document, QUndoStack* stack, std::function<Origin()> origin,
             QObject* parent = nullptr);
    ~Autosave() override;

    /// "<folder of the QSettings file>/recovery".
    static QString directory();
    /// Recovery files of editors that are no longer running, newest first. Stale lock files
    /// without a scene are removed on the way.
    static std::vector<Recovery> orphans();
    /// Reads a recovery's scene; an Error naming the file when it cannot be read.
    static Expected<Scene> load(const Recovery& recovery);
    /// Deletes a recovery's files.
    static void discard(const Recovery& recovery);

    /// This session's recovery file (it exists only while there are unsaved changes).
    QString scenePath() const;
    /// Writes the recovery file now; an Error naming the file on failure.
    Status writeNow();
    /// Deletes this session's recovery files.
    void discardOwn();

Q_SIGNALS:
    void written(const QString& path);
    void failed(const QString& message);

private:
    void documentChanged();

    const Document* m_doc;
    QUndoStack* m_stack;
    std::function<Origin()> m_origin;
    QString m_base; ///< directory()/session-<pid>, without suffix
    std::unique_ptr<QLockFile> m_lock;
    QTimer m_timer;
};

/// Keeps the current file at `path` as `path + ".bak"` (one generation: the older .bak is
/// replaced), copied through QSaveFile so a failed copy leaves the older .bak whole. True when
/// there is no file at `path`; an Error naming the file when the copy fails.
Status keepBackup(const QString& path);

} // namespace kw
