// The peer's model, reference and equal-quality search (peer_model.h).
#include "bench/peer_model.h"

#include "app/commands.h"
#include "model/cad/cadimport.h"
#include "model/cad/cadprocess.h"
#include "render/edge_metrics.h"
#include "render/gpu_layout.h"
#include "render/offscreen_renderer.h"
#include "render/reference_render.h"

#include <QFile>
#include <QFileInfo>
#include <algorithm>
#include <cmath>
#include <ctime>
#include <map>

namespace kw::bench {

double processCpuMs() {
    timespec t{};
    ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

double residentMiB() {
    QFile f(QStringLiteral("/proc/self/status"));
    if (!f.open(QIODevice::ReadOnly))
        return 0.0;
    for (const QByteArray& line : f.readAll().split('\n'))
        if (line.startsWith("VmRSS:"))
            return line.mid(6).trimmed().split(' ').value(0).toDouble() / 1024.0;
    return 0.0;
}

double median(std::vector<double> v) {
    if (v.empty())
        return 0.0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

QString cpuModel() {
    QFile f(QStringLiteral("/proc/cpuinfo"));
    if (f.open(QIODevice::ReadOnly))
        for (const QByteArray& line : f.readAll().split('\n'))
            if (line.startsWith("model name"))
                return QString::fromUtf8(line.mid(line.indexOf(':') + 1)).trimmed();
    return QStringLiteral("unknown CPU");
}

double linearStep(int k) {
    return 4e-3 / std::pow(2.0, k);
}
double angularStep(int k) {
    return std::round(20.0 / std::pow(2.0, k / 2.0) * 1000.0) / 1000.0;
}

TriangleMesh toTriangleMesh(const TaggedMeshSet& set, SurfaceId only, bool except) {
    TriangleMesh out;
    for (const TaggedMesh& f : set.faces) {
        if ((f.id == only) == except)
            continue;
        SurfaceMesh m;
        m.id = f.id;
        m.positions.assign(f.positions.begin(), f.positions.end());
        m.normals.assign(f.normals.begin(), f.normals.end());
        m.uvs.assign(f.uvs.begin(), f.uvs.end());
        m.indices = f.indices;
        out.surfaces.push_back(std::move(m));
    }
    return out;
}

PeerModel::PeerModel(OffscreenRenderer& r, FaceMesher& m, Limits l,
                     std::function<void(const QString&)> p)
    : renderer(r), mesher(m), limits(l), progress(std::move(p)) {}

Status PeerModel::load(const QString& file) {
    path = file;
    Expected<ImportResult> read = openModelFile(file);
    if (!read)
        return read.error();
    cli::printImportRemarks(file, read->report);
    if (const Status reset = doc.resetScene(read->scene); !reset)
        return Error(QStringLiteral("%1: %2").arg(file, reset.message()), file);
    const Scene& scene = doc.scene();
    if (scene.surfaces.empty())
        return Error(QStringLiteral("%1: the scene has no surfaces").arg(file), file);
    camera = scene.camera.authored ? scene.camera : fitCamera(scene, 1.0);
    // The largest side of the surfaces' bounds, as OCCT's viewers scale their default linear
    // deflection (0.004 of it) from the shape's bounding box.
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const Surface& s : scene.surfaces) {
        const TessellatedMesh t = tessellate(s.geometry, 16, 16);
        for (const glm::vec3& p : t.positions) {
            lo = glm::min(lo, glm::dvec3(p));
            hi = glm::max(hi, glm::dvec3(p));
        }
    }
    side = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1e-9});
    // The faces' tolerance as the STEP/IGES writer builds them (occtexport.cpp).
    tolerance = std::max(1e-5 * glm::length(hi - lo), 1e-7);
    for (const SharedEdge& e : scene.topology.edges)
        tolerance = std::max(tolerance, e.tolerance);
    return ok();
}

Status PeerModel::measureKnotwork(int sidePx, const RenderOptions& options) {
    reference = renderReference(doc.scene(), camera, sidePx, sidePx);
    if (Status sized = renderer.setSize(QSize(sidePx, sidePx), true); !sized)
        return sized;
    if (Status drawn = renderer.render(doc, camera, options); !drawn)
        return drawn;
    return compare(knotwork);
}

Status PeerModel::compare(ScreenQuality& q) {
    const AovBuffer aov = renderer.aov();
    glm::dvec3 lo(0.0), hi(0.0);
    sceneBounds(doc.scene(), lo, hi);
    const double pixelAngle =
        2.0 * std::tan(glm::radians(std::clamp(camera.fovYDegrees, 1.0, 170.0)) * 0.5) /
        double(aov.height);
    EdgeMetrics m;
    if (Status compared = compareWithReference(aov, reference, 1e-4 * glm::length(hi - lo), m,
                                               pixelAngle, &camera.eye);
        !compared)
        return compared;
    q.normalP99 = m.normalP99Degrees;
    q.silhouetteMax = m.silhouetteMaxPixels;
    return ok();
}

