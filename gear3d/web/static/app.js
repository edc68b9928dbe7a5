// gear3d serve: the page. Forms come from /api/schema/<family>; every build is the server's.
// Requests carry parameters only; a field left at its default is not sent (as with the CLI).
// Errors come back as {error, param}: shown next to that field, never a traceback.
// The current design lives in the URL's fragment (#family=...&teeth=...&b.width=...&pair.mate_teeth=...,
// the API's own query keys): every change rewrites it, and opening such a link fills the form.

const $ = (s) => document.querySelector(s);
const SCOPES = ["profile", "body", "pair", "export"];
const PREFIX = { profile: "", body: "b.", pair: "pair.", export: "x." };
let schema = null;            // current family's form schema
const state = { anim: null, frame: 0, playing: true, timer: null };
let presetList = [];          // the designs /api/schema offers (gear3d/web/presets.py)
let lastHash = null;          // the fragment this page wrote last (a different one is a pasted link)

function setStatus(text) { $("#status").textContent = text; }

// ------------------------------------------------------------------ forms

function fieldId(scope, name) { return `${scope}-${name.replace(/[^\w-]/g, "_")}`; }

function fmtDefault(v) { return v === null || v === undefined ? "" : String(v); }

function buildForm(scope, fields) {
  const form = $(`#form-${scope}`);
  form.innerHTML = "";
  // grouped (size, tooth form, body, print compensation, ...), each group in table order
  const order = (schema && schema.groups) || [];
  const rank = (f) => { const i = order.indexOf(f.group); return i < 0 ? order.length : i; };
  const sorted = fields.map((f, i) => [f, i]).sort((a, b) => rank(a[0]) - rank(b[0]) || a[1] - b[1]).map((x) => x[0]);
  let group = null;
  for (const f of sorted) {
    if (f.group && f.group !== group) {
      group = f.group;
      const h = document.createElement("div");
      h.className = "group";
      h.textContent = group;
      form.append(h);
    }
    const id = fieldId(scope, f.name);
    const row = document.createElement("div");
    row.className = "field";
    row.id = `field-${id}`;
    row.dataset.name = f.name;
    const label = document.createElement("label");
    label.htmlFor = `in-${id}`;
    label.textContent = f.label || f.name;
    // tooltip: what it is, its range, and the flag / TOML key it stands for
    label.title = (f.help || "") + (f.range ? ` (${f.range})` : "") + (f.flag ? `; ${f.flag}, key ${f.name}` : "");
    let input;
    if (f.type === "bool") {
      input = document.createElement("input");
      input.type = "checkbox";
      input.checked = !!f.default;
    } else if (f.choices) {
      input = document.createElement("select");
      if (f.default === null || f.default === undefined) input.add(new Option("(default)", ""));
      for (const c of f.choices) input.add(new Option(c, c));
      input.value = fmtDefault(f.default);
    } else {
      input = document.createElement("input");
      input.type = "text";
      if (f.type !== "str") input.inputMode = "decimal";
      input.value = fmtDefault(f.default);
      input.placeholder = f.required ? "required" : (f.default === null ? "auto" : "");
    }
    input.id = `in-${id}`;
    input.name = f.name;
    input.dataset.scope = scope;
    input.dataset.default = f.type === "bool" ? String(!!f.default) : fmtDefault(f.default);
    input.dataset.required = f.required ? "1" : "";
    input.title = label.title;
    const unit = document.createElement("span");
    unit.className = "unit";
    unit.textContent = f.unit || "";
    const help = document.createElement("div");
    help.className = "help";
    help.textContent = (f.flag ? f.flag + ": " : "") + (f.help || "");
    const err = document.createElement("div");
    err.className = "error";
    err.id = `err-${id}`;
    row.append(label, input, unit, help, err);
    form.append(row);
    const ev = f.type === "bool" || f.choices ? "change" : "input";
    input.addEventListener(ev, () => onChange(scope));
    input.addEventListener("focus", () => {
      $(`#help-${scope}`).textContent = help.textContent + (f.range ? ` [${f.range}]` : "");
    });
  }
  form.addEventListener("submit", (e) => e.preventDefault());
}

function value(input) { return input.type === "checkbox" ? String(input.checked) : input.value.trim(); }

