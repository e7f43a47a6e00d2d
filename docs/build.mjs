// Builds the documentation site into docs/dist/ (npm run build:docs; not
// committed): getting started, the CLI and JS API references (the options
// from the core's option table, with their units), the <vessel-mesher>
// element's contract, the method (docs/site/method.md) and live examples
// of the element meshing the bundled sample (written here by the API's
// makePhantom) in place. Text comes from README.md's sections, so the site
// and the README say the same. Needs the wasm and dist/element/ built.
import { cpSync, existsSync, mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';

import { marked } from 'marked';

import { createVesselmesh } from '../wasm/src/node.js';

const root = new URL('../', import.meta.url);
const out = new URL('docs/dist/', root);
const read = (path) => readFileSync(new URL(path, root), 'utf8');

if (!existsSync(new URL('dist/element/vessel-mesher.js', root))) {
  console.error('build:docs: dist/element/ is missing: run npm run build:web first');
  process.exit(1);
}

/** README.md's `## ` sections by title (the text under each heading). */
function sections(markdown) {
  const map = new Map();
  let title = '';
  for (const line of markdown.split('\n')) {
    const m = /^## (.+)$/.exec(line);
    if (m) {
      title = m[1].trim();
      map.set(title, '');
    } else map.set(title, (map.get(title) ?? '') + line + '\n');
  }
  return map;
}

const escapeHtml = (s) => String(s).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c]);

/** Markdown to HTML, with links to the repository's files made plain text
 * (the site has no copy of them) except the pages it has. */
function html(markdown) {
  const pages = { 'docs/ARCHITECTURE.md': 'architecture.html' };
  return marked
    .parse(markdown.replace(/<!--[\s\S]*?-->/g, ''))
    .replace(/<a href="([^"]+)">([\s\S]*?)<\/a>/g, (all, href, text) => {
      if (pages[href]) return `<a href="${pages[href]}">${text}</a>`;
      return /^(https?:|#)/.test(href) ? all : `<code>${text.replace(/<\/?code>/g, '')}</code>`;
    });
}

const UNIT = {
  length: "model's unit (mm, cm or m)",
  'fraction of R': 'fraction of the local radius R',
  'local radii': 'local radii R',
  degrees: 'degrees',
};

/** The options of a command as a table: key, type, range, default, unit. */
function optionsTable(table, command, keyOf) {
  const rows = table
    .filter((o) => o.commands.includes(command) && o.faces.includes(keyOf === 'js' ? 'js' : 'cli'))
    .map((o) => {
      const key = keyOf === 'js' ? o.js : `--${o.cli}${o.metavar ? ` ${o.metavar}` : ''}`;
      const def = o.type === 'flag' ? String(o.defaultOn) : o.default || '—';
      return `<tr id="${command}-${keyOf}-${escapeHtml(o.id)}"><td><code>${escapeHtml(key)}</code></td><td>${escapeHtml(o.type)}</td>` +
        `<td>${escapeHtml(o.needs || (o.choices.length ? o.choices.join(', ') : ''))}</td><td>${escapeHtml(def)}</td>` +
        `<td class="unit">${escapeHtml(UNIT[o.unit] ?? (o.unit || '—'))}</td><td>${escapeHtml(o.doc)}${o.offDoc ? ` (off: ${escapeHtml(o.offDoc)})` : ''}</td></tr>`;
    });
  return `<table class="options" data-command="${command}"><thead><tr><th>Option</th><th>Type</th><th>Values</th><th>Default</th><th>Unit</th><th>What it does</th></tr></thead><tbody>${rows.join('')}</tbody></table>`;
}

const NAV = [
  ['index.html', 'Getting started'],
  ['cli.html', 'Command line'],
  ['js-api.html', 'JavaScript API'],
  ['element.html', '<vessel-mesher>'],
  ['method.html', 'Method'],
  ['architecture.html', 'Architecture'],
];

const CSS = `
body { margin: 0; font: 16px/1.55 system-ui, sans-serif; color: #17212b; background: #f4f6f8; }
header { background: #17212b; color: #fff; padding: 0.6rem 1.2rem; display: flex; flex-wrap: wrap; gap: 0.4rem 1.2rem; align-items: baseline; }
header strong { font-size: 1.2rem; }
header nav { display: flex; flex-wrap: wrap; gap: 0.2rem 1rem; }
header a { color: #cfe0f5; text-decoration: none; }
header a[aria-current] { color: #fff; text-decoration: underline; }
main { max-width: 62rem; margin: 0 auto; padding: 1rem 1.2rem 3rem; background: #fff; }
pre { background: #eef2f6; padding: 0.7rem; overflow-x: auto; font-size: 0.85rem; }
code { font-size: 0.9em; }
table { border-collapse: collapse; font-size: 0.85rem; display: block; overflow-x: auto; }
th, td { border: 1px solid #d5dce3; padding: 0.25rem 0.45rem; vertical-align: top; text-align: left; }
vessel-mesher { margin: 1rem 0; }
.log { font: 0.8rem/1.4 monospace; background: #eef2f6; padding: 0.5rem; max-height: 10rem; overflow-y: auto; white-space: pre-wrap; }
`;

