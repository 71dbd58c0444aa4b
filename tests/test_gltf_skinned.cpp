// Skins and morph targets posed at a time (issue 59): every vertex of a two-joint bar and of a
// morphed triangle is found where the specification's formulas, worked by hand here, put it;
// malformed skins and targets are refused with the file and the JSON path.
#include "gltf_builder.h"
#include "penumbra/error.h"
#include "penumbra/scene.h"
#include "posed_gltf.h"
#include "scratch_dir.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

using namespace penumbra;
using namespace penumbra::test;
namespace fs = std::filesystem;
using J = nlohmann::json;

namespace {

constexpr float kFloat = 5e-6f;

int floats(GltfBuilder& b, const std::vector<float>& v, const char* type, size_t per) {
    return floatAccessor(b, v, type, per);
}

// A bar along x at height 1 (x = 0, 1, 2; z = 0 and 0.2) skinned to two joints: joint 0 at
// (0, 1, 0), joint 1 its child 1.5 further along x. The ends follow one joint each; the middle
// pair half and half. The bar's own node stands at (5, 0, 0), which skinning ignores. "bend"
// turns joint 1 a quarter turn about +z over 1 s.
struct Bar {
    GltfBuilder b;
    int mesh = -1, joint0 = -1, joint1 = -1, barNode = -1;
    int joints = -1, weights = -1, inverseBind = -1;
};

Bar bar() {
    Bar r;
    GltfBuilder& b = r.b;
    b.ground();
    const int pos = b.positions({0, 1, 0, 0, 1, 0.2f, 1, 1, 0, 1, 1, 0.2f, 2, 1, 0, 2, 1, 0.2f});
    const int idx = b.accessor(b.view(std::vector<uint16_t>{0, 1, 2, 2, 1, 3, 2, 3, 4, 4, 3, 5}),
                               5123, 12, "SCALAR");
    r.joints = b.accessor(b.view(std::vector<uint8_t>{0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0,
                                                      0, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}),
                          5121, 6, "VEC4");
    r.weights = floats(
        b, {1, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 0.5f, 0.5f, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0},
        "VEC4", 4);
    // Column-major inverses of the joints' bind transforms: translations by -(0,1,0), -(1.5,1,0).
    r.inverseBind = floats(b, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0,     -1, 0, 1,
                               1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -1.5f, -1, 0, 1},
                           "MAT4", 16);
    r.mesh = b.mesh(pos, idx);
    b.j["meshes"][r.mesh]["primitives"][0]["attributes"]["JOINTS_0"] = r.joints;
    b.j["meshes"][r.mesh]["primitives"][0]["attributes"]["WEIGHTS_0"] = r.weights;
    r.joint1 = b.node({{"translation", {1.5, 0, 0}}}, false);
    r.joint0 = b.node({{"translation", {0, 1, 0}}, {"children", {r.joint1}}});
    r.barNode = b.node({{"mesh", r.mesh}, {"skin", 0}, {"translation", {5, 0, 0}}});
    b.j["skins"] = {{{"joints", {r.joint0, r.joint1}}, {"inverseBindMatrices", r.inverseBind}}};
    const int input = keyframeTimes(b, {0.0f, 1.0f});
    const float h = std::sqrt(0.5f);
    const int turn = floats(b, {0, 0, 0, 1, 0, 0, h, h}, "VEC4", 4);
    b.j["animations"] = {
        {{"name", "bend"},
         {"channels", {{{"sampler", 0}, {"target", {{"node", r.joint1}, {"path", "rotation"}}}}}},
         {"samplers", {{{"input", input}, {"output", turn}}}}}};
    return r;
}

fs::path write(GltfBuilder& b, const std::string& name) {
    return b.writeGltf(scratchDir("skinned", name, true) / "a.gltf");
}

void expectVertexAt(const Scene& s, glm::vec3 want, const std::string& what) {
    float nearest = INFINITY;
    for (const Vertex& v : s.vertices)
        nearest = std::min(nearest, glm::length(v.position - want));
    EXPECT_LT(nearest, kFloat) << what << ": no vertex at (" << want.x << ", " << want.y << ", "
                               << want.z << ")";
}

