#include "core/page_decisions.h"

#include "virtual_pages.h" // shaders/include: VIRTUAL_NOT_RESIDENT

#include <algorithm>
#include <numeric>
#include <optional>

namespace penumbra {
namespace {

// The record of this frame's level an owner names (a short search: a frame has tens of levels).
std::optional<size_t> levelNamed(const std::vector<VirtualLevel>& levels, uint32_t packed) {
    for (size_t i = 0; i < levels.size(); ++i)
        if (packLevel(levels[i].light, levels[i].face, levels[i].level) == packed)
            return i;
    return std::nullopt;
}

// The level above `child` (its light's and face's next coarser), if the frame has it.
const VirtualLevel* parentOf(const std::vector<VirtualLevel>& levels, const VirtualLevel& child) {
    const std::optional<size_t> i =
        levelNamed(levels, packLevel(child.light, child.face, child.level + 1));
    return i ? &levels[*i] : nullptr;
}

} // namespace

std::vector<size_t> missingPageOrder(const std::vector<VirtualLevel>& levels) {
    std::vector<size_t> order(levels.size());
    std::iota(order.begin(), order.end(), size_t{0});
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        const VirtualLevel &x = levels[a], &y = levels[b];
        if (x.level != y.level)
            return x.level > y.level;
        return std::tie(x.light, x.face) < std::tie(y.light, y.face);
    });
    return order;
}

PageDecisions decidePages(std::vector<PageOwner>& owners, const PageDecisionInputs& in) {
    const std::vector<VirtualLevel>& levels = *in.levels;
    const size_t entries = in.requests.size();
    PageDecisions d;

    // Pass 1, per physical page: free it when its light's contents changed, or when anything
    // moved and it lies under a moved caster's pages or in a level this frame lacks.
    for (PageOwner& owner : owners) {
        if (owner.level == PageOwner::kFree)
            continue;
        bool drop = std::find(in.lightsRekeyed.begin(), in.lightsRekeyed.end(),
                              owner.level >> 16) != in.lightsRekeyed.end();
        if (!drop && !in.moved.empty()) {
            const std::optional<size_t> i = levelNamed(levels, owner.level);
            drop = !i || std::any_of(in.moved[*i].begin(), in.moved[*i].end(),
                                     [&](const PageRect& r) { return r.holds(owner.page); });
        }
        if (drop)
            owner.level = PageOwner::kFree;
    }

    // Pass 2, per entry: the pages asked for, and for each its chain of coarser pages up to the
    // first its level's parent window lacks (a flag any entry may set).
    std::vector<uint8_t> wanted(entries, 0);
    for (const VirtualLevel& level : levels)
        for (uint32_t local = 0; local < level.tableEntries(); ++local) {
            if (in.requests[level.tableOffset + local] == 0u)
                continue;
            wanted[level.tableOffset + local] = 1;
            const VirtualLevel* child = &level;
            glm::ivec2 page = level.firstPage + glm::ivec2(int(local % level.pagesPerSide),
                                                           int(local / level.pagesPerSide));
            // At most one step a level (a bound, not a rule: the chain ends at the coarsest).
            for (size_t up = 0; up < levels.size(); ++up) {
                const VirtualLevel* parent = parentOf(levels, *child);
                if (!parent)
                    break;
                // A clipmap's grids share their origin: page p's parent is p / 2; a fixed
                // window's pages count from its corner, which its mips share.
                const glm::ivec2 from = parent->followsCamera ? page : page - child->firstPage;
                page = glm::ivec2(from.x >> 1, from.y >> 1);
                const std::optional<uint32_t> e = entryOf(*parent, page);
                if (!e)
                    break;
                wanted[*e] = 1;
                child = parent;
            }
        }
    d.requested = static_cast<uint32_t>(std::count(wanted.begin(), wanted.end(), uint8_t{1}));

    // Pass 3, per physical page: a resident page asked for again stays, used this frame.
    std::vector<uint8_t> held(entries, 0);
    for (PageOwner& owner : owners) {
        if (owner.level == PageOwner::kFree)
            continue;
        const std::optional<size_t> i = levelNamed(levels, owner.level);
        const std::optional<uint32_t> e = i ? entryOf(levels[*i], owner.page) : std::nullopt;
        if (e && wanted[*e]) {
            held[*e] = 1;
            owner.lastUsed = in.frame;
            ++d.cached;
        }
    }

    // Pass 4, per entry: each missing page's rank, a prefix sum over the entries in priority
    // order: the coarsest levels first (a full pool keeps what every reader falls back on), then
    // by light, face, row and column.
    const std::vector<size_t> order = missingPageOrder(levels);
    std::vector<std::pair<size_t, uint32_t>> missing; // level record, entry; in rank order
    for (const size_t i : order)
        for (uint32_t e = levels[i].tableOffset;
             e < levels[i].tableOffset + levels[i].tableEntries(); ++e)
            if (wanted[e] && !held[e])
                missing.emplace_back(i, e);

    // Pass 5, per physical page: the candidates and their ranks: free pages first, then those no
    // one asked for this frame; each kind least recently used first (a freed page keeps the frame
    // it was last used), by index among equals. A rank is the count of candidates before it in
    // that order: a sort.
    std::vector<uint32_t> candidates;
    for (uint32_t p = 0; p < owners.size(); ++p)
        if (owners[p].level == PageOwner::kFree || owners[p].lastUsed < in.frame)
            candidates.push_back(p);
    std::stable_sort(candidates.begin(), candidates.end(), [&](uint32_t a, uint32_t b) {
        const bool freeA = owners[a].level == PageOwner::kFree;
        const bool freeB = owners[b].level == PageOwner::kFree;
        if (freeA != freeB)
            return freeA;
        return owners[a].lastUsed < owners[b].lastUsed;
    });

    // Pass 6, per missing page: the candidate of its rank, or none (the pool is full: its
    // readers fall back on the coarser pages, which rank before it).
    for (size_t r = 0; r < missing.size(); ++r) {
        const VirtualLevel& level = levels[missing[r].first];
        const PageKey key = pageKeyOf(level, missing[r].second);
        if (r >= candidates.size()) {
            ++d.dropped;
            continue;
        }
        PageOwner& owner = owners[candidates[r]];
        if (owner.level != PageOwner::kFree)
            ++d.evicted;
        owner = {.level = packLevel(key.light, key.face, key.level),
                 .page = key.page,
                 .lastUsed = in.frame};
        d.render.emplace_back(candidates[r], key);
    }

    // Pass 7, per physical page: the table, from the owners in this frame's windows.
    d.table.assign(entries, VIRTUAL_NOT_RESIDENT);
    for (uint32_t p = 0; p < owners.size(); ++p) {
        if (owners[p].level == PageOwner::kFree)
            continue;
        const std::optional<size_t> i = levelNamed(levels, owners[p].level);
        if (const std::optional<uint32_t> e =
                i ? entryOf(levels[*i], owners[p].page) : std::nullopt)
            d.table[*e] = p + 1u;
    }
    return d;
}

} // namespace penumbra