function page(file, title, body, { element = false } = {}) {
  const nav = NAV.map(([href, label]) => `<a href="${href}"${href === file ? ' aria-current="page"' : ''}>${escapeHtml(label)}</a>`).join('');
  const script = element ? '<script type="module" src="element/vessel-mesher.js"></script>' : '';
  writeFileSync(
    new URL(file, out),
    `<!doctype html>
<html lang="en"><head><meta charset="utf-8"><meta name="viewport" content="width=device-width, initial-scale=1">
<title>${escapeHtml(title)} — vesselmesh</title><link rel="icon" href="data:,"><style>${CSS}</style>${script}</head>
<body><header><strong>vesselmesh</strong><nav aria-label="Documentation">${nav.replace(/<\/a><a/g, '</a> <a')}</nav></header>
<main>${body}</main></body></html>
`,
  );
}

const LIVE = (id, attrs = '') =>
  `<vessel-mesher id="${id}" src="sample.stl" options='{"perCircumference": 12}'${attrs}></vessel-mesher>`;

rmSync(out, { recursive: true, force: true });
mkdirSync(out, { recursive: true });
cpSync(new URL('dist/element/', root), new URL('element/', out), { recursive: true });

const api = await createVesselmesh();
const sample = api.makePhantom({ kind: 'bifurcation', voxel: 0.08, noise: 0.3 });
if (!sample.ok) throw new Error(sample.error);
writeFileSync(new URL('sample.stl', out), sample.stl);

const readme = sections(read('README.md'));
const s = (title) => {
  const text = readme.get(title);
  if (text === undefined) throw new Error(`README.md has no section '${title}'`);
  return text;
};
const intro = readme.get('');
const table = api.optionTable;

page(
  'index.html',
  'Getting started',
  `${html(intro.replace(/^# .*\n/, ''))}
<h2>Try it here</h2>
<p>The bundled sample (a generated bifurcation with segmentation noise) in a
<code>&lt;vessel-mesher&gt;</code> element: press <em>Mesh</em>, then <em>Export</em>.</p>
${LIVE('start')}
<h2>Install and run</h2>${html(s('The two commands (Debian 12, as root or with sudo)'))}
<h2>npm package</h2>${html(s('npm package'))}`,
  { element: true },
);

page(
  'cli.html',
  'Command line',
  `<h1>Command line</h1>${html(s('Command line'))}
<h2>Options</h2><p>Every option, from the core's option table (the CLI, the
JS API and this page share it). Lengths are in the model's unit, R is the
local vessel radius, K an opening number as the analysis lists them.</p>
<h3><code>vesselmesh info</code></h3>${optionsTable(table, 'info', 'cli')}
<h3><code>vesselmesh mesh</code></h3>${optionsTable(table, 'mesh', 'cli')}
<h3><code>vesselmesh phantom</code></h3>${optionsTable(table, 'phantom', 'cli')}
<h2>Output groups</h2>${html(s('Output groups'))}`,
);

page(
  'js-api.html',
  'JavaScript API',
  `<h1>JavaScript API</h1>${html(s('JavaScript API (WebAssembly)'))}
<h2>npm package</h2>${html(s('npm package'))}
<h2>Options</h2><p>By their JS keys, with JS types; the same table as the CLI's.</p>
<h3><code>analyze()</code></h3>${optionsTable(table, 'info', 'js')}
<h3><code>mesh()</code></h3>${optionsTable(table, 'mesh', 'js')}
<h3><code>makePhantom()</code></h3>${optionsTable(table, 'phantom', 'js')}`,
);

page(
  'element.html',
  '<vessel-mesher>',
  `<h1>&lt;vessel-mesher&gt;</h1>${html(s('Embedding: `<vessel-mesher>`'))}
<h2>Live: the full element</h2>${LIVE('full')}
<h2>Live: compact, driven from a script</h2>
<p>This one is meshed by <code>mesh()</code> once it has analyzed the sample; its events are logged below.</p>
${LIVE('scripted', ' compact')}
<div class="log" id="log" aria-live="polite"></div>
<script type="module">
  const el = document.getElementById('scripted');
  const log = document.getElementById('log');
  const say = (text) => { log.textContent += text + '\\n'; log.scrollTop = log.scrollHeight; };
  let last = -1;
  el.addEventListener('vm-analyzed', (e) => {
    say('vm-analyzed: ' + e.detail.openings.length + ' openings');
    el.mesh({ perCircumference: 10 });
  });
  el.addEventListener('vm-progress', (e) => {
    const pct = Math.floor(e.detail.fraction * 10) * 10;
    if (pct !== last) say('vm-progress: ' + e.detail.stage + ' ' + pct + '%');
    last = pct;
  });
  el.addEventListener('vm-meshed', (e) => {
    say('vm-meshed: ' + (e.detail.volume.tets.length / 4) + ' tetrahedra');
    document.body.dataset.scripted = 'meshed';
  });
  el.addEventListener('vm-error', (e) => say('vm-error: ' + e.detail.message));
</script>`,
  { element: true },
);

page('method.html', 'Method', html(read('docs/site/method.md')) + `<h2>Limits</h2>${html(s('Limits'))}`);
page('architecture.html', 'Architecture', html(read('docs/ARCHITECTURE.md')));

console.log(`wrote ${new URL('.', out).pathname} (${NAV.length} pages, the element, sample.stl)`);
