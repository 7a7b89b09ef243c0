// Length units of a document: which unit its coordinates are in, and how values are shown.
#pragma once

#include <QString>
#include <optional>

namespace kw {

/// The length units CAD exchange knows (STEP's SI and conversion-based units, IGES's global
/// unit flag). A document's coordinates are numbers in its unit; nothing is scaled on import.
enum class LengthUnit {
    Millimetre, ///< the default: created documents, OBJ, BREP and old .knot files
    Centimetre,
    Metre,
    Kilometre,
    Micrometre,
    Inch,
    Foot,
    Mile,
    Mil, ///< a thousandth of an inch
    Microinch,
};

/// The key stored in files and shown after values: "mm", "cm", "m", "km", "um", "in", "ft",
/// "mi", "mil", "uin".
QString lengthUnitKey(LengthUnit unit);
/// The unit for a key (lengthUnitKey's), case-insensitive; nullopt for anything else.
std::optional<LengthUnit> lengthUnitFromKey(const QString& key);
/// A name for menus: "millimetre (mm)".
QString lengthUnitName(LengthUnit unit);
/// Millimetres in one `unit` (exact where the unit is defined so: 25.4 for the inch).
double millimetresPer(LengthUnit unit);
/// IGES's global unit flag for `unit` (1 inch, 2 mm, 4 ft, 5 mi, 6 m, 7 km, 8 mil, 9 um,
/// 10 cm, 11 uin), which is also OpenCASCADE's unit code (UnitsMethods).
int igesUnitFlag(LengthUnit unit);
/// The unit of IGES's global unit flag; nullopt for 3 (named in the file) and unknown flags.
std::optional<LengthUnit> lengthUnitFromIgesFlag(int flag);
/// Every unit, in menu order.
constexpr LengthUnit kLengthUnits[] = {
    LengthUnit::Millimetre, LengthUnit::Centimetre, LengthUnit::Metre, LengthUnit::Kilometre,
    LengthUnit::Micrometre, LengthUnit::Inch,       LengthUnit::Foot,  LengthUnit::Mile,
    LengthUnit::Mil,        LengthUnit::Microinch};

} // namespace kw
