// libFuzzer harness: the .knot reader (sceneFromJson) on arbitrary bytes. It must refuse with
// one line naming the file, or accept a scene that the document takes and that Save and OBJ
// export write back to an equal scene.
#include "fuzz_roundtrip.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
    const QByteArray bytes(reinterpret_cast<const char*>(data), qsizetype(size));
    const QString source = QStringLiteral("fuzz.knot");
    QString error;
    const auto scene = kw::sceneFromJson(bytes, source);
    if (scene)
        kw::fuzz::checkAcceptedScene(*scene);
    else
        kw::fuzz::checkRefusal(scene.message(), source);
    return 0;
}
