// The sweep's identities as properties, not examples: every input of a truth changes the truth
// cache's key, every field of a task changes its id, and nothing else does; and the merge's
// Pareto front against one worked out by hand, with costs that are not in proportion to each
// other (a front of the visibility pass alone, or of any one pass, differs from it).
#include "sweep/merge.h"
#include "sweep/plan.h"
#include "sweep/tasks.h"
#include "sweep/truth_bootstrap.h"
#include "sweep/truth_cache.h"

#include <gtest/gtest.h>

#include <functional>
#include <set>

using namespace penumbra;
using namespace penumbra::sweep;

namespace {

struct Edit {
    std::string what;
    std::function<void(Scene&)> apply;
};

Light lightOf(LightType type) {
    return {.name = "l",
            .type = type,
            .position = {1.0f, 4.0f, 2.0f},
            .direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.3f)),
            .range = 50.0f,
            .innerConeAngle = 0.2f,
            .outerConeAngle = 0.6f,
            .radius = type == LightType::Directional ? 0.0f : 0.3f,
            .angularDiameter = type == LightType::Directional ? 2.0f : 0.0f};
}

// A scene with one light of `type`, a named camera and a texture, so that every field the truth
// reads has a value to change.
Scene sceneWith(LightType type) {
    Scene s = loadScene("builtin:showcase");
    s.lights = {lightOf(type)};
    s.cameras = {Camera{.name = "c", .position = {0, 3, 9}, .target = {0, 0, 0}}};
    s.images = {
        TextureImage{.name = "i", .width = 2, .height = 1, .rgba = {1, 2, 3, 4, 5, 6, 7, 8}}};
    s.textures = {Texture{.image = 0}};
    s.materials[0].baseColorTexture = 0;
    s.materials[0].alphaMode = AlphaMode::Mask;
    return s;
}

