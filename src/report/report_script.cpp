#include "report/report_script.h"

namespace penumbra {

const std::string_view kComparerHtml = R"(<h2>Compare images</h2>
<section class="card comparer" id="comparer">
<div class="controls">
<label>Left <select id="cmp-a"></select></label>
<label>Right <select id="cmp-b"></select></label>
<label>Zoom <input type="range" id="cmp-zoom" min="1" max="32" value="1"></label>
<span id="cmp-values" class="values">move the cursor over the image</span>
</div>
<canvas id="cmp-canvas" width="16" height="16"></canvas>
<input type="range" id="cmp-split" min="0" max="1000" value="500" aria-label="split">
<p class="note">Drag the slider to move the split; click the image to zoom around that point
(nearest pixels, no smoothing); values are the pixels' grey levels, 0 to 1 (a heat map's are
its colour).</p>
</section>
)";

const std::string_view kReportScript = R"JS(
"use strict";
(function () {
  // Sorting: a header's click sorts the rows by its column, again the other way.
  const table = document.querySelector("table.results");
  if (table) {
    const heads = Array.from(table.querySelectorAll("thead th.sortable"));
    heads.forEach(function (th) {
      th.addEventListener("click", function () {
        const row = th.parentElement;
        let column = 0;
        // Header cells of the second row follow the technique's, which spans both rows.
        if (row.classList.contains("groups")) column = 0;
        else column = Array.from(row.children).indexOf(th) + 1;
        const body = table.tBodies[0];
        const rows = Array.from(body.rows);
        const down = th.dataset.order !== "asc";
        heads.forEach(function (h) { delete h.dataset.order; });
        th.dataset.order = down ? "asc" : "desc";
        const text = th.dataset.type === "text";
        rows.sort(function (a, b) {
          const x = a.cells[column].dataset.value, y = b.cells[column].dataset.value;
          const c = text ? x.localeCompare(y) : (parseFloat(x) || 0) - (parseFloat(y) || 0);
          return down ? c : -c;
        });
        rows.forEach(function (r) { body.appendChild(r); });
      });
    });
  }

  // The comparer.
  const canvas = document.getElementById("cmp-canvas");
  if (!canvas) return;
  const sources = [];
  const truth = document.querySelector("figure.reference img");
  if (truth) sources.push({ label: "truth", img: truth });
  document.querySelectorAll("figure.technique").forEach(function (f) {
    const name = f.dataset.technique;
    [["visibility", "visibility"], ["heatmap", "heat map"], ["lit", "lit image"]].forEach(
      function (k) {
        const img = f.querySelector("img." + k[0]);
        if (img) sources.push({ label: name + ": " + k[1], img: img });
      });
  });
  const selA = document.getElementById("cmp-a"), selB = document.getElementById("cmp-b");
  const split = document.getElementById("cmp-split"), zoom = document.getElementById("cmp-zoom");
  const values = document.getElementById("cmp-values");
  if (sources.length === 0) {
    document.getElementById("comparer").hidden = true;
    return;
  }
  sources.forEach(function (s, i) {
    selA.add(new Option(s.label, i));
    selB.add(new Option(s.label, i));
  });
  selB.value = String(Math.min(1, sources.length - 1));
  const pixels = new Map(); // a source's RGBA, read once
  function pixelsOf(i) {
    if (pixels.has(i)) return pixels.get(i);
    const img = sources[i].img, c = document.createElement("canvas");
    c.width = img.naturalWidth; c.height = img.naturalHeight;
    const g = c.getContext("2d");
    g.drawImage(img, 0, 0);
    const data = { w: c.width, h: c.height, rgba: g.getImageData(0, 0, c.width, c.height).data,
                   canvas: c };
    pixels.set(i, data);
    return data;
  }
  let centre = null; // the zoom's centre in image pixels
  function draw() {
    const a = pixelsOf(+selA.value), b = pixelsOf(+selB.value);
    const w = a.w, h = a.h;
    const shown = Math.min(canvas.parentElement.clientWidth - 40, 900);
    canvas.style.width = Math.max(shown, 16) + "px";
    canvas.width = Math.max(1, Math.round(Math.max(shown, 16)));
    canvas.height = Math.max(1, Math.round(canvas.width * h / w));
    const z = +zoom.value;
    if (!centre) centre = { x: w / 2, y: h / 2 };
    const vw = w / z, vh = h / z;
    const sx = Math.min(Math.max(centre.x - vw / 2, 0), w - vw);
    const sy = Math.min(Math.max(centre.y - vh / 2, 0), h - vh);
    const g = canvas.getContext("2d");
    g.imageSmoothingEnabled = false;
    g.clearRect(0, 0, canvas.width, canvas.height);
    g.drawImage(a.canvas, sx, sy, vw, vh, 0, 0, canvas.width, canvas.height);
    const cut = Math.round(canvas.width * split.value / 1000);
    g.save();
    g.beginPath(); g.rect(cut, 0, canvas.width - cut, canvas.height); g.clip();
    g.drawImage(b.canvas, sx * b.w / w, sy * b.h / h, vw * b.w / w, vh * b.h / h,
                0, 0, canvas.width, canvas.height);
    g.restore();
    g.fillStyle = "#ffd400"; g.fillRect(cut - 1, 0, 2, canvas.height);
    canvas.dataset.view = [sx, sy, vw, vh].join(" ");
  }
  function imagePixel(event) {
    const a = pixelsOf(+selA.value);
    const r = canvas.getBoundingClientRect(), v = canvas.dataset.view.split(" ").map(Number);
    return { x: Math.floor(v[0] + (event.clientX - r.left) / r.width * v[2]),
             y: Math.floor(v[1] + (event.clientY - r.top) / r.height * v[3]), w: a.w, h: a.h };
  }
  function valueAt(i, p) {
    const s = pixelsOf(i);
    const x = Math.min(s.w - 1, Math.floor(p.x * s.w / p.w));
    const y = Math.min(s.h - 1, Math.floor(p.y * s.h / p.h));
    const o = 4 * (y * s.w + x), d = s.rgba;
    if (d[o] === d[o + 1] && d[o] === d[o + 2]) return (d[o] / 255).toFixed(3);
    return "rgb(" + d[o] + ", " + d[o + 1] + ", " + d[o + 2] + ")";
  }
  canvas.addEventListener("mousemove", function (e) {
    const p = imagePixel(e);
    if (p.x < 0 || p.y < 0 || p.x >= p.w || p.y >= p.h) return;
    // Rendered pixels: a reduced page image's pixel starts at scale times its coordinates.
    const scale = +(document.querySelector("main").dataset.pageScale || 1);
    values.textContent = "pixel " + p.x * scale + ", " + p.y * scale +
                         (scale > 1 ? " (mean of " + scale + " \u00d7 " + scale + ")" : "") +
                         ": left " + valueAt(+selA.value, p) + ", right " +
                         valueAt(+selB.value, p);
  });
  canvas.addEventListener("click", function (e) {
    centre = imagePixel(e);
    if (+zoom.value === 1) zoom.value = 8;
    draw();
  });
  [selA, selB, split, zoom].forEach(function (el) { el.addEventListener("input", draw); });
  window.addEventListener("resize", draw);
  function start() {
    if (sources.every(function (s) { return s.img.complete; })) draw();
    else setTimeout(start, 20);
  }
  start();
})();
)JS";

