// The side panel: connection state, vehicles (path sizes, latest GNSS fix as text), registration health (sparklines,
// accepted/rejected counts) and services (state, uptime, staleness). Plain DOM, rebuilt at most a few times a second.
import { drawSparkline } from './sparkline.js';
import { stampSeconds } from './messages.js';

const HISTORY = 120; // registrations kept per vehicle for the sparklines
export const STALE_MS = 5000; // a service silent for longer is marked stale

function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'class') e.className = v;
    else e.setAttribute(k, v);
  }
  for (const c of children) e.append(c instanceof Node ? c : document.createTextNode(String(c)));
  return e;
}

function formatUptime(ms) {
  const s = Math.max(0, Math.floor((Number(ms) || 0) / 1000));
  const h = Math.floor(s / 3600);
  const m = Math.floor((s % 3600) / 60);
  return h > 0 ? `${h}h${String(m).padStart(2, '0')}m` : m > 0 ? `${m}m${String(s % 60).padStart(2, '0')}s` : `${s}s`;
}

const fmt = (v, digits = 2) => (Number.isFinite(v) ? v.toFixed(digits) : '–');

export class Panels {
  constructor(root) {
    this.root = root;
    this.connection = root.querySelector('#connection');
    this.serverStatus = root.querySelector('#server-status');
    this.vehiclesEl = root.querySelector('#vehicles');
    this.registrationEl = root.querySelector('#registration');
    this.servicesEl = root.querySelector('#services');
    this.registrations = new Map(); // vehicle -> {history[], accepted, rejected, byStatus{}, last}
    this.services = new Map(); // "service instance" -> {msg, seenAt}
    this.dirty = new Set();
    this.sparkCanvases = new Map(); // vehicle -> {rmse, inliers} canvases (kept across rebuilds)
    setInterval(() => this.renderServices(), 1000); // staleness advances without messages
  }

  setConnection({ state, detail, serverName }) {
    this.connection.className = `state ${state}`;
    this.connection.textContent = `${state}${serverName && state === 'connected' ? ` to ${serverName}` : ''}`;
    this.connection.title = detail || '';
    this.serverStatus.textContent = state === 'connected' ? '' : detail || '';
  }

  setServerStatus({ level, message }) {
    this.serverStatus.textContent = `${['info', 'warning', 'error'][level] ?? 'status'}: ${message}`;
  }

  addRegistration(vehicle, msg) {
    let r = this.registrations.get(vehicle);
    if (!r) {
      r = { history: [], accepted: 0, rejected: 0, byStatus: {}, last: null };
      this.registrations.set(vehicle, r);
    }
    r.history.push({ t: stampSeconds(msg.timestamp), rmse: msg.rmse_m, inliers: msg.inliers, accepted: !!msg.accepted });
    if (r.history.length > HISTORY) r.history.shift();
    if (msg.accepted) r.accepted += 1;
    else r.rejected += 1;
    const status = String(msg.status ?? 'UNKNOWN');
    r.byStatus[status] = (r.byStatus[status] || 0) + 1;
    r.last = msg;
    this.dirty.add('registration');
  }

  addService(msg) {
    const key = `${msg.service ?? '?'} ${msg.instance ?? ''} ${msg.vehicle_id ?? ''}`;
    this.services.set(key, { msg, seenAt: performance.now() });
    this.dirty.add('services');
  }

  // Called by the main loop at a few Hz: only the sections that changed are rebuilt.
  flush(vehicles) {
    this.renderVehicles(vehicles);
    if (this.dirty.has('registration')) this.renderRegistration();
    if (this.dirty.has('services')) this.renderServices();
    this.dirty.clear();
  }

  renderVehicles(vehicles) {
    const rows = [];
    for (const v of vehicles.byId.values()) {
      const p = v.pose?.p;
      const fix = v.gnss;
      rows.push(
        el(
          'div',
          { class: 'vehicle' },
          el('div', { class: 'name' }, v.id),
          el(
            'div',
            { class: 'kv' },
            `estimate ${v.counts['estimate/path']} · truth ${v.counts['truth/path']} · gnss ${v.counts['gnss/path']} poses`,
          ),
          el('div', { class: 'kv' }, p ? `pose ${fmt(p[0], 1)}, ${fmt(p[1], 1)}, ${fmt(p[2], 1)} m` : 'no pose yet'),
          el(
            'div',
            { class: 'kv' },
            `landmarks ${v.counts.landmarks} · registered ${v.counts['landmarks/registered']}`,
          ),
          el(
            'div',
            { class: 'kv' },
            fix ? `GNSS ${fmt(fix.latitude, 7)}°, ${fmt(fix.longitude, 7)}°, ${fmt(fix.altitude, 1)} m` : 'no GNSS fix',
          ),
        ),
      );
    }
    this.vehiclesEl.replaceChildren(...(rows.length ? rows : [el('div', { class: 'muted' }, 'no vehicle yet')]));
  }

