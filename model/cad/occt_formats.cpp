// The formats a binary reads through OCCT's data exchange, chosen when it is built: compiled
// into each OCCT module (and the in-process reader the tests link) with KW_OCCT_IGES and/or
// KW_OCCT_STEP, so that an IGES read does not map the STEP toolkits and the other way round.
#include "model/cad/occt_internal.h"

namespace kw::occt {

const ExchangeFormat* exchangeFormat(CadFormat format) {
#ifdef KW_OCCT_IGES
    if (format == CadFormat::Iges)
        return &igesFormat();
#endif
#ifdef KW_OCCT_STEP
    if (format == CadFormat::Step)
        return &stepFormat();
#endif
    Q_UNUSED(format);
    return nullptr;
}

} // namespace kw::occt
