// viewer.html's script, the map: the cells to show, the axes in metres with a scale bar, and per
// update the particles, scan endpoints, clusters, the reference and the estimated trajectory
// coloured by the localization state, with the re-localizations marked.
#include "viewer_template.hpp"

namespace mote::replay {

const std::string_view kViewerScriptMap = R"js(
  const MAP_MARGIN = { left: LEFT_PX, right: 12, top: 6, bottom: 40 };  // px around the cells

  // The map canvas: the cells in `box` at `scale` px per cell inside MAP_MARGIN, the axes drawn
  // once; draw(k) paints update k over the cells. `bulk` holds the decoded per-update columns.
  function makeMap(canvas, d, box, scale, bulk) {
    const width = Math.round((box.u1 - box.u0) * scale);
    const height = Math.round((box.v1 - box.v0) * scale);
    const M = MAP_MARGIN;
    canvas.width = width + M.left + M.right;
    canvas.height = height + M.top + M.bottom;
    const ctx = canvas.getContext("2d");
    const mapImage = document.createElement("canvas");
    paintCells(mapImage, d.map);
    const cx = (u) => M.left + (u - box.u0) * scale;  // grid cells -> canvas pixels
    const cy = (v) => M.top + (box.v1 - v) * scale;
    const fx = (u) => cx(u / d.per_cell);  // fixed point -> canvas pixels
    const fy = (v) => cy(v / d.per_cell);
    const axes = drawMapAxes(ctx, d.map, box, scale, width, height);
    const size = Math.max(2, scale);  // of a particle's or an endpoint's square, px

    function polyline(poses, count, color, lineWidth) {
      if (count < 2) return;
      ctx.strokeStyle = color;
      ctx.lineWidth = lineWidth;
      ctx.beginPath();
      for (let i = 0; i < count; ++i) ctx.lineTo(cx(poses[3 * i]), cy(poses[3 * i + 1]));
      ctx.stroke();
    }

    function drawParticles(k) {
      const { particleEnd: end, particles: p } = bulk;
      for (let i = k > 0 ? end[k - 1] : 0; i < end[k]; i += 3) {
        ctx.fillStyle = "rgba(40,90,255," + (0.15 + 0.85 * (p[i + 2] / 65535)).toFixed(2) + ")";
        ctx.fillRect(fx(p[i]) - size / 2, fy(p[i + 1]) - size / 2, size, size);
      }
    }

    function drawEndpoints(k) {
      const { endpointEnd: end, endpoints: p } = bulk;
      ctx.fillStyle = "#009988";
      for (let i = k > 0 ? end[k - 1] : 0; i < end[k]; i += 2)
        ctx.fillRect(fx(p[i]) - size / 2, fy(p[i + 1]) - size / 2, size, size);
    }

    // The other heavy clusters' means: purple rings, the area in proportion to the weight.
    function drawOtherClusters(k) {
      const { clusterEnd: end, clusters: c } = bulk;
      ctx.strokeStyle = "#7b2cbf";
      ctx.lineWidth = 2;
      for (let i = (k > 0 ? end[k - 1] : 0) + 3; i < end[k]; i += 3) {
        ctx.beginPath();
        ctx.arc(fx(c[i]), fy(c[i + 1]), 3 + 20 * Math.sqrt(c[i + 2] / 65535), 0, 2 * Math.PI);
        ctx.stroke();
      }
    }

    // The estimated trajectory up to update k: a white casing that keeps it readable over the
    // particles, then each step in the colour of the state the update ended in; the step into a
    // re-localization dashed (a jump, not travel) and its end marked with a diamond.
    function drawTrajectory(k) {
      const e = d.estimate, x = (i) => cx(e[3 * i]), y = (i) => cy(e[3 * i + 1]);
      ctx.lineJoin = ctx.lineCap = "round";
      polyline(e, k + 1, "#ffffff", 4);
      for (let i = 1; i <= k;) {
        const jump = d.relocalized[i] > 0;
        let j = i;
        while (!jump && j < k && d.state[j + 1] === d.state[i] && !(d.relocalized[j + 1] > 0)) ++j;
        ctx.strokeStyle = STATES[d.state[i]][1];
        ctx.lineWidth = 2;
        ctx.setLineDash(jump ? [6, 4] : []);
        ctx.beginPath();
        for (let m = i - 1; m <= j; ++m) ctx.lineTo(x(m), y(m));
        ctx.stroke();
        i = j + 1;
      }
      ctx.setLineDash([]);
      for (let i = 0; i <= k; ++i) {
        if (!(d.relocalized[i] > 0)) continue;
        ctx.fillStyle = "#ffffff";
        ctx.strokeStyle = RELOCALIZED;
        ctx.lineWidth = 2;
        ctx.beginPath();
        ctx.moveTo(x(i), y(i) - 8);
        ctx.lineTo(x(i) + 7, y(i));
        ctx.lineTo(x(i), y(i) + 8);
        ctx.lineTo(x(i) - 7, y(i));
        ctx.closePath();
        ctx.fill();
        ctx.stroke();
      }
    }

    // The estimate: a disc of exactly #ff00ff (a colour nothing else uses) and its heading.
    function drawEstimate(k) {
      const x = cx(d.estimate[3 * k]), y = cy(d.estimate[3 * k + 1]), a = d.estimate[3 * k + 2];
      const r = 4 + 2 * scale;
      ctx.fillStyle = ctx.strokeStyle = "#ff00ff";
      ctx.beginPath();
      ctx.arc(x, y, r, 0, 2 * Math.PI);
      ctx.fill();
      ctx.lineWidth = 2;
      ctx.beginPath();
      ctx.moveTo(x, y);
      ctx.lineTo(x + 3 * r * Math.cos(a), y - 3 * r * Math.sin(a));
      ctx.stroke();
    }

    return {
      axes,
      inner: { left: M.left, top: M.top, width, height },
      draw(k, referenceCount) {
        ctx.save();
        ctx.beginPath();
        ctx.rect(M.left, M.top, width, height);
        ctx.clip();
        ctx.imageSmoothingEnabled = false;
        // mapImage holds the embedded cells, from (u0, v0) of the map; its row 0 is their top.
        ctx.drawImage(mapImage, box.u0 - d.map.u0, d.map.v0 + d.map.height - box.v1,
                      box.u1 - box.u0, box.v1 - box.v0, M.left, M.top, width, height);
        // The reference wide and light under the estimate, which does not hide it.
        polyline(d.reference, referenceCount, "#6ed26e", 7);
        drawParticles(k);
        drawEndpoints(k);
        drawTrajectory(k);
        drawOtherClusters(k);
        drawEstimate(k);
        ctx.restore();
      },
    };
  }

