// Options and loading shared by 'knotwork render' and 'knotwork bench'.
#pragma once

#include "model/document/document.h"
#include "render/render_types.h"

#include <QCommandLineOption>
#include <QSize>
#include <QString>

class QCommandLineParser;

namespace kw::cli {

/// A section plane "X,Y,Z,NX,NY,NZ" (a point of it and the normal of the side it removes).
/// An Error (what it should be) when malformed or the normal has zero length.
Expected<SectionPlane> parseSectionPlane(const QString& text);
/// "WxH" with both in 1..16384; false when malformed.
bool parseImageSize(const QString& text, QSize& size);
/// "N" or "NxM" with values in [kMinPartitions, kMaxPartitions]; false when malformed.
bool parsePartitions(const QString& text, int& nu, int& nv);
/// An integer in [lo, hi]; false otherwise.
bool parseIntIn(const QString& text, int lo, int hi, int& value);
QString modeName(RenderMode mode);
/// "prepass" or "exact-depth": the --depth names of RenderOptions::Shading (how exact mode
/// resolves visibility; the analysis colouring is --shading).
QString shadingName(RenderOptions::Shading shading);

/// --mode, --partitions, --partition-mode, --pixel-tolerance, --lights, --depth, --no-trims,
/// --trim-mask-cap, --trim-mode, --trim-budget, --samples, --aa-method, --background,
/// --section (repeatable), --no-caps, --no-analytic and the analysis options
/// (--shading MODE, --isocurves, --iso-lines, --range, --scale, --stripes, --stripe-angle,
/// --isophote-bands, --pull, --draft-angle, --env-map).
struct RenderCliOptions {
    QCommandLineOption mode, partitions, partitionMode, pixelTolerance, lights, depth, noTrims,
        trimMaskCap, trimMode, trimBudget, samples, aaMethod, background;
    QCommandLineOption shading, isocurves, isoLines, range, scale, stripes, stripeAngle,
        isophoteBands, pull, draftAngle, envMap, directions;
    QCommandLineOption section{QStringLiteral("section")}, noCaps{QStringLiteral("no-caps")};
    QCommandLineOption noAnalytic{QStringLiteral("no-analytic")};
};
/// Adds the shared options to `parser`. `defaultPartitions` empty: none (each surface's own).
/// `defaultPartitioning`: "adaptive" (render) or "uniform" (bench: the paper's tables).
RenderCliOptions addRenderOptions(QCommandLineParser& parser, const QString& defaultPartitions,
                                  const QString& defaultPartitioning);
QString partitioningName(RenderOptions::Partitioning p);
/// Image pixels per trim grid texel, at most, for a surface as large as the whole image.
constexpr int kImagePixelsPerTrimTexel = 8;
/// The trim grid cap (RenderOptions::trimGridCap) for one image of `size` magnified `zoom`
/// times: the smallest power of two at least the longer side times `zoom` over
/// kImagePixelsPerTrimTexel, in [kMinTrimGridSize, kMaxTrimGridSide]. One frame pays once for
/// building the grids (texels) and once for the pixels' tests (curve pieces per texel); the
/// editor's many frames pay for the tests again each time, a render does not. A surface of a
/// fitted view spans at most the image, so its texels stay within 8 x 8 pixels. Measured on
/// hammer.iges (docs/PERFORMANCE.md ## Start-up): the grids were most of a 64 x 64 first
/// image's CPU time; with this cap every image tried (64 x 64 to 1024 x 768, the samples,
/// hammer.iges, Axis_of_bearing.brep) came out bit-identical. Not for --samples > 1: anti-aliased
/// trim edges read the texels about each pixel, and 0.1 % of hammer's pixels changed.
int trimGridCapForImage(QSize size, double zoom);
/// Reads them into `options`. On a malformed value prints "<cmd>: --option 'value' is ..."
/// on stderr and returns false (the caller exits with kExitUsage).
bool readRenderOptions(const QCommandLineParser& parser, const RenderCliOptions& o,
                       const QString& cmd, RenderOptions& options);
/// The development switches (readRenderOptions reads them too): environment variables that
/// turn one part of the exact pass off or move a threshold, for measuring (docs/RENDERING.md,
/// "The contract between C++ and the shaders"); each sets a RenderOptions field, and render/
/// reads no environment.
/// KW_TRIM_CELL_SPLIT=0, KW_BACK_FACES=1, KW_AFFINE=0, KW_MULTI_DRAW=0, KW_DEFERRED=0,
/// KW_EDGE_SKIRTS=0, KW_FINS=0, KW_POLYGONS_IN_VIEW=0, KW_GATHER_MIN_CELL_PX=N,
/// KW_DEFER_MAX_CELL_PX=N. A threshold
/// that is not a number >= 0 prints "<cmd>: NAME 'value' is ..." and returns false.
bool readDevelopmentSwitches(const QString& cmd, RenderOptions& options);

} // namespace kw::cli
