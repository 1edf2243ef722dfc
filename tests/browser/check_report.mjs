#!/usr/bin/env node
// Checks a stitchsim HTML report in Debian's headless Chromium (docs/report-format.md,
// "HTML report"):
//   node tests/browser/check_report.mjs FILE.html [--out DIR] [--expect-finding] [--timeout S]
//                                       [--expect-shown-error] [--afp-csv TOWS.csv --afp-program P.nc]
// Fails (exit 1, a message on stderr) on a console error or page error, a request that is not
// file:/data:/blob:, an error shown on the page, the page not ready within the timeout (60 s),
// a blank 3D canvas, a finding click that does not move the slider to the finding's line and
// change the view, or a plot click that does not move the slider. Screenshots go to --out
// (default: no files); stdout gets one JSON line {"load_s", "size_mb", "changed_fraction", ...}.
// --expect-shown-error (malformed data): passes only if the page shows its error message
// (and still logs no console error).
// --afp-csv / --afp-program (a fibre-placement ply planned with --tows-csv): also the laid-tow
// checks of check_afp.mjs (a picked tow's course, tow and line; hide, peel, colour switch).
import { chromium } from 'playwright-core';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { pathToFileURL } from 'node:url';
import { checkAfp } from './check_afp.mjs';

const BLANK_MIN_STDDEV = 6;       // luminance spread (0..255) a drawn scene exceeds
const BLANK_MIN_FRACTION = 0.02;  // share of pixels that must differ from the background
const CHANGE_PIXEL_DIFF = 40;     // a pixel "changed" when a channel moves by more than this
const CHANGE_MIN_FRACTION = 0.03; // share of changed pixels required after "go to finding"

function parseArgs(argv) {
  const args = { file: null, out: null, expectFinding: false, expectShownError: false,
                 timeoutS: 60, afpCsv: null, afpProgram: null };
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    if (a === '--out') args.out = argv[++i];
    else if (a === '--expect-finding') args.expectFinding = true;
    else if (a === '--expect-shown-error') args.expectShownError = true;
    else if (a === '--timeout') args.timeoutS = Number(argv[++i]);
    else if (a === '--afp-csv') args.afpCsv = argv[++i];
    else if (a === '--afp-program') args.afpProgram = argv[++i];
    else if (!args.file && !a.startsWith('--')) args.file = a;
    else throw new Error(`unknown argument ${a}`);
  }
  if (!args.afpCsv !== !args.afpProgram) throw new Error('--afp-csv and --afp-program go together');
  if (!args.file) {
    throw new Error('usage: check_report.mjs FILE.html [--out DIR] [--expect-finding] ' +
                    '[--timeout S]');
  }
  return args;
}

// Pixels of the 3D canvas (RGBA, downscaled to at most 480 px wide) read inside the page;
// the renderer keeps its drawing buffer (preserveDrawingBuffer), so drawImage sees the frame.
async function canvasPixels(page) {
  return page.evaluate(() => new Promise((resolve) => {
    requestAnimationFrame(() => requestAnimationFrame(() => {
      const src = document.querySelector('#view3d canvas');
      if (!src) return resolve(null);
      const w = Math.min(480, src.width);
      const h = Math.max(1, Math.round(src.height * w / src.width));
      const c = document.createElement('canvas');
      c.width = w;
      c.height = h;
      const g = c.getContext('2d');
      g.drawImage(src, 0, 0, w, h);
      resolve({ w, h, data: Array.from(g.getImageData(0, 0, w, h).data) });
    }));
  }));
}

function spread(px) {
  const n = px.w * px.h;
  const d = px.data;
  let sum = 0;
  let sum2 = 0;
  let off = 0;
  for (let i = 0; i < n; i++) {
    const y = 0.299 * d[4 * i] + 0.587 * d[4 * i + 1] + 0.114 * d[4 * i + 2];
    sum += y;
    sum2 += y * y;
    const bg = Math.abs(d[4 * i] - d[0]) + Math.abs(d[4 * i + 1] - d[1]) +
               Math.abs(d[4 * i + 2] - d[2]);
    if (bg > 24) off++;
  }
  const mean = sum / n;
  return { stddev: Math.sqrt(Math.max(0, sum2 / n - mean * mean)), nonBackground: off / n };
}

function changedFraction(a, b) {
  if (a.w !== b.w || a.h !== b.h) return 1;
  let changed = 0;
  for (let i = 0; i < a.w * a.h; i++) {
    for (let c = 0; c < 3; c++) {
      if (Math.abs(a.data[4 * i + c] - b.data[4 * i + c]) > CHANGE_PIXEL_DIFF) {
        changed++;
        break;
      }
    }
  }
  return changed / (a.w * a.h);
}

