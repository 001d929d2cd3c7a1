// The plot panel (rqt_plot): numeric fields of any topic against time, several series on one
// chart (uPlot). A series is a topic and a field path, written as rqt_plot takes them:
// /turtle1/pose/x, /odom/twist/twist/linear/x, /joint_states/position[0]. Its topic is
// subscribed in the "fields" form (every field, see convert.py) while the series is plotted;
// the time is when the viewer's server received the message. The chart follows the last
// seconds; Pause freezes it; drag across it to zoom in on a span, double-click to follow again.
import uPlot from "uplot";

const COLORS = ["#4fc3f7", "#ffb74d", "#81c784", "#e57373", "#ba68c8", "#fff176", "#4db6ac", "#f06292"];
const KEEP_SECONDS = 600; // samples older than this (behind the newest) are dropped
const NUMERIC = new Set(["bool", "byte", "char", "int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64", "float32", "float64"]);

// "position[0]/x" -> ["position", 0, "x"]
export function parsePath(text) {
  const parts = [];
  for (const piece of text.split("/").filter(Boolean)) {
    const match = /^([^[\]]*)((?:\[\d+\])*)$/.exec(piece);
    if (!match) return null;
    if (match[1] !== "") parts.push(/^\d+$/.test(match[1]) ? Number(match[1]) : match[1]);
    for (const index of match[2].matchAll(/\[(\d+)\]/g)) parts.push(Number(index[1]));
  }
  return parts;
}

function pick(value, path) {
  for (const key of path) {
    if (value === null || value === undefined) return null;
    value = value[key];
  }
  if (typeof value === "boolean") return value ? 1 : 0;
  return typeof value === "number" && Number.isFinite(value) ? value : null;
}

// The numeric field paths of a message schema (schema.py), sequences with their first element.
function numericPaths(fields, prefix = "") {
  const paths = [];
  for (const field of fields) {
    const name = `${prefix}/${field.name}`;
    const walk = (spec, path) => {
      if (spec.kind === "base") {
        if (NUMERIC.has(spec.type)) paths.push(path);
      } else if (spec.kind === "message") {
        paths.push(...numericPaths(spec.fields, path));
      } else {
        walk(spec.item, `${path}[0]`);
      }
    };
    walk(field, name);
  }
  return paths;
}

export class PlotPanel {
  constructor(ctx, root, topicsOf) {
    this.ctx = ctx;
    this.topicsOf = topicsOf; // () => [{name, type}] of the graph
    this.series = []; // {label, topic, path, color, times: [], values: []}
    this.paused = false;
    this.following = true;
    this.windowSeconds = 30;
    this.open = false;
    this.chart = null;
    this.dirty = false;

    const bar = document.createElement("div");
    bar.className = "panel-bar";
    this.input = Object.assign(document.createElement("input"), { id: "plot-field", placeholder: "/topic/field, e.g. /odom/twist/twist/linear/x", size: 36 });
    this.input.setAttribute("list", "plot-fields");
    this.choices = Object.assign(document.createElement("datalist"), { id: "plot-fields" });
    this.input.addEventListener("input", () => this.suggest());
    this.input.addEventListener("keydown", (event) => { if (event.key === "Enter") this.addFromInput(); });
    const add = Object.assign(document.createElement("button"), { id: "plot-add", textContent: "+", title: "plot this field" });
    add.addEventListener("click", () => this.addFromInput());
    this.pauseButton = Object.assign(document.createElement("button"), { id: "plot-pause", textContent: "Pause" });
    this.pauseButton.addEventListener("click", () => this.setPaused(!this.paused));
    const span = Object.assign(document.createElement("select"), { id: "plot-window", title: "seconds shown while following" });
    for (const seconds of [10, 30, 60, 300]) span.append(new Option(`${seconds} s`, String(seconds)));
    span.value = String(this.windowSeconds);
    span.addEventListener("change", () => { this.windowSeconds = Number(span.value); this.follow(); });
    const clear = Object.assign(document.createElement("button"), { id: "plot-clear", textContent: "Clear" });
    clear.addEventListener("click", () => { for (const s of this.series) { s.times = []; s.values = []; } this.redraw(); });
    this.message = Object.assign(document.createElement("span"), { className: "muted", id: "plot-message" });
    bar.append(this.input, this.choices, add, this.pauseButton, span, clear, this.message);
    this.legend = Object.assign(document.createElement("div"), { id: "plot-series", className: "panel-bar" });
    this.area = Object.assign(document.createElement("div"), { id: "plot-area", className: "plot-area" });
    root.append(bar, this.legend, this.area);
    new ResizeObserver(() => this.resize()).observe(this.area);
    ctx.conn.on("fields", (message) => this.receive(message));
  }

  show() {
    this.open = true;
    for (const s of this.series) this.ctx.conn.want(s.topic, "fields");
    this.build();
  }

  hide() {
    this.open = false;
    for (const s of this.series) this.ctx.conn.unwant(s.topic, "fields");
  }

  // The topic a field path starts with: the longest topic name of the graph that prefixes it.
  split(text) {
    const name = text.trim();
    let best = null;
    for (const topic of this.topicsOf()) {
      if ((name === topic.name || name.startsWith(`${topic.name}/`) || name.startsWith(`${topic.name}[`)) && (!best || topic.name.length > best.name.length)) best = topic;
    }
    if (!best) return null;
    const path = parsePath(name.slice(best.name.length));
    return path && path.length ? { topic: best, path } : null;
  }

