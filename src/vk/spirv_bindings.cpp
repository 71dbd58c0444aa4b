#include "vk/spirv_bindings.h"

#include "penumbra/error.h"

#include <algorithm>
#include <fmt/format.h>
#include <unordered_map>
#include <unordered_set>

namespace penumbra::vk {
namespace {

// The opcodes, decorations and storage classes read (the SPIR-V specification, section 3).
enum Op : uint32_t {
    OpEntryPoint = 15,
    OpTypeImage = 25,
    OpTypeSampler = 26,
    OpTypeSampledImage = 27,
    OpTypeArray = 28,
    OpTypeRuntimeArray = 29,
    OpTypeStruct = 30,
    OpTypePointer = 32,
    OpConstant = 43,
    OpSpecConstant = 50,
    OpVariable = 59,
    OpDecorate = 71,
    OpMemberDecorate = 72,
};
constexpr uint32_t kMagic = 0x07230203u;
constexpr uint32_t DecorationBlock = 2, DecorationBufferBlock = 3, DecorationNonWritable = 24,
                   DecorationNonReadable = 25, DecorationBinding = 33, DecorationDescriptorSet = 34;
constexpr uint32_t StorageUniformConstant = 0, StorageUniform = 2, StorageStorageBuffer = 12;
constexpr uint32_t DimBuffer = 5;

struct Module {
    std::unordered_set<uint32_t> interface; // the entry points' global variables
    std::unordered_map<uint32_t, uint32_t> binding, set;
    std::unordered_set<uint32_t> block, bufferBlock;
    // `readonly` and `writeonly`: on a variable (images), or on each member of a block (buffers:
    // the members so decorated, by struct).
    std::unordered_set<uint32_t> nonWritable, nonReadable;
    std::unordered_map<uint32_t, std::unordered_set<uint32_t>> nonWritableMembers,
        nonReadableMembers;
    struct Variable {
        uint32_t pointer, storage;
    };
    std::unordered_map<uint32_t, Variable> variables;
    std::unordered_map<uint32_t, uint32_t> pointee;  // pointer type -> its type
    std::unordered_map<uint32_t, uint32_t> constant; // (spec) constant -> its default value
    struct Type {
        uint32_t op;
        std::span<const uint32_t> operands; // past the result id
    };
    std::unordered_map<uint32_t, Type> types;
};

[[noreturn]] void malformed(const std::string& why) {
    fatal(__FILE__, __LINE__, "reflectBindings: " + why);
}

Module parse(std::span<const uint32_t> words) {
    if (words.size() < 5 || words[0] != kMagic)
        malformed("not a SPIR-V module");
    Module m;
    for (size_t at = 5; at < words.size();) {
        const uint32_t op = words[at] & 0xffffu, count = words[at] >> 16;
        if (count == 0 || at + count > words.size())
            malformed(fmt::format("an instruction of {} words at word {}", count, at));
        const std::span<const uint32_t> w = words.subspan(at, count);
        at += count;
        switch (op) {
        case OpEntryPoint: { // model, id, name (a literal string), then the interface ids
            size_t i = 3;
            while (i < w.size() && (w[i] >> 24) != 0 && (w[i] & 0xff) != 0 &&
                   ((w[i] >> 8) & 0xff) != 0 && ((w[i] >> 16) & 0xff) != 0)
                ++i;
            for (++i; i < w.size(); ++i)
                m.interface.insert(w[i]);
            break;
        }
        case OpDecorate:
            if (w.size() >= 3 && w[2] == DecorationBinding && w.size() >= 4)
                m.binding[w[1]] = w[3];
            else if (w.size() >= 4 && w[2] == DecorationDescriptorSet)
                m.set[w[1]] = w[3];
            else if (w.size() >= 3 && w[2] == DecorationBlock)
                m.block.insert(w[1]);
            else if (w.size() >= 3 && w[2] == DecorationBufferBlock)
                m.bufferBlock.insert(w[1]);
            else if (w.size() >= 3 && w[2] == DecorationNonWritable)
                m.nonWritable.insert(w[1]);
            else if (w.size() >= 3 && w[2] == DecorationNonReadable)
                m.nonReadable.insert(w[1]);
            break;
        case OpMemberDecorate: // struct, member, decoration
            if (w.size() >= 4 && w[3] == DecorationNonWritable)
                m.nonWritableMembers[w[1]].insert(w[2]);
            else if (w.size() >= 4 && w[3] == DecorationNonReadable)
                m.nonReadableMembers[w[1]].insert(w[2]);
            break;
        case OpVariable:
            if (w.size() >= 4)
                m.variables[w[2]] = {w[1], w[3]};
            break;
        case OpTypePointer:
            if (w.size() >= 4)
                m.pointee[w[1]] = w[3];
            break;
        case OpConstant:
        case OpSpecConstant:
            if (w.size() >= 4)
                m.constant[w[2]] = w[3];
            break;
        case OpTypeImage:
        case OpTypeSampler:
        case OpTypeSampledImage:
        case OpTypeArray:
        case OpTypeRuntimeArray:
        case OpTypeStruct:
            if (w.size() >= 2)
                m.types[w[1]] = {op, w.subspan(2)};
            break;
        default:
            break;
        }
    }
    return m;
}

const Module::Type& typeOf(const Module& m, uint32_t id) {
    const auto it = m.types.find(id);
    if (it == m.types.end())
        malformed(fmt::format("type %{} is not an image, sampler, array or struct", id));
    return it->second;
}

VkDescriptorType kindOf(const Module& m, uint32_t type, uint32_t storage) {
    const Module::Type& t = typeOf(m, type);
    if (storage == StorageStorageBuffer)
        return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    if (storage == StorageUniform) {
        if (m.bufferBlock.contains(type))
            return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        if (m.block.contains(type))
            return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        malformed(fmt::format("uniform %{} is neither a Block nor a BufferBlock", type));
    }
    if (storage != StorageUniformConstant)
        malformed(fmt::format("a descriptor in storage class {}", storage));
    switch (t.op) {
    case OpTypeSampledImage:
        return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    case OpTypeSampler:
        return VK_DESCRIPTOR_TYPE_SAMPLER;
    case OpTypeImage: { // sampled type, dim, depth, arrayed, MS, sampled (1 or 2), format
        if (t.operands.size() < 6)
            malformed("a short OpTypeImage");
        const bool storageImage = t.operands[5] == 2;
        if (t.operands[1] == DimBuffer)
            return storageImage ? VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER
                                : VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
        return storageImage ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE : VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
    }
    default:
        malformed(fmt::format("type %{} is no descriptor", type));
    }
}

// Whether the shader may read and write what variable `id` of descriptor type `type` (its
// element type `element`) binds: sampled images and uniforms are read only; a storage image or
// buffer is read unless `writeonly` and written unless `readonly`, on the variable or on every
// member of its block.
std::pair<bool, bool> accessOf(const Module& m, uint32_t id, uint32_t element,
                               VkDescriptorType type) {
    const bool storage = type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE ||
                         type == VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER ||
                         type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    if (!storage)
        return {type != VK_DESCRIPTOR_TYPE_SAMPLER, false};
    const auto everyMember = [&](const auto& decorated) {
        const Module::Type& t = typeOf(m, element);
        const auto it = decorated.find(element);
        return t.op == OpTypeStruct && it != decorated.end() &&
               it->second.size() == t.operands.size();
    };
    const bool readable = !m.nonReadable.contains(id) && !everyMember(m.nonReadableMembers);
    const bool writable = !m.nonWritable.contains(id) && !everyMember(m.nonWritableMembers);
    return {readable, writable};
}

} // namespace

std::vector<Binding> reflectBindings(std::span<const uint32_t> words) {
    const Module m = parse(words);
    std::vector<Binding> used;
    for (const auto& [id, variable] : m.variables) {
        if (!m.interface.contains(id) || !m.binding.contains(id))
            continue; // not used by the entry point, or not a descriptor (inputs, outputs, push)
        const auto set = m.set.find(id);
        if (set != m.set.end() && set->second != 0)
            malformed(fmt::format("binding {} in descriptor set {} (the renderer binds set 0)",
                                  m.binding.at(id), set->second));
        const auto pointee = m.pointee.find(variable.pointer);
        if (pointee == m.pointee.end())
            malformed(fmt::format("variable %{} is not a pointer", id));
        uint32_t type = pointee->second, count = 1;
        if (const Module::Type& t = typeOf(m, type);
            t.op == OpTypeArray || t.op == OpTypeRuntimeArray) {
            if (t.operands.empty())
                malformed("an array without its element type");
            if (t.op == OpTypeArray) {
                const auto length =
                    t.operands.size() > 1 ? m.constant.find(t.operands[1]) : m.constant.end();
                if (length == m.constant.end())
                    malformed(fmt::format("the length of array %{} is no constant", type));
                count = length->second;
            }
            type = t.operands[0];
        }
        const VkDescriptorType kind = kindOf(m, type, variable.storage);
        const auto [read, written] = accessOf(m, id, type, kind);
        used.push_back({.binding = m.binding.at(id),
                        .type = kind,
                        .count = count,
                        .read = read,
                        .written = written});
    }
    std::sort(used.begin(), used.end(),
              [](const Binding& a, const Binding& b) { return a.binding < b.binding; });
    return used;
}

std::string_view descriptorKind(VkDescriptorType type) {
    switch (type) {
    case VK_DESCRIPTOR_TYPE_SAMPLER:
        return "sampler";
    case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER:
        return "combined image sampler";
    case VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE:
        return "sampled image";
    case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
        return "storage image";
    case VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER:
        return "uniform texel buffer";
    case VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER:
        return "storage texel buffer";
    case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER:
        return "uniform buffer";
    case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER:
        return "storage buffer";
    default:
        return "descriptor";
    }
}

std::string bindingMismatch(std::span<const Binding> used, std::span<const Binding> layout) {
    for (const Binding& u : used) {
        const auto held = std::find_if(layout.begin(), layout.end(),
                                       [&](const Binding& l) { return l.binding == u.binding; });
        if (held == layout.end())
            return fmt::format("binding {} ({}) is not in the layout", u.binding,
                               descriptorKind(u.type));
        if (held->type != u.type)
            return fmt::format("binding {} is a {} in the shader, a {} in the layout", u.binding,
                               descriptorKind(u.type), descriptorKind(held->type));
        if (held->count < u.count)
            return fmt::format("binding {} is an array of {} in the shader, of {} in the layout",
                               u.binding, u.count, held->count);
    }
    return {};
}

} // namespace penumbra::vk
