#pragma once
// A shadow technique as the frame sees it: what it keeps per shadow view beside the light's depth
// map, the passes that fill it, the map the visibility pass filters, its specialization
// constants and capabilities, its parameters and how they pack into its parameter block, what it
// costs in memory, and its CPU reference. The frame (src/render) runs what a module declares and
// never asks which technique it is; each technique is one module in this folder, a line in
// shaders/include/technique_list.h and its shader include (docs/architecture.md, "Adding a
// technique").
#include "bindings.h"
#include "core/light_space.h"
#include "frame_block.h"
#include "light_geometry.h"
#include "params_tables.h"
#include "penumbra/settings.h"
#include "technique_block.h"

#include <glm/glm.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace penumbra {
struct FilterProbe; // penumbra/renderer.h
}

namespace penumbra::shadows {

// RGBA16: unorm.
enum class MapFormat { Depth32, R32F, RG32F, RGBA32F, R32UI, RG32UI, RGBA32UI, RGBA16 };
uint32_t bytesPerTexel(MapFormat format);
// Integer maps are read through usamplers: the visibility pass binds its filtered map at
// TECH_TABLE instead of TECH_MAP when it is one.
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
    // Its level 0 is the depth map's size >> shrink a side (smrt's bounds: 1, half).
    uint32_t shrink = 0;
    // Whether last frame's version stays readable beside this frame's, by the name
    // `<name> (previous)` (kPreviousMapSuffix) in a post pass's inputs or in visibilityMaps:
    // twice the memory; zeros where it holds nothing (the first frame, a new size, a cut, a
    // frame that did not write it; docs/architecture.md, "History").
    bool history = false;
};
inline constexpr std::string_view kPreviousMapSuffix = " (previous)";
MapFormat formatOf(const MapDecl& map, const ParameterValues& params);
bool mipmappedOf(const MapDecl& map, const ParameterValues& params);

struct TechniqueModule;
// The visibility pass's map slots for a module under `params`: shadowMaps' (float formats) and
// shadowTables' (integer formats), by map name in the order the module lists them. Float slots
// it leaves hold kDepthMap when it reads the depth map (it lists it, or lists no float map:
// shadowMap is then the depth map), else its first float map; integer ones "" (a placeholder).
// Fatal past TECH_MAX_MAPS of a kind or for a map the module does not declare.
struct VisibilitySlots {
    std::array<std::string_view, TECH_MAX_MAPS> floats, integers;
    // Whether the visibility pass reads the depth map (TECH_COMPARE holds it only then).
    bool readsDepthMap = true;
};
VisibilitySlots visibilitySlots(const TechniqueModule& module, const ParameterValues& params);

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

// A technique's parameter block as the shaders read it at TECH_PARAMS: its module packs its own
// std140 struct (shaders/include/params_<family>.h) into the first bytes.
class ParamBlock {
public:
    template <class Params>
    void set(const Params& params) {
        static_assert(std::is_trivially_copyable_v<Params> && sizeof(Params) <= sizeof mBytes);
        std::memcpy(mBytes.data(), &params, sizeof params);
    }
    template <class Params>
    Params get() const {
        static_assert(std::is_trivially_copyable_v<Params> && sizeof(Params) <= sizeof mBytes);
        Params params;
        std::memcpy(&params, mBytes.data(), sizeof params);
        return params;
    }
    std::span<const std::byte> bytes() const { return mBytes; }

private:
    alignas(16) std::array<std::byte, TECHNIQUE_BLOCK_BYTES> mBytes{};
};

// A square shadow map on the CPU, rows top to bottom: what the CPU references read.
struct ShadowMapView {
    std::span<const float> depth; // size x size
    uint32_t size = 0;
    float texel(int i, int j) const; // clamp-to-edge
};

// Records how close each depth comparison comes to a tie, when asked (the parity tests skip
// probes a float rounding could flip).
struct MarginTracker {
    float* margin = nullptr;
    void see(float a, float b) const;
};

