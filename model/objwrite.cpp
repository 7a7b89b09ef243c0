// OBJ writers: exact free-form OBJ 3.0 of a whole scene with trims, and a triangle mesh.
#include "model/objfile.h"
#include "model/trim.h"

#include <QFile>
#include <QSaveFile>
#include <QUrl>
#include <algorithm>

namespace kw {
namespace {

QByteArray num(double x) {
    return QByteArray::number(x, 'g', 17);
}

QByteArray vec(glm::dvec3 v) {
    return num(v.x) + ' ' + num(v.y) + ' ' + num(v.z);
}

bool isRational(const std::vector<double>& w) {
    return std::any_of(w.begin(), w.end(), [](double x) { return x != 1.0; });
}

// Nesting depth parity of each loop: a loop inside an odd number of others is a hole.
std::vector<bool> holeFlags(const Surface& s) {
    const double tol = trimTolerance(s.geometry);
    std::vector<TrimPolygon> polys;
    for (const TrimLoop& l : s.trims)
        polys.push_back(tessellateTrimLoop(l, tol));
    std::vector<bool> hole(polys.size(), false);
    for (size_t i = 0; i < polys.size(); ++i) {
        if (polys[i].empty())
            continue;
        // A point just off the loop's first vertex would be ambiguous; use a vertex itself,
        // tested against the other loops only.
        int depth = 0;
        for (size_t j = 0; j < polys.size(); ++j) {
            if (j == i || polys[j].size() < 3)
                continue;
            TrimRegion r;
            r.loops = {polys[j]};
            r.lo = {glm::dvec2(-1e300)};
            r.hi = {glm::dvec2(1e300)};
            depth += trimRegionContains(r, polys[i][polys[i].size() / 2]) ? 1 : 0;
        }
        hole[i] = depth % 2 == 1;
    }
    return hole;
}

void writeCurve2(QByteArray& out, const NurbsCurve2& c, int& vpCount) {
    const bool rat = isRational(c.weights);
    const int first = vpCount + 1;
    for (size_t i = 0; i < c.points.size(); ++i) {
        out += "vp " + num(c.points[i].x) + ' ' + num(c.points[i].y);
        if (rat)
            out += ' ' + num(c.weights[i]);
        out += '\n';
    }
    vpCount += static_cast<int>(c.points.size());
    out += rat ? "cstype rat bspline\n" : "cstype bspline\n";
    out += "deg " + QByteArray::number(c.degree) + '\n';
    out += "curv2";
    for (size_t i = 0; i < c.points.size(); ++i)
        out += ' ' + QByteArray::number(first + static_cast<int>(i));
    out += "\nparm u";
    for (double k : c.knots)
        out += ' ' + num(k);
    out += "\nend\n";
}

} // namespace

QByteArray writeObj(const Scene& scene) {
    QByteArray out;
    out += "# Knotwork free-form OBJ (OBJ 3.0: cstype, deg, surf, parm, curv2, trim, hole).\n";
    out += "# Lines '# knotwork ...' keep Knotwork's ids, names, partitions, materials, lights\n";
    out += "# and camera; other readers ignore them as comments.\n";
    out += "# knotwork nextid " + QByteArray::number(scene.nextId) + '\n';
    // The count lets the reader tell a file cut at an element boundary from a complete one.
    out += "# knotwork surfaces " + QByteArray::number(scene.surfaces.size()) + '\n';
    for (const Light& l : scene.lights)
        out += QByteArray("# knotwork light ") +
               (l.kind == Light::Kind::Point ? "point " : "directional ") + vec(l.vector) + ' ' +
               vec(l.ambient) + ' ' + vec(l.diffuse) + ' ' + vec(l.specular) + '\n';
    if (scene.camera.authored) {
        const Camera& c = scene.camera;
        out += "# knotwork camera " + vec(c.eye) + ' ' + vec(c.target) + ' ' + vec(c.up) + ' ' +
               num(c.fovYDegrees) + '\n';
    }
    int vCount = 0, vpCount = 0, curv2Count = 0;
    for (const Surface& s : scene.surfaces) {
        const NurbsSurface& g = s.geometry;
        out += "\n# surface " + QByteArray::number(s.id.value) + '\n';
        // Trim curves first: a trim statement may only name curv2 elements already defined.
        std::vector<int> firstCurve;
        for (const TrimLoop& l : s.trims) {
            firstCurve.push_back(curv2Count + 1);
            for (const NurbsCurve2& c : l.curves) {
                writeCurve2(out, c, vpCount);
                ++curv2Count;
            }
        }
        const bool rat = isRational(g.weights);
        for (size_t i = 0; i < g.points.size(); ++i) {
            out += "v " + vec(g.points[i]);
            if (rat)
                out += ' ' + num(g.weights[i]);
            out += '\n';
        }
        const Material& m = s.material;
        out += "# knotwork surface " + QByteArray::number(s.id.value) + ' ' +
               QByteArray::number(s.partitionsU) + ' ' + QByteArray::number(s.partitionsV) + ' ' +
               vec(m.color) + ' ' + num(m.ka) + ' ' + num(m.kd) + ' ' + num(m.ks) + ' ' +
               num(m.shininess) + '\n';
        out += "# knotwork name " + QUrl::toPercentEncoding(s.name) + '\n';
        if (!s.trims.empty()) {
            out += "# knotwork loops";
            for (const TrimLoop& l : s.trims)
                out += ' ' + QByteArray::number(l.id.value);
            out += '\n';
        }
        // `o` takes the rest of the line: keep the name on one line for other readers.
        out += "o " + s.name.simplified().toUtf8() + '\n';
        out += rat ? "cstype rat bspline\n" : "cstype bspline\n";
        out += "deg " + QByteArray::number(g.degreeU) + ' ' + QByteArray::number(g.degreeV) + '\n';
        const Interval du = surfaceDomainU(g), dv = surfaceDomainV(g);
        out +=
            "surf " + num(du.first) + ' ' + num(du.last) + ' ' + num(dv.first) + ' ' + num(dv.last);
        for (size_t i = 0; i < g.points.size(); ++i)
            out += ' ' + QByteArray::number(vCount + 1 + static_cast<int>(i));
        vCount += static_cast<int>(g.points.size());
        out += "\nparm u";
        for (double k : g.knotsU)
            out += ' ' + num(k);
        out += "\nparm v";
        for (double k : g.knotsV)
            out += ' ' + num(k);
        out += '\n';
        const std::vector<bool> hole = holeFlags(s);
        for (size_t l = 0; l < s.trims.size(); ++l) {
            out += hole[l] ? "hole" : "trim";
            for (size_t c = 0; c < s.trims[l].curves.size(); ++c) {
                const Interval d = curveDomain(s.trims[l].curves[c]);
                out += ' ' + num(d.first) + ' ' + num(d.last) + ' ' +
                       QByteArray::number(firstCurve[l] + static_cast<int>(c));
            }
            out += '\n';
        }
        out += "end\n";
    }
    return out;
}

QByteArray writeObjMesh(const Scene& scene, const ObjMeshOptions& options) {
    QByteArray out = "# Knotwork triangle mesh (surfaces sampled on their partition grids).\n";
    const int sub = std::max(options.subdivisions, 1);
    int base = 0;
    for (const Surface& s : scene.surfaces) {
        const NurbsSurface& g = s.geometry;
        const TrimRegion region = makeTrimRegion(s.trims, trimTolerance(g));
        const Interval du = surfaceDomainU(g), dv = surfaceDomainV(g);
        const int nu = s.partitionsU * sub, nv = s.partitionsV * sub;
        auto uvAt = [&](int i, int j) {
            return glm::dvec2(du.first + (du.last - du.first) * i / nu,
                              dv.first + (dv.last - dv.first) * j / nv);
        };
        out += "o " + s.name.simplified().toUtf8() + '\n';
        QByteArray normals;
        for (int j = 0; j <= nv; ++j) {
            for (int i = 0; i <= nu; ++i) {
                const glm::dvec2 uv = uvAt(i, j);
                const SurfaceFrame f = surfaceFrame(g, uv.x, uv.y);
                out += "v " + vec(f.point) + '\n';
                normals += "vn " + vec(f.normal) + '\n';
            }
        }
        out += normals;
        auto id = [&](int i, int j) {
            return QByteArray::number(base + j * (nu + 1) + i + 1);
        };
        auto tri = [&](int i0, int j0, int i1, int j1, int i2, int j2) {
            const glm::dvec2 c = (uvAt(i0, j0) + uvAt(i1, j1) + uvAt(i2, j2)) / 3.0;
            if (!trimRegionContains(region, c))
                return;
            out += "f " + id(i0, j0) + "//" + id(i0, j0) + ' ' + id(i1, j1) + "//" + id(i1, j1) +
                   ' ' + id(i2, j2) + "//" + id(i2, j2) + '\n';
        };
        for (int j = 0; j < nv; ++j) {
            for (int i = 0; i < nu; ++i) {
                tri(i, j, i + 1, j, i + 1, j + 1);
                tri(i, j, i + 1, j + 1, i, j + 1);
            }
        }
        base += (nu + 1) * (nv + 1);
    }
    return out;
}

bool writeFileBytes(const QString& path, const QByteArray& bytes, QString& error) {
    QSaveFile f(path);
    if (!f.open(QIODevice::WriteOnly) || f.write(bytes) != bytes.size() || !f.commit()) {
        error = QStringLiteral("%1: cannot write: %2").arg(path, f.errorString());
        return false;
    }
    return true;
}

} // namespace kw
