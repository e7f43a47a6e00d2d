// The served app's service worker (vite.config.js, installable(): built by
// vite-plugin-pwa's injectManifest into dist/sw.js, every import bundled).
// It precaches every file of the build, so that after one visit the app
// loads with no server, and it adds the cross-origin isolation headers to
// whatever it serves the page from its origin, precached or from the
// network, so that a static host that sends none still gets the threaded
// core (the page reloads once to come through it: isolation.js).
import { clientsClaim } from 'workbox-core';
import { addPlugins, cleanupOutdatedCaches, precacheAndRoute } from 'workbox-precaching';
import { registerRoute } from 'workbox-routing';

import { withIsolationHeaders } from './isolation-headers.js';

// A new version takes over the open pages at once.
self.skipWaiting();
clientsClaim();
cleanupOutdatedCaches();

// The precache's responses, as the page gets them (not as the install
// stores them: the cache keeps what the server sent).
addPlugins([
  {
    handlerWillRespond: async ({ event, request, response }) =>
      event?.type === 'fetch' ? withIsolationHeaders(response, request) : response,
  },
]);
precacheAndRoute(self.__WB_MANIFEST);

// Any other GET of this origin, from the network (it fails offline, as
// without a service worker).
registerRoute(
  ({ request, sameOrigin }) => sameOrigin && !(request.cache === 'only-if-cached' && request.mode !== 'same-origin'),
  async ({ request }) => withIsolationHeaders(await fetch(request), request),
);
