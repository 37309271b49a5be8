// The HTML report: one static page beside its images. The page is small
// (rows of markup and a few kilobytes of CSS and script, no inlined images);
// images are PNG files in the report folder, loaded lazily as rows scroll into
// view, so that a report of hundreds of scenes opens at once from disk
// (file://, no server). The first rows' images, which the first screen shows,
// load eagerly and decode synchronously: with decoding="async" a large image
// can still be a black box when the page is first painted (headless
// Chromium's screenshots showed it).
#include <cmath>
#include <cstdio>
#include <string>

#include "check/atomic_file.hpp"
#include "check/report.hpp"

namespace tessera::check {

namespace {

std::string html_escape(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;
            default: out += c;
        }
    }
    return out;
}

// A relative path as a URL: '/' kept, anything outside the unreserved set percent-encoded.
std::string url_of(std::string_view path) {
    static const char* hex = "0123456789ABCDEF";
    std::string out;
    for (unsigned char c : path) {
        if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_' ||
            c == '.' || c == '~' || c == '/') {
            out += char(c);
        } else {
            out += '%';
            out += hex[c >> 4];
            out += hex[c & 15];
        }
    }
    return out;
}

std::string format(const char* pattern, double value) {
    char text[64];
    std::snprintf(text, sizeof text, pattern, value);
    return text;
}

// A difference in the golden's units: 8-bit steps as well for PNG goldens.
std::string amount(double value, GoldenKind kind) {
    if (!std::isfinite(value)) return "none";
    if (kind == GoldenKind::png) return format("%.4g", value) + " (" + format("%.3g", value * 255.0) + "/255)";
    return format("%.4g", value);
}

std::string pixels_text(double allowed) { return std::isfinite(allowed) ? format("%.0f", std::floor(allowed)) : "no limit"; }

