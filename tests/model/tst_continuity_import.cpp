// The continuity kernel on the closed solids of tests/data as imported (no open edge, no free
// edge, as many shared edges as OpenCASCADE counts), and `knotwork info --continuity`.
#include "expected_test_util.h"
#include "knotwork_process.h"
#include "model/analysis/continuity.h"
#include "model/cad/cadimport.h"
#include "model/io/knotfile.h"

#include <QElapsedTimer>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>
#include <QTest>

#ifdef KW_HAVE_OCCT_TOOLKITS
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <STEPControl_Reader.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS_Shape.hxx>
#endif

using namespace kw;

namespace {

QString data(const QString& name) {
    return QStringLiteral(KW_TEST_DATA_DIR "/") + name;
}

#ifdef KW_HAVE_OCCT_TOOLKITS
/// OpenCASCADE's count of the edges of the file's shape that bound two different faces (a
/// seam, bounded by one face on both sides, and a degenerated edge are not counted).
int occtEdgesBetweenTwoFaces(const QString& path) {
    TopoDS_Shape shape;
    if (path.endsWith(QStringLiteral(".step"))) {
        STEPControl_Reader reader;
        if (reader.ReadFile(path.toLocal8Bit().constData()) != IFSelect_RetDone)
            return -1;
        reader.TransferRoots();
        shape = reader.OneShape();
    } else {
        BRep_Builder builder;
        if (!BRepTools::Read(shape, path.toLocal8Bit().constData(), builder))
            return -1;
    }
    TopTools_IndexedDataMapOfShapeListOfShape faces;
    TopExp::MapShapesAndUniqueAncestors(shape, TopAbs_EDGE, TopAbs_FACE, faces);
    int count = 0;
    for (int k = 1; k <= faces.Extent(); ++k) {
        const TopTools_ListOfShape& list = faces(k);
        if (list.Extent() == 2 && !list.First().IsSame(list.Last()))
            ++count;
    }
    return count;
}
#endif

} // namespace

class TestContinuityImport : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void closedSolids_data();
    void closedSolids();
    void dragStepCost();
    void infoContinuity();
    void infoUsesTheProjectsTolerances();
    void infoRejectsBadTolerances();
};

void TestContinuityImport::closedSolids_data() {
    QTest::addColumn<QString>("file");
    QTest::newRow("Pump_Nut.brep") << "Pump_Nut.brep";
    QTest::newRow("screw.step") << "screw.step";
    QTest::newRow("Axis_of_bearing.brep") << "Axis_of_bearing.brep";
}

// As imported, a closed solid has no open edge and no free edge, and its edges between two
// different faces are OpenCASCADE's.
void TestContinuityImport::closedSolids() {
    QFETCH(QString, file);
    const Expected<ImportResult> r = importFile(data(file));
    QVERIFY2(r, qPrintable(r.message()));
    QElapsedTimer clock;
    clock.start();
    const ContinuityReport report = continuityReport(r->scene, {});
    const qint64 ms = clock.elapsed();
    QCOMPARE(report.count(ContinuityClass::Open), 0);
    QCOMPARE(int(report.topology.freeSides.size()), 0);
    QCOMPARE(report.topology.unresolvedSides, 0);
    QCOMPARE(report.topology.matchedFaces, 0);
    int betweenTwoFaces = 0;
    for (const EdgeContinuity& e : report.edges) {
        QVERIFY(e.edge.recorded.isValid());
        betweenTwoFaces += e.edge.sides[0].surface != e.edge.sides[1].surface;
    }
    QVERIFY(betweenTwoFaces > 0);
    qInfo("%s: %d edges between two faces, %zu edges, %d G2, %d G1, %d G0; %lld ms",
          qPrintable(file), betweenTwoFaces, report.edges.size(), report.count(ContinuityClass::G2),
          report.count(ContinuityClass::G1), report.count(ContinuityClass::G0), ms);
#ifdef KW_HAVE_OCCT_TOOLKITS
    QCOMPARE(betweenTwoFaces, occtEdgesBetweenTwoFaces(data(file)));
#else
    QSKIP("built without OpenCASCADE: the count is not compared");
#endif
}

