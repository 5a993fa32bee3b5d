// Colours for values: a diverging blue–grey–red map (the shape of Moreland's "cool to warm",
// interpolated linearly in RGB between its three anchors), and a palette for objects drawn in one
// colour.

const LOW = [0.230, 0.299, 0.754];
const MID = [0.865, 0.865, 0.865];
const HIGH = [0.706, 0.016, 0.150];

/** RGB in [0, 1] for t in [0, 1] (clamped). */
export function coolToWarm(t) {
  const s = Math.min(1, Math.max(0, Number.isFinite(t) ? t : 0));
  const [a, b, u] = s < 0.5 ? [LOW, MID, s * 2] : [MID, HIGH, s * 2 - 1];
  return [0, 1, 2].map((k) => a[k] + (b[k] - a[k]) * u);
}

/** The colour of object number `index` when it is not coloured by an array. */
export function objectColour(index) {
  const palette = [
    [0.85, 0.55, 0.20], [0.30, 0.60, 0.30], [0.55, 0.40, 0.75], [0.20, 0.65, 0.75],
    [0.80, 0.75, 0.25], [0.70, 0.35, 0.45], [0.45, 0.55, 0.65],
  ];
  return palette[index % palette.length];
}

/** The colour of a plane or floor (a collider drawn as a square): a neutral grey. */
export const GROUND_COLOUR = [0.62, 0.62, 0.60];

/**
 * The scalar an array gives each point: the value itself, or the length of a vector.
 * @returns {Float64Array}
 */
export function pointScalars(array) {
  const { components, values } = array;
  const n = values.length / components;
  const out = new Float64Array(n);
  for (let i = 0; i < n; ++i) {
    let s = 0;
    for (let k = 0; k < components; ++k) s += values[i * components + k] ** 2;
    out[i] = components === 1 ? values[i] : Math.sqrt(s);
  }
  return out;
}

/** Draws the colour bar into a canvas, low at the left. */
export function paintColourBar(canvas) {
  const context = canvas.getContext('2d');
  for (let x = 0; x < canvas.width; ++x) {
    const [r, g, b] = coolToWarm(x / Math.max(1, canvas.width - 1));
    context.fillStyle = `rgb(${r * 255}, ${g * 255}, ${b * 255})`;
    context.fillRect(x, 0, 1, canvas.height);
  }
}
