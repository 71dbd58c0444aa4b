#include "base64_decode.h"
#include "report/bench_report.h"
#include "report/heatmap.h"
#include "report/html_report.h"
#include "report/report_plot.h"
#include "report/truth_notes.h"
#include "report/tune_report.h"

#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <tuple>

namespace penumbra {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

using Rgba = std::array<int, 4>;

Rgba pixel(const RgbaImage& im, uint32_t x, uint32_t y) {
    const uint8_t* p = im.pixels.data() + (size_t{y} * im.width + x) * 4;
    return {p[0], p[1], p[2], p[3]};
}

void expectNear(Rgba actual, Rgba expected, int tolerance) {
    for (size_t i = 0; i < 4; ++i)
        EXPECT_NEAR(actual[i], expected[i], tolerance) << "channel " << i;
}

// Errors -1, 0 and +1 in one 3x1 image.
RgbaImage threeErrors(float range = 1.0f, uint8_t maskValue = 1) {
    const std::vector<float> v = {0.0f, 0.5f, 1.0f}, t = {1.0f, 0.5f, 0.0f};
    const std::vector<uint8_t> mask(3, maskValue);
    return signedErrorHeatmap(3, 1, v, t, mask, range);
}

TEST(Heatmap, DivergingColoursAtTheEndsAndCentre) {
    RgbaImage im = threeErrors();
    Rgba low = pixel(im, 0, 0), zero = pixel(im, 1, 0), high = pixel(im, 2, 0);
    EXPECT_GT(low[2], low[0] + 60); // blue-ish: too dark
    EXPECT_GT(low[2], low[1] + 60);
    EXPECT_GT(high[0], high[2] + 60); // red-ish: too bright
    EXPECT_GT(high[0], high[1] + 60);
    for (size_t c = 0; c < 3; ++c)
        EXPECT_GT(zero[c], 200) << c; // near-white and neutral
    EXPECT_LE(std::max({zero[0], zero[1], zero[2]}) - std::min({zero[0], zero[1], zero[2]}), 4);
    // Moreland's published cool-warm end points and midpoint.
    // The ends go through sRGB -> Msh -> sRGB and must come back exactly.
    expectNear(low, {59, 76, 192, 255}, 0);
    expectNear(zero, {221, 221, 221, 255}, 2);
    expectNear(high, {180, 4, 38, 255}, 0);
}

TEST(Heatmap, ErrorIsClampedToRange) {
    RgbaImage wide = threeErrors(1.0f), narrow = threeErrors(0.25f);
    EXPECT_EQ(pixel(narrow, 0, 0), pixel(wide, 0, 0));
    EXPECT_EQ(pixel(narrow, 2, 0), pixel(wide, 2, 0));
    // With range 4, an error of 1 is only a quarter of the way to the end colour.
    RgbaImage faint = threeErrors(4.0f);
    EXPECT_GT(pixel(faint, 2, 0)[1], pixel(wide, 2, 0)[1] + 60);
}

TEST(Heatmap, UncountedPixelsAreBlendedTowardsGrey) {
    RgbaImage counted = threeErrors(), uncounted = threeErrors(1.0f, 0);
    for (uint32_t x = 0; x < 3; ++x) {
        Rgba c = pixel(counted, x, 0), u = pixel(uncounted, x, 0);
        for (size_t k = 0; k < 3; ++k)
            EXPECT_NEAR(u[k], (c[k] + 128) / 2, 1) << x << " " << k;
    }
}

TEST(Heatmap, LegendStripBelowTheImage) {
    const uint32_t w = 400, h = 50;
    std::vector<float> v(w * h, 0.5f), t(w * h, 0.5f);
    std::vector<uint8_t> mask(w * h, 1);
    RgbaImage im = signedErrorHeatmap(w, h, v, t, mask);
    ASSERT_EQ(im.width, w);
    ASSERT_GE(im.height, h + 28);
    ASSERT_EQ(im.pixels.size(), size_t{im.width} * im.height * 4);
    int blue = 0, red = 0, ink = 0;
    for (uint32_t y = h; y < im.height; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            Rgba p = pixel(im, x, y);
            EXPECT_EQ(p[3], 255);
            blue += p[2] > p[0] + 60;
            red += p[0] > p[2] + 60;
            ink += p[0] < 60 && p[1] < 60 && p[2] < 60;
        }
    EXPECT_GT(blue, 100); // the gradient's cool half
    EXPECT_GT(red, 100);  // and its warm half
    EXPECT_GT(ink, 50);   // tick marks and labels
    // A legend fits narrow images too, without drawing outside them.
    RgbaImage tiny = threeErrors();
    EXPECT_GE(tiny.height, 1u + 28);
    EXPECT_EQ(tiny.pixels.size(), size_t{tiny.width} * tiny.height * 4);
}

TEST(Heatmap, BackgroundIsADarkChecker) {
    std::vector<float> v(32 * 32, 0.0f), t(32 * 32, kNaN);
    std::vector<uint8_t> mask(32 * 32, 0);
    RgbaImage im = signedErrorHeatmap(32, 32, v, t, mask);
    Rgba a = pixel(im, 0, 0), b = pixel(im, 8, 0);
    EXPECT_NE(a, b);
    EXPECT_EQ(pixel(im, 7, 7), a);
    EXPECT_EQ(pixel(im, 8, 8), a);
    EXPECT_EQ(pixel(im, 0, 8), b);
    EXPECT_EQ(pixel(im, 31, 31), a);
    for (Rgba p : {a, b}) {
        EXPECT_LT(p[0], 0x60);
        EXPECT_EQ(p[0], p[1]);
        EXPECT_EQ(p[1], p[2]);
    }
}

TEST(Heatmap, VisibilityImage) {
    const std::vector<float> v = {0.0f, 1.0f, 0.5f, kNaN, -2.0f, 3.0f};
    RgbaImage im = visibilityImage(3, 2, v);
    EXPECT_EQ(pixel(im, 0, 0), (Rgba{0, 0, 0, 255}));
    EXPECT_EQ(pixel(im, 1, 0), (Rgba{255, 255, 255, 255}));
    EXPECT_EQ(pixel(im, 2, 0), (Rgba{128, 128, 128, 255}));
    EXPECT_EQ(pixel(im, 0, 1), (Rgba{0x8c, 0xa6, 0xcc, 255}));
    EXPECT_EQ(pixel(im, 1, 1), (Rgba{0, 0, 0, 255}));
    EXPECT_EQ(pixel(im, 2, 1), (Rgba{255, 255, 255, 255}));
}

TEST(Heatmap, EncodePngRoundTrips) {
    RgbaImage im = threeErrors();
    std::vector<uint8_t> png = encodePng(im);
    int w = 0, h = 0, n = 0;
    uint8_t* decoded =
        stbi_load_from_memory(png.data(), static_cast<int>(png.size()), &w, &h, &n, 4);
    ASSERT_NE(decoded, nullptr);
    EXPECT_EQ(uint32_t(w), im.width);
    EXPECT_EQ(uint32_t(h), im.height);
    EXPECT_TRUE(std::equal(im.pixels.begin(), im.pixels.end(), decoded));
    stbi_image_free(decoded);
}

ReportRow makeRow(std::string name, double rmse, std::vector<std::pair<std::string, double>> gpu) {
    ReportRow row;
    row.name = std::move(name);
    row.technique = "pcf";
    row.parameters = {{"kernel", "box7"}};
    row.metrics.rmse = rmse;
    row.metrics.mae = rmse / 2;
    row.metrics.max = 1;
    row.metrics.misclassified = 0.125;
    row.metrics.misclassifiedOutsideEdges = 0.0625;
    row.metrics.acne = 0.25;
    row.metrics.leak = 0.5;
    row.metrics.acneBeyondBlur = 0.03125;
    row.metrics.leakBeyondBlur = 0.015625;
    row.metrics.leakNearContact = 0.375;
    row.metrics.nearContact = 321;
    row.metrics.pixels = 1234;
    row.metrics.truthLit = 40213, row.metrics.truthShadowed = 300; // few shadowed: a note
    row.metrics.acnePixels = 12, row.metrics.leakPixels = 150;
    row.metrics.acneBeyondBlurPixels = 7, row.metrics.leakBeyondBlurPixels = 5;
    for (auto& [pass, ms] : gpu)
        row.gpuMs.push_back({.pass = pass, .cost = CostGroup::ShadowMaps, .medianMs = ms});
    row.imagePng = encodePng(visibilityImage(2, 2, std::vector<float>{0, 1, 0.5f, kNaN}));
    row.visibilityPng = {1, 2, 3, 4}; // not a PNG: exercises base64 with one byte left over
    row.heatmapPng = encodePng(threeErrors());
    return row;
}

ReportData makeReport() {
    ReportData d;
    d.scene = "builtin:showcase";
    d.device = "llvmpipe (LLVM 15.0.7, 256 bits)";
    d.driver = "Mesa 23.0";
    d.width = 640, d.height = 360, d.shadowMapSize = 2048, d.samples = 64;
    d.referenceSeconds = 12.5, d.raysPerSecond = 1.25e6;
    d.lights = {"sun: directional, angular diameter 0.53 deg", "lamp: spot, radius 0.1"};
    d.referenceVisibilityPng = {9, 8, 7, 6, 5}; // two bytes left over
    d.rows.push_back(makeRow("hard", 0.2, {{"shadow", 0.5}, {"main", 1.25}}));
    d.rows.push_back(makeRow("a<b&\"c\"", 0.1, {{"shadow", 0.75}, {"blur", 0.25}, {"main", 1}}));
    return d;
}

std::set<std::string> keysOf(const nlohmann::json& j) {
    std::set<std::string> keys;
    for (const auto& [key, value] : j.items())
        keys.insert(key);
    return keys;
}

TEST(MetricsJson, HasExactlyTheContractKeys) {
    const ReportData d = makeReport();
    nlohmann::json j = metricsJson(d); // not const: a missing key reads as null, not UB
    EXPECT_EQ(keysOf(j), (std::set<std::string>{"reference", "techniques", "notes"}));
    ASSERT_EQ(j["notes"].size(), 1u);
    EXPECT_NE(j["notes"][0].get<std::string>().find("300 fully shadowed"), std::string::npos);
    nlohmann::json& ref = j["reference"];
    EXPECT_EQ(keysOf(ref),
              (std::set<std::string>{"samples", "rays_per_pixel", "seconds", "rays_per_second",
                                     "lights", "scene", "width", "height", "device"}));
    EXPECT_EQ(ref["samples"], 64);
    EXPECT_EQ(ref["rays_per_pixel"], (nlohmann::json{64, 64})) << "both lights have a size";
    EXPECT_EQ(ref["seconds"], 12.5);
    EXPECT_EQ(ref["rays_per_second"], 1.25e6);
    EXPECT_EQ(ref["lights"], nlohmann::json(d.lights));
    EXPECT_EQ(ref["scene"], "builtin:showcase");
    EXPECT_EQ(ref["width"], 640);
    EXPECT_EQ(ref["height"], 360);
    EXPECT_EQ(ref["device"], d.device);
    EXPECT_EQ(keysOf(j["techniques"]), (std::set<std::string>{"hard", "a<b&\"c\""}));
    nlohmann::json& t = j["techniques"]["a<b&\"c\""];
    EXPECT_EQ(keysOf(t), (std::set<std::string>{"rmse", "mae", "max", "misclassified",
                                                "misclassified_outside_edges", "acne", "leak",
                                                "acne_beyond_blur", "leak_beyond_blur",
                                                "leak_near_contact", "near_contact_pixels",
                                                "pixels", "counts", "gpu_ms", "gpu_ms_by_cost"}));
    // Every pass of this row is declared a shadow-map cost: all its time, none elsewhere.
    EXPECT_EQ(t["gpu_ms_by_cost"],
              (nlohmann::json{
                  {"shadow_maps", t["gpu_ms"]["total"]}, {"per_pixel", 0.0}, {"frame", 0.0}}));
    EXPECT_EQ(t["counts"]["acne"], (nlohmann::json{{"pixels", 12}, {"of", 40213}}));
    EXPECT_EQ(t["counts"]["leak"], (nlohmann::json{{"pixels", 150}, {"of", 300}}));
    EXPECT_EQ(t["counts"]["acne_beyond_blur"], (nlohmann::json{{"pixels", 7}, {"of", 40213}}))
        << "beyond blur has acne's denominator";
    EXPECT_EQ(t["counts"]["leak_beyond_blur"], (nlohmann::json{{"pixels", 5}, {"of", 300}}));
    EXPECT_EQ(t["counts"]["misclassified"]["of"], 1234);
    ReportData plenty = makeReport();
    for (ReportRow& row : plenty.rows)
        row.metrics.truthShadowed = kFewJudgedPixels;
    EXPECT_TRUE(metricsJson(plenty)["notes"].empty());
    const std::string html = renderHtmlReport(d);
    EXPECT_NE(html.find("12/<wbr>40.2k"), std::string::npos) << "the pixels under each percentage";
    EXPECT_NE(html.find("title=\"150 of 300 pixels\""), std::string::npos);
    EXPECT_NE(html.find("class=\"note few-pixels\""), std::string::npos);
    EXPECT_EQ(renderHtmlReport(plenty).find("class=\"note few-pixels\""), std::string::npos);
    EXPECT_EQ(t["rmse"], 0.1);
    EXPECT_EQ(t["mae"], 0.05);
    EXPECT_EQ(t["max"], 1.0);
    EXPECT_EQ(t["misclassified"], 0.125);
    EXPECT_EQ(t["misclassified_outside_edges"], 0.0625);
    EXPECT_EQ(t["acne"], 0.25);
    EXPECT_EQ(t["leak"], 0.5);
    EXPECT_EQ(t["acne_beyond_blur"], 0.03125);
    EXPECT_EQ(t["leak_beyond_blur"], 0.015625);
    EXPECT_EQ(t["leak_near_contact"], 0.375);
    EXPECT_EQ(t["near_contact_pixels"], 321);
    EXPECT_EQ(t["pixels"], 1234);
    EXPECT_EQ(keysOf(t["gpu_ms"]), (std::set<std::string>{"shadow", "blur", "main", "total"}));
    EXPECT_EQ(t["gpu_ms"]["blur"], 0.25);
    EXPECT_DOUBLE_EQ(t["gpu_ms"]["total"].get<double>(), 2.0);
    EXPECT_DOUBLE_EQ(j["techniques"]["hard"]["gpu_ms"]["total"].get<double>(), 1.75);
}

size_t countOf(const std::string& text, const std::string& needle) {
    size_t count = 0;
    for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1))
        ++count;
    return count;
}