// The bar's six vertices with joint 1 turned by `a` radians about +z: a point p that follows
// joint 1 turns about its pivot (1.5, 1, 0); the middle pair averages that with staying put.
std::vector<glm::vec3> barAt(float a) {
    const auto turned = [a](glm::vec3 p) {
        const glm::vec3 r = p - glm::vec3(1.5f, 1, 0);
        return glm::vec3(1.5f + r.x * std::cos(a) - r.y * std::sin(a),
                         1 + r.x * std::sin(a) + r.y * std::cos(a), p.z);
    };
    std::vector<glm::vec3> out;
    for (const float z : {0.0f, 0.2f}) {
        out.push_back({0, 1, z});
        out.push_back(0.5f * (glm::vec3(1, 1, z) + turned({1, 1, z})));
        out.push_back(turned({2, 1, z}));
    }
    return out;
}

// The `vertices` vertices above the ground face up, and its `triangles` triangles are wound
// counter-clockwise seen from above, as their normals face: the rasterizer culls by the winding.
void expectRaisedFacesUp(const Scene& s, size_t vertices, size_t triangles) {
    size_t facing = 0;
    for (const Vertex& v : s.vertices)
        facing += v.position.y > 0.5f && glm::length(v.normal - glm::vec3(0, 1, 0)) < kFloat;
    EXPECT_EQ(facing, vertices) << "vertices above the ground face up";
    size_t up = 0, raised = 0;
    for (size_t t = 0; t < s.triangleCount(); ++t) {
        const glm::vec3 a = s.vertices[s.indices[3 * t]].position,
                        b = s.vertices[s.indices[3 * t + 1]].position,
                        c = s.vertices[s.indices[3 * t + 2]].position;
        if (a.y < 0.5f)
            continue;
        ++raised;
        up += glm::cross(b - a, c - a).y > 0.0f;
    }
    EXPECT_EQ(raised, triangles);
    EXPECT_EQ(up, raised) << "triangles above the ground wound to face up";
}

// The bar's six vertices and four triangles.
void expectBarFacesUp(const Scene& s) {
    expectRaisedFacesUp(s, 6, 4);
}

using Bad = Refusal<Bar>;

} // namespace

TEST(GltfSkinned, VerticesFollowTheirJointsAndTheMeshNodeIsIgnored) {
    Bar r = bar();
    const fs::path f = write(r.b, "bend");
    for (const double t : {0.0, 0.5, 1.0}) {
        const Scene s = loadAt(f, t);
        const float a = static_cast<float>(t * std::numbers::pi / 2);
        for (const glm::vec3& p : barAt(a))
            expectVertexAt(s, p, "bend at " + std::to_string(t));
    }
    // At rest the joints stand where they were bound: the bar as stored, not at (5, 0, 0).
    std::vector<std::string> warnings;
    const Scene rest = loadAt(f, std::nullopt, "", &warnings);
    for (const glm::vec3& p : barAt(0.0f))
        expectVertexAt(rest, p, "at rest");
    for (const std::string& w : warnings)
        EXPECT_EQ(w.find("skin(s) ignored"), std::string::npos) << "skins are used: " << w;
}

// A skin whose joints mirror the bar, without NORMAL: the faces' normals are made in bind space
// as the mesh winds them, and mirrored with it: the bar still faces up (+y is its own mirror).
TEST(GltfSkinned, AMirroringSkinWithoutNormalsKeepsTheFacesSide) {
    Bar r = bar();
    r.b.j["nodes"][r.joint0]["scale"] = {-1, 1, 1};
    expectBarFacesUp(loadAt(write(r.b, "mirroring-skin"), std::nullopt));
}

