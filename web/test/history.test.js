// Node tests of the preparation's undo history (web/src/history.js): the
// stack's moves, the states undone dropped by a new change, the limit, and
// the names of what changed.
import assert from 'node:assert/strict';
import { describe, test } from 'node:test';

import { prepChange, UndoHistory } from '../src/history.js';

const state = (over = {}) => ({
  prep: {},
  cuts: [],
  fromProposals: false,
  openings: { names: ['', ''], inlet: 1, flowAll: '0', extensions: ['0', '0'] },
  ...over,
});

describe('UndoHistory', () => {
  test('undo and redo walk the recorded states, and stop at the ends', () => {
    const h = new UndoHistory();
    assert.equal(h.current, undefined);
    assert.equal(h.canUndo, false);
    h.start({ n: 0 });
    assert.equal(h.push({ n: 1 }), true);
    assert.equal(h.push({ n: 2 }), true);
    assert.deepEqual(h.current, { n: 2 });
    assert.deepEqual(h.undo(), { n: 1 });
    assert.deepEqual(h.undo(), { n: 0 });
    assert.equal(h.undo(), undefined);
    assert.deepEqual(h.current, { n: 0 });
    assert.deepEqual(h.redo(), { n: 1 });
    assert.deepEqual(h.redo(), { n: 2 });
    assert.equal(h.redo(), undefined);
    assert.equal(h.canRedo, false);
  });

  test('the same state again is not recorded', () => {
    const h = new UndoHistory();
    h.start({ a: [1, 2] });
    assert.equal(h.push({ a: [1, 2] }), false);
    assert.equal(h.states.length, 1);
    assert.equal(h.canUndo, false);
  });

  test('a change after undo drops the states undone', () => {
    const h = new UndoHistory();
    h.start('a');
    h.push('b');
    h.push('c');
    h.undo();
    h.undo();
    h.push('d');
    assert.deepEqual(h.states, ['a', 'd']);
    assert.equal(h.canRedo, false);
    assert.equal(h.undo(), 'a');
  });

  test('push before start starts', () => {
    const h = new UndoHistory();
    assert.equal(h.push('x'), true);
    assert.equal(h.current, 'x');
    assert.equal(h.canUndo, false);
  });

  test('beyond the limit the oldest states are dropped', () => {
    const h = new UndoHistory(3);
    h.start(0);
    for (let i = 1; i <= 5; i++) h.push(i);
    assert.deepEqual(h.states, [3, 4, 5]);
    assert.equal(h.current, 5);
    assert.equal(h.undo(), 4);
    assert.equal(h.undo(), 3);
    assert.equal(h.undo(), undefined);
  });

  test('start forgets everything before', () => {
    const h = new UndoHistory();
    h.start(1);
    h.push(2);
    h.start(9);
    assert.deepEqual(h.states, [9]);
    assert.equal(h.canUndo, false);
  });
});

describe('prepChange', () => {
  test('names each part of the preparation that changed', () => {
    const a = state();
    assert.equal(prepChange(a, state()), '');
    assert.equal(prepChange(a, state({ prep: { units: 'cm' } })), 'units');
    assert.equal(prepChange(a, state({ prep: { keepCaps: true } })), 'caps');
    assert.equal(prepChange(a, state({ prep: { largestComponentOnly: true } })), 'components');
    assert.equal(prepChange(a, state({ prep: { smooth: 'off' } })), 'smoothing');
    assert.equal(prepChange(a, state({ prep: { holeFraction: 0.5 } })), 'repair');
    assert.equal(prepChange(a, state({ cuts: [{ point: [0, 0, 0] }] })), 'cuts');
    assert.equal(prepChange(a, state({ prep: { clipPlanes: [[0, 0, 0, 0, 0, 1]] } })), 'cuts');
    const o = (over) => state({ openings: { ...a.openings, ...over } });
    assert.equal(prepChange(a, o({ inlet: 2 })), 'inlet');
    assert.equal(prepChange(a, o({ names: ['in', ''] })), 'opening names');
    assert.equal(prepChange(a, o({ extensions: ['0', '5'] })), 'flow extensions');
  });

  test('other openings (cut otherwise) are not a change of their choices', () => {
    const b = state({ prep: { clipPlanes: [[0, 0, 0, 0, 0, 1]] }, openings: { names: ['', '', ''], inlet: 1, flowAll: '0', extensions: ['0', '0', '0'] } });
    assert.equal(prepChange(state(), b), 'cuts');
  });

  test('several changes are listed in order', () => {
    const b = state({ prep: { units: 'm' }, openings: { names: ['a', ''], inlet: 2, flowAll: '0', extensions: ['0', '0'] } });
    assert.equal(prepChange(state(), b), 'units, inlet and opening names');
  });

  test('the history names what undo and redo change', () => {
    const h = new UndoHistory();
    h.start(state());
    h.push(state({ prep: { units: 'cm' } }));
    h.push(state({ prep: { units: 'cm' }, cuts: [{ point: [1, 2, 3] }] }));
    assert.equal(h.undoLabel(), 'cuts');
    assert.equal(h.redoLabel(), '');
    h.undo();
    assert.equal(h.undoLabel(), 'units');
    assert.equal(h.redoLabel(), 'cuts');
    h.undo();
    assert.equal(h.undoLabel(), '');
  });
});
