// The browser test of a figure export (scripts/web-test.sh, docs/web.md): serves the folder on
// 127.0.0.1 and opens it in headless Chromium with WebGPU. Each picture the page draws is
// compared with the native render of the same graph, size and settings:
//   1. as opened, against --native;
//   2. after moving the control --control NODE.PARAM=VALUE's slider, against --control-native
//      (rendered natively with --set NODE.PARAM=VALUE);
//   3. after a mouse drag of --drag DX,DY pixels on the canvas, the picture of --drag-port
//      NODE.PORT against --drag-native (rendered with the camera turned as the page turns it:
//      DX·180°/width of azimuth, DY·180°/width of elevation). A port before the labels: the
//      layout starts from its last frame (temporal coherence), so labels placed during a drag
//      differ from a fresh render's. Each change must also change the picture.
// Every shader program of the node library must also compile in the browser, and a browser
// without WebGPU must show the poster.
//
// node check.mjs --dir EXPORT --native A.png --control N.P=V --control-native B.png
//                --drag DX,DY --drag-port NODE.PORT --drag-native C.png --out FOLDER
// node check.mjs --dir EXPORT --native A.png --out FOLDER --opened-only
//                [--drop FILE --drop-native D.png]
// Writes FOLDER/web.png, control.png, dragged.png and web-test.json; exits 1 naming the failed
// check.
import fs from "node:fs";
import path from "node:path";
import { createRequire } from "node:module";
import { serve, launch } from "./harness.mjs";

const require = createRequire(path.resolve(process.env.WEB_TOOLS ?? ".", "node_modules", "x.js"));
const { chromium } = require("playwright-core");
const { PNG } = require("pngjs");

const arg = name => {
  const i = process.argv.indexOf(`--${name}`);
  if (i < 0 || i + 1 >= process.argv.length) throw new Error(`missing --${name}`);
  return process.argv[i + 1];
};
const dir = arg("dir"), native = arg("native"), out = arg("out");
// --opened-only: step 1 alone (a figure with data files: the loaders in the browser).
const full = !process.argv.includes("--opened-only");
const [controlName, controlValue] = full ? arg("control").split("=") : [];
const [dragX, dragY] = full ? arg("drag").split(",").map(Number) : [];

// Tolerance against the native render: Chromium's WebGPU here is SwiftShader (Vulkan), the native
// render lavapipe. The nodes run the same shaders, but the two rasterisers place one-pixel lines
// (silhouettes, hatching strokes, glyph edges) a pixel apart in a few places. So: mean difference
// within 1/255 per channel, and at most 0.5 % of pixels more than 16/255 apart.
const MEAN_LIMIT = 1.0, FAR = 16, FAR_FRACTION_LIMIT = 0.005;
// Each change (a control, a drag) must change more than 2 % of the pixels.
const CHANGED_LIMIT = 0.02;

const { server, base } = await serve(dir);

const read = file => PNG.sync.read(fs.readFileSync(file));
function compare(a, b) {
  if (a.width !== b.width || a.height !== b.height) {
    throw new Error(`sizes differ: ${a.width}×${a.height} and ${b.width}×${b.height}`);
  }
  let sum = 0, far = 0, changed = 0, worst = { d: -1 };
  for (let i = 0; i < a.data.length; i += 4) {
    let d = 0;
    for (let c = 0; c < 3; c++) d = Math.max(d, Math.abs(a.data[i + c] - b.data[i + c]));
    sum += d;
    if (d > FAR) far++;
    if (d > 0) changed++;
    if (d > worst.d) {
      const p = i / 4;
      worst = { d, x: p % a.width, y: Math.floor(p / a.width) };
    }
  }
  const n = a.data.length / 4;
  return { mean: sum / n, farFraction: far / n, changedFraction: changed / n, worst };
}

