// viewer.html's script, the timelines: per-update statistics over a time axis in seconds, each
// with its value axis (logarithmic where a global set would flatten the rest), and the state
// band under the map with the re-localizations marked. A click on either picks the update.
#include "viewer_template.hpp"

namespace mote::replay {

const std::string_view kViewerScriptTimelines = R"js(
  // A key line: a swatch and a name per series (data-* attributes for the test), then a span
  // for the value at the cursor.
  function makeKey(parent, label, series) {
    const key = document.createElement("div");
    key.className = "key";
    if (label) key.append(label + ": ");
    for (const [id, color, name] of series) {
      const swatch = document.createElement("i");
      swatch.style.background = color;
      const item = document.createElement("span");
      item.dataset.key = id;
      item.dataset.color = color;
      item.append(swatch, name + " ");
      key.append(item);
    }
    const now = document.createElement("span");
    key.append(now);
    parent.appendChild(key);
    return now;
  }

  // The value axis of a timeline `height` px tall: y(v) in px from the top, round ticks, and
  // what the key says about it. Log: whole decades around the positive values (from 1 with
  // fromOne). Linear: from 0
  // to the 99th percentile, so that a few outliers leave the rest readable (taller bars are
  // clipped), at least to a drawn limit.
  function valueAxis(spec, d, n, value, height) {
    const values = Array.from({ length: n }, (_, k) => value(k));
    if (spec.log) {
      // A loop, not Math.min(...values): a long log's updates exceed the arguments allowed.
      let lo = Infinity, hi = 0;
      for (const v of values) if (v > 0) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
      if (!(hi > 0)) return null;
      const a = Math.min(spec.fromOne ? 0 : Infinity, Math.floor(Math.log10(lo)));
      const b = Math.max(a + 1, Math.ceil(Math.log10(hi)));
      const step = Math.ceil((b - a) / Math.max(1, Math.floor(height / 18)));
      const ticks = [];
      for (let e = a; e <= b; e += step) ticks.push([Math.pow(10, e), decadeLabel(e)]);
      const y = (v) => (v > 0 ? height - 1 - ((Math.log10(v) - a) / (b - a)) * (height - 3)
                              : height);
      return { ticks, note: "log axis", y };
    }
    const sorted = values.filter((v) => v !== null).sort((x, y) => x - y);
    if (sorted.length === 0) return null;
    let top = sorted[Math.min(sorted.length - 1, Math.floor(0.99 * sorted.length))];
    if (spec.limit) top = Math.max(top, 1.25 * limitMax(d[spec.limit]));
    if (!(top > 0)) top = Math.max(sorted[sorted.length - 1], 1);
    const t = niceTicks(0, top, Math.max(1, Math.floor(height / 30)));
    const clipped = sorted[sorted.length - 1] > top;
    return { ticks: t.values.map((v, i) => [v, t.labels[i]]),
             note: clipped ? "axis to " + format(top) + ", p99; taller clipped" : "",
             y: (v) => height - 1 - Math.min(1, v / top) * (height - 3) };
  }

  // A limit is one value for the run or one per update (the learned lost bound).
  function limitMax(limit) {
    if (!Array.isArray(limit)) return limit;
    let top = 0;
    for (const v of limit) if (v > top) top = v;
    return top;
  }

  // The limit as a dashed line in the lost colour, stepping where a per-update limit moves.
  function drawLimit(g, scale, axis, limit, n) {
    g.strokeStyle = STATES[2][1];
    g.setLineDash([5, 3]);
    g.beginPath();
    if (!Array.isArray(limit)) {
      g.moveTo(scale.left, Math.round(axis.y(limit)) + 0.5);
      g.lineTo(scale.left + scale.width, Math.round(axis.y(limit)) + 0.5);
    } else {
      for (let k = 0; k < n; ++k) {
        const [x, w] = scale.bar(k), y = Math.round(axis.y(limit[k])) + 0.5;
        if (k === 0) g.moveTo(x, y);
        else g.lineTo(x, y);
        g.lineTo(x + w, y);
      }
    }
    g.stroke();
    g.setLineDash([]);
  }

  // Light lines at the time ticks and the value ticks, with the values in the left margin.
  function drawGrid(g, scale, axis, height) {
    g.fillStyle = "#e6e6e6";
    for (const v of niceTicks(scale.t0, scale.t1, Math.max(2, Math.floor(scale.width / 80))).values)
      g.fillRect(Math.round(scale.x(v)), 0, 1, height);
    g.font = FONT;
    g.textAlign = "right";
    g.textBaseline = "middle";
    for (const [v, label] of axis.ticks) {
      const y = Math.round(axis.y(v));
      g.fillStyle = "#e6e6e6";
      g.fillRect(scale.left, y, scale.width, 1);
      g.fillStyle = "#222";
      g.fillText(label, scale.left - 5, Math.min(height - 6, Math.max(6, y)));
    }
  }