  renderRegistration() {
    const blocks = [];
    for (const [vehicle, r] of this.registrations) {
      let canvases = this.sparkCanvases.get(vehicle);
      if (!canvases) {
        canvases = { rmse: el('canvas', { class: 'spark' }), inliers: el('canvas', { class: 'spark' }) };
        this.sparkCanvases.set(vehicle, canvases);
      }
      const last = r.last;
      const statusClass = last.accepted ? 'ok' : 'bad';
      const statuses = Object.entries(r.byStatus)
        .sort((a, b) => b[1] - a[1])
        .map(([s, n]) => `${s} ${n}`)
        .join(' · ');
      blocks.push(
        el(
          'div',
          { class: 'reg' },
          el('div', { class: 'name' }, vehicle, ' ', el('span', { class: `badge ${statusClass}` }, last.status)),
          el('div', { class: 'kv' }, `accepted ${r.accepted} · rejected ${r.rejected}`),
          el('div', { class: 'kv small' }, statuses),
          el(
            'div',
            { class: 'kv' },
            `fitness ${fmt(last.fitness)} · correction ${fmt(last.correction_translation_m)} m / ${fmt(last.correction_rotation_deg, 1)}°`,
          ),
          el('div', { class: 'kv' }, `compute ${fmt(last.compute_ms, 1)} ms · latency ${fmt(last.latency_ms, 1)} ms`),
          canvases.rmse,
          canvases.inliers,
          last.reason ? el('div', { class: 'kv small muted' }, last.reason) : '',
        ),
      );
    }
    this.registrationEl.replaceChildren(...(blocks.length ? blocks : [el('div', { class: 'muted' }, 'no registration yet')]));
    // Canvases are drawn after insertion: their CSS size is known only once they are in the document.
    for (const [vehicle, r] of this.registrations) {
      const c = this.sparkCanvases.get(vehicle);
      drawSparkline(c.rmse, r.history.map((h) => h.rmse), { color: '#ff9f0a', label: 'RMSE m', digits: 3 });
      drawSparkline(c.inliers, r.history.map((h) => h.inliers), { color: '#64d2ff', label: 'inliers', digits: 0 });
    }
  }

  renderServices() {
    const now = performance.now();
    const rows = [...this.services.values()]
      .sort((a, b) => `${a.msg.service}${a.msg.instance}`.localeCompare(`${b.msg.service}${b.msg.instance}`))
      .map(({ msg, seenAt }) => {
        const stale = now - seenAt > STALE_MS;
        const state = String(msg.state ?? '?');
        // READY (joined, waiting for input) and DONE are healthy states too; only FAILED / STOPPING are alarms.
        const cls = stale ? 'stale' : ['RUNNING', 'READY', 'DONE', 'STARTING'].includes(state) ? 'ok' : 'bad';
        const counters = (msg.counters || []).map((c) => `${c.name}=${c.value}`).join(' ');
        return el(
          'tr',
          { class: cls, title: counters },
          el('td', {}, msg.service ?? '?', msg.vehicle_id ? ` (${msg.vehicle_id})` : ''),
          el('td', { class: 'small' }, msg.instance ?? ''),
          el('td', {}, stale ? `STALE ${Math.round((now - seenAt) / 1000)}s` : state),
          el('td', {}, formatUptime(msg.uptime_ms)),
        );
      });
    if (rows.length === 0) {
      this.servicesEl.replaceChildren(el('div', { class: 'muted' }, 'no service report yet'));
      return;
    }
    this.servicesEl.replaceChildren(
      el('table', {}, el('tr', {}, el('th', {}, 'service'), el('th', {}, 'instance'), el('th', {}, 'state'), el('th', {}, 'up')), ...rows),
    );
  }
}
