// The order of the frame graph's passes (render/frame_graph.h): by phase, and within a phase by
// what the passes read and write, ties in declaration order.
#include "render/frame_graph.h"

#include "penumbra/error.h"

#include <algorithm>
#include <queue>

namespace penumbra::render {

std::vector<size_t> FrameGraph::dependencyOrder() const {
    const size_t n = mPasses.size();
    // Edges within a phase: b runs after a.
    std::vector<std::vector<size_t>> after(n);
    std::vector<size_t> waiting(n, 0);
    const auto edge = [&](size_t a, size_t b) {
        after[a].push_back(b);
        ++waiting[b];
    };
    // Each resource's users, phase by phase, in declaration order.
    struct State {
        std::optional<size_t> lastWriter;
        std::vector<size_t> readersSince; // read what lastWriter wrote
        std::vector<size_t> early;        // read before any writer was declared
    };
    std::vector<size_t> byPhase(n);
    for (size_t i = 0; i < n; ++i)
        byPhase[i] = i;
    std::stable_sort(byPhase.begin(), byPhase.end(),
                     [&](size_t a, size_t b) { return mPasses[a].phase < mPasses[b].phase; });
    std::vector<State> states(resourceCount());
    std::vector<Phase> statePhase(states.size());
    for (size_t i : byPhase) {
        const PassDecl& pass = mPasses[i];
        for (size_t u = 0; u < pass.uses.size(); ++u) {
            const Use& use = pass.uses[u];
            if (std::any_of(pass.uses.begin(), pass.uses.begin() + static_cast<std::ptrdiff_t>(u),
                            [&](const Use& v) { return v.resource == use.resource; }))
                continue; // one resource, one dependency
            State& st = states[use.resource];
            if (statePhase[use.resource] != pass.phase) // a new phase starts afresh
                st = State{}, statePhase[use.resource] = pass.phase;
            if (!writes(use.access)) {
                if (st.lastWriter)
                    edge(*st.lastWriter, i), st.readersSince.push_back(i);
                else
                    st.early.push_back(i);
                continue;
            }
            if (st.lastWriter)
                edge(*st.lastWriter, i);
            else // a read declared before the first writer reads what it writes
                for (size_t r : st.early)
                    edge(i, r);
            for (size_t r : st.readersSince) // they read the version before this write
                edge(r, i);
            st.lastWriter = i;
            st.readersSince.clear();
        }
    }
    // Kahn's order, phase by phase, the earliest declared first among the ready ones.
    std::vector<size_t> order;
    order.reserve(n);
    for (size_t begin = 0; begin < n;) {
        size_t end = begin;
        while (end < n && mPasses[byPhase[end]].phase == mPasses[byPhase[begin]].phase)
            ++end;
        std::priority_queue<size_t, std::vector<size_t>, std::greater<>> ready;
        for (size_t k = begin; k < end; ++k)
            if (waiting[byPhase[k]] == 0)
                ready.push(byPhase[k]);
        const size_t placed = order.size();
        while (!ready.empty()) {
            const size_t i = ready.top();
            ready.pop();
            order.push_back(i);
            for (size_t j : after[i])
                if (--waiting[j] == 0)
                    ready.push(j);
        }
        if (order.size() - placed != end - begin) {
            std::string names;
            for (size_t k = begin; k < end; ++k)
                if (waiting[byPhase[k]] > 0)
                    names += (names.empty() ? "\"" : ", \"") + mPasses[byPhase[k]].name + "\"";
            fatal(__FILE__, __LINE__,
                  "FrameGraph: passes " + names + " read what each other writes (a cycle)");
        }
        begin = end;
    }
    return order;
}

} // namespace penumbra::render
