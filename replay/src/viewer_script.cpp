// viewer.html's script: plain JavaScript, no libraries. Opens at the last update, or at update N
// with #t=N in the URL; sizes the map and the timelines to the window so that both are in view
// without scrolling. The title says "mote viewer: update N of M" once drawn, "mote viewer:
// error: ..." on failure, and the body's data-timelines-bottom the timelines' lowest pixel row
// and data-viewport-height the window's (what tests/replay/test_viewer.py reads).
#include "viewer_template.hpp"

namespace mote::replay {

const std::string_view kViewerScript = R"js("use strict";
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

  // [data key, colour, name in the chart's key]
  const PHASES = [["motion_ms", "#4e79a7", "motion"], ["sensor_ms", "#f28e2b", "sensor"],
                  ["normalize_ms", "#59a14f", "normalize"], ["resample_ms", "#b07aa1", "resample"],
                  ["estimate_ms", "#9c755f", "estimate"]];
  const TIMELINES = [
    { label: "ms per update", stack: PHASES },
    { series: [["particles", "#285aff", "particles after the update"]] },
    { series: [["ess", "#e15759", "effective sample size before resampling"]] },
    { series: [["injected", "#76b7b2", "injected particles"]] },
    { series: [["tempering", "#edc948", "tempering exponent"]] },
    { series: [["error_m", "#dc1414", "position error vs reference, m"]] },
  ];
  const LABEL_PX = 20;  // height of a timeline's key line, px

