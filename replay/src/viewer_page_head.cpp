// viewer.html's head, style sheet and elements (the script is in viewer_script*.cpp).
#include "viewer_template.hpp"

namespace mote::replay {

const std::string_view kViewerPageHead = R"html(<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>mote viewer: loading</title>
<style>
body { font: 13px system-ui, sans-serif; margin: 8px; background: #f4f4f4; color: #222; }
header { display: flex; gap: 10px; align-items: center; margin-bottom: 4px; }
#slider { flex: 1; min-width: 120px; max-width: 700px; }
#info, #counts { font-variant-numeric: tabular-nums; white-space: pre-wrap; }
#layout { display: flex; flex-wrap: wrap; gap: 12px; align-items: flex-start; margin-top: 4px; }
#counts { margin-bottom: 4px; font-size: 12px; line-height: 17px; height: 85px; overflow: hidden; }
.key { font-size: 12px; line-height: 16px; margin-top: 4px; white-space: nowrap; overflow: hidden; }
.key i { display: inline-block; width: 10px; height: 10px; margin: 0 3px 0 8px; }
.key i:first-child { margin-left: 0; }
#state-key { margin-left: 52px; }
#state-key .key { white-space: normal; }
#state-now { font-weight: bold; }
#error { background: #b00; color: #fff; padding: 6px; margin-bottom: 6px; }
#legend span { margin-right: 14px; }
#legend i { display: inline-block; width: 10px; height: 10px; margin-right: 4px; }
canvas { display: block; background: #fff; }
#map-column canvas { background: none; }
#timelines canvas, #band { cursor: pointer; }
</style>
</head>
<body>
<div id="error" hidden></div>
<header>
<button id="play" type="button">play</button>
<input id="slider" type="range" min="0" max="0" value="0" step="1">
<span id="info"></span>
</header>
<div id="legend">
<span><i style="background:#ff00ff"></i>estimate</span>
<span><i id="trajectory-swatch"></i>estimated trajectory (colour: state, key under the map)</span>
<span><i style="background:#6ed26e"></i>reference</span>
<span><i style="background:#285aff"></i>particles (shade: weight)</span>
<span><i style="background:#009988"></i>scan endpoints from the estimate</span>
<span><i style="border:2px solid #7b2cbf;border-radius:50%;width:6px;height:6px"></i>other clusters (area: weight)</span>
</div>
<div id="layout">
<div id="map-column">
<canvas id="map"></canvas>
<canvas id="band"></canvas>
<div id="state-key"></div>
</div>
<div id="side">
<div id="counts"></div>
<div id="timelines"></div>
</div>
</div>
)html";

}  // namespace mote::replay
