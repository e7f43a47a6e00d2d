// The threaded WebAssembly core in Node (node.js): the module built for the
// browser (wasm/dist/vesselmesh_core_mt.*, -sENVIRONMENT=web,worker), with
// its pool of Workers on node:worker_threads. Emscripten's code makes its
// pool with the global Worker and talks to it as to a Web Worker
// (onmessage, onerror, postMessage, terminate), so while the module starts
// the global Worker is PoolWorker below, a Web Worker's face over a
// worker_threads Worker running node-pthread.js, which runs the module's
// pool Worker script; the global is restored before the first job, and the
// pool does not grow after the start. The shared memory and the compiled
// module cross to the pool as in the browser (worker_threads posts shared
// WebAssembly.Memory and WebAssembly.Module). The module's
// std::thread::hardware_concurrency() reads navigator.hardwareConcurrency,
// which Node 20 lacks: the core's calls run with it defined (and removed
// after) when it is not. Same API as threaded-core.js.
import { readFile } from 'node:fs/promises';
import os from 'node:os';
import { Worker } from 'node:worker_threads';

import { MAX_THREADS, within } from './threaded-core.js';

const SCRIPT = new URL('../dist/vesselmesh_core_mt.mjs', import.meta.url).href;
const WORKER_SCRIPT = new URL('../dist/vesselmesh_core_mt.worker.js', import.meta.url).href;
const WASM = new URL('../dist/vesselmesh_core_mt.wasm', import.meta.url);
const BOOTSTRAP = new URL('./node-pthread.js', import.meta.url);

/** The machine's cores as Node reports them. */
const cores = () => os.availableParallelism?.() ?? os.cpus().length;

/** Why the single-threaded core is used here, or '' when the threaded one
 * can run. */
export function singleThreadReason() {
  if (typeof SharedArrayBuffer !== 'function') return 'SharedArrayBuffer is not available here';
  if (cores() < 2) return 'Node reports one core';
  return '';
}

/** The machine's cores, at most MAX_THREADS. */
export const defaultThreads = () => Math.min(cores(), MAX_THREADS);

/** Runs `fn` with globalThis[name] = value, restored after: `fn` only
 * starts work that reads the global at once. */
function withGlobal(name, value, fn) {
  const saved = Object.getOwnPropertyDescriptor(globalThis, name);
  Object.defineProperty(globalThis, name, { value, configurable: true, writable: true });
  try {
    return fn();
  } finally {
    if (saved) Object.defineProperty(globalThis, name, saved);
    else delete globalThis[name];
  }
}

/** Runs `fn` with navigator.hardwareConcurrency readable, as the module's
 * std::thread::hardware_concurrency() needs (Node 21 has navigator). */
const withNavigator = (fn) =>
  globalThis.navigator === undefined ? withGlobal('navigator', { hardwareConcurrency: cores() }, fn) : fn();

/** The core with each of its functions called through withNavigator. */
const navigating = (core) =>
  new Proxy(core, {
    get(target, key) {
      const value = target[key];
      return typeof value === 'function' ? (...args) => withNavigator(() => value.apply(target, args)) : value;
    },
  });

/**
 * Loads the threaded core with a pool of `threads` - 1 worker_threads; the
 * core's jobs then use at most `threads` threads (2..MAX_THREADS).
 * @returns {Promise<object>} the Embind module
 */
export async function createThreadedCore(threads) {
  const [{ default: create }, wasmBinary] = await Promise.all([import(SCRIPT), readFile(WASM)]);
  const pool = [];
  let failStart;
  const failed = new Promise((_, reject) => (failStart = reject));
  failed.catch(() => {}); // after the start a pool thread's error is only logged

  /** A Web Worker's face over a worker_threads Worker, as Emscripten's
   * pthread code uses it; unref'd, so that the pool does not keep the
   * process alive. */
  class PoolWorker {
    constructor(workerScript) {
      this.onmessage = null;
      this.onerror = null;
      this.thread = new Worker(BOOTSTRAP, {
        workerData: { workerScript: String(workerScript), hardwareConcurrency: cores() },
        execArgv: [], // not the program's flags: some refuse a worker (--input-type)
      });
      this.thread.on('message', (data) => this.onmessage?.({ data }));
      this.thread.on('error', (error) => {
        failStart(error);
        try {
          // Logs it and throws it again, as a Web Worker's error handler.
          this.onerror?.({ message: error?.message ?? String(error), filename: '', lineno: 0, error });
        } catch {}
      });
      this.thread.on('exit', (code) => failStart(new Error(`a pool thread exited (code ${code})`)));
      this.thread.unref(); // after on('message'), which refs it again
      pool.push(this);
    }

    postMessage(message, transfer) {
      this.thread.postMessage(message, transfer);
    }

    terminate() {
      this.thread.terminate();
    }
  }

  const started = withGlobal('Worker', PoolWorker, () =>
    withNavigator(() =>
      create({
        wasmBinary,
        vmPoolSize: threads - 1, // read by the module (PTHREAD_POOL_SIZE, wasm/CMakeLists.txt)
        mainScriptUrlOrBlob: SCRIPT, // each pool thread imports it (a file: URL)
        locateFile: (name) => (name.endsWith('.worker.js') ? WORKER_SCRIPT : name),
        // The calling thread waits for the pool within a job, as the
        // browser's worker does: in Node the main thread may, so the
        // module's warning for a browser page's main thread is dropped.
        printErr: (text) => {
          if (!text.startsWith('Blocking on the main thread')) console.warn(text);
        },
      }),
    ),
  );
  let core;
  try {
    core = navigating(await within(Promise.race([started, failed]), 20_000, 'the threaded core'));
  } catch (error) {
    for (const worker of pool) worker.terminate();
    throw error;
  }
  core.setThreadLimit(threads);
  return core;
}