// Every data:image/png;base64 payload in the page, decoded.
std::vector<std::vector<uint8_t>> embeddedImages(const std::string& html) {
    const std::string prefix = "src=\"data:image/png;base64,";
    std::vector<std::vector<uint8_t>> images;
    for (size_t at = html.find(prefix); at != std::string::npos; at = html.find(prefix, at)) {
        at += prefix.size();
        const size_t end = html.find('"', at);
        images.push_back(test::decodeBase64(html.substr(at, end - at)));
    }
    return images;
}

// The truth's rays in words: every light with a size, none, a mix (either way round), none at
// all; one ray asked for is still "1 ray", not an exact one, towards a light with a size.
TEST(TruthNotes, TheRaysAreCountedPerLightAsTheTruthTracesThem) {
    EXPECT_EQ(truthRays(256, {true, false, true}), (std::vector<uint32_t>{256, 1, 256}));
    EXPECT_EQ(truthRays(256, {}), std::vector<uint32_t>{});
    EXPECT_EQ(truthRaysText(256, {true, true}), "256 rays per pixel and light");
    EXPECT_EQ(truthRaysText(1, {true}), "1 ray per pixel and light");
    EXPECT_EQ(truthRaysText(256, {false}),
              "1 exact ray per pixel (the light has no size: a hard truth)");
    EXPECT_EQ(truthRaysText(256, {false, false}),
              "1 exact ray per pixel and light (no light has a size: a hard truth)");
    EXPECT_EQ(truthRaysText(64, {true, false, false}),
              "64 rays per pixel towards the 1 light with a size, 1 exact ray towards the 2 lights "
              "without");
    EXPECT_EQ(truthRaysText(64, {false, true, true}),
              "64 rays per pixel towards the 2 lights with a size, 1 exact ray towards the 1 light "
              "without");
    EXPECT_EQ(truthRaysText(64, {}), "no shadow-casting light");
}

