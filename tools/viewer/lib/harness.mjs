// Node side of the viewer: a local static server for the page, its ES modules (three.js and
// ez-tree straight from node_modules) and the GLB files, and headless Chromium driven by
// playwright-core.
import http from 'node:http';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

let chromium;
try {
  ({ chromium } = await import('playwright-core'));
} catch {
  process.stderr.write('tools/viewer: playwright-core is not installed; run `bash scripts/compare-trees.sh` once, or `npm ci` in tools/viewer\n');
  process.exit(1);
}

export const VIEWER_DIR = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');

// The version of an npm package installed in the viewer.
export const pkgVersion = (name) => JSON.parse(fs.readFileSync(path.join(VIEWER_DIR, 'node_modules', name, 'package.json'), 'utf8')).version;

// The fields every run report starts with: when, what made the trees, and what drew them.
export const reportHeader = (opt, viewer) => ({
  generated: new Date().toISOString(),
  sylva_binary: opt.binary || null,
  preset_dir: opt.presetDir,
  ez_tree_version: pkgVersion('@dgreenheck/ez-tree'),
  three_version: pkgVersion('three'),
  renderer: viewer.webgl,
});

const TYPES = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.json': 'application/json',
  '.glb': 'model/gltf-binary',
  '.gltf': 'model/gltf+json',
  '.bin': 'application/octet-stream',
  '.png': 'image/png',
  '.jpg': 'image/jpeg',
  '.jpeg': 'image/jpeg',
  '.map': 'application/json',
};

// Serves VIEWER_DIR (page/, lib/, node_modules/) and the given files as /file/0, /file/1, ...
// Nothing outside those is reachable.
export function startServer(files = []) {
  const served = files.map((f) => path.resolve(f));
  const server = http.createServer((req, res) => {
    const url = new URL(req.url, 'http://localhost');
    const p = decodeURIComponent(url.pathname);
    let file = null;
    const m = /^\/file\/(\d+)(\.[a-z]+)?$/.exec(p);
    if (m) {
      file = served[Number(m[1])] || null;
    } else {
      const rel = p === '/' ? 'page/index.html' : p.replace(/^\/+/, '');
      const abs = path.resolve(VIEWER_DIR, rel);
      const allowed = ['page', 'lib', 'node_modules'].some((d) => abs.startsWith(path.join(VIEWER_DIR, d) + path.sep));
      if (allowed) file = abs;
    }
    if (!file || !fs.existsSync(file) || !fs.statSync(file).isFile()) {
      res.writeHead(404, { 'content-type': 'text/plain' });
      res.end(`not found: ${p}\n`);
      return;
    }
    res.writeHead(200, {
      'content-length': fs.statSync(file).size,
      'content-type': TYPES[path.extname(file).toLowerCase()] || 'application/octet-stream',
      'cache-control': 'no-store',
    });
    fs.createReadStream(file).pipe(res);
  });
  return new Promise((resolve, reject) => {
    server.on('error', reject);
    server.listen(0, '127.0.0.1', () => {
      const { port } = server.address();
      resolve({
        origin: `http://127.0.0.1:${port}`,
        fileUrl: (i) => `/file/${i}${path.extname(served[i] || '')}`,
        close: () => new Promise((r) => server.close(r)),
      });
    });
  });
}

export const CHROMIUM_ARGS = [
  '--headless',
  '--no-sandbox',
  '--disable-gpu',
  '--disable-quic',
  '--no-first-run',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  // WebGL without a GPU: ANGLE on SwiftShader (software Vulkan), which Chromium only allows
  // for WebGL when told it is acceptable.
  '--use-gl=angle',
  '--use-angle=swiftshader',
  '--enable-unsafe-swiftshader',
  '--ignore-gpu-blocklist',
];

export function chromiumPath() {
  return process.env.SYLVA_CHROMIUM || '/usr/bin/chromium';
}

