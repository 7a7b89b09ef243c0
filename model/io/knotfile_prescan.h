// A one-pass check of a .knot file's sizes over its raw bytes, before the JSON is parsed:
// Qt's JSON tree takes many times the file's size, so absurd counts are refused first.
#pragma once

#include "model/error.h"

#include <QByteArray>

namespace kw {

/// Most numbers one .knot file may hold (about 10 million control points in all); with the
/// per-surface limits of model/document/validation.h this bounds the memory a file can make the
/// reader take (docs/FILE_FORMAT.md, ## Limits).
constexpr long long kMaxKnotNumbers = 40'000'000;

/// Scans the JSON text once, keeping only a stack of open containers, and reports the first
/// of: an array longer than any limit allows (kMaxControlPoints elements); a surface object
/// whose countU x countV is above kMaxControlPoints; more than kMaxSurfaces surfaces; more than
/// kMaxKnotNumbers numbers in the file; nesting deeper than 64. Malformed JSON is not judged
/// here (the parser reports it with its position): the scan stops and returns ok(). The error's
/// message is the reason as the reader words it; its location the JSON path of the offending
/// member, e.g. "$.surfaces[0].countV" (the caller knows the file).
Status prescanKnotJson(const QByteArray& json);

} // namespace kw
