#pragma once
// A shadow technique as the frame sees it: what it keeps per shadow view beside the light's depth
// map, the passes that fill it, the map the visibility pass filters, its specialization
// constants, its parameters and how they pack into FrameData, and what it costs in memory. The
// frame (src/render) runs what a module declares and never asks which technique it is; each
// technique is one module in this folder plus its shader include (docs/architecture.md, "Adding a
// technique").
#include "bindings.h"
#include "frame_block.h"
#include "penumbra/settings.h"

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace penumbra::shadows {

enum class MapFormat { Depth32, R32F, RG32F, RGBA32F, RG32UI, RGBA32UI, RGBA16 }; // 16: unorm
uint32_t bytesPerTexel(MapFormat format);
// Integer maps are read through usamplers: the visibility pass binds its filtered map at
// VIS_SHADOW_TABLE instead of VIS_SHADOW_MAP when it is one.
bool holdsIntegers(MapFormat format);

// Every technique has the light's depth map, "depth" (Depth32, cleared to 1 = far).
inline constexpr std::string_view kDepthMap = "depth";

// A map the technique keeps per shadow view: a depth target that a depth pass renders, or an
// image a post pass writes.
struct MapDecl {
    std::string_view name;
    MapFormat format;
    // When set, the format follows the parameters (msm.precision); `format` is then the default.
    MapFormat (*formatFor)(const ParameterValues&) = nullptr;
    // When set and true for the parameters, the map has a full mip chain (vsm.filter=mip) that a
    // PostDispatch::MipChain pass fills; else one level.
    bool (*mipmappedFor)(const ParameterValues&) = nullptr;
};
MapFormat formatOf(const MapDecl& map, const ParameterValues& params);
bool mipmappedOf(const MapDecl& map, const ParameterValues& params);

// Another depth pass over the casters, into `target` (a Depth32 map), whose fragment shader
// reads the map `reads` at the fragment's texel (a depth peel, say).
struct DepthPassDecl {
    std::string_view target;
    std::string_view fragmentShader; // in shaders/
    std::string_view reads;
};

// A compute pass run over each shadow view after the depth passes: it samples `inputs` with a
// nearest sampler (bindings 0, 1, ...) and writes `outputs` as storage images (bindings 8, ...);
// its push constants are gpu::PostPassPush.
inline constexpr size_t kMaxPostPasses = 12; // each is a GPU timestamp scope of its own
// Texels: one invocation per texel (GROUP_SIZE x GROUP_SIZE groups); Lines: one per row or column
// of the (square) map, LINE_GROUP_SIZE a group (scans); MipChain: levels 1.. of its one output,
// a dispatch per level over its texels, reading the level above at binding 0 (`inputs` unused;
// nothing runs when the map has one level).
enum class PostDispatch { Texels, Lines, MipChain };
struct PostPassDecl {
    std::string_view shader; // in shaders/
    std::vector<std::string_view> inputs, outputs;
    PostDispatch dispatch = PostDispatch::Texels;
};

struct SpecConstant {
    uint32_t id; // SPEC_* in shaders/include/bindings.h
    uint32_t value;
    auto operator<=>(const SpecConstant&) const = default;
};

struct TechniqueModule {
    TechniqueInfo info;                         // name, summary, paper, parameter families, rows
    std::vector<ParameterInfo> parameters;      // the technique's own family (`pcf.*`, ...)
    std::vector<MapDecl> maps;                  // beyond kDepthMap
    std::vector<DepthPassDecl> depthPasses;     // beyond the light's depth pass
    std::vector<PostPassDecl> postPasses;       // in order
    std::string_view visibilityMap = kDepthMap; // what the visibility pass filters
    // Specialization constants of the visibility pass beyond TECHNIQUE (the module's id) and
    // RECEIVER (bias.receiver, every technique's).
    std::vector<SpecConstant> (*constants)(const ParameterValues&) = nullptr;
    // Writes the module's parameters into the frame block (its own fields).
    void (*pack)(const ParameterValues&, gpu::FrameData&) = nullptr;
    // Whether it models the light's size (its penumbra follows it): bias.horizon=soft applies.
    bool modelsLightSize = false;
    // The widest footprint the technique filters over, in texels from the receiver: the blur
    // radius a metric may allow at a shadow edge (0 for a single sample).
    double (*blurRadiusTexels)(const ParameterValues&) = nullptr;
    // Whether it traces the scene's distance field instead of filtering shadow maps (sdf): the
    // frame draws no shadow map, and the scene renderer builds the field (src/render/
    // distance_field.h) once per scene and field setting.
    bool tracesField = false;
};

// The separable Gaussian blur of the blurred-moment techniques (vsm, esm, evsm, msm;
// shaders/include/moments_blur.glsl): the `sizeKey` parameter (odd taps, sigma = size / 6), a
// row pass from the depth map into "rows" and a column pass into `output`, both maps of
// `format`, and the radius the blur and the bilinear fetch after it reach.
struct GaussianBlur {
    std::string_view sizeKey, rowsShader, columnsShader, output;
    MapFormat format;
    MapFormat (*outputFormatFor)(const ParameterValues&) = nullptr; // MapDecl::formatFor
    ParameterInfo sizeParameter() const;
    std::vector<MapDecl> maps() const;
    std::vector<PostPassDecl> passes() const;
    double radiusTexels(const ParameterValues& p) const;
};

// A summed-area table of fixed-point moments (shaders/include/sat_scan.glsl): a row pass from the
// depth map into "rowSums", a column pass into "table", both of `format` (RG32UI: offset VSM
// moments; RGBA32UI: MSM's four), with the technique's own pair of scan shaders.
inline constexpr std::string_view kMomentTable = "table";
struct SummedAreaTable {
    std::string_view rowsShader, columnsShader;
    MapFormat format;
    std::vector<MapDecl> maps() const;
    std::vector<PostPassDecl> passes() const;
};
// The summed-area soft members' common parameters (vssm, msm-soft; shadowSoftDetail in
// shaders/include/shadow_sat.glsl) under the family's own keys: the search and filter cap in
// texels, the kernel subdivision and the refining second search.
struct SoftSearch {
    std::string_view maxRadiusKey, subdivisionKey, refineKey;
    std::vector<ParameterInfo> parameters() const;
    // The cap, the two gpu::FrameData::softMode fields and the table's fixed-point scale.
    struct Packed {
        float maxRadius;
        uint32_t subdivision, refine;
        float tableScale;
    };
    Packed pack(const ParameterValues& p) const;
    double radiusTexels(const ParameterValues& p) const; // the widest footprint
};

// The fixed-point steps per unit that keep every box sum exact [Lauritzen 2007, GPU Gems 3
// ch. 8]: the tables wrap around 2^32, so a box's sum, a difference of corners, is exact as long
// as the true sum's magnitude stays under 2^31; boxes span at most `widestBox` texels a side (plus
// the two texels its fractional edges reach) and each texel's moments are at most one unit.
float fixedPointScale(double widestBox);

// The registered modules, in `penumbra techniques` order.
std::span<const TechniqueModule* const> allModules();
const TechniqueModule& moduleOf(Technique technique);

// Device memory the technique's maps take per shadow view of size x size texels.
uint64_t shadowMapBytes(const TechniqueModule& module, uint32_t size,
                        const ParameterValues& params);
// The guard band of a point light's cube faces and a sun's cascades (src/core/light_space.h,
// ViewFitting): the technique's widest footprint, the bilinear tap's reach and the normal offset,
// in texels, so a kernel near a view's edge reads the geometry across it from the same map.
uint32_t viewGuardTexels(const TechniqueModule& module, const ParameterValues& params);
// Every specialization constant of the visibility pass, TECHNIQUE first: the pipeline key.
std::vector<SpecConstant> visibilityConstants(const TechniqueModule& module,
                                              const ParameterValues& params);

// The modules, one per file of this folder.
const TechniqueModule& hardModule();
const TechniqueModule& pcfModule();
const TechniqueModule& pcssModule();
const TechniqueModule& secondDepthModule();
const TechniqueModule& vsmModule();
const TechniqueModule& esmModule();
const TechniqueModule& evsmModule();
const TechniqueModule& savsmModule();
const TechniqueModule& msmModule();
const TechniqueModule& vssmModule();
const TechniqueModule& msmSoftModule();
const TechniqueModule& sdfModule();

} // namespace penumbra::shadows
