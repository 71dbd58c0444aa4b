// The ground truth (include/penumbra/reference.h): Embree occlusion rays from every G-buffer
// pixel towards every shadow-casting light, parallel over rows with TBB.
#include "penumbra/reference.h"

#include "penumbra/error.h"
#include "reference/embree_scene.h"
#include "reference/sampling.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <limits>
#include <mutex>
#include <thread>
#include <unistd.h>

namespace penumbra {
namespace {

using Clock = std::chrono::steady_clock;

// How far along a shadow ray hits are ignored: the ray leaves the G-buffer position itself,
// whose float error grows with its magnitude (1e-4 relative; its floor, `least`, 1e-4 of the
// scene's size up to one unit: an absolute 1e-4 was the size of a scene made 1000 times smaller,
// whose spheres' truth then lost its contact shadows), and skips its
// own surface. Offsetting the origin off the surface instead would let rays that graze a closed
// mesh's terminator slip past a facet's edge into the light: near the edge the offset origin
// sits above the facet's plane, and a ray dipping under that plane leaves the facet first.
// Directions under the receiver's own triangle are blocked by it (an open surface lets no light
// through from its back). A ray rising at a shallow angle must travel further to clear an origin
// that lies that far under its surface (the rasterizer's depth error has either sign, and
// differs between devices): rayStart divides by the sine of the ray's angle above the face.
double selfHitDistance(const glm::dvec3& p, double least) {
    return 1e-4 * std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z), least});
}

// Where a ray leaving at `sine` (dir . face > 0) above its surface starts: clear of the surface by
// selfHitDistance, at most 64 times that far (rays under a degree above the surface).
float rayStart(double selfHit, double sine) {
    return static_cast<float>(selfHit / std::max(sine, 1.0 / 64.0));
}

// Prints a progress bar on stderr once the work has run for a second: redrawn in place on a
// terminal, one line per 10% otherwise.
class ProgressBar {
public:
    ProgressBar(bool enabled, uint64_t total) : mTotal(total) {
        if (enabled)
            mThread = std::thread([this] { run(); });
    }
    ~ProgressBar() {
        {
            std::lock_guard lock(mMutex);
            mDone = true;
        }
        mWake.notify_all();
        if (mThread.joinable())
            mThread.join();
    }
    void advance(uint64_t n) { mCount.fetch_add(n, std::memory_order_relaxed); }

private:
    void run() {
        const auto start = Clock::now();
        const bool tty = ::isatty(2);
        int lastDecile = -1;
        bool printed = false;
        std::unique_lock lock(mMutex);
        while (!mWake.wait_for(lock, std::chrono::milliseconds(250), [this] { return mDone; })) {
            const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
            if (elapsed < 1.0)
                continue;
            const double f = static_cast<double>(mCount.load()) / static_cast<double>(mTotal);
            const int decile = static_cast<int>(f * 10.0);
            if (!tty && decile == lastDecile)
                continue;
            lastDecile = decile;
            const int filled = static_cast<int>(f * 30.0);
            std::fprintf(stderr, "%sreference [%s%s] %3.0f%%  %.1f s", tty ? "\r" : "",
                         std::string(filled, '#').c_str(), std::string(30 - filled, '.').c_str(),
                         100.0 * f, elapsed);
            std::fprintf(stderr, tty ? "" : "\n");
            printed = true;
        }
        if (printed && tty)
            std::fprintf(stderr, "\n");
    }
    uint64_t mTotal;
    std::atomic<uint64_t> mCount{0};
    std::mutex mMutex;
    std::condition_variable mWake;
    bool mDone = false;
    std::thread mThread;
};

} // namespace

void validate(const ReferenceOptions& options) {
    if (options.samples == 0 || options.samples > 65536)
        throw InputError("--samples",
                         fmt::format("{} is out of range [1, 65536]", options.samples));
}

std::string embreeVersion() {
    return fmt::format("{}.{}.{}", RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH);
}

