/* The tesslod dashboard page (docs/dashboard.md). The data of the runs is a JSON island
 * (#tlod-data) written by `tlod dashboard` or `tlod play --serve`; every chart is a uPlot
 * chart. The first half is pure functions over that data (tested with node --test in
 * tests/dashboard/dashboard_logic.test.js); the second half builds the page. */
'use strict';

const BUDGETS_MS = [16.7, 33.3];
const LEVELS = 11;
const TIME_KEYS = ['frame_ms', 'scheduler_ms', 'backend_cpu_ms', 'backend_gpu_ms', 'backend_wall_ms'];
const STAGE_KEYS = ['silhouette_ms', 'metric_ms', 'levels_ms', 'morph_ms', 'strips_ms'];
const COLORS = ['#1f77b4', '#ff7f0e', '#2ca02c', '#d62728', '#9467bd', '#8c564b', '#e377c2', '#7f7f7f',
  '#bcbd22', '#17becf', '#393b79'];

/* Nearest-rank percentile of ascending values, as tlod play's summary computes it. */
function percentile(sorted, p) {
  if (!sorted.length) return NaN;
  const rank = Math.ceil((p / 100) * sorted.length);
  return sorted[Math.min(Math.max(rank, 1), sorted.length) - 1];
}

/* Count, mean, p50/p95/p99 and max of the finite values. */
function stats(values) {
  const v = values.filter(Number.isFinite).sort((a, b) => a - b);
  const sum = v.reduce((s, x) => s + x, 0);
  return {
    count: v.length, mean: v.length ? sum / v.length : NaN, p50: percentile(v, 50),
    p95: percentile(v, 95), p99: percentile(v, 99), max: v.length ? v[v.length - 1] : NaN,
  };
}

/* bins equal-width bins over the finite values: bin centres and counts. */
function histogram(values, bins) {
  const v = values.filter(Number.isFinite);
  if (!v.length) return { centers: [], counts: [] };
  const lo = Math.min(...v), hi = Math.max(...v), width = (hi - lo) / bins || 1;
  const counts = new Array(bins).fill(0);
  for (const x of v) counts[Math.min(bins - 1, Math.floor((x - lo) / width))]++;
  return { centers: counts.map((_, i) => lo + (i + 0.5) * width), counts };
}

/* Running sums: out[k][i] = sum of arrays[0..k][i] (the tops of a stacked chart). */
function stack(arrays) {
  let below = null;
  return arrays.map((a) => (below = a.map((x, i) => (below ? below[i] : 0) + (Number.isFinite(x) ? x : 0))));
}

/* backend_gpu_ms is -1 when no GPU result was ready: a gap, not a value. */
function gapsForMissing(values) {
  return values.map((x) => (Number.isFinite(x) && x >= 0 ? x : null));
}

/* A trace.json frame record (also a live event) as trace.csv columns. */
function recordColumns(rec) {
  const out = {};
  for (const k of ['frame', 'time_s', 'frame_ms', 'scheduler_ms', 'backend_cpu_ms', 'backend_gpu_ms',
    'backend_wall_ms', 'screenshot_ms', 'patches', 'visible', 'culled', 'strips', 'pattern_triangles',
    'strip_triangles', 'triangles', 'drawn_triangles', 'draw_calls', 'effective_epsilon', 'anim_ms', 'fovy']) {
    out[k] = typeof rec[k] === 'number' ? rec[k] : null;
  }
  const stages = rec.stage_ms || {};
  for (const k of STAGE_KEYS) out[k] = typeof stages[k.slice(0, -3)] === 'number' ? stages[k.slice(0, -3)] : null;
  const levels = Array.isArray(rec.level_histogram) ? rec.level_histogram : [];
  for (let l = 0; l < LEVELS; l++) out['level_' + l] = typeof levels[l] === 'number' ? levels[l] : null;
  return out;
}

/* Appends one frame record to run (live mode); returns the run. */
function appendRecord(run, rec) {
  const cols = recordColumns(rec);
  for (const k of Object.keys(cols)) (run.columns[k] = run.columns[k] || []).push(cols[k]);
  if (typeof rec.dropped === 'number') run.dropped = rec.dropped;
  return run;
}

/* The screenshot frame nearest to frame (screenshots: { "20": uri, ... }), or null. */
function nearestScreenshot(screenshots, frame) {
  let best = null;
  for (const f of Object.keys(screenshots || {}).map(Number)) {
    if (best === null || Math.abs(f - frame) < Math.abs(best - frame)) best = f;
  }
  return best;
}