// query of the given scopes: family + changed or required fields
function query(scopes, extra = {}) {
  const q = new URLSearchParams({ family: $("#family").value });
  for (const scope of scopes) {
    for (const input of document.querySelectorAll(`#form-${scope} [name]`)) {
      const v = value(input);
      if (v === "" || (v === input.dataset.default && !input.dataset.required)) continue;
      q.append(PREFIX[scope] + input.name, v);
    }
  }
  for (const [k, v] of Object.entries(extra)) q.append(k, v);
  return q.toString();
}

function clearErrors(scopes) {
  for (const scope of scopes) {
    for (const el of document.querySelectorAll(`#form-${scope} .error`)) el.textContent = "";
    for (const el of document.querySelectorAll(`#form-${scope} .field.invalid`)) el.classList.remove("invalid");
  }
}

// show a {error, param} next to its field: the first scope where the field was sent, else
// the first where it exists, else the panel's general line
function showError(scopes, general, res) {
  const name = res.param;
  let target = null;
  if (name) {
    const cands = scopes.map((s) => document.getElementById(`in-${fieldId(s, name)}`)).filter(Boolean);
    target = cands.find((i) => value(i) !== "" && value(i) !== i.dataset.default) || cands[0] || null;
  }
  if (target) {
    const id = target.id.slice(3);
    $(`#err-${id}`).textContent = res.error;
    $(`#field-${id}`).classList.add("invalid");
  } else {
    $(general).textContent = res.error || "error";
  }
}

// ------------------------------------------------------------------ requests

async function getJSON(url) {
  const r = await fetch(url, { cache: "no-store" });
  let body;
  try { body = await r.json(); } catch (e) { body = { error: `HTTP ${r.status}` }; }
  return { status: r.status, body };
}

// latest-wins runner: one request in flight per task; a change while it runs reruns it once
function task(fn, delay) {
  let timer = null, running = false, again = false;
  const run = async () => {
    if (running) { again = true; return; }
    running = true;
    try { await fn(); } finally {
      running = false;
      if (again) { again = false; run(); }
    }
  };
  return () => { clearTimeout(timer); timer = setTimeout(run, delay); };
}

async function retrying(fetcher) {   // 503 (server busy): retry, bounded
  for (let i = 0; i < 40; i++) {
    const res = await fetcher();
    if (res.status !== 503) return res;
    setStatus("server busy, retrying...");
    await new Promise((ok) => setTimeout(ok, 250 + 50 * i));
  }
  return { status: 503, body: { error: "server busy" } };
}

// ------------------------------------------------------------------ 2D preview + report

const fmt = (v, unit = "") => {
  if (v === null || v === undefined) return "-";
  if (typeof v === "number") return (Number.isInteger(v) ? String(v) : v.toPrecision(5).replace(/\.?0+$/, "")) + unit;
  if (typeof v === "boolean") return v ? "yes" : "no";
  return String(v);
};

function table(el, rows) {
  el.innerHTML = "";
  for (const [k, v, flag] of rows) {
    const tr = el.insertRow();
    tr.insertCell().textContent = k;
    const td = tr.insertCell();
    td.textContent = v;
    if (flag) td.className = "flag";
  }
}