// A ridge of two slopes skinned to one joint at rest, without NORMAL: each vertex's normal is the
// area-weighted sum of the faces of every triangle it is a corner of (the cross product of its
// edges, whose length is twice its area), as the test sums them.
TEST(GltfSkinned, NormalsMadeForASkinSumEveryTrianglesFace) {
    GltfBuilder b;
    const int pos =
        b.positions({0, 1, 0, 0, 1, 1, -1, 0.5f, 0, -1, 0.5f, 1, 1, 0.2f, 0, 1, 0.2f, 1});
    const int idx = b.accessor(b.view(std::vector<uint16_t>{2, 3, 0, 0, 3, 1, 0, 1, 4, 4, 1, 5}),
                               5123, 12, "SCALAR");
    const int mesh = b.mesh(pos, idx);
    J& attributes = b.j["meshes"][mesh]["primitives"][0]["attributes"];
    attributes["JOINTS_0"] = b.accessor(b.view(std::vector<uint8_t>(24, 0)), 5121, 6, "VEC4");
    std::vector<float> weights;
    for (int v = 0; v < 6; ++v)
        weights.insert(weights.end(), {1, 0, 0, 0});
    attributes["WEIGHTS_0"] = floats(b, weights, "VEC4", 4);
    const int joint = b.node({{"translation", {0, 0, 0}}});
    b.node({{"mesh", mesh}, {"skin", 0}});
    b.j["skins"] = {{{"joints", {joint}}}};
    const Scene s = loadAt(write(b, "ridge"), std::nullopt);
    ASSERT_EQ(s.triangleCount(), 4u);
    std::vector<glm::vec3> want(s.vertices.size(), glm::vec3(0.0f));
    for (size_t t = 0; t < s.triangleCount(); ++t) {
        const uint32_t* c = &s.indices[3 * t];
        const glm::vec3 face = glm::cross(s.vertices[c[1]].position - s.vertices[c[0]].position,
                                          s.vertices[c[2]].position - s.vertices[c[0]].position);
        for (int k = 0; k < 3; ++k)
            want[c[k]] += face;
    }
    for (size_t v = 0; v < s.vertices.size(); ++v)
        EXPECT_GT(glm::dot(glm::normalize(s.vertices[v].normal), glm::normalize(want[v])),
                  1.0f - 1e-5f)
            << "vertex " << v;
}

// One primitive of two quads, the first on a plain joint and the second on a mirroring one
// (joints as unsigned shorts, no inverse bind matrices: identities): each triangle is wound by
// its own joints, so both quads face up where they land, the mirrored one at x in [-3, -2].
TEST(GltfSkinned, EachTriangleOfASkinIsWoundByItsOwnJoints) {
    GltfBuilder b;
    b.ground();
    const int pos =
        b.positions({0, 1, 0, 1, 1, 0, 1, 1, 1, 0, 1, 1, 2, 1, 0, 3, 1, 0, 3, 1, 1, 2, 1, 1});
    const int idx = b.accessor(b.view(std::vector<uint16_t>{0, 2, 1, 0, 3, 2, 4, 6, 5, 4, 7, 6}),
                               5123, 12, "SCALAR");
    const int joints =
        b.accessor(b.view(std::vector<uint16_t>{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
                                                1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}),
                   5123, 8, "VEC4");
    std::vector<float> one;
    for (int v = 0; v < 8; ++v)
        one.insert(one.end(), {1, 0, 0, 0});
    const int weights = floats(b, one, "VEC4", 4);
    const int mesh = b.mesh(pos, idx);
    b.j["meshes"][mesh]["primitives"][0]["attributes"]["JOINTS_0"] = joints;
    b.j["meshes"][mesh]["primitives"][0]["attributes"]["WEIGHTS_0"] = weights;
    const int plain = b.node(J::object());
    const int mirror = b.node({{"scale", {-1, 1, 1}}});
    b.node({{"mesh", mesh}, {"skin", 0}});
    b.j["skins"] = {{{"joints", {plain, mirror}}}};
    const Scene s = loadAt(write(b, "two-quads"), std::nullopt);
    expectVertexAt(s, {-3, 1, 0}, "the mirrored quad's far corner");
    expectVertexAt(s, {1, 1, 1}, "the plain quad's corner");
    expectRaisedFacesUp(s, 8, 4);
}

