// Node tests of cross-origin isolation on a static host: the headers the
// service worker adds (web/src/isolation-headers.js) and when the page
// reloads once through it (web/src/isolation.js), with a fake browser.
import assert from 'node:assert/strict';
import { describe, test } from 'node:test';

import { withIsolationHeaders } from '../src/isolation-headers.js';
import { RELOADED_KEY, SERVICE_WORKER, startIsolated } from '../src/isolation.js';

const COOP = 'cross-origin-opener-policy';
const COEP = 'cross-origin-embedder-policy';
const CORP = 'cross-origin-resource-policy';

describe('the service worker headers', () => {
  const page = { mode: 'navigate' };
  const script = { mode: 'cors' };

  test('a navigation gets COOP and COEP, a subresource CORP too; the rest is kept', async () => {
    const original = new Response('<p>hi</p>', { status: 200, statusText: 'OK', headers: { 'content-type': 'text/html', etag: '"1"' } });
    const r = withIsolationHeaders(original, page);
    assert.equal(r.headers.get(COOP), 'same-origin');
    assert.equal(r.headers.get(COEP), 'require-corp');
    assert.equal(r.headers.get(CORP), null);
    assert.equal(r.headers.get('content-type'), 'text/html');
    assert.equal(r.headers.get('etag'), '"1"');
    assert.equal(r.statusText, 'OK');
    assert.equal(await r.text(), '<p>hi</p>');
    const s = withIsolationHeaders(new Response('x', { status: 404 }), script);
    assert.equal(s.status, 404);
    assert.equal(s.headers.get(CORP), 'same-origin');
    assert.equal(s.headers.get(COEP), 'require-corp');
  });

  test("the server's own values win; a response with them all is returned as it is", () => {
    const headers = { [COOP]: 'same-origin', [COEP]: 'credentialless', [CORP]: 'same-site' };
    const all = new Response('x', { headers });
    assert.equal(withIsolationHeaders(all, script), all);
    const some = withIsolationHeaders(new Response('x', { headers: { [COEP]: 'credentialless' } }), script);
    assert.equal(some.headers.get(COEP), 'credentialless');
    assert.equal(some.headers.get(COOP), 'same-origin');
  });

  test('errors, opaque, cross-origin and redirected responses are not copied', () => {
    const fake = (props) => ({ status: 200, redirected: false, type: 'basic', headers: new Headers(), ...props });
    for (const r of [
      Response.error(),
      fake({ type: 'opaque', status: 0 }),
      fake({ type: 'opaqueredirect', status: 0 }),
      fake({ type: 'cors' }),
      fake({ redirected: true }),
    ]) {
      assert.equal(withIsolationHeaders(r, page), r);
    }
    assert.equal(withIsolationHeaders(undefined, page), undefined);
  });
});

/** A fake browser: a page (isolated or not) with a sessionStorage, and a
 * service worker container whose registration `worker` describes: 'installs'
 * (a new worker that activates and claims the page after `claimAfter` ms),
 * 'fails' (it installs and becomes redundant), 'active' (a worker that does
 * not control the page: a hard reload), 'hangs' (never activates) or
 * 'rejects' (register() fails). */
function fakeBrowser({ isolated = false, controlled = false, worker = 'installs', claimAfter = 5, storage = new Map() } = {}) {
  const events = [];
  const serviceWorker = new EventTarget();
  serviceWorker.controller = controlled ? {} : null;
  serviceWorker.register = async (url, options) => {
    events.push(`register ${url} ${options.scope}`);
    if (worker === 'rejects') throw new Error('blocked');
    const incoming = Object.assign(new EventTarget(), { state: 'installing' });
    if (worker === 'installs') {
      setTimeout(() => {
        incoming.state = 'activated';
        serviceWorker.controller = incoming;
        serviceWorker.dispatchEvent(new Event('controllerchange'));
      }, claimAfter);
    } else if (worker === 'fails') {
      setTimeout(() => {
        incoming.state = 'redundant';
        incoming.dispatchEvent(new Event('statechange'));
      }, 5);
    }
    return worker === 'active' ? { active: {}, installing: null, waiting: null } : { installing: incoming, waiting: null };
  };
  const session = storage && {
    getItem: (k) => (storage.has(k) ? storage.get(k) : null),
    setItem: (k, v) => storage.set(k, String(v)),
    removeItem: (k) => storage.delete(k),
  };
  const env = {
    isolated,
    serviceWorker,
    storage: session,
    reload: () => events.push('reload'),
    afterLoad: (f) => {
      events.push('after load');
      f();
    },
  };
  return { env, events, storage };
}

