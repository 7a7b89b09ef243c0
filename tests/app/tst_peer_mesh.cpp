// The OpenCASCADE mesh peer: the tagged-mesh OBJ (model/io/meshobj.h) and
// `knotwork mesh` (BRepMesh in the CAD child process), checked against the kernel: every vertex
// lies on the surface its group names, at the (u, v) it carries, every triangle's centre lies
// within the linear deflection of the surface, and the normals are the surface's.
#include "expected_test_util.h"
#include "knotwork_process.h"
#include "model/io/knotfile.h"
#include "model/io/meshobj.h"
#include "model/nurbs/nurbs.h"

#include <QDir>
#include <QFile>
#include <QTest>
#include <cmath>
#include <map>

namespace {

QString output(const QString& name) {
    QDir(QStringLiteral(KW_TEST_OUTPUT_DIR)).mkpath(QStringLiteral("."));
    return QStringLiteral(KW_TEST_OUTPUT_DIR "/") + name;
}

QString data(const char* name) {
    return QStringLiteral(KW_TEST_DATA_DIR "/%1").arg(QLatin1String(name));
}

double degrees(const glm::dvec3& a, const glm::dvec3& b) {
    return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)) *
           180.0 / M_PI;
}

/// The closest point of `g` to `p` by Gauss-Newton from (u, v), kept in the domain: OCCT's
/// (u, v) of a node is its own surface's, and the exact B-spline conversion of an analytic
/// surface (a circle's rational quadratic arcs) does not keep the angle as the parameter, so
/// the .knot surface passes through the node at a nearby (u, v).
kw::SurfaceFrame project(const kw::NurbsSurface& g, glm::dvec3 p, glm::dvec2 uv) {
    const kw::Interval du = kw::surfaceDomainU(g), dv = kw::surfaceDomainV(g);
    kw::SurfaceFrame f = kw::surfaceFrame(g, uv.x, uv.y);
    for (int it = 0; it < 30; ++it) {
        const glm::dvec3 r = p - f.point;
        const double a = glm::dot(f.du, f.du), b = glm::dot(f.du, f.dv), c = glm::dot(f.dv, f.dv);
        const double det = a * c - b * b;
        if (!(std::abs(det) > 0.0))
            break;
        const double x = glm::dot(f.du, r), y = glm::dot(f.dv, r);
        uv += glm::dvec2((c * x - b * y) / det, (a * y - b * x) / det);
        uv.x = std::clamp(uv.x, du.first, du.last);
        uv.y = std::clamp(uv.y, dv.first, dv.last);
        f = kw::surfaceFrame(g, uv.x, uv.y);
    }
    return f;
}

struct MeshCheck {
    double worstVertex = 0.0; ///< largest |vertex - S(u, v)|
    double worstCentre = 0.0; ///< largest |triangle centre - S(mean u, v)|
    double worstNormal = 0.0; ///< largest angle to the surface normal (non-singular points)
    long long triangles = 0;
};

/// Measures `mesh` against the surfaces of `scene` its groups name; false when a group names
/// no surface.
bool check(const kw::Scene& scene, const kw::TaggedMeshSet& mesh, MeshCheck& c) {
    std::map<std::uint32_t, const kw::Surface*> byId;
    for (const kw::Surface& s : scene.surfaces)
        byId[s.id.value] = &s;
    for (const kw::TaggedMesh& f : mesh.faces) {
        const auto it = byId.find(f.id.value);
        if (it == byId.end())
            return false;
        const kw::NurbsSurface& g = it->second->geometry;
        for (size_t i = 0; i < f.positions.size(); ++i) {
            const kw::SurfaceFrame fr = project(g, f.positions[i], f.uvs[i]);
            c.worstVertex = std::max(c.worstVertex, glm::length(fr.point - f.positions[i]));
            // OCCT falls back to averaged triangle normals where the surface's is undefined.
            if (glm::length(glm::cross(fr.du, fr.dv)) >
                1e-9 * glm::length(fr.du) * glm::length(fr.dv))
                c.worstNormal = std::max(c.worstNormal, degrees(fr.normal, f.normals[i]));
        }
        for (size_t t = 0; t + 2 < f.indices.size(); t += 3) {
            const unsigned a = f.indices[t], b = f.indices[t + 1], d = f.indices[t + 2];
            const glm::dvec2 uv = (f.uvs[a] + f.uvs[b] + f.uvs[d]) / 3.0;
            const glm::dvec3 centre = (f.positions[a] + f.positions[b] + f.positions[d]) / 3.0;
            c.worstCentre =
                std::max(c.worstCentre, glm::length(project(g, centre, uv).point - centre));
            ++c.triangles;
        }
    }
    return true;
}

} // namespace

