// layertrace serve: the page's script (embedded in the binary; no libraries).
"use strict";

const $ = (id) => document.getElementById(id);
let file = null;
let size = null; // [width, height] of the last result
const urls = {}; // object URLs in use, by element id

function setUrl(id, blob) {
  if (urls[id]) URL.revokeObjectURL(urls[id]);
  urls[id] = blob ? URL.createObjectURL(blob) : "";
  return urls[id];
}

function pngBlob(base64) {
  const bin = atob(base64);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  return new Blob([bytes], { type: "image/png" });
}

function showError(message) {
  const box = $("error");
  box.textContent = message;
  box.hidden = !message;
}

function chooseFile(f) {
  if (!f) return;
  file = f;
  $("go").disabled = false;
  $("in-img").src = setUrl("in-img", f);
  convert();
}

function baseName(name) {
  const dot = name.lastIndexOf(".");
  return (dot > 0 ? name.slice(0, dot) : name) || "layertrace";
}

async function convert() {
  if (!file) return;
  const params = new URLSearchParams({
    model: $("model").value,
    threshold: $("threshold").value.trim(),
    cover: $("cover").value,
    turdsize: $("turdsize").value || "0",
    invert: $("invert").checked ? "1" : "0",
    colors: $("colors").value.trim(),
    layout: $("layout").value,
    smooth: $("smooth").value.trim(),
    alpha: $("alpha").checked ? "1" : "0",
    name: file.name,
  });
  $("go").disabled = true;
  showError("");
  $("status").textContent = `Converting ${file.name} (${file.size} bytes)…`;
  const start = performance.now();
  let answer;
  try {
    const response = await fetch(`/api/vectorize?${params}`, { method: "POST", body: file });
    answer = await response.json();
    if (!response.ok && !answer.error) answer.error = `HTTP ${response.status}`;
  } catch (e) {
    answer = { error: `the server did not answer (${e.message})` };
  }
  const ms = Math.round(performance.now() - start);
  $("go").disabled = false;
  if (answer.error) {
    $("status").textContent = `Failed after ${ms} ms.`;
    $("result").hidden = true;
    showError(answer.error);
    return;
  }
  show(answer, ms);
}

