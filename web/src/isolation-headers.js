// The headers that make the page cross-origin isolated, which the app's
// service worker (sw.js) adds to the responses it serves, so that a static
// host that sends none still gets the threaded core (isolation.js).

/** Each header and its value, added where the response has none. */
export const ISOLATION_HEADERS = {
  'Cross-Origin-Opener-Policy': 'same-origin',
  'Cross-Origin-Embedder-Policy': 'require-corp',
};
/** Added to subresources (not navigations) that have none. */
export const RESOURCE_POLICY = { 'Cross-Origin-Resource-Policy': 'same-origin' };

/**
 * `response` with the isolation headers it lacks (its other headers, status
 * and body kept), for `request`. Returned as it is: an error, an opaque or
 * opaque-redirect response, a cross-origin (cors) one, a redirected one
 * (a copy would lose its final URL), and one that has them all already.
 */
export function withIsolationHeaders(response, request) {
  if (!response || response.status === 0 || response.redirected) return response;
  if (response.type !== 'basic' && response.type !== 'default') return response;
  const wanted = request?.mode === 'navigate' ? ISOLATION_HEADERS : { ...ISOLATION_HEADERS, ...RESOURCE_POLICY };
  const missing = Object.entries(wanted).filter(([name]) => !response.headers.has(name));
  if (missing.length === 0) return response;
  const headers = new Headers(response.headers);
  for (const [name, value] of missing) headers.set(name, value);
  return new Response(response.body, { status: response.status, statusText: response.statusText, headers });
}