  function main() {
    const d = JSON.parse(document.getElementById("mote-data").textContent);
    const n = d.total_ms.length;
    if (n === 0) throw new Error("the run has no updates");
    const box = viewBox(d);  // cells shown: the known part of the map and the trajectories
    const fit = fitLayout(box);
    const scale = fit.scale;
    const particleEnd = decode(d.particle_end, 4, Uint32Array);
    const particles = decode(d.particle_uvw, 2, Uint16Array);
    const endpointEnd = decode(d.endpoint_end, 4, Uint32Array);
    const endpoints = decode(d.endpoint_uv, 2, Uint16Array);
    const clusterEnd = decode(d.cluster_end, 4, Uint32Array);
    const clusters = decode(d.cluster_uvw, 2, Uint16Array);
    if (particleEnd.length !== n || endpointEnd.length !== n || clusterEnd.length !== n)
      throw new Error("the data block's arrays do not match in length");

    const mapImage = document.createElement("canvas");
    paintCells(mapImage, d.map);
    const canvas = document.getElementById("map");
    canvas.width = Math.round((box.u1 - box.u0) * scale);
    canvas.height = Math.round((box.v1 - box.v0) * scale);
    const ctx = canvas.getContext("2d");
    const cx = (u) => (u - box.u0) * scale;  // grid cells -> canvas pixels
    const cy = (v) => (box.v1 - v) * scale;
    const fx = (u) => cx(u / d.per_cell);  // fixed point -> canvas pixels
    const fy = (v) => cy(v / d.per_cell);
    document.getElementById("side").style.width = fit.timelineWidth + "px";
    const timelines = TIMELINES.map((t) =>
      makeTimeline(t, d, n, fit.timelineWidth, fit.timelineHeight, (k) => show(k)));
    const slider = document.getElementById("slider");
    slider.max = String(n - 1);
    let current = 0;

    function polyline(poses, count, color, lineWidth) {
      if (count < 2) return;
      ctx.strokeStyle = color;
      ctx.lineWidth = lineWidth;
      ctx.beginPath();
      for (let i = 0; i < count; ++i) {
        const x = cx(poses[3 * i]), y = cy(poses[3 * i + 1]);
        if (i === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
      }
      ctx.stroke();
    }

    function drawParticles(k) {
      const begin = k > 0 ? particleEnd[k - 1] : 0;
      const size = Math.max(2, scale);
      for (let i = begin; i < particleEnd[k]; i += 3) {
        const alpha = 0.15 + 0.85 * (particles[i + 2] / 65535);
        ctx.fillStyle = "rgba(40,90,255," + alpha.toFixed(2) + ")";
        ctx.fillRect(fx(particles[i]) - size / 2, fy(particles[i + 1]) - size / 2, size, size);
      }
    }

    function drawEndpoints(k) {
      const begin = k > 0 ? endpointEnd[k - 1] : 0;
      const size = Math.max(2, scale);
      ctx.fillStyle = "#ff8c00";
      for (let i = begin; i < endpointEnd[k]; i += 2)
        ctx.fillRect(fx(endpoints[i]) - size / 2, fy(endpoints[i + 1]) - size / 2, size, size);
    }

    // The estimate: a disc of exactly #ff00ff (a colour nothing else uses) and its heading.
    function drawEstimate(k) {
      const x = cx(d.estimate[3 * k]), y = cy(d.estimate[3 * k + 1]), a = d.estimate[3 * k + 2];
      const r = 4 + 2 * scale;
      ctx.fillStyle = "#ff00ff";
      ctx.beginPath();
      ctx.arc(x, y, r, 0, 2 * Math.PI);
      ctx.fill();
      ctx.strokeStyle = "#ff00ff";
      ctx.lineWidth = 2;
      ctx.beginPath();
      ctx.moveTo(x, y);
      ctx.lineTo(x + 3 * r * Math.cos(a), y - 3 * r * Math.sin(a));
      ctx.stroke();
    }

    // The other heavy clusters' means: purple rings, the area in proportion to the weight.
    function drawOtherClusters(k) {
      ctx.strokeStyle = "#7b2cbf";
      ctx.lineWidth = 2;
      for (let i = (k > 0 ? clusterEnd[k - 1] : 0) + 3; i < clusterEnd[k]; i += 3) {
        ctx.beginPath();
        ctx.arc(fx(clusters[i]), fy(clusters[i + 1]), 3 + 20 * Math.sqrt(clusters[i + 2] / 65535),
                0, 2 * Math.PI);
        ctx.stroke();
      }
    }

    function clusterWeights(k) {
      const w = [];
      for (let i = k > 0 ? clusterEnd[k - 1] : 0; i < clusterEnd[k] && w.length < 3; i += 3)
        w.push((clusters[i + 2] / 65535).toFixed(2));
      return w.join(", ");
    }

    // Reference poses stamped up to t: a binary search over the sorted stamps.
    function referenceCount(t) {
      let lo = 0, hi = d.reference_t.length;
      while (lo < hi) {
        const mid = (lo + hi) >> 1;
        if (d.reference_t[mid] <= t) lo = mid + 1; else hi = mid;
      }
      return lo;
    }

    function show(k) {
      current = Math.max(0, Math.min(n - 1, Math.floor(k)));
      slider.value = String(current);
      ctx.imageSmoothingEnabled = false;
      // mapImage holds the embedded cells, from (u0, v0) of the map; its row 0 is their top.
      ctx.drawImage(mapImage, box.u0 - d.map.u0, d.map.v0 + d.map.height - box.v1,
                    box.u1 - box.u0, box.v1 - box.v0, 0, 0, canvas.width, canvas.height);
      // The reference wide and light under the estimate, which does not hide it.
      polyline(d.reference, referenceCount(d.estimate_t[current]), "#6ed26e", 4);
      drawParticles(current);
      drawEndpoints(current);
      polyline(d.estimate, current + 1, "#dc1414", 1.5);
      drawOtherClusters(current);
      drawEstimate(current);
      timelines.forEach((t) => t.cursor(current));
      const err = d.error_m[current];
      document.getElementById("info").textContent =
          "update " + current + " of " + n + "   t = " + d.estimate_t[current].toFixed(2) +
          " s   clusters " + d.clusters[current] + " (weights " + clusterWeights(current) +
          ")   error " + (err === null ? "-" : err.toFixed(3) + " m");
      document.getElementById("counts").textContent = countsText(d, current, particleEnd);
      document.title = "mote viewer: update " + current + " of " + n;
      const bottom = document.getElementById("timelines").getBoundingClientRect().bottom;
      document.body.dataset.timelinesBottom = String(Math.ceil(bottom + window.scrollY));
      document.body.dataset.viewportHeight = String(window.innerHeight);
    }

    let timer = null;
    const play = document.getElementById("play");
    function stop() { clearInterval(timer); timer = null; play.textContent = "play"; }
    play.addEventListener("click", () => {
      if (timer !== null) { stop(); return; }
      if (current >= n - 1) show(0);
      play.textContent = "pause";
      timer = setInterval(() => { if (current >= n - 1) stop(); else show(current + 1); }, 50);
    });
    slider.addEventListener("input", () => show(Number(slider.value)));
    document.addEventListener("keydown", (e) => {
      if (e.key === "ArrowRight") show(current + 1);
      if (e.key === "ArrowLeft") show(current - 1);
    });
    const fromHash = () => { const m = /t=(\d+)/.exec(location.hash); return m ? Number(m[1]) : n - 1; };
    window.addEventListener("hashchange", () => show(fromHash()));
    show(fromHash());
  }

  // The particle count and the effective sample size, each said in full: the ESS is of the
  // weights the scan gave the particles it weighed, before resampling drew the particles the
  // filter holds after the update, so it can exceed that count.
  function countsText(d, k, particleEnd) {
    const shown = (particleEnd[k] - (k > 0 ? particleEnd[k - 1] : 0)) / 3;
    const resampled = d.resampled[k] ? "then resampled to " + d.particles[k] :
                                       "not resampled (ESS above the threshold)";
    return "particles " + d.particles[k] + " after the update (" + shown + " drawn on the map)\n" +
           "weighed " + d.weighed[k] + " by the scan, " + resampled + "\n" +
           "effective sample size " + d.ess[k].toFixed(1) + ": (\u03a3w)\u00b2 / \u03a3w\u00b2 of the " +
           "weighed\nparticles' weights, before resampling";
  }

  // The map's scale (canvas px per cell) and the timelines' size: the map beside the timelines
  // when the window is wide enough, both within the window's height.
  function fitLayout(box) {
    const W = window.innerWidth || 1400, H = window.innerHeight || 900;
    const top = document.getElementById("layout").getBoundingClientRect().top + window.scrollY;
    const free = Math.max(320, H - top - 12);
    const side = W >= 1000 ? Math.min(640, Math.max(400, 0.4 * W)) : 0;
    const across = Math.max(300, W - side - 40);
    const scale = Math.min(8, across / (box.u1 - box.u0), free / (box.v1 - box.v0));
    if (side === 0) return { scale, timelineWidth: Math.max(300, W - 24), timelineHeight: 64 };
    const mapWidth = Math.round((box.u1 - box.u0) * scale);
    const counts = 4 * 17 + 8;  // the four lines of #counts
    const each = Math.floor((free - counts) / TIMELINES.length) - LABEL_PX;
    return { scale, timelineWidth: Math.max(360, W - mapWidth - 44),
             timelineHeight: Math.max(30, Math.min(90, each)) };
  }

  // The cells to show: the known (free or occupied) part of the embedded map, without the 0.5%
  // of known cells furthest out on each side (stray returns), and the trajectories, with a
  // margin; in cells of the whole map, within the embedded part.
  function viewBox(d) {
    const W = d.map.width, H = d.map.height, U0 = d.map.u0, V0 = d.map.v0;
    const cells = atob(d.map.cells);
    const byU = new Float64Array(W), byV = new Float64Array(H);
    let known = 0;
    for (let v = 0; v < H; ++v) {
      for (let u = 0; u < W; ++u) {
        if (cells.charCodeAt(v * W + u) === 2) continue;
        ++byU[u];
        ++byV[v];
        ++known;
      }
    }
    if (known === 0) return { u0: U0, u1: U0 + W, v0: V0, v1: V0 + H };
    const range = (counts, offset) => {
      let lo = 0, hi = counts.length - 1, sum = 0;
      while (sum + counts[lo] <= 0.005 * known) sum += counts[lo++];
      for (sum = 0; sum + counts[hi] <= 0.005 * known;) sum += counts[hi--];
      return [offset + lo, offset + hi + 1];
    };
    let [u0, u1] = range(byU, U0), [v0, v1] = range(byV, V0);
    for (const poses of [d.estimate, d.reference]) {
      for (let i = 0; i + 1 < poses.length; i += 3) {
        u0 = Math.min(u0, poses[i]); u1 = Math.max(u1, poses[i]);
        v0 = Math.min(v0, poses[i + 1]); v1 = Math.max(v1, poses[i + 1]);
      }
    }
    const m = 10;
    return { u0: Math.max(U0, Math.floor(u0) - m), u1: Math.min(U0 + W, Math.ceil(u1) + m),
             v0: Math.max(V0, Math.floor(v0) - m), v1: Math.min(V0 + H, Math.ceil(v1) + m) };
  }

  // The grid, one pixel per cell (row 0 of the grid is the bottom, of the image the top).
  function paintCells(target, map) {
    target.width = map.width;
    target.height = map.height;
    const g = target.getContext("2d");
    const img = g.createImageData(map.width, map.height);
    const cells = atob(map.cells);
    const shade = [255, 0, 190];  // free, occupied, unknown
    for (let v = 0; v < map.height; ++v) {
      for (let u = 0; u < map.width; ++u) {
        const c = shade[cells.charCodeAt(v * map.width + u)];
        const p = 4 * ((map.height - 1 - v) * map.width + u);
        img.data[p] = img.data[p + 1] = img.data[p + 2] = c;
        img.data[p + 3] = 255;
      }
    }
    g.putImageData(img, 0, 0);
  }

  const format = (v) => (Number.isInteger(v) ? String(v) : Number(v).toPrecision(4));

  // A timeline's key line: a swatch and a name per series, then the value at the cursor.
  function makeKey(spec, series) {
    const key = document.createElement("div");
    key.className = "key";
    for (const [, color, name] of series) {
      const swatch = document.createElement("i");
      swatch.style.background = color;
      key.append(swatch, name + " ");
    }
    if (spec.label) key.prepend(spec.label + ": ");
    const now = document.createElement("span");
    key.append(now);
    document.getElementById("timelines").appendChild(key);
    return now;
  }

  // One timeline: the series drawn once into a backing canvas, the cursor on top per update.
  function makeTimeline(spec, d, n, width, height, onPick) {
    const series = spec.stack ? spec.stack : spec.series;
    const now = makeKey(spec, series);
    const canvas = document.createElement("canvas");
    canvas.width = width;
    canvas.height = height;
    document.getElementById("timelines").appendChild(canvas);
    const back = document.createElement("canvas");
    back.width = width;
    back.height = height;
    const g = back.getContext("2d");
    g.fillStyle = "#fff";
    g.fillRect(0, 0, width, height);
    const value = (k) => series.reduce((s, [key]) => s + (d[key][k] || 0), 0);
    // The axis ends at the 99th percentile so that a few slow updates leave the rest readable;
    // taller bars are clipped.
    const sorted = Array.from({ length: n }, (_, k) => value(k)).sort((a, b) => a - b);
    let top = sorted[Math.min(n - 1, Math.floor(0.99 * n))];
    top = top > 0 ? top : Math.max(sorted[n - 1], 1);
    const barWidth = Math.max(1, width / n);
    for (let k = 0; k < n; ++k) {
      let base = height;
      for (const [key, color] of series) {
        const h = Math.min(((d[key][k] || 0) / top) * (height - 2), base - 2);
        g.fillStyle = color;
        g.fillRect((k * width) / n, base - h, barWidth, h);
        base -= h;
      }
    }
    const ctx = canvas.getContext("2d");
    canvas.addEventListener("click", (e) => {
      const r = canvas.getBoundingClientRect();
      onPick(((e.clientX - r.left) / r.width) * n);
    });
    const hasData = series.some(([key]) => d[key].some((v) => v !== null));
    return {
      cursor(k) {
        ctx.drawImage(back, 0, 0);
        ctx.fillStyle = "#000";
        ctx.fillRect(((k + 0.5) * width) / n - 1, 0, 2, height);
        const v = series.length > 1 ? value(k) : d[series[0][0]][k];
        now.textContent = !hasData ? "(none in this run)" :
          "= " + (v === null ? "-" : format(v)) + " (axis to " + format(top) + ", p99)";
      },
    };
  }

  try {
    main();
  } catch (e) {
    fail(e && e.message ? e.message : String(e));
  }
})();
)js";

}  // namespace mote::replay