/* One row of the per-run summary table. */
function summaryRow(run) {
  const c = run.columns, frame = stats(c.frame_ms || []);
  const mean = (k) => stats(c[k] || []).mean;
  return {
    label: run.label, frames: frame.count, p50: frame.p50, p95: frame.p95, p99: frame.p99, max: frame.max,
    scheduler: mean('scheduler_ms'), backend: mean('backend_cpu_ms'), triangles: mean('triangles'),
  };
}

/* Whether effective epsilon is worth a chart: a budget or target is set, or it moved. */
function epsilonVaries(run) {
  const e = (run.columns.effective_epsilon || []).filter(Number.isFinite);
  return (run.meta && run.meta.scene_budget > 0) || e.some((x) => x !== e[0]);
}

const logic = {
  percentile, stats, histogram, stack, gapsForMissing, recordColumns, appendRecord, nearestScreenshot,
  summaryRow, epsilonVaries, BUDGETS_MS,
};
if (typeof module !== 'undefined') module.exports = logic;

/* ---- the page ---- */

function el(tag, attrs, ...children) {
  const e = document.createElement(tag);
  Object.assign(e, attrs || {});
  for (const c of children) e.append(c);
  return e;
}

function fmt(x, digits) {
  return Number.isFinite(x) ? x.toFixed(digits === undefined ? 2 : digits) : '–';
}

/* Wheel zooms the x axis around the cursor; shift+wheel pans. (Drag zooms, double-click resets: uPlot.) */
function wheelZoom() {
  return {
    hooks: {
      ready: (u) => u.over.addEventListener('wheel', (e) => {
        e.preventDefault();
        const { min, max } = u.scales.x, at = u.posToVal(e.offsetX, 'x'), d = e.deltaY > 0 ? 1 : -1;
        if (e.shiftKey) {
          const shift = (max - min) * 0.1 * d;
          u.setScale('x', { min: min + shift, max: max + shift });
        } else {
          const k = d > 0 ? 1.25 : 0.8;
          u.setScale('x', { min: at - (at - min) * k, max: at + (max - at) * k });
        }
      }),
    },
  };
}

/* A uPlot chart from spec {title, x, series: [{label, values, ...series options}], extra} in parent. */
function chart(parent, spec) {
  const width = Math.max(320, Math.min(900, parent.clientWidth || 640));
  const opts = Object.assign({
    title: spec.title, width, height: 220, scales: { x: { time: false } }, plugins: [wheelZoom()],
    axes: [{}, { size: 60 }], // room for "100,000" triangles
    cursor: { sync: { key: 'frames' } },
    series: [{ label: spec.xLabel || 'frame' }].concat(spec.series.map((s, i) =>
      Object.assign({ stroke: COLORS[i % COLORS.length], width: 1.5, points: { show: false } }, s, { values: undefined }))),
  }, spec.extra || {});
  const u = new uPlot(opts, specData(spec), parent);
  window.tlodDashboard.charts.push({ title: spec.title, chart: u });
  return u;
}

function specData(spec) {
  return [spec.x].concat(spec.series.map((s) => s.values));
}

function budgetSeries(n) {
  return BUDGETS_MS.map((b) => ({ label: b + ' ms budget', values: new Array(n).fill(b), dash: [6, 4], stroke: '#999',
    points: { show: false } }));
}

function frameTimeSpec(run) {
  const c = run.columns, n = c.frame.length;
  const series = TIME_KEYS.map((k) => ({ label: k, values: k === 'backend_gpu_ms' ? gapsForMissing(c[k]) : c[k] }));
  const shots = c.frame.map((f) => (run.screenshots && run.screenshots[f] ? 0 : null));
  series.push({ label: 'screenshot', values: shots, stroke: '#000', paths: () => null, points: { show: true, size: 8 } });
  return { title: run.label + ': frame time (ms)', x: c.frame, series: series.concat(budgetSeries(n)), clickShows: true };
}

function histogramSpec(run) {
  const h = histogram(run.columns.frame_ms, 40);
  return { title: run.label + ': frame time histogram (frames per ms bin)', x: h.centers, xLabel: 'frame_ms',
    series: [{ label: 'frames', values: h.counts, fill: COLORS[0] + '88', paths: uPlot.paths.bars({ size: [0.9, 40] }) }],
    extra: { cursor: { sync: undefined } } };
}

