// A tiny hand-drawn line plot on a canvas: the last N values of a series, min/max labelled. No chart library: the
// panels need a trend at a glance, not axes and tooltips.
export function drawSparkline(canvas, values, { color = '#ff9f0a', label = '', digits = 2 } = {}) {
  const dpr = window.devicePixelRatio || 1;
  const w = canvas.clientWidth || 220;
  const h = canvas.clientHeight || 36;
  if (canvas.width !== Math.round(w * dpr) || canvas.height !== Math.round(h * dpr)) {
    canvas.width = Math.round(w * dpr);
    canvas.height = Math.round(h * dpr);
  }
  const ctx = canvas.getContext('2d');
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  ctx.clearRect(0, 0, w, h);
  const finite = values.filter(Number.isFinite);
  ctx.font = '10px system-ui, sans-serif';
  ctx.fillStyle = '#8b949e';
  if (finite.length === 0) {
    ctx.fillText(`${label}: no data`, 4, h / 2 + 3);
    return;
  }
  let lo = Math.min(...finite);
  let hi = Math.max(...finite);
  if (hi - lo < 1e-9) {
    lo -= 0.5;
    hi += 0.5;
  }
  const top = 12;
  const bottom = h - 3;
  const x = (i) => 2 + (i * (w - 4)) / Math.max(1, values.length - 1);
  const y = (v) => bottom - ((v - lo) / (hi - lo)) * (bottom - top);
  ctx.strokeStyle = color;
  ctx.lineWidth = 1.5;
  ctx.beginPath();
  let drawing = false;
  values.forEach((v, i) => {
    if (!Number.isFinite(v)) {
      drawing = false; // a gap where the value was missing (null from a NaN)
      return;
    }
    if (drawing) ctx.lineTo(x(i), y(v));
    else ctx.moveTo(x(i), y(v));
    drawing = true;
  });
  ctx.stroke();
  const last = finite[finite.length - 1];
  ctx.fillText(`${label} ${last.toFixed(digits)}  [${Math.min(...finite).toFixed(digits)}–${Math.max(...finite).toFixed(digits)}]`, 4, 10);
}