async function preview() {
  const q = query(["profile"]);
  const t0 = performance.now();
  const res = await retrying(() => getJSON(`/api/profile?${q}`));
  clearErrors(["profile"]);
  $("#err-profile-general").textContent = "";
  if (res.status !== 200) {
    showError(["profile"], "#err-profile-general", res.body);
    setStatus("profile: " + (res.body.param ? `${res.body.param}: invalid` : "error"));
    return;
  }
  const { svg, report: r, neck } = res.body;
  $("#preview").innerHTML = svg;
  const shown = Math.round(performance.now() - t0);
  $("#preview-info").textContent = `built in ${res.body.ms} ms, shown in ${shown} ms`;
  $("#preview").dataset.ms = String(shown);
  $("#preview").dataset.query = q;         // what is drawn (the browser test waits on it)
  if (r.limits) {           // a face gear: its band of radii and their limits (no body measured here)
    table($("#report"), [
      ["section", r.section], ["R1 (inner radius)", fmt(r.inner_radius, " mm")],
      ["R2 (outer radius)", fmt(r.outer_radius, " mm")], ["pitch_radius", fmt(r.pitch_radius, " mm")],
      ["inner limit (undercut, base circle)", fmt(r.limits.inner, " mm")],
      ["outer limit (pointing)", fmt(r.limits.outer, " mm")],
      ["tip land at R1", fmt(r.tip_land_inner, " mm")], ["tip land at R2", fmt(r.tip_land_outer, " mm")],
      ["tolerance", fmt(r.tolerance * 1000, " um")],
    ]);
    setStatus(`preview ${res.body.ms} ms`);
    return;
  }
  if (r.crossed) {          // a crossed helical pair: its placement and rolling check, wheel 1's section drawn
    const c = r.check || {}, s = r.section_report || {};
    table($("#report"), [
      ["section", r.section], ["centre distance", fmt(r.center_distance, " mm")],
      ["shaft angle", fmt(r.shaft_angle_deg, " deg")],
      ["helix angles", `${fmt(r.gear.helix_angle_deg, " deg")} / ${fmt(r.mate.helix_angle_deg, " deg")}`],
      ["contact ratio", fmt(r.contact_ratio), r.contact_ratio < 1],
      ["normal backlash (at this distance)", fmt(r.normal_backlash, " mm")],
      ["check: interference", r.check ? fmt(c.interference) : "-", !!c.interference],
      ["check: normal backlash", r.check ? `${fmt(c.backlash_normal_min, " mm")} .. ${fmt(c.backlash_normal_max, " mm")}` : "-"],
      ["check: contact ratio", r.check ? fmt(c.contact_ratio) : "-", r.check && c.contact_ratio < 1],
      ["sliding / pitch speed", fmt(r.sliding_per_pitch_speed)],
      ["section max_error (measured)", fmt(s.max_error * 1000, " um")], ["tolerance", fmt(s.tolerance * 1000, " um")],
    ]);
    setStatus(`preview ${res.body.ms} ms`);
    return;
  }
  table($("#report"), [
    ...(r.section ? [["section", r.section]] : []),
    ["max_error (measured)", fmt(r.max_error * 1000, " um")], ["tolerance", fmt(r.tolerance * 1000, " um")],
    ["undercut", fmt(r.undercut) + (r.undercut ? ` (depth ${fmt(r.undercut_depth, " mm")})` : ""), r.undercut],
    ["pointed", fmt(r.pointed) + (r.pointed ? ` (tip shortfall ${fmt(r.tip_shortfall, " mm")})` : ""), r.pointed],
    ["neck", neck ? `at r=${fmt(neck.radius, " mm")}: ${fmt(neck.thickness, " mm")} < ${fmt(neck.thicker_outside, " mm")}` : "no", !!neck],
    ["tip_radius", fmt(r.tip_radius, " mm")], ["root_radius", fmt(r.root_radius, " mm")],
    ["pitch_radius", fmt(r.pitch_radius, " mm")], ["base_radius", fmt(r.base_radius, " mm")],
    ["thickness_at_pitch", fmt(r.thickness_at_pitch, " mm")], ["tip_land_width", fmt(r.tip_land_width, " mm")],
    ["vertices", fmt(r.vertices)],
  ]);
  setStatus(`preview ${res.body.ms} ms`);
}

// ------------------------------------------------------------------ 3D body (three.js)

let three = null;   // {THREE, renderer, scene, camera, controls, mesh}

async function initThree() {
  if (three) return three;
  const el = $("#view3d");
  const THREE = await import("three");
  const { OrbitControls } = await import("three/addons/OrbitControls.js");
  let renderer;
  try {
    renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  } catch (e) {
    el.innerHTML = '<div class="note">WebGL is not available in this browser: no 3D preview (downloads still work)</div>';
    three = { failed: true };
    return three;
  }
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(el.clientWidth, el.clientHeight);
  el.innerHTML = "";
  el.append(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xeef1f6);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8090a0, 1.6));
  const camera = new THREE.PerspectiveCamera(35, el.clientWidth / el.clientHeight, 0.01, 1e5);
  camera.up.set(0, 0, 1);
  const sun = new THREE.DirectionalLight(0xffffff, 1.8);
  camera.add(sun);
  sun.position.set(1, 2, 3);
  scene.add(camera);
  const controls = new OrbitControls(camera, renderer.domElement);
  const render = () => renderer.render(scene, camera);
  controls.addEventListener("change", render);
  window.addEventListener("resize", () => {
    renderer.setSize(el.clientWidth, el.clientHeight);
    camera.aspect = el.clientWidth / el.clientHeight;
    camera.updateProjectionMatrix();
    render();
  });
  three = { THREE, renderer, scene, camera, controls, render, mesh: null };
  return three;
}

