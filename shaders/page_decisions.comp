#version 460
// Virtual pages decided on the device (src/render/page_decision_passes.h; docs/techniques.md,
// "Pages decided on the device"): the passes of decidePages (src/core/page_decisions.h), one
// pipeline each (SPEC_PAGE_PASS), run in order with a barrier between them. An invocation's work
// reads the others' only through a prefix sum or a flag any of them may set, so what they decide
// does not depend on the order the device runs them in.
#include "page_passes.h"

layout(constant_id = SPEC_PAGE_PASS) const uint PASS = PAGES_PASS_FREE;
layout(local_size_x = PAGES_BLOCK) in;

layout(set = 0, binding = PAGES_LEVELS, std430) readonly buffer Levels { PageLevelData levels[]; };
layout(set = 0, binding = PAGES_REQUESTS, std430) readonly buffer Requests { uint requests[]; };
layout(set = 0, binding = PAGES_OWNERS, std430) buffer Owners { PageOwnerData owners[]; };
layout(set = 0, binding = PAGES_MOVED, std430) readonly buffer Moved { PageRectData moved[]; };
layout(set = 0, binding = PAGES_REKEYED, std430) readonly buffer Rekeyed { uint rekeyed[]; };
layout(set = 0, binding = PAGES_WANTED, std430) buffer Wanted { uint wanted[]; };
layout(set = 0, binding = PAGES_MISSING, std430) buffer Missing { uint missing[]; };
layout(set = 0, binding = PAGES_SUMS, std430) buffer Sums { uint sums[]; };
layout(set = 0, binding = PAGES_RANKED, std430) buffer Ranked { uint ranked[]; };
layout(set = 0, binding = PAGES_CANDIDATES, std430) buffer Candidates { uint candidates[]; };
layout(set = 0, binding = PAGES_RENDER, std430) writeonly buffer Render { PageRenderData render[]; };
layout(set = 0, binding = PAGES_TABLE, std430) writeonly buffer Table { uint table[]; };
layout(set = 0, binding = PAGES_COUNTS, std430) buffer Counts { PageCounts counts; };
layout(push_constant) uniform Push { PagePush push; };

shared uint scanned[PAGES_BLOCK];
shared uvec2 tile[PAGES_BLOCK];
shared uint carry;
shared uint stillCounting[2];

// The level record named `name` (a frame has tens of levels: a short search).
uint levelNamed(uint name) {
    for (uint i = 0u; i < push.levelCount; ++i)
        if (levels[i].name == name) return i;
    return PAGES_NONE;
}

// The level whose table holds entry `entry`: their tables follow one another, so a binary search
// on where each starts (a frame has about a hundred levels; every entry asks).
uint levelHolding(uint entry) {
    uint lo = 0u, hi = push.levelCount; // the level is in [lo, hi)
    while (hi - lo > 1u) {
        uint mid = (lo + hi) / 2u;
        if (levels[mid].tableOffset <= entry) lo = mid;
        else hi = mid;
    }
    return lo;
}

// The entry of absolute page `page` in level i's window, or PAGES_NONE outside it.
uint entryOf(uint i, ivec2 page) {
    ivec2 local = page - levels[i].firstPage;
    int n = int(levels[i].pagesPerSide);
    if (any(lessThan(local, ivec2(0))) || any(greaterThanEqual(local, ivec2(n))))
        return PAGES_NONE;
    return levels[i].tableOffset + uint(local.y) * levels[i].pagesPerSide + uint(local.x);
}

// Where a resident page's entry is in this frame's table, or PAGES_NONE.
uint ownerEntry(uint p) {
    if (owners[p].level == PAGES_FREE) return PAGES_NONE;
    uint i = levelNamed(owners[p].level);
    return i == PAGES_NONE ? PAGES_NONE : entryOf(i, owners[p].page);
}

bool underMoved(uint i, ivec2 page) {
    for (uint r = levels[i].movedFirst; r < levels[i].movedFirst + levels[i].movedCount; ++r)
        if (all(greaterThanEqual(page, moved[r].lo)) && all(lessThanEqual(page, moved[r].hi)))
            return true;
    return false;
}

void freePage(uint p) {
    uint name = owners[p].level;
    if (name == PAGES_FREE) return;
    uint light = name >> 16u;
    bool drop = light / 32u < push.rekeyedWords && (rekeyed[light / 32u] & (1u << (light % 32u))) != 0u;
    if (!drop && push.anyMoved != 0u) {
        uint i = levelNamed(name);
        drop = i == PAGES_NONE || underMoved(i, owners[p].page);
    }
    if (drop) owners[p].level = PAGES_FREE;
}