// What a module's CPU reference reads: the shader's inputs (src/shadows/cpu_filters.h has the
// taps they are built from).
struct FilterInput {
    const ShadowMapView& map;
    const FilterProbe& probe;
    const gpu::FrameData& frame;     // the shared settings: bias, the Poisson disk
    const ParamBlock& params;        // the module's own, as it packed them
    const gpu::ShadowViewData& view; // only what the filters read is filled
    MarginTracker margins;
};

// An edge-aware spatial filter of a technique's visibility
// (shaders/include/visibility_filter_weights.h).
struct VisibilityFilter {
    uint32_t radius = 0;        // pixels each side along rows, then columns (0: none)
    float tolerance = 0.5f;     // visibility steps beyond this stay sharp
    uint32_t cubeRadius = 0;    // radius under point lights (their cube faces' own budget)
    float cubeTolerance = 0.5f; // tolerance under point lights
    uint32_t wide = 0;          // radius inside a wide penumbra (at least `radius`; none where
    uint32_t cubeWide = 0;      // `radius` is 0), and under point lights
    // The radius, the tolerance and the radius inside a wide penumbra for a light of this kind
    // (LIGHT_*).
    uint32_t radiusFor(uint32_t lightType) const;
    float toleranceFor(uint32_t lightType) const;
    uint32_t wideFor(uint32_t lightType) const;
    bool runs() const { return radius > 0 || cubeRadius > 0; }
};

// Checkerboard tracing of a technique's visibility (shaders/include/checkerboard.h): half the
// pixels traced, each other one filled from its four traced neighbours on its surface where they
// lie within `range` of one another (`cubeRange` under point lights), the rest traced after.
struct Checkerboard {
    bool runs = false;
    float range = 0.0f, cubeRange = 0.0f;
    // Under a light without size none (a negative range: every pixel traced), since a filled
    // pixel can only lose what its neighbours miss where the exact answer is as cheap.
    float rangeFor(uint32_t lightType, bool sized) const;
};

// How a screen pass uses an image it binds.
enum class ScreenAccess { Read, Write, ReadWrite };
// The frame's screen scratch (R32F, one layer per light with shadow views), made when a screen
// pass binds it.
inline constexpr std::string_view kScreenScratch = "screen.scratch";

// A screen pass a technique adds after its visibility dispatch: its own compute shader on the
// layers' pipeline layout (LAYER_*: the G-buffer, the lights' visibility layers, an image at
// LAYER_RESULTS), dispatched over the image for each light with shadow views. The frame runs
// the passes a module lists, in order, and asks nothing else about them.
struct ScreenPassDecl {
    std::string_view name;   // its row in the pass costs ("visibility": the technique's own)
    std::string_view shader; // shaders/<shader>
    ScreenAccess visibility = ScreenAccess::ReadWrite;
    // At LAYER_RESULTS: kScreenScratch, or (empty) the layers' results (the viewer's
    // intermediates, a 1x1 stand-in otherwise).
    std::string_view results;
    ScreenAccess resultsAccess = ScreenAccess::Write;
    // Its specialization constants for a light of this type (LIGHT_*) and size.
    std::vector<SpecConstant> (*constants)(const ParameterValues&, uint32_t lightType,
                                           bool sized) = nullptr;
    // Whether it runs for a light of this type (nullptr: for every light).
    bool (*runsFor)(const ParameterValues&, uint32_t lightType) = nullptr;
    // Checkerboard tracing (shaders/include/checkerboard.h): the visibility dispatch traces the
    // even pixels alone; this pass, over their rows, fills the odd ones and lists those it cannot
    // (at VIS_TRACE_LIST / LAYER_TRACE_LIST), which the visibility pass then traces. The lights
    // take turns at the one list. At most one such pass, the first; left out when the viewer
    // asks for intermediates (they need every pixel traced); it runs for every light (no
    // `runsFor`). `parameter`: what turns it off (the messages name it).
    bool fillsCheckerboard = false;
    std::string_view parameter;
};

