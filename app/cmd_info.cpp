// knotwork info FILE [--json] [--continuity]: a summary of a .knot project's surfaces, topology,
// lights and camera, or the continuity of its edges.
#include "app/commands.h"
#include "app/info_continuity.h"
#include "model/analysis/mass_properties.h"
#include "model/cad/cadimport.h"
#include "model/document/seamgaps.h"
#include "model/nurbs/analytic_eval.h"
#include "model/nurbs/trim.h"

#include <QCommandLineParser>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <algorithm>
#include <set>

namespace kw::cli {

namespace {

/// Domain of a knot vector and how many distinct knot values lie strictly inside it.
struct KnotSummary {
    Interval domain;
    int knots = 0;
    int distinctInterior = 0;
};

KnotSummary summarise(const std::vector<double>& knots, int degree) {
    KnotSummary k;
    k.domain = knotDomain(knots, degree);
    k.knots = int(knots.size());
    std::set<double> interior;
    for (double t : knots)
        if (t > k.domain.first && t < k.domain.last)
            interior.insert(t);
    k.distinctInterior = int(interior.size());
    return k;
}

bool isRational(const NurbsSurface& g) {
    for (double w : g.weights)
        if (w != g.weights.front())
            return true;
    return false;
}

QJsonArray vec(const glm::dvec3& v) {
    return QJsonArray{v.x, v.y, v.z};
}

QJsonValue bboxJson(const glm::dvec3& lo, const glm::dvec3& hi) {
    return QJsonObject{{QStringLiteral("min"), vec(lo)}, {QStringLiteral("max"), vec(hi)}};
}

QString text(const glm::dvec3& v) {
    return QStringLiteral("(%1, %2, %3)").arg(v.x).arg(v.y).arg(v.z);
}

QJsonObject knotJson(const KnotSummary& k) {
    return QJsonObject{{QStringLiteral("first"), k.domain.first},
                       {QStringLiteral("last"), k.domain.last},
                       {QStringLiteral("count"), k.knots},
                       {QStringLiteral("distinctInterior"), k.distinctInterior}};
}

QString knotText(const KnotSummary& k) {
    return QStringLiteral("[%1, %2], %3 knots, %4 distinct interior")
        .arg(k.domain.first)
        .arg(k.domain.last)
        .arg(k.knots)
        .arg(k.distinctInterior);
}

QString lightKind(const Light& l) {
    return l.kind == Light::Kind::Point ? QStringLiteral("point") : QStringLiteral("directional");
}

// The topology kept from a B-rep import and what edits did to it: the shared edges, how many
// are open (seamGaps: their sides lie farther apart than the edge's tolerance), and each shell,
// closed or not.
struct TopologySummary {
    std::vector<SeamGap> gaps;
    std::vector<ShellState> shells;
    int open = 0;
};

TopologySummary summariseTopology(const Scene& scene) {
    TopologySummary t;
    t.gaps = seamGaps(scene);
    t.shells = closedShells(scene, t.gaps);
    t.open =
        int(std::count_if(t.gaps.begin(), t.gaps.end(), [](const SeamGap& g) { return g.open(); }));
    return t;
}

QJsonObject topologyJson(const Scene& scene) {
    const TopologySummary t = summariseTopology(scene);
    QJsonArray shells;
    for (size_t k = 0; k < t.shells.size(); ++k) {
        const ShellState& s = t.shells[k];
        QJsonObject o{{QStringLiteral("id"), qint64(s.shell.value)},
                      {QStringLiteral("faces"), s.faces},
                      {QStringLiteral("recordedClosed"), scene.topology.shells[k].closed},
                      {QStringLiteral("closed"), s.closed},
                      {QStringLiteral("openEdges"), s.openEdges},
                      {QStringLiteral("largestGap"), s.largestGap}};
        if (s.solid >= 0)
            o.insert(QStringLiteral("solid"), s.solid);
        shells.append(o);
    }
    QJsonArray open;
    for (const SeamGap& g : t.gaps)
        if (g.open())
            open.append(QJsonObject{{QStringLiteral("edge"), qint64(g.edge.value)},
                                    {QStringLiteral("faceA"), qint64(g.faceA.value)},
                                    {QStringLiteral("faceB"), qint64(g.faceB.value)},
                                    {QStringLiteral("gap"), g.gap},
                                    {QStringLiteral("tolerance"), g.tolerance},
                                    {QStringLiteral("where"), vec(g.where)}});
    double largest = 0.0;
    for (const SeamGap& g : t.gaps)
        largest = std::max(largest, g.gap);
    return QJsonObject{{QStringLiteral("sharedEdges"), int(t.gaps.size())},
                       {QStringLiteral("openEdges"), open},
                       {QStringLiteral("largestGap"), largest},
                       {QStringLiteral("shells"), shells}};
}

QString topologyText(const Scene& scene) {
    if (scene.topology.empty())
        return QStringLiteral("topology: none (loose faces)\n");
    const TopologySummary t = summariseTopology(scene);
    QString out = QStringLiteral("topology: %1 shared edge(s), %2 open; %3 shell(s)\n")
                      .arg(t.gaps.size())
                      .arg(t.open)
                      .arg(t.shells.size());
    const auto name = [&scene](SurfaceId id) {
        for (const Surface& s : scene.surfaces)
            if (s.id == id)
                return QStringLiteral("%1 \"%2\"").arg(id.value).arg(s.name);
        return QString::number(id.value);
    };
    for (size_t k = 0; k < t.shells.size(); ++k) {
        const ShellState& s = t.shells[k];
        QString state = s.closed ? QStringLiteral("closed") : QStringLiteral("open");
        if (!scene.topology.shells[k].closed)
            state += QStringLiteral(" (not closed as recorded)");
        else if (s.openEdges > 0)
            state += QStringLiteral(" (%1 seam(s) apart, largest gap %2 %3)")
                         .arg(s.openEdges)
                         .arg(s.largestGap, 0, 'g', 3)
                         .arg(lengthUnitKey(scene.unit));
        out += QStringLiteral("  shell %1: %2 face(s)%3, %4\n")
                   .arg(s.shell.value)
                   .arg(s.faces)
                   .arg(s.solid >= 0 ? QStringLiteral(", solid %1").arg(s.solid) : QString())
                   .arg(state);
    }
    // All of them are in --json; the text names the first few.
    constexpr int kListed = 20;
    int listed = 0;
    for (const SeamGap& g : t.gaps)
        if (g.open() && listed++ < kListed)
            out += QStringLiteral("  edge %1 between surfaces %2 and %3 open: gap %4 %7 "
                                  "(tolerance %5) at %6\n")
                       .arg(g.edge.value)
                       .arg(name(g.faceA), name(g.faceB))
                       .arg(g.gap, 0, 'g', 4)
                       .arg(g.tolerance, 0, 'g', 3)
                       .arg(text(g.where))
                       .arg(lengthUnitKey(scene.unit));
    if (listed > kListed)
        out += QStringLiteral("  %1 more open edge(s) (--json lists them all)\n")
                   .arg(listed - kListed);
    return out;
}

QJsonObject toJson(const QString& file, const Scene& scene) {
    const ModelProperties model = modelProperties(scene);
    QJsonArray surfaces;
    for (size_t k = 0; k < scene.surfaces.size(); ++k) {
        const Surface& s = scene.surfaces[k];
        const NurbsSurface& g = s.geometry;
        QJsonArray loops;
        const QStringList warnings = trimWarnings(s);
        for (const TrimLoop& loop : s.trims)
            loops.append(QJsonObject{{QStringLiteral("id"), qint64(loop.id.value)},
                                     {QStringLiteral("curves"), int(loop.curves.size())}});
        QJsonObject o{
            {QStringLiteral("id"), qint64(s.id.value)},
            {QStringLiteral("name"), s.name},
            {QStringLiteral("degreeU"), g.degreeU},
            {QStringLiteral("degreeV"), g.degreeV},
            {QStringLiteral("countU"), g.countU},
            {QStringLiteral("countV"), g.countV},
            {QStringLiteral("rational"), isRational(g)},
            {QStringLiteral("knotsU"), knotJson(summarise(g.knotsU, g.degreeU))},
            {QStringLiteral("knotsV"), knotJson(summarise(g.knotsV, g.degreeV))},
            {QStringLiteral("trimLoops"), loops},
            {QStringLiteral("trimWarnings"), QJsonArray::fromStringList(warnings)},
            {QStringLiteral("partitions"), QJsonArray{s.partitionsU, s.partitionsV}},
            {QStringLiteral("color"), vec(s.material.color)},
        };
        const FaceProperties& props = model.faces[k];
        o.insert(QStringLiteral("type"), surfaceTypeName(props.type));
        // The closed form the importer kept (Surface::analytic), "none" once edited.
        o.insert(QStringLiteral("analytic"),
                 QString::fromLatin1(analyticKindName(s.analytic.kind)));
        o.insert(QStringLiteral("area"), props.area);
        if (props.approximate) // hostile trims spent the exact measure's budget
            o.insert(QStringLiteral("areaApproximate"), true);
        o.insert(QStringLiteral("bbox"),
                 props.hasBounds ? bboxJson(props.lo, props.hi) : QJsonValue(QJsonValue::Null));
        if (s.solid >= 0) // as the .knot file writes it (docs/FILE_FORMAT.md, "Solid")
            o.insert(QStringLiteral("solid"),
                     QJsonObject{{QStringLiteral("index"), s.solid},
                                 {QStringLiteral("outside"), s.outsideAlongNormal
                                                                 ? QStringLiteral("normal")
                                                                 : QStringLiteral("reversed")}});
        surfaces.append(o);
    }
    QJsonArray lights;
    for (const Light& l : scene.lights)
        lights.append(QJsonObject{{QStringLiteral("kind"), lightKind(l)},
                                  {QStringLiteral("vector"), vec(l.vector)}});
    QJsonObject root{{QStringLiteral("file"), file},
                     {QStringLiteral("surfaces"), surfaces},
                     {QStringLiteral("lights"), lights},
                     {QStringLiteral("topology"), topologyJson(scene)},
                     {QStringLiteral("unit"), lengthUnitKey(scene.unit)},
                     {QStringLiteral("nextId"), qint64(scene.nextId)}};
    root.insert(QStringLiteral("area"), model.area);
    if (model.approximate)
        root.insert(QStringLiteral("areaApproximate"), true);
    root.insert(QStringLiteral("volume"),
                model.volume ? QJsonValue(*model.volume) : QJsonValue(QJsonValue::Null));
    root.insert(QStringLiteral("bbox"),
                model.hasBounds ? bboxJson(model.lo, model.hi) : QJsonValue(QJsonValue::Null));
    if (scene.camera.authored)
        root.insert(QStringLiteral("camera"),
                    QJsonObject{{QStringLiteral("eye"), vec(scene.camera.eye)},
                                {QStringLiteral("target"), vec(scene.camera.target)},
                                {QStringLiteral("up"), vec(scene.camera.up)},
                                {QStringLiteral("fovYDegrees"), scene.camera.fovYDegrees}});
    else
        root.insert(QStringLiteral("camera"), QJsonValue::Null);
    return root;
}

QString toText(const QString& file, const Scene& scene) {
    const ModelProperties model = modelProperties(scene);
    QString out = QStringLiteral("%1: %2 surface(s), %3 light(s)\n")
                      .arg(file)
                      .arg(scene.surfaces.size())
                      .arg(scene.lights.size());
    out += QStringLiteral("unit: %1 (lengths below are in it)\n").arg(lengthUnitName(scene.unit));
    for (size_t k = 0; k < scene.surfaces.size(); ++k) {
        const Surface& s = scene.surfaces[k];
        const NurbsSurface& g = s.geometry;
        out += QStringLiteral("surface %1 \"%2\": degree %3 x %4, %5 x %6 control points%7\n")
                   .arg(s.id.value)
                   .arg(s.name)
                   .arg(g.degreeU)
                   .arg(g.degreeV)
                   .arg(g.countU)
                   .arg(g.countV)
                   .arg(isRational(g) ? QStringLiteral(", rational") : QString());
        const FaceProperties& props = model.faces[k];
        out += QStringLiteral("  type %1 (analytic form: %2), area %3%4\n")
                   .arg(surfaceTypeName(props.type))
                   .arg(QString::fromLatin1(analyticKindName(s.analytic.kind)))
                   .arg(QString::number(props.area, 'g', 12) +
                        (props.approximate ? QStringLiteral(" (approximate)") : QString()))
                   .arg(props.hasBounds
                            ? QStringLiteral(", bbox %1 .. %2").arg(text(props.lo), text(props.hi))
                            : QString());
        out += QStringLiteral("  knots u: %1\n").arg(knotText(summarise(g.knotsU, g.degreeU)));
        out += QStringLiteral("  knots v: %1\n").arg(knotText(summarise(g.knotsV, g.degreeV)));
        QStringList loops;
        for (const TrimLoop& loop : s.trims)
            loops << QStringLiteral("loop %1: %2 curve(s)")
                         .arg(loop.id.value)
                         .arg(loop.curves.size());
        out += QStringLiteral("  trims: %1\n")
                   .arg(loops.isEmpty() ? QStringLiteral("none")
                                        : QStringLiteral("%1 loop(s) (%2)")
                                              .arg(loops.size())
                                              .arg(loops.join(QStringLiteral(", "))));
        for (const QString& w : trimWarnings(s))
            out += QStringLiteral("  trim warning: %1\n").arg(w);
        out += QStringLiteral("  partitions: %1 x %2\n").arg(s.partitionsU).arg(s.partitionsV);
        if (s.solid >= 0)
            out += QStringLiteral("  face of closed solid %1, outside %2\n")
                       .arg(s.solid)
                       .arg(s.outsideAlongNormal ? QStringLiteral("along Su x Sv")
                                                 : QStringLiteral("against Su x Sv"));
    }
    out += topologyText(scene);
    out +=
        QStringLiteral("area: %1\nvolume: %2\n")
            .arg(QString::number(model.area, 'g', 12) +
                 (model.approximate ? QStringLiteral(" (approximate: hostile trims)") : QString()))
            .arg(model.volume ? QString::number(*model.volume, 'g', 12)
                              : QStringLiteral("none (no closed solid)"));
    if (model.hasBounds)
        out += QStringLiteral("bbox: %1 .. %2\n").arg(text(model.lo), text(model.hi));
    for (size_t k = 0; k < scene.lights.size(); ++k)
        out += QStringLiteral("light %1: %2 %3\n")
                   .arg(k + 1)
                   .arg(lightKind(scene.lights[k]), text(scene.lights[k].vector));
    if (scene.camera.authored)
        out += QStringLiteral("camera: eye %1, target %2, up %3, fov %4 deg\n")
                   .arg(text(scene.camera.eye), text(scene.camera.target), text(scene.camera.up))
                   .arg(scene.camera.fovYDegrees);
    else
        out += QStringLiteral("camera: none (views fit one to the scene)\n");
    return out;
}

} // namespace

int runInfo(const QStringList& args) {
    QCommandLineParser parser;
    parser.setApplicationDescription(QStringLiteral(
        "Summarise a .knot project (or a CAD file, imported): surfaces (id, name, "
        "degrees, control-point "
        "counts, knot ranges, trim loops, partitions, type, trimmed area, bounds), the "
        "shared edges and shells kept from a B-rep import (which seams are open), "
        "the model's area, closed-solid volume and bounds, lights and camera."));
    const QCommandLineOption json(QStringLiteral("json"), QStringLiteral("Print JSON."));
    parser.addOption(json);
    const QCommandLineOption continuity(
        QStringLiteral("continuity"),
        QStringLiteral("Instead, report the continuity of every edge where faces meet (G0 gap, "
                       "G1 angle, G2 curvature jump; recorded by the import or found by matching "
                       "boundaries), the free edges and the tolerances; with --json as "
                       "{\"edges\", \"freeEdges\", \"tolerances\"}."));
    parser.addOption(continuity);
    const ContinuityTolerances defaults;
    const QCommandLineOption g0(
        QStringLiteral("g0"),
        QStringLiteral("G0 tolerance in model units (default %1).").arg(defaults.g0),
        QStringLiteral("GAP"));
    const QCommandLineOption g1(
        QStringLiteral("g1"),
        QStringLiteral("G1 tolerance in degrees (default %1).").arg(defaults.g1Degrees),
        QStringLiteral("DEGREES"));
    const QCommandLineOption g2(
        QStringLiteral("g2"),
        QStringLiteral("G2 tolerance in percent (default %1).").arg(defaults.g2Percent),
        QStringLiteral("PERCENT"));
    const QCommandLineOption match(
        QStringLiteral("match"),
        QStringLiteral("How close boundaries of faces without a shared-edge record must lie to "
                       "be one edge, in model units (default %1).")
            .arg(defaults.match),
        QStringLiteral("DISTANCE"));
    parser.addOptions({g0, g1, g2, match});
    parser.addPositionalArgument(
        QStringLiteral("FILE"),
        QStringLiteral("A .knot project, or .igs/.iges, .stp/.step, .brep/.brp or .obj (imported "
                       "as 'knotwork convert' does; skipped faces and warnings on stderr)."));
    if (const int code = parseOrExit(parser, args); code >= 0)
        return code;
    const QStringList files = parser.positionalArguments();
    if (files.size() != 1) {
        printError(QStringLiteral("%1: expected one FILE, got %2 (see --help)")
                       .arg(args.value(0))
                       .arg(files.size()));
        return kExitUsage;
    }
    // The tolerances: the project's own (saved with it; the defaults for other files), each
    // replaced by its option when given. Checked once before reading the file (a usage error
    // should not wait for an import) and again with the project's values.
    std::optional<double> given[4];
    const QCommandLineOption* options[4] = {&g0, &g1, &g2, &match};
    for (int k = 0; k < 4; ++k) {
        if (!parser.isSet(*options[k]))
            continue;
        bool ok = false;
        given[k] = parser.value(*options[k]).toDouble(&ok);
        if (!ok) {
            printError(
                QStringLiteral("%1: --%2: not a number: '%3'")
                    .arg(args.value(0), options[k]->names().front(), parser.value(*options[k])));
            return kExitUsage;
        }
    }
    const auto withOptions = [&](ContinuityTolerances t) {
        double* values[4] = {&t.g0, &t.g1Degrees, &t.g2Percent, &t.match};
        for (int k = 0; k < 4; ++k)
            if (given[k])
                *values[k] = *given[k];
        // A G0 tolerance above the match distance takes the match distance with it.
        if (!given[3])
            t.match = std::max(t.match, t.g0);
        return t;
    };
    if (const QString why = checkContinuityTolerances(withOptions({})).message(); !why.isEmpty()) {
        printError(QStringLiteral("%1: tolerances: %2").arg(args.value(0), why));
        return kExitUsage;
    }
    const Expected<ImportResult> imported = openModelFile(files[0]);
    if (!imported) {
        printError(imported.message());
        return kExitBadInput;
    }
    printImportRemarks(files[0], imported->report);
    const Scene& scene = imported->scene;
    if (parser.isSet(continuity)) {
        const ContinuityTolerances tolerances = withOptions(continuityTolerances(scene));
        if (const QString why = checkContinuityTolerances(tolerances).message(); !why.isEmpty()) {
            printError(QStringLiteral("%1: tolerances: %2").arg(args.value(0), why));
            return kExitUsage;
        }
        const ContinuityReport report = continuityReport(scene, tolerances);
        if (parser.isSet(json)) {
            printOut(QString::fromUtf8(QJsonDocument(continuityJson(report)).toJson()));
            // What the JSON's keys do not hold (degenerate sides, faces without a record).
            printError(QStringLiteral("%1: %2").arg(files[0], continuitySummary(report)));
        } else {
            printOut(continuityText(files[0], report));
        }
        return kExitOk;
    }
    if (parser.isSet(json))
        printOut(QString::fromUtf8(QJsonDocument(toJson(files[0], scene)).toJson()));
    else
        printOut(toText(files[0], scene));
    return kExitOk;
}

} // namespace kw::cli