void want(uint e) {
    if (requests[e] == 0u) return;
    atomicOr(wanted[e], 1u);
    uint child = levelHolding(e);
    uint local = e - levels[child].tableOffset;
    uint n = levels[child].pagesPerSide;
    ivec2 page = levels[child].firstPage + ivec2(int(local % n), int(local / n));
    // At most one step a level (a bound, not a rule: the chain ends at the coarsest).
    for (uint up = 0u; up < push.levelCount; ++up) {
        uint parent = levels[child].parent;
        if (parent == PAGES_NONE) break;
        // A clipmap's grids share their origin: page p's parent is p / 2 (rounded down); a fixed
        // window's pages count from its corner, which its mips share.
        ivec2 from = levels[parent].followsCamera != 0u ? page : page - levels[child].firstPage;
        page = from >> 1;
        uint up_entry = entryOf(parent, page);
        if (up_entry == PAGES_NONE) break;
        atomicOr(wanted[up_entry], 1u);
        child = parent;
    }
}

void hold(uint p) {
    uint e = ownerEntry(p);
    if (e == PAGES_NONE || (wanted[e] & 1u) == 0u) return;
    atomicOr(wanted[e], 2u);
    owners[p].lastUsed = push.frame;
    atomicAdd(counts.cached, 1u);
}

void markMissing(uint e) {
    uint i = levelHolding(e);
    uint w = wanted[e];
    if ((w & 1u) != 0u) atomicAdd(counts.requested, 1u);
    missing[levels[i].priorityStart + e - levels[i].tableOffset] = w == 1u ? e + 1u : 0u;
}

// Shared memory is written by the invocations that come later in a workgroup and read by the
// earlier ones wherever that can be arranged: a device that runs a workgroup's invocations in
// order up to each barrier (llvmpipe runs them eight at a time) then reads stale values wherever
// a barrier is missing, and the tests see it.

// The workgroup's inclusive prefix of `value`, every invocation taking part: suffix sums (Hillis
// and Steele), each step reading a later invocation's sum, then the total less the suffix.
uint inclusivePrefix(uint value) {
    uint id = gl_LocalInvocationID.x;
    scanned[id] = value;
    barrier();
    for (uint step = 1u; step < PAGES_BLOCK; step <<= 1u) {
        uint add = id + step < PAGES_BLOCK ? scanned[id + step] : 0u;
        barrier();
        scanned[id] += add;
        barrier();
    }
    return scanned[0] - scanned[id] + value;
}

uint missingFlag(uint slot) {
    return slot < push.entries && missing[slot] != 0u ? 1u : 0u;
}

// The block's missing slots as PAGES_BLOCK bits: a slot's rank in its block is the count of bits
// before its own (two barriers, where a scan of the block's flags takes fourteen). The last
// invocations clear the words; every count reads the words of later ones.
shared uint blockBits[PAGES_BLOCK / 32u];

void gatherBlockBits(uint flag) {
    uint id = gl_LocalInvocationID.x;
    uint firstClearing = PAGES_BLOCK - PAGES_BLOCK / 32u;
    if (id >= firstClearing) blockBits[id - firstClearing] = 0u;
    barrier();
    if (flag != 0u) atomicOr(blockBits[id / 32u], 1u << (id % 32u));
    barrier();
}

// Set bits at slot `id` of the block and after it.
uint bitsFrom(uint id) {
    uint count = bitCount(blockBits[id / 32u] & ~((1u << (id % 32u)) - 1u));
    for (uint w = id / 32u + 1u; w < PAGES_BLOCK / 32u; ++w) count += bitCount(blockBits[w]);
    return count;
}

void scanSums() {
    // One workgroup walks the block sums a block at a time, carrying the total (kept by the last
    // invocation at first, then by the first: see above).
    if (gl_LocalInvocationID.x == PAGES_BLOCK - 1u) carry = 0u;
    barrier();
    for (uint first = 0u; first < push.scanBlocks; first += PAGES_BLOCK) {
        uint b = first + gl_LocalInvocationID.x;
        uint value = b < push.scanBlocks ? sums[b] : 0u;
        uint inclusive = inclusivePrefix(value);
        uint before = carry;
        if (b < push.scanBlocks) sums[b] = before + inclusive - value;
        barrier();
        if (gl_LocalInvocationID.x == 0u) carry = before + scanned[0]; // the turn's total
        barrier();
    }
    if (gl_LocalInvocationID.x == 0u) counts.missing = carry;
}

void rank(uint slot) {
    uint flag = missingFlag(slot);
    gatherBlockBits(flag);
    if (flag != 0u)
        ranked[sums[gl_WorkGroupID.x] + bitsFrom(0u) - bitsFrom(gl_LocalInvocationID.x)] =
            missing[slot] - 1u;
}