// The distance field a technique traces (TechniqueModule::tracedField): the keys of the
// parameters that set it, so that its builder, the device checks and the refusal audit read them
// through the module (reference/field_refusal.h), never by a technique's name.
struct DistanceFieldDecl {
    std::string_view resolutionKey; // voxels on the scene's longest axis (0: automatic)
    std::string_view thicknessKey;  // open geometry's half-thickness, voxels
    std::string_view refuseKey;     // the audit's limit against the plain depth test (0: off)
};

struct TechniqueModule {
    TechniqueInfo info;                     // name, summary, paper, parameter families, rows
    std::vector<ParameterInfo> parameters;  // the technique's own family (`pcf.*`, ...)
    std::vector<MapDecl> maps;              // beyond kDepthMap
    std::vector<DepthPassDecl> depthPasses; // beyond the light's depth pass
    std::vector<PostPassDecl> postPasses;   // in order
    // The maps its visibility pass reads (visibilitySlots): those of float formats at TECH_MAP's
    // slots (shadowMaps[0], [1], ...), those of integer formats at TECH_TABLE's (shadowTables),
    // each kind in this order, at most TECH_MAX_MAPS of each. A float slot it leaves holds the
    // depth map (smrt lists its bounds alone and marches the depth map at shadowMaps[0]).
    std::vector<std::string_view> visibilityMaps{kDepthMap};
    // Its own specialization constants of the visibility pass (SPEC_FILTER: pcf.filter), among
    // them what the pass does around it, each false unless listed: SPEC_FOOTPRINT (the pass
    // computes the pixel's footprint in the map: vsm.filter=mip), SPEC_BLOCKER_SEARCH (in a sun's
    // cascades the pass runs its search, STAGE_SEARCH, and its filter, STAGE_FILTER, in the
    // finest cascades that hold them, capped at its blockerSearchKey's texels: pcss),
    // SPEC_TRACES_FIELD (it is handed the receiver itself and clips the light at its horizon:
    // sdf). An id the shared constants set (visibilityConstants) is refused.
    std::vector<SpecConstant> (*constants)(const ParameterValues&) = nullptr;
    // Writes the module's parameters into its block (its struct, params_<family>.h).
    void (*pack)(const ParameterValues&, ParamBlock&) = nullptr;
    // Its CPU reference: the shader include's operations transcribed (float arithmetic, the same
    // texel clamping as the texture unit's clamp-to-edge). x visibility, yzw what the shader's
    // entry point returns there. The parity tests compare it with Renderer::probeTechnique.
    glm::vec4 (*reference)(const FilterInput&) = nullptr;
    // Whether it models the light's size (its penumbra follows it): bias.horizon=soft applies.
    bool modelsLightSize = false;
    // The widest footprint the technique filters over, in texels from the receiver: the blur
    // radius a metric may allow at a shadow edge (0 for a single sample). On a point light's cube
    // faces cubeRadiusTexels where set (the soft members' `<family>.cubeRadius`);
    // widestRadiusTexels is the larger of the two.
    double (*blurRadiusTexels)(const ParameterValues&) = nullptr;
    double (*cubeRadiusTexels)(const ParameterValues&) = nullptr;
    // When set, it searches the map for blockers and its visibility pass's intermediates hold the
    // average blocker's depth (z) and the filter's radius in texels (w), capped by this parameter
    // (the viewer's blocker-depth and penumbra views; pcss, vssm, msm-soft): the cap
    // FrameData::filterLimits.x carries, and a reach virtual maps fetch pages for.
    std::string_view blockerSearchKey;
    // Whether its kernels reach no further than the light seen from the receiver (the cone
    // towards the light, cut at the near plane) and, under a light without size, than one
    // bilinear tap: a sun's cascades and a point light's cube faces then keep guard bands that
    // wide (viewGuardBand), capped by the footprint above, and their texels are finer.
    bool footprintFollowsLight = false;

