// Every given figure export opened in headless Chromium with WebGPU (scripts/web-presets.sh):
// whether it draws, the time to its first picture, and how far its canvas is from its poster
// (the native render of the same graph and size). Prints a Markdown table; exits 0 (a report).
// Each canvas is left beside its poster as web.png.
//
// node presets.mjs EXPORT_DIR...
import fs from "node:fs";
import path from "node:path";
import { createRequire } from "node:module";
import { serve, launch } from "./harness.mjs";

const require = createRequire(path.resolve(process.env.WEB_TOOLS ?? ".", "node_modules", "x.js"));
const { chromium } = require("playwright-core");
const { PNG } = require("pngjs");

const root = path.resolve(path.dirname(process.argv[2] ?? "."));
const { server, base } = await serve(root);
const browser = await launch(chromium);
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
