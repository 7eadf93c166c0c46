// ffr replay player: builds the 3D scene and the charts with Plotly from the
// embedded mission data, then moves the robot, its beams, fans and the flame
// and the charts' cursor as simulated time goes on. Plain ES2017, no modules,
// so the page works from a file:// URL with nothing fetched.
(function () {
  "use strict";
  const D = JSON.parse(document.getElementById("ffr-data").textContent);
  const M = D.meta, S = D.scene, R = D.robot, F = D.frames, C = D.charts;
  const NF = F.t.length;
  const T_END = M.t_end;
  const T_EXT = M.time_to_extinguish_s;  // null: the flame never went out
  const sceneDiv = document.getElementById("view3d");
  const chartDiv = document.getElementById("charts");
  const slider = document.getElementById("slider");
  const playBtn = document.getElementById("play");
  const speedSel = document.getElementById("speed");
  const clock = document.getElementById("clock");
  const $ = (id) => document.getElementById(id);

  // ---- helpers -----------------------------------------------------------
  function frameAt(t) {  // last frame with F.t <= t (binary search)
    let lo = 0, hi = NF - 1;
    if (t <= F.t[0]) return 0;
    if (t >= F.t[hi]) return hi;
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (F.t[mid] <= t) lo = mid; else hi = mid;
    }
    return lo;
  }
  function lerp(a, b, u) { return a + (b - a) * u; }
  function lerpAngle(a, b, u) {
    let d = b - a;
    while (d > Math.PI) d -= 2 * Math.PI;
    while (d < -Math.PI) d += 2 * Math.PI;
    return a + d * u;
  }
  // Pose and the continuous quantities at time t, interpolated between frames.
  function sample(t) {
    const i = frameAt(t);
    const j = Math.min(i + 1, NF - 1);
    const span = F.t[j] - F.t[i];
    const u = span > 0 ? Math.min(Math.max((t - F.t[i]) / span, 0), 1) : 0;
    return {
      i: i, t: t,
      x: lerp(F.x[i], F.x[j], u), y: lerp(F.y[i], F.y[j], u), th: lerpAngle(F.theta[i], F.theta[j], u),
      fanT: lerp(F.fan_t[i], F.fan_t[j], u),
      encL: lerp(F.enc_l[i], F.enc_l[j], u), encR: lerp(F.enc_r[i], F.enc_r[j], u),
    };
  }
  function stateName(code) { return D.states[code] || ("state " + code); }
  function lit(t) { return T_EXT === null || t < T_EXT; }

  // ---- the robot: body mesh + fan blades, in the body frame ---------------
  const body = R.mesh;
  const NB = body.x.length;
  const BLADES = 3, BLADE_HALF = 0.38;  // rad, half the angular width of a blade
  const bladeI = [], bladeJ = [], bladeK = [];
  {
    let v = NB;
    for (let f = 0; f < R.fans.length; f++) {
      for (let b = 0; b < BLADES; b++) {  // 4 vertices, 2 triangles per blade
        bladeI.push(v, v); bladeJ.push(v + 1, v + 2); bladeK.push(v + 2, v + 3);
        v += 4;
      }
    }
  }
  const robotI = body.i.concat(bladeI), robotJ = body.j.concat(bladeJ), robotK = body.k.concat(bladeK);
  const bladeOn = "#4fc3f7", bladeOff = "#8a8a8a";
  function robotColors(fanOn) {
    const c = body.facecolor.slice();
    for (let n = 0; n < bladeI.length; n++) c.push(fanOn ? bladeOn : bladeOff);
    return c;
  }
  const colorsOn = robotColors(true), colorsOff = robotColors(false);

  function robotGeometry(s) {
    const c = Math.cos(s.th), sn = Math.sin(s.th);
    const X = new Array(NB), Y = new Array(NB), Z = new Array(NB);
    for (let n = 0; n < NB; n++) {
      X[n] = s.x + c * body.x[n] - sn * body.y[n];
      Y[n] = s.y + sn * body.x[n] + c * body.y[n];
      Z[n] = body.z[n];
    }
    // Blades in the fan's plane (body y-z), turning with the fans' running time.
    const spin = 2 * Math.PI * R.fan_rev_per_s * s.fanT;
    R.fans.forEach(function (f, fi) {
      const dir = fi % 2 === 0 ? 1 : -1;  // counter-rotating pair
      for (let b = 0; b < BLADES; b++) {
        const a = dir * spin + (2 * Math.PI * b) / BLADES;
        const pts = [[0.006, a - BLADE_HALF / 3], [f.r, a - BLADE_HALF], [f.r, a + BLADE_HALF],
                     [0.006, a + BLADE_HALF / 3]];
        pts.forEach(function (p) {
          const ly = f.y + p[0] * Math.cos(p[1]), lz = f.z + p[0] * Math.sin(p[1]);
          X.push(s.x + c * f.x - sn * ly);
          Y.push(s.y + sn * f.x + c * ly);
          Z.push(lz);
        });
      }
    });
    return { x: X, y: Y, z: Z };
  }

  // Track cleats: short bars across each belt, moving with the wheel encoder.
  const CLEAT_SPACING = 0.025;
  function beltPoint(tr, p) {  // arc position p (m) from the rear end of the bottom run -> [x, z]
    const r = tr.r, straight = tr.x_front - tr.x_rear - 2 * r, half = Math.PI * r;
    const L = 2 * straight + 2 * half;
    p = ((p % L) + L) % L;
    if (p < straight) return [tr.x_rear + r + p, 0.001];
    p -= straight;
    if (p < half) { const a = -Math.PI / 2 + p / r; return [tr.x_front - r + r * Math.cos(a), r + r * Math.sin(a)]; }
    p -= half;
    if (p < straight) return [tr.x_front - r - p, 2 * r + 0.001];
    p -= straight;
    const a = Math.PI / 2 + p / r;
    return [tr.x_rear + r + r * Math.cos(a), r + r * Math.sin(a)];
  }
  function cleats(s) {
    const c = Math.cos(s.th), sn = Math.sin(s.th);
    const X = [], Y = [], Z = [];
    R.tracks.forEach(function (tr, side) {
      const enc = side === 0 ? s.encL : s.encR;
      const travel = (enc / R.ticks_per_rev) * 2 * Math.PI * R.wheel_radius;
      const r = tr.r, L = 2 * (tr.x_front - tr.x_rear - 2 * r) + 2 * Math.PI * r;
      const n = Math.floor(L / CLEAT_SPACING);
      for (let m = 0; m < n; m++) {
        // The belt's bottom run stays on the ground, so it moves backwards in the body frame.
        const xz = beltPoint(tr, m * (L / n) - travel);
        [tr.y - tr.half_width, tr.y + tr.half_width].forEach(function (ly) {
          X.push(s.x + c * xz[0] - sn * ly); Y.push(s.y + sn * xz[0] + c * ly); Z.push(xz[1]);
        });
        X.push(null); Y.push(null); Z.push(null);
      }
    });
    return { x: X, y: Y, z: Z };
  }

  // IR beams: from each ranger along its axis, as long as its reading says.
  function beams(s) {
    const c = Math.cos(s.th), sn = Math.sin(s.th);
    const hit = { x: [], y: [], z: [] }, miss = { x: [], y: [], z: [] };
    R.ir.forEach(function (p, n) {
      const ox = s.x + c * p.x - sn * p.y, oy = s.y + sn * p.x + c * p.y;
      const a = s.th + p.angle, len = F.ir_len[n][s.i];
      const dst = F.ir_ok[n][s.i] ? hit : miss;
      dst.x.push(ox, ox + len * Math.cos(a), null);
      dst.y.push(oy, oy + len * Math.sin(a), null);
      dst.z.push(p.z, p.z, null);
    });
    return [hit, miss];
  }

  // The flame: a flickering cone over the wick while lit.
  const FLAME_SEG = 10;
  const flameI = [], flameJ = [], flameK = [];
  for (let n = 0; n < FLAME_SEG; n++) {
    const a = 1 + n, b = 1 + ((n + 1) % FLAME_SEG);
    flameI.push(0, FLAME_SEG + 1); flameJ.push(a, b); flameK.push(b, a);
  }
  function flame(t) {
    const f = S.flame;
    const k = 1 + 0.12 * Math.sin(2 * Math.PI * 7.3 * t) + 0.06 * Math.sin(2 * Math.PI * 11.9 * t + 1.3);
    const X = [f.x], Y = [f.y], Z = [f.z0];
    const zr = f.z0 + 0.3 * (f.z1 - f.z0) * k;
    for (let n = 0; n < FLAME_SEG; n++) {
      const a = (2 * Math.PI * n) / FLAME_SEG;
      X.push(f.x + f.r * Math.cos(a)); Y.push(f.y + f.r * Math.sin(a)); Z.push(zr);
    }
    X.push(f.x + 0.002 * Math.sin(2 * Math.PI * 3.1 * t)); Y.push(f.y); Z.push(f.z0 + (f.z1 - f.z0) * k);
    return { x: X, y: Y, z: Z };
  }

  // ---- the 3D scene --------------------------------------------------------
  const W = S.size[0], H = S.size[1], ZMAX = 0.45, PAD = 0.05;
  const ASPECT = { x: 1, y: (H + 2 * PAD) / (W + 2 * PAD), z: ZMAX / (W + 2 * PAD) };
  function ring(cx, cy, r, z) {
    const X = [], Y = [], Z = [];
    for (let n = 0; n <= 64; n++) {
      const a = (2 * Math.PI * n) / 64;
      X.push(cx + r * Math.cos(a)); Y.push(cy + r * Math.sin(a)); Z.push(z);
    }
    return { x: X, y: Y, z: Z };
  }
  const noHover = { hoverinfo: "skip", showlegend: false };
  const flat = { flatshading: true, lighting: { ambient: 0.55, diffuse: 0.8, specular: 0.1, roughness: 0.8 },
                 lightposition: { x: 1000, y: 600, z: 3000 } };
  const traces = [];
  function add(tr) { traces.push(tr); return traces.length - 1; }
  add(Object.assign({ type: "mesh3d", name: "floor", x: [0, W, W, 0], y: [0, 0, H, H], z: [0, 0, 0, 0],
    i: [0, 0], j: [1, 2], k: [2, 3], color: "#1c1c1c" }, noHover, flat));
  add(Object.assign({ type: "mesh3d", name: "walls" }, S.walls, noHover, flat));
  add(Object.assign({ type: "scatter3d", mode: "lines", name: "wall tops", line: { color: "#6b6b6b", width: 2 } },
    S.wall_edges, noHover));
  add(Object.assign({ type: "mesh3d", name: "doorway lines" }, S.doors, noHover, flat));
  const lw = Math.max(3, S.line_width * 160);
  add(Object.assign({ type: "scatter3d", mode: "lines", name: "home circle", line: { color: "#ffffff", width: lw } },
    ring(S.home.x, S.home.y, S.home.r, 0.004), noHover));
  add(Object.assign({ type: "scatter3d", mode: "lines", name: "candle circle", line: { color: "#ffffff", width: lw } },
    ring(S.candle_circle.x, S.candle_circle.y, S.candle_circle.r, 0.004), noHover));
  add(Object.assign({ type: "mesh3d", name: "candle" }, S.candle, noHover, flat));
  add({ type: "scatter3d", mode: "text", name: "labels", hoverinfo: "skip", showlegend: false,
    x: S.rooms.map((r) => r.x).concat([S.home.x]), y: S.rooms.map((r) => r.y).concat([S.home.y]),
    z: S.rooms.map(() => 0.01).concat([0.01]),
    text: S.rooms.map((r) => "room " + r.id).concat(["H"]), textfont: { color: "#8d8d8d", size: 13 } });
  Object.keys(M.path).forEach(function (name) {
    const p = M.path[name];
    add({ type: "scatter3d", mode: "lines", name: name, x: p.x, y: p.y, z: p.x.map((v) => (v === null ? null : 0.006)),
      line: { color: D.state_colors[name] || "#ffffff", width: 3 }, hoverinfo: "skip", legendgroup: "path",
      legendgrouptitle: { text: "path: firmware state" } });
  });
  const s0 = sample(0);
  const iRobot = add(Object.assign({ type: "mesh3d", name: "robot", uid: "robot", i: robotI, j: robotJ, k: robotK,
    facecolor: F.fan[0] ? colorsOn : colorsOff }, robotGeometry(s0), noHover, flat));
  const iCleats = add(Object.assign({ type: "scatter3d", mode: "lines", name: "tracks", uid: "cleats",
    line: { color: "#9a9a9a", width: 2 } }, cleats(s0), noHover));
  const b0 = beams(s0);
  const iBeamHit = add(Object.assign({ type: "scatter3d", mode: "lines", name: "IR beams", uid: "beams",
    line: { color: "#ff3b30", width: 5 }, hoverinfo: "skip", showlegend: true }, b0[0]));
  const iBeamMiss = add(Object.assign({ type: "scatter3d", mode: "lines", name: "IR: no wall in 80 cm",
    uid: "beams-none", line: { color: "#ff9c96", width: 2, dash: "dash" }, hoverinfo: "skip", showlegend: true },
    b0[1]));
  const iFlame = add(Object.assign({ type: "mesh3d", name: "flame", uid: "flame", i: flameI, j: flameJ, k: flameK,
    color: "#ff9f1a", opacity: 0.95, visible: lit(0), lighting: { ambient: 1, diffuse: 0 } }, flame(0), noHover));
  const DYN = [iRobot, iCleats, iBeamHit, iBeamMiss, iFlame];

  const axis = function (lo, hi, title) {
    return { range: [lo, hi], title: { text: title }, color: "#777", gridcolor: "#2a2a2a", zeroline: false,
      showbackground: false, showspikes: false };
  };
  const TOP_ZOOM = 1.55;
  const CAMERAS = {
    orbit: { eye: { x: 0.12, y: -1.0, z: 0.9 }, up: { x: 0, y: 0, z: 1 }, center: { x: 0, y: 0, z: -0.1 },
      projection: { type: "perspective" } },
    top: { eye: { x: 0, y: 0, z: 1.0 }, up: { x: 0, y: 1, z: 0 }, center: { x: 0, y: 0, z: 0 },
      projection: { type: "orthographic" } },
  };
  const sceneLayout = {
    paper_bgcolor: "#15171a", margin: { l: 0, r: 0, t: 0, b: 0 }, showlegend: true,
    legend: { x: 0.99, xanchor: "right", y: 0.99, bgcolor: "rgba(20,22,26,0.8)", font: { color: "#ccc", size: 11 } },
    scene: {
      xaxis: axis(-PAD, W + PAD, "x (m)"), yaxis: axis(-PAD, H + PAD, "y (m)"), zaxis: axis(0, ZMAX, "z"),
      aspectmode: "manual", aspectratio: ASPECT, camera: CAMERAS.orbit, dragmode: "orbit", bgcolor: "#15171a",
      hovermode: false,
    },
  };
  sceneLayout.scene.zaxis.visible = false;

  // ---- charts: sensors and commands over time, one row each -----------------
  const ROWS = [
    { key: "ir", title: "IR rangers (mV)", h: 0.26 },
    { key: "flame", title: "flame sensors (ADC)", h: 0.17 },
    { key: "pwm", title: "motor PWM (\u2030)", h: 0.2 },
    { key: "dig", title: "fans / line / contact", h: 0.13 },
    { key: "state", title: "firmware state", h: 0.24 },
  ];
  const GAP = 0.045;
  const chartTraces = [];
  const chartLayout = {
    paper_bgcolor: "#15171a", plot_bgcolor: "#1b1e22", font: { color: "#bbb", size: 11 },
    margin: { l: 92, r: 70, t: 24, b: 36 }, hovermode: "x", showlegend: true, shapes: [], annotations: [],
  };
  {
    let top = 1;
    ROWS.forEach(function (row, n) {
      const span = row.h * (1 - GAP * (ROWS.length - 1));
      row.domain = [Math.max(top - span, 0), top];
      top = top - span - GAP;
      const ax = n === 0 ? "" : String(n + 1);
      const last = n === ROWS.length - 1;
      row.xref = "x" + ax;
      row.yref = "y" + ax;
      row.legend = "legend" + ax;
      // One x axis per row, all zoomed together; only the bottom one is labelled.
      chartLayout["xaxis" + ax] = { anchor: row.yref, matches: n === 0 ? undefined : "x", range: [0, T_END],
        gridcolor: "#2c3036", zeroline: false, showticklabels: last, title: { text: last ? "t (s)" : "" } };
      chartLayout["yaxis" + ax] = { anchor: row.xref, domain: row.domain, gridcolor: "#2c3036", zeroline: false,
        fixedrange: true, title: { text: row.title, font: { size: 11 }, standoff: 4 } };
      chartLayout[row.legend] = { x: 1.005, xanchor: "left", y: row.domain[1], yanchor: "top",
        font: { size: 10 }, bgcolor: "rgba(0,0,0,0)" };
    });
  }
  const IR_COLORS = ["#e6194b", "#3cb44b", "#4363d8", "#f58231", "#911eb4"];
  function line(row, name, y, color, extra) {
    chartTraces.push(Object.assign({ type: "scatter", mode: "lines", name: name, x: C.t, y: y, xaxis: row.xref,
      yaxis: row.yref, legend: row.legend, line: { color: color, width: 1.3, shape: "hv" } }, extra || {}));
  }
  const row = {};
  ROWS.forEach((r) => { row[r.key] = r; });
  M.ir_names.forEach((name, n) => line(row.ir, name, C.ir_mv[name], IR_COLORS[n]));
  line(row.flame, "left", C.flame.L, "#ffb000");
  line(row.flame, "right", C.flame.R, "#ff5e00");
  line(row.pwm, "left", C.pwm.L, "#4fc3f7");
  line(row.pwm, "right", C.pwm.R, "#f06292");
  line(row.dig, "fans", C.fan.map((v) => 2 + 0.8 * v), "#4fc3f7");
  line(row.dig, "line", C.line.map((v) => 1 + 0.8 * v), "#eeeeee");
  line(row.dig, "contact", C.contact.map((v) => 0.8 * v), "#ff3b30");
  line(row.state, "state", C.state, "#dddddd", { showlegend: false,
    text: C.state.map(stateName), hovertemplate: "%{text}<extra></extra>" });
  chartLayout[row.dig.yref.replace("y", "yaxis")].tickvals = [0.4, 1.4, 2.4];
  chartLayout[row.dig.yref.replace("y", "yaxis")].ticktext = ["contact", "line", "fans"];
  chartLayout[row.dig.yref.replace("y", "yaxis")].range = [-0.2, 3];
  {
    const seen = Array.from(new Set(C.state)).sort((a, b) => a - b);
    const ya = chartLayout[row.state.yref.replace("y", "yaxis")];
    ya.tickvals = seen; ya.ticktext = seen.map(stateName); ya.range = [seen[0] - 0.7, seen[seen.length - 1] + 0.7];
    ya.title.text = "";
  }
  if (T_EXT !== null) {
    chartLayout.shapes.push({ type: "line", xref: "x", yref: "paper", x0: T_EXT, x1: T_EXT, y0: 0, y1: 1,
      line: { color: "#ff9f1a", width: 1, dash: "dot" } });
    chartLayout.annotations.push({ xref: "x", yref: "paper", x: T_EXT, y: 1, yanchor: "bottom", text: "flame out",
      showarrow: false, font: { color: "#ff9f1a", size: 10 } });
  }
  // The time cursor is a plain element over the charts: moving a Plotly shape redraws the whole
  // chart (tens of ms), moving a div costs nothing. Placed from the x axis' range and the plot area.
  const cursor = document.createElement("div");
  cursor.id = "cursor";
  document.getElementById("right").appendChild(cursor);
  function placeCursor(at) {
    const fl = chartDiv._fullLayout;
    if (!fl || !fl._size) return;
    const sz = fl._size, rg = fl.xaxis.range;
    const u = (at - rg[0]) / (rg[1] - rg[0]);
    cursor.style.display = u < 0 || u > 1 ? "none" : "block";
    cursor.style.left = (sz.l + u * sz.w).toFixed(1) + "px";
    cursor.style.top = sz.t + "px";
    cursor.style.height = sz.h + "px";
  }

  // ---- header ---------------------------------------------------------------
  (function summary() {
    const f = (text) => (text === "-" ? text : text + " s");
    $("summary").innerHTML = "outcome <b>" + M.outcome + "</b>" + (M.detail ? " (" + escapeHtml(M.detail) + ")" : "") +
      " &middot; flame out <b>" + f(M.flame_out_text) + "</b> &middot; home <b>" + f(M.home_text) + "</b>" +
      " &middot; wall contacts <b>" + M.wall_contacts + "</b> &middot; candle (" + M.candle.join(", ") + ") m" +
      " &middot; seed " + M.seed;
  })();
  function escapeHtml(s) {
    return String(s).replace(/[&<>"]/g, (ch) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;" }[ch]));
  }

  // ---- player ---------------------------------------------------------------
  let t = 0, playing = false, speed = 1, view = "orbit";
  let wall = null, busy = false, drawnT = -1;
  slider.max = String(Math.round(T_END * 1000));
  const api = { renderedT: -1, t: 0, frames: NF, ready: false, draws: 0 };
  window.ffrReplay = api;

  function hud(s) {
    const i = s.i;
    $("ro-t").textContent = s.t.toFixed(2);
    $("ro-state").textContent = stateName(F.state[i]);
    $("ro-state").style.color = D.state_colors[stateName(F.state[i])] || "#eee";
    $("ro-x").textContent = s.x.toFixed(3);
    $("ro-y").textContent = s.y.toFixed(3);
    $("ro-th").textContent = ((s.th * 180) / Math.PI).toFixed(1);
    $("ro-pwm").textContent = F.pwm_l[i] + ", " + F.pwm_r[i] + " \u2030";
    $("ro-fan").textContent = F.fan[i] ? "on" : "off";
    $("ro-flame").textContent = lit(s.t) ? "burning" : "out (at " + T_EXT.toFixed(2) + " s)";
    $("ro-ir").textContent = M.ir_names.map((n, k) =>
      n + " " + (F.ir_ok[k][i] ? (F.ir_len[k][i] * 100).toFixed(0) : "--")).join("  ");
    $("ro-fs").textContent = "L " + F.flame_l[i] + "  R " + F.flame_r[i];
    $("ro-line").textContent = (F.line[i] ? "white" : "black") + "; " + F.enc_l[i] + ", " + F.enc_r[i];
    clock.textContent = s.t.toFixed(1) + " / " + T_END.toFixed(1) + " s";
  }

  function followCamera(s) {
    // Plotly's camera lives in the scene box's normalised coordinates: centre 0, sides = aspect ratio.
    const nx = ((s.x + PAD) / (W + 2 * PAD) - 0.5) * ASPECT.x;
    const ny = ((s.y + PAD) / (H + 2 * PAD) - 0.5) * ASPECT.y;
    const nz = -0.5 * ASPECT.z;
    const back = 0.26, up = 0.3;
    return { center: { x: nx, y: ny, z: nz }, up: { x: 0, y: 0, z: 1 }, projection: { type: "perspective" },
      eye: { x: nx - back * Math.cos(s.th), y: ny - back * Math.sin(s.th), z: nz + up } };
  }

  function draw() {
    if (busy || !api.ready || t === drawnT) return;
    busy = true;
    const want = t;
    const s = sample(want);
    const rg = robotGeometry(s), cl = cleats(s), bm = beams(s), fl = flame(want);
    const on = lit(want);
    const upd = {
      x: [rg.x, cl.x, bm[0].x, bm[1].x, fl.x], y: [rg.y, cl.y, bm[0].y, bm[1].y, fl.y],
      z: [rg.z, cl.z, bm[0].z, bm[1].z, fl.z],
      facecolor: [F.fan[s.i] ? colorsOn : colorsOff, null, null, null, null],
      visible: [true, true, true, true, on],
    };
    const lay = view === "follow" ? { "scene.camera": followCamera(s) } : {};
    hud(s);
    placeCursor(want);
    Plotly.update(sceneDiv, upd, lay, DYN).then(function () {
      drawnT = want;
      api.renderedT = want;
      api.draws += 1;
      busy = false;
    }, function () { busy = false; });
  }

  function seek(to) {
    t = Math.min(Math.max(to, 0), T_END);
    api.t = t;
    slider.value = String(Math.round(t * 1000));
    if (!playing) clock.textContent = t.toFixed(1) + " / " + T_END.toFixed(1) + " s";
  }
  function setPlaying(p) {
    playing = p;
    if (p && t >= T_END) seek(0);
    playBtn.innerHTML = p ? "&#10074;&#10074; pause" : "&#9654; play";
    wall = null;
  }
  function loop(now) {
    if (playing) {
      if (wall !== null) seek(t + ((now - wall) / 1000) * speed);
      wall = now;
      if (t >= T_END) setPlaying(false);
    }
    draw();
    requestAnimationFrame(loop);
  }
  function setView(v) {
    view = v;
    document.querySelectorAll("[data-view]").forEach((b) => b.classList.toggle("on", b.dataset.view === v));
    drawnT = -1;  // redraw with the new camera
    // Plotly zooms an orthographic camera through the aspect ratio, not the eye's distance.
    const k = v === "top" ? TOP_ZOOM : 1;
    const lay = { "scene.aspectratio": { x: ASPECT.x * k, y: ASPECT.y * k, z: ASPECT.z * k } };
    if (v !== "follow") lay["scene.camera"] = CAMERAS[v];
    Plotly.relayout(sceneDiv, lay);
  }
  api.seek = function (to) { seek(to); };
  api.play = function () { setPlaying(true); };
  api.pause = function () { setPlaying(false); };
  api.setView = setView;
  api.robotXY = function () {  // mean of the robot mesh's vertices as drawn: what the viewer sees
    const d = sceneDiv.data[iRobot];
    let sx = 0, sy = 0;
    for (let n = 0; n < d.x.length; n++) { sx += d.x[n]; sy += d.y[n]; }
    return [sx / d.x.length, sy / d.y.length];
  };

  playBtn.addEventListener("click", () => setPlaying(!playing));
  speedSel.addEventListener("change", () => { speed = parseFloat(speedSel.value); });
  slider.addEventListener("input", () => { seek(parseFloat(slider.value) / 1000); });
  document.querySelectorAll("[data-view]").forEach((b) => b.addEventListener("click", () => setView(b.dataset.view)));
  document.addEventListener("keydown", function (ev) {
    if (ev.target && (ev.target.tagName === "SELECT" || ev.target.tagName === "INPUT")) return;  // they have their own keys
    if (ev.key === " ") { ev.preventDefault(); setPlaying(!playing); }
    else if (ev.key === "ArrowRight") seek(t + 1 / M.fps);
    else if (ev.key === "ArrowLeft") seek(t - 1 / M.fps);
  });

  // plotly renders 3D at twice the pixel ratio by default: four times the pixels for no gain on a plain screen
  const config = { displaylogo: false, responsive: true, modeBarButtonsToRemove: ["toImage"],
    plotGlPixelRatio: Math.max(1, Math.min(2, window.devicePixelRatio || 1)) };
  Promise.all([
    Plotly.newPlot(sceneDiv, traces, sceneLayout, config),
    Plotly.newPlot(chartDiv, chartTraces, chartLayout, Object.assign({}, config, { scrollZoom: false })),
  ]).then(function () {
    chartDiv.on("plotly_click", function (ev) { if (ev.points && ev.points.length) seek(ev.points[0].x); });
    // zooming or resizing the charts moves the axis under the cursor
    chartDiv.on("plotly_relayout", function () { placeCursor(t); });
    window.addEventListener("resize", function () { setTimeout(function () { placeCursor(t); }, 100); });
    hud(s0);
    api.ready = true;
    requestAnimationFrame(loop);
  });
})();
