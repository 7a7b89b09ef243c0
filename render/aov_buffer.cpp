// AOV channel names, in the order of AovBuffer's channels.
#include "render/aov_buffer.h"

namespace kw {

const char* const AovBuffer::kChannelNames[AovBuffer::kChannels] = {
    "id", "u", "v", "P.x", "P.y", "P.z", "N.x", "N.y", "N.z", "Z"};
const char* const AovBuffer::kCurvatureNames[AovBuffer::kCurvatureChannels] = {
    "K", "H", "k1", "k2", "d1.x", "d1.y", "d1.z"};

} // namespace kw
