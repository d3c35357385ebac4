// viewer.html's script, first part: it opens the script's function scope and holds the helpers
// and tables the other parts share (what each timeline shows, the states' colours, round ticks).
#include "viewer_template.hpp"

namespace mote::replay {

const std::string_view kViewerScriptHead = R"js("use strict";
(function () {
  function fail(message) {
    document.title = "mote viewer: error: " + message;
    const box = document.getElementById("error");
    box.textContent = "viewer error: " + message;
    box.hidden = false;
  }
  window.addEventListener("error", (e) => fail(e.message));

  // base64 of little-endian unsigned integers of `size` bytes -> array of numbers.
  function decode(b64, size, Type) {
    const s = atob(b64);
    const out = new Type(Math.floor(s.length / size));
    for (let i = 0; i < out.length; ++i) {
      let v = 0;
      for (let b = size - 1; b >= 0; --b) v = v * 256 + s.charCodeAt(i * size + b);
      out[i] = v;
    }
    return out;
  }

  // The localization states in the order of the data's codes (0, 1, 2) and their colours: Paul
  // Tol's high-contrast scheme, which keeps the three apart with any colour vision and in grey.
  const STATES = [["tracking", "#004488"], ["uncertain", "#ddaa33"], ["lost", "#bb5566"]];
  const RELOCALIZED = "#000000";  // re-localization marks: band, map and timeline

  // [data key, colour, name in the chart's key, and in a stack's value at the cursor (else the
  // stack's total is given)]
  const PHASES = [["motion_ms", "#4e79a7", "motion"], ["sensor_ms", "#f28e2b", "sensor"],
                  ["normalize_ms", "#59a14f", "normalize"], ["resample_ms", "#b07aa1", "resample"],
                  ["estimate_ms", "#9c755f", "estimate"]];
  // log: a logarithmic value axis, for what a global set (a global start or a re-localization,
  // 10-100 times the tracking set) would otherwise flatten, from 1 with fromOne; limit: a data
  // key (one value, or one per update) drawn as a dashed line in the lost colour.
  const TIMELINES = [
    { label: "ms per update", stack: PHASES, log: true },
    { series: [["particles", "#285aff", "particles after the update"]], log: true },
    { series: [["ess", "#e15759", "effective sample size before resampling"]], log: true },
    { label: "particles added", log: true, fromOne: true,
      stack: [["relocalized", RELOCALIZED, "re-localization (a global set)", "re-localized"],
              ["injected", "#76b7b2", "injected (augmented MCL)", "injected"]] },
    { series: [["misfit", "#777777", "misfit (smoothed), lost above the dashed line"]],
      limit: "lost_bound" },
    { series: [["tempering", "#edc948", "tempering exponent"]] },
    { series: [["error_m", "#dc1414", "position error vs reference, m"]] },
  ];
  const LABEL_PX = 20;  // height of a timeline's key line, px
  const AXIS_PX = 30;   // height of a time axis with its labels, px
  const LEFT_PX = 52;   // left margin of the map and the timelines for their value labels, px
  const FONT = "11px system-ui, sans-serif";

  const format = (v) => (Number.isInteger(v) ? String(v) : Number(v).toPrecision(4));

  // Round values 1, 2 or 5 times a power of ten apart, about `count` of them in [lo, hi], and
  // their labels with as many decimals as the step needs.
  function niceTicks(lo, hi, count) {
    if (!(hi > lo)) return { values: [lo], labels: [format(lo)] };
    const raw = (hi - lo) / Math.max(1, count);
    const p = Math.pow(10, Math.floor(Math.log10(raw)));
    const step = [1, 2, 5, 10].map((m) => m * p).find((s) => s >= raw * 0.999);
    const decimals = Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
    const values = [];
    for (let i = Math.ceil(lo / step - 1e-9); i * step <= hi + 1e-9 * step; ++i)
      values.push(i * step);
    const label = (v) => (Math.abs(v) < step / 2 ? 0 : v).toFixed(decimals);
    return { values, labels: values.map(label) };
  }

  // A power of ten as a short label: 0.01, 0.1, 1, 10, 100, 1k, 10k, 100k, 1M.
  function decadeLabel(e) {
    if (e < 0) return Math.pow(10, e).toFixed(-e);
    if (e < 3) return String(Math.pow(10, e));
    return (e < 6 ? String(Math.pow(10, e - 3)) + "k" : String(Math.pow(10, e - 6)) + "M");
  }

  // Seconds -> x pixels over a plot `width` px wide from `left`: each update's bar runs from its
  // stamp to the next update's (the last one's for the median gap), on whole pixels; pick() is
  // the update shown at a pixel (the last one stamped at or before its time).
  function timeScale(t, left, width) {
    const n = t.length, gaps = [];
    for (let k = 1; k < n; ++k) if (t[k] > t[k - 1]) gaps.push(t[k] - t[k - 1]);
    gaps.sort((a, b) => a - b);
    const t0 = t[0], t1 = t[n - 1] + (gaps.length ? gaps[gaps.length >> 1] : 1);
    const x = (s) => left + ((s - t0) / (t1 - t0)) * width;
    return {
      x, t0, t1, left, width,
      bar(k) {  // on whole pixels: no seams between neighbours
        const a = Math.round(x(t[k])), b = Math.round(k + 1 < n ? x(t[k + 1]) : left + width);
        return [a, Math.max(1, b - a)];
      },
      pick(px) {
        const s = t0 + ((px - left) / width) * (t1 - t0);
        let lo = 0, hi = n;
        while (lo < hi) {
          const mid = (lo + hi) >> 1;
          if (t[mid] <= s) lo = mid + 1; else hi = mid;
        }
        return Math.max(0, lo - 1);
      },
    };
  }

  // The time axis along y (its line, ticks and labels below), the title in the left margin;
  // returns the labels drawn.
  function drawTimeAxis(g, scale, y) {
    const ticks = niceTicks(scale.t0, scale.t1, Math.max(2, Math.floor(scale.width / 80)));
    g.strokeStyle = g.fillStyle = "#222";
    g.lineWidth = 1;
    g.font = FONT;
    g.beginPath();
    g.moveTo(scale.left, y + 0.5);
    g.lineTo(scale.left + scale.width, y + 0.5);
    for (const v of ticks.values) {
      const x = Math.round(scale.x(v)) + 0.5;
      g.moveTo(x, y);
      g.lineTo(x, y + 4);
    }
    g.stroke();
    g.textBaseline = "top";
    g.textAlign = "center";
    ticks.values.forEach((v, i) => g.fillText(ticks.labels[i], scale.x(v), y + 6));
    g.textAlign = "right";
    g.fillText("time (s)", scale.left - 6, y + 6);
    return ticks.labels;
  }
)js";

}  // namespace mote::replay
