// Every CAD part of tests/data imported as the editor imports it: its area and enclosed volume
// against OpenCASCADE's BRepGProp on the source shape, read in process, within 1e-6 relative.
#include "cad_test_util.h"
#include "model/analysis/mass_properties.h"
#include "model/cad/igesrepair.h"

#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepGProp.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <IGESControl_Reader.hxx>
#include <QElapsedTimer>
#include <QFile>
#include <QTemporaryFile>
#include <QTest>
#include <STEPControl_Reader.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shape.hxx>
#include <cmath>
#include <map>

using namespace kw;

class TestMassOcct : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void againstBRepGProp_data();
    void againstBRepGProp();
};

namespace {

TopoDS_Shape readShape(const QString& file) {
    const QByteArray path = QStringLiteral(KW_TEST_DATA_DIR "/%1").arg(file).toLocal8Bit();
    TopoDS_Shape shape;
    if (file.endsWith(QLatin1String(".brep"))) {
        BRep_Builder builder;
        BRepTools::Read(shape, path.constData(), builder);
    } else if (file.endsWith(QLatin1String(".step"))) {
        STEPControl_Reader reader;
        if (reader.ReadFile(path.constData()) == IFSelect_RetDone && reader.TransferRoots() > 0)
            shape = reader.OneShape();
    } else {
        // As the importer does: an IGES file with broken section numbering is renumbered first.
        QFile in(QString::fromLocal8Bit(path));
        QByteArray bytes = in.open(QIODevice::ReadOnly) ? in.readAll() : QByteArray();
        QTemporaryFile repaired;
        QByteArray toRead = path;
        if (igesNumberingNeedsRepair(bytes)) {
            QString note;
            const std::optional<QByteArray> fixed = repairIgesNumbering(bytes, note);
            if (!fixed || !repaired.open() || repaired.write(*fixed) != fixed->size() ||
                !repaired.flush())
                return shape;
            toRead = QFile::encodeName(repaired.fileName());
        }
        IGESControl_Reader reader;
        if (reader.ReadFile(toRead.constData()) == IFSelect_RetDone && reader.TransferRoots() > 0)
            shape = reader.OneShape();
    }
    return shape;
}

} // namespace

void TestMassOcct::againstBRepGProp_data() {
    QTest::addColumn<QString>("file");
    for (const char* f : {"Axis_of_bearing.brep", "Pump_Nut.brep", "screw.step",
                          "rhino_unset_names.step", "hammer.iges", "teapot.igs"})
        QTest::newRow(f) << QString::fromLatin1(f);
}

void TestMassOcct::againstBRepGProp() {
    QFETCH(QString, file);
    const TopoDS_Shape shape = readShape(file);
    QVERIFY2(!shape.IsNull(), qPrintable(file));
    GProp_GProps surface;
    BRepGProp::SurfaceProperties(shape, surface, 1e-10);
    const std::optional<Scene> scene = kwtest::importedPart(file);
    QVERIFY(scene.has_value());
    QElapsedTimer clock;
    clock.start();
    const ModelProperties m = modelProperties(*scene);
    qInfo("%s: %zu faces measured in %lld ms", qPrintable(file), scene->surfaces.size(),
          clock.elapsed());
    const double area = surface.Mass();
    qInfo("%s: area %.15g (OCCT %.15g, relative %.3g)", qPrintable(file), m.area, area,
          std::abs(m.area - area) / area);
    QVERIFY(area > 0.0);
    QVERIFY2(std::abs(m.area - area) <= 1e-6 * area,
             qPrintable(
                 QStringLiteral("area %1, OCCT %2").arg(m.area, 0, 'g', 15).arg(area, 0, 'g', 15)));
    // The box of the exact trimmed faces: OCCT's optimal box (no triangulation, no tolerances).
    Bnd_Box box;
    BRepBndLib::AddOptimal(shape, box, false, false);
    double x0, y0, z0, x1, y1, z1;
    box.Get(x0, y0, z0, x1, y1, z1);
    const glm::dvec3 lo(x0, y0, z0), hi(x1, y1, z1);
    const double diagonal = glm::length(hi - lo);
    const double boxError = std::max(glm::length(m.lo - lo), glm::length(m.hi - hi)) / diagonal;
    qInfo("%s: box (%g %g %g)..(%g %g %g), OCCT (%g %g %g)..(%g %g %g), %.3g of the diagonal",
          qPrintable(file), m.lo.x, m.lo.y, m.lo.z, m.hi.x, m.hi.y, m.hi.z, x0, y0, z0, x1, y1, z1,
          boxError);
    QVERIFY(m.hasBounds);
    QVERIFY2(boxError < 1e-6, qPrintable(QString::number(boxError)));
    // Surface types: as many planes, cylinders, cones, spheres and tori as OCCT records. Where
    // the source also has free-form faces (B-splines, which may be analytic in truth), at least
    // as many of each.
    std::map<QString, int> occtTypes, ourTypes;
    int occtFreeForm = 0;
    for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next()) {
        switch (BRepAdaptor_Surface(TopoDS::Face(e.Current()), false).GetType()) {
        case GeomAbs_Plane:
            ++occtTypes[QStringLiteral("plane")];
            break;
        case GeomAbs_Cylinder:
            ++occtTypes[QStringLiteral("cylinder")];
            break;
        case GeomAbs_Cone:
            ++occtTypes[QStringLiteral("cone")];
            break;
        case GeomAbs_Sphere:
            ++occtTypes[QStringLiteral("sphere")];
            break;
        case GeomAbs_Torus:
            ++occtTypes[QStringLiteral("torus")];
            break;
        default:
            ++occtFreeForm;
            break;
        }
    }
    for (const FaceProperties& f : m.faces)
        if (f.type != SurfaceType::FreeForm)
            ++ourTypes[surfaceTypeName(f.type)];
    QString tally;
    for (const auto& [type, count] : occtTypes)
        tally += QStringLiteral(" %1 %2/%3").arg(type).arg(ourTypes[type]).arg(count);
    qInfo("%s: types (ours/OCCT)%s, OCCT free-form %d", qPrintable(file), qPrintable(tally),
          occtFreeForm);
    for (const auto& [type, count] : occtTypes)
        QVERIFY2(occtFreeForm > 0 ? ourTypes[type] >= count : ourTypes[type] == count,
                 qPrintable(tally));
    int solids = 0;
    for (TopExp_Explorer e(shape, TopAbs_SOLID); e.More(); e.Next())
        ++solids;
    if (solids == 0) {
        QVERIFY2(!m.volume, qPrintable(file));
        return;
    }
    GProp_GProps volume;
    BRepGProp::VolumeProperties(shape, volume, 1e-10, true);
    QVERIFY2(m.volume.has_value(), qPrintable(file));
    qInfo("%s: volume %.15g (OCCT %.15g, relative %.3g)", qPrintable(file), *m.volume,
          volume.Mass(), std::abs(*m.volume - volume.Mass()) / volume.Mass());
    QVERIFY2(std::abs(*m.volume - volume.Mass()) <= 1e-6 * std::abs(volume.Mass()),
             qPrintable(QStringLiteral("volume %1, OCCT %2")
                            .arg(*m.volume, 0, 'g', 15)
                            .arg(volume.Mass(), 0, 'g', 15)));
}

QTEST_GUILESS_MAIN(TestMassOcct)
#include "tst_mass_occt.moc"