// Two skins over the same joints in opposite orders, each with a mesh whose JOINTS_0 names them
// in its skin's order: both bars bend alike, so each skin reads its own joints.
TEST(GltfSkinned, EachSkinReadsItsOwnJoints) {
    Bar r = bar();
    GltfBuilder& b = r.b;
    const int swapped = b.accessor(b.view(std::vector<uint8_t>{1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0,
                                                               1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}),
                                   5121, 6, "VEC4");
    const int reversedBind = floats(b, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -1.5f, -1, 0, 1,
                                        1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0,     -1, 0, 1},
                                    "MAT4", 16);
    J mesh = b.j["meshes"][r.mesh];
    mesh["primitives"][0]["attributes"]["JOINTS_0"] = swapped;
    b.j["meshes"].push_back(mesh);
    const int second = static_cast<int>(b.j["meshes"].size()) - 1;
    b.j["skins"].push_back(
        {{"joints", {r.joint1, r.joint0}}, {"inverseBindMatrices", reversedBind}});
    b.node({{"mesh", second}, {"skin", 1}});
    const Scene s = loadAt(write(b, "two-skins"), 0.5);
    ASSERT_EQ(s.skinning.joints.size(), 4u) << "two joints a skin";
    ASSERT_EQ(s.skinning.vertices.size(), 12u);
    for (const glm::vec3& want : barAt(static_cast<float>(std::numbers::pi / 4))) {
        size_t near = 0;
        for (const Vertex& v : s.vertices)
            near += glm::length(v.position - want) < kFloat;
        EXPECT_EQ(near, 2u) << "both bars at (" << want.x << ", " << want.y << ", " << want.z
                            << ")";
    }
}

TEST(GltfSkinned, NormalsTurnWithTheirJointsAndAMirroringMeshNodeFlipsNothing) {
    Bar r = bar();
    GltfBuilder& b = r.b;
    const int up = floats(
        b, std::vector<float>{0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0}, "VEC3", 3);
    b.j["meshes"][r.mesh]["primitives"][0]["attributes"]["NORMAL"] = up;
    const float h = std::sqrt(0.5f); // the ignored mesh node turns a quarter about +z
    b.j["nodes"][r.barNode]["rotation"] = {0, 0, h, h};
    const fs::path f = write(b, "normals");
    const auto hasNormal = [](const Scene& s, glm::vec3 n) {
        for (const Vertex& v : s.vertices)
            if (glm::length(v.normal - n) < kFloat)
                return true;
        return false;
    };
    expectBarFacesUp(loadAt(f, 0.0)); // the mesh node turns no normal
    // The far end follows joint 1 a quarter turn about +z: up becomes -x.
    EXPECT_TRUE(hasNormal(loadAt(f, 1.0), {-1, 0, 0}));
    EXPECT_TRUE(hasNormal(loadAt(f, 0.5), {-std::sqrt(0.5f), std::sqrt(0.5f), 0}));
    // A joint scaled unevenly: normals take the inverse transpose and stay perpendicular to the
    // surface, so (1, 1, 0) under a scale of 2 along x leans to +y, as (1/2, 1, 0) does.
    Bar slanted = bar();
    const float c = std::sqrt(0.5f);
    const int leaning =
        floats(slanted.b, std::vector<float>{c, c, 0, c, c, 0, c, c, 0, c, c, 0, c, c, 0, c, c, 0},
               "VEC3", 3);
    slanted.b.j["meshes"][slanted.mesh]["primitives"][0]["attributes"]["NORMAL"] = leaning;
    slanted.b.j["nodes"][slanted.joint0]["scale"] = {2, 1, 1};
    const Scene stretched = loadAt(write(slanted.b, "stretched"), std::nullopt);
    EXPECT_TRUE(hasNormal(stretched, glm::normalize(glm::vec3(0.5f, 1, 0))));
    // Without NORMAL the faces' own (+y, as wound) hold though the ignored mesh node mirrors.
    b.j["meshes"][r.mesh]["primitives"][0]["attributes"].erase("NORMAL");
    b.j["nodes"][r.barNode]["scale"] = {-1, 1, 1};
    expectBarFacesUp(loadAt(write(b, "mirrored"), std::nullopt));
}

