// Modeling commands: affine placement of surfaces, hiding, knot removal and trim loop
// replacement.
#include "ui/edit/modelcommands.h"

#include "model/analysis/continuity.h"
#include "model/document/validation.h"
#include "model/nurbs/nurbs_construct.h"
#include "ui/edit/commandsupport.h"

#include <cmath>
#include <numeric>
#include <set>

namespace kw {

using namespace edit_detail;

// ---- TransformSurfaces

Expected<std::unique_ptr<TransformSurfaces>>
TransformSurfaces::create(Document* document, std::vector<SurfaceId> surfaces,
                          const glm::dmat4& transform, const QString& text) {
    if (!document)
        return Error(noDocument());
    if (surfaces.empty())
        return Error(QStringLiteral("select a surface to transform"));
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(transform[c][r]))
                return Error(QStringLiteral("the transformation is not finite"));
    if (transform[0][3] != 0.0 || transform[1][3] != 0.0 || transform[2][3] != 0.0 ||
        transform[3][3] != 1.0)
        return Error(QStringLiteral("the transformation is not affine"));
    std::set<SurfaceId> seen;
    std::unique_ptr<TransformSurfaces> c(new TransformSurfaces(document, text));
    bool moves = false;
    for (SurfaceId id : surfaces) {
        const Surface* s = document->surface(id);
        if (!s)
            return Error(noSurface(document, id));
        if (!seen.insert(id).second)
            return Error(QStringLiteral("surface %1 listed twice").arg(id.value));
        std::vector<glm::dvec3> to;
        to.reserve(s->geometry.points.size());
        for (const glm::dvec3& p : s->geometry.points) {
            const glm::dvec3 q = glm::dvec3(transform * glm::dvec4(p, 1.0));
            if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
                return Error(QStringLiteral("a transformed point is not finite"));
            to.push_back(q);
        }
        moves = moves || to != s->geometry.points;
        c->m_surfaces.push_back(id);
        c->m_from.push_back(s->geometry.points);
        c->m_to.push_back(std::move(to));
    }
    if (!moves)
        return Error(QStringLiteral("the transformation moves nothing"));
    return c;
}

void TransformSurfaces::apply(bool forward, const char* what) {
    // A placement, not a point edit: analytic forms follow a similarity (and only here is one
    // fitted).
    for (size_t k = 0; k < m_surfaces.size(); ++k)
        check(document()->placeControlPoints(m_surfaces[k], forward ? m_to[k] : m_from[k]), what);
}

void TransformSurfaces::redo() {
    apply(true, "redo");
}
void TransformSurfaces::undo() {
    apply(false, "undo");
}

// ---- SetUnits

Expected<std::unique_ptr<SetUnits>> SetUnits::create(Document* document, LengthUnit unit,
                                                     bool convert) {
    if (!document)
        return Error(noDocument());
    const LengthUnit from = document->scene().unit;
    const double factor = convert ? millimetresPer(from) / millimetresPer(unit) : 1.0;
    std::unique_ptr<SetUnits> c(
        new SetUnits(document, convert ? QObject::tr("Convert to %1").arg(lengthUnitKey(unit))
                                       : QObject::tr("Set unit to %1").arg(lengthUnitKey(unit))));
    c->m_from = document->lengths();
    c->m_to = Document::scaledLengths(c->m_from, unit, factor);
    if (c->m_to == c->m_from)
        return Error(QStringLiteral("the document is already in %1").arg(lengthUnitKey(unit)));
    for (const glm::dvec3& p : c->m_to.points)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return Error(QStringLiteral("a converted control point is not finite"));
    return c;
}

void SetUnits::redo() {
    check(document()->setLengths(m_to), "redo");
}
void SetUnits::undo() {
    check(document()->setLengths(m_from), "undo");
}

// ---- SetContinuityTolerances

Expected<std::unique_ptr<SetContinuityTolerances>>
SetContinuityTolerances::create(Document* document, const ContinuityTolerances& to) {
    if (!document)
        return Error(noDocument());
    if (const QString why = checkContinuityTolerances(to).message(); !why.isEmpty())
        return Error(why);
    if (document->scene().continuity == to)
        return Error(QStringLiteral("the continuity tolerances are already these"));
    std::unique_ptr<SetContinuityTolerances> c(
        new SetContinuityTolerances(document, QObject::tr("Set continuity tolerances")));
    c->m_from = document->scene().continuity;
    c->m_to = to;
    return c;
}

void SetContinuityTolerances::redo() {
    check(document()->setContinuityTolerances(m_to), "redo");
}
void SetContinuityTolerances::undo() {
    check(document()->setContinuityTolerances(m_from), "undo");
}

// ---- SetSurfacesHidden