async function body3d() {
  const q = query(["profile", "body"]);
  const res = await retrying(async () => {
    const r = await fetch(`/api/body?${q}`, { cache: "no-store" });
    if (r.ok) return { status: 200, buf: await r.arrayBuffer(), report: JSON.parse(r.headers.get("X-Gear3d-Report") || "{}") };
    let body;
    try { body = await r.json(); } catch (e) { body = { error: `HTTP ${r.status}` }; }
    return { status: r.status, body };
  });
  clearErrors(["body"]);
  $("#err-body-general").textContent = "";
  if (res.status !== 200) {
    showError(["body", "profile"], "#err-body-general", res.body);
    return;
  }
  const t = await initThree();
  const r = res.report;
  table($("#body-report"), [
    ["kind", fmt(r.kind)], ["triangles", fmt(r.triangles)], ["max_error (measured)", fmt(r.max_error * 1000, " um")],
    ["tolerance", fmt(r.tolerance * 1000, " um")], ["volume", fmt(r.volume, " mm3")], ["watertight", fmt(r.watertight)],
    ["layers", fmt(r.layers)], ["total_twist_deg", fmt(r.total_twist_deg, " deg")],
  ]);
  const view = $("#view3d");
  view.dataset.family = r.family;
  view.dataset.internal = String(r.internal);
  view.dataset.triangles = String(r.triangles);     // set with or without WebGL (the report is shown either way)
  if (t.failed) return;
  const { THREE } = t;
  const head = new Uint32Array(res.buf, 0, 2);
  const nv = head[0], nf = head[1];
  const pos = new Float32Array(res.buf, 8, nv * 3);
  const idx = new Uint32Array(res.buf, 8 + 12 * nv, nf * 3);
  const geo = new THREE.BufferGeometry();
  geo.setAttribute("position", new THREE.BufferAttribute(pos, 3));
  geo.setIndex(new THREE.BufferAttribute(idx, 1));
  geo.computeVertexNormals();
  geo.computeBoundingSphere();
  if (t.mesh) { t.scene.remove(t.mesh); t.mesh.geometry.dispose(); t.mesh.material.dispose(); }
  const mat = new THREE.MeshStandardMaterial({ color: 0x5b7fb8, metalness: 0.15, roughness: 0.55, flatShading: true });
  t.mesh = new THREE.Mesh(geo, mat);
  t.scene.add(t.mesh);
  const s = geo.boundingSphere;
  // fit the camera on the first body, a new family or a body of another size; keep the user's view otherwise
  const ratio = t.fitRadius ? s.radius / t.fitRadius : 0;
  if (!t.fitted || t.fitFamily !== r.family || ratio > 1.5 || ratio < 0.67) {
    t.fitRadius = s.radius;
    t.fitFamily = r.family;
    const d = s.radius / Math.sin((t.camera.fov * Math.PI) / 360) * 1.05;
    t.camera.position.set(s.center.x + 0.45 * d, s.center.y - 0.65 * d, s.center.z + 0.6 * d);
    t.controls.target.copy(s.center);
    t.fitted = true;
  }
  t.camera.near = s.radius / 100;
  t.camera.far = s.radius * 100;
  t.camera.updateProjectionMatrix();
  t.controls.update();
  t.render();
  view.dataset.rendered = String(nf);
}

// ------------------------------------------------------------------ pair check + animation

const SVGNS = "http://www.w3.org/2000/svg";
const pathOf = (loops) => loops.map((l) => "M" + l.map((p) => `${p[0]},${p[1]}`).join("L") + "Z").join("");

