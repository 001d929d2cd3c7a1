// The topic publisher panel (rqt_publisher): a topic (one of the graph's, or a new one) and its
// message type, a form built from the type's fields, and Publish once or at a rate. Publications
// at a rate are listed and keep going while the page is open, whichever panel is shown (so their
// effect can be watched in the plot or the 3D view), until stopped.
import { MessageForm } from "./forms.js";

export class PublisherPanel {
  constructor(ctx, root, topicsOf) {
    this.ctx = ctx;
    this.topicsOf = topicsOf;
    this.form = null;
    this.type = null;
    this.running = []; // {topic, type, rate, message, timer, sent}
    this.sent = 0;

    const bar = document.createElement("div");
    bar.className = "panel-bar";
    this.topic = Object.assign(document.createElement("input"), { id: "pub-topic", placeholder: "/topic", size: 24 });
    this.topic.setAttribute("list", "pub-topics");
    this.topicChoices = Object.assign(document.createElement("datalist"), { id: "pub-topics" });
    this.topic.addEventListener("focus", () => this.listTopics());
    this.topic.addEventListener("change", () => {
      const known = this.topicsOf().find((t) => t.name === this.topic.value.trim());
      if (known) { this.typeBox.value = known.type; this.load(); }
    });
    this.typeBox = Object.assign(document.createElement("input"), { id: "pub-type", placeholder: "pkg/msg/Type", size: 28 });
    this.typeBox.addEventListener("change", () => this.load());
    this.rate = Object.assign(document.createElement("input"), { id: "pub-rate", type: "number", min: "0.1", step: "any", value: "1", title: "messages a second" });
    this.once = Object.assign(document.createElement("button"), { id: "pub-once", textContent: "Publish once", disabled: true });
    this.once.addEventListener("click", () => this.publishOnce());
    this.start = Object.assign(document.createElement("button"), { id: "pub-start", textContent: "Publish at rate", disabled: true });
    this.start.addEventListener("click", () => this.startRate());
    this.status = Object.assign(document.createElement("span"), { id: "pub-status", className: "muted" });
    bar.append("Topic ", this.topic, this.topicChoices, " Type ", this.typeBox, this.once, this.rate, "Hz ", this.start, this.status);
    this.formBox = Object.assign(document.createElement("div"), { id: "pub-form", className: "form-box" });
    this.list = Object.assign(document.createElement("ul"), { id: "pub-running", className: "running-list" });
    const columns = document.createElement("div");
    columns.className = "two-columns";
    const right = document.createElement("div");
    right.append(Object.assign(document.createElement("h3"), { textContent: "Publishing" }), this.list);
    columns.append(this.formBox, right);
    root.append(bar, columns);
  }

  show() { this.listTopics(); }

  hide() {}

  listTopics() {
    this.topicChoices.replaceChildren(...this.topicsOf().map((t) => new Option(t.name, t.name)));
  }

  async load() {
    const type = this.typeBox.value.trim();
    this.once.disabled = this.start.disabled = true;
    if (!type) return;
    const schema = await this.ctx.conn.schema(type);
    if (this.typeBox.value.trim() !== type) return;
    if (schema.error || !schema.message) {
      this.status.textContent = schema.error || `${type} is not a message type`;
      this.formBox.replaceChildren();
      return;
    }
    this.status.textContent = "";
    this.type = schema.type;
    this.form = new MessageForm(this.formBox, schema.message);
    this.once.disabled = this.start.disabled = false;
  }

  // The topic and message to send, or null (with the reason shown).
  message() {
    const topic = this.topic.value.trim();
    if (!topic.startsWith("/")) {
      this.status.textContent = "the topic must be an absolute name (/...)";
      return null;
    }
    try {
      return { topic, type: this.type, message: this.form.read() };
    } catch (error) {
      this.status.textContent = error.message;
      return null;
    }
  }

  publishOnce() {
    const what = this.message();
    if (!what) return;
    this.ctx.conn.publish(what.topic, what.type, what.message);
    this.sent += 1;
    this.status.textContent = `published once on ${what.topic}`;
  }

  startRate() {
    const what = this.message();
    const rate = Number(this.rate.value);
    if (!what) return;
    if (!(rate > 0)) {
      this.status.textContent = "the rate must be above 0";
      return;
    }
    const entry = { ...what, rate, sent: 0 };
    entry.timer = setInterval(() => {
      this.ctx.conn.publish(entry.topic, entry.type, entry.message);
      entry.sent += 1;
      this.sent += 1;
    }, 1000 / rate);
    this.running.push(entry);
    this.renderList();
  }

  stop(entry) {
    clearInterval(entry.timer);
    this.running.splice(this.running.indexOf(entry), 1);
    this.renderList();
  }

  renderList() {
    this.list.replaceChildren(...this.running.map((entry) => {
      const item = document.createElement("li");
      item.dataset.topic = entry.topic;
      const stop = Object.assign(document.createElement("button"), { textContent: "Stop" });
      stop.addEventListener("click", () => this.stop(entry));
      item.append(`${entry.topic} [${entry.type}] at ${entry.rate} Hz `, stop);
      item.title = JSON.stringify(entry.message);
      return item;
    }));
  }
}
