// Range allocation in the shared scene buffers.
#include "render/gpu_pool.h"

#include <algorithm>

namespace kw {

std::int64_t RangeAllocator::allocate(std::int64_t count) {
    for (auto it = m_free.begin(); it != m_free.end(); ++it) {
        if (it->second < count)
            continue;
        const std::int64_t offset = it->first, left = it->second - count;
        m_free.erase(it);
        if (left > 0)
            m_free.emplace(offset + count, left);
        m_used += count;
        return offset;
    }
    const std::int64_t offset = m_end;
    m_end += count;
    m_used += count;
    return offset;
}

void RangeAllocator::free(std::int64_t offset, std::int64_t count) {
    if (count <= 0)
        return;
    m_used -= count;
    // Merge with the free neighbours on both sides.
    auto next = m_free.lower_bound(offset);
    if (next != m_free.end() && next->first == offset + count) {
        count += next->second;
        next = m_free.erase(next);
    }
    if (next != m_free.begin()) {
        auto prev = std::prev(next);
        if (prev->first + prev->second == offset) {
            offset = prev->first;
            count += prev->second;
            m_free.erase(prev);
        }
    }
    if (offset + count == m_end)
        m_end = offset; // the top range: the end moves down instead
    else
        m_free.emplace(offset, count);
}

std::int64_t GpuPool::allocate(std::int64_t count) {
    if (count <= 0)
        return 0;
    const std::int64_t offset = m_ranges.allocate(count);
    const std::int64_t need = m_ranges.end();
    if (need > m_capacity) {
        std::int64_t capacity = std::max<std::int64_t>(m_capacity * 2, 1024);
        while (capacity < need)
            capacity *= 2;
        const std::int64_t limit = m_maxBytes / m_elementBytes;
        capacity = std::min(capacity, limit);
        if (capacity < need) {
            m_ranges.free(offset, count);
            return -1;
        }
        GLuint grown = 0;
        m_gl->glCreateBuffers(1, &grown);
        m_gl->glNamedBufferData(grown, GLsizeiptr(capacity * m_elementBytes), nullptr,
                                GL_DYNAMIC_DRAW);
        if (m_buffer) {
            m_gl->glCopyNamedBufferSubData(m_buffer, grown, 0, 0,
                                           GLsizeiptr(m_capacity * m_elementBytes));
            // The copy must have run before the old buffer goes and before the next
            // glNamedBufferSubData into the new one. GL orders them, but NVIDIA 580.159 (H100,
            // GLX) did not: ranges copied here read as zeros in the draws (vertices at the
            // origin, stray triangles on every CAD part; docs/PERFORMANCE.md "On a GPU").
            // A pool grows only when it doubles, so the wait is rare.
            m_gl->glFinish();
            m_gl->glDeleteBuffers(1, &m_buffer);
        }
        m_buffer = grown;
        m_capacity = capacity;
    }
    return offset;
}

void GpuPool::free(std::int64_t offset, std::int64_t count) {
    if (offset < 0 || count <= 0) // never allocated (a failed allocation leaves -1)
        return;
    m_ranges.free(offset, count);
    if (m_ranges.used() == 0)
        release();
}

void GpuPool::write(std::int64_t offset, std::int64_t count, const void* data) {
    if (count > 0)
        m_gl->glNamedBufferSubData(m_buffer, GLintptr(offset * m_elementBytes),
                                   GLsizeiptr(count * m_elementBytes), data);
}

void GpuPool::release() {
    if (m_buffer && m_gl)
        m_gl->glDeleteBuffers(1, &m_buffer);
    m_buffer = 0;
    m_capacity = 0;
    m_ranges.clear();
}

} // namespace kw
