// Per-vehicle 3D content: estimate / truth / GNSS trajectories, the current pose marker and the latest landmark clouds.
// Trajectories are drawn over the buildings (no depth test): a path hidden behind a tower tells the viewer nothing,
// and the estimate is drawn last and narrower than the truth so both stay visible where they overlap.
import {
  BufferAttribute,
  BufferGeometry,
  Box3,
  Color,
  Group,
  Points,
  PointsMaterial,
  Quaternion,
  Vector3,
} from 'three';
import { Line2 } from 'three/examples/jsm/lines/Line2.js';
import { LineGeometry } from 'three/examples/jsm/lines/LineGeometry.js';
import { LineMaterial } from 'three/examples/jsm/lines/LineMaterial.js';
import { COLORS } from './colors.js';
import { decodePointCloud, decodePose } from './messages.js';

// Path styles: width in CSS px, draw order (later on top).
const PATHS = {
  'truth/path': { color: COLORS.truth, width: 8, order: 10 },
  'estimate/path': { color: COLORS.estimate, width: 5, order: 12 },
};

function lineMaterial(color, width, resolution) {
  // LineMaterial is unlit and not tone-mapped: its pixels are the exact colour away from the edges.
  const m = new LineMaterial({ color: new Color(color), linewidth: width, depthTest: false, depthWrite: false });
  // The uniform holds the stage's own Vector2 (not a copy), so a window resize reaches every line at once.
  m.uniforms.resolution.value = resolution;
  return m;
}

function pointsMaterial(color, sizePx, depthTest) {
  return new PointsMaterial({ color: new Color(color), size: sizePx, sizeAttenuation: false, depthTest });
}

class Vehicle {
  constructor(id, parent, resolution) {
    this.id = id;
    this.group = new Group();
    this.group.name = `vehicle/${id}`;
    parent.add(this.group);
    this.resolution = resolution;
    this.paths = {}; // kind -> {object, count, bounds}
    this.counts = { 'estimate/path': 0, 'truth/path': 0, 'gnss/path': 0, landmarks: 0, 'landmarks/registered': 0 };
    this.clouds = {}; // kind -> Points
    this.pose = null; // {p, q, stamp}
    this.gnss = null; // latest LocationFix
    this.registration = null; // the latest RegistrationHealth (panels keep the history)

    this.marker = new Group();
    this.marker.renderOrder = 20;
    const dot = new Points(
      new BufferGeometry().setAttribute('position', new BufferAttribute(new Float32Array([0, 0, 0]), 3)),
      pointsMaterial(COLORS.pose, 11, false),
    );
    dot.renderOrder = 20;
    this.heading = new Line2(new LineGeometry(), lineMaterial(COLORS.pose, 3, resolution));
    this.heading.renderOrder = 20;
    this.marker.add(dot, this.heading);
    this.marker.visible = false;
    this.group.add(this.marker);
  }

  setPath(kind, msg) {
    const poses = (msg.poses || []).map(decodePose);
    const positions = new Float32Array(poses.length * 3);
    poses.forEach((pose, i) => positions.set(pose.p, i * 3));
    this.counts[kind] = poses.length;
    const old = this.paths[kind];
    if (old) {
      this.group.remove(old.object);
      old.object.geometry.dispose();
      old.object.material.dispose();
    }
    let object;
    if (kind === 'gnss/path') {
      // GNSS fixes are scattered samples, not a continuous track: drawn as dots.
      const geometry = new BufferGeometry().setAttribute('position', new BufferAttribute(positions, 3));
      object = new Points(geometry, pointsMaterial(COLORS.gnss, 6, false));
      object.renderOrder = 11;
    } else {
      const style = PATHS[kind];
      const geometry = new LineGeometry();
      // A single pose is drawn as a zero-length segment (a dot of the line's width), not skipped.
      geometry.setPositions(poses.length === 1 ? [...positions, ...positions] : positions);
      object = new Line2(geometry, lineMaterial(style.color, style.width, this.resolution));
      object.renderOrder = style.order;
      object.visible = poses.length > 0;
    }
    this.group.add(object);
    const bounds = new Box3();
    for (const p of poses) bounds.expandByPoint(new Vector3(...p.p));
    this.paths[kind] = { object, bounds };
  }

  setPose(msg, frameSize) {
    const pose = decodePose(msg.pose);
    this.pose = { ...pose, stamp: msg.timestamp };
    this.marker.position.set(...pose.p);
    // The heading tick is a fixed fraction of the framed scene, so it stays visible at any zoom.
    const len = Math.max(2, frameSize * 0.03);
    const forward = new Vector3(len, 0, 0).applyQuaternion(new Quaternion(...pose.q));
    this.heading.geometry.dispose();
    this.heading.geometry = new LineGeometry();
    this.heading.geometry.setPositions([0, 0, 0, forward.x, forward.y, forward.z]);
    this.marker.visible = true;
  }

  setCloud(kind, msg) {
    const xyz = decodePointCloud(msg);
    const old = this.clouds[kind];
    if (old) {
      this.group.remove(old);
      old.geometry.dispose();
    }
    const geometry = new BufferGeometry().setAttribute('position', new BufferAttribute(xyz, 3));
    const color = kind === 'landmarks' ? COLORS.landmarks : COLORS.registered;
    const points = new Points(geometry, old ? old.material : pointsMaterial(color, 3, true));
    points.renderOrder = 5;
    this.clouds[kind] = points;
    this.counts[kind] = xyz.length / 3;
    this.group.add(points);
  }

  // What framing follows: the trajectories (landmarks may hold far outliers).
  bounds() {
    const box = new Box3();
    for (const { bounds } of Object.values(this.paths)) box.union(bounds);
    if (this.pose) box.expandByPoint(new Vector3(...this.pose.p));
    return box;
  }
}

export class Vehicles {
  constructor(scene, resolution) {
    this.group = new Group();
    this.group.name = 'vehicles';
    scene.add(this.group);
    this.resolution = resolution;
    this.byId = new Map();
  }

  get(id) {
    let v = this.byId.get(id);
    if (!v) {
      v = new Vehicle(id, this.group, this.resolution);
      this.byId.set(id, v);
    }
    return v;
  }

  bounds() {
    const box = new Box3();
    for (const v of this.byId.values()) box.union(v.bounds());
    return box;
  }
}
