// Small helpers shared by the edit command sources (not part of the public API).
#pragma once

#include "model/document/document.h"

#include <QString>
#include <cstddef>

namespace kw::edit_detail {

inline QString noDocument() {
    return QStringLiteral("no document");
}

inline const TrimLoop* findLoop(const Surface* s, TrimLoopId id) {
    if (s)
        for (const TrimLoop& l : s->trims)
            if (l.id == id)
                return &l;
    return nullptr;
}

/// The surface with this id, or nullptr (also for a null document).
inline const Surface* surfaceIn(const Document* d, SurfaceId id) {
    return d ? d->surface(id) : nullptr;
}

inline QString noSurface(const Document* d, SurfaceId id) {
    return d ? QStringLiteral("no surface with id %1").arg(id.value) : noDocument();
}

} // namespace kw::edit_detail
