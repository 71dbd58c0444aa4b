#pragma once
// A shadow in the first picture (docs/scenes.md, "A shadow in the first picture"): what a camera
// sees of a scene and how much of it lies in a cast shadow, measured with rays on a 64 x 36 grid
// of the view; and the choices made with it when a scene comes without lights, cameras or
// anything to receive a shadow.
// - A pixel is in a cast shadow when its surface (turned to the camera) faces the light, lies in
//   a spot's cone, and another surface lies between it and the light. Surfaces turned away are
//   not counted: they are dark whatever the technique does.
// - The default light keeps its standard placement (scene/interior.h) when that shows at least
//   2% of the view in cast shadow; else of 28 suns round the camera (7 azimuths, 4 elevations) or
//   18 bulbs in an interior (along the view, to its sides, at two heights under the ceiling), the
//   one that shows the most, among those that light at least a quarter of what is in view.
// - A ground (scene/framing.h's quad under the subject) is added when nothing lies under the
//   subject to receive its shadow (in fewer than half of a 9 x 9 grid of columns over its
//   footprint does a ray down from 2%, 25% or 50% of its height meet a surface facing up,
//   through the model's own underside) and the ground adds at least half a percent of the view
//   in cast shadow: a lone object's shadow falls on nothing; a model on a floor or a thick
//   base, a terrain and a view that does not show it get none.
// - An interior without camera or lights whose view shows under 2% with its best light turns
//   its camera (8 directions, level or 20 degrees down) to the view that shows the most.
// - An automatic exterior view that shows under 2% (after the ground) turns round its target.
// - A scene without a camera whose own bulbs or spots light a level or an interior is seen from
//   near them: from 8 sides of the spot each light makes on what it shines at, when that shows
//   more cast shadow than the standard framing with the subject at least 15% of the view.
#include "penumbra/scene.h"
#include "scene/ray_cast.h"

#include <optional>
#include <span>

namespace penumbra {

inline constexpr float kEnoughShadow = 0.02f; // of the view: a standard light is kept
inline constexpr float kGroundGain = 0.005f;  // of the view: a ground is worth adding
inline constexpr float kLeastSubject = 0.15f; // of the view: a camera shows the subject
inline constexpr float kLeastLit = 0.25f;     // of what is in view: a light lights the view

struct ViewShadow {
    float covered = 0.0f;    // share of the view showing a surface
    float subject = 0.0f;    // share showing a surface inside the subject's box
    float lit = 0.0f;        // share facing the light with nothing between
    float castShadow = 0.0f; // share facing the light with a surface between
};

// The camera's rays and where they meet the scene, cast once; measure() casts one shadow ray per
// pixel that faces the light. The scene and hierarchy must outlive it.
class ViewProbe {
public:
    ViewProbe(const Scene& scene, const TriangleBvh& bvh, const Camera& camera);
    // With the scene's subjectBounds given: many cameras of one scene measure it once.
    ViewProbe(const Scene& scene, const TriangleBvh& bvh, const Camera& camera, Bounds subject);
    ViewShadow measure(const Light& light) const;
    // The share of the view in a visible cast shadow of the scene's lights that cast shadows and
    // light the view (lightsTheView: a bulb behind a wall shadows the whole view and shows no
    // shadow): the pixels that some of them face and whose light from them, as shaded (colour,
    // intensity, inverse square, range, cone, cosine), is blocked to under kVisibleShadow of what
    // it would be (one light: measure(light).castShadow within its range). 0 without any.
    float castShadow(std::span<const Light> lights) const;
    float subject() const; // ViewShadow::subject, which needs no light

private:
    struct Sample {
        glm::vec3 point{0.0f}, normal{0.0f}; // the normal turned to the camera
        bool inSubject = false;
    };
    struct Arrival {
        float irradiance = 0.0f; // unshadowed, the channels' mean
        bool visible = false;    // nothing between
    };
    // The light `light` would bring `s`, and whether it does; none where it cannot (turned
    // away, grazing, outside a spot's cone).
    std::optional<Arrival> arrival(const Sample& s, const Light& light) const;
    float share(size_t pixels) const;
    const TriangleBvh& mBvh;
    std::vector<Sample> mSamples; // the rays that met a surface
    size_t mPixels = 0;
    float mOffset = 0.0f; // how far a shadow ray starts off its surface
};

// What the first picture shows: the share of `camera`'s view in a visible cast shadow of the
// scene's lights (ViewProbe::castShadow) and the share that shows the subject (stats.json's
// `view`).
struct PictureMeasure {
    float castShadow = 0.0f, subject = 0.0f;
};
PictureMeasure measurePicture(const Scene& scene, const Camera& camera);

// The share of a 9 x 9 grid of columns over the subject's footprint (at the cells' centres) in
// which something lies below to receive a shadow (the rule above); a ground is considered
// below half.
float floorShare(const Scene& scene, const TriangleBvh& bvh);
// Whether a ray straight down from `top` leaves the scene through the front of a surface: an open
// surface facing up at the bottom (a terrain, a ground), not the underside of a closed model met
// from within. It follows at most kMostSurfacesDown surfaces (moving `step` past each); a column
// with more is taken as ending on none.
inline constexpr int kMostSurfacesDown = 16;
bool endsOnAnOpenSurface(const TriangleBvh& bvh, const glm::vec3& top, float step);
// A pixel shows a shadow when its lights bring it under this share of their light.
inline constexpr float kVisibleShadow = 0.5f;
// Whether a candidate light lights at least kLeastLit of what is in view (a bulb inside a wall
// shadows everything and lights nothing).
bool lightsTheView(const ViewShadow& v);

// The lights chooseDefaultLight weighs against `standard`: for a sun, the 28 suns; for a bulb,
// the 18 bulbs, their feet short of the walls.
std::vector<Light> defaultLightCandidates(const Scene& scene, const TriangleBvh& bvh,
                                          const Camera& camera, const Light& standard);
// The standard light (defaultLightFor's rule), or a better placed one as above.
Light chooseDefaultLight(const Scene& scene, const Camera& camera, const Light& standard);

// For an interior camera (scene/interior.h) whose best default light shows less than 2% of the
// view in cast shadow: the same camera turned to one of 8 directions, level or 20 degrees down,
// where the best default light shows the most; nullopt when none shows more.
std::optional<Camera> betterInteriorView(const Scene& scene, const Camera& standard);

// Adds the ground quad named "ground (automatic)" when nothing lies under the subject and the
// ground adds kGroundGain of the first camera's view in cast shadow (a default light is chosen
// again for the grounded scene); sets scene.automaticGround. Returns whether it did.
bool addGroundWhereNothingReceives(Scene& scene);
// An automatic exterior camera ("auto (exterior)") whose view shows under 2% in cast shadow with
// the scene's lights (a default light: its best) turns round its target, at its height and
// distance: of 8 directions, the one that shows the most with the subject at least 15% of the
// view (a default light follows it). Returns whether it turned.
bool turnExteriorView(Scene& scene);
// The one line that says so: "added a ground under 'NAME' ... (--no-ground leaves it out)".
std::string automaticGroundNote(const Scene& scene);

// For a scene without cameras whose own spot and point lights light a level or an interior (or
// an exterior whose standard framing shows the subject on less than 15% of the view): a camera
// near them, when it shows more cast shadow than `standard` with the subject at least 15% of the
// view; nullopt otherwise.
std::optional<Camera> cameraFromLights(const Scene& scene, const Camera& standard,
                                       bool levelOrInterior);

} // namespace penumbra
