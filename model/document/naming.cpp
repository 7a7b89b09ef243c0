// Surface names made distinct by a per-name index.
#include "model/document/naming.h"

#include <QHash>

namespace kw {

int makeSurfaceNamesDistinct(Scene& scene, const QString& fallback) {
    QHash<QString, int> uses;
    for (const Surface& s : scene.surfaces)
        ++uses[s.name.trimmed()];
    QHash<QString, int> next;
    int renamed = 0;
    for (Surface& s : scene.surfaces) {
        const QString name = s.name.trimmed();
        if (!name.isEmpty() && uses.value(name) == 1)
            continue;
        const QString base = name.isEmpty() ? fallback : name;
        QString candidate;
        do { // skip an index whose name another surface already has
            candidate = QStringLiteral("%1 %2").arg(base).arg(++next[name]);
        } while (uses.contains(candidate));
        s.name = candidate;
        ++renamed;
    }
    return renamed;
}

} // namespace kw
