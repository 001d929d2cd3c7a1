// The transform tree from /tf and /tf_static: the latest transform of every frame to its parent,
// and the pose of any frame in any other frame of the same tree.
import * as THREE from "three";

const MAX_DEPTH = 100;
const TOLERANCE = 1e-4; // metres, and about radians: far below a pixel at any sensible zoom

export class TfTree {
  constructor() {
    this.frames = new Map(); // child -> {parent, matrix}
    this.version = 0;
  }

  clear() {
    this.frames.clear();
    this.version += 1;
  }

  // Store a transform; whether it changed visibly. A robot standing still republishes the same
  // transforms, or ones that creep by micrometres (the simulator's wheels settle): those are kept
  // back until they add up to more than TOLERANCE, so the view is not drawn again for nothing.
  set(parent, child, t, q) {
    if (!parent || !child || parent === child) return false;
    const matrix = new THREE.Matrix4().compose(
      new THREE.Vector3(t[0] ?? 0, t[1] ?? 0, t[2] ?? 0),
      new THREE.Quaternion(q[0] ?? 0, q[1] ?? 0, q[2] ?? 0, q[3] ?? 1).normalize(),
      new THREE.Vector3(1, 1, 1),
    );
    const old = this.frames.get(child);
    if (old && old.parent === parent && old.matrix.elements.every((v, i) => Math.abs(v - matrix.elements[i]) < TOLERANCE)) {
      return false;
    }
    this.frames.set(child, { parent, matrix });
    this.version += 1;
    return true;
  }

  has(frame) {
    if (this.frames.has(frame)) return true;
    for (const entry of this.frames.values()) if (entry.parent === frame) return true;
    return false;
  }

  names() {
    const names = new Set(this.frames.keys());
    for (const entry of this.frames.values()) names.add(entry.parent);
    return [...names].sort();
  }

  // The root of `frame`'s tree and the pose of `frame` in it.
  toRoot(frame) {
    const matrix = new THREE.Matrix4();
    let current = frame;
    for (let depth = 0; depth < MAX_DEPTH; depth++) {
      const entry = this.frames.get(current);
      if (!entry) return { root: current, matrix };
      matrix.premultiply(entry.matrix);
      current = entry.parent;
    }
    return null; // a loop in the tree
  }

  rootOf(frame) {
    const found = this.toRoot(frame);
    return found ? found.root : null;
  }

  // The pose of `source` in `target` (a Matrix4), or null when they are not connected.
  lookup(target, source) {
    const a = this.toRoot(source);
    const b = this.toRoot(target);
    if (!a || !b || a.root !== b.root) return null;
    return b.matrix.clone().invert().multiply(a.matrix);
  }
}
