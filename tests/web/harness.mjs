// What the browser checks share (check.mjs, presets.mjs): a static server for a folder and
// headless Chromium with WebGPU.
import http from "node:http";
import fs from "node:fs";
import path from "node:path";

const types = { ".html": "text/html", ".js": "text/javascript", ".wasm": "application/wasm",
                ".json": "application/json", ".png": "image/png" };

// Serves `dir` on 127.0.0.1 (a free port; "/" is index.html). Returns the server and its base URL.
export async function serve(dir) {
  const root = path.resolve(dir);
  const server = http.createServer((req, res) => {
    const url = decodeURIComponent(new URL(req.url, "http://x").pathname);
    const file = path.resolve(root, "." + (url === "/" ? "/index.html" : url));
    if (!file.startsWith(root) || !fs.existsSync(file) || fs.statSync(file).isDirectory()) {
      res.writeHead(404).end();
      return;
    }
    res.writeHead(200, { "content-type": types[path.extname(file)] ?? "application/octet-stream" });
    fs.createReadStream(file).pipe(res);
  });
  await new Promise(r => server.listen(0, "127.0.0.1", r));
  return { server, base: `http://127.0.0.1:${server.address().port}/` };
}

// Headless Chromium with WebGPU on SwiftShader's Vulkan, for WebGPU and for compositing: with
// Chromium's default (GL) compositor the WebGPU canvas reaches the page but not screenshots.
export function launch(chromium) {
  return chromium.launch({
    executablePath: process.env.CHROMIUM ?? "/usr/bin/chromium",
    args: ["--headless=new", "--enable-unsafe-webgpu", "--enable-features=Vulkan",
           "--use-vulkan=swiftshader", "--use-angle=vulkan", "--no-sandbox", "--no-first-run",
           "--disable-background-networking", "--disable-component-update", "--disable-sync"],
  });
}
