// The displays of an rviz config, drawn in the 3D view: Grid, RobotModel, TF, LaserScan and
// Odometry (Image and Camera displays go to the image panel, see image.js). Each one subscribes
// to its topics only while it is enabled, and poses what it draws from TF in the fixed frame.
import * as THREE from "three";
import { buildRobot, parseUrdf } from "./urdf.js";

// rviz's "R; G; B" colour text as a THREE.Color (`fallback`: [r, g, b] 0-255).
export function rvizColour(text, fallback) {
  const parts = String(text ?? "").split(";").map((p) => Number(p.trim()));
  const rgb = parts.length === 3 && parts.every((p) => p >= 0 && p <= 255) ? parts : fallback;
  return new THREE.Color().setRGB(rgb[0] / 255, rgb[1] / 255, rgb[2] / 255, THREE.SRGBColorSpace);
}

function option(spec, name, fallback) {
  const value = Number(spec.options?.[name]);
  return Number.isFinite(value) && value > 0 ? value : fallback;
}

class Display {
  constructor(ctx, spec) {
    this.ctx = ctx;
    this.spec = spec;
    this.enabled = false;
    this.root = new THREE.Group();
    this.root.visible = false;
    ctx.scene.scene.add(this.root);
  }

  topics() {
    return [];
  }

  setEnabled(on) {
    if (on === this.enabled) return;
    this.enabled = on;
    this.root.visible = on;
    for (const topic of this.topics()) {
      if (on) this.ctx.conn.want(topic);
      else this.ctx.conn.unwant(topic);
    }
    this.ctx.scene.requestRender();
  }

  onMessage() {}
  update() {}
  reset() {}
}

class GridDisplay extends Display {
  constructor(ctx, spec) {
    super(ctx, spec);
    const size = option(spec, "Cell Size", 1);
    const count = Math.round(option(spec, "Plane Cell Count", 10));
    const colour = rvizColour(spec.options?.Color, [160, 160, 164]);
    const grid = new THREE.GridHelper(size * count, count, colour, colour);
    grid.rotation.x = Math.PI / 2; // three's grid lies in x-z; ROS's ground is x-y
    grid.material.transparent = true;
    grid.material.opacity = 0.5;
    this.root.add(grid);
  }
}

class RobotModelDisplay extends Display {
  constructor(ctx, spec) {
    super(ctx, spec);
    this.topic = spec.topic || "/robot_description";
    this.text = null;
    this.links = new Map();
  }

  topics() {
    return [this.topic];
  }

  reset() {
    this.text = null;
  }

  onMessage(topic, type, msg) {
    if (type !== "std_msgs/msg/String" || msg.data === this.text) return;
    this.text = msg.data;
    for (const group of this.links.values()) this.root.remove(group);
    this.links.clear();
    let model;
    try {
      model = parseUrdf(msg.data);
    } catch (error) {
      this.ctx.problem(`RobotModel: ${error.message}`);
      return;
    }
    this.ctx.stats.meshesLoaded = 0;
    this.ctx.stats.meshesFailed = 0;
    const built = buildRobot(model, (pending) => {
      this.ctx.stats.meshesLoaded = pending.loaded;
      this.ctx.stats.meshesFailed = pending.failed;
      this.ctx.scene.requestRender();
    });
    this.links = built.links;
    for (const group of this.links.values()) this.root.add(group);
    this.ctx.stats.robotLinkCount = this.links.size;
    this.ctx.robotChanged(model);
    // draw the new model now: a robot without meshes asks for no later frame, and when its
    // transforms arrived first nothing else will (the view stayed empty)
    this.ctx.scene.requestRender();
  }

  update() {
    let posed = 0;
    const fixed = this.ctx.fixedFrame();
    for (const [name, group] of this.links) {
      const pose = this.ctx.tf.lookup(fixed, name);
      group.visible = pose !== null;
      if (pose) {
        group.matrix.copy(pose);
        group.matrixWorldNeedsUpdate = true;
        posed += 1;
      }
    }
    this.ctx.stats.robotLinks = this.enabled ? posed : 0;
  }
}

class TfDisplay extends Display {
  constructor(ctx, spec) {
    super(ctx, spec);
    this.scale = option(spec, "Marker Scale", 1) * 0.25;
    this.axes = new Map();
  }

  topics() {
    return ["/tf", "/tf_static"];
  }

  reset() {
    for (const axes of this.axes.values()) this.root.remove(axes);
    this.axes.clear();
  }

  update() {
    const fixed = this.ctx.fixedFrame();
    for (const frame of this.ctx.tf.names()) {
      let axes = this.axes.get(frame);
      if (!axes) {
        axes = new THREE.AxesHelper(this.scale);
        axes.matrixAutoUpdate = false;
        this.axes.set(frame, axes);
        this.root.add(axes);
      }
      const pose = this.ctx.tf.lookup(fixed, frame);
      axes.visible = pose !== null;
      if (pose) axes.matrix.copy(pose);
    }
  }
}

class LaserScanDisplay extends Display {
  constructor(ctx, spec) {
    super(ctx, spec);
    this.topic = spec.topic || "/scan";
    this.frame = null;
    this.geometry = new THREE.BufferGeometry();
    const material = new THREE.PointsMaterial({
      color: rvizColour(spec.options?.Color, [255, 64, 64]),
      size: Math.max(option(spec, "Size (m)", 0.04), 0.03),
    });
    this.points = new THREE.Points(this.geometry, material);
    this.points.matrixAutoUpdate = false;
    this.root.add(this.points);
  }

