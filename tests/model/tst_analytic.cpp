// Closed forms of analytic faces (model/nurbs/analytic_eval.h): the forms of the kernel's own
// exact shapes match their NURBS point for point and normal for normal, the parameter maps
// invert, the closed-form ray hits are the roots a brute-force march finds, and a similarity
// of the NURBS carries the form along while any other change does not.
#include "model/io/knotfile.h"
#include "model/nurbs/analytic_eval.h"
#include "model/nurbs/nurbs_shapes.h"

#include <QTest>
#include <cmath>
#include <numbers>
#include <random>

using namespace kw;
using Kind = AnalyticForm::Kind;
using MapKind = AnalyticParamMap::Kind;

namespace {

constexpr double kPi = std::numbers::pi;

struct Case {
    const char* name;
    NurbsSurface nurbs;
    AnalyticForm form;
};

AnalyticParamMap linear(double offset, double scale) {
    return {MapKind::Linear, offset, scale};
}
AnalyticParamMap halfAngle(double offset, double scale) {
    return {MapKind::HalfAngle, offset, scale};
}

AnalyticForm form(Kind kind, glm::dvec3 origin, double r0, double r1, double semi,
                  AnalyticParamMap u, AnalyticParamMap v) {
    AnalyticForm f;
    f.kind = kind;
    f.origin = origin;
    f.radius = r0;
    f.minorRadius = r1;
    f.semiAngle = semi;
    f.u = u;
    f.v = v;
    return f;
}

NurbsSurface transposed(const NurbsSurface& s) {
    NurbsSurface t;
    t.degreeU = s.degreeV;
    t.degreeV = s.degreeU;
    t.countU = s.countV;
    t.countV = s.countU;
    t.knotsU = s.knotsV;
    t.knotsV = s.knotsU;
    for (int j = 0; j < t.countV; ++j)
        for (int i = 0; i < t.countU; ++i) {
            t.points.push_back(s.points[size_t(s.index(j, i))]);
            t.weights.push_back(s.weights[size_t(s.index(j, i))]);
        }
    return t;
}

NurbsSurface moved(NurbsSurface s, const glm::dmat3& m, const glm::dvec3& t) {
    for (glm::dvec3& p : s.points)
        p = m * p + t;
    return s;
}

// The kernel's exact shapes (nurbs_shapes.h: u around +z from +x, quarter arcs in standard
// form over knots 0, 1/4, ..., 1) with the forms that describe them, plus a cone (a revolved
// line), a mirrored cylinder (an indirect frame) and a transposed torus (swapped maps).
std::vector<Case> cases() {
    const glm::dvec3 c(1.5, -2.0, 0.5);
    std::vector<Case> out;
    out.push_back({"plane", makePlane(c, {3, 0, 0}, {0, 2, 0}),
                   form(Kind::Plane, c, 0, 0, 0, linear(0, 3), linear(0, 2))});
    out.push_back({"cylinder", makeCylinder(c, 2.0, 5.0),
                   form(Kind::Cylinder, c, 2, 0, 0, halfAngle(0, 2 * kPi), linear(0, 5))});
    out.push_back(
        {"sphere", makeSphere(c, 3.0),
         form(Kind::Sphere, c, 3, 0, 0, halfAngle(0, 2 * kPi), halfAngle(-kPi / 2, kPi))});
    out.push_back({"torus", makeTorus(c, 4.0, 1.0),
                   form(Kind::Torus, c, 4, 1, 0, halfAngle(0, 2 * kPi), halfAngle(0, 2 * kPi))});
    // A cone from radius 1 at z = 0 to radius 3 at z = 4: semi-angle atan(2/4), generatrix
    // length sqrt(20) over v in [0, 1].
    NurbsCurve2 line;
    line.degree = 1;
    line.knots = {0, 0, 1, 1};
    line.points = {{1.0, 0.0}, {3.0, 4.0}};
    line.weights = {1, 1};
    out.push_back({"cone", makeRevolution(c, line),
                   form(Kind::Cone, c, 1, 0, std::atan(0.5), halfAngle(0, 2 * kPi),
                        linear(0, std::sqrt(20.0)))});
    // Mirrored through z: the frame turns indirect, the NURBS's normal turns with it.
    const glm::dmat3 mirror(1, 0, 0, 0, 1, 0, 0, 0, -1);
    out.push_back({"mirrored cylinder", moved(makeCylinder(c, 2.0, 5.0), mirror, {}),
                   analyticTransformed(out[1].form, mirror, {})});
    // A spindle torus (r > R): where R + r cos b < 0 its points lie across the axis.
    out.push_back({"spindle torus", makeTorus(c, 1.0, 2.0),
                   form(Kind::Torus, c, 1, 2, 0, halfAngle(0, 2 * kPi), halfAngle(0, 2 * kPi))});
    Case swapped{"transposed torus", transposed(makeTorus(c, 4.0, 1.0)), out[3].form};
    swapped.form.swapped = true;
    std::swap(swapped.form.u, swapped.form.v); // the map named u takes the NURBS's u (was v)
    out.push_back(swapped);
    return out;
}

double size(const NurbsSurface& s) {
    glm::dvec3 lo, hi;
    surfaceControlBounds(s, lo, hi);
    return glm::length(hi - lo);
}

// The implicit equation of the whole surface, in the form's frame, scaled to a length.
double implicit(const AnalyticForm& f, const glm::dvec3& p) {
    const glm::dvec3 d = p - f.origin;
    const double x = glm::dot(d, f.xAxis), y = glm::dot(d, f.yAxis), z = glm::dot(d, f.zAxis);
    switch (f.kind) {
    case Kind::Plane:
        return z;
    case Kind::Cylinder:
        return x * x + y * y - f.radius * f.radius;
    case Kind::Cone: {
        const double r = f.radius + z * std::tan(f.semiAngle);
        return x * x + y * y - r * r;
    }
    case Kind::Sphere:
        return x * x + y * y + z * z - f.radius * f.radius;
    case Kind::Torus: {
        const double q =
            x * x + y * y + z * z + f.radius * f.radius - f.minorRadius * f.minorRadius;
        return q * q - 4 * f.radius * f.radius * (x * x + y * y);
    }
    case Kind::None:
        break;
    }
    return 0.0;
}

// Distance from p to the form's surface, through its closed-form projection.
double offSurface(const AnalyticForm& f, const glm::dvec3& p) {
    const glm::dvec2 ab = analyticProject(f, p);
    if (f.kind == Kind::Plane)
        return std::abs(glm::dot(p - f.origin, f.zAxis));
    // The nearest point of a cone, sphere or torus is not at the projection's (a, b) in general;
    // the point at (a, b) lies on the same meridian, so compare along the meridian's normal.
    const glm::dvec3 q = analyticPoint(f, ab.x, ab.y);
    return std::abs(glm::dot(p - q, analyticNormal(f, ab.x, ab.y)));
}

} // namespace

