// The CAD child's binary hand-over (see handover.h).
#include "model/cad/handover.h"

#include "model/document/validation.h"

#include <cstring>
#include <type_traits>

namespace kw {
namespace {

// "KWIMPORT", then the version: bump it with any change below. The end mark catches a block
// cut at a field boundary.
constexpr char kMagic[8] = {'K', 'W', 'I', 'M', 'P', 'O', 'R', 'T'};
// 2: Surface::solid, outsideAlongNormal; 3: Scene::topology; 4: DisplaySettings::background;
// 5: DisplaySettings::sections, sectionCaps
// 6: DisplaySettings::pullDirection, draftAngleDegrees
// 7: Scene::continuity
// 8: Scene::unit (Scene's size did not change: it took the padding after nextId)
// 9: Surface::analytic
constexpr std::uint32_t kVersion = 9;
constexpr std::uint32_t kEndMark = 0x454e444bu; // "KDNE"

// A field added to these types must be added to the hand-over (and kVersion bumped): the sizes
// are checked so that the build fails instead of the field being dropped on the way back.
static_assert(sizeof(void*) != 8 || sizeof(Surface) == 432, "update the CAD hand-over");
static_assert(sizeof(NurbsSurface) == 112, "update the CAD hand-over");
static_assert(sizeof(NurbsCurve2) == 80, "update the CAD hand-over");
static_assert(sizeof(TrimLoop) == 32, "update the CAD hand-over");
static_assert(sizeof(Light) == 104, "update the CAD hand-over");
static_assert(sizeof(Camera) == 88, "update the CAD hand-over");
static_assert(sizeof(DisplaySettings) == 120, "update the CAD hand-over");
static_assert(sizeof(SectionPlane) == 56, "update the CAD hand-over");
static_assert(sizeof(Scene) == 344, "update the CAD hand-over");
static_assert(sizeof(ContinuityTolerances) == 32, "update the CAD hand-over");
static_assert(sizeof(EdgeUse) == 16, "update the CAD hand-over");
static_assert(sizeof(SharedEdge) == 48, "update the CAD hand-over");
static_assert(sizeof(Shell) == 40, "update the CAD hand-over");
static_assert(sizeof(Topology) == 48, "update the CAD hand-over");
static_assert(sizeof(Material) == 56, "update the CAD hand-over");
static_assert(sizeof(AnalyticForm) == 184, "update the CAD hand-over");

class Writer {
public:
    template <class T> void value(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        m_out.append(reinterpret_cast<const char*>(&v), sizeof(T));
    }
    template <class T> void array(const std::vector<T>& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        value(std::uint32_t(v.size()));
        m_out.append(reinterpret_cast<const char*>(v.data()), qsizetype(v.size() * sizeof(T)));
    }
    void string(const QString& s) {
        value(std::uint32_t(s.size()));
        m_out.append(reinterpret_cast<const char*>(s.utf16()), s.size() * 2);
    }
    void strings(const QStringList& list) {
        value(std::uint32_t(list.size()));
        for (const QString& s : list)
            string(s);
    }
    void raw(const char* bytes, qsizetype n) { m_out.append(bytes, n); }
    QByteArray take() { return std::move(m_out); }

private:
    QByteArray m_out;
};

class Reader {
public:
    explicit Reader(const QByteArray& block) : m_block(block) {}
    bool failed() const { return !m_why.isEmpty(); }
    const QString& why() const { return m_why; }
    qsizetype position() const { return m_at; }
    qsizetype failedAt() const { return m_failedAt; }
    bool atEnd() const { return m_at == m_block.size(); }

