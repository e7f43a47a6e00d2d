// The one-file app's stand-in for wasm/src/threaded-core.js (vite.config.js,
// mode 'singlefile'): a page opened from disk is never cross-origin
// isolated, so the threaded core could not run; leaving it out keeps a
// second copy of the wasm out of the file.
export const MAX_THREADS = 1;

export const singleThreadReason = () => 'the one-file app runs on one thread';

export const defaultThreads = () => 1;

export async function createThreadedCore() {
  throw new Error('the one-file app has no threaded core');
}
