// The document's rules for inserting a surface or a trim loop and for naming a surface, as
// check forms: Document's mutators apply them (document.cpp) and the undo commands ask them
// before they build a step (ui/edit), so both refuse the same edits with the same reason.
#pragma once

#include "model/document/scene.h"
#include "model/error.h"

#include <QString>

namespace kw {

/// Whether `surface` may be inserted at `index` (0..size) of `scene`'s surfaces, as
/// Document::insertSurface: the index in range, the surface valid (kw::checkSurface), its id
/// and its loops' ids valid, unused in the scene and not the largest id (no room left after
/// it), and the scene below kMaxSurfaces. ok(), or the reason in Document's words.
Status checkInsertSurface(const Scene& scene, int index, const Surface& surface);
/// Whether `loop` may be inserted at `index` (0..count) of `target`'s trims in `scene`, as
/// Document::insertTrimLoop: the index in range, the loop valid (kw::checkTrimLoop), its id
/// unused in the scene and not the largest id, and `target` below kMaxTrimLoops loops.
Status checkInsertTrimLoop(const Scene& scene, const Surface& target, int index,
                           const TrimLoop& loop);
/// A surface name needs a visible character (Document::setName).
Status checkSurfaceName(const QString& name);

} // namespace kw
