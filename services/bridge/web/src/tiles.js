// The digital twin: /twin/tiles (foxglove.SceneUpdate), one entity per map tile, each replacing the entity of the
// same id. Only triangle lists are drawn: that is all the bridge puts in a tile.
import { Box3, BufferAttribute, BufferGeometry, DoubleSide, Group, Mesh, MeshLambertMaterial } from 'three';
import { decodePose } from './messages.js';

// One neutral grey-blue for all buildings (not the message's colour): the test and the legend rely on buildings
// being this colour, and lit faces of it never look like a trajectory colour.
export const TILE_COLOR = 0xaab4c6;

export class Tiles {
  constructor(scene) {
    this.group = new Group();
    this.group.name = 'tiles';
    scene.add(this.group);
    this.entities = new Map(); // entity id -> Group
    this.material = new MeshLambertMaterial({ color: TILE_COLOR, side: DoubleSide });
    this.cachedBounds = new Box3();
    this.cachedTriangles = 0;
    // A late viewer receives every latched tile in a burst: bounds are recomputed once when asked, not per tile.
    this.dirty = false;
  }

  get bounds() {
    this.refresh();
    return this.cachedBounds;
  }

  get triangles() {
    this.refresh();
    return this.cachedTriangles;
  }

  get count() {
    return this.entities.size;
  }

  apply(update) {
    for (const d of update.deletions || []) {
      if (d.type === 1) {
        for (const id of [...this.entities.keys()]) this.remove(id); // ALL
      } else {
        this.remove(d.id); // MATCHING_ID
      }
    }
    for (const entity of update.entities || []) this.replace(entity);
    this.dirty = true;
  }

  remove(id) {
    const old = this.entities.get(id);
    if (!old) return;
    this.group.remove(old);
    old.traverse((o) => o.geometry?.dispose());
    this.entities.delete(id);
  }

  replace(entity) {
    const id = String(entity.id ?? '');
    this.remove(id);
    const group = new Group();
    group.name = id;
    for (const list of entity.triangles || []) {
      const geometry = triangleGeometry(list);
      if (!geometry) continue;
      const mesh = new Mesh(geometry, this.material);
      const pose = decodePose(list.pose);
      mesh.position.set(...pose.p);
      mesh.quaternion.set(...pose.q);
      group.add(mesh);
    }
    if (group.children.length === 0) return; // an empty tile: nothing to draw (and it was removed above)
    this.entities.set(id, group);
    this.group.add(group);
  }

  refresh() {
    if (!this.dirty) return;
    this.dirty = false;
    this.group.updateMatrixWorld(true);
    this.cachedBounds = new Box3().setFromObject(this.group);
    let n = 0;
    this.group.traverse((o) => {
      if (o.isMesh) n += o.geometry.attributes.position.count / 3;
    });
    this.cachedTriangles = n;
  }
}

// A TriangleListPrimitive -> a non-indexed BufferGeometry with flat normals (each triangle its own vertices, so the
// faces of a box shade distinctly instead of being smoothed into a blob).
function triangleGeometry(list) {
  const points = list.points || [];
  let indices = list.indices || [];
  if (indices.length === 0) indices = points.map((_, i) => i); // no indices: points are consecutive triangles
  const count = indices.length - (indices.length % 3);
  const positions = new Float32Array(count * 3);
  let n = 0;
  for (let t = 0; t < count; t += 3) {
    const tri = [indices[t], indices[t + 1], indices[t + 2]].map((i) => points[i]);
    if (tri.some((p) => !p || ![p.x, p.y, p.z].every(Number.isFinite))) continue; // a broken triangle is skipped
    for (const p of tri) {
      positions[n++] = p.x;
      positions[n++] = p.y;
      positions[n++] = p.z;
    }
  }
  if (n === 0) return null;
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(positions.subarray(0, n), 3));
  geometry.computeVertexNormals();
  geometry.computeBoundingBox();
  return geometry;
}
