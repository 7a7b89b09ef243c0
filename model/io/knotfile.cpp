// Writing .knot project files: Scene -> versioned JSON, saved atomically (reading:
// knotfile_read.cpp).
#include "model/io/knotfile.h"

#include "model/io/inputcheck.h"
#include "model/io/savefile.h"
#include "model/nurbs/analytic_eval.h"

#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>

namespace kw {

namespace {

QJsonArray toJson(const glm::dvec3& v) {
    return QJsonArray{v.x, v.y, v.z};
}
QJsonArray toJson(const glm::dvec2& v) {
    return QJsonArray{v.x, v.y};
}

QJsonArray toJson(const std::vector<double>& values) {
    QJsonArray a;
    for (double d : values)
        a.append(d);
    return a;
}

template <typename Vec> QJsonArray pointsToJson(const std::vector<Vec>& points) {
    QJsonArray a;
    for (const Vec& p : points)
        a.append(toJson(p));
    return a;
}

QJsonObject curveToJson(const NurbsCurve2& c) {
    QJsonObject o;
    o.insert(QStringLiteral("degree"), c.degree);
    o.insert(QStringLiteral("knots"), toJson(c.knots));
    o.insert(QStringLiteral("points"), pointsToJson(c.points));
    o.insert(QStringLiteral("weights"), toJson(c.weights));
    return o;
}

QJsonObject materialToJson(const Material& m) {
    QJsonObject o;
    o.insert(QStringLiteral("color"), toJson(m.color));
    o.insert(QStringLiteral("ka"), m.ka);
    o.insert(QStringLiteral("kd"), m.kd);
    o.insert(QStringLiteral("ks"), m.ks);
    o.insert(QStringLiteral("shininess"), m.shininess);
    return o;
}

QJsonObject mapToJson(const AnalyticParamMap& m) {
    return QJsonObject{{QStringLiteral("map"), m.kind == AnalyticParamMap::Kind::HalfAngle
                                                   ? QStringLiteral("halfAngle")
                                                   : QStringLiteral("linear")},
                       {QStringLiteral("offset"), m.offset},
                       {QStringLiteral("scale"), m.scale}};
}

// Only the members the kind uses are written (docs/FILE_FORMAT.md, Analytic).
QJsonObject analyticToJson(const AnalyticForm& f) {
    QJsonObject o{{QStringLiteral("kind"), QString::fromLatin1(analyticKindName(f.kind))},
                  {QStringLiteral("origin"), toJson(f.origin)},
                  {QStringLiteral("xAxis"), toJson(f.xAxis)},
                  {QStringLiteral("yAxis"), toJson(f.yAxis)},
                  {QStringLiteral("zAxis"), toJson(f.zAxis)},
                  {QStringLiteral("u"), mapToJson(f.u)},
                  {QStringLiteral("v"), mapToJson(f.v)}};
    if (f.kind != AnalyticForm::Kind::Plane)
        o.insert(QStringLiteral("radius"), f.radius);
    if (f.kind == AnalyticForm::Kind::Torus)
        o.insert(QStringLiteral("minorRadius"), f.minorRadius);
    if (f.kind == AnalyticForm::Kind::Cone)
        o.insert(QStringLiteral("semiAngle"), f.semiAngle);
    if (f.swapped)
        o.insert(QStringLiteral("swapped"), true);
    return o;
}

QJsonObject surfaceToJson(const Surface& s) {
    const NurbsSurface& g = s.geometry;
    QJsonObject o;
    o.insert(QStringLiteral("id"), qint64(s.id.value));
    o.insert(QStringLiteral("name"), s.name);
    o.insert(QStringLiteral("degreeU"), g.degreeU);
    o.insert(QStringLiteral("degreeV"), g.degreeV);
    o.insert(QStringLiteral("countU"), g.countU);
    o.insert(QStringLiteral("countV"), g.countV);
    o.insert(QStringLiteral("knotsU"), toJson(g.knotsU));
    o.insert(QStringLiteral("knotsV"), toJson(g.knotsV));
    o.insert(QStringLiteral("points"), pointsToJson(g.points));
    o.insert(QStringLiteral("weights"), toJson(g.weights));
    QJsonArray trims;
    for (const TrimLoop& loop : s.trims) {
        QJsonArray curves;
        for (const NurbsCurve2& c : loop.curves)
            curves.append(curveToJson(c));
        trims.append(QJsonObject{{QStringLiteral("id"), qint64(loop.id.value)},
                                 {QStringLiteral("curves"), curves}});
    }
    o.insert(QStringLiteral("trims"), trims);
    o.insert(QStringLiteral("partitions"), QJsonArray{s.partitionsU, s.partitionsV});
    o.insert(QStringLiteral("material"), materialToJson(s.material));
    if (s.hidden) // optional, written only when set: files of visible scenes stay as they were
        o.insert(QStringLiteral("hidden"), true);
    if (s.solid >= 0) // optional (1.2): a face of a closed solid, as imported
        o.insert(QStringLiteral("solid"),
                 QJsonObject{{QStringLiteral("index"), s.solid},
                             {QStringLiteral("outside"), s.outsideAlongNormal
                                                             ? QStringLiteral("normal")
                                                             : QStringLiteral("reversed")}});
    if (s.analytic.kind != AnalyticForm::Kind::None) // optional (1.5): the file's closed form
        o.insert(QStringLiteral("analytic"), analyticToJson(s.analytic));
    return o;
}

QJsonObject edgeToJson(const SharedEdge& e) {
    QJsonArray sides;
    for (const EdgeUse& side : e.sides)
        sides.append(QJsonObject{{QStringLiteral("surface"), qint64(side.surface.value)},
                                 {QStringLiteral("loop"), qint64(side.loop.value)},
                                 {QStringLiteral("curve"), side.curve},
                                 {QStringLiteral("reversed"), side.reversed}});
    return QJsonObject{{QStringLiteral("id"), qint64(e.id.value)},
                       {QStringLiteral("tolerance"), e.tolerance},
                       {QStringLiteral("sides"), sides}};
}

QJsonObject shellToJson(const Shell& shell) {
    QJsonArray faces;
    for (SurfaceId f : shell.faces)
        faces.append(qint64(f.value));
    QJsonObject o{{QStringLiteral("id"), qint64(shell.id.value)},
                  {QStringLiteral("closed"), shell.closed},
                  {QStringLiteral("faces"), faces}};
    if (shell.solid >= 0)
        o.insert(QStringLiteral("solid"), shell.solid);
    return o;
}

QJsonObject topologyToJson(const Topology& t) {
    QJsonArray edges, shells;
    for (const SharedEdge& e : t.edges)
        edges.append(edgeToJson(e));
    for (const Shell& shell : t.shells)
        shells.append(shellToJson(shell));
    return QJsonObject{{QStringLiteral("edges"), edges}, {QStringLiteral("shells"), shells}};
}

QJsonObject lightToJson(const Light& l) {
    QJsonObject o;
    o.insert(QStringLiteral("kind"), l.kind == Light::Kind::Point ? QStringLiteral("point")
                                                                  : QStringLiteral("directional"));
    o.insert(QStringLiteral("vector"), toJson(l.vector));
    o.insert(QStringLiteral("ambient"), toJson(l.ambient));
    o.insert(QStringLiteral("diffuse"), toJson(l.diffuse));
    o.insert(QStringLiteral("specular"), toJson(l.specular));
    return o;
}

QJsonObject cameraToJson(const Camera& c) {
    QJsonObject o;
    o.insert(QStringLiteral("eye"), toJson(c.eye));
    o.insert(QStringLiteral("target"), toJson(c.target));
    o.insert(QStringLiteral("up"), toJson(c.up));
    o.insert(QStringLiteral("fovYDegrees"), c.fovYDegrees);
    return o;
}

} // namespace

QByteArray sceneToJson(const Scene& scene) {
    QJsonObject root;
    root.insert(QStringLiteral("format"), QStringLiteral("knotwork"));
    root.insert(QStringLiteral("version"),
                QStringLiteral("%1.%2").arg(kKnotFormatMajor).arg(kKnotFormatMinor));
    root.insert(QStringLiteral("nextId"), qint64(scene.nextId));
    QJsonArray surfaces;
    for (const Surface& s : scene.surfaces)
        surfaces.append(surfaceToJson(s));
    root.insert(QStringLiteral("surfaces"), surfaces);
    QJsonArray lights;
    for (const Light& l : scene.lights)
        lights.append(lightToJson(l));
    root.insert(QStringLiteral("lights"), lights);
    if (scene.camera.authored)
        root.insert(QStringLiteral("camera"), cameraToJson(scene.camera));
    if (scene.unit != LengthUnit::Millimetre) // optional (1.4): millimetres when absent
        root.insert(QStringLiteral("unit"), lengthUnitKey(scene.unit));
    if (!scene.topology.empty()) // optional (1.3): what a B-rep import kept
        root.insert(QStringLiteral("topology"), topologyToJson(scene.topology));
    if (scene.continuity != ContinuityTolerances{}) // optional (1.4)
        root.insert(QStringLiteral("continuity"),
                    QJsonObject{{QStringLiteral("g0"), scene.continuity.g0},
                                {QStringLiteral("g1Degrees"), scene.continuity.g1Degrees},
                                {QStringLiteral("g2Percent"), scene.continuity.g2Percent},
                                {QStringLiteral("match"), scene.continuity.match}});
    const DisplaySettings& d = scene.display;
    if (!d.partitionMode.isEmpty() || !d.background.isEmpty() || !d.sections.empty() ||
        !d.sectionCaps || d.customDraft()) {
        QJsonObject display{{QStringLiteral("pixelTolerance"), scene.display.pixelTolerance}};
        if (!scene.display.partitionMode.isEmpty())
            display.insert(QStringLiteral("partitionMode"), scene.display.partitionMode);
        if (!scene.display.background.isEmpty())
            display.insert(QStringLiteral("background"), scene.display.background);
        if (!d.sections.empty()) { // optional (1.4)
            QJsonArray planes;
            for (const SectionPlane& p : d.sections)
                planes.append(QJsonObject{{QStringLiteral("position"), toJson(p.position)},
                                          {QStringLiteral("normal"), toJson(p.normal)},
                                          {QStringLiteral("flip"), p.flip}});
            display.insert(QStringLiteral("sections"), planes);
        }
        if (!d.sectionCaps) // optional (1.4): caps are on unless turned off
            display.insert(QStringLiteral("sectionCaps"), false);
        if (scene.display.customDraft()) {
            display.insert(QStringLiteral("pullDirection"), toJson(scene.display.pullDirection));
            display.insert(QStringLiteral("draftAngle"), scene.display.draftAngleDegrees);
        }
        root.insert(QStringLiteral("display"), display);
    }
    return QJsonDocument(root).toJson(QJsonDocument::Indented);
}

Status writeKnotFile(const QString& path, const Scene& scene) {
    if (const QString why = checkScene(scene).message(); !why.isEmpty())
        return Error(QStringLiteral("%1: not written, the scene is not valid: %2").arg(path, why),
                     path);
    return saveBytesAtomically(path, sceneToJson(scene));
}

Expected<Scene> readKnotFile(const QString& path) {
    // Nothing but a regular file within the size limit is opened, and a file that does not
    // start like JSON is refused from its first bytes, whatever its size.
    // (A missing file is left to open(), which names the reason.)
    QString why = QFileInfo::exists(path)
                      ? checkRegularFile(path, kMaxKnotFileBytes, QStringLiteral(".knot")).message()
                      : QString();
    if (why.isEmpty() && QFileInfo::exists(path))
        why = checkKnotHead(fileHead(path, kSniffBytes)).message();
    if (!why.isEmpty())
        return Error(QStringLiteral("%1: %2").arg(path, why), path);
    QFile file(path);
    if (!file.open(QIODevice::ReadOnly))
        return Error(QStringLiteral("%1: cannot open: %2").arg(path, file.errorString()), path);
    if (file.size() > kMaxKnotFileBytes)
        return Error(QStringLiteral("%1: file is %2 bytes, more than the 1 GiB limit")
                         .arg(path)
                         .arg(file.size()),
                     path);
    const QByteArray data = file.readAll();
    if (file.error() != QFileDevice::NoError)
        return Error(QStringLiteral("%1: cannot read: %2").arg(path, file.errorString()), path);
    return sceneFromJson(data, path);
}

} // namespace kw
