// IGES files whose sequence numbers or parameter back-pointers disagree with their directory.
#pragma once

#include <QByteArray>
#include <QByteArrayView>
#include <QString>
#include <optional>

namespace kw {

/// Some writers (e.g. the teapot.igs of gpucast) number every directory entry "1, 2" and point
/// every parameter line back to entry 1; OpenCASCADE then glues all parameters onto the first
/// entity. When the directory's own parameter pointers are consistent (increasing, starting at
/// 1, inside the P section), this rebuilds the sequence numbers, back-pointers, parameter line
/// counts and the Terminate record from them. Returns the repaired file, or nullopt when the
/// file is already consistent or cannot be repaired this way (it is then read as it is).
/// `note` describes the repair, for the import report.
/// It first asks igesNumberingNeedsRepair, so a consistent file costs one pass and no copy.
std::optional<QByteArray> repairIgesNumbering(const QByteArray& file, QString& note);

/// True when repairIgesNumbering would return a repaired file: the same checks on views of
/// the lines, building nothing (for hammer.iges, 1 MB, the full rebuild took ~5 ms of the CAD
/// child's ~80 ms only to find nothing to repair).
bool igesNumberingNeedsRepair(QByteArrayView file);

/// repairIgesNumbering without that first check: always rebuilds, then compares (the tests
/// check that both give the same answer).
std::optional<QByteArray> rebuildIgesNumbering(const QByteArray& file, QString& note);

} // namespace kw
