// Trims on the GPU, in one of two modes (RenderOptions::TrimMode):
//  - exact: each trimmed surface's hybrid trim grid (render/trim_grid.h) in a block of
//    one texture buffer, sized by the surface's own need under a memory budget; the surface
//    passes classify each fragment's exact (u, v) against it (shaders/trim_exact.glsl);
//  - mask (paper 3.4.2): each trimmed surface's loops drawn in (u, v) into one layer of a
//    GL_TEXTURE_2D_ARRAY by triangle fans with XOR parity; the surface passes sample it.
#pragma once

#include "model/document/document.h"
#include "render/exact_contract.h"
#include "render/render_types.h"
#include "render/shader_library.h"
#include "render/trim_grid_store.h"

#include <QOpenGLFunctions_4_5_Core>
#include <QString>
#include <QStringList>
#include <glm/glm.hpp>
#include <map>
#include <vector>

class QOpenGLShaderProgram;

namespace kw {

struct SurfaceRecord;
struct TrimSurfaceArcs;

/// One surface's trims on the GPU. Mask mode: texels [0, width) x [0, height) of layer `layer`
/// span `rect` in (u, v), the part of the domain inside the bounding box of the trim curves'
/// control points (the curves lie in it: convex hull property). Outside it no point is inside
/// any loop, so the shader discards there without a lookup, and the texels go where the trims
/// are. Exact mode: `grid` is the surface's block of the trim grid buffer, whose width x height
/// texels span `rect` (the arcs' bounds), and layer is -1.
struct TrimMask {
    int layer = -1;
    int width = 0, height = 0;
    glm::dvec4 rect{0.0, 1.0, 0.0, 1.0}; ///< (u first, u last, v first, v last)
    std::uint64_t trimsRevision = 0;     ///< the trims the mask shows
    std::uint64_t knotsRevision = 0;     ///< the domain it was drawn for
    /// False when every loop was dropped (degenerate): the surface is drawn untrimmed, as
    /// trimRegionContains treats a region without loops.
    bool active = false;
    QStringList warnings; ///< from makeTrimRegion (makeTrimArcs) when last drawn (built)
    TrimMaskStats stats;  ///< since creation or resetStats()
    TrimGridBlock grid;   ///< exact mode: the block (grid.words == 0: none)
    /// Exact mode: the grid's texels (width x height over rect, as TrimGrid) as 0 outside,
    /// 1 inside, 2 edge (a curve crosses it), for splitByTrims; empty otherwise.
    std::vector<std::uint8_t> texelClass;
    std::uint64_t classSerial = 0; ///< changes whenever texelClass is rebuilt or dropped

    /// Whether the passes classify by it: a mask layer or a grid block holding a loop.
    bool usable() const { return active && (layer >= 0 || grid.words > 0); }
};

class TrimMaskPass {
public:
    /// Needs the context current for every call below; `shaders` outlives the pass.
    void initialize(QOpenGLFunctions_4_5_Core* gl, ShaderLibrary* shaders);

    /// Brings the trims of the records' surfaces up to date for this frame in options.trimMode
    /// and frees what records no longer trimmed (and the other mode) held. Exact mode: see
    /// syncExact. Mask mode: frees the
    /// layers of records no longer trimmed. A surface's mask is redrawn only when its trims (or
    /// knots, which move the domain) revision changed or its mask resolution changed; the
    /// resolution is four times the surface's control-net length on screen (pixels) along u and
    /// along v, times the share of the domain the mask rectangle spans, rounded up to a power
    /// of two, within [kMinTrimMaskSize, options.trimMaskCap]. Leaves GL_FRAMEBUFFER bound to
    /// 0 and the logic op and scissor test disabled. Returns the error when the
    /// shaders do not build or the masks do not fit the GPU's array limits (those surfaces draw
    /// untrimmed).
    Status sync(const Document& doc, const std::vector<SurfaceRecord*>& records,
                const FrameCamera& camera, const RenderOptions& options);
    /// Gives the mask's layer or grid block back (a removed, hidden or untrimmed surface);
    /// keeps its statistics.
    void freeLayer(TrimMask& mask);

    /// Whether the last sync was in exact mode: the trimmed shader variants then need the
    /// KW_TRIM_EXACT define (trimDefines()).
    bool exact() const { return m_exactMode; }
    /// The trim features of the trimmed shader variants for the mode of the last sync, and
    /// their defines.
    ExactFeatures trimFeatures() const;
    QStringList trimDefines() const;

