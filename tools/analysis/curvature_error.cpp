// kw_curvature_error FILE.knot... [--partitions 30,100] [--image OUT.png --surface K]
// Mean curvature from a render mesh, as mesh-based tools compute it, against the exact mean
// curvature of kw::surfaceCurvature: each surface is tessellated on a uniform N x N grid of its
// domain (exact points), H at each interior vertex is the cotangent-Laplacian estimate (Meyer,
// Desbrun, Schroeder and Barr 2003, "Discrete Differential-Geometry Operators for Triangulated
// 2-Manifolds", eq. 8, with barycentric vertex areas) signed by the area-weighted vertex normal
// (oriented like Su x Sv), and compared with exact H at the vertex's (u, v). Errors are
// relative to the model's curvature scale: the 98th percentile of |H| over all its vertices.
// Prints a Markdown table row per file and N; --image writes a side-by-side picture of one
// surface's domain: exact H, then H from each mesh, on the same colour scale.
#include "model/io/knotfile.h"
#include "model/nurbs/nurbs_curvature.h"
#include "render/analysis.h"
#include "render/image_save.h"

#include <QFileInfo>
#include <QGuiApplication>
#include <QImage>
#include <QPainter>
#include <QStringList>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace {

struct Grid {
    int n = 0; // cells per direction
    std::vector<glm::dvec3> p;
    std::vector<double> exactH, meshH;
    std::vector<bool> valid; // interior vertex with a non-degenerate one-ring
    int at(int i, int j) const { return j * (n + 1) + i; }
};

double cotangent(const glm::dvec3& a, const glm::dvec3& b) {
    const double s = glm::length(glm::cross(a, b));
    return s > 0.0 ? glm::dot(a, b) / s : std::numeric_limits<double>::infinity();
}

Grid meshCurvature(const kw::NurbsSurface& g, int n) {
    Grid grid;
    grid.n = n;
    const kw::Interval du = kw::surfaceDomainU(g), dv = kw::surfaceDomainV(g);
    const int side = n + 1;
    grid.p.resize(size_t(side * side));
    grid.exactH.resize(grid.p.size());
    grid.meshH.assign(grid.p.size(), 0.0);
    grid.valid.assign(grid.p.size(), false);
    std::vector<glm::dvec3> normal(grid.p.size(), glm::dvec3(0.0)),
        lap(grid.p.size(), glm::dvec3(0.0));
    std::vector<double> area(grid.p.size(), 0.0);
    std::vector<bool> degenerate(grid.p.size(), false);
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const double u = du.first + (du.last - du.first) * i / n;
            const double v = dv.first + (dv.last - dv.first) * j / n;
            const kw::SurfaceCurvature c = kw::surfaceCurvature(g, u, v);
            grid.p[size_t(grid.at(i, j))] = c.point;
            grid.exactH[size_t(grid.at(i, j))] = c.mean;
        }
    // Two triangles per cell, counter-clockwise in (u, v) so face normals follow Su x Sv.
    const auto triangle = [&](int a, int b, int c) {
        const glm::dvec3 &pa = grid.p[size_t(a)], &pb = grid.p[size_t(b)], &pc = grid.p[size_t(c)];
        const glm::dvec3 cr = glm::cross(pb - pa, pc - pa);
        const double ar = 0.5 * glm::length(cr);
        if (!(ar > 1e-14 * glm::dot(pb - pa, pb - pa) + 1e-300)) {
            degenerate[size_t(a)] = degenerate[size_t(b)] = degenerate[size_t(c)] = true;
            return;
        }
        const int idx[3] = {a, b, c};
        for (int k = 0; k < 3; ++k) {
            const int i0 = idx[k], i1 = idx[(k + 1) % 3], i2 = idx[(k + 2) % 3];
            // The angle at i0 weighs the opposite edge (i1, i2).
            const double w = 0.5 * cotangent(grid.p[size_t(i1)] - grid.p[size_t(i0)],
                                             grid.p[size_t(i2)] - grid.p[size_t(i0)]);
            lap[size_t(i1)] += w * (grid.p[size_t(i2)] - grid.p[size_t(i1)]);
            lap[size_t(i2)] += w * (grid.p[size_t(i1)] - grid.p[size_t(i2)]);
            normal[size_t(i0)] += cr; // area-weighted
            area[size_t(i0)] += ar / 3.0;
        }
    };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            triangle(grid.at(i, j), grid.at(i + 1, j), grid.at(i + 1, j + 1));
            triangle(grid.at(i, j), grid.at(i + 1, j + 1), grid.at(i, j + 1));
        }
    for (int j = 1; j < n; ++j)
        for (int i = 1; i < n; ++i) {
            const size_t k = size_t(grid.at(i, j));
            if (degenerate[k] || !(area[k] > 0.0) || !(glm::length(normal[k]) > 0.0))
                continue;
            // Mean curvature normal K = lap / A = -2 H n with our sign (positive bending away
            // from the normal, as kw::surfaceCurvature).
            const glm::dvec3 kn = lap[k] / area[k];
            grid.meshH[k] = -0.5 * glm::dot(kn, glm::normalize(normal[k]));
            grid.valid[k] = std::isfinite(grid.meshH[k]);
        }
    return grid;
}

