// Reads the VTK XML files moreau writes: unstructured grids (.vtu) and poly data (.vtp) whose
// arrays are raw little-endian binary in an <AppendedData encoding="raw"> section, each block
// preceded by its byte count (header_type UInt64 or UInt32). Files of other writers in that layout
// open too; inline (ascii, base64) and compressed arrays do not.

const TYPED = {
  Float64: Float64Array, Float32: Float32Array,
  Int64: BigInt64Array, UInt64: BigUint64Array,
  Int32: Int32Array, UInt32: Uint32Array,
  Int16: Int16Array, UInt16: Uint16Array,
  Int8: Int8Array, UInt8: Uint8Array,
};

/** VTK cell type ids the viewer draws. */
export const VtkCell = { vertex: 1, line: 3, triangle: 5, quad: 9, tetra: 10, hexahedron: 12 };

/**
 * Parses a .vtu or .vtp file.
 * @param {ArrayBuffer} buffer the whole file
 * @returns {{points: Float64Array, pointData: Object<string, {components: number, values: Float64Array}>,
 *            cellData: Object<string, {components: number, values: Float64Array}>,
 *            cells: {connectivity: Int32Array, offsets: Int32Array, types: Uint8Array}}}
 *   poly data's verts and lines become cells of type vertex and line
 */
export function readVtk(buffer, name = 'file') {
  const bytes = new Uint8Array(buffer);
  const marker = findAppendedMarker(bytes);
  // The XML part ends where the raw bytes begin; close the tags it leaves open to parse it.
  const xmlText = new TextDecoder().decode(bytes.subarray(0, marker < 0 ? bytes.length : marker)) +
      (marker < 0 ? '' : '</AppendedData></VTKFile>');
  const xml = new DOMParser().parseFromString(xmlText, 'application/xml');
  if (xml.querySelector('parsererror')) throw new Error(`${name}: not a VTK XML file`);
  const root = xml.documentElement;
  if (root.getAttribute('byte_order') === 'BigEndian') throw new Error(`${name}: big-endian data is not supported`);
  if (root.getAttribute('compressor')) throw new Error(`${name}: compressed data is not supported`);
  const appended = root.querySelector('AppendedData');
  if (appended && appended.getAttribute('encoding') !== 'raw') throw new Error(`${name}: only raw appended data is read`);
  const headerBytes = root.getAttribute('header_type') === 'UInt64' ? 8 : 4;
  const appendedStart = marker + 1;  // after the '_'

  const readArray = (element) => {
    const type = element.getAttribute('type');
    const Typed = TYPED[type];
    if (!Typed) throw new Error(`${name}: array type ${type} is not supported`);
    const format = element.getAttribute('format');
    if (format !== 'appended' || marker < 0)
      throw new Error(`${name}: ${format} arrays are not supported (the viewer reads raw appended data)`);
    const at = appendedStart + Number(element.getAttribute('offset'));
    const view = new DataView(buffer);
    const length = headerBytes === 8 ? Number(view.getBigUint64(at, true)) : view.getUint32(at, true);
    const start = at + headerBytes;
    // Copy: the block is not aligned to its element size inside the file.
    return new Typed(buffer.slice(start, start + length));
  };
  const toFloat = (v) => (v instanceof Float64Array ? v : Float64Array.from(v, Number));
  const toInt = (v) => Int32Array.from(v, Number);

  const piece = root.querySelector('Piece');
  if (!piece) throw new Error(`${name}: no <Piece>`);
  const arraysOf = (section) => {
    const out = {};
    const element = piece.querySelector(`:scope > ${section}`);
    if (!element) return out;
    for (const a of element.querySelectorAll(':scope > DataArray')) {
      const components = Number(a.getAttribute('NumberOfComponents') || 1);
      out[a.getAttribute('Name')] = { components, values: toFloat(readArray(a)) };
    }
    return out;
  };
  const pointsArray = piece.querySelector(':scope > Points > DataArray');
  const points = pointsArray ? toFloat(readArray(pointsArray)) : new Float64Array(0);

  const cellArrays = (sectionName) => {
    const section = piece.querySelector(`:scope > ${sectionName}`);
    if (!section) return null;
    const named = (n) => section.querySelector(`:scope > DataArray[Name="${n}"]`);
    return {
      connectivity: toInt(readArray(named('connectivity'))),
      offsets: toInt(readArray(named('offsets'))),
      types: named('types') ? Uint8Array.from(readArray(named('types')), Number) : null,
    };
  };
  let cells = cellArrays('Cells');
  if (!cells) {
    // Poly data: verts, lines and polys, each a list of cells of its kind.
    const parts = [['Verts', VtkCell.vertex], ['Lines', VtkCell.line], ['Polys', VtkCell.triangle]]
        .map(([section, type]) => [cellArrays(section), type]).filter(([c]) => c && c.offsets.length);
    cells = mergeCells(parts);
  }
  return { points, pointData: arraysOf('PointData'), cellData: arraysOf('CellData'), cells };
}

// Index of the '_' that starts the raw appended bytes, or -1.
function findAppendedMarker(bytes) {
  const tag = new TextEncoder().encode('<AppendedData');
  outer: for (let i = 0; i + tag.length < bytes.length; ++i) {
    for (let k = 0; k < tag.length; ++k) if (bytes[i + k] !== tag[k]) continue outer;
    for (let j = i + tag.length; j < bytes.length; ++j) if (bytes[j] === 0x5f /* _ */) return j;
    return -1;
  }
  return -1;
}

// One cell list from poly data's sections; a poly's type follows its size (3: triangle, 4: quad).
function mergeCells(parts) {
  const connectivity = [], offsets = [], types = [];
  let base = 0;
  for (const [c, type] of parts) {
    let previous = 0;
    for (let k = 0; k < c.offsets.length; ++k) {
      const size = c.offsets[k] - previous;
      for (let j = previous; j < c.offsets[k]; ++j) connectivity.push(c.connectivity[j]);
      previous = c.offsets[k];
      offsets.push(base + previous);
      types.push(type !== VtkCell.triangle ? type : size === 4 ? VtkCell.quad : VtkCell.triangle);
    }
    base += previous;
  }
  return { connectivity: Int32Array.from(connectivity), offsets: Int32Array.from(offsets), types: Uint8Array.from(types) };
}

/**
 * Parses a ParaView collection (.pvd) into frames: one per distinct time, each with its parts.
 * @returns {{time: number, parts: {part: number, file: string}[]}[]} in time order
 */
export function readPvd(text, name = 'collection') {
  const xml = new DOMParser().parseFromString(text, 'application/xml');
  if (xml.querySelector('parsererror')) throw new Error(`${name}: not a .pvd collection`);
  const frames = new Map();
  for (const d of xml.querySelectorAll('DataSet')) {
    const time = Number(d.getAttribute('timestep') || 0);
    if (!frames.has(time)) frames.set(time, []);
    frames.get(time).push({ part: Number(d.getAttribute('part') || 0), file: d.getAttribute('file') });
  }
  return [...frames.entries()].sort((a, b) => a[0] - b[0]).map(([time, parts]) => ({ time, parts }));
}
