// <vessel-mesher>: the mesher as a custom element, for embedding in any page
// (documentation, a host app) from a plain <script type="module">. Its UI
// lives in a shadow root, so the host page's CSS cannot reach it. Each
// element has its own worker (wasm/src/client.js), started from the script
// next to this module: same origin as the page when the page serves the
// package itself.
//
// Contract:
//   attributes  src      URL of a surface file to load (on connect and on change)
//               options  JSON of the JS API's mesh options (docs/options.md)
//               compact  present: viewer + Mesh + Export only
//               report   present: a "Download report" button once meshed
//   methods     load(fileOrBytes)  File | Blob | ArrayBuffer | typed array | URL
//                                  -> Promise of the analysis (rejects with the
//                                  reason when the surface cannot be read)
//               mesh(options?)     -> Promise of the JS API's mesh result
//                                  ({ ok, file, msh, report, surface, ... } or
//                                  { ok: false, error }); options override
//                                  the `options` attribute; with `family` N > 1
//                                  a mesh-independence family (the result's
//                                  `family` its table, `file` the zip)
//               export(format)     -> Promise of a Blob of the last mesh in
//                                  'msh' | 'vtu' | 'vtp' | 'stl' | 'mesh-complete'
//                                  (after a family, in its format: the zip)
//               report()           -> Promise of a Blob (text/html) of the methods
//                                  report of the last mesh, with the pictures
//                                  drawn by the element's view
//   events      vm-analyzed  detail: the analysis
//               vm-progress  detail: { fraction, stage }
//               vm-meshed    detail: the mesh result
//               vm-error     detail: { message }
// Events bubble and cross the shadow boundary (composed).
import { VesselmeshClient } from '../../../wasm/src/client.js';
import { withPrismsSplit } from '../prisms.js';
import { captureReportViews } from '../report-views.js';
import { Viewer } from '../viewer.js';
import { VolumeView } from '../volume-view.js';

const FORMATS = ['msh', 'vtu', 'vtp', 'stl', 'mesh-complete'];
const MIME = { msh: 'text/plain', vtu: 'application/xml', vtp: 'application/xml', stl: 'model/stl', 'mesh-complete': 'application/zip' };

/** Whether MSH bytes (or text) are Gmsh's binary layout (header line "4.1 1 8"). */
function isBinaryMsh(file) {
  const head = typeof file === 'string' ? file.slice(0, 24) : new TextDecoder().decode(file.subarray(0, 24));
  return /^\$MeshFormat\r?\n\S+ 1 /.test(head);
}

const STYLE = `
:host { display: block; position: relative; min-height: 320px; height: 420px; border: 1px solid #c9d2dc;
  border-radius: 6px; overflow: hidden; font: 14px/1.4 system-ui, sans-serif; color: #17212b; background: #e9edf1;
  contain: content; }
:host([hidden]) { display: none; }
.view { position: absolute; inset: 0; }
.view canvas { display: block; width: 100%; height: 100%; }
/* Inherited properties (color, font) would come from the host page: set here. */
.bar { position: absolute; left: 0; right: 0; bottom: 0; display: flex; flex-wrap: wrap; gap: 6px; align-items: center;
  padding: 6px 8px; background: rgba(255, 255, 255, 0.9); border-top: 1px solid #c9d2dc;
  font: 14px/1.4 system-ui, sans-serif; color: #17212b; text-align: left; letter-spacing: normal; }
button, select { font: inherit; padding: 4px 10px; border: 1px solid #9aa8b6; border-radius: 4px; background: #fff;
  color: #17212b; cursor: pointer; }
button.primary { background: #1d5fae; border-color: #1d5fae; color: #fff; }
button:disabled { opacity: 0.5; cursor: default; }
button:focus-visible, select:focus-visible { outline: 2px solid #1d5fae; outline-offset: 2px; }
.status { flex: 1 1 12em; min-width: 0; overflow: hidden; text-overflow: ellipsis; white-space: nowrap; }
.status.error { color: #a11a1a; }
progress { width: 6em; }
:host([compact]) .full { display: none; }
:host(:not([report])) .report { display: none; }
`;

const TEMPLATE = `
<style>${STYLE}</style>
<div class="view" part="view"></div>
<div class="bar" part="bar">
  <button type="button" class="full" data-act="open">Open…</button>
  <input type="file" hidden accept=".stl,.vtp,.vtk,.obj,.ply,.gz" />
  <button type="button" class="primary" data-act="mesh" disabled>Mesh</button>
  <select class="full" aria-label="Export format">${FORMATS.map((f) => `<option value="${f}">${f}</option>`).join('')}</select>
  <button type="button" data-act="export" disabled>Export</button>
  <button type="button" class="report" data-act="report" hidden>Download report</button>
  <progress max="1" value="0" hidden></progress>
  <span class="status" role="status" aria-live="polite"></span>
</div>`;