// Every field of what decides a truth, each changed alone.
std::vector<Edit> truthEdits() {
    std::vector<Edit> e;
    const auto light = [&](std::string what, std::function<void(Light&)> f) {
        e.push_back({"light " + what, [f](Scene& s) { f(s.lights[0]); }});
    };
    light("type", [](Light& l) {
        l.type = l.type == LightType::Point ? LightType::Spot : LightType::Point;
    });
    for (int axis = 0; axis < 3; ++axis) {
        light("position " + std::to_string(axis), [axis](Light& l) { l.position[axis] += 0.5f; });
        light("direction " + std::to_string(axis),
              [axis](Light& l) { l.direction[axis] += 0.25f; });
    }
    light("range", [](Light& l) { l.range = 7.0f; });
    light("inner cone", [](Light& l) { l.innerConeAngle = 0.1f; });
    light("outer cone", [](Light& l) { l.outerConeAngle = 0.7f; });
    light("radius", [](Light& l) { l.radius += 0.1f; });
    light("angular diameter", [](Light& l) { l.angularDiameter += 0.5f; });
    light("casts shadow", [](Light& l) { l.castsShadow = false; });
    e.push_back({"a second light", [](Scene& s) { s.lights.push_back(s.lights[0]); }});
    const auto camera = [&](std::string what, std::function<void(Camera&)> f) {
        e.push_back({"camera " + what, [f](Scene& s) { f(s.cameras[0]); }});
    };
    for (int axis = 0; axis < 3; ++axis) {
        camera("position " + std::to_string(axis), [axis](Camera& c) { c.position[axis] += 1; });
        camera("target " + std::to_string(axis), [axis](Camera& c) { c.target[axis] += 1; });
        camera("up " + std::to_string(axis), [axis](Camera& c) { c.up[axis] += 0.5f; });
    }
    camera("yfov", [](Camera& c) { c.yfov = 0.5f; });
    camera("orthographic", [](Camera& c) { c.orthographic = true; });
    camera("ymag", [](Camera& c) { c.ymag = 3.0f; });
    camera("znear", [](Camera& c) { c.znear = 0.5f; });
    camera("zfar", [](Camera& c) { c.zfar = 60.0f; });
    const auto content = [&](std::string what, std::function<void(Scene&)> f) {
        e.push_back({"scene " + what, f});
    };
    for (bool first : {true, false}) { // the last one too: a hash of a prefix misses it
        const auto at = [first](Scene& s) -> Vertex& {
            return first ? s.vertices.front() : s.vertices.back();
        };
        const std::string which = first ? " (first vertex)" : " (last vertex)";
        content("position" + which, [at](Scene& s) { at(s).position.y += 0.01f; });
        content("normal" + which, [at](Scene& s) { at(s).normal.x += 0.5f; });
        content("material" + which, [at](Scene& s) { at(s).material ^= 1u; });
        content("uv" + which, [at](Scene& s) { at(s).uv.y += 0.5f; });
        content("vertex alpha" + which, [at](Scene& s) { at(s).color.w = 0.25f; });
    }
    content("indices", [](Scene& s) { std::swap(s.indices[0], s.indices[1]); });
    content("last index", [](Scene& s) { // the first stays: a hash of a prefix misses it
        std::swap(s.indices.back(), s.indices[s.indices.size() - 2]);
    });
    content("a vertex more", [](Scene& s) { s.vertices.push_back(s.vertices.back()); });
    content("alpha mode", [](Scene& s) { s.materials[0].alphaMode = AlphaMode::Opaque; });
    content("alpha cutoff", [](Scene& s) { s.materials[0].alphaCutoff = 0.3f; });
    content("base alpha", [](Scene& s) { s.materials[0].baseColor.w = 0.5f; });
    content("texture index", [](Scene& s) { s.materials[0].baseColorTexture = -1; });
    content("double sided", [](Scene& s) { s.materials.back().doubleSided ^= true; });
    content("texture image", [](Scene& s) {
        s.images.push_back(s.images[0]);
        s.textures[0].image = 1;
    });
    content("wrap s", [](Scene& s) { s.textures[0].wrapS = TextureWrap::ClampToEdge; });
    content("wrap t", [](Scene& s) { s.textures[0].wrapT = TextureWrap::MirroredRepeat; });
    content("nearest", [](Scene& s) { s.textures[0].nearest = true; });
    content("image width", [](Scene& s) { s.images[0].width = 1, s.images[0].height = 2; });
    content("image texel", [](Scene& s) { s.images[0].rgba.back() = 9; });
    content("transmission", [](Scene& s) { s.materials[0].transmission = 0.5f; });
    content("transmission texture", [](Scene& s) { s.materials[0].transmissionTexture = 0; });
    content("thickness", [](Scene& s) { s.materials[0].thickness = 0.5f; });
    content("attenuation distance", [](Scene& s) { s.materials[0].attenuationDistance = 2.0f; });
    content("attenuation colour", [](Scene& s) { s.materials[0].attenuationColor.y = 0.5f; });
    content("a translucent material's tint", [](Scene& s) {
        s.materials[0].transmission = 0.5f;
        s.materials[0].baseColor.x = 0.1f;
    });
    content("a vertex colour under translucent materials", [](Scene& s) {
        for (Material& m : s.materials)
            m.transmission = 0.5f;
        s.vertices.front().color.x = 0.3f;
    });
    return e;
}

} // namespace

// The names of results and truth files are 64-bit FNV-1a (core/fnv1a.h): the published vectors,
// so that a machine of another build names the same task the same way.
TEST(SweepTasks, NamesAreFnv1aOfWhatTheyName) {
    EXPECT_EQ(hashHex(""), "cbf29ce484222325");
    EXPECT_EQ(hashHex("a"), "af63dc4c8601ec8c");
    EXPECT_EQ(hashHex("foobar"), "85944171f73967e8");
}

