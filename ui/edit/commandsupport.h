// Small helpers shared by the edit command sources (not part of the public API).
#pragma once

#include "model/scene.h"

#include <QString>
#include <cstddef>

namespace kw::edit_detail {

/// Sets *error (if given) and yields the nullptr a rejecting factory returns.
inline std::nullptr_t fail(QString* error, const QString& why) {
    if (error)
        *error = why;
    return nullptr;
}

inline const TrimLoop* findLoop(const Surface* s, TrimLoopId id) {
    if (s)
        for (const TrimLoop& l : s->trims)
            if (l.id == id)
                return &l;
    return nullptr;
}

inline QString noSurface(SurfaceId id) {
    return QStringLiteral("no surface with id %1").arg(id.value);
}

} // namespace kw::edit_detail