const results = { wasmBytes: fs.statSync(path.join(dir, "hatchery_web_bg.wasm")).size };
const fail = message => {
  results.failure = message;
  fs.writeFileSync(path.join(out, "web-test.json"), JSON.stringify(results, null, 2));
  console.error(`web-test: FAILED: ${message} (pictures and web-test.json in ${out})`);
  process.exitCode = 1;
};

const browser = await launch(chromium);
try {
  const page = await browser.newPage({ viewport: { width: 1400, height: 1100 }, deviceScaleFactor: 1 });
  const log = [];
  page.on("console", m => log.push(`${m.type()}: ${m.text()}`));
  page.on("pageerror", e => log.push(`page error: ${e.message}`));
  const ready = async frames => {
    await page.waitForFunction(
      n => document.body.dataset.state === "error" || document.body.dataset.state === "no-webgpu" ||
           (window.hatchery && window.hatchery.frames >= n && document.body.dataset.state === "ready"),
      frames, { timeout: 300_000 });
    const state = await page.evaluate(() => document.body.dataset.state);
    if (state !== "ready") {
      throw new Error(`the page says ${state}: ${await page.textContent("#status")}\n${log.join("\n")}`);
    }
  };
  const shot = async name => {
    const file = path.join(out, name);
    await page.locator("#figure").screenshot({ path: file });
    return read(file);
  };

  const opened = Date.now();
  await page.goto(base + "index.html");
  await ready(1);
  results.firstPictureMs = await page.evaluate(() => window.hatchery.firstPictureMs);
  results.pageLoadToPictureMs = Date.now() - opened;
  results.status = await page.textContent("#status");

  const against = (name, picture, file) => {
    const d = compare(picture, read(file));
    results[name] = d;
    console.log(`web-test: ${name}: mean ${d.mean.toFixed(3)}/255, ` +
                `${(100 * d.farFraction).toFixed(3)} % of pixels over ${FAR}/255, ` +
                `worst ${d.worst.d}/255 at (${d.worst.x}, ${d.worst.y}) against ${file}`);
    if (d.mean > MEAN_LIMIT || d.farFraction > FAR_FRACTION_LIMIT) {
      fail(`${name}: the canvas differs from the native render beyond the tolerance ` +
           `(mean ≤ ${MEAN_LIMIT}/255, ≤ ${100 * FAR_FRACTION_LIMIT} % over ${FAR}/255)`);
    }
  };
  const changedFrom = (name, picture, before) => {
    const d = compare(picture, before);
    console.log(`web-test: ${name} changed ${(100 * d.changedFraction).toFixed(1)} % of the pixels`);
    if (d.changedFraction < CHANGED_LIMIT) fail(`${name} did not change the picture`);
  };
  const settled = async frames => {
    await ready(frames);
    await page.waitForFunction(() => !window.hatchery.busy, null, { timeout: 300_000 });
  };

  const web = await shot("web.png");
  against("as opened", web, native);

  // --drop FILE: the file dropped on the figure, as a reader drops their own data, against
  // --drop-native (rendered with --input NAME=FILE).
  const dropIndex = process.argv.indexOf("--drop");
  if (dropIndex > 0) {
    const file = process.argv[dropIndex + 1];
    const frames = await page.evaluate(() => window.hatchery.frames);
    await page.evaluate(({ name, b64 }) => {
      const bytes = Uint8Array.from(atob(b64), c => c.charCodeAt(0));
      const data = new DataTransfer();
      data.items.add(new File([bytes], name));
      document.getElementById("view").dispatchEvent(
        new DragEvent("drop", { dataTransfer: data, bubbles: true, cancelable: true }));
    }, { name: path.basename(file), b64: fs.readFileSync(file).toString("base64") });
    await settled(frames + 1);
    const dropped = await shot("dropped.png");
    changedFrom(`dropping ${path.basename(file)}`, dropped, web);
    against(`after dropping ${path.basename(file)}`, dropped, arg("drop-native"));
  }

  // Steps 2–4: a nested function so that --opened-only can leave them out.
  async function interact() {
    // Every shader program, compiled by the browser's WGSL compiler (Tint), stricter than naga in
    // places: the figure above uses only some of them. Programs with 64-bit integers run only on
    // adapters that have them (DepthLayers' k-buffer; WebGPU has none) and are left out.
    const compiled = await page.evaluate(async () => {
      const build = await import("./hatchery_web.js");
      const programs = JSON.parse(build.shader_programs());
      const device = await (await navigator.gpu.requestAdapter()).requestDevice();
      const failed = [], skipped = [];
      for (const { name, source } of programs) {
        if (/\b[ui]64\b/.test(source)) { skipped.push(name); continue; }
        const info = await device.createShaderModule({ code: source, label: name }).getCompilationInfo();
        for (const m of info.messages.filter(m => m.type === "error")) {
          const line = source.split("\n")[m.lineNum - 1] ?? "";
          failed.push(`${name}:${m.lineNum}:${m.linePos}: ${m.message} | ${line.trim()}`);
        }
      }
      return { count: programs.length, failed, skipped };
    });
    results.shaders = compiled;
    console.log(`web-test: ${compiled.count - compiled.skipped.length} shader programs compiled by ` +
                `the browser (${compiled.skipped.join(", ")} left out: 64-bit integers)`);
    if (compiled.failed.length > 0) {
      fail(`the browser's WGSL compiler refuses ${compiled.failed.length} shader(s):\n` +
           compiled.failed.join("\n"));
    }

    // The control's slider, as a reader moves it.
    const [node, param] = controlName.split(".");
    const slider = page.locator(`#control-${node}-${param}`);
    if (await slider.count() === 0) {
      throw new Error(`the page shows no control for ${controlName}`);
    }
    let frames = await page.evaluate(() => window.hatchery.frames);
    await slider.evaluate((e, v) => { e.value = v; e.dispatchEvent(new Event("input")); }, controlValue);
    await settled(frames + 1);
    const controlled = await shot("control.png");
    changedFrom(`the control ${controlName}`, controlled, web);
    against(`after ${controlName}=${controlValue}`, controlled, arg("control-native"));

    // A drag across the canvas with the mouse, as a reader turns the figure.
    const box = await page.locator("#figure").boundingBox();
    const [cx, cy] = [box.x + box.width / 2, box.y + box.height / 2];
    frames = await page.evaluate(() => window.hatchery.frames);
    await page.mouse.move(cx, cy);
    await page.mouse.down();
    const steps = 8;
    for (let i = 1; i <= steps; i++) await page.mouse.move(cx + dragX * i / steps, cy + dragY * i / steps);
    await page.mouse.up();
    await settled(frames + 1);
    const dragged = await shot("dragged.png");
    changedFrom("the drag", dragged, controlled);
    const [shownNode, shownPort] = arg("drag-port").split(".");
    frames = await page.evaluate(() => window.hatchery.frames);
    await page.evaluate(([n, p]) => { window.hatchery.figure.show(n, p); window.hatchery.changed(); },
                        [shownNode, shownPort]);
    await settled(frames + 1);
    const turned = await shot("dragged-port.png");
    against(`${shownNode}.${shownPort} after a drag of (${dragX}, ${dragY})`, turned,
            arg("drag-native"));

    // The wheel: one mouse notch (100 px) zooms in; a trackpad's twenty small events of 5 px
    // zoom as far as that notch, not twenty notches.
    const wheel = async deltas => {
      frames = await page.evaluate(() => window.hatchery.frames);
      await page.mouse.move(cx, cy);
      for (const d of deltas) await page.mouse.wheel(0, d);
      await settled(frames + 1);
    };
    await wheel([-100]);
    const notch = await shot("wheel-notch.png");
    changedFrom("a wheel notch", notch, turned);
    await wheel([100]);
    await wheel(Array(20).fill(-5));
    against("twenty 5 px wheel events against one 100 px notch", await shot("wheel-pad.png"),
            path.join(out, "wheel-notch.png"));

    // Without WebGPU, or with WebGPU but no adapter, the page keeps the poster and says why.
    const setups = {
      withoutWebGpu: () =>
        Object.defineProperty(Navigator.prototype, "gpu", { get: () => undefined }),
      withoutAdapter: () => { GPU.prototype.requestAdapter = async () => null; },
    };
    for (const [name, setup] of Object.entries(setups)) {
      const plain = await browser.newPage();
      await plain.addInitScript(setup);
      await plain.goto(base + "index.html");
      await plain.waitForFunction(() => document.body.dataset.state, null, { timeout: 60_000 });
      const fallback = await plain.evaluate(() => ({
        state: document.body.dataset.state,
        status: document.getElementById("status").textContent,
        poster: document.getElementById("poster").complete &&
                document.getElementById("poster").naturalWidth > 0 &&
                getComputedStyle(document.getElementById("poster")).display !== "none",
      }));
      results[name] = fallback;
      if (fallback.state !== "no-webgpu" || !fallback.poster) {
        fail(`${name}: the page should show the poster: ${JSON.stringify(fallback)}`);
      }
      await plain.close();
    }

    // Embedded with docs/web.md's snippet: the iframe, written too short, grows to the page's
    // height (the status line below the controls in view, nothing to scroll).
    const host = await browser.newPage({ viewport: { width: 1400, height: 1100 } });
    await host.goto(base + "figure.json");  // the figure's origin, to look inside the iframe
    await host.setContent(`<iframe src="${base}index.html" width="600" height="200"
      style="border: 0"></iframe>
      <script>
      addEventListener("message", e => {
        if (e.data?.hatchery !== "size") return;
        for (const f of document.querySelectorAll("iframe"))
          if (f.contentWindow === e.source) f.height = e.data.height;
      });
      </script>`);
    await host.waitForFunction(
      () => document.querySelector("iframe").contentDocument?.body?.dataset.state === "ready",
      null, { timeout: 300_000 });
    await host.waitForTimeout(200);
    const embed = await host.evaluate(() => {
      const f = document.querySelector("iframe"), d = f.contentDocument;
      return { iframe: f.clientHeight, needs: d.documentElement.scrollHeight,
               status: Math.ceil(d.getElementById("status").getBoundingClientRect().bottom) };
    });
    results.embedded = embed;
    if (embed.iframe < embed.needs || embed.status > embed.iframe || embed.iframe <= 200) {
      fail(`the embedded page should size its iframe: ${JSON.stringify(embed)}`);
    }
    await host.close();

    // A ?show= naming no output of the graph: the figure as it is, and a line saying why.
    const shown = await browser.newPage({ viewport: { width: 1400, height: 1100 } });
    await shown.goto(base + "index.html?show=hatching.no_such_port");
    await shown.waitForFunction(
      () => ["ready", "error"].includes(document.body.dataset.state), null, { timeout: 300_000 });
    const showStatus = await shown.evaluate(
      () => [document.body.dataset.state, document.getElementById("status").textContent]);
    results.badShow = showStatus;
    if (showStatus[0] !== "ready" || !showStatus[1].includes("?show=hatching.no_such_port") ||
        !showStatus[1].includes("no output port `no_such_port`")) {
      fail(`?show= of a missing port should say so and show the figure: ${showStatus}`);
    }
    await shown.close();
  }
  if (full) await interact();
} catch (e) {
  fail(e.message);
} finally {
  await browser.close();
  server.close();
}
if (!results.failure) {
  fs.writeFileSync(path.join(out, "web-test.json"), JSON.stringify(results, null, 2));
  console.log(`web-test: passed (first picture ${results.firstPictureMs.toFixed(0)} ms after the page ` +
              `started, wasm ${(results.wasmBytes / 1e6).toFixed(1)} MB)`);
}