/* A stacked chart: the tops are drawn largest first, hover shows each layer's own value. */
function stackedSpec(title, x, layers) {
  const tops = stack(layers.map((l) => l.values));
  const series = layers.map((l, i) => ({
    label: l.label, values: tops[i], fill: COLORS[i % COLORS.length], stroke: COLORS[i % COLORS.length],
    value: (u, v, si, idx) => (idx == null ? '–' : fmt(l.values[idx], 3)),
  })).reverse();
  const fromZero = { x: { time: false }, y: { range: (u, min, max) => [0, max > 0 ? max : 1] } };
  return { title, x, series, extra: { scales: fromZero } };
}

/* Every chart of one run, as specs (live mode rebuilds them to update the data). */
function runSpecs(run) {
  const c = run.columns, x = c.frame, t = run.label + ': ';
  const specs = [frameTimeSpec(run), histogramSpec(run),
    stackedSpec(t + 'scheduler stages (ms, stacked)', x, STAGE_KEYS.map((k) => ({ label: k, values: c[k] }))),
    { title: t + 'triangles and strips', x, series: [{ label: 'triangles', values: c.triangles },
      { label: 'strips', values: c.strips, scale: 'strips' }],
    extra: { axes: [{}, { size: 60 }, { scale: 'strips', side: 1, size: 60, grid: { show: false } }] } },
    stackedSpec(t + 'visible patches per level (stacked)', x,
      Array.from({ length: LEVELS }, (_, l) => ({ label: 'level ' + l, values: c['level_' + l] })))];
  if (epsilonVaries(run)) {
    specs.push({ title: t + 'effective epsilon (px)', x, series: [{ label: 'effective_epsilon', values: c.effective_epsilon }] });
  }
  if (run.object_triangles && run.object_triangles.length > 1) {
    specs.push({ title: t + 'triangles per object', x,
      series: run.object_triangles.map((v, i) => ({ label: run.objects[i], values: v })) });
  }
  return specs;
}

function runCharts(box, run) {
  return runSpecs(run).map((spec) => {
    const u = chart(box, spec);
    if (spec.clickShows) {
      u.over.addEventListener('click', () => {
        if (u.cursor.idx != null && !u.select.width) showScreenshot(run, run.columns.frame[u.cursor.idx]);
      });
    }
    return u;
  });
}

function showScreenshot(run, frame) {
  const f = nearestScreenshot(run.screenshots, frame), box = run.shotBox;
  if (f === null || !box) return;
  box.replaceChildren(el('figcaption', { textContent: run.label + ', frame ' + f }),
    el('img', { src: run.screenshots[f], alt: 'frame ' + f }));
}

function metaLine(run) {
  const m = run.meta || {};
  const view = m.debug_view && m.debug_view !== 'none' ? 'debug view ' + m.debug_view : '';
  const field = m.field ? 'field ' + m.field : '';
  return [m.scene, m.path, m.mode, m.backend, m.surface, view, field,
    m.stopped].filter(Boolean).join(' · ');
}

function runSection(run) {
  run.metaBox = el('p', { className: 'meta', textContent: metaLine(run) });
  const box = el('section', { className: 'run' }, el('h2', { textContent: run.label }), run.metaBox);
  if (run.truncated) box.append(el('p', { className: 'warning', textContent: run.truncated + ' (showing what it has)' }));
  if (run.screenshots_omitted) box.append(el('p', { className: 'note', textContent:
    run.screenshots_omitted + ' screenshots left out (over the page\'s size budget)' }));
  run.dropBox = el('p', { className: 'note' });
  run.shotBox = el('figure', { className: 'shot' }, el('figcaption', { textContent: 'click a frame to see its screenshot' }));
  box.append(run.dropBox, run.shotBox);
  return box;
}

function summaryTable(runs) {
  const head = ['run', 'frames', 'p50 ms', 'p95 ms', 'p99 ms', 'max ms', 'scheduler ms', 'backend cpu ms', 'triangles'];
  const rows = runs.map(summaryRow).map((r) => [r.label, String(r.frames), fmt(r.p50), fmt(r.p95), fmt(r.p99),
    fmt(r.max), fmt(r.scheduler, 3), fmt(r.backend, 3), fmt(r.triangles, 0)]);
  return table('summary', head, rows);
}

function table(id, head, rows) {
  return el('table', { id }, el('thead', {}, el('tr', {}, ...head.map((h) => el('th', { textContent: h })))),
    el('tbody', {}, ...rows.map((r) => el('tr', {}, ...r.map((v) => el('td', { textContent: v }))))));
}