class TestAnalytic : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void kindNames();
    void formsMatchTheirNurbs();
    void wrongFormsDeviate();
    void parametersInvert();
    void normalsFollowTheNurbs();
    void rayHitsAreTheRoots();
    void rayHitsFromFarAway();
    void similaritiesCarryTheForm();
    void formErrors();
    void importedFormsMatchTheirNurbs();
    void knotInsertionAndTheMaps();
};

void TestAnalytic::kindNames() {
    for (Kind k : {Kind::None, Kind::Plane, Kind::Cylinder, Kind::Cone, Kind::Sphere, Kind::Torus})
        QCOMPARE(analyticKindNamed(analyticKindName(k)), std::optional<Kind>(k));
    QVERIFY(!analyticKindNamed("ellipsoid"));
}

void TestAnalytic::formsMatchTheirNurbs() {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (const Case& c : cases()) {
        QVERIFY2(checkAnalyticForm(c.form, c.nurbs).has_value(), c.name);
        const double tol = 1e-12 * size(c.nurbs);
        QVERIFY2(analyticDeviation(c.form, c.nurbs) <= tol, c.name);
        for (int k = 0; k < 200; ++k) {
            const double u = unit(rng), v = unit(rng);
            const glm::dvec2 ab = analyticParameters(c.form, c.nurbs, u, v);
            const double d =
                glm::length(surfacePoint(c.nurbs, u, v) - analyticPoint(c.form, ab.x, ab.y));
            QVERIFY2(
                d <= tol,
                qPrintable(QStringLiteral("%1 at (%2, %3): %4").arg(c.name).arg(u).arg(v).arg(d)));
        }
    }
}

