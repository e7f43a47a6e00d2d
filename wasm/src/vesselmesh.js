// The vesselmesh JavaScript API over the WebAssembly core: checks that the
// input is bytes, parses the JSON reports and returns every failure as
// { ok: false, error, kind } (nothing throws for a user error). Options are
// checked by the core against its option table, in the JS vocabulary.
// analyze() and mesh() give their result's `handle`; the calls on an
// analysis or a mesh take one, or act on this API object's newest
// (handles.js).
import createVesselmeshCore from '../dist/vesselmesh_core.mjs';
import { HandleRegistry } from './handles.js';
import { createThreadedCore, defaultThreads, MAX_THREADS, singleThreadReason } from './threaded-core.js';

const fail = (error) => ({ ok: false, error });

/** What the calls on an analysis say when there is none. */
const NOTHING_ANALYZED = 'nothing analyzed yet: analyze a surface first';

/** Uint8Array view of STL input, or null when the input is not bytes. */
function asBytes(input) {
  if (input instanceof Uint8Array) return input;
  if (input instanceof ArrayBuffer) return new Uint8Array(input);
  if (ArrayBuffer.isView(input)) {
    return new Uint8Array(input.buffer, input.byteOffset, input.byteLength);
  }
  return null;
}

function progressCallback(onProgress) {
  if (onProgress === undefined || onProgress === null) return undefined;
  if (typeof onProgress !== 'function') return null;
  return onProgress;
}

/** The input bytes and progress callback of a job (`name`: analyze, mesh),
 * or {failed} saying which of them is unusable. */
function jobInput(name, bytesIn, onProgress) {
  const bytes = asBytes(bytesIn);
  if (!bytes) return { failed: fail(`${name}: the input must be a Uint8Array or ArrayBuffer`) };
  const progress = progressCallback(onProgress);
  if (progress === null) return { failed: fail(`${name}: onProgress must be a function`) };
  return { bytes, progress };
}

async function loadWasmBinary() {
  const url = new URL('../dist/vesselmesh_core.wasm', import.meta.url);
  const response = await fetch(url);
  if (!response.ok) throw new Error(`cannot load ${url}: HTTP ${response.status}`);
  return response.arrayBuffer();
}

/** A core result as the API returns it: failures keep their kind, the
 * option they concern (its JS name), `cancelled` and the remedy core
 * offers. */
function failure(raw) {
  return {
    ok: false,
    error: raw.error,
    kind: raw.kind,
    ...(raw.option && { option: raw.option }),
    ...(raw.cancelled && { cancelled: true }),
    ...(raw.remedy && { remedy: raw.remedy }),
  };
}

/** A core result as the API returns it: a success as it is, a failure by
 * failure(). */
function answer(raw) {
  return raw.ok ? raw : failure(raw);
}

/** Whether what a core call threw is its memory running out: a failed
 * growth or allocation (RangeError, Emscripten's "Aborted(OOM)"), or a
 * C++ exception, which the WebAssembly build does not catch (it is thrown
 * as a number) and the core throws none but std::bad_alloc: its own
 * errors are values. */
const isOutOfMemory = (thrown) =>
  typeof thrown === 'number' || thrown instanceof RangeError || /\bOOM\b|out of memory|memory/i.test(String(thrown?.message ?? thrown));

/** The failure of a core call `call` that threw `thrown`: the module is
 * left unusable (its stack and heap unwound without the C++ cleanups), so
 * `restart` says to load a new one (the worker client does). `heapBytes`:
 * the module's memory then. */
function stopped(call, thrown, heapBytes) {
  const mb = (bytes) => `${Math.round(bytes / 2 ** 20)} MB`;
  if (isOutOfMemory(thrown)) {
    return {
      ok: false,
      kind: 'out_of_memory',
      error: `out of memory ${DOING[call] ?? `in ${call}()`}: the mesher's memory (${heapBytes ? `${mb(heapBytes)} in use, ` : ''}at most ${mb(MAX_MEMORY)}) ran out; try a coarser size (a larger size or a smaller perCircumference)`,
      restart: true,
    };
  }
  return { ok: false, kind: 'internal', error: `internal error: the mesher stopped in ${call}() (${String(thrown?.message ?? thrown)}); please report it`, restart: true };
}

/** What the calls that take memory do, for the message. */
const DOING = { analyze: 'while reading the surface', mesh: 'while meshing', export: 'while writing the file', report: 'while writing the report' };

/** The WebAssembly module's MAXIMUM_MEMORY (wasm/CMakeLists.txt). */
const MAX_MEMORY = 4 * 2 ** 30;