/* The comparisons `tlod compare` computes (common/run_compare.c), one table per pair. */
function comparisonTables(data) {
  return (data.comparisons || []).map((cmp) => {
    const title = data.runs[cmp.run].label + ' vs ' + data.runs[cmp.base].label;
    if (cmp.error) return el('p', { className: 'warning', textContent: title + ': ' + cmp.error });
    const rows = cmp.result.rows.map((r) => [r.metric, fmt(r.base, 3), fmt(r.new, 3), r.ratio === null ? '–' : fmt(r.ratio, 3),
      fmt(r.change_pct, 1) + '%', r.limit_pct >= 0 ? fmt(r.limit_pct, 1) + '%' : '', r.regressed ? 'REGRESSION' : '']);
    return el('div', {}, el('h3', { textContent: title + (cmp.result.note ? ' (' + cmp.result.note + ')' : '') }),
      table('compare-' + cmp.run, ['metric', 'baseline', 'new', 'ratio', 'change', 'limit', ''], rows));
  });
}

function overlayChart(box, runs) {
  const n = Math.max(...runs.map((r) => r.columns.frame.length));
  const x = Array.from({ length: n }, (_, i) => i);
  const series = runs.map((r) => ({
    label: r.label, values: x.map((i) => (i < r.columns.frame_ms.length ? r.columns.frame_ms[i] : null)) }));
  chart(box, { title: 'frame time of every run (ms)', x, series: series.concat(budgetSeries(n)) });
}

/* A run of its own for live frames, with its section and a redraw at most once per animation frame. */
function liveRun(data, root, meta) {
  const run = { label: 'live' + (meta.mode ? ': ' + meta.mode : ''), meta, columns: {}, screenshots: {} };
  for (const k of Object.keys(recordColumns({}))) run.columns[k] = [];
  data.runs.push(run);
  const box = el('div', { className: 'charts' });
  root.append(runSection(run), box);
  let charts = null, pending = false;
  run.redraw = () => {
    pending = false;
    if (!charts) charts = runCharts(box, run);
    else runSpecs(run).slice(0, charts.length).forEach((spec, i) => charts[i].setData(specData(spec)));
    run.dropBox.textContent = 'live: ' + run.columns.frame.length + ' frames, ' + (run.dropped || 0) +
      ' dropped for this page' + (run.ended ? ' (the run ended)' : '');
  };
  run.add = (rec) => {
    appendRecord(run, rec);
    if (!pending) pending = requestAnimationFrame(run.redraw);
  };
  return run;
}

/* Live mode: frames from the server's event stream (tlod play --serve: an event "run" with the settings,
 * one message per frame, "run" again when the next --compare mode starts, "end" when playing ends). */
function startLive(data, root) {
  const source = new EventSource(data.config.live);
  const live = { run: liveRun(data, root, {}), source };
  source.onmessage = (e) => live.run.add(JSON.parse(e.data));
  source.addEventListener('run', (e) => {
    const meta = JSON.parse(e.data);
    if (live.run.columns.frame.length) live.run = liveRun(data, root, meta); // the next mode: frames from 0
    live.run.meta = meta;
    live.run.metaBox.textContent = metaLine(live.run);
  });
  source.addEventListener('end', (e) => {
    source.close(); // no reconnecting to a server that is done
    live.run.dropped = JSON.parse(e.data).dropped;
    live.run.ended = true;
    live.run.redraw();
  });
  window.tlodDashboard.live = live;
}

function main() {
  const data = JSON.parse(document.getElementById('tlod-data').textContent);
  const root = document.getElementById('runs');
  window.tlodDashboard = { data, charts: [] };
  document.title = data.config.title;
  document.getElementById('title').textContent = data.config.title;
  if (data.runs.length) root.append(el('h2', { textContent: 'Summary' }), summaryTable(data.runs));
  if (data.runs.length > 1) {
    overlayChart(root, data.runs);
    root.append(el('h2', { textContent: 'Every run against the first (as tlod compare)' }),
      el('div', { className: 'comparisons' }, ...comparisonTables(data)));
  }
  const grid = el('div', { className: data.runs.length > 1 ? 'side-by-side' : '' });
  root.append(grid);
  // Every column first, so each chart is sized to its column's final width.
  const cols = data.runs.map((run) => grid.appendChild(el('div', {}, runSection(run))));
  data.runs.forEach((run, i) => runCharts(cols[i], run));
  if (data.config.live) startLive(data, root);
}

if (typeof document !== 'undefined') document.addEventListener('DOMContentLoaded', main);
