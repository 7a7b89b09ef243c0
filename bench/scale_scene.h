// The scale table's models (docs/PERFORMANCE.md ## Scale): one real part tiled in a grid.
#pragma once

#include "model/document/scene.h"

namespace kw::bench {

/// `copies` copies of `unit`'s surfaces (trims, partitions and materials kept) laid out in a
/// near-square grid in the plane of unit's two largest extents, each cell the unit's bounds
/// plus a quarter of its largest side as a gap. Surface and trim loop ids are renumbered
/// (unique, nextId above them); lights are unit's; the camera is left unauthored so views fit
/// the whole grid. `copies` >= 1; an empty unit gives an empty scene.
Scene tileScene(const Scene& unit, int copies);

/// Copies needed to reach at least `faces` surfaces with `unitFaces` per copy (>= 1).
int copiesForFaces(int unitFaces, int faces);

/// A camera at `aspect` that frames the first copy of tileScene(unit, n) alone, from close up
/// (the fitted view of unit, moved to that copy): a view whose visible faces do not grow
/// with n.
Camera closeUpCamera(const Scene& unit, double aspect);

} // namespace kw::bench