// The check the importer relies on tells a right form from slightly wrong ones.
void TestAnalytic::wrongFormsDeviate() {
    for (const Case& c : cases()) {
        const double big = 1e-4 * size(c.nurbs);
        AnalyticForm f = c.form;
        f.u.offset += 1e-2;
        QVERIFY2(analyticDeviation(f, c.nurbs) > big, c.name);
        f = c.form;
        f.radius *= 1.001;
        f.origin.z += c.form.kind == Kind::Plane ? 1e-3 : 0.0;
        QVERIFY2(analyticDeviation(f, c.nurbs) > big, c.name);
        if (c.form.u.kind == MapKind::HalfAngle) {
            f = c.form;
            f.u.kind = MapKind::Linear; // right at the knots, wrong between them
            QVERIFY2(analyticDeviation(f, c.nurbs) > big, c.name);
        }
    }
}

void TestAnalytic::parametersInvert() {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (const Case& c : cases()) {
        for (int k = 0; k < 200; ++k) {
            const double u = unit(rng), v = unit(rng);
            const glm::dvec2 ab = analyticParameters(c.form, c.nurbs, u, v);
            // Angles come back from any turn.
            const AnalyticParamMap& toA = c.form.swapped ? c.form.v : c.form.u;
            const double turn = toA.kind == MapKind::HalfAngle ? 2 * kPi * (k % 3 - 1) : 0.0;
            const std::optional<glm::dvec2> uv =
                nurbsParameters(c.form, c.nurbs, ab.x + turn, ab.y);
            QVERIFY2(uv, c.name);
            // At u = 0 and u = 1 a full turn's seam is both; compare points there.
            const double d =
                glm::length(surfacePoint(c.nurbs, uv->x, uv->y) - surfacePoint(c.nurbs, u, v));
            QVERIFY2(d <= 1e-12 * size(c.nurbs),
                     qPrintable(QStringLiteral("%1: %2").arg(c.name).arg(d)));
        }
    }
    // Outside the domain: the cylinder's height beyond its top.
    const Case cyl = cases()[1];
    QVERIFY(!nurbsParameters(cyl.form, cyl.nurbs, 0.3, 5.5));
    QVERIFY(nurbsParameters(cyl.form, cyl.nurbs, 0.3, 5.0));
    // A quarter of a cylinder: angles outside [0, pi/2] are not on it.
    AnalyticForm qf = cyl.form;
    qf.u.scale = kPi / 2;
    NurbsSurface arc;
    arc.degreeU = 2;
    arc.degreeV = 1;
    arc.countU = 3;
    arc.countV = 2;
    arc.knotsU = {0, 0, 0, 1, 1, 1};
    arc.knotsV = {0, 0, 1, 1};
    const double w = std::sqrt(0.5);
    for (double z : {0.0, 5.0})
        for (glm::dvec3 p : {glm::dvec3(2, 0, 0), glm::dvec3(2, 2, 0), glm::dvec3(0, 2, 0)}) {
            arc.points.push_back(cyl.form.origin + p + glm::dvec3(0, 0, z));
            arc.weights.push_back(p.x == p.y ? w : 1.0);
        }
    QVERIFY(analyticDeviation(qf, arc) <= 1e-12 * size(arc));
    QVERIFY(nurbsParameters(qf, arc, 1.0, 1.0));
    QVERIFY(!nurbsParameters(qf, arc, 2.0, 1.0));
    QVERIFY(!nurbsParameters(qf, arc, -0.5, 1.0));
}

void TestAnalytic::normalsFollowTheNurbs() {
    std::mt19937 rng(13);
    std::uniform_real_distribution<double> unit(0.02, 0.98);
    for (const Case& c : cases()) {
        for (int k = 0; k < 200; ++k) {
            const double u = unit(rng), v = unit(rng);
            const glm::dvec2 ab = analyticParameters(c.form, c.nurbs, u, v);
            const glm::dvec3 n = analyticNormal(c.form, ab.x, ab.y);
            const glm::dvec3 m = surfaceFrame(c.nurbs, u, v).normal;
            QVERIFY2(std::abs(glm::length(n) - 1.0) < 1e-12, c.name);
            QVERIFY2(glm::dot(n, m) > 1.0 - 1e-10,
                     qPrintable(QStringLiteral("%1 at (%2, %3): n.m = %4")
                                    .arg(c.name)
                                    .arg(u)
                                    .arg(v)
                                    .arg(glm::dot(n, m))));
        }
    }
}

