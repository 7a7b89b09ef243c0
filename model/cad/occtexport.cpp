// STEP and IGES through OpenCASCADE: faces built exactly, sewn, closed shells made solids,
// written with reals at full precision under a temporary name.
#include "model/cad/occtexport.h"

#include "model/cad/matchedtopology.h"
#include "model/cad/occtbuild.h"
#include "model/document/seamgaps.h"
#include "model/io/savefile.h"

#include <APIHeaderSection_MakeHeader.hxx>
#include <BRepAdaptor_Curve.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepLib.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GCPnts_AbscissaPoint.hxx>
#include <GeomAPI_ProjectPointOnCurve.hxx>
#include <IGESBasic_Name.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <IGESData_IGESEntity.hxx>
#include <IGESData_IGESModel.hxx>
#include <IGESData_IGESWriter.hxx>
#include <IGESSelect_WorkLibrary.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <OSD.hxx>
#include <Precision.hxx>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QHash>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>
#include <StepData_Protocol.hxx>
#include <StepData_StepModel.hxx>
#include <StepData_StepWriter.hxx>
#include <StepShape_AdvancedFace.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_DataMapOfShapeInteger.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <TransferBRep.hxx>
#include <TransferBRep_ShapeMapper.hxx>
#include <Transfer_FinderProcess.hxx>
#include <UnitsMethods.hxx>
#include <XSControl_TransferWriter.hxx>
#include <XSControl_WorkSession.hxx>
#include <algorithm>
#include <mutex>
#include <ostream>
#include <set>
#include <streambuf>

namespace kw {
namespace {

// Progress in 1000 steps: faces 0..600, sewing 600..800, writing 800..1000.
constexpr int kSteps = 1000;
// Free edges of two faces closer than this share of the scene's diagonal are reported as one
// open seam; farther ones are boundaries of an open shell.
constexpr double kSeamPairing = 0.05;
constexpr int kMaxSeamLines = 50;
// OpenCASCADE's STEP and IGES readers keep a written p-curve only where it lies within
// min(1, 2 x the file's precision) of its edge's 3D curve (XSAlgo_AlgoContainer::CheckPCurve,
// in model units); beyond, they replace it by the 3D curve's projection, which moves that face's
// trim by the gap. Boundaries found by matching that lie further apart than this (half the fixed
// limit, for the reader's own re-fit) are written as two edges, an open seam, so every reader
// gets each face's own trim; the file's precision is its greatest tolerance, so 2 x precision
// covers every edge written shared.
constexpr double kReaderKeepsPCurve = 0.5;

void setUpOcctOnce() {
    static std::once_flag once;
    std::call_once(once, [] {
        OSD::SetSignal(OSD_SignalMode_Set, Standard_False);
        Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_Printer));
        STEPControl_Controller::Init();
        IGESControl_Controller::Init();
    });
}

QString failure(const Standard_Failure& e) {
    return QStringLiteral("%1 (%2)").arg(QString::fromUtf8(e.GetMessageString()),
                                         QString::fromLatin1(e.DynamicType()->Name()));
}

const char* stepSchemaValue(const QString& schema) {
    if (schema == QLatin1String("ap203"))
        return "AP203";
    if (schema == QLatin1String("ap242"))
        return "AP242DIS";
    return "AP214IS";
}

// Reals as 17 significant digits (enough for any double to read back as itself): OCCT's default
// (12 digits) would round every pole. Not with OCCT's zero suppression, which looks for the
// exponent in the first 16 characters only and mangles longer numbers; the writers' buffers
// (24 characters) hold "-d.dddddddddddddddE-dd", which is why two-digit exponents are kept
// (twoDigitExponents).
void exactReals(Interface_FloatWriter& w) {
    w.SetFormat("%.16E");
}

