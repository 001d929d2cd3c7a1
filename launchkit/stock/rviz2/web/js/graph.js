// The node graph panel (rqt_graph): nodes as ellipses, topics, services and actions as boxes,
// an arrow from each publisher to its topic and from the topic to each subscriber. Services are
// drawn client -> service -> server (who calls whom); an action, its five hidden topics and
// services taken together, server -> action -> client (where its feedback and status go), as
// rqt_graph draws it. Namespaces are drawn as boxes around their members. The server sends the
// graph while this panel is open (graph_view.py).
import { SvgGraph } from "./svggraph.js";

const DEBUG_TOPICS = new Set(["/rosout", "/parameter_events"]);
const PARAMETER_SERVICES = new Set([
  "describe_parameters", "get_parameter_types", "get_parameters", "list_parameters",
  "set_parameters", "set_parameters_atomically", "get_type_description",
]);

// ros2cli's rule: a name with any part starting with "_" is hidden.
export function isHidden(name) {
  return name.split("/").some((part) => part.startsWith("_"));
}

function namespaceOf(name) {
  const cut = name.lastIndexOf("/");
  return cut > 0 ? name.slice(0, cut) : "/";
}

function isDebug(name, kind, viewer) {
  if (kind === "node") return name === viewer;
  if (kind === "topic") return DEBUG_TOPICS.has(name);
  if (kind === "service") return PARAMETER_SERVICES.has(name.slice(name.lastIndexOf("/") + 1));
  return false;
}

const OPTIONS = [
  // [key, label, default, title]
  ["topics", "Topics", true, "draw topics as boxes (off: one arrow per topic from node to node)"],
  ["services", "Services", false, "draw services"],
  ["actions", "Actions", true, "draw actions"],
  ["groupNamespaces", "Group namespaces", true, "a box around each namespace"],
  ["groupActions", "Group actions", true, "an action as one box (off: its topics and services)"],
  ["hideDebug", "Hide debug", true, "hide /rosout, /parameter_events, parameter services and the viewer itself"],
  ["hideHidden", "Hide hidden", true, "hide names with a part starting with _"],
  ["hideLeaves", "Hide leaf topics", false, "hide topics with publishers but no subscribers, or the reverse"],
];

export class GraphPanel {
  constructor(ctx, root) {
    this.ctx = ctx;
    this.model = null;
    this.options = Object.fromEntries(OPTIONS.map(([key, , value]) => [key, value]));
    this.filter = "";
    this.drawn = { nodes: [], edges: [] };
    this.open = false;
    const bar = document.createElement("div");
    bar.className = "panel-bar";
    for (const [key, label, value, title] of OPTIONS) {
      const box = Object.assign(document.createElement("input"), { type: "checkbox", checked: value });
      box.dataset.option = key;
      box.addEventListener("change", () => { this.options[key] = box.checked; this.render(); });
      const wrap = document.createElement("label");
      wrap.title = title;
      wrap.append(box, ` ${label}`);
      bar.append(wrap);
    }
    const filter = Object.assign(document.createElement("input"), { type: "search", placeholder: "filter names", id: "graph-filter" });
    filter.addEventListener("input", () => { this.filter = filter.value.trim(); this.render(); });
    const fit = Object.assign(document.createElement("button"), { textContent: "Fit", title: "show the whole graph (or double-click it)" });
    fit.addEventListener("click", () => this.picture.fit());
    bar.append(filter, fit);
    this.summary = Object.assign(document.createElement("span"), { className: "muted", id: "graph-summary" });
    bar.append(this.summary);
    const svg = document.createElementNS("http://www.w3.org/2000/svg", "svg");
    svg.id = "graph-svg";
    svg.classList.add("graph-canvas");
    root.append(bar, svg);
    this.picture = new SvgGraph(svg, "LR");
    ctx.conn.on("graph", (message) => { this.model = message.graph; if (this.open) this.render(); });
  }

  show() {
    this.open = true;
    this.ctx.conn.watchGraph(true);
    this.render();
  }

  hide() {
    this.open = false;
    this.ctx.conn.watchGraph(false);
  }