void TestAnalytic::rayHitsAreTheRoots() {
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> box(-8.0, 8.0);
    int compared = 0, hitsSeen = 0;
    for (const Case& c : cases()) {
        const double len = size(c.nurbs);
        for (int k = 0; k < 300; ++k) {
            const glm::dvec3 o = c.form.origin + glm::dvec3(box(rng), box(rng), box(rng));
            const glm::dvec3 target =
                c.form.origin + 0.3 * glm::dvec3(box(rng), box(rng), box(rng));
            const glm::dvec3 d = (target - o) * (0.5 + std::abs(box(rng)) / 4); // not unit
            const AnalyticRayHits hits = analyticRayHits(c.form, o, d);
            QVERIFY(std::is_sorted(hits.t, hits.t + hits.count));
            for (int i = 0; i < hits.count; ++i)
                QVERIFY2(offSurface(c.form, o + hits.t[i] * d) <= 1e-9 * len,
                         qPrintable(QStringLiteral("%1: hit %2 lies %3 off")
                                        .arg(c.name)
                                        .arg(hits.t[i])
                                        .arg(offSurface(c.form, o + hits.t[i] * d))));
            // Brute force: sign changes of the implicit equation over t in [-T, T].
            const double T = 40.0 / glm::length(d);
            const int steps = 20000;
            std::vector<double> roots;
            bool nearTangent = false;
            double prev = implicit(c.form, o - T * d);
            for (int s = 1; s <= steps; ++s) {
                const double t = -T + 2 * T * s / steps;
                const double f = implicit(c.form, o + t * d);
                if ((prev < 0) != (f < 0)) {
                    double lo = t - 2 * T / steps, hi = t;
                    for (int b = 0; b < 80; ++b) {
                        const double mid = 0.5 * (lo + hi);
                        ((implicit(c.form, o + lo * d) < 0) == (implicit(c.form, o + mid * d) < 0)
                             ? lo
                             : hi) = mid;
                    }
                    roots.push_back(0.5 * (lo + hi));
                }
                prev = f;
            }
            // Roots closer than a march step, or a tangent graze, are left out of the count.
            for (size_t i = 1; i < roots.size(); ++i)
                nearTangent = nearTangent || roots[i] - roots[i - 1] < 1e-3 * T;
            for (int i = 1; i < hits.count; ++i)
                nearTangent = nearTangent || hits.t[i] - hits.t[i - 1] < 1e-3 * T;
            if (nearTangent || (hits.count > 0 && std::abs(hits.t[hits.count - 1]) > 0.99 * T) ||
                (hits.count > 0 && std::abs(hits.t[0]) > 0.99 * T))
                continue;
            ++compared;
            hitsSeen += hits.count;
            QCOMPARE(hits.count, int(roots.size()));
            for (int i = 0; i < hits.count; ++i)
                QVERIFY2(std::abs(hits.t[i] - roots[size_t(i)]) * glm::length(d) <= 1e-9 * len,
                         c.name);
        }
    }
    qInfo("%d rays compared with the march, %d hits", compared, hitsSeen);
    QVERIFY(compared > 1500);
    QVERIFY(hitsSeen > 2000);
}

// A camera a million times the torus's size away: the hits keep their digits (the solve runs
// from the ray's point nearest the frame's origin).
void TestAnalytic::rayHitsFromFarAway() {
    const Case torus = cases()[3];
    std::mt19937 rng(19);
    std::normal_distribution<double> g;
    int hit = 0;
    for (int k = 0; k < 200; ++k) {
        const glm::dvec3 dir = glm::normalize(glm::dvec3(g(rng), g(rng), g(rng)));
        const glm::dvec3 aim = torus.form.origin + glm::dvec3(g(rng), g(rng), 0.5 * g(rng)) * 3.0;
        const glm::dvec3 o = aim - 1e7 * dir;
        const AnalyticRayHits hits = analyticRayHits(torus.form, o, dir);
        for (int i = 0; i < hits.count; ++i)
            QVERIFY2(offSurface(torus.form, o + hits.t[i] * dir) <= 1e-7,
                     qPrintable(QString::number(offSurface(torus.form, o + hits.t[i] * dir))));
        hit += hits.count > 0;
    }
    QVERIFY(hit > 50);
}

