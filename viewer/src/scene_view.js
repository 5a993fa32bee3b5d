// The 3D view: one three.js object group per scene object ("part" of the .pvd), refilled from each
// frame's file. Surfaces are lit meshes, rods line segments, particles instanced spheres of their
// `radius` array. An object is drawn in its own colour, or coloured by a point array through the
// colour map.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

import { drawableCells, isInwardClosedSurface, isPlaneSquare } from './cell_geometry.js';
import { coolToWarm, GROUND_COLOUR, objectColour, pointScalars } from './colour_map.js';

export class SceneView {
  /** `keepPicture`: keep the drawing after it is shown, so it can be read back (moreau render). */
  constructor(container, { keepPicture = false } = {}) {
    this.container = container;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: keepPicture });
    this.renderer.setPixelRatio(window.devicePixelRatio);
    container.appendChild(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0x1d2127);
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
    this.scene.add(this.camera);
    // Light from the sky and from the eye, so every side the camera sees is lit.
    // (Weak enough that no lit colour saturates a channel, which would shift its hue.)
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x444444, 0.9));
    const headlight = new THREE.DirectionalLight(0xffffff, 1.2);
    headlight.position.set(0.3, 0.5, 1);
    this.camera.add(headlight);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.addEventListener('change', () => this.render());
    this.parts = new Map();  // part number -> PartView
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  /** Draws `width` x `height` pixels whatever the window's size (moreau render's pictures). */
  fixSize(width, height) {
    this.fixedSize = { width, height };
    this.renderer.setPixelRatio(1);
    this.resize();
  }

  resize() {
    const { clientWidth: w, clientHeight: h } = this.fixedSize
      ? { clientWidth: this.fixedSize.width, clientHeight: this.fixedSize.height } : this.container;
    if (w === 0 || h === 0) return;
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.render();
  }

  render() { this.renderer.render(this.scene, this.camera); }


  /**
   * Shows one frame: `files` maps part numbers to {name, data} (readVtk's result); `colouring` is
   * null (each object in its colour) or {array, min, max}.
   */
  show(files, colouring) {
    for (const [part, view] of this.parts) if (!files.has(part)) view.group.visible = false;
    for (const [part, { name, data }] of files) {
      if (!this.parts.has(part)) {
        const view = new PartView(name, part);
        this.parts.set(part, view);
        this.scene.add(view.group);
      }
      const view = this.parts.get(part);
      view.group.visible = true;
      view.update(data, colouring);
    }
    this.render();
  }

  /**
   * Points the camera at the box holding every point of `files` (the first frame). Collider planes
   * are squares sized to hold the whole scene, so only their centres count (the floor things fall
   * to is in view); every point of them counts when there is nothing else.
   */
  frame(files) {
    const box = new THREE.Box3();
    const all = [...files.values()].map(({ data }) => data);
    const onlyPlanes = all.every(isPlaneSquare);
    for (const data of all) {
      const p = data.points, n = p.length / 3;
      const points = [];
      for (let i = 0; i < n; ++i) points.push(new THREE.Vector3(p[i * 3], p[i * 3 + 1], p[i * 3 + 2]));
      if (isPlaneSquare(data) && !onlyPlanes) box.expandByPoint(points.reduce((c, x) => c.add(x)).divideScalar(n));
      else for (const x of points) box.expandByPoint(x);
    }
    if (box.isEmpty()) box.set(new THREE.Vector3(-1, -1, -1), new THREE.Vector3(1, 1, 1));
    const centre = box.getCenter(new THREE.Vector3());
    const radius = Math.max(box.getSize(new THREE.Vector3()).length() / 2, 1e-3);
    const distance = radius / Math.sin(THREE.MathUtils.degToRad(this.camera.fov / 2));
    // Looking from the front, a little from above and from the right (y up, as the scenes are);
    // a plane model (a 2D flow or solid, all z = 0) straight on.
    const flat = box.getSize(new THREE.Vector3()).z <= 1e-9 * radius;
    const direction = flat ? new THREE.Vector3(0, 0, 1) : new THREE.Vector3(0.35, 0.45, 1).normalize();
    this.camera.position.copy(centre).addScaledVector(direction, distance);
    this.camera.near = distance / 100;
    this.camera.far = distance * 100;
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(centre);
    this.controls.update();
  }

  /** The position of world point (x, y, z) on the canvas, in CSS pixels from its top left. */
  project(x, y, z) {
    const v = new THREE.Vector3(x, y, z).project(this.camera);
    const canvas = this.renderer.domElement.getBoundingClientRect();
    return { x: (v.x + 1) / 2 * canvas.width, y: (1 - v.y) / 2 * canvas.height, visible: Math.abs(v.z) <= 1 };
  }
}

// One object's drawing: a mesh for its surface, segments for its lines, spheres for its points.
class PartView {
  constructor(name, index) {
    this.name = name;
    this.group = new THREE.Group();
    this.group.name = name;
    this.baseColour = objectColour(index);
    this.surface = null;
    this.lines = null;
    this.spheres = null;
  }

