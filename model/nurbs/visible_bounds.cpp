// Trim parameter boxes and bounds of the exact trimmed geometry, cached by content.
#include "model/nurbs/visible_bounds.h"

#include "model/nurbs/trim.h"

#include <algorithm>
#include <cstring>
#include <mutex>
#include <unordered_map>

namespace kw {
namespace {

constexpr int kGrid = 33;

/// FNV-1a over the bytes of what the bounds depend on.
struct ContentHash {
    std::uint64_t h = 1469598103934665603ull;
    void bytes(const void* p, size_t n) {
        const auto* c = static_cast<const unsigned char*>(p);
        for (size_t k = 0; k < n; ++k)
            h = (h ^ c[k]) * 1099511628211ull;
    }
    template <class T> void values(const std::vector<T>& v) {
        const size_t n = v.size();
        bytes(&n, sizeof n);
        if (n)
            bytes(v.data(), n * sizeof(T));
    }
};

std::uint64_t contentHash(const Surface& s) {
    ContentHash c;
    const NurbsSurface& g = s.geometry;
    const int dims[4] = {g.degreeU, g.degreeV, g.countU, g.countV};
    c.bytes(dims, sizeof dims);
    c.values(g.knotsU);
    c.values(g.knotsV);
    c.values(g.points);
    c.values(g.weights);
    for (const TrimLoop& loop : s.trims)
        for (const NurbsCurve2& curve : loop.curves) {
            c.bytes(&curve.degree, sizeof curve.degree);
            c.values(curve.knots);
            c.values(curve.points);
            c.values(curve.weights);
        }
    return c.h;
}

struct CachedBounds {
    bool ok = false;
    glm::dvec3 lo{0.0}, hi{0.0};
};

void grow(bool& any, glm::dvec3& lo, glm::dvec3& hi, const glm::dvec3& p) {
    lo = any ? glm::min(lo, p) : p;
    hi = any ? glm::max(hi, p) : p;
    any = true;
}

} // namespace

ParameterBox trimParameterBox(const Surface& surface) {
    const ParameterBox domain{surfaceDomainU(surface.geometry), surfaceDomainV(surface.geometry)};
    bool any = false;
    glm::dvec2 lo(0.0), hi(0.0);
    for (const TrimLoop& loop : surface.trims)
        for (const NurbsCurve2& c : loop.curves) {
            if (!checkNurbsCurve(c))
                continue;
            for (const glm::dvec2& p : c.points) {
                lo = any ? glm::min(lo, p) : p;
                hi = any ? glm::max(hi, p) : p;
                any = true;
            }
        }
    if (!any)
        return domain;
    ParameterBox box;
    box.u = {std::clamp(lo.x, domain.u.first, domain.u.last),
             std::clamp(hi.x, domain.u.first, domain.u.last)};
    box.v = {std::clamp(lo.y, domain.v.first, domain.v.last),
             std::clamp(hi.y, domain.v.first, domain.v.last)};
    // Loops wholly outside the domain keep nothing of it; draw the domain rather than nothing.
    if (!(box.u.first < box.u.last) || !(box.v.first < box.v.last))
        return domain;
    return box;
}

bool surfaceVisibleBounds(const Surface& surface, glm::dvec3& lo, glm::dvec3& hi) {
    const NurbsSurface& g = surface.geometry;
    if (!checkNurbsSurface(g))
        return false;
    const ParameterBox box = trimParameterBox(surface);
    const TrimRegion region =
        surface.trims.empty() ? TrimRegion{} : makeTrimRegion(surface.trims, trimTolerance(g));
    bool any = false;
    glm::dvec3 a(0.0), b(0.0);
    // Column by column: one walk of the loops classifies a whole column (the answers of
    // trimRegionContains at each point; this is most of fitCamera's time on imported parts).
    double v[kGrid];
    bool inside[kGrid];
    for (int j = 0; j < kGrid; ++j)
        v[j] = box.v.first + (box.v.last - box.v.first) * j / (kGrid - 1);
    for (int i = 0; i < kGrid; ++i) {
        const double u = box.u.first + (box.u.last - box.u.first) * i / (kGrid - 1);
        trimRegionContainsColumn(region, u, v, kGrid, inside);
        for (int j = 0; j < kGrid; ++j)
            if (inside[j])
                grow(any, a, b, surfacePoint(g, u, v[j]));
    }
    // The loops are where trimmed faces end; a small face may hold no grid point at all.
    const Interval du = surfaceDomainU(g), dv = surfaceDomainV(g);
    for (const TrimPolygon& loop : region.loops)
        for (const glm::dvec2& uv : loop)
            if (uv.x >= du.first && uv.x <= du.last && uv.y >= dv.first && uv.y <= dv.last)
                grow(any, a, b, surfacePoint(g, uv.x, uv.y));
    if (!any)
        return false;
    lo = a;
    hi = b;
    return true;
}

bool sceneVisibleBounds(const Scene& scene, glm::dvec3& lo, glm::dvec3& hi, bool shownOnly) {
    static std::mutex mutex;
    static std::unordered_map<std::uint64_t, CachedBounds> cache;
    bool any = false;
    for (const Surface& s : scene.surfaces) {
        if (shownOnly && s.hidden)
            continue;
        const std::uint64_t key = contentHash(s);
        CachedBounds entry;
        bool found = false;
        {
            const std::lock_guard<std::mutex> lock(mutex);
            const auto it = cache.find(key);
            if (it != cache.end()) {
                entry = it->second;
                found = true;
            }
        }
        if (!found) {
            entry.ok = surfaceVisibleBounds(s, entry.lo, entry.hi);
            const std::lock_guard<std::mutex> lock(mutex);
            if (cache.size() > 100000) // edits leave old versions behind: start over
                cache.clear();
            cache[key] = entry;
        }
        if (!entry.ok)
            continue;
        grow(any, lo, hi, entry.lo);
        grow(any, lo, hi, entry.hi);
    }
    return any;
}

} // namespace kw