    // When set, it traces a signed distance field of the scene instead of filtering shadow maps
    // (with SPEC_TRACES_FIELD among its constants; sdf): the scene renderer builds the field
    // (src/render/distance_field.h) once per scene and setting. Such a module reads no map
    // (visibilityMaps empty), so the frame draws none.
    std::optional<DistanceFieldDecl> tracedField;
    // It takes a model's inside from closed, consistently wound surfaces (sdf's field, second-
    // depth's back faces): the commands warn about scenes with open or mis-wound ones.
    bool needsClosedSurfaces = false;
    // It reads its depth map texel by texel, through map_reads.glsl (hard, pcf, pcss): its taps
    // can go through a virtual map's page table (virtual.enabled, SPEC_VIRTUAL). A technique
    // that filters whole maps in post passes (blurs, tables) cannot: its passes do not cross
    // pages.
    bool readsVirtualMaps = false;
    // The screen passes it adds after its visibility dispatch, for these parameters, in order
    // (ScreenPassDecl; smrt's checkerboard fill and its visibility filter).
    std::vector<ScreenPassDecl> (*screenPasses)(const ParameterValues&) = nullptr;
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
// `<family>.cubeRadius` of the soft members (pcss, vssm, msm-soft): their search and filter cap
// on a point light's cube faces (kernelCap, light_geometry.h).
ParameterInfo cubeRadiusParameter(std::string_view key);

// The summed-area soft members' common parameters (vssm, msm-soft; shadowSoftDetail in
// shaders/include/shadow_sat.glsl) under the family's own keys: the search and filter cap in
// texels, the kernel subdivision and the refining second search.
struct SoftSearch {
    std::string_view maxRadiusKey, cubeRadiusKey, subdivisionKey, refineKey;
    int defaultSubdivision = 3; // by measurement, per member (docs/techniques.md)
    std::vector<ParameterInfo> parameters() const;
    // The cap, the subdivision, the refining search and the table's fixed-point scale (the
    // member fills in its own bound's settings).
    gpu::SoftParams pack(const ParameterValues& p) const;
    double radiusTexels(const ParameterValues& p) const;     // the widest footprint
    double cubeRadiusTexels(const ParameterValues& p) const; // on a point light's cube faces
};

// The fixed-point steps per unit that keep every box sum exact [Lauritzen 2007, GPU Gems 3
// ch. 8]: the tables wrap around 2^32, so a box's sum, a difference of corners, is exact as long
// as the true sum's magnitude stays under 2^31; boxes span at most `widestBox` texels a side (plus
// the two texels its fractional edges reach) and each texel's moments are at most one unit.
float fixedPointScale(double widestBox);

// The registered modules, in `penumbra techniques` order.
std::span<const TechniqueModule* const> allModules();
const TechniqueModule& moduleOf(Technique technique);

// The techniques whose module has `property`, in registry order, as a list in a sentence:
// "hard, pcf, pcss and smrt" (what a message names, never a list written by hand).
std::string techniquesWhere(bool (*property)(const TechniqueModule&));

// The screen passes the module adds for these parameters (none when it declares none); a
// declaration the frame cannot run (a fill not first, without its parameter or choosing its
// lights, an image at LAYER_RESULTS the frame does not make) is a programmer error.
std::vector<ScreenPassDecl> screenPassesOf(const TechniqueModule& module,
                                           const ParameterValues& params);
// The pass among them that fills a checkerboard (ScreenPassDecl::fillsCheckerboard), if any.
const ScreenPassDecl* checkerboardFill(std::span<const ScreenPassDecl> passes);

// Whether the frame draws the light's maps for it: a module whose visibility pass reads no map
// (a distance field's tracer) gets 1x1 stand-ins, only bound.
bool drawsLightMaps(const TechniqueModule& module);
// The side of the light's maps a frame makes for the module: `shadowMapSize`, or 1 for the
// stand-ins of one that draws none. The frame and the renderer's memory check both ask it.
uint32_t drawnMapSize(const TechniqueModule& module, uint32_t shadowMapSize);

// Device memory the technique's maps take per shadow view of size x size texels (0 when it draws
// none).
uint64_t shadowMapBytes(const TechniqueModule& module, uint32_t size,
                        const ParameterValues& params);
// The guard band of a point light's cube faces (cubeFace) or a sun's cascades
// (src/core/light_space.h, ViewFitting): the technique's widest footprint on those views, the
// bilinear tap's reach and the normal offset, in texels, so a kernel near a view's edge reads the
// geometry across it from the same map.
uint32_t viewGuardTexels(const TechniqueModule& module, const ParameterValues& params,
                         bool cubeFace = false);
// viewGuardTexels, or, for a technique whose footprint follows the light, the band that follows
// `light`'s size (GuardBand): what shadowViewsOf fits a light's views with.
GuardBand viewGuardBand(const TechniqueModule& module, const ParameterValues& params,
                        const Light& light);
// The footprint on any view: the larger of blurRadiusTexels and cubeRadiusTexels (what the
// metrics' blur band and the virtual pages' marking allow for); 0 without one.
double widestRadiusTexels(const TechniqueModule& module, const ParameterValues& params);
// The blocker search's cap in texels (its blockerSearchKey), 0 without one: FrameData's
// filterLimits.x, which SPEC_BLOCKER_SEARCH's cascade choice reads.
double searchCapTexels(const TechniqueModule& module, const ParameterValues& params);
// How far from its receiver's texel the visibility pass reads the map, in texels: the widest
// footprint, a blocker search's cap, and one texel at least (a bilinear tap). What virtual maps
// fetch pages for around each receiver.
double readReachTexels(const TechniqueModule& module, const ParameterValues& params);
// blurRadiusTexels (0 without one) and cubeRadiusTexels (negative without one): the blur band a
// metric allows per light type (report/blur_band.h, BlurReach).
std::pair<double, double> blurRadii(const TechniqueModule& module, const ParameterValues& params);
// Every specialization constant of the visibility pass, TECHNIQUE first: the pipeline key.
std::vector<SpecConstant> visibilityConstants(const TechniqueModule& module,
                                              const ParameterValues& params);

// The shared settings and the module's packed block for these parameters: what the visibility
// pass and the probe read (FrameData's technique-independent part: bias, the Poisson disk, the
// device's hardware depth filtering and its sub-texel bits).
struct FilterSettings {
    gpu::FrameData frame{};
    ParamBlock params;
};
FilterSettings filterSettings(const TechniqueModule& module, const ParameterValues& params,
                              bool hardwareDepthFilter, uint32_t subTexelBits);
// The technique-independent part alone, into an existing frame block.
void setSharedSettings(gpu::FrameData& frame, const TechniqueModule& module,
                       const ParameterValues& params, bool hardwareDepthFilter,
                       uint32_t subTexelBits);

// The module's CPU reference at `probe` (its `reference`); InputError for a technique without
// one (sdf traces a field: there is no shadow-map filter to evaluate).
glm::vec4 techniqueReference(Technique technique, const ShadowMapView& map,
                             const FilterProbe& probe, const FilterSettings& settings,
                             const gpu::ShadowViewData& view);
// The smallest |receiver depth + correction - stored depth| over every texel the filter reads.
float smallestComparisonMargin(Technique technique, const ShadowMapView& map,
                               const FilterProbe& probe, const FilterSettings& settings,
                               const gpu::ShadowViewData& view);

// The modules, one per file of this folder, from the technique list.
#define PENUMBRA_TECHNIQUE(id, Name, module, shader) const TechniqueModule& module##Module();
#include "technique_list.h"

} // namespace penumbra::shadows
