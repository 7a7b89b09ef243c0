// Options and loading shared by 'knotwork render' and 'knotwork bench'.
#pragma once

#include "model/document.h"
#include "render/render_types.h"

#include <QCommandLineOption>
#include <QSize>
#include <QString>

class QCommandLineParser;

namespace kw::cli {

/// "WxH" with both in 1..16384; false when malformed.
bool parseImageSize(const QString& text, QSize& size);
/// "N" or "NxM" with values in [kMinPartitions, kMaxPartitions]; false when malformed.
bool parsePartitions(const QString& text, int& nu, int& nv);
/// An integer in [lo, hi]; false otherwise.
bool parseIntIn(const QString& text, int lo, int hi, int& value);
QString modeName(RenderMode mode);
QString shadingName(RenderOptions::Shading shading);

/// --mode, --partitions, --lights, --shading, --no-trims and --trim-mask-cap.
struct RenderCliOptions {
    QCommandLineOption mode, partitions, lights, shading, noTrims, trimMaskCap;
};
/// Adds the shared options to `parser`. `defaultPartitions` empty: none (each surface's own).
RenderCliOptions addRenderOptions(QCommandLineParser& parser, const QString& defaultPartitions);
/// Reads them into `options`. On a malformed value prints "<cmd>: --option 'value' is ..."
/// on stderr and returns false (the caller exits with kExitUsage).
bool readRenderOptions(const QCommandLineParser& parser, const RenderCliOptions& o,
                       const QString& cmd, RenderOptions& options);

/// Reads `file` into `doc`. On failure prints the error naming the file and returns false
/// (the caller exits with kExitBadInput).
bool loadDocument(const QString& file, Document& doc);

} // namespace kw::cli
