// SignalLog: records every Document signal as text, in order, for exact-sequence assertions.
#pragma once

#include "model/document/document.h"

#include <QStringList>

namespace kw::test {

inline QString aspectsText(Aspects a) {
    QStringList parts;
    if (a & Aspect::Points)
        parts << QStringLiteral("Points");
    if (a & Aspect::Knots)
        parts << QStringLiteral("Knots");
    if (a & Aspect::Trims)
        parts << QStringLiteral("Trims");
    if (a & Aspect::Display)
        parts << QStringLiteral("Display");
    if (a & Aspect::Name)
        parts << QStringLiteral("Name");
    return parts.join(QLatin1Char('|'));
}

/// Entries look like "inserted 5 @0", "changed 5 Points|Knots", "lights".
class SignalLog : public QObject {
public:
    explicit SignalLog(const Document* d) {
        auto add = [this](const QString& s) {
            entries << s;
        };
        connect(d, &Document::sceneAboutToBeReset, this, [=] { add("aboutToReset"); });
        connect(d, &Document::sceneReset, this, [=] { add("reset"); });
        connect(d, &Document::surfaceAboutToBeInserted, this,
                [=](int i) { add(QStringLiteral("aboutToInsert @%1").arg(i)); });
        connect(d, &Document::surfaceInserted, this, [=](SurfaceId id, int i) {
            add(QStringLiteral("inserted %1 @%2").arg(id.value).arg(i));
        });
        connect(d, &Document::surfaceAboutToBeRemoved, this, [=](SurfaceId id, int i) {
            add(QStringLiteral("aboutToRemove %1 @%2").arg(id.value).arg(i));
        });
        connect(d, &Document::surfaceRemoved, this,
                [=](SurfaceId id) { add(QStringLiteral("removed %1").arg(id.value)); });
        connect(d, &Document::surfaceChanged, this, [=](SurfaceId id, Aspects a) {
            add(QStringLiteral("changed %1 %2").arg(id.value).arg(aspectsText(a)));
        });
        connect(d, &Document::trimLoopAboutToBeInserted, this, [=](SurfaceId id, int i) {
            add(QStringLiteral("aboutToInsertLoop %1 @%2").arg(id.value).arg(i));
        });
        connect(d, &Document::trimLoopInserted, this, [=](SurfaceId id, int i) {
            add(QStringLiteral("insertedLoop %1 @%2").arg(id.value).arg(i));
        });
        connect(d, &Document::trimLoopAboutToBeRemoved, this, [=](SurfaceId id, int i) {
            add(QStringLiteral("aboutToRemoveLoop %1 @%2").arg(id.value).arg(i));
        });
        connect(d, &Document::trimLoopRemoved, this, [=](SurfaceId id, int i) {
            add(QStringLiteral("removedLoop %1 @%2").arg(id.value).arg(i));
        });
        connect(d, &Document::lightsChanged, this, [=] { add("lights"); });
        connect(d, &Document::cameraChanged, this, [=] { add("camera"); });
    }
    QStringList take() {
        QStringList out;
        out.swap(entries);
        return out;
    }
    QStringList entries;
};

} // namespace kw::test
