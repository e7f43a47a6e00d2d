// Module Web Worker serving the vesselmesh API. Protocol:
//   in:  { id, op: 'analyze' | 'mesh' | 'makePhantom' | 'export' | 'report' |
//          'openingNames' | 'cutAt' | 'layerFractions' | 'sizeField' |
//          'keep' | 'release',
//          args: [bytes?, options] }
//        (export: args [format, options]; cutAt: [point, options];
//        keep, release: [handle])
//   out: { type: 'ready', version, threads, threadsNote, optionTable, solverPresets }
//        | { type: 'error', error } once
//        at start;
//        { id, type: 'progress', fraction, stage } during a job (at most one
//        every 50 ms); { id, type: 'result', result } at the end, with the
//        result's typed-array buffers (file, msh, stl, surface.*, volume.*,
//        sizeField's arrays)
//        transferred, not copied; a result with `restart: true` (the module
//        ran out of memory or stopped, see the API's stopped()) is this
//        worker's last: the client replaces it.
// Handles: the API's handles (Embind objects) stay here, in a Map owned by
// this worker; the client gets { kind: 'analysis' | 'mesh', id, worker }
// (worker: this worker's token, as a handle of a restarted worker is
// refused) as a result's `handle`, and gives it back as the options'
// `analysis` or `mesh`, or to keep and release. The API frees a handle
// replaced as its newest unless kept, and the Map forgets freed ones.
import { refusal, releasedError, restartedError } from './handles.js';
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

// Where the operations on an analysis or a mesh find its handle: [the
// argument (an options object), the key in it].
const HANDLE_ARGUMENT = {
  export: [1, 'mesh'],
  report: [0, 'mesh'],
  openingNames: [0, 'analysis'],
  sizeField: [0, 'analysis'],
  cutAt: [1, 'analysis'],
};

/** id -> the API's handle, for the client's { kind, id, worker }. */
const handles = new Map();
let nextHandle = 1;
/** This worker's token in its handles: a new worker (after cancel) refuses the old ones. */
const token = `${Date.now().toString(36)}-${Math.random().toString(36).slice(2)}`;

/** A job's result as the client gets it: its handle as an id here. */
function outward(result, kind) {
  if (!result?.ok || !result.handle) return result;
  for (const [id, handle] of handles) if (handle.isDeleted()) handles.delete(id);
  const id = nextHandle++;
  handles.set(id, result.handle);
  return { ...result, handle: { kind, id, worker: token } };
}

/** Whether `ref` has the shape of a client's handle. */
const isRef = (ref) => typeof ref === 'object' && ref !== null && (ref.kind === 'analysis' || ref.kind === 'mesh');

/** What a value that is no handle is, for a message. */
const what = (value) => (value === null ? 'null' : typeof value === 'object' ? 'another object' : `a ${typeof value}`);

/** The API's live handle of the client's `ref`, or {failed}. */
function lookup(ref, call) {
  if (ref.worker !== token) return { failed: refusal(restartedError(call, ref.kind)) };
  const handle = handles.get(ref.id);
  if (!handle || handle.isDeleted()) return { failed: refusal(releasedError(call, ref.kind)) };
  return { handle };
}

/** The API's handle for the options' `key` ('analysis' or 'mesh') of a
 * call: undefined when none is given (the API's newest), or {failed}. */
function inward(ref, key, call) {
  if (ref === undefined || ref === null) return { handle: undefined };
  if (!isRef(ref) || ref.kind !== key) {
    return {
      failed: {
        ok: false,
        error: `${call}: ${key} must be the handle of a ${key} of this client (the \`handle\` of ${key === 'mesh' ? 'mesh()' : 'analyze()'}'s result), not ${isRef(ref) ? `the handle of a ${ref.kind}` : what(ref)}`,
        kind: 'bad_option',
        option: key,
      },
    };
  }
  return lookup(ref, call);
}

/** keep(ref) or release(ref): releasing one already gone is nothing. */
function keepOrRelease(api, op, ref) {
  if (!isRef(ref)) {
    return { ok: false, error: `${op}: give the \`handle\` of an analyze() or mesh() result of this client, not ${what(ref)}`, kind: 'bad_input' };
  }
  const { handle, failed } = lookup(ref, op);
  if (op === 'keep') return failed ?? api.keep(handle);
  if (failed) return { ok: true };
  handles.delete(ref.id);
  return api.release(handle);
}

/** The result of `op` on `args`, the client's handles in them as the API's. */
function answer(api, op, args, onProgress) {
  if (op === 'analyze' || op === 'mesh') {
    return outward(api[op](args[0], { ...args[1], onProgress }), op === 'mesh' ? 'mesh' : 'analysis');
  }
  if (op === 'keep' || op === 'release') return keepOrRelease(api, op, args[0]);
  if (!ANSWERED_AS_IS.has(op)) return { ok: false, error: `unknown operation '${op}'` };
  const where = HANDLE_ARGUMENT[op];
  if (where) {
    const [at, key] = where;
    const options = args[at] ?? {};
    const { handle, failed } = inward(options[key], key, op);
    if (failed) return failed;
    args = [...args];
    args[at] = { ...options, [key]: handle };
  }
  return api[op](...args);
}

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
  // A call that throws past the API, or a result too large to post, is
  // this worker's end: the client replaces it (restart).
  const failed = (what, error) => ({
    ok: false,
    kind: error instanceof RangeError ? 'out_of_memory' : 'internal',
    error: `${error instanceof RangeError ? 'out of memory' : 'internal error'}: the mesher worker failed ${what} ${op} (${error?.message ?? error})`,
    restart: true,
  });
  let result;
  try {
    result = answer(api, op, args, onProgress);
  } catch (error) {
    result = failed('in', error);
  }
  try {
    self.postMessage({ id, type: 'result', result }, transferables(result));
  } catch (error) {
    self.postMessage({ id, type: 'result', result: failed('to send the result of', error) });
  }
};
