// The audit behind sdf.refuse (src/reference/visibility_audit.h) on the CPU: which pixels it
// reads, what it measures them against, and where it refuses. The G-buffer is a synthetic grid on
// the plane under a sphere; the "techniques" are the ground truth itself, made wrong on purpose.
#include "analytic_scenes.h"
#include "penumbra/reference.h"
#include "reference/visibility_audit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace penumbra;
using namespace penumbra::test;

namespace {

// What sdf's refusals name (its module's DistanceFieldDecl, the plain depth test).
const AuditNames kSdfNames{.technique = "sdf",
                           .plain = "hard",
                           .refuseKey = "sdf.refuse",
                           .resolutionKey = "sdf.resolution"};

constexpr uint32_t kWidth = 256, kHeight = 144; // a grid every 2 pixels: 128 x 72

// Pixels on the plane y = 0 over the sphere's shadow under acceptanceSun, 3.2 x 1.8 units.
RenderResult planeView() {
    RenderResult g{.width = kWidth, .height = kHeight};
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            const float px = 0.4f + 3.2f * ((float(x) + 0.5f) / kWidth - 0.5f);
            const float pz = 0.3f + 1.8f * ((float(y) + 0.5f) / kHeight - 0.5f);
            g.position.insert(g.position.end(), {px, 0.0f, pz});
            g.normal.insert(g.normal.end(), {0.0f, 1.0f, 0.0f});
        }
    return g;
}

bool gridCentre(size_t i) { // the pixel the audit reads in its 2 x 2 cell
    return (i % kWidth) % 2 == 1 && (i / kWidth) % 2 == 1;
}

struct Views {
    Scene scene = sphereOverPlane(acceptanceSun(6.0f));
    RenderResult gbuffer = planeView();
    ReferenceResult truth = computeReference(scene, gbuffer, {.samples = 256});
    // `visibility` at the grid's centres, its opposite everywhere else: reading any other pixel
    // of a cell shows as a large error.
    RenderResult technique(const std::vector<float>& visibility) const {
        RenderResult r = gbuffer;
        r.visibility = {visibility};
        for (size_t i = 0; i < visibility.size(); ++i)
            if (!gridCentre(i))
                r.visibility[0][i] = 1.0f - visibility[i];
        return r;
    }
    std::vector<float> centreRays() const { // an exact hard shadow
        std::vector<float> v;
        for (float d : truth.occluderDistance[0])
            v.push_back(std::isinf(d) ? 1.0f : 0.0f);
        return v;
    }
};

const Views& views() {
    static const Views v;
    return v;
}

} // namespace

TEST(Audit, ReadsEachCellsCentreAgainstTheRays) {
    const Views& v = views();
    const RenderResult soft = v.technique(v.truth.visibility[0]);
    const RenderResult hard = v.technique(v.centreRays());
    const VisibilityAudit audit = auditVisibility(v.scene, soft, hard);
    EXPECT_EQ(audit.stride, 2u);
    EXPECT_EQ(audit.pixels, uint64_t{128} * 72);
    // The hard shadow's error over the cells' centres, from the full view's truth: the audit's
    // rays are another draw of the same estimate (256 rays a pixel).
    double squared = 0.0;
    size_t count = 0;
    for (size_t i = 0; i < v.truth.visibility[0].size(); ++i)
        if (gridCentre(i)) {
            const double e = v.centreRays()[i] - v.truth.visibility[0][i];
            squared += e * e, ++count;
        }
    const double expectedHard = std::sqrt(squared / double(count));
    ASSERT_GT(expectedHard, 0.05) << "the view must hold a penumbra";
    EXPECT_NEAR(audit.hardRmse, expectedHard, 0.1 * expectedHard);
    // Two draws of 256 rays differ by about 0.03 RMS in the penumbra only.
    EXPECT_LT(audit.rmse, 0.2 * expectedHard);
    EXPECT_EQ(auditRefusal(audit, 1.5, kSdfNames), "");
    // The same pictures swapped: the audited one now errs as hard does, against a perfect hard.
    const VisibilityAudit swapped = auditVisibility(v.scene, hard, soft);
    EXPECT_NEAR(swapped.rmse, audit.hardRmse, 1e-9);
    EXPECT_NEAR(swapped.hardRmse, audit.rmse, 1e-9);
    EXPECT_NE(auditRefusal(swapped, 1.5, kSdfNames), "");
    EXPECT_EQ(auditRefusal(swapped, 0.0, kSdfNames), "") << "sdf.refuse=0 never refuses";
}

