// What a preparation change did beyond what was asked: the openings, the
// caps found, the inlet (the largest opening, the default) or the unit
// changed with it (turning smoothing on can make a cap no longer planar, a
// repair can close a loop that was an opening). Said in one line, with
// Undo (the action bar's notice). Pure logic over two analyses.
import { point } from './units.js';

/**
 * The effects of going from the analysis `before` to `after`, as phrases
 * ('openings 1 → 0', 'caps found 1 → 0', 'the inlet moved to (…) mm',
 * 'units mm → m'); [] when none.
 */
export function sideEffects(before, after) {
  if (!before || !after) return [];
  const effects = [];
  const [a, b] = [before.openings ?? [], after.openings ?? []];
  if (a.length !== b.length) effects.push(`openings ${a.length} → ${b.length}`);
  const [ca, cb] = [before.caps_removed ?? 0, after.caps_removed ?? 0];
  if (ca !== cb) effects.push(`caps found ${ca} → ${cb}`);
  const unit = after.units?.unit ?? '';
  if (before.units?.unit !== unit) effects.push(`units ${before.units?.unit} → ${unit}`);
  // The default inlet: the largest opening. Moved when the new largest is
  // not where the old one was (within its radius).
  if (a.length && b.length) {
    const [p, q] = [a[0].centroid, b[0].centroid];
    if (Math.hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]) > a[0].radius) {
      effects.push(`the inlet moved to ${point(q, after.bounding_box?.diagonal ?? 0)} ${unit}`.trimEnd());
    }
  }
  return effects;
}

/**
 * The notice's line: 'Changing the smoothing also changed: openings 1 → 0,
 * the inlet moved to (…) mm.'; '' when there are no effects.
 * @param {string} cause what the user changed ('smoothing', 'repair')
 * @param {string[]} effects sideEffects()
 */
export function sideEffectText(cause, effects) {
  if (!effects.length) return '';
  return `Changing the ${cause || 'preparation'} also changed: ${effects.join(', ')}.`;
}
