// The probes of probes.csv plotted against time under the view (uPlot), with a marker at the time
// of the frame shown. One probe is plotted at a time (probes differ in unit and scale), chosen in a
// list; a probe with several columns (a point's x, y, z) is one series per column, and the legend
// toggles each.
import uPlot from 'uplot';

/**
 * Parses probes.csv: a header row ("time", then one column per probe component) and rows of numbers.
 * @returns {{names: string[], columns: Float64Array[]}} columns[0] is time
 */
export function readProbesCsv(text) {
  const lines = text.split('\n').filter((l) => l.trim().length);
  if (lines.length === 0) return { names: [], columns: [] };
  const names = lines[0].split(',');
  const columns = names.map(() => new Float64Array(lines.length - 1));
  for (let r = 1; r < lines.length; ++r) {
    const cells = lines[r].split(',');
    for (let c = 0; c < names.length; ++c) columns[c][r - 1] = Number(cells[c]);
  }
  return { names, columns };
}

export class ProbePlot {
  /** Plots `probes` (readProbesCsv's result) into `container`. */
  constructor(container, probes) {
    this.container = container;
    this.time = 0;
    const series = [{ label: 'time (s)' }];
    for (let c = 1; c < probes.names.length; ++c)
      series.push({ label: probes.names[c], stroke: seriesColour(c - 1), width: 1.5 });
    const marker = {
      hooks: {
        draw: [(u) => {
          const x = u.valToPos(this.time, 'x', true);
          const { top, height } = u.bbox;
          u.ctx.save();
          u.ctx.strokeStyle = '#e0e0e0';
          u.ctx.setLineDash([4, 4]);
          u.ctx.beginPath();
          u.ctx.moveTo(x, top);
          u.ctx.lineTo(x, top + height);
          u.ctx.stroke();
          u.ctx.restore();
        }],
      },
    };
    const axis = { stroke: '#c8c8c8', grid: { stroke: '#3a3f47' }, ticks: { stroke: '#3a3f47' } };
    this.plot = new uPlot({
      width: Math.max(300, container.clientWidth), height: 190, series, plugins: [marker],
      scales: { x: { time: false } }, axes: [{ ...axis, label: 'time (s)' }, axis],
      legend: { live: false },
    }, probes.columns, container);
    // The probe of a column: "cloth_corner.x" -> "cloth_corner".
    const probeOf = (c) => probes.names[c].replace(/\.[xyz]$/, '');
    const choice = document.createElement('select');
    choice.setAttribute('aria-label', 'probe');
    for (const name of new Set(probes.names.slice(1).map((_, k) => probeOf(k + 1)))) choice.add(new Option(name, name));
    const show = () => {
      for (let c = 1; c < probes.names.length; ++c) this.plot.setSeries(c, { show: probeOf(c) === choice.value });
    };
    choice.addEventListener('change', show);
    const label = document.createElement('label');
    label.append('probe ', choice);
    container.prepend(label);
    show();
    new ResizeObserver(() => this.plot.setSize({ width: Math.max(300, container.clientWidth), height: 190 }))
        .observe(container);
  }

  /** Moves the marker to simulated time `t` (s). */
  mark(t) {
    this.time = t;
    this.plot.redraw(false, false);
  }
}

function seriesColour(k) {
  const colours = ['#f28e2b', '#4e79a7', '#59a14f', '#e15759', '#b07aa1', '#76b7b2', '#edc948', '#ff9da7', '#9c755f'];
  return colours[k % colours.length];
}
