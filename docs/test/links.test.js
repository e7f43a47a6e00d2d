// The README is a short front door and the references live in docs/: every
// relative link of README.md and docs/*.md reaches a file of the repository
// (and a heading of it, for a fragment), and every page is on the site.
import assert from 'node:assert/strict';
import { existsSync, readdirSync, readFileSync } from 'node:fs';
import { test } from 'node:test';

import { anchors, links, PAGES, resolve } from '../links.mjs';

const root = new URL('../../', import.meta.url);
const read = (path) => readFileSync(new URL(path, root), 'utf8');
const pages = ['README.md', ...readdirSync(new URL('docs/', root)).filter((f) => f.endsWith('.md')).map((f) => `docs/${f}`)];

test('the README is at most 150 lines', () => {
  const lines = read('README.md').split('\n').length - 1;
  assert.ok(lines <= 150, `README.md has ${lines} lines: move the detail to docs/`);
});

test('every documentation page is a page of the site (docs/links.mjs, PAGES)', () => {
  assert.deepEqual(pages.filter((p) => !PAGES[p]), []);
  for (const p of Object.keys(PAGES)) assert.ok(existsSync(new URL(p, root)), p);
});

test('every relative link of README.md and docs/*.md resolves, fragments to a heading', () => {
  const broken = [];
  for (const page of pages) {
    for (const href of links(read(page))) {
      const target = resolve(page, href);
      if (!target) continue;
      if (!existsSync(new URL(target.path, root))) broken.push(`${page}: ${href} (no ${target.path})`);
      else if (target.fragment && target.path.endsWith('.md') && !anchors(read(target.path)).has(target.fragment)) {
        broken.push(`${page}: ${href} (no heading #${target.fragment} in ${target.path})`);
      }
    }
  }
  assert.deepEqual(broken, []);
});