// What a drag step costs the live overlay: updateContinuity for the edges of one face, for each
// face of hammer.iges (docs/PERFORMANCE.md); the median of 15 runs per face. Printed, and held
// to a bound loose enough for a loaded machine.
void TestContinuityImport::dragStepCost() {
    const Expected<ImportResult> r = importFile(data(QStringLiteral("hammer.iges")));
    QVERIFY2(r, qPrintable(r.message()));
    const Scene& scene = r->scene;
    ContinuityReport report = continuityReport(scene, {});
    std::vector<double> perFace;
    int worstEdges = 0;
    for (const Surface& s : scene.surfaces) {
        std::vector<double> runs;
        int measured = 0;
        for (int k = 0; k < 15; ++k) {
            QElapsedTimer clock;
            clock.start();
            measured = updateContinuity(report, scene, {s.id});
            runs.push_back(double(clock.nsecsElapsed()) * 1e-6);
        }
        std::sort(runs.begin(), runs.end());
        perFace.push_back(runs[runs.size() / 2]);
        if (perFace.back() >= *std::max_element(perFace.begin(), perFace.end()))
            worstEdges = measured;
    }
    std::vector<double> sorted = perFace;
    std::sort(sorted.begin(), sorted.end());
    qInfo("hammer.iges: %zu faces, %zu edges; drag step (one face's edges): median %.3f ms, "
          "worst face %.3f ms (%d edges)",
          scene.surfaces.size(), report.edges.size(), sorted[sorted.size() / 2], sorted.back(),
          worstEdges);
    QVERIFY(sorted.back() < 50.0);
}

// `knotwork info --continuity --json`: exactly the keys the issue names, and the kernel's values;
// the text: one row per edge and the summary.
void TestContinuityImport::infoContinuity() {
    const QString file = data(QStringLiteral("Pump_Nut.brep"));
    Run run = knotwork(
        {QStringLiteral("info"), file, QStringLiteral("--continuity"), QStringLiteral("--json")});
    QCOMPARE(run.code, 0);
    const QJsonObject root = QJsonDocument::fromJson(run.out.toUtf8()).object();
    QStringList keys = root.keys();
    QCOMPARE(keys, (QStringList{"edges", "freeEdges", "tolerances"}));
    const Expected<ImportResult> r = importFile(file);
    QVERIFY2(r, qPrintable(r.message()));
    const ContinuityReport report = continuityReport(r->scene, {});
    const QJsonArray edges = root[QStringLiteral("edges")].toArray();
    QCOMPARE(edges.size(), qsizetype(report.edges.size()));
    QCOMPARE(root[QStringLiteral("freeEdges")].toInt(), 0);
    const QJsonObject tolerances = root[QStringLiteral("tolerances")].toObject();
    QCOMPARE(tolerances[QStringLiteral("g0")].toDouble(), 0.001);
    QCOMPARE(tolerances[QStringLiteral("g1Degrees")].toDouble(), 0.5);
    QCOMPARE(tolerances[QStringLiteral("g2Percent")].toDouble(), 5.0);
    for (qsizetype k = 0; k < edges.size(); ++k) {
        const QJsonObject e = edges[k].toObject();
        QCOMPARE(e.keys(), (QStringList{"continuity", "faces", "g0", "g1Degrees", "g2Percent"}));
        const EdgeContinuity& x = report.edges[size_t(k)];
        QCOMPARE(e[QStringLiteral("faces")].toArray(),
                 (QJsonArray{qint64(x.edge.sides[0].surface.value),
                             qint64(x.edge.sides[1].surface.value)}));
        QCOMPARE(e[QStringLiteral("g1Degrees")].toDouble(), x.g1Degrees);
        QCOMPARE(e[QStringLiteral("continuity")].toString(), continuityClassName(x.continuity));
    }
    // Pump_Nut has G2, G1 and G0 edges.
    QVERIFY(report.count(ContinuityClass::G2) > 0 && report.count(ContinuityClass::G1) > 0 &&
            report.count(ContinuityClass::G0) > 0);

    // The table: a title, a header, one row per edge and the summary ...
    run = knotwork({QStringLiteral("info"), file, QStringLiteral("--continuity")});
    QCOMPARE(run.code, 0);
    const QStringList lines = run.out.trimmed().split(QLatin1Char('\n'));
    QCOMPARE(lines.size(), qsizetype(report.edges.size()) + 3); // title, header, summary
    QCOMPARE(lines.last(), QStringLiteral("%1 shared edge(s): %2 G2, %3 G1, %4 G0, 0 open; 0 "
                                          "free edge(s)")
                               .arg(report.edges.size())
                               .arg(report.count(ContinuityClass::G2))
                               .arg(report.count(ContinuityClass::G1))
                               .arg(report.count(ContinuityClass::G0)));
    // ... and a G2 tolerance above the largest jump makes the G1 edges G2.
    run = knotwork({QStringLiteral("info"), file, QStringLiteral("--continuity"),
                    QStringLiteral("--g2"), QStringLiteral("1000")});
    QCOMPARE(run.code, 0);
    QVERIFY2(run.out.contains(
                 QStringLiteral(" %1 G2, 0 G1, ")
                     .arg(report.count(ContinuityClass::G2) + report.count(ContinuityClass::G1))),
             qPrintable(run.out.right(200)));
}