  // Metres along the map's axes: the map frame's x and y when the map is not turned (the yaw of
  // its origin 0), else the distance from the origin along the image's columns and rows.
  function metres(map) {
    const turned = Math.abs(map.origin_yaw) > 1e-9, r = map.resolution;
    return {
      x: (u) => (turned ? 0 : map.origin_x) + u * r,
      y: (v) => (turned ? 0 : map.origin_y) + v * r,
      xTitle: turned ? "m along the image (map yaw " + map.origin_yaw.toFixed(2) + " rad)" :
                       "x (m)",
      yTitle: turned ? "m along the image" : "y (m)",
    };
  }

  // Ticks and labels in metres below and left of the cells, the axes' titles and a scale bar;
  // returns what was written (the page's data-map-* attributes).
  function drawMapAxes(ctx, map, box, scale, width, height) {
    const M = MAP_MARGIN, m = metres(map), pxPerM = scale / map.resolution;
    const xs = niceTicks(m.x(box.u0), m.x(box.u1), Math.max(2, Math.floor(width / 70)));
    const ys = niceTicks(m.y(box.v0), m.y(box.v1), Math.max(2, Math.floor(height / 50)));
    const px = (x) => M.left + (x - m.x(box.u0)) * pxPerM;
    const py = (y) => M.top + height - (y - m.y(box.v0)) * pxPerM;
    ctx.strokeStyle = ctx.fillStyle = "#222";
    ctx.lineWidth = 1;
    ctx.font = FONT;
    ctx.strokeRect(M.left - 0.5, M.top - 0.5, width + 1, height + 1);
    ctx.beginPath();
    for (const x of xs.values) {
      ctx.moveTo(Math.round(px(x)) + 0.5, M.top + height);
      ctx.lineTo(Math.round(px(x)) + 0.5, M.top + height + 4);
    }
    for (const y of ys.values) {
      ctx.moveTo(M.left - 4, Math.round(py(y)) + 0.5);
      ctx.lineTo(M.left, Math.round(py(y)) + 0.5);
    }
    ctx.stroke();
    ctx.textBaseline = "top";
    ctx.textAlign = "center";
    xs.values.forEach((x, i) => ctx.fillText(xs.labels[i], px(x), M.top + height + 6));
    ctx.fillText(m.xTitle, M.left + width / 2, M.top + height + 22);
    ctx.textAlign = "right";
    ctx.textBaseline = "middle";
    ys.values.forEach((y, i) => ctx.fillText(ys.labels[i], M.left - 6, py(y)));
    ctx.save();
    ctx.translate(10, M.top + height / 2);
    ctx.rotate(-Math.PI / 2);
    ctx.textAlign = "center";
    ctx.fillText(m.yTitle, 0, 0);
    ctx.restore();
    // The scale bar: the longest of 1, 2 or 5 times a power of ten within a fifth of the width.
    const fifth = width / pxPerM / 5, p = Math.pow(10, Math.floor(Math.log10(fifth)));
    const bar = [5, 2, 1].map((f) => f * p).find((b) => b <= fifth * 1.001);
    const x1 = M.left + width, x0 = x1 - bar * pxPerM, y = M.top + height + 28.5;
    ctx.beginPath();
    ctx.moveTo(x0, y - 4); ctx.lineTo(x0, y); ctx.lineTo(x1, y); ctx.lineTo(x1, y - 4);
    ctx.stroke();
    ctx.textAlign = "right";
    ctx.fillText(format(bar) + " m", x0 - 6, y - 2);
    return { xTicks: xs.labels, yTicks: ys.labels, xTitle: m.xTitle, yTitle: m.yTitle,
             scaleBar: format(bar) + " m" };
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
)js";

}  // namespace mote::replay
