// The solver presets in the page: what the chosen solver's preset sets,
// said under the select; the controls it decides (element types, export
// format, units) set to its values when it is chosen (the user may change
// them after); and a setting of a mesh report's preset in the page's words
// (results.js). The presets come from the core (the API's solverPresets).
import { EXPORT_FORMATS, exportFormat } from './files.js';
import { inPageWords } from './words.js';

const $ = (id) => document.getElementById(id);

/** The preset of the chosen solver, or undefined. */
const chosen = (presets) => presets?.find((p) => p.name === $('solver').value);

/** Says what the chosen solver's preset sets, under the select. */
export function showSolverHint(presets) {
  const preset = chosen(presets);
  $('solver-hint').hidden = !preset;
  if (!preset) return;
  const units = preset.outputUnits ? `written in ${preset.outputUnits}` : "in the input's unit";
  const format = preset.format === 'msh' ? `MSH ${preset.mshVersion}` : exportFormat(preset.format).label;
  const elements = preset.prisms ? 'layer prisms kept' : 'tetrahedra only';
  $('solver-hint').textContent = `${preset.label}: ${elements}, ${format}, ${units}.${preset.note ? ` Then: ${preset.note}.` : ''}`;
}

/** Sets the controls the chosen solver's preset decides to its values,
 * then `onFormats` (the export formats follow), and says it. */
export function applySolverPreset(presets, onFormats) {
  const preset = chosen(presets);
  if (preset) {
    $('prisms').checked = preset.prisms;
    $('format').value = preset.format === 'msh' ? `msh-${preset.mshVersion}` : preset.format;
    $('output-units').value = preset.outputUnits;
    onFormats();
  }
  showSolverHint(presets);
}

/** A setting of the report's preset {option, value} in the page's words
 * ('layer prisms kept', 'MSH 2.2', 'written in m', 'OpenFOAM case'). */
export function presetSettingText({ option, value }) {
  switch (option) {
    case 'prisms':
      return value === 'true' ? 'layer prisms kept' : 'tetrahedra only';
    case 'mshVersion':
      return `MSH ${value}`;
    case 'outputUnits':
      return value ? `written in ${value}` : "in the input's unit";
    case 'format': {
      const format = EXPORT_FORMATS.find((f) => f.format === value);
      return format ? format.label.replace(/,? ?\(.*\)$|, polyMesh.*$/, '').replace(/ \d\.\d$/, '') : String(value);
    }
    default: {
      // An option the page has no words for yet: its control's name, or its words.
      const words = inPageWords(option);
      return `${words === option ? option.replace(/([a-z])([A-Z])/g, '$1 $2').toLowerCase() : words} ${value}`;
    }
  }
}
