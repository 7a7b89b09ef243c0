// The 3D view's tool registry and DraggedPoints, the point set the point and surface drags move.
#include "ui/tools/viewtools.h"

#include "ui/viewport.h"

#include <set>

namespace kw {

// One line per tool, in the order a left press is offered to them: X(Name) registers the
// factory `std::unique_ptr<Tool> makeNameTool(Viewport*)` defined in the tool's own file.
#define KW_VIEW_TOOLS(X)                                                                           \
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

void DraggedPoints::add(const ControlPointRef& ref, const glm::dvec3& from) {
    m_refs.push_back(ref);
    m_from.push_back(from);
}

std::vector<SurfaceId> DraggedPoints::surfaces() const {
    std::vector<SurfaceId> ids;
    std::set<SurfaceId> seen;
    for (const ControlPointRef& r : m_refs)
        if (seen.insert(r.surface).second)
            ids.push_back(r.surface);
    return ids;
}

QString DraggedPoints::step(LiveEdit& live, const glm::dmat4& map) const {
    std::vector<glm::dvec3> to;
    to.reserve(m_from.size());
    for (const glm::dvec3& p : m_from)
        to.push_back(glm::dvec3(map * glm::dvec4(p, 1.0)));
    return live.moveControlPoints(m_refs, to);
}

} // namespace kw