function drawPair(a) {
  // the wheels turn: bound by circles about their centres
  let xmin = Infinity, xmax = -Infinity, ymin = Infinity, ymax = -Infinity;
  for (const w of [a.wheel1, a.wheel2]) {
    let R = 0;
    for (const l of w.loops) for (const p of l) R = Math.max(R, Math.hypot(p[0], p[1]));
    xmin = Math.min(xmin, w.centre[0] - R); xmax = Math.max(xmax, w.centre[0] + R);
    ymin = Math.min(ymin, w.centre[1] - R); ymax = Math.max(ymax, w.centre[1] + R);
  }
  const m = 0.03 * (xmax - xmin);
  const full = [xmin - m, -(ymax + m), xmax - xmin + 2 * m, ymax - ymin + 2 * m];
  const focus = a.worst || a.pitch_point;
  const zw = 4 * (2 * a.wheel1.pitch_radius / Math.max(a.teeth1 || 1, 1));
  const zoom = [focus[0] - zw / 2, -focus[1] - zw / 2, zw, zw];
  const scene = `
    <defs><g id="pair-scene"><g transform="scale(1,-1)">
      <g id="pair-w2" transform=""><path class="wheel2" d="${pathOf(a.wheel2.loops)}" fill="#e8e8e8" fill-rule="evenodd" stroke="#222" stroke-width="1" vector-effect="non-scaling-stroke"/></g>
      <g id="pair-w1" transform=""><path class="wheel1" d="${pathOf(a.wheel1.loops)}" fill="#c9d8f0" fill-opacity="0.8" fill-rule="evenodd" stroke="#1f3b73" stroke-width="1" vector-effect="non-scaling-stroke"/></g>
      <g id="pair-int"></g>
      ${a.worst ? `<circle class="worst" cx="${a.worst[0]}" cy="${a.worst[1]}" r="${zw / 40}" fill="none" stroke="#000" stroke-width="1.5" vector-effect="non-scaling-stroke"/>` : ""}
    </g></g></defs>`;
  $("#pair-view").innerHTML = `<svg xmlns="${SVGNS}" viewBox="0 0 960 480" id="pair-svg">${scene}
    <svg x="0" y="0" width="480" height="480" viewBox="${full.join(" ")}"><use href="#pair-scene"/></svg>
    <svg x="480" y="0" width="480" height="480" viewBox="${zoom.join(" ")}"><use href="#pair-scene"/></svg>
    <text x="8" y="18" font-size="14" font-family="sans-serif">the pair</text>
    <text x="488" y="18" font-size="14" font-family="sans-serif">${a.worst ? "at the worst interference" : "at the pitch point"}</text>
    <rect x="480" y="0" width="480" height="480" fill="none" stroke="#ccd"/></svg>`;
}

function showFrame(k) {
  const a = state.anim;
  if (!a) return;
  state.frame = k;
  const f = a.frames[k];
  $("#pair-w1").setAttribute("transform", `translate(${a.wheel1.centre[0]},${a.wheel1.centre[1]}) rotate(${f.angle1_deg})`);
  $("#pair-w2").setAttribute("transform", `translate(${a.wheel2.centre[0]},${a.wheel2.centre[1]}) rotate(${f.angle2_deg})`);
  $("#pair-int").innerHTML = f.interference.map((poly) =>
    `<path class="interference" d="${pathOf([poly])}" fill="#ff0000" fill-opacity="0.85" stroke="#ff0000" stroke-width="2" vector-effect="non-scaling-stroke"/>`).join("");
  $("#pair-frame").value = String(k);
  $("#pair-frame-label").textContent = `frame ${k + 1}/${a.frames.length}, wheel 1 at ${f.angle1_deg.toFixed(2)} deg` +
    (f.interference.length ? ", interference" : "");
}

function play(on) {
  state.playing = on;
  $("#pair-play").textContent = on ? "pause" : "play";
  clearInterval(state.timer);
  if (on && state.anim) state.timer = setInterval(() => showFrame((state.frame + 1) % state.anim.frames.length), 110);
}