// The scene with every magnitude below 1e-99 written as 0 (there is no room for a three-digit
// exponent; a length of 1e-99 model units is zero for any CAD system), counted in `flushed`.
// Refused (the surface named) for a magnitude of 1e100 or more, which no writer here can hold.
Status twoDigitExponents(Scene& scene, int& flushed) {
    bool held = true; // every magnitude fits
    const auto fix = [&](double& x) {
        const double a = std::abs(x);
        if (a > 0 && a < 1e-99) {
            x = 0.0;
            ++flushed;
        } else if (a >= 1e100) {
            held = false;
        }
    };
    for (Surface& s : scene.surfaces) {
        for (glm::dvec3& p : s.geometry.points)
            fix(p.x), fix(p.y), fix(p.z);
        for (double& w : s.geometry.weights)
            fix(w);
        for (double& k : s.geometry.knotsU)
            fix(k);
        for (double& k : s.geometry.knotsV)
            fix(k);
        for (TrimLoop& l : s.trims)
            for (NurbsCurve2& c : l.curves) {
                for (glm::dvec2& p : c.points)
                    fix(p.x), fix(p.y);
                for (double& w : c.weights)
                    fix(w);
                for (double& k : c.knots)
                    fix(k);
            }
        if (!held)
            return Error(QStringLiteral("surface '%1' has a coordinate, weight or knot of "
                                        "magnitude 1e100 or more, which STEP and IGES writers "
                                        "cannot hold")
                             .arg(s.name));
    }
    return ok();
}

// An output stream straight into a QByteArray: the writers' text (150 MB for 10,000 faces) is
// held once, not in a string stream, then its copy, then a QByteArray of that.
class ByteArrayBuffer : public std::streambuf {
public:
    explicit ByteArrayBuffer(QByteArray& bytes) : bytes_(bytes) {}

protected:
    int_type overflow(int_type c) override {
        if (!traits_type::eq_int_type(c, traits_type::eof()))
            bytes_.append(char(c));
        return traits_type::not_eof(c);
    }
    std::streamsize xsputn(const char* s, std::streamsize n) override {
        bytes_.append(s, qsizetype(n));
        return n;
    }

private:
    QByteArray& bytes_;
};

// The unit name IGES's global section holds for `unit` (IGESData_BasicEditor's names).
QByteArray igesUnitName(LengthUnit unit) {
    switch (unit) {
    case LengthUnit::Inch:
        return "IN";
    case LengthUnit::Foot:
        return "FT";
    case LengthUnit::Mile:
        return "MI";
    case LengthUnit::Metre:
        return "M";
    case LengthUnit::Kilometre:
        return "KM";
    case LengthUnit::Mil:
        return "MIL";
    case LengthUnit::Micrometre:
        return "UM";
    case LengthUnit::Centimetre:
        return "CM";
    case LengthUnit::Microinch:
        return "UIN";
    case LengthUnit::Millimetre:
        break;
    }
    return "MM";
}

// The report's line for an open seam.
QString seamLine(const QString& a, const QString& b, double gap, LengthUnit unit) {
    return QStringLiteral("seam between face '%1' and face '%2' is open: largest gap %3 %4")
        .arg(a, b)
        .arg(gap, 0, 'g', 6)
        .arg(lengthUnitKey(unit));
}

// A free edge sampled for the seam report.
struct FreeEdge {
    TopoDS_Edge edge;
    int face = 0; // index into the names
    std::vector<gp_Pnt> samples;
    Bnd_Box box;
    double length = 0.0;
};

// Largest distance from a's samples to edge b (its 3D curve over its range; the ends when a
// sample projects outside it).
double oneSidedGap(const FreeEdge& a, const FreeEdge& b) {
    double first = 0.0, last = 0.0;
    const Handle(Geom_Curve) c = BRep_Tool::Curve(b.edge, first, last);
    double worst = 0.0;
    for (const gp_Pnt& p : a.samples) {
        double d = std::min(p.Distance(b.samples.front()), p.Distance(b.samples.back()));
        if (!c.IsNull()) {
            GeomAPI_ProjectPointOnCurve proj(p, c, first, last);
            if (proj.NbPoints() > 0)
                d = std::min(d, proj.LowerDistance());
        } else {
            for (const gp_Pnt& q : b.samples)
                d = std::min(d, p.Distance(q));
        }
        worst = std::max(worst, d);
    }
    return worst;
}