    /// Binds the trim data of the last sync's mode: the grid buffer to kTrimGridUnit, or the
    /// mask array to `unit` with uTrimMask and uTrimLayerScale set on the bound program. The
    /// program's shaders read each surface's rectangle, size and layer or block from its row of
    /// the surface table (shaders/surface_data.glsl).
    void bindArray(QOpenGLShaderProgram* program, int unit) const;

    /// bindArray, then trim_sample.glsl's per-surface uniforms on the bound program.
    void setUniforms(QOpenGLShaderProgram* program, const TrimMask& mask, int unit) const;

    /// The mask array (0 before the first trimmed surface) and its layer size in texels.
    GLuint texture() const { return m_texture; }
    int layerSize() const { return m_size; }
    int layerCount() const { return m_layers; }
    /// Mask arrays allocated since the last resetArrayAllocations().
    std::int64_t arrayAllocations() const { return m_arrayAllocations; }
    void resetArrayAllocations() { m_arrayAllocations = 0; }
    /// What the last sync did (for FrameReport).
    const TrimMaskStats& frameStats() const { return m_frame; }
    /// Bytes of the mask array and of the trim grid buffer.
    std::int64_t residentBytes() const;
    /// Exact mode: bytes of the grid blocks in use (the buffer holds them with packing slack),
    /// and the warning while the budget coarsened the grids (else empty).
    std::int64_t gridBytesUsed() const { return m_grids.usedBytes(); }
    const QString& budgetWarning() const { return m_budgetWarning; }
    int drawCalls = 0; ///< mask draws of the last sync
    /// The mask texels read back (width x height, row 0 at v first; 0 trimmed, 255 kept), for
    /// tests. Empty for an inactive mask.
    std::vector<unsigned char> readMask(const TrimMask& mask) const;

    /// Frees every GL object; the context must be current.
    void release();

    /// The mask resolution for `surface` seen by `camera` (see sync), capped at `cap`.
    static glm::ivec2 maskResolution(const Surface& surface, const FrameCamera& camera, int cap);
    /// The rectangle a surface's mask spans (TrimMask::rect): the trim control points' bounding
    /// box clipped to the domain, or the whole domain when that leaves no area.
    static glm::dvec4 maskRect(const Surface& surface);

private:
    /// Exact mode: every trimmed record's grid built (only when its trims or knots changed, or
    /// the budget's cap moved past its size) and placed in the word array, which goes up whole
    /// when it grew or was compacted, else block by block. Past the budget (options'
    /// trimBudgetBytes, at most what one texture buffer holds) the cap on the grids' sides is
    /// halved for the largest until they fit: classification stays exact, more fragments walk
    /// lists; the warning says so. Errors leave the trimmed surfaces untrimmed this frame.
    /// Records wholly outside `camera`'s view (ExactPlanner::outsideView, with
    /// options.cullOutsideView) hold no grid: dropGrid.
    Status syncExact(const std::vector<SurfaceRecord*>& records, const FrameCamera& camera,
                     const RenderOptions& options);
    /// Gives a grid block back, keeping the mask's warnings and statistics.
    void dropGrid(TrimMask& m);
    void buildGrid(TrimMask& m, const Surface& s, const Revisions& rev, bool* grew);
    void buildGrid(TrimMask& m, const TrimSurfaceArcs& arcs, const Revisions& rev, bool* grew);
    void freeArray();
    void freeGrids();
    Status ensureArray(int size, int layers);
    void redraw(TrimMask& m, const Surface& s, glm::ivec2 resolution);

    QOpenGLFunctions_4_5_Core* m_gl = nullptr;
    ShaderLibrary* m_shaders = nullptr;
    GLuint m_texture = 0, m_fbo = 0, m_vao = 0, m_buffer = 0;
    int m_size = 0, m_layers = 0; ///< allocated array size
    std::vector<int> m_freeLayers;
    std::int64_t m_arrayAllocations = 0;
    TrimMaskStats m_frame;
    // Exact mode (trim_mask_pass_exact.cpp).
    bool m_exactMode = false; ///< the mode of the last sync
    TrimGridStore m_grids;
    GLuint m_gridBuffer = 0, m_gridView = 0; ///< the words and their R32UI texture buffer
    GLuint m_gridQuads = 0;                  ///< the same words as an RGBA32UI texture buffer
    std::int64_t m_gridBufferBytes = 0;
    int m_gridCap = kMaxTrimGridSide; ///< the side cap the budget allows now
    std::int64_t m_gridBudget = 0;    ///< the budget the cap was found under
    int m_gridOptionCap = 0;          ///< RenderOptions::trimGridCap the cap was found under
    QString m_budgetWarning;
};

} // namespace kw