    void fail(const QString& what, const QString& reason) {
        if (m_why.isEmpty()) {
            m_why = QStringLiteral("%1 at byte %2: %3").arg(what).arg(m_at).arg(reason);
            m_failedAt = m_at;
        }
    }
    bool bytes(void* to, qsizetype n, const char* what) {
        if (failed())
            return false;
        if (n < 0 || m_block.size() - m_at < n) {
            fail(QString::fromLatin1(what), QStringLiteral("the block is truncated"));
            return false;
        }
        std::memcpy(to, m_block.constData() + m_at, size_t(n));
        m_at += n;
        return true;
    }
    template <class T> T value(const char* what) {
        T v{};
        bytes(&v, sizeof(T), what);
        return v;
    }
    bool flag(const char* what) {
        const auto b = value<std::uint8_t>(what);
        if (b > 1)
            fail(QString::fromLatin1(what), QStringLiteral("a flag is %1, not 0 or 1").arg(b));
        return b == 1;
    }
    // A count of items of `size` bytes each, refused when the bytes left cannot hold them (so
    // a corrupt count never allocates).
    std::uint32_t count(qsizetype size, const char* what) {
        const auto n = value<std::uint32_t>(what);
        if (!failed() && qsizetype(n) > (m_block.size() - m_at) / size) {
            fail(QString::fromLatin1(what),
                 QStringLiteral("a count of %1 is more than the block holds").arg(n));
            return 0;
        }
        return failed() ? 0 : n;
    }
    template <class T> std::vector<T> array(const char* what) {
        std::vector<T> v(count(sizeof(T), what));
        bytes(v.data(), qsizetype(v.size() * sizeof(T)), what);
        return v;
    }
    QString string(const char* what) {
        QString s(count(2, what), Qt::Uninitialized);
        bytes(s.data(), s.size() * 2, what);
        return s;
    }
    QStringList strings(const char* what) {
        QStringList list;
        const std::uint32_t n = count(4, what); // each string has at least its length
        for (std::uint32_t k = 0; k < n && !failed(); ++k)
            list << string(what);
        return list;
    }

private:
    const QByteArray& m_block;
    qsizetype m_at = 0;
    QString m_why;
    qsizetype m_failedAt = 0;
};

void writeCurve(Writer& w, const NurbsCurve2& c) {
    w.value(std::int32_t(c.degree));
    w.array(c.knots);
    w.array(c.points);
    w.array(c.weights);
}

NurbsCurve2 readCurve(Reader& r) {
    NurbsCurve2 c;
    c.degree = r.value<std::int32_t>("trim curve degree");
    c.knots = r.array<double>("trim curve knots");
    c.points = r.array<glm::dvec2>("trim curve points");
    c.weights = r.array<double>("trim curve weights");
    return c;
}

void writeAnalytic(Writer& w, const AnalyticForm& a) {
    w.value(std::uint8_t(a.kind));
    for (const glm::dvec3& v : {a.origin, a.xAxis, a.yAxis, a.zAxis})
        w.value(v);
    for (double d : {a.radius, a.minorRadius, a.semiAngle})
        w.value(d);
    for (const AnalyticParamMap& m : {a.u, a.v}) {
        w.value(std::uint8_t(m.kind));
        w.value(m.offset);
        w.value(m.scale);
    }
    w.value(std::uint8_t(a.swapped));
}

AnalyticForm readAnalytic(Reader& r) {
    AnalyticForm a;
    const auto kind = r.value<std::uint8_t>("surface analytic kind");
    if (kind > std::uint8_t(AnalyticForm::Kind::Torus))
        r.fail(QStringLiteral("surface analytic kind"),
               QStringLiteral("unknown kind %1").arg(kind));
    a.kind = AnalyticForm::Kind(kind);
    for (glm::dvec3* v : {&a.origin, &a.xAxis, &a.yAxis, &a.zAxis})
        *v = r.value<glm::dvec3>("surface analytic frame");
    for (double* d : {&a.radius, &a.minorRadius, &a.semiAngle})
        *d = r.value<double>("surface analytic radii");
    for (AnalyticParamMap* m : {&a.u, &a.v}) {
        const auto mapKind = r.value<std::uint8_t>("surface analytic map");
        if (mapKind > std::uint8_t(AnalyticParamMap::Kind::HalfAngle))
            r.fail(QStringLiteral("surface analytic map"),
                   QStringLiteral("unknown kind %1").arg(mapKind));
        m->kind = AnalyticParamMap::Kind(mapKind);
        m->offset = r.value<double>("surface analytic map");
        m->scale = r.value<double>("surface analytic map");
    }
    a.swapped = r.flag("surface analytic swapped flag");
    return a;
}

void writeSurface(Writer& w, const Surface& s) {
    w.value(s.id.value);
    w.string(s.name);
    const NurbsSurface& g = s.geometry;
    for (int v : {g.degreeU, g.degreeV, g.countU, g.countV})
        w.value(std::int32_t(v));
    w.array(g.knotsU);
    w.array(g.knotsV);
    w.array(g.points);
    w.array(g.weights);
    w.value(std::uint32_t(s.trims.size()));
    for (const TrimLoop& loop : s.trims) {
        w.value(loop.id.value);
        w.value(std::uint32_t(loop.curves.size()));
        for (const NurbsCurve2& c : loop.curves)
            writeCurve(w, c);
    }
    w.value(std::int32_t(s.partitionsU));
    w.value(std::int32_t(s.partitionsV));
    w.value(s.material);
    w.value(std::uint8_t(s.hidden));
    w.value(std::int32_t(s.solid));
    w.value(std::uint8_t(s.outsideAlongNormal));
    writeAnalytic(w, s.analytic);
}

Surface readSurface(Reader& r) {
    Surface s;
    s.id.value = r.value<std::uint32_t>("surface id");
    s.name = r.string("surface name");
    NurbsSurface& g = s.geometry;
    for (int* v : {&g.degreeU, &g.degreeV, &g.countU, &g.countV})
        *v = r.value<std::int32_t>("surface degrees and counts");
    g.knotsU = r.array<double>("surface knots");
    g.knotsV = r.array<double>("surface knots");
    g.points = r.array<glm::dvec3>("surface points");
    g.weights = r.array<double>("surface weights");
    // A loop is at least its id and curve count; a curve at least its degree and three counts.
    s.trims.resize(r.count(8, "trim loop count"));
    for (TrimLoop& loop : s.trims) {
        loop.id.value = r.value<std::uint32_t>("trim loop id");
        loop.curves.resize(r.count(16, "trim curve count"));
        for (NurbsCurve2& c : loop.curves)
            c = readCurve(r);
        if (r.failed())
            break;
    }
    s.partitionsU = r.value<std::int32_t>("surface partitions");
    s.partitionsV = r.value<std::int32_t>("surface partitions");
    s.material = r.value<Material>("surface material");
    s.hidden = r.flag("surface hidden flag");
    s.solid = r.value<std::int32_t>("surface solid");
    s.outsideAlongNormal = r.flag("surface outside flag");
    s.analytic = readAnalytic(r);
    return s;
}

void writeTopology(Writer& w, const Topology& t) {
    w.value(std::uint32_t(t.edges.size()));
    for (const SharedEdge& e : t.edges) {
        w.value(e.id.value);
        w.value(e.tolerance);
        for (const EdgeUse& side : e.sides) {
            w.value(side.surface.value);
            w.value(side.loop.value);
            w.value(std::int32_t(side.curve));
            w.value(std::uint8_t(side.reversed));
        }
    }
    w.value(std::uint32_t(t.shells.size()));
    for (const Shell& shell : t.shells) {
        w.value(shell.id.value);
        w.value(std::uint8_t(shell.closed));
        w.value(std::int32_t(shell.solid));
        std::vector<std::uint32_t> faces;
        for (SurfaceId f : shell.faces)
            faces.push_back(f.value);
        w.array(faces);
    }
}

Topology readTopology(Reader& r) {
    Topology t;
    // An edge is 38 bytes (id, tolerance, two sides of 13), a shell at least 13.
    t.edges.resize(r.count(38, "shared edge count"));
    for (SharedEdge& e : t.edges) {
        e.id.value = r.value<std::uint32_t>("shared edge id");
        e.tolerance = r.value<double>("shared edge tolerance");
        for (EdgeUse& side : e.sides) {
            side.surface.value = r.value<std::uint32_t>("shared edge surface");
            side.loop.value = r.value<std::uint32_t>("shared edge loop");
            side.curve = r.value<std::int32_t>("shared edge curve");
            side.reversed = r.flag("shared edge reversed flag");
        }
        if (r.failed())
            break;
    }
    t.shells.resize(r.count(13, "shell count"));
    for (Shell& shell : t.shells) {
        shell.id.value = r.value<std::uint32_t>("shell id");
        shell.closed = r.flag("shell closed flag");
        shell.solid = r.value<std::int32_t>("shell solid");
        for (std::uint32_t f : r.array<std::uint32_t>("shell faces"))
            shell.faces.push_back(SurfaceId{f});
        if (r.failed())
            break;
    }
    return t;
}

} // namespace

QByteArray encodeImportHandover(const ImportResult& result) {
    Writer w;
    const Scene& scene = result.scene;
    w.raw(kMagic, sizeof(kMagic));
    w.value(kVersion);
    w.value(scene.nextId);
    w.value(std::uint32_t(scene.surfaces.size()));
    for (const Surface& s : scene.surfaces)
        writeSurface(w, s);
    writeTopology(w, scene.topology);
    w.value(std::uint32_t(scene.lights.size()));
    for (const Light& l : scene.lights) {
        w.value(std::uint8_t(l.kind == Light::Kind::Point));
        for (const glm::dvec3& v : {l.vector, l.ambient, l.diffuse, l.specular})
            w.value(v);
    }
    const Camera& c = scene.camera;
    for (const glm::dvec3& v : {c.eye, c.target, c.up})
        w.value(v);
    w.value(c.fovYDegrees);
    w.value(std::uint8_t(c.authored));
    w.string(scene.display.partitionMode);
    w.value(scene.display.pixelTolerance);
    w.string(scene.display.background);
    w.value(std::uint32_t(scene.display.sections.size()));
    for (const SectionPlane& p : scene.display.sections) {
        w.value(p.position);
        w.value(p.normal);
        w.value(std::uint8_t(p.flip));
    }
    w.value(std::uint8_t(scene.display.sectionCaps));
    w.value(scene.display.pullDirection);
    w.value(scene.display.draftAngleDegrees);
    w.value(scene.continuity);
    w.string(lengthUnitKey(scene.unit));
    w.value(std::int32_t(result.report.facesImported));
    w.strings(result.report.skipped);
    w.strings(result.report.warnings);
    w.value(result.report.seconds);
    std::vector<std::int32_t> faces(result.sourceFaces.begin(), result.sourceFaces.end());
    w.array(faces);
    w.value(kEndMark);
    return w.take();
}

Expected<ImportResult> decodeImportHandover(const QByteArray& block) {
    Reader r(block);
    char magic[sizeof(kMagic)] = {};
    r.bytes(magic, sizeof(magic), "header");
    if (!r.failed() && std::memcmp(magic, kMagic, sizeof(kMagic)) != 0)
        r.fail(QStringLiteral("header"), QStringLiteral("not a Knotwork import hand-over"));
    const auto version = r.value<std::uint32_t>("header");
    if (!r.failed() && version != kVersion)
        r.fail(QStringLiteral("header"),
               QStringLiteral("version %1, this build reads version %2 (the CAD reader is "
                              "another build of knotwork)")
                   .arg(version)
                   .arg(kVersion));
    ImportResult result;
    Scene& scene = result.scene;
    scene.nextId = r.value<std::uint32_t>("next id");
    // A surface is at least 69 bytes (ids, counts, partitions, material, flag).
    scene.surfaces.resize(r.count(69, "surface count"));
    for (Surface& s : scene.surfaces) {
        s = readSurface(r);
        if (r.failed())
            break;
    }
    scene.topology = readTopology(r);
    scene.lights.resize(r.count(1 + 4 * sizeof(glm::dvec3), "light count"));
    for (Light& l : scene.lights) {
        l.kind = r.flag("light kind") ? Light::Kind::Point : Light::Kind::Directional;
        for (glm::dvec3* v : {&l.vector, &l.ambient, &l.diffuse, &l.specular})
            *v = r.value<glm::dvec3>("light");
    }
    Camera& c = scene.camera;
    for (glm::dvec3* v : {&c.eye, &c.target, &c.up})
        *v = r.value<glm::dvec3>("camera");
    c.fovYDegrees = r.value<double>("camera");
    c.authored = r.flag("camera authored flag");
    scene.display.partitionMode = r.string("display partition mode");
    scene.display.pixelTolerance = r.value<double>("display pixel tolerance");
    scene.display.background = r.string("display background");
    // A plane is 49 bytes: a point, a normal and the flip flag.
    scene.display.sections.resize(r.count(49, "section plane count"));
    for (SectionPlane& p : scene.display.sections) {
        p.position = r.value<glm::dvec3>("section plane position");
        p.normal = r.value<glm::dvec3>("section plane normal");
        p.flip = r.flag("section plane flip flag");
    }
    scene.display.sectionCaps = r.flag("section caps flag");
    scene.display.pullDirection = r.value<glm::dvec3>("display pull direction");
    scene.display.draftAngleDegrees = r.value<double>("display draft angle");
    scene.continuity = r.value<ContinuityTolerances>("continuity tolerances");
    const QString unit = r.string("length unit");
    if (const auto u = lengthUnitFromKey(unit))
        scene.unit = *u;
    else if (!r.failed())
        r.fail(QStringLiteral("length unit"), QStringLiteral("unknown unit '%1'").arg(unit));
    result.report.facesImported = r.value<std::int32_t>("report face count");
    result.report.skipped = r.strings("report skipped faces");
    result.report.warnings = r.strings("report warnings");
    result.report.seconds = r.value<double>("report seconds");
    const std::vector<std::int32_t> faces = r.array<std::int32_t>("source faces");
    result.sourceFaces.assign(faces.begin(), faces.end());
    if (r.value<std::uint32_t>("end mark") != kEndMark && !r.failed())
        r.fail(QStringLiteral("end mark"), QStringLiteral("missing: the block is corrupt"));
    if (!r.failed() && !r.atEnd())
        r.fail(QStringLiteral("end mark"),
               QStringLiteral("%1 bytes follow it").arg(block.size() - r.position()));
    if (r.failed())
        return Error(r.why(), QString(), QStringLiteral("byte %1").arg(r.failedAt()));
    if (result.sourceFaces.size() != scene.surfaces.size())
        return Error(QStringLiteral("%1 source faces for %2 surfaces")
                         .arg(result.sourceFaces.size())
                         .arg(scene.surfaces.size()));
    if (const Status valid = checkScene(scene); !valid)
        return Error(QStringLiteral("the scene is not valid: %1").arg(valid.message()));
    return result;
}

} // namespace kw
