// The handles of the JS API (vesselmesh.js). analyze() and mesh() give
// their result's `handle`: an Embind object of the core (class Analysis or
// Mesh) that owns the analyzed surface or the mesh in the module's memory.
// The calls on an analysis (openingNames, cutAt, sizeField) or on a mesh
// (export, report) take one, or act on the API's newest of that kind: the
// API's default, kept here on the JS side (the binding holds no state).
// When a newer job replaces the newest, the replaced one is freed, unless
// the caller kept it (keep()); release() frees one at once. The worker
// (worker.js) gives its client ids of these handles instead.

/** What to do again when a handle of a kind is gone. */
const AGAIN = { analysis: 'analyze the surface again', mesh: 'mesh again' };

/** A refusal as the core words its own: a bad input. */
export const refusal = (error) => ({ ok: false, error, kind: 'bad_input' });

/** Why `call` cannot use a freed handle of `kind`. */
export const releasedError = (call, kind) =>
  `${call}: this ${kind} was released (by release(), or freed when a newer ${kind} replaced it as the newest without keep()): ${AGAIN[kind]}`;

/** Why `call` cannot use a handle of a restarted worker (worker.js). */
export const restartedError = (call, kind) =>
  `${call}: this ${kind} was made by a mesher worker since restarted (cancel()): ${AGAIN[kind]}`;

/** The handles one API object issued: which are live, which are kept, and
 * the newest of each kind. */
export class HandleRegistry {
  #issued = { analysis: new WeakSet(), mesh: new WeakSet() };
  #kept = new WeakSet();
  #newest = { analysis: null, mesh: null };

  /** Before a job of `kind`: its newest is no longer the default, and is
   * freed unless kept (its memory, before the job needs more). */
  retire(kind) {
    const handle = this.#newest[kind];
    this.#newest[kind] = null;
    if (handle && !this.#kept.has(handle) && !handle.isDeleted()) handle.delete();
  }

  /** After a job of `kind`: `handle` is its newest. */
  issue(kind, handle) {
    this.#issued[kind].add(handle);
    this.#newest[kind] = handle;
    return handle;
  }

  /** The kind ('analysis' or 'mesh') of a handle issued here, or null. */
  kindOf(handle) {
    for (const kind of ['analysis', 'mesh']) if (this.#issued[kind].has(handle)) return kind;
    return null;
  }

  /**
   * The live handle of `kind` that `call` acts on: `given` (the options'
   * key `kind`), or without one the newest; else {failed}: `none` when
   * there is no newest, or why the given one is unusable.
   */
  pick(kind, given, call, none) {
    const handle = given ?? this.#newest[kind];
    if (!handle) return { failed: refusal(none) };
    if (!this.#issued[kind].has(handle)) {
      return {
        failed: {
          ok: false,
          error: `${call}: ${kind} must be the handle of a ${kind} of this API (the \`handle\` of ${kind === 'mesh' ? 'mesh()' : 'analyze()'}'s result), not ${describe(handle)}`,
          kind: 'bad_option',
          option: kind,
        },
      };
    }
    if (handle.isDeleted()) return { failed: refusal(releasedError(call, kind)) };
    return { handle };
  }

  /** The caller keeps `handle`: a newer job does not free it; release() does. */
  keep(handle) {
    const kind = this.kindOf(handle);
    if (!kind) return notHandle('keep', handle);
    if (handle.isDeleted()) return refusal(releasedError('keep', kind));
    this.#kept.add(handle);
    return { ok: true };
  }

  /** Frees `handle` now (again: nothing); the newest of its kind then is none. */
  release(handle) {
    const kind = this.kindOf(handle);
    if (!kind) return notHandle('release', handle);
    if (this.#newest[kind] === handle) this.#newest[kind] = null;
    if (!handle.isDeleted()) handle.delete();
    return { ok: true };
  }
}

/** A value in a message: its type, or the text of a short string or number. */
function describe(value) {
  if (value === null) return 'null';
  if (typeof value === 'number' || (typeof value === 'string' && value.length <= 40)) return JSON.stringify(value);
  return typeof value === 'object' ? 'another object' : `a ${typeof value}`;
}

function notHandle(call, value) {
  return {
    ok: false,
    error: `${call}: give the \`handle\` of an analyze() or mesh() result of this API, not ${describe(value)}`,
    kind: 'bad_input',
  };
}