  // One timeline: the series drawn once into a backing canvas, the cursor on top per update.
  // A stack on a log axis is drawn to its total with each part in proportion.
  function makeTimeline(parent, spec, d, n, width, height, scale, onPick) {
    const series = spec.stack ? spec.stack : spec.series;
    const now = makeKey(parent, spec.label, series);
    const canvas = document.createElement("canvas");
    canvas.width = width;
    canvas.height = height;
    parent.appendChild(canvas);
    const back = document.createElement("canvas");
    back.width = width;
    back.height = height;
    const g = back.getContext("2d");
    g.fillStyle = "#fff";
    g.fillRect(0, 0, width, height);
    const value = (k) => series.reduce((s, [key]) => s + (d[key][k] || 0), 0);
    const axis = valueAxis(spec, d, n, value, height);
    if (axis) {
      drawGrid(g, scale, axis, height);
      for (let k = 0; k < n; ++k) {
        const [x, w] = scale.bar(k), total = value(k), top = axis.y(total);
        let base = height;
        for (const [key, color] of series) {
          const h = total > 0 ? ((d[key][k] || 0) / total) * (height - top) : 0;
          g.fillStyle = color;
          g.fillRect(x, base - h, w, h);
          base -= h;
        }
      }
      if (spec.limit) drawLimit(g, scale, axis, d[spec.limit], n);
    }
    const ctx = canvas.getContext("2d");
    onClick(canvas, scale, onPick);
    const hasData = series.some(([key]) => d[key].some((v) => v !== null));
    const note = axis && axis.note ? " (" + axis.note + ")" : "";
    return {
      cursor(k) {
        ctx.drawImage(back, 0, 0);
        cursorLine(ctx, scale, k, 0, height);
        now.textContent = !hasData ? "(none in this run)" :
                                     "\u2014 " + valueText(series, d, k, value(k)) + note;
      },
    };
  }

  // A timeline's value at update k: a series' value; a stack's parts when they have short names,
  // else its total.
  function valueText(series, d, k, total) {
    if (series.length === 1) return d[series[0][0]][k] === null ? "-" : format(d[series[0][0]][k]);
    const part = ([key, , , short]) => format(d[key][k] || 0) + " " + short;
    if (series.every((s) => s[3])) return series.map(part).join(", ");
    return "total " + format(total);
  }

  // A click on a timeline or the band picks the update shown at its x.
  function onClick(canvas, scale, onPick) {
    canvas.addEventListener("click", (e) => {
      onPick(scale.pick(e.clientX - canvas.getBoundingClientRect().left));
    });
  }

  // The cursor: a black line 2 px wide in the middle of update k's bar.
  function cursorLine(g, scale, k, top, height) {
    const [x, w] = scale.bar(k);
    g.fillStyle = "#000";
    g.fillRect(Math.round(x + Math.min(w, 4) / 2) - 1, top, 2, height);
  }

  // The time axis under the timelines; returns its labels.
  function makeTimeAxis(parent, width, scale) {
    const canvas = document.createElement("canvas");
    canvas.width = width;
    canvas.height = AXIS_PX;
    canvas.style.background = "none";
    parent.appendChild(canvas);
    return drawTimeAxis(canvas.getContext("2d"), scale, 0);
  }

  const BAND = { marks: 10, bar: 18 };  // px: re-localization marks above the bar, the bar

  // The state band: the state each update ended in over time, a black line and a triangle at
  // each re-localization, the time axis under it; the key (with data-key and data-color for
  // each state) and the state at the cursor under that.
  function makeStateBand(canvas, keyBox, d, n, scale, onPick) {
    canvas.height = BAND.marks + BAND.bar + AXIS_PX;
    const back = document.createElement("canvas");
    back.width = canvas.width;
    back.height = canvas.height;
    const g = back.getContext("2d");
    // The commonest state first, the rarer ones over it: where several updates share a pixel
    // column, a single uncertain or lost update is not overdrawn by the tracking ones around it.
    const counts = STATES.map((_, s) => d.state.filter((v) => v === s).length);
    const order = STATES.map((_, s) => s).sort((a, b) => counts[b] - counts[a]);
    for (const s of order) {
      g.fillStyle = STATES[s][1];
      for (let k = 0; k < n; ++k) {
        if (d.state[k] !== s) continue;
        const [x, w] = scale.bar(k);
        g.fillRect(x, BAND.marks, w, BAND.bar);
      }
    }
    let relocalizations = 0;
    for (let k = 0; k < n; ++k) {
      if (!(d.relocalized[k] > 0)) continue;
      ++relocalizations;
      const x = Math.round(scale.bar(k)[0]);
      g.fillStyle = RELOCALIZED;
      // One pixel just before the update's own column, which keeps the state it ended in.
      g.fillRect(x - 1, BAND.marks, 1, BAND.bar);
      g.beginPath();
      g.moveTo(x - 5, 0);
      g.lineTo(x + 5, 0);
      g.lineTo(x, BAND.marks - 1);
      g.fill();
    }
    const timeLabels = drawTimeAxis(g, scale, BAND.marks + BAND.bar + 1);
    const states = STATES.map(([name, color]) => [name, color, name]);
    const now = makeKey(keyBox, "state", states);
    now.id = "state-now";
    now.before("\u25bc re-localization (" + relocalizations + " in this run; on the map \u25c7, " +
               "the jump dashed)   now: ");
    const ctx = canvas.getContext("2d");
    onClick(canvas, scale, onPick);
    return {
      timeLabels,
      cursor(k) {
        ctx.clearRect(0, 0, canvas.width, canvas.height);
        ctx.drawImage(back, 0, 0);
        cursorLine(ctx, scale, k, BAND.marks - 3, BAND.bar + 6);
        now.textContent = STATES[d.state[k]][0] + (d.relocalized[k] > 0 ? ", re-localized" : "");
      },
    };
  }
)js";

}  // namespace mote::replay
