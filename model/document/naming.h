// Surface names: make repeated names distinct (CAD files often name every face alike).
#pragma once

#include "model/document/scene.h"

namespace kw {

/// Renames surfaces whose name is shared with another surface (or empty) to "BASE k", k
/// counting 1.. within each repeated name in document order; BASE is the repeated name, or
/// `fallback` (e.g. the file name) for empty names. Distinct names are kept. Returns how many
/// surfaces were renamed.
int makeSurfaceNamesDistinct(Scene& scene, const QString& fallback);

} // namespace kw
