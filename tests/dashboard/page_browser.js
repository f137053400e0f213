// The dashboard page in a real browser (headless Chromium from Debian, driven by playwright-core):
//   node page_browser.js TLOD WORK_DIR gl|nogl [--update-image REPO]
// A real `tlod play` run is made here (nothing committed); the page must load with no console
// errors and no network request, its charts must hold one point per frame of trace.csv, its summary
// table must match figures computed here from trace.csv, and its picture must show charts. Bad run
// folders give their messages; a cut trace still renders; the live hook plots streamed frames.
// --update-image REPO also writes the README's picture, REPO/docs/images/dashboard.png.
'use strict';
const assert = require('node:assert/strict');
const { execFileSync, spawnSync } = require('node:child_process');
const fs = require('node:fs');
const http = require('node:http');
const path = require('node:path');

const [tlod, work, gl] = process.argv.slice(2, 5);
const updateAt = process.argv.indexOf('--update-image');
const repo = updateAt > 0 ? process.argv[updateAt + 1] : null;
const FRAMES = 60;

function tlodRun(args, expectStatus = 0) {
  const r = spawnSync(tlod, args, { encoding: 'utf8', timeout: 300000 });
  assert.equal(r.status, expectStatus, `tlod ${args.join(' ')}: exit ${r.status}\n${r.stderr}`);
  return r;
}

function play(out, extra) {
  const backend = gl === 'gl' ? ['--screenshot-every', '20'] : ['--backend', 'cpu'];
  tlodRun(['play', '--frames', String(FRAMES), '--size', '640x360', '--out', out, ...backend, ...extra]);
}

// trace.csv as {column: [numbers]} (the test's own reading, not the page's).
function readCsv(file) {
  const [head, ...lines] = fs.readFileSync(file, 'utf8').trim().split('\n');
  const names = head.split(','), cols = Object.fromEntries(names.map((n) => [n, []]));
  for (const line of lines) line.split(',').forEach((v, i) => cols[names[i]].push(Number(v)));
  return cols;
}

// Nearest rank: the smallest value with at least p% of the values at or below it.
function rank(values, p) {
  const v = [...values].sort((a, b) => a - b);
  return v[Math.max(1, Math.ceil((p * v.length) / 100)) - 1];
}

function expectedRow(label, cols) {
  const mean = (a) => a.reduce((s, x) => s + x, 0) / a.length;
  const ms = cols.frame_ms;
  return [label, String(ms.length), ...[50, 95, 99, 100].map((p) => rank(ms, p).toFixed(2)),
    mean(cols.scheduler_ms).toFixed(3), mean(cols.backend_cpu_ms).toFixed(3), mean(cols.triangles).toFixed(0)];
}

async function openPage(browser, url) {
  const page = await browser.newPage({ viewport: { width: 1280, height: 900 } });
  const problems = [], requests = [];
  page.on('console', (m) => ['error', 'warning'].includes(m.type()) && problems.push(m.type() + ': ' + m.text()));
  page.on('pageerror', (e) => problems.push('exception: ' + e.message));
  page.on('request', (r) => requests.push(r.url()));
  await page.goto(url);
  await page.waitForFunction(() => window.tlodDashboard && window.tlodDashboard.charts.length > 0);
  return { page, problems, requests };
}