void TestAnalytic::similaritiesCarryTheForm() {
    const glm::dmat3 rot = glm::dmat3(glm::dvec3(0.36, 0.48, -0.8), glm::dvec3(-0.8, 0.6, 0.0),
                                      glm::dvec3(0.48, 0.64, 0.6));
    const glm::dvec3 t(10.0, -3.0, 7.5);
    for (const Case& c : cases()) {
        for (const glm::dmat3& m :
             {rot, 2.5 * rot, glm::dmat3(1.0), rot * glm::dmat3(1, 0, 0, 0, -1, 0, 0, 0, 1)}) {
            const NurbsSurface to = moved(c.nurbs, m, t);
            const std::optional<AnalyticForm> f = analyticFollow(c.form, c.nurbs, to);
            QVERIFY2(f, c.name);
            QVERIFY2(checkAnalyticForm(*f, to).has_value(), c.name);
            QVERIFY2(analyticDeviation(*f, to) <= 1e-12 * size(to), c.name);
            const glm::dvec2 ab = analyticParameters(*f, to, 0.3, 0.6);
            QVERIFY2(glm::dot(analyticNormal(*f, ab.x, ab.y), surfaceFrame(to, 0.3, 0.6).normal) >
                         1 - 1e-10,
                     c.name);
        }
        // Not a similarity: stretched along one axis, one control point moved, a weight changed.
        QVERIFY2(!analyticFollow(c.form, c.nurbs,
                                 moved(c.nurbs, glm::dmat3(1, 0, 0, 0, 1.5, 0, 0, 0, 1), t)),
                 c.name);
        NurbsSurface bent = c.nurbs;
        bent.points[1] += glm::dvec3(0.0, 0.0, 1e-3);
        QVERIFY2(!analyticFollow(c.form, c.nurbs, bent), c.name);
        NurbsSurface heavier = c.nurbs;
        heavier.weights[1] *= 1.5;
        QVERIFY2(!analyticFollow(c.form, c.nurbs, heavier), c.name);
        QVERIFY(!analyticFollow(AnalyticForm{}, c.nurbs, c.nurbs));
    }
}

void TestAnalytic::formErrors() {
    const Case cyl = cases()[1];
    QVERIFY(checkAnalyticForm(AnalyticForm{}, cyl.nurbs).has_value());
    AnalyticForm f = cyl.form;
    f.xAxis *= 1.01;
    QVERIFY(!checkAnalyticForm(f, cyl.nurbs));
    f = cyl.form;
    f.yAxis = glm::normalize(glm::dvec3(0.1, 1, 0));
    QVERIFY(!checkAnalyticForm(f, cyl.nurbs));
    f = cyl.form;
    f.radius = 0.0;
    QVERIFY(!checkAnalyticForm(f, cyl.nurbs));
    f = cyl.form;
    f.origin.x = std::nan("");
    QVERIFY(!checkAnalyticForm(f, cyl.nurbs));
    f = cyl.form;
    f.v.kind = MapKind::HalfAngle; // the height is degree 1
    QVERIFY(!checkAnalyticForm(f, cyl.nurbs));
    f = cyl.form;
    f.u.scale = 0.0;
    QVERIFY(!checkAnalyticForm(f, cyl.nurbs));
    f = cyl.form;
    f.u.scale = 5 * kPi; // a quarter span would turn by more than pi
    QVERIFY(!checkAnalyticForm(f, cyl.nurbs));
    f = cases()[4].form;
    f.semiAngle = kPi / 2;
    QVERIFY(!checkAnalyticForm(f, cases()[4].nurbs));
    f = cases()[3].form;
    f.minorRadius = -1.0;
    QVERIFY(!checkAnalyticForm(f, cases()[3].nurbs));
}

