// The vesselmesh JavaScript API over the WebAssembly core: validates inputs,
// applies defaults, parses the JSON reports and maps every failure to
// { ok: false, error } (nothing throws for a user error).
import createVesselmeshCore from '../dist/vesselmesh_core.mjs';

const PHANTOM_KINDS = ['tube', 'bifurcation', 'aneurysm', 'torus'];
const MSH_VERSIONS = ['4.1', '2.2'];

const fail = (error) => ({ ok: false, error });

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

async function loadWasmBinary() {
  const url = new URL('../dist/vesselmesh_core.wasm', import.meta.url);
  const response = await fetch(url);
  if (!response.ok) throw new Error(`cannot load ${url}: HTTP ${response.status}`);
  return response.arrayBuffer();
}

/** JS mesh option name -> core option name (vesselmesh CLI flag). */
const MESH_OPTIONS = {
  size: 'size',
  perCircumference: 'per-circumference',
  sizeMin: 'size-min',
  sizeMax: 'size-max',
  gradation: 'gradation',
  curvature: 'curvature',
  param: 'param',
  mesher2d: 'mesher2d',
  featureAngle: 'feature-angle',
  fidelity: 'fidelity',
  inlet: 'inlet',
  coreSize: 'core-size',
  layers: 'layers',
  layerThickness: 'layer-thickness',
  firstLayer: 'first-layer',
  growth: 'growth',
  wallThickness: 'wall-thickness',
  wallLayers: 'wall-layers',
};
/** Core flag -> JS option, for error messages (the core speaks CLI). */
const JS_NAMES = {
  ...Object.fromEntries(Object.entries(MESH_OPTIONS).map(([js, core]) => [core, js])),
  'msh-version': 'mshVersion',
  'largest-component': 'largestComponentOnly',
  'surface-only': 'surfaceOnly',
  'tag-layer': 'tagLayer',
  prisms: 'prisms',
};

/** A core error message in the JS API's words. */
const jsMessage = (message) =>
  message
    .replace(/--([a-z0-9-]+)/g, (m, flag) => JS_NAMES[flag] ?? m)
    .replace(/`vesselmesh info`/g, 'analysis.openings');

/**
 * Loads the WebAssembly module and returns the API.
 * @param {{ wasmBinary?: ArrayBuffer|Uint8Array }} [options] In Node pass
 *   wasmBinary (fs.readFileSync of wasm/dist/vesselmesh_core.wasm); in the
 *   browser it is fetched next to this module.
 */