  topics() {
    return [this.topic];
  }

  reset() {
    this.last = null;
  }

  onMessage(topic, type, msg) {
    if (type !== "sensor_msgs/msg/LaserScan") return;
    this.ctx.stats.scanMessages += 1;
    const same = this.last && this.frame === msg.frame && this.last.length === msg.ranges.length && this.last.every((r, i) => r === msg.ranges[i]);
    if (same) return; // the same scan again: nothing to draw
    this.last = msg.ranges;
    const positions = [];
    msg.ranges.forEach((range, i) => {
      if (range === null || range < msg.range_min || range > msg.range_max) return;
      const angle = msg.angle_min + i * msg.angle_increment;
      positions.push(range * Math.cos(angle), range * Math.sin(angle), 0);
    });
    this.geometry.setAttribute("position", new THREE.Float32BufferAttribute(positions, 3));
    this.geometry.computeBoundingSphere();
    this.frame = msg.frame;
    this.ctx.stats.scanPoints = positions.length / 3;
    this.ctx.scene.requestRender();
  }

  update() {
    const pose = this.frame && this.ctx.tf.lookup(this.ctx.fixedFrame(), this.frame);
    this.points.visible = Boolean(pose);
    if (pose) this.points.matrix.copy(pose);
  }
}

const TRAIL = 5000; // odometry positions kept in the trail

class OdometryDisplay extends Display {
  constructor(ctx, spec) {
    super(ctx, spec);
    this.topic = spec.topic || "/odom";
    this.keep = Math.round(option(spec, "Keep", 100));
    this.colour = rvizColour(spec.options?.Color, [255, 25, 0]);
    this.arrows = [];
    this.poses = []; // [{frame, matrix}] of the kept arrows
    this.trail = new Float32Array(TRAIL * 3);
    this.trailLength = 0;
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.BufferAttribute(this.trail, 3));
    geometry.setDrawRange(0, 0);
    this.trailLine = new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: this.colour }));
    this.trailLine.matrixAutoUpdate = false;
    this.root.add(this.trailLine);
  }

  topics() {
    return [this.topic];
  }

  reset() {
    for (const arrow of this.arrows) this.root.remove(arrow);
    this.arrows = [];
    this.poses = [];
    this.trailLength = 0;
    this.trailLine.geometry.setDrawRange(0, 0);
  }

  onMessage(topic, type, msg) {
    if (type !== "nav_msgs/msg/Odometry" || msg.p.some((v) => v === null)) return;
    this.ctx.stats.odomMessages += 1;
    const position = new THREE.Vector3(...msg.p);
    const rotation = new THREE.Quaternion(...msg.q.map((v) => v ?? 0)).normalize();
    const last = this.poses[this.poses.length - 1];
    const moved = !last || last.position.distanceTo(position) > 0.1 || last.rotation.angleTo(rotation) > 0.1;
    if (moved) {
      const arrow = new THREE.ArrowHelper(new THREE.Vector3(1, 0, 0), new THREE.Vector3(), 0.6, this.colour, 0.15, 0.08);
      arrow.matrixAutoUpdate = false;
      this.arrows.push(arrow);
      this.poses.push({ frame: msg.frame, position, rotation });
      this.root.add(arrow);
      while (this.arrows.length > this.keep) {
        this.root.remove(this.arrows.shift());
        this.poses.shift();
      }
    }
    const end = this.trailLength * 3;
    const still = this.trailLength > 0 && Math.hypot(msg.p[0] - this.trail[end - 3], msg.p[1] - this.trail[end - 2], msg.p[2] - this.trail[end - 1]) < 0.005;
    this.frame = msg.frame;
    if (still && !moved) return; // standing still: nothing new to draw
    if (this.trailLength === TRAIL) {
      this.trail.copyWithin(0, 3); // drop the oldest point
      this.trailLength -= 1;
    }
    this.trail.set(msg.p, this.trailLength * 3);
    this.trailLength += 1;
    const geometry = this.trailLine.geometry;
    geometry.setDrawRange(0, this.trailLength);
    geometry.attributes.position.needsUpdate = true;
    geometry.computeBoundingSphere();
    this.ctx.scene.requestRender();
  }

  update() {
    const fixed = this.ctx.fixedFrame();
    this.poses.forEach((pose, i) => {
      const base = this.ctx.tf.lookup(fixed, pose.frame);
      const arrow = this.arrows[i];
      arrow.visible = base !== null;
      if (base) arrow.matrix.copy(base).multiply(new THREE.Matrix4().compose(pose.position, pose.rotation, new THREE.Vector3(1, 1, 1)));
    });
    const base = this.frame && this.ctx.tf.lookup(fixed, this.frame);
    this.trailLine.visible = Boolean(base);
    if (base) this.trailLine.matrix.copy(base);
  }
}

const CLASSES = {
  Grid: GridDisplay,
  RobotModel: RobotModelDisplay,
  TF: TfDisplay,
  LaserScan: LaserScanDisplay,
  Odometry: OdometryDisplay,
};

// The display for a config entry; null for Image/Camera (the image panel) and unknown classes.
export function makeDisplay(ctx, spec) {
  const Class = CLASSES[spec.class];
  return Class ? new Class(ctx, spec) : null;
}

// Display classes that can be added from the topic list, by message type.
export const DISPLAY_FOR_TYPE = {
  "sensor_msgs/msg/LaserScan": "LaserScan",
  "nav_msgs/msg/Odometry": "Odometry",
};
