// Kernel basis-function tests: span search, partition of unity, non-negativity, agreement with
// the Cox-de Boor recursion, and derivatives against central differences, degrees 1..15.
#include "kernel_test_util.h"

#include <QTest>
#include <cstdint>
#include <set>

using namespace kw;

namespace {

/// Reference: all N_{i,p}(u) from the Cox-de Boor recursion (Eq. 2.5) tabulated degree by
/// degree over every i, with 0/0 = 0 and half-open spans, except that at the end of the domain
/// only the last non-empty span `lastSpan` counts (the limit from the left).
std::vector<double> coxDeBoor(const std::vector<double>& U, int p, double u, double last,
                              int lastSpan) {
    const int m = int(U.size()) - 1;
    std::vector<double> n(size_t(m), 0.0);
    for (int i = 0; i < m; ++i)
        n[size_t(i)] = u == last ? (i == lastSpan ? 1.0 : 0.0)
                                 : ((U[size_t(i)] <= u && u < U[size_t(i + 1)]) ? 1.0 : 0.0);
    for (int q = 1; q <= p; ++q) {
        for (int i = 0; i + q < m; ++i) {
            double r = 0.0;
            const double d1 = U[size_t(i + q)] - U[size_t(i)];
            const double d2 = U[size_t(i + q + 1)] - U[size_t(i + 1)];
            if (d1 > 0.0)
                r += (u - U[size_t(i)]) / d1 * n[size_t(i)];
            if (d2 > 0.0)
                r += (U[size_t(i + q + 1)] - u) / d2 * n[size_t(i + 1)];
            n[size_t(i)] = r;
        }
    }
    return n; // n[i] = N_{i,p}(u) for i + p < m
}

} // namespace

class TestNurbsBasis : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void findSpanCases();
    void spanCounts();
    void partitionOfUnity_data();
    void partitionOfUnity();
    void derivativesMatchFiniteDifferences_data();
    void derivativesMatchFiniteDifferences();
    void derivativesAboveDegreeAreZero();
};

void TestNurbsBasis::findSpanCases() {
    const std::vector<double> U = {0, 0, 0, 1, 2, 2, 3, 4, 4, 4};
    const int p = 2;
    QCOMPARE(findSpan(p, U, 0.0), 2);
    QCOMPARE(findSpan(p, U, 0.5), 2);
    QCOMPARE(findSpan(p, U, 1.0), 3);
    QCOMPARE(findSpan(p, U, 2.0), 5); // multiplicity 2: the span after the double knot
    QCOMPARE(findSpan(p, U, 2.5), 5);
    QCOMPARE(findSpan(p, U, 4.0), 6); // domain end: last non-empty span
    QCOMPARE(findSpan(p, U, 7.0), 6); // clamped
    QCOMPARE(findSpan(p, U, -3.0), 2);
    QCOMPARE(findSpan(p, U, std::nan("")), 2);
    QCOMPARE(knotDomain(U, p), (Interval{0.0, 4.0}));
    // Unclamped knots: domain [u_p, u_{m-p}].
    const std::vector<double> V = {0, 1, 2, 3, 4, 5, 6, 7};
    QCOMPARE(knotDomain(V, 3), (Interval{3.0, 4.0}));
    QCOMPARE(findSpan(3, V, 4.0), 3);
}