ReferenceResult computeReference(const Scene& sceneIn, const RenderResult& gbuffer,
                                 const ReferenceOptions& options) {
    const auto start = Clock::now();
    Scene scene = sceneIn;
    dropInvalidTriangles(scene); // the rule the rasterizer applies, so both see one geometry
    const EmbreeScene embree(scene, options.embreeConfig);

    std::vector<const Light*> lights; // same order as the renderer's visibility images
    for (const Light& l : scene.lights)
        if (castsShadowMap(l))
            lights.push_back(&l);

    const uint32_t w = gbuffer.width, h = gbuffer.height;
    const size_t pixels = size_t{w} * h;
    ReferenceResult result{.width = w, .height = h, .triangles = embree.triangles()};
    result.visibility.assign(lights.size(),
                             std::vector<float>(pixels, std::numeric_limits<float>::quiet_NaN()));
    result.occluderDistance = result.visibility;
    const bool coloured = embree.translucent();
    if (coloured)
        result.transmittance.assign(
            lights.size(), std::vector<float>(3 * pixels, std::numeric_limits<float>::quiet_NaN()));
    const uint32_t samples = std::max(options.samples, 1u);
    // selfHitDistance's floor: the scene's size (its bounds' largest extent), at most one unit.
    const Bounds bounds = scene.bounds();
    const glm::dvec3 extent = glm::dvec3(bounds.max) - glm::dvec3(bounds.min);
    const double size = std::max({extent.x, extent.y, extent.z});
    const double least = std::isfinite(size) && size > 0.0 ? std::min(size, 1.0) : 1.0;
    const auto traceStart = Clock::now();
    std::atomic<uint64_t> rays{0};
    ProgressBar progress(options.progress, h);

    tbb::parallel_for(
        tbb::blocked_range<uint32_t>(0, h), [&](const tbb::blocked_range<uint32_t>& rows) {
            uint64_t localRays = 0;
            for (uint32_t y = rows.begin(); y != rows.end(); ++y) {
                if (options.cancel && options.cancel->load(std::memory_order_relaxed))
                    break;
                for (uint32_t x = 0; x < w; ++x) {
                    const size_t i = size_t{y} * w + x;
                    const glm::dvec3 p(gbuffer.position[3 * i], gbuffer.position[3 * i + 1],
                                       gbuffer.position[3 * i + 2]);
                    const glm::dvec3 n(gbuffer.normal[3 * i], gbuffer.normal[3 * i + 1],
                                       gbuffer.normal[3 * i + 2]);
                    if (!std::isfinite(p.x) || !std::isfinite(n.x))
                        continue;
                    const glm::dvec3 origin = p;
                    const auto tnear = static_cast<float>(selfHitDistance(p, least));
                    const glm::dvec3 face = embree.surfaceNormal(
                        glm::vec3(p), glm::vec3(glm::normalize(n)), 10.0f * tnear);
                    for (uint32_t l = 0; l < lights.size(); ++l) {
                        const LightCone cone = coneTowards(*lights[l], origin);
                        if (cone.inside) {
                            result.visibility[l][i] = 1.0f;
                            if (coloured)
                                std::fill_n(result.transmittance[l].begin() + 3 * i, 3, 1.0f);
                            result.occluderDistance[l][i] = std::numeric_limits<float>::infinity();
                            continue;
                        }
                        { // the ray to the light's centre (its axis): the nearest occluder
                            const double sine = glm::dot(cone.axis, face);
                            result.occluderDistance[l][i] =
                                sine <= 0.0
                                    ? 0.0f // the surface itself hides the light
                                    : embree.hitDistance(
                                          glm::vec3(origin), glm::vec3(cone.axis),
                                          rayStart(tnear, sine),
                                          static_cast<float>(std::min(
                                              distanceToLight(cone, origin, cone.axis), 1e30)));
                        }
                        const uint32_t count = cone.single ? 1 : samples;
                        const glm::dvec2 shift = pixelShift(x, y, l);
                        uint32_t visible = 0;
                        glm::dvec3 through(0.0); // coloured: the transmittances' sum
                        for (uint32_t s = 0; s < count; ++s) {
                            const glm::dvec3 dir =
                                sampleDirection(cone, hammersley(s, count, shift));
                            const double sine = glm::dot(dir, face);
                            if (sine <= 0.0)
                                continue;
                            const double tfar = distanceToLight(cone, origin, dir);
                            const float from = rayStart(tnear, sine);
                            const auto end = static_cast<float>(std::min(tfar, 1e30));
                            if (coloured)
                                through += glm::dvec3(embree.transmittance(
                                    glm::vec3(origin), glm::vec3(dir), from, end));
                            else
                                visible +=
                                    !embree.occluded(glm::vec3(origin), glm::vec3(dir), from, end);
                        }
                        localRays += count;
                        result.visibility[l][i] =
                            static_cast<float>(visible) / static_cast<float>(count);
                        if (coloured) {
                            through /= static_cast<double>(count);
                            for (int c = 0; c < 3; ++c)
                                result.transmittance[l][3 * i + c] = static_cast<float>(through[c]);
                            result.visibility[l][i] =
                                static_cast<float>(luminance(through.x, through.y, through.z));
                        }
                    }
                }
                progress.advance(1);
                if (options.rowsDone)
                    options.rowsDone->fetch_add(1, std::memory_order_relaxed);
            }
            rays.fetch_add(localRays, std::memory_order_relaxed);
        });
    result.rays = rays.load();
    result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    result.traceSeconds = std::chrono::duration<double>(Clock::now() - traceStart).count();
    return result;
}

} // namespace penumbra
