// Driving from the page: teleop_twist_keyboard's keys (and the arrow keys) and on-screen
// buttons publish geometry_msgs/Twist on /cmd_vel while held, ten times a second, and a zero
// twist when let go (or when the page loses focus), so the robot never runs away unattended.

const MOVES = {
  // key: [x, y, z, turn], as teleop_twist_keyboard's moveBindings
  i: [1, 0, 0, 0], o: [1, 0, 0, -1], j: [0, 0, 0, 1], l: [0, 0, 0, -1],
  u: [1, 0, 0, 1], ",": [-1, 0, 0, 0], ".": [-1, 0, 0, 1], m: [-1, 0, 0, -1],
  O: [1, -1, 0, 0], I: [1, 0, 0, 0], J: [0, 1, 0, 0], L: [0, -1, 0, 0],
  U: [1, 1, 0, 0], "<": [-1, 0, 0, 0], ">": [-1, -1, 0, 0], M: [-1, 1, 0, 0],
  t: [0, 0, 1, 0], b: [0, 0, -1, 0], k: [0, 0, 0, 0],
  ArrowUp: [1, 0, 0, 0], ArrowDown: [-1, 0, 0, 0], ArrowLeft: [0, 0, 0, 1], ArrowRight: [0, 0, 0, -1],
};
const SPEEDS = {
  // key: [speed factor, turn factor], as speedBindings
  q: [1.1, 1.1], z: [0.9, 0.9], w: [1.1, 1], x: [0.9, 1], e: [1, 1.1], c: [1, 0.9],
};
const PERIOD_MS = 100;

export class Drive {
  constructor(ctx, pad, speedLabel, topicLabel, topic = "/cmd_vel") {
    this.ctx = ctx;
    this.topic = topic;
    this.speed = 0.5;
    this.turn = 1.0;
    this.held = new Set();
    this.timer = null;
    this.speedLabel = speedLabel;
    topicLabel.textContent = topic;
    this.showSpeed();
    window.addEventListener("keydown", (e) => this.keyDown(e));
    window.addEventListener("keyup", (e) => this.keyUp(e));
    window.addEventListener("blur", () => this.releaseAll());
    document.addEventListener("visibilitychange", () => { if (document.hidden) this.releaseAll(); });
    for (const button of pad.querySelectorAll("button")) {
      const key = button.dataset.key;
      button.addEventListener("pointerdown", (e) => { button.setPointerCapture(e.pointerId); button.classList.add("active"); this.press(key); });
      const up = () => { button.classList.remove("active"); this.release(key); };
      button.addEventListener("pointerup", up);
      button.addEventListener("pointercancel", up);
    }
  }

  showSpeed() {
    this.speedLabel.textContent = `speed ${this.speed.toFixed(2)} m/s · turn ${this.turn.toFixed(2)} rad/s (q/z w/x e/c)`;
  }

  typing(event) {
    const target = event.target;
    return target && (target.tagName === "INPUT" || target.tagName === "SELECT" || target.tagName === "TEXTAREA");
  }

  keyDown(event) {
    if (this.typing(event) || event.ctrlKey || event.metaKey || event.altKey) return;
    if (this.ctx.drivingKeys && !this.ctx.drivingKeys()) return;
    const key = event.key;
    if (SPEEDS[key]) {
      this.speed *= SPEEDS[key][0];
      this.turn *= SPEEDS[key][1];
      this.showSpeed();
      event.preventDefault();
      return;
    }
    if (!MOVES[key] && key !== " ") return;
    event.preventDefault();
    if (!event.repeat) this.press(key === " " ? "k" : key);
  }

  keyUp(event) {
    const key = event.key === " " ? "k" : event.key;
    // shift changes a key's case between press and release: release both
    for (const held of [...this.held]) if (held.toLowerCase() === key.toLowerCase()) this.release(held);
  }

  press(key) {
    if (!MOVES[key]) return;
    this.held.add(key);
    this.send();
    if (!this.timer) this.timer = setInterval(() => this.send(), PERIOD_MS);
  }

  release(key) {
    if (!this.held.delete(key)) return;
    if (this.held.size === 0) this.stop();
    else this.send();
  }

  releaseAll() {
    if (this.held.size) {
      this.held.clear();
      this.stop();
    }
  }

  stop() {
    clearInterval(this.timer);
    this.timer = null;
    this.publish([0, 0, 0, 0]);
  }

  send() {
    const sum = [0, 0, 0, 0];
    for (const key of this.held) MOVES[key].forEach((v, i) => { sum[i] += v; });
    const clamp = (v) => Math.max(-1, Math.min(1, v));
    this.publish(sum.map(clamp));
  }

  publish([x, y, z, th]) {
    this.ctx.conn.publish(this.topic, "geometry_msgs/msg/Twist", {
      linear: { x: x * this.speed, y: y * this.speed, z: z * this.speed },
      angular: { x: 0, y: 0, z: th * this.turn },
    });
    this.ctx.stats.twistsSent += 1;
  }
}