  async suggest() {
    const text = this.input.value.trim();
    const topic = this.topicsOf().filter((t) => text.startsWith(t.name)).sort((a, b) => b.name.length - a.name.length)[0];
    if (!topic || this.suggested === topic.name) return;
    this.suggested = topic.name;
    const schema = await this.ctx.conn.schema(topic.type);
    if (!schema.message) return;
    this.choices.replaceChildren(...numericPaths(schema.message.fields, topic.name).map((p) => new Option(p)));
  }

  addFromInput() {
    const text = this.input.value.trim();
    if (!text) return;
    if (!this.add(text)) return;
    this.input.value = "";
  }

  // Plot `text` (/topic/field...); whether it names a topic of the graph and a field path.
  add(text) {
    const found = this.split(text);
    if (!found) {
      this.message.textContent = `no topic of the graph starts ${text}`;
      return false;
    }
    if (this.series.some((s) => s.label === text)) return true;
    const color = COLORS[this.series.length % COLORS.length];
    const series = { label: text, topic: found.topic.name, path: found.path, color, times: [], values: [], misses: 0 };
    this.series.push(series);
    if (this.open) this.ctx.conn.want(series.topic, "fields");
    this.message.textContent = "";
    this.build();
    return true;
  }

  remove(label) {
    const index = this.series.findIndex((s) => s.label === label);
    if (index < 0) return;
    const [series] = this.series.splice(index, 1);
    if (this.open) this.ctx.conn.unwant(series.topic, "fields");
    this.build();
  }

  receive(message) {
    if (this.paused) return;
    for (const s of this.series) {
      if (s.topic !== message.topic) continue;
      const value = pick(message.msg, s.path);
      if (value === null) {
        s.misses += 1;
        continue;
      }
      s.times.push(message.t);
      s.values.push(value);
      const oldest = message.t - KEEP_SECONDS;
      let drop = 0;
      while (drop < s.times.length && s.times[drop] < oldest) drop += 1;
      if (drop) { s.times.splice(0, drop); s.values.splice(0, drop); }
    }
    this.scheduleRedraw();
  }

  setPaused(paused) {
    this.paused = paused;
    this.pauseButton.textContent = paused ? "Resume" : "Pause";
    this.pauseButton.classList.toggle("active", paused);
  }

  follow() {
    this.following = true;
    this.redraw();
  }

  // The series joined on one time axis (uPlot wants aligned columns): null where a series has no
  // sample at a time.
  aligned() {
    const times = [...new Set(this.series.flatMap((s) => s.times))].sort((a, b) => a - b);
    const index = new Map(times.map((t, i) => [t, i]));
    const columns = this.series.map((s) => {
      const column = new Array(times.length).fill(null);
      s.times.forEach((t, i) => { column[index.get(t)] = s.values[i]; });
      return column;
    });
    return [times, ...columns];
  }

  build() {
    this.legend.replaceChildren(...this.series.map((s) => {
      const chip = document.createElement("span");
      chip.className = "series-chip";
      chip.dataset.series = s.label;
      chip.style.borderColor = s.color;
      const remove = Object.assign(document.createElement("button"), { textContent: "−", title: `stop plotting ${s.label}` });
      remove.addEventListener("click", () => this.remove(s.label));
      chip.append(`${s.label} `, remove);
      return chip;
    }));
    if (this.chart) this.chart.destroy();
    this.chart = null;
    if (!this.open) return;
    const options = {
      width: Math.max(this.area.clientWidth, 100),
      height: Math.max(this.area.clientHeight - 40, 100),
      scales: { x: { time: true } },
      legend: { show: true, live: true },
      cursor: { drag: { x: true, y: false } },
      axes: [
        { stroke: "#bbb", grid: { stroke: "#3a3b40" }, ticks: { stroke: "#555" } },
        { stroke: "#bbb", grid: { stroke: "#3a3b40" }, ticks: { stroke: "#555" } },
      ],
      series: [{}, ...this.series.map((s) => ({ label: s.label, stroke: s.color, width: 1.5, spanGaps: true, points: { show: false } }))],
      hooks: {
        setSelect: [(u) => {
          // a drag across the chart zooms into that span (uPlot does it): stop following
          if (u.select.width > 0) this.following = false;
        }],
      },
    };
    this.chart = new uPlot(options, this.aligned(), this.area);
    this.chart.over.addEventListener("dblclick", () => this.follow());
    this.redraw();
  }

  scheduleRedraw() {
    if (this.dirty || !this.open) return;
    this.dirty = true;
    requestAnimationFrame(() => { this.dirty = false; this.redraw(); });
  }

  redraw() {
    if (!this.chart) return;
    const data = this.aligned();
    // following: the ranges from the data, then the x window on the newest samples (uPlot ranges
    // y over what x shows); zoomed in: the span chosen stays
    this.chart.setData(data, this.following);
    const times = data[0];
    if (this.following && times.length) {
      const newest = times[times.length - 1];
      this.chart.setScale("x", { min: newest - this.windowSeconds, max: newest });
    }
  }

  resize() {
    if (this.chart) this.chart.setSize({ width: Math.max(this.area.clientWidth, 100), height: Math.max(this.area.clientHeight - 40, 100) });
  }

  // For tests: each series' samples, and the x range shown.
  state() {
    return {
      series: this.series.map((s) => ({ label: s.label, topic: s.topic, times: [...s.times], values: [...s.values], misses: s.misses })),
      following: this.following,
      paused: this.paused,
      x: this.chart ? { min: this.chart.scales.x.min, max: this.chart.scales.x.max } : null,
    };
  }
}