  update(data, colouring) {
    const { triangles, segments, points } = drawableCells(data.cells);
    const positions = Float32Array.from(data.points);
    // A container's near walls would hide what it holds: it draws only the faces that look at the
    // camera, which for its inward triangles are the far walls (checked once per topology). It
    // and planes are scenery, drawn grey.
    if (this.topology !== triangles.length) {
      this.topology = triangles.length;
      this.container = isInwardClosedSurface(positions, triangles);
    }
    const colours = this.pointColours(data, colouring, isPlaneSquare(data) || this.container);
    this.updateSurface(positions, triangles, colours);
    this.updateLines(positions, segments, colours);
    this.updateSpheres(data, points, colours);
  }

  // RGB per point, linear (the colours are given as sRGB, as a screen shows them, and three.js
  // lights in linear RGB): from the colour map where the object has the array, else its own colour.
  pointColours(data, colouring, ground) {
    const n = data.points.length / 3;
    const colours = new Float32Array(n * 3);
    // Scenery (planes, containers) stays grey: the ground the rest is seen against.
    const array = colouring && !ground && data.pointData[colouring.array];
    const scalars = array ? pointScalars(array) : null;
    const span = colouring ? colouring.max - colouring.min : 0;
    const base = ground ? GROUND_COLOUR : this.baseColour;
    const linear = new THREE.Color();
    for (let i = 0; i < n; ++i) {
      const c = scalars ? coolToWarm(span > 0 ? (scalars[i] - colouring.min) / span : 0) : base;
      linear.setRGB(c[0], c[1], c[2], THREE.SRGBColorSpace);  // stored in three's linear working space
      colours.set([linear.r, linear.g, linear.b], i * 3);
    }
    return colours;
  }

  updateSurface(positions, triangles, colours) {
    if (triangles.length === 0) {
      if (this.surface) this.surface.visible = false;
      return;
    }
    if (!this.surface) {
      const material = new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide });
      this.surface = new THREE.Mesh(new THREE.BufferGeometry(), material);
      this.group.add(this.surface);
    }
    const side = this.container ? THREE.FrontSide : THREE.DoubleSide;
    if (this.surface.material.side !== side) {
      this.surface.material.side = side;
      this.surface.material.needsUpdate = true;
    }
    fillGeometry(this.surface.geometry, positions, colours, triangles);
    this.surface.geometry.computeVertexNormals();
    this.surface.visible = true;
  }

  updateLines(positions, segments, colours) {
    if (segments.length === 0) {
      if (this.lines) this.lines.visible = false;
      return;
    }
    if (!this.lines) {
      this.lines = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ vertexColors: true }));
      this.group.add(this.lines);
    }
    fillGeometry(this.lines.geometry, positions, colours, segments);
    this.lines.visible = true;
  }

  // Particles as spheres of their `radius` array (or of 1/300 of the object's size without one).
  updateSpheres(data, points, colours) {
    const n = points.length;
    if (this.spheres && this.spheres.count !== n) {
      this.group.remove(this.spheres);
      this.spheres.dispose();
      this.spheres = null;
    }
    if (n === 0) return;
    if (!this.spheres) {
      const detail = n > 20000 ? [6, 4] : [12, 8];
      const sphere = new THREE.SphereGeometry(1, detail[0], detail[1]);
      this.spheres = new THREE.InstancedMesh(sphere, new THREE.MeshLambertMaterial(), n);
      this.spheres.instanceMatrix.setUsage(THREE.DynamicDrawUsage);
      this.group.add(this.spheres);
    }
    const radius = data.pointData.radius ? data.pointData.radius.values : null;
    const fallback = defaultRadius(data.points);
    const matrix = new THREE.Matrix4(), colour = new THREE.Color();
    const p = data.points;
    for (let k = 0; k < n; ++k) {
      const i = points[k];
      const r = radius ? radius[i] : fallback;
      matrix.makeScale(r, r, r).setPosition(p[i * 3], p[i * 3 + 1], p[i * 3 + 2]);
      this.spheres.setMatrixAt(k, matrix);
      this.spheres.setColorAt(k, colour.setRGB(colours[i * 3], colours[i * 3 + 1], colours[i * 3 + 2], THREE.LinearSRGBColorSpace));
    }
    this.spheres.instanceMatrix.needsUpdate = true;
    this.spheres.instanceColor.needsUpdate = true;
    this.spheres.computeBoundingSphere();
  }
}

// Points, their colours and the index list of the triangles or segments drawn through them.
function fillGeometry(geometry, positions, colours, index) {
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  geometry.setAttribute('color', new THREE.BufferAttribute(colours, 3));
  geometry.setIndex(new THREE.BufferAttribute(index, 1));
  geometry.computeBoundingSphere();
}

function defaultRadius(p) {
  const box = new THREE.Box3();
  for (let i = 0; i + 2 < p.length; i += 3) box.expandByPoint(new THREE.Vector3(p[i], p[i + 1], p[i + 2]));
  return Math.max(box.getSize(new THREE.Vector3()).length() / 300, 1e-4);
}