async function checkPair() {
  const q = query(["profile", "pair"]);
  $("#pair-summary").textContent = "rolling the pair...";
  $("#pair-summary").className = "";
  const res = await retrying(() => getJSON(`/api/pair?${q}`));
  clearErrors(["pair"]);
  $("#err-pair-general").textContent = "";
  if (res.status !== 200) {
    $("#pair-summary").textContent = "";
    showError(["pair", "profile"], "#err-pair-general", res.body);
    return;
  }
  const { report: r, summary, animation } = res.body;
  $("#pair-summary").textContent = summary;
  $("#pair-summary").className = r.interference ? "bad" : "";
  const at = r.interference_at || {};
  table($("#pair-report"), [
    ["interference", fmt(r.interference), r.interference],
    ["max_penetration", fmt(r.max_penetration * 1000, " um"), r.interference],
    ["interference at", r.interference ? `wheel 1 r=${fmt(at.radius1, " mm")}, wheel 2 r=${fmt(at.radius2, " mm")}` +
      (at.opposite_pitch_point ? " (opposite the pitch point)" : "") : "-"],
    ["contact_ratio", fmt(r.contact_ratio)], ["min_clearance", fmt(r.min_clearance === null ? null : r.min_clearance * 1000, " um")],
    ["backlash", fmt(r.backlash, " mm")], ["center_distance", fmt(r.center_distance, " mm")],
    ["transmission_error_pp", fmt(r.transmission_error_pp, " mm")], ["tolerance", fmt(r.tolerance * 1000, " um")],
  ]);
  animation.teeth1 = r.teeth[0];
  state.anim = animation;
  drawPair(animation);
  $("#pair-controls").hidden = false;
  $("#pair-frame").max = String(animation.frames.length - 1);
  showFrame(0);
  play(state.playing);
}

// ------------------------------------------------------------------ downloads

async function download(fmtName) {
  // a mesh is built from the body (the schema says which downloads); every download takes its options
  const scopes = (schema.body_downloads || []).includes(fmtName) ? ["profile", "body", "export"] : ["profile", "export"];
  const q = query(scopes, { fmt: fmtName });
  $("#err-download-general").textContent = "";
  setStatus(`building ${fmtName.toUpperCase()}...`);
  const res = await retrying(async () => {
    const r = await fetch(`/api/download?${q}`, { cache: "no-store" });
    if (r.ok) return { status: 200, blob: await r.blob(), disp: r.headers.get("Content-Disposition") || "" };
    let body;
    try { body = await r.json(); } catch (e) { body = { error: `HTTP ${r.status}` }; }
    return { status: r.status, body };
  });
  clearErrors(scopes);
  if (res.status !== 200) {
    showError(scopes.slice().reverse(), "#err-download-general", res.body);
    setStatus(`${fmtName.toUpperCase()}: not built`);
    return;
  }
  const m = /filename="([^"]+)"/.exec(res.disp);
  const a = document.createElement("a");
  a.href = URL.createObjectURL(res.blob);
  a.download = m ? m[1] : `gear.${fmtName}`;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 60000);
  setStatus(`${a.download}: ${res.blob.size} bytes`);
}

// ------------------------------------------------------------------ wiring

const schedulePreview = task(preview, 30);
const scheduleBody = task(body3d, 800);

function onChange(scope) {
  if (scope === "profile") { schedulePreview(); scheduleBody(); }
  if (scope === "body") scheduleBody();
  notPreset();
  saveURL();
}

// the family's forms, at their defaults (true once built)
async function loadFamily(name) {
  const res = await getJSON(`/api/schema/${encodeURIComponent(name)}`);
  if (res.status !== 200) { setStatus(res.body.error); return false; }
  schema = res.body;
  for (const s of SCOPES) buildForm(s, schema[s]);
  // a worm, bevel or face gear set: one form (its table), no body or pair form, its own downloads
  const isSet = !!schema.set;
  for (const id of ["#section-body", "#section-pair", "#pair-panel"]) $(id).hidden = isSet;
  const titles = {worm: ["Worm pair", "Wheel mid-plane section"], bevel: ["Bevel pair", "Gear heel section"],
                  "face-gear": ["Face gear set", "Sections at R1, mid-radius and R2, unrolled"],
                  crossed: ["Crossed helical pair", "Wheel 1 transverse section; the pair's check"]};
  $("#title-profile").textContent = isSet ? titles[name][0] : "Profile";
  $("#preview-title").textContent = isSet ? titles[name][1] : "Profile";
  for (const b of document.querySelectorAll("#downloads button")) b.hidden = !(schema.downloads || []).includes(b.dataset.fmt);
  document.body.dataset.family = name;
  document.body.dataset.set = isSet ? "1" : "";
  if (!presetList.length && schema.presets) fillPresets(schema.presets);
  return true;
}

