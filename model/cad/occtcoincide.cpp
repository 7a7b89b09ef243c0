// Faces that lie on one another (kw::occt::coincidentFaces): the same surface given twice, or a
// face lying on part of another. Neither face is wrong on its own, but where both are drawn
// their depths are equal and either may show, pixel by pixel.
#include "model/cad/occt_internal.h"

#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_Surface.hxx>
#include <QElapsedTimer>
#include <TopExp.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace kw::occt {

namespace {

/// What the test needs of one imported face.
struct FaceProbe {
    int surface = 0; ///< index into the imported scene's surfaces
    Bnd_Box box;     ///< enlarged by the tolerance
    Handle(Geom_Surface) geometry;
    double u0 = 0, u1 = 0, v0 = 0, v1 = 0; ///< the face's (u, v) bounds
    std::unique_ptr<BRepTopAdaptor_FClass2d> inside;
    std::vector<gp_Pnt> samples; ///< points of the face, inside its wires
    double tolerance = 0.0;
    int solid = 0; ///< 1-based index of the solid holding the face, 0 for none
};

/// Up to 9 points inside the face's wires (parametersInside).
void sample(const TopoDS_Face& face, FaceProbe& f) {
    BRepAdaptor_Surface surface(face);
    for (const gp_Pnt2d& p : parametersInside(face, *f.inside, 9))
        f.samples.push_back(surface.Value(p.X(), p.Y()));
}

/// How many of a's samples lie on b (within the tolerance, inside b's wires); stops at the
/// first miss among the first two.
int onFace(const FaceProbe& a, const FaceProbe& b, double tolerance) {
    int hits = 0;
    for (size_t k = 0; k < a.samples.size(); ++k) {
        const gp_Pnt& p = a.samples[k];
        if (b.box.IsOut(p)) {
            if (k < 2)
                return 0;
            continue;
        }
        GeomAPI_ProjectPointOnSurf projection;
        const double du = 1e-6 * (b.u1 - b.u0), dv = 1e-6 * (b.v1 - b.v0);
        projection.Init(p, b.geometry, b.u0 - du, b.u1 + du, b.v0 - dv, b.v1 + dv);
        bool on = false;
        if (projection.NbPoints() > 0 && projection.LowerDistance() <= tolerance) {
            double u = 0.0, v = 0.0;
            projection.LowerDistanceParameters(u, v);
            on = b.inside->Perform(gp_Pnt2d(u, v)) == TopAbs_IN;
        }
        hits += on;
        if (!on && k < 2)
            return 0;
    }
    return hits;
}

} // namespace

