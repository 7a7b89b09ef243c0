// Shared GPU buffers for the per-surface data of the whole scene: every
// surface's control points, span tables, base polygon vertices and indices live at an offset in
// one buffer per kind, so the exact pass binds them once and draws many surfaces per call.
#pragma once

#include <QOpenGLFunctions_4_5_Core>
#include <cstdint>
#include <map>

namespace kw {

/// First-fit allocator of element ranges in [0, end()) with coalescing free ranges (no GL, so
/// it is testable alone). Ranges are in elements; freeing the last range lowers end().
class RangeAllocator {
public:
    /// Offset of `count` free elements (count > 0): the first free range that fits, or the end.
    std::int64_t allocate(std::int64_t count);
    /// Returns [offset, offset + count) to the free ranges (must have come from allocate).
    void free(std::int64_t offset, std::int64_t count);
    /// One past the highest allocated element.
    std::int64_t end() const { return m_end; }
    /// Elements in live ranges.
    std::int64_t used() const { return m_used; }
    void clear() { m_free.clear(), m_end = 0, m_used = 0; }

private:
    std::map<std::int64_t, std::int64_t> m_free; ///< offset -> count, below m_end
    std::int64_t m_end = 0;
    std::int64_t m_used = 0;
};

/// One GL buffer holding elements of `elementBytes` each, sub-allocated by a RangeAllocator.
/// It grows by doubling (the old contents copied on the GPU, waited for: see allocate) and is
/// deleted when its last range is freed, so an empty scene holds no pool memory. Growth replaces
/// the buffer name: users re-bind buffer() after every allocate (GpuScene does, once per sync).
class GpuPool {
public:
    void initialize(QOpenGLFunctions_4_5_Core* gl, std::int64_t elementBytes,
                    std::int64_t maxBytes) {
        m_gl = gl, m_elementBytes = elementBytes, m_maxBytes = maxBytes;
    }
    /// Offset (in elements) of `count` elements, or -1 when the buffer would exceed maxBytes.
    std::int64_t allocate(std::int64_t count);
    void free(std::int64_t offset, std::int64_t count);
    /// Writes `count` elements at `offset` (glNamedBufferSubData).
    void write(std::int64_t offset, std::int64_t count, const void* data);
    GLuint buffer() const { return m_buffer; }
    /// Bytes of the GL buffer (capacity, not only the live ranges).
    std::int64_t residentBytes() const { return m_capacity * m_elementBytes; }
    std::int64_t usedElements() const { return m_ranges.used(); }
    std::int64_t maxBytes() const { return m_maxBytes; }
    /// Frees the GL buffer and every range.
    void release();

private:
    QOpenGLFunctions_4_5_Core* m_gl = nullptr;
    std::int64_t m_elementBytes = 1;
    std::int64_t m_maxBytes = 0;
    std::int64_t m_capacity = 0; ///< elements
    GLuint m_buffer = 0;
    RangeAllocator m_ranges;
};

} // namespace kw