// ------------------------------------------------------------------ presets + the design in the URL

// the design in the URL's fragment, replaced (not pushed: no history entry per keystroke)
function saveURL() {
  const h = "#" + query(SCOPES);
  lastHash = h;
  if (location.hash !== h || location.search) history.replaceState(null, "", location.pathname + h);
  $("#design-link").href = location.href;
}

function inputFor(key) {
  const scope = SCOPES.find((s) => PREFIX[s] && key.startsWith(PREFIX[s])) || "profile";
  return document.getElementById(`in-${fieldId(scope, key.slice(PREFIX[scope].length))}`);
}

// put a text in a field as a person would; false when the field cannot hold it (a select's unknown choice)
function setInput(input, text) {
  if (input.type === "checkbox") {
    input.checked = ["1", "true", "on", "yes"].includes(text.toLowerCase());
    return true;
  }
  input.value = text;
  return input.value === text;
}

// fill the forms with a design (URLSearchParams of family, NAME, b.NAME, pair.NAME): the
// fields it leaves out take their defaults; what no field takes is named beside the presets
async function applyDesign(params) {
  const sel = $("#family");
  const fam = params.get("family") || sel.value || "involute";
  const names = [...sel.options].map((o) => o.value);
  if (!names.includes(fam)) {
    $("#preset-info").textContent = `link: family = ${fam} is not allowed: one of ${names.join(", ")}`;
    return false;
  }
  sel.value = fam;
  if (!(await loadFamily(fam))) return false;
  const ignored = [];
  for (const [k, v] of params) {
    if (k === "family") continue;
    const input = inputFor(k);
    if (!input || !setInput(input, v)) ignored.push(`${k}=${v}`);
  }
  $("#preset-info").textContent = ignored.length ? `link: no field takes ${ignored.join(", ")}` : "";
  saveURL();
  schedulePreview();
  scheduleBody();
  return true;
}

function fillPresets(list) {
  presetList = list;
  const sel = $("#preset");
  for (const p of list) {
    const o = new Option(p.label, p.name);
    o.title = p.description;
    sel.add(o);
  }
}

async function choosePreset(name) {
  const p = presetList.find((x) => x.name === name);
  if (!p) return;
  await applyDesign(new URLSearchParams(p.query));
  $("#preset").value = p.name;
  $("#preset-info").textContent = p.description;
}

// an edit makes the design the user's own
function notPreset() {
  if ($("#preset").value) { $("#preset").value = ""; $("#preset-info").textContent = ""; }
}

async function main() {
  const res = await getJSON("/api/families");
  const sel = $("#family");
  for (const f of res.body.families) sel.add(new Option(f, f));
  sel.value = res.body.families.includes("involute") ? "involute" : res.body.families[0];
  sel.addEventListener("change", async () => {
    notPreset();
    if (await loadFamily(sel.value)) { saveURL(); schedulePreview(); scheduleBody(); }
  });
  $("#preset").addEventListener("change", (e) => choosePreset(e.target.value));
  window.addEventListener("hashchange", () => {     // a link pasted into this tab
    if (location.hash !== lastHash) applyDesign(new URLSearchParams(location.hash.slice(1)));
  });
  const dl = $("#downloads");
  for (const f of res.body.downloads) {
    const b = document.createElement("button");
    b.type = "button";
    b.id = `download-${f}`;
    b.dataset.fmt = f;
    b.textContent = f.toUpperCase();
    b.addEventListener("click", () => download(f));
    dl.append(b);
  }
  $("#check-pair").addEventListener("click", checkPair);
  $("#pair-play").addEventListener("click", () => play(!state.playing));
  $("#pair-frame").addEventListener("input", (e) => { play(false); showFrame(Number(e.target.value)); });
  // a link holds a design (#..., or ?... as the API's query): fill the form with it
  const link = location.hash.length > 1 ? location.hash.slice(1) : location.search.slice(1);
  const given = new URLSearchParams(link);
  if ([...given.keys()].length) await applyDesign(given);
  else if (await loadFamily(sel.value)) { saveURL(); schedulePreview(); scheduleBody(); }
  document.body.dataset.ready = "1";
}

main().catch((e) => setStatus(`page error: ${e.message}`));
