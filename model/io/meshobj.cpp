// Tagged triangle meshes as OBJ (model/io/meshobj.h).
#include "model/io/meshobj.h"

#include <QFile>
#include <charconv>
#include <cmath>
#include <cstring>
#include <unordered_map>

namespace kw {

long long TaggedMeshSet::triangleCount() const {
    long long n = 0;
    for (const TaggedMesh& f : faces)
        n += (long long)(f.indices.size() / 3);
    return n;
}

long long TaggedMeshSet::vertexCount() const {
    long long n = 0;
    for (const TaggedMesh& f : faces)
        n += (long long)f.positions.size();
    return n;
}

namespace {

// std::to_chars / from_chars: exact and independent of the C locale (a German locale would
// write and expect decimal commas with printf / strtod).
void appendNumber(QByteArray& out, double x) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::general, 9);
    out.append(buf, r.ptr - buf);
}

void appendIndex(QByteArray& out, long long i) {
    char buf[24];
    const auto r = std::to_chars(buf, buf + sizeof buf, i);
    out.append(buf, r.ptr - buf);
}

} // namespace

QByteArray writeTaggedMeshObj(const TaggedMeshSet& set) {
    QByteArray out;
    out.reserve(qsizetype(set.vertexCount() * 90 + set.triangleCount() * 40 + 256));
    out += "# knotwork tagged mesh: one group surface_<id> per face, ids of the matching .knot\n";
    out += "# deflection linear ";
    appendNumber(out, set.linearDeflection);
    out += " angular-degrees ";
    appendNumber(out, set.angularDeflectionDegrees);
    out += '\n';
    long long base = 0; // vertices written before this face
    for (const TaggedMesh& f : set.faces) {
        out += "g surface_";
        appendIndex(out, f.id.value);
        out += "\n# face ";
        appendIndex(out, f.sourceFace);
        out += '\n';
        const auto line = [&](const char* tag, const double* x, int n) {
            out += tag;
            for (int k = 0; k < n; ++k) {
                out += ' ';
                appendNumber(out, x[k]);
            }
            out += '\n';
        };
        for (size_t i = 0; i < f.positions.size(); ++i) {
            line("v", &f.positions[i].x, 3);
            const glm::dvec2 uv = i < f.uvs.size() ? f.uvs[i] : glm::dvec2(0.0);
            line("vt", &uv.x, 2);
            const glm::dvec3 n = i < f.normals.size() ? f.normals[i] : glm::dvec3(0.0, 0.0, 1.0);
            line("vn", &n.x, 3);
        }
        for (size_t t = 0; t + 2 < f.indices.size(); t += 3) {
            out += 'f';
            for (int c = 0; c < 3; ++c) {
                const long long i = base + f.indices[t + size_t(c)] + 1;
                out += ' ';
                appendIndex(out, i);
                out += '/';
                appendIndex(out, i);
                out += '/';
                appendIndex(out, i);
            }
            out += '\n';
        }
        base += (long long)f.positions.size();
    }
    return out;
}

namespace {

struct Parser {
    const QString& file;
    Error& error;
    long long lineNo = 0;