const std::string_view kReportInteractiveStyle = R"(
table.results th { white-space: normal; vertical-align: bottom; line-height: 1.2; }
table.results th small { display: block; font-weight: 400; color: var(--muted); }
table.results tr.groups th { text-align: center; background: #e8edf3; }
table.results th.sortable { cursor: pointer; }
table.results th[data-order="asc"]::after { content: " \25B2"; font-size: 10px; }
table.results th[data-order="desc"]::after { content: " \25BC"; font-size: 10px; }
table.results { font-size: 13.5px; }
table.results th, table.results td { padding: 5px 6px; }
table.results .group, table.results td.first { border-left: 1px solid var(--line); }
td.name { text-align: left; max-width: 190px; }
table.results td .count { color: var(--muted); font-size: 11px; white-space: normal; }
td.name .params { color: var(--muted); font-weight: 400; font-size: 12px; overflow: hidden;
  text-overflow: ellipsis; white-space: nowrap; max-width: 190px; }
.plot-switch { display: flex; gap: 16px; margin-bottom: 8px; font-size: 14px; }
.plots svg.log { display: none; }
#cost-log:checked ~ .plots svg.log { display: block; }
#cost-log:checked ~ .plots svg.error-vs-cost:not(.log) { display: none; }
.plots { display: flex; flex-wrap: wrap; gap: 16px; align-items: flex-start; }
.plots svg { flex: 1 1 560px; min-width: 0; }
ul.legend { list-style: none; margin: 0; padding: 0; font-size: 13px; flex: 0 1 260px; }
ul.legend li { margin: 2px 0; } ul.legend li.on-front { font-weight: 600; }
ul.legend .dot { display: inline-block; width: 10px; height: 10px; border-radius: 5px;
  margin-right: 6px; }
ul.legend .dot.dashed { border-radius: 0; height: 3px; width: 14px; margin-bottom: 3px; }
svg path.front { fill: none; stroke: #2f855a; stroke-width: 2; stroke-dasharray: 6 4; }
svg .on-front circle { stroke: #22543d; stroke-width: 2.5; }
svg .plot-label { fill: var(--ink); font-size: 12px; }
svg .front-label { fill: #22543d; font-weight: 600; }
.comparer .controls { display: flex; flex-wrap: wrap; gap: 12px 20px; align-items: center;
  margin-bottom: 10px; font-size: 14px; }
.comparer select { max-width: 260px; }
.comparer canvas { display: block; image-rendering: pixelated; max-width: 100%;
  background: #e4e7eb; cursor: crosshair; }
.comparer #cmp-split { width: 100%; max-width: 900px; margin-top: 8px; }
.comparer .values { font-variant-numeric: tabular-nums; color: var(--muted); }
)";

} // namespace penumbra
