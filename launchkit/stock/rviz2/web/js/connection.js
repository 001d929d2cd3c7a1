// The page's WebSocket to the rviz2 stand-in (subprotocol launchkit.viewer.v1), reconnecting by
// itself: while the launch is down the page keeps trying, and when it is back every topic the
// page shows is subscribed again.

export const SUBPROTOCOL = "launchkit.viewer.v1";
const RETRY_MS = [250, 500, 1000, 1000, 2000];

export class Connection {
  constructor(url, handlers) {
    this.url = url;
    this.handlers = handlers; // hello, topics, sliders, rates, msg, image, error, state
    this.counts = new Map(); // "form topic" -> how many parts of the page show it in that form
    this.listeners = new Map(); // op -> functions, for the panels (see on())
    this.pending = new Map(); // call id -> {resolve}
    this.interfaces = new Map(); // type -> promise of its schema
    this.graphWatchers = 0;
    this.nextId = 1;
    this.socket = null;
    this.connected = false;
    this.attempt = 0;
  }

  // Also call `listener(message)` for every message of `op` (several parts may listen).
  on(op, listener) {
    if (!this.listeners.has(op)) this.listeners.set(op, []);
    this.listeners.get(op).push(listener);
  }

  start() {
    const socket = new WebSocket(this.url, [SUBPROTOCOL]);
    socket.binaryType = "arraybuffer";
    this.socket = socket;
    socket.onopen = () => {
      this.attempt = 0;
      this.connected = true;
      this.handlers.state(true);
      const byForm = new Map();
      for (const key of this.counts.keys()) {
        const [form, topic] = splitKey(key);
        if (!byForm.has(form)) byForm.set(form, []);
        byForm.get(form).push(topic);
      }
      for (const [form, topics] of byForm) this.send({ op: "subscribe", topics, form });
      if (this.graphWatchers > 0) this.send({ op: "graph", watch: true });
    };
    socket.onmessage = (event) => this.receive(event.data);
    socket.onclose = () => {
      if (this.socket !== socket) return;
      const was = this.connected;
      this.connected = false;
      this.socket = null;
      for (const { resolve } of this.pending.values()) resolve({ error: "the connection to the viewer was lost" });
      this.pending.clear();
      this.interfaces.clear();
      if (was) this.handlers.state(false);
      const delay = RETRY_MS[Math.min(this.attempt, RETRY_MS.length - 1)];
      this.attempt += 1;
      setTimeout(() => this.start(), delay);
    };
  }

  receive(data) {
    if (typeof data !== "string") {
      const view = new DataView(data);
      const length = view.getUint32(0, true);
      const header = JSON.parse(new TextDecoder().decode(new Uint8Array(data, 4, length)));
      this.handlers.image(header, new Uint8Array(data, 4 + length));
      return;
    }
    const message = JSON.parse(data);
    if (message.op === "reply") {
      const waiting = this.pending.get(message.id);
      this.pending.delete(message.id);
      if (waiting) waiting.resolve(message);
      return;
    }
    const handler = this.handlers[message.op];
    if (handler) handler(message);
    for (const listener of this.listeners.get(message.op) || []) listener(message);
  }

  send(message) {
    if (this.connected && this.socket) this.socket.send(JSON.stringify(message));
  }

  // A part of the page starts showing `topic`: subscribed while at least one part shows it. The
  // form is "view" (what the displays and the console read) or "fields" (every field: the plot).
  want(topic, form = "view") {
    const key = `${form} ${topic}`;
    const count = this.counts.get(key) || 0;
    this.counts.set(key, count + 1);
    if (count === 0) this.send({ op: "subscribe", topics: [topic], form });
  }

  unwant(topic, form = "view") {
    const key = `${form} ${topic}`;
    const count = this.counts.get(key) || 0;
    if (count <= 1) {
      this.counts.delete(key);
      if (count === 1) this.send({ op: "unsubscribe", topics: [topic], form });
    } else {
      this.counts.set(key, count - 1);
    }
  }

  // The topics wanted in any form, sorted.
  wantedTopics() {
    return [...new Set([...this.counts.keys()].map((key) => splitKey(key)[1]))].sort();
  }

  // A part of the page shows the node graph: the server sends it now and after each change.
  watchGraph(on) {
    this.graphWatchers += on ? 1 : -1;
    if (on && this.graphWatchers === 1) this.send({ op: "graph", watch: true });
    if (!on && this.graphWatchers === 0) this.send({ op: "graph", watch: false });
  }

  // A service call through the server: a promise of {response} or {error}.
  call(service, type, request) {
    if (!this.connected) return Promise.resolve({ error: "not connected to the viewer" });
    const id = this.nextId++;
    return new Promise((resolve) => {
      this.pending.set(id, { resolve });
      this.send({ op: "call", id, service, type, request });
    });
  }

  // The fields of a message or service type (schema.py's form): a promise, asked once per type.
  schema(type) {
    if (!this.interfaces.has(type)) {
      this.interfaces.set(type, new Promise((resolve) => {
        const listener = (message) => {
          if (message.type !== type) return;
          const list = this.listeners.get("interface");
          list.splice(list.indexOf(listener), 1);
          resolve(message);
        };
        this.on("interface", listener);
        this.send({ op: "interface", type });
      }));
    }
    return this.interfaces.get(type);
  }

  publish(topic, type, msg) {
    this.send({ op: "publish", topic, type, msg });
  }
}

function splitKey(key) {
  const space = key.indexOf(" ");
  return [key.slice(0, space), key.slice(space + 1)];
}
