#pragma once
// The scene model every part of Penumbra consumes: world-space triangles (already flattened
// through the node hierarchy), materials, lights and cameras. Loaders (built-in generators,
// glTF) produce it; the renderer and the ground-truth reference read the same triangles.
#include <glm/glm.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace penumbra {

struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;      // unit length
    uint32_t material;     // index into Scene::materials
    glm::vec2 uv{0.0f};    // the coordinates of the material's base-colour texture
    glm::vec4 color{1.0f}; // linear RGBA vertex colour (glTF COLOR_0), multiplies baseColor
};

// Vertices a skin places (glTF skins, builtin:walker's figure): linear blend skinning, each
// vertex by the weighted sum of its joints' matrices. The renderer places them on the GPU (the
// frame's `skin` pass, in the first frame after each pose); Scene::vertices holds the same
// placement made on the host (placeSkinnedVertices), which the ground truth, the bounds and
// culling read and the GPU's is checked against. Edit a skinned vertex through this, not
// through Scene::vertices: the GPU places it from here.
struct SkinnedVertex {
    uint32_t vertex;         // its index in Scene::vertices
    uint32_t firstInfluence; // its influences: [firstInfluence, firstInfluence + influenceCount)
    uint32_t influenceCount; // at least 1
    glm::vec3 position;      // in bind space (morph targets blended at the scene's time)
    glm::vec3 normal;        // in bind space, of any length (the placed normal is made unit)
};
struct SkinInfluence {
    uint32_t joint; // into Skinning::joints
    float weight;   // more than 0; a vertex's weights sum to 1 (to a float's rounding)
};
struct Skinning {
    std::vector<SkinnedVertex> vertices;
    std::vector<SkinInfluence> influences;
    // This pose's joint matrices: each joint's posed world transform times its inverse bind
    // matrix (every skin's joints in one list).
    std::vector<glm::mat4> joints;
    bool empty() const { return vertices.empty(); }
};

// Decoded image pixels: RGBA8, sRGB-encoded colour, linear alpha (glTF's convention), rows top
// to bottom.
struct TextureImage {
    std::string name;
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> rgba;
};

enum class TextureWrap { Repeat, ClampToEdge, MirroredRepeat };

// An image with the way it is sampled (glTF texture + sampler).
struct Texture {
    uint32_t image = 0; // index into Scene::images
    TextureWrap wrapS = TextureWrap::Repeat;
    TextureWrap wrapT = TextureWrap::Repeat;
    bool nearest = false; // magnification filter NEAREST (else linear)
};

// glTF alpha modes. Blend is drawn opaque, and its alpha is coverage in the shadows: the
// ground truth lets 1 - alpha of the light through it (Scene::transmittance).
enum class AlphaMode { Opaque, Mask, Blend };

struct Material {
    std::string name;
    glm::vec4 baseColor{0.8f, 0.8f, 0.8f, 1.0f}; // linear RGBA
    int32_t baseColorTexture = -1;               // index into Scene::textures, -1 for none
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f; // Mask: coverage below it is a hole (in the image and the shadow)
    bool doubleSided = true;  // false: back faces are culled in the camera's view
    // Light through the covered surface (docs/translucency.md): KHR_materials_transmission's
    // factor, times its texture's red channel, tinted by the base colour ...
    float transmission = 0.0f;
    int32_t transmissionTexture = -1; // index into Scene::textures, -1 for none
    // ... and KHR_materials_volume: a closed mesh of this thickness (mesh units; 0: thin-walled)
    // whose inside keeps attenuationColor of the light every attenuationDistance.
    float thickness = 0.0f;
    float attenuationDistance = std::numeric_limits<float>::infinity();
    glm::vec3 attenuationColor{1.0f};
    bool alphaTested() const { return alphaMode == AlphaMode::Mask; }
    // Whether light passes it in part: Blend (its alpha is coverage) or transmission.
    bool translucent() const { return alphaMode == AlphaMode::Blend || transmission > 0.0f; }
};

enum class LightType { Directional, Spot, Point };

// "directional", "spot", "point": glTF's KHR_lights_punctual names, used everywhere.
std::string_view lightTypeName(LightType type);
// The type with that name; false if there is none.
bool lightTypeFromName(std::string_view name, LightType& type);