// A project's own tolerances (saved with it) are the ones `info` judges by; options override.
void TestContinuityImport::infoUsesTheProjectsTolerances() {
    Expected<ImportResult> r = importFile(data(QStringLiteral("Pump_Nut.brep")));
    QVERIFY2(r, qPrintable(r.message()));
    r->scene.continuity.g2Percent = 1000.0;
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("nut.knot"));
    KW_VERIFY_OK(writeKnotFile(path, r->scene));
    Run run = knotwork(
        {QStringLiteral("info"), path, QStringLiteral("--continuity"), QStringLiteral("--json")});
    QCOMPARE(run.code, 0);
    QJsonObject root = QJsonDocument::fromJson(run.out.toUtf8()).object();
    QCOMPARE(root[QStringLiteral("tolerances")][QStringLiteral("g2Percent")].toDouble(), 1000.0);
    for (const QJsonValue& e : root[QStringLiteral("edges")].toArray())
        QVERIFY(e[QStringLiteral("continuity")].toString() != QStringLiteral("G1"));
    run = knotwork({QStringLiteral("info"), path, QStringLiteral("--continuity"),
                    QStringLiteral("--json"), QStringLiteral("--g2"), QStringLiteral("5")});
    root = QJsonDocument::fromJson(run.out.toUtf8()).object();
    QCOMPARE(root[QStringLiteral("tolerances")][QStringLiteral("g2Percent")].toDouble(), 5.0);
}

void TestContinuityImport::infoRejectsBadTolerances() {
    const QString file = data(QStringLiteral("Pump_Nut.brep"));
    Run run = knotwork({QStringLiteral("info"), file, QStringLiteral("--continuity"),
                        QStringLiteral("--g0"), QStringLiteral("-1")});
    QCOMPARE(run.code, 2);
    QVERIFY2(run.err.contains(QStringLiteral("g0")), qPrintable(run.err));
    run = knotwork({QStringLiteral("info"), file, QStringLiteral("--continuity"),
                    QStringLiteral("--g1"), QStringLiteral("x")});
    QCOMPARE(run.code, 2);
    QVERIFY(run.out.isEmpty());
}

QTEST_GUILESS_MAIN(TestContinuityImport)
#include "tst_continuity_import.moc"
