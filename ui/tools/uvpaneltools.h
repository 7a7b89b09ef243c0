// The UV panel's tools: the trim point drag (registered, offered every left press) and the
// drawing tools installed by the panel's tool buttons.
#pragma once

#include "ui/tools/tool.h"
#include "ui/uvpanel.h"

#include <memory>

namespace kw {

/// Picks the nearest trim control point and drags it with the curve ends that coincide with it
/// (so the loop stays closed); a press away from every point unpicks. One undo step per drag.
std::unique_ptr<Tool> makeTrimDragTool(UvPanel* panel);
/// Rectangle (corner to corner) or Circle (centre to radius, exact rational) by a drag.
std::unique_ptr<Tool> makeUvShapeTool(UvPanel* panel, UvTool shape);
/// Polygon or Spline by clicks, ended by a double click or Enter; Backspace drops the last
/// point, Esc drops them all.
std::unique_ptr<Tool> makeUvClickTool(UvPanel* panel, UvTool shape);

} // namespace kw
