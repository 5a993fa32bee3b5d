// What of a VTK cell list the viewer draws: the triangles of surfaces (triangles and quads as
// they are; the boundary of volume meshes, the faces of tetrahedra and hexahedra that belong to one
// cell only), line segments (rods, polylines) and lone points (particles).
import { VtkCell } from './vtk_reader.js';

// Faces of a cell with outward normals for VTK's node order, as vertex slots of the cell.
const TET_FACES = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
const HEX_FACES = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]];

/**
 * @param {{connectivity: Int32Array, offsets: Int32Array, types: Uint8Array|null}} cells
 * @returns {{triangles: Uint32Array, segments: Uint32Array, points: Uint32Array}} vertex indices:
 *   three per triangle, two per segment, one per point
 */
export function drawableCells(cells) {
  const triangles = [], segments = [], points = [];
  const faceCount = new Map();  // sorted-node key -> [count, face nodes]
  const addFace = (nodes) => {
    const key = [...nodes].sort((a, b) => a - b).join(',');
    const seen = faceCount.get(key);
    if (seen) seen[0] += 1;
    else faceCount.set(key, [1, nodes]);
  };
  const addPolygon = (nodes) => {
    for (let k = 1; k + 1 < nodes.length; ++k) triangles.push(nodes[0], nodes[k], nodes[k + 1]);
  };
  let begin = 0;
  for (let c = 0; c < cells.offsets.length; ++c) {
    const end = cells.offsets[c];
    const nodes = cells.connectivity.subarray(begin, end);
    const type = cells.types ? cells.types[c] : guessType(end - begin);
    begin = end;
    switch (type) {
      case VtkCell.vertex: points.push(nodes[0]); break;
      case VtkCell.line: segments.push(nodes[0], nodes[1]); break;
      case VtkCell.triangle: case VtkCell.quad: addPolygon(nodes); break;
      case VtkCell.tetra: for (const f of TET_FACES) addFace(f.map((i) => nodes[i])); break;
      case VtkCell.hexahedron: for (const f of HEX_FACES) addFace(f.map((i) => nodes[i])); break;
      default: break;  // other cell types are not drawn
    }
  }
  for (const [count, nodes] of faceCount.values()) if (count === 1) addPolygon(nodes);
  return { triangles: Uint32Array.from(triangles), segments: Uint32Array.from(segments), points: Uint32Array.from(points) };
}

function guessType(size) {
  return size === 1 ? VtkCell.vertex : size === 2 ? VtkCell.line : VtkCell.triangle;
}

/** Whether a frame is a collider plane, which moreau writes as one square: four points, two triangles. */
export function isPlaneSquare(data) {
  return data.points.length === 12 && data.cells.offsets.length === 2 &&
      (!data.cells.types || data.cells.types.every((t) => t === VtkCell.triangle));
}

/**
 * Whether the triangles enclose a volume with their normals pointing in: a container (a tank),
 * whose near walls a viewer should not draw. Closed: every edge belongs to exactly two triangles;
 * inward: the enclosed signed volume, Σ x₀ · (x₁ × x₂) / 6, is negative.
 */
export function isInwardClosedSurface(points, triangles) {
  if (triangles.length === 0) return false;
  const edges = new Map();
  for (let t = 0; t < triangles.length; t += 3)
    for (let k = 0; k < 3; ++k) {
      const a = triangles[t + k], b = triangles[t + (k + 1) % 3];
      const key = a < b ? `${a},${b}` : `${b},${a}`;
      edges.set(key, (edges.get(key) || 0) + 1);
    }
  for (const count of edges.values()) if (count !== 2) return false;
  let volume = 0;
  const p = (i, k) => points[triangles[i] * 3 + k];
  for (let t = 0; t < triangles.length; t += 3) {
    const [ax, ay, az, bx, by, bz, cx, cy, cz] = [0, 1, 2].flatMap((j) => [p(t + j, 0), p(t + j, 1), p(t + j, 2)]);
    volume += ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx);
  }
  return volume < 0;
}
