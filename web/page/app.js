import { showMesh } from './view.js';

// The page: files in, the command line's figures out, each with its guarantee
// and its unit. The work runs in worker.js; this thread only shows it.
const $ = (id) => document.getElementById(id);
const worker = new Worker('worker.js', { type: 'module' });
const pending = new Map();
let nextId = 0;

worker.onmessage = ({ data }) => {
  const p = pending.get(data.id);
  if (data.progress) return p.onProgress?.(data.progress);
  pending.delete(data.id);
  if (data.error !== undefined) p.reject(new Error(data.error));
  else p.resolve(data.answer);
};
// A worker that cannot start (a missing or broken script) fails every request
// in words, and the error is thrown where a test or a console sees it.
let broken = null;
worker.onerror = (e) => {
  const why = `The measuring worker failed: ${e.message || 'its script did not load'}`;
  broken = why;
  for (const p of pending.values()) p.reject(new Error(why));
  pending.clear();
  $('status').textContent = why;
  setTimeout(() => { throw new Error(why); });
};

// One request to the worker: the answer of web/src/polyvol_wasm.cpp;
// onProgress({file, stage, fraction}) meanwhile.
function ask(command, files, options, onProgress) {
  const id = ++nextId;
  if (broken) return Promise.reject(new Error(broken));
  return new Promise((resolve, reject) => {
    pending.set(id, { resolve, reject, onProgress });
    // A File goes as it is (the worker reads it window by window); bytes are handed over.
    worker.postMessage({ id, command, files, options }, files.map((f) => f.data).filter((d) => d instanceof ArrayBuffer));
  });
}

function options() {
  const material = $('material').value;
  const units = $('units').value;
  // units: only for files that state none (3MF, AMF and glTF state theirs);
  // every figure is shown in it.
  return {
    density: material === 'custom' ? $('density').value : material, units, to: units, unitsWhereUnstated: true,
    massUnit: $('mass-unit').value,
  };
}

// A figure to the digits its relative error supports (all of them when it
// is correctly rounded or exact), rounded to nearest; the copied JSON has
// every digit.
function shown(x, relativeError = 0) {
  if (x === null || x === undefined) return '—';
  if (!(relativeError > 0) || x === 0) return String(x);
  const digits = Math.min(17, Math.max(1, Math.floor(-Math.log10(relativeError))));
  return String(Number(x.toPrecision(digits)));
}
const number = (x) => shown(x);
const vector = (v, e = 0) => (v ? `(${v.map((x) => shown(x, e)).join(', ')})` : '—');
const relative = (e) => (e === 0 ? 'exact' : `relative error ≤ ${e.toPrecision(2)}`);
const bound = (e) => (e === null || e === undefined ? '—' : e.toPrecision(2));

function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  for (const c of children) e.append(c);
  return e;
}

// The topology in words: what makes the file a solid, or why it is not one.
function verdict(r) {
  const problems = [];
  if (r.boundary_edges) problems.push(`${r.boundary_edges} boundary edges (${r.holes ?? '?'} holes): the surface is open`);
  if (r.nonmanifold_edges) problems.push(`${r.nonmanifold_edges} edges shared by more than two faces`);
  if (r.misoriented_edges) problems.push(`${r.misoriented_edges} edges where neighbouring faces are wound inconsistently`);
  if (r.unbalanced_edges && !r.boundary_edges) problems.push(`${r.unbalanced_edges} unbalanced edges`);
  if (r.overlapping_shells) problems.push(`${r.overlapping_shells} shells overlap one another: the volume is the solid's (counted once)`);
  if (r.self_crossing_pairs) problems.push(`the surface crosses itself (${r.self_crossing_pairs} pairs of triangles)`);
  if (!problems.length) return `Closed and consistently oriented: a solid (${r.components} shell${r.components === 1 ? '' : 's'}).`;
  return problems.join('; ') + '.';
}

function rows(r) {
  const u = r.unit ?? 'units of the file';
  const m = r.mass_unit ?? '(density × volume)';
  const out = [];
  if (r.volume !== undefined) {
    const exact = r.accuracy === 'correctly-rounded';
    const g = exact ? 'correctly rounded' : `± ${bound(r.volume_error_bound)}`;
    out.push(['Volume', `${shown(r.volume, exact ? 0 : r.volume_error_bound / Math.abs(r.volume))} ${u}³`, g, 'volume']);
  }
  const momentsError = r.moments_accuracy === 'correctly-rounded' ? 0 : r.moments_relative_error;
  if (r.mass !== undefined) out.push(['Mass', `${shown(r.mass, momentsError || 2 ** -52)} ${m}`, 'density × volume', 'mass']);
  if (r.area !== undefined) out.push(['Surface area', `${shown(r.area, r.area_relative_error)} ${u}²`, relative(r.area_relative_error), 'area']);
  if (r.centroid) out.push(['Centroid', `${vector(r.centroid, momentsError)} ${u}`, momentsError ? relative(momentsError) + ' (of the largest coordinate)' : 'correctly rounded', 'centroid']);
  if (r.bounds) out.push(['Bounding box', `${vector(r.bounds.slice(0, 3))} to ${vector(r.bounds.slice(3))} ${u}`, 'exact', 'bounds']);
  if (r.size) out.push(['Size', `${r.size.map(number).join(' × ')} ${u}`, 'differences rounded once', 'size']);
  if (r.principal_moments) {
    const largest = Math.max(...r.principal_moments.map(Math.abs));
    const e = largest > 0 ? r.principal_moment_error / largest : 0;
    out.push(['Principal moments', `${r.principal_moments.map((x) => shown(x, e)).join(', ')} ${m}·${u}²`, `each within ${bound(r.principal_moment_error)}`, 'principal_moments']);
  }
  if (r.edge_length !== undefined) out.push(['Edge length', `${shown(r.edge_length, r.edge_length_relative_error)} ${u}`, relative(r.edge_length_relative_error), 'edge_length']);
  return out;
}

