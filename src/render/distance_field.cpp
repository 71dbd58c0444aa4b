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

} // namespace

uint64_t fieldBuildBytes(const shadows::FieldLayout& layout) {
    return layout.voxels() * 12; // R32F field + two R32UI id images
}

namespace {

shadows::FieldLayout fieldFits(const vk::Context& ctx, const Bounds& bounds, uint32_t resolution) {
    const shadows::FieldLayout layout = shadows::fieldLayout(bounds, resolution);
    const uint32_t limit = ctx.limits().maxImageDimension3D;
    if (std::max({layout.size.x, layout.size.y, layout.size.z}) > limit)
        throw InputError("sdf.resolution",
                         fmt::format("{} makes a field of {}x{}x{} voxels, past this device's "
                                     "3D image size limit of {}",
                                     resolution, layout.size.x, layout.size.y, layout.size.z,
                                     limit));
    const double have = static_cast<double>(deviceMemoryForChecks(ctx.deviceLocalHeapBytes()));
    if (static_cast<double>(fieldBuildBytes(layout)) > 0.5 * have)
        throw InputError("sdf.resolution",
                         fmt::format("{} needs {:.2f} GiB of device memory to build its field; "
                                     "the device has {:.2f} GiB",
                                     resolution,
                                     static_cast<double>(fieldBuildBytes(layout)) / (1 << 30),
                                     have / (1 << 30)));
    return layout;
}

} // namespace

shadows::FieldLayout checkDistanceField(const vk::Context& ctx, const Scene& scene,
                                        const ParameterValues& parameters) {
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
    return fieldFits(ctx, bounds, static_cast<uint32_t>(parameters.number("sdf.resolution")));
}

DistanceField buildDistanceField(const vk::Context& ctx, FramePipelines& pipelines,
                                 const Scene& scene, uint32_t resolution, float thicknessVoxels) {
    const auto cpuStart = std::chrono::steady_clock::now();
    DistanceField field{.layout = fieldFits(ctx, scene.bounds(), resolution)};
    const shadows::FieldLayout& layout = field.layout;
    const shadows::FieldGeometry geometry = shadows::fieldGeometry(scene, layout);
    field.triangles = static_cast<uint32_t>(geometry.triangles.size());
    field.closedTriangles = geometry.closedTriangles;
    field.openTriangles = geometry.openTriangles;
    field.alphaTriangles = geometry.alphaTriangles;
    field.thickness = thicknessVoxels * layout.voxel;
    field.cpuMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - cpuStart)
            .count();

    const vk::Buffer triangles = upload(ctx, geometry.triangles, "field triangles");
    const vk::Buffer starts = upload(ctx, geometry.brickStarts, "field brick starts");
    const vk::Buffer list = upload(ctx, geometry.brickList, "field brick lists");
    constexpr VkImageUsageFlags storage = VK_IMAGE_USAGE_STORAGE_BIT;
    std::array<vk::Image, 2> ids{
        fieldImage(ctx, "distance field ids", VK_FORMAT_R32_UINT, layout, storage),
        fieldImage(ctx, "distance field ids", VK_FORMAT_R32_UINT, layout, storage)};
    field.image =
        fieldImage(ctx, "distance field", VK_FORMAT_R32_SFLOAT, layout,
                   storage | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);

    const FieldPipelines& p = pipelines.field();
    gpu::FieldPush push{.origin = glm::vec4(layout.origin, layout.voxel),
                        .size = glm::uvec4(layout.size, 0u),
                        .thickness = {field.thickness, 0.0f, 0.0f, 0.0f}};
    auto dispatch = [&](VkCommandBuffer cmd, VkPipeline pipeline, const vk::Image& in,
                        const vk::Image& out, bool columns) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
        vk::PushDescriptors()
            .storageBuffer(FIELD_TRIANGLES, triangles.get())
            .storageBuffer(FIELD_BRICK_STARTS, starts.get())
            .storageBuffer(FIELD_BRICK_LIST, list.get())
            .storageImage(FIELD_IDS_IN, in.view.get())
            .storageImage(FIELD_IDS_OUT, out.view.get())
            .storageImage(FIELD_OUT, field.image.view.get())
            .push(ctx, cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.layout);
        vkCmdPushConstants(cmd, p.layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
        if (columns)
            vkCmdDispatch(cmd, groupsOf(layout.size.x, 8), groupsOf(layout.size.y, 8), 1);
        else
            vkCmdDispatch(cmd, groupsOf(layout.size.x, 4), groupsOf(layout.size.y, 4),
                          groupsOf(layout.size.z, 4));
    };
    auto between = [](VkCommandBuffer cmd, const vk::Image& image) {
        vk::imageBarrier(cmd, image, kComputeReadWrite, kComputeReadWrite);
    };
    vk::GpuTimer timer(ctx, 3);
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        timer.reset(cmd);
        vk::Barriers()
            .image(ids[0], vk::kUndefined, kComputeReadWrite)
            .image(ids[1], vk::kUndefined, kComputeReadWrite)
            .image(field.image, vk::kUndefined, kComputeReadWrite)
            .record(cmd);
        timer.begin(cmd, "sdf_seed");
        dispatch(cmd, p.seed.get(), ids[1], ids[0], false);
        timer.end(cmd);
        timer.begin(cmd, "sdf_flood");
        // Steps n/2, n/4, ..., 1, then 1 again (JFA+1): ids[0] holds the latest after each swap.
        // Rounds of steps k, k/2, ..., 1 carry an id up to 2k - 1 voxels: enough to cross the
        // widest gap between a voxel and the nearest seeded brick.
        uint32_t step = 1;
        while (2 * step < geometry.seedGap + 1 &&
               step * 2 < std::max({layout.size.x, layout.size.y, layout.size.z}))
            step *= 2;
        std::vector<uint32_t> steps;
        for (; step >= 1; step /= 2)
            steps.push_back(step);
        steps.push_back(1);
        for (const uint32_t s : steps) {
            between(cmd, ids[0]);
            between(cmd, ids[1]);
            push.size.w = s;
            dispatch(cmd, p.flood.get(), ids[0], ids[1], false);
            std::swap(ids[0], ids[1]);
        }
        timer.end(cmd);
        between(cmd, ids[0]);
        timer.begin(cmd, "sdf_resolve");
        dispatch(cmd, p.resolve.get(), ids[0], ids[1], true);
        timer.end(cmd);
        vk::imageBarrier(cmd, field.image, kComputeReadWrite, vk::kComputeSampled);
    });
    for (const auto& [pass, ms] : timer.read()) {
        field.buildMs += ms;
        field.passMs.push_back({pass, ms});
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
