// Edge ranges against the curves they run along (occtranges.h).
#include "model/cad/occtranges.h"

#include <BRep_Tool.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom_Curve.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <cmath>

namespace kw::occt {
namespace {

QString number(double x) {
    return QString::number(x, 'g', 6);
}

// Empty when [first, last] is a proper range inside [lo, hi] (a relative slack of 1e-9; an
// unbounded side is no bound).
QString rangeFault(const char* curve, double first, double last, bool periodic, double lo,
                   double hi) {
    if (!std::isfinite(first) || !std::isfinite(last) || !(first < last))
        return QStringLiteral("its %1 range [%2, %3] is empty, reversed or not finite")
            .arg(QLatin1String(curve), number(first), number(last));
    if (periodic)
        return {};
    const double slack = 1e-9 * std::max({1.0, std::fabs(first), std::fabs(last)});
    if ((std::isfinite(lo) && first < lo - slack) || (std::isfinite(hi) && last > hi + slack))
        return QStringLiteral("its range [%1, %2] leaves its %3's domain [%4, %5]")
            .arg(number(first), number(last), QLatin1String(curve), number(lo), number(hi));
    return {};
}

} // namespace

Status checkEdgeRanges(const TopoDS_Face& face) {
    int k = 0;
    for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next()) {
        ++k;
        const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
        QString why;
        double first = 0, last = 0;
        if (!BRep_Tool::Degenerated(edge)) {
            TopLoc_Location location;
            const Handle(Geom_Curve) c = BRep_Tool::Curve(edge, location, first, last);
            if (!c.IsNull())
                why = rangeFault("3D curve", first, last, c->IsPeriodic(), c->FirstParameter(),
                                 c->LastParameter());
        }
        if (why.isEmpty()) {
            const Handle(Geom2d_Curve) p = BRep_Tool::CurveOnSurface(edge, face, first, last);
            if (!p.IsNull())
                why = rangeFault("p-curve", first, last, p->IsPeriodic(), p->FirstParameter(),
                                 p->LastParameter());
        }
        if (!why.isEmpty())
            return Error(QStringLiteral("edge %1: %2").arg(k).arg(why));
    }
    return ok();
}

} // namespace kw::occt