/** Uint8Array of what load() accepts; a string is a URL. */
async function toBytes(input) {
  if (typeof input === 'string' || input instanceof URL) {
    const response = await fetch(input);
    if (!response.ok) throw new Error(`cannot load ${input}: HTTP ${response.status}`);
    return { bytes: new Uint8Array(await response.arrayBuffer()), name: String(input).split(/[/?#]/).filter(Boolean).pop() || 'surface' };
  }
  if (input instanceof Blob) return { bytes: new Uint8Array(await input.arrayBuffer()), name: input.name || 'surface' };
  if (input instanceof ArrayBuffer) return { bytes: new Uint8Array(input), name: 'surface' };
  if (ArrayBuffer.isView(input)) {
    return { bytes: new Uint8Array(input.buffer, input.byteOffset, input.byteLength), name: 'surface' };
  }
  throw new TypeError('load: give a File, Blob, ArrayBuffer, typed array or URL');
}

export class VesselMesher extends HTMLElement {
  static observedAttributes = ['src'];

  constructor() {
    super();
    this.attachShadow({ mode: 'open' }).innerHTML = TEMPLATE;
    const $ = (s) => this.shadowRoot.querySelector(s);
    this._ui = {
      view: $('.view'),
      file: $('input[type=file]'),
      mesh: $('[data-act=mesh]'),
      format: $('select'),
      export: $('[data-act=export]'),
      report: $('[data-act=report]'),
      progress: $('progress'),
      status: $('.status'),
    };
    $('[data-act=open]').addEventListener('click', () => this._ui.file.click());
    this._ui.file.addEventListener('change', () => {
      const file = this._ui.file.files[0];
      if (file) this.load(file).catch(() => {});
    });
    this._ui.mesh.addEventListener('click', () => this.mesh());
    this._ui.export.addEventListener('click', () => this._download(this._ui.format.value));
    this._ui.report.addEventListener('click', () => this._downloadReport());
    this._client = null;
    this._viewer = null;
    this._input = null; // { bytes, name }
    this._result = null; // the last mesh result
  }

  connectedCallback() {
    if (!this._client) this._client = new VesselmeshClient();
    if (!this._viewer) this._viewer = new Viewer(this._ui.view);
    const src = this.getAttribute('src');
    if (src && !this._input) this.load(src).catch(() => {});
  }

  disconnectedCallback() {
    // A new worker on reconnection holds no mesh: export() needs a new one.
    this._client?.dispose();
    this._client = null;
    this._result = null;
    this._ui.export.disabled = true;
    this._ui.report.hidden = true;
  }

  attributeChangedCallback(name, old, value) {
    if (name === 'src' && value && old !== null && value !== old && this.isConnected) this.load(value).catch(() => {});
  }

  /** The `options` attribute as an object ({} when absent). */
  get meshOptions() {
    const text = this.getAttribute('options');
    if (!text) return {};
    const options = JSON.parse(text);
    if (options === null || typeof options !== 'object' || Array.isArray(options)) {
      throw new Error('the options attribute must be a JSON object');
    }
    return options;
  }

  /** Reads and analyzes a surface; resolves with its analysis. */
  async load(fileOrBytes) {
    this._ensureClient();
    this._result = null;
    this._ui.export.disabled = true;
    this._ui.report.hidden = true;
    this._status('reading…');
    let input;
    try {
      input = await toBytes(fileOrBytes);
    } catch (e) {
      throw this._fail(e.message);
    }
    const result = await this._client.analyze(input.bytes, { onProgress: (f, s) => this._progress(f, s) });
    this._progress(null);
    if (!result.ok) throw this._fail(`${input.name}: ${result.error}`);
    this._input = input;
    this._viewer.setSurface(result.surface);
    this._ui.mesh.disabled = false;
    const a = result.analysis;
    this._status(`${input.name}: ${a.openings?.length ?? 0} openings — press Mesh`);
    this._emit('vm-analyzed', result.analysis);
    return result.analysis;
  }

  /** Meshes the loaded surface; resolves with the JS API's mesh result. */
  async mesh(options = {}) {
    this._ensureClient();
    if (!this._input) {
      const error = 'nothing to mesh: load a surface first (src attribute or load())';
      this._fail(error);
      return { ok: false, error };
    }
    let merged;
    try {
      merged = { ...this.meshOptions, ...options };
    } catch (e) {
      this._fail(e.message);
      return { ok: false, error: e.message };
    }
    this._ui.mesh.disabled = true;
    this._status('meshing…');
    const result = await this._client.mesh(this._input.bytes, {
      ...merged,
      onProgress: (fraction, stage) => this._progress(fraction, stage),
    });
    this._progress(null);
    this._ui.mesh.disabled = false;
    if (!result.ok) {
      this._fail(result.error);
      return result;
    }
    this._result = result;
    this._viewer.setSurface(result.surface, { fit: false });
    this._ui.export.disabled = false;
    this._ui.report.hidden = false;
    const tets = result.volume ? result.volume.tets.length / 4 : 0;
    const triangles = result.report.output?.triangles ?? 0;
    const family = result.family ? `; a family of ${result.family.members} meshes (Export: a zip)` : '';
    const counts = `${triangles.toLocaleString('en')} wall triangles, ${tets.toLocaleString('en')} tetrahedra`;
    this._status(`meshed: ${counts}${family}`);
    this._emit('vm-meshed', result);
    return result;
  }

  /** The last mesh as a Blob in a format (default: the one it was meshed in). */
  async export(format = this._result?.format ?? 'msh') {
    if (!this._result) throw this._fail('nothing to export: mesh first');
    let file = this._result.format === format ? this._result.file : null;
    // A family's file is the zip of its meshes.
    const zip = file && this._result.family;
    if (!file) {
      const result = await this._client.export(format, { mesh: this._result.handle });
      if (!result.ok) throw this._fail(result.error);
      file = result.file;
    }
    // A binary MSH (meshed with mshBinary) says so in its header: "4.1 1 8".
    const binary = format === 'msh' && isBinaryMsh(file);
    const type = zip ? 'application/zip' : binary ? 'application/octet-stream' : MIME[format];
    return new Blob([file], { type: type ?? 'application/octet-stream' });
  }

  /** The methods report of the last mesh as a Blob (text/html): the pictures
   * are the element's view's (or, if it cannot draw them, the core's). */
  async report() {
    if (!this._result) throw this._fail('nothing to report on: mesh first');
    const result = this._result;
    const viewer = this._viewer;
    const images = await captureReportViews({
      viewer,
      volumeView: new VolumeView(viewer),
      result: { ...result, volume: withPrismsSplit(result.volume) },
      restore: () => viewer.setSurface(result.surface, { fit: false }),
    }).catch(() => undefined);
    const made = await this._client.report({ ...(images && { images }), inputName: this._input.name, mesh: result.handle });
    if (!made.ok) throw this._fail(made.error);
    return new Blob([made.file], { type: 'text/html' });
  }

  async _download(format) {
    try {
      const blob = await this.export(format);
      const a = document.createElement('a');
      a.href = URL.createObjectURL(blob);
      const base = this._baseName();
      const family = this._result.family && format === this._result.format;
      a.download = family ? `${base}-mesh-family.zip` : `${base}.${format === 'mesh-complete' ? 'zip' : format}`;
      a.click();
      setTimeout(() => URL.revokeObjectURL(a.href), 10_000);
    } catch {
      // reported by export() (vm-error, status line)
    }
  }

  async _downloadReport() {
    this._ui.report.disabled = true;
    this._status('writing the report…');
    try {
      const blob = await this.report();
      const a = document.createElement('a');
      a.href = URL.createObjectURL(blob);
      a.download = `${this._baseName()}-report.html`;
      a.click();
      setTimeout(() => URL.revokeObjectURL(a.href), 10_000);
      this._status(`report: ${a.download}`);
    } catch {
      // reported by report() (vm-error, status line)
    } finally {
      this._ui.report.disabled = false;
    }
  }

  _baseName() {
    return this._input.name.replace(/\.[^.]*$/, '');
  }

  _ensureClient() {
    if (!this._client) this._client = new VesselmeshClient();
    if (!this._viewer) this._viewer = new Viewer(this._ui.view);
  }

  _progress(fraction, stage) {
    const bar = this._ui.progress;
    bar.hidden = fraction === null;
    if (fraction === null) return;
    bar.value = fraction;
    this._status(`${stage} ${Math.round(fraction * 100)}%`);
    this._emit('vm-progress', { fraction, stage });
  }

  _status(text, error = false) {
    this._ui.status.textContent = text;
    this._ui.status.classList.toggle('error', error);
  }

  /** Reports an error (status line, vm-error); returns it as an Error. */
  _fail(message) {
    this._status(message, true);
    this._emit('vm-error', { message });
    return new Error(message);
  }

  _emit(type, detail) {
    this.dispatchEvent(new CustomEvent(type, { detail, bubbles: true, composed: true }));
  }
}

if (!customElements.get('vessel-mesher')) customElements.define('vessel-mesher', VesselMesher);
