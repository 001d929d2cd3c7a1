// A URDF robot description as three.js objects: one group per link holding its visuals (box,
// cylinder, sphere, meshes), each group posed by the viewer from TF, as rviz's RobotModel does.
import * as THREE from "three";
import { STLLoader } from "three/addons/loaders/STLLoader.js";
import { OBJLoader } from "three/addons/loaders/OBJLoader.js";
import { ColladaLoader } from "three/addons/loaders/ColladaLoader.js";

const DEFAULT_COLOUR = [0.8, 0.8, 0.8, 1];

function numbers(text, count, fallback) {
  if (!text) return fallback;
  const values = text.trim().split(/\s+/).map(Number);
  return values.length === count && values.every(Number.isFinite) ? values : fallback;
}

function originMatrix(element) {
  const origin = element && [...element.children].find((c) => c.tagName === "origin");
  const xyz = numbers(origin?.getAttribute("xyz"), 3, [0, 0, 0]);
  const rpy = numbers(origin?.getAttribute("rpy"), 3, [0, 0, 0]);
  // URDF's rpy: roll about x, then pitch about y, then yaw about z, in fixed axes
  const rotation = new THREE.Quaternion().setFromEuler(new THREE.Euler(rpy[0], rpy[1], rpy[2], "ZYX"));
  return new THREE.Matrix4().compose(new THREE.Vector3(...xyz), rotation, new THREE.Vector3(1, 1, 1));
}

function child(element, tag) {
  return element ? [...element.children].find((c) => c.tagName === tag) : undefined;
}

// The URL the page fetches a mesh from: package://PKG/x -> asset/package/PKG/x
export function assetUrl(uri) {
  if (uri.startsWith("package://")) return "asset/package/" + uri.slice("package://".length);
  if (uri.startsWith("file://")) return "asset/file/" + uri.slice("file://".length).replace(/^\/+/, "");
  if (uri.startsWith("/")) return "asset/file/" + uri.replace(/^\/+/, "");
  return null;
}

export function parseUrdf(text) {
  const doc = new DOMParser().parseFromString(text, "application/xml");
  const robot = doc.documentElement;
  if (!robot || robot.tagName !== "robot" || doc.querySelector("parsererror")) {
    throw new Error("the robot description is not a URDF");
  }
  const materials = new Map();
  for (const material of [...robot.children].filter((c) => c.tagName === "material")) {
    materials.set(material.getAttribute("name"), material);
  }
  const links = [...robot.children].filter((c) => c.tagName === "link");
  const joints = [...robot.children].filter((c) => c.tagName === "joint").map((joint) => {
    const limit = child(joint, "limit");
    return {
      name: joint.getAttribute("name"),
      type: joint.getAttribute("type"),
      parent: child(joint, "parent")?.getAttribute("link"),
      child: child(joint, "child")?.getAttribute("link"),
      lower: Number(limit?.getAttribute("lower") ?? 0),
      upper: Number(limit?.getAttribute("upper") ?? 0),
      mimic: Boolean(child(joint, "mimic")),
    };
  });
  const children = new Set(joints.map((j) => j.child));
  const root = links.map((l) => l.getAttribute("name")).find((name) => !children.has(name));
  return { name: robot.getAttribute("name"), links, joints, materials, root };
}

function colourOf(visual, materials) {
  let material = child(visual, "material");
  if (material && !child(material, "color") && materials.has(material.getAttribute("name"))) {
    material = materials.get(material.getAttribute("name"));
  }
  const rgba = numbers(child(material, "color")?.getAttribute("rgba"), 4, null);
  return rgba || null;
}

function makeMaterial(rgba) {
  const [r, g, b, a] = rgba || DEFAULT_COLOUR;
  return new THREE.MeshStandardMaterial({
    color: new THREE.Color().setRGB(r, g, b, THREE.SRGBColorSpace),
    transparent: a < 1,
    opacity: a,
    roughness: 0.7,
    metalness: 0.1,
  });
}

