// Kernel construction tests: patch, cone, revolution, extrusion, loft, iso-curves, knot
// removal and curve interpolation (A9.1), each stated as a property of the surface it builds.
#include "kernel_test_util.h"
#include "model/nurbs/nurbs_construct.h"

#include <QTest>

using namespace kw;

namespace {

NurbsCurve3 randomCurve3(std::mt19937& rng, int degree, int count, bool rational) {
    std::uniform_real_distribution<double> coord(-1.0, 1.0), weight(0.5, 2.0);
    NurbsCurve3 c;
    c.degree = degree;
    c.knots = kwtest::randomKnots(rng, degree, count, 1);
    for (int k = 0; k < count; ++k) {
        c.points.emplace_back(coord(rng), coord(rng), coord(rng));
        c.weights.push_back(rational ? weight(rng) : 1.0);
    }
    return c;
}

/// t in [0, 1] mapped into the curve's domain.
double at(const NurbsCurve3& c, double t) {
    const Interval d = knotDomain(c.knots, c.degree);
    return d.first + t * (d.last - d.first);
}

double maxDeviation(const NurbsSurface& a, const NurbsSurface& b) {
    const Interval du = surfaceDomainU(a), dv = surfaceDomainV(a);
    double worst = 0.0;
    for (int i = 0; i <= 20; ++i)
        for (int j = 0; j <= 20; ++j) {
            const double u = du.first + (du.last - du.first) * i / 20.0;
            const double v = dv.first + (dv.last - dv.first) * j / 20.0;
            worst = std::max(worst, glm::length(surfacePoint(a, u, v) - surfacePoint(b, u, v)));
        }
    return worst;
}

} // namespace