function show(a, ms) {
  size = [a.width, a.height];
  $("pieces").textContent = a.pieces;
  $("contours").textContent = a.contours;
  const diff = $("differing");
  diff.textContent = a.differing === null ? "not checked" : String(a.differing);
  // Smooth runs may change pixels within ν: there the figure to watch is "beyond ν".
  diff.className = a.differing === 0 ? "good" : a.beyond === null ? "bad" : "";
  $("iou").textContent = a.iou === null || a.iou === undefined ? "–" : a.iou.toFixed(6);
  $("band-figure").hidden = a.beyond === null;
  if (a.beyond !== null) {
    $("beyond").textContent = `${a.beyond} (ν = ${a.smooth}, max ${a.max_distance.toFixed(3)} px)`;
    $("beyond").className = a.beyond === 0 ? "good" : "bad";
  }
  const tiled = a.chromium_tiles === null || a.chromium_tiles === undefined;
  $("tiles-figure").hidden = tiled;
  if (!tiled) {
    $("tiles").textContent = String(a.chromium_tiles);
    $("tiles").className = a.chromium_tiles === 0 ? "good" : "bad";
  }
  $("seams-figure").hidden = a.seams === null;
  if (a.seams !== null) {
    $("seams").textContent = String(a.seams);
    $("seams").className = a.seams === 0 ? "good" : "bad";
  }
  $("diff-key").textContent = a.colours
    ? "(regions faded, wrong colour red, painted outside them blue)"
    : "(mask black, missing red, extra blue)";
  const list = $("colours");
  list.replaceChildren();
  list.hidden = !a.colours;
  for (const c of a.colours || []) {
    const item = document.createElement("li");
    const swatch = document.createElement("span");
    swatch.className = "swatch";
    swatch.style.background = c.colour;
    item.append(swatch, `${c.colour}: ${c.pixels} px, ${c.differing} differing`);
    list.append(item);
  }
  $("commands").textContent = a.commands;
  $("svgbytes").textContent = `${a.svg_bytes} bytes`;
  $("size").textContent = `${a.width} × ${a.height} px`;
  $("seconds").textContent = `${(a.seconds * 1000).toFixed(0)} ms (page ${ms} ms)`;

  const svg = new Blob([a.svg], { type: "image/svg+xml" });
  const json = new Blob([a.json], { type: "application/json" });
  $("out-svg").src = setUrl("out-svg", svg);
  $("out-diff").src = a.diff_png ? setUrl("out-diff", pngBlob(a.diff_png)) : "";
  $("out-dec").src = a.decomposition_png ? setUrl("out-dec", pngBlob(a.decomposition_png)) : "";
  // (`hidden` would lose to the stylesheet's `display: block`.)
  $("out-dec").style.display = a.decomposition_png ? "" : "none";
  $("no-dec").hidden = Boolean(a.decomposition_png);
  const name = baseName(a.name);
  $("dl-svg").href = setUrl("dl-svg", svg);
  $("dl-svg").download = `${name}.svg`;
  $("dl-json").href = setUrl("dl-json", json);
  $("dl-json").download = `${name}.json`;
  $("result").hidden = false;
  const colours = a.colours ? `${a.colours.length} colours, ` : "";
  $("status").textContent = `${a.name}: ${colours}${a.pieces} pieces, ${a.differing} differing pixels.`;
  document.body.dataset.state = "done";
  zoom();
}

function zoom() {
  const z = Number($("zoom").value);
  $("zoomvalue").textContent = `${z}×`;
  if (!size) return;
  for (const id of ["in-img", "out-svg", "out-diff", "out-dec"]) {
    const img = $(id);
    img.style.width = `${size[0] * z}px`;
    img.style.height = `${size[1] * z}px`;
  }
}

// The four views scroll together, so the same pixels stay side by side when zoomed.
let syncing = false;
function syncScroll(event) {
  if (syncing) return;
  syncing = true;
  const src = event.target;
  for (const view of document.querySelectorAll(".view")) {
    if (view !== src) {
      view.scrollLeft = src.scrollLeft;
      view.scrollTop = src.scrollTop;
    }
  }
  syncing = false;
}

document.addEventListener("DOMContentLoaded", () => {
  const drop = $("drop");
  $("file").addEventListener("change", (e) => chooseFile(e.target.files[0]));
  drop.addEventListener("keydown", (e) => {
    if (e.key === "Enter" || e.key === " ") { e.preventDefault(); $("file").click(); }
  });
  for (const type of ["dragenter", "dragover"]) {
    drop.addEventListener(type, (e) => { e.preventDefault(); drop.classList.add("over"); });
  }
  for (const type of ["dragleave", "drop"]) {
    drop.addEventListener(type, () => drop.classList.remove("over"));
  }
  drop.addEventListener("drop", (e) => {
    e.preventDefault();
    chooseFile(e.dataTransfer.files[0]);
  });
  $("controls").addEventListener("submit", (e) => { e.preventDefault(); convert(); });
  $("zoom").addEventListener("input", zoom);
  // A colour run reads no threshold, inversion, turdsize or alpha mask.
  const colourFields = () => {
    const colour = $("colors").value.trim() !== "";
    for (const id of ["threshold", "invert", "turdsize", "alpha"]) $(id).disabled = colour;
    $("layout").disabled = !colour;
  };
  $("colors").addEventListener("input", colourFields);
  colourFields();
  for (const view of document.querySelectorAll(".view")) {
    view.addEventListener("scroll", syncScroll);
  }
  document.body.dataset.state = "ready";
});
