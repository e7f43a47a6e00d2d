// The package's entry in browsers and bundlers ('vesselmesh'): the API (the
// wasm is fetched next to vesselmesh.js) and its Web Worker client.
export { createVesselmesh } from './vesselmesh.js';
export { VesselmeshClient } from './client.js';
