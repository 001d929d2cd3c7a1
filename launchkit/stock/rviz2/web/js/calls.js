// The service caller panel (rqt_service_caller): pick a service of the graph, fill its request in
// a form built from the request's fields, call it through the viewer's server and read the
// response. The service list comes with the node graph, which the server sends while this panel
// is open.
import { MessageForm } from "./forms.js";
import { isHidden } from "./graph.js";

export class ServiceCallerPanel {
  constructor(ctx, root) {
    this.ctx = ctx;
    this.services = [];
    this.form = null;
    this.current = null;
    this.open = false;
    this.calls = 0;

    const bar = document.createElement("div");
    bar.className = "panel-bar";
    this.select = Object.assign(document.createElement("select"), { id: "call-service" });
    this.select.addEventListener("change", () => this.choose(this.select.value));
    this.hidden = Object.assign(document.createElement("input"), { type: "checkbox", id: "call-hidden" });
    this.hidden.addEventListener("change", () => this.listServices());
    const hiddenLabel = document.createElement("label");
    hiddenLabel.append(this.hidden, " hidden services");
    this.button = Object.assign(document.createElement("button"), { id: "call-button", textContent: "Call", disabled: true });
    this.button.addEventListener("click", () => this.call());
    bar.append("Service ", this.select, hiddenLabel, this.button);
    this.formBox = Object.assign(document.createElement("div"), { id: "call-form", className: "form-box" });
    this.result = Object.assign(document.createElement("div"), { className: "result-box" });
    this.status = Object.assign(document.createElement("div"), { id: "call-status", className: "muted" });
    this.response = Object.assign(document.createElement("pre"), { id: "call-response" });
    this.result.append(this.status, this.response);
    const columns = document.createElement("div");
    columns.className = "two-columns";
    columns.append(this.formBox, this.result);
    root.append(bar, columns);
    ctx.conn.on("graph", (message) => {
      this.services = message.graph.services;
      if (this.open) this.listServices();
    });
  }

  show() {
    this.open = true;
    this.ctx.conn.watchGraph(true);
    this.listServices();
  }

  hide() {
    this.open = false;
    this.ctx.conn.watchGraph(false);
  }

  listServices() {
    const shown = this.services.filter((s) => this.hidden.checked || !isHidden(s.name));
    const current = this.select.value;
    this.select.replaceChildren(new Option("(choose a service)", ""), ...shown.map((s) => new Option(`${s.name} [${s.types.join(", ")}]`, s.name)));
    if (shown.some((s) => s.name === current)) this.select.value = current;
  }

  async choose(name) {
    const service = this.services.find((s) => s.name === name);
    this.current = service || null;
    this.button.disabled = true;
    this.response.textContent = "";
    this.status.textContent = "";
    if (!service) {
      this.formBox.replaceChildren();
      return;
    }
    const type = service.types[0];
    const schema = await this.ctx.conn.schema(type);
    if (this.current !== service) return;
    if (schema.error) {
      this.formBox.textContent = schema.error;
      return;
    }
    this.formBox.replaceChildren(Object.assign(document.createElement("h3"), { textContent: `Request (${type})` }));
    const holder = document.createElement("div");
    this.formBox.append(holder);
    this.form = new MessageForm(holder, schema.request);
    this.button.disabled = false;
  }

  async call() {
    if (!this.current || !this.form) return;
    let request;
    try {
      request = this.form.read();
    } catch (error) {
      this.status.textContent = error.message;
      return;
    }
    const started = performance.now();
    this.status.textContent = `calling ${this.current.name}…`;
    this.response.textContent = "";
    const reply = await this.ctx.conn.call(this.current.name, this.current.types[0], request);
    this.calls += 1;
    const took = `${(performance.now() - started).toFixed(0)} ms`;
    if (reply.error) {
      this.status.textContent = `failed after ${took}: ${reply.error}`;
      this.response.dataset.state = "error";
      return;
    }
    this.status.textContent = `response after ${took}`;
    this.response.dataset.state = "ok";
    this.response.textContent = JSON.stringify(reply.response, null, 2);
    this.lastResponse = reply.response;
  }
}