class TestPeerMesh : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void objRoundTrip() {
        kw::TaggedMeshSet set;
        set.linearDeflection = 0.25;
        set.angularDeflectionDegrees = 12.5;
        for (std::uint32_t id : {3u, 7u}) {
            kw::TaggedMesh m;
            m.id = kw::SurfaceId{id};
            m.sourceFace = int(id) + 1;
            m.positions = {{0, 0, id}, {1, 0, 0.125}, {0, 1, -2.5e-7}, {1, 1, 1e6}};
            m.normals = {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}, {0, 0, -1}};
            m.uvs = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
            m.indices = {0, 1, 2, 2, 1, 3};
            set.faces.push_back(m);
        }
        const QByteArray text = kw::writeTaggedMeshObj(set);
        const kw::Expected<kw::TaggedMeshSet> parsed =
            kw::parseTaggedMeshObj(text, QStringLiteral("m.obj"));
        QVERIFY2(parsed, qPrintable(parsed.message()));
        const kw::TaggedMeshSet& back = *parsed;
        QCOMPARE(back.faces.size(), size_t(2));
        QCOMPARE(back.linearDeflection, 0.25);
        QCOMPARE(back.angularDeflectionDegrees, 12.5);
        for (size_t k = 0; k < 2; ++k) {
            QCOMPARE(back.faces[k].id, set.faces[k].id);
            QCOMPARE(back.faces[k].sourceFace, set.faces[k].sourceFace);
            QCOMPARE(back.faces[k].indices, set.faces[k].indices);
            for (size_t i = 0; i < 4; ++i) {
                QVERIFY(glm::length(back.faces[k].positions[i] - set.faces[k].positions[i]) <=
                        1e-8 * (1.0 + glm::length(set.faces[k].positions[i])));
                QCOMPARE(back.faces[k].normals[i], set.faces[k].normals[i]);
                QCOMPARE(back.faces[k].uvs[i], set.faces[k].uvs[i]);
            }
        }
    }

    void objFansPolygonsAndFlatNormals() {
        const QByteArray text = "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\ng surface_5\nf 1 2 3 4\n";
        const kw::Expected<kw::TaggedMeshSet> parsed =
            kw::parseTaggedMeshObj(text, QStringLiteral("q.obj"));
        QVERIFY2(parsed, qPrintable(parsed.message()));
        const kw::TaggedMeshSet& set = *parsed;
        QCOMPARE(set.triangleCount(), 2LL);
        QCOMPARE(set.faces[0].normals[0], glm::dvec3(0, 0, 1));
    }

    void objErrorsNameFileAndLine_data() {
        QTest::addColumn<QByteArray>("text");
        QTest::addColumn<QString>("where");
        QTest::newRow("outside group")
            << QByteArray("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n") << QStringLiteral("bad.obj:4:");
        QTest::newRow("group name") << QByteArray("g wheel\n") << QStringLiteral("bad.obj:1:");
        QTest::newRow("index") << QByteArray("v 0 0 0\ng surface_1\nf 1 2 3\n")
                               << QStringLiteral("bad.obj:3:");
        QTest::newRow("number") << QByteArray("v 0 x 0\n") << QStringLiteral("bad.obj:1:");
        QTest::newRow("nan") << QByteArray("v 0 nan 0\n") << QStringLiteral("bad.obj:1:");
        QTest::newRow("empty") << QByteArray("# nothing\n") << QStringLiteral("bad.obj: no");
        QTest::newRow("free-form")
            << QByteArray("g surface_2\ncurv2 1 2\n") << QStringLiteral("bad.obj:2:");
    }
    void objErrorsNameFileAndLine() {
        QFETCH(QByteArray, text);
        QFETCH(QString, where);
        const auto result = kw::parseTaggedMeshObj(text, QStringLiteral("bad.obj"));
        QVERIFY(!result);
        QVERIFY2(result.message().startsWith(where), qPrintable(result.message()));
    }

