// How the page starts its mesher worker. The served app uses the client's
// default (the worker script next to the bundle, a file of its own that the
// service worker precaches); the one-file build (vite.config.js, mode
// 'singlefile') replaces this module with worker-inline.js.
export const createWorker = undefined;
