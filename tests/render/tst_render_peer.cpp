// GL test: `knotwork render --peer-mesh` draws an OpenCASCADE mesh (`knotwork mesh`) in place
// of the document's surfaces, with the same view and AOVs, so the edge report measures it
// against the CPU reference: its normal error falls with the deflection, and a mesh whose ids
// are wrong shows up as visible-id disagreements.
#include "expected_test_util.h"
#include "knotwork_process.h"
#include "model/io/meshobj.h"

#include <QDir>
#include <QFile>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTest>

namespace {

QString output(const QString& name) {
    QDir(QStringLiteral(KW_TEST_OUTPUT_DIR)).mkpath(QStringLiteral("."));
    return QStringLiteral(KW_TEST_OUTPUT_DIR "/") + name;
}

const QString kKnot = QStringLiteral("rpeer_nut.knot");

/// render --peer-mesh MESH --edge-report at 192x192; the report, or empty on failure.
QJsonObject peerReport(const QString& mesh, QString* out = nullptr) {
    const QString json = output(QFileInfo(mesh).baseName() + QStringLiteral(".json"));
    QFile::remove(json);
    const Run r = knotwork({QStringLiteral("render"), output(kKnot), QStringLiteral("-o"),
                            output(QStringLiteral("rpeer.png")), QStringLiteral("--size"),
                            QStringLiteral("192x192"), QStringLiteral("--peer-mesh"), mesh,
                            QStringLiteral("--edge-report"), json, QStringLiteral("--time-frames"),
                            QStringLiteral("2")});
    if (r.code != 0)
        qWarning("%s", qPrintable(r.err));
    if (out)
        *out = r.out;
    QFile f(json);
    if (!f.open(QIODevice::ReadOnly))
        return {};
    return QJsonDocument::fromJson(f.readAll()).object();
}

QString meshAt(double linear, double angular) {
    const QString obj = output(QStringLiteral("rpeer_%1.obj").arg(linear));
    const Run r = knotwork({QStringLiteral("mesh"),
                            QStringLiteral(KW_TEST_DATA_DIR "/Pump_Nut.brep"), QStringLiteral("-o"),
                            obj, QStringLiteral("--linear-deflection"), QString::number(linear),
                            QStringLiteral("--angular-deflection"), QString::number(angular)});
    if (r.code != 0)
        qWarning("%s", qPrintable(r.err));
    return r.code == 0 ? obj : QString();
}

} // namespace

