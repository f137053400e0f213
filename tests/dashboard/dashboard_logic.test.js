// The dashboard page's pure functions (tools/dashboard/dashboard.js), with node's own test runner:
// node --test tests/dashboard/dashboard_logic.test.js. Expected values are worked out by hand here.
'use strict';
const test = require('node:test');
const assert = require('node:assert/strict');
const path = require('node:path');
const d = require(path.join(__dirname, '..', '..', 'tools', 'dashboard', 'dashboard.js'));

test('percentile is nearest-rank, as tlod play summary computes it', () => {
  const v = [1, 2, 3, 4, 5, 6, 7, 8, 9, 10];
  assert.equal(d.percentile(v, 50), 5); // ceil(0.5 * 10) = rank 5
  assert.equal(d.percentile(v, 95), 10); // ceil(9.5) = rank 10
  assert.equal(d.percentile(v, 0), 1);
  assert.ok(Number.isNaN(d.percentile([], 50)));
});

test('stats skip gaps (null, NaN) and sort numerically', () => {
  const s = d.stats([10, null, 2, NaN, 30, 4]);
  assert.deepEqual(s, { count: 4, mean: 11.5, p50: 4, p95: 30, p99: 30, max: 30 });
});

test('histogram: equal bins over the range, every value counted once', () => {
  const h = d.histogram([0, 1, 2, 3, 4, 10], 5);
  assert.deepEqual(h.counts, [2, 2, 1, 0, 1]);
  assert.deepEqual(h.centers, [1, 3, 5, 7, 9]);
  assert.equal(h.counts.reduce((a, b) => a + b), 6);
  assert.deepEqual(d.histogram([5, 5], 4).counts, [2, 0, 0, 0]); // one value: no division by zero
  assert.deepEqual(d.histogram([], 4), { centers: [], counts: [] });
});

test('stack: running sums, a gap counts as zero', () => {
  assert.deepEqual(d.stack([[1, 2], [10, null], [100, 200]]), [[1, 2], [11, 2], [111, 202]]);
});

test('a GPU time of -1 (no result that frame) is a gap', () => {
  assert.deepEqual(d.gapsForMissing([1.5, -1, 0, null]), [1.5, null, 0, null]);
});

test('a live frame record maps to the trace.csv columns', () => {
  const rec = { frame: 7, frame_ms: 12.5, stage_ms: { silhouette: 0.25, strips: 1 }, level_histogram: [3, 4],
    triangles: 99, dropped: 2 };
  const c = d.recordColumns(rec);
  assert.equal(c.frame, 7);
  assert.equal(c.silhouette_ms, 0.25);
  assert.equal(c.strips_ms, 1);
  assert.equal(c.metric_ms, null);
  assert.equal(c.level_0, 3);
  assert.equal(c.level_1, 4);
  assert.equal(c.level_10, null);
  const run = { columns: {} };
  d.appendRecord(run, rec);
  d.appendRecord(run, Object.assign({}, rec, { frame: 8, dropped: 5 }));
  assert.deepEqual(run.columns.frame, [7, 8]);
  assert.deepEqual(run.columns.triangles, [99, 99]);
  assert.equal(run.dropped, 5);
});

test('the nearest screenshot to a clicked frame', () => {
  const shots = { 0: 'a', 20: 'b', 40: 'c' };
  assert.equal(d.nearestScreenshot(shots, 9), 0);
  assert.equal(d.nearestScreenshot(shots, 11), 20);
  assert.equal(d.nearestScreenshot(shots, 100), 40);
  assert.equal(d.nearestScreenshot({}, 3), null);
});

test('summary row of a run', () => {
  const run = { label: 'r', columns: { frame_ms: [4, 1, 3, 2], scheduler_ms: [1, 1, 1, 3], backend_cpu_ms: [2, 2, 2, 2],
    triangles: [10, 20, 30, 40] } };
  assert.deepEqual(d.summaryRow(run), { label: 'r', frames: 4, p50: 2, p95: 4, p99: 4, max: 4, scheduler: 1.5,
    backend: 2, triangles: 25 });
});

test('effective epsilon gets a chart only when it matters', () => {
  assert.equal(d.epsilonVaries({ meta: {}, columns: { effective_epsilon: [0.5, 0.5] } }), false);
  assert.equal(d.epsilonVaries({ meta: {}, columns: { effective_epsilon: [0.5, 0.7] } }), true);
  assert.equal(d.epsilonVaries({ meta: { scene_budget: 1000 }, columns: { effective_epsilon: [1, 1] } }), true);
});
