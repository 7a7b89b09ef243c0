// IGES, STEP and BREP files through OpenCASCADE: read, check, transfer, convert every face.
#include "model/cad/occtimport.h"

#include "model/cad/cadprecheck.h"
#include "model/cad/igesrepair.h"
#include "model/cad/occt_internal.h"
#include "model/cad/occtranges.h"
#include "model/io/safetext.h"

#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <Interface_Check.hxx>
#include <Interface_CheckIterator.hxx>
#include <Interface_InterfaceModel.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_ProgressIndicator.hxx>
#include <Message_ProgressScope.hxx>
#include <OSD.hxx>
#include <QFile>
#include <QHash>
#include <QTemporaryFile>
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shape.hxx>
#include <TransferBRep.hxx>
#include <Transfer_Binder.hxx>
#include <Transfer_TransientProcess.hxx>
#include <UnitsMethods.hxx>
#include <XSControl_TransferReader.hxx>
#include <XSControl_WorkSession.hxx>
#include <fstream>
#include <mutex>
#include <vector>

namespace kw {
namespace {

// Progress of the whole import in 1000 steps: transfer 0..400, faces 400..1000.
constexpr int kSteps = 1000;
constexpr int kTransferSteps = 400;

// Forwards OCCT's transfer progress to the caller's callback and asks it whether to go on.
class ProgressBridge : public Message_ProgressIndicator {
public:
    explicit ProgressBridge(const ImportProgress& progress) : m_progress(progress) {}
    Standard_Boolean UserBreak() override { return m_cancelled; }
    void Show(const Message_ProgressScope&, const Standard_Boolean) override {
        if (m_progress && !m_progress(static_cast<int>(GetPosition() * kTransferSteps), kSteps))
            m_cancelled = true;
    }
    bool cancelled() const { return m_cancelled; }

private:
    ImportProgress m_progress;
    bool m_cancelled = false;
};

void setUpOcctOnce() {
    static std::once_flag once;
    std::call_once(once, [] {
        // Signals (SIGSEGV, SIGFPE, ...) inside OCC_CATCH_SIGNALS become Standard_Failure.
        OSD::SetSignal(OSD_SignalMode_Set, Standard_False);
        // OCCT's own console messages would mix with ours; errors are reported by us.
        Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_Printer));
        // Keep B-spline surfaces whole: do not split them at C0 knots into several faces.
        Interface_Static::SetIVal("read.iges.bspline.continuity", 0);
    });
}

// The first few load failures of a file (syntax errors, truncated records), or empty.
QString loadFailures(const Handle(XSControl_WorkSession) & ws) {
    QStringList lines;
    Interface_CheckIterator checks = ws->ModelCheckList(Standard_False);
    for (checks.Start(); checks.More() && lines.size() < 3; checks.Next()) {
        const Handle(Interface_Check)& c = checks.Value();
        for (int i = 1; i <= c->NbFails() && lines.size() < 3; ++i)
            lines << occtMessageText(c->Fail(i)->ToCString());
    }
    return lines.join(QStringLiteral("; "));
}

// Whether every load failure is a string parameter (a name or description) holding something
// else, such as $: OCCT then sets it to the empty string and reads the rest of the entity.
bool onlyUnsetNames(const Handle(XSControl_WorkSession) & ws) {
    Interface_CheckIterator checks = ws->ModelCheckList(Standard_False);
    int fails = 0;
    for (checks.Start(); checks.More(); checks.Next()) {
        const Handle(Interface_Check)& c = checks.Value();
        for (int i = 1; i <= c->NbFails(); ++i, ++fails)
            if (!QByteArray(c->Fail(i)->ToCString()).contains("not a quoted String"))
                return false;
    }
    return fails > 0;
}

