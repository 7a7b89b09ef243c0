// STEP through OCCT's data exchange (TKSTEP, TKSTEPBase): the reader and the names of STEP
// representation items.
#include "model/cad/occt_internal.h"

#include <STEPControl_Reader.hxx>
#include <StepRepr_RepresentationItem.hxx>
#include <TCollection_HAsciiString.hxx>

namespace kw::occt {
namespace {

QString stepEntityName(const Handle(Standard_Transient) & entity, int* igesType) {
    *igesType = 0;
    const auto step = Handle(StepRepr_RepresentationItem)::DownCast(entity);
    if (step.IsNull() || step->Name().IsNull())
        return {};
    return QString::fromUtf8(step->Name()->ToCString()).trimmed();
}

} // namespace

const ExchangeFormat& stepFormat() {
    static const ExchangeFormat format{
        [] { return std::unique_ptr<XSControl_Reader>(std::make_unique<STEPControl_Reader>()); },
        stepEntityName};
    return format;
}

} // namespace kw::occt
