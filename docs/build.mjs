// Builds the documentation site into docs/dist/ (npm run build:docs; not
// committed): one page for each documentation page of the repository
// (README.md as getting started, docs/*.md: the command line, options,
// outputs, JS API, <vessel-mesher>, web app, method, benchmarks, limits,
// architecture, decisions; docs/links.mjs lists them), the options as tables from the
// core's option table (with their units), and live examples of the element
// meshing the bundled sample (written here by the API's makePhantom) in
// place. The site and the repository's Markdown say the same. Needs the
// wasm and dist/element/ built.
import { cpSync, existsSync, mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';

import { marked } from 'marked';

import { createVesselmesh } from '../wasm/src/node.js';
import { anchorMaker, headingText, PAGES, resolve } from './links.mjs';

const root = new URL('../', import.meta.url);
const out = new URL('docs/dist/', root);
const read = (path) => readFileSync(new URL(path, root), 'utf8');

if (!existsSync(new URL('dist/element/vessel-mesher.js', root))) {
  console.error('build:docs: dist/element/ is missing: run npm run build:web first');
  process.exit(1);
}

const escapeHtml = (s) => String(s).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c]);

/** The page being rendered: its repository path (for its relative links)
 * and the anchors of its headings so far. */
let current = { path: 'README.md', anchor: anchorMaker() };

marked.use({
  renderer: {
    /** Headings with GitHub's anchors, so that links to them work on the
     * site as in the repository. */
    heading({ tokens, depth, text }) {
      return `<h${depth} id="${escapeHtml(current.anchor(headingText(text)))}">${this.parser.parseInline(tokens)}</h${depth}>\n`;
    },
  },
});

/** A link of the current page on the site: to a documentation page, that
 * page of the site (with its fragment); to another file of the repository,
 * null (the site has no copy of it). */
function siteHref(href) {
  const target = resolve(current.path, href);
  if (!target) return href;
  const page = PAGES[target.path];
  if (!page) return null;
  return (target.path === current.path ? '' : page) + (target.fragment ? `#${encodeURIComponent(target.fragment)}` : '');
}

/** The Markdown of the repository page at `path` (or `markdown`, from it)
 * as HTML; links to the repository's other files become plain text. */
function html(path, markdown = read(path)) {
  if (current.path !== path) current = { path, anchor: anchorMaker() };
  return marked
    .parse(markdown)
    .replace(/<a href="([^"]+)">([\s\S]*?)<\/a>/g, (all, href, text) => {
      const to = siteHref(href.replace(/&amp;/g, '&'));
      return to === null ? `<code>${text.replace(/<\/?code>/g, '')}</code>` : `<a href="${escapeHtml(to)}">${text}</a>`;
    });
}

const UNIT = {
  length: "model's unit (mm, cm or m)",
  'fraction of R': 'fraction of the local radius R',
  'local radii': 'local radii R',
  degrees: 'degrees',
};

/** The options of a command as a table: CLI flag, JS key, type, range,
 * default, unit (rows `COMMAND-ID`). */
function optionsTable(table, command) {
  const rows = table
    .filter((o) => o.commands.includes(command))
    .map((o) => {
      const cli = o.faces.includes('cli') ? `<code>--${escapeHtml(o.cli)}${o.metavar ? ` ${escapeHtml(o.metavar)}` : ''}</code>` : '—';
      const js = o.faces.includes('js') ? `<code>${escapeHtml(o.js)}</code>` : '—';
      const def = o.type === 'flag' ? String(o.defaultOn) : o.default || '—';
      return `<tr id="${command}-${escapeHtml(o.id)}"><td>${cli}</td><td>${js}</td><td>${escapeHtml(o.type)}</td>` +
        `<td>${escapeHtml(o.needs || (o.choices.length ? o.choices.join(', ') : ''))}</td><td>${escapeHtml(def)}</td>` +
        `<td class="unit">${escapeHtml(UNIT[o.unit] ?? (o.unit || '—'))}</td><td>${escapeHtml(o.doc)}${o.offDoc ? ` (off: ${escapeHtml(o.offDoc)})` : ''}</td></tr>`;
    });
  return `<table class="options" data-command="${command}"><thead><tr><th>CLI</th><th>JS</th><th>Type</th><th>Values</th><th>Default</th><th>Unit</th><th>What it does</th></tr></thead><tbody>${rows.join('')}</tbody></table>`;
}