// A soft technique ranked against a hard truth is told so, naming the lights without a size and
// the rows that model one; not when every light has a size, when no row models one, or when the
// only such row was skipped. The report and metrics.json carry it, and the rays per light.
TEST(TruthNotes, SoftRowsAgainstAHardTruthGetANote) {
    ReportData d = makeReport();
    d.rows[1].modelsLightSize = true;
    EXPECT_EQ(hardTruthNote(d), "") << "both lights have a size";
    d.lightSized = {true, false};
    const std::string note = hardTruthNote(d);
    EXPECT_NE(note.find("towards lamp "), std::string::npos) << note;
    EXPECT_EQ(note.find("sun"), std::string::npos) << "the sun has a size: " << note;
    EXPECT_NE(note.find("of a<b&\"c\" count"), std::string::npos) << note;
    EXPECT_EQ(note.find("hard,"), std::string::npos) << "hard models no size: " << note;
    nlohmann::json j = metricsJson(d);
    EXPECT_EQ(j["reference"]["rays_per_pixel"], (nlohmann::json{64, 1}));
    ASSERT_EQ(j["notes"].size(), 2u) << "the hard truth's and the few pixels'";
    EXPECT_EQ(j["notes"][0], note);
    const std::string html = renderHtmlReport(d);
    EXPECT_NE(html.find("<p class=\"note hard-truth\"><strong>" + escapeHtml(note)),
              std::string::npos);
    EXPECT_NE(html.find("64 rays per pixel towards the 1 light with a size, 1 exact ray towards "
                        "the 1 light without"),
              std::string::npos);

    ReportData hardRows = d;
    hardRows.rows[1].modelsLightSize = false;
    EXPECT_EQ(hardTruthNote(hardRows), "");
    EXPECT_EQ(renderHtmlReport(hardRows).find("note hard-truth"), std::string::npos);
    ReportData skipped = d;
    skipped.rows[1].skipped = "the device cannot hold it";
    EXPECT_EQ(hardTruthNote(skipped), "");
    ReportData sized = d;
    sized.lightSized = {true, true};
    EXPECT_EQ(hardTruthNote(sized), "");
    EXPECT_EQ(metricsJson(sized)["notes"].size(), 1u);

    ReportData uneven = d;
    uneven.lightSized = {false}; // one flag for two lights: a programmer's error
    EXPECT_DEATH(hardTruthNote(uneven), "one per light");
    EXPECT_DEATH(metricsJson(uneven), "one per light");

    TuneData t{.scene = "s", .technique = "pcss", .samples = 32, .lightSized = {false}};
    t.candidates.push_back(TuneCandidate{});
    EXPECT_EQ(tuneJson(t)["rays_per_pixel"], (nlohmann::json{1}));
    EXPECT_NE(tuneHtml(t).find("1 exact ray per pixel"), std::string::npos);
}

