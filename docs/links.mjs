// The documentation's Markdown as GitHub (and npm) show it: heading anchors
// by GitHub's rule and the links of a page, for the site builder
// (docs/build.mjs) and the link check (docs/test/links.test.js).
import { marked } from 'marked';

/** The documentation pages, by their path in the repository, and the page
 * of the site (docs/dist/) each becomes. */
export const PAGES = {
  'README.md': 'index.html',
  'docs/cli.md': 'cli.html',
  'docs/options.md': 'options.html',
  'docs/outputs.md': 'outputs.html',
  'docs/javascript.md': 'js-api.html',
  'docs/element.md': 'element.html',
  'docs/family.md': 'family.html',
  'docs/page.md': 'app.html',
  'docs/method.md': 'method.html',
  'docs/benchmarks.md': 'benchmarks.html',
  'docs/limits.md': 'limits.html',
  'docs/ARCHITECTURE.md': 'architecture.html',
  'docs/decisions.md': 'decisions.html',
};

const ENTITIES = { '&lt;': '<', '&gt;': '>', '&amp;': '&', '&quot;': '"', '&#39;': "'" };

/** A heading's text as a reader sees it (Markdown inline syntax and tags
 * removed). */
export function headingText(markdown) {
  return marked
    .parseInline(markdown)
    .replace(/<[^>]*>/g, '')
    .replace(/&(lt|gt|amp|quot|#39);/g, (e) => ENTITIES[e]);
}

/** GitHub's anchor of a heading's text: lower case, punctuation dropped,
 * each space a hyphen. */
export const slug = (text) =>
  text
    .trim()
    .toLowerCase()
    .replace(/[^\p{L}\p{M}\p{N}\p{Pc} -]/gu, '')
    .replace(/ /g, '-');

/** A function giving each heading of one page its anchor, the second of
 * the same text with -1 appended, and so on (as GitHub does). */
export function anchorMaker() {
  const seen = new Map();
  return (text) => {
    const base = slug(text);
    const n = seen.get(base) ?? 0;
    seen.set(base, n + 1);
    return n === 0 ? base : `${base}-${n}`;
  };
}

/** Every anchor of a Markdown page. */
export function anchors(markdown) {
  const make = anchorMaker();
  const ids = new Set();
  marked.walkTokens(marked.lexer(markdown), (token) => {
    if (token.type === 'heading') ids.add(make(headingText(token.text)));
  });
  return ids;
}

/** Every link target of a Markdown page (not those in code). */
export function links(markdown) {
  const hrefs = [];
  marked.walkTokens(marked.lexer(markdown), (token) => {
    if (token.type === 'link' || token.type === 'image') hrefs.push(token.href);
    if (token.type === 'html') for (const m of token.raw.matchAll(/\bhref="([^"]+)"/g)) hrefs.push(m[1]);
  });
  return hrefs;
}

/** What a link of the page at `from` (a repository path) points to: the
 * repository path and the fragment (a fragment alone: `from` itself); null
 * for an absolute URL. */
export function resolve(from, href) {
  if (/^[a-z][a-z0-9+.-]*:/i.test(href)) return null;
  const url = new URL(href, `file:///repo/${from}`);
  return { path: decodeURIComponent(url.pathname.replace(/^\/repo\//, '')), fragment: decodeURIComponent(url.hash.slice(1)) };
}
