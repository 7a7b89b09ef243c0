// The hybrid trim grids of every trimmed surface packed into one word array (the texture buffer
// shaders/trim_exact.glsl reads), each surface in a block sized by its own need, under a memory
// budget. No GL here: TrimMaskPass uploads the words.
#pragma once

#include "render/trim_grid.h"

#include <QStringList>
#include <cstdint>
#include <map>
#include <vector>

namespace kw {

/// Where one surface's grid lies in the word array. Offsets are in 32-bit words from the
/// block's start. Layout (matches shaders/trim_exact.glsl):
///   header: 4 words, the offsets of entries, pieces, arcs and points in the block;
///   texels: width * height + 1 words from word 4, texel k = first entry << 2 | near bit << 1 |
///           base bit (the next word's first entry ends the list; near: an edge texel is among
///           the 3 x 3 about it);
///   entries: piece << 2 | left bit << 1 | right bit (render/trim_grid.h);
///   pieces: 8 words each from a multiple of 4: p0.x p0.y p1.x p1.y t0 t1 (floats), arc, 0;
///   arcs: 2 words each: first control point (index into points), degree;
///   points: 4 words each from a multiple of 4: w u, w v, w (floats), 0.
/// A block's size is a multiple of 4 words, so blocks placed in a TrimWordArena start on one
/// too, and the shader reads a piece's half or a point as one RGBA32UI texel.
struct TrimGridBlock {
    std::uint32_t offset = 0, words = 0; ///< words == 0: no block
    int cap = 0; ///< the resolution cap it was built under (budget degradation); 0: not built
};

/// Packs a grid and its arcs into block words (layout above). Floats are stored by their bits.
std::vector<std::uint32_t> packTrimGrid(const TrimGrid& grid, const TrimArcs& arcs);

/// First-fit allocation of word ranges in an array that grows by a quarter (at least what the
/// range needs, in steps of 1024 words). Freed ranges are merged with free neighbours.
class TrimWordArena {
public:
    /// What allocate() returns when 2^32 - 1 words cannot hold the range.
    static constexpr std::uint32_t kNoRoom = 0xFFFFFFFFu;
    /// Offset of a new range of `words` words; grows the capacity when no free range fits.
    std::uint32_t allocate(std::uint32_t words);
    void release(std::uint32_t offset, std::uint32_t words);
    std::uint32_t capacity() const { return m_capacity; }
    std::uint32_t used() const { return m_used; }
    /// Drops everything and sets the capacity to exactly `words` (compaction).
    void reset(std::uint32_t words);

private:
    void addFree(std::uint32_t offset, std::uint32_t words); ///< merged with free neighbours
    std::map<std::uint32_t, std::uint32_t> m_free;           ///< offset -> words
    std::uint32_t m_capacity = 0, m_used = 0;
};

/// The word array and its allocation. Blocks belong to their surfaces' records (TrimMask::grid):
/// the owner of the records places, releases and, when asked, moves them (compact).
class TrimGridStore {
public:
    /// Copies `data` into a new range for `block` (its old range, if any, is released first).
    /// Sets *grew when the array grew: every block's words must then go up again. False (and
    /// no block) when the array cannot address that many words.
    bool place(TrimGridBlock& block, const std::vector<std::uint32_t>& data, bool* grew);
    void release(TrimGridBlock& block);
    /// Moves `blocks` (every live block) to the front of an array of exactly their size.
    void compact(const std::vector<TrimGridBlock*>& blocks);
    /// Whether compact() is due under `budgetBytes`: the array (grown in steps) exceeds the
    /// budget while the blocks fit, or is over four times their size.
    bool wantsCompaction(std::int64_t budgetBytes) const;

    const std::vector<std::uint32_t>& words() const { return m_words; }
    /// Bytes of the word array (its capacity) and of the blocks in it.
    std::int64_t capacityBytes() const { return 4 * std::int64_t(m_arena.capacity()); }
    std::int64_t usedBytes() const { return 4 * std::int64_t(m_arena.used()); }
    /// Drops the word array (no block may be live).
    void clear();

private:
    std::vector<std::uint32_t> m_words;
    TrimWordArena m_arena;
};

} // namespace kw