double percentile(std::vector<double> v, double p) {
    if (v.empty())
        return 0.0;
    std::sort(v.begin(), v.end());
    return v[size_t(std::lround(p * double(v.size() - 1)))];
}

QImage domainImage(const kw::NurbsSurface& g, const Grid* mesh, int side, const kw::ValueRange& r) {
    QImage img(side, side, QImage::Format_RGB32);
    const kw::Interval du = kw::surfaceDomainU(g), dv = kw::surfaceDomainV(g);
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            const double s = (x + 0.5) / side, t = 1.0 - (y + 0.5) / side;
            double h = 0.0;
            if (!mesh) {
                h = kw::surfaceCurvature(g, du.first + s * (du.last - du.first),
                                         dv.first + t * (dv.last - dv.first))
                        .mean;
            } else { // bilinear between the cell's vertex values, as a Gouraud-shaded mesh
                     // shows them (boundary vertices have no one-ring: their inner neighbours)
                const double fx = s * mesh->n, fy = t * mesh->n;
                const int i0 = std::clamp(int(fx), 0, mesh->n - 1);
                const int j0 = std::clamp(int(fy), 0, mesh->n - 1);
                const double ax = fx - i0, ay = fy - j0;
                double sum = 0.0, weight = 0.0;
                for (int c = 0; c < 4; ++c) {
                    const int i = std::clamp(i0 + (c & 1), 1, mesh->n - 1);
                    const int j = std::clamp(j0 + (c >> 1), 1, mesh->n - 1);
                    const size_t k = size_t(mesh->at(i, j));
                    const double w = ((c & 1) ? ax : 1.0 - ax) * ((c >> 1) ? ay : 1.0 - ay);
                    if (mesh->valid[k]) {
                        sum += w * mesh->meshH[k];
                        weight += w;
                    }
                }
                if (!(weight > 0.0)) {
                    img.setPixel(x, y, qRgb(128, 128, 128));
                    continue;
                }
                h = sum / weight;
            }
            const glm::vec3 c =
                kw::rampColour(kw::colourScalePosition(h, r, kw::ColourScale::Symmetric));
            img.setPixel(x, y, qRgb(int(255 * c.x), int(255 * c.y), int(255 * c.z)));
        }
    return img;
}

} // namespace