TEST(GltfSkinned, WeightsOfNormalizedBytesAreScaledToSumToOne) {
    Bar r = bar();
    GltfBuilder& b = r.b;
    // 255 is 1; the middle pair's 100 and 100 sum to 200/255 and are scaled to a half each.
    const int bytes =
        b.accessor(b.view(std::vector<uint8_t>{255, 0,   0, 0, 255, 0, 0, 0, 100, 100, 0, 0,
                                               100, 100, 0, 0, 255, 0, 0, 0, 255, 0,   0, 0}),
                   5121, 6, "VEC4", true);
    b.j["meshes"][r.mesh]["primitives"][0]["attributes"]["WEIGHTS_0"] = bytes;
    const Scene s = loadAt(write(b, "byte-weights"), 1.0);
    for (const glm::vec3& p : barAt(static_cast<float>(std::numbers::pi / 2)))
        expectVertexAt(s, p, "byte weights at 1 s");
    // The GPU sums them as they are: each vertex's influences sum to 1, and none is 0.
    for (const SkinnedVertex& sv : s.skinning.vertices) {
        float sum = 0.0f;
        for (uint32_t k = sv.firstInfluence; k < sv.firstInfluence + sv.influenceCount; ++k) {
            EXPECT_GT(s.skinning.influences[k].weight, 0.0f);
            sum += s.skinning.influences[k].weight;
        }
        EXPECT_NEAR(sum, 1.0f, 1e-6f);
    }
}

// Weights near the float's limit sum in double: 3e38 and 3e38 are a half each, not an
// overflow to infinity.
TEST(GltfSkinned, WeightsNearTheFloatsLimitAreScaledLikeSmallOnes) {
    Bar r = bar();
    r.b.j["accessors"][r.weights]["bufferView"] = r.b.view(std::vector<float>{
        1, 0, 0, 0, 1, 0, 0, 0, 3e38f, 3e38f, 0, 0, 3e38f, 3e38f, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0});
    const Scene s = loadAt(write(r.b, "huge-weights"), 1.0);
    for (const glm::vec3& p : barAt(static_cast<float>(std::numbers::pi / 2)))
        expectVertexAt(s, p, "huge weights at 1 s");
}

// Every one of a set's four slots counts: the middle pair's second joint in the fourth slot,
// the far end's only joint in the third.
TEST(GltfSkinned, EachOfASetsFourInfluencesCounts) {
    Bar r = bar();
    GltfBuilder& b = r.b;
    b.j["accessors"][r.joints]["bufferView"] = b.view(std::vector<uint8_t>{
        0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 0});
    b.j["accessors"][r.weights]["bufferView"] = b.view(std::vector<float>{
        1, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0, 0, 0.5f, 0.5f, 0, 0, 0.5f, 0, 0, 1, 0, 0, 0, 1, 0});
    const Scene s = loadAt(write(b, "four-slots"), 1.0);
    for (const glm::vec3& p : barAt(static_cast<float>(std::numbers::pi / 2)))
        expectVertexAt(s, p, "slots 3 and 4 at 1 s");
}

