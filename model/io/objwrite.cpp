// OBJ writers: exact free-form OBJ 3.0 of a whole scene with trims, and a triangle mesh.
#include "model/document/validation.h"
#include "model/io/objfile.h"
#include "model/io/savefile.h"
#include "model/nurbs/trim.h"

#include <QBuffer>
#include <QFile>
#include <QUrl>
#include <algorithm>
#include <limits>

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
    out += "# Lines '# knotwork ...' keep Knotwork's ids, names, partitions, materials, lights,\n";
    out += "# camera and topology; other readers ignore them as comments.\n";
    out += "# knotwork nextid " + QByteArray::number(scene.nextId) + '\n';
    // The count lets the reader tell a file cut at an element boundary from a complete one.
    out += "# knotwork surfaces " + QByteArray::number(scene.surfaces.size()) + '\n';
    // The count first: "lights 0" keeps an unlit scene unlit (no light lines would mean the
    // default lights to the reader).
    out += "# knotwork lights " + QByteArray::number(qsizetype(scene.lights.size())) + '\n';
    for (const Light& l : scene.lights)
        out += QByteArray("# knotwork light ") +
               (l.kind == Light::Kind::Point ? "point " : "directional ") + vec(l.vector) + ' ' +
               vec(l.ambient) + ' ' + vec(l.diffuse) + ' ' + vec(l.specular) + '\n';
    if (scene.camera.authored) {
        const Camera& c = scene.camera;
        out += "# knotwork camera " + vec(c.eye) + ' ' + vec(c.target) + ' ' + vec(c.up) + ' ' +
               num(c.fovYDegrees) + '\n';
    }
    // "-" for no partition mode; the background, when set, last.
    if (!scene.display.partitionMode.isEmpty() || !scene.display.background.isEmpty())
        out += "# knotwork display " +
               (scene.display.partitionMode.isEmpty() ? QByteArray("-")
                                                      : scene.display.partitionMode.toLatin1()) +
               ' ' + num(scene.display.pixelTolerance) +
               (scene.display.background.isEmpty() ? QByteArray()
                                                   : ' ' + scene.display.background.toLatin1()) +
               '\n';
    if (scene.display.customDraft())
        out += "# knotwork draft " + vec(scene.display.pullDirection) + ' ' +
               num(scene.display.draftAngleDegrees) + '\n';
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
        if (s.hidden) // hidden in the editor: a saved flag like the name (docs/FILE_FORMAT.md)
            out += "# knotwork hidden\n";
        if (s.solid >= 0) // a face of a closed solid (docs/FILE_FORMAT.md, "Solid")
            out += "# knotwork solid " + QByteArray::number(s.solid) +
                   (s.outsideAlongNormal ? " normal\n" : " reversed\n");
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
    // The topology a CAD import kept (docs/FILE_FORMAT.md, Topology), after the surfaces it
    // names; the counts first, so that a file cut among these lines is refused.
    const Topology& t = scene.topology;
    if (!t.empty()) {
        out += "\n# knotwork topology " + QByteArray::number(qsizetype(t.edges.size())) + ' ' +
               QByteArray::number(qsizetype(t.shells.size())) + '\n';
        for (const SharedEdge& e : t.edges) {
            out += "# knotwork edge " + QByteArray::number(e.id.value) + ' ' + num(e.tolerance);
            for (const EdgeUse& side : e.sides)
                out += ' ' + QByteArray::number(side.surface.value) + ' ' +
                       QByteArray::number(side.loop.value) + ' ' + QByteArray::number(side.curve) +
                       (side.reversed ? " reversed" : " forward");
            out += '\n';
        }
        for (const Shell& shell : t.shells) {
            out += "# knotwork shell " + QByteArray::number(shell.id.value) +
                   (shell.closed ? " closed " : " open ") + QByteArray::number(shell.solid);
            for (SurfaceId f : shell.faces)
                out += ' ' + QByteArray::number(f.value);
            out += '\n';
        }
    }
    return out;
}