async function checkStaticPage(browser, file, runs) {
  const { page, problems, requests } = await openPage(browser, 'file://' + file);
  assert.deepEqual(problems, [], 'console errors');
  const outside = requests.filter((u) => !u.startsWith('file://') && !u.startsWith('data:'));
  assert.deepEqual(outside, [], 'the page fetched from the network');
  const counts = await page.evaluate(() => window.tlodDashboard.charts.map((c) => ({
    title: c.chart.series[0] && c.title, lengths: c.chart.data.map((s) => s.length) })));
  for (const [label, cols] of runs) {
    for (const kind of ['frame time (ms)', 'scheduler stages (ms, stacked)', 'triangles and strips',
      'visible patches per level (stacked)']) {
      const c = counts.find((x) => x.title === `${label}: ${kind}`);
      assert.ok(c, `no chart "${label}: ${kind}" in ${counts.map((x) => x.title)}`);
      assert.ok(c.lengths.every((n) => n === cols.frame_ms.length), `${label}: ${kind}: ${c.lengths}`);
    }
  }
  const overlay = counts.find((x) => x.title === 'frame time of every run (ms)');
  assert.equal(overlay.lengths.length, 1 + runs.length + 2, 'overlay: x, one line per run, two budgets');
  const table = await page.$$eval('#summary tbody tr', (rows) => rows.map((r) => [...r.cells].map((c) => c.textContent)));
  assert.deepEqual(table, runs.map(([label, cols]) => expectedRow(label, cols)));
  await checkComparison(page, runs);
  return page;
}

// The tlod compare table for run 1 against run 0: its ratio column is new / baseline.
async function checkComparison(page, runs) {
  const rows = await page.$$eval('#compare-1 tbody tr', (t) => t.map((r) => [...r.cells].map((c) => c.textContent)));
  const p95 = rows.find((r) => r[0] === 'frame_ms p95');
  assert.ok(p95, 'compare table: no frame_ms p95 row');
  // The table shows 3 decimals (half a unit of the last: 5e-4) of trace.json's figures.
  assert.ok(Math.abs(Number(p95[1]) - rank(runs[0][1].frame_ms, 95)) < 6e-4, `baseline p95 ${p95}`);
  assert.ok(Math.abs(Number(p95[2]) - rank(runs[1][1].frame_ms, 95)) < 6e-4, `new p95 ${p95}`);
  assert.ok(Math.abs(Number(p95[3]) - Number(p95[2]) / Number(p95[1])) < 2e-3, `ratio ${p95}`);
}

// Clicking frame 20 of the frame-time chart shows that frame's screenshot.
async function checkScreenshotClick(page, label) {
  const box = await page.evaluate((title) => {
    const u = window.tlodDashboard.charts.find((c) => c.title === title).chart;
    u.over.scrollIntoView({ block: 'center' });
    const r = u.over.getBoundingClientRect();
    return { x: r.left + u.valToPos(20, 'x'), y: r.top + r.height / 2 };
  }, `${label}: frame time (ms)`);
  await page.mouse.move(box.x, box.y);
  await page.mouse.click(box.x, box.y);
  const shot = await page.waitForSelector('figure.shot img');
  const info = await shot.evaluate((img) => ({ src: img.src.slice(0, 22), width: img.naturalWidth, alt: img.alt }));
  assert.deepEqual(info, { src: 'data:image/png;base64,', width: 640, alt: 'frame 20' });
}

// The picture of the page: not blank, and the charts' first colour (frame_ms, #1f77b4) drawn in it.
async function checkPicture(browser, png) {
  const page = await browser.newPage();
  await page.setContent('<canvas></canvas>');
  const s = await page.evaluate(async (uri) => {
    const img = new Image();
    img.src = uri;
    await img.decode();
    const c = document.querySelector('canvas'), g = c.getContext('2d');
    c.width = img.width, c.height = img.height;
    g.drawImage(img, 0, 0);
    const d = g.getImageData(0, 0, c.width, c.height).data;
    let ink = 0, blue = 0;
    for (let i = 0; i < d.length; i += 4) {
      if (d[i] + d[i + 1] + d[i + 2] < 600) ink++;
      if (Math.abs(d[i] - 0x1f) < 40 && Math.abs(d[i + 1] - 0x77) < 40 && Math.abs(d[i + 2] - 0xb4) < 40) blue++;
    }
    return { ink: ink / (d.length / 4), blue };
  }, 'data:image/png;base64,' + png.toString('base64'));
  await page.close();
  assert.ok(s.ink > 0.03, `the page's picture is nearly blank (${s.ink})`);
  // A drawn line is hundreds of pixels of its colour, none without charts; how many depends on the run's frame
  // times (a flat line under the others' keeps fewer exact-colour pixels: 192 seen on a loaded machine).
  assert.ok(s.blue > 60, `no chart line in the picture (${s.blue} pixels of #1f77b4)`);
}

