// libFuzzer harness: what the CAD reader's child runs on an IGES file before OpenCASCADE (the
// first-record sniff, the parameter-data number range check with Hollerith strings skipped)
// and the message helpers.
#include "fuzz_cad.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
    kw::fuzz::checkCadPrecheck(kw::CadFormat::Iges, data, size);
    return 0;
}
