// OBJ 3.0 free-form reader: rational/polynomial B-spline and Bezier surfaces with curv2 trims.
#include "model/document/validation.h"
#include "model/io/inputcheck.h"
#include "model/io/objfile.h"
#include "model/io/safetext.h"
#include "model/nurbs/trim.h"

#include <QFile>
#include <QFileInfo>
#include <QRegularExpression>
#include <QUrl>
#include <algorithm>
#include <cmath>
#include <new>
#include <optional>

namespace kw {
namespace {

struct ParseError {
    int line;
    QString reason;
};

[[noreturn]] void fail(int line, const QString& reason) {
    throw ParseError{line, reason};
}

double toNumber(const QByteArray& token, int line) {
    bool ok = false;
    const double x = token.toDouble(&ok);
    if (!ok || !std::isfinite(x))
        fail(line, QStringLiteral("'%1' is not a finite number").arg(quoteInput(token)));
    return x;
}

int toInt(const QByteArray& token, int line) {
    bool ok = false;
    const int x = token.toInt(&ok);
    if (!ok)
        fail(line, QStringLiteral("'%1' is not an integer").arg(quoteInput(token)));
    return x;
}

// Resolves a 1-based (or negative, relative) OBJ reference into a 0-based index.
int resolve(int ref, int count, int line, const char* what) {
    const int index = ref > 0 ? ref - 1 : count + ref;
    if (ref == 0 || index < 0 || index >= count)
        fail(line, QStringLiteral("%1 index %2 out of range (%3 defined so far)")
                       .arg(QLatin1String(what))
                       .arg(ref)
                       .arg(count));
    return index;
}

struct TrimRef {
    double t0, t1;
    int curve; // 0-based into curv2 list
};

struct Element {
    enum class Kind { None, Surface, Curve2, Other } kind = Kind::None;
    int line = 0;
    bool rational = false;
    bool bezier = false;
    bool supported = true;
    QString typeName;
    int degU = 1, degV = 1;
    double range[4] = {0, 0, 0, 0};
    std::vector<int> cps; // 0-based into v (surface) or vp (curv2)
    std::vector<double> parmU, parmV;
    std::vector<std::vector<TrimRef>> loops;
};

// Knots of a B-spline made of Bezier pieces with the given breakpoints: multiplicity = degree
// inside, degree + 1 at the ends.
std::vector<double> bezierKnots(const std::vector<double>& breaks, int degree) {
    std::vector<double> k;
    for (size_t i = 0; i < breaks.size(); ++i) {
        const int mult = (i == 0 || i + 1 == breaks.size()) ? degree + 1 : degree;
        k.insert(k.end(), mult, breaks[i]);
    }
    return k;
}

int controlCount(const std::vector<double>& parm, int degree, bool bezier) {
    if (bezier)
        return parm.size() < 2 ? -1 : degree * static_cast<int>(parm.size() - 1) + 1;
    return static_cast<int>(parm.size()) - degree - 1;
}

// The part of a surface over [a, b] in u (alongU) or v, exactly: knots inserted to
// multiplicity degree at a and b (kernel A5.3), then the clamped piece of the net cut out.
NurbsSurface surfaceSegment(NurbsSurface s, bool alongU, double a, double b) {
    const int p = alongU ? s.degreeU : s.degreeV;
    for (double t : {a, b}) {
        const std::vector<double>& k = alongU ? s.knotsU : s.knotsV;
        const int have = static_cast<int>(std::count(k.begin(), k.end(), t));
        if (have < p)
            s = alongU ? surfaceInsertKnotU(s, t, p - have) : surfaceInsertKnotV(s, t, p - have);
    }
    const std::vector<double>& k = alongU ? s.knotsU : s.knotsV;
    const auto first = std::lower_bound(k.begin(), k.end(), a) - k.begin();
    const int start = static_cast<int>(first + std::count(k.begin(), k.end(), a)) - p - 1;
    std::vector<double> knots(p + 1, a);
    for (double t : k)
        if (t > a && t < b)
            knots.push_back(t);
    knots.insert(knots.end(), p + 1, b);
    const int count = static_cast<int>(knots.size()) - p - 1;
    NurbsSurface out = s;
    (alongU ? out.knotsU : out.knotsV) = knots;
    (alongU ? out.countU : out.countV) = count;
    out.points.clear();
    out.weights.clear();
    for (int j = 0; j < out.countV; ++j) {
        for (int i = 0; i < out.countU; ++i) {
            const int src = alongU ? s.index(start + i, j) : s.index(i, start + j);
            out.points.push_back(s.points[src]);
            out.weights.push_back(s.weights[src]);
        }
    }
    return out;
}

struct Metadata {
    std::optional<std::uint32_t> id;
    std::optional<QString> name;
    int nu = 0, nv = 0;
    std::optional<Material> material;
    std::vector<std::uint32_t> loopIds;
    bool hidden = false;
    int solid = -1;
    bool outsideAlongNormal = true;
};

class ObjParser {
public:
    ObjParser(const QString& fileName, ImportReport& report) : m_file(fileName), m_report(report) {}
    Scene parse(const QByteArray& text);
    /// The line of the '# knotwork edge' or 'shell' line a topology problem's place names
    /// ("edges[3]...", "shells[0]..."), 0 when none.
    int topologyLine(const QString& place) const;

private:
    void statement(const QList<QByteArray>& t, const QByteArray& rest, int line);
    void knotworkComment(const QList<QByteArray>& t, int line);
    void finish(int line);
    void finishCurve2();
    void finishSurface();
    std::vector<double> knotsFor(const std::vector<double>& parm, int degree, bool bezier,
                                 const char* dir) const;
    void need(const QList<QByteArray>& t, int n, int line) const {
        if (t.size() < n)
            fail(
                line,
                QStringLiteral("'%1' needs at least %2 value(s)").arg(quoteInput(t[0])).arg(n - 1));
    }