// The report's poses read from the file itself (a second route to the joints the page shows).
function readPoses(file) {
  const html = fs.readFileSync(file, 'utf8');
  const open = '<script id="stitchsim-data" type="application/json">';
  const start = html.indexOf(open);
  const end = html.indexOf('</script>', start);
  if (start < 0 || end < 0) return null;
  let data;
  try {
    data = JSON.parse(html.slice(start + open.length, end));
  } catch (e) {
    return null;
  }
  const bytes = (b64) => Uint8Array.from(Buffer.from(b64 || '', 'base64')).buffer;
  const poses = data.poses || {};
  return { lines: new Int32Array(bytes(poses.lines)), q: new Float32Array(bytes(poses.q)),
           dof: (data.cell && data.cell.joints || []).length };
}

// jointsAt at a recorded line equals that record; between two records, the linear blend.
async function checkPoses(args, page, failures, line) {
  const poses = readPoses(args.file);
  if (!poses || !poses.dof) return;
  const row = (k) => Array.from(poses.q.subarray(k * poses.dof, (k + 1) * poses.dof));
  const near = (a, b) => a.length === b.length && a.every((v, j) => Math.abs(v - b[j]) < 1e-5);
  const k = poses.lines.indexOf(line);
  if (line > 0 && k < 0) failures.push(`no recorded pose at the finding's line ${line}`);
  const cases = [];
  if (k >= 0) cases.push([line, row(k)]);
  for (let i = 0; i + 1 < poses.lines.length && cases.length < 3; i++) {
    const gap = poses.lines[i + 1] - poses.lines[i];
    if (gap >= 2 && poses.lines[i] > 0) {
      const a = row(i);
      const b = row(i + 1);
      const f = Math.floor(gap / 2) / gap;
      cases.push([poses.lines[i] + Math.floor(gap / 2), a.map((v, j) => v + (b[j] - v) * f)]);
    }
  }
  for (const [at, want] of cases) {
    const got = await page.evaluate((l) => window.stitchsim.jointsAt(l), at);
    if (!near(got, want)) {
      failures.push(`jointsAt(${at}) = ${JSON.stringify(got)}, the data say ` +
                    `${JSON.stringify(want)}`);
    }
  }
}

async function sliderLine(page) {
  return page.evaluate(() => ({ slider: Number(document.getElementById('slider').value),
                                api: window.stitchsim.line }));
}

async function settle(page) {
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() =>
    requestAnimationFrame(r))));
}

async function run(args, page, failures, summary) {
  const url = pathToFileURL(path.resolve(args.file)).href;
  await page.goto(url, { waitUntil: 'load', timeout: args.timeoutS * 1000 });
  await page.waitForFunction(() => window.stitchsimReady || window.stitchsimFailed,
                             null, { timeout: args.timeoutS * 1000, polling: 100 });
  const shown = await page.evaluate(() => ({
    ready: !!window.stitchsimReady, loadMs: window.stitchsimLoadMs,
    errors: window.stitchsimErrors || [], errorBox: !document.getElementById('error').hidden,
  }));
  summary.load_s = shown.loadMs ? Number((shown.loadMs / 1000).toFixed(3)) : null;
  if (args.expectShownError) {
    const text = await page.locator('#error').innerText();
    summary.shown_error = text;
    if (!shown.errorBox || !text.trim()) failures.push('no error message shown on the page');
    if (args.out) await page.screenshot({ path: path.join(args.out, 'page_error.png') });
    return;
  }
  if (!shown.ready || shown.errorBox) {
    failures.push(`the page shows errors: ${shown.errors.join(' | ')}`);
    return;
  }
  const shot = async (name) => {
    if (!args.out) return;
    await page.locator('#view3d canvas').screenshot({ path: path.join(args.out, name) });
  };
  if (args.out) await page.screenshot({ path: path.join(args.out, 'page.png'), fullPage: true });
  const before = await canvasPixels(page);
  if (!before) { failures.push('no 3D canvas'); return; }
  const s = spread(before);
  summary.canvas_stddev = Number(s.stddev.toFixed(1));
  summary.canvas_drawn_fraction = Number(s.nonBackground.toFixed(3));
  if (s.stddev < BLANK_MIN_STDDEV || s.nonBackground < BLANK_MIN_FRACTION) {
    failures.push(`the 3D canvas looks blank (luminance spread ${s.stddev.toFixed(1)}, ` +
                  `${(100 * s.nonBackground).toFixed(1)} % of pixels drawn)`);
  }
  await shot('view_start.png');
  await checkFinding(args, page, failures, summary, before, shot);
  await checkPlot(page, failures, summary);
  await checkPlay(page, failures, summary);
  const q = await page.evaluate(() => window.stitchsim.jointsAt(window.stitchsim.line));
  if (!Array.isArray(q) || !q.length || !q.every(Number.isFinite)) {
    failures.push(`stitchsim.jointsAt gave ${JSON.stringify(q)}`);
  }
  if (args.afpCsv) {
    await checkAfp(args, page, failures, summary, { canvasPixels, settle, changedFraction,
                                                    minChange: CHANGE_MIN_FRACTION });
  }
}

