// The laid-tow checks of check_report.mjs --afp-csv TOWS.csv --afp-program PROG.nc (docs/
// report-format.md, "HTML report", "Laid tows"): a click on a tow shows the course and tow the
// planner's tow CSV gives for that point and the programme line that the programme text gives
// for it (read here from the text: the laying G1 move of that course, with that tow on, whose
// segment the point lies beside); hiding a ply, peeling and the colour switch change the
// canvas.
import fs from 'node:fs';

const PICKS = 3;             // points tried, spread over the courses and tows
const END_MARGIN = 0.1;      // a point this close (share of its move) to a move's end is skipped
const CLOSE_UP_M = 0.12;     // camera distance scale for the picks (m)

// course,tow,segment,s_start_mm,s_end_mm,s_mm,left_xyz,right_xyz rows grouped by tow piece.
export function readTowsCsv(file) {
  const lines = fs.readFileSync(file, 'utf8').trim().split('\n');
  const head = lines.shift().split(',');
  const col = (name) => {
    const i = head.indexOf(name);
    if (i < 0) throw new Error(`${file}: no column ${name}`);
    return i;
  };
  const c = { course: col('course'), tow: col('tow'), seg: col('segment'), s: col('s_mm'),
              l: col('left_x'), r: col('right_x') };
  const pieces = new Map();
  for (const text of lines) {
    const v = text.split(',').map(Number);
    const key = `${v[c.course]}/${v[c.tow]}/${v[c.seg]}`;
    if (!pieces.has(key)) pieces.set(key, { course: v[c.course], tow: v[c.tow], rows: [] });
    pieces.get(key).rows.push({ s: v[c.s], l: v.slice(c.l, c.l + 3), r: v.slice(c.r, c.r + 3) });
  }
  return [...pieces.values()];
}

// Laying moves of the programme text: G1 with the head down (M21) in a course (M71 .. M72)
// with some tow on (M62 / M63, P0 = all), each with the tool point before and after it.
export function readLayingMoves(file) {
  const moves = [];
  let course = 0;
  let down = false;
  let tows = new Set();
  let at = null;
  fs.readFileSync(file, 'utf8').split('\n').forEach((raw, i) => {
    const text = raw.replace(/\(.*?\)/g, '').toUpperCase();
    const word = (letter) => {
      const m = new RegExp(`(?:^|\\s)${letter}(-?[0-9.]+)`).exec(text);
      return m ? Number(m[1]) : null;
    };
    const codes = (letter) => [...text.matchAll(new RegExp(`(?:^|\\s)${letter}(\\d+)`, 'g'))]
      .map((m) => Number(m[1]));
    const m = codes('M');
    const p = word('P');
    if (m.includes(71)) course = p;
    if (m.includes(72)) course = 0;
    if (m.includes(21)) down = true;
    if (m.includes(20)) down = false;
    if (m.includes(62)) {
      if (p === 0) for (let t = 1; t <= 64; t++) tows.add(t); else tows.add(p);
    }
    if (m.includes(63)) {
      if (p === 0) tows = new Set(); else tows.delete(p);
    }
    const g = codes('G');
    const x = word('X');
    if (x === null) return;
    const to = [x, word('Y'), word('Z')];
    if (g.includes(1) && down && course > 0 && tows.size && at) {
      moves.push({ line: i + 1, course, tows: new Set(tows), from: at, to });
    }
    at = to;
  });
  return moves;
}

const sub = (a, b) => a.map((v, i) => v - b[i]);
const dot = (a, b) => a.reduce((s, v, i) => s + v * b[i], 0);
const mid = (pts) => [0, 1, 2].map((c) => pts.reduce((s, p) => s + p[c], 0) / pts.length);
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
  a[0] * b[1] - a[1] * b[0]];

// The move whose segment the point lies beside (its projection inside, nearest sideways).
function lineFor(moves, course, tow, p) {
  let best = null;
  for (const mv of moves) {
    if (mv.course !== course || !mv.tows.has(tow)) continue;
    const d = sub(mv.to, mv.from);
    const len2 = dot(d, d);
    if (len2 <= 0) continue;
    const f = dot(sub(p, mv.from), d) / len2;
    if (f < 0 || f > 1) continue;
    const side = sub(sub(p, mv.from), d.map((v) => v * f));
    const dist = Math.sqrt(dot(side, side));
    if (!best || dist < best.dist) best = { line: mv.line, f, dist };
  }
  return best;
}