function render(file, answer, source) {
  const card = el('article', { class: 'result', 'data-file': file, 'data-exit-code': String(answer.exitCode) });
  card.dataset.json = answer.stdout;
  if (answer.csv) card.dataset.csv = answer.csv;
  card.append(el('h2', {}, file));
  const results = answer.stdout ? JSON.parse(answer.stdout) : [];
  for (const r of results) {
    if (results.length > 1) card.append(el('h3', {}, r.file));
    card.append(el('p', { class: r.exit_code ? 'verdict bad' : 'verdict' }, r.error ? r.error : verdict(r)));
    const table = el('table', {});
    for (const [name, value, guarantee, key] of rows(r))
      table.append(el('tr', { 'data-key': key }, el('th', {}, name), el('td', {}, value), el('td', { class: 'guarantee' }, guarantee)));
    if (table.childElementCount) card.append(table);
    for (const n of r.notes ?? []) card.append(el('p', { class: 'note', title: n }, `Note: ${answer.noteWords?.[n] ?? n}.`));
  }
  // The command line's stderr, less what the cards above already say.
  const said = new Set(results.map((r) => r.error).filter(Boolean));
  for (const msg of answer.messages) {
    const text = msg.replace(/^polyvol: /, '');
    if (!said.has(text)) card.append(el('p', { class: 'message' }, text));
  }
  const copy = el('button', { type: 'button', class: 'copy-json' }, 'Copy JSON');
  copy.onclick = () => navigator.clipboard.writeText(answer.stdout);
  const actions = el('p', { class: 'actions' }, copy);
  for (const r of results) {
    if (!r.triangles) continue;  // unread: nothing to draw
    const member = r.file.startsWith(`${file}:`) ? r.file.slice(file.length + 1) : '';
    const show = el('button', { type: 'button', class: 'view-3d' }, results.length > 1 ? `View ${member || r.file} in 3D` : 'View in 3D');
    show.onclick = () => view(source, member, r.file);
    actions.append(' ', show);
  }
  if (answer.csv) {
    // The rows of `polyvol measure --csv`, for a spreadsheet.
    const csv = el('button', { type: 'button', class: 'copy-csv' }, 'Copy CSV');
    csv.onclick = () => navigator.clipboard.writeText(answer.csv);
    actions.append(' ', csv);
  }
  card.append(actions);
  return card;
}

// The 3D view of a measured file (of one member of an archive).
async function view(f, member, title) {
  const section = $('view');
  section.hidden = false;
  $('view-title').textContent = `3D view: ${title}`;
  $('view-words').textContent = 'Reading the mesh…';
  delete section.dataset.ready;
  try {
    const m = await ask('mesh', [{ name: f.name, data: f }], { member });
    if (m.exitCode) throw new Error(m.error);
    section.dataset.triangles = String(m.triangles.length / 3);
    section.dataset.problemEdges = String(m.problemEdges.length / 6);
    section.dataset.shells = m.shells.map((s) => s.role).join(' ');
    $('view-words').textContent = showMesh($('view-canvas'), m);
  } catch (e) {
    $('view-words').textContent = `No 3D view: ${e.message}`;
  }
  section.dataset.ready = '1';
  section.scrollIntoView({ block: 'nearest' });
}

// The files measured so far, for the overlap (a File can be read again).
const measured = [];

function remember(file) {
  measured.push(file);
  for (const id of ['overlap-a', 'overlap-b']) {
    const select = $(id);
    select.append(el('option', { value: String(measured.length - 1) }, file.name));
    if (id === 'overlap-b' && measured.length === 2) select.value = '1';
  }
  $('overlap').hidden = measured.length < 2;
}

const OVERLAP_ROWS = [
  ['A', 'volume_a', 'area_a'], ['B', 'volume_b', 'area_b'], ['A ∩ B', 'intersection', 'area_intersection'],
  ['A ∪ B', 'union', 'area_union'], ['A − B', 'a_minus_b', 'area_a_minus_b'], ['B − A', 'b_minus_a', 'area_b_minus_a'],
];