TEST(TruthCache, EveryInputOfATruthChangesItsKeyUnderEveryLightType) {
    for (LightType type : {LightType::Directional, LightType::Spot, LightType::Point}) {
        const Scene base = sceneWith(type);
        const std::string name(lightTypeName(type));
        const std::string key = truthKey(base, "c", 64, 48, 16);
        std::set<std::string> keys{key};
        for (const Edit& edit : truthEdits()) {
            Scene s = base;
            edit.apply(s);
            const std::string changed = truthKey(s, "c", 64, 48, 16);
            EXPECT_NE(changed, key) << name << ": " << edit.what;
            keys.insert(changed);
        }
        EXPECT_EQ(keys.size(), truthEdits().size() + 1) << name << ": two edits, one key";
        EXPECT_NE(truthKey(base, "c", 65, 48, 16), key) << name << ": width";
        EXPECT_NE(truthKey(base, "c", 64, 49, 16), key) << name << ": height";
        EXPECT_NE(truthKey(base, "c", 48, 64, 16), key) << name << ": width and height swapped";
        EXPECT_NE(truthKey(base, "c", 64, 48, 17), key) << name << ": samples";
        // What the truth does not read leaves the key alone: names, colours, intensities.
        Scene same = base;
        same.name = "renamed";
        same.lights[0].name = "other";
        same.lights[0].color = glm::vec3(0.2f);
        same.lights[0].intensity = 30.0f;
        same.materials[0].baseColor.x = 0.1f;
        same.vertices[0].color.x = 0.3f;
        same.cameras[0].name = "d";
        EXPECT_EQ(truthKey(same, "d", 64, 48, 16), key) << name;
    }
    // The camera the key names is the one it hashes.
    Scene two = sceneWith(LightType::Spot);
    two.cameras.push_back(Camera{.name = "far", .position = {0, 3, 30}});
    EXPECT_NE(truthKey(two, "far", 64, 48, 16), truthKey(two, "c", 64, 48, 16));
}

namespace {

Plan onePlan() {
    Plan p;
    p.scenes = {{.label = "builtin:showcase", .spec = "builtin:showcase"}};
    p.lights = {{.name = "l",
                 .kind = "spot",
                 .position = glm::vec3(1, 4, 2),
                 .direction = glm::vec3(0, -1, 0),
                 .coneDegrees = 30.0f,
                 .size = 0.2f}};
    p.cameras = {""};
    p.settings = {{.technique = "pcf", .sets = {{"pcf.size", "5"}}}};
    return p;
}

std::string onlyTaskId(const Plan& p) {
    const SweepTasks t = expandTasks(p);
    EXPECT_EQ(t.tasks.size(), 1u);
    return t.tasks.empty() ? "" : t.tasks[0].id;
}

} // namespace

