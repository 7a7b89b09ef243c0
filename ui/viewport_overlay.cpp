// Viewport overlays drawn with QPainter over the rendered frame (selection highlight, control
// nets of the selected surfaces, ground grid, axis indicator, the tools' overlays).
#include "model/nurbs/trim.h"
#include "ui/view_surface.h"
#include "ui/viewport.h"

#include <QPainter>
#include <algorithm>
#include <cmath>

namespace kw {

namespace {

/// The outline of a surface in 3D: its trim loops mapped through S(u, v) when it has any,
/// else the four domain edges, each as a polyline.
std::vector<std::vector<glm::dvec3>> outline(const Surface& s) {
    std::vector<std::vector<glm::dvec3>> lines;
    const NurbsSurface& g = s.geometry;
    if (!s.trims.empty()) {
        const TrimRegion region = makeTrimRegion(s.trims, trimTolerance(g, 1e-3));
        for (const TrimPolygon& poly : region.loops) {
            std::vector<glm::dvec3> line;
            for (const glm::dvec2& uv : poly)
                line.push_back(surfacePoint(g, uv.x, uv.y));
            if (!line.empty())
                line.push_back(line.front());
            lines.push_back(std::move(line));
        }
        return lines;
    }
    const Interval du = surfaceDomainU(g), dv = surfaceDomainV(g);
    const int n = 48;
    for (int edge = 0; edge < 4; ++edge) {
        std::vector<glm::dvec3> line;
        for (int k = 0; k <= n; ++k) {
            const double t = double(k) / n;
            const double u =
                edge < 2 ? du.first + t * (du.last - du.first) : (edge == 2 ? du.first : du.last);
            const double v =
                edge >= 2 ? dv.first + t * (dv.last - dv.first) : (edge == 0 ? dv.first : dv.last);
            line.push_back(surfacePoint(g, u, v));
        }
        lines.push_back(std::move(line));
    }
    return lines;
}

void drawPolyline3(QPainter& p, const ViewProjection& view, const std::vector<glm::dvec3>& line) {
    QPolygonF poly;
    for (const glm::dvec3& x : line) {
        const auto px = view.project(x);
        if (!px) { // behind the eye: break the line there
            if (poly.size() > 1)
                p.drawPolyline(poly);
            poly.clear();
            continue;
        }
        poly << *px;
    }
    if (poly.size() > 1)
        p.drawPolyline(poly);
}

/// The parts of a polyline on the kept side of every section plane (as the renderer cuts the
/// surfaces and its lines): each segment clipped to the kept half-spaces (Liang-Barsky on
/// one parameter), consecutive kept parts joined.
std::vector<std::vector<glm::dvec3>> keptPieces(const std::vector<glm::dvec3>& line,
                                                const std::vector<SectionPlane>& planes) {
    if (planes.empty())
        return {line};
    std::vector<std::vector<glm::dvec3>> pieces;
    std::vector<glm::dvec3> piece;
    const auto flush = [&] {
        if (piece.size() > 1)
            pieces.push_back(std::move(piece));
        piece.clear();
    };
    for (size_t k = 0; k + 1 < line.size(); ++k) {
        const glm::dvec3 a = line[k], b = line[k + 1];
        double t0 = 0.0, t1 = 1.0;
        for (const SectionPlane& plane : planes) {
            const glm::dvec3 n = plane.removedSide();
            const double da = glm::dot(n, a - plane.position), db = glm::dot(n, b - plane.position);
            if (da > 0.0 && db > 0.0) {
                t0 = 1.0, t1 = 0.0; // wholly removed
                break;
            }
            if (da > 0.0)
                t0 = std::max(t0, da / (da - db));
            else if (db > 0.0)
                t1 = std::min(t1, da / (da - db));
        }
        if (t0 >= t1) {
            flush();
            continue;
        }
        const glm::dvec3 from = a + t0 * (b - a), to = a + t1 * (b - a);
        if (piece.empty() || t0 > 0.0) {
            flush();
            piece.push_back(from);
        }
        piece.push_back(to);
        if (t1 < 1.0)
            flush();
    }
    flush();
    return pieces;
}

bool kept(const glm::dvec3& x, const std::vector<SectionPlane>& planes) {
    for (const SectionPlane& plane : planes)
        if (glm::dot(plane.removedSide(), x - plane.position) > 0.0)
            return false;
    return true;
}

} // namespace

void Viewport::drawSelection(QPainter& p) {
    const std::vector<ControlPointRef>& refs = m_selection->controlPoints();
    // QPainter after raw GL: it sets up its own state; the renderer resets what it needs.
    p.setRenderHint(QPainter::Antialiasing);
    const ViewProjection view = viewProjection();
    drawOverlays(p, view);
    p.setPen(QPen(QColor(255, 80, 40), 2.0));
    p.setBrush(Qt::NoBrush);
    for (const ControlPointRef& r : refs) {
        const Surface* s = m_doc->surface(r.surface);
        if (!s)
            continue;
        if (const auto px = view.project(s->geometry.points[size_t(s->geometry.index(r.i, r.j))]))
            p.drawRect(QRectF(*px - QPointF(5, 5), QSizeF(10, 10)));
    }
    m_tools.paint(p);
}

void Viewport::drawOverlays(QPainter& p, const ViewProjection& view) {
    if (m_grid) {
        // Ground grid in the z = 0 plane around the target, spacing a power of ten.
        const Camera& c = m_camera.camera();
        const double d = glm::length(c.eye - c.target);
        const double step = std::pow(10.0, std::floor(std::log10(std::max(d, 1e-9) / 4.0)));
        const glm::dvec3 o(std::round(c.target.x / step) * step,
                           std::round(c.target.y / step) * step, 0.0);
        const int n = 20;
        for (int k = -n; k <= n; ++k) {
            p.setPen(QPen(k == 0 ? QColor(150, 150, 160, 170) : QColor(120, 120, 130, 90), 1.0));
            drawPolyline3(
                p, view,
                {o + glm::dvec3(k * step, -n * step, 0), o + glm::dvec3(k * step, n * step, 0)});
            drawPolyline3(
                p, view,
                {o + glm::dvec3(-n * step, k * step, 0), o + glm::dvec3(n * step, k * step, 0)});
        }
    }
    // Selected surfaces: outlined.
    // Like the surfaces, they are cut by the section planes.
    const std::vector<SectionPlane>& planes = m_view.options.sections;
    const auto drawCut = [&](const std::vector<glm::dvec3>& line) {
        for (const std::vector<glm::dvec3>& piece : keptPieces(line, planes))
            drawPolyline3(p, view, piece);
    };
    const std::vector<SurfaceId> selected = shownSurfaces(true);
    p.setPen(QPen(QColor(255, 170, 40), 2.0));
    for (SurfaceId id : selected)
        if (const Surface* s = m_doc->surface(id))
            for (const auto& line : outline(*s))
                drawCut(line);
    // Control nets of the selected surfaces (the renderer draws them all when asked to).
    if (m_view.options.controlNet && !m_view.netForAll) {
        for (SurfaceId id : selected) {
            const Surface* s = m_doc->surface(id);
            if (!s)
                continue;
            const NurbsSurface& g = s->geometry;
            p.setPen(QPen(QColor(230, 230, 240, 200), 1.0));
            for (int j = 0; j < g.countV; ++j) {
                std::vector<glm::dvec3> row;
                for (int i = 0; i < g.countU; ++i)
                    row.push_back(g.points[size_t(g.index(i, j))]);
                drawCut(row);
            }
            for (int i = 0; i < g.countU; ++i) {
                std::vector<glm::dvec3> col;
                for (int j = 0; j < g.countV; ++j)
                    col.push_back(g.points[size_t(g.index(i, j))]);
                drawCut(col);
            }
            p.setPen(Qt::NoPen);
            p.setBrush(QColor(250, 250, 255));
            for (const glm::dvec3& x : g.points)
                if (const auto px = view.project(x); px && kept(x, planes))
                    p.drawEllipse(*px, 2.5, 2.5);
            p.setBrush(Qt::NoBrush);
        }
    }
    if (m_axes) {
        // Axis indicator: the world axes as the camera sees them, bottom left. Its red is
        // pinker than the picked-point marks so the two are told apart (tests count those).
        const Camera& c = m_camera.camera();
        const glm::dvec3 f = glm::normalize(c.target - c.eye);
        const glm::dvec3 r = glm::normalize(glm::cross(f, c.up));
        const glm::dvec3 u = glm::cross(r, f);
        const QPointF o(34, height() - 34);
        static const QColor colors[3] = {QColor(235, 95, 115), QColor(90, 200, 90),
                                         QColor(90, 130, 240)};
        static const char* const names[3] = {"x", "y", "z"};
        for (int k = 0; k < 3; ++k) {
            glm::dvec3 a(0.0);
            a[k] = 1.0;
            const QPointF tip = o + 24.0 * QPointF(glm::dot(a, r), -glm::dot(a, u));
            p.setPen(QPen(colors[k], 2.0));
            p.drawLine(o, tip);
            p.drawText(tip + QPointF(3, 4), QLatin1String(names[k]));
        }
    }
}

} // namespace kw
