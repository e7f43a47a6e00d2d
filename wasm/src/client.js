// Promise-based client of the vesselmesh worker (worker.js): the page's only
// way to the WebAssembly core. One job runs at a time in the worker; cancel()
// terminates it and starts a fresh worker. A result's `handle` is
// { kind, id, worker }: an id of the analysis or mesh the worker holds; the
// calls on one take it (options `analysis` or `mesh`), or act on the
// worker's newest. The worker frees the newest of a kind when a newer job
// replaces it, unless kept (keep()); release() frees one; a cancel frees all.
// A result with `restart: true` (the worker's module ran out of memory, or
// stopped) replaces the worker the same way, and calls onRestart(result):
// the page keeps working, without the old worker's handles.

const defaultWorker = () =>
  new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });

export class VesselmeshClient {
  /** @param {{ createWorker?: () => Worker }} [options] */
  constructor({ createWorker = defaultWorker } = {}) {
    this._createWorker = createWorker;
    /** Called with the failure after the worker was replaced because its
     * module stopped (out of memory): the handles of the old one are gone. */
    this.onRestart = null;
    this._nextId = 1;
    this._pending = new Map();
    this._start();
  }

  _start() {
    this._worker = this._createWorker();
    this.ready = new Promise((resolve, reject) => {
      this._readyResolve = resolve;
      this._readyReject = reject;
    });
    // A failed load rejects `ready`; calls then resolve with { ok: false }.
    this.ready.catch(() => {});
    this._worker.onmessage = (event) => this._onMessage(event.data);
    this._worker.onerror = (event) => {
      const error = `the mesher worker failed: ${event.message || 'unknown error'}`;
      this._readyReject(new Error(error));
      this._failAll({ ok: false, error });
    };
  }

  _onMessage(msg) {
    if (msg.type === 'ready') {
      this.version = msg.version;
      /** The most threads a job runs on, and on one thread why (see the
       * API's threads and threadsNote), once ready. */
      this.threads = msg.threads;
      this.threadsNote = msg.threadsNote;
      /** The option table (see the API's optionTable), once ready. */
      this.optionTable = msg.optionTable;
      /** The solver presets (see the API's solverPresets), once ready. */
      this.solverPresets = msg.solverPresets;
      this._readyResolve(msg.version);
      return;
    }
    if (msg.type === 'error') {
      this._readyReject(new Error(msg.error));
      this._failAll({ ok: false, error: msg.error });
      return;
    }
    const job = this._pending.get(msg.id);
    if (!job) return;
    if (msg.type === 'progress') {
      job.onProgress?.(msg.fraction, msg.stage);
    } else if (msg.type === 'result') {
      this._pending.delete(msg.id);
      if (!msg.result?.restart) {
        job.resolve(msg.result);
      } else {
        job.resolve({ ...msg.result, error: `${msg.result.error}; the mesher was restarted` });
        this._replace({ ok: false, error: `the mesher was restarted: ${msg.result.error}` });
        this.onRestart?.(msg.result);
      }
    }
  }

  /** A fresh worker for the old one; its pending jobs resolve `result`. */
  _replace(result) {
    this._worker.terminate();
    this._failAll(result);
    this._start();
  }

  _failAll(result) {
    for (const job of this._pending.values()) job.resolve(result);
    this._pending.clear();
  }

  _call(op, args, onProgress) {
    const id = this._nextId++;
    return new Promise((resolve) => {
      this._pending.set(id, { resolve, onProgress });
      this._worker.postMessage({ id, op, args });
    });
  }

  /** Reads, repairs and analyzes a surface file's bytes (copied, not moved);
   * options as in the API's analyze(). The result's `handle` is the
   * worker's analysis, now its newest. */
  analyze(bytes, { onProgress, ...options } = {}) {
    return this._call('analyze', [bytes, options], onProgress);
  }

  /**
   * Meshes STL bytes; options as in the API's mesh(). The result's typed
   * arrays (msh, surface, volume) arrive moved from the worker, not copied;
   * its `handle` is the worker's mesh, now its newest.
   */
  mesh(bytes, { onProgress, ...options } = {}) {
    return this._call('mesh', [bytes, options], onProgress);
  }

  /** A mesh (options.mesh: its handle; default the newest) in another
   * format (API export()): no meshing again. */
  export(format, options = {}) {
    return this._call('export', [format, options]);
  }

  /** The methods report of a mesh (options.mesh: its handle; default the
   * newest) (API report()): {file, fileName}. */
  report(options = {}) {
    return this._call('report', [options]);
  }

  /** The names an analyzed surface's openings get (options.analysis: its
   * handle; default the newest) (API openingNames()). */
  openingNames(options = {}) {
    return this._call('openingNames', [options]);
  }

  /** The cut across the vessel nearest a point of an analyzed surface
   * (options.analysis: its handle; default the newest) (API cutAt()). */
  cutAt(point, options = {}) {
    return this._call('cutAt', [Array.from(point), options]);
  }

  /** The layers' cumulative height fractions (API layerFractions()). */
  layerFractions(options = {}) {
    return this._call('layerFractions', [options]);
  }

  /** The size field of an analyzed surface (options.analysis: its handle;
   * default the newest) for these mesh options (API sizeField()). */
  sizeField(options = {}) {
    return this._call('sizeField', [options]);
  }

  /** Generates a phantom STL; options as in the API's makePhantom(). */
  makePhantom(options = {}) {
    return this._call('makePhantom', [options]);
  }

  /** Keeps a result's handle in the worker when a newer job replaces it as
   * the newest, until release(handle) (API keep()). */
  keep(handle) {
    return this._call('keep', [handle]);
  }

  /** Frees a result's handle in the worker now (API release()). */
  release(handle) {
    return this._call('release', [handle]);
  }

  /** Stops the running job: its promise resolves { ok: false, cancelled: true }. */
  cancel() {
    this._replace({ ok: false, cancelled: true, error: 'cancelled' });
  }

  /** Ends the worker for good. */
  dispose() {
    this._worker.terminate();
    this._failAll({ ok: false, error: 'the mesher was closed' });
  }
}