/** startIsolated's outcome within `ms` ('pending' when it does not resolve:
 * the page reloads). */
const outcome = (promise, ms = 200) => Promise.race([promise, new Promise((r) => setTimeout(() => r('pending'), ms))]);

describe('the page reloads once through its service worker', () => {
  test('without a service worker (the one-file app, the element, Node) it starts at once', async () => {
    assert.equal(SERVICE_WORKER, null); // no build defined one here
    const { env, events } = fakeBrowser();
    assert.equal(await startIsolated(null, env), 'no service worker');
    assert.equal(await startIsolated('./sw.js', { ...env, serviceWorker: null }), 'no service worker');
    assert.deepEqual(events, []);
  });

  test('an isolated page registers the worker once loaded, forgets the reload and starts', async () => {
    const { env, events, storage } = fakeBrowser({ isolated: true, storage: new Map([[RELOADED_KEY, '1']]) });
    assert.equal(await startIsolated('./sw.js', env), 'isolated');
    assert.deepEqual(events, ['after load', 'register ./sw.js ./']);
    assert.equal(storage.has(RELOADED_KEY), false);
  });

  test('first visit: once the new worker claims the page, it notes the reload and reloads', async () => {
    const { env, events, storage } = fakeBrowser();
    assert.equal(await outcome(startIsolated('./sw.js', env)), 'pending');
    assert.deepEqual(events, ['register ./sw.js ./', 'reload']);
    assert.equal(storage.get(RELOADED_KEY), '1');
  });

  test('a page the worker controls already, but not isolated, reloads at once', async () => {
    const { env, events } = fakeBrowser({ controlled: true });
    assert.equal(await outcome(startIsolated('./sw.js', env)), 'pending');
    assert.deepEqual(events, ['reload']);
  });

  test('after the one reload, still not isolated, it starts without reloading again', async () => {
    const { env, events } = fakeBrowser({ controlled: true, storage: new Map([[RELOADED_KEY, '1']]) });
    assert.equal(await startIsolated('./sw.js', env), 'reloaded once already');
    assert.deepEqual(events, ['after load', 'register ./sw.js ./']);
  });

  test('without sessionStorage there is no guard: it never reloads', async () => {
    const { env, events } = fakeBrowser({ controlled: true, storage: null });
    assert.equal(await startIsolated('./sw.js', env), 'no storage');
    const denied = () => {
      throw new Error('denied');
    };
    const blocked = { getItem: denied, setItem: denied, removeItem: denied };
    assert.equal(await startIsolated('./sw.js', { ...env, storage: blocked }), 'no storage');
    assert.equal(events.includes('reload'), false);
  });

  test('a worker that fails, does not register, or only a hard-reloaded page: it starts as it is', async () => {
    for (const [worker, why] of [
      ['fails', 'not controlled'],
      ['rejects', 'not registered'],
      ['active', 'not controlled'],
    ]) {
      const { env, events } = fakeBrowser({ worker });
      assert.equal(await startIsolated('./sw.js', env), why, worker);
      assert.equal(events.includes('reload'), false, worker);
    }
  });

  test('a worker that takes too long: it starts on one thread, and its later claim does not reload', async () => {
    const { env, events } = fakeBrowser({ claimAfter: 60 });
    assert.equal(await startIsolated('./sw.js', env, 20), 'timed out');
    await new Promise((r) => setTimeout(r, 80));
    assert.equal(env.serviceWorker.controller !== null, true);
    assert.equal(events.includes('reload'), false);
    const hung = fakeBrowser({ worker: 'hangs' });
    assert.equal(await startIsolated('./sw.js', hung.env, 20), 'timed out');
  });
});
