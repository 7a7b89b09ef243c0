// B-spline basis functions: span search, values and derivatives (The NURBS Book, A2.1-A2.3).
#include "model/nurbs/nurbs.h"

#include <algorithm>
#include <cmath>

namespace kw {

double grevilleAbscissa(const std::vector<double>& knots, int degree, int i) {
    double sum = 0.0;
    for (int k = 1; k <= degree; ++k)
        sum += knots[size_t(i + k)];
    return sum / double(degree);
}

Interval knotDomain(const std::vector<double>& knots, int degree) {
    // Domain [u_p, u_{m-p}] with m = knots.size() - 1. A knot vector too short for the degree
    // (invalid, see checkKnotVector) yields its own first and last knot, or [0, 0] if empty.
    if (knots.empty())
        return {0.0, 0.0};
    const size_t m = knots.size() - 1;
    if (degree < 0 || 2 * size_t(degree) > m)
        return {knots.front(), knots.back()};
    return {knots[size_t(degree)], knots[m - size_t(degree)]};
}

// The NURBS Book, A2.1 (FindSpan): binary search for k with knots[k] <= u < knots[k+1],
// restricted to the spans [degree, n] of the domain. u below the domain (or NaN) maps to the
// first non-empty span, u at or above the last knot of the domain to the last non-empty span.
int findSpan(int degree, const std::vector<double>& knots, double u) {
    const int n = int(knots.size()) - degree - 2; // index of the last control point
    if (degree < 0 || n < degree)
        return std::max(degree, 0); // invalid knot vector: any in-range answer, never a crash
    if (u >= knots[size_t(n + 1)]) {
        int k = n;
        while (k > degree && knots[size_t(k)] == knots[size_t(k + 1)])
            --k;
        return k;
    }
    if (!(u > knots[size_t(degree)])) { // also catches NaN
        int k = degree;
        while (k < n && knots[size_t(k)] == knots[size_t(k + 1)])
            ++k;
        return k;
    }
    int low = degree;
    int high = n + 1;
    int mid = (low + high) / 2;
    while (u < knots[size_t(mid)] || u >= knots[size_t(mid + 1)]) {
        if (u < knots[size_t(mid)])
            high = mid;
        else
            low = mid;
        mid = (low + high) / 2;
    }
    return mid;
}

int nonEmptySpanCount(int degree, const std::vector<double>& knots) {
    // Spans k in [degree, n], n = knots.size() - degree - 2 (the last control point).
    int count = 0;
    for (int k = std::max(degree, 0); k + degree + 2 <= int(knots.size()); ++k)
        count += knots[size_t(k)] < knots[size_t(k + 1)];
    return count;
}

int surfaceSpanCount(const NurbsSurface& s) {
    return nonEmptySpanCount(s.degreeU, s.knotsU) * nonEmptySpanCount(s.degreeV, s.knotsV);
}

// The NURBS Book, A2.2 (BasisFuns): the triangular scheme of the Cox-de Boor recurrence,
// with left[j] = u - u_{span+1-j} and right[j] = u_{span+j} - u.
void basisFunctions(int span, double u, int degree, const std::vector<double>& knots, double* out) {
    double left[kMaxDegree + 1];
    double right[kMaxDegree + 1];
    out[0] = 1.0;
    for (int j = 1; j <= degree; ++j) {
        left[j] = u - knots[size_t(span + 1 - j)];
        right[j] = knots[size_t(span + j)] - u;
        double saved = 0.0;
        for (int r = 0; r < j; ++r) {
            const double temp = out[r] / (right[r + 1] + left[j - r]);
            out[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        out[j] = saved;
    }
}

// The NURBS Book, A2.3 (DersBasisFuns): ndu holds the basis functions (upper triangle) and the
// knot differences (lower triangle); a[2][] holds the coefficients a_{k,j} of Eq. 2.9 in two
// alternating rows. Everything lives on the stack (degree <= kMaxDegree).
void basisFunctionDerivatives(int span, double u, int degree, int order,
                              const std::vector<double>& knots, double* out) {
    const int p = degree;
    double ndu[kMaxDegree + 1][kMaxDegree + 1];
    double a[2][kMaxDegree + 1];
    double left[kMaxDegree + 1];
    double right[kMaxDegree + 1];
    ndu[0][0] = 1.0;
    for (int j = 1; j <= p; ++j) {
        left[j] = u - knots[size_t(span + 1 - j)];
        right[j] = knots[size_t(span + j)] - u;
        double saved = 0.0;
        for (int r = 0; r < j; ++r) {
            ndu[j][r] = right[r + 1] + left[j - r]; // lower triangle: knot differences
            const double temp = ndu[r][j - 1] / ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp; // upper triangle: basis functions
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    for (int j = 0; j <= p; ++j)
        out[j] = ndu[j][p];
    const int top = std::min(order, p);
    for (int r = 0; r <= p; ++r) {
        int s1 = 0;
        int s2 = 1;
        a[0][0] = 1.0;
        for (int k = 1; k <= top; ++k) {
            double d = 0.0;
            const int rk = r - k;
            const int pk = p - k;
            if (r >= k) {
                a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
                d = a[s2][0] * ndu[rk][pk];
            }
            const int j1 = rk >= -1 ? 1 : -rk;
            const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
            for (int j = j1; j <= j2; ++j) {
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
                d += a[s2][j] * ndu[rk + j][pk];
            }
            if (r <= pk) {
                a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
                d += a[s2][k] * ndu[r][pk];
            }
            out[k * (p + 1) + r] = d;
            std::swap(s1, s2);
        }
    }
    // Multiply by the factors p! / (p - k)! of Eq. 2.9.
    double factor = p;
    for (int k = 1; k <= top; ++k) {
        for (int j = 0; j <= p; ++j)
            out[k * (p + 1) + j] *= factor;
        factor *= p - k;
    }
    for (int k = top + 1; k <= order; ++k)
        for (int j = 0; j <= p; ++j)
            out[k * (p + 1) + j] = 0.0;
}

} // namespace kw
