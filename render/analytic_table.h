// The analytic forms on the GPU: one row per surface-table slot, read by the exact pass's
// KW_ANALYTIC programs (shaders/analytic.glsl) to intersect the pixel's ray in closed form.
#pragma once

#include "model/nurbs/analytic.h"
#include "render/exact_contract.h"

#include <QOpenGLFunctions_4_5_Core>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace kw {

struct Surface;
struct SurfaceRecord;

/// One surface's analytic row (kAnalyticTexels RGBA32F texels, analytic.glsl reads them by
/// name). Positions are relative to the surface's control-texel origin (SurfaceGpu::origin), as
/// the control texels are, so the shader works with the same small numbers as for the NURBS.
/// kind 0 (a row of no form) is never read: the planner draws such a surface the NURBS way.
struct AnalyticEntry {
    glm::vec4 origin{0.0f}; ///< xyz: the frame's origin - the control origin; w: kind (1..5)
    glm::vec4 xAxis{0.0f};  ///< xyz: X; w: radius (R)
    glm::vec4 yAxis{0.0f};  ///< xyz: Y; w: minor radius (r)
    glm::vec4 zAxis{0.0f};  ///< xyz: Z; w: sin(semi-angle)
    /// The NURBS u's map: kind (0 linear, 1 half angle), offset, scale; w: 1 when swapped (u
    /// gives b, v gives a)
    glm::vec4 mapU{0.0f};
    glm::vec4 mapV{0.0f}; ///< the NURBS v's map likewise; w: cos(semi-angle)
    bool operator==(const AnalyticEntry&) const = default;
};
static_assert(sizeof(AnalyticEntry) == kAnalyticTexels * sizeof(glm::vec4),
              "must match exact_contract.h's kAnalyticTexels, which analytic.glsl reads");

/// Whether the exact pass can draw `form` in closed form: a kind other than None, finite
/// values, a frame of unit and mutually orthogonal axes (to 1e-9), positive radii where the
/// kind has them (the torus's minor one too), a cone's semi-angle within (-pi/2, pi/2) and
/// maps of non-zero finite scale. A surface whose form fails this is drawn the NURBS way.
bool analyticUsable(const AnalyticForm& form);

/// The row of `form` for a surface whose control texels are relative to `controlOrigin`.
AnalyticEntry packAnalytic(const AnalyticForm& form, const glm::dvec3& controlOrigin);

/// The analytic rows of a GpuScene's surface-table slots, in their own texture buffer (bound to
/// kAnalyticUnit). Rows are written only when they changed; a surface whose form an edit
/// dropped keeps a stale row that no program reads (the planner looks at the document's form).
class AnalyticTable {
public:
    /// Updates the rows of `records` (those with exact data and a slot) and grows the buffer to
    /// `slots` rows; only the changed range is written. The context must be current.
    void sync(QOpenGLFunctions_4_5_Core* gl, const std::vector<SurfaceRecord*>& records, int slots);
    /// Binds the rows to kAnalyticUnit (nothing while no surface has a form).
    void bind(QOpenGLFunctions_4_5_Core* gl) const;
    /// Frees the buffer and its view.
    void release(QOpenGLFunctions_4_5_Core* gl);
    std::int64_t bytes() const { return std::int64_t(m_capacity) * sizeof(AnalyticEntry); }

private:
    std::vector<AnalyticEntry> m_rows;
    int m_capacity = 0;
    GLuint m_buffer = 0, m_view = 0;
};

} // namespace kw