class TestNurbsConstruct : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void patchIsFlatClampedAndSized() {
        const NurbsSurface s = makePatch({1, 2, 3}, 3, 2, 6, 4, 4.0, 2.0);
        QVERIFY2(checkNurbsSurface(s).has_value(), qPrintable(checkNurbsSurface(s).message()));
        QCOMPARE(s.knotsU, (std::vector<double>{0, 0, 0, 0, 1.0 / 3, 2.0 / 3, 1, 1, 1, 1}));
        QCOMPARE(s.knotsV, (std::vector<double>{0, 0, 0, 0.5, 1, 1, 1}));
        const glm::dvec3 c00 = surfacePoint(s, 0, 0), c11 = surfacePoint(s, 1, 1);
        QVERIFY(glm::length(c00 - glm::dvec3(-1, 1, 3)) < 1e-12);
        QVERIFY(glm::length(c11 - glm::dvec3(3, 3, 3)) < 1e-12);
        QCOMPARE(surfacePoint(s, 0.37, 0.61).z, 3.0);
    }

    void coneIsExact() {
        const glm::dvec3 base(0.5, -1, 2);
        const NurbsSurface s = makeCone(base, 2.0, 3.0, 0.5);
        QVERIFY(checkNurbsSurface(s).has_value());
        for (int i = 0; i <= 16; ++i)
            for (int j = 0; j <= 8; ++j) {
                const glm::dvec3 p = surfacePoint(s, i / 16.0, j / 8.0) - base;
                const double h = p.z, r = std::hypot(p.x, p.y);
                QVERIFY(std::abs(r - (2.0 + (0.5 - 2.0) * h / 3.0)) < 1e-12);
                QVERIFY(std::abs(h - 3.0 * j / 8.0) < 1e-12);
            }
        // A pointed cone collapses to its apex and still validates.
        const NurbsSurface pointed = makeCone(base, 1.0, 2.0);
        QVERIFY(checkNurbsSurface(pointed).has_value());
        QVERIFY(glm::length(surfacePoint(pointed, 0.3, 1.0) - (base + glm::dvec3(0, 0, 2))) <
                1e-12);
    }

    void revolutionKeepsDistanceAndHeight() {
        std::mt19937 rng(5);
        for (bool rational : {false, true}) {
            const NurbsCurve3 profile = randomCurve3(rng, 3, 6, rational);
            const glm::dvec3 o(0.3, -0.2, 0.1), axis = glm::normalize(glm::dvec3(1, 2, -0.5));
            const NurbsSurface s = makeRevolution3(profile, o, axis * 3.0);
            QVERIFY(checkNurbsSurface(s).has_value());
            for (int j = 0; j <= 10; ++j) {
                const double v = at(profile, j / 10.0);
                const glm::dvec3 c = curve3Point(profile, v) - o;
                const double h = glm::dot(c, axis), r = glm::length(c - h * axis);
                for (int i = 0; i <= 12; ++i) {
                    const glm::dvec3 p = surfacePoint(s, i / 12.0, v) - o;
                    const double ph = glm::dot(p, axis);
                    QVERIFY2(std::abs(ph - h) < 1e-12, qPrintable(QString::number(ph - h)));
                    QVERIFY(std::abs(glm::length(p - ph * axis) - r) < 1e-12);
                }
                // u = 0 is the profile itself.
                QVERIFY(glm::length(surfacePoint(s, 0.0, v) - o - c) < 1e-12);
            }
        }
    }

    void extrusionSweepsTheCurve() {
        std::mt19937 rng(6);
        const NurbsCurve3 c = randomCurve3(rng, 2, 5, true);
        const glm::dvec3 d(0.2, 0.1, 1.5);
        const NurbsSurface s = makeExtrusion(c, d);
        QVERIFY(checkNurbsSurface(s).has_value());
        for (int i = 0; i <= 10; ++i) {
            const double u = at(c, i / 10.0);
            for (double v : {0.0, 0.3, 1.0})
                QVERIFY(glm::length(surfacePoint(s, u, v) - (curve3Point(c, u) + v * d)) < 1e-12);
        }
    }

    void loftInterpolatesIncompatibleSections() {
        std::mt19937 rng(7);
        // Different degrees, counts, knot vectors, domains and weights.
        std::vector<NurbsCurve3> sections = {
            randomCurve3(rng, 2, 4, false), randomCurve3(rng, 3, 7, true),
            randomCurve3(rng, 1, 3, false), randomCurve3(rng, 3, 5, true)};
        for (size_t k = 0; k < sections.size(); ++k)
            for (glm::dvec3& p : sections[k].points)
                p.z += 2.0 * double(k); // stacked, so chord lengths are clear
        std::vector<double> v;
        const Expected<NurbsSurface> loft = makeLoft(sections, 3, &v);
        QVERIFY2(loft, qPrintable(loft.message()));
        const NurbsSurface& s = *loft;
        QVERIFY(checkNurbsSurface(s).has_value());
        QCOMPARE(s.degreeU, 3);
        QCOMPARE(s.degreeV, 3);
        QCOMPARE(v.size(), sections.size());
        for (size_t k = 0; k < sections.size(); ++k)
            for (int i = 0; i <= 20; ++i) {
                const double t = i / 20.0;
                const double d = glm::length(surfacePoint(s, t, v[k]) -
                                             curve3Point(sections[k], at(sections[k], t)));
                QVERIFY2(d < 1e-9,
                         qPrintable(QStringLiteral("section %1 t %2: %3").arg(k).arg(t).arg(d)));
            }
        // Two sections give a ruled surface (degree 1 in v).
        const Expected<NurbsSurface> ruled = makeLoft({sections[0], sections[1]}, 3);
        QVERIFY(ruled);
        QCOMPARE(ruled->degreeV, 1);
        // Refusals name the reason.
        const Expected<NurbsSurface> one = makeLoft({sections[0]}, 3);
        QVERIFY(!one);
        QVERIFY(one.message().contains(QLatin1String("two")));
        const Expected<NurbsSurface> same = makeLoft({sections[0], sections[0]}, 3);
        QVERIFY(!same);
        QVERIFY(same.message().contains(QLatin1String("coincide")));
    }

    void isoCurveLiesOnTheSurface() {
        std::mt19937 rng(8);
        for (int trial = 0; trial < 6; ++trial) {
            const NurbsSurface s =
                kwtest::randomSurface(rng, 1 + trial % 3, 2 + trial % 2, 5, 6, trial % 2 == 1, 2);
            const Interval du = surfaceDomainU(s), dv = surfaceDomainV(s);
            for (bool alongU : {true, false})
                for (double f : {0.0, 0.41, 1.0}) {
                    const double fixed = alongU ? dv.first + f * (dv.last - dv.first)
                                                : du.first + f * (du.last - du.first);
                    const NurbsCurve3 c = surfaceIsoCurve(s, alongU, fixed);
                    QVERIFY(checkNurbsCurve3(c).has_value());
                    for (int i = 0; i <= 15; ++i) {
                        const Interval d = alongU ? du : dv;
                        const double t = d.first + (d.last - d.first) * i / 15.0;
                        const glm::dvec3 on =
                            alongU ? surfacePoint(s, t, fixed) : surfacePoint(s, fixed, t);
                        QVERIFY(glm::length(curve3Point(c, t) - on) < 1e-12);
                    }
                }
        }
    }

    void knotRemovalUndoesInsertionAndKeepsTolerance() {
        std::mt19937 rng(9);
        for (int trial = 0; trial < 8; ++trial) {
            const bool rational = trial % 2 == 1;
            const NurbsSurface s = kwtest::randomSurface(rng, 2 + trial % 3, 3, 7, 5, rational);
            const bool alongU = trial % 3 != 0;
            const Interval d = alongU ? surfaceDomainU(s) : surfaceDomainV(s);
            const double x = d.first + 0.437 * (d.last - d.first);
            const NurbsSurface refined =
                alongU ? surfaceInsertKnotU(s, x, 2) : surfaceInsertKnotV(s, x, 2);
            int removed = 0;
            const NurbsSurface back = surfaceRemoveKnots(refined, alongU, 1e-9, &removed);
            // The two inserted knots go; the random net's own knots are essential.
            QCOMPARE(removed, 2);
            QCOMPARE(alongU ? back.knotsU : back.knotsV, alongU ? s.knotsU : s.knotsV);
            QVERIFY(maxDeviation(back, s) < 1e-9);
            // A loose tolerance removes more, and never moves the surface by more than it.
            const double tol = 0.05;
            const NurbsSurface loose = surfaceRemoveKnots(s, alongU, tol, &removed);
            QVERIFY2(maxDeviation(loose, s) <= tol,
                     qPrintable(QString::number(maxDeviation(loose, s))));
            // Zero tolerance on the random net removes nothing and returns it unchanged.
            QVERIFY(surfaceRemoveKnots(s, alongU, 0.0, &removed) == s);
            QCOMPARE(removed, 0);
        }
        // A Bezier patch refined at three values (one of them twice) gets back to Bezier.
        const NurbsSurface bezier = makePatch({0, 0, 0}, 3, 3, 4, 4, 2, 2);
        NurbsSurface refined = surfaceInsertKnotU(bezier, 0.2);
        refined = surfaceInsertKnotU(refined, 0.5, 2);
        refined = surfaceInsertKnotU(refined, 0.8);
        QCOMPARE(refined.countU, 8);
        int removed = 0;
        const NurbsSurface bare = surfaceRemoveKnots(refined, true, 1e-9, &removed);
        QCOMPARE(removed, 4);
        QCOMPARE(bare.countU, 4);
        QVERIFY(maxDeviation(bare, bezier) < 1e-9);
    }

    void trimCurvePointInsertionAndRemoval() {
        std::mt19937 rng(10);
        for (int degree = 1; degree <= 3; ++degree) {
            const NurbsCurve2 c = kwtest::randomCurve(rng, degree, 6, degree == 2);
            const Interval d = curveDomain(c);
            const double t = d.first + 0.38 * (d.last - d.first);
            const NurbsCurve2 more = curve2InsertKnot(c, t);
            QCOMPARE(more.points.size(), c.points.size() + 1);
            QVERIFY(checkNurbsCurve(more).has_value());
            for (int i = 0; i <= 20; ++i) { // same shape
                const double x = d.first + (d.last - d.first) * i / 20.0;
                QVERIFY(glm::length(curvePoint(more, x) - curvePoint(c, x)) < 1e-12);
            }
            // Removing an interior point keeps the ends (the loop stays closed) and validity.
            const NurbsCurve2 fewer = curve2RemovePoint(more, 2);
            QCOMPARE(fewer.points.size(), c.points.size());
            QVERIFY2(checkNurbsCurve(fewer).has_value(),
                     qPrintable(checkNurbsCurve(fewer).message()));
            QVERIFY(glm::length(curvePoint(fewer, d.first) - curvePoint(c, d.first)) < 1e-12);
            QVERIFY(glm::length(curvePoint(fewer, d.last) - curvePoint(c, d.last)) < 1e-12);
            // Ends cannot be removed.
            QVERIFY(curve2RemovePoint(c, 0) == c);
            QVERIFY(curve2RemovePoint(c, int(c.points.size()) - 1) == c);
        }
        // Down to the last interior point of a cubic: the degree drops.
        NurbsCurve2 cubic = kwtest::randomCurve(rng, 3, 4, false);
        cubic = curve2RemovePoint(cubic, 1);
        QCOMPARE(cubic.degree, 2);
        QVERIFY(checkNurbsCurve(cubic).has_value());
    }

    void interpolationPassesThroughThePoints() {
        // A9.1 with chord-length parameters and averaged knots: C(t_k) = Q_k for random points,
        // 2 to 12 of them, degree 1 to 3 (lowered to n - 1 for few points).
        std::mt19937 rng(913);
        std::uniform_real_distribution<double> coord(-3.0, 3.0);
        for (int n = 2; n <= 12; ++n)
            for (int degree = 1; degree <= 3; ++degree) {
                std::vector<glm::dvec3> q;
                for (int k = 0; k < n; ++k)
                    q.emplace_back(coord(rng), coord(rng), coord(rng));
                std::vector<double> t;
                const Expected<NurbsCurve3> interpolated = interpolateCurve3(q, degree, &t);
                QVERIFY2(interpolated, qPrintable(interpolated.message()));
                const NurbsCurve3& c = *interpolated;
                QVERIFY(checkNurbsCurve3(c).has_value());
                QCOMPARE(c.degree, std::min(degree, n - 1));
                QCOMPARE(c.points.size(), size_t(n));
                QCOMPARE(t.size(), size_t(n));
                QCOMPARE(t.front(), 0.0);
                QCOMPARE(t.back(), 1.0);
                for (int k = 0; k < n; ++k)
                    QVERIFY2(
                        glm::length(curve3Point(c, t[size_t(k)]) - q[size_t(k)]) < 1e-12,
                        qPrintable(
                            QStringLiteral("n %1 degree %2 point %3").arg(n).arg(degree).arg(k)));
            }
        // Collinear evenly spaced points give the straight line through them.
        const NurbsCurve3 line = *interpolateCurve3({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}});
        QVERIFY(glm::length(curve3Point(line, 0.5) - glm::dvec3(1.5, 0, 0)) < 1e-12);
        // Refused: too few points, a repeated point, a non-finite point.
        const Expected<NurbsCurve3> single = interpolateCurve3({{1, 2, 3}}, 3);
        QVERIFY(!single);
        QVERIFY(!single.message().isEmpty());
        const Expected<NurbsCurve3> repeated =
            interpolateCurve3({{0, 0, 0}, {1, 0, 0}, {1, 0, 0}}, 3);
        QVERIFY(!repeated);
        QVERIFY(repeated.message().contains(QStringLiteral("coincide")));
        QVERIFY(!interpolateCurve3({{0, 0, 0}, {std::nan(""), 0, 0}}, 3));
        // The control-point curve: clamped uniform, its ends on the first and last points.
        const NurbsCurve3 cp =
            controlPointCurve3({{0, 0, 0}, {1, 1, 0}, {2, 0, 0}, {3, 1, 0}, {4, 0, 0}});
        QVERIFY(checkNurbsCurve3(cp).has_value());
        QCOMPARE(cp.degree, 3);
        QCOMPARE(curve3Point(cp, 0.0), glm::dvec3(0, 0, 0));
        QCOMPARE(curve3Point(cp, 1.0), glm::dvec3(4, 0, 0));
        QCOMPARE(controlPointCurve3({{0, 0, 0}, {1, 0, 0}}).degree, 1);
    }
};

QTEST_GUILESS_MAIN(TestNurbsConstruct)
#include "tst_nurbs_construct.moc"
