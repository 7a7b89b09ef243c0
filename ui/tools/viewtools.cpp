// The 3D view's tool registry, and the status bar for refused drag steps.
#include "ui/tools/viewtools.h"

#include "ui/viewport.h"

namespace kw {

// One line per tool, in the order a left press is offered to them: X(Name) registers the
// factory `std::unique_ptr<Tool> makeNameTool(Viewport*)` defined in the tool's own file.
#define KW_VIEW_TOOLS(X)                                                                           \
    X(SectionHandle)                                                                               \
    X(WeightDrag)                                                                                  \
    X(SurfaceDrag)                                                                                 \
    X(PointDrag)                                                                                   \
    X(RubberBand)

#define KW_DECLARE_TOOL(name) std::unique_ptr<Tool> make##name##Tool(Viewport* view);
KW_VIEW_TOOLS(KW_DECLARE_TOOL)
#undef KW_DECLARE_TOOL

std::unique_ptr<Tool> makeSurfaceDragTool(Viewport* view) {
    return std::make_unique<SurfaceDragTool>(view);
}

std::vector<std::unique_ptr<Tool>> makeViewTools(Viewport* view) {
    std::vector<std::unique_ptr<Tool>> tools;
#define KW_MAKE_TOOL(name) tools.push_back(make##name##Tool(view));
    KW_VIEW_TOOLS(KW_MAKE_TOOL)
#undef KW_MAKE_TOOL
    return tools;
}

void showRefusals(LiveEdit& live, Viewport* view) {
    QObject::connect(&live, &LiveEdit::refused, view, [view](const QString& why) {
        view->showMessage(QObject::tr("Drag step refused: %1").arg(why));
    });
}

} // namespace kw
