// Decoding of the JSON forms of Foxglove's well-known schemas as the bridge writes them
// (common/foxglove/src/well_known.cpp), and the mapping of a topic to (vehicle, kind).

// Longest suffixes first: "/V/landmarks/registered" must not be taken for "/V/landmarks" of vehicle "V/landmarks".
const KINDS = [
  'landmarks/registered',
  'estimate/path',
  'estimate/pose',
  'truth/path',
  'gnss/path',
  'registration',
  'landmarks',
  'gnss',
];

// "/car1/estimate/path" -> {vehicle: "car1", kind: "estimate/path"}; other topics -> {vehicle: null, kind: topic}.
export function routeTopic(topic) {
  if (topic === '/twin/tiles' || topic === '/services') return { vehicle: null, kind: topic };
  for (const kind of KINDS) {
    const suffix = `/${kind}`;
    if (topic.length > suffix.length + 1 && topic.endsWith(suffix) && topic.startsWith('/')) {
      return { vehicle: topic.slice(1, topic.length - suffix.length), kind };
    }
  }
  return { vehicle: null, kind: topic };
}

const finite = (v, fallback = 0) => (typeof v === 'number' && Number.isFinite(v) ? v : fallback);

// A Foxglove Pose -> {p:[x,y,z], q:[x,y,z,w]}; nulls (the C++ side writes NaN as null) become identity parts.
export function decodePose(pose) {
  const p = pose?.position ?? {};
  const o = pose?.orientation ?? {};
  let q = [finite(o.x), finite(o.y), finite(o.z), finite(o.w, 1)];
  const n = Math.hypot(...q);
  q = n > 0 ? q.map((c) => c / n) : [0, 0, 0, 1];
  return { p: [finite(p.x), finite(p.y), finite(p.z)], q };
}

export function stampSeconds(t) {
  return finite(t?.sec) + finite(t?.nsec) * 1e-9;
}

// Rotates v by unit quaternion q = [x,y,z,w] and adds t.
export function transformPoint(q, t, v) {
  const [qx, qy, qz, qw] = q;
  const [vx, vy, vz] = v;
  // v' = v + 2w(q x v) + 2 q x (q x v)
  const cx = qy * vz - qz * vy;
  const cy = qz * vx - qx * vz;
  const cz = qx * vy - qy * vx;
  const dx = qy * cz - qz * cy;
  const dy = qz * cx - qx * cz;
  const dz = qx * cy - qy * cx;
  return [vx + 2 * (qw * cx + dx) + t[0], vy + 2 * (qw * cy + dy) + t[1], vz + 2 * (qw * cz + dz) + t[2]];
}

function base64Bytes(text) {
  const binary = atob(text || '');
  const out = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; ++i) out[i] = binary.charCodeAt(i);
  return out;
}

// Foxglove NumericType values this view reads (the bridge writes FLOAT32 = 7).
const READERS = {
  7: (view, off) => view.getFloat32(off, true),
  8: (view, off) => view.getFloat64(off, true),
};

// A foxglove.PointCloud -> Float32Array of x,y,z in the message frame (the cloud's pose applied); bad clouds -> empty.
export function decodePointCloud(msg) {
  const fields = new Map((msg.fields || []).map((f) => [f.name, f]));
  const fx = fields.get('x');
  const fy = fields.get('y');
  const fz = fields.get('z');
  const stride = Number(msg.point_stride) || 0;
  if (!fx || !fy || !fz || stride <= 0) return new Float32Array(0);
  const readers = [fx, fy, fz].map((f) => READERS[f.type]);
  if (readers.some((r) => !r)) return new Float32Array(0);
  let bytes;
  try {
    bytes = base64Bytes(msg.data);
  } catch {
    return new Float32Array(0);
  }
  const view = new DataView(bytes.buffer);
  const count = Math.floor(bytes.length / stride);
  const pose = decodePose(msg.pose);
  const out = new Float32Array(count * 3);
  let n = 0;
  for (let i = 0; i < count; ++i) {
    const base = i * stride;
    if (base + Math.max(fx.offset, fy.offset, fz.offset) + 4 > bytes.length) break;
    const v = [readers[0](view, base + fx.offset), readers[1](view, base + fy.offset), readers[2](view, base + fz.offset)];
    if (!v.every(Number.isFinite)) continue; // a NaN point would poison the bounds
    const w = transformPoint(pose.q, pose.p, v);
    out[n++] = w[0];
    out[n++] = w[1];
    out[n++] = w[2];
  }
  return out.subarray(0, n);
}