/** Where the cores come from in the browser: the single-threaded core's
 * wasm fetched, the threaded core on Web Workers (threaded-core.js). The
 * Node entry (node.js) passes its own, of the same shape. */
const BROWSER = { loadWasmBinary, singleThreadReason, defaultThreads, createThreadedCore };

/** The single-threaded core, from `wasmBinary` or the host's. */
async function createSingleThreadedCore(host, wasmBinary) {
  return createVesselmeshCore({ wasmBinary: wasmBinary ?? (await host.loadWasmBinary()) });
}

/** The core for createVesselmesh's options, with the number of threads its
 * jobs may use and, on one thread, why. `threads` as the job option: 0 (or
 * none) for all the machine's cores. */
async function loadCore(host, { wasmBinary, threads = 0 }) {
  if (!(Number.isInteger(threads) && threads >= 0 && threads <= 256)) {
    throw new TypeError(`createVesselmesh: threads must be an integer from 0 (all cores) to 256, not ${threads}`);
  }
  const reason = wasmBinary
    ? 'a wasmBinary was given (the single-threaded core)'
    : host.singleThreadReason() || (threads === 1 ? 'threads: 1 was asked' : '');
  if (reason) return { core: await createSingleThreadedCore(host, wasmBinary), threads: 1, why: reason };
  const wanted = Math.min(threads || host.defaultThreads(), MAX_THREADS);
  try {
    return { core: await host.createThreadedCore(wanted), threads: wanted, why: '' };
  } catch (error) {
    const why = `the threaded core did not start (${error?.message ?? error})`;
    return { core: await createSingleThreadedCore(host), threads: 1, why };
  }
}

/**
 * Loads the WebAssembly module and returns the API.
 * @param {{ wasmBinary?: ArrayBuffer|Uint8Array, threads?: number }} [options]
 *   In the browser the wasm is fetched next to this module (in Node, use
 *   node.js, the package's Node entry, or pass wasmBinary: fs.readFileSync
 *   of wasm/dist/vesselmesh_core.wasm, the single-threaded core).
 *   threads: the most threads jobs may use (0, the default: the browser's
 *   cores; at most 8); more than 1 loads the threaded core, which needs a
 *   cross-origin isolated page; elsewhere, or when it fails to start, the
 *   single-threaded core is used (see `threads` and `threadsNote` on the
 *   API).
 */
export async function createVesselmesh(options = {}) {
  return createVesselmeshIn(BROWSER, options);
}

/**
 * createVesselmesh with the cores of `host` ({ loadWasmBinary,
 * singleThreadReason, defaultThreads, createThreadedCore }, as BROWSER):
 * node.js passes Node's.
 */
