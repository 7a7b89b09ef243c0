// Per-pixel arbitrary output variables read back from a frame; plain data, no GL.
#pragma once

#include <cstddef>
#include <vector>

namespace kw {

/// Per-pixel arbitrary output variables, row 0 at the top. Channels per pixel (kChannels):
/// surface id (-1 background; the SurfaceId value otherwise), u, v, P.x, P.y, P.z, N.x, N.y,
/// N.z (unit, Su x Sv side), Z (eye-space depth along the view direction, model units).
struct AovBuffer {
    static constexpr int kChannels = 10;
    static const char* const kChannelNames[kChannels]; ///< id,u,v,P.x,P.y,P.z,N.x,N.y,N.z,Z
    int width = 0;
    int height = 0;
    std::vector<float> data;
    /// With the curvature AOV (RenderTarget::curvatureAov): kCurvatureChannels floats per pixel
    /// K, H, k1, k2 (kw::surfaceCurvature's signs), then d1.x, d1.y, d1.z: the unit world
    /// principal direction of k1 (any tangent direction at umbilics; sign arbitrary; the
    /// direction of k2 is N x d1); all 0 on background. Else empty.
    static constexpr int kCurvatureChannels = 7;
    static const char* const kCurvatureNames[kCurvatureChannels]; ///< K,H,k1,k2,d1.x,d1.y,d1.z
    std::vector<float> curvature;

    const float* pixel(int x, int y) const {
        return data.data() + (size_t(y) * size_t(width) + size_t(x)) * kChannels;
    }
    /// Nullptr without the curvature AOV.
    const float* curvaturePixel(int x, int y) const {
        return curvature.empty() ? nullptr
                                 : curvature.data() +
                                       (size_t(y) * size_t(width) + size_t(x)) * kCurvatureChannels;
    }
};

} // namespace kw
