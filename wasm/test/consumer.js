// A fresh project that installed this repository's npm package: `npm pack`
// (the built wasm and element must exist: prepack checks), then
// `npm install <tarball>` offline (the package has no dependencies) into a
// temporary directory. Used by package.test.js (Node, tsc, a Vite app) and
// the e2e element spec (a host page serving the installed package).
import { execFileSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

export const REPO = new URL('../../', import.meta.url).pathname;

const npm = (args, cwd) => execFileSync('npm', args, { cwd, encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });

/**
 * Packs the package and installs it into a new project; resolves with
 * { dir, pkg (the installed package's folder), tarball, cleanup() }.
 */
export function installedConsumer() {
  const dir = mkdtempSync(join(tmpdir(), 'vm-consumer-'));
  const packs = join(dir, 'packs');
  mkdirSync(packs);
  npm(['pack', '--silent', '--pack-destination', packs], REPO);
  const tarball = join(packs, readdirSync(packs).find((f) => f.endsWith('.tgz')));
  const project = join(dir, 'project');
  mkdirSync(project);
  writeFileSync(join(project, 'package.json'), JSON.stringify({ name: 'consumer', private: true, type: 'module' }, null, 2));
  npm(['install', tarball, '--offline', '--no-audit', '--no-fund', '--ignore-scripts'], project);
  return {
    dir: project,
    pkg: join(project, 'node_modules', 'vesselmesh'),
    tarball,
    cleanup: () => rmSync(dir, { recursive: true, force: true }),
  };
}

const VITE_APP_HTML = `<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>consumer</title></head>
<body><vessel-mesher id="el" compact style="height: 300px"></vessel-mesher><output id="out"></output>
<script type="module" src="./main.js"></script></body></html>`;

// Meshes the sample three ways: the worker client, the API on the main
// thread and the element; the counts end up in #out's data-result.
const VITE_APP_MAIN = `import { createVesselmesh, VesselmeshClient } from 'vesselmesh';
import 'vesselmesh/element';

const out = document.getElementById('out');
try {
  const client = new VesselmeshClient();
  const sample = await client.makePhantom({ kind: 'bifurcation', voxel: 0.08, noise: 0.3 });
  const viaWorker = await client.mesh(sample.stl, { perCircumference: 10 });
  const api = await createVesselmesh();
  const direct = api.mesh(sample.stl, { perCircumference: 10, surfaceOnly: true });
  const el = document.getElementById('el');
  await el.load(sample.stl);
  const viaElement = await el.mesh({ perCircumference: 10 });
  out.dataset.result = JSON.stringify({
    worker: viaWorker.ok && viaWorker.volume.tets.length / 4,
    direct: direct.ok && direct.surface.triangles.length / 3,
    element: viaElement.ok && viaElement.volume.tets.length / 4,
  });
} catch (e) {
  out.dataset.result = JSON.stringify({ error: String(e) });
}
`;

/** Builds a Vite app in the consumer project that imports 'vesselmesh' and
 * 'vesselmesh/element' (no Vite configuration); returns its dist folder. */
export function buildViteApp(consumer) {
  const app = join(consumer.dir, 'app');
  mkdirSync(app, { recursive: true });
  writeFileSync(join(app, 'index.html'), VITE_APP_HTML);
  writeFileSync(join(app, 'main.js'), VITE_APP_MAIN);
  const vite = join(REPO, 'node_modules/vite/bin/vite.js');
  execFileSync(process.execPath, [vite, 'build', '--logLevel', 'error', '--base', './'], { cwd: app, stdio: 'pipe' });
  return join(app, 'dist');
}
