// libFuzzer harness: what the CAD reader's child runs on a STEP file before OpenCASCADE (the
// header sniff, the list-length guard, the number range check) and the message helpers.
#include "fuzz_cad.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
    kw::fuzz::checkCadPrecheck(kw::CadFormat::Step, data, size);
    return 0;
}