QStringList coincidentFaces(const TopoDS_Shape& shape, const TopTools_IndexedMapOfShape& faces,
                            const std::vector<int>& sourceFaces, const QStringList& labels,
                            int maxReported) {
    TopTools_IndexedMapOfShape solids;
    TopExp::MapShapes(shape, TopAbs_SOLID, solids);
    TopTools_IndexedDataMapOfShapeListOfShape solidOf;
    TopExp::MapShapesAndAncestors(shape, TopAbs_FACE, TopAbs_SOLID, solidOf);
    // A file of many faces piled on one another (hostile, or a model of 100 000 faces) would
    // make the pairs too many: the check stops after kBudgetMs and says so.
    constexpr qint64 kBudgetMs = 3000;
    QElapsedTimer clock;
    clock.start();
    bool stopped = false;
    std::vector<FaceProbe> probes;
    Bnd_Box all;
    probes.reserve(sourceFaces.size());
    for (size_t s = 0; s < sourceFaces.size() && !stopped; ++s) {
        stopped = clock.elapsed() > kBudgetMs;
        const TopoDS_Face& face = TopoDS::Face(faces(sourceFaces[s]));
        FaceProbe f;
        f.surface = int(s);
        BRepBndLib::Add(face, f.box, false);
        if (f.box.IsVoid())
            continue;
        all.Add(f.box);
        BRepTools::UVBounds(face, f.u0, f.u1, f.v0, f.v1);
        f.geometry = BRep_Tool::Surface(face);
        if (f.geometry.IsNull())
            continue;
        f.tolerance = BRep_Tool::Tolerance(face);
        if (const TopTools_ListOfShape* owners = solidOf.Seek(face); owners && !owners->IsEmpty())
            f.solid = solids.FindIndex(owners->First());
        f.inside = std::make_unique<BRepTopAdaptor_FClass2d>(face, 1e-9);
        sample(face, f);
        if (!f.samples.empty())
            probes.push_back(std::move(f));
    }
    QStringList found;
    if ((probes.size() < 2 || all.IsVoid()) && !stopped)
        return found;
    // Coincident within the faces' own tolerances, and never closer than a millionth of the
    // model: the depth buffer cannot tell such faces apart either.
    const double modelSize = std::sqrt(all.SquareExtent());
    for (FaceProbe& f : probes)
        f.box.Enlarge(std::max(f.tolerance, 1e-6 * modelSize));
    // Sweep along x: only faces whose boxes overlap are compared.
    std::sort(probes.begin(), probes.end(), [](const FaceProbe& a, const FaceProbe& b) {
        return a.box.CornerMin().X() < b.box.CornerMin().X();
    });
    // Faces of two different solids that coincide are parts of an assembly in contact: said
    // once, with the first pair. Within one solid (or a shell) a face lies on another: each
    // pair is said, up to maxReported.
    const auto face = [&](const FaceProbe& f) {
        return QStringLiteral("face %1 (%2)")
            .arg(sourceFaces[size_t(f.surface)])
            .arg(labels.value(f.surface));
    };
    int duplicates = 0, contacts = 0;
    QString firstContact;
    std::int64_t steps = 0;
    size_t compared = 0; // faces whose pairs with every later face were tested
    for (size_t i = 0; i < probes.size() && !stopped; ++i, compared = i) {
        const double xMax = probes[i].box.CornerMax().X();
        for (size_t j = i + 1; j < probes.size() && probes[j].box.CornerMin().X() <= xMax; ++j) {
            if ((++steps & 255) == 0 && clock.elapsed() > kBudgetMs) {
                stopped = true;
                break;
            }
            const FaceProbe &a = probes[i], &b = probes[j];
            if (a.box.IsOut(b.box))
                continue;
            const double tolerance = std::max({a.tolerance, b.tolerance, 1e-6 * modelSize});
            // Either may lie on part of the other.
            const FaceProbe* on = &a;
            const FaceProbe* under = &b;
            int hits = onFace(a, b, tolerance);
            if (2 * hits < int(a.samples.size()) + 1) {
                on = &b;
                under = &a;
                hits = onFace(b, a, tolerance);
            }
            if (2 * hits < int(on->samples.size()) + 1)
                continue;
            const FaceProbe& first = a.surface < b.surface ? a : b;
            const FaceProbe& second = a.surface < b.surface ? b : a;
            if (a.solid != 0 && b.solid != 0 && a.solid != b.solid) {
                if (contacts++ == 0)
                    firstContact = QStringLiteral("%1 of solid %2 and %3 of solid %4")
                                       .arg(face(first))
                                       .arg(first.solid)
                                       .arg(face(second))
                                       .arg(second.solid);
                continue;
            }
            if (duplicates++ >= maxReported)
                continue;
            found << QStringLiteral("%1 and %2 coincide: %3 of %4 points inside face %5 lie on "
                                    "face %6 (within %7), a face given twice or lying on "
                                    "another; where both are drawn either may show")
                         .arg(face(first), face(second))
                         .arg(hits)
                         .arg(on->samples.size())
                         .arg(sourceFaces[size_t(on->surface)])
                         .arg(sourceFaces[size_t(under->surface)])
                         .arg(tolerance, 0, 'g', 2);
        }
    }
    if (stopped)
        found << QStringLiteral("the check for coincident faces stopped after %1 s, %2 of %3 "
                                "faces compared with the others; more may coincide")
                     .arg(kBudgetMs / 1000)
                     .arg(compared)
                     .arg(sourceFaces.size());
    if (duplicates > maxReported)
        found << QStringLiteral("%1 more pairs of coincident faces").arg(duplicates - maxReported);
    if (contacts > 0)
        found << QStringLiteral("%1 pair(s) of faces of different solids coincide, parts in "
                                "contact (the first: %2); where such a face is seen, either of "
                                "the two may show")
                     .arg(contacts)
                     .arg(firstContact);
    return found;
}

} // namespace kw::occt
