// IGES through OCCT's data exchange (TKIGES): the reader and the names of IGES entities.
#include "model/cad/occt_internal.h"

#include <IGESControl_Reader.hxx>
#include <IGESData_BasicEditor.hxx>
#include <IGESData_GlobalSection.hxx>
#include <IGESData_IGESEntity.hxx>
#include <IGESData_IGESModel.hxx>
#include <TCollection_HAsciiString.hxx>

namespace kw::occt {
namespace {

QString igesEntityName(const Handle(Standard_Transient) & entity, int* igesType) {
    *igesType = 0;
    const auto iges = Handle(IGESData_IGESEntity)::DownCast(entity);
    if (iges.IsNull())
        return {};
    *igesType = iges->TypeNumber();
    if (iges->HasName()) {
        QString name = QString::fromUtf8(iges->NameValue()->ToCString()).trimmed();
        // OCCT appends the subscript as "label(n)", also when the file's subscript is 0.
        if (iges->HasSubScriptNumber() && iges->SubScriptNumber() == 0 &&
            name.endsWith(QLatin1String("(0)")))
            name.chop(3);
        return name;
    }
    if (iges->HasShortLabel())
        return QString::fromUtf8(iges->ShortLabel()->ToCString()).trimmed();
    return {};
}

// The global section's unit flag, or for flag 3 its unit name.
std::optional<LengthUnit> igesFileUnit(XSControl_Reader& reader) {
    const auto model = Handle(IGESData_IGESModel)::DownCast(reader.Model());
    if (model.IsNull())
        return std::nullopt;
    const IGESData_GlobalSection& g = model->GlobalSection();
    int flag = g.UnitFlag();
    if (flag == 3 && !g.UnitName().IsNull())
        flag = IGESData_BasicEditor::UnitNameFlag(g.UnitName()->ToCString());
    return lengthUnitFromIgesFlag(flag);
}

} // namespace

const ExchangeFormat& igesFormat() {
    static const ExchangeFormat format{
        [] { return std::unique_ptr<XSControl_Reader>(std::make_unique<IGESControl_Reader>()); },
        igesEntityName, igesFileUnit, nullptr};
    return format;
}

} // namespace kw::occt
