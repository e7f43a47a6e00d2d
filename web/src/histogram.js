// Bar chart of a histogram of counts over [0, 1], drawn as SVG (the axis'
// labels are HTML under it, .histogram-axis, so they are never stretched).
const NS = 'http://www.w3.org/2000/svg';

function el(name, attrs) {
  const node = document.createElementNS(NS, name);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, String(v));
  return node;
}

/** Draws `counts` (equal bins over [0, 1]) of `unit` into the <svg> element. */
export function drawHistogram(svg, counts, unit = 'triangles') {
  svg.replaceChildren();
  const width = 320;
  const height = 96;
  const bottom = 1;
  svg.setAttribute('viewBox', `0 0 ${width} ${height}`);
  svg.setAttribute('preserveAspectRatio', 'none');
  const max = Math.max(1, ...counts);
  const w = width / counts.length;
  counts.forEach((c, i) => {
    const h = c > 0 ? Math.max(1, (c / max) * (height - bottom - 4)) : 0;
    const bar = el('rect', { x: i * w + 0.5, y: height - bottom - h, width: w - 1, height: h });
    const lo = (i / counts.length).toFixed(2);
    const hi = ((i + 1) / counts.length).toFixed(2);
    const title = el('title', {});
    title.textContent = `${lo}–${hi}: ${c.toLocaleString('en')} ${unit}`;
    bar.append(title);
    svg.append(bar);
  });
}
