// The checks a CAD file passes before OpenCASCADE sees it: plain byte scans, no OCCT, so they
// run in milliseconds per megabyte and can be fuzzed in process (tests/fuzz/fuzz_step.cpp,
// fuzz_iges.cpp).
#pragma once

#include "model/cad/cadimport.h"
#include "model/error.h"

#include <QByteArrayView>
#include <QString>

namespace kw {

/// Most items one STEP list may hold, however they are separated (commas, spaces, line
/// breaks): OCCT's STEP parser takes quadratic time in the length of one list
/// (StepFile_ReadData::CreateNewArg: 16k items 2.8 s, 32k 9.8 s, 400k never finish).
constexpr long long kMaxStepListItems = 50'000;

/// Largest magnitude of a number a CAD file may hold: beyond it (and for NaN or infinity)
/// OCCT's algorithms run for a minute or more on a small file (a 1.0D308 coordinate in an IGES
/// file, a -inf pole in a BREP file), and no real model needs it.
constexpr double kMaxCadMagnitude = 1e100;

/// ok() when `head` (a file's first bytes, inputcheck.h kSniffBytes) can start a file of
/// `format` (IGES: the first record is 80 columns with 'S' in column 73; STEP: it starts with
/// "ISO-10303-21;"; BREP: "DBRep_DrawableShape" or "CASCADE Topology"). Otherwise an Error,
/// with a short safe quote of what is there. Other formats: always ok().
Status checkCadHead(CadFormat format, QByteArrayView head);

/// The whole file's scan for `format`, on its bytes. ok() when OpenCASCADE may read it;
/// otherwise an Error "line N: reason". Refused:
/// - STEP: a list with more than kMaxStepListItems items; a number in the DATA section that is
///   not finite or larger in magnitude than kMaxCadMagnitude.
/// - IGES: such a number in the parameter data section (strings, Hollerith "nH...", skipped).
/// - BREP: such a number anywhere (including "inf" and "nan").
/// Also the head check above. Runs in time linear in the size and allocates nothing that grows
/// with it.
Status checkCadContent(CadFormat format, QByteArrayView bytes);

/// checkCadContent on the file at `path`, mapped into memory rather than read (nothing grows
/// with its size), after inputcheck.h's checkRegularFile. ok() when it passes.
Status checkCadFile(const QString& path, CadFormat format);

} // namespace kw