int main(int argc, char** argv) {
    QGuiApplication app(argc, argv); // QImage/QPainter text needs a GUI application (offscreen)
    QStringList files;
    std::vector<int> parts = {30, 100};
    QString imagePath;
    int imageSurface = 0;
    const QStringList args = app.arguments();
    for (int k = 1; k < args.size(); ++k) {
        if (args[k] == QLatin1String("--partitions") && k + 1 < args.size()) {
            parts.clear();
            for (const QString& p : args[++k].split(QLatin1Char(',')))
                parts.push_back(std::max(2, p.toInt()));
        } else if (args[k] == QLatin1String("--image") && k + 1 < args.size()) {
            imagePath = args[++k];
        } else if (args[k] == QLatin1String("--surface") && k + 1 < args.size()) {
            imageSurface = args[++k].toInt();
        } else {
            files << args[k];
        }
    }
    if (files.isEmpty()) {
        std::fprintf(stderr, "usage: kw_curvature_error FILE.knot... [--partitions 30,100] "
                             "[--image OUT.png --surface K]\n");
        return 2;
    }
    std::printf("| model | mesh | vertices | median error | 95th pct | max | H scale |\n");
    std::printf("|---|---|---|---|---|---|---|\n");
    for (const QString& file : files) {
        const kw::Expected<kw::Scene> scene = kw::readKnotFile(file);
        if (!scene) {
            std::fprintf(stderr, "%s\n", qPrintable(scene.message()));
            return 1;
        }
        for (int n : parts) {
            std::vector<double> absH, err;
            std::vector<Grid> grids;
            for (const kw::Surface& s : scene->surfaces)
                grids.push_back(meshCurvature(s.geometry, n));
            for (const Grid& g : grids)
                for (size_t k = 0; k < g.p.size(); ++k)
                    if (g.valid[k])
                        absH.push_back(std::abs(g.exactH[k]));
            const double scale = std::max(percentile(absH, 0.98), 1e-300);
            for (const Grid& g : grids)
                for (size_t k = 0; k < g.p.size(); ++k)
                    if (g.valid[k])
                        err.push_back(std::abs(g.meshH[k] - g.exactH[k]) / scale);
            std::printf("| %s | %dx%d | %zu | %.2f%% | %.2f%% | %.1f%% | %.4g |\n",
                        qPrintable(QFileInfo(file).fileName()), n, n, err.size(),
                        100 * percentile(err, 0.5), 100 * percentile(err, 0.95),
                        100 * percentile(err, 1.0), scale);
        }
        if (!imagePath.isEmpty() && file == files.front()) {
            if (imageSurface < 0 || imageSurface >= int(scene->surfaces.size())) {
                std::fprintf(stderr, "%s: no surface %d\n", qPrintable(file), imageSurface);
                return 1;
            }
            const kw::NurbsSurface& g = scene->surfaces[size_t(imageSurface)].geometry;
            std::vector<Grid> meshes;
            for (int n : parts)
                meshes.push_back(meshCurvature(g, n));
            std::vector<double> absH;
            for (size_t k = 0; k < meshes.back().p.size(); ++k)
                if (meshes.back().valid[k])
                    absH.push_back(std::abs(meshes.back().exactH[k]));
            const double m = std::max(percentile(absH, 0.98), 1e-12);
            const kw::ValueRange r{-m, m};
            const int side = 320, label = 24;
            QImage out(side * int(1 + parts.size()), side + label, QImage::Format_RGB32);
            out.fill(Qt::white);
            QPainter painter(&out);
            painter.drawImage(0, label, domainImage(g, nullptr, side, r));
            painter.drawText(QRect(0, 0, side, label), Qt::AlignCenter,
                             QStringLiteral("exact H (per pixel)"));
            for (size_t k = 0; k < parts.size(); ++k) {
                painter.drawImage(side * int(k + 1), label, domainImage(g, &meshes[k], side, r));
                painter.drawText(QRect(side * int(k + 1), 0, side, label), Qt::AlignCenter,
                                 QStringLiteral("cotangent H, %1x%1 mesh").arg(parts[k]));
            }
            painter.end();
            if (const kw::Status saved = kw::saveImageAtomically(out, imagePath); !saved) {
                std::fprintf(stderr, "%s\n", qPrintable(saved.message()));
                return 1;
            }
            std::printf("\nwrote %s (surface %d of %s, colour scale +-%.4g)\n",
                        qPrintable(imagePath), imageSurface, qPrintable(file), m);
        }
    }
    return 0;
}
