// The page's WebSocket to the rviz2 stand-in (subprotocol launchkit.viewer.v1), reconnecting by
// itself: while the launch is down the page keeps trying, and when it is back every topic the
// page shows is subscribed again.

export const SUBPROTOCOL = "launchkit.viewer.v1";
const RETRY_MS = [250, 500, 1000, 1000, 2000];

export class Connection {
  constructor(url, handlers) {
    this.url = url;
    this.handlers = handlers; // hello, topics, sliders, rates, msg, image, error, state
    this.counts = new Map(); // topic -> how many parts of the page show it
    this.socket = null;
    this.connected = false;
    this.attempt = 0;
  }

  start() {
    const socket = new WebSocket(this.url, [SUBPROTOCOL]);
    socket.binaryType = "arraybuffer";
    this.socket = socket;
    socket.onopen = () => {
      this.attempt = 0;
      this.connected = true;
      this.handlers.state(true);
      const topics = [...this.counts.keys()];
      if (topics.length) this.send({ op: "subscribe", topics });
    };
    socket.onmessage = (event) => this.receive(event.data);
    socket.onclose = () => {
      if (this.socket !== socket) return;
      const was = this.connected;
      this.connected = false;
      this.socket = null;
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
    const handler = this.handlers[message.op];
    if (handler) handler(message);
  }

  send(message) {
    if (this.connected && this.socket) this.socket.send(JSON.stringify(message));
  }

  // A part of the page starts showing `topic`: subscribed while at least one part shows it.
  want(topic) {
    const count = this.counts.get(topic) || 0;
    this.counts.set(topic, count + 1);
    if (count === 0) this.send({ op: "subscribe", topics: [topic] });
  }

  unwant(topic) {
    const count = this.counts.get(topic) || 0;
    if (count <= 1) {
      this.counts.delete(topic);
      if (count === 1) this.send({ op: "unsubscribe", topics: [topic] });
    } else {
      this.counts.set(topic, count - 1);
    }
  }

  publish(topic, type, msg) {
    this.send({ op: "publish", topic, type, msg });
  }
}
