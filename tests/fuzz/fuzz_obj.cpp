// libFuzzer harness: the free-form OBJ reader (parseObj) on arbitrary bytes. It must refuse
// with "<file>:<line>: reason" and leave the scene untouched, or accept a scene that the
// document takes and that Save and OBJ export write back to an equal scene.
#include "fuzz_roundtrip.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
    const QByteArray bytes(reinterpret_cast<const char*>(data), qsizetype(size));
    const QString source = QStringLiteral("fuzz.obj");
    kw::Scene scene;
    scene.nextId = 77; // a marker: a refused file must leave the scene as it was
    const kw::Scene untouched = scene;
    kw::ImportReport report;
    if (const kw::Status parsed = kw::parseObj(bytes, source, scene, report)) {
        kw::fuzz::checkAcceptedScene(scene);
    } else {
        kw::fuzz::checkRefusal(parsed.message(), source);
        KW_FUZZ_CHECK(scene == untouched, "a refused OBJ changed the scene");
    }
    return 0;
}
