// The checks every harness applies to a scene Knotwork accepted: the document takes it, and
// what Save (.knot) and convert (OBJ) write from it reads back to the same scene.
#pragma once

#include "fuzz_util.h"
#include "model/document/document.h"
#include "model/io/knotfile.h"
#include "model/io/objfile.h"

namespace kw::fuzz {

/// Where two scenes differ first, for the failure message.
inline QString firstDifference(const Scene& a, const Scene& b) {
    if (a.surfaces.size() != b.surfaces.size())
        return QStringLiteral("surface count %1 vs %2")
            .arg(a.surfaces.size())
            .arg(b.surfaces.size());
    for (size_t i = 0; i < a.surfaces.size(); ++i) {
        const Surface &x = a.surfaces[i], &y = b.surfaces[i];
        const QString at = QStringLiteral("surface %1: ").arg(i);
        if (x.id != y.id || x.name != y.name)
            return at + QStringLiteral("id or name '%1' vs '%2'").arg(x.name, y.name);
        if (x.geometry != y.geometry)
            return at + QStringLiteral("geometry");
        if (x.trims != y.trims)
            return at + QStringLiteral("trims");
        if (x.partitionsU != y.partitionsU || x.partitionsV != y.partitionsV)
            return at + QStringLiteral("partitions");
        if (x.material != y.material)
            return at + QStringLiteral("material");
    }
    if (a.lights != b.lights)
        return QStringLiteral("lights");
    if (a.camera != b.camera)
        return QStringLiteral("camera (authored %1 vs %2)")
            .arg(a.camera.authored)
            .arg(b.camera.authored);
    if (a.nextId != b.nextId)
        return QStringLiteral("nextId %1 vs %2").arg(a.nextId).arg(b.nextId);
    return QStringLiteral("nothing");
}

/// The scene as files keep it: a camera the user never set (authored false) is not saved,
/// since views fit their own to the scene; its values mean nothing.
inline Scene asSaved(Scene scene) {
    if (!scene.camera.authored)
        scene.camera = Camera{};
    return scene;
}

/// Aborts unless `scene` is valid for the document and survives .knot and OBJ round trips.
inline void checkAcceptedScene(const Scene& given) {
    const Scene scene = asSaved(given);
    const QString why = Document::validate(given).message();
    KW_FUZZ_CHECK(why.isEmpty(), why);
    Document doc;
    const Status reset = doc.resetScene(given);
    KW_FUZZ_CHECK(bool(reset), reset.message());

    const QByteArray json = sceneToJson(scene);
    const auto back = sceneFromJson(json, QStringLiteral("roundtrip.knot"));
    // One validation (model/document/validation.h): every scene Knotwork accepts is written so that
    // it reopens; no refusal of a written file is tolerated.
    KW_FUZZ_CHECK(back.has_value(),
                  QStringLiteral("the .knot written does not reopen: ") + back.message());
    KW_FUZZ_CHECK(*back == scene,
                  QStringLiteral("the .knot written reopens as a different scene: ") +
                      firstDifference(scene, *back));

    // OBJ has no notion of an empty scene: a file without surfaces is refused on import.
    if (scene.surfaces.empty())
        return;
    const QByteArray obj = writeObj(scene);
    Scene fromObj;
    ImportReport report;
    const Status parsed = parseObj(obj, QStringLiteral("roundtrip.obj"), fromObj, report);
    KW_FUZZ_CHECK(bool(parsed), QStringLiteral("the OBJ written does not reopen: ") + parsed.message());
    KW_FUZZ_CHECK(fromObj == scene,
                  QStringLiteral("the OBJ written reopens as a different scene: ") +
                      firstDifference(scene, fromObj));
}

/// A refusal is one line that names the source.
inline void checkRefusal(const QString& error, const QString& source) {
    KW_FUZZ_CHECK(error.startsWith(source + QLatin1Char(':')), error);
    KW_FUZZ_CHECK(!error.contains(QLatin1Char('\n')), error);
}

} // namespace kw::fuzz
