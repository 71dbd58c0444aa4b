// The report's reduced images (src/report/page_image.h): the factor, linear-light means, the cut
// blocks at the border, and the links to the full-size files.
#include "report/html_report.h"
#include "report/page_image.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace penumbra {
namespace {

RgbaImage uniform(uint32_t width, uint32_t height, uint8_t grey, uint8_t alpha = 255) {
    RgbaImage image{width, height, {}};
    for (size_t i = 0; i < size_t{width} * height; ++i)
        image.pixels.insert(image.pixels.end(), {grey, grey, grey, alpha});
    return image;
}

const uint8_t* pixelAt(const RgbaImage& image, uint32_t x, uint32_t y) {
    return &image.pixels[(size_t{y} * image.width + x) * 4];
}

TEST(PageImage, TheFactorIsTheSmallestWholeOneThatFitsThePage) {
    EXPECT_EQ(pageScale(1), 1u);
    EXPECT_EQ(pageScale(kPageImageWidth), 1u);
    EXPECT_EQ(pageScale(kPageImageWidth + 1), 2u);
    EXPECT_EQ(pageScale(1920), 2u);
    EXPECT_EQ(pageScale(2 * kPageImageWidth + 1), 3u);
    EXPECT_EQ(pageScale(3840), 4u);
    EXPECT_EQ(pageScale(100, 10), 10u);
    EXPECT_EQ(pageScale(101, 10), 11u);
}

TEST(PageImage, ColoursAreAveragedInLinearLight) {
    // A black and white checker: the mean in linear light is 0.5, which sRGB encodes as
    // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354, byte 187.5 -> 188 (the mean of the bytes is 128).
    RgbaImage checker{4, 2, {}};
    for (uint32_t y = 0; y < 2; ++y)
        for (uint32_t x = 0; x < 4; ++x) {
            const uint8_t v = (x + y) % 2 ? 255 : 0;
            checker.pixels.insert(checker.pixels.end(), {v, v, v, uint8_t(x < 2 ? 0 : 255)});
        }
    const RgbaImage reduced = reduceImage(checker, 2);
    ASSERT_EQ(reduced.width, 2u);
    ASSERT_EQ(reduced.height, 1u);
    for (uint32_t x = 0; x < 2; ++x)
        for (size_t c = 0; c < 3; ++c)
            EXPECT_EQ(pixelAt(reduced, x, 0)[c], 188) << "channel " << c;
    EXPECT_EQ(pixelAt(reduced, 0, 0)[3], 0) << "alpha is averaged as stored";
    EXPECT_EQ(pixelAt(reduced, 1, 0)[3], 255);
    // Channels stay apart: red and blue halves give a mean of each, not of their sum.
    RgbaImage redBlue{2, 1, {255, 0, 0, 255, 0, 0, 255, 255}};
    const RgbaImage purple = reduceImage(redBlue, 2);
    const uint8_t* p = pixelAt(purple, 0, 0);
    EXPECT_EQ(p[0], 188);
    EXPECT_EQ(p[1], 0);
    EXPECT_EQ(p[2], 188);
}

TEST(PageImage, BlocksAtTheBorderAverageOnlyThePixelsTheyHold) {
    // 5 x 3 at factor 2 -> 3 x 2: the last column and row of blocks are cut by the border. Each
    // uniform block keeps its grey exactly (sRGB to linear and back rounds to the same byte).
    RgbaImage image = uniform(5, 3, 40);
    for (uint32_t y = 0; y < 3; ++y) // the fifth column alone
        image.pixels[(size_t{y} * 5 + 4) * 4] = 200;
    for (uint32_t x = 0; x < 4; ++x) // the third row, first four columns
        image.pixels[(size_t{2} * 5 + x) * 4 + 1] = 90;
    const RgbaImage reduced = reduceImage(image, 2);
    ASSERT_EQ(reduced.width, 3u);
    ASSERT_EQ(reduced.height, 2u);
    EXPECT_EQ(pixelAt(reduced, 2, 0)[0], 200) << "the cut column's block holds only column 4";
    EXPECT_EQ(pixelAt(reduced, 2, 1)[0], 200);
    EXPECT_EQ(pixelAt(reduced, 0, 1)[1], 90) << "the cut row's block holds only row 2";
    EXPECT_EQ(pixelAt(reduced, 0, 0)[1], 40);
    for (uint8_t grey = 0; grey < 255; ++grey)
        ASSERT_EQ(pixelAt(reduceImage(uniform(3, 3, grey), 3), 0, 0)[0], grey);
}

TEST(PageImage, FactorOneKeepsTheImage) {
    const RgbaImage image = uniform(3, 2, 77, 9);
    const RgbaImage same = reduceImage(image, 1);
    EXPECT_EQ(same.width, 3u);
    EXPECT_EQ(same.pixels, image.pixels);
}

TEST(PageImage, TheReportLinksTheFullSizeFilesAndSaysTheScale) {
    ReportData d{.scene = "builtin:demo", .width = 1920, .height = 1080, .pageScale = 2};
    ReportRow row{.name = "pcf[box7]", .technique = "pcf"};
    row.imagePng = row.visibilityPng = row.heatmapPng = {1, 2, 3};
    row.imageFile = "pcf-box7.image.png";
    row.heatmapFile = "a\"b.heatmap.png"; // escaped in the attribute
    d.rows.push_back(row);
    std::string html = renderHtmlReport(d);
    EXPECT_NE(html.find("<a class=\"full-size\" href=\"pcf-box7.image.png\""), std::string::npos);
    EXPECT_NE(html.find("href=\"a&quot;b.heatmap.png\""), std::string::npos);
    EXPECT_NE(html.find("<main data-page-scale=\"2\">"), std::string::npos);
    EXPECT_NE(html.find("shown at 1/2 of the rendered size (1920 &times; 1080)"),
              std::string::npos);
    d.pageScale = 1;
    html = renderHtmlReport(d);
    EXPECT_EQ(html.find("of the rendered size"), std::string::npos) << "no note at full size";
    EXPECT_NE(html.find("<main data-page-scale=\"1\">"), std::string::npos);
}

} // namespace
} // namespace penumbra
