// Edit commands that change a surface's degrees, knots and net: knot vector edit, knot insertion
// (A5.3) and degree elevation (A5.9), all through Document::setGeometry.
#include "ui/edit/commands.h"
#include "ui/edit/commandsupport.h"

#include <cmath>

namespace kw {

using namespace edit_detail;

namespace {

char axis(Direction d) {
    return d == Direction::U ? 'u' : 'v';
}

} // namespace

GeometryCommand::GeometryCommand(Document* d, const QString& text, SurfaceId surface,
                                 NurbsSurface from, NurbsSurface to)
    : DocumentCommand(d, text), m_surface(surface), m_from(std::move(from)), m_to(std::move(to)) {}

void GeometryCommand::redo() {
    check(document()->setGeometry(m_surface, m_to), "redo");
}
void GeometryCommand::undo() {
    check(document()->setGeometry(m_surface, m_from), "undo");
}

Expected<std::unique_ptr<SetKnotVector>> SetKnotVector::create(Document* document,
                                                               SurfaceId surface,
                                                               Direction direction,
                                                               std::vector<double> knots) {
    const Surface* s = surfaceIn(document, surface);
    if (!s)
        return Error(noSurface(document, surface));
    NurbsSurface g = s->geometry;
    const bool u = direction == Direction::U;
    const Status valid = checkKnotVector(knots, u ? g.degreeU : g.degreeV, u ? g.countU : g.countV);
    if (!valid)
        return Error(
            QStringLiteral("knot vector %1: %2").arg(axis(direction)).arg(valid.message()));
    (u ? g.knotsU : g.knotsV) = std::move(knots);
    if (g == s->geometry)
        return Error(QStringLiteral("knot vector %1 unchanged").arg(axis(direction)));
    const QString text = QStringLiteral("Edit knot vector %1").arg(axis(direction));
    return std::unique_ptr<SetKnotVector>(
        new SetKnotVector(document, text, surface, s->geometry, std::move(g)));
}

Expected<std::unique_ptr<InsertKnot>> InsertKnot::create(Document* document, SurfaceId surface,
                                                         Direction direction, double value,
                                                         int times) {
    const Surface* s = surfaceIn(document, surface);
    if (!s)
        return Error(noSurface(document, surface));
    if (!std::isfinite(value) || times < 1)
        return Error(QStringLiteral("knot value must be finite, times >= 1"));
    const bool u = direction == Direction::U;
    const NurbsSurface& g = s->geometry;
    const Interval dom = u ? surfaceDomainU(g) : surfaceDomainV(g);
    NurbsSurface to = u ? surfaceInsertKnotU(g, value, times) : surfaceInsertKnotV(g, value, times);
    if (to == g)
        return Error(QStringLiteral("cannot insert knot %1 = %2 %3 times: it must lie in "
                                    "(%4, %5) and its multiplicity stay <= the degree %6")
                         .arg(axis(direction))
                         .arg(value)
                         .arg(times)
                         .arg(dom.first)
                         .arg(dom.last)
                         .arg(u ? g.degreeU : g.degreeV));
    QString text = QStringLiteral("Insert knot %1 = %2").arg(axis(direction)).arg(value);
    if (times > 1)
        text += QStringLiteral(" (×%1)").arg(times);
    return std::unique_ptr<InsertKnot>(new InsertKnot(document, text, surface, g, std::move(to)));
}

Expected<std::unique_ptr<ElevateDegree>>
ElevateDegree::create(Document* document, SurfaceId surface, Direction direction, int by) {
    const Surface* s = surfaceIn(document, surface);
    if (!s)
        return Error(noSurface(document, surface));
    const bool u = direction == Direction::U;
    const NurbsSurface& g = s->geometry;
    const int degree = (u ? g.degreeU : g.degreeV);
    if (by < 1 || degree + by > kMaxDegree)
        return Error(QStringLiteral("cannot raise degree %1 from %2 by %3: the maximum "
                                    "is %4")
                         .arg(axis(direction))
                         .arg(degree)
                         .arg(by)
                         .arg(kMaxDegree));
    NurbsSurface to = u ? surfaceElevateDegreeU(g, by) : surfaceElevateDegreeV(g, by);
    if (to == g || !checkNurbsSurface(to))
        return Error(QStringLiteral("degree elevation in %1 failed").arg(axis(direction)));
    const QString text =
        QStringLiteral("Elevate degree %1 to %2").arg(axis(direction)).arg(degree + by);
    return std::unique_ptr<ElevateDegree>(
        new ElevateDegree(document, text, surface, g, std::move(to)));
}

} // namespace kw