function checkBadFolders(run) {
  const empty = path.join(work, 'empty');
  fs.mkdirSync(empty);
  let r = tlodRun(['dashboard', empty, '-o', path.join(work, 'x.html')], 1);
  assert.match(r.stderr, new RegExp(`${empty}: not a run \\(no trace.json\\)`));
  const v9 = path.join(work, 'v9');
  fs.mkdirSync(v9);
  const text = fs.readFileSync(path.join(run, 'trace.json'), 'utf8');
  fs.writeFileSync(path.join(v9, 'trace.json'), text.replace('tlod-play-trace/2', 'tlod-play-trace/9'));
  r = tlodRun(['dashboard', v9, '-o', path.join(work, 'x.html')], 1);
  assert.match(r.stderr, /v9\/trace.json: schema 'tlod-play-trace\/9' is not tlod-play-trace\/2/);
  assert.ok(!fs.existsSync(path.join(work, 'x.html')), 'a refused run left a page');
  checkScreenshotEscape(text);
}

// A trace whose screenshot paths climb out of its folder (to real PNGs): none is inlined, all are counted.
function checkScreenshotEscape(text) {
  const evil = path.join(work, 'evil');
  fs.mkdirSync(evil);
  fs.writeFileSync(path.join(evil, 'trace.json'), text.replaceAll('"screenshots/frame_', '"../run/screenshots/frame_'));
  const out = path.join(work, 'evil.html');
  tlodRun(['dashboard', evil, '-o', out]);
  const island = /<script type="application\/json" id="tlod-data">([^]*?)<\/script>/.exec(fs.readFileSync(out, 'utf8'));
  const r = JSON.parse(island[1]).runs[0];
  assert.deepEqual(r.screenshots, {});
  assert.equal(r.screenshots_omitted, gl === 'gl' ? 3 : 0);
}

// A trace cut in the middle of a frame: the page shows the frames before it and says so.
async function checkCutTrace(browser, run) {
  const cut = path.join(work, 'cut');
  fs.mkdirSync(cut);
  const text = fs.readFileSync(path.join(run, 'trace.json'), 'utf8');
  const at = text.indexOf('"frame": 37') + 40; // inside frame 37's record
  fs.writeFileSync(path.join(cut, 'trace.json'), text.slice(0, at));
  const out = path.join(work, 'cut.html');
  const r = tlodRun(['dashboard', cut, '-o', out]);
  assert.match(r.stderr, /cut\/trace.json: truncated after frame 36/);
  const { page, problems } = await openPage(browser, 'file://' + out);
  assert.deepEqual(problems, []);
  const n = await page.evaluate(() => window.tlodDashboard.charts[0].chart.data[0].length);
  assert.equal(n, 37);
  assert.match(await page.textContent('.warning'), /truncated after frame 36 \(showing what it has\)/);
  await page.close();
}