TEST(GltfSkinned, ASecondSetOfJointsAndWeightsAddsToTheFirst) {
    Bar r = bar();
    GltfBuilder& b = r.b;
    // The far end's weight split between the sets: half on joint 1 in the first, half on joint
    // 0 in the second, so that it moves as the middle pair does (half turned, half still).
    b.j["accessors"][r.weights]["bufferView"] = b.view(std::vector<float>{
        1, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 0.5f, 0.5f, 0, 0, 0.5f, 0, 0, 0, 0.5f, 0, 0, 0});
    const int joints0 = b.accessor(b.view(std::vector<uint8_t>(24, 0)), 5121, 6, "VEC4");
    const int weights1 =
        floats(b, {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0.5f, 0, 0, 0},
               "VEC4", 4);
    b.j["meshes"][r.mesh]["primitives"][0]["attributes"]["JOINTS_1"] = joints0;
    b.j["meshes"][r.mesh]["primitives"][0]["attributes"]["WEIGHTS_1"] = weights1;
    const fs::path f = write(b, "two-sets");
    const Scene s = loadAt(f, 1.0);
    const std::vector<glm::vec3> turned = barAt(static_cast<float>(std::numbers::pi / 2));
    for (size_t v = 0; v < turned.size(); ++v) {
        const bool farEnd = v % 3 == 2; // barAt: x = 0, 1, 2 for each z
        const glm::vec3 still(2, 1, v < 3 ? 0.0f : 0.2f);
        expectVertexAt(s, farEnd ? 0.5f * (still + turned[v]) : turned[v], "two sets at 1 s");
    }
}

TEST(GltfSkinned, MorphWeightsMoveVerticesAndNormalsFromTheMeshTheNodeOrTheAnimation) {
    GltfBuilder b;
    b.ground();
    const int pos = b.positions({0, 1, 0, 1, 1, 0, 0, 1, 1});
    const int up = floats(b, {0, 1, 0, 0, 1, 0, 0, 1, 0}, "VEC3", 3);
    const int alongX = floats(b, {1, 0, 0, 1, 0, 0, 1, 0, 0}, "VEC3", 3);
    const int alongZ = floats(b, {0, 0, 2, 0, 0, 2, 0, 0, 2}, "VEC3", 3);
    const int tilt = floats(b, {1, -1, 0, 1, -1, 0, 1, -1, 0}, "VEC3", 3);
    const int mesh = b.mesh(pos);
    b.j["meshes"][mesh]["primitives"][0]["attributes"]["NORMAL"] = up;
    b.j["meshes"][mesh]["primitives"][0]["targets"] = {{{"POSITION", alongX}, {"NORMAL", tilt}},
                                                       {{"POSITION", alongZ}}};
    b.j["meshes"][mesh]["weights"] = {0.25, 0};
    const int node = b.node({{"mesh", mesh}});
    const int input = keyframeTimes(b, {0.0f, 1.0f, 2.0f});
    const int weights = floats(b, {0, 0, 1, 0, 0, 1}, "SCALAR", 1);
    b.j["animations"] = {
        {{"channels", {{{"sampler", 0}, {"target", {{"node", node}, {"path", "weights"}}}}}},
         {"samplers", {{{"input", input}, {"output", weights}}}}}};
    const fs::path f = write(b, "morph");
    const auto expectTriangleAt = [](const Scene& s, glm::vec3 offset, glm::vec3 normal,
                                     const std::string& what) {
        for (const glm::vec3 corner : {glm::vec3(0, 1, 0), glm::vec3(1, 1, 0), glm::vec3(0, 1, 1)})
            expectVertexAt(s, corner + offset, what);
        bool found = false;
        for (const Vertex& v : s.vertices)
            found = found || glm::length(v.normal - glm::normalize(normal)) < kFloat;
        EXPECT_TRUE(found) << what << ": no normal along (" << normal.x << ", " << normal.y << ", "
                           << normal.z << ")";
    };
    // At rest the mesh's default weights: a quarter of the x nudge and of the tilt.
    expectTriangleAt(loadAt(f, std::nullopt), {0.25f, 0, 0}, {0.25f, 0.75f, 0}, "mesh weights");
    // Animated, 1.5 s: halfway from (1, 0) to (0, 1).
    expectTriangleAt(loadAt(f, 1.5), {0.5f, 0, 1}, {0.5f, 0.5f, 0}, "animated at 1.5 s");
    // The node's own weights win over the mesh's.
    b.j["nodes"][node]["weights"] = {0, 0.75};
    const fs::path own = write(b, "morph-node");
    expectTriangleAt(loadAt(own, std::nullopt), {0, 0, 1.5f}, {0, 1, 0}, "node weights");
}

namespace {

class GltfSkinnedRefused : public ::testing::TestWithParam<Bad> {};

} // namespace