// A candidate's order: free pages first, then the least recently used, then by index.
bool before(uvec2 a, uint ia, uvec2 b, uint ib) {
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    return ia < ib;
}

void rankCandidate(uint p) {
    // Nothing missing (a still view): no candidate is taken. The same for every invocation, so
    // none is left at a barrier.
    uint wanted = counts.missing;
    if (wanted == 0u) return;
    // Every invocation loads the pool a tile at a time; a candidate counts those before it, up
    // to the missing pages' count (a rank past it takes nothing).
    bool inPool = p < push.pages;
    uvec2 mine = uvec2(0u);
    bool candidate = false;
    if (inPool) {
        mine = uvec2(owners[p].level == PAGES_FREE ? 0u : 1u, owners[p].lastUsed);
        candidate = mine.x == 0u || mine.y < push.frame;
    }
    uint rankOf = 0u;
    // Whether an invocation of the workgroup still counts, by the tile's parity: each is reset a
    // tile before it is set, between two barriers that no read of it crosses. When none counts,
    // the workgroup reads no more tiles.
    if (gl_LocalInvocationID.x == PAGES_BLOCK - 1u) stillCounting[0] = 0u;
    barrier();
    uint turn = 0u;
    for (uint first = 0u; first < push.pages; first += PAGES_BLOCK, turn ^= 1u) {
        uint q = first + gl_LocalInvocationID.x;
        uvec2 key = uvec2(2u, 0u); // past the pool: no candidate
        if (q < push.pages) {
            key = uvec2(owners[q].level == PAGES_FREE ? 0u : 1u, owners[q].lastUsed);
            if (key.x == 1u && key.y >= push.frame) key.x = 2u;
        }
        tile[gl_LocalInvocationID.x] = key;
        if (gl_LocalInvocationID.x == 0u) atomicAdd(counts.tilesRead, 1u);
        barrier();
        if (gl_LocalInvocationID.x == PAGES_BLOCK - 1u) stillCounting[turn ^ 1u] = 0u;
        if (candidate && rankOf < wanted) {
            for (uint k = 0u; k < PAGES_BLOCK; ++k)
                if (tile[k].x < 2u && before(tile[k], first + k, mine, p)) ++rankOf;
            if (rankOf < wanted) stillCounting[turn] = 1u;
        }
        barrier();
        if (stillCounting[turn] == 0u) break;
    }
    if (candidate) {
        if (rankOf < wanted) candidates[rankOf] = p;
        atomicAdd(counts.candidates, 1u);
    }
}

void assign(uint r) {
    uint taken = min(counts.missing, counts.candidates);
    if (r == 0u) {
        counts.rendered = taken;
        counts.dropped = counts.missing - taken;
    }
    if (r >= taken) return;
    uint p = candidates[r];
    uint e = ranked[r];
    uint i = levelHolding(e);
    uint local = e - levels[i].tableOffset;
    uint n = levels[i].pagesPerSide;
    if (owners[p].level != PAGES_FREE) atomicAdd(counts.evicted, 1u);
    owners[p].page = levels[i].firstPage + ivec2(int(local % n), int(local / n));
    owners[p].level = levels[i].name;
    owners[p].lastUsed = push.frame;
    render[r] = PageRenderData(p, e);
}

void main() {
    uint id = gl_GlobalInvocationID.x;
    if (PASS == PAGES_PASS_SCAN_BLOCKS) {
        gatherBlockBits(missingFlag(id));
        if (gl_LocalInvocationID.x == 0u) sums[gl_WorkGroupID.x] = bitsFrom(0u);
    } else if (PASS == PAGES_PASS_SCAN_SUMS) {
        scanSums();
    } else if (PASS == PAGES_PASS_RANK) {
        rank(id);
    } else if (PASS == PAGES_PASS_CANDIDATES) {
        rankCandidate(id);
    } else if (PASS == PAGES_PASS_FREE || PASS == PAGES_PASS_HOLD || PASS == PAGES_PASS_TABLE ||
               PASS == PAGES_PASS_ASSIGN) {
        if (id >= push.pages) return;
        if (PASS == PAGES_PASS_FREE) freePage(id);
        if (PASS == PAGES_PASS_HOLD) hold(id);
        if (PASS == PAGES_PASS_ASSIGN) assign(id);
        if (PASS == PAGES_PASS_TABLE) {
            if (owners[id].level != PAGES_FREE) atomicAdd(counts.resident, 1u);
            uint e = ownerEntry(id);
            if (e != PAGES_NONE) table[e] = id + 1u;
        }
    } else {
        if (id >= push.entries) return;
        if (PASS == PAGES_PASS_WANT) want(id);
        if (PASS == PAGES_PASS_MISSING) markMissing(id);
    }
}
