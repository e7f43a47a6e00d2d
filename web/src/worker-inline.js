// The one-file build's mesher worker: its script (with the wasm inlined as a
// data: URL) is inside the page and started from a blob: URL, so the page
// works opened from disk (file://), where no script can be fetched. It is a
// classic (iife) worker: Chromium refuses module workers from blob: URLs there.
import InlineWorker from '../../wasm/src/worker.js?worker&inline';

export const createWorker = () => new InlineWorker();