void TestNurbsBasis::spanCounts() {
    // Known cases: a double interior knot leaves an empty span; an unclamped vector's domain
    // is one span; a vector too short for its degree has none.
    QCOMPARE(nonEmptySpanCount(2, {0, 0, 0, 1, 2, 2, 3, 4, 4, 4}), 4);
    QCOMPARE(nonEmptySpanCount(3, {0, 1, 2, 3, 4, 5, 6, 7}), 1);
    QCOMPARE(nonEmptySpanCount(1, {0, 0, 1, 1}), 1);
    QCOMPARE(nonEmptySpanCount(2, {0, 0, 1}), 0);
    QCOMPARE(nonEmptySpanCount(1, {}), 0);
    // Property: the count is the number of distinct spans findSpan gives over the domain
    // (sampled at every knot and between them), for knot vectors with repeated knots.
    std::uint32_t seed = 12345;
    const auto next = [&seed] {
        return (seed = seed * 1664525u + 1013904223u) >> 8;
    };
    for (int trial = 0; trial < 200; ++trial) {
        const int p = 1 + int(next() % 5);
        const int count = p + 1 + int(next() % 8);
        std::vector<double> U(size_t(count + p + 1));
        double t = 0.0;
        for (size_t i = 0; i < U.size(); ++i) {
            if (i > 0 && next() % 3 != 0)
                t += 1.0 + double(next() % 3);
            U[i] = t;
        }
        const Interval dom = knotDomain(U, p);
        if (!(dom.first < dom.last))
            continue; // no domain: not a valid knot vector
        std::set<int> seen;
        for (double k : U) {
            const double mid = k + 0.5;
            for (double u : {k, mid})
                if (u >= dom.first && u <= dom.last)
                    seen.insert(findSpan(p, U, u));
        }
        QCOMPARE(nonEmptySpanCount(p, U), int(seen.size()));
    }
    // A surface: the product of its two directions' counts.
    NurbsSurface s;
    s.degreeU = 2;
    s.degreeV = 1;
    s.knotsU = {0, 0, 0, 1, 2, 2, 3, 4, 4, 4};
    s.knotsV = {0, 0, 1, 1, 2, 2};
    s.countU = 7;
    s.countV = 4;
    QCOMPARE(surfaceSpanCount(s), 4 * 2);
}

void TestNurbsBasis::partitionOfUnity_data() {
    QTest::addColumn<int>("degree");
    QTest::addColumn<int>("maxMult");
    QTest::addColumn<bool>("unclamped");
    for (int p = 1; p <= kMaxDegree; ++p) {
        QTest::addRow("p%d simple", p) << p << 1 << false;
        QTest::addRow("p%d multiple", p) << p << p << false;
        QTest::addRow("p%d discontinuous", p) << p << p + 1 << false;
        QTest::addRow("p%d unclamped", p) << p << std::max(1, p / 2) << true;
    }
}

void TestNurbsBasis::partitionOfUnity() {
    QFETCH(int, degree);
    QFETCH(int, maxMult);
    QFETCH(bool, unclamped);
    std::mt19937 rng(1000u + unsigned(degree) * 7u + unsigned(maxMult) + (unclamped ? 500u : 0u));
    for (int trial = 0; trial < 20; ++trial) {
        const int count = degree + 1 + int(rng() % 12);
        const std::vector<double> U = kwtest::randomKnots(rng, degree, count, maxMult, unclamped);
        QVERIFY2(checkKnotVector(U, degree, count).has_value(),
                 qPrintable(checkKnotVector(U, degree, count).message()));
        const Interval d = knotDomain(U, degree);
        int lastSpan = count - 1;
        while (U[size_t(lastSpan)] == U[size_t(lastSpan + 1)])
            --lastSpan;
        std::uniform_real_distribution<double> ud(d.first, d.last);
        for (int k = 0; k < 50; ++k) {
            double u = k == 0 ? d.first : (k == 1 ? d.last : ud(rng));
            if (k == 2) // exactly on an interior knot
                u = U[size_t(degree + (count - degree) / 2)];
            const int span = findSpan(degree, U, u);
            QVERIFY(span >= degree && span <= count - 1);
            QVERIFY(U[size_t(span)] <= u && (u < U[size_t(span + 1)] || u == d.last));
            double n[kMaxDegree + 1];
            basisFunctions(span, u, degree, U, n);
            const std::vector<double> all = coxDeBoor(U, degree, u, d.last, lastSpan);
            // Only N[span-degree .. span] can be non-zero at u (checks findSpan too).
            for (int i = 0; i < count; ++i)
                if (i < span - degree || i > span)
                    QCOMPARE(all[size_t(i)], 0.0);
            double sum = 0.0;
            for (int j = 0; j <= degree; ++j) {
                QVERIFY2(n[j] >= -1e-15, qPrintable(QString("N = %1").arg(n[j])));
                sum += n[j];
                const double ref = all[size_t(span - degree + j)];
                QVERIFY2(
                    std::abs(n[j] - ref) < 1e-12,
                    qPrintable(QString("N[%1] = %2, Cox-de Boor %3").arg(j).arg(n[j]).arg(ref)));
            }
            QVERIFY2(std::abs(sum - 1.0) < 1e-13,
                     qPrintable(QString("sum %1").arg(sum, 0, 'g', 17)));
            // Row 0 of the derivative routine equals the plain basis functions.
            double ders[3 * (kMaxDegree + 1)];
            basisFunctionDerivatives(span, u, degree, 2, U, ders);
            double dsum1 = 0.0, dsum2 = 0.0;
            for (int j = 0; j <= degree; ++j) {
                QVERIFY(std::abs(ders[j] - n[j]) < 1e-14);
                dsum1 += ders[(degree + 1) + j];
                dsum2 += ders[2 * (degree + 1) + j];
            }
            // Derivatives of a partition of unity sum to zero.
            QVERIFY2(std::abs(dsum1) < 1e-9 * std::pow(double(degree) + 1.0, 2.0),
                     qPrintable(QString("sum N' = %1").arg(dsum1)));
            QVERIFY2(std::abs(dsum2) < 1e-7 * std::pow(double(degree) + 1.0, 4.0),
                     qPrintable(QString("sum N'' = %1").arg(dsum2)));
        }
    }
}

