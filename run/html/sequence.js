// The `stitchsim sequence --html` page (docs/sequence.md, "The page"): the courses on the part,
// the original and the new off-part paths (side by side, one alone, or overlaid), the course
// order numbered, plies shown or hidden, and the report's figures in tables. Every figure is
// read from the embedded report (data.report), never computed here. For tests:
// window.stitchsimReady, window.stitchsimErrors, window.stitchsimSequence.
(function () {
  'use strict';
  const errors = [];
  window.stitchsimErrors = errors;
  const COLORS = { before: 0xc62828, after: 0x1f5fbf, course: 0x8a94a3 };

  function fail(message) {
    errors.push(message);
    const box = document.getElementById('error');
    box.style.display = 'block';
    box.textContent = 'This page cannot be shown: ' + message;
  }

  function readData() {
    const node = document.getElementById('stitchsim-data');
    const data = JSON.parse(node.textContent);
    if (data.stitchsim_sequence_page !== 1 || !data.report || !data.after) {
      throw new Error('not a stitchsim sequence page (stitchsim_sequence_page 1)');
    }
    return data;
  }

  // Text of a number at `dec` decimals; data-path / data-dec say where it comes from (tests).
  function cell(row, value, dec, path) {
    const td = document.createElement('td');
    if (value === null || value === undefined) {
      td.textContent = '-';
    } else if (typeof value === 'number') {
      td.textContent = value.toFixed(dec);
      if (path) {
        td.dataset.path = path;
        td.dataset.dec = String(dec);
      }
    } else {
      td.textContent = String(value);
      td.className = 'l';
    }
    row.appendChild(td);
    return td;
  }

  function change(row, before, after) {
    const td = cell(row, before > 0 ? -100 * (before - after) / before : 0, 1, null);
    td.textContent += ' %';
    td.classList.add(after < before ? 'better' : after > before ? 'worse' : 'same');
  }

  function table(id, headers, fill) {
    const t = document.createElement('table');
    const head = t.insertRow();
    for (const h of headers) {
      const th = document.createElement('th');
      th.textContent = h;
      head.appendChild(th);
    }
    fill(t);
    document.getElementById(id).appendChild(t);
  }

  const MEASURES = [['axes', 3], ['time_s', 3], ['tool_mm', 1], ['timed_s', 3]];
  const FLOWN_HEAD = ['flown off-part before (mm)', 'after (mm)', 'change',
                      'flown total before (mm)', 'after (mm)', 'change', 'lay-up (mm)'];
  const MEASURE_HEAD = ['axes before', 'after', 'time before (s)', 'after (s)',
                        'tool before (mm)', 'after (mm)', 'timed before (s)', 'after (s)'];

  // The flown columns and every measure, before and after, from one report object `o` at `path`.
  function figures(row, o, path, flown) {
    const f = o.flown_tool_mm;
    const fp = path + '.flown_tool_mm.';
    cell(row, f.offpart_before, 1, fp + 'offpart_before');
    cell(row, f.offpart_after, 1, fp + 'offpart_after');
    change(row, f.offpart_before, f.offpart_after);
    cell(row, f.total_before, 1, fp + 'total_before');
    cell(row, f.total_after, 1, fp + 'total_after');
    change(row, f.total_before, f.total_after);
    cell(row, f.layup, 1, fp + 'layup');
    for (const [m, dec] of MEASURES) {
      cell(row, o.offpart_before[m], dec, path + '.offpart_before.' + m);
      cell(row, o.offpart_after[m], dec, path + '.offpart_after.' + m);
    }
    return flown;
  }

  function tables(report) {
    table('plyTable', ['ply', 'name', 'courses'].concat(FLOWN_HEAD, MEASURE_HEAD), (t) => {
      report.plies.forEach((p, i) => {
        const row = t.insertRow();
        cell(row, 'P' + p.ply);
        cell(row, p.comment || '');
        cell(row, p.courses, 0, 'plies.' + i + '.courses');
        figures(row, p, 'plies.' + i);
      });
    });
    table('totalTable', ['', 'courses'].concat(FLOWN_HEAD, MEASURE_HEAD), (t) => {
      const row = t.insertRow();
      cell(row, 'whole programme');
      cell(row, report.order.length, 0, null);
      figures(row, report.totals, 'totals');
    });
    const totals = report.totals;
    const p = document.createElement('p');
    p.className = 'note';
    p.textContent = 'Cost ' + report.cost + ', solver ' + report.solver +
        (report.bidirectional ? ', bidirectional' : '') +
        (report.return_home ? ', return home' : '') + '; sets\u2019 cost ' +
        totals.cost.toFixed(4) + ', lower bound ' +
        (totals.bound === null ? '-' : totals.bound.toFixed(4)) + '; joined sets saved ' +
        report.joined_saving.toFixed(4) +
        (report.kept_programme ? '; the programme\u2019s order was kept' : '') + '.';
    document.getElementById('totalTable').appendChild(p);
    table('setTable', ['set', 'plies', 'courses', 'solver', 'stopped', 'kept original',
                       'programme order cost', 'cost', 'optimum', 'lower bound', 'bound by',
                       'gap (%)', 'solver s'], (t) => {
      report.sets.forEach((s, i) => {
        const row = t.insertRow();
        const at = 'sets.' + i + '.';
        cell(row, s.set, 0, at + 'set');
        cell(row, s.plies.join(', '));
        cell(row, s.courses, 0, at + 'courses');
        cell(row, s.solver);
        cell(row, s.status);
        cell(row, s.kept_original ? 'yes' : 'no');
        cell(row, s.original_cost, 4, at + 'original_cost');
        cell(row, s.cost, 4, at + 'cost');
        cell(row, s.optimum, 4, at + 'optimum');
        cell(row, s.bound, 4, at + 'bound');
        cell(row, s.bound_method || '-');
        const gap = cell(row, s.gap === null ? null : 100 * s.gap, 3, null);
        if (s.gap !== null) gap.dataset.gap = at + 'gap';
        cell(row, s.seconds, 2, at + 'seconds');
      });
    });
  }

  function lineOf(points, color) {
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.Float32BufferAttribute(points.flat(), 3));
    return new THREE.Line(g, new THREE.LineBasicMaterial({ color }));
  }

  function label(text, at, size, color) {
    const c = document.createElement('canvas');
    c.width = 64;
    c.height = 32;
    const g = c.getContext('2d');
    g.fillStyle = 'rgba(255,255,255,0.85)';
    g.fillRect(0, 0, 64, 32);
    g.fillStyle = color;
    g.font = 'bold 24px sans-serif';
    g.textAlign = 'center';
    g.textBaseline = 'middle';
    g.fillText(text, 32, 17);
    const sprite = new THREE.Sprite(new THREE.SpriteMaterial({
      map: new THREE.CanvasTexture(c), depthTest: false }));
    sprite.position.set(at[0], at[1], at[2]);
    sprite.scale.set(size, size / 2, 1);
    sprite.renderOrder = 2;
    return sprite;
  }

  // One programme's drawing: per ply a group of its stretches and one of its order numbers.
  function pathGroups(data, which, bounds) {
    const path = data[which];
    const plyOf = (c) => data.courses[c].ply;
    const lastPly = plyOf(path.visits[path.visits.length - 1].course);
    const lines = {}, numbers = {};
    for (const p of data.report.plies) {
      lines[p.ply] = new THREE.Group();
      numbers[p.ply] = new THREE.Group();
    }
    for (const s of path.stretches) {
      lines[s.course < 0 ? lastPly : plyOf(s.course)].add(lineOf(s.points, COLORS[which]));
    }
    path.visits.forEach((v, i) => {
      numbers[plyOf(v.course)].add(label(String(i + 1), v.start, bounds.size / 14,
                                         which === 'before' ? '#c62828' : '#1f5fbf'));
    });
    return { lines, numbers };
  }

  function boundsOf(data) {
    const box = new THREE.Box3();
    for (const c of data.courses) for (const p of c.points) box.expandByPoint(new THREE.Vector3(...p));
    for (const w of ['before', 'after']) {
      for (const s of data[w].stretches) for (const p of s.points) {
        box.expandByPoint(new THREE.Vector3(...p));
      }
    }
    const size = box.getSize(new THREE.Vector3());
    return { box, center: box.getCenter(new THREE.Vector3()), size: Math.max(size.x, size.y, size.z, 1) };
  }

  function makeView(host, data, bounds) {
    const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    renderer.setClearColor(0xffffff);
    host.appendChild(renderer.domElement);
    const scene = new THREE.Scene();
    const camera = new THREE.PerspectiveCamera(35, 1, bounds.size / 1000, bounds.size * 20);
    camera.up.set(0, 0, 1);
    const c = bounds.center;
    camera.position.set(c.x - 0.2 * bounds.size, c.y - 0.9 * bounds.size, c.z + 1.6 * bounds.size);
    const controls = new THREE.OrbitControls(camera, renderer.domElement);
    controls.target.copy(c);
    controls.update();
    const courses = {};
    for (const p of data.report.plies) courses[p.ply] = new THREE.Group();
    for (const co of data.courses) courses[co.ply].add(lineOf(co.points, COLORS.course));
    for (const g of Object.values(courses)) scene.add(g);
    const view = { host, renderer, scene, camera, controls, courses,
                   before: pathGroups(data, 'before', bounds),
                   after: pathGroups(data, 'after', bounds) };
    for (const w of ['before', 'after']) {
      for (const g of Object.values(view[w].lines)) scene.add(g);
      for (const g of Object.values(view[w].numbers)) scene.add(g);
    }
    view.render = () => {
      const w = host.clientWidth, h = host.clientHeight;
      if (w > 0 && h > 0) {
        renderer.setSize(w, h, false);
        renderer.domElement.style.width = w + 'px';
        renderer.domElement.style.height = h + 'px';
        camera.aspect = w / h;
        camera.updateProjectionMatrix();
      }
      renderer.render(scene, camera);
    };
    controls.addEventListener('change', view.render);
    return view;
  }

  function main() {
    let data;
    try {
      data = readData();
    } catch (e) {
      fail(String(e.message || e));
      return;
    }
    const report = data.report;
    document.getElementById('subtitle').textContent = report.program + ' \u2192 ' + report.output +
        ' (scene ' + report.scene + '): ' + report.order.length + ' courses, ' +
        report.plies.length + ' plies, ' + report.sets.length + ' precedence sets';
    tables(report);
    const bounds = boundsOf(data);
    const views = ['viewA', 'viewB'].map((id) =>
      makeView(document.querySelector('#' + id + ' .canvas'), data, bounds));
    const shown = new Set(report.plies.map((p) => p.ply));
    const toggles = document.getElementById('plyToggles');
    for (const p of report.plies) {
      const l = document.createElement('label');
      const box = document.createElement('input');
      box.type = 'checkbox';
      box.checked = true;
      box.dataset.ply = String(p.ply);
      box.addEventListener('change', () => {
        if (box.checked) shown.add(p.ply); else shown.delete(p.ply);
        update();
      });
      l.appendChild(box);
      l.appendChild(document.createTextNode(' P' + p.ply + ' ' +
                                            (p.comment || '').replace(/^PLY\s*/, '')));
      toggles.appendChild(l);
    }
    const mode = document.getElementById('mode');
    const numbers = document.getElementById('showNumbers');
    // What each view shows per mode: [A's paths, B's paths] (B hidden when empty).
    const MODES = { side: [['before'], ['after']], original: [['before'], []],
                    new: [['after'], []], overlay: [['before', 'after'], []] };
    const TITLES = { before: 'original order', after: 'new order' };
    function update() {
      const plan = MODES[mode.value];
      document.getElementById('viewB').classList.toggle('hidden', plan[1].length === 0);
      views.forEach((v, k) => {
        const paths = plan[k];
        document.getElementById(k ? 'titleB' : 'titleA').textContent =
            paths.map((w) => TITLES[w]).join(' and ') +
            (paths.length ? ' (' + paths.map((w) => 'off-part ' +
              report.totals.flown_tool_mm['offpart_' + w].toFixed(1) + ' mm').join(', ') + ')' : '');
        for (const p of report.plies) {
          v.courses[p.ply].visible = shown.has(p.ply);
          for (const w of ['before', 'after']) {
            const on = shown.has(p.ply) && paths.includes(w);
            v[w].lines[p.ply].visible = on;
            // Overlaid, the new order's numbers only (two sets of numbers on one spot clash).
            v[w].numbers[p.ply].visible = on && numbers.checked &&
                (paths.length === 1 || w === 'after');
          }
        }
        v.render();
      });
    }
    mode.addEventListener('change', update);
    numbers.addEventListener('change', update);
    window.addEventListener('resize', update);
    update();
    window.stitchsimSequence = { data, update };
    window.stitchsimReady = errors.length === 0;
  }

  window.addEventListener('error', (e) => fail(String(e.message)));
  if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', main);
  else main();
})();