constexpr const char* kStyle = R"CSS(
:root { color-scheme: dark; --bg: #16181c; --row: #1f2228; --text: #e4e6ea; --dim: #9aa0aa;
  --pass: #3fb950; --warn: #d29922; --fail: #f85149; --missing: #a371f7; --error: #ff7b72; }
* { box-sizing: border-box; }
[hidden] { display: none !important; }  /* over the display rules below */
body { margin: 0; background: var(--bg); color: var(--text); font: 14px/1.4 system-ui, sans-serif; }
header { position: sticky; top: 0; z-index: 2; background: #0d0f12; padding: 10px 16px; border-bottom: 1px solid #333; }
h1 { font-size: 18px; margin: 0 8px 0 0; display: inline; }
.chip { display: inline-block; border-radius: 10px; padding: 1px 9px; margin-right: 4px; font-weight: 600; color: #111; }
.chip.pass, .badge.pass { background: var(--pass); } .chip.warn, .badge.warn { background: var(--warn); }
.chip.fail, .badge.fail { background: var(--fail); } .chip.missing, .badge.missing { background: var(--missing); }
.chip.error, .badge.error { background: var(--error); }
.run { color: var(--dim); margin: 4px 0; }
nav button, .modes button { background: #2a2f37; color: var(--text); border: 1px solid #444; border-radius: 4px;
  padding: 2px 8px; cursor: pointer; }
nav button[aria-pressed=true], .modes button[aria-pressed=true] { background: #3b5bdb; border-color: #5c7cfa; }
main { padding: 8px 16px; }
.scene { background: var(--row); border-radius: 6px; margin: 10px 0; padding: 8px 12px; border-left: 5px solid var(--dim); }
.scene[data-status=pass] { border-left-color: var(--pass); } .scene[data-status=warn] { border-left-color: var(--warn); }
.scene[data-status=fail] { border-left-color: var(--fail); } .scene[data-status=missing] { border-left-color: var(--missing); }
.scene[data-status=error] { border-left-color: var(--error); }
body.hide-pass .scene[data-status=pass] { display: none; }
h2 { font-size: 15px; margin: 2px 0; }
.badge { display: inline-block; min-width: 56px; text-align: center; border-radius: 4px; color: #111; font-size: 12px;
  text-transform: uppercase; padding: 1px 4px; margin-right: 6px; }
.file { color: var(--dim); font-weight: normal; font-size: 12px; margin-left: 8px; }
.reason { margin: 2px 0 6px; color: #ffd8d3; white-space: pre-wrap; }
.scene[data-status=pass] .reason, .scene[data-status=warn] .reason { color: #f2dfb0; }
.body { display: flex; gap: 12px; align-items: flex-start; }
.views { flex: 1 1 auto; min-width: 0; }
.side { display: flex; gap: 8px; }
figure { margin: 0; flex: 1 1 0; min-width: 0; max-width: 33%; }  /* a lone image as wide as one of three */
figcaption { color: var(--dim); font-size: 12px; }
img { display: block; width: 100%; height: auto; background: #000; cursor: zoom-in; }
.stack { position: relative; max-width: 66%; }
.stack img.over { position: absolute; left: 0; top: 0; }
.stack input { width: 100%; }
.numbers { flex: 0 0 330px; border-collapse: collapse; font-size: 12px; }
.numbers th { text-align: left; color: var(--dim); font-weight: normal; padding: 1px 8px 1px 0; vertical-align: top; }
.numbers td { padding: 1px 0; font-variant-numeric: tabular-nums; word-break: break-all; }
.modes { margin: 4px 0; }
dialog { background: #0d0f12; color: var(--text); border: 1px solid #555; width: 96vw; max-width: 96vw; }
dialog .panes { display: flex; gap: 8px; }
dialog .pane { flex: 1 1 0; height: 60vh; overflow: hidden; position: relative; background: #000; cursor: crosshair; }
dialog .pane img { position: absolute; max-width: none; width: auto; image-rendering: pixelated; cursor: crosshair; }
dialog .pane span { position: absolute; left: 4px; top: 2px; background: #000a; padding: 0 4px; z-index: 1; }
)CSS";

// Modes per row (side by side, slider, flicker), filters, and the pixel zoom.
// Plain script, no libraries: it runs from file:// with no network.
constexpr const char* kScript = R"JS(
'use strict';
const flickers = new Map();
function setMode(row, mode) {
  if (!row.querySelector('.stack')) return;
  row.dataset.mode = mode;
  row.querySelectorAll('.modes button').forEach(b => b.setAttribute('aria-pressed', String(b.dataset.mode === mode)));
  row.querySelector('.side').hidden = mode !== 'side';
  const stack = row.querySelector('.stack');
  stack.hidden = mode === 'side';
  const over = stack.querySelector('img.over');
  const slider = stack.querySelector('input');
  slider.hidden = mode !== 'slider';
  clearInterval(flickers.get(row));
  flickers.delete(row);
  over.style.visibility = 'visible';
  if (mode === 'slider') over.style.clipPath = 'inset(0 ' + (100 - slider.value) + '% 0 0)';
  if (mode === 'flicker') {
    over.style.clipPath = 'none';
    flickers.set(row, setInterval(() => {
      over.style.visibility = over.style.visibility === 'hidden' ? 'visible' : 'hidden';
      stack.querySelector('.showing').textContent = over.style.visibility === 'hidden' ? 'expected' : 'actual';
    }, 600));
  }
  stack.querySelector('.showing').textContent = mode === 'flicker' ? 'actual' : 'left: actual, right: expected';
}
document.querySelectorAll('.scene').forEach(row => {
  row.querySelectorAll('.modes button').forEach(b => b.addEventListener('click', () => setMode(row, b.dataset.mode)));
  const slider = row.querySelector('.stack input');
  if (slider) slider.addEventListener('input', () => {
    row.querySelector('img.over').style.clipPath = 'inset(0 ' + (100 - slider.value) + '% 0 0)';
  });
});
document.querySelectorAll('nav button[data-mode]').forEach(b => b.addEventListener('click', () => {
  document.querySelectorAll('nav button[data-mode]').forEach(o => o.setAttribute('aria-pressed', String(o === b)));
  document.querySelectorAll('.scene').forEach(row => setMode(row, b.dataset.mode));
}));
document.getElementById('hide-pass').addEventListener('change', e => document.body.classList.toggle('hide-pass', e.target.checked));

// Zoom: every image of the row, cropped around the same pixel and magnified without smoothing.
const zoom = document.getElementById('zoom');
let zoomed = null;
function drawZoom() {
  const { row, x, y, scale } = zoomed;
  zoom.querySelector('.where').textContent = row.dataset.name + ': pixel (' + x + ', ' + y + '), ' + scale + '×';
  zoom.querySelectorAll('.pane').forEach(pane => {
    const img = pane.querySelector('img');
    img.style.width = (Number(row.dataset.width) * scale) + 'px';
    img.style.left = (pane.clientWidth / 2 - (x + 0.5) * scale) + 'px';
    img.style.top = (pane.clientHeight / 2 - (y + 0.5) * scale) + 'px';
  });
}
function openZoom(row, img, event) {
  const rect = img.getBoundingClientRect();
  const width = Number(row.dataset.width), height = Number(row.dataset.height);
  const panes = zoom.querySelector('.panes');
  panes.textContent = '';
  row.querySelectorAll('.side img').forEach(source => {
    const pane = document.createElement('div');
    pane.className = 'pane';
    const label = document.createElement('span');
    label.textContent = source.alt;
    const copy = document.createElement('img');
    copy.src = source.getAttribute('src');
    copy.alt = source.alt;
    pane.append(label, copy);
    pane.addEventListener('click', e => {  // recentre on the clicked pixel
      const r = pane.getBoundingClientRect();
      zoomed.x = Math.max(0, Math.min(width - 1, Math.floor(zoomed.x + 0.5 + (e.clientX - r.left - r.width / 2) / zoomed.scale)));
      zoomed.y = Math.max(0, Math.min(height - 1, Math.floor(zoomed.y + 0.5 + (e.clientY - r.top - r.height / 2) / zoomed.scale)));
      drawZoom();
    });
    panes.append(pane);
  });
  zoomed = { row, scale: 8,
    x: Math.max(0, Math.min(width - 1, Math.floor((event.clientX - rect.left) / rect.width * width))),
    y: Math.max(0, Math.min(height - 1, Math.floor((event.clientY - rect.top) / rect.height * height))) };
  zoom.showModal();
  drawZoom();
}
document.querySelectorAll('.scene img').forEach(img => img.addEventListener('click', e => openZoom(img.closest('.scene'), img, e)));
zoom.querySelectorAll('button[data-scale]').forEach(b => b.addEventListener('click', () => {
  zoomed.scale = Math.max(1, Math.min(64, zoomed.scale * Number(b.dataset.scale)));
  drawZoom();
}));
zoom.querySelector('button.close').addEventListener('click', () => zoom.close());
document.querySelectorAll('.max-at').forEach(link => link.addEventListener('click', e => {
  e.preventDefault();
  const row = link.closest('.scene');
  const img = row.querySelector('.side img');
  const r = img.getBoundingClientRect();
  openZoom(row, img, { clientX: r.left + (Number(link.dataset.x) + 0.5) / Number(row.dataset.width) * r.width,
                       clientY: r.top + (Number(link.dataset.y) + 0.5) / Number(row.dataset.height) * r.height });
}));
document.body.dataset.ready = 'true';
)JS";

// Rows whose images the first screen of the report shows (about three rows at 1000 px).
constexpr std::size_t kFirstScreenRows = 3;

std::string image_tag(const std::string& link, const char* alt, const SceneResult& r, bool first_screen,
                      const char* css_class = "") {
    return "<img src=\"" + url_of(link) + "\" alt=\"" + alt + "\" class=\"" + css_class + "\" " +
           (first_screen ? "loading=\"eager\" decoding=\"sync\"" : "loading=\"lazy\" decoding=\"async\"") +
           " width=\"" + std::to_string(r.width) + "\" height=\"" + std::to_string(r.height) + "\">";
}

std::string numbers_table(const SceneResult& r) {
    std::string t = "<table class=\"numbers\">";
    const auto row = [&](const std::string& name, const std::string& value) {
        t += "<tr><th>" + name + "</th><td>" + value + "</td></tr>";
    };
    const Thresholds& th = r.thresholds;
    const GoldenKind kind = r.golden_kind;
    if (r.compared) {
        const Metrics& m = r.metrics;
        row("largest difference", amount(m.max_error, kind) + " at <a href=\"#\" class=\"max-at\" data-x=\"" +
                                      std::to_string(m.max_x) + "\" data-y=\"" + std::to_string(m.max_y) + "\">(" +
                                      std::to_string(m.max_x) + ", " + std::to_string(m.max_y) + ")</a> channel " +
                                      std::to_string(m.max_channel));
        row("mean / RMS", format("%.3g", m.mean_error) + " / " + format("%.3g", m.rms_error));
        row("PSNR", std::isfinite(m.psnr) ? format("%.2f dB", m.psnr) : "identical");
        if (m.ignored_pixels > 0)
            row("ignored pixels", std::to_string(m.ignored_pixels) + " (not compared; blue in the diff)");
        row("pixels over fail", std::to_string(m.pixels_over_fail) + " (allowed " +
                                    pixels_text(allowed_pixels(th.fail_pixels, th.fail_ratio, m.pixels)) + ")");
        row("pixels over warn", std::to_string(m.pixels_over_warn) + " (warn past " +
                                    pixels_text(allowed_pixels(th.warn_pixels, th.warn_ratio, m.pixels)) + ", fail past " +
                                    pixels_text(allowed_pixels(th.max_warn_pixels, th.max_warn_ratio, m.pixels)) + ")");
        if (m.perceptual_fail >= 0) row("perceptual (Yee)", std::to_string(m.perceptual_fail) + " pixels fail");
    }
    row("tolerances", "fail " + amount(th.fail, kind) + (th.fail_relative > 0 ? format(" and %.3g relative", th.fail_relative) : "") +
                          ", warn " + amount(th.warn, kind) + ", ceiling " + amount(th.max_error, kind));
    if (r.width > 0)
        row("image", std::to_string(r.width) + "×" + std::to_string(r.height) + ", MSAA " + std::to_string(r.msaa) + ", " +
                         (kind == GoldenKind::exr ? "EXR (scene-linear radiance)" : "PNG (8-bit display)"));
    row("time", format("render %.0f ms", r.render_ms) + format(", compare %.0f ms", r.compare_ms));
    row("golden", html_escape(r.golden.string()));
    if (!r.images.diff.empty())
        row("diff", "|actual − expected|, largest channel; full brightness at " + amount(r.images.diff_scale, kind));
    if (!r.update.empty()) row("update", html_escape(r.update));
    return t + "</table>";
}

std::string scene_row(const SceneResult& r, bool first_screen) {
    const std::string status(status_name(r.status));
    std::string row = "<section class=\"scene\" id=\"scene-" + html_escape(r.name) + "\" data-status=\"" + status +
                      "\" data-name=\"" + html_escape(r.name) + "\" data-width=\"" + std::to_string(r.width) +
                      "\" data-height=\"" + std::to_string(r.height) + "\" data-mode=\"side\">\n";
    row += "<h2><span class=\"badge " + status + "\">" + status + "</span><span class=\"name\">" + html_escape(r.name) +
           "</span><span class=\"file\">" + html_escape(r.scene.string()) + "</span></h2>\n";
    if (!r.reason.empty()) row += "<p class=\"reason\">" + html_escape(r.reason) + "</p>\n";
    row += "<div class=\"body\"><div class=\"views\">";
    const bool both = !r.images.expected.empty() && !r.images.actual.empty();
    if (both && r.images.expected != r.images.actual)
        row += "<div class=\"modes\"><button data-mode=\"side\" aria-pressed=\"true\">side by side</button>"
               "<button data-mode=\"slider\" aria-pressed=\"false\">slider</button>"
               "<button data-mode=\"flicker\" aria-pressed=\"false\">flicker</button></div>";
    row += "<div class=\"side\">";
    if (both && r.images.expected == r.images.actual) {
        row += "<figure>" + image_tag(r.images.actual, "expected = actual", r, first_screen) +
               "<figcaption>expected = actual (identical)</figcaption></figure>";
    } else {
        if (!r.images.expected.empty())
            row += "<figure>" + image_tag(r.images.expected, "expected", r, first_screen) + "<figcaption>expected</figcaption></figure>";
        if (!r.images.actual.empty())
            row += "<figure>" + image_tag(r.images.actual, "actual", r, first_screen) + "<figcaption>actual</figcaption></figure>";
        if (!r.images.diff.empty())
            row += "<figure>" + image_tag(r.images.diff, "diff", r, first_screen) + "<figcaption>diff</figcaption></figure>";
    }
    row += "</div>";
    if (both && r.images.expected != r.images.actual)
        row += "<div class=\"stack\" hidden>" + image_tag(r.images.expected, "expected", r, false, "under") +
               image_tag(r.images.actual, "actual", r, false, "over") +
               "<input type=\"range\" min=\"0\" max=\"100\" value=\"50\" aria-label=\"slider\">"
               "<figcaption class=\"showing\"></figcaption></div>";
    row += "</div>" + numbers_table(r) + "</div>\n</section>\n";
    return row;
}

}  // namespace

void write_html_report(const CheckRun& run, const std::filesystem::path& report_dir) {
    const int failing = run.count(Status::fail) + run.count(Status::missing) + run.count(Status::error);
    std::string html = "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
                       "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>tessera check: ";
    html += failing == 0 ? "all " + std::to_string(run.scenes.size()) + " pass"
                         : std::to_string(failing) + " of " + std::to_string(run.scenes.size()) + " not passing";
    html += "</title>\n<style>" + std::string(kStyle) + "</style></head>\n<body>\n<header><h1>tessera check</h1>";
    for (Status s : {Status::error, Status::fail, Status::missing, Status::warn, Status::pass}) {
        const int n = run.count(s);
        if (n > 0)
            html += "<span class=\"chip " + std::string(status_name(s)) + "\">" + std::to_string(n) + " " +
                    std::string(status_name(s)) + "</span>";
    }
    html += "<p class=\"run\">" + std::to_string(run.scenes.size()) + " scenes in " + format("%.1f s", run.seconds) +
            ", " + html_escape(run.isa) + " kernels, " + std::to_string(run.threads) + " threads" +
            (run.updated() > 0 ? ", " + std::to_string(run.updated()) + " golden images updated" : "") +
            ". Failures first, worst first. Click an image to zoom to its pixels.</p>\n";
    html += "<nav><label><input type=\"checkbox\" id=\"hide-pass\"> hide passing</label> &nbsp; every row: "
            "<button data-mode=\"side\" aria-pressed=\"true\">side by side</button> "
            "<button data-mode=\"slider\" aria-pressed=\"false\">slider</button> "
            "<button data-mode=\"flicker\" aria-pressed=\"false\">flicker</button></nav></header>\n<main id=\"scenes\">\n";
    std::size_t index = 0;
    for (const SceneResult* r : worst_first(run)) html += scene_row(*r, index++ < kFirstScreenRows);
    html += "</main>\n<dialog id=\"zoom\"><p><span class=\"where\"></span> &nbsp; "
            "<button data-scale=\"0.5\">−</button> <button data-scale=\"2\">+</button> "
            "<button class=\"close\">close (Esc)</button> &nbsp; click a pane to centre it there</p>"
            "<div class=\"panes\"></div></dialog>\n<script>" +
            std::string(kScript) + "</script>\n</body></html>\n";
    write_text_atomically(report_dir / "index.html", html);
}

}  // namespace tessera::check