export async function createVesselmesh({ wasmBinary } = {}) {
  const binary = wasmBinary ?? (await loadWasmBinary());
  const core = await createVesselmeshCore({ wasmBinary: binary });

  const withSurface = (raw, extra) => ({ ok: true, ...extra, surface: raw.surface });

  return {
    version: core.version(),

    /**
     * Reads, welds, repairs and analyzes an STL.
     * @returns {{ok: true, analysis: object, surface: {positions: Float32Array,
     *   triangles: Uint32Array, quality: Float32Array}} | {ok: false, error: string}}
     */
    analyze(stlBytes, { onProgress } = {}) {
      const bytes = asBytes(stlBytes);
      if (!bytes) return fail('analyze: the input must be a Uint8Array or ArrayBuffer');
      const progress = progressCallback(onProgress);
      if (progress === null) return fail('analyze: onProgress must be a function');
      const raw = core.analyze(bytes, progress);
      if (!raw.ok) return { ok: false, error: raw.error, ...(raw.cancelled && { cancelled: true }) };
      return withSurface(raw, { analysis: JSON.parse(raw.analysisJson) });
    },

    /**
     * Meshes an STL: remeshes the surface by conformal maps (unless
     * remesh is false), caps the openings and fills the lumen with
     * tetrahedra (unless surfaceOnly), and returns the MSH file bytes, the
     * report, the wall surface and the volume: { positions, tets,
     * tetQuality (gamma_t), tetRegion, triangles, triangleTag, surfaceNames
     * (per tag: 'wall', 'inlet', 'outlet_1'...), regionNames }. `inlet`
     * (1-based, the analysis' opening order) picks the inlet; `coreSize`
     * caps the size in the core. Boundary layers: `layers` (default 4, 0:
     * none), `layerThickness` (fraction of the local radius, default 0.2)
     * or `firstLayer` (height) with `growth`; the vessel wall:
     * `wallThickness` (fraction of R, e.g. 0.1), `wallLayers` (default 4);
     * `tagLayer` makes the viscous layer its own region `boundary_layer`.
     * volume.tetPart tells each tet's part: 0 core, 1 viscous layer, 2 wall.
     * `prisms: true` keeps the layers' prisms: volume.prisms (6 a prism, 0-1-2
     * then 3-4-5 above them), prismRegion, and their faces at the openings
     * volume.quads (4 a quad) with quadTag; the tets are then the core's.
     * Size: `size` (uniform h) or `perCircumference` (h = 2 pi R / N, the
     * default with N = 20), clamps `sizeMin` / `sizeMax`, `gradation`,
     * `curvature`, `featureAngle` (degrees; sharper creases are kept, 180:
     * none), `fidelity` (default 0.1: input vertices farther than 0.1 h from
     * the wall get a wall vertex pinned onto them and a finer size around
     * them where quality and size allow; 0: none, bumps are smoothed over);
     * advanced: `param` ('lscm' | 'harmonic' | 'floater'),
     * `mesher2d` ('frontal' | 'delaunay' | 'adapt').
     * @returns {{ok: true, msh: Uint8Array, report: object, surface: object,
     *   volume?: object} | {ok: false, error: string}} (no volume when
     *   surfaceOnly)
     */
    mesh(
      stlBytes,
      {
        mshVersion = '4.1',
        largestComponentOnly = false,
        remesh = true,
        surfaceOnly = false,
        tagLayer = false,
        prisms = false,
        onProgress,
        ...rest
      } = {},
    ) {
      const bytes = asBytes(stlBytes);
      if (!bytes) return fail('mesh: the input must be a Uint8Array or ArrayBuffer');
      if (!MSH_VERSIONS.includes(mshVersion)) {
        return fail(`mesh: unknown mshVersion '${mshVersion}' (use 4.1 or 2.2)`);
      }
      for (const [name, value] of [
        ['largestComponentOnly', largestComponentOnly],
        ['remesh', remesh],
        ['surfaceOnly', surfaceOnly],
        ['tagLayer', tagLayer],
        ['prisms', prisms],
      ]) {
        if (typeof value !== 'boolean') return fail(`mesh: ${name} must be true or false`);
      }
      const options = {
        'msh-version': mshVersion,
        largestComponentOnly,
        remesh,
        surfaceOnly,
        tagLayer,
        prisms,
      };
      for (const [name, value] of Object.entries(rest)) {
        const coreName = MESH_OPTIONS[name];
        if (!coreName) return fail(`mesh: unknown option '${name}'`);
        if (value === undefined) continue;
        const isText = typeof value === 'string';
        if (!isText && (typeof value !== 'number' || !Number.isFinite(value))) {
          return fail(`mesh: ${name} must be a finite number or a string`);
        }
        options[coreName] = String(value);
      }
      const progress = progressCallback(onProgress);
      if (progress === null) return fail('mesh: onProgress must be a function');
      const raw = core.mesh(bytes, options, progress);
      if (!raw.ok) {
        // Core messages name CLI flags (--size); name the JS option instead.
        return { ok: false, error: jsMessage(raw.error), ...(raw.cancelled && { cancelled: true }) };
      }
      return withSurface(raw, {
        msh: raw.msh,
        report: JSON.parse(raw.reportJson),
        ...(raw.volume && { volume: raw.volume }),
      });
    },

    /**
     * Generates a synthetic segmentation-like vessel surface as binary STL.
     * @returns {{ok: true, stl: Uint8Array} | {ok: false, error: string}}
     */
    makePhantom({
      kind = 'bifurcation',
      voxel = 0.08,
      openEnds = true,
      noise = 0.3,
      seed = 1,
      scale = 1,
    } = {}) {
      if (!PHANTOM_KINDS.includes(kind)) {
        return fail(`makePhantom: unknown kind '${kind}' (${PHANTOM_KINDS.join(', ')})`);
      }
      for (const [name, value] of [['voxel', voxel], ['scale', scale]]) {
        if (typeof value !== 'number' || !(value > 0) || !Number.isFinite(value)) {
          return fail(`makePhantom: ${name} must be a positive number`);
        }
      }
      if (typeof noise !== 'number' || !(noise >= 0)) {
        return fail('makePhantom: noise must be a non-negative number');
      }
      if (!Number.isInteger(seed) || seed < 0 || seed > 0xffffffff) {
        return fail('makePhantom: seed must be an unsigned 32-bit integer');
      }
      return core.makePhantom(kind, voxel, Boolean(openEnds), noise, seed, scale);
    },
  };
}