TEST(Audit, CountsTheShadowLostAndAdded) {
    const Views& v = views();
    const RenderResult hard = v.technique(v.centreRays());
    const std::vector<float> ones(size_t{kWidth} * kHeight, 1.0f), zeros(ones.size(), 0.0f);
    const VisibilityAudit lit = auditVisibility(v.scene, v.technique(ones), hard);
    EXPECT_EQ(lit.lost, 1.0);
    EXPECT_EQ(lit.added, 0.0);
    const VisibilityAudit dark = auditVisibility(v.scene, v.technique(zeros), hard);
    EXPECT_EQ(dark.lost, 0.0);
    EXPECT_EQ(dark.added, 1.0);
    // compare's leak and acne, away from the edges: every settled umbra pixel leaks in the lit
    // picture, every settled lit one is acne in the dark one; a soft shadow that is right has
    // neither.
    EXPECT_GT(lit.umbra, 100u);
    EXPECT_EQ(lit.leaked, lit.umbra);
    EXPECT_EQ(lit.acne, 0u);
    EXPECT_GT(dark.fullyLit, 1000u);
    EXPECT_EQ(dark.acne, dark.fullyLit);
    EXPECT_EQ(dark.leaked, 0u);
    EXPECT_EQ(dark.umbra, lit.umbra);
    const VisibilityAudit right =
        auditVisibility(v.scene, v.technique(v.truth.visibility[0]), hard);
    EXPECT_EQ(right.leaked, 0u);
    EXPECT_EQ(right.acne, 0u);

    const std::string reason = auditRefusal(lit, 1.5, kSdfNames);
    EXPECT_NE(reason.find("loses 100.0% of the shadowed pixels"), std::string::npos) << reason;
    EXPECT_NE(reason.find("sdf.refuse=0"), std::string::npos) << reason;
    EXPECT_NE(reason.find("sdf.resolution"), std::string::npos) << reason;
}

// Under a sun without size the umbra's cells border lit ones: those on the edge are left out, as
// compare leaves out pixels within 2 of a shadow's edge.
TEST(Audit, LeavesTheUmbrasEdgeOut) {
    const Scene scene = sphereOverPlane(acceptanceSun(0.0f));
    RenderResult view = planeView();
    const ReferenceResult truth = computeReference(scene, view, {.samples = 1});
    view.visibility = {std::vector<float>(size_t{kWidth} * kHeight, 1.0f)};
    const VisibilityAudit audit = auditVisibility(scene, view, view);
    const auto shadowed = [&](int x, int y) { // grid cell (x, y), off the grid: not
        return x >= 0 && y >= 0 && x < int(kWidth / 2) && y < int(kHeight / 2) &&
               truth.visibility[0][size_t(2 * y + 1) * kWidth + size_t(2 * x + 1)] == 0.0f;
    };
    uint64_t cells = 0, inside = 0;
    for (int y = 0; y < int(kHeight / 2); ++y)
        for (int x = 0; x < int(kWidth / 2); ++x)
            if (shadowed(x, y)) {
                ++cells;
                const bool edge = (x > 0 && !shadowed(x - 1, y)) ||
                                  (x + 1 < int(kWidth / 2) && !shadowed(x + 1, y)) ||
                                  (y > 0 && !shadowed(x, y - 1)) ||
                                  (y + 1 < int(kHeight / 2) && !shadowed(x, y + 1));
                inside += !edge;
            }
    ASSERT_GT(cells, inside + 20) << "the view must hold an edge";
    EXPECT_EQ(audit.umbra, inside);
    EXPECT_EQ(audit.leaked, inside);
}

