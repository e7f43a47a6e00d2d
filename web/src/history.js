// Undo and redo of the preparation: a list of states (plain JSON-able
// objects) with the one shown, and what changed from one to the next, for
// the buttons' names. Pure (tested in Node); prep-history.js takes and puts
// back the page's states.

const same = (a, b) => JSON.stringify(a) === JSON.stringify(b);

export class UndoHistory {
  /** @param {number} limit the most states kept (the oldest dropped) */
  constructor(limit = 100) {
    this.limit = limit;
    this.states = [];
    this.index = -1;
  }

  /** Starts again from `state` alone (a new file). */
  start(state) {
    this.states = [state];
    this.index = 0;
  }

  /** The state shown, or undefined before start. */
  get current() {
    return this.states[this.index];
  }

  get canUndo() {
    return this.index > 0;
  }

  get canRedo() {
    return this.index < this.states.length - 1;
  }

  /** Records `state` after the shown one (the states undone are dropped);
   * false when it is the shown state again (nothing recorded). */
  push(state) {
    if (this.index < 0) {
      this.start(state);
      return true;
    }
    if (same(state, this.current)) return false;
    this.states.splice(this.index + 1, Infinity, state);
    this.index++;
    if (this.states.length > this.limit) {
      this.states.splice(0, this.states.length - this.limit);
      this.index = this.states.length - 1;
    }
    return true;
  }

  /** Steps back: the state to show, or undefined when there is none. */
  undo() {
    if (!this.canUndo) return undefined;
    return this.states[--this.index];
  }

  /** Steps forward: the state to show, or undefined when there is none. */
  redo() {
    if (!this.canRedo) return undefined;
    return this.states[++this.index];
  }

  /** What undo would change back ('' when nothing), by prepChange(). */
  undoLabel() {
    return this.canUndo ? prepChange(this.states[this.index - 1], this.current) : '';
  }

  /** What redo would change again ('' when nothing). */
  redoLabel() {
    return this.canRedo ? prepChange(this.current, this.states[this.index + 1]) : '';
  }
}

// What a preparation state holds, and how a change of it is named.
const PARTS = [
  ['units', (s) => s.prep?.units],
  ['caps', (s) => s.prep?.keepCaps],
  ['components', (s) => s.prep?.largestComponentOnly],
  ['smoothing', (s) => s.prep?.smooth],
  ['repair', (s) => [s.prep?.repair, s.prep?.holeFraction]],
  ['cuts', (s) => [s.prep?.clipPlanes, s.cuts, s.fromProposals]],
  ['inlet', (s) => s.openings?.inlet],
  ['opening names', (s) => s.openings?.names],
  ['flow extensions', (s) => [s.openings?.flowAll, s.openings?.extensions]],
];
const OPENING_PARTS = new Set(['inlet', 'opening names', 'flow extensions']);

/**
 * What differs between two preparation states ({prep: the analyze options,
 * cuts, fromProposals, openings: {names, inlet, flowAll, extensions}}), as
 * words: 'units', 'cuts and inlet', '' when nothing.
 */
export function prepChange(a, b) {
  // Other openings (the surface was cut otherwise): their choices follow.
  const sameOpenings = (a?.openings?.names?.length ?? 0) === (b?.openings?.names?.length ?? 0);
  const changed = PARTS.filter(([name, get]) => (sameOpenings || !OPENING_PARTS.has(name)) && !same(get(a ?? {}), get(b ?? {})))
    .map(([name]) => name);
  if (changed.length <= 1) return changed[0] ?? '';
  return `${changed.slice(0, -1).join(', ')} and ${changed.at(-1)}`;
}
