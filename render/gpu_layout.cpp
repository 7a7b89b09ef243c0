// CPU-side GPU layouts: homogeneous control points, span tables, base polygon, tessellation.
#include "render/gpu_layout.h"

#include <algorithm>
#include <cmath>

namespace kw {

glm::dvec3 controlOrigin(const NurbsSurface& s) {
    glm::dvec3 lo, hi;
    surfaceControlBounds(s, lo, hi);
    // Rounded to float so that the shader's float uOrigin is exactly this value.
    return glm::dvec3(glm::vec3(0.5 * (lo + hi)));
}

std::vector<glm::vec4> packControlPoints(const NurbsSurface& s, const glm::dvec3& origin) {
    std::vector<glm::vec4> out(s.points.size());
    for (size_t k = 0; k < s.points.size(); ++k) {
        const double w = s.weights[k];
        out[k] = glm::vec4(glm::dvec4((s.points[k] - origin) * w, w));
    }
    return out;
}

std::vector<glm::vec4> packSpanTable(const std::vector<double>& U, int p, int count) {
    const int rows = count - p;
    const int texels = spanTableTexels(p);
    std::vector<float> row(size_t(texels) * 4);
    std::vector<glm::vec4> out(size_t(rows) * texels, glm::vec4(0.0f));
    for (int r = 0; r < rows; ++r) {
        const int k = r + p;
        std::fill(row.begin(), row.end(), 0.0f);
        int f = 0;
        for (int j = 1; j <= p; ++j)
            row[f++] = float(U[k + 1 - j]);
        for (int j = 1; j <= p; ++j)
            row[f++] = float(U[k + j]);
        for (int j = 1; j <= p; ++j)
            for (int q = 0; q < j; ++q) {
                const double d = U[k + q + 1] - U[k + 1 - j + q];
                row[f++] = d > 0.0 ? float(1.0 / d) : 0.0f; // 0 only in rows of empty spans
            }
        for (int t = 0; t < texels; ++t)
            out[size_t(r) * texels + t] =
                glm::vec4(row[4 * t], row[4 * t + 1], row[4 * t + 2], row[4 * t + 3]);
    }
    return out;
}

std::vector<double> cellBreaks(const std::vector<double>& knots, int n, Interval range) {
    const double len = range.last - range.first;
    std::vector<double> b;
    for (int c = 0; c <= n; ++c)
        b.push_back(c == n ? range.last : range.first + len * double(c) / double(n));
    for (double k : knots)
        if (k > range.first && k < range.last)
            b.push_back(k);
    std::sort(b.begin(), b.end());
    // Keep knots exactly: drop a uniform break that nearly coincides with a kept value.
    std::vector<double> out;
    const double eps = 1e-9 * len;
    for (double x : b) {
        const bool isKnot = std::find(knots.begin(), knots.end(), x) != knots.end();
        if (!out.empty() && x - out.back() <= eps) {
            if (isKnot && out.size() > 1)
                out.back() = x;
            continue;
        }
        out.push_back(x);
    }
    out.back() = range.last;
    return out;
}

namespace {

std::vector<int> cellSpans(const std::vector<double>& breaks, const std::vector<double>& knots,
                           int degree) {
    std::vector<int> spans;
    for (size_t c = 0; c + 1 < breaks.size(); ++c)
        spans.push_back(findSpan(degree, knots, 0.5 * (breaks[c] + breaks[c + 1])));
    return spans;
}

// Vertex (gu, gv): exact point, (u, v), and the span of the cell it is the lower-left corner of.
void setVertex(BasePolygon& poly, const NurbsSurface& s, int gu, int gv) {
    BaseVertex& vx = poly.vertices[size_t(gv * poly.nodesU() + gu)];
    const double u = poly.breaksU[size_t(gu)], v = poly.breaksV[size_t(gv)];
    const int cu = std::min(gu, poly.cellsU() - 1), cv = std::min(gv, poly.cellsV() - 1);
    vx.position = glm::vec3(surfacePoint(s, u, v));
    vx.uv = glm::vec2(float(u), float(v));
    vx.span = glm::ivec2(poly.spanU[size_t(cu)], poly.spanV[size_t(cv)]);
    vx.spanScale = spanScale(s, vx.span.x, vx.span.y);
}

} // namespace

float spanScale(const NurbsSurface& s, int ku, int kv) {
    glm::dvec3 lo = s.points[size_t(s.index(ku - s.degreeU, kv - s.degreeV))], hi = lo;
    for (int j = kv - s.degreeV; j <= kv; ++j)
        for (int i = ku - s.degreeU; i <= ku; ++i) {
            lo = glm::min(lo, s.points[size_t(s.index(i, j))]);
            hi = glm::max(hi, s.points[size_t(s.index(i, j))]);
        }
    return float(glm::length(hi - lo));
}

BasePolygon buildBasePolygon(const NurbsSurface& s, int nu, int nv) {
    return buildBasePolygon(s, ParameterBox{surfaceDomainU(s), surfaceDomainV(s)}, nu, nv);
}

BasePolygon buildBasePolygon(const NurbsSurface& s, const ParameterBox& box, int nu, int nv) {
    return buildBasePolygon(s, box, PolygonCut{nu, nv, {}, {}});
}

BasePolygon buildBasePolygon(const NurbsSurface& s, const ParameterBox& box,
                             const PolygonCut& cut) {
    BasePolygon poly;
    const bool given = cut.breaksU.size() >= 2 && cut.breaksV.size() >= 2;
    poly.breaksU = given ? cut.breaksU : cellBreaks(s.knotsU, std::max(cut.nu, 1), box.u);
    poly.breaksV = given ? cut.breaksV : cellBreaks(s.knotsV, std::max(cut.nv, 1), box.v);
    poly.spanU = cellSpans(poly.breaksU, s.knotsU, s.degreeU);
    poly.spanV = cellSpans(poly.breaksV, s.knotsV, s.degreeV);
    const int nodesV = int(poly.breaksV.size());
    poly.vertices.resize(size_t(poly.nodesU()) * size_t(nodesV));
    for (int gv = 0; gv < nodesV; ++gv)
        for (int gu = 0; gu < poly.nodesU(); ++gu)
            setVertex(poly, s, gu, gv);
    return poly;
}

bool updateBasePolygon(BasePolygon& poly, const NurbsSurface& s, int i0, int i1, int j0, int j1,
                       int& first, int& last) {
    // N_{i,p} is non-zero on [U_i, U_{i+p+1}) (The NURBS Book P2.1).
    const double ua = s.knotsU[size_t(i0)], ub = s.knotsU[size_t(i1 + s.degreeU + 1)];
    const double va = s.knotsV[size_t(j0)], vb = s.knotsV[size_t(j1 + s.degreeV + 1)];
    auto nodeRange = [](const std::vector<double>& b, double a, double e, int& g0, int& g1) {
        g0 = int(std::lower_bound(b.begin(), b.end(), a) - b.begin());
        g1 = int(std::upper_bound(b.begin(), b.end(), e) - b.begin()) - 1;
        return g0 <= g1;
    };
    int gu0, gu1, gv0, gv1;
    if (!nodeRange(poly.breaksU, ua, ub, gu0, gu1) || !nodeRange(poly.breaksV, va, vb, gv0, gv1))
        return false;
    // The nodes inside the support move; the span scale changes for the cells there, whose
    // lower-left corners reach one node further down and left.
    gu0 = std::max(gu0 - 1, 0);
    gv0 = std::max(gv0 - 1, 0);
    for (int gv = gv0; gv <= gv1; ++gv)
        for (int gu = gu0; gu <= gu1; ++gu)
            setVertex(poly, s, gu, gv);
    first = gv0 * poly.nodesU() + gu0;
    last = gv1 * poly.nodesU() + gu1;
    return true;
}

std::vector<unsigned> basePolygonTriangles(const BasePolygon& poly) {
    std::vector<unsigned> idx;
    idx.reserve(size_t(poly.cellCount()) * 6);
    const unsigned row = unsigned(poly.nodesU());
    for (unsigned cv = 0; cv < unsigned(poly.cellsV()); ++cv)
        for (unsigned cu = 0; cu < unsigned(poly.cellsU()); ++cu) {
            const unsigned ll = cv * row + cu, lr = ll + 1, ul = ll + row, ur = ul + 1;
            idx.insert(idx.end(), {ll, lr, ur, ll, ur, ul});
        }
    return idx;
}

std::vector<unsigned> basePolygonOutlines(const BasePolygon& poly) {
    std::vector<unsigned> idx;
    idx.reserve(size_t(poly.cellCount()) * 8);
    const unsigned row = unsigned(poly.nodesU());
    for (unsigned cv = 0; cv < unsigned(poly.cellsV()); ++cv)
        for (unsigned cu = 0; cu < unsigned(poly.cellsU()); ++cu) {
            const unsigned ll = cv * row + cu, lr = ll + 1, ul = ll + row, ur = ul + 1;
            idx.insert(idx.end(), {ll, lr, lr, ur, ur, ul, ul, ll});
        }
    return idx;
}

std::vector<SkirtVertex> skirtVertices(const BasePolygon& poly) {
    std::vector<SkirtVertex> out;
    const int nu = poly.nodesU(), nv = int(poly.breaksV.size());
    if (nu < 2 || nv < 2 || poly.vertices.size() != size_t(nu) * size_t(nv))
        return out;
    const auto side = [&](int g0u, int g0v, int du, int dv, int count, glm::vec2 outward) {
        for (int k = 0; k < count; ++k) {
            const BaseVertex& b = poly.vertices[size_t((g0v + k * dv) * nu + g0u + k * du)];
            out.push_back({b, glm::vec2(0.0f)});
            out.push_back({b, outward});
        }
    };
    side(0, 0, 1, 0, nu, {0.0f, -1.0f});     // bottom, u increasing
    side(nu - 1, 0, 0, 1, nv, {1.0f, 0.0f}); // right, v increasing
    side(0, nv - 1, 1, 0, nu, {0.0f, 1.0f}); // top, u increasing
    side(0, 0, 0, 1, nv, {-1.0f, 0.0f});     // left, v increasing
    return out;
}

void buildSkirt(const BasePolygon& poly, std::vector<SkirtVertex>& vertices,
                std::vector<unsigned>& indices) {
    vertices = skirtVertices(poly);
    indices.clear();
    if (vertices.empty())
        return;
    const unsigned nu = unsigned(poly.nodesU()), nv = unsigned(poly.breaksV.size());
    // Each side's nodes run with increasing u or v, so a segment's first node is the lower-left
    // corner of (or, on the last row and column, repeats the span of) the cell it borders.
    unsigned first = 0;
    for (unsigned count : {nu, nv, nu, nv}) {
        for (unsigned k = 0; k + 1 < count; ++k) {
            const unsigned a = first + 2 * k, aOut = a + 1, b = a + 2, bOut = a + 3;
            indices.insert(indices.end(), {a, b, bOut, a, bOut, aOut});
        }
        first += 2 * count;
    }
    // The wedge between two sides' pushes at each corner: a triangle from the corner's inner
    // copy (the corner cell's span) to the two sides' outer copies.
    const unsigned right = 2 * nu, top = 2 * nu + 2 * nv, left = 4 * nu + 2 * nv;
    const unsigned corners[4][3] = {
        {0, 1, left + 1},                                                       // (0, 0)
        {2 * (nu - 1), 2 * (nu - 1) + 1, right + 1},                            // (last, 0)
        {top + 2 * (nu - 1), top + 2 * (nu - 1) + 1, right + 2 * (nv - 1) + 1}, // (last, last)
        {top, top + 1, left + 2 * (nv - 1) + 1}};                               // (0, last)
    for (const auto& c : corners)
        indices.insert(indices.end(), {c[0], c[1], c[2]});
}

void buildFins(const BasePolygon& poly, const glm::dmat4& viewProjection, const glm::dvec3& eye,
               glm::ivec2 viewport, double pixels, std::vector<SkirtVertex>& vertices,
               std::vector<unsigned>& indices) {
    const int nu = poly.nodesU(), nv = int(poly.breaksV.size());
    if (nu < 2 || nv < 2 || poly.vertices.size() != size_t(nu) * size_t(nv) || viewport.x < 1 ||
        viewport.y < 1)
        return;
    const int cu = nu - 1, cv = nv - 1;
    const auto pos = [&](int node) {
        return glm::dvec3(poly.vertices[size_t(node)].position);
    };
    // Facing of triangle t of cell c (t = 0: ll, lr, ur; t = 1: ll, ur, ul): +1 towards the
    // eye, -1 away, 0 for no area or edge on.
    std::vector<signed char> facing(size_t(cu) * size_t(cv) * 2);
    const auto face = [&](int a, int b, int c) {
        const glm::dvec3 pa = pos(a), n = glm::cross(pos(b) - pa, pos(c) - pa);
        const glm::dvec3 view = pa - eye;
        const double f = glm::dot(n, view);
        if (!(std::abs(f) > 1e-9 * glm::length(n) * glm::length(view)))
            return (signed char)0;
        return f < 0.0 ? (signed char)1 : (signed char)-1;
    };
    for (int j = 0; j < cv; ++j)
        for (int i = 0; i < cu; ++i) {
            const int ll = j * nu + i, lr = ll + 1, ul = ll + nu, ur = ul + 1;
            const size_t c = size_t(j * cu + i) * 2;
            facing[c] = face(ll, lr, ur);
            facing[c + 1] = face(ll, ur, ul);
        }
    const glm::dmat4 inverse = glm::inverse(viewProjection);
    const glm::dvec2 size(viewport);
    const auto fin = [&](int a, int b) {
        const glm::dvec4 ca = viewProjection * glm::dvec4(pos(a), 1.0);
        const glm::dvec4 cb = viewProjection * glm::dvec4(pos(b), 1.0);
        if (!(ca.w > 0.0) || !(cb.w > 0.0))
            return;
        const glm::dvec2 wa = (glm::dvec2(ca) / ca.w * 0.5 + 0.5) * size;
        const glm::dvec2 wb = (glm::dvec2(cb) / cb.w * 0.5 + 0.5) * size;
        const double length = glm::length(wb - wa);
        if (!(length > 1e-3))
            return;
        const glm::dvec2 along = (wb - wa) / length, across(-along.y, along.x);
        // A window position at the clip depth of `c`, back in model space.
        const auto lift = [&](const glm::dvec4& c, const glm::dvec2& w) {
            const glm::dvec2 ndc = w / size * 2.0 - 1.0;
            const glm::dvec4 h = inverse * glm::dvec4(ndc * c.w, c.z, c.w);
            return glm::dvec3(h) / h.w;
        };
        const unsigned first = unsigned(vertices.size());
        for (const auto& [node, clip, window, end] :
             {std::tuple{a, ca, wa, -1.0}, std::tuple{b, cb, wb, 1.0}})
            for (const double side : {1.0, -1.0}) {
                SkirtVertex v{poly.vertices[size_t(node)], glm::vec2(0.0f)};
                v.base.position =
                    glm::vec3(lift(clip, window + pixels * (end * along + side * across)));
                vertices.push_back(v);
            }
        // a+, a-, b+, b-: two triangles from a's copies (a's span, first-vertex provoking).
        indices.insert(indices.end(), {first, first + 1, first + 3, first, first + 3, first + 2});
    };
    const auto flips = [&](size_t t0, size_t t1) {
        return facing[t0] * facing[t1] < 0;
    };
    for (int j = 0; j < cv; ++j)
        for (int i = 0; i < cu; ++i) {
            const int ll = j * nu + i, lr = ll + 1, ul = ll + nu, ur = ul + 1;
            const size_t c = size_t(j * cu + i) * 2;
            if (flips(c, c + 1))
                fin(ll, ur); // the diagonal
            if (j > 0 && flips(c, size_t((j - 1) * cu + i) * 2 + 1))
                fin(ll, lr); // the bottom edge: the cell below's upper triangle
            if (i > 0 && flips(c + 1, size_t(j * cu + i - 1) * 2))
                fin(ll, ul); // the left edge: the cell to the left's lower triangle
        }
}

TessellatedMesh tessellate(const NurbsSurface& s, int nu, int nv) {
    TessellatedMesh m;
    nu = std::max(nu, 1);
    nv = std::max(nv, 1);
    const Interval du = surfaceDomainU(s), dv = surfaceDomainV(s);
    for (int b = 0; b <= nv; ++b)
        for (int a = 0; a <= nu; ++a) {
            const double u = a == nu ? du.last : du.first + (du.last - du.first) * a / nu;
            const double v = b == nv ? dv.last : dv.first + (dv.last - dv.first) * b / nv;
            const SurfaceFrame f = surfaceFrame(s, u, v);
            m.positions.emplace_back(f.point);
            m.normals.emplace_back(f.normal);
            m.uvs.emplace_back(float(u), float(v));
        }
    for (unsigned b = 0; b < unsigned(nv); ++b)
        for (unsigned a = 0; a < unsigned(nu); ++a) {
            const unsigned i = b * unsigned(nu + 1) + a, r = unsigned(nu + 1);
            m.indices.insert(m.indices.end(), {i, i + 1, i + r + 1, i, i + r + 1, i + r});
        }
    return m;
}

} // namespace kw