TEST(Audit, CountsOnlyThePixelsTheLightsMaskKeeps) {
    const Views& v = views();
    const RenderResult hard = v.technique(v.centreRays());
    std::vector<std::vector<uint8_t>> left(1);
    for (size_t i = 0; i < size_t{kWidth} * kHeight; ++i)
        left[0].push_back(i % kWidth < kWidth / 2);
    // The left half of the view: wrong everywhere, which the audit counts; the right half read
    // exactly, which it may not count.
    std::vector<float> visibility = v.truth.visibility[0];
    for (size_t i = 0; i < visibility.size(); ++i)
        if (i % kWidth < kWidth / 2)
            visibility[i] = 1.0f - visibility[i];
    const VisibilityAudit audit = auditVisibility(v.scene, v.technique(visibility), hard, left);
    EXPECT_EQ(audit.pixels, uint64_t{64} * 72);
    EXPECT_GT(audit.rmse, 0.3);
}

TEST(Audit, RefusesPastTheLimitAndTheSlack) {
    // allowed^2 = (1.5 x 0.02)^2 + 1 / 10000 = 0.001: 0.031623 RMSE.
    VisibilityAudit a{.stride = 3, .pixels = 10000, .rmse = 0.0316, .hardRmse = 0.02};
    EXPECT_EQ(auditRefusal(a, 1.5, kSdfNames), "");
    a.rmse = 0.0317;
    EXPECT_NE(auditRefusal(a, 1.5, kSdfNames), "");
    EXPECT_EQ(auditRefusal(a, 1.6, kSdfNames), ""); // sqrt(0.001024 + 0.0001) = 0.0335
    // Nothing measured: nothing to refuse.
    EXPECT_EQ(auditRefusal(VisibilityAudit{.rmse = 1.0}, 1.5, kSdfNames), "");
    // A view whose hard shadow is exact on the grid (a light without size): one wrong pixel of
    // 4000 is within the slack, two are not.
    VisibilityAudit point{
        .stride = 3, .pixels = 4000, .rmse = std::sqrt(0.99 / 4000), .hardRmse = 0};
    EXPECT_EQ(auditRefusal(point, 1.5, kSdfNames), "");
    point.rmse = std::sqrt(2.0 / 4000);
    const std::string exact = auditRefusal(point, 1.5, kSdfNames);
    EXPECT_NE(exact.find("its shadow errs where the hard technique's is exact (RMSE 0.0224"),
              std::string::npos)
        << exact;
}