void TestNurbsBasis::derivativesMatchFiniteDifferences_data() {
    QTest::addColumn<int>("degree");
    for (int p = 1; p <= kMaxDegree; ++p)
        QTest::addRow("p%d", p) << p;
}

void TestNurbsBasis::derivativesMatchFiniteDifferences() {
    QFETCH(int, degree);
    const int p = degree;
    std::mt19937 rng(77u + unsigned(p));
    const int order = std::min(p, 3);
    for (int trial = 0; trial < 30; ++trial) {
        const int count = p + 1 + int(rng() % 8);
        const std::vector<double> U = kwtest::randomKnots(rng, p, count, std::max(1, p - 1));
        double width = 0.0;
        const double u = kwtest::randomInSpan(rng, U, p, 0.1, width);
        const double h = 1e-4 * width;
        const int span = findSpan(p, U, u);
        QCOMPARE(findSpan(p, U, u - h), span);
        QCOMPARE(findSpan(p, U, u + h), span);
        double d0[4 * (kMaxDegree + 1)], dm[4 * (kMaxDegree + 1)], dp[4 * (kMaxDegree + 1)];
        basisFunctionDerivatives(span, u, p, order, U, d0);
        basisFunctionDerivatives(span, u - h, p, order, U, dm);
        basisFunctionDerivatives(span, u + h, p, order, U, dp);
        for (int k = 1; k <= order; ++k) {
            double scale = 0.0;
            for (int j = 0; j <= p; ++j)
                scale = std::max(scale, std::abs(d0[k * (p + 1) + j]));
            for (int j = 0; j <= p; ++j) {
                // Central difference of the (k-1)-th derivative.
                const double fd = (dp[(k - 1) * (p + 1) + j] - dm[(k - 1) * (p + 1) + j]) / (2 * h);
                const double an = d0[k * (p + 1) + j];
                QVERIFY2(std::abs(fd - an) <= 1e-5 * (1.0 + scale),
                         qPrintable(QString("p=%1 k=%2 j=%3 analytic %4 fd %5")
                                        .arg(p)
                                        .arg(k)
                                        .arg(j)
                                        .arg(an)
                                        .arg(fd)));
            }
        }
    }
}

void TestNurbsBasis::derivativesAboveDegreeAreZero() {
    const std::vector<double> U = {0, 0, 0.3, 1, 1};
    double d[4 * 2];
    std::fill(std::begin(d), std::end(d), 42.0);
    basisFunctionDerivatives(1, 0.1, 1, 3, U, d);
    QCOMPARE(d[0], 1.0 - 0.1 / 0.3);
    QCOMPARE(d[1], 0.1 / 0.3);
    QCOMPARE(d[2], -1.0 / 0.3);
    QCOMPARE(d[3], 1.0 / 0.3);
    for (int k = 4; k < 8; ++k)
        QCOMPARE(d[k], 0.0);
}

QTEST_APPLESS_MAIN(TestNurbsBasis)
#include "tst_nurbs_basis.moc"
