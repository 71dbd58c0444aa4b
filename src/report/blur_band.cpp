#include "report/blur_band.h"

#include <glm/glm.hpp>

#include "penumbra/error.h"
#include "shadows/contact.h"

#include <cmath>
#include <limits>

namespace penumbra {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// A texel's world size at `world` in `view` (perspective views: grows with the distance along
// the view's axis, the clip w).
float texelWorldAt(const ShadowViewInfo& view, const glm::vec3& world) {
    if (view.projection != "perspective")
        return view.texelWorldSize;
    const float w = (view.worldToShadow * glm::vec4(world, 1.0f)).w;
    return view.texelWorldSize * std::max(w, 0.0f);
}

// The view that holds `world`: a point light's cube face, else the first (a sun's cascades all
// scale their kernels to the first's texels, and a spot light has one).
const ShadowViewInfo* viewHolding(const LightShadow& shadow, const glm::vec3& world) {
    if (shadow.projection != "cube")
        return &shadow.views.front();
    for (const ShadowViewInfo& view : shadow.views) {
        const glm::vec4 s = view.worldToShadow * glm::vec4(world, 1.0f);
        if (s.w <= 0.0f)
            continue;
        const glm::vec2 uv = glm::vec2(s) / s.w;
        if (uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f)
            return &view;
    }
    return nullptr;
}

} // namespace

std::vector<float> blurBandPixels(const Light& light, const LightShadow& shadow,
                                  const RenderResult& gbuffer, double blurTexels) {
    const uint32_t w = gbuffer.width, h = gbuffer.height;
    std::vector<float> band(size_t{w} * h, kNaN);
    if (shadow.visibilityIndex < 0 || shadow.views.empty())
        return band;
    const auto position = [&](int64_t x, int64_t y) {
        const float* p = gbuffer.position.data() + 3 * (size_t(y) * w + size_t(x));
        return glm::vec3(p[0], p[1], p[2]);
    };
    const auto valid = [](const glm::vec3& p) {
        return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
    };
    // The step to the nearer valid neighbour along one axis; zero when there is none.
    const auto step = [&](int64_t x, int64_t y, int64_t dx, int64_t dy, const glm::vec3& p) {
        glm::vec3 best(0.0f);
        float bestLength = std::numeric_limits<float>::infinity();
        for (int side = -1; side <= 1; side += 2) {
            const int64_t qx = x + side * dx, qy = y + side * dy;
            if (qx < 0 || qy < 0 || qx >= int64_t{w} || qy >= int64_t{h})
                continue;
            const glm::vec3 q = position(qx, qy);
            if (!valid(q) || glm::length(q - p) >= bestLength)
                continue;
            best = q - p;
            bestLength = glm::length(best);
        }
        return best;
    };
    for (int64_t y = 0; y < int64_t{h}; ++y)
        for (int64_t x = 0; x < int64_t{w}; ++x) {
            const glm::vec3 p = position(x, y);
            if (!valid(p))
                continue;
            const ShadowViewInfo* view = viewHolding(shadow, p);
            if (view == nullptr)
                continue;
            const glm::vec3 ray =
                light.type == LightType::Directional ? light.direction : p - light.position;
            if (glm::length(ray) <= 0.0f)
                continue;
            const glm::vec3 d = glm::normalize(ray);
            // The footprint's two edges, across the light's rays.
            glm::vec3 a = step(x, y, 1, 0, p), b = step(x, y, 0, 1, p);
            a -= d * glm::dot(d, a);
            b -= d * glm::dot(d, b);
            // The smaller singular value of [a b]: the least world distance one pixel can span.
            const double aa = glm::dot(a, a), bb = glm::dot(b, b), ab = glm::dot(a, b);
            if (aa == 0.0 && bb == 0.0)
                continue; // no neighbour: the metric's minimum band
            const double trace = aa + bb, det = std::max(aa * bb - ab * ab, 0.0);
            // A lone neighbour (a one-pixel-wide sliver) gives one axis only.
            const double smallest =
                aa == 0.0 || bb == 0.0
                    ? trace
                    : 0.5 * (trace - std::sqrt(std::max(trace * trace - 4.0 * det, 0.0)));
            const double radius = blurTexels * texelWorldAt(*view, p);
            // A footprint seen edge-on along one axis (det 0): the blur spans that axis without
            // end; the metric caps it.
            band[size_t(y) * w + size_t(x)] = smallest > 0.0
                                                  ? static_cast<float>(radius / std::sqrt(smallest))
                                                  : std::numeric_limits<float>::infinity();
        }
    return band;
}

ErrorMetrics metricsAgainstTruth(const Scene& lit, std::span<const TruthView> views,
                                 BlurReach blur) {
    std::vector<std::vector<float>> bands; // moved, never copied: the layers' spans stay valid
    std::vector<MetricLayer> layers;
    uint32_t width = 0, height = 0;
    for (const TruthView& view : views) {
        const RenderResult& result = *view.result;
        PENUMBRA_CHECK(layers.empty() || (result.width == width && result.height == height),
                       "pooled views differ in size");
        width = result.width, height = result.height;
        std::vector<std::vector<float>> viewBands(view.truth.size());
        for (const LightShadow& s : result.lights)
            if (s.visibilityIndex >= 0 && size_t(s.visibilityIndex) < viewBands.size())
                viewBands[size_t(s.visibilityIndex)] = blurBandPixels(
                    lit.lights[s.sceneLight], s, result, blur.on(lit.lights[s.sceneLight]));
        for (std::vector<float>& b : viewBands)
            bands.push_back(std::move(b));
        for (size_t l = 0; l < view.truth.size(); ++l)
            layers.push_back(
                {.visibility = result.visibility[l],
                 .truth = view.truth[l],
                 .mask = view.masks[l],
                 .blurBand = bands[bands.size() - view.truth.size() + l],
                 .occluderDistance = l < view.occluderDistance.size()
                                         ? std::span<const float>(view.occluderDistance[l])
                                         : std::span<const float>(),
                 .contactBand = view.contactBand});
    }
    return computeMetrics(width, height, layers);
}

ErrorMetrics metricsAgainstTruth(const Scene& lit, const RenderResult& result,
                                 std::span<const std::vector<float>> truth,
                                 std::span<const std::vector<uint8_t>> masks, BlurReach blur,
                                 std::span<const std::vector<float>> occluderDistance) {
    const TruthView view{.result = &result,
                         .truth = truth,
                         .masks = masks,
                         .occluderDistance = occluderDistance,
                         .contactBand = contactBand(lit)};
    return metricsAgainstTruth(lit, std::span(&view, 1), blur);
}

std::vector<double> firstLightRmsePerChannel(const RenderResult& result,
                                             std::span<const std::vector<float>> truthTransmittance,
                                             std::span<const std::vector<uint8_t>> masks) {
    if (truthTransmittance.empty() || masks.empty() || result.visibility.empty())
        return {};
    const std::array<double, 3> perChannel = rmsePerChannel(
        result.transmittance.empty() ? std::span<const float>{}
                                     : std::span<const float>(result.transmittance[0]),
        result.visibility[0], truthTransmittance[0], masks[0]);
    return {perChannel.begin(), perChannel.end()};
}

double contactBand(const Scene& scene) {
    return shadows::kContactRowFraction * double(scene.bounds().radius());
}

} // namespace penumbra
