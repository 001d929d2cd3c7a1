// The parameters panel (rqt_reconfigure): pick a node, see its parameters with their types,
// values and descriptors (description, read-only, ranges), and change a value in place. It
// talks to the node's own parameter services (~/list_parameters, ~/get_parameters,
// ~/describe_parameters, ~/set_parameters) through the viewer's server, and reads the node's
// values again when /parameter_events says they changed.
import { isHidden } from "./graph.js";

const SRV = "rcl_interfaces/srv/";
// rcl_interfaces/msg/ParameterType
const TYPES = ["not set", "bool", "integer", "double", "string", "byte[]", "bool[]", "integer[]", "double[]", "string[]"];
const FIELD = [null, "bool_value", "integer_value", "double_value", "string_value", "byte_array_value", "bool_array_value", "integer_array_value", "double_array_value", "string_array_value"];

function valueOf(value) {
  const field = FIELD[value.type];
  return field ? value[field] : null;
}

// A ParameterValue of `type` from what the editor holds; throws Error when it does not fit.
function toParameterValue(type, raw) {
  const value = { type };
  if (type === 1) value.bool_value = Boolean(raw);
  else if (type === 2) {
    const number = Number(raw);
    if (!Number.isInteger(number)) throw new Error(`${raw} is not an integer`);
    value.integer_value = number;
  } else if (type === 3) {
    const number = Number(raw);
    if (!Number.isFinite(number)) throw new Error(`${raw} is not a number`);
    value.double_value = number;
  } else if (type === 4) value.string_value = String(raw);
  else {
    let list;
    try {
      list = JSON.parse(raw);
    } catch {
      throw new Error(`${raw} is not a JSON list`);
    }
    if (!Array.isArray(list)) throw new Error(`${raw} is not a JSON list`);
    value[FIELD[type]] = list;
  }
  return value;
}

export class ParametersPanel {
  constructor(ctx, root) {
    this.ctx = ctx;
    this.nodes = [];
    this.node = null;
    this.params = []; // {name, type, value, descriptor}
    this.open = false;
    this.sets = 0;
    // The last set's outcome per parameter of the chosen node: a /parameter_events reload
    // re-renders the rows, maybe before the set's answer comes, and must not lose it.
    this.outcomes = new Map();

    const side = document.createElement("div");
    side.className = "node-list";
    this.filter = Object.assign(document.createElement("input"), { type: "search", placeholder: "filter nodes", id: "params-filter" });
    this.filter.addEventListener("input", () => this.listNodes());
    this.nodeList = Object.assign(document.createElement("ul"), { id: "params-nodes" });
    side.append(this.filter, this.nodeList);
    const main = document.createElement("div");
    main.className = "params-main";
    this.title = Object.assign(document.createElement("h3"), { id: "params-title", textContent: "choose a node" });
    this.status = Object.assign(document.createElement("div"), { id: "params-status", className: "muted" });
    const refresh = Object.assign(document.createElement("button"), { textContent: "Refresh", id: "params-refresh" });
    refresh.addEventListener("click", () => this.load());
    this.table = Object.assign(document.createElement("table"), { id: "params-table", className: "params-table" });
    this.table.createTHead().insertRow().append(...["name", "value", "type", "description"].map((t) => Object.assign(document.createElement("th"), { textContent: t })));
    this.body = this.table.createTBody();
    main.append(this.title, refresh, this.status, this.table);
    const columns = document.createElement("div");
    columns.className = "side-and-main";
    columns.append(side, main);
    root.append(columns);
    ctx.conn.on("graph", (message) => {
      this.nodes = message.graph.nodes.map((n) => n.name);
      if (this.open) this.listNodes();
    });
    ctx.conn.on("fields", (message) => {
      if (message.topic === "/parameter_events" && this.open && message.msg.node === this.node) this.load();
    });
  }

  show() {
    this.open = true;
    this.ctx.conn.watchGraph(true);
    this.ctx.conn.want("/parameter_events", "fields");
    this.listNodes();
  }

  hide() {
    this.open = false;
    this.ctx.conn.watchGraph(false);
    this.ctx.conn.unwant("/parameter_events", "fields");
  }

  listNodes() {
    const filter = this.filter.value.trim().toLowerCase();
    const names = this.nodes.filter((n) => !isHidden(n) && (!filter || n.toLowerCase().includes(filter)));
    this.nodeList.replaceChildren(...names.map((name) => {
      const item = Object.assign(document.createElement("li"), { textContent: name });
      item.dataset.node = name;
      if (name === this.node) item.className = "chosen";
      item.addEventListener("click", () => this.choose(name));
      return item;
    }));
  }