async function checkFinding(args, page, failures, summary, before, shot) {
  let row = page.locator('#finding-table tbody tr[data-line]:has(td.sev-error)').first();
  if (await row.count() === 0) row = page.locator('#finding-table tbody tr[data-line]').first();
  if (await row.count() === 0) {
    if (args.expectFinding) failures.push('no finding rows (--expect-finding)');
    return;
  }
  const line = Number(await row.getAttribute('data-line'));
  await row.click();
  await page.waitForTimeout(300);
  await settle(page);
  const at = await sliderLine(page);
  summary.finding_line = line;
  if (at.slider !== line || at.api !== line) {
    failures.push(`after clicking the finding at line ${line} the slider shows ${at.slider} ` +
                  `(stitchsim.line ${at.api})`);
  }
  const after = await canvasPixels(page);
  const changed = changedFraction(before, after);
  summary.changed_fraction = Number(changed.toFixed(3));
  if (changed < CHANGE_MIN_FRACTION) {
    failures.push(`the view hardly changed after "go to finding" (${(100 * changed).toFixed(1)}` +
                  ` % of pixels, need ${100 * CHANGE_MIN_FRACTION} %)`);
  }
  await shot('view_finding.png');
  if (args.out) await page.screenshot({ path: path.join(args.out, 'page_finding.png') });
  await checkPoses(args, page, failures, line);
}

// Play moves the slider forward; pause stops it.
async function checkPlay(page, failures, summary) {
  const lines = await page.evaluate(() => Number(document.getElementById('slider').max));
  if (lines < 3) return;
  await page.evaluate(() => window.stitchsim.goTo(1));
  await page.click('#play');
  await page.waitForTimeout(1000);
  await page.click('#play');
  const stopped = (await sliderLine(page)).slider;
  await page.waitForTimeout(300);
  const later = (await sliderLine(page)).slider;
  summary.play_lines = [stopped, later];
  if (stopped <= 1) failures.push('Play did not move the slider in 1 s');
  if (later !== stopped) failures.push(`the slider moved after Pause (${stopped} -> ${later})`);
}

async function checkPlot(page, failures, summary) {
  const plot = page.locator('.plot canvas').first();
  if (await plot.count() === 0) return;
  const box = await plot.boundingBox();
  const lines = [];
  for (const f of [0.3, 0.75]) {
    const previous = (await sliderLine(page)).slider;
    await plot.click({ position: { x: box.width * f, y: box.height / 2 } });
    await settle(page);
    const at = await sliderLine(page);
    if (at.slider === previous || at.slider !== at.api) {
      failures.push(`clicking the plot at ${100 * f} % left the slider at ${at.slider} ` +
                    `(was ${previous}, stitchsim.line ${at.api})`);
    }
    lines.push(at.slider);
  }
  summary.plot_lines = lines;
  if (!(lines[0] < lines[1])) failures.push(`plot clicks went to lines ${lines.join(', ')}`);
}

async function main() {
  const args = parseArgs(process.argv.slice(2));
  if (args.out) fs.mkdirSync(args.out, { recursive: true });
  const summary = { file: args.file, size_mb: Number((fs.statSync(args.file).size / 1e6)
    .toFixed(2)), load_s: null, changed_fraction: null };
  const failures = [];
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), `stitchsim-chromium-${process.pid}-`));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: '/usr/bin/chromium', headless: true,
    viewport: { width: 1400, height: 1000 },
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
           '--disable-background-networking', '--disable-component-update', '--disable-sync',
           '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
  });
  try {
    await context.route('**/*', (route) => {
      const u = route.request().url();  // file: and data: are not routed; kept for safety
      if (/^(file|data|blob):/.test(u)) return route.continue();
      failures.push(`network request: ${u}`);
      return route.abort();
    });
    const page = context.pages()[0] || await context.newPage();
    page.on('console', (m) => { if (m.type() === 'error') failures.push(`console: ${m.text()}`); });
    page.on('pageerror', (e) => failures.push(`page error: ${e.message}`));
    page.on('request', (r) => {
      if (!/^(file|data|blob):/.test(r.url())) failures.push(`request: ${r.url()}`);
    });
    await run(args, page, failures, summary);
  } catch (e) {
    failures.push(e.message.split('\n')[0]);
  } finally {
    await context.close();
    fs.rmSync(profile, { recursive: true, force: true });
  }
  process.stderr.write(`${args.file}: ${summary.size_mb} MB, ready after ${summary.load_s} s\n`);
  console.log(JSON.stringify(summary));
  if (failures.length) {
    for (const f of failures) process.stderr.write(`FAIL: ${f}\n`);
    process.exit(1);
  }
}

main().catch((e) => {
  process.stderr.write(`FAIL: ${e.stack || e}\n`);
  process.exit(1);
});