class TestRenderPeer : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void initTestCase() {
#ifndef KW_HAVE_OCCT
        QSKIP("built without OpenCASCADE");
#endif
        const Run r = knotwork({QStringLiteral("convert"),
                                QStringLiteral(KW_TEST_DATA_DIR "/Pump_Nut.brep"), output(kKnot)});
        QVERIFY2(r.code == 0, qPrintable(r.err));
    }

    void normalErrorFallsWithTheDeflection() {
        const QString coarse = meshAt(0.5, 20.0), fine = meshAt(0.02, 5.0);
        QVERIFY(!coarse.isEmpty() && !fine.isEmpty());
        QString text;
        const QJsonObject c = peerReport(coarse, &text);
        QVERIFY2(text.contains(QStringLiteral("median frame")), qPrintable(text));
        // The timing names the device it was taken on (GL_RENDERER, GL_VERSION).
        QVERIFY2(text.contains(QRegularExpression(QStringLiteral("median frame .* on .+OpenGL"))),
                 qPrintable(text));
        QVERIFY2(text.contains(QStringLiteral("916 triangles")), qPrintable(text));
        QVERIFY2(text.contains(QStringLiteral("bytes on the GPU")), qPrintable(text));
        const QJsonObject f = peerReport(fine);
        QVERIFY(!c.isEmpty() && !f.isEmpty());
        for (const char* key : {"silhouetteMaxPixels", "crackPixels", "idDisagreements",
                                "depthDisagreements", "normalP99Degrees", "normalPixels"})
            QVERIFY2(c.contains(QLatin1String(key)) && f.contains(QLatin1String(key)), key);
        const double p99c = c[QStringLiteral("normalP99Degrees")].toDouble();
        const double p99f = f[QStringLiteral("normalP99Degrees")].toDouble();
        qInfo("normal p99 %.3f deg at 0.5 / 20 deg, %.4f at 0.02 / 5 deg; ids %g / %g", p99c, p99f,
              c[QStringLiteral("idDisagreements")].toDouble(),
              f[QStringLiteral("idDisagreements")].toDouble());
        // The mesh covers what the reference covers, with the surfaces' ids.
        QVERIFY(f[QStringLiteral("normalPixels")].toDouble() > 5000);
        QCOMPARE(f[QStringLiteral("idDisagreements")].toDouble(), 0.0);
        QVERIFY(f[QStringLiteral("silhouetteMaxPixels")].toDouble() <= 1.0);
        QVERIFY(p99c > 0.1);
        QVERIFY(p99f < 0.5 * p99c);
    }

    void wrongIdsAreSeen() {
        const QString fine = output(QStringLiteral("rpeer_0.02.obj"));
        kw::Expected<kw::TaggedMeshSet> read = kw::readTaggedMeshObjFile(fine);
        QVERIFY2(read, qPrintable(read.message()));
        kw::TaggedMeshSet mesh = std::move(read).value();
        // Every face tagged with the next face's id: the geometry is right, the ids are not.
        const kw::SurfaceId first = mesh.faces.front().id;
        for (size_t k = 0; k + 1 < mesh.faces.size(); ++k)
            mesh.faces[k].id = mesh.faces[k + 1].id;
        mesh.faces.back().id = first;
        const QString rotated = output(QStringLiteral("rpeer_rotated.obj"));
        QFile f(rotated);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(kw::writeTaggedMeshObj(mesh));
        f.close();
        const QJsonObject r = peerReport(rotated);
        QVERIFY(!r.isEmpty());
        QVERIFY2(r[QStringLiteral("idDisagreements")].toDouble() > 1000,
                 qPrintable(QString::number(r[QStringLiteral("idDisagreements")].toDouble())));
    }

    // --zoom F narrows the field of view: the part covers more of the frame, the peer mesh and
    // the reference alike (the edge report still agrees on ids).
    void zoomMagnifiesTheView() {
        const QString json = output(QStringLiteral("rpeer_zoom.json"));
        QFile::remove(json);
        const Run r = knotwork({QStringLiteral("render"), output(kKnot), QStringLiteral("-o"),
                                output(QStringLiteral("rpeer_zoom.png")), QStringLiteral("--size"),
                                QStringLiteral("192x192"), QStringLiteral("--peer-mesh"),
                                output(QStringLiteral("rpeer_0.02.obj")), QStringLiteral("--zoom"),
                                QStringLiteral("3"), QStringLiteral("--edge-report"), json});
        QVERIFY2(r.code == 0, qPrintable(r.err));
        QFile f(json);
        QVERIFY(f.open(QIODevice::ReadOnly));
        const QJsonObject zoomed = QJsonDocument::fromJson(f.readAll()).object();
        const QJsonObject fitted = peerReport(output(QStringLiteral("rpeer_0.02.obj")));
        const double ratio = zoomed[QStringLiteral("referenceCovered")].toDouble() /
                             fitted[QStringLiteral("referenceCovered")].toDouble();
        qInfo("covered pixels x%.2f at --zoom 3", ratio);
        QVERIFY(ratio > 1.3); // the frame fills up: 1.58 measured
        QCOMPARE(zoomed[QStringLiteral("idDisagreements")].toDouble(), 0.0);
        const Run bad = knotwork({QStringLiteral("render"), output(kKnot), QStringLiteral("-o"),
                                  output(QStringLiteral("rpeer_zoom.png")),
                                  QStringLiteral("--zoom"), QStringLiteral("0.5")});
        QCOMPARE(bad.code, 2);
    }

    void meshOfAnotherModelIsRefused() {
        const QString other = output(QStringLiteral("rpeer_other.obj"));
        QFile f(other);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\ng surface_4000000\nf 1 2 3\n");
        f.close();
        const Run r = knotwork({QStringLiteral("render"), output(kKnot), QStringLiteral("-o"),
                                output(QStringLiteral("rpeer_x.png")), QStringLiteral("--size"),
                                QStringLiteral("64x64"), QStringLiteral("--peer-mesh"), other});
        QCOMPARE(r.code, 1);
        QVERIFY2(r.err.contains(other) && r.err.contains(QStringLiteral("surface_4000000")),
                 qPrintable(r.err));
        const Run missing =
            knotwork({QStringLiteral("render"), output(kKnot), QStringLiteral("-o"),
                      output(QStringLiteral("rpeer_x.png")), QStringLiteral("--peer-mesh"),
                      output(QStringLiteral("no_such.obj"))});
        QCOMPARE(missing.code, 1);
        QVERIFY2(missing.err.contains(QStringLiteral("no_such.obj")), qPrintable(missing.err));
    }
};

QTEST_GUILESS_MAIN(TestRenderPeer)
#include "tst_render_peer.moc"
