// The entries of a ZIP archive as text, for the tests: the specs' reader
// (e2e/zip.js, by the central directory) with each entry decoded.
import { readZip } from '../../e2e/zip.js';

/** The entries of a ZIP archive by name, as text. */
export function unzip(bytes) {
  const decoder = new TextDecoder();
  return Object.fromEntries([...readZip(bytes)].map(([name, data]) => [name, decoder.decode(data)]));
}