// The cost columns group the passes by the group each declares, never by its name: the shadow
// maps' (the depth pass and the technique's own), the per-pixel ones (visibility, smrt's filter,
// composite, the contact layer), and the total of every pass, the frame's too, worked out by hand;
// metrics.json sums the same groups.
TEST(HtmlReport, CostColumnsGroupThePasses) {
    ReportData d = makeReport();
    d.rows.resize(1);
    const auto pass = [](std::string name, CostGroup cost, double ms) {
        return PassTime{.pass = std::move(name), .cost = cost, .medianMs = ms};
    };
    d.rows[0].gpuMs = {pass("shadow", CostGroup::ShadowMaps, 0.5),
                       pass("blur", CostGroup::ShadowMaps, 0.25),
                       pass("gbuffer", CostGroup::Frame, 2.0),
                       pass("visibility", CostGroup::PerPixel, 1.0),
                       pass("filter", CostGroup::PerPixel, 4.0),
                       pass("composite", CostGroup::PerPixel, 0.125),
                       pass("contact_march", CostGroup::PerPixel, 0.0625)};
    const std::string html = renderHtmlReport(d);
    EXPECT_NE(html.find("<td data-value=\"0.75\" class=\"first\">0.750</td>"), std::string::npos)
        << "shadow + blur";
    EXPECT_NE(html.find("<td data-value=\"5.1875\">"), std::string::npos)
        << "visibility + filter + composite + contact_march";
    EXPECT_NE(html.find("<td data-value=\"7.9375\" title=\"shadow 0.500, blur 0.250, gbuffer "
                        "2.000, visibility 1.000, filter 4.000, composite 0.125, contact_march "
                        "0.062\">"),
              std::string::npos)
        << "every pass";
    const nlohmann::json byCost = metricsRowJson(d.rows[0])["gpu_ms_by_cost"];
    EXPECT_EQ(byCost,
              (nlohmann::json{{"shadow_maps", 0.75}, {"per_pixel", 5.1875}, {"frame", 2.0}}));
    EXPECT_EQ(gpuMsByCost({}),
              (nlohmann::json{{"shadow_maps", 0.0}, {"per_pixel", 0.0}, {"frame", 0.0}}));
}