TEST(SweepTasks, EveryFieldOfATaskChangesItsIdAndOnlyThose) {
    const std::string id = onlyTaskId(onePlan());
    const std::vector<std::pair<std::string, std::function<void(Plan&)>>> edits = {
        {"scene", [](Plan& p) { p.scenes[0].label = "builtin:resting"; }},
        {"light kind", [](Plan& p) { p.lights[0].kind = "point"; }},
        {"light size", [](Plan& p) { p.lights[0].size = 0.3f; }},
        {"light position x", [](Plan& p) { p.lights[0].position->x = 2; }},
        {"light position y", [](Plan& p) { p.lights[0].position->y = 5; }},
        {"light position z", [](Plan& p) { p.lights[0].position->z = 3; }},
        {"light without a position", [](Plan& p) { p.lights[0].position.reset(); }},
        {"light direction x", [](Plan& p) { p.lights[0].direction->x = 0.5f; }},
        {"light direction y", [](Plan& p) { p.lights[0].direction->y = -0.5f; }},
        {"light direction z", [](Plan& p) { p.lights[0].direction->z = 0.5f; }},
        {"light without a direction", [](Plan& p) { p.lights[0].direction.reset(); }},
        {"cone", [](Plan& p) { p.lights[0].coneDegrees = 40.0f; }},
        {"no cone", [](Plan& p) { p.lights[0].coneDegrees.reset(); }},
        {"camera", [](Plan& p) { p.cameras[0] = "top"; }},
        {"width", [](Plan& p) { p.width += 1; }},
        {"height", [](Plan& p) { p.height += 1; }},
        {"samples", [](Plan& p) { p.samples += 1; }},
        {"shadow map size", [](Plan& p) { p.shadowMapSize = 2048; }},
        {"frames", [](Plan& p) { p.frames += 1; }},
        {"a time", [](Plan& p) { p.times = {0.5}; }},
        {"another time", [](Plan& p) { p.times = {0.25}; }},
        {"the time 0", [](Plan& p) { p.times = {0.0}; }},
        {"an animation", [](Plan& p) { p.times = {0.5}, p.animation = "1"; }},
        {"technique", [](Plan& p) { p.settings[0].technique = "pcss"; }},
        {"parameter value", [](Plan& p) { p.settings[0].sets[0].second = "7"; }},
        {"parameter name", [](Plan& p) { p.settings[0].sets[0].first = "pcf.samples"; }},
        {"a parameter more", [](Plan& p) {
             p.settings[0].sets.push_back({"pcf.tap", "1"});
         }}};
    std::set<std::string> ids{id};
    for (const auto& [what, edit] : edits) {
        Plan p = onePlan();
        edit(p);
        const std::string changed = onlyTaskId(p);
        EXPECT_NE(changed, id) << what;
        ids.insert(changed);
    }
    EXPECT_EQ(ids.size(), edits.size() + 1) << "two fields, one id";
    // A plan without times keeps the ids it had before times were read: the view is described
    // as it always was.
    EXPECT_EQ(expandTasks(onePlan()).views[0].id,
              hashHex("scene=builtin:showcase;light=kind=spot;size=0.2;pos=1,4,2;dir=0,-1,0;"
                      "cone=30;camera=;size=320x180;samples=64"));
    // Labels and paths do not decide what a task computes.
    Plan same = onePlan();
    same.lights[0].name = "renamed";
    same.scenes[0].spec = "/elsewhere/showcase";
    same.path = "/plans/other.toml";
    EXPECT_EQ(onlyTaskId(same), id);
    // The view's id changes with the view's fields only: a setting is not part of it.
    Plan otherSetting = onePlan();
    otherSetting.settings[0].technique = "hard";
    otherSetting.settings[0].sets.clear();
    EXPECT_EQ(expandTasks(otherSetting).views[0].id, expandTasks(onePlan()).views[0].id);
    Plan otherSize = onePlan();
    otherSize.lights[0].size = 0.0f;
    EXPECT_NE(expandTasks(otherSize).views[0].id, expandTasks(onePlan()).views[0].id);
}

namespace {

TaskRecord costed(const std::string& setting, double rmse, double shadowMs, double visibilityMs) {
    TaskRecord r{.id = setting + "1", .scene = "s", .setting = setting, .technique = "pcf"};
    for (const MetricField& f : kMetricFields) {
        r.metrics[std::string(f.name)] = f.name == "rmse" ? rmse : 0.0;
        r.replicates[std::string(f.name)] = {r.metrics[std::string(f.name)]};
    }
    r.shadowMs = shadowMs;
    r.visibilityMs = visibilityMs;
    r.device = "gpu " + setting;
    return r;
}

} // namespace