#ifdef KW_HAVE_OCCT
    // Pump_Nut (25 faces: planes, cylinders, cones, tori) at a coarse and a fine deflection:
    // the mesh lies on the .knot surfaces its groups name, within the deflection.
    void meshLiesOnTheConvertedSurfaces_data() {
        QTest::addColumn<double>("linear");
        QTest::addColumn<double>("angular");
        QTest::newRow("coarse") << 0.5 << 20.0;
        QTest::newRow("fine") << 0.02 << 5.0;
    }
    void meshLiesOnTheConvertedSurfaces() {
        QFETCH(double, linear);
        QFETCH(double, angular);
        const QString obj = output(QStringLiteral("peer_nut_%1.obj").arg(linear));
        const QString knot = output(QStringLiteral("peer_nut.knot"));
        QFile::remove(obj);
        Run r = knotwork({QStringLiteral("convert"), data("Pump_Nut.brep"), knot});
        QVERIFY2(r.code == 0, qPrintable(r.err));
        r = knotwork({QStringLiteral("mesh"), data("Pump_Nut.brep"), QStringLiteral("-o"), obj,
                      QStringLiteral("--linear-deflection"), QString::number(linear),
                      QStringLiteral("--angular-deflection"), QString::number(angular)});
        QVERIFY2(r.code == 0, qPrintable(r.err));
        QVERIFY2(r.out.contains(QStringLiteral("25 of 25 face(s) meshed")), qPrintable(r.out));
        const auto scene = kw::readKnotFile(knot);
        QVERIFY2(scene, qPrintable(scene.message()));
        const kw::Expected<kw::TaggedMeshSet> read = kw::readTaggedMeshObjFile(obj);
        QVERIFY2(read, qPrintable(read.message()));
        const kw::TaggedMeshSet& mesh = *read;
        QCOMPARE(mesh.faces.size(), scene->surfaces.size());
        QCOMPARE(mesh.linearDeflection, linear);
        MeshCheck c;
        QVERIFY(check(*scene, mesh, c));
        glm::dvec3 lo, hi;
        kw::sceneBounds(*scene, lo, hi);
        const double size = glm::length(hi - lo);
        qInfo("linear %g: %lld triangles, vertex off %.3g, centre off %.3g (deflection %g), "
              "normal off %.3g deg",
              linear, c.triangles, c.worstVertex, c.worstCentre, linear, c.worstNormal);
        QVERIFY(c.triangles > 100);
        QVERIFY2(c.worstVertex <= 1e-6 * size, "a vertex is off the surface its group names");
        QVERIFY2(c.worstCentre <= 1.05 * linear, "a triangle is farther than the deflection");
        QVERIFY2(c.worstNormal <= 0.01, "a normal is not the surface's");
    }

    // The check above is not vacuous: faces tagged with each other's ids fail it.
    void swappedIdsAreCaught() {
        const QString knot = output(QStringLiteral("peer_nut.knot"));
        const QString obj = output(QStringLiteral("peer_nut_0.5.obj"));
        const auto scene = kw::readKnotFile(knot);
        kw::Expected<kw::TaggedMeshSet> read = kw::readTaggedMeshObjFile(obj);
        if (!scene || !read)
            QSKIP("needs meshLiesOnTheConvertedSurfaces's files");
        kw::TaggedMeshSet mesh = std::move(read).value();
        std::swap(mesh.faces[0].id, mesh.faces[1].id);
        MeshCheck c;
        QVERIFY(check(*scene, mesh, c));
        QVERIFY(c.worstVertex > 1e-3);
    }

    void badInputIsReported() {
        const QString obj = output(QStringLiteral("peer_bad.obj"));
        const QString garbage = output(QStringLiteral("peer_garbage.brep"));
        QFile f(garbage);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write("not a brep\n");
        f.close();
        Run r = knotwork({QStringLiteral("mesh"), garbage, QStringLiteral("-o"), obj});
        QCOMPARE(r.code, 1);
        QVERIFY2(r.err.contains(garbage), qPrintable(r.err));
        QVERIFY(!QFile::exists(obj));
        r = knotwork({QStringLiteral("mesh"), data("Pump_Nut.brep"), QStringLiteral("-o"), obj,
                      QStringLiteral("--linear-deflection"), QStringLiteral("-1")});
        QCOMPARE(r.code, 2);
        r = knotwork({QStringLiteral("mesh"), data("Pump_Nut.brep"), QStringLiteral("-o"),
                      output(QStringLiteral("x.png"))});
        QCOMPARE(r.code, 2);
        r = knotwork({QStringLiteral("mesh"), output(QStringLiteral("missing.step")),
                      QStringLiteral("-o"), obj});
        QCOMPARE(r.code, 1);
        QVERIFY2(r.err.contains(QStringLiteral("missing.step")), qPrintable(r.err));
    }
#endif
};

QTEST_GUILESS_MAIN(TestPeerMesh)
#include "tst_peer_mesh.moc"
