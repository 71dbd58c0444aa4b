#pragma once
// The summed-area members' table on the CPU (savsm, vssm, msm-soft): the table as the two scan
// passes leave it (shaders/include/sat_scan.glsl: wrapping integer sums), its box queries, and
// the soft members' shadowSoftDetail (shaders/include/shadow_sat.glsl), loop for loop.
#include "moments.h"
#include "params_tables.h"
#include "shadows/technique.h"

#include <glm/glm.hpp>

#include <vector>

namespace penumbra::shadows {

// A summed-area table of fixed-point moments as the two scan passes write it (sat_scan.glsl):
// wrapping uint sums along rows, then down columns.
class MomentTable {
public:
    MomentTable(const ShadowMapView& map, const gpu::ShadowViewData& view, uint32_t kind,
                float scale)
        : n_(static_cast<int>(map.size)),
          table_(static_cast<size_t>(n_) * static_cast<size_t>(n_)) {
        std::vector<glm::uvec4> rows(table_.size());
        for (int j = 0; j < n_; ++j) {
            glm::uvec4 sum(0u);
            for (int i = 0; i < n_; ++i) {
                sum += gpu::tableMoments(kind, gpu::momentDepth(view, map.texel(i, j)), scale);
                rows[at(i, j)] = sum;
            }
        }
        for (int i = 0; i < n_; ++i) {
            glm::uvec4 sum(0u);
            for (int j = 0; j < n_; ++j) {
                sum += rows[at(i, j)];
                table_[at(i, j)] = sum;
            }
        }
    }

    // A table the device wrote, read back (size x size sums, rows first): the tests evaluate
    // the reference on the GPU's own sums.
    MomentTable(int size, std::vector<glm::uvec4> sums) : n_(size), table_(std::move(sums)) {}

    // One texel's fixed-point moments, from its cell's corners.
    glm::vec4 texelMoments(int i, int j) const {
        return gpu::boxFromCorners(corner({i, j}), corner({i + 1, j}), corner({i, j + 1}),
                                   corner({i + 1, j + 1}));
    }

    // tableBoxSum, loop for loop.
    glm::vec4 boxSum(glm::vec2 lo, glm::vec2 hi) const {
        const glm::ivec2 a = glm::min(glm::ivec2(glm::floor(lo)), glm::ivec2(n_ - 1));
        const glm::ivec2 b = glm::min(glm::ivec2(glm::floor(hi)), glm::ivec2(n_ - 1));
        const glm::vec2 fa = lo - glm::vec2(a), fb = hi - glm::vec2(b);
        const int xs[4] = {a.x, a.x + 1, b.x, b.x + 1}, ys[4] = {a.y, a.y + 1, b.y, b.y + 1};
        const float wx[4] = {1.0f - fa.x, fa.x, 1.0f - fb.x, fb.x};
        const float wy[4] = {1.0f - fa.y, fa.y, 1.0f - fb.y, fb.y};
        glm::uvec4 c[4][4];
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i)
                c[j][i] = corner({xs[i], ys[j]});
        glm::vec4 sum(0.0f);
        for (int y0 = 0; y0 < 2; ++y0)
            for (int y1 = 2; y1 < 4; ++y1)
                for (int x0 = 0; x0 < 2; ++x0)
                    for (int x1 = 2; x1 < 4; ++x1)
                        sum += wy[y0] * wy[y1] * wx[x0] * wx[x1] *
                               gpu::boxFromCorners(c[y0][x0], c[y0][x1], c[y1][x0], c[y1][x1]);
        return sum;
    }

    // tableBoxMean.
    glm::vec4 boxMean(uint32_t kind, float scale, glm::vec2 lo, glm::vec2 hi) const {
        const float area = std::max((hi.x - lo.x) * (hi.y - lo.y), 1e-6f);
        return gpu::tableMean(kind, boxSum(lo, hi) / area, scale);
    }

private:
    size_t at(int i, int j) const {
        return static_cast<size_t>(j) * static_cast<size_t>(n_) + static_cast<size_t>(i);
    }
    glm::uvec4 corner(glm::ivec2 c) const {
        return c.x <= 0 || c.y <= 0 ? glm::uvec4(0u) : table_[at(c.x - 1, c.y - 1)];
    }

    int n_;
    std::vector<glm::uvec4> table_;
};

// satBox: the box of half-width `reach` texels around uv, cut to the map.
void satBox(glm::vec2 uv, float reach, float size, glm::vec2& lo, glm::vec2& hi);

// shadowSoftDetail for a table of `kind` (MOMENTS_VSM: vssm; MOMENTS_MSM: msm-soft) with the
// member's own settings.
glm::vec4 softReference(uint32_t kind, const gpu::SoftParams& params, const FilterInput& in);
// The same on a given table (one the device wrote: tests).
glm::vec4 softReference(uint32_t kind, const gpu::SoftParams& params, const FilterInput& in,
                        const MomentTable& table);

} // namespace penumbra::shadows