// The best value of a column is marked only where the rows differ: the lower RMSE of two, not
// a Max every row shares, nor a column of one row.
TEST(HtmlReport, TheBestIsMarkedOnlyWhereValuesDiffer) {
    const ReportData d = makeReport(); // RMSE 0.2 and 0.1, MAE half; every other error the same
    const std::string html = renderHtmlReport(d);
    auto count = [](const std::string& text, const std::string& what) {
        size_t n = 0;
        for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
            ++n;
        return n;
    };
    EXPECT_EQ(count(html, "<td data-value=\"0.1\" class=\"best\">0.1000</td>"), 1u);
    EXPECT_EQ(count(html, "<td data-value=\"0.05\" class=\"best\">0.0500</td>"), 1u);
    EXPECT_EQ(count(html, "class=\"best"), 2u) << "RMSE's and MAE's alone";
    ReportData worse = d;
    worse.rows[0].metrics.max = 0.5;
    worse.rows[1].metrics.acne = 0.0;
    const std::string two = renderHtmlReport(worse);
    EXPECT_EQ(count(two, "<td data-value=\"0.5\" class=\"best\">0.5000</td>"), 1u);
    EXPECT_EQ(count(two, "<td data-value=\"0\" class=\"best first\" title=\"12 of"), 1u);
    EXPECT_EQ(count(two, "class=\"best"), 4u);
    ReportData one = worse;
    one.rows.resize(1);
    EXPECT_EQ(count(renderHtmlReport(one), "class=\"best"), 0u);
}

// A coloured truth's error per channel goes under each row's RMSE, red, green and blue in that
// order, in a cell of the RMSE column (no column of its own: the Error group keeps its five); a
// row without them shows none, and a grey report has no such line at all.
TEST(HtmlReport, AColouredTruthAddsTheErrorOfEachChannel) {
    ReportData d = makeReport(); // RMSE 0.2 and 0.1
    const std::string grey = renderHtmlReport(d);
    EXPECT_EQ(countOf(grey, "class=\"channels\""), 0u);
    d.rows[0].rmsePerChannel = {0.25, 0.375, 0.5};
    d.rows[1].rmsePerChannel = {0.75, 0.125, 0.07};
    d.rows.push_back(makeRow("grey", 0.3, {}));
    const std::string html = renderHtmlReport(d);
    EXPECT_EQ(countOf(html, "<th colspan=\"5\">Error</th>"), 1u);
    EXPECT_EQ(countOf(html, "class=\"channels\""), 2u) << "the grey row has none";
    // The first row: its RMSE with its three channels beneath, then its MAE.
    const size_t row = html.find("<tr class=\"technique-row\" data-technique=\"hard\"");
    ASSERT_NE(row, std::string::npos);
    const std::string cells = html.substr(row, html.find("</tr>", row) - row);
    const std::vector<std::string> expected{
        "<td data-value=\"0.2\">0.2000<div class=\"channels\" title=\"red, green, blue\">"
        "0.250<br>0.375<br>0.500</div></td>",
        "<td data-value=\"0.1\">0.1000</td>"};
    size_t at = 0;
    for (const std::string& cell : expected) {
        const size_t next = cells.find(cell, at);
        ASSERT_NE(next, std::string::npos) << cell;
        at = next + cell.size();
    }
    EXPECT_NE(html.find("<td data-value=\"0.1\" class=\"best\">0.1000<div class=\"channels\" "
                        "title=\"red, green, blue\">0.750<br>0.125<br>0.070</div></td>"),
              std::string::npos);
}

