// The page's 3D view (three.js, vendored from npm): a file's triangles, each
// shell coloured by its role, and the edges `check` finds wrong drawn over
// them (shells crossing another amber) — boundary (open) edges red, edges of more than two faces orange,
// inconsistently wound edges magenta. Drag to turn, wheel to zoom.
import * as THREE from './vendor/three.module.js';

const ROLE_COLOURS = {
  solid: 0xb8c4d6, cavity: 0x7fa8e0, 'inside-out': 0xb07fe0, nested: 0xf0a040, open: 0xd8d0c0, undecided: 0xcccccc,
};
const ROLE_WORDS = {
  solid: 'solid', cavity: 'cavity', 'inside-out': 'inside out', nested: 'inside another shell (overlapping solids)',
  open: 'open', undecided: 'nesting undecided',
};
const CROSSING = 0xf0a040;  // a shell crossing another: the solid counts their overlap once
// An edge's colour by its worst problem (bits: 1 boundary, 2 non-manifold, 4 misoriented).
const edgeColour = (bits) => (bits & 1 ? [0.85, 0.1, 0.1] : bits & 2 ? [1, 0.55, 0] : bits & 4 ? [0.85, 0, 0.85] : [0.3, 0.3, 0.3]);

let renderer = null;

// Shows `m` (the package's mesh(): typed arrays) in `canvas`; returns a
// sentence saying what is drawn, or throws when WebGL is missing.
export function showMesh(canvas, m) {
  renderer ??= new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
  const width = canvas.clientWidth || 640, height = canvas.clientHeight || 420;
  renderer.setSize(width, height, false);
  renderer.setClearColor(0xffffff);
  const scene = new THREE.Scene();

  // The triangles in shell order, one group (one material) per shell.
  const count = m.triangleShell.length;
  const shells = m.shells.length;
  const start = new Uint32Array(shells + 1);
  for (let t = 0; t < count; ++t) start[m.triangleShell[t] + 1] += 1;
  for (let s = 0; s < shells; ++s) start[s + 1] += start[s];
  const fill = start.slice(0, shells);
  const index = new Uint32Array(3 * count);
  for (let t = 0; t < count; ++t) {
    const at = 3 * fill[m.triangleShell[t]]++;
    index[at] = m.triangles[3 * t]; index[at + 1] = m.triangles[3 * t + 1]; index[at + 2] = m.triangles[3 * t + 2];
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(m.positions, 3));
  geometry.setIndex(new THREE.BufferAttribute(index, 1));
  geometry.computeVertexNormals();
  const colour = (s) => (s.crosses ? CROSSING : ROLE_COLOURS[s.role] ?? 0xcccccc);
  const materials = m.shells.map((s) => new THREE.MeshLambertMaterial({ color: colour(s), side: THREE.DoubleSide }));
  for (let s = 0; s < shells; ++s) geometry.addGroup(3 * start[s], 3 * (start[s + 1] - start[s]), s);
  scene.add(new THREE.Mesh(geometry, materials));

  const edges = m.problemEdges.length / 6;
  const disposable = [];
  if (edges) {
    const lines = new THREE.BufferGeometry();
    lines.setAttribute('position', new THREE.BufferAttribute(m.problemEdges, 3));
    const colours = new Float32Array(6 * edges);
    for (let e = 0; e < edges; ++e) colours.set([...edgeColour(m.problems[e]), ...edgeColour(m.problems[e])], 6 * e);
    lines.setAttribute('color', new THREE.BufferAttribute(colours, 3));
    const lineMaterial = new THREE.LineBasicMaterial({ vertexColors: true, depthTest: false });
    disposable.push(lines, lineMaterial);
    const segments = new THREE.LineSegments(lines, lineMaterial);
    segments.renderOrder = 1;
    scene.add(segments);
  }
  scene.add(new THREE.AmbientLight(0xffffff, 0.45));
  const light = new THREE.DirectionalLight(0xffffff, 0.9);
  scene.add(light);

  // The camera on the bounding sphere, turned by dragging, moved by the wheel.
  geometry.computeBoundingSphere();
  const { center, radius } = geometry.boundingSphere;
  const r = radius > 0 && Number.isFinite(radius) ? radius : 1;
  const camera = new THREE.PerspectiveCamera(35, width / height, r / 100, r * 100);
  let yaw = 0.7, pitch = 0.5, distance = 3.2 * r;
  const draw = () => {
    camera.position.set(
      center.x + distance * Math.cos(pitch) * Math.sin(yaw), center.y + distance * Math.sin(pitch),
      center.z + distance * Math.cos(pitch) * Math.cos(yaw));
    camera.lookAt(center);
    light.position.copy(camera.position);
    renderer.render(scene, camera);
  };
  canvas.onpointerdown = (e) => {
    canvas.setPointerCapture(e.pointerId);
    let [x, y] = [e.clientX, e.clientY];
    canvas.onpointermove = (f) => {
      yaw -= (f.clientX - x) * 0.01;
      pitch = Math.max(-1.5, Math.min(1.5, pitch + (f.clientY - y) * 0.01));
      [x, y] = [f.clientX, f.clientY];
      draw();
    };
    canvas.onpointerup = () => { canvas.onpointermove = null; };
  };
  canvas.onwheel = (e) => { e.preventDefault(); distance *= Math.exp(e.deltaY * 0.001); draw(); };
  draw();
  // The previous view's buffers and materials, freed on the GPU.
  for (const old of canvas.__polyvolDispose ?? []) old.dispose();
  canvas.__polyvolDispose = [geometry, ...materials, ...disposable];

  // What is drawn, in words.
  const roles = {};
  for (const s of m.shells) roles[s.role] = (roles[s.role] ?? 0) + 1;
  const crossing = m.shells.filter((s) => s.crosses).length;
  const said = [`${shells} shell${shells === 1 ? '' : 's'}: ` +
    Object.entries(roles).map(([role, n]) => `${n} ${ROLE_WORDS[role] ?? role}`).join(', ')];
  if (crossing) said.push(`${crossing} crossing another shell (amber; the solid counts their overlap once)`);
  const e = m.edges;
  if (e.boundary) said.push(`${e.boundary} boundary edges (red)`);
  if (e.nonmanifold) said.push(`${e.nonmanifold} edges of more than two faces (orange)`);
  if (e.misoriented) said.push(`${e.misoriented} inconsistently wound edges (magenta)`);
  const total = e.boundary + e.nonmanifold + e.misoriented;
  if (edges < total) said.push(`the first ${edges} drawn`);
  return said.join('; ') + '.';
}
