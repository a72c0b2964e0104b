// report.html's charts, drawn with uPlot (inlined before this script) from the page's own data
// (the <script id="report-data"> element, written by floorgrid's report writer).
(function () {
  'use strict';
  const data = JSON.parse(document.getElementById('report-data').textContent);
  const palette = ['#1f77b4', '#ff7f0e', '#2ca02c', '#d62728', '#9467bd', '#8c564b', '#e377c2',
                   '#7f7f7f', '#bcbd22', '#17becf'];
  const charts = [];

  function chartWidth(element) {
    return Math.max(320, Math.min(element.parentElement.clientWidth, 1100));
  }

  function place(element, opts, columns) {
    opts.width = chartWidth(element);
    const chart = new uPlot(opts, columns, element);
    charts.push([chart, element]);
    return chart;
  }

  // Error histograms: the share of the domain's points per 0.05 m bin, one stepped line per
  // model, the chosen model drawn thicker; then the same added up (share within each error).
  function drawHistograms(elementId, cumulative) {
    const element = document.getElementById(elementId);
    const names = data.models.filter((name) => name in data.histograms);
    if (!element || names.length === 0) return;
    const bins = data.histograms[names[0]].length;
    const x = Array.from({ length: bins }, (_, i) => 0.05 * (cumulative ? i + 1 : i));
    const columns = [x];
    const series = [{ label: cumulative ? 'error up to' : 'error',
                      value: (u, v) => (v == null ? '' : cumulative ? upTo(v) : binLabel(v)) }];
    names.forEach((name, k) => {
      const counts = data.histograms[name];
      const total = counts.reduce((a, b) => a + b, 0);
      let sum = 0;
      columns.push(counts.map((n) => {
        sum += n;
        return total > 0 ? (100 * (cumulative ? sum : n)) / total : null;
      }));
      const chosen = name === data.chosen;
      series.push({
        label: chosen ? name + ' (chosen)' : name,
        stroke: palette[k % palette.length],
        width: chosen ? 3 : 1.5,
        paths: uPlot.paths.stepped({ align: cumulative ? -1 : 1 }),
        points: { show: false },
        value: (u, v) => (v == null ? '' : v.toFixed(1) + '%'),
      });
    });
    // Up to the last bin that holds at least 0.5% of some model's points (and one bin more):
    // the whole width to 1.0 m and more only when a model has errors that large.
    let last = 0;
    names.forEach((name) => {
      const counts = data.histograms[name];
      const total = counts.reduce((a, b) => a + b, 0);
      counts.forEach((n, i) => { if (total > 0 && n / total >= 0.005) last = Math.max(last, i); });
    });
    const right = 0.05 * Math.min(bins, last + 2);
    place(element, {
      height: cumulative ? 240 : 280,
      series: series,
      scales: { x: { time: false, range: [0, right] },
                y: { range: cumulative ? [0, 100] : (u, lo, hi) => [0, hi * 1.05] } },
      axes: [
        { label: cumulative ? 'error against the truth (m)'
                            : 'error against the truth (m); the last bin is 1.0 m and more',
          // Ticks on the bins' edges (0.05 m), never between them.
          incrs: [0.05, 0.1, 0.25, 0.5], values: (u, splits) => splits.map((v) => v.toFixed(2)) },
        { label: cumulative ? 'points within (%)' : 'share of points (%)', size: 60 },
      ],
    }, columns);
  }

  function upTo(v) {
    return v >= 1.04 ? 'any' : v.toFixed(2) + ' m';
  }

  function binLabel(from) {
    return from >= 0.999 ? '1.0 m and more' : from.toFixed(2) + '-' + (from + 0.05).toFixed(2) + ' m';
  }

  // The localization scan by scan: three bars (gridmap filter converged, plan filter
  // converged, pairs made) where each was true, and the pairs per scan below, cursors synced.
  function drawLocalization() {
    const scans = data.scans;
    const top = document.getElementById('chart-localization');
    const bottom = document.getElementById('chart-scan-pairs');
    if (!scans || !top || !bottom || scans.scan.length < 2) return;
    const row = (values, level) => values.map((v) => (v == null ? null : level));
    const sync = { key: 'scans' };
    const rows = ['', 'pairs made', 'plan filter', 'gridmap filter'];
    const band = (label, colour) => ({
      label: label, stroke: colour, width: 10, points: { show: false },
      value: (u, v, seriesIndex, index) => (index == null ? '' : v == null ? 'no' : 'yes'),
    });
    place(top, {
      height: 150,
      cursor: { sync: sync, y: false },
      series: [
        { label: 'scan' },
        band('gridmap filter converged', '#2b6cb0'),
        band('plan filter converged', '#dd6b20'),
        band('pairs made', '#2f855a'),
      ],
      scales: { x: { time: false }, y: { range: [0.4, 3.6] } },
      axes: [
        { label: 'scan' },
        { size: 110, splits: () => [1, 2, 3], values: (u, splits) => splits.map((v) => rows[v]),
          grid: { show: false } },
      ],
    }, [scans.scan, row(scans.grid, 3), row(scans.plan, 2), row(scans.paired, 1)]);
    place(bottom, {
      height: 180,
      cursor: { sync: sync },
      series: [
        { label: 'scan' },
        { label: scans.bucket > 1 ? 'pairs per ' + scans.bucket + ' scans' : 'pairs per scan',
          stroke: '#2f855a', fill: 'rgba(47, 133, 90, 0.25)', width: 1,
          paths: uPlot.paths.stepped({ align: 1 }), points: { show: false } },
      ],
      scales: { x: { time: false } },
      axes: [{ label: 'scan' }, { label: 'pairs', size: 110 }],
    }, [scans.scan, scans.pairs]);
  }

  // Pictures enlarge on a click and shrink on the next.
  function zoomablePictures() {
    document.querySelectorAll('figure.zoomable').forEach((figure) => {
      figure.addEventListener('click', () => figure.classList.toggle('wide'));
    });
  }

  drawHistograms('chart-histogram', false);
  drawHistograms('chart-cumulative', true);
  drawLocalization();
  zoomablePictures();
  window.addEventListener('resize', () => {
    for (const [chart, element] of charts)
      chart.setSize({ width: chartWidth(element), height: chart.height });
  });
})();