// Free edges of `shape` (used by one face, not degenerated, not a seam of its face).
std::vector<FreeEdge> freeEdges(const TopoDS_Shape& shape,
                                const TopTools_DataMapOfShapeInteger& ids) {
    TopTools_IndexedDataMapOfShapeListOfShape edgeFaces;
    TopExp::MapShapesAndAncestors(shape, TopAbs_EDGE, TopAbs_FACE, edgeFaces);
    std::vector<FreeEdge> out;
    for (int k = 1; k <= edgeFaces.Extent(); ++k) {
        const TopoDS_Edge& e = TopoDS::Edge(edgeFaces.FindKey(k));
        const TopTools_ListOfShape& faces = edgeFaces(k);
        if (faces.Extent() != 1 || BRep_Tool::Degenerated(e))
            continue;
        const TopoDS_Face& f = TopoDS::Face(faces.First());
        if (BRep_Tool::IsClosed(e, f))
            continue;
        FreeEdge fe;
        fe.edge = e;
        fe.face = ids.IsBound(f) ? ids.Find(f) : -1;
        BRepAdaptor_Curve curve(e);
        const double a = curve.FirstParameter(), b = curve.LastParameter();
        for (int s = 0; s <= 24; ++s)
            fe.samples.push_back(curve.Value(a + (b - a) * s / 24));
        for (size_t s = 1; s < fe.samples.size(); ++s)
            fe.length += fe.samples[s].Distance(fe.samples[s - 1]);
        BRepBndLib::Add(e, fe.box);
        out.push_back(std::move(fe));
    }
    return out;
}

// One line per pair of free edges of two faces that lie close together (an open seam, with its
// largest gap); a count of the other free edges (boundaries of open shells). Pairs of faces in
// `reported` (index pairs, lower first) have their seam reported already, with its exact gap.
void reportFreeEdges(const std::vector<FreeEdge>& edges, const QStringList& names, double diagonal,
                     LengthUnit unit, const std::set<std::pair<int, int>>& reported,
                     ExportReport& report) {
    std::vector<int> partner(edges.size(), -1);
    std::vector<double> gap(edges.size(), 0.0);
    const double reach = kSeamPairing * diagonal;
    for (size_t i = 0; i < edges.size(); ++i) {
        Bnd_Box box = edges[i].box;
        box.Enlarge(reach);
        double best = reach;
        for (size_t j = 0; j < edges.size(); ++j) {
            if (j == i || edges[j].face == edges[i].face || box.IsOut(edges[j].box))
                continue;
            const double g =
                std::max(oneSidedGap(edges[i], edges[j]), oneSidedGap(edges[j], edges[i]));
            // A gap as wide as a quarter of the shorter edge is not one seam pulled apart.
            if (g < best && g < 0.25 * std::min(edges[i].length, edges[j].length)) {
                best = g;
                partner[i] = int(j);
                gap[i] = g;
            }
        }
    }
    const auto name = [&](int face) {
        return face >= 0 && face < names.size() ? names[face] : QStringLiteral("?");
    };
    int lines = 0, more = 0, boundary = 0;
    for (size_t i = 0; i < edges.size(); ++i) {
        const int j = partner[i];
        if (j < 0) {
            ++boundary;
            continue;
        }
        // Each pair once: from the edge whose partner names it back, lower index first.
        if (partner[size_t(j)] == int(i) && size_t(j) < i)
            continue;
        const int fa = edges[i].face, fb = edges[size_t(j)].face;
        if (reported.count({std::min(fa, fb), std::max(fa, fb)}))
            continue;
        if (lines++ >= kMaxSeamLines) {
            ++more;
            continue;
        }
        report.warnings << seamLine(name(edges[i].face), name(edges[size_t(j)].face), gap[i], unit);
    }
    if (more > 0)
        report.warnings << QStringLiteral("%1 more open seam(s)").arg(more);
    if (boundary > 0)
        report.warnings << QStringLiteral("%1 edge(s) bound an open shell (no face lies across "
                                          "them)")
                               .arg(boundary);
}