const NAV = [
  ['index.html', 'Getting started'],
  ['cli.html', 'Command line'],
  ['options.html', 'Options'],
  ['outputs.html', 'Outputs'],
  ['js-api.html', 'JavaScript API'],
  ['element.html', '<vessel-mesher>'],
  ['family.html', 'Family & report'],
  ['app.html', 'Web app'],
  ['method.html', 'Method'],
  ['benchmarks.html', 'Benchmarks'],
  ['limits.html', 'Limits'],
  ['architecture.html', 'Architecture'],
  ['decisions.html', 'Decisions'],
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

/** A page's Markdown cut before its first `## ` heading (or `at`). */
function split(markdown, at = /^## /m) {
  const i = markdown.search(at);
  if (i < 0) throw new Error(`no ${at} in the page`);
  return [markdown.slice(0, i), markdown.slice(i)];
}

const [intro, rest] = split(read('README.md'));
page(
  'index.html',
  'Getting started',
  `${html('README.md', intro)}
<h2>Try it here</h2>
<p>The bundled sample (a generated bifurcation with segmentation noise) in a
<code>&lt;vessel-mesher&gt;</code> element: press <em>Mesh</em>, then <em>Export</em>.</p>
${LIVE('start')}
${html('README.md', rest)}`,
  { element: true },
);

page('cli.html', 'Command line', html('docs/cli.md'));

// The option list: the generated Markdown block gives way to the same
// table with each option's unit, a table per command.
const [optionsIntro] = split(read('docs/options.md'), /<!-- options:begin/);
page(
  'options.html',
  'Options',
  `${html('docs/options.md', optionsIntro)}
<h2 id="info"><code>vesselmesh info</code> (JS <code>analyze()</code>)</h2>${optionsTable(api.optionTable, 'info')}
<h2 id="mesh"><code>vesselmesh mesh</code> (JS <code>mesh()</code>)</h2>${optionsTable(api.optionTable, 'mesh')}
<h2 id="phantom"><code>vesselmesh phantom</code> (JS <code>makePhantom()</code>)</h2>${optionsTable(api.optionTable, 'phantom')}`,
);

page('outputs.html', 'Outputs', html('docs/outputs.md'));
page('js-api.html', 'JavaScript API', html('docs/javascript.md'));

page(
  'element.html',
  '<vessel-mesher>',
  `${html('docs/element.md')}
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

page(
  'family.html',
  'Mesh families and the methods report',
  `${html('docs/family.md')}
<h2>Live: a family of three and its report</h2>
<p>Press <em>Mesh</em>: the sample is meshed three times, each mesh 1.4 times finer than the last.
<em>Export</em> gives the zip of the three meshes and their table, and <em>Download report</em> gives the methods report.</p>
<vessel-mesher id="family" src="sample.stl" report options='{"perCircumference": 10, "family": 3, "ratio": 1.4}'></vessel-mesher>`,
  { element: true },
);
page('app.html', 'Web app', html('docs/page.md'));
page('method.html', 'Method', html('docs/method.md'));
page('benchmarks.html', 'Benchmarks', html('docs/benchmarks.md'));
page('limits.html', 'Limits', html('docs/limits.md'));
page('architecture.html', 'Architecture', html('docs/ARCHITECTURE.md'));
page('decisions.html', 'Decisions', html('docs/decisions.md'));

const missing = Object.values(PAGES).filter((file) => !NAV.some(([href]) => href === file));
if (missing.length) throw new Error(`pages not in the navigation: ${missing.join(', ')}`);
console.log(`wrote ${new URL('.', out).pathname} (${NAV.length} pages, the element, sample.stl)`);
