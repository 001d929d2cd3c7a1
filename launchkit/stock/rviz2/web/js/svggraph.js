// A directed graph laid out by dagre and drawn as SVG: the node graph's and the TF tree's
// picture. Boxes and ellipses with labels, clusters (namespaces) around their members, edges as
// arrows with optional labels; the wheel zooms and a drag pans. Every drawn element carries its
// id in data attributes (g.gnode[data-id], path.gedge[data-from][data-to]), so what is drawn can
// be read back from the DOM.
import dagre from "dagre";

const SVG = "http://www.w3.org/2000/svg";
const FONT = "12px system-ui, sans-serif";
const PAD_X = 12;
const HEIGHT = 26;

let measureContext = null;
function textWidth(text) {
  measureContext ??= document.createElement("canvas").getContext("2d");
  measureContext.font = FONT;
  return measureContext.measureText(text).width;
}

function element(tag, attributes = {}, parent = null) {
  const node = document.createElementNS(SVG, tag);
  for (const [key, value] of Object.entries(attributes)) node.setAttribute(key, value);
  if (parent) parent.append(node);
  return node;
}

export class SvgGraph {
  // `svg` is an <svg> element that the graph fills; `rankdir` is dagre's ("LR", "TB").
  constructor(svg, rankdir = "LR") {
    this.svg = svg;
    this.rankdir = rankdir;
    this.view = null; // [x, y, width, height] of the viewBox
    this.bounds = null;
    this.userMoved = false;
    this.installNavigation();
  }

  // Draw `graph` = {nodes: [{id, label, shape: "box"|"ellipse", kind, parent, title}],
  // clusters: [{id, label, parent}], edges: [{from, to, label, kind}]}.
  draw(graph) {
    const layout = new dagre.graphlib.Graph({ compound: true, multigraph: true });
    layout.setGraph({ rankdir: this.rankdir, nodesep: 18, ranksep: 46, edgesep: 10, marginx: 12, marginy: 12 });
    layout.setDefaultEdgeLabel(() => ({}));
    for (const cluster of graph.clusters || []) layout.setNode(cluster.id, { label: cluster.label, clusterLabelPos: "top" });
    for (const cluster of graph.clusters || []) if (cluster.parent) layout.setParent(cluster.id, cluster.parent);
    for (const node of graph.nodes) {
      const width = textWidth(node.label) + 2 * PAD_X + (node.shape === "ellipse" ? 18 : 0);
      layout.setNode(node.id, { width, height: HEIGHT });
      if (node.parent) layout.setParent(node.id, node.parent);
    }
    graph.edges.forEach((edge, index) => {
      const label = edge.label ? { label: edge.label, width: textWidth(edge.label) + 6, height: 14, labelpos: "c" } : {};
      layout.setEdge(edge.from, edge.to, label, `e${index}`);
    });
    dagre.layout(layout);

    this.svg.replaceChildren();
    const defs = element("defs", {}, this.svg);
    const marker = element("marker", { id: `${this.svg.id}-arrow`, viewBox: "0 0 10 10", refX: 9, refY: 5, markerWidth: 7, markerHeight: 7, orient: "auto-start-reverse" }, defs);
    element("path", { d: "M0,0 L10,5 L0,10 z", class: "garrowhead" }, marker);
    const root = element("g", { class: "groot" }, this.svg);

    for (const cluster of graph.clusters || []) {
      const box = layout.node(cluster.id);
      if (!box || !Number.isFinite(box.x)) continue;
      const group = element("g", { class: "gcluster", "data-id": cluster.id }, root);
      element("rect", { x: box.x - box.width / 2, y: box.y - box.height / 2, width: box.width, height: box.height, rx: 6 }, group);
      element("text", { x: box.x - box.width / 2 + 6, y: box.y - box.height / 2 + 13 }, group).textContent = cluster.label;
    }
    graph.edges.forEach((edge, index) => {
      const route = layout.edge({ v: edge.from, w: edge.to, name: `e${index}` });
      if (!route) return;
      const d = route.points.map((p, i) => `${i ? "L" : "M"}${p.x.toFixed(1)},${p.y.toFixed(1)}`).join(" ");
      const path = element("path", { d, class: `gedge ${edge.kind || ""}`, "data-from": edge.from, "data-to": edge.to, "marker-end": `url(#${this.svg.id}-arrow)` }, root);
      if (edge.label) {
        path.setAttribute("data-label", edge.label);
        element("text", { x: route.x, y: route.y + 4, class: "gedgelabel", "text-anchor": "middle", "data-from": edge.from, "data-to": edge.to }, root).textContent = edge.label;
      }
    });
    for (const node of graph.nodes) {
      const box = layout.node(node.id);
      const group = element("g", { class: `gnode ${node.kind || ""}`, "data-id": node.id, transform: `translate(${box.x},${box.y})` }, root);
      if (node.title) element("title", {}, group).textContent = node.title;
      if (node.shape === "ellipse") element("ellipse", { rx: box.width / 2, ry: box.height / 2 }, group);
      else element("rect", { x: -box.width / 2, y: -box.height / 2, width: box.width, height: box.height, rx: 3 }, group);
      element("text", { y: 4, "text-anchor": "middle" }, group).textContent = node.label;
    }
    const size = layout.graph();
    this.bounds = [0, 0, Math.max(size.width || 0, 10), Math.max(size.height || 0, 10)];
    if (!this.userMoved || !this.view) this.fit();
    else this.apply();
    return layout;
  }

