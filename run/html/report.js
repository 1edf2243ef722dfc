/* stitchsim HTML report: the page app (docs/report-format.md, "HTML report").
 *
 * Plain ES2017, no modules: `stitchsim verify --html` inlines this file into
 * app/html/report.html after three.js (global THREE) and OrbitControls, and the report data
 * as JSON in <script id="stitchsim-data">. Nothing is fetched. Errors are shown on the page
 * (#error), never left to a blank page. For tests: window.stitchsimReady, window.stitchsim.
 */
(function () {
  'use strict';

  const VERDICT_COLOURS = [[0.16, 0.62, 0.27], [0.95, 0.55, 0.0], [0.86, 0.1, 0.1]];
  const VERDICT_NAMES = ['clean stitch', 'warning', 'error'];
  const VERDICT_SIZES_PX = [3, 5, 6];
  const PATH_COLOUR = 0x8aa4c8;
  const PATH_DONE_COLOUR = 0x1f5fbf;
  const TOOL_COLOUR = 0xd81b9a;
  const FINDING_COLOUR = 0xc62828;
  const FINDINGS_PAGE = 500;
  const LITTLE_ENDIAN = new Uint8Array(new Uint16Array([1]).buffer)[0] === 1;

  const state = {
    data: null, lines: 1, line: 1, poses: null, stitches: null, path: null, findings: [],
    viewer: null, plots: [], filter: {rule: '', severity: ''}, shownFindings: 0,
    selectedFinding: -1, afp: null, playing: false, playPos: 0, playTime: 0, lastFrame: 0, errors: [],
  };

  // ---------- small helpers ----------
  function $(id) { return document.getElementById(id); }

  function el(tag, attrs, children) {
    const node = document.createElement(tag);
    Object.keys(attrs || {}).forEach((k) => {
      if (k === 'text') node.textContent = attrs[k];
      else if (k === 'class') node.className = attrs[k];
      else if (k.startsWith('on')) node.addEventListener(k.slice(2), attrs[k]);
      else node.setAttribute(k, attrs[k]);
    });
    (children || []).forEach((c) => node.appendChild(typeof c === 'string' ?
      document.createTextNode(c) : c));
    return node;
  }

  function showError(message) {
    state.errors.push(message);
    window.stitchsimErrors = state.errors;
    const box = $('error');
    if (!box) return;
    box.hidden = false;
    box.textContent = 'This report could not be shown completely:\n' + state.errors.join('\n');
  }

  // Runs one part of the page; a failure is shown and the other parts still run.
  function guard(what, fn) {
    try {
      return fn();
    } catch (e) {
      showError(what + ': ' + (e && e.message ? e.message : String(e)));
      return null;
    }
  }

  function fmt(v) {
    if (v === null || v === undefined || typeof v !== 'number' || !isFinite(v)) return '\u2013';
    if (Number.isInteger(v)) return v.toLocaleString('en-US');
    if (Math.abs(v) >= 1000) return Math.round(v).toLocaleString('en-US');
    return String(Number(v.toPrecision(4)));
  }

  function fmtTime(s) {
    if (typeof s !== 'number' || !isFinite(s)) return '\u2013';
    if (s < 60) return s.toFixed(1) + ' s';
    const h = Math.floor(s / 3600);
    const m = Math.floor((s % 3600) / 60);
    const sec = Math.floor(s % 60);
    const two = (x) => (x < 10 ? '0' : '') + x;
    return (h ? h + ':' + two(m) : m) + ':' + two(sec) + ' (' + fmt(Math.round(s)) + ' s)';
  }

  function withUnit(v, unit) {
    return typeof v === 'number' && isFinite(v) ? fmt(v) + unit : '\u2013';
  }

  // A rule id that may wrap after its dots and underscores (zero-width spaces, display only).
  function breakable(id) { return String(id || '').replace(/([._])/g, '$1\u200b'); }

  function list(x) { return Array.isArray(x) ? x : []; }

  // Index of the first element > value in an ascending typed array (binary search).
  function upperBound(arr, value) {
    let lo = 0;
    let hi = arr.length;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (arr[mid] <= value) lo = mid + 1; else hi = mid;
    }
    return lo;
  }

  // ---------- data decoding ----------
  function base64Bytes(text, what) {
    if (text === undefined || text === null || text === '') return new Uint8Array(0);
    if (typeof text !== 'string') throw new Error(what + ' is not a base64 string');
    let bin;
    try {
      bin = atob(text);
    } catch (e) {
      throw new Error(what + ' is not valid base64');
    }
    const out = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; i++) out[i] = bin.charCodeAt(i);
    return out;
  }

  // A little-endian typed array from base64 ("b64" fields of the data).
  function typed(text, Type, what) {
    const bytes = base64Bytes(text, what);
    const size = Type.BYTES_PER_ELEMENT;
    if (bytes.length % size) {
      throw new Error(what + ': ' + bytes.length + ' bytes is not a whole number of values');
    }
    if (LITTLE_ENDIAN) return new Type(bytes.buffer, 0, bytes.length / size);
    const view = new DataView(bytes.buffer);
    const out = new Type(bytes.length / size);
    const get = {1: 'getUint8', 4: Type === Float32Array ? 'getFloat32' :
      (Type === Int32Array ? 'getInt32' : 'getUint32')}[size];
    for (let i = 0; i < out.length; i++) out[i] = view[get](i * size, true);
    return out;
  }

  function expectLength(arr, n, what) {
    if (arr.length !== n) throw new Error(what + ' has ' + arr.length + ' values, expected ' + n);
  }

  function readData() {
    const node = $('stitchsim-data');
    if (!node) throw new Error('no report data in this file (the <script id="stitchsim-data">)');
    let data;
    try {
      data = JSON.parse(node.textContent);
    } catch (e) {
      throw new Error('the report data is not valid JSON (' + e.message + ')');
    }
    if (!data || typeof data !== 'object') throw new Error('the report data is not an object');
    if (data.format !== 'stitchsim-html-1') {
      throw new Error('unknown report data format "' + data.format + '" (expected stitchsim-html-1)');
    }
    if (!data.summary || typeof data.summary !== 'object') throw new Error('no summary');
    return data;
  }

  function decodeProgramme(data) {
    const cell = data.cell || {};
    const joints = list(cell.joints);
    const st = data.stitches || {};
    const stitches = {
      positions: typed(st.positions, Float32Array, 'stitches.positions'),
      verdict: typed(st.verdict, Uint8Array, 'stitches.verdict'),
      lines: typed(st.lines, Int32Array, 'stitches.lines'),
    };
    const count = stitches.positions.length / 3;
    if (!Number.isInteger(count)) throw new Error('stitches.positions is not xyz triples');
    expectLength(stitches.verdict, count, 'stitches.verdict');
    expectLength(stitches.lines, count, 'stitches.lines');
    stitches.total = typeof st.total === 'number' ? st.total : count;
    const pa = data.path || {};
    const path = {
      positions: typed(pa.positions, Float32Array, 'path.positions'),
      lines: typed(pa.lines, Int32Array, 'path.lines'),
    };
    expectLength(path.positions, path.lines.length * 3, 'path.positions');
    const po = data.poses || {};
    const poses = {
      lines: typed(po.lines, Int32Array, 'poses.lines'),
      q: typed(po.q, Float32Array, 'poses.q'),
      t: typed(po.t, Float32Array, 'poses.t'),
      dof: joints.length,
      home: list(cell.home).map(Number),
    };
    expectLength(poses.q, poses.lines.length * poses.dof, 'poses.q');
    expectLength(poses.t, poses.lines.length, 'poses.t');
    while (poses.home.length < poses.dof) poses.home.push(0);
    return {stitches: stitches, path: path, poses: poses};
  }

  // ---------- programme position: joints, time, stitch at a line ----------
  // Joints at a programme line: exact at a recorded line, else interpolated between the
  // neighbouring recorded lines (line 0 = home), held after the last one.
  function poseAt(line) {
    const p = state.poses;
    const n = p.lines.length;
    const dof = p.dof;
    if (n === 0) return {q: p.home.slice(), t: 0, exact: false};
    const i = upperBound(p.lines, line) - 1;
    const row = (k) => Array.from(p.q.subarray(k * dof, k * dof + dof));
    if (i >= 0 && p.lines[i] === line) return {q: row(i), t: p.t[i], exact: true};
    if (i === n - 1) return {q: row(i), t: p.t[i], exact: false};
    const l0 = i < 0 ? 0 : p.lines[i];
    const q0 = i < 0 ? p.home : row(i);
    const t0 = i < 0 ? 0 : p.t[i];
    const l1 = p.lines[i + 1];
    const q1 = row(i + 1);
    const f = l1 > l0 ? (line - l0) / (l1 - l0) : 0;
    return {
      q: q0.map((v, j) => v + (q1[j] - v) * f), t: t0 + (p.t[i + 1] - t0) * f, exact: false,
    };
  }

  // The programme line reached at time t (s), for real-time playback.
  function lineAtTime(t) {
    const p = state.poses;
    const n = p.lines.length;
    if (n === 0) return state.lines;
    const i = upperBound(p.t, t) - 1;
    if (i < 0) return Math.max(1, Math.round(p.t[0] > 0 ? p.lines[0] * t / p.t[0] : 1));
    if (i >= n - 1) return state.lines;
    const dt = p.t[i + 1] - p.t[i];
    const f = dt > 0 ? (t - p.t[i]) / dt : 0;
    return Math.round(p.lines[i] + (p.lines[i + 1] - p.lines[i]) * f);
  }

  function stitchAt(line) {
    const s = state.stitches;
    const n = s.lines.length;
    const k = upperBound(s.lines, line);
    if (n === 0 || s.total <= n) return {text: fmt(k), total: s.total};
    return {text: '\u2248' + fmt(Math.round(k * s.total / n)), total: s.total};
  }

  // Tool point (part frame, mm) at a line, along the thinned path.
  function toolPointAt(line) {
    const pa = state.path;
    const n = pa.lines.length;
    if (n === 0) return null;
    const i = Math.max(0, upperBound(pa.lines, line) - 1);
    const j = Math.min(n - 1, i + 1);
    const l0 = pa.lines[i];
    const l1 = pa.lines[j];
    const f = l1 > l0 ? Math.min(1, Math.max(0, (line - l0) / (l1 - l0))) : 0;
    const p = pa.positions;
    return [0, 1, 2].map((c) => p[3 * i + c] + (p[3 * j + c] - p[3 * i + c]) * f);
  }

  // ---------- header, rules, findings, gallery ----------
  function buildHeader(s) {
    const box = $('summary');
    const kv = (key, value) => el('div', {class: 'kv'}, [el('span', {text: key}),
      el('span', {text: value === undefined || value === null ? '\u2013' : String(value)})]);
    const verdict = s.verdict === 'pass' ? 'pass' : 'fail';
    box.appendChild(el('span', {class: 'badge ' + verdict, id: 'verdict',
      text: verdict.toUpperCase()}));
    box.appendChild(kv('Programme', s.program));
    box.appendChild(kv('Scene', s.scene || s.scene_file));
    box.appendChild(kv('Head', s.head));
    box.appendChild(kv('Errors', fmt(s.errors)));
    box.appendChild(kv('Warnings', fmt(s.warnings)));
    box.appendChild(kv('Lines', fmt(s.lines)));
    box.appendChild(kv(s.kind === 'afp' ? 'Moves' : 'Stitches',
      fmt(s.kind === 'afp' ? s.moves : s.stitches)));
    box.appendChild(kv('Cycle time', fmtTime(s.cycle_time_s)));
    if (typeof s.cycle_time_timed_s === 'number') {
      box.appendChild(kv('Timed cycle', fmtTime(s.cycle_time_timed_s)));
    }
    box.appendChild(kv('stitchsim', s.tool_version));
    document.title = 'stitchsim ' + verdict.toUpperCase() + ' \u2013 ' + (s.program || 'report');
  }

  function buildRules(data) {
    const table = $('rule-table');
    const head = ['Rule', 'Checked', 'Errors', 'Warnings', 'Worst', 'Limits'];
    table.appendChild(el('thead', {}, [el('tr', {}, head.map((h, i) =>
      el('th', {class: i > 0 && i < 4 ? 'num' : '', text: h})))]));
    const body = el('tbody');
    list(data.rules).forEach((r) => {
      const unit = r.unit ? ' ' + r.unit : '';
      const worst = el('td', {text: withUnit(r.worst_value, unit)});
      if (typeof r.worst_line === 'number' && r.worst_line > 0) {
        worst.appendChild(document.createTextNode(' at '));
        worst.appendChild(el('a', {href: '#', text: 'line ' + fmt(r.worst_line),
          onclick: (e) => { e.preventDefault(); e.stopPropagation(); setLine(r.worst_line); }}));
      }
      const cls = r.errors > 0 ? 'has-error' : (r.warnings > 0 ? 'has-warning' : '');
      const tr = el('tr', {class: cls, 'data-rule': r.id, title: (r.description || '') +
        (r.truncated ? ' (finding list truncated)' : '') + ' \u2013 click: show its findings'}, [
        el('td', {text: breakable(r.id) + (r.truncated ? ' *' : '')}), el('td', {class: 'num',
          text: fmt(r.checked)}),
        el('td', {class: 'num' + (r.errors ? ' sev-error' : ''), text: fmt(r.errors)}),
        el('td', {class: 'num' + (r.warnings ? ' sev-warning' : ''), text: fmt(r.warnings)}),
        worst, el('td', {}, [el('span', {class: 'sev-error', text: 'E'}), ' ' +
          withUnit(r.error_limit, unit), el('br'), el('span', {class: 'sev-warning', text: 'W'}),
          ' ' + withUnit(r.warning_limit, unit)]),
      ]);
      tr.addEventListener('click', () => {
        state.filter.rule = state.filter.rule === r.id ? '' : r.id;
        $('filter-rule').value = state.filter.rule;
        markRuleRow();
        renderFindings();
      });
      body.appendChild(tr);
    });
    table.appendChild(body);
    const skipped = list(data.skipped);
    if (skipped.length) {
      $('skipped').appendChild(el('p', {class: 'muted', text: 'Skipped: ' +
        skipped.map((s) => s.id + ' (' + s.reason + ')').join('; ')}));
    }
  }

  function markRuleRow() {
    document.querySelectorAll('#rule-table tbody tr').forEach((tr) =>
      tr.classList.toggle('selected', tr.getAttribute('data-rule') === state.filter.rule));
  }

  function buildFindingFilters() {
    const rules = Array.from(new Set(state.findings.map((f) => f.rule))).sort();
    const ruleSelect = el('select', {id: 'filter-rule', title: 'Show one rule'},
      [el('option', {value: '', text: 'all rules'})].concat(rules.map((r) =>
        el('option', {value: r, text: r}))));
    const sevSelect = el('select', {id: 'filter-severity', title: 'Show one severity'}, [
      el('option', {value: '', text: 'errors and warnings'}),
      el('option', {value: 'error', text: 'errors'}),
      el('option', {value: 'warning', text: 'warnings'})]);
    ruleSelect.addEventListener('change', () => {
      state.filter.rule = ruleSelect.value;
      markRuleRow();
      renderFindings();
    });
    sevSelect.addEventListener('change', () => {
      state.filter.severity = sevSelect.value;
      renderFindings();
    });
    const box = $('finding-filters');
    box.appendChild(ruleSelect);
    box.appendChild(sevSelect);
    box.appendChild(el('span', {id: 'finding-count', class: 'muted'}));
    const head = ['Rule', 'Severity', 'Line', 'Stitch', 'Value', 'Limit', 'Subject', 'Message'];
    $('finding-table').appendChild(el('thead', {}, [el('tr', {}, head.map((h, i) =>
      el('th', {class: i >= 2 && i <= 5 ? 'num' : '', text: h})))]));
    $('finding-table').appendChild(el('tbody'));
  }

  function filteredFindings() {
    const f = state.filter;
    const out = [];
    state.findings.forEach((x, i) => {
      if ((!f.rule || x.rule === f.rule) && (!f.severity || x.severity === f.severity)) {
        out.push(i);
      }
    });
    return out;
  }

  function findingRow(i) {
    const f = state.findings[i];
    const unit = f.unit ? ' ' + f.unit : '';
    const tr = el('tr', {'data-line': String(f.line), 'data-finding': String(i),
      class: i === state.selectedFinding ? 'selected' : ''}, [
      el('td', {text: breakable(f.rule)}),
      el('td', {class: 'sev-' + f.severity, text: f.severity}),
      el('td', {class: 'num', text: fmt(f.line)}), el('td', {class: 'num',
        text: typeof f.stitch === 'number' && f.stitch > 0 ? fmt(f.stitch) : '\u2013'}),
      el('td', {class: 'num', text: withUnit(f.value, unit)}),
      el('td', {class: 'num', text: withUnit(f.limit, unit)}),
      el('td', {text: f.subject || ''}), el('td', {text: f.message || ''})]);
    tr.addEventListener('click', () => goToFinding(i));
    return tr;
  }

  function renderFindings(more) {
    const rows = filteredFindings();
    const body = $('finding-table').tBodies[0];
    if (!more) {
      body.textContent = '';
      state.shownFindings = 0;
    }
    const end = Math.min(rows.length, state.shownFindings + FINDINGS_PAGE);
    const frag = document.createDocumentFragment();
    for (let k = state.shownFindings; k < end; k++) frag.appendChild(findingRow(rows[k]));
    body.appendChild(frag);
    state.shownFindings = end;
    $('finding-count').textContent = rows.length + ' of ' + state.findings.length + ' shown' +
      (state.filter.rule ? ' (rule ' + state.filter.rule + ')' : '');
    const moreBox = $('finding-more');
    moreBox.textContent = '';
    if (end < rows.length) {
      moreBox.appendChild(el('button', {type: 'button', text: 'Show ' +
        Math.min(FINDINGS_PAGE, rows.length - end) + ' more (' + (rows.length - end) + ' left)',
        onclick: () => renderFindings(true)}));
    }
    if (!state.findings.length) {
      body.appendChild(el('tr', {}, [el('td', {colspan: '8', class: 'muted',
        text: 'No findings: every checked rule passed.'})]));
    }
  }

  function buildGallery(data) {
    const thumbs = $('gallery-thumbs');
    const shots = list(data.snapshots);
    if (!shots.length) {
      thumbs.appendChild(el('p', {class: 'muted', text: 'No snapshots in this report.'}));
      return;
    }
    const box = $('lightbox');
    const big = box.querySelector('img');
    box.addEventListener('click', () => { box.hidden = true; });
    shots.forEach((s) => {
      const src = 'data:image/png;base64,' + s.png;
      const fig = el('figure', {title: s.name + ' \u2013 click to enlarge'}, [
        el('img', {src: src, alt: s.name, loading: 'lazy'}),
        el('figcaption', {text: s.name})]);
      fig.addEventListener('click', () => {
        big.src = src;
        big.alt = s.name;
        box.hidden = false;
      });
      thumbs.appendChild(fig);
    });
  }

  // ---------- 3D view ----------
  function discTexture(ring) {
    const c = document.createElement('canvas');
    c.width = c.height = 64;
    const g = c.getContext('2d');
    g.beginPath();
    g.arc(32, 32, ring ? 26 : 30, 0, 2 * Math.PI);
    if (ring) {
      g.lineWidth = 8;
      g.strokeStyle = '#fff';
      g.stroke();
    } else {
      g.fillStyle = '#fff';
      g.fill();
    }
    return new THREE.CanvasTexture(c);
  }

  function pointsObject(positions, colour, sizePx, texture, onTop) {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    const material = new THREE.PointsMaterial({color: colour, size: sizePx,
      sizeAttenuation: false, map: texture, alphaTest: 0.5, depthTest: !onTop});
    const points = new THREE.Points(geometry, material);
    points.frustumCulled = false;
    if (onTop) {
      material.transparent = true;  // drawn in the last pass, after the x-ray copies
      points.renderOrder = 10;
    }
    return points;
  }

  // A faint copy drawn through everything (x-ray), as a child sharing the geometry: stitches
  // and paths inside or under a part's surface (a preform over the stitch plane) stay visible,
  // dimmed where something hides them; hiding the object hides its copy.
  function addXray(object, opacity) {
    const material = object.material.clone();
    material.transparent = true;
    material.opacity = opacity;
    material.depthTest = false;
    material.depthWrite = false;
    if (material.alphaTest) material.alphaTest = 0.05;
    const copy = object.isPoints ? new THREE.Points(object.geometry, material) :
      new THREE.Line(object.geometry, material);
    copy.frustumCulled = false;
    copy.renderOrder = 5;
    object.add(copy);
    return object;
  }

  // A capsule of radius r and half-length h along z (MuJoCo), as a lathe about y turned to z.
  function capsuleGeometry(r, h) {
    const profile = [];
    const steps = 8;
    for (let i = 0; i <= steps; i++) {
      const a = -Math.PI / 2 + (i / steps) * (Math.PI / 2);
      profile.push(new THREE.Vector2(r * Math.cos(a), -h + r * Math.sin(a)));
    }
    for (let i = 0; i <= steps; i++) {
      const a = (i / steps) * (Math.PI / 2);
      profile.push(new THREE.Vector2(r * Math.cos(a), h + r * Math.sin(a)));
    }
    return new THREE.LatheBufferGeometry(profile, 20).rotateX(Math.PI / 2);
  }

  function meshGeometry(mesh, index) {
    const vertices = typed(mesh.vertices, Float32Array, 'cell.meshes[' + index + '].vertices');
    const faces = typed(mesh.faces, Uint32Array, 'cell.meshes[' + index + '].faces');
    if (vertices.length % 3 || faces.length % 3) {
      throw new Error('cell.meshes[' + index + '] is not xyz / ijk triples');
    }
    const count = vertices.length / 3;
    for (let i = 0; i < faces.length; i++) {
      if (faces[i] >= count) throw new Error('cell.meshes[' + index + '] face index out of range');
    }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(vertices, 3));
    geometry.setIndex(new THREE.BufferAttribute(faces, 1));
    geometry.computeVertexNormals();
    return geometry;
  }

  function geomGeometry(g, meshGeometries) {
    const s = list(g.size).map(Number);
    while (s.length < 3) s.push(0);
    switch (g.type) {
      case 'box': return new THREE.BoxBufferGeometry(2 * s[0], 2 * s[1], 2 * s[2]);
      case 'sphere': return new THREE.SphereBufferGeometry(s[0], 24, 16);
      case 'ellipsoid': return new THREE.SphereBufferGeometry(1, 24, 16).scale(s[0], s[1], s[2]);
      case 'capsule': return capsuleGeometry(s[0], s[1]);
      case 'cylinder':
        return new THREE.CylinderBufferGeometry(s[0], s[0], 2 * s[1], 24).rotateX(Math.PI / 2);
      case 'plane': return new THREE.PlaneBufferGeometry(2 * (s[0] || 15), 2 * (s[1] || 15));
      case 'mesh':
        if (!meshGeometries[g.mesh]) throw new Error('geom ' + g.name + ': no mesh ' + g.mesh);
        return meshGeometries[g.mesh];
      default: throw new Error('geom ' + g.name + ': unknown type ' + g.type);
    }
  }

  function material(rgba, cache) {
    const c = list(rgba).length === 4 ? rgba : [0.6, 0.6, 0.6, 1];
    const key = c.join(',');
    if (!cache[key]) {
      cache[key] = new THREE.MeshPhongMaterial({
        color: new THREE.Color(c[0], c[1], c[2]), shininess: 25, side: THREE.DoubleSide,
        transparent: c[3] < 1, opacity: c[3], depthWrite: c[3] >= 1,
        // Surfaces pushed back in depth: stitches, paths and drawings lie on them (a part's
        // surface holds its stitches at depth 0) and must win the depth test.
        polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 4,
      });
    }
    return cache[key];
  }

  function vec3(a) { return new THREE.Vector3(Number(a[0]), Number(a[1]), Number(a[2])); }
  function quat(a) {  // MuJoCo [w, x, y, z]
    return new THREE.Quaternion(Number(a[1]), Number(a[2]), Number(a[3]), Number(a[0]))
        .normalize();
  }

  // One THREE.Group per body, nested as in the model; FK = each body's matrix from its
  // pos/quat in the parent and its joint value (MuJoCo: hinge about axis through the anchor,
  // slide along axis, both in the body frame).
  function buildCell(cell, root) {
    const meshGeometries = list(cell.meshes).map(meshGeometry);
    const materials = {};
    const bodies = list(cell.bodies).map((b, i) => {
      if (!(b.parent < i)) throw new Error('body ' + b.name + ': parent ' + b.parent + ' >= ' + i);
      const group = new THREE.Group();
      group.name = b.name;
      group.matrixAutoUpdate = false;
      const base = new THREE.Matrix4().compose(vec3(b.pos || [0, 0, 0]),
        quat(b.quat || [1, 0, 0, 0]), new THREE.Vector3(1, 1, 1));
      list(b.geoms).forEach((g) => {
        const rgba = list(g.rgba);
        if (rgba.length === 4 && rgba[3] <= 0) return;
        const mesh = new THREE.Mesh(geomGeometry(g, meshGeometries), material(g.rgba, materials));
        mesh.name = g.name || '';
        mesh.userData.plane = g.type === 'plane';  // left out of camera fits
        mesh.position.copy(vec3(g.pos || [0, 0, 0]));
        mesh.quaternion.copy(quat(g.quat || [1, 0, 0, 0]));
        group.add(mesh);
      });
      if (b.parent < 0) root.add(group);
      return {group: group, base: base, joint: b.joint || null, parent: b.parent};
    });
    bodies.forEach((b) => { if (b.parent >= 0) bodies[b.parent].group.add(b.group); });
    return bodies;
  }

  function poseCell(bodies, q) {
    const m = new THREE.Matrix4();
    bodies.forEach((b) => {
      b.group.matrix.copy(b.base);
      const j = b.joint;
      if (j && typeof j.index === 'number' && j.index < q.length) {
        const v = q[j.index] - (j.ref || 0);  // MuJoCo turns a joint by q - qpos0
        const axis = vec3(j.axis || [0, 0, 1]).normalize();
        if (j.type === 'slide') {
          m.makeTranslation(axis.x * v, axis.y * v, axis.z * v);
        } else {
          const anchor = vec3(j.pos || [0, 0, 0]);
          m.makeTranslation(anchor.x, anchor.y, anchor.z)
              .multiply(new THREE.Matrix4().makeRotationAxis(axis, v))
              .multiply(new THREE.Matrix4().makeTranslation(-anchor.x, -anchor.y, -anchor.z));
        }
        b.group.matrix.multiply(m);
      }
      b.group.matrixWorldNeedsUpdate = true;
    });
  }

  function buildPartLayer(part, data) {
    const disc = discTexture(false);
    const st = state.stitches;
    const n = st.verdict.length;
    const legend = [];
    for (let v = 2; v >= 0; v--) {
      let count = 0;
      for (let i = 0; i < n; i++) if (st.verdict[i] === v) count++;
      if (!count) continue;
      const pos = new Float32Array(count * 3);
      for (let i = 0, k = 0; i < n; i++) {
        if (st.verdict[i] !== v) continue;
        pos[k++] = st.positions[3 * i];
        pos[k++] = st.positions[3 * i + 1];
        pos[k++] = st.positions[3 * i + 2];
      }
      const c = VERDICT_COLOURS[v];
      const points = pointsObject(pos, new THREE.Color(c[0], c[1], c[2]), VERDICT_SIZES_PX[v],
        disc, false);
      points.renderOrder = 3 - v;
      points.name = 'stitches-' + v;
      part.add(addXray(points, 0.4));
      const shown = st.total > n ? ' shown' : '';
      legend.push({css: c, label: VERDICT_NAMES[v] + ' (' + fmt(count) + shown + ')'});
    }
    list(data.drawings).forEach((d, i) => {
      if (data.laid && d.label === 'afp_laid') return;  // drawn as ribbons (afp_view.js)
      const pos = typed(d.positions, Float32Array, 'drawings[' + i + '].positions');
      const c = list(d.rgba).length === 4 ? d.rgba : [0.2, 0.4, 0.9, 1];
      const points = pointsObject(pos, new THREE.Color(c[0], c[1], c[2]), 2, disc, false);
      points.name = 'drawing-' + d.label;
      part.add(addXray(points, 0.3));
      legend.push({css: c, label: d.label});
    });
    return legend;
  }

  function pathObjects(part) {
    const positions = state.path.positions;
    const all = new THREE.BufferGeometry();
    all.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    const full = new THREE.Line(all, new THREE.LineBasicMaterial({color: PATH_COLOUR,
      transparent: true, opacity: 0.55}));
    const doneGeometry = new THREE.BufferGeometry();
    doneGeometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    const done = new THREE.Line(doneGeometry, new THREE.LineBasicMaterial({
      color: PATH_DONE_COLOUR}));
    full.frustumCulled = done.frustumCulled = false;
    part.add(addXray(full, 0.25));
    part.add(addXray(done, 0.5));
    return {full: full, done: done};
  }

  function createViewer(data) {
    if (typeof THREE === 'undefined') throw new Error('three.js is missing from this file');
    if (typeof THREE.OrbitControls !== 'function') throw new Error('OrbitControls is missing');
    const box = $('view3d');
    let renderer;
    try {
      renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
    } catch (e) {
      throw new Error('WebGL is not available in this browser (' + e.message + ')');
    }
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    renderer.setClearColor(0xe9edf2);
    box.appendChild(renderer.domElement);
    const scene = new THREE.Scene();
    const camera = new THREE.PerspectiveCamera(40, 1, 0.005, 500);
    camera.up.set(0, 0, 1);  // MuJoCo: z up
    scene.add(camera);
    const sky = new THREE.HemisphereLight(0xffffff, 0x7d838c, 0.65);
    sky.position.set(0, 0, 1);  // sky above in z, not three.js's default y
    scene.add(sky);
    const light = new THREE.DirectionalLight(0xffffff, 0.65);
    light.position.set(0.5, 1, 1.5);
    camera.add(light);
    const world = new THREE.Group();
    scene.add(world);
    const cell = data.cell || {};
    const bodies = buildCell(cell, world);
    const partIndex = cell.part_body;
    const partBody = typeof partIndex === 'number' && bodies[partIndex] ?
      bodies[partIndex].group : world;
    const part = new THREE.Group();  // part frame, mm
    part.scale.set(0.001, 0.001, 0.001);
    partBody.add(part);
    const legend = guard('drawing the stitches', () => buildPartLayer(part, data)) || [];
    const path = pathObjects(part);
    const tool = pointsObject(new Float32Array(3), TOOL_COLOUR, 13, discTexture(false), true);
    const marker = pointsObject(new Float32Array(3), FINDING_COLOUR, 30, discTexture(true), true);
    marker.visible = false;
    part.add(tool);
    part.add(marker);
    const controls = new THREE.OrbitControls(camera, renderer.domElement);
    controls.enableDamping = false;
    controls.screenSpacePanning = true;
    let dirty = true;
    const viewer = {
      renderer: renderer, scene: scene, camera: camera, controls: controls, bodies: bodies,
      part: part, partBody: partBody, path: path, tool: tool, marker: marker, legend: legend,
      world: world,
      requestRender: () => { dirty = true; },
      render: () => {
        dirty = false;
        renderer.render(scene, camera);
      },
      frame: () => { if (dirty) viewer.render(); },
    };
    controls.enableKeys = false;  // the arrow keys belong to the slider
    controls.addEventListener('change', () => {
      // Keep the depth range around what is looked at, close up or from afar.
      const dist = camera.position.distanceTo(controls.target);
      camera.near = Math.max(0.0005, dist / 500);
      camera.far = dist * 50 + 100;
      camera.updateProjectionMatrix();
      viewer.requestRender();
    });
    const resize = () => {
      const w = Math.max(1, box.clientWidth);
      const h = Math.max(1, box.clientHeight);
      renderer.setSize(w, h);
      camera.aspect = w / h;
      camera.updateProjectionMatrix();
      viewer.requestRender();
    };
    resize();
    window.addEventListener('resize', resize);
    viewer.resize = resize;
    return viewer;
  }

  function setViewerLine(viewer, line, q) {
    poseCell(viewer.bodies, q);
    const p = toolPointAt(line);
    viewer.tool.visible = !!p;
    if (p) {
      const attr = viewer.tool.geometry.attributes.position;
      attr.setXYZ(0, p[0], p[1], p[2]);
      attr.needsUpdate = true;
    }
    viewer.path.done.geometry.setDrawRange(0, upperBound(state.path.lines, line));
    viewer.requestRender();
  }

  // Bounding box (world) of an object's meshes and points; empty objects are skipped.
  function worldBox(object) {
    state.viewer.scene.updateMatrixWorld(true);
    const box = new THREE.Box3();
    object.traverse((o) => {
      if (!o.visible || !o.geometry || o.userData.plane || o === state.viewer.tool ||
          o === state.viewer.marker) {
        return;
      }
      if (!o.geometry.boundingBox) o.geometry.computeBoundingBox();
      const b = o.geometry.boundingBox.clone();
      if (!b.isEmpty()) box.union(b.applyMatrix4(o.matrixWorld));
    });
    return box;
  }

  // Camera looking along -direction at centre, far enough to show a sphere of radius r (m).
  function frameSphere(viewer, centre, r, direction) {
    const cam = viewer.camera;
    const dir = (direction || cam.position.clone().sub(viewer.controls.target)).normalize();
    const fov = THREE.MathUtils ? THREE.MathUtils.degToRad(cam.fov) : cam.fov * Math.PI / 180;
    const dist = r / Math.sin(Math.min(fov, fov * cam.aspect) / 2);
    cam.position.copy(centre).addScaledVector(dir, dist);
    viewer.controls.target.copy(centre);
    viewer.controls.update();
    viewer.requestRender();
  }

  function fitPart(viewer) {
    let box = worldBox(viewer.part);
    if (box.isEmpty()) box = worldBox(viewer.partBody);
    if (box.isEmpty()) box = worldBox(viewer.world);
    const sphere = box.getBoundingSphere(new THREE.Sphere());
    viewer.partRadius = Math.max(sphere.radius, 0.05);
    // The part and some room around it, so the head and the arm near it show.
    frameSphere(viewer, sphere.center, viewer.partRadius * 1.3 + 0.6,
      new THREE.Vector3(0.55, -1, 0.8));
  }

  function fitCell(viewer) {
    const sphere = worldBox(viewer.world).getBoundingSphere(new THREE.Sphere());
    frameSphere(viewer, sphere.center, Math.max(sphere.radius, 0.1) * 0.9, null);
  }

  function partPointWorld(viewer, p) {
    viewer.scene.updateMatrixWorld(true);
    return new THREE.Vector3(p[0], p[1], p[2]).applyMatrix4(viewer.part.matrixWorld);
  }

  // "Go to this finding" in the view: marker at its point, camera turned and zoomed to it.
  function focusFinding(viewer, f) {
    const p = Array.isArray(f.position_mm) && f.position_mm.length === 3 ? f.position_mm :
      (f.line > 0 ? toolPointAt(f.line) : null);
    viewer.marker.visible = !!p;
    if (!p) return;
    const attr = viewer.marker.geometry.attributes.position;
    attr.setXYZ(0, p[0], p[1], p[2]);
    attr.needsUpdate = true;
    const r = Math.min(Math.max(viewer.partRadius * 0.35, 0.35), 2.0);
    frameSphere(viewer, partPointWorld(viewer, p), r, null);
  }

  function buildLegend(viewer) {
    const box = $('legend');
    const item = (css, label, bar) => el('div', {}, [el('i', {class: bar ? 'bar' : '',
      style: 'background:' + css}), label]);
    const rgb = (c) => 'rgb(' + c.slice(0, 3).map((x) => Math.round(255 * x)).join(',') + ')';
    const hex = (n) => '#' + ('00000' + n.toString(16)).slice(-6);
    viewer.legend.forEach((l) => box.appendChild(item(rgb(l.css), l.label, false)));
    if (state.afp) state.afp.legend.forEach((l) => box.appendChild(item(rgb(l.css), l.label, l.bar)));
    box.appendChild(item(hex(PATH_DONE_COLOUR), 'path done', true));
    box.appendChild(item(hex(PATH_COLOUR), 'path to come', true));
    box.appendChild(item(hex(TOOL_COLOUR), 'tool point', false));
    const ring = item('transparent', 'selected finding', false);
    ring.firstChild.style.border = '2px solid ' + hex(FINDING_COLOUR);
    box.appendChild(ring);
  }

  function buildViewTools(viewer) {
    const box = $('view-tools');
    box.appendChild(el('button', {type: 'button', text: 'Fit part',
      onclick: () => fitPart(viewer)}));
    box.appendChild(el('button', {type: 'button', text: 'Fit cell',
      onclick: () => fitCell(viewer)}));
    const toggle = (label, objects, off) => {
      const input = el('input', {type: 'checkbox', 'data-toggle': label});
      input.checked = !off;
      input.addEventListener('change', () => {
        objects().forEach((o) => { o.visible = input.checked; });
        viewer.requestRender();
      });
      box.appendChild(el('label', {}, [input, ' ' + label]));
    };
    const byName = (prefix) => () => viewer.part.children.filter((o) =>
      o.name.startsWith(prefix));
    toggle('cell', () => {
      const meshes = [];
      viewer.world.traverse((o) => { if (o.isMesh) meshes.push(o); });
      return meshes;
    });
    if (byName('stitches-')().length) toggle('stitches', byName('stitches-'));
    toggle('path', () => [viewer.path.full, viewer.path.done]);
    if (list(state.data.drawings).length) toggle('drawings', byName('drawing-'));
    if (state.afp) state.afp.toggles.forEach(([label, objects, off]) => toggle(label, objects, off));
  }

  // ---------- plots: one per series, min/max envelope per bucket along the programme ----------
  const PLOT_MARGIN = {left: 58, right: 10, top: 16, bottom: 20};

  function niceStep(range, count) {
    const raw = range / Math.max(1, count);
    const mag = Math.pow(10, Math.floor(Math.log10(raw)));
    const norm = raw / mag;
    return (norm < 1.5 ? 1 : norm < 3 ? 2 : norm < 7 ? 5 : 10) * mag;
  }

  // A tick value with as many decimals as the tick step needs (1,657,970.5, not 1,657,971).
  function tickLabel(v, step) {
    const decimals = Math.min(12, Math.max(0, -Math.floor(Math.log10(step) + 1e-9)));
    return v.toLocaleString('en-US', {minimumFractionDigits: decimals,
      maximumFractionDigits: decimals});
  }

  function buildPlot(s, index) {
    const min = typed(s.min, Float32Array, 'series[' + index + '].min');
    const max = typed(s.max, Float32Array, 'series[' + index + '].max');
    expectLength(max, min.length, 'series[' + index + '].max');
    let lo = Infinity;
    let hi = -Infinity;
    for (let k = 0; k < min.length; k++) {
      if (min[k] < lo) lo = min[k];  // NaN compares false: skipped
      if (max[k] > hi) hi = max[k];
    }
    [s.error_limit, s.warning_limit].forEach((v) => {
      if (typeof v === 'number') { lo = Math.min(lo, v); hi = Math.max(hi, v); }
    });
    if (!isFinite(lo) || !isFinite(hi)) { lo = 0; hi = 1; }
    if (hi - lo < 1e-12) { lo -= 1; hi += 1; }
    const pad = (hi - lo) * 0.06;
    const unit = s.unit ? ' (' + s.unit + ')' : '';
    const limits = [];
    if (typeof s.error_limit === 'number') limits.push('error ' + fmt(s.error_limit));
    if (typeof s.warning_limit === 'number') limits.push('warning ' + fmt(s.warning_limit));
    const canvas = el('canvas', {'data-rule': s.rule || '', title: 'Click: go to this line'});
    const div = el('div', {class: 'plot'}, [el('div', {class: 'title'}, [
      (s.rule || '') + (s.subject ? ' \u00b7 ' + s.subject : '') + unit + ' ',
      el('small', {text: (s.lower_bound ? 'must stay above' : 'must stay below') +
        (limits.length ? ' \u2013 ' + limits.join(', ') : '')})]), canvas]);
    $('plot-list').appendChild(div);
    const plot = {s: s, min: min, max: max, lo: lo - pad, hi: hi + pad, canvas: canvas,
      base: null, first: Number(s.first_line) || 1, bucket: Math.max(1, Number(s.bucket_lines) || 1)};
    canvas.addEventListener('click', (e) => {
      const r = canvas.getBoundingClientRect();
      setLine(plotLineAt(plot, e.clientX - r.left));
    });
    return plot;
  }

  function plotArea(plot) {
    const w = plot.canvas.clientWidth;
    const h = plot.canvas.clientHeight;
    return {x0: PLOT_MARGIN.left, x1: w - PLOT_MARGIN.right, y0: PLOT_MARGIN.top,
      y1: h - PLOT_MARGIN.bottom, w: w, h: h};
  }

  function plotX(plot, line) {
    const a = plotArea(plot);
    return a.x0 + (a.x1 - a.x0) * (line - 1) / Math.max(1, state.lines - 1);
  }

  function plotLineAt(plot, x) {
    const a = plotArea(plot);
    const f = Math.min(1, Math.max(0, (x - a.x0) / Math.max(1, a.x1 - a.x0)));
    return Math.round(1 + f * (state.lines - 1));
  }

  // The static part of a plot (axes, limits, envelope) drawn once per size into plot.base.
  function drawPlotBase(plot) {
    const a = plotArea(plot);
    const dpr = window.devicePixelRatio || 1;
    const base = document.createElement('canvas');
    base.width = Math.max(1, Math.round(a.w * dpr));
    base.height = Math.max(1, Math.round(a.h * dpr));
    const g = base.getContext('2d');
    g.scale(dpr, dpr);
    g.fillStyle = '#fff';
    g.fillRect(0, 0, a.w, a.h);
    const y = (v) => a.y1 - (a.y1 - a.y0) * (v - plot.lo) / (plot.hi - plot.lo);
    const s = plot.s;
    g.font = '11px system-ui, sans-serif';
    g.fillStyle = '#687385';
    g.strokeStyle = '#e3e7ec';
    g.textAlign = 'right';
    g.textBaseline = 'middle';
    const step = niceStep(plot.hi - plot.lo, 4);
    for (let v = Math.ceil(plot.lo / step) * step; v <= plot.hi; v += step) {
      g.beginPath();
      g.moveTo(a.x0, Math.round(y(v)) + 0.5);
      g.lineTo(a.x1, Math.round(y(v)) + 0.5);
      g.stroke();
      g.fillText(tickLabel(Math.abs(v) < step * 1e-6 ? 0 : v, step), a.x0 - 4, y(v));
    }
    g.textAlign = 'left';
    g.textBaseline = 'top';
    g.fillText(s.unit || '', 2, 1);
    g.textAlign = 'center';
    const lstep = niceStep(state.lines, 6);
    for (let l = lstep; l <= state.lines; l += lstep) g.fillText(fmt(l), plotX(plot, l), a.y1 + 4);
    const limits = [[s.warning_limit, '#e08a00', [5, 4]], [s.error_limit, '#c62828', []]];
    limits.forEach((lim) => {
      if (typeof lim[0] !== 'number') return;
      g.strokeStyle = lim[1];
      g.setLineDash(lim[2]);
      g.lineWidth = 1.5;
      g.beginPath();
      g.moveTo(a.x0, y(lim[0]));
      g.lineTo(a.x1, y(lim[0]));
      g.stroke();
    });
    g.setLineDash([]);
    drawEnvelope(plot, g, a, y);
    g.strokeStyle = '#b8c0cc';
    g.lineWidth = 1;
    g.strokeRect(a.x0 + 0.5, a.y0 + 0.5, a.x1 - a.x0, a.y1 - a.y0);
    plot.base = base;
  }

  // Min/max per pixel column (many buckets share a column, or one bucket spans several),
  // coloured by the worst limit the column crosses.
  function drawEnvelope(plot, g, a, y) {
    const cols = Math.max(1, Math.ceil(a.x1 - a.x0));
    const cmin = new Float32Array(cols).fill(Infinity);
    const cmax = new Float32Array(cols).fill(-Infinity);
    for (let k = 0; k < plot.min.length; k++) {
      if (!(plot.min[k] <= plot.max[k])) continue;  // NaN: nothing checked in this bucket
      const l0 = plot.first + k * plot.bucket;
      const c0 = Math.floor(plotX(plot, l0) - a.x0);
      // The bucket's lines span x(l0) up to x(l0 + bucket), the next bucket's start.
      const c1 = Math.max(c0, Math.ceil(plotX(plot, l0 + plot.bucket) - a.x0) - 1);
      for (let c = Math.max(0, c0); c <= Math.min(cols - 1, c1); c++) {
        if (plot.min[k] < cmin[c]) cmin[c] = plot.min[k];
        if (plot.max[k] > cmax[c]) cmax[c] = plot.max[k];
      }
    }
    const s = plot.s;
    const beyond = (c, limit) => typeof limit === 'number' &&
      (s.lower_bound ? cmin[c] < limit : cmax[c] > limit);
    for (let c = 0; c < cols; c++) {
      if (!(cmin[c] <= cmax[c])) continue;
      g.fillStyle = beyond(c, s.error_limit) ? '#c62828' :
        (beyond(c, s.warning_limit) ? '#e08a00' : '#3d6fb6');
      const top = y(cmax[c]);
      g.fillRect(a.x0 + c, top, 1, Math.max(1.5, y(cmin[c]) - top));
    }
  }

  function drawPlot(plot) {
    const c = plot.canvas;
    const dpr = window.devicePixelRatio || 1;
    const w = Math.round(c.clientWidth * dpr);
    const h = Math.round(c.clientHeight * dpr);
    if (!plot.base || plot.base.width !== w || plot.base.height !== h) {
      c.width = w;
      c.height = h;
      drawPlotBase(plot);
    }
    const g = c.getContext('2d');
    g.setTransform(1, 0, 0, 1, 0, 0);
    g.drawImage(plot.base, 0, 0);
    g.scale(dpr, dpr);
    const a = plotArea(plot);
    const x = Math.round(plotX(plot, state.line)) + 0.5;
    g.strokeStyle = '#1d2530';
    g.lineWidth = 1;
    g.beginPath();
    g.moveTo(x, a.y0);
    g.lineTo(x, a.y1);
    g.stroke();
  }

  function buildPlots(data) {
    const series = list(data.series);
    if (!series.length) {
      $('plot-list').appendChild(el('p', {class: 'muted', text: 'No rule values recorded.'}));
    }
    series.forEach((s, i) => {
      const plot = guard('plot ' + (s.rule || i), () => buildPlot(s, i));
      if (plot) state.plots.push(plot);
    });
    state.plots.forEach(drawPlot);
  }

  // ---------- the programme slider, playback, "go to" ----------
  function setLine(line) {
    const l = Math.min(state.lines, Math.max(1, Math.round(Number(line) || 1)));
    state.line = l;
    $('slider').value = String(l);
    const pose = poseAt(l);
    const stitch = stitchAt(l);
    const readout = $('readout');
    const stitchText = stitch.total > 0 ? ' \u00b7 stitch ' + stitch.text + ' / ' +
      fmt(stitch.total) : '';  // none in fibre placement
    readout.textContent = 'line ' + fmt(l) + ' / ' + fmt(state.lines) + stitchText + ' \u00b7 t ' +
      fmtTime(pose.t) + ' \u00b7 ';
    readout.appendChild(el('span', {class: pose.exact ? '' : 'interp',
      text: pose.exact ? 'recorded pose' : 'interpolated'}));
    if (state.viewer) guard('posing the robot', () => setViewerLine(state.viewer, l, pose.q));
    state.plots.forEach(drawPlot);
  }

  function goToFinding(i) {
    const f = state.findings[i];
    if (!f) return;
    state.selectedFinding = i;
    document.querySelectorAll('#finding-table tr.selected').forEach((tr) =>
      tr.classList.remove('selected'));
    const row = document.querySelector('#finding-table tr[data-finding="' + i + '"]');
    if (row) row.classList.add('selected');
    setPlaying(false);
    if (f.line > 0) setLine(f.line);  // line 0: not tied to a line
    if (state.viewer) guard('showing the finding', () => focusFinding(state.viewer, f));
    if (state.afp) guard('showing the finding\'s tow', () => state.afp.onFinding(f));
  }

  const SPEEDS = [['l10', '10 lines/s'], ['l100', '100 lines/s'], ['l1000', '1,000 lines/s'],
    ['l10000', '10,000 lines/s'], ['t1', 'real time'], ['t10', '10\u00d7 real time'],
    ['t100', '100\u00d7 real time']];

  function setPlaying(on) {
    state.playing = on;
    $('play').innerHTML = on ? '&#10074;&#10074; Pause' : '&#9654; Play';
    if (on) {
      if (state.line >= state.lines) setLine(1);
      state.playPos = state.line;
      state.playTime = poseAt(state.line).t;
      state.lastFrame = performance.now();
    }
  }

  function playStep(now) {
    const dt = Math.min(0.25, (now - state.lastFrame) / 1000);
    state.lastFrame = now;
    const speed = $('speed').value;
    const rate = Number(speed.slice(1));
    let line;
    if (speed[0] === 't') {
      state.playTime += dt * rate;
      line = lineAtTime(state.playTime);
    } else {
      state.playPos += dt * rate;
      line = Math.floor(state.playPos);
    }
    if (line !== state.line) setLine(line);
    if (state.line >= state.lines) setPlaying(false);
  }

  function buildTimeline() {
    const slider = $('slider');
    slider.max = String(state.lines);
    slider.addEventListener('input', () => setLine(Number(slider.value)));
    const speed = $('speed');
    SPEEDS.forEach((s) => speed.appendChild(el('option', {value: s[0], text: s[1]})));
    // Default: the whole programme in about a minute.
    const want = state.lines / 60;
    speed.value = SPEEDS.filter((s) => s[0][0] === 'l').reduce((best, s) =>
      Math.abs(Math.log(Number(s[0].slice(1)) / want)) <
      Math.abs(Math.log(Number(best[0].slice(1)) / want)) ? s : best)[0];
    $('play').addEventListener('click', () => setPlaying(!state.playing));
    document.addEventListener('keydown', (e) => {
      const tag = e.target && e.target.tagName;
      if (e.key === ' ' && tag !== 'INPUT' && tag !== 'SELECT' && tag !== 'BUTTON') {
        e.preventDefault();
        setPlaying(!state.playing);
      } else if (e.key === 'Escape') {
        $('lightbox').hidden = true;
      }
    });
  }

  function loop(now) {
    if (state.playing) guard('playback', () => playStep(now));
    if (state.viewer) state.viewer.frame();
    window.requestAnimationFrame(loop);
  }

  // The laid-tow layer (afp_view.js, inlined after this file) with the helpers it shares.
  function startAfpView(data) {
    if (typeof window.stitchsimAfpView !== 'function') throw new Error('afp_view.js is missing');
    const viewer = state.viewer;
    return window.stitchsimAfpView({
      data: data, viewer: viewer, findings: state.findings, typed: typed,
      expectLength: expectLength, el: el, fmt: fmt, $: $, guard: guard, setLine: setLine,
      path: () => state.path,
      frame: (p, r, dir) => frameSphere(viewer, partPointWorld(viewer, p), r,
        dir ? new THREE.Vector3(dir[0], dir[1], dir[2])
          .transformDirection(viewer.part.matrixWorld) : null),
    });
  }

  // ---------- start ----------
  function main() {
    const data = guard('reading the report data', readData);
    if (!data) {
      window.stitchsimFailed = true;
      return;
    }
    state.data = data;
    state.lines = Math.max(1, Number(data.summary.lines) || 1);
    state.findings = list(data.findings);
    guard('the summary', () => buildHeader(data.summary));
    guard('the rule table', () => buildRules(data));
    guard('the findings', () => { buildFindingFilters(); renderFindings(); });
    guard('the snapshots', () => buildGallery(data));
    const programme = guard('decoding the programme data', () => decodeProgramme(data));
    if (!programme) {
      window.stitchsimFailed = true;
      return;
    }
    state.stitches = programme.stitches;
    state.path = programme.path;
    state.poses = programme.poses;
    buildTimeline();
    state.viewer = guard('the 3D view', () => createViewer(data));
    if (state.viewer && data.laid) state.afp = guard('the laid tows', () => startAfpView(data));
    guard('the plots', () => buildPlots(data));
    window.addEventListener('resize', () => state.plots.forEach(drawPlot));
    // Start where the work starts: the first recorded pose (line 1 is often still at home).
    const start = state.poses.lines.length ? Math.max(1, state.poses.lines[0]) : 1;
    setLine(start);
    if (state.viewer) {
      guard('the 3D view', () => {
        poseCell(state.viewer.bodies, poseAt(start).q);
        fitPart(state.viewer);
        buildLegend(state.viewer);
        buildViewTools(state.viewer);
        state.viewer.render();
      });
    }
    window.requestAnimationFrame(loop);
    window.stitchsimLoadMs = performance.now();
    if (state.errors.length) window.stitchsimFailed = true;
    else window.stitchsimReady = true;
  }

  window.stitchsim = {
    get line() { return state.line; },
    jointsAt: (line) => poseAt(Number(line)).q,
    goTo: (line) => setLine(line),
    goToFinding: goToFinding,
    get viewer() { return state.viewer; },  // for debugging in the browser console
    get afp() { return state.afp ? state.afp.api : null; },  // laid tows (afp_view.js)
  };
  window.addEventListener('error', (e) => showError('script error: ' + e.message));
  if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', main);
  else main();
})();