Expected<std::unique_ptr<SetSurfacesHidden>>
SetSurfacesHidden::create(Document* document, const std::vector<std::pair<SurfaceId, bool>>& states,
                          const QString& text) {
    if (!document)
        return Error(noDocument());
    std::set<SurfaceId> seen;
    std::unique_ptr<SetSurfacesHidden> c(new SetSurfacesHidden(document, text));
    for (const auto& [id, hidden] : states) {
        const Surface* s = document->surface(id);
        if (!s)
            return Error(noSurface(document, id));
        if (!seen.insert(id).second)
            return Error(QStringLiteral("surface %1 listed twice").arg(id.value));
        if (s->hidden == hidden)
            continue;
        c->m_ids.push_back(id);
        c->m_to.push_back(hidden);
    }
    if (c->m_ids.empty())
        return Error(QStringLiteral("nothing to hide or show"));
    return c;
}

void SetSurfacesHidden::apply(bool forward, const char* what) {
    for (size_t k = 0; k < m_ids.size(); ++k)
        check(document()->setHidden(m_ids[k], forward ? m_to[k] : !m_to[k]), what);
}

void SetSurfacesHidden::redo() {
    apply(true, "redo");
}
void SetSurfacesHidden::undo() {
    apply(false, "undo");
}

// ---- RemoveKnots

Expected<std::unique_ptr<MatchSurfaceCommand>>
MatchSurfaceCommand::create(Document* document, const MatchRequest& request,
                            const ContinuityTolerances& tolerances) {
    const Surface* s = surfaceIn(document, request.surface);
    if (!s)
        return Error(noSurface(document, request.surface));
    Expected<MatchResult> r = matchSurface(document->scene(), request, tolerances);
    if (!r)
        return Error(r.message());
    static const char* const names[] = {"G0", "G1", "G2"};
    const QString text =
        QStringLiteral("Match surface (%1)").arg(QLatin1String(names[int(request.continuity)]));
    std::unique_ptr<MatchSurfaceCommand> c(
        new MatchSurfaceCommand(document, text, request.surface, s->geometry, r->geometry));
    c->m_result = std::move(*r);
    return c;
}

Expected<std::unique_ptr<RemoveKnots>> RemoveKnots::create(Document* document, SurfaceId surface,
                                                           Direction direction, double tolerance) {
    const Surface* s = surfaceIn(document, surface);
    if (!s)
        return Error(noSurface(document, surface));
    if (!(tolerance >= 0.0) || !std::isfinite(tolerance))
        return Error(QStringLiteral("the tolerance must be a finite number >= 0"));
    int removed = 0;
    NurbsSurface g =
        surfaceRemoveKnots(s->geometry, direction == Direction::U, tolerance, &removed);
    const char axis = direction == Direction::U ? 'u' : 'v';
    if (removed == 0)
        return Error(QStringLiteral("no knot in %1 can be removed within %2")
                         .arg(QLatin1Char(axis))
                         .arg(tolerance));
    const QString text = QStringLiteral("Remove %1 knot%2 in %3")
                             .arg(removed)
                             .arg(removed == 1 ? QString() : QStringLiteral("s"))
                             .arg(QLatin1Char(axis));
    std::unique_ptr<RemoveKnots> c(
        new RemoveKnots(document, text, surface, s->geometry, std::move(g)));
    c->m_removed = removed;
    return c;
}

// ---- ReplaceTrimLoop

Expected<std::unique_ptr<ReplaceTrimLoop>>
ReplaceTrimLoop::create(Document* document, SurfaceId surface, TrimLoop loop, const QString& text) {
    const Surface* s = surfaceIn(document, surface);
    if (!s)
        return Error(noSurface(document, surface));
    const TrimLoop* old = findLoop(s, loop.id);
    if (!old)
        return Error(
            QStringLiteral("surface %1 has no trim loop %2").arg(surface.value).arg(loop.id.value));
    if (Status valid = checkTrimLoop(loop); !valid)
        return std::move(valid).error();
    if (loop == *old)
        return Error(QStringLiteral("the trim loop is unchanged"));
    std::unique_ptr<ReplaceTrimLoop> c(new ReplaceTrimLoop(document, text));
    c->m_surface = surface;
    c->m_from = *old;
    c->m_to = std::move(loop);
    c->m_index = int(old - s->trims.data());
    return c;
}

void ReplaceTrimLoop::redo() {
    Status done = document()->removeTrimLoop(m_surface, m_from.id);
    if (done)
        done = document()->insertTrimLoop(m_surface, m_index, m_to);
    check(done, "redo");
}
void ReplaceTrimLoop::undo() {
    Status done = document()->removeTrimLoop(m_surface, m_to.id);
    if (done)
        done = document()->insertTrimLoop(m_surface, m_index, m_from);
    check(done, "undo");
}

} // namespace kw