    bool fail(const QString& why) {
        error = Error(QStringLiteral("%1:%2: %3").arg(file).arg(lineNo).arg(why), file,
                      QStringLiteral("line %1").arg(lineNo));
        return false;
    }
};

const char* skipSpace(const char* p, const char* end) {
    while (p < end && (*p == ' ' || *p == '\t' || *p == '\r'))
        ++p;
    return p;
}

bool readDoubles(const char* p, const char* end, double* out, int need, int atMost) {
    int n = 0;
    for (p = skipSpace(p, end); p < end; p = skipSpace(p, end)) {
        double x = 0.0;
        const auto r = std::from_chars(p, end, x);
        if (r.ec != std::errc() || !std::isfinite(x) || n == atMost)
            return false;
        out[n++] = x;
        p = r.ptr;
    }
    return n >= need;
}

// An OBJ index (1-based, or negative counting back from `count`) to 0-based; -1 when bad.
long long resolveIndex(long long i, size_t count) {
    if (i > 0 && (size_t)i <= count)
        return i - 1;
    if (i < 0 && (size_t)(-i) <= count)
        return (long long)count + i;
    return -1;
}

struct Corner {
    long long v = -1, t = -1, n = -1;
    bool operator==(const Corner&) const = default;
};

struct CornerHash {
    size_t operator()(const Corner& c) const {
        return std::hash<long long>()(c.v * 73856093LL ^ c.t * 19349663LL ^ c.n * 83492791LL);
    }
};

// The parse itself; false with `error` set on the first problem.
bool parseMesh(const QByteArray& text, const QString& fileName, TaggedMeshSet& set, Error& error) {
    Parser ps{fileName, error};
    std::vector<glm::dvec3> v, vn;
    std::vector<glm::dvec2> vt;
    TaggedMeshSet result;
    TaggedMesh* face = nullptr;
    std::unordered_map<Corner, unsigned, CornerHash> corners; // of the current face
    std::unordered_map<std::uint32_t, size_t> byId;
    const char* p = text.constData();
    const char* const end = p + text.size();
    std::vector<Corner> poly;
    while (p < end) {
        ++ps.lineNo;
        const char* eol = static_cast<const char*>(std::memchr(p, '\n', size_t(end - p)));
        const char* lineEnd = eol ? eol : end;
        const char* s = skipSpace(p, lineEnd);
        const char* word = s;
        while (s < lineEnd && *s != ' ' && *s != '\t' && *s != '\r')
            ++s;
        const QByteArray tag(word, s - word);
        p = eol ? eol + 1 : end;
        if (tag == "#" && face) { // "# face K" after a group: the CAD file's face index
            const QByteArray rest = QByteArray(s, lineEnd - s).trimmed();
            if (rest.startsWith("face "))
                face->sourceFace = rest.mid(5).toInt();
            continue;
        }
        if (tag.isEmpty() || tag.startsWith('#') || tag == "o" || tag == "s" || tag == "usemtl" ||
            tag == "mtllib")
            continue;
        double x[4];
        if (tag == "v") {
            if (!readDoubles(s, lineEnd, x, 3, 4)) // an optional weight is ignored
                return ps.fail(QStringLiteral("a vertex needs 3 finite numbers"));
            v.emplace_back(x[0], x[1], x[2]);
        } else if (tag == "vn") {
            if (!readDoubles(s, lineEnd, x, 3, 3))
                return ps.fail(QStringLiteral("a normal needs 3 finite numbers"));
            vn.emplace_back(x[0], x[1], x[2]);
        } else if (tag == "vt") {
            if (!readDoubles(s, lineEnd, x, 1, 3))
                return ps.fail(QStringLiteral("a texture vertex needs 1 to 3 finite numbers"));
            vt.emplace_back(x[0], x[1]);
        } else if (tag == "g") {
            const QByteArray name = QByteArray(s, lineEnd - s).trimmed();
            bool ok = false;
            const qulonglong id = name.startsWith("surface_") ? name.mid(8).toULongLong(&ok) : 0;
            if (!ok || id == 0 || id > 0xfffffffeULL)
                return ps.fail(QStringLiteral("group '%1' is not surface_<id> with an id in 1 "
                                              "... 4294967294")
                                   .arg(QString::fromUtf8(name.left(60))));
            const auto [it, added] = byId.emplace(std::uint32_t(id), result.faces.size());
            if (added) {
                result.faces.emplace_back();
                result.faces.back().id = SurfaceId{std::uint32_t(id)};
            }
            face = &result.faces[it->second];
            corners.clear(); // a group seen again continues its face with new vertices
        } else if (tag == "f") {
            if (!face)
                return ps.fail(QStringLiteral("a face outside a 'g surface_<id>' group"));
            poly.clear();
            for (const char* q = skipSpace(s, lineEnd); q < lineEnd; q = skipSpace(q, lineEnd)) {
                long long idx[3] = {0, 0, 0};
                for (int part = 0; part < 3 && q < lineEnd && *q != ' ' && *q != '\t' && *q != '\r';
                     ++part) {
                    if (*q != '/') {
                        const auto r = std::from_chars(q, lineEnd, idx[part]);
                        if (r.ec != std::errc())
                            return ps.fail(QStringLiteral("a face corner is not v, v/vt, "
                                                          "v//vn or v/vt/vn"));
                        q = r.ptr;
                    }
                    if (q < lineEnd && *q == '/')
                        ++q;
                }
                Corner c{resolveIndex(idx[0], v.size()),
                         idx[1] ? resolveIndex(idx[1], vt.size()) : -2,
                         idx[2] ? resolveIndex(idx[2], vn.size()) : -2};
                if (c.v < 0 || c.t == -1 || c.n == -1)
                    return ps.fail(QStringLiteral("a face index is out of range"));
                poly.push_back(c);
            }
            if (poly.size() < 3)
                return ps.fail(QStringLiteral("a face needs at least 3 corners"));
            // The flat normal, for corners that name none.
            glm::dvec3 flat = glm::cross(v[size_t(poly[1].v)] - v[size_t(poly[0].v)],
                                         v[size_t(poly[2].v)] - v[size_t(poly[0].v)]);
            const double len = glm::length(flat);
            flat = len > 0.0 ? flat / len : glm::dvec3(0.0, 0.0, 1.0);
            std::vector<unsigned> local(poly.size());
            for (size_t k = 0; k < poly.size(); ++k) {
                const auto [it, added] = corners.emplace(poly[k], unsigned(face->positions.size()));
                if (added) {
                    face->positions.push_back(v[size_t(poly[k].v)]);
                    face->uvs.push_back(poly[k].t >= 0 ? vt[size_t(poly[k].t)] : glm::dvec2(0.0));
                    glm::dvec3 n = poly[k].n >= 0 ? vn[size_t(poly[k].n)] : flat;
                    const double nl = glm::length(n);
                    face->normals.push_back(nl > 0.0 ? n / nl : flat);
                }
                local[k] = it->second;
            }
            for (size_t k = 1; k + 1 < poly.size(); ++k) // a fan
                face->indices.insert(face->indices.end(), {local[0], local[k], local[k + 1]});
        } else if (tag == "l" || tag == "p" || tag == "curv2" || tag == "surf") {
            return ps.fail(QStringLiteral("'%1' is not a triangle-mesh statement")
                               .arg(QString::fromUtf8(tag)));
        } else {
            continue; // other statements carry nothing a triangle mesh needs
        }
    }
    // The header comment's deflections, when present.
    const qsizetype at = text.indexOf("# deflection linear ");
    if (at >= 0) {
        const qsizetype eol = text.indexOf('\n', at);
        const QList<QByteArray> w = text.mid(at, eol < 0 ? -1 : eol - at).split(' ');
        if (w.size() == 6) {
            result.linearDeflection = w[3].toDouble();
            result.angularDeflectionDegrees = w[5].toDouble();
        }
    }
    if (result.triangleCount() == 0) {
        error =
            Error(QStringLiteral("%1: no triangles in any 'g surface_<id>' group").arg(fileName),
                  fileName);
        return false;
    }
    set = std::move(result);
    return true;
}

} // namespace

Expected<TaggedMeshSet> parseTaggedMeshObj(const QByteArray& text, const QString& fileName) {
    TaggedMeshSet set;
    Error error;
    if (!parseMesh(text, fileName, set, error))
        return error;
    return set;
}

Expected<TaggedMeshSet> readTaggedMeshObjFile(const QString& path) {
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly))
        return Error(QStringLiteral("%1: cannot open: %2").arg(path, f.errorString()), path);
    const QByteArray bytes = f.readAll();
    if (f.error() != QFileDevice::NoError)
        return Error(QStringLiteral("%1: cannot read: %2").arg(path, f.errorString()), path);
    return parseTaggedMeshObj(bytes, path);
}

} // namespace kw
