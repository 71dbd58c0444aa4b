#include "shadows/sdf_cut.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace penumbra::shadows {

gpu::FieldTriangle fieldTriangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, uint32_t flags) {
    float f;
    std::memcpy(&f, &flags, sizeof f);
    return {glm::vec4(a, f), glm::vec4(b, 0.0f), glm::vec4(c, 0.0f)};
}

uint32_t flagsOf(const gpu::FieldTriangle& t) {
    uint32_t flags;
    std::memcpy(&flags, &t.a.w, sizeof flags);
    return flags;
}

namespace {

// The largest piece, in voxels: holes smaller than the field's voxels close up in it anyway.
constexpr float kPieceVoxels = 1.5f;

class CoverageCut {
public:
    CoverageCut(const Scene& scene, const std::array<const Vertex*, 3>& v, uint32_t n)
        : mScene(scene), mV(v), mN(static_cast<int>(n)), mUp(n * n), mDown(n * n) {
        for (int i = 0; i < mN; ++i)
            for (int j = 0; i + j < mN; ++j) {
                mUp[i * mN + j] = sample(glm::vec2(i, j) + glm::vec2(1.0f / 3.0f));
                if (i + j + 2 <= mN)
                    mDown[i * mN + j] = sample(glm::vec2(i, j) + glm::vec2(2.0f / 3.0f));
            }
    }
    // Appends the covered parts; returns how many.
    size_t emit(std::vector<gpu::FieldTriangle>& out) {
        const size_t before = out.size();
        node(out, false, 0, 0, mN);
        return out.size() - before;
    }

private:
    bool sample(glm::vec2 grid) const {
        const glm::vec2 st = grid / static_cast<float>(mN);
        const float w0 = 1.0f - st.x - st.y;
        const glm::vec2 uv = w0 * mV[0]->uv + st.x * mV[1]->uv + st.y * mV[2]->uv;
        const float alpha = w0 * mV[0]->color.w + st.x * mV[1]->color.w + st.y * mV[2]->color.w;
        return mScene.covers(mV[0]->material, uv, alpha);
    }
    // Pieces outside the triangle count as covered: its own edges continue into its neighbours.
    bool up(int i, int j) const { return i < 0 || j < 0 || i + j >= mN || mUp[i * mN + j]; }
    bool down(int i, int j) const { return i < 0 || j < 0 || i + j + 2 > mN || mDown[i * mN + j]; }
    // Piece counts: 0 none covered, 2 all, 1 some.
    int coverage(bool isDown, int i, int j, int m) const {
        if (m == 1)
            return (isDown ? down(i, j) : up(i, j)) ? 2 : 0;
        const int h = m / 2;
        const std::array<int, 4> c =
            isDown ? std::array{coverage(true, i + h, j, h), coverage(true, i + h, j + h, h),
                                coverage(true, i, j + h, h), coverage(false, i + h, j + h, h)}
                   : std::array{coverage(false, i, j, h), coverage(false, i + h, j, h),
                                coverage(false, i, j + h, h), coverage(true, i, j, h)};
        if (c[0] == 2 && c[1] == 2 && c[2] == 2 && c[3] == 2)
            return 2;
        return c[0] == 0 && c[1] == 0 && c[2] == 0 && c[3] == 0 ? 0 : 1;
    }
    void node(std::vector<gpu::FieldTriangle>& out, bool isDown, int i, int j, int m) {
        const int c = coverage(isDown, i, j, m);
        if (c == 0)
            return;
        if (c == 2) {
            emitWhole(out, isDown, i, j, m);
            return;
        }
        const int h = m / 2;
        if (isDown) {
            node(out, true, i + h, j, h);
            node(out, true, i + h, j + h, h);
            node(out, true, i, j + h, h);
            node(out, false, i + h, j + h, h);
        } else {
            node(out, false, i, j, h);
            node(out, false, i + h, j, h);
            node(out, false, i, j + h, h);
            node(out, true, i, j, h);
        }
    }
    // A covered sub-triangle: an edge is an outline when a piece across it was cut away.
    void emitWhole(std::vector<gpu::FieldTriangle>& out, bool isDown, int i, int j, int m) {
        bool ab = true, bc = true, ca = true; // the neighbours across each edge all covered
        for (int k = 0; k < m; ++k) {
            if (isDown) { // corners (i + m, j), (i + m, j + m), (i, j + m)
                ab = ab && up(i + m, j + k);
                bc = bc && up(i + k, j + m);
                ca = ca && up(i + k, j + m - 1 - k);
            } else { // corners (i, j), (i + m, j), (i, j + m)
                ab = ab && down(i + k, j - 1);
                bc = bc && down(i + k, j + m - 1 - k);
                ca = ca && down(i - 1, j + k);
            }
        }
        const std::array<glm::vec2, 3> g =
            isDown ? std::array{glm::vec2(i + m, j), glm::vec2(i + m, j + m), glm::vec2(i, j + m)}
                   : std::array{glm::vec2(i, j), glm::vec2(i + m, j), glm::vec2(i, j + m)};
        const glm::vec3 a = mV[0]->position, b = mV[1]->position, cc = mV[2]->position;
        auto at = [&](glm::vec2 p) {
            const glm::vec2 st = p / static_cast<float>(mN);
            return a + st.x * (b - a) + st.y * (cc - a);
        };
        const uint32_t flags = FIELD_OPEN | (ab ? 0u : FIELD_OUTLINE_AB) |
                               (bc ? 0u : FIELD_OUTLINE_BC) | (ca ? 0u : FIELD_OUTLINE_CA);
        out.push_back(fieldTriangle(at(g[0]), at(g[1]), at(g[2]), flags));
    }

    const Scene& mScene;
    std::array<const Vertex*, 3> mV;
    int mN;
    std::vector<bool> mUp, mDown;
};

} // namespace

void cutByCoverage(const Scene& scene, const std::array<const Vertex*, 3>& v, float voxel,
                   uint64_t& budget, std::vector<gpu::FieldTriangle>& out) {
    const glm::vec3 a = v[0]->position, b = v[1]->position, c = v[2]->position;
    const float edge = std::max({glm::distance(a, b), glm::distance(b, c), glm::distance(c, a)});
    uint32_t n = 1;
    while (n < 64 && static_cast<float>(n) * kPieceVoxels * voxel < edge)
        n *= 2;
    while (n > 1 && uint64_t{n} * n > budget)
        n /= 2;
    CoverageCut(scene, v, n).emit(out);
    budget -= std::min<uint64_t>(budget, uint64_t{n} * n);
}

} // namespace penumbra::shadows