TEST(HtmlReport, IsSelfContainedAndEscaped) {
    const ReportData d = makeReport();
    const std::string html = renderHtmlReport(d);
    EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
    EXPECT_NE(html.find("<meta charset=\"utf-8\">"), std::string::npos);
    EXPECT_EQ(countOf(html, "<tr class=\"technique-row\""), 2u);
    EXPECT_EQ(countOf(html, "<img class=\"heatmap\""), 2u);
    EXPECT_EQ(countOf(html, "<figure class=\"card technique\" data-technique="), 2u);
    EXPECT_EQ(countOf(html, "class=\"error-vs-cost\""), 1u);
    for (const char* banned : {"http:", "https:", "src=\"//", "href=\"//", "<script src", "url("})
        EXPECT_EQ(html.find(banned), std::string::npos) << banned;
    EXPECT_EQ(countOf(html, "<script>"), 1u) << "one inline script: sorting and the comparer";
    EXPECT_EQ(countOf(html, "<svg class=\"error-vs-cost"), 2u) << "linear and logarithmic cost";
    EXPECT_EQ(html.find("a<b&\"c\""), std::string::npos);
    EXPECT_NE(html.find("data-technique=\"a&lt;b&amp;&quot;c&quot;\""), std::string::npos);
    EXPECT_NE(html.find("LLVM 15.0.7"), std::string::npos);
    EXPECT_NE(html.find("sun: directional"), std::string::npos);
}

TEST(HtmlReport, EmbeddedImagesDecode) {
    const ReportData d = makeReport();
    const std::vector<std::vector<uint8_t>> images = embeddedImages(renderHtmlReport(d));
    ASSERT_EQ(images.size(), 1u + 3 * d.rows.size());
    EXPECT_EQ(images[0], d.referenceVisibilityPng);
    EXPECT_EQ(images[1], d.rows[0].imagePng);
    EXPECT_EQ(images[2], d.rows[0].visibilityPng);
    EXPECT_EQ(images[3], d.rows[0].heatmapPng);
    int w = 0, h = 0, n = 0;
    uint8_t* decoded =
        stbi_load_from_memory(images[3].data(), static_cast<int>(images[3].size()), &w, &h, &n, 4);
    ASSERT_NE(decoded, nullptr);
    EXPECT_EQ(w, 3);
    EXPECT_GE(h, 29);
    stbi_image_free(decoded);
}

// The front: what no other row beats on both counts; a tie on one count and a loss on the
// other is dominated; non-finite rows are never on it.
TEST(ReportPlot, TheParetoFrontHoldsWhatNoOtherRowBeatsOnBoth) {
    const std::vector<PlotPoint> points{{"cheap", 1.0, 0.30}, {"balanced", 2.0, 0.10},
                                        {"worse", 2.0, 0.20}, {"costly", 5.0, 0.05},
                                        {"same", 5.0, 0.05},  {"tie-cost", 1.0, 0.35},
                                        {"nan", NAN, 0.01},   {"dominated", 6.0, 0.06}};
    const std::vector<bool> front = paretoFront(points);
    const std::vector<bool> expected{true, true, false, true, true, false, false, false};
    EXPECT_EQ(front, expected);
}

// Labels never overlap one another or a point, stay inside the plot, and a label with no room
// left is left out rather than drawn over another.
TEST(ReportPlot, LabelsAreSetWhereNothingElseIs) {
    const PlotBox bounds{0, 0, 300, 200};
    std::vector<PlotBox> points, sizes;
    for (int i = 0; i < 12; ++i) { // a tight cluster and a few apart
        points.push_back({100.0 + 3 * (i % 4), 100.0 + 3 * (i / 4)});
        sizes.push_back({0, 0, labelWidth("pcf[poisson32]"), 15});
    }
    points.push_back({280, 190}); // near a corner: its label must turn inwards
    sizes.push_back({0, 0, labelWidth("vsm[mip]"), 15});
    const std::vector<PlotBox> placed = placeLabels(points, 6, sizes, bounds);
    ASSERT_EQ(placed.size(), points.size());
    int shown = 0;
    for (size_t i = 0; i < placed.size(); ++i) {
        if (placed[i].w == 0)
            continue;
        ++shown;
        EXPECT_GE(placed[i].x, bounds.x);
        EXPECT_GE(placed[i].y, bounds.y);
        EXPECT_LE(placed[i].x + placed[i].w, bounds.x + bounds.w);
        EXPECT_LE(placed[i].y + placed[i].h, bounds.y + bounds.h);
        for (size_t j = 0; j < placed.size(); ++j) {
            if (j != i && placed[j].w > 0) {
                EXPECT_FALSE(placed[i].intersects(placed[j])) << i << " " << j;
            }
            const PlotBox disc{points[j].x - 6, points[j].y - 6, 12, 12};
            EXPECT_FALSE(placed[i].intersects(disc)) << "label " << i << " over point " << j;
        }
    }
    EXPECT_GE(shown, 4) << "room around the cluster for a few, and the corner's";
    EXPECT_LT(shown, 13) << "not every label of a tight cluster fits";
    EXPECT_GT(placed.back().w, 0.0);
    EXPECT_LT(placed.back().x, 280.0) << "the corner's label to its left";
}

// A label's box holds its text in DejaVu Sans at 12 px (advances in em: 'm' 0.974, 'w' 0.818,
// 'W' 0.989, 'o' 0.612, '[' 0.39), from 2 units into the box: "msm" once overflowed its box and
// touched a neighbouring point.
TEST(ReportPlot, ALabelsBoxHoldsItsWidestLetters) {
    auto dejaVu = [](const std::string& text) {
        double em = 0;
        for (char c : text)
            em += c == 'm'   ? 0.974
                  : c == 'w' ? 0.818
                  : c == 'W' ? 0.989
                  : c == 's' ? 0.521
                  : c == 'o' ? 0.612
                  : c == '[' ? 0.39
                             : 0.636;
        return 2.0 + 12.0 * em;
    };
    for (const std::string text : {"msm", "mmmm", "www", "Wm", "pcf[box7]", "msm[16]"})
        EXPECT_GE(labelWidth(text), dejaVu(text)) << text;
}