  choose(name) {
    if (name !== this.node) this.outcomes.clear();
    this.node = name;
    this.listNodes();
    this.load();
  }

  async call(service, request) {
    const reply = await this.ctx.conn.call(`${this.node}/${service}`, SRV + service.split("_").map((w) => w[0].toUpperCase() + w.slice(1)).join(""), request);
    if (reply.error) throw new Error(`${this.node}/${service}: ${reply.error}`);
    return reply.response;
  }

  async load() {
    const node = this.node;
    if (!node) return;
    this.title.textContent = node;
    this.status.textContent = "reading parameters…";
    try {
      const listed = await this.call("list_parameters", { prefixes: [], depth: 0 });
      const names = [...listed.result.names].sort();
      const values = (await this.call("get_parameters", { names })).values;
      const descriptors = (await this.call("describe_parameters", { names })).descriptors;
      if (node !== this.node) return;
      this.params = names.map((name, i) => ({ name, type: values[i].type, value: valueOf(values[i]), descriptor: descriptors[i] || {} }));
      this.status.textContent = `${names.length} parameters`;
      this.render();
    } catch (error) {
      if (node === this.node) this.status.textContent = error.message;
    }
  }

  render() {
    this.body.replaceChildren(...this.params.map((p) => this.row(p)));
  }

  row(param) {
    const row = document.createElement("tr");
    row.dataset.param = param.name;
    row.insertCell().textContent = param.name;
    const cell = row.insertCell();
    const d = param.descriptor;
    const readOnly = Boolean(d.read_only);
    let editor;
    if (param.type === 1) {
      editor = Object.assign(document.createElement("input"), { type: "checkbox", checked: Boolean(param.value) });
      editor.addEventListener("change", () => this.set(param, editor.checked));
      cell.append(editor);
    } else if (param.type === 2 || param.type === 3) {
      const range = (param.type === 2 ? d.integer_range : d.floating_point_range) || [];
      editor = Object.assign(document.createElement("input"), { type: "number", value: String(param.value), step: param.type === 2 ? "1" : "any" });
      if (range.length) {
        const { from_value: low, to_value: high, step } = range[0];
        const slider = Object.assign(document.createElement("input"), { type: "range", min: String(low), max: String(high), step: step ? String(step) : param.type === 2 ? "1" : "any", value: String(param.value), disabled: readOnly });
        slider.addEventListener("input", () => { editor.value = slider.value; });
        slider.addEventListener("change", () => this.set(param, slider.value));
        Object.assign(editor, { min: String(low), max: String(high) });
        cell.append(slider);
        row.dataset.range = `${low}..${high}`;
      }
      editor.addEventListener("change", () => this.set(param, editor.value));
      cell.append(editor);
    } else {
      const text = param.type === 4 ? String(param.value ?? "") : JSON.stringify(param.value ?? []);
      editor = Object.assign(document.createElement("input"), { type: "text", value: text, size: 24 });
      editor.addEventListener("change", () => this.set(param, editor.value));
      cell.append(editor);
    }
    editor.dataset.editor = param.name;
    editor.disabled = readOnly || param.type === 0;
    const result = Object.assign(document.createElement("span"), { className: "set-result" });
    const outcome = this.outcomes.get(param.name);
    if (outcome) Object.assign(result, outcome);
    cell.append(result);
    row.insertCell().textContent = TYPES[param.type] || String(param.type);
    const described = row.insertCell();
    described.className = "description";
    described.textContent = [d.description, readOnly ? "(read only)" : "", d.additional_constraints].filter(Boolean).join(" ");
    return row;
  }

  async set(param, raw) {
    let value;
    try {
      value = toParameterValue(param.type, raw);
    } catch (error) {
      this.showOutcome(param.name, ` ✗ ${error.message}`, false);
      return;
    }
    try {
      const response = await this.call("set_parameters", { parameters: [{ name: param.name, value }] });
      const outcome = response.results[0];
      this.sets += 1;
      this.showOutcome(param.name, outcome.successful ? " ✓" : ` ✗ ${outcome.reason}`, outcome.successful);
      if (outcome.successful) param.value = valueOf(value);
    } catch (error) {
      this.showOutcome(param.name, ` ✗ ${error.message}`, false);
    }
  }

  showOutcome(name, text, ok) {
    const outcome = { textContent: text, className: `set-result ${ok ? "ok" : "failed"}` };
    this.outcomes.set(name, outcome);
    const row = [...this.body.rows].find((r) => r.dataset.param === name);
    if (row) Object.assign(row.querySelector(".set-result"), outcome);
  }
}
