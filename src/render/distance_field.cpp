#include "render/distance_field.h"

#include "core/fault_injection.h"
#include "penumbra/error.h"
#include "vk/pipelines.h"
#include "vk/sync.h"
#include "vk/timestamps.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <span>
#include <utility>

namespace penumbra::render {
namespace {

// Storage images read and written by consecutive passes.
constexpr vk::ImageState kComputeReadWrite{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                           VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                                               VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                           VK_IMAGE_LAYOUT_GENERAL};

uint32_t groupsOf(uint32_t n, uint32_t size) {
    return (n + size - 1) / size;
}

vk::Image fieldImage(const vk::Context& ctx, const char* name, VkFormat format,
                     const shadows::FieldLayout& layout, VkImageUsageFlags usage) {
    return vk::createImage(ctx, {.name = name,
                                 .format = format,
                                 .width = layout.size.x,
                                 .height = layout.size.y,
                                 .usage = usage,
                                 .depth = layout.size.z});
}

// Storage buffers cannot be empty: an empty list uploads one unused entry.
template <typename T>
vk::Buffer upload(const vk::Context& ctx, const std::vector<T>& items, const char* name) {
    std::vector<T> data = items;
    if (data.empty())
        data.resize(1);
    return vk::uploadBuffer(ctx, std::as_bytes(std::span(data)), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                            name);
}

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

// Each pass is submitted in this many slabs (fewer where the field is thinner).
constexpr uint32_t kFieldSlabs = 8;

// Reports a build's progress through a ProgressFn: once it has run for a second, then every
// two seconds, each line with its share of the passes' estimated work done and the time left at
// the passes' rate so far (the CPU's part before them is done).
class BuildProgress {
public:
    BuildProgress(const ProgressFn& progress, std::chrono::steady_clock::time_point start,
                  const std::vector<FieldSlab>& slabs)
        : mProgress(progress), mStart(start), mSlabs(slabs) {
        for (const FieldSlab& s : slabs)
            mTotal += s.cost;
        const double elapsed = msSince(mStart) / 1000.0;
        if (mProgress && elapsed >= 1.0) {
            mProgress(fmt::format("distance field: triangle lists ready, {:.1f} s", elapsed));
            mLast = elapsed;
        }
    }
    void done(size_t slab) {
        mDone += mSlabs[slab].cost;
        const double elapsed = msSince(mStart) / 1000.0;
        if (!mProgress || elapsed < 1.0 || elapsed < mLast + 2.0 || slab + 1 == mSlabs.size())
            return;
        mLast = elapsed;
        const double fraction = mDone / std::max(mTotal, 1.0);
        mProgress(fieldProgressLine(fraction, elapsed,
                                    fieldTimeLeft(fraction, msSince(mPasses) / 1000.0),
                                    mSlabs[slab + 1].pass));
    }

private:
    const ProgressFn& mProgress;
    std::chrono::steady_clock::time_point mStart, mPasses = std::chrono::steady_clock::now();
    const std::vector<FieldSlab>& mSlabs;
    double mTotal = 0.0, mDone = 0.0, mLast = 0.0;
};

} // namespace

std::vector<FieldSlab> fieldSlabs(const shadows::FieldLayout& layout,
                                  const std::vector<uint32_t>& brickStarts, uint32_t count) {
    const glm::uvec3 bricks = layout.bricks();
    // The work of a brick's list in each pass: sdf_seed measures every listed triangle from each
    // of its voxels, sdf_resolve tests each for a crossing once per column.
    auto listed = [&](uint32_t axis, uint32_t first, uint32_t last) {
        double entries = 0.0;
        for (uint32_t z = 0; z < bricks.z; ++z)
            for (uint32_t y = 0; y < bricks.y; ++y) {
                const uint32_t at = axis == 2 ? z : y;
                if (at < first || at >= last)
                    continue;
                const size_t row = (size_t{z} * bricks.y + y) * bricks.x;
                entries += brickStarts[row + bricks.x] - brickStarts[row];
            }
        return entries;
    };
    const double brickVoxels = double(FIELD_BRICK) * FIELD_BRICK * FIELD_BRICK;
    std::vector<FieldSlab> slabs;
    for (const std::string_view pass : {kSeed, kFlood, kResolve}) {
        const uint32_t axis = pass == kResolve ? 1 : 2;
        const uint32_t n = std::min(count, bricks[axis]);
        for (uint32_t k = 0; k < n; ++k) {
            const uint32_t first = bricks[axis] * k / n, last = bricks[axis] * (k + 1) / n;
            const double voxels =
                double(layout.size.x) * layout.size[3 - axis] * double(last - first) * FIELD_BRICK;
            const double entries = listed(axis, first, last);
            const double cost = pass == kSeed    ? voxels + entries * brickVoxels
                                : pass == kFlood ? 4.0 * voxels
                                                 : voxels + entries * FIELD_BRICK * FIELD_BRICK;
            slabs.push_back({.pass = pass,
                             .first = first * FIELD_BRICK,
                             .count = (last - first) * FIELD_BRICK,
                             .columns = pass == kResolve,
                             .cost = cost});
        }
    }
    return slabs;
}

double fieldTimeLeft(double fraction, double seconds) {
    return fraction > 0.0 ? seconds * (1.0 - fraction) / fraction : 0.0;
}

std::string fieldProgressLine(double fraction, double elapsedSeconds, double leftSeconds,
                              std::string_view next) {
    return fmt::format("distance field {:.0f}% ({}), {:.1f} s, about {:.0f} s left",
                       100.0 * fraction, next, elapsedSeconds, std::ceil(leftSeconds));
}

uint64_t fieldBuildBytes(const shadows::FieldLayout& layout) {
    return layout.voxels() * 12; // R32F field + two R32UI id images
}

namespace {

shadows::FieldLayout fieldFits(const vk::Context& ctx, const Bounds& bounds,
                               const FieldSetting& setting) {
    const uint32_t resolution = setting.resolution;
    const std::string key(setting.resolutionKey);
    const shadows::FieldLayout layout = shadows::fieldLayout(bounds, resolution);
    // What the messages name: the resolution asked for, or the automatic one it stood for.
    const std::string asked =
        resolution > 0 ? std::to_string(resolution)
                       : fmt::format("0 (automatic: {})", shadows::fieldResolution(bounds, 0));
    const uint32_t limit = ctx.limits().maxImageDimension3D;
    if (std::max({layout.size.x, layout.size.y, layout.size.z}) > limit)
        throw InputError(key,
                         fmt::format("{} makes a field of {}x{}x{} voxels, past this device's "
                                     "3D image size limit of {}",
                                     asked, layout.size.x, layout.size.y, layout.size.z, limit));
    const double have = static_cast<double>(deviceMemoryForChecks(ctx.deviceLocalHeapBytes()));
    if (static_cast<double>(fieldBuildBytes(layout)) > 0.5 * have)
        throw InputError(
            key, fmt::format("{} needs {:.2f} GiB of device memory to build its field; "
                             "the device has {:.2f} GiB",
                             asked, static_cast<double>(fieldBuildBytes(layout)) / (1 << 30),
                             have / (1 << 30)));
    return layout;
}

} // namespace

FieldSetting FieldSetting::of(const shadows::DistanceFieldDecl& decl,
                              const ParameterValues& params) {
    return {.resolution = static_cast<uint32_t>(params.number(decl.resolutionKey)),
            .thicknessVoxels = static_cast<float>(params.number(decl.thicknessKey)),
            .resolutionKey = decl.resolutionKey};
}

shadows::FieldLayout checkDistanceField(const vk::Context& ctx, const Scene& scene,
                                        const FieldSetting& setting) {
    // The bounds of the triangles the field is built from (dropInvalidTriangles' coordinate
    // rule), without copying the scene.
    Bounds bounds;
    auto usable = [](const glm::vec3& p) {
        return glm::all(glm::lessThan(glm::abs(p), glm::vec3(kMaxCoordinate)));
    };
    for (size_t t = 0; t < scene.triangleCount(); ++t) {
        const std::array<uint32_t, 3> v{scene.indices[3 * t], scene.indices[3 * t + 1],
                                        scene.indices[3 * t + 2]};
        if (std::any_of(v.begin(), v.end(), [&](uint32_t i) {
                return i >= scene.vertices.size() || !usable(scene.vertices[i].position);
            }))
            continue;
        for (uint32_t i : v)
            bounds.grow(scene.vertices[i].position);
    }
    if (bounds.empty())
        throw InputError(scene.name, "the scene has no valid triangles");
    return fieldFits(ctx, bounds, setting);
}

DistanceField buildDistanceField(const vk::Context& ctx, FramePipelines& pipelines,
                                 const Scene& scene, const FieldSetting& setting,
                                 const ProgressFn& progress) {
    const auto cpuStart = std::chrono::steady_clock::now();
    DistanceField field{.layout = fieldFits(ctx, scene.bounds(), setting)};
    const shadows::FieldLayout& layout = field.layout;
    if (progress) // the size chosen, not the resolution's 0 for "automatic"
        progress(fmt::format(
            "building the distance field: {}x{}x{} voxels of {:.3g} units{}", layout.size.x,
            layout.size.y, layout.size.z, layout.voxel,
            setting.resolution == 0 ? fmt::format(" ({} automatic)", setting.resolutionKey) : ""));
    field.thickness = setting.thicknessVoxels * layout.voxel;
    const shadows::FieldGeometry geometry = shadows::fieldGeometry(scene, layout, field.thickness);
    field.sceneTriangles = geometry.sceneTriangles;
    field.triangles = static_cast<uint32_t>(geometry.triangles.size());
    field.closedTriangles = geometry.closedTriangles;
    field.openTriangles = geometry.openTriangles;
    field.alphaTriangles = geometry.alphaTriangles;
    field.alphaPieces = geometry.alphaPieces;
    field.warnings = geometry.warnings;
    field.cpuMs = msSince(cpuStart);

    const vk::Buffer triangles = upload(ctx, geometry.triangles, "field triangles");
    const vk::Buffer starts = upload(ctx, geometry.brickStarts, "field brick starts");
    const vk::Buffer list = upload(ctx, geometry.brickList, "field brick lists");
    const vk::Buffer nearest = upload(ctx, geometry.farCandidates, "field far candidates");
    constexpr VkImageUsageFlags storage = VK_IMAGE_USAGE_STORAGE_BIT;
    std::array<vk::Image, 2> ids{
        fieldImage(ctx, "distance field ids", VK_FORMAT_R32_UINT, layout, storage),
        fieldImage(ctx, "distance field ids", VK_FORMAT_R32_UINT, layout, storage)};
    field.image =
        fieldImage(ctx, "distance field", VK_FORMAT_R32_SFLOAT, layout,
                   storage | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);

    const FieldPipelines& p = pipelines.field();
    const gpu::FieldPush base{.origin = glm::vec4(layout.origin, layout.voxel),
                              .size = glm::uvec4(layout.size, 0u),
                              .thickness = {field.thickness, 0.0f, 0.0f, 0.0f}};
    // Each pass in slabs, one submission each, so that a long build reports its progress: the
    // seed and flood passes in slabs along z, the resolve pass (columns along z) along y.
    const std::vector<FieldSlab> slabs = fieldSlabs(layout, geometry.brickStarts, kFieldSlabs);
    auto dispatch = [&](VkCommandBuffer cmd, VkPipeline pipeline, const vk::Image& in,
                        const vk::Image& out, const FieldSlab& slab) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
        vk::PushDescriptors()
            .storageBuffer(FIELD_TRIANGLES, triangles.get())
            .storageBuffer(FIELD_BRICK_STARTS, starts.get())
            .storageBuffer(FIELD_BRICK_LIST, list.get())
            .storageBuffer(FIELD_FAR_CANDIDATES, nearest.get())
            .storageImage(FIELD_IDS_IN, in.view.get())
            .storageImage(FIELD_IDS_OUT, out.view.get())
            .storageImage(FIELD_OUT, field.image.view.get())
            .push(ctx, cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.layout);
        gpu::FieldPush push = base;
        push.size.w = slab.first;
        vkCmdPushConstants(cmd, p.layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
        if (slab.columns)
            vkCmdDispatch(cmd, groupsOf(layout.size.x, 8), groupsOf(slab.count, 8), 1);
        else
            vkCmdDispatch(cmd, groupsOf(layout.size.x, 4), groupsOf(layout.size.y, 4),
                          groupsOf(slab.count, 4));
    };
    vk::GpuTimer timer(ctx, static_cast<uint32_t>(slabs.size()));
    BuildProgress report(progress, cpuStart, slabs);
    for (size_t i = 0; i < slabs.size(); ++i) {
        const FieldSlab& slab = slabs[i];
        ctx.submitAndWait([&](VkCommandBuffer cmd) {
            if (i == 0) {
                timer.reset(cmd);
                vk::Barriers()
                    .image(ids[0], vk::kUndefined, kComputeReadWrite)
                    .image(ids[1], vk::kUndefined, kComputeReadWrite)
                    .image(field.image, vk::kUndefined, kComputeReadWrite)
                    .record(cmd);
            } else { // the previous submission's writes
                vk::Barriers()
                    .image(ids[0], kComputeReadWrite, kComputeReadWrite)
                    .image(ids[1], kComputeReadWrite, kComputeReadWrite)
                    .image(field.image, kComputeReadWrite, kComputeReadWrite)
                    .record(cmd);
            }
            timer.begin(cmd, std::string(slab.pass), CostGroup::ShadowMaps); // the field: its map
            // sdf_seed writes ids[0], sdf_flood reads it and writes ids[1], sdf_resolve reads that.
            if (slab.pass == kSeed)
                dispatch(cmd, p.seed.get(), ids[1], ids[0], slab);
            else if (slab.pass == kFlood)
                dispatch(cmd, p.flood.get(), ids[0], ids[1], slab);
            else
                dispatch(cmd, p.resolve.get(), ids[1], ids[0], slab);
            timer.end(cmd);
            if (i + 1 == slabs.size())
                vk::imageBarrier(cmd, field.image, kComputeReadWrite, vk::kComputeSampled);
        });
        report.done(i);
    }
    for (const PassTime& pass : timer.read()) {
        field.buildMs += pass.medianMs;
        field.passMs.push_back(pass);
    }
    return field;
}

std::vector<float> readDistanceField(const vk::Context& ctx, const DistanceField& field) {
    const uint64_t bytes = field.bytes();
    vk::Buffer readback = vk::createBuffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                           vk::MemoryUse::Readback, "distance field readback");
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        vk::imageBarrier(cmd, field.image, vk::kComputeSampled, vk::kTransferRead);
        vk::copyImageToBuffer(cmd, field.image, readback.get());
        vk::imageBarrier(cmd, field.image, vk::kTransferRead, vk::kComputeSampled);
    });
    std::vector<float> voxels(field.layout.voxels());
    std::memcpy(voxels.data(), readback.mapped, bytes);
    return voxels;
}

} // namespace penumbra::render