namespace {

// Vertices of the whole mesh: (nu * sub + 1) x (nv * sub + 1) per surface.
long long meshVertexCount(const Scene& scene, int sub) {
    long long n = 0;
    for (const Surface& s : scene.surfaces)
        n += (long long)(s.partitionsU * sub + 1) * (s.partitionsV * sub + 1);
    return n;
}

// Streams the mesh surface by surface into `out`; false with *error once more than maxBytes
// would be written (checked before each surface from its vertex count and after it exactly).
bool streamObjMesh(QIODevice& out, const Scene& scene, const ObjMeshOptions& options,
                   QString* error) {
    const int sub = std::max(options.subdivisions, 1);
    auto tooLarge = [&](long long bytes) {
        if (error)
            *error = QStringLiteral("the mesh would be larger than the limit of %1 MB (at least "
                                    "%2 MB at --subdivisions %3); raise --max-mesh-mb or lower "
                                    "--subdivisions")
                         .arg(options.maxBytes >> 20)
                         .arg(bytes >> 20)
                         .arg(sub);
        return false;
    };
    // A vertex costs at least two short lines ("v 0 0 0\n", "vn 0 0 1\n"): refuse at once what
    // cannot fit rather than after minutes of writing.
    constexpr long long kMinBytesPerVertex = 17;
    if (meshVertexCount(scene, sub) * kMinBytesPerVertex > options.maxBytes)
        return tooLarge(meshVertexCount(scene, sub) * kMinBytesPerVertex);
    QByteArray head = "# Knotwork triangle mesh (surfaces sampled on their partition grids).\n";
    long long written = 0;
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
        QByteArray chunk = std::move(head);
        head.clear();
        chunk += "o " + s.name.simplified().toUtf8() + '\n';
        QByteArray normals;
        for (int j = 0; j <= nv; ++j) {
            for (int i = 0; i <= nu; ++i) {
                const glm::dvec2 uv = uvAt(i, j);
                const SurfaceFrame f = surfaceFrame(g, uv.x, uv.y);
                chunk += "v " + vec(f.point) + '\n';
                normals += "vn " + vec(f.normal) + '\n';
            }
        }
        chunk += normals;
        auto id = [&](int i, int j) {
            return QByteArray::number(base + j * (nu + 1) + i + 1);
        };
        auto tri = [&](int i0, int j0, int i1, int j1, int i2, int j2) {
            const glm::dvec2 c = (uvAt(i0, j0) + uvAt(i1, j1) + uvAt(i2, j2)) / 3.0;
            if (!trimRegionContains(region, c))
                return;
            chunk += "f " + id(i0, j0) + "//" + id(i0, j0) + ' ' + id(i1, j1) + "//" + id(i1, j1) +
                     ' ' + id(i2, j2) + "//" + id(i2, j2) + '\n';
        };
        for (int j = 0; j < nv; ++j) {
            for (int i = 0; i < nu; ++i) {
                tri(i, j, i + 1, j, i + 1, j + 1);
                tri(i, j, i + 1, j + 1, i, j + 1);
            }
        }
        base += (nu + 1) * (nv + 1);
        written += chunk.size();
        if (written > options.maxBytes)
            return tooLarge(written);
        if (out.write(chunk) != chunk.size()) {
            if (error)
                *error = QStringLiteral("cannot write: %1").arg(out.errorString());
            return false;
        }
    }
    return true;
}

} // namespace

QByteArray writeObjMesh(const Scene& scene, const ObjMeshOptions& options) {
    QBuffer buffer;
    buffer.open(QIODevice::WriteOnly);
    ObjMeshOptions unlimited = options;
    unlimited.maxBytes = std::numeric_limits<long long>::max();
    streamObjMesh(buffer, scene, unlimited, nullptr);
    return buffer.data();
}

Status writeObjMeshFile(const QString& path, const Scene& scene, const ObjMeshOptions& options) {
    QString why;
    Status written = saveFileAtomically(
        path, [&](QIODevice& d) { return streamObjMesh(d, scene, options, &why); });
    if (!written && !why.isEmpty())
        return Error(QStringLiteral("%1: %2").arg(path, why), path);
    return written;
}

Status writeFileBytes(const QString& path, const QByteArray& bytes) {
    return saveBytesAtomically(path, bytes);
}

Status writeObjFile(const QString& path, const Scene& scene) {
    if (const QString why = checkScene(scene).message(); !why.isEmpty())
        return Error(QStringLiteral("%1: not written, the scene is not valid: %2").arg(path, why),
                     path);
    return writeFileBytes(path, writeObj(scene));
}

} // namespace kw
