// Triangle meshes tagged with surface ids, as OBJ: the OpenCASCADE mesh peer
// (`knotwork mesh` writes one, `knotwork render --peer-mesh` draws it in place of the
// document's surfaces). Plain data; the model's dependencies only (Qt Core, GLM).
#pragma once

#include "model/document/scene.h"
#include "model/error.h"

#include <QByteArray>
#include <QString>
#include <glm/glm.hpp>
#include <vector>

namespace kw {

/// One face's triangles: positions, unit normals and (u, v) per vertex, GL_TRIANGLES indices.
/// `id` is the surface the face became in the matching .knot; `sourceFace` the 1-based face
/// index of the CAD file (ImportResult::sourceFaces), 0 when unknown.
struct TaggedMesh {
    SurfaceId id;
    int sourceFace = 0;
    std::vector<glm::dvec3> positions;
    std::vector<glm::dvec3> normals;
    std::vector<glm::dvec2> uvs;
    std::vector<unsigned> indices;
};

/// A mesh of a whole CAD file, one TaggedMesh per imported face, in the .knot's surface order,
/// with the meshing parameters it was made with (for the record; 0 when not known).
struct TaggedMeshSet {
    double linearDeflection = 0.0;
    double angularDeflectionDegrees = 0.0;
    std::vector<TaggedMesh> faces;
    long long triangleCount() const;
    long long vertexCount() const;
};

/// The set as OBJ text: a header comment with the deflections, then per face
/// `g surface_<id>` and a `# face <k>` comment, its v / vt / vn lines and `f a/a/a b/b/b c/c/c`
/// triangles (indices global and 1-based, as OBJ numbers them), numbers in %.9g.
QByteArray writeTaggedMeshObj(const TaggedMeshSet& set);

/// Parses what writeTaggedMeshObj writes, and any triangle OBJ whose faces lie in groups named
/// `surface_<id>`: v, vt, vn, g, f with v/vt/vn, v//vn or v/vt corners (negative indices count
/// back; polygons are fanned), comments, o, s and usemtl/mtllib ignored. A corner without a
/// normal gets the face's flat normal. Returns the error "<fileName>:<line>: <reason>"
/// (Error::location "line N") for a malformed number, an index out of range, a face outside a
/// `surface_<id>` group or a group name that is not one, and "<fileName>: <reason>" for a file
/// with no triangle.
Expected<TaggedMeshSet> parseTaggedMeshObj(const QByteArray& text, const QString& fileName);
/// Reads a file and parses it as above; an unreadable file is an error naming the file.
Expected<TaggedMeshSet> readTaggedMeshObjFile(const QString& path);

} // namespace kw
