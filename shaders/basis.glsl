// Non-zero B-spline basis functions and first derivatives for one knot span (The NURBS Book
// A2.2 and A2.3, order 1), reading a span table row (kw::packSpanTable) instead of the knot
// vector: no search, no division. Included once per direction with BASIS_FN (function name),
// BASIS_P (degree) and BASIS_TEXEL(x, row) (texel x of span-table row `row`) defined.
//   row layout: U[k+1-j] (j=1..p) | U[k+j] (j=1..p) | 1/(U[k+r+1]-U[k+1-j+r]) (j=1..p, r<j)

void BASIS_FN(int row, float u, out float N[BASIS_P + 1], out float dN[BASIS_P + 1]) {
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
    N[0] = 1.0;
    int inv = 2 * BASIS_P; // index of 1/(right[r+1]+left[j-r]) for the current (j, r)
    for (int j = 1; j <= BASIS_P; ++j) {
        float saved = 0.0;
        for (int r = 0; r < j; ++r) {
            if (j == BASIS_P)
                lower[r] = N[r];
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
}