// Axis ticks at 1, 2 or 5 x 10^k, covering the data (bench.html once ticked at 35.7, 71.4).
TEST(ReportPlot, AxesTickAtRoundNumbers) {
    for (const auto& [max, step, top] : {std::tuple{107.0, 50.0, 150.0},
                                         {0.0231, 0.005, 0.025},
                                         {4.2, 1.0, 5.0},
                                         {1.0, 0.5, 1.5}}) {
        const Axis a = niceAxis(max);
        EXPECT_DOUBLE_EQ(a.step, step) << max;
        EXPECT_NEAR(a.max, top, 1e-12) << max;
        EXPECT_GE(a.max, max);
    }
    const Axis none = niceAxis(NAN);
    EXPECT_EQ(none.max, 1.0);
}

// On both cost axes every point and grid line lies inside the plot (x from 70 to 740), in the
// order of the costs; on the logarithmic one the geometric mean of two costs lies halfway
// between them. Costs that straddle 1 ms (0.2 to 50): log10 of the axis' ends differ in sign.
TEST(ReportPlot, CostsLieInsideThePlotOnBothAxes) {
    std::vector<ReportRow> rows;
    const double costs[] = {0.2, std::sqrt(0.2 * 50.0), 50.0};
    for (const double ms : costs)
        rows.push_back(makeRow("r" + std::to_string(rows.size()), 0.1, {{"shadow", ms}}));
    auto numbers = [](const std::string& svg, const std::string& key) {
        std::vector<double> xs;
        for (size_t at = svg.find(key); at != std::string::npos; at = svg.find(key, at + 1))
            xs.push_back(std::stod(svg.substr(at + key.size())));
        return xs;
    };
    for (const bool log : {false, true}) {
        const std::string svg = errorVsCostSvg(rows, log);
        const std::vector<double> cx = numbers(svg, "<circle cx=\""),
                                  grid = numbers(svg, "<line class=\"grid\" x1=\"");
        ASSERT_EQ(cx.size(), 3u);
        for (const double x : cx) {
            EXPECT_GE(x, 70.0 - 0.05) << log;
            EXPECT_LE(x, 740.0 + 0.05) << log;
        }
        EXPECT_LT(cx[0], cx[1]);
        EXPECT_LT(cx[1], cx[2]);
        for (const double x : grid) {
            EXPECT_GE(x, 70.0 - 0.05) << log;
            EXPECT_LE(x, 740.0 + 0.05) << log;
        }
        if (log) {
            EXPECT_NEAR(cx[1], 0.5 * (cx[0] + cx[2]), 0.11) << "the geometric mean halfway";
            EXPECT_GT(cx[2] - cx[0], 0.5 * 670) << "the costs span most of the axis";
        }
    }
}

TEST(HtmlReport, PlotHandlesASingleZeroRow) {
    ReportData d;
    d.rows.push_back(ReportRow{.name = "none"});
    const std::string html = renderHtmlReport(d);
    const size_t begin = html.find("<svg"), end = html.find("</svg>");
    ASSERT_NE(begin, std::string::npos);
    ASSERT_NE(end, std::string::npos);
    const std::string svg = html.substr(begin, end - begin);
    EXPECT_EQ(countOf(svg, "<circle"), 1u);
    EXPECT_EQ(svg.find("nan"), std::string::npos);
    EXPECT_EQ(svg.find("inf"), std::string::npos);
    EXPECT_NE(html.find("no image"), std::string::npos);
}

} // namespace
} // namespace penumbra

