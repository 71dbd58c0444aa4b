#pragma once
// The descriptor bindings a SPIR-V module uses, read from its words: what a pipeline layout must
// hold for it. createComputePipeline and createGraphicsPipeline check each shader against its
// layout with these, so a binding written differently in GLSL and in C++ is an error that names
// the shader and the binding on any device, not a validation message on some.
#include "vk/pipelines.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace penumbra::vk {

// The bindings of descriptor set 0 that the entry point uses (its interface: SPIR-V 1.4 and
// later list every global variable a shader uses there), sorted by binding, with their
// descriptor types, array sizes and whether it reads and writes them (Binding::read, written). A
// malformed module, a set other than 0 or a kind the renderer does not bind is a programmer's error
// (fatal).
std::vector<Binding> reflectBindings(std::span<const uint32_t> words);

// The bindings of the shader embedded as `shader` (cmake/Shaders.cmake; fatal when none is).
std::vector<Binding> reflectEmbedded(std::string_view shader);

// Why a shader that uses `used` cannot run on a layout of `layout`: the first binding it uses
// that the layout lacks, holds as another kind, or holds fewer of; empty when it can.
std::string bindingMismatch(std::span<const Binding> used, std::span<const Binding> layout);

// A storage image format as GLSL declares it ("rg32f"; "unknown" for VK_FORMAT_UNDEFINED), or
// "VkFormat <n>" for one no GLSL qualifier names.
std::string storageFormatName(VkFormat format);

// Why an image of format `bound` cannot be written where shaders declare the storage format
// `declared` (VK_FORMAT_UNDEFINED: none declared, any will do): "declared rg32f in its shaders,
// the image is r32f"; empty when it can. PassBindings and the post passes both ask it.
std::string storageFormatMismatch(VkFormat declared, VkFormat bound);

// The kind of a descriptor in words ("combined image sampler", "storage image", ...).
std::string_view descriptorKind(VkDescriptorType type);

} // namespace penumbra::vk