// The front of RMSE against shadow time (every pass but the G-buffer), worked out by hand: a
// setting is off it when another has no more of either and less of one. The visibility pass's
// times are ordered against the shadow times, so a front of them differs.
TEST(SweepMerge, TheFrontIsRmseAgainstShadowTimeWorkedOutByHand) {
    const std::vector<TaskRecord> records = {
        costed("a", 0.10, 5.0, 1.0),   // on: nothing cheaper is as good
        costed("b", 0.20, 2.0, 2.0),   // on: the cheapest
        costed("c", 0.30, 3.0, 0.5),   // off: b is better and cheaper
        costed("d", 0.05, 10.0, 9.0),  // on: the best
        costed("e", 0.20, 2.0, 1.5),   // on: b's twin; neither is better in either
        costed("f", 0.15, 6.0, 0.1),   // off: a is better and cheaper
        costed("g", 0.10, 7.0, 0.2),   // off: as good as a, dearer
        costed("h", 0.40, 2.0, 0.05)}; // off: as cheap as b, worse
    const MergeResult m = mergeRecords(records);
    ASSERT_EQ(m.groups.size(), 2u);
    const std::set<std::string> expected = {"a", "b", "d", "e"};
    for (const GroupSummary& g : m.groups) {
        ASSERT_EQ(g.settings.size(), records.size()) << g.name;
        for (size_t i = 0; i < g.settings.size(); ++i) {
            const SettingSummary& s = g.settings[i];
            EXPECT_EQ(s.onFront, expected.count(s.setting) == 1) << g.name << ": " << s.setting;
            EXPECT_EQ(s.views, 1u);
            EXPECT_EQ(s.setting, records[i].setting) << "sorted by name";
            EXPECT_EQ(s.visibilityMs, records[i].visibilityMs) << s.setting;
            EXPECT_EQ(s.shadowMs, records[i].shadowMs) << s.setting;
            EXPECT_EQ(s.devices, std::vector<std::string>{"gpu " + s.setting});
        }
    }
    // A setting without a finite time is on no front and takes no one off it.
    std::vector<TaskRecord> withNan = records;
    withNan.push_back(costed("i", 0.01, NAN, NAN));
    const MergeResult mn = mergeRecords(withNan);
    for (const SettingSummary& s : mn.groups[0].settings)
        EXPECT_EQ(s.onFront, expected.count(s.setting) == 1) << s.setting;
    // The front is of the means over the views: x's two views, (0.25, 7) and (0.05, 1), average
    // to (0.15, 4), on the front (nothing is as good and as cheap), although its first view
    // alone is not.
    std::vector<TaskRecord> two = records;
    two.push_back(costed("x", 0.25, 7.0, 0.0));
    two.push_back(costed("x", 0.05, 1.0, 0.0));
    two.back().id = "x2";
    two.back().scene = "t";
    const MergeResult mx = mergeRecords(two);
    const auto& corpus = mx.groups[0].settings;
    const auto x = std::find_if(corpus.begin(), corpus.end(),
                                [](const SettingSummary& s) { return s.setting == "x"; });
    ASSERT_NE(x, corpus.end());
    EXPECT_NEAR(x->metrics.at("rmse").value, 0.15, 1e-12);
    EXPECT_NEAR(x->shadowMs, 4.0, 1e-12);
    EXPECT_TRUE(x->onFront);
    EXPECT_NEAR(x->visibilityMs, 0.0, 1e-12);
    EXPECT_EQ(x->devices, std::vector<std::string>{"gpu x"}) << "one device, named once";
    for (const SettingSummary& s : corpus)
        EXPECT_TRUE(!s.onFront || (s.setting != "f" && s.setting != "g")) << s.setting;
}

// Records that disagree on what they hold: a view with fewer bootstrap replicates than another
// (the interval takes the replicates both have), a record without a metric (the mean is unknown,
// NaN, and ranks last, 0, never first).
TEST(SweepMerge, UnevenRecordsMergeOnWhatTheyShare) {
    std::vector<TaskRecord> records = {costed("a", 0.2, 1.0, 1.0), costed("a", 0.4, 1.0, 1.0),
                                       costed("b", 0.5, 2.0, 2.0), costed("c", 0.1, 3.0, 3.0)};
    records[1].id = "a2";
    records[1].scene = "t";
    records[0].replicates["rmse"] = {0.25, 0.15, 0.30};
    records[1].replicates["rmse"] = {0.45, 0.35};
    records[3].metrics.erase("acne");
    const MergeResult m = mergeRecords(records);
    const SettingSummary& a = m.groups[0].settings[0];
    ASSERT_EQ(a.setting, "a");
    EXPECT_NEAR(a.metrics.at("rmse").value, 0.3, 1e-12);
    // Replicate-wise means of the two both views have: 0.35 and 0.25; reflected about 0.3.
    EXPECT_NEAR(a.metrics.at("rmse").lo, 2 * 0.3 - 0.35, 1e-3);
    EXPECT_NEAR(a.metrics.at("rmse").hi, 2 * 0.3 - 0.25, 1e-3);
    const SettingSummary& c = m.groups[0].settings[2];
    ASSERT_EQ(c.setting, "c");
    EXPECT_TRUE(std::isnan(c.metrics.at("acne").value));
    EXPECT_EQ(c.metrics.at("acne").rank, 0) << "unknown ranks last";
    EXPECT_EQ(c.metrics.at("rmse").rank, 1);
    EXPECT_EQ(a.metrics.at("acne").rank, 1) << "the others tie";
}