// Names the entities the writer made of each face.
template <class EntityType>
void nameEntities(const Handle(Transfer_FinderProcess) & fp, const TopoDS_Shape& shape,
                  const TopTools_DataMapOfShapeInteger& ids, const QStringList& names,
                  const std::function<void(const Handle(EntityType) &, const QString&)>& set) {
    if (fp.IsNull())
        return;
    TopTools_IndexedMapOfShape faces;
    TopExp::MapShapes(shape, TopAbs_FACE, faces);
    for (int k = 1; k <= faces.Extent(); ++k) {
        if (!ids.IsBound(faces(k)))
            continue;
        const QString& name = names[ids.Find(faces(k))];
        if (name.isEmpty())
            continue;
        Handle(Standard_Transient) entity;
        const Handle(TransferBRep_ShapeMapper) mapper = TransferBRep::ShapeMapper(fp, faces(k));
        if (fp->FindTypedTransient(mapper, STANDARD_TYPE(EntityType), entity))
            set(Handle(EntityType)::DownCast(entity), name);
    }
}

Expected<QByteArray> writeStep(const TopoDS_Shape& shape, const QString& path,
                               const ExportOptions& options, LengthUnit unit,
                               const TopTools_DataMapOfShapeInteger& ids,
                               const QStringList& names) {
    Interface_Static::SetCVal("write.step.schema", stepSchemaValue(options.stepSchema));
    Interface_Static::SetIVal("write.step.unit", igesUnitFlag(unit));
    STEPControl_Writer writer;
    if (writer.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone)
        return Error(QStringLiteral("OpenCASCADE's STEP writer could not transfer the shape"));
    nameEntities<StepShape_AdvancedFace>(
        writer.WS()->TransferWriter()->FinderProcess(), shape, ids, names,
        [](const Handle(StepShape_AdvancedFace) & f, const QString& name) {
            f->SetName(new TCollection_HAsciiString(name.toUtf8().constData()));
        });
    const Handle(StepData_StepModel) model = writer.Model();
    APIHeaderSection_MakeHeader header(model);
    header.SetName(new TCollection_HAsciiString(QFileInfo(path).fileName().toUtf8().constData()));
    header.SetOriginatingSystem(new TCollection_HAsciiString("Knotwork"));
    const auto protocol = Handle(StepData_Protocol)::DownCast(writer.WS()->Protocol());
    StepData_StepWriter sw(model);
    exactReals(sw.FloatWriter());
    sw.SendModel(protocol);
    QByteArray bytes;
    ByteArrayBuffer buffer(bytes);
    std::ostream out(&buffer);
    if (!sw.Print(out) || !out)
        return Error(QStringLiteral("OpenCASCADE's STEP writer failed"));
    return bytes;
}

Expected<QByteArray> writeIges(const TopoDS_Shape& shape, const ExportOptions& options,
                               LengthUnit unit, const TopTools_DataMapOfShapeInteger& ids,
                               const QStringList& names) {
    const QByteArray unitName = igesUnitName(unit);
    Interface_Static::SetCVal("write.iges.unit", unitName.constData());
    IGESControl_Writer writer(unitName.constData(), options.igesFaces ? 0 : 1);
    // A trimmed surface (144) has no orientation of its own: OCCT writes a reversed face's
    // surface reversed. Every face goes as its surface runs, so the surfaces stay exact.
    TopoDS_Shape toWrite = shape;
    if (options.igesFaces) {
        TopoDS_Compound faces;
        BRep_Builder b;
        b.MakeCompound(faces);
        for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next())
            b.Add(faces, e.Current().Oriented(TopAbs_FORWARD));
        toWrite = faces;
    }
    if (!writer.AddShape(toWrite))
        return Error(QStringLiteral("OpenCASCADE's IGES writer could not transfer the shape"));
    const Handle(IGESData_IGESModel) model = writer.Model();
    // Short labels hold 8 characters: the whole name goes in a Name property (406 form 15),
    // which readers prefer.
    nameEntities<IGESData_IGESEntity>(
        writer.TransferProcess(), toWrite, ids, names,
        [&](const Handle(IGESData_IGESEntity) & e, const QString& name) {
            const QByteArray utf8 = name.toUtf8();
            e->SetLabel(new TCollection_HAsciiString(utf8.left(8).constData()));
            Handle(IGESBasic_Name) property = new IGESBasic_Name;
            property->Init(1, new TCollection_HAsciiString(utf8.constData()));
            model->AddEntity(property);
            e->AddProperty(property);
        });
    writer.ComputeModel();
    IGESData_IGESWriter iw(model);
    exactReals(iw.FloatWriter());
    iw.SendModel(IGESSelect_WorkLibrary::DefineProtocol());
    QByteArray bytes;
    ByteArrayBuffer buffer(bytes);
    std::ostream out(&buffer);
    if (!iw.Print(out) || !out)
        return Error(QStringLiteral("OpenCASCADE's IGES writer failed"));
    return bytes;
}

} // namespace

