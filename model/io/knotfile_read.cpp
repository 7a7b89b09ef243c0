// Reading .knot project files: JSON -> validated Scene, with one-line errors naming the JSON path.
#include "model/analysis/continuity.h"
#include "model/document/validation.h"
#include "model/io/knotfile.h"
#include "model/io/knotfile_prescan.h"
#include "model/nurbs/analytic_eval.h"

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLocale>
#include <QRegularExpression>
#include <cmath>
#include <map>
#include <optional>

namespace kw {

namespace {

// Thrown inside this file only and caught by sceneFromJson, so no partial scene escapes.
struct FileError {
    QString path;
    QString reason;
};

[[noreturn]] void fail(const QString& path, const QString& reason) {
    throw FileError{path, reason};
}

// Shortest text that reads back as the same double: "0.2", not "0.20000000000000001".
QString num(double d) {
    return QString::number(d, 'g', QLocale::FloatingPointShortest);
}
QString member(const QString& path, const char* key) {
    return path + QLatin1Char('.') + QLatin1String(key);
}
QString element(const QString& path, qsizetype i) {
    return path + QLatin1Char('[') + QString::number(i) + QLatin1Char(']');
}

QString describe(const QJsonValue& v) {
    switch (v.type()) {
    case QJsonValue::Null:
        return QStringLiteral("null");
    case QJsonValue::Bool:
        return QStringLiteral("a boolean");
    case QJsonValue::Double:
        return QStringLiteral("the number ") + num(v.toDouble());
    case QJsonValue::String: {
        QString s = v.toString();
        if (s.size() > 24)
            s = s.left(24) + QStringLiteral("...");
        return QStringLiteral("the string \"%1\"").arg(s);
    }
    case QJsonValue::Array:
        return QStringLiteral("an array");
    case QJsonValue::Object:
        return QStringLiteral("an object");
    case QJsonValue::Undefined:
        break;
    }
    return QStringLiteral("nothing");
}

QJsonValue required(const QJsonObject& o, const QString& path, const char* key) {
    const auto it = o.constFind(QLatin1String(key));
    if (it == o.constEnd())
        fail(member(path, key), QStringLiteral("missing required member"));
    return it.value();
}

QJsonObject asObject(const QJsonValue& v, const QString& path) {
    if (!v.isObject())
        fail(path, QStringLiteral("expected an object, found ") + describe(v));
    return v.toObject();
}

QJsonArray asArray(const QJsonValue& v, const QString& path) {
    if (!v.isArray())
        fail(path, QStringLiteral("expected an array, found ") + describe(v));
    return v.toArray();
}

QString asString(const QJsonValue& v, const QString& path) {
    if (!v.isString())
        fail(path, QStringLiteral("expected a string, found ") + describe(v));
    return v.toString();
}

// Qt's parser already rejects NaN, Infinity and out-of-range literals such as 1e999; the
// isfinite test keeps that guarantee independent of the parser.
double asNumber(const QJsonValue& v, const QString& path) {
    if (!v.isDouble())
        fail(path, QStringLiteral("expected a number, found ") + describe(v));
    const double d = v.toDouble();
    if (!std::isfinite(d))
        fail(path, QStringLiteral("number is not finite"));
    return d;
}

double asNumberIn(const QJsonValue& v, const QString& path, double lo, double hi) {
    const double d = asNumber(v, path);
    if (d < lo || d > hi)
        fail(path, QStringLiteral("%1 is outside the allowed range [%2, %3]")
                       .arg(num(d), num(lo), num(hi)));
    return d;
}

long long asInteger(const QJsonValue& v, const QString& path, long long lo, long long hi) {
    const double d = asNumber(v, path);
    if (d != std::floor(d))
        fail(path, QStringLiteral("expected an integer, found ") + num(d));
    if (d < double(lo) || d > double(hi))
        fail(
            path,
            QStringLiteral("%1 is outside the allowed range [%2, %3]").arg(num(d)).arg(lo).arg(hi));
    return static_cast<long long>(d);
}

QJsonArray asArrayOfSize(const QJsonValue& v, const QString& path, qsizetype n,
                         const QString& what) {
    const QJsonArray a = asArray(v, path);
    if (a.size() != n)
        fail(path, QStringLiteral("expected %1, found %2 elements").arg(what).arg(a.size()));
    return a;
}

// The elements of the big arrays (points, knots, weights) are read by the functions below
// without their JSON path, which only an error needs: building "$.surfaces[0].points[12][1]"
// for every number took more time than reading the numbers (an eighth of fuzz_document's
// time, 2026-11-23). Whatever plainNumber does not accept goes to the checks above, with the
// path, so the values and the errors are the same as with the checks alone.

/// A finite number in [lo, hi]: exactly what asNumberIn accepts, with the same value.
std::optional<double> plainNumber(const QJsonValue& v, double lo = -HUGE_VAL,
                                  double hi = HUGE_VAL) {
    if (!v.isDouble())
        return std::nullopt;
    const double d = v.toDouble();
    if (!std::isfinite(d) || d < lo || d > hi)
        return std::nullopt;
    return d;
}

/// asNumber(a[k], element(path, k)), the path built only for an error.
double numberAt(const QJsonArray& a, qsizetype k, const QString& path) {
    const QJsonValue v = a[k];
    if (const std::optional<double> d = plainNumber(v))
        return *d;
    return asNumber(v, element(path, k));
}

glm::dvec3 asVec3(const QJsonValue& v, const QString& path, double lo = -HUGE_VAL,
                  double hi = HUGE_VAL) {
    const QJsonArray a = asArrayOfSize(v, path, 3, QStringLiteral("3 numbers"));
    glm::dvec3 r;
    for (int k = 0; k < 3; ++k) {
        const std::optional<double> d = plainNumber(a[k], lo, hi);
        r[k] = d ? *d : asNumberIn(a[k], element(path, k), lo, hi);
    }
    return r;
}

glm::dvec2 asVec2(const QJsonValue& v, const QString& path) {
    const QJsonArray a = asArrayOfSize(v, path, 2, QStringLiteral("2 numbers"));
    return {numberAt(a, 0, path), numberAt(a, 1, path)};
}

/// asVec3(a[k], element(path, k)) and asVec2 likewise, the path built only for an error.
glm::dvec3 vec3At(const QJsonArray& a, qsizetype k, const QString& path) {
    const QJsonValue v = a[k];
    if (v.isArray()) {
        const QJsonArray c = v.toArray();
        if (c.size() == 3) {
            const std::optional<double> x = plainNumber(c[0]), y = plainNumber(c[1]),
                                        z = plainNumber(c[2]);
            if (x && y && z)
                return {*x, *y, *z};
        }
    }
    return asVec3(v, element(path, k));
}

glm::dvec2 vec2At(const QJsonArray& a, qsizetype k, const QString& path) {
    const QJsonValue v = a[k];
    if (v.isArray()) {
        const QJsonArray c = v.toArray();
        if (c.size() == 2) {
            const std::optional<double> x = plainNumber(c[0]), y = plainNumber(c[1]);
            if (x && y)
                return {*x, *y};
        }
    }
    return asVec2(v, element(path, k));
}

// Ids of surfaces and loops come from one counter, so all of them must differ.
class IdRegistry {
public:
    std::uint32_t take(const QJsonValue& v, const QString& path) {
        // The largest id leaves room for nextId = id + 1 in 32 bits.
        const auto id = std::uint32_t(asInteger(v, path, 1, 0xFFFFFFFEll));
        const auto [it, inserted] = m_paths.emplace(id, path);
        if (!inserted)
            fail(path, QStringLiteral("id %1 is already used at %2").arg(id).arg(it->second));
        return id;
    }
    std::uint32_t maxId() const { return m_paths.empty() ? 0 : m_paths.rbegin()->first; }

private:
    std::map<std::uint32_t, QString> m_paths;
};

// Element-wise checks first so the error points at the offending knot; the kernel's
// checkKnotVector then covers whatever else makes the vector unusable (e.g. an empty domain).
std::vector<double> readKnots(const QJsonValue& v, const QString& path, int degree, int count,
                              const QString& countName, const QString& degreeName) {
    const qsizetype expected = qsizetype(count) + degree + 1;
    const QJsonArray a = asArrayOfSize(v, path, expected,
                                       QStringLiteral("%1 knots (%2 %3 + %4 %5 + 1)")
                                           .arg(expected)
                                           .arg(countName)
                                           .arg(count)
                                           .arg(degreeName)
                                           .arg(degree));
    std::vector<double> knots(size_t(a.size()));
    int multiplicity = 0;
    for (qsizetype k = 0; k < a.size(); ++k) {
        knots[size_t(k)] = numberAt(a, k, path);
        if (k > 0 && knots[size_t(k)] < knots[size_t(k - 1)])
            fail(element(path, k), QStringLiteral("knot %1 is smaller than the previous knot %2 "
                                                  "(knots must not decrease)")
                                       .arg(num(knots[size_t(k)]), num(knots[size_t(k - 1)])));
        multiplicity = (k > 0 && knots[size_t(k)] == knots[size_t(k - 1)]) ? multiplicity + 1 : 1;
        if (multiplicity > degree + 1)
            fail(element(path, k), QStringLiteral("knot %1 repeats %2 times, more than %3 + 1 = %4")
                                       .arg(num(knots[size_t(k)]))
                                       .arg(multiplicity)
                                       .arg(degreeName)
                                       .arg(degree + 1));
    }
    const Status valid = checkKnotVector(knots, degree, count);
    if (!valid)
        fail(path, valid.message());
    return knots;
}

std::vector<double> readWeights(const QJsonValue& v, const QString& path, qsizetype n) {
    const QJsonArray a =
        asArrayOfSize(v, path, n, QStringLiteral("%1 weights, one per control point").arg(n));
    std::vector<double> w(size_t(a.size()));
    for (qsizetype k = 0; k < a.size(); ++k) {
        w[size_t(k)] = numberAt(a, k, path);
        if (!(w[size_t(k)] > 0.0))
            fail(element(path, k),
                 QStringLiteral("weight must be positive, found ") + num(w[size_t(k)]));
    }
    return w;
}

NurbsCurve2 readCurve(const QJsonObject& o, const QString& path) {
    NurbsCurve2 c;
    c.degree = int(asInteger(required(o, path, "degree"), member(path, "degree"), 1, kMaxDegree));
    const QString pointsPath = member(path, "points");
    const QJsonArray pts = asArray(required(o, path, "points"), pointsPath);
    if (pts.size() < c.degree + 1 || pts.size() > kMaxKnotCurvePoints)
        fail(pointsPath, QStringLiteral("a degree-%1 curve needs %2 to %3 control points, found %4")
                             .arg(c.degree)
                             .arg(c.degree + 1)
                             .arg(kMaxKnotCurvePoints)
                             .arg(pts.size()));
    for (qsizetype k = 0; k < pts.size(); ++k)
        c.points.push_back(vec2At(pts, k, pointsPath));
    const int n = int(pts.size());
    c.knots = readKnots(required(o, path, "knots"), member(path, "knots"), c.degree, n,
                        QStringLiteral("points"), QStringLiteral("degree"));
    c.weights = readWeights(required(o, path, "weights"), member(path, "weights"), n);
    const Status valid = checkNurbsCurve(c);
    if (!valid)
        fail(path, valid.message());
    return c;
}

// A loop is a closed chain: each curve starts where the previous one ends (cyclically), within
// the tolerance every other check uses (kw::trimLoopOpenAt).
void checkClosed(const TrimLoop& loop, const QString& curvesPath) {
    glm::dvec2 start, end;
    if (const int k = trimLoopOpenAt(loop, &start, &end); k >= 0)
        fail(element(curvesPath, qsizetype(k)),
             QStringLiteral("curve starts at (%1, %2) but the previous curve of the loop ends "
                            "at (%3, %4); a trim loop must be closed")
                 .arg(num(start.x), num(start.y), num(end.x), num(end.y)));
}

TrimLoop readLoop(const QJsonObject& o, const QString& path, IdRegistry& ids) {
    TrimLoop loop;
    loop.id = TrimLoopId{ids.take(required(o, path, "id"), member(path, "id"))};
    const QString curvesPath = member(path, "curves");
    const QJsonArray curves = asArray(required(o, path, "curves"), curvesPath);
    if (curves.isEmpty() || curves.size() > kMaxKnotLoopCurves)
        fail(curvesPath, QStringLiteral("a trim loop needs 1 to %1 curves, found %2")
                             .arg(kMaxKnotLoopCurves)
                             .arg(curves.size()));
    for (qsizetype k = 0; k < curves.size(); ++k) {
        const QString p = element(curvesPath, k);
        loop.curves.push_back(readCurve(asObject(curves[k], p), p));
    }
    checkClosed(loop, curvesPath);
    return loop;
}

Material readMaterial(const QJsonObject& o, const QString& path) {
    Material m;
    m.color = asVec3(required(o, path, "color"), member(path, "color"), 0.0, 1.0);
    m.ka = asNumberIn(required(o, path, "ka"), member(path, "ka"), 0.0, 1.0);
    m.kd = asNumberIn(required(o, path, "kd"), member(path, "kd"), 0.0, 1.0);
    m.ks = asNumberIn(required(o, path, "ks"), member(path, "ks"), 0.0, 1.0);
    m.shininess =
        asNumberIn(required(o, path, "shininess"), member(path, "shininess"), 0.0, kMaxShininess);
    return m;
}

void readNet(const QJsonObject& o, const QString& path, NurbsSurface& g) {
    g.degreeU =
        int(asInteger(required(o, path, "degreeU"), member(path, "degreeU"), 1, kMaxDegree));
    g.degreeV =
        int(asInteger(required(o, path, "degreeV"), member(path, "degreeV"), 1, kMaxDegree));
    g.countU = int(
        asInteger(required(o, path, "countU"), member(path, "countU"), 1, kMaxKnotControlPoints));
    g.countV = int(
        asInteger(required(o, path, "countV"), member(path, "countV"), 1, kMaxKnotControlPoints));
    const long long total = (long long)g.countU * g.countV;
    if (total > kMaxKnotControlPoints)
        fail(member(path, "countV"),
             QStringLiteral("countU %1 x countV %2 = %3 control points, more than the limit %4")
                 .arg(g.countU)
                 .arg(g.countV)
                 .arg(total)
                 .arg(kMaxKnotControlPoints));
    if (g.countU < g.degreeU + 1)
        fail(member(path, "countU"), QStringLiteral("countU %1 is too small for degreeU %2 (at "
                                                    "least degreeU + 1 control points needed)")
                                         .arg(g.countU)
                                         .arg(g.degreeU));
    if (g.countV < g.degreeV + 1)
        fail(member(path, "countV"), QStringLiteral("countV %1 is too small for degreeV %2 (at "
                                                    "least degreeV + 1 control points needed)")
                                         .arg(g.countV)
                                         .arg(g.degreeV));
    g.knotsU = readKnots(required(o, path, "knotsU"), member(path, "knotsU"), g.degreeU, g.countU,
                         QStringLiteral("countU"), QStringLiteral("degreeU"));
    g.knotsV = readKnots(required(o, path, "knotsV"), member(path, "knotsV"), g.degreeV, g.countV,
                         QStringLiteral("countV"), QStringLiteral("degreeV"));
    const QString pointsPath = member(path, "points");
    const QJsonArray pts = asArrayOfSize(required(o, path, "points"), pointsPath, total,
                                         QStringLiteral("%1 control points (countU %2 x countV %3)")
                                             .arg(total)
                                             .arg(g.countU)
                                             .arg(g.countV));
    g.points.reserve(size_t(total));
    for (qsizetype k = 0; k < pts.size(); ++k)
        g.points.push_back(vec3At(pts, k, pointsPath));
    g.weights = readWeights(required(o, path, "weights"), member(path, "weights"), total);
}

AnalyticParamMap readMap(const QJsonObject& o, const QString& path) {
    AnalyticParamMap m;
    const QString kindPath = member(path, "map");
    const QString kind = asString(required(o, path, "map"), kindPath);
    if (kind == QLatin1String("halfAngle"))
        m.kind = AnalyticParamMap::Kind::HalfAngle;
    else if (kind != QLatin1String("linear"))
        fail(kindPath, QStringLiteral("expected \"linear\" or \"halfAngle\", found ") +
                           describe(QJsonValue(kind)));
    m.offset = asNumber(required(o, path, "offset"), member(path, "offset"));
    m.scale = asNumber(required(o, path, "scale"), member(path, "scale"));
    return m;
}

// The closed form of an imported face (1.5): its members, then the rules of checkAnalyticForm,
// then that it describes this surface's NURBS (a form left from before an edit of the points
// would draw another surface than the one saved).
AnalyticForm readAnalytic(const QJsonObject& o, const QString& path, const NurbsSurface& g) {
    using Kind = AnalyticForm::Kind;
    AnalyticForm f;
    const QString kindPath = member(path, "kind");
    const QString kind = asString(required(o, path, "kind"), kindPath);
    const std::optional<Kind> k = analyticKindNamed(kind.toStdString());
    if (!k || *k == Kind::None)
        fail(kindPath,
             QStringLiteral("expected \"plane\", \"cylinder\", \"cone\", \"sphere\" or \"torus\", "
                            "found ") +
                 describe(QJsonValue(kind)));
    f.kind = *k;
    f.origin = asVec3(required(o, path, "origin"), member(path, "origin"));
    f.xAxis = asVec3(required(o, path, "xAxis"), member(path, "xAxis"));
    f.yAxis = asVec3(required(o, path, "yAxis"), member(path, "yAxis"));
    f.zAxis = asVec3(required(o, path, "zAxis"), member(path, "zAxis"));
    if (f.kind != Kind::Plane)
        f.radius = asNumber(required(o, path, "radius"), member(path, "radius"));
    if (f.kind == Kind::Torus)
        f.minorRadius = asNumber(required(o, path, "minorRadius"), member(path, "minorRadius"));
    if (f.kind == Kind::Cone)
        f.semiAngle = asNumber(required(o, path, "semiAngle"), member(path, "semiAngle"));
    const QString uPath = member(path, "u"), vPath = member(path, "v");
    f.u = readMap(asObject(required(o, path, "u"), uPath), uPath);
    f.v = readMap(asObject(required(o, path, "v"), vPath), vPath);
    if (o.contains(QLatin1String("swapped"))) {
        const QJsonValue v = o.value(QLatin1String("swapped"));
        if (!v.isBool())
            fail(member(path, "swapped"),
                 QStringLiteral("expected true or false, found ") + describe(v));
        f.swapped = v.toBool();
    }
    if (const Status valid = checkAnalyticForm(f, g); !valid)
        fail(path, valid.message());
    const double off = analyticDeviation(f, g), limit = analyticMatchLimit(g);
    if (!(off <= limit))
        fail(path, QStringLiteral("the form lies %1 from the surface's NURBS, more than %2 "
                                  "(a millionth of its control net's size)")
                       .arg(num(off), num(limit)));
    return f;
}

Surface readSurface(const QJsonObject& o, const QString& path, IdRegistry& ids) {
    Surface s;
    s.id = SurfaceId{ids.take(required(o, path, "id"), member(path, "id"))};
    s.name = asString(required(o, path, "name"), member(path, "name"));
    readNet(o, path, s.geometry);
    const Status valid = checkNurbsSurface(s.geometry);
    if (!valid)
        fail(path, valid.message());

    if (o.contains(QLatin1String("trims"))) {
        const QString trimsPath = member(path, "trims");
        const QJsonArray trims = asArray(o.value(QLatin1String("trims")), trimsPath);
        if (trims.size() > kMaxKnotTrimLoops)
            fail(trimsPath, QStringLiteral("%1 trim loops, more than the limit %2")
                                .arg(trims.size())
                                .arg(kMaxKnotTrimLoops));
        for (qsizetype k = 0; k < trims.size(); ++k) {
            const QString p = element(trimsPath, k);
            s.trims.push_back(readLoop(asObject(trims[k], p), p, ids));
        }
    }
    if (o.contains(QLatin1String("partitions"))) {
        const QString p = member(path, "partitions");
        const QJsonArray a = asArrayOfSize(o.value(QLatin1String("partitions")), p, 2,
                                           QStringLiteral("2 integers [u, v]"));
        s.partitionsU = int(asInteger(a[0], element(p, 0), kMinPartitions, kMaxPartitions));
        s.partitionsV = int(asInteger(a[1], element(p, 1), kMinPartitions, kMaxPartitions));
    }
    if (o.contains(QLatin1String("material"))) {
        const QString p = member(path, "material");
        s.material = readMaterial(asObject(o.value(QLatin1String("material")), p), p);
    }
    if (o.contains(QLatin1String("hidden"))) {
        const QJsonValue v = o.value(QLatin1String("hidden"));
        if (!v.isBool())
            fail(member(path, "hidden"),
                 QStringLiteral("expected true or false, found ") + describe(v));
        s.hidden = v.toBool();
    }
    if (o.contains(QLatin1String("solid"))) {
        const QString p = member(path, "solid");
        const QJsonObject solid = asObject(o.value(QLatin1String("solid")), p);
        s.solid =
            int(asInteger(required(solid, p, "index"), member(p, "index"), 0, kMaxKnotSurfaces));
        const QString outsidePath = member(p, "outside");
        const QString outside = asString(required(solid, p, "outside"), outsidePath);
        if (outside == QLatin1String("normal") || outside == QLatin1String("reversed"))
            s.outsideAlongNormal = outside == QLatin1String("normal");
        else
            fail(outsidePath, QStringLiteral("expected \"normal\" or \"reversed\", found ") +
                                  describe(QJsonValue(outside)));
    }
    if (o.contains(QLatin1String("analytic"))) {
        const QString p = member(path, "analytic");
        s.analytic = readAnalytic(asObject(o.value(QLatin1String("analytic")), p), p, s.geometry);
    }
    return s;
}

bool asBool(const QJsonValue& v, const QString& path) {
    if (!v.isBool())
        fail(path, QStringLiteral("expected true or false, found ") + describe(v));
    return v.toBool();
}

std::uint32_t asId(const QJsonValue& v, const QString& path) {
    return std::uint32_t(asInteger(v, path, 1, 0xFFFFFFFEll));
}

SharedEdge readEdge(const QJsonObject& o, const QString& path) {
    SharedEdge e;
    e.id = EdgeId{asId(required(o, path, "id"), member(path, "id"))};
    e.tolerance =
        asNumberIn(required(o, path, "tolerance"), member(path, "tolerance"), 0.0, HUGE_VAL);
    const QString sidesPath = member(path, "sides");
    const QJsonArray sides = asArrayOfSize(required(o, path, "sides"), sidesPath, 2,
                                           QStringLiteral("2 sides, one per face"));
    for (qsizetype k = 0; k < 2; ++k) {
        const QString p = element(sidesPath, k);
        const QJsonObject side = asObject(sides[k], p);
        EdgeUse& use = e.sides[size_t(k)];
        use.surface = SurfaceId{asId(required(side, p, "surface"), member(p, "surface"))};
        use.loop = TrimLoopId{asId(required(side, p, "loop"), member(p, "loop"))};
        use.curve =
            int(asInteger(required(side, p, "curve"), member(p, "curve"), 0, kMaxLoopCurves - 1));
        use.reversed = asBool(required(side, p, "reversed"), member(p, "reversed"));
    }
    return e;
}

Shell readShell(const QJsonObject& o, const QString& path) {
    Shell shell;
    shell.id = ShellId{asId(required(o, path, "id"), member(path, "id"))};
    shell.closed = asBool(required(o, path, "closed"), member(path, "closed"));
    if (o.contains(QLatin1String("solid")))
        shell.solid = int(
            asInteger(o.value(QLatin1String("solid")), member(path, "solid"), 0, kMaxKnotSurfaces));
    const QString facesPath = member(path, "faces");
    const QJsonArray faces = asArray(required(o, path, "faces"), facesPath);
    for (qsizetype k = 0; k < faces.size(); ++k)
        shell.faces.push_back(SurfaceId{asId(faces[k], element(facesPath, k))});
    return shell;
}

// Read after the surfaces, whose ids and loops it names: each reference is checked with
// kw::topologyProblem, the rule Document and the importers use, and a bad one named by its path.
Topology readTopology(const QJsonObject& o, const QString& path) {
    Topology t;
    const QString edgesPath = member(path, "edges");
    const QJsonArray edges = asArray(required(o, path, "edges"), edgesPath);
    if (edges.size() > kMaxSharedEdges)
        fail(edgesPath, QStringLiteral("%1 shared edges, more than the limit %2")
                            .arg(edges.size())
                            .arg(kMaxSharedEdges));
    for (qsizetype k = 0; k < edges.size(); ++k) {
        const QString p = element(edgesPath, k);
        t.edges.push_back(readEdge(asObject(edges[k], p), p));
    }
    const QString shellsPath = member(path, "shells");
    const QJsonArray shells = asArray(required(o, path, "shells"), shellsPath);
    if (shells.size() > kMaxShells)
        fail(
            shellsPath,
            QStringLiteral("%1 shells, more than the limit %2").arg(shells.size()).arg(kMaxShells));
    for (qsizetype k = 0; k < shells.size(); ++k) {
        const QString p = element(shellsPath, k);
        t.shells.push_back(readShell(asObject(shells[k], p), p));
    }
    return t;
}

Light readLight(const QJsonObject& o, const QString& path) {
    Light l;
    const QString kindPath = member(path, "kind");
    const QString kind = asString(required(o, path, "kind"), kindPath);
    if (kind == QLatin1String("directional"))
        l.kind = Light::Kind::Directional;
    else if (kind == QLatin1String("point"))
        l.kind = Light::Kind::Point;
    else
        fail(kindPath, QStringLiteral("expected \"directional\" or \"point\", found ") +
                           describe(QJsonValue(kind)));
    l.vector = asVec3(required(o, path, "vector"), member(path, "vector"));
    if (l.kind == Light::Kind::Directional && glm::length(l.vector) == 0.0)
        fail(member(path, "vector"), QStringLiteral("a directional light needs a non-zero vector"));
    l.ambient =
        asVec3(required(o, path, "ambient"), member(path, "ambient"), 0.0, kMaxLightIntensity);
    l.diffuse =
        asVec3(required(o, path, "diffuse"), member(path, "diffuse"), 0.0, kMaxLightIntensity);
    l.specular =
        asVec3(required(o, path, "specular"), member(path, "specular"), 0.0, kMaxLightIntensity);
    return l;
}

Camera readCamera(const QJsonObject& o, const QString& path) {
    Camera c;
    c.eye = asVec3(required(o, path, "eye"), member(path, "eye"));
    c.target = asVec3(required(o, path, "target"), member(path, "target"));
    c.up = asVec3(required(o, path, "up"), member(path, "up"));
    c.fovYDegrees = asNumber(required(o, path, "fovYDegrees"), member(path, "fovYDegrees"));
    if (!(c.fovYDegrees > 0.0 && c.fovYDegrees < 180.0))
        fail(member(path, "fovYDegrees"),
             QStringLiteral("%1 is outside the open range (0, 180)").arg(num(c.fovYDegrees)));
    const glm::dvec3 view = c.target - c.eye;
    if (glm::length(view) == 0.0)
        fail(member(path, "target"), QStringLiteral("target equals eye"));
    if (glm::length(glm::cross(view, c.up)) <= 1e-12 * glm::length(view) * glm::length(c.up))
        fail(member(path, "up"), QStringLiteral("up is zero or parallel to the view direction"));
    c.authored = true;
    if (const QString why = checkCamera(c).message(); !why.isEmpty())
        fail(path, why);
    return c;
}

DisplaySettings readDisplay(const QJsonObject& o, const QString& path) {
    DisplaySettings d;
    // partitionMode may be absent since the background, the draft settings (1.3) and the
    // sections (1.4) can be set alone.
    if (o.contains(QLatin1String("partitionMode")) ||
        !(o.contains(QLatin1String("background")) || o.contains(QLatin1String("sections")) ||
          o.contains(QLatin1String("sectionCaps")) || o.contains(QLatin1String("pullDirection")) ||
          o.contains(QLatin1String("draftAngle")))) {
        d.partitionMode =
            asString(required(o, path, "partitionMode"), member(path, "partitionMode"));
        if (d.partitionMode != QLatin1String("adaptive") &&
            d.partitionMode != QLatin1String("uniform"))
            fail(member(path, "partitionMode"),
                 QStringLiteral("expected \"adaptive\" or \"uniform\", found ") +
                     describe(QJsonValue(d.partitionMode)));
    }
    if (o.contains(QLatin1String("background"))) {
        d.background = asString(o.value(QLatin1String("background")), member(path, "background"));
        if (d.background != QLatin1String("dark") && d.background != QLatin1String("light"))
            fail(member(path, "background"),
                 QStringLiteral("expected \"dark\" or \"light\", found ") +
                     describe(QJsonValue(d.background)));
    }
    if (o.contains(QLatin1String("sections"))) {
        const QString sp = member(path, "sections");
        const QJsonArray planes = asArray(o.value(QLatin1String("sections")), sp);
        if (planes.size() > kMaxSectionPlanes)
            fail(sp, QStringLiteral("%1 section planes, more than the limit %2")
                         .arg(planes.size())
                         .arg(kMaxSectionPlanes));
        for (qsizetype k = 0; k < planes.size(); ++k) {
            const QString p = element(sp, k);
            const QJsonObject po = asObject(planes[k], p);
            SectionPlane plane;
            plane.position = asVec3(required(po, p, "position"), member(p, "position"));
            plane.normal = asVec3(required(po, p, "normal"), member(p, "normal"));
            if (po.contains(QLatin1String("flip")))
                plane.flip = asBool(po.value(QLatin1String("flip")), member(p, "flip"));
            if (Status valid = checkSectionPlane(plane); !valid)
                fail(member(p, "normal"), valid.message());
            d.sections.push_back(plane);
        }
    }
    if (o.contains(QLatin1String("sectionCaps")))
        d.sectionCaps = asBool(o.value(QLatin1String("sectionCaps")), member(path, "sectionCaps"));
    if (o.contains(QLatin1String("pullDirection"))) {
        d.pullDirection =
            asVec3(o.value(QLatin1String("pullDirection")), member(path, "pullDirection"));
        if (!(glm::length(d.pullDirection) > 0.0))
            fail(member(path, "pullDirection"), QStringLiteral("the pull direction is zero"));
    }
    if (o.contains(QLatin1String("draftAngle"))) {
        d.draftAngleDegrees =
            asNumber(o.value(QLatin1String("draftAngle")), member(path, "draftAngle"));
        if (!(d.draftAngleDegrees >= 0.0 && d.draftAngleDegrees <= 90.0))
            fail(member(path, "draftAngle"),
                 QStringLiteral("%1 is outside 0..90").arg(num(d.draftAngleDegrees)));
    }
    if (o.contains(QLatin1String("pixelTolerance"))) {
        d.pixelTolerance =
            asNumber(o.value(QLatin1String("pixelTolerance")), member(path, "pixelTolerance"));
        if (!(d.pixelTolerance >= kMinPixelTolerance && d.pixelTolerance <= kMaxPixelTolerance))
            fail(member(path, "pixelTolerance"), QStringLiteral("%1 is outside %2..%3")
                                                     .arg(num(d.pixelTolerance))
                                                     .arg(kMinPixelTolerance)
                                                     .arg(kMaxPixelTolerance));
    }
    return d;
}

ContinuityTolerances readContinuity(const QJsonObject& o, const QString& path) {
    ContinuityTolerances t;
    t.g0 = asNumber(required(o, path, "g0"), member(path, "g0"));
    t.g1Degrees = asNumber(required(o, path, "g1Degrees"), member(path, "g1Degrees"));
    t.g2Percent = asNumber(required(o, path, "g2Percent"), member(path, "g2Percent"));
    t.match = asNumber(required(o, path, "match"), member(path, "match"));
    if (const QString why = checkContinuityTolerances(t).message(); !why.isEmpty())
        fail(path, why);
    return t;
}

void checkVersion(const QJsonObject& root) {
    const QString path = QStringLiteral("$.version");
    const QString version = asString(required(root, QStringLiteral("$"), "version"), path);
    static const QRegularExpression re(QStringLiteral("^(\\d{1,6})\\.(\\d{1,6})$"));
    const QRegularExpressionMatch m = re.match(version);
    if (!m.hasMatch())
        fail(path,
             QStringLiteral("expected \"MAJOR.MINOR\", found ") + describe(QJsonValue(version)));
    const int major = m.captured(1).toInt();
    if (major > kKnotFormatMajor)
        fail(path, QStringLiteral("file format version %1 is newer than this Knotwork can read "
                                  "(%2.x); open it with a newer Knotwork")
                       .arg(version)
                       .arg(kKnotFormatMajor));
    if (major < 1)
        fail(path, QStringLiteral("file format version %1 does not exist").arg(version));
}

Scene readScene(const QJsonObject& root) {
    const QString top = QStringLiteral("$");
    const QString format = asString(required(root, top, "format"), QStringLiteral("$.format"));
    if (format != QLatin1String("knotwork"))
        fail(QStringLiteral("$.format"),
             QStringLiteral("expected \"knotwork\", found ") + describe(QJsonValue(format)));
    checkVersion(root);

    Scene scene;
    IdRegistry ids;
    const QString surfacesPath = QStringLiteral("$.surfaces");
    const QJsonArray surfaces = asArray(required(root, top, "surfaces"), surfacesPath);
    if (surfaces.size() > kMaxKnotSurfaces)
        fail(surfacesPath, QStringLiteral("%1 surfaces, more than the limit %2")
                               .arg(surfaces.size())
                               .arg(kMaxKnotSurfaces));
    for (qsizetype k = 0; k < surfaces.size(); ++k) {
        const QString p = element(surfacesPath, k);
        scene.surfaces.push_back(readSurface(asObject(surfaces[k], p), p, ids));
    }

    const QString lightsPath = QStringLiteral("$.lights");
    const QJsonArray lights = asArray(required(root, top, "lights"), lightsPath);
    if (lights.size() > kMaxLights)
        fail(
            lightsPath,
            QStringLiteral("%1 lights, more than the limit %2").arg(lights.size()).arg(kMaxLights));
    scene.lights.clear();
    for (qsizetype k = 0; k < lights.size(); ++k) {
        const QString p = element(lightsPath, k);
        scene.lights.push_back(readLight(asObject(lights[k], p), p));
    }

    if (root.contains(QLatin1String("camera")))
        scene.camera =
            readCamera(asObject(root.value(QLatin1String("camera")), QStringLiteral("$.camera")),
                       QStringLiteral("$.camera"));
    if (root.contains(QLatin1String("continuity")))
        scene.continuity = readContinuity(
            asObject(root.value(QLatin1String("continuity")), QStringLiteral("$.continuity")),
            QStringLiteral("$.continuity"));
    if (root.contains(QLatin1String("display")))
        scene.display =
            readDisplay(asObject(root.value(QLatin1String("display")), QStringLiteral("$.display")),
                        QStringLiteral("$.display"));
    if (root.contains(QLatin1String("nextId")))
        scene.nextId = std::uint32_t(asInteger(root.value(QLatin1String("nextId")),
                                               QStringLiteral("$.nextId"), 1, 0xFFFFFFFFll));
    scene.nextId = std::max(scene.nextId, ids.maxId() + 1);
    // Optional (1.4): the document's length unit; older files are in millimetres.
    if (root.contains(QLatin1String("unit"))) {
        const QString path = QStringLiteral("$.unit");
        const QString key = asString(root.value(QLatin1String("unit")), path);
        if (const auto unit = lengthUnitFromKey(key); unit && key == lengthUnitKey(*unit))
            scene.unit = *unit;
        else
            fail(path, QStringLiteral("expected a length unit (mm, cm, m, km, um, in, ft, mi, "
                                      "mil, uin), found ") +
                           describe(QJsonValue(key)));
    }
    if (root.contains(QLatin1String("topology"))) {
        const QString path = QStringLiteral("$.topology");
        scene.topology = readTopology(asObject(root.value(QLatin1String("topology")), path), path);
        if (const auto bad = topologyProblem(scene))
            fail(path + QLatin1Char('.') + bad->place, bad->reason);
    }
    // The member checks above name the exact place; this is the same rule Document, the
    // importers and the writers apply, so what reads here also opens, edits and saves.
    if (const QString why = checkScene(scene).message(); !why.isEmpty())
        fail(top, why);
    return scene;
}

// "line L, column C" of a byte offset, for JSON syntax errors.
QString lineColumn(const QByteArray& json, int offset) {
    offset = std::clamp(offset, 0, int(json.size()));
    const QByteArray head = json.left(offset);
    const int line = int(head.count('\n')) + 1;
    const int column = offset - int(head.lastIndexOf('\n'));
    return QStringLiteral("line %1, column %2").arg(line).arg(column);
}

QString oneLine(QString s) {
    s.replace(QLatin1Char('\n'), QLatin1Char(' '));
    s.replace(QLatin1Char('\r'), QLatin1Char(' '));
    return s;
}

} // namespace

Expected<Scene> sceneFromJson(const QByteArray& json, const QString& sourceName) {
    try {
        // Sizes first, on the raw bytes: the JSON tree would take many times the file's size.
        if (const Status sizes = prescanKnotJson(json); !sizes)
            fail(sizes.error().location, sizes.error().message);
        QJsonParseError parseError;
        const QJsonDocument doc = QJsonDocument::fromJson(json, &parseError);
        if (parseError.error != QJsonParseError::NoError)
            fail(QStringLiteral("$"),
                 QStringLiteral("not valid JSON: %1 at %2")
                     .arg(parseError.errorString(), lineColumn(json, parseError.offset)));
        if (!doc.isObject())
            fail(QStringLiteral("$"), QStringLiteral("expected an object at the top level"));
        return readScene(doc.object());
    } catch (const FileError& e) {
        return Error(oneLine(QStringLiteral("%1: %2: %3").arg(sourceName, e.path, e.reason)),
                     sourceName, e.path);
    } catch (const std::bad_alloc&) {
        return Error(oneLine(QStringLiteral("%1: $: out of memory while reading").arg(sourceName)),
                     sourceName, QStringLiteral("$"));
    }
}

} // namespace kw