function loadMesh(uri, rgba, target, pending) {
  const url = assetUrl(uri);
  if (!url) {
    console.warn(`mesh ${uri}: only package:// and file:// meshes can be shown`);
    return;
  }
  const extension = uri.split(".").pop().toLowerCase();
  const done = (object) => { target.add(object); pending.loaded += 1; pending.onLoad(pending); };
  const failed = (error) => { console.warn(`mesh ${uri}: ${error}`); pending.failed += 1; pending.onLoad(pending); };
  pending.total += 1;
  if (extension === "stl") {
    new STLLoader().load(url, (geometry) => {
      geometry.computeVertexNormals(); // STL files often carry zero or wrong facet normals
      done(new THREE.Mesh(geometry, makeMaterial(rgba)));
    }, undefined, failed);
  } else if (extension === "dae") {
    new ColladaLoader().load(url, (collada) => {
      const scene = collada.scene;
      // three turns Z-up COLLADA into its own Y-up; ROS frames are Z-up, so undo that (and turn
      // Y-up files the other way), as rviz shows them
      scene.rotation.set(scene.rotation.x === 0 ? Math.PI / 2 : 0, 0, 0);
      if (rgba) scene.traverse((o) => { if (o.isMesh) o.material = makeMaterial(rgba); });
      done(scene);
    }, undefined, failed);
  } else if (extension === "obj") {
    new OBJLoader().load(url, (group) => {
      if (rgba) group.traverse((o) => { if (o.isMesh) o.material = makeMaterial(rgba); });
      done(group);
    }, undefined, failed);
  } else {
    failed(`.${extension} meshes are not supported (stl, dae and obj are)`);
  }
}

// The robot's links as groups: {links: Map(name -> Group), pending} (meshes load in the background).
export function buildRobot(model, onLoad) {
  const links = new Map();
  const pending = { total: 0, loaded: 0, failed: 0, onLoad };
  for (const link of model.links) {
    const group = new THREE.Group();
    group.name = link.getAttribute("name");
    group.matrixAutoUpdate = false;
    for (const visual of [...link.children].filter((c) => c.tagName === "visual")) {
      const holder = new THREE.Group();
      holder.matrixAutoUpdate = false;
      holder.matrix.copy(originMatrix(visual));
      const rgba = colourOf(visual, model.materials);
      const geometry = child(visual, "geometry");
      const shape = geometry && [...geometry.children][0];
      if (!shape) continue;
      if (shape.tagName === "box") {
        const size = numbers(shape.getAttribute("size"), 3, [0.1, 0.1, 0.1]);
        holder.add(new THREE.Mesh(new THREE.BoxGeometry(...size), makeMaterial(rgba)));
      } else if (shape.tagName === "cylinder") {
        const radius = Number(shape.getAttribute("radius") || 0.1);
        const length = Number(shape.getAttribute("length") || 0.1);
        const mesh = new THREE.Mesh(new THREE.CylinderGeometry(radius, radius, length, 32), makeMaterial(rgba));
        mesh.rotation.x = Math.PI / 2; // three's cylinders run along y, URDF's along z
        holder.add(mesh);
      } else if (shape.tagName === "sphere") {
        const radius = Number(shape.getAttribute("radius") || 0.1);
        holder.add(new THREE.Mesh(new THREE.SphereGeometry(radius, 32, 16), makeMaterial(rgba)));
      } else if (shape.tagName === "mesh") {
        const scale = numbers(shape.getAttribute("scale"), 3, [1, 1, 1]);
        const scaled = new THREE.Group();
        scaled.scale.set(...scale);
        holder.add(scaled);
        loadMesh(shape.getAttribute("filename") || "", rgba, scaled, pending);
      }
      holder.updateMatrixWorld(true);
      group.add(holder);
    }
    links.set(group.name, group);
  }
  return { links, pending };
}