TEST_P(GltfSkinnedRefused, WithTheFileAndItsJsonPath) {
    Bar r = bar();
    GetParam().change(r);
    const fs::path f = write(r.b, std::string("refused-") + GetParam().name);
    expectRefusedAtRestAndPosed(f, GetParam().expected);
}

INSTANTIATE_TEST_SUITE_P(
    SkinsAndTargets, GltfSkinnedRefused,
    ::testing::Values(
        Bad{"joint_past_the_skins_joints",
            [](Bar& r) {
                r.b.j["accessors"][r.joints]["bufferView"] = r.b.view(std::vector<uint8_t>{
                    0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 0, 0});
            },
            "meshes[1].primitives[0].attributes.JOINTS_0: vertex 4's joint 2 is past skins[0]'s "
            "2 joints"},
        Bad{"joint_node_out_of_range", [](Bar& r) { r.b.j["skins"][0]["joints"][1] = 9; },
            "skins[0].joints[1]: index 9 is out of range (4 nodes)"},
        Bad{"joint_twice", [](Bar& r) { r.b.j["skins"][0]["joints"][1] = r.joint0; },
            "skins[0].joints[1]: nodes[2] is joints[0] already"},
        Bad{"too_few_inverse_bind_matrices",
            [](Bar& r) { r.b.j["accessors"][r.inverseBind]["count"] = 1; },
            "skins[0].inverseBindMatrices: accessors[6] holds 1 matrices for 2 joints"},
        Bad{"inverse_bind_matrices_not_mat4",
            [](Bar& r) {
                r.b.j["skins"][0]["inverseBindMatrices"] =
                    floats(r.b, std::vector<float>(32, 1.0f), "VEC4", 4);
            },
            "skins[0].inverseBindMatrices: accessors[9] is not MAT4 floats"},
        Bad{"joints_of_floats",
            [](Bar& r) {
                r.b.j["meshes"][r.mesh]["primitives"][0]["attributes"]["JOINTS_0"] = r.weights;
            },
            "meshes[1].primitives[0].attributes.JOINTS_0: accessors[5] is not VEC4 unsigned "
            "bytes or shorts"},
        Bad{"weights_of_plain_bytes",
            [](Bar& r) {
                r.b.j["meshes"][r.mesh]["primitives"][0]["attributes"]["WEIGHTS_0"] = r.joints;
            },
            "meshes[1].primitives[0].attributes.WEIGHTS_0: accessors[4] is not VEC4 floats or "
            "normalized unsigned bytes or shorts"},
        Bad{"weights_all_zero",
            [](Bar& r) {
                r.b.j["accessors"][r.weights]["bufferView"] =
                    r.b.view(std::vector<float>{1,    0,    0, 0, 0, 0, 0, 0, 0.5f, 0.5f, 0, 0,
                                                0.5f, 0.5f, 0, 0, 1, 0, 0, 0, 1,    0,    0, 0});
            },
            "meshes[1].primitives[0].attributes.WEIGHTS_0: vertex 1's weights sum to 0"},
        Bad{"weight_below_zero",
            [](Bar& r) {
                r.b.j["accessors"][r.weights]["bufferView"] =
                    r.b.view(std::vector<float>{1,    0,    0, 0, 1, 0, 0, 0, 1.5f, -0.5f, 0, 0,
                                                0.5f, 0.5f, 0, 0, 1, 0, 0, 0, 1,    0,     0, 0});
            },
            "meshes[1].primitives[0].attributes.WEIGHTS_0: vertex 2's weight 1 is -0.5; weights "
            "are 0 or more"},
        Bad{"joints_normalized", [](Bar& r) { r.b.j["accessors"][r.joints]["normalized"] = true; },
            "meshes[1].primitives[0].attributes.JOINTS_0: accessors[4] is not VEC4 unsigned "
            "bytes or shorts"},
        Bad{"second_joints_without_weights",
            [](Bar& r) {
                r.b.j["meshes"][r.mesh]["primitives"][0]["attributes"]["JOINTS_1"] = r.joints;
            },
            "meshes[1].primitives[0].attributes: JOINTS_1 and WEIGHTS_1 come in pairs; WEIGHTS_1 "
            "is missing"},
        Bad{"second_weights_without_joints",
            [](Bar& r) {
                r.b.j["meshes"][r.mesh]["primitives"][0]["attributes"]["WEIGHTS_1"] = r.weights;
            },
            "meshes[1].primitives[0].attributes: JOINTS_1 and WEIGHTS_1 come in pairs; JOINTS_1 "
            "is missing"},
        Bad{"inverse_bind_matrices_of_shorts",
            [](Bar& r) { r.b.j["accessors"][r.inverseBind]["componentType"] = 5123; },
            "skins[0].inverseBindMatrices: accessors[6] is not MAT4 floats"},
        Bad{"inverse_bind_matrix_not_finite",
            [](Bar& r) {
                std::vector<float> values(32, 0.0f);
                for (int i = 0; i < 4; ++i)
                    values[5 * i] = values[16 + 5 * i] = 1.0f;
                values[16 + 13] = INFINITY;
                r.b.j["accessors"][r.inverseBind]["bufferView"] = r.b.view(values);
            },
            "skins[0].inverseBindMatrices: matrix 1 is not finite"},
        Bad{"skeleton_out_of_range", [](Bar& r) { r.b.j["skins"][0]["skeleton"] = 4; },
            "skins[0].skeleton: index 4 is out of range (4 nodes)"},
        Bad{"skin_without_joints", [](Bar& r) { r.b.j["skins"][0]["joints"] = J::array(); },
            "skins[0].joints: no joints"},
        Bad{"skin_without_joints_attribute",
            [](Bar& r) {
                r.b.j["meshes"][r.mesh]["primitives"][0]["attributes"].erase("JOINTS_0");
            },
            "nodes[3]: skins[0] needs JOINTS_0 and WEIGHTS_0 in meshes[1].primitives[0]"},
        Bad{"node_weights_without_targets",
            [](Bar& r) { r.b.j["nodes"][r.barNode]["weights"] = {0.5}; },
            "nodes[3].weights: 1 weights for 0 morph targets"},
        Bad{"skin_without_mesh", [](Bar& r) { r.b.j["nodes"][r.joint1]["skin"] = 0; },
            "nodes[1].skin: a skin without a mesh to deform"},
        Bad{"morph_target_counts_differ",
            [](Bar& r) {
                J second = r.b.j["meshes"][r.mesh]["primitives"][0];
                second["targets"] = {{{"POSITION", r.b.positions(std::vector<float>(18, 0.0f))}}};
                r.b.j["meshes"][r.mesh]["primitives"].push_back(second);
            },
            "meshes[1].primitives[1].targets: 1 morph targets; primitives[0] has 0"},
        Bad{"morph_target_not_vec3",
            [](Bar& r) {
                r.b.j["meshes"][r.mesh]["primitives"][0]["targets"] = {
                    {{"POSITION", floats(r.b, std::vector<float>(12, 0.0f), "VEC2", 2)}}};
            },
            "meshes[1].primitives[0].targets[0].POSITION: accessors[9] is not VEC3"},
        Bad{"morph_weights_of_another_length",
            [](Bar& r) {
                r.b.j["meshes"][r.mesh]["primitives"][0]["targets"] = {
                    {{"POSITION", r.b.positions(std::vector<float>(18, 0.0f))}}};
                r.b.j["meshes"][r.mesh]["weights"] = {0.5, 0.5};
            },
            "meshes[1].weights: 2 weights for 1 morph targets"},
        Bad{"morph_target_of_another_count",
            [](Bar& r) {
                r.b.j["meshes"][r.mesh]["primitives"][0]["targets"] = {
                    {{"POSITION", r.b.positions({0, 0, 0, 0, 0, 0, 0, 0, 0})}}};
            },
            "meshes[1].primitives[0].targets[0].POSITION: accessors[9] has 3 elements for the "
            "primitive's 6 vertices"}),
    [](const auto& row) { return std::string(row.param.name); });