struct Light {
    std::string name;
    LightType type = LightType::Directional;
    glm::vec3 position{0.0f};               // spot and point
    glm::vec3 direction{0.0f, -1.0f, 0.0f}; // unit, the direction light travels (spot, directional)
    glm::vec3 color{1.0f};                  // linear RGB
    float intensity = 1.0f;                 // directional: irradiance; spot/point: per sr at 1 unit
    float range = 0.0f;                     // spot/point; 0 = unlimited
    float innerConeAngle = 0.0f;            // radians, spot
    float outerConeAngle = 0.7853982f;      // radians, spot (glTF default pi/4)
    float radius = 0.0f;                    // world units, spot/point area light size (0 = point)
    float angularDiameter = 0.0f;           // degrees, directional light size (0 = parallel)
    bool castsShadow = true;
    // A radius (spot, point) or an angle (directional): its shadows have penumbrae, and the
    // truth traces `--samples` rays towards it; without, one exact ray (a hard truth).
    bool hasSize() const {
        return type == LightType::Directional ? angularDiameter > 0.0f : radius > 0.0f;
    }
};

struct Camera {
    std::string name;
    glm::vec3 position{0.0f, 2.0f, 8.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float yfov = 0.8f; // radians (perspective)
    bool orthographic = false;
    float ymag = 1.0f; // orthographic: half the view's height (glTF's ymag); x follows the image
    float znear = 0.05f;
    float zfar = 200.0f;
    // Made by framing the scene, not the scene's own (whatever its name): a timeline or played
    // frames keep the first frame's, as its bounds move with the animation.
    bool automatic = false;
};

struct Bounds {
    glm::vec3 min{std::numeric_limits<float>::max()};
    glm::vec3 max{-std::numeric_limits<float>::max()};
    void grow(const glm::vec3& p) { min = glm::min(min, p), max = glm::max(max, p); }
    glm::vec3 center() const { return 0.5f * (min + max); }
    glm::vec3 extent() const { return max - min; }
    float radius() const { return 0.5f * glm::length(extent()); } // the bounding sphere's
    bool empty() const { return min.x > max.x; }
};

// --view: the automatic camera's kind; Auto measures it (docs/scenes.md).
enum class ViewChoice { Auto, Exterior, Interior };

// --add-light KIND:key=value,... as given: the kind, what the text set, the text itself.
struct AddedLight {
    LightType type = LightType::Directional;
    std::optional<glm::vec3> position, direction; // pos=, dir= (the direction light travels)
    std::optional<float> angleDegrees;            // sun: angular diameter
    std::optional<float> coneDegrees;             // spot: outer half-angle
    std::optional<float> radius, intensity;
    // orbit=SECONDS: one turn about the vertical axis through about=X,Y,Z (default: the scene's
    // bounds centre) every SECONDS, negative the other way, posed at the scene's --time.
    std::optional<float> orbitSeconds;
    std::optional<glm::vec3> orbitCentre;
    std::string name; // empty: "<kind> (--add-light <n>)"
    std::string text; // as typed
};

// Scene control from the command line (issue 16), applied to the loaded scene by every command
// that takes one, so that the render and the ground truth see the same lights and view.
struct SceneEdits {
    std::optional<glm::vec3> sunDirection; // --sun-dir: the direction the light travels
    std::vector<std::pair<std::string, glm::vec3>> lightPositions;  // --light-pos NAME=X,Y,Z
    std::vector<std::pair<std::string, glm::vec3>> lightDirections; // --light-dir NAME=X,Y,Z
    std::optional<glm::vec3> cameraPosition, lookAt;                // --camera-pos, --look-at
    std::optional<float> fovDegrees;                                // --fov, vertical
    std::vector<AddedLight> addedLights;                            // --add-light
    std::optional<ViewChoice> view;                                 // --view
    bool ground = false;                                            // --ground
    bool noGround = false;    // --no-ground: no automatic ground (docs/scenes.md)
    bool doubleSided = false; // --double-sided
    bool empty() const;
};

struct Scene {
    std::string name;
    std::vector<Vertex> vertices;  // world space
    std::vector<uint32_t> indices; // triangle list
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<TextureImage> images;
    std::vector<Light> lights;
    std::vector<Camera> cameras;
    bool defaultLight = false;    // lights[0] is the loader's stand-in for an asset without lights
    bool automaticGround = false; // applySceneEdits added a ground to catch a shadow
    SceneEdits edits;             // what applySceneEdits changed
    // Animation (glTF): the one chosen ("" when the scene has none), its length in seconds, and
    // the time it is posed at (none: the nodes at rest).
    std::string animation;
    float animationDuration = 0.0f;
    std::optional<double> time;
    Skinning skinning; // the vertices a skin places (empty: none)

