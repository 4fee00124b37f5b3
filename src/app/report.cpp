// The HTML report of `caustica converge`: one self-contained page with the PNGs embedded as
// data URIs, a tabbed viewer (zoom, pan, exposure), an inline-SVG log-log plot and tables.
#include "app/report.h"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <unistd.h>
#include "io/atomic_file.h"
#include "io/json_reader.h"

namespace caustica {
namespace fs = std::filesystem;

namespace {

// The error counter is installed before anything else so the self-check sees every error.
// The CSP forbids any fetch: the page must work from file:// with no network.
const char* kHead = R"HTML(<meta http-equiv="Content-Security-Policy" content="default-src 'none'; img-src data:; style-src 'unsafe-inline'; script-src 'unsafe-inline'">
<link rel="icon" href="data:,">
<script>
window.reportErrors = 0;
function reportError() { window.reportErrors++; if (window.reportSelftest) window.reportSelftest(); }
window.onerror = reportError;
window.addEventListener('unhandledrejection', reportError);
document.addEventListener('securitypolicyviolation', reportError);
</script>
<style>
body { font: 14px/1.4 system-ui, sans-serif; margin: 16px 24px; color: #222; background: #fafafa; }
h1 { font-size: 20px; margin: 0 0 12px; } h2 { font-size: 16px; margin: 18px 0 8px; }
.top { display: grid; grid-template-columns: minmax(0, 1fr) 560px; gap: 20px; align-items: start; }
@media (max-width: 1100px) { .top { grid-template-columns: minmax(0, 1fr); } }
#tabs button { font: inherit; margin: 0 4px 4px 0; padding: 3px 10px; border: 1px solid #bbb; border-radius: 4px;
  background: #fff; cursor: pointer; }
#tabs button.active { background: #2d6cdf; border-color: #2d6cdf; color: #fff; }
kbd { font-size: 11px; opacity: 0.7; margin-right: 4px; }
.controls { display: flex; gap: 14px; align-items: center; flex-wrap: wrap; margin: 4px 0 6px; color: #555; }
#view { display: block; width: 100%; height: 560px; background: #2b2b2b; cursor: grab; border-radius: 4px; }
#thumbs { display: grid; grid-template-columns: repeat(auto-fill, minmax(200px, 1fr)); gap: 12px; }
figure { margin: 0; padding: 6px; background: #fff; border: 2px solid #ddd; border-radius: 4px; cursor: pointer; }
figure.active { border-color: #2d6cdf; }
figure img { display: block; width: 100%; image-rendering: pixelated; }
figcaption { text-align: center; margin-top: 4px; }
table { border-collapse: collapse; background: #fff; }
th, td { border: 1px solid #ddd; padding: 3px 10px; text-align: left; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
.scroll { max-height: 420px; overflow: auto; display: inline-block; }
svg { background: #fff; border: 1px solid #ddd; border-radius: 4px; width: 100%; height: auto; }
#selftest { color: #888; font-size: 12px; }
</style>
</head>
<body>
)HTML";

const char* kScript = R"HTML(<script>
(function () {
  'use strict';
  var figures = Array.prototype.slice.call(document.querySelectorAll('#thumbs figure'));
  var tabs = Array.prototype.slice.call(document.querySelectorAll('#tabs button'));
  var canvas = document.getElementById('view'), ctx = canvas.getContext('2d');
  var slider = document.getElementById('exposure'), status = document.getElementById('status');
  var images = figures.map(function (f) { return { label: f.dataset.label, src: f.querySelector('img').src }; });
  var loaded = 0, current = 0, stops = 0, drag = null, mouse = null;
  var view = { scale: 1, x: 0, y: 0, set: false };  // shared by all tabs: canvas px = image px * scale + x
  var exposed = document.createElement('canvas'), exposedKey = '';

  function selftest() {
    document.getElementById('selftest').textContent = 'images=' + images.length + ' loaded=' + loaded +
      ' plot_series=' + document.querySelectorAll('#plot .series').length + ' errors=' + window.reportErrors;
  }
  window.reportSelftest = selftest;

  function toLinear(v) { return v <= 0.04045 ? v / 12.92 : Math.pow((v + 0.055) / 1.055, 2.4); }
  function toSrgb(v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * Math.pow(v, 1 / 2.4) - 0.055; }
  // sRGB byte -> linear -> * 2^stops -> sRGB byte.
  function exposureTable(s) {
    var table = new Uint8ClampedArray(256), gain = Math.pow(2, s);
    for (var i = 0; i < 256; i++) table[i] = Math.round(255 * toSrgb(Math.min(1, toLinear(i / 255) * gain)));
    return table;
  }
  function source() {
    var e = images[current];
    if (!e || !e.canvas) return null;
    if (stops === 0) return e.canvas;
    if (exposedKey !== current + ':' + stops) {
      var table = exposureTable(stops), src = e.pixels.data, out = new ImageData(e.w, e.h), d = out.data;
      for (var p = 0; p < src.length; p += 4) {
        d[p] = table[src[p]]; d[p + 1] = table[src[p + 1]]; d[p + 2] = table[src[p + 2]]; d[p + 3] = src[p + 3];
      }
      exposed.width = e.w; exposed.height = e.h;
      exposed.getContext('2d').putImageData(out, 0, 0);
      exposedKey = current + ':' + stops;
    }
    return exposed;
  }
  function draw() {
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.clearRect(0, 0, canvas.width, canvas.height);
    var src = source();
    if (src) {
      ctx.imageSmoothingEnabled = false;
      ctx.setTransform(view.scale, 0, 0, view.scale, view.x, view.y);
      ctx.drawImage(src, 0, 0);
    }
    showStatus();
  }
  function showStatus() {
    var e = images[current], text = images.length ? e.label + ' \u00b7 zoom ' + Math.round(view.scale * 100) + '%' : 'no images';
    if (e && e.pixels && mouse) {
      var x = Math.floor((mouse.x - view.x) / view.scale), y = Math.floor((mouse.y - view.y) / view.scale);
      if (x >= 0 && y >= 0 && x < e.w && y < e.h) {
        var i = 4 * (y * e.w + x), d = e.pixels.data;
        text += ' \u00b7 pixel ' + x + ', ' + y + ' \u00b7 sRGB ' + d[i] + ' ' + d[i + 1] + ' ' + d[i + 2];
      }
    }
    status.textContent = text;
  }
  function fit() {
    var e = images[current];
    if (!e || !e.w) return;
    var s = Math.min(canvas.width / e.w, canvas.height / e.h);
    view.scale = s >= 1 ? Math.floor(s) : s;  // whole screen pixels per image pixel when enlarging
    view.x = Math.round((canvas.width - e.w * view.scale) / 2);
    view.y = Math.round((canvas.height - e.h * view.scale) / 2);
    view.set = true;
  }
  function zoomAt(factor, px, py) {
    var s = Math.min(512, Math.max(1 / 64, view.scale * factor));
    view.x = px - (px - view.x) * s / view.scale;
    view.y = py - (py - view.y) * s / view.scale;
    view.scale = s; view.set = true;
    draw();
  }
  function select(i) {
    if (!images.length) return;
    current = (i % images.length + images.length) % images.length;
    tabs.forEach(function (t, k) { t.classList.toggle('active', k === current); });
    figures.forEach(function (f, k) { f.classList.toggle('active', k === current); });
    if (!view.set) fit();
    draw();
  }
  function setExposure(s) {
    stops = Math.max(-8, Math.min(8, Math.round(s * 4) / 4));
    slider.value = stops;
    document.getElementById('exposure-value').textContent = (stops > 0 ? '+' : '') + stops.toFixed(2) + ' stops';
    draw();
  }
  function resize() {
    var r = canvas.getBoundingClientRect(), dpr = window.devicePixelRatio || 1;
    canvas.width = Math.max(1, Math.round(r.width * dpr));
    canvas.height = Math.max(1, Math.round(r.height * dpr));
    draw();
  }
  function canvasPoint(ev) {
    var r = canvas.getBoundingClientRect(), dpr = window.devicePixelRatio || 1;
    return { x: (ev.clientX - r.left) * dpr, y: (ev.clientY - r.top) * dpr };
  }

  images.forEach(function (e, i) {
    var img = new Image();
    img.onload = function () {
      var c = document.createElement('canvas');
      c.width = e.w = img.naturalWidth; c.height = e.h = img.naturalHeight;
      var g = c.getContext('2d');
      g.drawImage(img, 0, 0);
      e.pixels = g.getImageData(0, 0, e.w, e.h);  // allowed: data URIs do not taint the canvas
      e.canvas = c;
      loaded++;
      if (i === current) { if (!view.set) fit(); draw(); }
      selftest();
    };
    img.onerror = function () { reportError(); };
    img.src = e.src;
  });
  tabs.forEach(function (t, i) { t.addEventListener('click', function () { select(i); }); });
  figures.forEach(function (f, i) { f.addEventListener('click', function () { select(i); }); });
  slider.addEventListener('input', function () { setExposure(parseFloat(slider.value)); });
  document.getElementById('reset').addEventListener('click', function () { fit(); draw(); });
  canvas.addEventListener('wheel', function (ev) {
    ev.preventDefault();
    var p = canvasPoint(ev);
    zoomAt(ev.deltaY < 0 ? 1.25 : 0.8, p.x, p.y);
  }, { passive: false });
  canvas.addEventListener('mousedown', function (ev) { drag = canvasPoint(ev); ev.preventDefault(); });
  window.addEventListener('mouseup', function () { drag = null; });
  window.addEventListener('mousemove', function (ev) {
    var p = canvasPoint(ev);
    mouse = ev.target === canvas ? p : null;
    if (drag) { view.x += p.x - drag.x; view.y += p.y - drag.y; view.set = true; drag = p; draw(); } else showStatus();
  });
  document.addEventListener('keydown', function (ev) {
    if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
    var k = ev.key, cx = canvas.width / 2, cy = canvas.height / 2;
    if (/^[1-9]$/.test(k)) { if (+k <= images.length) select(+k - 1); }
    else if (k === 'ArrowRight' || k === 'j') select(current + 1);
    else if (k === 'ArrowLeft' || k === 'k') select(current - 1);
    else if (k === '+' || k === '=') zoomAt(1.25, cx, cy);
    else if (k === '-' || k === '_') zoomAt(0.8, cx, cy);
    else if (k === '0') { fit(); draw(); }
    else if (k === 'e') setExposure(stops + 0.5);
    else if (k === 'E') setExposure(stops - 0.5);
    else return;
    ev.preventDefault();
  });
  window.addEventListener('resize', resize);
  resize();
  select(0);
  selftest();
})();
</script>
)HTML";

std::string html_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
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

std::string base64(const std::string& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const size_t n = std::min<size_t>(3, bytes.size() - i);
    uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
    if (n > 1) v |= uint32_t(uint8_t(bytes[i + 1])) << 8;
    if (n > 2) v |= uint32_t(uint8_t(bytes[i + 2]));
    out += digits[(v >> 18) & 63];
    out += digits[(v >> 12) & 63];
    out += n > 1 ? digits[(v >> 6) & 63] : '=';
    out += n > 2 ? digits[v & 63] : '=';
  }
  return out;
}

std::string read_png(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw InputError(path.string() + ": report image not found");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot read report image");
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0) throw InputError(path.string() + ": not a PNG file");
  return bytes;
}

std::string format(const char* fmt, double v) {
  std::string out(size_t(std::snprintf(nullptr, 0, fmt, v)), '\0');
  std::snprintf(out.data(), out.size() + 1, fmt, v);
  return out;
}

bool plottable(const ReportPoint& p) {
  return p.seconds > 0 && p.relmse > 0 && std::isfinite(p.seconds) && std::isfinite(p.relmse);
}

// A log10 axis over whole decades [lo, hi], labelled every `step` decades.
struct LogAxis {
  int lo = 0, hi = 1, step = 1;
  LogAxis(double min_value, double max_value) {
    lo = int(std::floor(std::log10(min_value)));
    hi = std::max(lo + 1, int(std::ceil(std::log10(max_value))));
    step = std::max(1, (hi - lo + 9) / 10);
  }
  double at(double v) const { return (std::log10(v) - lo) / (hi - lo); }  // 0..1
};

std::string decade_label(int k) {
  if (k >= 0 && k <= 4) return std::to_string(int(std::lround(std::pow(10.0, k))));
  if (k < 0 && k >= -3) return format("%g", std::pow(10.0, k));
  return "10<tspan dy=\"-6\" font-size=\"9\">" + std::to_string(k) + "</tspan>";
}

// The legend's and the table's name of a series, with its late convergence rate.
std::string series_label(const ReportSeries& s) {
  const double slope = convergence_slope(s);
  if (!std::isfinite(slope)) return s.integrator;
  return s.integrator + format(" (t^%.2f", slope) + (slope > -0.2 ? ", flattening)" : ")");
}

std::string plot_svg(const std::vector<ReportSeries>& series) {
  static const char* colors[] = {"#4e79a7", "#e15759", "#59a14f", "#f28e2b", "#b07aa1", "#76b7b2", "#edc948", "#9c755f"};
  const double W = 560, H = 380, L = 64, R = 16, T = 16, B = 48, pw = W - L - R, ph = H - T - B;
  double t0 = INFINITY, t1 = 0, e0 = INFINITY, e1 = 0;
  for (const ReportSeries& s : series) {
    for (const ReportPoint& p : s.points) {
      if (!plottable(p)) continue;
      t0 = std::min(t0, p.seconds), t1 = std::max(t1, p.seconds);
      e0 = std::min(e0, p.relmse), e1 = std::max(e1, p.relmse);
    }
  }
  std::string svg = "<svg id=\"plot\" viewBox=\"0 0 560 380\" font-size=\"12\">\n";
  if (t1 == 0) return svg + "<text x=\"280\" y=\"190\" text-anchor=\"middle\">no measurements to plot</text></svg>\n";
  const LogAxis tx(t0, t1), ey(e0, e1);
  auto X = [&](double v) { return format("%.1f", L + tx.at(v) * pw); };
  auto Y = [&](double v) { return format("%.1f", T + ph - ey.at(v) * ph); };
  // Grid: a line per decade, fainter lines at 2..9 times a decade.
  for (int k = tx.lo; k <= tx.hi; ++k) {
    for (int m = 1; m < (k < tx.hi && tx.step == 1 ? 10 : 2); ++m) {
      const std::string x = X(m * std::pow(10.0, k));
      svg += "<line x1=\"" + x + "\" x2=\"" + x + format("\" y1=\"%g\"", T) + format(" y2=\"%g\"", T + ph) +
             (m == 1 ? " stroke=\"#ccc\"/>" : " stroke=\"#eee\"/>");
    }
    if ((k - tx.lo) % tx.step == 0) {
      svg += "<text x=\"" + X(std::pow(10.0, k)) + format("\" y=\"%g\" text-anchor=\"middle\">", T + ph + 18) +
             decade_label(k) + "</text>";
    }
  }
  for (int k = ey.lo; k <= ey.hi; ++k) {
    for (int m = 1; m < (k < ey.hi && ey.step == 1 ? 10 : 2); ++m) {
      const std::string y = Y(m * std::pow(10.0, k));
      svg += "<line y1=\"" + y + "\" y2=\"" + y + format("\" x1=\"%g\"", L) + format(" x2=\"%g\"", L + pw) +
             (m == 1 ? " stroke=\"#ccc\"/>" : " stroke=\"#eee\"/>");
    }
    if ((k - ey.lo) % ey.step == 0) {
      svg += "<text y=\"" + Y(std::pow(10.0, k)) + format("\" x=\"%g\" dy=\"4\" text-anchor=\"end\">", L - 6) +
             decade_label(k) + "</text>";
    }
  }
  svg += format("<rect x=\"%g\"", L) + format(" y=\"%g\"", T) + format(" width=\"%g\"", pw) +
         format(" height=\"%g\" fill=\"none\" stroke=\"#888\"/>\n", ph);
  svg += format("<text x=\"%g\"", L + pw / 2) + format(" y=\"%g\" text-anchor=\"middle\">time (s)</text>", H - 8);
  svg += format("<text transform=\"translate(16 %g) rotate(-90)\" text-anchor=\"middle\">relMSE</text>\n", T + ph / 2);
  // One polyline with markers per series, and its legend entry in the top right corner.
  std::string legend;
  int drawn = 0;
  size_t longest = 0;
  for (const ReportSeries& s : series) longest = std::max(longest, series_label(s).size());
  const double lw = 46 + 7.5 * double(longest), lx = L + pw - lw - 8;
  for (const ReportSeries& s : series) {
    std::string points, markers;
    for (const ReportPoint& p : s.points) {
      if (!plottable(p)) continue;
      points += X(p.seconds) + "," + Y(p.relmse) + " ";
      markers += "<circle cx=\"" + X(p.seconds) + "\" cy=\"" + Y(p.relmse) + "\" r=\"3.5\"><title>" +
                 html_escape(s.integrator) + format(": %.3g s", p.seconds) + format(", relMSE %.3g", p.relmse) +
                 "</title></circle>";
    }
    if (points.empty()) continue;
    const std::string color = colors[drawn % 8];
    svg += "<g class=\"series\" stroke=\"" + color + "\" fill=\"" + color + "\"><polyline points=\"" + points +
           "\" fill=\"none\" stroke-width=\"2\"/>" + markers + "</g>\n";
    const double ly = T + 20 + 18 * drawn;
    legend += format("<line x1=\"%g\"", lx + 8) + format(" x2=\"%g\"", lx + 30) + format(" y1=\"%g\"", ly) +
              format(" y2=\"%g\" stroke-width=\"2\" stroke=\"", ly) + color + "\"/>" +
              format("<circle cx=\"%g\"", lx + 19) + format(" cy=\"%g\" r=\"3.5\" fill=\"", ly) + color + "\"/>" +
              format("<text x=\"%g\"", lx + 36) + format(" y=\"%g\" dy=\"4\">", ly) + html_escape(series_label(s)) +
              "</text>\n";
    ++drawn;
  }
  svg += format("<rect x=\"%g\"", lx) + format(" y=\"%g\"", T + 6) + format(" width=\"%g\"", lw) +
         format(" height=\"%g\" fill=\"#fff\" fill-opacity=\"0.9\" stroke=\"#ccc\"/>\n", 18.0 * drawn + 10);
  return svg + legend + "</svg>\n";
}

}  // namespace

double convergence_slope(const ReportSeries& series) {
  double last = 0;
  for (const ReportPoint& p : series.points) {
    if (plottable(p)) last = std::max(last, p.seconds);
  }
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const ReportPoint& p : series.points) {
    if (!plottable(p) || p.seconds < 0.25 * last) continue;
    const double x = std::log(p.seconds), y = std::log(p.relmse);
    n += 1, sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double d = n * sxx - sx * sx;
  if (n < 2 || !(d > 1e-12)) return std::nan("");
  return (n * sxy - sx * sy) / d;
}

void write_report(const std::string& dir, const ReportData& data) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(dir + ": report folder does not exist");
  if (access(dir.c_str(), W_OK) != 0) throw InputError(dir + ": report folder is not writable");

  std::string tabs, thumbs;
  for (size_t i = 0; i < data.images.size(); ++i) {
    const ReportImage& image = data.images[i];
    const std::string png = read_png(fs::path(dir) / image.file), label = html_escape(image.label);
    const std::string key = i < 9 ? "<kbd>" + std::to_string(i + 1) + "</kbd>" : std::string();
    tabs += "<button>" + key + label + "</button>";
    thumbs += "<figure data-label=\"" + label + "\"><img alt=\"" + label + "\" src=\"data:image/png;base64," +
              base64(png) + "\"><figcaption>" + label + "</figcaption></figure>\n";
  }
  std::string facts;
  for (const auto& [key, value] : data.facts) facts += "<tr><th>" + html_escape(key) + "</th><td>" + html_escape(value) + "</td></tr>\n";
  std::string rows;
  for (const ReportSeries& s : data.series) {
    for (const ReportPoint& p : s.points) {
      rows += "<tr><td>" + html_escape(s.integrator) + "</td><td class=\"num\">" + format("%.3f", p.seconds) +
              "</td><td class=\"num\">" + std::to_string(p.passes) + "</td><td class=\"num\">" + format("%.4g", p.rmse) +
              "</td><td class=\"num\">" + format("%.4g", p.relmse) + "</td></tr>\n";
    }
  }
  const std::string title = html_escape(data.title);
  std::string html = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" + title + "</title>\n";
  html += kHead;
  html += "<h1>" + title + "</h1>\n<div class=\"top\">\n<section>\n<div id=\"tabs\">" + tabs + "</div>\n";
  html += "<div class=\"controls\"><label>exposure <input id=\"exposure\" type=\"range\" min=\"-8\" max=\"8\" step=\"0.25\" "
          "value=\"0\"></label><span id=\"exposure-value\">+0.00 stops</span><button id=\"reset\">reset view</button>"
          "<span>keys: 1-9 / \u2190\u2192 / j k tabs, wheel or + - zoom, drag pan, 0 reset, e E exposure</span></div>\n";
  html += "<canvas id=\"view\"></canvas>\n<div id=\"status\" class=\"controls\"></div>\n</section>\n<section>\n";
  html += "<h2>Convergence</h2>\n" + plot_svg(data.series) + "<h2>Facts</h2>\n<table>\n" + facts + "</table>\n";
  html += "</section>\n</div>\n<h2>Images</h2>\n<div id=\"thumbs\">\n" + thumbs + "</div>\n";
  html += "<h2>Measurements</h2>\n<div class=\"scroll\"><table>\n<tr><th>integrator</th><th>seconds</th><th>passes</th>"
          "<th>RMSE</th><th>relMSE</th></tr>\n" + rows + "</table></div>\n";
  html += "<pre id=\"selftest\">selftest: the script did not run</pre>\n";
  html += kScript;
  html += "</body>\n</html>\n";
  write_file_atomically((fs::path(dir) / "index.html").string(), html, "report");
}

}  // namespace caustica