// Real faces as the CAD reader imported them (tests/data/kernel/rational_faces.knot: a torus,
// cone and cylinder from Pump_Nut.brep, a sphere from Axis_of_bearing.brep): the forms agree
// with their NURBS on a dense grid, edges, seams and poles included, point and normal, and the
// maps invert inside the domain (on a seam, a or b may come back as the other turn).
void TestAnalytic::importedFormsMatchTheirNurbs() {
    const Expected<Scene> scene =
        readKnotFile(QStringLiteral(KW_TEST_DATA_DIR "/kernel/rational_faces.knot"));
    QVERIFY(scene);
    int forms = 0;
    for (const Surface& f : scene->surfaces) {
        if (f.analytic.kind == Kind::None)
            continue;
        ++forms;
        const NurbsSurface& g = f.geometry;
        double far = 0.0;
        for (const glm::dvec3& p : g.points)
            far = std::max(far, glm::length(p));
        const double tol = 1e-13 * (size(g) + far); // measured: 5e-16
        const Interval du = surfaceDomainU(g), dv = surfaceDomainV(g);
        const int n = 40;
        for (int i = 0; i <= n; ++i)
            for (int j = 0; j <= n; ++j) {
                const double u = du.first + (du.last - du.first) * i / n;
                const double v = dv.first + (dv.last - dv.first) * j / n;
                const glm::dvec2 ab = analyticParameters(f.analytic, g, u, v);
                const SurfaceFrame fr = surfaceFrame(g, u, v);
                const QString at = QStringLiteral("%1 at (%2, %3)").arg(f.name).arg(u).arg(v);
                QVERIFY2(glm::length(analyticPoint(f.analytic, ab.x, ab.y) - fr.point) <= tol,
                         qPrintable(at));
                // Measured: 7e-12 (the cone's apex side, the sphere's poles included).
                QVERIFY2(glm::length(analyticNormal(f.analytic, ab.x, ab.y) - fr.normal) < 1e-9,
                         qPrintable(at));
                if (i == 0 || i == n || j == 0 || j == n)
                    continue;
                const std::optional<glm::dvec2> back = nurbsParameters(f.analytic, g, ab.x, ab.y);
                QVERIFY2(back, qPrintable(at));
                QVERIFY2(std::abs(back->x - u) <= 1e-12 * (du.last - du.first) &&
                             std::abs(back->y - v) <= 1e-12 * (dv.last - dv.first),
                         qPrintable(at));
            }
    }
    QCOMPARE(forms, 4);
}

// Knot insertion does not move the surface, but a HalfAngle map is defined by the knots it
// reads: at each distinct knot the angle is linear in the parameter, which holds for the
// quarter arcs in standard form and not at a knot inserted inside one. Read through the new
// knots, a cylinder's form is off by 0.0164 of its radius (0.033 at radius 2): the document
// drops the form on any such edit (tst_analytic_document). Through the original knots the
// refined NURBS still matches it exactly, and a knot in the Linear direction keeps it valid.
void TestAnalytic::knotInsertionAndTheMaps() {
    const Case c = cases()[1];
    QCOMPARE(c.form.kind, Kind::Cylinder);
    const double tol = 1e-12 * size(c.nurbs);
    for (double x : {0.1, 0.3, 0.6}) {
        const NurbsSurface alongAngle = surfaceInsertKnotU(c.nurbs, x, 1);
        const NurbsSurface alongHeight = surfaceInsertKnotV(c.nurbs, x, 1);
        QVERIFY(analyticDeviation(c.form, alongHeight) <= tol);
        const double off = analyticDeviation(c.form, alongAngle);
        QVERIFY2(off > 1e-3 * c.form.radius, qPrintable(QString::number(off)));
        for (int k = 0; k <= 100; ++k) {
            const double u = k / 100.0, v = 0.37;
            const glm::dvec2 ab = analyticParameters(c.form, c.nurbs, u, v);
            QVERIFY(glm::length(surfacePoint(alongAngle, u, v) -
                                analyticPoint(c.form, ab.x, ab.y)) <= tol);
        }
    }
}

QTEST_GUILESS_MAIN(TestAnalytic)
#include "tst_analytic.moc"
