// Every given figure export opened in headless Chromium with WebGPU (scripts/web-presets.sh):
// whether it draws, the time to its first picture, and how far its canvas is from its poster
// (the native render of the same graph and size). Prints a Markdown table; exits 0 (a report).
// Each canvas is left beside its poster as web.png.
//
// node presets.mjs EXPORT_DIR...
import http from "node:http";
import fs from "node:fs";
import path from "node:path";
import { createRequire } from "node:module";

const require = createRequire(path.resolve(process.env.WEB_TOOLS ?? ".", "node_modules", "x.js"));
const { chromium } = require("playwright-core");
const { PNG } = require("pngjs");

const root = path.resolve(path.dirname(process.argv[2] ?? "."));
const types = { ".html": "text/html", ".js": "text/javascript", ".wasm": "application/wasm",
                ".json": "application/json", ".png": "image/png" };
const server = http.createServer((req, res) => {
  const file = path.resolve(root, "." + decodeURIComponent(new URL(req.url, "http://x").pathname));
  if (!file.startsWith(root) || !fs.existsSync(file) || fs.statSync(file).isDirectory()) {
    res.writeHead(404).end();
    return;
  }
  res.writeHead(200, { "content-type": types[path.extname(file)] ?? "application/octet-stream" });
  fs.createReadStream(file).pipe(res);
});
await new Promise(r => server.listen(0, "127.0.0.1", r));
const base = `http://127.0.0.1:${server.address().port}/`;

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
  args: ["--headless=new", "--enable-unsafe-webgpu", "--enable-features=Vulkan",
         "--use-vulkan=swiftshader", "--use-angle=vulkan", "--no-sandbox", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"],
});
console.log("| graph | in the browser | first picture | against the poster |");
console.log("|---|---|---|---|");
for (const dir of process.argv.slice(2)) {
  const name = path.basename(dir);
  const page = await browser.newPage({ viewport: { width: 1400, height: 1100 }, deviceScaleFactor: 1 });
  let row;
  try {
    await page.goto(`${base}${name}/index.html`);
    await page.waitForFunction(() => ["ready", "error", "no-webgpu"].includes(document.body.dataset.state),
                               null, { timeout: 600_000 });
    const state = await page.evaluate(() => document.body.dataset.state);
    if (state !== "ready") {
      row = [`error: ${(await page.textContent("#status")).replace(/\|/g, "\\|").slice(0, 300)}`, "", ""];
    } else {
      const ms = await page.evaluate(() => window.hatchery.firstPictureMs);
      const shot = PNG.sync.read(await page.locator("#figure").screenshot({ path: path.join(dir, "web.png") }));
      const poster = PNG.sync.read(fs.readFileSync(path.join(dir, "poster.png")));
      let sum = 0, far = 0;
      for (let i = 0; i < shot.data.length; i += 4) {
        let d = 0;
        for (let c = 0; c < 3; c++) d = Math.max(d, Math.abs(shot.data[i + c] - poster.data[i + c]));
        sum += d;
        if (d > 16) far++;
      }
      const n = shot.data.length / 4;
      row = ["draws", `${(ms / 1000).toFixed(1)} s`,
             `mean ${(sum / n).toFixed(2)}/255, ${(100 * far / n).toFixed(2)} % over 16/255`];
    }
  } catch (e) {
    row = [`failed: ${e.message.split("\n")[0]}`, "", ""];
  }
  console.log(`| ${name} | ${row.join(" | ")} |`);
  await page.close();
}
await browser.close();
server.close();
