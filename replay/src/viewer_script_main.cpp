// viewer.html's script, last part: main() and the end of the script's function scope. Opens at
// the last update, or at update N (counted from 1) with #t=N in the URL; sizes the map and the
// timelines to the window so that both are in view without scrolling. The title says "mote
// viewer: update N of M" once drawn, "mote viewer: error: ..." on failure; the body's data-*
// attributes say what tests/replay/test_viewer.py checks: the timelines' lowest pixel row and
// the window's height, the page's width and the window's, where the map's cells and the state
// band are, and the labels of the map's and the band's axes.
#include "viewer_template.hpp"

namespace mote::replay {

const std::string_view kViewerScriptMain = R"js(
  function main() {
    const d = JSON.parse(document.getElementById("mote-data").textContent);
    const n = d.total_ms.length;
    if (n === 0) throw new Error("the run has no updates");
    const bulk = {
      particleEnd: decode(d.particle_end, 4, Uint32Array),
      particles: decode(d.particle_uvw, 2, Uint16Array),
      endpointEnd: decode(d.endpoint_end, 4, Uint32Array),
      endpoints: decode(d.endpoint_uv, 2, Uint16Array),
      clusterEnd: decode(d.cluster_end, 4, Uint32Array),
      clusters: decode(d.cluster_uvw, 2, Uint16Array),
    };
    if ([bulk.particleEnd, bulk.endpointEnd, bulk.clusterEnd].some((a) => a.length !== n))
      throw new Error("the data block's arrays do not match in length");
    const stops = STATES.map(([, c], i) => c + " " + 33 * i + "% " + 33 * (i + 1) + "%");
    document.getElementById("trajectory-swatch").style.background =
        "linear-gradient(90deg," + stops.join(",") + ")";

    const box = viewBox(d);  // cells shown: the known part of the map and the trajectories
    const fit = fitLayout(box);
    const map = makeMap(document.getElementById("map"), d, box, fit.scale, bulk);
    const bandCanvas = document.getElementById("band");
    bandCanvas.width = map.inner.left + map.inner.width + MAP_MARGIN.right;
    document.getElementById("map-column").style.width = bandCanvas.width + "px";
    const band = makeStateBand(bandCanvas, document.getElementById("state-key"), d, n,
                               timeScale(d.estimate_t, map.inner.left, map.inner.width),
                               (k) => show(k));
    document.getElementById("side").style.width = fit.timelineWidth + "px";
    const lines = document.getElementById("timelines");
    const scale = timeScale(d.estimate_t, LEFT_PX, fit.timelineWidth - LEFT_PX - 14);
    const timelines = TIMELINES.map((t) =>
      makeTimeline(lines, t, d, n, fit.timelineWidth, fit.timelineHeight, scale, (k) => show(k)));
    makeTimeAxis(lines, fit.timelineWidth, scale);
    const slider = document.getElementById("slider");
    slider.max = String(n - 1);
    let current = 0;

    function clusterWeights(k) {
      const w = [], end = bulk.clusterEnd;
      for (let i = k > 0 ? end[k - 1] : 0; i < end[k] && w.length < 3; i += 3)
        w.push((bulk.clusters[i + 2] / 65535).toFixed(2));
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
      map.draw(current, referenceCount(d.estimate_t[current]));
      band.cursor(current);
      timelines.forEach((t) => t.cursor(current));
      const err = d.error_m[current];
      document.getElementById("info").textContent =
          "update " + (current + 1) + " of " + n + "   t = " + d.estimate_t[current].toFixed(2) +
          " s   " + STATES[d.state[current]][0] + "   clusters " + d.clusters[current] +
          " (weights " + clusterWeights(current) + ")   error " +
          (err === null ? "-" : err.toFixed(3) + " m");
      document.getElementById("counts").textContent = countsText(d, current, bulk.particleEnd);
      document.title = "mote viewer: update " + (current + 1) + " of " + n;
      describe(map, band);
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
    const fromHash = () => {
      const m = /t=(\d+)/.exec(location.hash);
      return m ? Number(m[1]) - 1 : n - 1;
    };
    window.addEventListener("hashchange", () => show(fromHash()));
    show(fromHash());
  }

  // The body's data-* attributes that say where things are and what the axes read.
  function describe(map, band) {
    const b = document.body.dataset, root = document.documentElement;
    const rect = (el, inner) => {
      const r = el.getBoundingClientRect();
      return [r.left + window.scrollX + inner.left, r.top + window.scrollY + inner.top,
              inner.width, inner.height].map(Math.round).join(",");
    };
    const timelines = document.getElementById("timelines").getBoundingClientRect();
    b.timelinesBottom = String(Math.ceil(timelines.bottom + window.scrollY));
    b.viewportHeight = String(window.innerHeight);
    b.viewportWidth = String(root.clientWidth);
    b.pageWidth = String(root.scrollWidth);
    b.mapRect = rect(document.getElementById("map"), map.inner);
    const bar = { left: map.inner.left, top: BAND.marks, width: map.inner.width, height: BAND.bar };
    b.bandRect = rect(document.getElementById("band"), bar);
    b.mapXTicks = map.axes.xTicks.join(" ");
    b.mapYTicks = map.axes.yTicks.join(" ");
    b.mapXTitle = map.axes.xTitle;
    b.mapYTitle = map.axes.yTitle;
    b.mapScaleBar = map.axes.scaleBar;
    b.timeTicks = band.timeLabels.join(" ");
  }

  // The particle counts, each said in full: the ESS is of the weights the scan gave the
  // particles it weighed, before resampling drew the particles the filter holds after the
  // update, so it can exceed that count; a re-localization's global set is among the weighed.
  function countsText(d, k, particleEnd) {
    const shown = (particleEnd[k] - (k > 0 ? particleEnd[k - 1] : 0)) / 3;
    const resampled = d.resampled[k] ? "then resampled to " + d.particles[k] :
                                       "not resampled (ESS above the threshold)";
    const added = d.relocalized[k] > 0 ?
        d.relocalized[k] + " of them added by a re-localization (a global set over free space)" :
        "no re-localization";
    return "particles " + d.particles[k] + " after the update (" + shown + " drawn on the map)\n" +
           "weighed " + d.weighed[k] + " by the scan, " + resampled + "\n" +
           "weighed: " + added + ", " + d.injected[k] + " injected (augmented MCL)\n" +
           "effective sample size " + d.ess[k].toFixed(1) +
           ": (\u03a3w)\u00b2 / \u03a3w\u00b2 of the " +
           "weighed\nparticles' weights, before resampling";
  }

  // The map's scale (canvas px per cell) and the timelines' size: the map beside the timelines
  // when the window is wide enough, map, axes and state band within the window's height; a
  // narrower window puts the timelines under the map, the page no wider than the window.
  function fitLayout(box) {
    const W = document.documentElement.clientWidth || 1400, H = window.innerHeight || 900;
    const top = document.getElementById("layout").getBoundingClientRect().top + window.scrollY;
    const free = Math.max(320, H - top - 12);
    const band = BAND.marks + BAND.bar + AXIS_PX + LABEL_PX + 4;
    const frame = [MAP_MARGIN.left + MAP_MARGIN.right, MAP_MARGIN.top + MAP_MARGIN.bottom];
    const side = W >= 1000 ? Math.min(640, Math.max(400, 0.4 * W)) : 0;
    const across = Math.max(200, W - side - 40 - frame[0]);
    const high = free - band - frame[1];
    const scale = Math.min(8, across / (box.u1 - box.u0), high / (box.v1 - box.v0));
    if (side === 0) return { scale, timelineWidth: Math.max(300, W - 40), timelineHeight: 64 };
    const mapWidth = Math.round((box.u1 - box.u0) * scale) + frame[0];
    const counts = 5 * 17 + 4;  // #counts' five lines and its margin
    const each = Math.floor((free - counts - AXIS_PX) / TIMELINES.length) - LABEL_PX;
    return { scale, timelineWidth: Math.max(360, W - mapWidth - 44),
             timelineHeight: Math.max(30, Math.min(90, each)) };
  }

  try {
    main();
  } catch (e) {
    fail(e && e.message ? e.message : String(e));
  }
})();
)js";

}  // namespace mote::replay
