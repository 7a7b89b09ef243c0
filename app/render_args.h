// Parsing of the render options shared by 'knotwork render' and 'knotwork bench'.
#pragma once

#include "render/render_types.h"

#include <QSize>
#include <QString>

namespace kw::cli {

/// "WxH" with both in 1..16384; false when malformed.
bool parseImageSize(const QString& text, QSize& size);
/// "N" or "NxM" with values in [kMinPartitions, kMaxPartitions]; false when malformed.
bool parsePartitions(const QString& text, int& nu, int& nv);
/// "exact" or "tessellated"; false otherwise.
bool parseMode(const QString& text, RenderMode& mode);
/// An integer in [lo, hi]; false otherwise.
bool parseIntIn(const QString& text, int lo, int hi, int& value);
QString modeName(RenderMode mode);
/// "prepass" or "exact-depth"; false otherwise.
bool parseShading(const QString& text, RenderOptions::Shading& shading);
QString shadingName(RenderOptions::Shading shading);

} // namespace kw::cli