Status PeerModel::staticMesh(double linear, double angular, TaggedMeshSet& out) {
    const CadFormat format = cadFormatFromPath(path);
    if (format == CadFormat::Iges || format == CadFormat::Step || format == CadFormat::Brep) {
        MeshDeflection deflection;
        deflection.linear = linear;
        deflection.angularDegrees = angular;
        if (Expected<ImportResult> read = importInChildProcess(path, format, {}, &deflection, &out);
            !read)
            return read.error();
        return ok();
    }
    FaceMeshCost cost;
    if (Status meshed = mesher.mesh(doc.scene().surfaces, tolerance, linear, angular, out, cost);
        !meshed)
        return Error(QStringLiteral("%1: %2").arg(path, meshed.message()), path);
    return ok();
}

Status PeerModel::search(const MeshMaker& make, int li, int ai, PeerChoice& out) {
    struct Tried {
        ScreenQuality q;
        long long triangles = 0;
    };
    std::map<std::pair<int, int>, Tried> tried;
    RenderOptions o;
    o.lightCount = limits.lights;
    const auto at = [&](int l, int a, Tried& t) -> Status {
        if (auto it = tried.find({l, a}); it != tried.end()) {
            t = it->second;
            return ok();
        }
        TriangleMesh mesh;
        if (Status made = make(linearStep(l) * side, angularStep(a), mesh, t.triangles); !made)
            return made;
        if (renderer.setMesh(0, mesh) < 0)
            return Error(QStringLiteral("lost the OpenGL context"));
        if (Status drawn = renderer.renderMesh(doc, 0, camera, o); !drawn)
            return drawn;
        if (Status compared = compare(t.q); !compared)
            return compared;
        tried[{l, a}] = t;
        progress(QStringLiteral("%1: peer linear %2 angular %3 deg: %4 triangles, silhouette max "
                                "%5 px, normal p99 %6 deg")
                     .arg(QFileInfo(path).fileName())
                     .arg(linearStep(l) * side, 0, 'g', 3)
                     .arg(angularStep(a))
                     .arg(t.triangles)
                     .arg(t.q.silhouetteMax, 0, 'f', 2)
                     .arg(t.q.normalP99, 0, 'f', 4));
        return ok();
    };
    li = std::clamp(li, 0, kDeflectionSteps - 1);
    ai = std::clamp(ai, 0, kDeflectionSteps - 1);
    Tried t;
    Status first = at(li, ai, t);
    // A start too fine for BRepMesh (a close-up's start, the fitted choice made zoom times
    // finer, can leave a face with no triangles): one step coarser at a time, as the refinement
    // below stops at its first failure.
    while (!first && li > 0) {
        progress(QStringLiteral("%1: %2; one step coarser")
                     .arg(QFileInfo(path).fileName(), first.message()));
        first = at(--li, ai, t);
    }
    if (!first)
        return first;
    while (!good(t.q) && std::max(li, ai) + 1 < kDeflectionSteps &&
           t.triangles < limits.maxTriangles) {
        // A finer mesh can pass the CAD child's time or memory limit: the search stops there,
        // with the finest mesh made (peer_search.py does the same).
        Tried finer;
        if (Status made = at(li + 1, ai + 1, finer); !made) {
            progress(QStringLiteral("%1: stopped refining: %2")
                         .arg(QFileInfo(path).fileName(), made.message()));
            break;
        }
        t = finer;
        ++li;
        ++ai;
    }
    // Relax one deflection at a time while the quality holds and the triangles drop.
    for (bool improved = good(t.q); improved;) {
        improved = false;
        for (auto [l, a] : {std::pair{li - 1, ai}, std::pair{li, ai - 1}}) {
            Tried r;
            if (l < 0 || a < 0 || !at(l, a, r))
                continue;
            if (good(r.q) && r.triangles < t.triangles) {
                t = r;
                li = l;
                ai = a;
                improved = true;
                break;
            }
        }
    }
    out.linearIndex = li;
    out.angularIndex = ai;
    out.linear = linearStep(li) * side;
    out.angular = angularStep(ai);
    out.matched = good(t.q);
    out.quality = t.q;
    out.triangles = t.triangles;
    return ok();
}

Status PeerModel::searchStatic(PeerChoice& out) {
    return search(
        [&](double linear, double angular, TriangleMesh& mesh, long long& triangles) -> Status {
            TaggedMeshSet set;
            if (Status made = staticMesh(linear, angular, set); !made)
                return made;
            triangles = set.triangleCount();
            mesh = toTriangleMesh(set, SurfaceId{}, true);
            return ok();
        },
        0, 0, out);
}

} // namespace kw::bench
