// Module Web Worker serving the vesselmesh API. Protocol:
//   in:  { id, op: 'analyze' | 'mesh' | 'makePhantom' | 'export' | 'openingNames' |
//          'cutAt' | 'layerFractions' | 'sizeField',
//          args: [bytes?, options] }
//        (export: args [format, options]: the last mesh in another format)
//   out: { type: 'ready', version, optionTable, solverPresets } | { type: 'error', error } once
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
  switch (op) {
    case 'analyze':
      result = api.analyze(args[0], { ...args[1], onProgress });
      break;
    case 'mesh':
      result = api.mesh(args[0], { ...args[1], onProgress });
      break;
    case 'makePhantom':
      result = api.makePhantom(args[0]);
      break;
    case 'export':
      result = api.export(args[0], args[1]);
      break;
    case 'openingNames':
      result = api.openingNames(args[0]);
      break;
    case 'cutAt':
      result = api.cutAt(args[0]);
      break;
    case 'layerFractions':
      result = api.layerFractions(args[0]);
      break;
    case 'sizeField':
      result = api.sizeField(args[0]);
      break;
    default:
      result = { ok: false, error: `unknown operation '${op}'` };
  }
  self.postMessage({ id, type: 'result', result }, transferables(result));
};
