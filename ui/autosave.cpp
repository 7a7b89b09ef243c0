// Autosave: recovery files for unsaved edits and .bak copies on save.
#include "ui/autosave.h"

#include "model/document/document.h"
#include "model/io/knotfile.h"

#include <QCoreApplication>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLockFile>
#include <QSaveFile>
#include <QSettings>
#include <QUndoStack>
#include <algorithm>
#include <cerrno>

namespace kw {

namespace {

const QString kSceneSuffix = QStringLiteral(".knot");
const QString kInfoSuffix = QStringLiteral(".json");
const QString kLockSuffix = QStringLiteral(".lock");

/// QSaveFile with the explicit flush check that Qt 6.4's commit() lacks (a failed final flush
/// would otherwise replace the old file with a truncated one).
Status writeAtomically(const QString& path, const QByteArray& bytes) {
    QSaveFile file(path);
    QString why;
    errno = 0;
    if (!file.open(QIODevice::WriteOnly))
        why = file.errorString();
    else if (file.write(bytes) != bytes.size() || !file.flush())
        why = errno ? qt_error_string(errno) : QStringLiteral("incomplete write");
    else if (!file.commit())
        why = file.errorString();
    if (why.isEmpty())
        return ok();
    file.cancelWriting();
    return Error(QStringLiteral("%1: cannot write: %2").arg(path, why), path);
}

/// A lock file whose owner has ended can be taken; one held by a live editor cannot.
/// staleLockTime 0: age alone never makes a live editor's lock stale.
bool ownerGone(const QString& lockPath) {
    if (!QFileInfo::exists(lockPath))
        return true;
    QLockFile lock(lockPath);
    lock.setStaleLockTime(0);
    if (!lock.tryLock(0))
        return false;
    lock.unlock(); // removes the stale file
    return true;
}

} // namespace

Autosave::Autosave(const Document* document, QUndoStack* stack, std::function<Origin()> origin,
                   QObject* parent)
    : QObject(parent), m_doc(document), m_stack(stack), m_origin(std::move(origin)) {
    m_base = directory() + QStringLiteral("/session-%1").arg(QCoreApplication::applicationPid());
    if (QDir().mkpath(directory())) {
        m_lock = std::make_unique<QLockFile>(m_base + kLockSuffix);
        m_lock->setStaleLockTime(0);
        if (!m_lock->tryLock(0)) // the id of a dead process reused: its files are orphans then
            m_lock.reset();
    }
    m_timer.setSingleShot(true);
    connect(&m_timer, &QTimer::timeout, this, [this] {
        if (m_stack->isClean())
            return;
        if (const Status saved = writeNow())
            Q_EMIT written(scenePath());
        else
            Q_EMIT failed(saved.message());
    });
    // Every edit, undo and redo moves the index; an import or a recovery leaves the clean state.
    connect(m_stack, &QUndoStack::indexChanged, this, &Autosave::documentChanged);
    connect(m_stack, &QUndoStack::cleanChanged, this, &Autosave::documentChanged);
}

Autosave::~Autosave() {
    discardOwn();
}

QString Autosave::directory() {
    return QFileInfo(QSettings().fileName()).absolutePath() + QStringLiteral("/recovery");
}

QString Autosave::scenePath() const {
    return m_base + kSceneSuffix;
}

// The first change after a write arms the timer; later changes wait for it, so a busy editing
// session writes at most once per interval. The interval is read when arming, so a change in
// Preferences applies from the next edit on.
void Autosave::documentChanged() {
    if (m_stack->isClean()) {
        m_timer.stop();
        discardOwn();
        return;
    }
    const int seconds = QSettings().value(kAutosaveIntervalKey, 60).toInt();
    if (seconds <= 0) {
        m_timer.stop();
        return;
    }
    if (!m_timer.isActive())
        m_timer.start(std::chrono::seconds(seconds));
}

Status Autosave::writeNow() {
    if (!QDir().mkpath(directory()))
        return Error(QStringLiteral("%1: cannot create the folder").arg(directory()), directory());
    const Origin origin = m_origin ? m_origin() : Origin{};
    QJsonObject info;
    info.insert(QStringLiteral("format"), QStringLiteral("knotwork-recovery"));
    info.insert(QStringLiteral("originalPath"), origin.path);
    info.insert(QStringLiteral("importedFrom"), origin.importedFrom);
    info.insert(QStringLiteral("savedAt"),
                QDateTime::currentDateTimeUtc().toString(Qt::ISODateWithMs));
    // The scene first: an info file never describes a scene that is not there yet.
    if (Status written = writeKnotFile(scenePath(), m_doc->scene()); !written)
        return written;
    return writeAtomically(m_base + kInfoSuffix, QJsonDocument(info).toJson());
}

void Autosave::discardOwn() {
    QFile::remove(m_base + kSceneSuffix);
    QFile::remove(m_base + kInfoSuffix);
}

std::vector<Recovery> Autosave::orphans() {
    std::vector<Recovery> out;
    const QDir dir(directory());
    for (const QFileInfo& lock :
         dir.entryInfoList({QStringLiteral("session-*") + kLockSuffix}, QDir::Files))
        if (!QFileInfo::exists(dir.filePath(lock.completeBaseName() + kSceneSuffix)))
            ownerGone(lock.filePath());
    for (const QFileInfo& scene :
         dir.entryInfoList({QStringLiteral("session-*") + kSceneSuffix}, QDir::Files)) {
        const QString base = dir.filePath(scene.completeBaseName());
        if (!ownerGone(base + kLockSuffix))
            continue; // a running editor's
        Recovery r;
        r.scenePath = scene.filePath();
        r.infoPath = base + kInfoSuffix;
        r.savedAt = scene.lastModified();
        QFile f(r.infoPath);
        if (f.open(QIODevice::ReadOnly)) {
            const QJsonObject info = QJsonDocument::fromJson(f.read(1 << 20)).object();
            r.originalPath = info.value(QStringLiteral("originalPath")).toString();
            r.importedFrom = info.value(QStringLiteral("importedFrom")).toString();
            const QDateTime at = QDateTime::fromString(
                info.value(QStringLiteral("savedAt")).toString(), Qt::ISODateWithMs);
            if (at.isValid())
                r.savedAt = at;
        }
        out.push_back(r);
    }
    std::sort(out.begin(), out.end(),
              [](const Recovery& a, const Recovery& b) { return a.savedAt > b.savedAt; });
    return out;
}

Expected<Scene> Autosave::load(const Recovery& recovery) {
    return readKnotFile(recovery.scenePath);
}

void Autosave::discard(const Recovery& recovery) {
    QFile::remove(recovery.scenePath);
    QFile::remove(recovery.infoPath);
}

Status keepBackup(const QString& path) {
    QFile source(path);
    if (!source.exists())
        return ok();
    const QString target = path + QStringLiteral(".bak");
    const auto fail = [](const QString& why) -> Status {
        return Error(why);
    };
    if (!source.open(QIODevice::ReadOnly))
        return fail(QStringLiteral("%1: cannot read: %2").arg(path, source.errorString()));
    QSaveFile copy(target);
    if (!copy.open(QIODevice::WriteOnly))
        return fail(QStringLiteral("%1: cannot write: %2").arg(target, copy.errorString()));
    // In pieces: a project file may be large.
    errno = 0;
    while (!source.atEnd()) {
        const QByteArray chunk = source.read(1 << 20);
        if (chunk.isEmpty() && source.error() != QFileDevice::NoError) {
            copy.cancelWriting();
            return fail(QStringLiteral("%1: cannot read: %2").arg(path, source.errorString()));
        }
        if (copy.write(chunk) != chunk.size()) {
            copy.cancelWriting();
            return fail(QStringLiteral("%1: cannot write: %2").arg(target, copy.errorString()));
        }
    }
    if (!copy.flush() || !copy.commit()) {
        const QString why = errno ? qt_error_string(errno) : copy.errorString();
        copy.cancelWriting();
        return fail(QStringLiteral("%1: cannot write: %2").arg(target, why));
    }
    return ok();
}

} // namespace kw