// Structural checks OCCT's parsers are lenient about: a STEP file must end with its
// END-ISO-10303-21 line, an IGES file with its Terminate (T) record.
QString truncation(const QString& path, CadFormat format) {
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly))
        return QStringLiteral("cannot open: %1").arg(f.errorString());
    const qint64 size = f.size();
    f.seek(std::max<qint64>(0, size - 4096));
    const QByteArray tail = f.readAll().trimmed();
    if (format == CadFormat::Step && !tail.endsWith("END-ISO-10303-21;"))
        return QStringLiteral("truncated STEP file: it does not end with 'END-ISO-10303-21;'");
    if (format == CadFormat::Iges) {
        const QByteArray last = tail.mid(tail.lastIndexOf('\n') + 1);
        if (last.size() < 73 || last[72] != 'T')
            return QStringLiteral("truncated IGES file: the last record is not the Terminate "
                                  "section (column 73 'T')");
    }
    return {};
}

// Where a face came from in the file: the name of its entity and, for IGES, the entity type
// (144/143 are trimmed/bounded surfaces; any other type is an untrimmed surface); for STEP the
// name of the innermost product holding it (the one with the fewest faces), which names the
// faces the file leaves unnamed.
struct FaceOrigin {
    QString name;
    int igesType = 0;
    bool fromFaceEntity = false;
    QString product;
    int productFaces = 0; ///< faces of that product's shape (0: none)
};

// Walks the transfer's entity -> shape records and assigns each face of `faces` the entity
// that produced exactly that face (or, failing that, a named entity holding only that face).
std::vector<FaceOrigin> faceOrigins(const Handle(XSControl_TransferReader) & reader,
                                    const occt::ExchangeFormat* format,
                                    const TopTools_IndexedMapOfShape& faces) {
    std::vector<FaceOrigin> origins(faces.Extent() + 1);
    if (!format || reader.IsNull() || reader->TransientProcess().IsNull())
        return origins;
    const Handle(Transfer_TransientProcess) tp = reader->TransientProcess();
    for (int i = 1; i <= tp->NbMapped(); ++i) {
        const TopoDS_Shape shape = TransferBRep::ShapeResult(tp->MapItem(i));
        if (shape.IsNull())
            continue;
        TopTools_IndexedMapOfShape inside;
        TopExp::MapShapes(shape, TopAbs_FACE, inside);
        if (const QString product =
                format->productName ? format->productName(tp->Mapped(i)) : QString();
            !product.isEmpty())
            for (int f = 1; f <= inside.Extent(); ++f)
                if (const int index = faces.FindIndex(inside(f)); index != 0) {
                    FaceOrigin& o = origins[size_t(index)];
                    if (o.productFaces == 0 || inside.Extent() < o.productFaces) {
                        o.product = product;
                        o.productFaces = inside.Extent();
                    }
                }
        if (inside.Extent() != 1)
            continue;
        const int index = faces.FindIndex(inside(1));
        if (index == 0)
            continue;
        const bool isFace = shape.ShapeType() == TopAbs_FACE;
        FaceOrigin& o = origins[index];
        if (o.fromFaceEntity && !isFace)
            continue; // the entity that made exactly this face wins over its containers
        int igesType = 0;
        const QString name = format->entityName(tp->Mapped(i), &igesType);
        if (!name.isEmpty())
            o.name = name;
        if (isFace) {
            o.fromFaceEntity = true;
            o.igesType = igesType;
        }
    }
    return origins;
}

struct ReadShape {
    TopoDS_Shape shape;
    std::unique_ptr<XSControl_Reader> reader;     // kept alive: it owns the transfer records
    Handle(XSControl_TransferReader) names;       // null for BREP
    const occt::ExchangeFormat* format = nullptr; // null for BREP
    QStringList notes;                            // for the report's warnings
    QStringList skipped;                          // root entities that gave no shape
    LengthUnit unit = LengthUnit::Millimetre;     // the file's, which the shape is in
};

