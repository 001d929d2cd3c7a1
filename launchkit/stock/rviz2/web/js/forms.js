// Forms built from a message's fields (schema.py's description, from the server's type store):
// a number box per numeric field, a check box per bool, a text box per string, a box per nested
// message, and arrays written as JSON lists ([1, 2, 3]). Each input carries its field path in
// data-path ("linear.x"), and read() gives the message as the server's `build` takes it.

const INTEGER = new Set(["byte", "char", "int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64"]);
const FLOAT = new Set(["float32", "float64"]);

function typeLabel(spec) {
  if (spec.kind === "base") return spec.type;
  if (spec.kind === "message") return spec.type.replace("/msg/", "/");
  const inner = typeLabel(spec.item);
  if (spec.kind === "array") return `${inner}[${spec.length}]`;
  return spec.bound ? `${inner}[<=${spec.bound}]` : `${inner}[]`;
}

export class MessageForm {
  // `schema` is {type, fields, constants}; `depth` nested boxes are drawn open.
  constructor(container, schema, openDepth = 2) {
    this.inputs = []; // {path, spec, input}
    this.root = document.createElement("div");
    this.root.className = "message-form";
    if (!schema.fields.length) this.root.append(Object.assign(document.createElement("div"), { className: "muted", textContent: "(no fields)" }));
    this.addFields(this.root, schema.fields, "", 0, openDepth);
    container.replaceChildren(this.root);
  }

  addFields(parent, fields, prefix, depth, openDepth) {
    for (const field of fields) {
      const path = prefix ? `${prefix}.${field.name}` : field.name;
      if (field.kind === "message") {
        const box = document.createElement("details");
        box.open = depth < openDepth;
        box.append(Object.assign(document.createElement("summary"), { textContent: `${field.name} (${typeLabel(field)})` }));
        this.addFields(box, field.fields, path, depth + 1, openDepth);
        parent.append(box);
        continue;
      }
      const row = document.createElement("label");
      row.className = "form-row";
      const name = Object.assign(document.createElement("span"), { className: "form-name", textContent: field.name });
      const type = Object.assign(document.createElement("span"), { className: "muted form-type", textContent: typeLabel(field) });
      const input = document.createElement("input");
      input.dataset.path = path;
      if (field.kind === "base" && field.type === "bool") {
        input.type = "checkbox";
      } else if (field.kind === "base" && (INTEGER.has(field.type) || FLOAT.has(field.type))) {
        input.type = "number";
        input.step = INTEGER.has(field.type) ? "1" : "any";
        input.value = "0";
      } else if (field.kind === "base") {
        input.type = "text";
      } else {
        input.type = "text";
        input.value = field.kind === "array" ? JSON.stringify(new Array(field.length).fill(defaultOf(field.item))) : "[]";
        input.title = "a JSON list";
      }
      row.append(name, input, type);
      parent.append(row);
      this.inputs.push({ path, spec: field, input });
    }
  }

  // Set a field's input (tests, and the publisher's remembered messages).
  set(path, value) {
    const entry = this.inputs.find((i) => i.path === path);
    if (!entry) return false;
    if (entry.input.type === "checkbox") entry.input.checked = Boolean(value);
    else entry.input.value = typeof value === "string" ? value : JSON.stringify(value);
    return true;
  }

  // The message as nested objects; throws Error naming the field whose text does not fit.
  read() {
    const message = {};
    for (const { path, spec, input } of this.inputs) {
      let value;
      if (spec.kind === "base") {
        value = readBase(spec.type, input, path);
      } else {
        try {
          value = JSON.parse(input.value.trim() || "[]");
        } catch {
          throw new Error(`${path}: ${input.value} is not a JSON list`);
        }
        if (!Array.isArray(value)) throw new Error(`${path}: expected a JSON list`);
      }
      const keys = path.split(".");
      let target = message;
      for (const key of keys.slice(0, -1)) target = target[key] ??= {};
      target[keys[keys.length - 1]] = value;
    }
    return message;
  }
}

function defaultOf(spec) {
  if (spec.kind !== "base") return {};
  if (spec.type === "bool") return false;
  if (INTEGER.has(spec.type) || FLOAT.has(spec.type)) return 0;
  return "";
}

function readBase(type, input, path) {
  if (type === "bool") return input.checked;
  if (INTEGER.has(type)) {
    const value = Number(input.value || 0);
    if (!Number.isInteger(value)) throw new Error(`${path}: ${input.value} is not an integer`);
    return value;
  }
  if (FLOAT.has(type)) {
    const value = Number(input.value || 0);
    if (!Number.isFinite(value)) throw new Error(`${path}: ${input.value} is not a number`);
    return value;
  }
  return input.value;
}