export async function createVesselmeshIn(host, { wasmBinary, threads } = {}) {
  const loaded = await loadCore(host, { wasmBinary, threads });
  const { core } = loaded;

  const withSurface = (raw, extra) => ({ ok: true, ...extra, surface: raw.surface });
  /** The failure that stopped the module, once a core call threw: every
   * later call refuses with it. */
  let broken = null;
  /** `call` (a name) run as `run()`, unless the module stopped; a throw
   * stops it (stopped()). */
  const guard = (call, run) => {
    if (broken) {
      return { ok: false, kind: broken.kind, error: `the mesher stopped after an earlier failure (${broken.error}): create a new one (createVesselmesh())`, restart: true };
    }
    try {
      return run();
    } catch (thrown) {
      broken = stopped(call, thrown, core.HEAP8?.buffer.byteLength);
      return broken;
    }
  };
  /** The analyses and meshes this API object gave, and its newest of each:
   * what the calls given no handle act on. */
  const handles = new HandleRegistry();
  /** The option table (core/pipeline/option_table.h) as parsed JSON. */
  const optionTable = JSON.parse(core.optionTable());
  /** The solver presets (core/pipeline/solver_preset.h) as parsed JSON. */
  const solverPresets = JSON.parse(core.solverPresets());

  return {
    version: core.version(),

    /** The most threads a job runs on (the `threads` job option is capped
     * at it); 1 with the single-threaded core. The mesh does not depend on
     * it. */
    threads: loaded.threads,

    /** On one thread, why ('' with the threaded core). */
    threadsNote: loaded.why,

    /** Every option of analyze, mesh and makePhantom: id, js (the key
     * here), type, range, default, unit, doc (see vesselmesh.d.ts). */
    optionTable,

    /** The solver presets of the `solver` option: name, label, and what
     * each sets (prisms, format, mshVersion, outputUnits; '' = the
     * input's unit), with a note on what the solver needs. */
    solverPresets,

    /**
     * Reads, welds, repairs and analyzes a surface file (STL). `handle`:
     * the analyzed surface, for openingNames, cutAt and sizeField (option
     * `analysis`); it becomes this API's newest analysis, which those calls
     * use when given none. The newest before it is freed as the job starts,
     * unless kept (keep()).
     * @returns {{ok: true, analysis: object, surface: {positions: Float32Array,
     *   triangles: Uint32Array, quality: Float32Array}, handle: object}
     *   | {ok: false, error: string}}
     */
    analyze(bytesIn, { onProgress, ...options } = {}) {
      const { bytes, progress, failed } = jobInput('analyze', bytesIn, onProgress);
      if (failed) return failed;
      return guard('analyze', () => {
        handles.retire('analysis');
        const raw = core.analyze(bytes, options, progress);
        if (!raw.ok) return failure(raw);
        const handle = handles.issue('analysis', raw.handle);
        return withSurface(raw, { analysis: JSON.parse(raw.analysisJson), handle });
      });
    },

    /**
     * Meshes a surface file: remeshes the surface by conformal maps (unless
     * remesh is false), caps the openings, grows the boundary layers and
     * fills the lumen with tetrahedra (unless surfaceOnly). Options: the
     * option table's mesh options by their JS keys (docs/options.md;
     * vesselmesh.d.ts). Returns the MSH file bytes, the report, the wall
     * surface and the volume (see vesselmesh.d.ts, MeshVolume). `file` is
     * the written file in `format` (default msh, then also as `msh`; a zip
     * for mesh-complete and foam), `fileName` a name for it. With `family`
     * N > 1 (a mesh-independence family, `ratio`, `familyLayers`): `file` is
     * a zip "mesh-family.zip" of the N meshes (mesh_k.<ext>) and the table
     * (family.csv, family.json), `family` the table ({members, ratio,
     * layers, unit, rows}) and `familyCsv` its CSV; the report, surface and
     * volume are the first member's. `handle`: the mesh (a family: its
     * first member, with the table), for export and report (option
     * `mesh`); it becomes this API's newest mesh, which they use when given
     * none. The newest before it is freed as the job starts, unless kept
     * (keep()).
     * @returns {{ok: true, file: Uint8Array, fileName: string, format: string,
     *   msh?: Uint8Array, report: object, surface: object, volume?: object,
     *   handle: object} | {ok: false, error: string}} (no volume when surfaceOnly)
     */
    mesh(bytesIn, { onProgress, ...options } = {}) {
      const { bytes, progress, failed } = jobInput('mesh', bytesIn, onProgress);
      if (failed) return failed;
      return guard('mesh', () => {
        handles.retire('mesh');
        const raw = core.mesh(bytes, options, progress);
        if (!raw.ok) return failure(raw);
        return withSurface(raw, {
          handle: handles.issue('mesh', raw.handle),
          file: raw.file,
          fileName: raw.fileName,
          format: raw.format,
          ...(raw.format === 'msh' && { msh: raw.file }),
          report: JSON.parse(raw.reportJson),
          ...(raw.volume && { volume: raw.volume }),
          ...(raw.familyJson && { family: JSON.parse(raw.familyJson), familyCsv: raw.familyCsv }),
        });
      });
    },

    /**
     * The methods report of a mesh (`mesh`: its handle; default this API's
     * newest mesh; after a family: its first member, and the family's
     * table): one offline HTML page with pictures,
     * quality histograms, parameters, openings, repairs, provenance and a
     * paragraph for a paper's methods section. `images`: the pictures
     * ([{title, alt, png: Uint8Array}], e.g. the page's views); without
     * them, views rendered by the core without a GPU. `inputName`: the
     * input file's name, shown in the report.
     * @returns {{ok: true, file: Uint8Array, fileName: string}
     *   | {ok: false, error: string}}
     */
    report({ mesh, images, inputName } = {}) {
      if (images !== undefined && !Array.isArray(images)) return fail('report: images must be an array');
      const { handle, failed } = handles.pick('mesh', mesh, 'report', 'no report yet: mesh a surface first');
      if (failed) return failed;
      return guard('report', () => answer(core.methodsReport(handle, { ...(images && { images }), ...(inputName && { inputName }) })));
    },

    /**
     * A mesh in another format, without meshing again (`mesh`: its handle;
     * default this API's newest mesh):
     * 'msh' | 'vtu' | 'vtp' | 'stl' | 'mesh-complete' (a zip of the
     * folder) | 'foam' (a zip of the OpenFOAM case: constant/polyMesh,
     * system/controlDict, case.foam), with mshVersion and outputUnits as in
     * mesh() (outputUnits 'm' for OpenFOAM's solvers).
     * @returns {{ok: true, file: Uint8Array, fileName: string, format: string}
     *   | {ok: false, error: string}}
     */
    export(format, { mesh, ...options } = {}) {
      const { handle, failed } = handles.pick('mesh', mesh, 'export', 'nothing to export: mesh a surface first');
      if (failed) return failed;
      return guard('export', () => answer(core.exportMesh(handle, { ...options, format })));
    },

    /**
     * The cut across the vessel at the point of an analyzed surface
     * (`analysis`: its handle; default this API's newest analysis) nearest
     * `point` ([x, y, z]): perpendicular to the vessel, through the centre
     * of its section, the normal toward the side with less surface (the
     * side a cut by clipPlanes [...point, ...normal] removes).
     * @returns {{ok: true, point: number[], normal: number[], radius: number,
     *   areaRemoved: number} | {ok: false, error: string}}
     */
    cutAt(point, { analysis } = {}) {
      const { handle, failed } = handles.pick('analysis', analysis, 'cutAt', NOTHING_ANALYZED);
      if (failed) return failed;
      return guard('cutAt', () => {
        const raw = core.cutAt(handle, Array.from(point ?? []));
        return raw.ok ? { ...raw, point: Array.from(raw.point), normal: Array.from(raw.normal) } : failure(raw);
      });
    },

    /**
     * The group names the openings of an analyzed surface (`analysis`: its
     * handle; default this API's newest analysis) get with these mesh
     * options (`names`, `inlet`), as mesh() would name them, or the error
     * mesh() would give (a bad or repeated name).
     * @returns {{ok: true, names: string[]} | {ok: false, error: string}}
     */
    openingNames({ analysis, ...options } = {}) {
      const { handle, failed } = handles.pick('analysis', analysis, 'openingNames', NOTHING_ANALYZED);
      if (failed) return failed;
      return guard('openingNames', () => answer(core.openingNames(handle, options)));
    },

    /**
     * The size field mesh() would remesh an analyzed surface (`analysis`:
     * its handle; default this API's newest analysis) with, before
     * meshing: at each vertex of that surface (its positions and
     * triangles, as analyze() gave them) the local vessel radius R and the
     * edge length h the size options ask for (perCircumference or size,
     * sizeMin, sizeMax, curvature, gradation, refine), in the model's
     * `unit`; or the error mesh() would give for these options.
     * @returns {{ok: true, positions: Float32Array, triangles: Uint32Array,
     *   radius: Float32Array, size: Float32Array, unit: string}
     *   | {ok: false, error: string}}
     */
    sizeField({ analysis, ...options } = {}) {
      const { handle, failed } = handles.pick('analysis', analysis, 'sizeField', NOTHING_ANALYZED);
      if (failed) return failed;
      return guard('sizeField', () => answer(core.sizeField(handle, options)));
    },

    /**
     * Keeps a result's `handle` (of analyze() or mesh()) alive when a newer
     * job replaces it as this API's newest, until release(handle): to use
     * two meshes or analyses at once. Without keep(), only the newest of
     * each kind is held, so a long session does not grow.
     * @returns {{ok: true} | {ok: false, error: string}}
     */
    keep(handle) {
      return handles.keep(handle);
    },

    /**
     * Frees a result's `handle` now (its surface or mesh in the module's
     * memory); calls given it then refuse, and if it was the newest of its
     * kind, calls given no handle refuse until the next job. Releasing
     * twice is nothing.
     * @returns {{ok: true} | {ok: false, error: string}}
     */
    release(handle) {
      return handles.release(handle);
    },

    /**
     * The cumulative height fractions of the boundary layer's layers for
     * these options (`layers`, `growth`): layers + 1 values from 0 to 1, the
     * first layer's height being fractions[1] times the total thickness.
     * @returns {{ok: true, fractions: Float64Array} | {ok: false, error: string}}
     */
    layerFractions(options = {}) {
      return guard('layerFractions', () => answer(core.layerFractions(options)));
    },

    /**
     * Generates a synthetic segmentation-like vessel surface as binary STL;
     * a labelled kind ('outlets') also as VTK XML PolyData with its face
     * labels (ModelFaceID), `vtp`.
     * @returns {{ok: true, stl: Uint8Array, vtp?: Uint8Array} | {ok: false, error: string}}
     */
    makePhantom(options = {}) {
      return guard('makePhantom', () => answer(core.makePhantom(options)));
    },
  };
}
