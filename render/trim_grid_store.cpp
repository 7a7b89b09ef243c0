// Trim grid blocks: packing for the shader, first-fit word allocation, budget degradation.
#include "render/trim_grid_store.h"

#include <algorithm>
#include <bit>

namespace kw {
namespace {

std::uint32_t floatBits(double x) {
    return std::bit_cast<std::uint32_t>(float(x));
}

} // namespace

std::vector<std::uint32_t> packTrimGrid(const TrimGrid& grid, const TrimArcs& arcs) {
    std::vector<std::uint32_t> w(4, 0u); // the header, filled below
    const size_t texels = size_t(grid.texelCount());
    w.reserve(4 + texels + 1 + grid.entries.size() + 8 * grid.pieces.size() + 2 * arcs.arcs.size());
    // The near bit: an edge texel in the 3 x 3 texels about this one. The anti-aliased edge
    // pass skips a texel without it at once when the pixel's footprint is at most a texel.
    const auto nearEdge = [&](int i, int j) {
        for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
                const int x = i + di, y = j + dj;
                if (x >= 0 && y >= 0 && x < grid.width && y < grid.height &&
                    grid.isEdge(y * grid.width + x))
                    return true;
            }
        return false;
    };
    for (size_t k = 0; k <= texels; ++k) {
        const bool near = k < texels && nearEdge(int(k) % grid.width, int(k) / grid.width);
        w.push_back(grid.first[k] << 2 | std::uint32_t(near) << 1 |
                    (k < texels ? grid.base[k] : 0u));
    }
    w[0] = std::uint32_t(w.size());
    w.insert(w.end(), grid.entries.begin(), grid.entries.end());
    // Pieces and points start on 4 words, which the shader reads 4 at a time (kwTrimQuad).
    const auto align = [&w] {
        w.resize((w.size() + 3) & ~size_t(3), 0u);
    };
    align();
    w[1] = std::uint32_t(w.size());
    for (const TrimPiece& p : grid.pieces)
        w.insert(w.end(), {floatBits(p.p0.x), floatBits(p.p0.y), floatBits(p.p1.x),
                           floatBits(p.p1.y), floatBits(p.t0), floatBits(p.t1), p.arc, 0u});
    w[2] = std::uint32_t(w.size());
    std::uint32_t point = 0;
    for (const TrimArc& a : arcs.arcs) {
        w.insert(w.end(), {point, std::uint32_t(a.degree)});
        point += std::uint32_t(a.hw.size());
    }
    align();
    w[3] = std::uint32_t(w.size());
    for (const TrimArc& a : arcs.arcs)
        for (const glm::dvec3& h : a.hw)
            w.insert(w.end(), {floatBits(h.x), floatBits(h.y), floatBits(h.z), 0u});
    return w;
}

std::uint32_t TrimWordArena::allocate(std::uint32_t words) {
    words = std::max<std::uint32_t>(words, 1);
    for (auto it = m_free.begin(); it != m_free.end(); ++it) {
        if (it->second < words)
            continue;
        const std::uint32_t offset = it->first, left = it->second - words;
        m_free.erase(it);
        if (left)
            m_free[offset + words] = left;
        m_used += words;
        return offset;
    }
    // Grow by a quarter (at least to fit, in steps of 1024 words), the new space free after the
    // old end. The GPU buffer is the whole array, so the growth step is memory the GPU holds
    // unused: doubling left Motor-c's 8.04 MiB of grids in a 16 MiB buffer. A quarter keeps
    // that under 25 % and still grows an array built block by block in logarithmically many
    // steps (each one a whole upload). The steps keep every range on a multiple of 4 words
    // (TrimGridStore::place). Offsets are the shader's 32-bit words, so the array stops at
    // 2^32 - 1 words (16 GiB; the budget stays far below, kMaxTrimBudgetBytes).
    const std::uint64_t old = m_capacity;
    std::uint64_t cap = old + std::max<std::uint64_t>({words, old / 4, 1024});
    cap = std::min<std::uint64_t>((cap + 1023) / 1024 * 1024, kNoRoom);
    if (cap - old < words)
        return kNoRoom;
    m_capacity = std::uint32_t(cap);
    addFree(std::uint32_t(old), std::uint32_t(cap - old));
    return allocate(words);
}

void TrimWordArena::release(std::uint32_t offset, std::uint32_t words) {
    words = std::max<std::uint32_t>(words, 1);
    m_used -= std::min(m_used, words);
    addFree(offset, words);
}

void TrimWordArena::addFree(std::uint32_t offset, std::uint32_t words) {
    auto next = m_free.lower_bound(offset);
    if (next != m_free.end() && next->first == offset + words) {
        words += next->second;
        next = m_free.erase(next);
    }
    if (next != m_free.begin()) {
        auto prev = std::prev(next);
        if (prev->first + prev->second == offset) {
            prev->second += words;
            return;
        }
    }
    m_free[offset] = words;
}

void TrimWordArena::reset(std::uint32_t words) {
    m_free.clear();
    m_used = 0;
    m_capacity = words;
    if (words)
        m_free[0] = words;
}

bool TrimGridStore::place(TrimGridBlock& block, const std::vector<std::uint32_t>& data,
                          bool* grew) {
    release(block);
    // Whole quads (packTrimGrid's blocks are already): every range the arena hands out then
    // starts on a multiple of 4 words, where the shader's RGBA32UI view of the array reads.
    const std::uint32_t words =
        std::max<std::uint32_t>((std::uint32_t(data.size()) + 3u) & ~3u, 4u);
    const std::uint32_t before = m_arena.capacity();
    const std::uint32_t offset = m_arena.allocate(words);
    if (offset == TrimWordArena::kNoRoom)
        return false;
    block.offset = offset;
    block.words = words;
    if (m_arena.capacity() != before) {
        *grew = true;
        m_words.resize(m_arena.capacity(), 0u);
    }
    std::copy(data.begin(), data.end(), m_words.begin() + block.offset);
    return true;
}

void TrimGridStore::release(TrimGridBlock& block) {
    if (block.words)
        m_arena.release(block.offset, block.words);
    block.offset = block.words = 0;
}

void TrimGridStore::compact(const std::vector<TrimGridBlock*>& blocks) {
    std::uint32_t total = 0;
    for (const TrimGridBlock* b : blocks)
        total += b->words;
    std::vector<std::uint32_t> old = std::move(m_words);
    m_arena.reset(total);
    m_words.assign(total, 0u);
    for (TrimGridBlock* b : blocks) {
        const std::uint32_t from = b->offset;
        b->offset = m_arena.allocate(b->words);
        std::copy(old.begin() + from, old.begin() + from + b->words, m_words.begin() + b->offset);
    }
}

bool TrimGridStore::wantsCompaction(std::int64_t budgetBytes) const {
    const std::int64_t used = usedBytes(), capacity = capacityBytes();
    return (capacity > budgetBytes && used <= budgetBytes) ||
           (capacity > 4 * used && capacity > 16384);
}

void TrimGridStore::clear() {
    m_arena.reset(0);
    m_words.clear();
    m_words.shrink_to_fit();
}

} // namespace kw