TEST(Audit, RefusesALeakOrAcneAsTheGateCountsThem) {
    // A grid every 2 pixels: 250 grid pixels stand for the gate's 1000. 0.3% of 1000 is 3, one
    // pixel allowed besides.
    VisibilityAudit a{.stride = 2, .pixels = 10000, .umbra = 1000, .leaked = 4};
    EXPECT_EQ(auditRefusal(a, 1.2, kSdfNames), "");
    a.leaked = 5;
    const std::string leak = auditRefusal(a, 1.2, kSdfNames);
    EXPECT_NE(leak.find("it lights 0.50% of the umbra (5 of 1000 pixels)"), std::string::npos)
        << leak;
    EXPECT_EQ(auditRefusal(a, 0.0, kSdfNames), "") << "sdf.refuse=0 never refuses";
    a.umbra = 249, a.leaked = 100; // too few for the leak's rule, as the gate's 1000, ...
    const std::string settled = auditRefusal(a, 1.2, kSdfNames);
    EXPECT_EQ(settled.find("it lights"), std::string::npos) << settled;
    // ... but 40% of what lies away from edges: the pixels there count however few they are.
    EXPECT_NE(settled.find("it reads 40.16% of the pixels away from shadow edges on the wrong side "
                           "(100 of 249)"),
              std::string::npos)
        << settled;
    a.fullyLit = 33000; // 0.3% of 33249 is 99.7, one pixel besides: within
    EXPECT_EQ(auditRefusal(a, 1.2, kSdfNames), "");
    a.leaked = 101;
    EXPECT_NE(auditRefusal(a, 1.2, kSdfNames), "");
    a.leaked = 100;
    a.umbra = 250;
    EXPECT_NE(auditRefusal(a, 1.2, kSdfNames), "");
    a.stride = 3; // 1000 / 9 = 111 grid pixels suffice
    a.umbra = 112, a.leaked = 2;
    EXPECT_NE(auditRefusal(a, 1.2, kSdfNames), "");
    VisibilityAudit acne{.stride = 2, .pixels = 10000, .fullyLit = 2000, .acne = 7};
    EXPECT_EQ(auditRefusal(acne, 1.2, kSdfNames), "");
    acne.acne = 8;
    const std::string dark = auditRefusal(acne, 1.2, kSdfNames);
    EXPECT_NE(dark.find("it darkens 0.40% of the fully lit pixels (8 of 2000)"), std::string::npos)
        << dark;
}

// Grey counts as compare counts it: a settled umbra read above 0.1 leaks, a settled lit pixel
// read below 0.9 is acne; 0.05 and 0.95 are neither.
TEST(Audit, CountsGreyAsCompareDoes) {
    const Views& v = views();
    const RenderResult hard = v.technique(v.centreRays());
    const auto greyed = [&](float shadow, float light) {
        std::vector<float> grey = v.truth.visibility[0];
        for (float& x : grey)
            x = x < 0.05f ? shadow : x > 0.95f ? light : x; // the grid's own rays differ a little
        return auditVisibility(v.scene, v.technique(grey), hard);
    };
    const VisibilityAudit wrong = greyed(0.3f, 0.7f);
    EXPECT_GT(wrong.umbra, 100u);
    EXPECT_EQ(wrong.leaked, wrong.umbra);
    EXPECT_EQ(wrong.acne, wrong.fullyLit);
    const VisibilityAudit close = greyed(0.05f, 0.95f);
    EXPECT_EQ(close.leaked, 0u);
    EXPECT_EQ(close.acne, 0u);
}

// A cell beside the background (no surface, no truth) is settled by its other neighbours: the
// sky does not hide acne along a silhouette.
TEST(Audit, TheBackgroundLeavesItsNeighboursSettled) {
    const Views& v = views();
    const std::vector<float> zeros(size_t{kWidth} * kHeight, 0.0f);
    const RenderResult hard = v.technique(v.centreRays());
    const VisibilityAudit whole = auditVisibility(v.scene, v.technique(zeros), hard);
    // Grid columns 2 to 4 (pixels 4 to 9) become sky, where every cell around them is lit.
    RenderResult sky = v.technique(zeros), skyHard = hard;
    uint64_t removed = 0;
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 2; x < 12; ++x) {
            const size_t i = size_t{y} * kWidth + x;
            ASSERT_EQ(v.truth.visibility[0][i], 1.0f) << "a lit margin round the sky";
            if (x >= 4 && x < 10) {
                for (RenderResult* r : {&sky, &skyHard})
                    for (int k = 0; k < 3; ++k)
                        r->position[3 * i + k] = std::numeric_limits<float>::quiet_NaN();
                removed += gridCentre(i);
            }
        }
    const VisibilityAudit cut = auditVisibility(v.scene, sky, skyHard);
    EXPECT_EQ(removed, 3u * kHeight / 2);
    EXPECT_EQ(cut.fullyLit, whole.fullyLit - removed);
    EXPECT_EQ(cut.acne, cut.fullyLit);
}