Expected<QByteArray> exportOcctBytes(const Scene& original, const QString& path,
                                     const ExportOptions& options, ExportReport& report,
                                     const ImportProgress& progress) {
    // Every failure is an Error of `path`.
    const auto fail = [&path](QString message) {
        return Error(std::move(message), path);
    };
    QElapsedTimer timer;
    timer.start();
    const CadFormat format = cadFormatFromPath(path);
    if (format != CadFormat::Step && format != CadFormat::Iges)
        return fail(
            QStringLiteral("%1: not a STEP (.step, .stp) or IGES (.iges, .igs) name").arg(path));
    if (const QString bad = checkExportOptions(options).message(); !bad.isEmpty())
        return fail(QStringLiteral("%1: %2").arg(path, bad));
    if (original.surfaces.empty())
        return fail(
            QStringLiteral("%1: nothing to export: the document has no surfaces").arg(path));
    Scene scene = original;
    int flushed = 0;
    if (const Status held = twoDigitExponents(scene, flushed); !held)
        return fail(QStringLiteral("%1: %2").arg(path, held.message()));
    if (flushed > 0)
        report.warnings
            << QStringLiteral("%1 value(s) of magnitude below 1e-99 written as 0").arg(flushed);
    setUpOcctOnce();
    OSD::SetThreadLocalSignal(OSD_SignalMode_Set, Standard_False);
    // The shape is in the document's unit, and so is the file: OCCT scales from its "cascade"
    // unit to the file's, so both are the document's and nothing is scaled.
    Interface_Static::SetIVal("xstep.cascade.unit", igesUnitFlag(scene.unit));
    UnitsMethods::SetCasCadeLengthUnit(igesUnitFlag(scene.unit));
    // The file's precision (STEP's uncertainty, IGES's resolution) is the shape's greatest
    // tolerance: readers take it as theirs and keep every p-curve within twice it of its edge
    // (kReaderKeepsPCurve); OCCT's default, the average, makes them re-fit the trims of the
    // edges whose two sides lie further apart than that.
    Interface_Static::SetIVal("write.precision.mode", 1);
    const auto step = [&](int done) {
        return !progress || progress(done, kSteps);
    };
    const auto cancelled = [&] {
        return fail(QStringLiteral("%1: export cancelled").arg(path));
    };

    glm::dvec3 lo, hi;
    sceneBounds(scene, lo, hi);
    const double diagonal = std::max(glm::length(hi - lo), 1e-9);
    // The source's edge tolerances where the import recorded them: its shared edges were one
    // edge within those, so sewing at the largest closes every seam the source had closed.
    double tolerance = std::max(1e-5 * diagonal, 1e-7);
    for (const SharedEdge& e : scene.topology.edges)
        tolerance = std::max(tolerance, e.tolerance);
    if (options.tolerance > 0)
        tolerance = options.tolerance;
    QStringList names;
    for (const Surface& s : scene.surfaces)
        names << s.name;
    try {
        OCC_CATCH_SIGNALS
        const int n = int(scene.surfaces.size());
        // With the import's record, the seams are measured on the exact surfaces against each
        // edge's own tolerance (kw::seamGaps): an open seam is built as two edges, and a shell
        // with one is never a solid.
        std::vector<bool> onOpenSeam(size_t(n), false);
        std::vector<std::uint32_t> openIds;
        QStringList seamLines;
        if (!scene.topology.edges.empty()) {
            QHash<std::uint32_t, int> index;
            for (int k = 0; k < n; ++k)
                index.insert(scene.surfaces[size_t(k)].id.value, k);
            for (const SeamGap& g : seamGaps(scene)) {
                if (!g.open())
                    continue;
                openIds.push_back(g.edge.value);
                const int a = index.value(g.faceA.value, -1), c = index.value(g.faceB.value, -1);
                if (a < 0 || c < 0)
                    continue;
                onOpenSeam[size_t(a)] = onOpenSeam[size_t(c)] = true;
                seamLines << seamLine(names[a], names[c], g.gap, scene.unit);
            }
        }
        // Faces the record covers get its shared edges as they are (no face's trims move), and
        // so do faces without a record whose boundaries pair up end to end within the sewing
        // tolerance (found as the continuity kernel finds them, each with its measured gap as
        // its tolerance); the others are built alone and sewn, which gives both faces of an
        // edge one re-fitted p-curve and moves their trims by up to the tolerance.
        const bool hadRecord = !scene.topology.empty();
        const Topology recordOnly = scene.topology;
        const MatchedTopology matched = matchedTopology(scene, tolerance, kReaderKeepsPCurve);
        // Seams left open for the readers' sake, with their gaps as measured on the exact
        // surfaces (the free edges' report would give its coarser measure).
        std::set<std::pair<int, int>> farFaces;
        for (const MatchedTopology::FarPair& far : matched.tooFar) {
            const auto index = [&](SurfaceId id) {
                for (int k = 0; k < n; ++k)
                    if (scene.surfaces[size_t(k)].id == id)
                        return k;
                return -1;
            };
            const int a = index(far.faces[0]), c = index(far.faces[1]);
            if (a < 0 || c < 0)
                continue;
            farFaces.insert({std::min(a, c), std::max(a, c)});
            seamLines << seamLine(names[a], names[c], far.gap, scene.unit);
        }
        const bool anyMatched = !matched.shells.empty();
        scene.topology.edges.insert(scene.topology.edges.end(), matched.edges.begin(),
                                    matched.edges.end());
        scene.topology.shells.insert(scene.topology.shells.end(), matched.shells.begin(),
                                     matched.shells.end());
        occt::RecordedFaces recorded;
        if (!scene.topology.empty()) {
            const double least = std::max(1e-7, 1e-9 * diagonal);
            Status built = occt::buildRecordedFaces(scene, openIds, least, recorded);
            if (!built && anyMatched) {
                // OCCT refused an edge found by matching: those faces are sewn as before.
                scene.topology = recordOnly;
                recorded = {};
                if (hadRecord)
                    built = occt::buildRecordedFaces(scene, openIds, least, recorded);
            }
            if (!built && hadRecord)
                report.warnings << QStringLiteral("the import's shared edges could not be built "
                                                  "(%1): the faces are sewn instead")
                                       .arg(built.message());
            if (!built)
                recorded = {};
        }
        std::vector<TopoDS_Face> faces(static_cast<size_t>(n), TopoDS_Face());
        if (!recorded.faces.empty())
            faces = recorded.faces;
        BRepBuilderAPI_Sewing sewing(tolerance);
        int toSew = 0;
        for (int k = 0; k < n; ++k) {
            if (!step(600 * k / n))
                return cancelled();
            if (!faces[size_t(k)].IsNull())
                continue;
            const Expected<TopoDS_Face> face =
                occt::buildFace(scene.surfaces[size_t(k)], tolerance);
            if (!face)
                return fail(QStringLiteral("%1: surface '%2' cannot be written: %3")
                                .arg(path, names[k], face.message()));
            faces[size_t(k)] = *face;
            sewing.Add(*face);
            ++toSew;
        }
        if (!step(600))
            return cancelled();
        TopTools_DataMapOfShapeInteger ids;
        TopoDS_Shape sewn;
        if (toSew > 0) {
            // Sewing makes the edges two faces share one edge, written once and used by both.
            sewing.Perform();
            sewn = sewing.SewedShape();
        }
        for (int k = 0; k < n; ++k) {
            const TopoDS_Face& f = faces[size_t(k)];
            const bool sewnFace = recorded.faces.empty() || recorded.faces[size_t(k)].IsNull();
            ids.Bind(sewnFace && sewing.IsModified(f) ? sewing.Modified(f) : f, k);
        }
        if (!step(800))
            return cancelled();

        // Closed shells become solids facing outward; the rest stay shells or loose faces.
        TopoDS_Compound result;
        BRep_Builder b;
        b.MakeCompound(result);
        std::vector<TopoDS_Shell> shells;
        std::vector<TopoDS_Face> loose;
        // The record's shells, and its faces in none each on its own (or loose).
        std::vector<bool> placed(size_t(n), false);
        for (const std::vector<int>& members : recorded.shells) {
            TopoDS_Shell shell;
            b.MakeShell(shell);
            int count = 0;
            for (int k : members) {
                if (placed[size_t(k)] || recorded.faces[size_t(k)].IsNull())
                    continue;
                b.Add(shell, recorded.faces[size_t(k)]);
                placed[size_t(k)] = true;
                ++count;
            }
            if (count == 0)
                continue;
            shell.Closed(BRep_Tool::IsClosed(shell));
            shells.push_back(shell);
        }
        for (size_t k = 0; k < recorded.faces.size(); ++k) {
            if (placed[k] || recorded.faces[k].IsNull())
                continue;
            TopoDS_Shell shell;
            b.MakeShell(shell);
            b.Add(shell, recorded.faces[k]);
            if (BRep_Tool::IsClosed(shell))
                shells.push_back(shell);
            else
                loose.push_back(recorded.faces[k]);
        }
        // Shells of the sewn shape, and faces sewn to no other face each as a shell of its own
        // (a sphere or a torus is one face that closes on itself).
        TopTools_IndexedMapOfShape inShells;
        for (TopExp_Explorer e(sewn, TopAbs_SHELL); !sewn.IsNull() && e.More(); e.Next()) {
            shells.push_back(TopoDS::Shell(e.Current()));
            TopExp::MapShapes(e.Current(), TopAbs_FACE, inShells);
        }
        for (TopExp_Explorer e(sewn, TopAbs_FACE, TopAbs_SHELL); !sewn.IsNull() && e.More();
             e.Next()) {
            if (inShells.Contains(e.Current()))
                continue;
            TopoDS_Shell shell;
            b.MakeShell(shell);
            b.Add(shell, e.Current());
            if (BRep_Tool::IsClosed(shell))
                shells.push_back(shell);
            else
                loose.push_back(TopoDS::Face(e.Current()));
        }
        const auto hasOpenSeam = [&](const TopoDS_Shell& shell) {
            for (TopExp_Explorer f(shell, TopAbs_FACE); f.More(); f.Next())
                if (ids.IsBound(f.Current()) && onOpenSeam[size_t(ids.Find(f.Current()))])
                    return true;
            return false;
        };
        for (const TopoDS_Shell& shell : shells) {
            if (BRep_Tool::IsClosed(shell) && hasOpenSeam(shell)) {
                report.warnings << QStringLiteral("a shell closed within the sewing tolerance "
                                                  "has seams opened beyond their own tolerance: "
                                                  "written as a shell");
            } else if (BRep_Tool::IsClosed(shell)) {
                // Sewing, and the record's build, orient a closed shell's faces consistently;
                // which way the whole shell faces is found by classifying a point at infinity
                // (BRepLib::OrientClosedSolid): the sign of the enclosed volume said the same at
                // seven times the cost (0.3 s of hammer.iges's 0.9 s export).
                TopoDS_Solid solid;
                b.MakeSolid(solid);
                b.Add(solid, shell);
                if (BRepLib::OrientClosedSolid(solid)) {
                    b.Add(result, solid);
                    ++report.solids;
                    continue;
                }
                TopTools_IndexedMapOfShape shellFaces;
                TopExp::MapShapes(shell, TopAbs_FACE, shellFaces);
                report.warnings << QStringLiteral("a closed shell of %1 face(s) does not bound a "
                                                  "valid solid: written as a shell")
                                       .arg(shellFaces.Extent());
            }
            b.Add(result, shell);
            ++report.openShells;
        }
        for (const TopoDS_Face& f : loose) {
            b.Add(result, f);
            ++report.looseFaces;
        }
        TopTools_IndexedMapOfShape written;
        TopExp::MapShapes(result, TopAbs_FACE, written);
        report.faces = written.Extent();
        if (report.faces != n)
            report.warnings << QStringLiteral("%1 surface(s) became %2 face(s) when sewn")
                                   .arg(n)
                                   .arg(report.faces);
        const std::vector<FreeEdge> free = freeEdges(result, ids);
        report.freeEdges = int(free.size());
        if (!hadRecord) {
            report.warnings << seamLines.mid(0, kMaxSeamLines);
            if (seamLines.size() > kMaxSeamLines)
                report.warnings
                    << QStringLiteral("%1 more open seam(s)").arg(seamLines.size() - kMaxSeamLines);
            reportFreeEdges(free, names, diagonal, scene.unit, farFaces, report);
        } else {
            // The record names the open seams; free edges beyond them are open boundaries.
            report.warnings << seamLines.mid(0, kMaxSeamLines);
            if (seamLines.size() > kMaxSeamLines)
                report.warnings
                    << QStringLiteral("%1 more open seam(s)").arg(seamLines.size() - kMaxSeamLines);
            if (!free.empty())
                report.warnings
                    << QStringLiteral("%1 edge(s) bound no other face").arg(free.size());
        }
        if (options.requireClosed && (report.openShells > 0 || report.looseFaces > 0)) {
            int outside = 0; // loose faces and faces of open shells
            for (TopExp_Explorer f(result, TopAbs_FACE, TopAbs_SHELL); f.More(); f.Next())
                ++outside;
            for (TopExp_Explorer sh(result, TopAbs_SHELL, TopAbs_SOLID); sh.More(); sh.Next())
                for (TopExp_Explorer f(sh.Current(), TopAbs_FACE); f.More(); f.Next())
                    ++outside;
            const QString first = report.warnings.isEmpty()
                                      ? QString()
                                      : QStringLiteral("; ") + report.warnings.front();
            return fail(QStringLiteral("%1: not written: %2 of %3 face(s) do not end in a closed "
                                       "solid (--require-closed)%4")
                            .arg(path)
                            .arg(outside)
                            .arg(report.faces)
                            .arg(first));
        }

        // The built shape is all the writer needs: the scene's copy goes before the writer's
        // model and text, the peak of a large export.
        std::vector<Surface>().swap(scene.surfaces);
        scene.topology = {};
        QElapsedTimer writer;
        writer.start();
        Expected<QByteArray> bytes = format == CadFormat::Step
                                         ? writeStep(result, path, options, scene.unit, ids, names)
                                         : writeIges(result, options, scene.unit, ids, names);
        if (!bytes)
            return fail(QStringLiteral("%1: %2").arg(path, bytes.message()));
        report.writerSeconds = writer.nsecsElapsed() * 1e-9;
        step(kSteps);
        report.seconds = timer.nsecsElapsed() * 1e-9;
        return bytes;
    } catch (const Standard_Failure& e) {
        return fail(
            QStringLiteral("%1: OpenCASCADE failed writing the file: %2").arg(path, failure(e)));
    }
}

Status exportOcctFile(const Scene& scene, const QString& path, const ExportOptions& options,
                      ExportReport& report, const ImportProgress& progress) {
    const Expected<QByteArray> bytes = exportOcctBytes(scene, path, options, report, progress);
    if (!bytes)
        return bytes.error();
    return saveBytesAtomically(path, *bytes);
}

} // namespace kw
