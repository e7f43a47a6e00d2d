// The core's messages in the page's words: the core names its options by
// their JS keys (clipPlanes, smooth 10, featureAngle 180, maxElements...),
// which the page does not show; here each becomes the control that does it
// (or is dropped when the page has none), coordinates get 4 significant
// digits and lengths and areas their unit. Pure text (no DOM).
import { point } from './units.js';

/** Phrases naming an option with a value, replaced first (most specific). */
const PHRASES = [
  [/^names needs K=NAME with NAME\b/, 'A name needs'],
  [/^names cannot be\b/, 'A name cannot be'],
  [/^names gives\b/, 'The names give'],
  [/\(\s*featureAngle 180\s*\)/g, ''],
  [/,? or turn crease detection off\s*/g, ' '],
  [/(\d+) passes \(smooth \1\)/g, '$1 passes'],
  [/\bsmooth (\d+)\b/g, 'Smoothing: $1 passes'],
  [/^size makes\b/, 'The edge length h makes'],
  [/^coreSize makes\b/, 'The core size makes'],
  [/\bsmooth off\b/g, 'Smoothing “Off”'],
  [/\brepair off\b/g, 'Repair “Off”'],
  [/\brepair auto\b/g, 'Repair “Auto”'],
  [/\bclip auto\b/g, 'the proposed cuts'],
  [/\blayers 0\b/g, 'Layers 0 (no boundary layer)'],
  [/\bmaxElements (\d+)\b/g, (_, n) => `${Number(n).toLocaleString('en')} elements`],
  [/\bdrop wallThickness\b/g, 'turn the vessel wall off'],
  [/\(or give clipPlanes or clipAt\)/g, '(or add your own)'],
  [/\bgive clipPlanes or clipAt\b/g, 'add cuts'],
  [/\bgive the cuts with clipPlanes( or clipAt)?\b/g, 'add a cut on each vessel end'],
  [/\bcut it with clipPlanes\b/g, 'add a cut on it'],
  [/\bcut that part off with clipPlanes\b/g, 'cut that part off'],
  [/\bsay units\b/g, 'choose the Units'],
];

/** The JS keys of the options, as the page names their controls. */
const OPTION_WORDS = {
  clipPlanes: 'a cut',
  clipAt: 'a cut',
  clipDistance: 'the cut distance',
  perCircumference: 'N (edges per circumference)',
  sizeMin: 'the smallest edge length',
  sizeMax: 'the largest edge length',
  keepCaps: '“Keep flat caps as wall”',
  largestComponentOnly: '“Keep the largest component only”',
  holeFraction: '“Holes up to”',
  featureAngle: 'crease detection',
  maxElements: 'the element budget',
  maxVolumeChange: '“Largest volume change”',
  coreSize: 'the core size',
  flowExtension: 'the flow extension',
  layerThickness: 'the layers’ total thickness',
  firstLayer: 'the first-layer height',
  firstLayerYplus: 'the target y+',
  wallThickness: 'the vessel wall’s thickness',
  wallLayers: 'the vessel wall’s layers',
  tagLayer: '“Separate boundary_layer group”',
  surfaceOnly: '“Surface only”',
  outputUnits: 'the output units',
};
const OPTION_RE = new RegExp(`\\b(${Object.keys(OPTION_WORDS).join('|')})\\b`, 'g');

// A number as the core writes it: -1.5, 2e-05, 148.603.
const NUM = String.raw`-?\d+(?:\.\d+)?(?:e[-+]?\d+)?`;
const TRIPLE = new RegExp(String.raw`\((${NUM}), (${NUM}), (${NUM})\)( ?(?:mm|cm|m)\b)?`, 'g');

/**
 * `message` in the page's words: option keys replaced by the controls'
 * names, coordinates shortened to 4 significant digits and given the model's
 * `unit` (when not given already), radii and areas with their unit.
 * @param {string} message a core message (error or warning)
 * @param {{unit?: string, scale?: number}} model the model's unit and size
 *   (coordinates within 1e-6 of it shown as 0)
 */
export function inPageWords(message, { unit = '', scale = 0 } = {}) {
  let text = String(message);
  for (const [re, to] of PHRASES) text = text.replace(re, to);
  text = text.replace(OPTION_RE, (key) => OPTION_WORDS[key]);
  text = text.replace(TRIPLE, (_, x, y, z) => `${point([x, y, z].map(Number), scale)}${unit ? ` ${unit}` : ''}`);
  // The size that fits, as the size field names it: h in the model's unit.
  text = text.replace(new RegExp(String.raw`\((size|the core size) (${NUM}) fits\)`, 'g'), (_, what, h) =>
    `(${what === 'size' ? 'h' : what} = ${h}${unit ? ` ${unit}` : ''} fits)`,
  );
  if (unit) {
    text = text.replace(new RegExp(String.raw`\bof radius (${NUM})(?! ?(?:mm|cm|m)\b)`, 'g'), `of radius $1 ${unit}`);
    text = text.replace(new RegExp(String.raw`\((${NUM}) of area removed\)`, 'g'), `($1 ${unit}² of area removed)`);
  }
  return text.replace(/ {2,}/g, ' ').replace(/ ([,;.)])/g, '$1').trim();
}

/** Whether `text` still names an option of the API the page does not show
 * (for tests: every message shown must pass). */
export function namesApiOption(text) {
  return [
    /\b(clipPlanes|clipAt|featureAngle|maxElements|perCircumference|keepCaps|largestComponentOnly|holeFraction)\b/,
    /\b(smooth|layers) \d+/,
    /\b(clip auto|repair off|repair auto|say units)\b/,
  ].some((re) => re.test(text));
}
