#include "render/access_states.h"

#include "penumbra/error.h"

namespace penumbra::render {

bool writes(Access access) {
    switch (access) {
    case Access::DepthAttachment:
    case Access::ColorAttachment:
    case Access::ComputeWrite:
    case Access::ComputeReadWrite:
    case Access::TransferWrite:
        return true;
    default:
        return false;
    }
}

// Whether the use reads what it finds (the frame's attachments are cleared on load).
bool reads(Access access) {
    return access != Access::DepthAttachment && access != Access::ColorAttachment &&
           access != Access::ComputeWrite && access != Access::TransferWrite;
}

vk::ImageState imageState(Access access) {
    switch (access) {
    case Access::DepthAttachment:
        return vk::kDepthWrite;
    case Access::ColorAttachment:
        return vk::kColorWrite;
    case Access::FragmentSampled:
        return vk::kFragmentSampled;
    case Access::ComputeSampled:
        return vk::kComputeSampled;
    case Access::ComputeWrite:
        return vk::kComputeWrite;
    case Access::ComputeReadWrite:
        return vk::kComputeReadWrite;
    case Access::ComputeRead: // a storage image only read
        return {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT,
                VK_IMAGE_LAYOUT_GENERAL};
    // Transfers at every transfer stage: copies, blits and clears alike.
    case Access::TransferRead:
        return {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL};
    case Access::TransferWrite:
        return {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL};
    default:
        break;
    }
    fatal(__FILE__, __LINE__, "FrameGraph: a buffer access on an image");
}

vk::BufferState bufferState(Access access) {
    constexpr VkPipelineStageFlags2 shaders = VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                                              VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT |
                                              VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    constexpr VkPipelineStageFlags2 compute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    switch (access) {
    case Access::UniformRead:
        return {shaders, VK_ACCESS_2_UNIFORM_READ_BIT};
    case Access::ComputeRead:
        return {compute, VK_ACCESS_2_SHADER_STORAGE_READ_BIT};
    case Access::ComputeWrite:
        return {compute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
    case Access::ComputeReadWrite:
        return {compute,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
    case Access::IndirectRead:
        return {VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | compute,
                VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT};
    case Access::TransferRead:
        return {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT};
    case Access::TransferWrite:
        return {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT};
    case Access::HostRead:
        return {VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT};
    case Access::VertexRead:
        return {VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT,
                VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT};
    case Access::VertexStorageRead:
        return {VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT};
    default:
        break;
    }
    fatal(__FILE__, __LINE__, "FrameGraph: an image access on a buffer");
}

} // namespace penumbra::render