// Reads and transfers the file into `out`; refused with the fault (not naming the file) on any.
Status readShape(const QString& path, CadFormat format, ProgressBridge& bridge, ReadShape& out) {
    const QByteArray native = QFile::encodeName(path);
    if (format == CadFormat::Brep) {
        if (Status checked = checkCadFile(path, format); !checked)
            return checked;
        std::ifstream in(native.constData(), std::ios::binary);
        if (!in)
            return Error(QStringLiteral("cannot open the file"));
        // OCCT's BREP reader loops for ever on a truncated file or on a section count larger
        // than its data (it reads on past the end without checking the stream). With
        // exceptions on, every read that fails (past the end, a word where a number belongs)
        // throws instead; complete files never fail a read (tested on the OCCT samples).
        in.exceptions(std::ios::failbit | std::ios::badbit);
        BRep_Builder builder;
        try {
            BRepTools::Read(out.shape, in, builder, bridge.Start());
        } catch (const std::ios_base::failure&) {
            return Error(
                QStringLiteral("truncated or corrupt BREP file: a section ends before the "
                               "count of entries its header states (read failed at byte "
                               "%1)")
                    .arg(in.rdbuf() ? qint64(in.rdbuf()->pubseekoff(0, std::ios::cur)) : -1));
        }
        if (out.shape.IsNull())
            return Error(QStringLiteral("not a readable BREP file"));
        return ok();
    }
    QString cut = truncation(path, format);
    if (cut.isEmpty()) // numbers and lists OCCT would choke on (cadprecheck.h)
        cut = checkCadFile(path, format).message();
    if (!cut.isEmpty())
        return Error(cut);
    QByteArray fileToRead = native;
    QTemporaryFile repaired;
    if (format == CadFormat::Iges) {
        QFile f(path);
        QString note;
        std::optional<QByteArray> fixed;
        if (f.open(QIODevice::ReadOnly))
            fixed = repairIgesNumbering(f.readAll(), note);
        if (fixed) {
            if (!repaired.open() || repaired.write(*fixed) != fixed->size() || !repaired.flush())
                return Error(
                    QStringLiteral("cannot write a repaired copy: %1").arg(repaired.errorString()));
            fileToRead = QFile::encodeName(repaired.fileName());
            out.notes << note;
        }
    }
    out.format = occt::exchangeFormat(format);
    if (!out.format) // a module built for other formats (cmd_readcad.cpp picks the right one)
        return Error(QStringLiteral("this OpenCASCADE module does not read %1 files")
                         .arg(cadFormatName(format)));
    std::unique_ptr<XSControl_Reader> reader = out.format->makeReader();
    if (reader->ReadFile(fileToRead.constData()) != IFSelect_RetDone) {
        const QString why = loadFailures(reader->WS());
        return Error(QStringLiteral("not a readable %1 file%2")
                         .arg(cadFormatName(format),
                              why.isEmpty() ? QString() : QStringLiteral(": ") + why));
    }
    // Entities the parser could not make sense of mean a corrupt file: refuse it rather than
    // import what happens to survive. The one exception is a name or description that is not a
    // string: Rhino writes `$` (unset) there, e.g. AXIS2_PLACEMENT_3D($, ...). OCCT reads such an
    // entity whole with an empty name, so its geometry is intact; warn, as OCCT does.
    const Handle(Interface_InterfaceModel) model = reader->WS()->Model();
    int broken = 0;
    for (int i = 1; i <= model->NbEntities(); ++i)
        broken += model->IsErrorEntity(i) ? 1 : 0;
    if (broken > 0 && format == CadFormat::Step && onlyUnsetNames(reader->WS())) {
        out.notes << QStringLiteral("%1 of %2 entities have a name that is not a string (such as "
                                    "$, as Rhino writes); read with empty names")
                         .arg(broken)
                         .arg(model->NbEntities());
        broken = 0;
    }
    if (broken > 0)
        return Error(QStringLiteral("corrupt %1 file: %2 of %3 entities could not be parsed (%4)")
                         .arg(cadFormatName(format))
                         .arg(broken)
                         .arg(model->NbEntities())
                         .arg(loadFailures(reader->WS())));
    // The shape is made in the file's own unit (OCCT's "cascade" unit set to it), so every
    // coordinate stays the number the file holds; a file that names no unit Knotwork knows is
    // read in millimetres, OCCT's default.
    if (const std::optional<LengthUnit> unit = out.format->fileUnit(*reader))
        out.unit = *unit;
    Interface_Static::SetIVal("xstep.cascade.unit", igesUnitFlag(out.unit));
    UnitsMethods::SetCasCadeLengthUnit(igesUnitFlag(out.unit));
    const int roots = reader->NbRootsForTransfer();
    reader->TransferRoots(bridge.Start());
    if (bridge.cancelled())
        return Error(QStringLiteral("import cancelled"));
    // Root entities that produced no shape are reported, not silently dropped.
    const Handle(Transfer_TransientProcess) tp = reader->WS()->TransferReader()->TransientProcess();
    for (int i = 1; i <= roots && !tp.IsNull(); ++i) {
        const Handle(Standard_Transient) root = reader->RootForTransfer(i);
        if (root.IsNull() || !TransferBRep::ShapeResult(tp, root).IsNull())
            continue;
        QString why = QStringLiteral("OpenCASCADE could not transfer it");
        const Handle(Transfer_Binder) binder = tp->Find(root);
        if (!binder.IsNull() && binder->Check()->NbFails() > 0)
            why += QStringLiteral(": ") + occtMessageText(binder->Check()->Fail(1)->ToCString());
        const Handle(TCollection_HAsciiString) label = model->StringLabel(root);
        out.skipped << QStringLiteral("entity %1 (%2): %3")
                           .arg(label.IsNull() ? QStringLiteral("?")
                                               : QString::fromUtf8(label->ToCString()),
                                QString::fromLatin1(root->DynamicType()->Name()), why);
    }
    out.shape = reader->OneShape();
    out.names = reader->WS()->TransferReader();
    out.reader = std::move(reader);
    if (out.shape.IsNull())
        return Error(QStringLiteral("the %1 file holds no shape that could be transferred%2")
                         .arg(cadFormatName(format),
                              out.skipped.isEmpty()
                                  ? QString()
                                  : QStringLiteral(" (") + out.skipped.front() + QLatin1Char(')')));
    return ok();
}

} // namespace

