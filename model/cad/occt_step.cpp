// STEP through OCCT's data exchange (TKSTEP, TKSTEPBase): the reader and the names of STEP
// representation items.
#include "model/cad/occt_internal.h"

#include <STEPControl_Reader.hxx>
#include <StepBasic_Product.hxx>
#include <StepBasic_ProductDefinition.hxx>
#include <StepBasic_ProductDefinitionFormation.hxx>
#include <StepRepr_RepresentationItem.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
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

QString stepProductName(const Handle(Standard_Transient) & entity) {
    const auto definition = Handle(StepBasic_ProductDefinition)::DownCast(entity);
    if (definition.IsNull() || definition->Formation().IsNull())
        return {};
    const Handle(StepBasic_Product) product = definition->Formation()->OfProduct();
    if (product.IsNull())
        return {};
    const auto text = [](const Handle(TCollection_HAsciiString) & s) {
        return s.IsNull() ? QString() : QString::fromUtf8(s->ToCString()).trimmed();
    };
    QString name = text(product->Name());
    if (name.isEmpty())
        name = text(product->Id());
    // OCCT's writer names a product it was given no name for "Open CASCADE STEP translator
    // <version> <n>": not a name anybody chose.
    if (name.startsWith(QLatin1String("Open CASCADE STEP translator")))
        return {};
    return name;
}

// The first length unit of the file's contexts, by the name OCCT gives it ("MM", "INCH", ...).
std::optional<LengthUnit> stepFileUnit(XSControl_Reader& reader) {
    auto* step = dynamic_cast<STEPControl_Reader*>(&reader);
    if (!step)
        return std::nullopt;
    TColStd_SequenceOfAsciiString lengths, angles, solidAngles;
    step->FileUnits(lengths, angles, solidAngles);
    if (lengths.IsEmpty())
        return std::nullopt;
    const QString name = QString::fromLatin1(lengths.First().ToCString()).trimmed().toUpper();
    static const std::pair<const char*, LengthUnit> names[] = {
        {"MM", LengthUnit::Millimetre},
        {"MILLIMETRE", LengthUnit::Millimetre},
        {"CM", LengthUnit::Centimetre},
        {"CENTIMETRE", LengthUnit::Centimetre},
        {"M", LengthUnit::Metre},
        {"METRE", LengthUnit::Metre},
        {"KM", LengthUnit::Kilometre},
        {"KILOMETRE", LengthUnit::Kilometre},
        {"UM", LengthUnit::Micrometre},
        {"MICROMETRE", LengthUnit::Micrometre},
        {"INCH", LengthUnit::Inch},
        {"IN", LengthUnit::Inch},
        {"FT", LengthUnit::Foot},
        {"FOOT", LengthUnit::Foot},
        {"MI", LengthUnit::Mile},
        {"MILE", LengthUnit::Mile},
        {"MIL", LengthUnit::Mil},
        {"UIN", LengthUnit::Microinch},
        {"MICROINCH", LengthUnit::Microinch}};
    for (const auto& [n, unit] : names)
        if (name == QLatin1String(n))
            return unit;
    return std::nullopt;
}

} // namespace

const ExchangeFormat& stepFormat() {
    static const ExchangeFormat format{
        [] { return std::unique_ptr<XSControl_Reader>(std::make_unique<STEPControl_Reader>()); },
        stepEntityName, stepFileUnit, stepProductName};
    return format;
}

} // namespace kw::occt
