// The table of length units: keys, names, sizes and IGES flags in one place.
#include "model/document/units.h"

namespace kw {
namespace {

struct UnitRow {
    LengthUnit unit;
    const char* key;
    const char* name;
    double millimetres;
    int igesFlag;
};

constexpr UnitRow kRows[] = {
    {LengthUnit::Millimetre, "mm", "millimetre", 1.0, 2},
    {LengthUnit::Centimetre, "cm", "centimetre", 10.0, 10},
    {LengthUnit::Metre, "m", "metre", 1000.0, 6},
    {LengthUnit::Kilometre, "km", "kilometre", 1e6, 7},
    {LengthUnit::Micrometre, "um", "micrometre", 1e-3, 9},
    {LengthUnit::Inch, "in", "inch", 25.4, 1},
    {LengthUnit::Foot, "ft", "foot", 304.8, 4},
    {LengthUnit::Mile, "mi", "mile", 1609344.0, 5},
    {LengthUnit::Mil, "mil", "mil", 0.0254, 8},
    {LengthUnit::Microinch, "uin", "microinch", 25.4e-6, 11},
};

const UnitRow& row(LengthUnit unit) {
    for (const UnitRow& r : kRows)
        if (r.unit == unit)
            return r;
    return kRows[0];
}

} // namespace

QString lengthUnitKey(LengthUnit unit) {
    return QString::fromLatin1(row(unit).key);
}

std::optional<LengthUnit> lengthUnitFromKey(const QString& key) {
    for (const UnitRow& r : kRows)
        if (key.compare(QLatin1String(r.key), Qt::CaseInsensitive) == 0)
            return r.unit;
    return std::nullopt;
}

QString lengthUnitName(LengthUnit unit) {
    return QStringLiteral("%1 (%2)").arg(QLatin1String(row(unit).name), lengthUnitKey(unit));
}

double millimetresPer(LengthUnit unit) {
    return row(unit).millimetres;
}

int igesUnitFlag(LengthUnit unit) {
    return row(unit).igesFlag;
}

std::optional<LengthUnit> lengthUnitFromIgesFlag(int flag) {
    for (const UnitRow& r : kRows)
        if (r.igesFlag == flag)
            return r.unit;
    return std::nullopt;
}

} // namespace kw