// Launches Chromium and a server for `files`, and returns helpers. Each show() of a new tree
// runs in a fresh page (a crashed page or browser is replaced), so one huge tree cannot starve
// the next. Every request the pages make is recorded; any that leaves the local server is
// refused.
export async function openViewer(files = [], { size = 768, verbose = false } = {}) {
  const server = await startServer(files);
  const requests = [];
  const errors = [];
  let browser = null;
  let page = null;
  let pageKey = null; // the spec the current page holds

  async function newPage() {
    if (page) await page.close().catch(() => {});
    page = null;
    pageKey = null;
    if (!browser || !browser.isConnected()) {
      if (browser) await browser.close().catch(() => {});
      browser = await chromium.launch({ executablePath: chromiumPath(), args: CHROMIUM_ARGS, headless: true });
    }
    const p = await browser.newPage({ viewport: { width: size, height: size }, deviceScaleFactor: 1 });
    await p.route('**/*', (route) => {
      const u = route.request().url();
      if (u.startsWith(server.origin) || u.startsWith('data:') || u.startsWith('blob:')) return route.continue();
      errors.push(`refused request outside the local server: ${u}`);
      return route.abort();
    });
    p.on('request', (r) => {
      const u = r.url();
      if (!u.startsWith('data:') && !u.startsWith('blob:')) requests.push(u.replace(server.origin, ''));
    });
    // three's FileLoader reads a fetch body through its own stream wrapper; Chromium then
    // reports the finished request as ERR_ABORTED although every byte arrived. Only a request
    // that got no successful response counts as failed.
    const answered = new Set();
    p.on('response', (r) => {
      if (r.status() >= 400) errors.push(`HTTP ${r.status()}: ${r.url()}`);
      else answered.add(r.url());
    });
    p.on('requestfailed', (r) => {
      const why = r.failure()?.errorText || '';
      if (why.includes('ERR_ABORTED') && answered.has(r.url())) return;
      errors.push(`request failed: ${r.url()} ${why}`);
    });
    p.on('pageerror', (e) => errors.push(`page error: ${e.message}`));
    p.on('console', (m) => {
      if (verbose || m.type() === 'error') process.stderr.write(`[page ${m.type()}] ${m.text()}\n`);
    });
    await p.goto(`${server.origin}/`);
    try {
      await p.waitForFunction(() => window.viewer && window.viewer.ready, null, { timeout: 60000 });
    } catch (e) {
      throw new Error(`the viewer page did not start: ${errors.join('; ') || e.message}`);
    }
    page = p;
  }

  try {
    await newPage();
  } catch (e) {
    if (browser) await browser.close().catch(() => {});
    await server.close();
    throw e;
  }
  const webgl = await page.evaluate(() => {
    const gl = document.createElement('canvas').getContext('webgl2');
    if (!gl) return null;
    const ext = gl.getExtension('WEBGL_debug_renderer_info');
    return ext ? gl.getParameter(ext.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER);
  });
  return {
    requests,
    errors,
    webgl,
    fileUrl: server.fileUrl,
    // spec: { kind: 'glb', file: index } or { kind: 'ez', preset: name }. The same spec as the
    // last call reuses the loaded tree (another view of it); a different one gets a fresh page.
    async show(spec, opts) {
      const s = spec.kind === 'glb' ? { kind: 'glb', url: server.fileUrl(spec.file) } : spec;
      const key = JSON.stringify(s);
      if (pageKey !== null && pageKey !== key) await newPage();
      else if (!page || page.isClosed() || !browser.isConnected()) await newPage();
      pageKey = key;
      try {
        return await page.evaluate(([s2, o]) => window.viewer.show(s2, o), [s, opts]);
      } catch (e) {
        pageKey = null;
        if (page.isClosed() || !browser.isConnected()) page = null;
        throw e;
      }
    },
    async close() {
      if (browser) await browser.close().catch(() => {});
      await server.close();
    },
  };
}

export function writeDataURL(dataURL, file) {
  fs.mkdirSync(path.dirname(path.resolve(file)), { recursive: true });
  fs.writeFileSync(file, Buffer.from(dataURL.replace(/^data:image\/png;base64,/, ''), 'base64'));
}
