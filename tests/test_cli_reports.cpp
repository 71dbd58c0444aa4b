// The reports as a reader sees them, in headless Chromium (Debian's package, installed by
// `make deps`): report.html loads without console messages with a row and a heat map per
// technique, and report.html, bench.html and tune.html read at 1000, 1400 and 1920 pixels.
#include "process.h"
#include "scratch_dir.h"
#include "small_comparison.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

using namespace penumbra::test;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
    return outputScratch(name);
}

} // namespace

// report.html in headless Chromium (Debian's package, installed by `make deps`): it loads
// with no console messages, and its DOM has a row and a heat map for every technique.
TEST(Cli, ReportLoadsInChromiumWithARowAndHeatmapPerTechnique) {
    const fs::path chromium = "/usr/bin/chromium";
    ASSERT_TRUE(fs::exists(chromium)) << "install Debian's chromium package (make deps does)";
    const fs::path& out = smallComparison();
    const std::string html = slurp(out / "report.html");
    for (const char* remote : {"http:", "https:", "src=\"//", "href=\"//"})
        EXPECT_EQ(html.find(remote), std::string::npos) << "network reference: " << remote;
    const fs::path profile = scratch("chromium-profile");
    const ProcessResult r = runProcess(
        {chromium.string(), "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
         "--no-first-run", "--disable-background-networking", "--disable-component-update",
         "--disable-sync", "--user-data-dir=" + profile.string(), "--enable-logging=stderr",
         "--v=0", "--virtual-time-budget=3000", "--dump-dom",
         "file://" + fs::absolute(out / "report.html").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    // Console messages (script errors, refused or broken resources) are logged as CONSOLE.
    EXPECT_EQ(r.err.find("CONSOLE"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("Uncaught"), std::string::npos) << r.err;
    const auto metrics = nlohmann::json::parse(slurp(out / "metrics.json"));
    auto count = [&](const std::string& needle) {
        size_t n = 0;
        for (size_t at = r.out.find(needle); at != std::string::npos;
             at = r.out.find(needle, at + 1))
            ++n;
        return n;
    };
    for (const auto& [name, m] : metrics["techniques"].items()) {
        EXPECT_EQ(count("<tr class=\"technique-row\" data-technique=\"" + name + "\""), 1u) << name;
        EXPECT_EQ(count("<figure class=\"card technique\" data-technique=\"" + name + "\""), 1u)
            << name;
    }
    EXPECT_EQ(count("class=\"technique-row\""), metrics["techniques"].size());
    EXPECT_EQ(count("class=\"heatmap\""), metrics["techniques"].size());
    EXPECT_EQ(count("<img"), count("src=\"data:image/png;base64,"));
}

namespace {

// A page as a reader sees it, in headless Chromium at `width` pixels: a check script appended
// to a copy of it measures the laid-out page (elements wider than the window; plot labels over
// labels or points on either cost axis; the comparer's slider; a header click's sort) and writes
// what it found into the DOM, which Chromium dumps. Console messages fail the test.
nlohmann::json layoutIn(const fs::path& page, int width) {
    const std::string check = R"JS(<script>
window.addEventListener("load", function () { setTimeout(function () {
  const W = document.documentElement.clientWidth, found = { width: W, wide: [], overlaps: [],
    labels: 0, slider: false, sorted: false, clipped: [] };
  // The pixel counts under the percentages as wide as a 4K frame's ("9.99M/9.99M"): a small
  // test image must not hide a table that only a large one pushes past the window.
  document.querySelectorAll("table .count").forEach(function (c) {
    c.innerHTML = c.innerHTML.replace(/[0-9][0-9.]*[kM]?/g, "9.99M"); });
  found.scroll = document.documentElement.scrollWidth;
  function boxes() {
    document.querySelectorAll("body *").forEach(function (el) {
      const style = getComputedStyle(el);
      if (/auto|scroll|hidden/.test(style.overflowX) && el.scrollWidth > el.clientWidth + 0.5 &&
          el.tagName !== "svg" && !el.closest("td"))  // an ellipsis inside a cell is meant
        found.clipped.push(el.tagName + "." + el.getAttribute("class") + " " + el.scrollWidth +
                           " > " + el.clientWidth);
    });
    document.querySelectorAll("body *").forEach(function (el) {
      const r = el.getBoundingClientRect();
      if (r.width > 0 && (r.right > W + 0.5 || r.left < -0.5))
        found.wide.push(el.tagName + "." + el.getAttribute("class") + " " + r.left + ".." + r.right);
    });
    document.querySelectorAll("svg.error-vs-cost").forEach(function (svg) {
      if (svg.getBoundingClientRect().width === 0) return;
      const labels = Array.from(svg.querySelectorAll("text.plot-label")).map(function (t) {
        return [t.textContent, t.getBoundingClientRect()]; });
      const discs = Array.from(svg.querySelectorAll("circle")).map(function (c) {
        return ["point", c.getBoundingClientRect()]; });
      found.labels += labels.length;
      function meet(a, b) { return a.left < b.right - 0.5 && b.left < a.right - 0.5 &&
                                   a.top < b.bottom - 0.5 && b.top < a.bottom - 0.5; }
      labels.forEach(function (a, i) {
        labels.concat(discs).forEach(function (b, j) {
          if (j > i && meet(a[1], b[1])) found.overlaps.push(a[0] + " / " + b[0]);
        });
      });
    });
  }
  boxes();
  const log = document.getElementById("cost-log");
  if (log) { log.checked = true; boxes(); }
  const canvas = document.getElementById("cmp-canvas");
  if (canvas) {
    const before = canvas.toDataURL(), split = document.getElementById("cmp-split");
    split.value = 150;
    split.dispatchEvent(new Event("input"));
    found.slider = canvas.toDataURL() !== before;
  }
  const rmse = document.querySelectorAll("table.results thead tr:nth-child(2) th")[0];
  if (rmse) {
    rmse.click();
    const values = Array.from(document.querySelectorAll("table.results tbody tr")).map(
      function (r) { return parseFloat(r.cells[1].dataset.value); });
    found.sorted = values.every(function (v, i) { return i === 0 || values[i - 1] <= v; });
  }
  document.body.setAttribute("data-check", JSON.stringify(found));
}, 300); });
</script>)JS";
    std::string html = slurp(page);
    html.insert(html.rfind("</body>"), check);
    const fs::path dir = scratch("layout-" + page.stem().string());
    fs::create_directories(dir);
    const fs::path copy = dir / page.filename();
    std::ofstream(copy) << html;
    const ProcessResult r = runProcess(
        {"/usr/bin/chromium", "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
         "--no-first-run", "--disable-background-networking", "--disable-component-update",
         "--disable-sync", "--hide-scrollbars",
         "--user-data-dir=" + scratch("chromium-widths").string(), "--enable-logging=stderr",
         "--v=0", "--virtual-time-budget=5000", "--window-size=" + std::to_string(width) + ",900",
         "--dump-dom", "file://" + fs::absolute(copy).string()});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err.find("CONSOLE"), std::string::npos) << r.err;
    const std::string key = "data-check=\"";
    const size_t at = r.out.find(key);
    EXPECT_NE(at, std::string::npos) << "the check did not run: " << r.out.substr(0, 400) << r.err;
    if (at == std::string::npos)
        return {};
    std::string json =
        r.out.substr(at + key.size(), r.out.find('"', at + key.size()) - at - key.size());
    for (const auto& [entity, c] : {std::pair{std::string("&quot;"), std::string("\"")},
                                    std::pair{std::string("&lt;"), std::string("<")},
                                    std::pair{std::string("&gt;"), std::string(">")},
                                    std::pair{std::string("&amp;"), std::string("&")}})
        for (size_t p = json.find(entity); p != std::string::npos; p = json.find(entity, p))
            json.replace(p, entity.size(), c);
    return nlohmann::json::parse(json);
}

} // namespace

// The three reports at 1000, 1400 and 1920 pixels (and report.html with a coloured truth's
// columns): no sideways scrolling, nothing wider than the window, no table scrolled inside its
// card (with a 4K frame's pixel counts); report.html's
// plot labels clear of each other and of the points on both cost axes, its comparer's slider
// changing the picture, a click on RMSE sorting by it.
TEST(Cli, ReportsReadAtThreeWidthsWithoutOverlapsInChromium) {
    const fs::path bench = scratch("widths-bench"), tune = scratch("widths-tune");
    ASSERT_EQ(runCli({"bench", "builtin:showcase", "-o", (bench / "b.json").string(),
                      "--techniques", "hard,pcf,vsm,msm-soft", "--sweep", "pcf.size=3,7", "--width",
                      "96", "--height", "64", "--frames", "2"})
                  .exitCode,
              0);
    ASSERT_EQ(runCli({"tune", "builtin:showcase", "--technique", "pcf", "-o", tune.string(),
                      "--width", "96", "--height", "64", "--samples", "4"})
                  .exitCode,
              0);
    // A coloured truth's report: three columns more, the error of each channel.
    const fs::path coloured = scratch("widths-coloured");
    ASSERT_EQ(runCli({"compare", "builtin:sheets", "-o", coloured.string(), "--techniques",
                      "hard,pcf[box3]+translucent,pcss+contact", "--width", "96", "--height", "64",
                      "--shadow-map-size", "256", "--frames", "1", "--samples", "1"})
                  .exitCode,
              0);
    ASSERT_NE(slurp(coloured / "report.html").find("class=\"channels\""), std::string::npos);
    for (const int width : {1000, 1400, 1920}) {
        SCOPED_TRACE(width);
        for (const fs::path& page : {smallComparison() / "report.html", bench / "bench.html",
                                     tune / "tune.html", coloured / "report.html"}) {
            SCOPED_TRACE(page.filename().string());
            const nlohmann::json found = layoutIn(page, width);
            ASSERT_FALSE(found.is_null());
            EXPECT_LE(found["scroll"].get<int>(), found["width"].get<int>()) << found.dump();
            EXPECT_TRUE(found["wide"].empty()) << found["wide"].dump(1);
            EXPECT_TRUE(found["clipped"].empty())
                << "a column scrolled out of its card: " << found["clipped"].dump(1);
            if (page.filename() != "report.html" || page.parent_path() == coloured)
                continue;
            EXPECT_TRUE(found["overlaps"].empty()) << found["overlaps"].dump(1);
            EXPECT_GT(found["labels"].get<int>(), 4) << "labels are drawn, not all left out";
            EXPECT_TRUE(found["slider"].get<bool>());
            EXPECT_TRUE(found["sorted"].get<bool>()) << "a click on RMSE sorts by it";
        }
    }
}

// merge's report.html over a small sweep at 1000, 1400 and 1920 pixels: no sideways scrolling,
// nothing wider than the window, the plots' labels clear of each other and of the points.
TEST(Cli, MergeReportReadsAtThreeWidthsInChromium) {
    const fs::path plan = scratchDir("merge-widths") / "plan.toml";
    std::ofstream(plan) << "width = 64\nheight = 48\nsamples = 4\nshadow_map_size = 256\n"
                           "frames = 1\nscenes = [\"builtin:showcase\", \"builtin:resting\"]\n"
                           "[[techniques]]\nname = \"hard\"\n[[techniques]]\nname = \"pcf\"\n"
                           "pcf.filter = [\"box\", \"poisson\"]\npcf.size = [3, 7]\n";
    const fs::path sweep = scratch("merge-widths-sweep"), report = scratch("merge-widths-report");
    ProcessResult r = runCli({"sweep", plan.string(), "-o", sweep.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = runCli({"merge", sweep.string(), "-o", report.string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const int width : {1000, 1400, 1920}) {
        SCOPED_TRACE(width);
        const nlohmann::json found = layoutIn(report / "report.html", width);
        ASSERT_FALSE(found.is_null());
        EXPECT_LE(found["scroll"].get<int>(), found["width"].get<int>()) << found.dump();
        EXPECT_TRUE(found["wide"].empty()) << found["wide"].dump(1);
        EXPECT_TRUE(found["clipped"].empty()) << found["clipped"].dump(1);
        EXPECT_TRUE(found["overlaps"].empty()) << found["overlaps"].dump(1);
    }
}