// Live: a page made with --live /events, served here; five frame records arrive as events.
async function checkLive(browser, run) {
  const page = path.join(work, 'live.html');
  tlodRun(['dashboard', '--live', '/events', '-o', page]);
  const frames = JSON.parse(fs.readFileSync(path.join(run, 'trace.json'), 'utf8')).frames.slice(0, 5);
  let stream = null;
  const server = http.createServer((req, res) => {
    if (req.url === '/') return res.writeHead(200, { 'Content-Type': 'text/html' }), res.end(fs.readFileSync(page));
    if (req.url !== '/events') return res.writeHead(404), res.end();
    res.writeHead(200, { 'Content-Type': 'text/event-stream' });
    res.write('event: run\ndata: {"scene": "demo:live", "mode": "adaptive"}\n\n');
    frames.forEach((f, i) => res.write(`data: ${JSON.stringify(Object.assign({}, f, { dropped: i === 4 ? 3 : 0 }))}\n\n`));
    stream = res; // "end" is sent once the frames have been checked
  });
  await new Promise((ok) => server.listen(0, '127.0.0.1', ok));
  const base = `http://127.0.0.1:${server.address().port}`;
  const p = await browser.newPage();
  const problems = [];
  p.on('console', (m) => m.type() === 'error' && problems.push(m.text()));
  await p.goto(base + '/');
  await p.waitForFunction(() => window.tlodDashboard.charts.length > 0 &&
    window.tlodDashboard.charts[0].chart.data[0].length === 5, null, { timeout: 10000 });
  assert.match(await p.textContent('.run .note'), /live: 5 frames, 3 dropped for this page/);
  assert.match(await p.textContent('.run .meta'), /demo:live · adaptive/);
  // The next --compare mode: a "run" event, then frames from 0 again, into a second live run.
  stream.write('event: run\ndata: {"scene": "demo:live", "mode": "uniform:2"}\n\n');
  frames.slice(0, 3).forEach((f) => stream.write(`data: ${JSON.stringify(Object.assign({}, f, { dropped: 3 }))}\n\n`));
  await p.waitForFunction(() => window.tlodDashboard.data.runs.length === 2 &&
    window.tlodDashboard.data.runs[1].columns.frame.length === 3);
  stream.end('event: end\ndata: {"dropped": 4}\n\n');
  await p.waitForFunction(() => /ended/.test(document.querySelectorAll('.run .note')[1].textContent));
  const notes = await p.$$eval('.run .note', (n) => n.map((x) => x.textContent));
  assert.deepEqual(notes, ['live: 5 frames, 3 dropped for this page',
    'live: 3 frames, 4 dropped for this page (the run ended)']);
  assert.equal(await p.evaluate(() => window.tlodDashboard.data.runs[0].columns.frame.length), 5);
  assert.deepEqual(problems, []);
  await p.close();
  server.closeAllConnections();
  server.close();
}

async function main() {
  fs.rmSync(work, { recursive: true, force: true });
  fs.mkdirSync(work, { recursive: true });
  const run = path.join(work, 'run'), cmp = path.join(work, 'cmp');
  play(run, []);
  play(cmp, ['--compare', 'adaptive,uniform:2']);
  const runs = [['run', readCsv(path.join(run, 'trace.csv'))], ['adaptive', readCsv(path.join(cmp, 'adaptive', 'trace.csv'))],
    ['uniform-2', readCsv(path.join(cmp, 'uniform-2', 'trace.csv'))]];
  assert.equal(runs[0][1].frame_ms.length, FRAMES);
  const file = path.join(work, 'page.html');
  tlodRun(['dashboard', run, cmp, '-o', file]);
  const chromium = execFileSync('sh', ['-c', 'command -v chromium'], { encoding: 'utf8' }).trim();
  const { chromium: pw } = require(path.join(__dirname, '..', '..', 'node_modules', 'playwright-core'));
  const browser = await pw.launch({ executablePath: chromium, args: ['--no-sandbox'] });
  try {
    const page = await checkStaticPage(browser, file, runs);
    if (gl === 'gl') await checkScreenshotClick(page, 'run');
    else console.log('page_browser: nogl build: no screenshots to click (the cpu backend draws no image)');
    await page.evaluate(() => window.scrollTo(0, 0));
    const png = await page.screenshot();
    fs.writeFileSync(path.join(work, 'dashboard.png'), png);
    await checkPicture(browser, png);
    if (repo) fs.writeFileSync(path.join(repo, 'docs', 'images', 'dashboard.png'), png);
    checkBadFolders(run);
    await checkCutTrace(browser, run);
    await checkLive(browser, run);
  } finally {
    await browser.close();
  }
  console.log('page_browser: ok');
}

main().catch((e) => {
  console.error(e);
  process.exit(1);
});
