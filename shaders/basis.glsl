// Non-zero B-spline basis functions and first derivatives for one knot span (The NURBS Book
// A2.2 and A2.3, order 1; order 2 too when KW_SECOND_ORDER is defined), reading a span table row (kw::packSpanTable) instead of the knot
// vector: no search, no division. Included once per direction with BASIS_FN (function name),
// BASIS_P (degree) and BASIS_TEXEL(x, row) (texel x of span-table row `row`) defined.
//   row layout: U[k+1-j] (j=1..p) | U[k+j] (j=1..p) | 1/(U[k+r+1]-U[k+1-j+r]) (j=1..p, r<j)

#ifdef KW_SECOND_ORDER
void BASIS_FN(int row, float u, out float N[BASIS_P + 1], out float dN[BASIS_P + 1],
              out float d2N[BASIS_P + 1]) {
#else
void BASIS_FN(int row, float u, out float N[BASIS_P + 1], out float dN[BASIS_P + 1]) {
#endif
    const int kFloats = 2 * BASIS_P + BASIS_P * (BASIS_P + 1) / 2;
    const int kTexels = (kFloats + 3) / 4;
    float t[kTexels * 4];
    for (int x = 0; x < kTexels; ++x) {
        vec4 c = BASIS_TEXEL(x, row);
        t[4 * x] = c.x;
        t[4 * x + 1] = c.y;
        t[4 * x + 2] = c.z;
        t[4 * x + 3] = c.w;
    }
    // Degree p-1 values, kept for the derivative (A2.3: ders[1] from ndu[.][p-1]).
    float lower[BASIS_P + 1];
#ifdef KW_SECOND_ORDER
    float lower2[BASIS_P + 1]; // degree p-2 values (only p >= 2 uses them)
    lower2[0] = 1.0;
#endif
    N[0] = 1.0;
    int inv = 2 * BASIS_P; // index of 1/(right[r+1]+left[j-r]) for the current (j, r)
    for (int j = 1; j <= BASIS_P; ++j) {
        float saved = 0.0;
        for (int r = 0; r < j; ++r) {
            if (j == BASIS_P)
                lower[r] = N[r];
#ifdef KW_SECOND_ORDER
            if (j == BASIS_P - 1)
                lower2[r] = N[r];
#endif
            // right[r+1] = U[k+r+1] - u and left[j-r] = u - U[k+1-j+r], straight from the row
            // (no left/right arrays: Mesa 22.3 llvmpipe miscompiled them in one shader).
            float temp = N[r] * t[inv + r];
            N[r] = saved + (t[BASIS_P + r] - u) * temp;
            saved = (u - t[j - r - 1]) * temp;
        }
        N[j] = saved;
        if (j < BASIS_P)
            inv += j;
    }
    // N'_{k-p+r} = p (N_{r-1,p-1}/(U[k+r]-U[k+r-p]) - N_{r,p-1}/(U[k+r+1]-U[k+r+1-p])), eq. 3.4
    const float p = float(BASIS_P);
    dN[0] = -p * lower[0] * t[inv];
    for (int r = 1; r < BASIS_P; ++r)
        dN[r] = p * (lower[r - 1] * t[inv + r - 1] - lower[r] * t[inv + r]);
    dN[BASIS_P] = p * lower[BASIS_P - 1] * t[inv + BASIS_P - 1];
#ifdef KW_SECOND_ORDER
    // Eq. 2.7 differentiated once more (A2.3 with k = 2): the degree p-1 derivatives d1 from the
    // degree p-2 values and the reciprocals of row j = p-1 (they start at 2p + (p-1)(p-2)/2),
    // then N'' = p (d1[r-1] / (U[k+r]-U[k+r-p]) - d1[r] / (U[k+r+1]-U[k+r+1-p])).
    for (int r = 0; r <= BASIS_P; ++r)
        d2N[r] = 0.0;
#if BASIS_P >= 2
    {
        const int invLow = 2 * BASIS_P + (BASIS_P - 1) * (BASIS_P - 2) / 2;
        const float q = float(BASIS_P - 1);
        float d1[BASIS_P + 1];
        d1[0] = -q * lower2[0] * t[invLow];
        for (int r = 1; r < BASIS_P - 1; ++r)
            d1[r] = q * (lower2[r - 1] * t[invLow + r - 1] - lower2[r] * t[invLow + r]);
        d1[BASIS_P - 1] = q * lower2[BASIS_P - 2] * t[invLow + BASIS_P - 2];
        d2N[0] = -p * d1[0] * t[inv];
        for (int r = 1; r < BASIS_P; ++r)
            d2N[r] = p * (d1[r - 1] * t[inv + r - 1] - d1[r] * t[inv + r]);
        d2N[BASIS_P] = p * d1[BASIS_P - 1] * t[inv + BASIS_P - 1];
    }
#endif // BASIS_P >= 2
#endif // KW_SECOND_ORDER
}
