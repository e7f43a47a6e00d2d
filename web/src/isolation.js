// The served app registers its service worker (sw.js) here, and gets
// cross-origin isolated (hence the threaded core, wasm/src/threaded-core.js)
// on a static host that sends no COOP/COEP headers: the worker adds them to
// what it serves, so a page that came without them reloads once it is
// controlled (on the first visit: once the worker has precached the app and
// claimed the page), before the app starts. One reload per tab session
// (sessionStorage): a page still not isolated after it stays on one thread.
// The one-file app and the element have no service worker (the constant
// below is defined by installable() in vite.config.js, for the served
// build only) and start at once; so does the page if anything here fails.

/* global __VM_SERVICE_WORKER__ */
/** The service worker's URL relative to the page, or null without one. */
export const SERVICE_WORKER = typeof __VM_SERVICE_WORKER__ === 'string' ? __VM_SERVICE_WORKER__ : null;

/** The sessionStorage key set just before the reload. */
export const RELOADED_KEY = 'vesselmesh:isolation-reload';

/** How long a first visit waits for the worker to control the page before
 * the app starts on one thread (the worker keeps installing: the next
 * visit is isolated). */
export const CLAIM_TIMEOUT_MS = 15_000;

/** `get()`, or null where it throws (a sandboxed page, blocked storage). */
const tryGet = (get) => {
  try {
    return get() ?? null;
  } catch {
    return null;
  }
};

const browser = () => ({
  isolated: globalThis.crossOriginIsolated === true,
  serviceWorker: tryGet(() => globalThis.navigator.serviceWorker),
  storage: tryGet(() => globalThis.sessionStorage),
  reload: () => globalThis.location.reload(),
  afterLoad: (f) => (document.readyState === 'complete' ? f() : globalThis.addEventListener('load', f, { once: true })),
});

/**
 * Registers the service worker `url` and resolves when the app may start,
 * with why it starts as it does: 'isolated', 'no service worker',
 * 'reloaded once already', 'no storage', 'not registered', 'not controlled'
 * or 'timed out'. When the page reloads, the promise never resolves.
 * @param {string | null} url
 * @param {object} [env] the browser's state and actions (tests pass their own)
 */
export async function startIsolated(url = SERVICE_WORKER, env = browser(), timeout = CLAIM_TIMEOUT_MS) {
  const { isolated, serviceWorker, storage } = env;
  if (!url || !serviceWorker) return 'no service worker';
  // As a page that needs nothing more: registered once the page has loaded,
  // its precaching does not compete with the app's own loading.
  const registerLater = () => env.afterLoad(() => register(serviceWorker, url).catch(() => {}));
  if (isolated) {
    forget(storage);
    registerLater();
    return 'isolated';
  }
  const reloaded = readFlag(storage);
  if (reloaded !== false) {
    registerLater();
    return reloaded === null ? 'no storage' : 'reloaded once already';
  }
  if (!serviceWorker.controller) {
    const outcome = await claim(serviceWorker, url, timeout);
    if (outcome !== 'claimed') return outcome;
  }
  try {
    storage.setItem(RELOADED_KEY, '1');
  } catch {
    return 'no storage';
  }
  env.reload();
  return new Promise(() => {});
}

/** The worker's registration (a promise, rejected rather than thrown). */
const register = async (serviceWorker, url) => serviceWorker.register(url, { scope: './' });

/** Registers the worker and waits until it controls the page: 'claimed',
 * or why not. */
async function claim(serviceWorker, url, timeout) {
  let timer;
  const late = new Promise((resolve) => (timer = setTimeout(() => resolve('timed out'), timeout)));
  const claimed = new Promise((resolve) => serviceWorker.addEventListener('controllerchange', () => resolve('claimed'), { once: true }));
  const registered = register(serviceWorker, url).then(
    (registration) => {
      if (serviceWorker.controller) return 'claimed';
      // A worker on its way claims the page once active; without one (an
      // active worker that a hard reload bypassed) the page stays as it is.
      const incoming = registration.installing ?? registration.waiting;
      if (!incoming || incoming.state === 'redundant') return 'not controlled';
      return new Promise((resolve) => {
        incoming.addEventListener('statechange', () => incoming.state === 'redundant' && resolve('not controlled'));
        claimed.then(resolve);
      });
    },
    () => 'not registered',
  );
  try {
    return await Promise.race([claimed, registered, late]);
  } finally {
    clearTimeout(timer);
  }
}

/** Whether the page reloaded for isolation in this tab session already;
 * null when sessionStorage cannot be used (then it never reloads). */
function readFlag(storage) {
  try {
    return storage.getItem(RELOADED_KEY) !== null;
  } catch {
    return null;
  }
}

function forget(storage) {
  try {
    storage?.removeItem(RELOADED_KEY);
  } catch {
    // nothing to forget
  }
}
