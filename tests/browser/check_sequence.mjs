#!/usr/bin/env node
// Checks a `stitchsim sequence --html` page in Debian's headless Chromium (docs/sequence.md,
// "The page"):
//   node tests/browser/check_sequence.mjs PAGE.html REPORT.json [--out DIR]
// Fails (exit 1, a message on stderr) on a console or page error, any request that is not
// file:/data:/blob:, the page not ready, a blank view, a view that does not change when the
// original path is swapped for the new one, a shown figure that differs from REPORT.json (the
// file --report wrote, read here, not the page's copy) by more than half its last printed
// digit, or a ply or the whole missing its flown lengths before and after. Screenshots go to
// --out; stdout gets one JSON line {"figures", "changed_fraction", ...}.
import { chromium } from 'playwright-core';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const PIXEL_DIFF = 40;           // a channel moving by more than this: the pixel changed
const MIN_DRAWN_FRACTION = 0.01; // share of a view's pixels off the white background
const MIN_CHANGE_FRACTION = 0.005;

// RGBA of the first view's canvas (preserveDrawingBuffer keeps the frame readable).
async function viewPixels(page, id) {
  return page.evaluate((sel) => new Promise((resolve) => {
    requestAnimationFrame(() => requestAnimationFrame(() => {
      const src = document.querySelector(sel);
      const c = document.createElement('canvas');
      c.width = 400;
      c.height = Math.max(1, Math.round(src.height * 400 / src.width));
      const g = c.getContext('2d');
      g.drawImage(src, 0, 0, c.width, c.height);
      resolve(Array.from(g.getImageData(0, 0, c.width, c.height).data));
    }));
  }), `#${id} canvas`);
}

function drawnFraction(px) {
  let n = 0;
  for (let i = 0; i < px.length; i += 4) if (px[i] + px[i + 1] + px[i + 2] < 3 * 255 - 60) n++;
  return n / (px.length / 4);
}

function changedFraction(a, b) {
  if (a.length !== b.length) return 1;
  let n = 0;
  for (let i = 0; i < a.length; i += 4) {
    if ([0, 1, 2].some((c) => Math.abs(a[i + c] - b[i + c]) > PIXEL_DIFF)) n++;
  }
  return n / (a.length / 4);
}

// The value at "a.0.b" in `obj`.
function at(obj, dotted) {
  return dotted.split('.').reduce((o, k) => (o === undefined || o === null ? o : o[k]), obj);
}

async function run(page, file, report, out, failures, summary) {
  await page.goto(pathToFileURL(path.resolve(file)).href, { waitUntil: 'load' });
  await page.waitForFunction(() => window.stitchsimReady === true ||
                                   (window.stitchsimErrors || []).length > 0, null,
                             { timeout: 60000 });
  const shownErrors = await page.evaluate(() => window.stitchsimErrors);
  if (shownErrors.length) failures.push(`the page shows: ${shownErrors.join('; ')}`);
  if (out) await page.screenshot({ path: path.join(out, 'sequence_side.png'), fullPage: true });
  // Side by side: both views drawn.
  for (const id of ['viewA', 'viewB']) {
    const f = drawnFraction(await viewPixels(page, id));
    summary[`drawn_${id}`] = f;
    if (f < MIN_DRAWN_FRACTION) failures.push(`${id} is blank (${f} drawn)`);
  }
  // One view: the original path, then the new one, must differ.
  await page.selectOption('#mode', 'original');
  const original = await viewPixels(page, 'viewA');
  if (out) await page.screenshot({ path: path.join(out, 'sequence_original.png') });
  await page.selectOption('#mode', 'new');
  const fresh = await viewPixels(page, 'viewA');
  if (out) await page.screenshot({ path: path.join(out, 'sequence_new.png') });
  summary.changed_fraction = changedFraction(original, fresh);
  if (summary.changed_fraction < MIN_CHANGE_FRACTION) {
    failures.push(`original and new paths draw the same (${summary.changed_fraction} changed)`);
  }
  // Hiding a ply changes the view too.
  const before = await viewPixels(page, 'viewA');
  await page.click('#plyToggles input >> nth=0');
  const hidden = changedFraction(before, await viewPixels(page, 'viewA'));
  if (hidden < MIN_CHANGE_FRACTION) failures.push(`hiding a ply changes nothing (${hidden})`);
  await page.click('#plyToggles input >> nth=0');
  await page.selectOption('#mode', 'side');
  // Every shown figure against the report file.
  const cells = await page.$$eval('td[data-path]', (tds) => tds.map((td) => (
    { path: td.dataset.path, dec: Number(td.dataset.dec), text: td.textContent })));
  summary.figures = cells.length;
  const paths = new Set(cells.map((c) => c.path));
  for (const c of cells) {
    const want = at(report, c.path);
    const got = Number(c.text);
    if (typeof want !== 'number' || !Number.isFinite(got) ||
        Math.abs(got - want) > 0.5 * 10 ** -c.dec + 1e-9 * Math.abs(want)) {
      failures.push(`${c.path}: the page shows ${c.text}, the report has ${want}`);
    }
  }
  const needed = ['totals'].concat(report.plies.map((p, i) => `plies.${i}`));
  for (const n of needed) {
    for (const k of ['offpart_before', 'offpart_after', 'total_before', 'total_after']) {
      if (!paths.has(`${n}.flown_tool_mm.${k}`)) failures.push(`${n}: no ${k} shown`);
    }
  }
}

async function main() {
  const [file, reportFile, ...rest] = process.argv.slice(2);
  const out = rest[0] === '--out' ? rest[1] : null;
  if (!file || !reportFile) throw new Error('usage: check_sequence.mjs PAGE.html REPORT.json');
  if (out) fs.mkdirSync(out, { recursive: true });
  const report = JSON.parse(fs.readFileSync(reportFile, 'utf8'));
  const summary = { file, size_mb: Number((fs.statSync(file).size / 1e6).toFixed(2)) };
  const failures = [];
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), `stitchsim-seq-${process.pid}-`));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: '/usr/bin/chromium', headless: true, viewport: { width: 1400, height: 900 },
    args: ['--no-sandbox', '--disable-gpu', '--no-first-run', '--disable-background-networking',
           '--disable-component-update', '--use-angle=swiftshader',
           '--enable-unsafe-swiftshader'],
  });
  try {
    const page = context.pages()[0] || await context.newPage();
    page.on('console', (m) => { if (m.type() === 'error') failures.push(`console: ${m.text()}`); });
    page.on('pageerror', (e) => failures.push(`page error: ${e.message}`));
    page.on('request', (r) => {
      if (!/^(file|data|blob):/.test(r.url())) failures.push(`request: ${r.url()}`);
    });
    await run(page, file, report, out, failures, summary);
  } catch (e) {
    failures.push(String(e.message).split('\n')[0]);
  } finally {
    await context.close();
    fs.rmSync(profile, { recursive: true, force: true });
  }
  console.log(JSON.stringify(summary));
  for (const f of failures) process.stderr.write(`FAIL: ${f}\n`);
  process.exit(failures.length ? 1 : 0);
}

main().catch((e) => {
  process.stderr.write(`FAIL: ${e.stack || e}\n`);
  process.exit(1);
});
