// Module Web Worker serving the vesselmesh API. Protocol:
//   in:  { id, op: 'analyze' | 'mesh' | 'makePhantom' | 'export' | 'report' |
//          'openingNames' | 'cutAt' | 'layerFractions' | 'sizeField',
//          args: [bytes?, options] }
//        (export: args [format, options]: the last mesh in another format)
//   out: { type: 'ready', version, threads, threadsNote, optionTable, solverPresets }
//        | { type: 'error', error } once
//        at start;
//        { id, type: 'progress', fraction, stage } during a job (at most one
//        every 50 ms); { id, type: 'result', result } at the end, with the
//        result's typed-array buffers (file, msh, stl, surface.*, volume.*,
//        sizeField's arrays)
//        transferred, not copied.
import { transferables } from './transfer.js';
import { createVesselmesh } from './vesselmesh.js';

const apiPromise = createVesselmesh().then(
  (api) => {
    self.postMessage({
      type: 'ready',
      version: api.version,
      threads: api.threads,
      threadsNote: api.threadsNote,
      optionTable: api.optionTable,
      solverPresets: api.solverPresets,
    });
    return api;
  },
  (error) => {
    self.postMessage({ type: 'error', error: `cannot load the mesher: ${error}` });
    return null;
  },
);

// The operations but the two jobs (which report progress): the API's method
// of that name called with the message's arguments.
const ANSWERED_AS_IS = new Set(['makePhantom', 'export', 'report', 'openingNames', 'cutAt', 'layerFractions', 'sizeField']);

self.onmessage = async (event) => {
  const { id, op, args = [] } = event.data;
  const api = await apiPromise;
  if (!api) {
    self.postMessage({ id, type: 'result', result: { ok: false, error: 'the mesher failed to load' } });
    return;
  }
  let last = 0;
  const onProgress = (fraction, stage) => {
    const now = performance.now();
    if (now - last >= 50 || fraction >= 1) {
      last = now;
      self.postMessage({ id, type: 'progress', fraction, stage });
    }
    return true;
  };
  let result;
  if (op === 'analyze' || op === 'mesh') result = api[op](args[0], { ...args[1], onProgress });
  else if (ANSWERED_AS_IS.has(op)) result = api[op](...args);
  else result = { ok: false, error: `unknown operation '${op}'` };
  self.postMessage({ id, type: 'result', result }, transferables(result));
};
