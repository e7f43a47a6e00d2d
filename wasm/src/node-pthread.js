// A pool Worker of the threaded core in Node (started by node-threads.js on
// node:worker_threads): gives Emscripten's pool Worker script
// (wasm/dist/vesselmesh_core_mt.worker.js, built for Web Workers) the
// globals it uses there, `self`, `self.onmessage`, `postMessage` and
// `navigator.hardwareConcurrency`, then runs it as the classic script it is.
// Its 'load' message then imports vesselmesh_core_mt.mjs by its file: URL.
// This thread's globals are its own: nothing here reaches the user's.
import { readFileSync } from 'node:fs';
import { parentPort, workerData } from 'node:worker_threads';

const { workerScript, hardwareConcurrency } = workerData;

globalThis.self = globalThis;
globalThis.postMessage = (message, transfer) => parentPort.postMessage(message, transfer);
// std::thread::hardware_concurrency() reads it (Node 21 has navigator, 20 not).
globalThis.navigator ??= { hardwareConcurrency };

// A function body, not a module: it is a classic script (its own `var`s
// stay its own); import() in it loads the module by the URL it is given.
new Function(`${readFileSync(new URL(workerScript), 'utf8')}\n//# sourceURL=${workerScript}`)();
parentPort.on('message', (data) => self.onmessage({ data }));
