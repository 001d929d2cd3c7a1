// The TF tree panel (view_frames): every frame with its parent, how often its transform arrives
// (the average over the last seconds, as view_frames reports per frame; "static" for
// /tf_static), how long ago the last one came, and the tree drawn. The page receives /tf and
// /tf_static whatever panel is shown (the 3D view needs them), so this panel subscribes nothing.
// "Save SVG" downloads the picture.
import { SvgGraph } from "./svggraph.js";

const WINDOW_S = 5;

export class TfTreePanel {
  constructor(ctx, root) {
    this.ctx = ctx;
    this.frames = new Map(); // child -> {parent, static, arrivals: [seconds], last}
    this.open = false;
    this.drawnVersion = -1;
    this.version = 0;

    const bar = document.createElement("div");
    bar.className = "panel-bar";
    const save = Object.assign(document.createElement("button"), { id: "tf-save", textContent: "Save SVG", title: "download the tree as an SVG picture" });
    save.addEventListener("click", () => this.save());
    const fit = Object.assign(document.createElement("button"), { textContent: "Fit" });
    fit.addEventListener("click", () => this.picture.fit());
    this.summary = Object.assign(document.createElement("span"), { className: "muted", id: "tf-summary" });
    bar.append(save, fit, this.summary);
    const columns = document.createElement("div");
    columns.className = "side-and-main";
    const scroller = document.createElement("div");
    scroller.className = "table-scroll frame-list";
    this.table = Object.assign(document.createElement("table"), { id: "tf-table" });
    this.table.createTHead().insertRow().append(...["frame", "parent", "rate (Hz)", "age (s)"].map((t) => Object.assign(document.createElement("th"), { textContent: t })));
    this.body = this.table.createTBody();
    scroller.append(this.table);
    const svg = document.createElementNS("http://www.w3.org/2000/svg", "svg");
    svg.id = "tf-svg";
    svg.classList.add("graph-canvas");
    columns.append(scroller, svg);
    root.append(bar, columns);
    this.picture = new SvgGraph(svg, "LR");
    setInterval(() => { if (this.open) this.render(); }, 1000);
  }

  show() {
    this.open = true;
    this.render();
  }

  hide() { this.open = false; }

  clear() {
    this.frames.clear();
    this.version += 1;
  }

  // The transforms of one /tf or /tf_static message (compact form: {parent, child, t, q}).
  observe(topic, transforms) {
    const now = performance.now() / 1000;
    for (const t of transforms) {
      if (!t.parent || !t.child) continue;
      let frame = this.frames.get(t.child);
      if (!frame) {
        frame = { arrivals: [] };
        this.frames.set(t.child, frame);
      }
      if (frame.parent !== t.parent) this.version += 1;
      frame.parent = t.parent;
      frame.static = topic.endsWith("tf_static");
      frame.last = now;
      frame.arrivals.push(now);
      while (frame.arrivals.length && frame.arrivals[0] < now - WINDOW_S) frame.arrivals.shift();
    }
  }

  rate(frame, now) {
    if (frame.static) return "static";
    const recent = frame.arrivals.filter((t) => t >= now - WINDOW_S);
    if (recent.length < 2) return "0.0";
    return ((recent.length - 1) / Math.max(recent[recent.length - 1] - recent[0], 1e-3)).toFixed(1);
  }

  // Frames with their parents, rates and ages, sorted by name.
  rows() {
    const now = performance.now() / 1000;
    return [...this.frames.entries()].sort(([a], [b]) => a.localeCompare(b)).map(([child, f]) => ({
      frame: child, parent: f.parent, rate: this.rate(f, now), age: (now - f.last).toFixed(1),
    }));
  }

  render() {
    const rows = this.rows();
    this.body.replaceChildren(...rows.map((r) => {
      const row = document.createElement("tr");
      row.dataset.frame = r.frame;
      row.dataset.parent = r.parent;
      for (const text of [r.frame, r.parent, r.rate, r.age]) row.insertCell().textContent = text;
      return row;
    }));
    const roots = new Set(rows.map((r) => r.parent).filter((p) => !this.frames.has(p)));
    this.summary.textContent = `${rows.length + roots.size} frames · root${roots.size === 1 ? "" : "s"} ${[...roots].join(", ")}`;
    const label = (r) => (r.rate === "static" ? "static" : `${r.rate} Hz`);
    if (this.drawnVersion === this.version) {
      // the same tree: only the rates on its arrows change (no new layout each second)
      for (const r of rows) {
        const text = this.picture.svg.querySelector(`text.gedgelabel[data-to="${CSS.escape(r.frame)}"]`);
        if (text) text.textContent = label(r);
      }
      return;
    }
    this.drawnVersion = this.version;
    const names = new Set([...roots, ...rows.map((r) => r.frame)]);
    this.picture.draw({
      nodes: [...names].map((name) => ({ id: name, label: name, shape: "ellipse", kind: roots.has(name) ? "root" : "frame" })),
      edges: rows.map((r) => ({ from: r.parent, to: r.frame, label: label(r), kind: "tf" })),
    });
  }

  save() {
    const svg = this.picture.svg.cloneNode(true);
    svg.setAttribute("xmlns", "http://www.w3.org/2000/svg");
    const style = document.createElementNS("http://www.w3.org/2000/svg", "style");
    style.textContent = "text{font:12px sans-serif;fill:#000}ellipse,rect{fill:#fff;stroke:#000}path.gedge{fill:none;stroke:#000}.garrowhead{fill:#000}.gedgelabel{font-size:10px}";
    svg.prepend(style);
    const blob = new Blob([new XMLSerializer().serializeToString(svg)], { type: "image/svg+xml" });
    const link = Object.assign(document.createElement("a"), { href: URL.createObjectURL(blob), download: "frames.svg" });
    link.click();
    URL.revokeObjectURL(link.href);
  }
}