namespace occt {

Expected<ImportResult> importShape(const QString& path, CadFormat format,
                                   const ImportProgress& progress, const AfterImport& after) {
    setUpOcctOnce();
    // Also in this thread (the editor imports on a worker thread): FPE masks and handlers.
    OSD::SetThreadLocalSignal(OSD_SignalMode_Set, Standard_False);
    Handle(ProgressBridge) bridgeHandle = new ProgressBridge(progress);
    ProgressBridge& bridge = *bridgeHandle;
    ReadShape read;
    ImportResult result;
    TopTools_IndexedMapOfShape faces;
    std::vector<FaceOrigin> origins;
    try {
        OCC_CATCH_SIGNALS
        if (const Status readable = readShape(path, format, bridge, read); !readable) {
            return Error(bridge.cancelled()
                             ? QStringLiteral("%1: import cancelled").arg(path)
                             : QStringLiteral("%1: %2").arg(path, readable.message()),
                         path);
        }
        TopExp::MapShapes(read.shape, TopAbs_FACE, faces);
        origins = faceOrigins(read.names, read.format, faces);
        for (const QString& n : read.notes)
            result.report.warnings << n;
        result.report.skipped << read.skipped;
    } catch (const Standard_Failure& e) {
        return Error(QStringLiteral("%1: OpenCASCADE failed reading the file: %2 (%3)")
                         .arg(path, occtMessageText(e.GetMessageString()),
                              QString::fromLatin1(e.DynamicType()->Name())),
                     path);
    }
    if (faces.IsEmpty()) {
        return Error(QStringLiteral("%1: the file holds no faces to import").arg(path), path);
    }

    Scene& scene = result.scene;
    scene.unit = read.unit;
    std::vector<occt::FaceEdges> faceEdges; // parallel to scene.surfaces
    QHash<QString, int> productFaces;       // unnamed faces numbered within their product
    for (int k = 1; k <= faces.Extent(); ++k) {
        if (progress &&
            !progress(kTransferSteps + (kSteps - kTransferSteps) * (k - 1) / faces.Extent(),
                      kSteps)) {
            return Error(QStringLiteral("%1: import cancelled").arg(path), path);
        }
        const TopoDS_Face& face = TopoDS::Face(faces(k));
        Surface surface;
        QString why;
        QStringList warnings;
        QString name;
        occt::FaceEdges edges;
        bool ok = false;
        try {
            OCC_CATCH_SIGNALS
            name = origins[k].name;
            // IGES surfaces that are not trimmed (144) or bounded (143) have no boundary in
            // the file: OCCT's natural wire is not kept. Other formats state their bounds.
            const int type = origins[k].igesType;
            const bool untrimmedInFile =
                format == CadFormat::Iges && (type == 0 || (type != 144 && type != 143));
            std::uint32_t ids = scene.nextId + 1; // the surface id comes first
            // An edge range outside its curve sends the conversion's projections into a
            // minute of approximation: such a face is skipped before they see it.
            Status converted = occt::checkEdgeRanges(face);
            if (converted)
                converted =
                    occt::convertFace(face, surface, ids, untrimmedInFile, warnings, &edges);
            ok = bool(converted);
            why = converted.message();
            if (ok) {
                surface.id = SurfaceId{scene.nextId};
                scene.nextId = ids;
            }
        } catch (const Standard_Failure& e) {
            why = QStringLiteral("OpenCASCADE failed: %1 (%2)")
                      .arg(occtMessageText(e.GetMessageString()),
                           QString::fromLatin1(e.DynamicType()->Name()));
        }
        const QString& product = origins[k].product;
        const QString label =
            !name.isEmpty() ? name
            : product.isEmpty()
                ? QStringLiteral("Face %1").arg(k)
                : QStringLiteral("%1 face %2").arg(product).arg(++productFaces[product]);
        for (const QString& w : warnings)
            result.report.warnings << QStringLiteral("face %1 (%2): %3").arg(k).arg(label, w);
        if (!ok) {
            result.report.skipped << QStringLiteral("face %1 (%2): %3").arg(k).arg(label, why);
            continue;
        }
        surface.name = label;
        scene.surfaces.push_back(std::move(surface));
        faceEdges.push_back(std::move(edges));
        result.sourceFaces.push_back(k);
        ++result.report.facesImported;
    }
    if (scene.surfaces.empty()) {
        return Error(
            QStringLiteral("%1: none of the %2 face(s) could be imported; first reason: %3")
                .arg(path)
                .arg(faces.Extent())
                .arg(result.report.skipped.value(0)),
            path);
    }
    // Faces lying on one another: a defect of the file that shows as either face, pixel by
    // pixel, where both are drawn.
    try {
        OCC_CATCH_SIGNALS
        QStringList labels;
        for (const Surface& s : scene.surfaces)
            labels << s.name;
        result.report.warnings << coincidentFaces(read.shape, faces, result.sourceFaces, labels,
                                                  20);
    } catch (const Standard_Failure& e) {
        result.report.warnings << QStringLiteral("the check for coincident faces failed: %1")
                                      .arg(occtMessageText(e.GetMessageString()));
    }
    // Closed solids: the renderer skips their polygons' back faces.
    try {
        OCC_CATCH_SIGNALS
        markClosedSolids(read.shape, faces, result.sourceFaces, scene);
    } catch (const Standard_Failure& e) {
        for (Surface& s : scene.surfaces)
            s.solid = -1;
        result.report.warnings << QStringLiteral("the check for closed solids failed: %1")
                                      .arg(occtMessageText(e.GetMessageString()));
    }
    // Which trim curves are one edge, which faces one shell: kept for the writers and for
    // the seam check after edits (model/document/topology.h, model/document/seamgaps.h).
    try {
        OCC_CATCH_SIGNALS
        recordTopology(read.shape, faces, result.sourceFaces, faceEdges, scene,
                       result.report.warnings);
    } catch (const Standard_Failure& e) {
        scene.topology = Topology{};
        result.report.warnings << QStringLiteral("the record of shared edges and shells failed: "
                                                 "%1; the faces are kept as loose faces")
                                      .arg(QString::fromUtf8(e.GetMessageString()));
    }
    if (after)
        if (Status done = after(read.shape, faces, result); !done)
            return Error(std::move(done).error().message, path);
    if (progress)
        progress(kSteps, kSteps);
    return result;
}

} // namespace occt

Expected<ImportResult> importOcctFile(const QString& path, CadFormat format,
                                      const ImportProgress& progress) {
    return occt::importShape(path, format, progress, {});
}

} // namespace kw