namespace penumbra {
namespace {

TuneCandidate tuneCandidate(const char* set, double acne, double leak, double rmse = 0.1,
                            double misclassified = 0.0) {
    TuneCandidate c;
    c.setLine = set;
    c.sets = {{"bias.constant", set}};
    c.metrics.acneBeyondBlur = acne;
    c.metrics.leakBeyondBlur = leak;
    c.metrics.rmse = rmse;
    c.metrics.misclassifiedOutsideEdges = misclassified;
    return c;
}

TEST(TuneReport, TheFrontHoldsWhatNoOtherBeatsOnBothCounts) {
    std::vector<TuneCandidate> c{tuneCandidate("", 0.02, 0.0), tuneCandidate("a", 0.01, 0.01),
                                 tuneCandidate("b", 0.02, 0.02), tuneCandidate("c", 0.0, 0.03),
                                 tuneCandidate("d", 0.01, 0.01)};
    markFront(c);
    EXPECT_TRUE(c[0].onFront);  // least leak
    EXPECT_TRUE(c[1].onFront);  // a tie with d beats neither
    EXPECT_FALSE(c[2].onFront); // beaten by a on both counts
    EXPECT_TRUE(c[3].onFront);  // least acne
    EXPECT_TRUE(c[4].onFront);
}

TEST(TuneReport, RecommendsTheLowestRmseWithinATieOfTheLeastAcneAndLeak) {
    std::vector<TuneCandidate> c{tuneCandidate("", 0.03, 0.0), tuneCandidate("a", 0.01, 0.01),
                                 tuneCandidate("b", 0.02, 0.01, 0.05)};
    c[0].isDefault = true;
    EXPECT_EQ(recommend(c), 1u); // the least sum; b's lower RMSE is too far off
    c[2].metrics.acneBeyondBlur = 0.01 + 0.5 * kTuneTolerance; // now a tie: the lower RMSE
    EXPECT_EQ(recommend(c), 2u);
    c[2].metrics.acneBeyondBlur = 0.01 + 1.5 * kTuneTolerance;
    EXPECT_EQ(recommend(c), 1u);
    c[2].metrics.acneBeyondBlur = 0.01;
    c[2].metrics.rmse = 0.1; // equal RMSE: fewer misclassified away from edges
    c[1].metrics.misclassifiedOutsideEdges = 0.001;
    EXPECT_EQ(recommend(c), 2u);
    c[2].metrics.misclassifiedOutsideEdges = 0.001; // a full tie: the earlier
    EXPECT_EQ(recommend(c), 1u);
    // Never above the defaults' acne + leak, however low the RMSE.
    std::vector<TuneCandidate> d{tuneCandidate("", 0.5 * kTuneTolerance, 0.0, 0.1),
                                 tuneCandidate("a", 0.0, 0.0, 0.2),
                                 tuneCandidate("b", 0.9 * kTuneTolerance, 0.0, 0.01)};
    d[0].isDefault = true;
    EXPECT_EQ(recommend(d), 0u);
}

TEST(TuneReport, JsonAndPageCarryEveryCandidateAndTheRecommendation) {
    TuneData d{.scene = "builtin:figure", .technique = "pcf[box3]", .device = "dev <1>"};
    d.views = {""};
    d.candidates = {tuneCandidate("", 0.02, 0.0),
                    tuneCandidate("--set bias.constant=0.001", 0.001, 0.0)};
    d.candidates[0].isDefault = true;
    markFront(d.candidates);
    d.recommended = recommend(d.candidates);
    const nlohmann::json j = tuneJson(d);
    EXPECT_EQ(j["candidates"].size(), 2u);
    EXPECT_EQ(j["recommended"]["index"], 1);
    EXPECT_EQ(j["recommended"]["set"], "--set bias.constant=0.001");
    EXPECT_EQ(j["candidates"][0]["defaults"], true);
    EXPECT_EQ(j["candidates"][1]["front"], true);
    EXPECT_EQ(j["candidates"][0]["front"], false);
    EXPECT_DOUBLE_EQ(j["candidates"][1]["acne_beyond_blur"].get<double>(), 0.001);
    const std::string html = tuneHtml(d);
    EXPECT_NE(html.find("dev &lt;1&gt;"), std::string::npos);
    EXPECT_NE(html.find("<code>--set bias.constant=0.001</code>"), std::string::npos);
    EXPECT_EQ(html.find("<script"), std::string::npos);
    EXPECT_EQ(std::count(html.begin(), html.end(), '<') - std::count(html.begin(), html.end(), '>'),
              0);
}

} // namespace
TEST(BenchStats, PercentilesInterpolateBetweenTheSortedFrames) {
    // Five frames given out of order: the median is the middle one; the 10th and 90th
    // percentiles sit 0.4 of the way between the two smallest and the two largest (q (n - 1)).
    const PassStats odd = passStats("shadow", {5, 1, 4, 2, 3});
    EXPECT_EQ(odd.pass, "shadow");
    EXPECT_DOUBLE_EQ(odd.median, 3.0);
    EXPECT_DOUBLE_EQ(odd.p10, 1.4);
    EXPECT_DOUBLE_EQ(odd.p90, 4.6);
    // Four frames: the median halfway between the middle two.
    const PassStats even = passStats("total", {10, 40, 20, 30});
    EXPECT_DOUBLE_EQ(even.median, 25.0);
    EXPECT_DOUBLE_EQ(even.p10, 13.0);
    EXPECT_DOUBLE_EQ(even.p90, 37.0);
    // One frame is every percentile; none gives zeros.
    const PassStats one = passStats("gbuffer", {7});
    EXPECT_EQ(std::tie(one.median, one.p10, one.p90), std::make_tuple(7.0, 7.0, 7.0));
    const PassStats none = passStats("gbuffer", {});
    EXPECT_EQ(std::tie(none.median, none.p10, none.p90), std::make_tuple(0.0, 0.0, 0.0));
}

} // namespace penumbra

// bench's memory entry carries the transient images' measured bytes, each under its own name.
TEST(BenchStats, TheMemoryEntryCarriesTheTransientImagesBothWays) {
    penumbra::BenchData data{.scene = "s", .frames = 1};
    penumbra::BenchRun run;
    penumbra::RenderResult result;
    result.transientMemory = {.separateBytes = 300, .sharedBytes = 200};
    penumbra::estimateMemory(run, penumbra::RenderOptions{}, result);
    data.runs.push_back(run);
    const nlohmann::json memory = penumbra::benchJson(data)["runs"][0]["memory"];
    EXPECT_EQ(memory["transient_separate"], 300u);
    EXPECT_EQ(memory["transient_shared"], 200u);
}
