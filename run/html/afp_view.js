/* stitchsim HTML report: laid fibre-placement material in the 3D view (docs/report-format.md,
 * "HTML report", "Laid tows").
 *
 * Plain ES2017, no modules, inlined after report.js: sets window.stitchsimAfpView, which
 * report.js calls with its helpers once the 3D view exists and the data has a "laid" part.
 * Draws each ply's tows as ribbons on the part (one merged, indexed BufferGeometry per ply,
 * lifted along the surface normal), colours them by ply, course or verdict, lets the reader
 * show, hide and peel plies, draws the off-part path, and answers a click on a ribbon with
 * the ply, course, tow, programme line, head state, steering radius and fibre angle there.
 */
(function () {
  'use strict';

  const LIFT_MM = 0.25;         // ribbons float this far above the surface they lie on
  const PICK_STACK_MM = 3;      // hits this close behind the first belong to one stack
  const CLICK_SLOP_PX = 4;      // a press that moves further is an orbit drag, not a pick
  const PLY_COLOURS = [0x17becf, 0xff7f0e, 0x9467bd, 0x8c564b, 0xe377c2, 0x1f77b4, 0x2ca02c,
    0xbcbd22, 0x7f7f7f, 0x393b79, 0xad494a, 0x637939, 0x8c6d31, 0x843c39, 0x7b4173, 0x3182bd];
  const VERDICT_RGB = {clean: [0.16, 0.62, 0.27], warning: [0.95, 0.55, 0.0],
    error: [0.86, 0.1, 0.1]};
  const HIGHLIGHT_COLOUR = 0xffd400;
  const TOW_SHADE = 0.82;       // odd tows' colour scale
  const OFF_PART_COLOUR = 0x6a3fb5;

  function decodeLaid(laid, h) {
    const k = Number(laid.tows);
    const per = Number(laid.bounds_per_station);
    if (!(k >= 1 && k <= 64)) throw new Error('laid.tows is ' + laid.tows);
    if (per !== k + 1 && per !== 2) throw new Error('laid.bounds_per_station is ' + per);
    const s = laid.strips || {};
    const st = laid.stations || {};
    const f32 = (o, key, what) => h.typed(o[key], Float32Array, what + '.' + key);
    const i32 = (o, key, what) => h.typed(o[key], Int32Array, what + '.' + key);
    const d = {
      tows: k, per: per, outer: per === 2, note: String(laid.note || ''),
      perTow: laid.figures_per_tow !== false,
      line: i32(s, 'line', 'laid.strips'), ply: i32(s, 'ply', 'laid.strips'),
      course: i32(s, 'course', 'laid.strips'), maskLo: h.typed(s.mask_lo, Uint32Array,
        'laid.strips.mask_lo'), maskHi: h.typed(s.mask_hi, Uint32Array, 'laid.strips.mask_hi'),
      feed: f32(s, 'feed', 'laid.strips'), first: i32(s, 'first', 'laid.strips'),
      steer: f32(s, 'steer', 'laid.strips'), angle: f32(s, 'angle', 'laid.strips'),
      fraction: f32(st, 'fraction', 'laid.stations'), tool: f32(st, 'tool', 'laid.stations'),
      normal: f32(st, 'normal', 'laid.stations'), bound: f32(st, 'boundary', 'laid.stations'),
      plyNames: laid.ply_names || {},
    };
    const n = d.line.length;
    const m = d.fraction.length;
    ['ply', 'course', 'maskLo', 'maskHi', 'feed'].forEach((key) =>
      h.expectLength(d[key], n, 'laid.strips.' + key));
    h.expectLength(d.first, n + 1, 'laid.strips.first');
    h.expectLength(d.steer, d.perTow ? n * k : n, 'laid.strips.steer');
    h.expectLength(d.angle, d.perTow ? n * k : n, 'laid.strips.angle');
    h.expectLength(d.tool, 3 * m, 'laid.stations.tool');
    h.expectLength(d.normal, 3 * m, 'laid.stations.normal');
    h.expectLength(d.bound, 3 * m * per, 'laid.stations.boundary');
    for (let i = 0; i < n; i++) {
      if (!(d.first[i] <= d.first[i + 1]) || d.first[i + 1] > m) {
        throw new Error('laid.strips.first is not ascending within the stations');
      }
    }
    return d;
  }

  function towLaid(d, i, t) {  // t 1-based
    return t <= 32 ? ((d.maskLo[i] >>> (t - 1)) & 1) === 1 : ((d.maskHi[i] >>> (t - 33)) & 1) === 1;
  }

  function laidTows(d, i) {
    const out = [];
    for (let t = 1; t <= d.tows; t++) if (towLaid(d, i, t)) out.push(t);
    return out;
  }

  function ranges(tows) {  // [1,2,3,7] -> "1-3, 7"
    const parts = [];
    for (let a = 0; a < tows.length;) {
      let b = a;
      while (b + 1 < tows.length && tows[b + 1] === tows[b] + 1) b++;
      parts.push(a === b ? String(tows[a]) : tows[a] + '\u2013' + tows[b]);
      a = b + 1;
    }
    return parts.join(', ') || 'none';
  }

  // The ribbons of one strip: [left boundary index, right boundary index, tow] per ribbon.
  function stripRibbons(d, i) {
    const tows = laidTows(d, i);
    if (!tows.length) return [];
    if (d.outer) return [[0, 1, 0]];  // one ribbon: outermost laid boundaries
    return tows.map((t) => [t - 1, t, t]);
  }

  // One mesh per ply: each ribbon its own two columns of vertices (left and right edge at
  // every station, lifted along the normal), so neighbouring tows can be shaded apart.
  function buildPlyMesh(d, strips, order, THREE) {
    let verts = 0;
    let faces = 0;
    strips.forEach((i) => {
      const m = d.first[i + 1] - d.first[i];
      const r = stripRibbons(d, i).length;
      verts += r * m * 2;
      faces += r * Math.max(0, m - 1) * 2;
    });
    const pos = new Float32Array(3 * verts);
    const vertTow = new Uint8Array(verts);
    const index = new Uint32Array(3 * faces);
    const faceStrip = new Int32Array(faces);
    const faceTow = new Uint8Array(faces);
    const faceStation = new Int32Array(faces);
    const stripVerts = [];
    let v = 0;
    let f = 0;
    // Writes station st's boundary b at vertex k; false when it left the surface.
    const put = (k, st, b) => {
      let ok = true;
      for (let c = 0; c < 3; c++) {
        const x = d.bound[3 * (st * d.per + b) + c] + LIFT_MM * d.normal[3 * st + c];
        ok = ok && isFinite(x);
        pos[3 * k + c] = x;
      }
      if (!ok) for (let c = 0; c < 3; c++) pos[3 * k + c] = d.tool[3 * st + c];
      return ok;
    };
    strips.forEach((i) => {
      const s0 = d.first[i];
      const m = d.first[i + 1] - s0;
      const v0 = v;
      stripRibbons(d, i).forEach((r) => {
        const ok = new Uint8Array(m);
        for (let s = 0; s < m; s++) {
          ok[s] = put(v + 2 * s, s0 + s, r[0]) & put(v + 2 * s + 1, s0 + s, r[1]);
          vertTow[v + 2 * s] = vertTow[v + 2 * s + 1] = r[2];
        }
        for (let s = 0; s + 1 < m; s++) {
          const a = v + 2 * s;
          // A quad with a boundary off the surface: both triangles degenerate (not drawn).
          index.set(ok[s] && ok[s + 1] ? [a, a + 1, a + 2, a + 1, a + 3, a + 2] :
            [a, a, a, a, a, a], 3 * f);
          for (let q = 0; q < 2; q++, f++) {
            faceStrip[f] = i;
            faceTow[f] = r[2];
            faceStation[f] = s0 + s;
          }
        }
        v += 2 * m;
      });
      stripVerts.push([i, v0, v - v0]);
    });
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(pos, 3));
    geometry.setAttribute('color', new THREE.BufferAttribute(new Float32Array(3 * verts), 3));
    geometry.setIndex(new THREE.BufferAttribute(index, 1));
    geometry.computeVertexNormals();
    geometry.computeBoundingSphere();
    // Unlit: a tow reads in its colour whichever way the skin faces the light.
    const material = new THREE.MeshBasicMaterial({vertexColors: THREE.VertexColors,
      side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: -1 - order,
      polygonOffsetUnits: -4 - 4 * order});
    const mesh = new THREE.Mesh(geometry, material);
    mesh.userData = {faceStrip: faceStrip, faceTow: faceTow, faceStation: faceStation,
      stripVerts: stripVerts, vertTow: vertTow, order: order};
    return mesh;
  }

  function courseColour(course, THREE) {
    const c = new THREE.Color();
    c.setHSL(((course * 0.618034) % 1 + 1) % 1, 0.65, 0.72);  // lighter than any ply colour
    return c;
  }

  function findingSeverityByLine(findings) {
    const by = {};
    findings.forEach((f) => {
      if (!(f.line > 0)) return;
      if (f.severity === 'error' || !by[f.line]) by[f.line] = f.severity;
    });
    return by;
  }

  function colourMeshes(view) {
    const THREE = window.THREE;
    const d = view.d;
    view.meshes.forEach((mesh) => {
      const attr = mesh.geometry.attributes.color;
      mesh.userData.stripVerts.forEach(([i, v0, count]) => {
        let c;
        if (view.mode === 'course') {
          c = courseColour(d.course[i] + 7 * d.ply[i], THREE);
        } else if (view.mode === 'verdict') {
          const sev = view.severity[d.line[i]];
          c = new THREE.Color().fromArray(sev ? VERDICT_RGB[sev] : VERDICT_RGB.clean);
        } else {
          c = new THREE.Color(PLY_COLOURS[mesh.userData.order % PLY_COLOURS.length]);
        }
        // Odd tows a shade darker: the tows of a strip read apart in any colouring.
        for (let k = v0; k < v0 + count; k++) {
          const shade = mesh.userData.vertTow[k] % 2 ? TOW_SHADE : 1;
          attr.setXYZ(k, c.r * shade, c.g * shade, c.b * shade);
        }
      });
      attr.needsUpdate = true;
    });
    view.viewer.requestRender();
  }

  function applyVisibility(view) {
    view.meshes.forEach((mesh) => {
      const o = mesh.userData.order;
      mesh.visible = view.shown[o] && o < view.peel;
    });
    view.viewer.requestRender();
  }

  // Off-part path: the thinned tool path's steps that end on a line laying nothing.
  function offPartPath(h, laying, THREE) {
    const pa = h.path();
    const pts = [];
    for (let i = 1; i < pa.lines.length; i++) {
      if (laying.has(pa.lines[i])) continue;
      for (const j of [i - 1, i]) pts.push(pa.positions[3 * j], pa.positions[3 * j + 1],
        pa.positions[3 * j + 2]);
    }
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(new Float32Array(pts), 3));
    const line = new THREE.LineSegments(g, new THREE.LineBasicMaterial({color: OFF_PART_COLOUR}));
    line.frustumCulled = false;
    line.name = 'afp-off-part';
    return line;
  }

  // What lies under a client point: the topmost visible ply's strip and tow there.
  function pickAt(view, clientX, clientY) {
    const THREE = window.THREE;
    const viewer = view.viewer;
    const rect = viewer.renderer.domElement.getBoundingClientRect();
    const ndc = new THREE.Vector2(2 * (clientX - rect.left) / rect.width - 1,
      -2 * (clientY - rect.top) / rect.height + 1);
    const ray = new THREE.Raycaster();
    ray.setFromCamera(ndc, viewer.camera);
    viewer.scene.updateMatrixWorld(true);
    const hits = ray.intersectObjects(view.meshes.filter((m) => m.visible), false);
    if (!hits.length) return null;
    const scale = viewer.part.matrixWorld.getMaxScaleOnAxis();  // m per mm
    let best = hits[0];
    hits.forEach((x) => {
      if (x.distance - hits[0].distance <= PICK_STACK_MM * scale &&
          x.object.userData.order > best.object.userData.order) best = x;
    });
    const u = best.object.userData;
    const i = u.faceStrip[best.faceIndex];
    const s = u.faceStation[best.faceIndex];
    const local = viewer.part.worldToLocal(best.point.clone());
    return describe(view, i, s, u.faceTow[best.faceIndex], [local.x, local.y, local.z]);
  }

  // The tow at a point of strip i between stations s and s + 1 (outer-only ribbons: the laid
  // tow whose share of the width the point falls in).
  function describe(view, i, s, tow, p) {
    const d = view.d;
    const at = (arr, st, c) => arr[3 * st + c];
    const dir = [0, 1, 2].map((c) => at(d.tool, s + 1, c) - at(d.tool, s, c));
    const len2 = dir.reduce((a, x) => a + x * x, 0);
    const rel = [0, 1, 2].map((c) => p[c] - at(d.tool, s, c));
    const f = len2 > 0 ? Math.min(1, Math.max(0, rel.reduce((a, x, c) => a + x * dir[c], 0) /
      len2)) : 0;
    const tool = [0, 1, 2].map((c) => at(d.tool, s, c) + f * dir[c]);
    if (!tow) {
      const tows = laidTows(d, i);
      const bl = [0, 1, 2].map((c) => d.bound[3 * (s * 2) + c]);
      const br = [0, 1, 2].map((c) => d.bound[3 * (s * 2 + 1) + c]);
      const across = [0, 1, 2].map((c) => br[c] - bl[c]);
      const w2 = across.reduce((a, x) => a + x * x, 0);
      const g = w2 > 0 ? [0, 1, 2].reduce((a, c) => a + (p[c] - bl[c]) * across[c], 0) / w2 : 0;
      const span = tows[tows.length - 1] - tows[0] + 1;
      tow = tows[0] + Math.min(span - 1, Math.max(0, Math.floor(g * span)));
    }
    const fig = d.perTow ? i * d.tows + tow - 1 : i;
    return {
      strip: i, ply: d.ply[i], ply_name: d.plyNames[d.ply[i]] || '', course: d.course[i],
      tow: tow, line: d.line[i], point_mm: p, tool_mm: tool,
      fraction: d.fraction[s] + f * (d.fraction[s + 1] - d.fraction[s]),
      active_tows: laidTows(d, i), feed_mm_s: d.feed[i],
      steering_radius_mm: d.steer[fig], fiber_angle_deg: d.angle[fig],
      approximate_tow: d.outer, figures_per_tow: d.perTow,
    };
  }

  function showPick(view, info) {
    const h = view.h;
    const box = h.$('afp-pick');
    box.textContent = '';
    ['ply', 'course', 'tow', 'line'].forEach((key) =>
      box.setAttribute('data-' + key, info ? String(info[key]) : ''));
    if (!info) {
      box.appendChild(h.el('p', {class: 'muted', text: 'Nothing laid under that point.'}));
      return;
    }
    const of = info.figures_per_tow ? 'this tow and line' : 'this line\'s tows';
    const mm = (a) => a.map((x) => h.fmt(Number(x.toFixed(2)))).join(', ') + ' mm';
    const rows = [
      ['Ply', 'P' + info.ply + (info.ply_name ? ' (' + info.ply_name + ')' : '')],
      ['Course', String(info.course)],
      ['Tow', String(info.tow) + (info.approximate_tow ? ' (from its share of the strip: ' +
        'the page draws whole strips)' : '')],
      ['Programme line', null],
      ['Head at that line', 'tool ' + mm(info.tool_mm) + ' (' + h.fmt(Number(
        (100 * info.fraction).toFixed(1))) + ' % along the line)'],
      ['Active tows', ranges(info.active_tows)],
      ['Feed', h.fmt(info.feed_mm_s) + ' mm/s'],
      ['Steering radius', isFinite(info.steering_radius_mm) ? h.fmt(info.steering_radius_mm) +
        ' mm (the smallest afp.steering_radius measured on ' + of + ')' :
        (info.steering_radius_mm === Infinity ? 'straight (no turn measured on ' + of + ')' :
          'not measured (the rule did not run)')],
      ['Fibre angle', isFinite(info.fiber_angle_deg) ? h.fmt(info.fiber_angle_deg) +
        '\u00b0 off the ply angle (the largest measured on ' + of + ')' : 'not measured'],
      ['Point', mm(info.point_mm)],
    ];
    const table = h.el('table', {}, [h.el('tbody', {}, rows.map(([k, v]) => {
      const cell = h.el('td', {text: v === null ? '' : v});
      if (v === null) {
        cell.appendChild(h.el('a', {href: '#', text: 'line ' + h.fmt(info.line),
          onclick: (e) => { e.preventDefault(); h.setLine(info.line); }}));
      }
      return h.el('tr', {}, [h.el('th', {text: k}), cell]);
    }))]);
    box.appendChild(table);
  }

  function highlightStrip(view, i, tow) {
    const THREE = window.THREE;
    if (view.highlight) {
      view.viewer.part.remove(view.highlight);
      view.highlight.geometry.dispose();
      view.highlight = null;
    }
    if (i < 0) return;
    const d = view.d;
    const sub = {};
    Object.keys(d).forEach((key) => { sub[key] = d[key]; });
    // The strip alone, its mask narrowed to the named tow when the finding names one.
    if (tow > 0 && !d.outer && towLaid(d, i, tow)) {
      sub.maskLo = new Uint32Array(d.maskLo.length);
      sub.maskHi = new Uint32Array(d.maskHi.length);
      if (tow <= 32) sub.maskLo[i] = 1 << (tow - 1); else sub.maskHi[i] = 1 << (tow - 33);
    }
    const mesh = buildPlyMesh(sub, [i], 40, THREE);
    mesh.material = new THREE.MeshBasicMaterial({color: HIGHLIGHT_COLOUR, side: THREE.DoubleSide,
      depthTest: false, transparent: true, opacity: 0.85});
    mesh.renderOrder = 12;
    mesh.name = 'afp-highlight';
    view.highlight = mesh;
    view.viewer.part.add(mesh);
    view.viewer.requestRender();
  }

  function buildControls(view, plies) {
    const h = view.h;
    const box = h.$('afp');
    box.hidden = false;
    const mode = h.el('select', {id: 'afp-colour', title: 'Colour the tows by'}, [
      h.el('option', {value: 'ply', text: 'by ply'}),
      h.el('option', {value: 'course', text: 'by course'}),
      h.el('option', {value: 'verdict', text: 'by verdict'})]);
    mode.addEventListener('change', () => { view.mode = mode.value; colourMeshes(view); });
    const peel = h.el('input', {id: 'afp-peel', type: 'range', min: '0', max: String(plies.length),
      value: String(plies.length), step: '1', 'aria-label': 'Peel to ply'});
    const peelText = h.el('span', {id: 'afp-peel-text'});
    const peelLabel = () => {
      const k = Number(peel.value);
      peelText.textContent = k >= plies.length ? 'all plies' : (k === 0 ? 'no ply' :
        'plies 1\u2013' + k + ' (P' + plies[k - 1] + ' on top)');
    };
    peel.addEventListener('input', () => { view.peel = Number(peel.value); peelLabel();
      applyVisibility(view); });
    peelLabel();
    const list = h.el('div', {id: 'afp-plies'});
    plies.forEach((p, o) => {
      const input = h.el('input', {type: 'checkbox', 'data-ply': String(p)});
      input.checked = true;
      input.addEventListener('change', () => { view.shown[o] = input.checked;
        applyVisibility(view); });
      const swatch = h.el('i', {style: 'background:#' + ('00000' + PLY_COLOURS[o %
        PLY_COLOURS.length].toString(16)).slice(-6)});
      const name = view.d.plyNames[p] ? ' ' + view.d.plyNames[p] : '';
      list.appendChild(h.el('label', {}, [input, swatch, ' ' + (o + 1) + '. P' + p + name]));
    });
    const controls = h.$('afp-controls');
    controls.appendChild(h.el('label', {}, ['Colour ', mode]));
    controls.appendChild(h.el('label', {}, ['Peel to ply ', peel, ' ', peelText]));
    controls.appendChild(list);
    if (view.d.note) h.$('afp-note').textContent = view.d.note;
    showPick(view, null);
    h.$('afp-pick').firstChild.textContent = 'Click a tow in the 3D view to see what laid it.';
  }

  function listenForPicks(view) {
    const dom = view.viewer.renderer.domElement;
    let down = null;
    dom.addEventListener('pointerdown', (e) => { down = [e.clientX, e.clientY]; });
    dom.addEventListener('pointerup', (e) => {
      if (!down || Math.hypot(e.clientX - down[0], e.clientY - down[1]) > CLICK_SLOP_PX) return;
      down = null;
      const info = view.h.guard('picking a tow', () => pickAt(view, e.clientX, e.clientY));
      showPick(view, info);
      highlightStrip(view, info ? info.strip : -1, info ? info.tow : 0);
    });
  }

  // Entry point from report.js. h: its helpers; returns legend rows and the finding hook.
  window.stitchsimAfpView = function (h) {
    const THREE = window.THREE;
    const d = decodeLaid(h.data.laid, h);
    const plies = [];
    const byPly = {};
    for (let i = 0; i < d.line.length; i++) {
      if (!byPly[d.ply[i]]) { byPly[d.ply[i]] = []; plies.push(d.ply[i]); }
      byPly[d.ply[i]].push(i);
    }
    const view = {h: h, d: d, viewer: h.viewer, mode: 'ply', peel: plies.length,
      shown: plies.map(() => true), severity: findingSeverityByLine(h.findings), highlight: null};
    view.meshes = plies.map((p, o) => {
      const mesh = buildPlyMesh(d, byPly[p], o, THREE);
      mesh.name = 'afp-ply-' + p;
      h.viewer.part.add(mesh);
      return mesh;
    });
    // The stitching preform block (the scene's preform thickness over the mould) would hide
    // the material laid on the mould: hidden here, a view toggle brings it back.
    const preform = [];
    h.viewer.world.traverse((o) => { if (o.isMesh && o.name === 'part_preform') preform.push(o); });
    preform.forEach((o) => { o.visible = false; });
    const laying = new Set(Array.from(d.line));
    h.viewer.part.add(offPartPath(h, laying, THREE));
    colourMeshes(view);
    buildControls(view, plies);
    listenForPicks(view);
    const lineStrip = {};
    for (let i = 0; i < d.line.length; i++) lineStrip[d.line[i]] = i;
    return {
      legend: [{css: [0.09, 0.75, 0.81], label: 'laid tows (ribbons; colour: see Laid material)'},
        {css: [0.42, 0.25, 0.71], label: 'off-part path', bar: true}],
      toggles: [['tows', () => view.meshes], ['off-part path', () =>
        h.viewer.part.children.filter((o) => o.name === 'afp-off-part')],
      ['preform block', () => preform, true]],
      onFinding: (f) => {
        const i = lineStrip[f.line];
        const m = /\btow (\d+)/.exec(String(f.subject || '') + ' ' + String(f.message || ''));
        highlightStrip(view, i === undefined ? -1 : i, m ? Number(m[1]) : 0);
      },
      api: {
        plies: plies.slice(),
        pickAt: (x, y) => pickAt(view, x, y),
        // Client (page) coordinates of a part-frame point (mm), as the camera shows it.
        screenOf: (p) => {
          const v = h.viewer;
          v.scene.updateMatrixWorld(true);
          const w = new THREE.Vector3(p[0], p[1], p[2]).applyMatrix4(v.part.matrixWorld)
            .project(v.camera);
          const r = v.renderer.domElement.getBoundingClientRect();
          return {x: r.left + (w.x + 1) / 2 * r.width, y: r.top + (1 - w.y) / 2 * r.height,
            inside: Math.abs(w.x) < 1 && Math.abs(w.y) < 1 && w.z < 1};
        },
        // Camera close to a part-frame point (mm), r_m metres away, looking down its normal.
        frame: (p, r, dir) => h.frame(p, r, dir),
        render: () => h.viewer.render(),
      },
    };
  };
})();