    size_t triangleCount() const { return indices.size() / 3; }
    // The coverage (alpha) of `material` at a texture coordinate and vertex alpha, as the
    // shadow pass and the ground truth test it: bilinear at full resolution, wrap as sampled.
    float coverage(uint32_t material, glm::vec2 uv, float vertexAlpha) const;
    // Whether a surface point of `material` exists (Mask: coverage >= cutoff).
    bool covers(uint32_t material, glm::vec2 uv, float vertexAlpha) const;
    // The fraction of light, per channel (linear RGB), a shadow ray keeps crossing `material`
    // at a texture coordinate with a vertex colour: 0 for an opaque surface, 1 for a hole
    // (docs/translucency.md has the rule).
    glm::vec3 transmittance(uint32_t material, glm::vec2 uv, glm::vec4 vertexColor) const;
    // Whether any triangle's material is translucent.
    bool hasTranslucentCasters() const;
    Bounds bounds() const;
    // The camera named `name`; empty name: the first camera, else an automatic framing.
    // Throws InputError when a named camera does not exist.
    Camera camera(std::string_view cameraName) const;
};

struct SceneLoadOptions {
    uint64_t maxFileSize = uint64_t{1} << 30; // cap for a glTF file and each file it uses
    // Caps on what a small file can ask for: triangles after instancing (a mesh used by many
    // nodes is copied per node) and decoded image bytes (a PNG inflates ~1000:1). Defaults:
    // 100M triangles; 4 x maxFileSize of pixels, at least 64 MiB.
    uint64_t maxTriangles = 100'000'000;
    uint64_t maxImageBytes = 0;                   // 0: the default above
    std::vector<std::string>* warnings = nullptr; // content skipped while loading
    // --time: seconds into the animation (none: at rest; negative or not finite: InputError);
    // --animation: its name or index ("" the first; one the scene lacks: InputError).
    std::optional<double> time;
    std::string animation;
    // An --add-light orbits: --time moves it on a still scene too (no warning that it does not).
    bool lightsMove = false;
};

// Loads `spec`: "builtin:NAME", or a glTF 2.0 file (.gltf, .glb), with invalid triangles
// already dropped. Throws InputError on anything malformed.
Scene loadScene(std::string_view spec, const SceneLoadOptions& options = {});

// The one rule that decides which triangles exist, applied before the rasterizer and the
// ground truth see a scene: drops triangles with an index out of range, a non-finite vertex,
// a coordinate past kMaxCoordinate, or no area. Non-finite normals become the face normal.
// Returns how many triangles were dropped.
inline constexpr float kMaxCoordinate = 1e15f;
size_t dropInvalidTriangles(Scene& scene);

// Places every skinned vertex of `scene` (Scene::skinning) on the host: its position by the
// weighted sum of its joints' matrices (summed in double, over the weights' own sum), its
// normal by that matrix's inverse transpose, made unit ((0, 1, 0) where it has no direction).
// The reference the GPU's skinning is checked against. Checks the skinning first.
void placeSkinnedVertices(Scene& scene);
// InputError(scene.name, "skinned vertex N: ...") for a skinned vertex past Scene::vertices or
// listed twice, influences out of range or none, a joint out of range, weights that do not sum
// to more than 0: what the renderer checks before the GPU reads it.
void checkSkinning(const Scene& scene);

// Whether `light` gets a shadow map, and so a visibility image and a ground truth: the one rule
// the renderer, the reference and the CLI share (every light type: suns and spots get one view,
// point lights a cube of six).
bool castsShadowMap(const Light& light);
// How many shadow views (map layers) it takes: 0 without a shadow map, 6 cube faces for a point
// light, `cascades` (csm.cascades) for a directional light, 1 for a spot.
uint32_t shadowViewCount(const Light& light, uint32_t cascades);

// The distance from `p` to the nearest point of any triangle (infinity for none): how near a
// light's shadow views may put their near plane without clipping a caster.
float nearestSurfaceDistance(const Scene& scene, const glm::vec3& p);

// A camera's view volume as a frame: unit axes (forward from the position to the target, right,
// up) and the half width and height of the view at distance 1 along forward (perspective) or at
// any distance (orthographic); `aspect` is the image's width over its height.
struct ViewFrustum {
    glm::vec3 position{0.0f}, forward{0.0f, 0.0f, -1.0f}, right{1.0f, 0.0f, 0.0f},
        up{0.0f, 1.0f, 0.0f};
    glm::vec2 halfExtentPerDistance{0.0f}; // perspective
    glm::vec2 halfExtent{0.0f};            // orthographic
    glm::vec2 halfExtentAt(float distance) const {
        return halfExtent + halfExtentPerDistance * distance;
    }
};
ViewFrustum viewFrustum(const Camera& camera, float aspect);
// The distances along the camera's view axis at which some triangle lies inside its view volume
// (image aspect `aspect`, between znear and zfar), as {nearest, farthest}; empty (x > y) when no
// triangle is in view. What a sun's cascades must cover, and no more.
glm::vec2 visibleDepthRange(const Scene& scene, const Camera& camera, float aspect);
// --sun-dir (replaces the loader's default light, else adds a sun named "sun"), --light-pos and
// --light-dir (a light by name: a position for spots and point lights, a direction for spots and
// suns), --camera-pos with --look-at and --fov (a camera named "command line" that becomes the
// scene's first). Throws InputError naming the option.
// --ground adds a ground quad under the subject (scene/framing.h), three times its largest extent;
// without --ground or --no-ground, the same quad is added when it adds a cast shadow to the first
// camera's view (scene/first_picture.h), and scene.automaticGround says so;
// --double-sided makes every material double-sided;
// --view puts the automatic camera of that kind first (a default light follows it).
// --add-light adds its lights after --sun-dir's (replacing the loader's default light too), each
// named as given or "<kind> (--add-light <n>)"; a name the scene already has is an InputError.
void applySceneEdits(Scene& scene, const SceneEdits& edits);
// "sun:dir=X,Y,Z[,angle=DEG]", "spot:pos=X,Y,Z,dir=X,Y,Z[,cone=DEG][,radius=R]",
// "point:pos=X,Y,Z[,radius=R]", each with optional intensity= and name=; InputError("--add-light",
// ...) naming what is wrong otherwise.
AddedLight parseAddedLight(std::string_view text);
// "auto", "exterior", "interior"; InputError("--view", ...) otherwise.
ViewChoice parseViewChoice(std::string_view text);
std::string_view viewChoiceName(ViewChoice choice);
// The quad --ground adds, its material named `material`.
void addGround(Scene& scene, std::string_view material = "ground (--ground)");
// The light an --add-light makes in `scene` (the index-th): unless given, a sun as bright as
// --sun-dir's (2), a spot or point light as bright at the scene's centre, a spot's cone 45
// degrees with a soft rim (inner 0.8 of the outer), sizes 0.
Light makeAddedLight(const AddedLight& added, const Scene& scene, size_t index);
// "X,Y,Z" as three finite numbers, and "NAME=X,Y,Z"; InputError(option, ...) otherwise.
glm::vec3 parseVector3(std::string_view text, std::string_view option);
using NamedVector = std::pair<std::string, glm::vec3>;
NamedVector parseNamedVector3(std::string_view text, std::string_view option);
// --light-radius / --light-angle: negative values leave the scene's sizes alone.
void applyLightSizeOverrides(Scene& scene, float radius, float angleDegrees);
std::vector<std::string_view> builtinSceneNames();

} // namespace penumbra