    QString m_file;
    ImportReport& m_report;
    Scene m_scene;
    std::vector<glm::dvec4> m_v;
    std::vector<glm::dvec3> m_vp;
    std::vector<std::optional<NurbsCurve2>> m_curv2; // nullopt: unsupported kind, reported
    bool m_rational = false, m_bezier = false, m_supported = true;
    QString m_typeName = QStringLiteral("bspline");
    int m_degU = -1, m_degV = -1;
    QString m_object, m_group;
    Element m_el;
    Metadata m_meta;
    bool m_metaPending = false;
    bool m_lightsFromFile = false;
    int m_polygons = 0, m_ignored = 0, m_surfaceNumber = 0;
    std::optional<std::uint32_t> m_nextId;
    int m_announced = -1, m_announcedLine = 0;
    int m_edgesAnnounced = -1, m_shellsAnnounced = -1, m_topologyLine = 0;
    std::vector<int> m_edgeLines, m_shellLines;
};

int ObjParser::topologyLine(const QString& place) const {
    static const QRegularExpression re(QStringLiteral("^(edges|shells)\\[(\\d+)\\]"));
    const QRegularExpressionMatch m = re.match(place);
    if (!m.hasMatch())
        return m_topologyLine;
    const std::vector<int>& lines =
        m.captured(1) == QLatin1String("edges") ? m_edgeLines : m_shellLines;
    const size_t k = m.captured(2).toULongLong();
    return k < lines.size() ? lines[k] : m_topologyLine;
}

Scene ObjParser::parse(const QByteArray& text) {
    const QList<QByteArray> lines = text.split('\n');
    QByteArray pending;
    int pendingLine = 0;
    for (int i = 0; i < lines.size(); ++i) {
        QByteArray l = lines[i];
        if (l.endsWith('\r'))
            l.chop(1);
        if (pending.isEmpty())
            pendingLine = i + 1;
        if (l.endsWith('\\')) { // continuation
            l.chop(1);
            pending += l + ' ';
            continue;
        }
        pending += l;
        const QByteArray s = pending.trimmed();
        pending.clear();
        if (s.isEmpty())
            continue;
        const QList<QByteArray> t = s.simplified().split(' ');
        if (s.startsWith('#')) {
            if (t.size() >= 2 && t[0] == "#" && t[1] == "knotwork")
                knotworkComment(t, pendingLine);
            continue;
        }
        statement(t, s.mid(t[0].size()).trimmed(), pendingLine);
    }
    if (m_el.kind != Element::Kind::None)
        fail(m_el.line,
             QStringLiteral("element is not closed by 'end' before the end of the file"));
    // A file Knotwork wrote says how many surfaces follow: fewer means it was cut short at an
    // element boundary, which would otherwise read as a complete, smaller scene.
    if (m_announced >= 0 && m_surfaceNumber != m_announced)
        fail(m_announcedLine, QStringLiteral("'# knotwork surfaces %1' but the file holds %2 "
                                             "surface(s): is it cut short?")
                                  .arg(m_announced)
                                  .arg(m_surfaceNumber));
    if (m_edgesAnnounced >= 0 && (m_scene.topology.edges.size() != size_t(m_edgesAnnounced) ||
                                  m_scene.topology.shells.size() != size_t(m_shellsAnnounced)))
        fail(m_topologyLine, QStringLiteral("'# knotwork topology %1 %2' but the file holds %3 "
                                            "edge(s) and %4 shell(s): is it cut short?")
                                 .arg(m_edgesAnnounced)
                                 .arg(m_shellsAnnounced)
                                 .arg(m_scene.topology.edges.size())
                                 .arg(m_scene.topology.shells.size()));
    if (m_polygons > 0)
        m_report.warnings << QStringLiteral("%1: %2 polygon statement(s) (f, l, p) ignored: "
                                            "Knotwork imports free-form surfaces only")
                                 .arg(m_file)
                                 .arg(m_polygons);
    if (m_ignored > 0)
        m_report.warnings << QStringLiteral("%1: %2 free-form element(s) without a surface "
                                            "(curv, scrv, sp, con) ignored")
                                 .arg(m_file)
                                 .arg(m_ignored);
    std::uint32_t maxId = 0;
    for (const Surface& s : m_scene.surfaces) {
        maxId = std::max(maxId, s.id.value);
        for (const TrimLoop& l : s.trims)
            maxId = std::max(maxId, l.id.value);
    }
    m_scene.nextId = std::max(m_nextId.value_or(0), maxId + 1);
    return m_scene;
}

void ObjParser::knotworkComment(const QList<QByteArray>& t, int line) {
    if (t.size() < 3)
        return;
    const QByteArray& key = t[2];
    auto num = [&](int i) {
        if (i >= t.size())
            fail(line, QStringLiteral("knotwork %1: missing value").arg(quoteInput(key)));
        return toNumber(t[i], line);
    };
    // Ids and counts: integers in range before they are converted (a cast of an out-of-range
    // double is undefined behaviour).
    auto integer = [&](int i, double lo, double hi) {
        const double x = num(i);
        if (x != std::floor(x) || x < lo || x > hi)
            fail(line, QStringLiteral("knotwork %1: %2 is not an integer in [%3, %4]")
                           .arg(quoteInput(key), quoteInput(t[i]))
                           .arg(lo, 0, 'f', 0)
                           .arg(hi, 0, 'f', 0));
        return x;
    };
    auto check = [&](const QString& why) {
        if (!why.isEmpty())
            fail(line, QStringLiteral("knotwork %1: %2").arg(quoteInput(key), why));
    };
    if (key == "nextid") {
        m_nextId = static_cast<std::uint32_t>(integer(3, 1, 4294967295.0));
    } else if (key == "surfaces") {
        m_announced = static_cast<int>(integer(3, 0, kMaxSurfaces));
        m_announcedLine = line;
    } else if (key == "lights") { // the count; 0: an unlit scene, not the default lights
        integer(3, 0, kMaxLights);
        if (!m_lightsFromFile)
            m_scene.lights.clear();
        m_lightsFromFile = true;
    } else if (key == "light") {
        if (!m_lightsFromFile)
            m_scene.lights.clear();
        m_lightsFromFile = true;
        Light l;
        l.kind = t.value(3) == "point" ? Light::Kind::Point : Light::Kind::Directional;
        l.vector = {num(4), num(5), num(6)};
        l.ambient = {num(7), num(8), num(9)};
        l.diffuse = {num(10), num(11), num(12)};
        l.specular = {num(13), num(14), num(15)};
        check(checkLight(l).message());
        m_scene.lights.push_back(l);
        if (static_cast<int>(m_scene.lights.size()) > kMaxLights)
            fail(line, QStringLiteral("more than %1 lights").arg(kMaxLights));
    } else if (key == "camera") {
        Camera& c = m_scene.camera;
        c.eye = {num(3), num(4), num(5)};
        c.target = {num(6), num(7), num(8)};
        c.up = {num(9), num(10), num(11)};
        c.fovYDegrees = num(12);
        c.authored = true;
        check(checkCamera(c).message());
    } else if (key == "display") {
        const QString mode = QString::fromLatin1(t.value(3));
        m_scene.display.partitionMode = mode == QLatin1String("-") ? QString() : mode;
        m_scene.display.pixelTolerance = num(4);
        m_scene.display.background = QString::fromLatin1(t.value(5));
        check(checkDisplay(m_scene.display).message());
    } else if (key == "draft") {
        m_scene.display.pullDirection = {num(3), num(4), num(5)};
        m_scene.display.draftAngleDegrees = num(6);
        check(checkDisplay(m_scene.display).message());
    } else if (key == "surface") {
        m_meta = Metadata{};
        m_metaPending = true;
        m_meta.id = static_cast<std::uint32_t>(integer(3, 1, 4294967294.0));
        m_meta.nu = static_cast<int>(integer(4, kMinPartitions, kMaxPartitions));
        m_meta.nv = static_cast<int>(integer(5, kMinPartitions, kMaxPartitions));
        Material m;
        m.color = {num(6), num(7), num(8)};
        m.ka = num(9);
        m.kd = num(10);
        m.ks = num(11);
        m.shininess = num(12);
        check(checkMaterial(m).message());
        m_meta.material = m;
    } else if (key == "name") {
        m_meta.name = QUrl::fromPercentEncoding(t.value(3));
    } else if (key == "hidden") {
        m_meta.hidden = true;
    } else if (key == "solid") {
        m_meta.solid = static_cast<int>(integer(3, 0, kMaxSurfaces));
        const QByteArray side = t.value(4);
        if (side != "normal" && side != "reversed")
            fail(line, QStringLiteral("knotwork solid: expected normal or reversed, found '%1'")
                           .arg(quoteInput(side)));
        m_meta.outsideAlongNormal = side == "normal";
    } else if (key == "topology") {
        m_edgesAnnounced = static_cast<int>(integer(3, 0, kMaxSharedEdges));
        m_shellsAnnounced = static_cast<int>(integer(4, 0, kMaxShells));
        m_topologyLine = line;
    } else if (key == "edge") {
        SharedEdge e;
        e.id = EdgeId{static_cast<std::uint32_t>(integer(3, 1, 4294967294.0))};
        e.tolerance = num(4);
        if (!(e.tolerance >= 0.0))
            fail(line, QStringLiteral("knotwork edge: tolerance %1 is below 0")
                           .arg(QString::fromUtf8(t[4])));
        for (int k = 0; k < 2; ++k) {
            EdgeUse& side = e.sides[size_t(k)];
            const int at = 5 + 4 * k;
            side.surface = SurfaceId{static_cast<std::uint32_t>(integer(at, 1, 4294967294.0))};
            side.loop = TrimLoopId{static_cast<std::uint32_t>(integer(at + 1, 1, 4294967294.0))};
            side.curve = static_cast<int>(integer(at + 2, 0, kMaxLoopCurves - 1));
            const QByteArray way = t.value(at + 3);
            if (way != "forward" && way != "reversed")
                fail(line, QStringLiteral("knotwork edge: expected forward or reversed, found '%1'")
                               .arg(QString::fromUtf8(way)));
            side.reversed = way == "reversed";
        }
        m_scene.topology.edges.push_back(e);
        m_edgeLines.push_back(line);
    } else if (key == "shell") {
        Shell shell;
        shell.id = ShellId{static_cast<std::uint32_t>(integer(3, 1, 4294967294.0))};
        const QByteArray closed = t.value(4);
        if (closed != "closed" && closed != "open")
            fail(line, QStringLiteral("knotwork shell: expected closed or open, found '%1'")
                           .arg(QString::fromUtf8(closed)));
        shell.closed = closed == "closed";
        shell.solid = static_cast<int>(integer(5, -1, kMaxSurfaces));
        for (int i = 6; i < t.size(); ++i)
            shell.faces.push_back(
                SurfaceId{static_cast<std::uint32_t>(integer(i, 1, 4294967294.0))});
        m_scene.topology.shells.push_back(std::move(shell));
        m_shellLines.push_back(line);
    } else if (key == "loops") {
        for (int i = 3; i < t.size(); ++i)
            m_meta.loopIds.push_back(static_cast<std::uint32_t>(integer(i, 1, 4294967294.0)));
    }
}

void ObjParser::statement(const QList<QByteArray>& t, const QByteArray& rest, int line) {
    const QByteArray& k = t[0];
    if (k == "v") {
        need(t, 4, line);
        m_v.emplace_back(toNumber(t[1], line), toNumber(t[2], line), toNumber(t[3], line),
                         t.size() > 4 ? toNumber(t[4], line) : 1.0);
    } else if (k == "vp") {
        need(t, 2, line);
        m_vp.emplace_back(toNumber(t[1], line), t.size() > 2 ? toNumber(t[2], line) : 0.0,
                          t.size() > 3 ? toNumber(t[3], line) : 1.0);
    } else if (k == "vt" || k == "vn" || k == "s" || k == "mtllib" || k == "usemtl" ||
               k == "ctech" || k == "stech" || k == "lod" || k == "shadow_obj" ||
               k == "trace_obj" || k == "bevel" || k == "c_interp" || k == "d_interp") {
        // Texture/normal data and display attributes do not change the geometry.
    } else if (k == "o") {
        m_object = QString::fromUtf8(rest);
    } else if (k == "g") {
        m_group = QString::fromUtf8(rest);
    } else if (k == "f" || k == "l" || k == "p") {
        ++m_polygons;
    } else if (k == "cstype") {
        need(t, 2, line);
        m_rational = t[1] == "rat";
        if (m_rational) // before t[2] is read (found by fuzz_obj: SIGSEGV or double free)
            need(t, 3, line);
        const QByteArray type = t[m_rational ? 2 : 1];
        m_typeName = quoteInput(type);
        m_bezier = type == "bezier";
        m_supported = type == "bspline" || type == "bezier";
        if (!m_supported && type != "bmatrix" && type != "cardinal" && type != "taylor")
            fail(line, QStringLiteral("unknown cstype '%1'").arg(m_typeName));
    } else if (k == "deg") {
        need(t, 2, line);
        m_degU = toInt(t[1], line);
        m_degV = t.size() > 2 ? toInt(t[2], line) : -1;
        if (m_degU < 1 || (t.size() > 2 && m_degV < 1))
            fail(line, QStringLiteral("degree must be at least 1"));
    } else if (k == "surf" || k == "curv2" || k == "curv" || k == "scrv" || k == "sp" ||
               k == "con") {
        if (k == "sp" || k == "con") {
            ++m_ignored;
            return;
        }
        if (m_el.kind != Element::Kind::None)
            fail(line, QStringLiteral("'%1' inside an element that has no 'end' (opened on "
                                      "line %2)")
                           .arg(quoteInput(k))
                           .arg(m_el.line));
        m_el = Element{};
        m_el.line = line;
        m_el.rational = m_rational;
        m_el.bezier = m_bezier;
        m_el.supported = m_supported;
        m_el.typeName = m_typeName;
        m_el.degU = m_degU;
        m_el.degV = m_degV;
        if (k == "surf") {
            m_el.kind = Element::Kind::Surface;
            need(t, 6, line);
            if (m_degU < 1 || m_degV < 1)
                fail(line, QStringLiteral("surf needs 'deg degu degv' before it"));
            for (int i = 0; i < 4; ++i)
                m_el.range[i] = toNumber(t[1 + i], line);
            for (int i = 5; i < t.size(); ++i)
                m_el.cps.push_back(resolve(toInt(t[i].split('/')[0], line),
                                           static_cast<int>(m_v.size()), line, "vertex"));
        } else if (k == "curv2") {
            m_el.kind = Element::Kind::Curve2;
            need(t, 3, line);
            if (m_degU < 1)
                fail(line, QStringLiteral("curv2 needs 'deg' before it"));
            for (int i = 1; i < t.size(); ++i)
                m_el.cps.push_back(resolve(toInt(t[i], line), static_cast<int>(m_vp.size()), line,
                                           "parameter vertex (vp)"));
        } else {
            m_el.kind = Element::Kind::Other;
        }
    } else if (k == "parm") {
        need(t, 3, line);
        if (m_el.kind == Element::Kind::None)
            fail(line, QStringLiteral("'parm' outside an element"));
        std::vector<double>& p = t[1] == "v" ? m_el.parmV : m_el.parmU;
        if (t[1] != "u" && t[1] != "v")
            fail(line, QStringLiteral("parm direction must be u or v"));
        for (int i = 2; i < t.size(); ++i)
            p.push_back(toNumber(t[i], line));
    } else if (k == "trim" || k == "hole") {
        if (m_el.kind != Element::Kind::Surface)
            fail(line, QStringLiteral("'%1' outside a surf element").arg(quoteInput(k)));
        if (t.size() < 4 || (t.size() - 1) % 3 != 0)
            fail(line, QStringLiteral("'%1' needs triples 'u0 u1 curv2d'").arg(quoteInput(k)));
        std::vector<TrimRef> loop;
        for (int i = 1; i + 2 < t.size(); i += 3)
            loop.push_back(
                {toNumber(t[i], line), toNumber(t[i + 1], line),
                 resolve(toInt(t[i + 2], line), static_cast<int>(m_curv2.size()), line, "curv2")});
        m_el.loops.push_back(std::move(loop));
    } else if (k == "end") {
        if (m_el.kind == Element::Kind::None)
            fail(line, QStringLiteral("'end' without an element"));
        finish(line);
    } else if (k == "bmat" || k == "step" || k == "sp") {
        // Basis matrices of unsupported curve types; the element is reported as skipped.
    } else {
        fail(line, QStringLiteral("unknown statement '%1'").arg(quoteInput(k)));
    }
}

std::vector<double> ObjParser::knotsFor(const std::vector<double>& parm, int degree, bool bezier,
                                        const char* dir) const {
    if (parm.empty())
        fail(m_el.line, QStringLiteral("element has no 'parm %1'").arg(QLatin1String(dir)));
    return bezier ? bezierKnots(parm, degree) : parm;
}

void ObjParser::finish(int line) {
    try {
        if (m_el.kind == Element::Kind::Curve2)
            finishCurve2();
        else if (m_el.kind == Element::Kind::Surface)
            finishSurface();
        else
            ++m_ignored;
    } catch (ParseError& e) {
        e.reason += QStringLiteral(" (element ending on line %1)").arg(line);
        throw;
    }
    m_el = Element{};
}

void ObjParser::finishCurve2() {
    if (!m_el.supported || m_el.degU > kMaxDegree) {
        // Reported here; a trim that uses it is then an error naming this curve.
        m_curv2.push_back(std::nullopt);
        m_report.warnings << QStringLiteral("%1:%2: curv2 of type '%3', degree %4, not supported")
                                 .arg(m_file)
                                 .arg(m_el.line)
                                 .arg(m_el.typeName)
                                 .arg(m_el.degU);
        return;
    }
    NurbsCurve2 c;
    c.degree = m_el.degU;
    c.knots = knotsFor(m_el.parmU, c.degree, m_el.bezier, "u");
    for (int i : m_el.cps) {
        c.points.emplace_back(m_vp[i].x, m_vp[i].y);
        c.weights.push_back(m_el.rational ? m_vp[i].z : 1.0);
    }
    if (m_el.bezier &&
        controlCount(m_el.parmU, c.degree, true) != static_cast<int>(c.points.size()))
        fail(m_el.line, QStringLiteral("Bezier curv2 with %1 control points does not match its "
                                       "parm u")
                            .arg(c.points.size()));
    const Status valid = checkNurbsCurve(c);
    if (!valid)
        fail(m_el.line, QStringLiteral("invalid curv2: %1").arg(valid.message()));
    m_curv2.push_back(c);
}

void ObjParser::finishSurface() {
    ++m_surfaceNumber;
    Surface s;
    s.name = !m_object.isEmpty()  ? m_object
             : !m_group.isEmpty() ? m_group
                                  : QStringLiteral("Surface %1").arg(m_surfaceNumber);
    const QString what =
        QStringLiteral("%1:%2: surface '%3'").arg(m_file).arg(m_el.line).arg(s.name);
    const Metadata meta = m_metaPending ? m_meta : Metadata{};
    m_metaPending = false;
    m_meta = Metadata{};
    if (!m_el.supported) {
        m_report.skipped << what +
                                QStringLiteral(": cstype '%1' is not supported").arg(m_el.typeName);
        return;
    }
    if (m_el.degU > kMaxDegree || m_el.degV > kMaxDegree) {
        m_report.skipped << what + QStringLiteral(": degree %1x%2 above the maximum %3")
                                       .arg(m_el.degU)
                                       .arg(m_el.degV)
                                       .arg(kMaxDegree);
        return;
    }
    NurbsSurface& g = s.geometry;
    g.degreeU = m_el.degU;
    g.degreeV = m_el.degV;
    g.knotsU = knotsFor(m_el.parmU, g.degreeU, m_el.bezier, "u");
    g.knotsV = knotsFor(m_el.parmV, g.degreeV, m_el.bezier, "v");
    g.countU = static_cast<int>(g.knotsU.size()) - g.degreeU - 1;
    g.countV = static_cast<int>(g.knotsV.size()) - g.degreeV - 1;
    if (g.countU < 1 || g.countV < 1 || static_cast<size_t>(g.countU) * g.countV != m_el.cps.size())
        fail(m_el.line, QStringLiteral("surf has %1 control points but its parm u/v and degrees "
                                       "need %2 x %3")
                            .arg(m_el.cps.size())
                            .arg(g.countU)
                            .arg(g.countV));
    for (int i : m_el.cps) {
        g.points.emplace_back(m_v[i]);
        g.weights.push_back(m_el.rational ? m_v[i].w : 1.0);
    }
    const Status valid = checkNurbsSurface(g);
    if (!valid)
        fail(m_el.line, QStringLiteral("invalid surface: %1").arg(valid.message()));
    // The surf range s0 s1 t0 t1 selects part of the knot domain: cut the surface to it.
    const Interval du = surfaceDomainU(g), dv = surfaceDomainV(g);
    const double* r = m_el.range;
    auto same = [](double x, double y) {
        return std::abs(x - y) <= 1e-12 * (1.0 + std::abs(y));
    };
    if (!(r[0] < r[1]) || !(r[2] < r[3]) || r[0] < du.first - 1e-12 * (1 + std::abs(du.first)) ||
        r[1] > du.last + 1e-12 * (1 + std::abs(du.last)) ||
        r[2] < dv.first - 1e-12 * (1 + std::abs(dv.first)) ||
        r[3] > dv.last + 1e-12 * (1 + std::abs(dv.last)))
        fail(m_el.line, QStringLiteral("surf range [%1, %2] x [%3, %4] is empty or outside the "
                                       "knot domain [%5, %6] x [%7, %8]")
                            .arg(r[0])
                            .arg(r[1])
                            .arg(r[2])
                            .arg(r[3])
                            .arg(du.first)
                            .arg(du.last)
                            .arg(dv.first)
                            .arg(dv.last));
    if (!same(r[0], du.first) || !same(r[1], du.last))
        g = surfaceSegment(g, true, std::max(r[0], du.first), std::min(r[1], du.last));
    if (!same(r[2], dv.first) || !same(r[3], dv.last))
        g = surfaceSegment(g, false, std::max(r[2], dv.first), std::min(r[3], dv.last));
    for (size_t l = 0; l < m_el.loops.size(); ++l) {
        TrimLoop loop;
        for (const TrimRef& ref : m_el.loops[l]) {
            if (!m_curv2[ref.curve]) {
                fail(m_el.line, QStringLiteral("trim uses curv2 %1, which is not supported")
                                    .arg(ref.curve + 1));
            }
            const NurbsCurve2& c = *m_curv2[ref.curve];
            const Interval d = curveDomain(c);
            const double a = std::min(ref.t0, ref.t1), b = std::max(ref.t0, ref.t1);
            if (a < d.first - 1e-12 * (1 + std::abs(d.first)) ||
                b > d.last + 1e-12 * (1 + std::abs(d.last)) || !(b > a))
                fail(m_el.line, QStringLiteral("trim range [%1, %2] is outside curv2 %3's domain")
                                    .arg(ref.t0)
                                    .arg(ref.t1)
                                    .arg(ref.curve + 1));
            NurbsCurve2 piece =
                (a <= d.first && b >= d.last)
                    ? c
                    : trimCurveSegment(c, std::max(a, d.first), std::min(b, d.last));
            loop.curves.push_back(ref.t0 > ref.t1 ? trimCurveReversed(piece) : piece);
        }
        loop.id = l < meta.loopIds.size() ? TrimLoopId{meta.loopIds[l]} : TrimLoopId{};
        s.trims.push_back(std::move(loop));
    }
    if (meta.id) {
        if (*meta.id == 0 || meta.nu < kMinPartitions || meta.nu > kMaxPartitions ||
            meta.nv < kMinPartitions || meta.nv > kMaxPartitions)
            fail(m_el.line, QStringLiteral("knotwork surface metadata out of range (id %1, "
                                           "partitions %2 x %3)")
                                .arg(*meta.id)
                                .arg(meta.nu)
                                .arg(meta.nv));
        s.id = SurfaceId{*meta.id};
        s.partitionsU = meta.nu;
        s.partitionsV = meta.nv;
        s.material = *meta.material;
    }
    if (meta.name)
        s.name = *meta.name;
    s.hidden = meta.hidden;
    s.solid = meta.solid;
    s.outsideAlongNormal = meta.outsideAlongNormal;
    m_object.clear();
    m_scene.surfaces.push_back(std::move(s));
    ++m_report.facesImported;
}

} // namespace

Status parseObj(const QByteArray& text, const QString& fileName, Scene& scene,
                ImportReport& report) {
    ImportReport local;
    ObjParser parser(fileName, local);
    Scene out;
    try {
        out = parser.parse(text);
    } catch (const ParseError& e) {
        return Error(QStringLiteral("%1:%2: %3").arg(fileName).arg(e.line).arg(e.reason), fileName,
                     QStringLiteral("line %1").arg(e.line));
    } catch (const std::bad_alloc&) {
        return Error(QStringLiteral("%1: too large to read (out of memory)").arg(fileName),
                     fileName);
    }
    // Ids from the file must be unique; surfaces and loops without one get fresh ones.
    std::vector<std::uint32_t> used;
    for (const Surface& s : out.surfaces) {
        if (s.id.isValid())
            used.push_back(s.id.value);
        for (const TrimLoop& l : s.trims)
            if (l.id.isValid())
                used.push_back(l.id.value);
    }
    std::sort(used.begin(), used.end());
    if (std::adjacent_find(used.begin(), used.end()) != used.end()) {
        return Error(QStringLiteral("%1: knotwork metadata repeats an id").arg(fileName), fileName);
    }
    for (Surface& s : out.surfaces) {
        if (!s.id.isValid())
            s.id = SurfaceId{out.nextId++};
        for (TrimLoop& l : s.trims)
            if (!l.id.isValid())
                l.id = TrimLoopId{out.nextId++};
    }
    // Loops bridged on import are saved closed (docs/FILE_FORMAT.md): each gap between trim
    // pieces is closed as the renderer would bridge it, with a warning; then the one rule of a
    // valid scene (model/document/validation.h), so an accepted file always saves and reopens.
    for (const QString& line : closeSceneTrimLoops(out))
        local.warnings << QStringLiteral("%1: %2").arg(fileName, line);
    // The topology's references, named by the line that makes them.
    if (const auto bad = topologyProblem(out)) {
        const int line = parser.topologyLine(bad->place);
        return Error(QStringLiteral("%1:%2: knotwork topology: %3: %4")
                         .arg(fileName)
                         .arg(line)
                         .arg(bad->place, bad->reason),
                     fileName, QStringLiteral("line %1").arg(line));
    }
    if (const QString why = checkScene(out).message(); !why.isEmpty())
        return Error(QStringLiteral("%1: %2").arg(fileName, why), fileName);
    if (out.surfaces.empty() && local.skipped.isEmpty())
        return Error(
            QStringLiteral("%1: no free-form surfaces (surf ... end) in the file").arg(fileName),
            fileName);
    report = local;
    scene = std::move(out);
    return ok();
}

Status readObjFile(const QString& path, Scene& scene, ImportReport& report) {
    // Only a regular file within the size limit, and only text that starts like OBJ: random
    // bytes are refused from their first 4 KiB, not after reading and splitting all of them.
    QString why = checkRegularFile(path, kMaxObjFileBytes, QStringLiteral("OBJ")).message();
    if (why.isEmpty())
        why = checkObjHead(fileHead(path, kSniffBytes)).message();
    if (!why.isEmpty()) {
        if (why.startsWith(QLatin1String("line ")))
            return Error(QStringLiteral("%1:%2").arg(path, why.mid(5)), path,
                         why.section(QLatin1Char(':'), 0, 0));
        return Error(QStringLiteral("%1: %2").arg(path, why), path);
    }
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly))
        return Error(QStringLiteral("%1: cannot open: %2").arg(path, f.errorString()), path);
    return parseObj(f.readAll(), path, scene, report);
}

} // namespace kw