  // Show the whole graph.
  // Show the whole graph, at its natural size when it fits (a small graph is not blown up).
  fit() {
    this.userMoved = false;
    const [x, y, w, h] = this.bounds || [0, 0, 100, 100];
    const rect = this.svg.getBoundingClientRect();
    const width = Math.max(w, rect.width || 0);
    const height = Math.max(h, rect.height || 0);
    this.view = [x - (width - w) / 2, y - (height - h) / 2, width, height];
    this.apply();
  }

  apply() {
    if (this.view) this.svg.setAttribute("viewBox", this.view.map((v) => v.toFixed(1)).join(" "));
  }

  installNavigation() {
    this.svg.addEventListener("wheel", (event) => {
      if (!this.view) return;
      event.preventDefault();
      const factor = Math.exp(event.deltaY * 0.0015);
      const rect = this.svg.getBoundingClientRect();
      const fx = (event.clientX - rect.left) / Math.max(rect.width, 1);
      const fy = (event.clientY - rect.top) / Math.max(rect.height, 1);
      const [x, y, w, h] = this.view;
      const nw = w * factor;
      const nh = h * factor;
      this.view = [x + (w - nw) * fx, y + (h - nh) * fy, nw, nh];
      this.userMoved = true;
      this.apply();
    }, { passive: false });
    let drag = null;
    this.svg.addEventListener("pointerdown", (event) => {
      if (!this.view || event.button !== 0) return;
      drag = { x: event.clientX, y: event.clientY, view: [...this.view] };
      this.svg.setPointerCapture(event.pointerId);
    });
    this.svg.addEventListener("pointermove", (event) => {
      if (!drag) return;
      const rect = this.svg.getBoundingClientRect();
      // the viewBox keeps its aspect inside the element: one scale for both axes
      const scale = Math.max(drag.view[2] / Math.max(rect.width, 1), drag.view[3] / Math.max(rect.height, 1));
      this.view = [drag.view[0] - (event.clientX - drag.x) * scale, drag.view[1] - (event.clientY - drag.y) * scale, drag.view[2], drag.view[3]];
      this.userMoved = true;
      this.apply();
    });
    const end = () => { drag = null; };
    this.svg.addEventListener("pointerup", end);
    this.svg.addEventListener("pointercancel", end);
    this.svg.addEventListener("dblclick", () => this.fit());
  }
}