// Points to click: the middle of a tow piece's quad between two CSV rows, for pieces spread
// over the list, away from the ends of the programme move they lie on.
export function pickTargets(pieces, moves) {
  const targets = [];
  const long = pieces.filter((q) => q.rows.length >= 4);
  for (let k = 0; k < long.length && targets.length < PICKS; k++) {
    const q = long[Math.floor((k * 7919) % long.length)];
    for (let j = Math.floor(q.rows.length * (0.25 + 0.25 * (k % 3))); j + 1 < q.rows.length;
      j++) {
      const a = q.rows[j];
      const b = q.rows[j + 1];
      const p = mid([a.l, a.r, b.l, b.r]);
      const hit = lineFor(moves, q.course, q.tow, p);
      if (!hit || hit.f < END_MARGIN || hit.f > 1 - END_MARGIN) continue;
      const normal = cross(sub(b.l, a.l), sub(a.l, a.r));
      const n = Math.sqrt(dot(normal, normal)) || 1;
      targets.push({ course: q.course, tow: q.tow, line: hit.line, point: p,
                     normal: normal.map((v) => v / n) });
      break;
    }
  }
  return targets;
}

async function pick(page, t) {
  await page.locator('#view3d canvas').scrollIntoViewIfNeeded();  // the plots' clicks scrolled
  await page.evaluate((x) => { window.stitchsim.afp.frame(x.point, x.r, x.normal);
    window.stitchsim.afp.render(); }, { point: t.point, r: CLOSE_UP_M, normal: t.normal });
  const at = await page.evaluate((p) => window.stitchsim.afp.screenOf(p), t.point);
  await page.mouse.click(at.x, at.y);
  return page.evaluate(() => {
    const box = document.getElementById('afp-pick');
    const get = (k) => Number(box.getAttribute('data-' + k));
    return { course: get('course'), tow: get('tow'), line: get('line'), ply: get('ply') };
  });
}

// The canvas changes when `act` runs (then `undo` puts it back).
async function changes(page, tools, what, act, undo, failures, summary) {
  const before = await tools.canvasPixels(page);
  await act();
  await tools.settle(page);
  const after = await tools.canvasPixels(page);
  const f = tools.changedFraction(before, after);
  summary[`afp_${what}_changed`] = Number(f.toFixed(3));
  if (f < tools.minChange) {
    failures.push(`${what} hardly changed the canvas (${(100 * f).toFixed(1)} % of pixels)`);
  }
  await undo();
  await tools.settle(page);
}

export async function checkAfp(args, page, failures, summary, tools) {
  const has = await page.evaluate(() => !!(window.stitchsim && window.stitchsim.afp));
  if (!has) { failures.push('no laid tows in the page (window.stitchsim.afp)'); return; }
  const targets = pickTargets(readTowsCsv(args.afpCsv), readLayingMoves(args.afpProgram));
  if (!targets.length) { failures.push('no tow point to pick from the tow CSV'); return; }
  summary.afp_picks = [];
  for (const t of targets) {
    const got = await pick(page, t);
    summary.afp_picks.push({ want: { course: t.course, tow: t.tow, line: t.line }, got });
    for (const k of ['course', 'tow', 'line']) {
      if (got[k] !== t[k]) {
        failures.push(`picking (${t.point.map((v) => v.toFixed(1)).join(', ')}) shows ${k} ` +
                      `${got[k]}; the tow CSV and programme give ${t[k]}`);
      }
    }
  }
  if (args.out) {
    await page.locator('#view3d canvas').screenshot({ path: `${args.out}/afp_pick.png` });
    await page.locator('#afp').screenshot({ path: `${args.out}/afp_panel.png` });
  }
  // The whole ply from above its middle, the robot at home (line 1), for the canvas checks.
  const pts = readTowsCsv(args.afpCsv).flatMap((q) => q.rows.flatMap((r) => [r.l, r.r]));
  const lo = [0, 1, 2].map((c) => Math.min(...pts.map((p) => p[c])));
  const hi = [0, 1, 2].map((c) => Math.max(...pts.map((p) => p[c])));
  const half = Math.sqrt(dot(sub(hi, lo), sub(hi, lo))) / 2;
  await page.evaluate((x) => { window.stitchsim.goTo(1);
    window.stitchsim.afp.frame(x.centre, x.r, x.normal); }, { centre: mid([lo, hi]),
    r: half / 1000 * 0.9, normal: targets[0].normal[2] < 0 ? targets[0].normal.map((v) => -v) :
      targets[0].normal });
  await tools.settle(page);
  if (args.out) await page.locator('#view3d canvas').screenshot({ path: `${args.out}/afp_ply.png` });
  const plies = await page.evaluate(() => window.stitchsim.afp.plies);
  const box = page.locator(`#afp-plies input[data-ply="${plies[plies.length - 1]}"]`);
  await changes(page, tools, 'hiding_a_ply', () => box.uncheck(), () => box.check(), failures,
                summary);
  const peel = (v) => page.evaluate((x) => {
    const s = document.getElementById('afp-peel');
    s.value = String(x);
    s.dispatchEvent(new Event('input'));
  }, v);
  await changes(page, tools, 'peeling', () => peel(plies.length - 1), () => peel(plies.length),
                failures, summary);
  for (const mode of ['course', 'verdict']) {
    await changes(page, tools, `colour_by_${mode}`, () => page.selectOption('#afp-colour', mode),
                  () => page.selectOption('#afp-colour', 'ply'), failures, summary);
  }
}