function renderOverlap(a, b, answer) {
  const card = el('article', { class: 'result overlap', 'data-overlap': `${a} ${b}`, 'data-exit-code': String(answer.exitCode) });
  card.dataset.json = answer.stdout;
  card.append(el('h2', {}, `Overlap: A = ${a}, B = ${b}`));
  if (answer.stdout) {
    const r = JSON.parse(answer.stdout);
    const u = r.unit ?? 'units of the files';
    const exact = r.accuracy === 'correctly-rounded';
    const table = el('table', {}, el('tr', {}, el('th', {}, ''), el('th', {}, `Volume (${u}³)`), el('th', {}, `Boundary area (${u}²)`)));
    for (const [name, volume, area] of OVERLAP_ROWS) {
      const v = exact ? shown(r[volume]) : `${shown(r[volume], r.volume_error_bound / Math.abs(r[volume] || 1))} ± ${bound(r.volume_error_bound)}`;
      const ar = r[area] === null ? '—' : `${shown(r[area], r.area_error_bound / Math.abs(r[area] || 1))} ± ${bound(r.area_error_bound)}`;
      table.append(el('tr', { 'data-key': volume }, el('th', {}, name), el('td', {}, v), el('td', {}, ar)));
    }
    card.append(table);
    card.append(el('p', { class: 'note' }, exact ? 'Volumes correctly rounded (the exact volumes of the meshes as read, rounded once).'
      : 'Volumes within the ± shown (a change of unit, or coordinates computed by the reader).'));
  }
  for (const msg of answer.messages) card.append(el('p', { class: 'message' }, msg.replace(/^polyvol: /, '')));
  const copy = el('button', { type: 'button', class: 'copy-json' }, 'Copy JSON');
  copy.onclick = () => navigator.clipboard.writeText(answer.stdout);
  card.append(el('p', { class: 'actions' }, copy));
  return card;
}

$('overlap-go').addEventListener('click', async () => {
  const [fa, fb] = [measured[Number($('overlap-a').value)], measured[Number($('overlap-b').value)]];
  $('status').textContent = `Computing the overlap of ${fa.name} and ${fb.name}…`;
  $('progress').hidden = false;
  $('progress').removeAttribute('value');
  try {
    const files = [{ name: fa.name, data: fa }, { name: fb.name, data: fb }];
    const { units } = options();
    const answer = await ask('overlap', files, { units, to: units, unitsWhereUnstated: true });
    $('results').prepend(renderOverlap(fa.name, fb.name, answer));
    $('status').textContent = 'Done: the overlap.';
  } catch (e) {
    $('status').textContent = String(e.message);
  }
  $('progress').hidden = true;
  document.body.dataset.done = String(Number(document.body.dataset.done ?? 0) + 1);
});

const STAGES = ['reading', 'checking', 'measuring'];
const STAGE_WORDS = { reading: 'reading', checking: 'checking its shells', measuring: 'measuring' };

async function measureFiles(list) {
  const files = [...list];
  if (!files.length) return;
  const bar = $('progress');
  bar.hidden = false;
  bar.max = files.length;
  for (let i = 0; i < files.length; ++i) {
    const f = files[i];
    // Files done of all, and of this one its stages (reading, checking,
    // measuring: a third each), never back (a file streamed, then loaded).
    bar.value = i;
    const counting = `Measuring ${f.name} (${i + 1} of ${files.length})`;
    $('status').textContent = `${counting}…`;
    const onProgress = ({ file, stage, fraction }) => {
      bar.value = Math.max(bar.value, i + (STAGES.indexOf(stage) + fraction) / STAGES.length);
      const member = file === f.name ? '' : `, ${file.slice(f.name.length + 1)}`;
      const percent = fraction > 0 && fraction < 1 ? ` ${Math.floor(100 * fraction)}%` : '';
      $('status').textContent = `${counting}${member}: ${STAGE_WORDS[stage]}${percent}…`;
    };
    try {
      const answer = await ask('measure', [{ name: f.name, data: f }], options(), onProgress);
      $('results').prepend(render(f.name, answer, f));
      remember(f);
    } catch (e) {
      $('results').prepend(el('article', { class: 'result failed', 'data-file': f.name }, el('h2', {}, f.name), el('p', { class: 'message' }, String(e.message))));
    }
  }
  bar.hidden = true;
  $('status').textContent = `Done: ${files.length} file${files.length === 1 ? '' : 's'}.`;
  document.body.dataset.done = String(Number(document.body.dataset.done ?? 0) + 1);
}

$('files').addEventListener('change', (e) => measureFiles(e.target.files));
const drop = $('drop');
drop.addEventListener('dragover', (e) => { e.preventDefault(); drop.classList.add('over'); });
drop.addEventListener('dragleave', () => drop.classList.remove('over'));
drop.addEventListener('drop', (e) => { e.preventDefault(); drop.classList.remove('over'); measureFiles(e.dataTransfer.files); });
$('material').addEventListener('change', () => { $('custom-density').hidden = $('material').value !== 'custom'; });