  // What to draw, from the model and the options.
  build() {
    const o = this.options;
    const model = this.model;
    const viewer = model.viewer;
    const keep = (name, kind) =>
      !(o.hideHidden && isHidden(name)) && !(o.hideDebug && isDebug(name, kind, viewer));
    const nodes = model.nodes.map((n) => n.name).filter((n) => keep(n, "node"));
    const nodeSet = new Set(nodes);
    const graph = { nodes: [], edges: [], clusters: [] };
    const namespaces = new Set();
    const addNode = (id, label, shape, kind, title) => {
      graph.nodes.push({ id, label, shape, kind, title, namespace: namespaceOf(label) });
    };
    for (const name of nodes) addNode(`n:${name}`, name, "ellipse", "node", `node ${name}`);

    const entities = [];
    if (o.topics) {
      for (const t of model.topics) if (!(o.groupActions && o.actions && t.action)) entities.push({ kind: "topic", id: `t:${t.name}`, name: t.name, type: t.types.join(", "), from: t.publishers, to: t.subscribers });
    }
    if (o.services) {
      for (const s of model.services) if (!(o.groupActions && o.actions && s.action)) entities.push({ kind: "service", id: `s:${s.name}`, name: s.name, type: s.types.join(", "), from: s.clients, to: s.servers });
    }
    if (o.actions && o.groupActions) {
      for (const a of model.actions) entities.push({ kind: "action", id: `a:${a.name}`, name: a.name, type: a.types.join(", "), from: a.servers, to: a.clients });
    }
    const filter = this.filter.toLowerCase();
    for (const e of entities) {
      if (!keep(e.name, e.kind)) continue;
      const from = e.from.filter((n) => nodeSet.has(n));
      const to = e.to.filter((n) => nodeSet.has(n));
      if (!from.length && !to.length) continue;
      if (e.kind === "topic" && o.hideLeaves && (!from.length || !to.length)) continue;
      if (filter && !e.name.toLowerCase().includes(filter) && ![...from, ...to].some((n) => n.toLowerCase().includes(filter))) continue;
      if (!o.topics && e.kind === "topic") continue;
      addNode(e.id, e.name, "box", e.kind, `${e.kind} ${e.name} [${e.type}]`);
      for (const n of from) graph.edges.push({ from: `n:${n}`, to: e.id, kind: e.kind });
      for (const n of to) graph.edges.push({ from: e.id, to: `n:${n}`, kind: e.kind });
    }
    if (!o.topics) {
      // rqt_graph's "Nodes only": one labelled arrow per topic between publisher and subscriber
      for (const t of model.topics) {
        if (!keep(t.name, "topic") || (o.groupActions && t.action)) continue;
        for (const p of t.publishers) for (const s of t.subscribers) {
          if (nodeSet.has(p) && nodeSet.has(s) && p !== s) graph.edges.push({ from: `n:${p}`, to: `n:${s}`, label: t.name, kind: "topic" });
        }
      }
    }
    // a node drawn only when it is not filtered out, or when something it talks to is shown
    if (filter) {
      const linked = new Set(graph.edges.flatMap((e) => [e.from, e.to]));
      graph.nodes = graph.nodes.filter((n) => n.kind !== "node" || linked.has(n.id) || n.label.toLowerCase().includes(filter));
    }
    if (o.groupNamespaces) {
      for (const node of graph.nodes) {
        if (node.namespace === "/") continue;
        node.parent = `ns:${node.namespace}`;
        let ns = node.namespace;
        while (ns !== "/" && !namespaces.has(ns)) {
          namespaces.add(ns);
          ns = namespaceOf(ns);
        }
      }
      for (const ns of [...namespaces].sort()) {
        const parent = namespaceOf(ns);
        graph.clusters.push({ id: `ns:${ns}`, label: ns, parent: parent === "/" ? null : `ns:${parent}` });
      }
    }
    return graph;
  }

  render() {
    if (!this.open) return;
    if (!this.model) {
      this.summary.textContent = "waiting for the graph…";
      return;
    }
    const graph = this.build();
    this.picture.draw(graph);
    this.drawn = {
      nodes: graph.nodes.map((n) => ({ id: n.id, label: n.label, kind: n.kind, parent: n.parent || null })),
      edges: graph.edges.map((e) => [e.from, e.to, e.label || null]),
      clusters: graph.clusters.map((c) => c.id),
    };
    const count = (kind) => graph.nodes.filter((n) => n.kind === kind).length;
    this.summary.textContent = `${count("node")} nodes · ${count("topic")} topics · ${count("service")} services · ${count("action")} actions`;
  }
}
