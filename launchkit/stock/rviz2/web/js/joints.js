// Joint sliders, as joint_state_publisher_gui's window offers them: shown while that node runs
// (the server says on which topic it takes slider positions), one slider per moving joint of the
// robot (revolute and prismatic within their limits, continuous over a full turn; fixed and
// mimic joints have none), with Center and Randomize. Moving a slider publishes the positions;
// the node publishes them on /joint_states, so the robot model follows through TF.

const MOVING = new Set(["revolute", "continuous", "prismatic"]);
const PERIOD_MS = 50;

function range(joint) {
  if (joint.type === "continuous") return [-Math.PI, Math.PI];
  if (joint.upper > joint.lower) return [joint.lower, joint.upper];
  return [-Math.PI, Math.PI];
}

export class JointSliders {
  constructor(ctx, panel, container, topicLabel, center, randomize) {
    this.ctx = ctx;
    this.panel = panel;
    this.container = container;
    this.topicLabel = topicLabel;
    this.topic = null;
    this.joints = [];
    this.inputs = new Map();
    this.touched = false;
    this.pending = null;
    this.watching = false;
    // as joint_state_publisher: a joint rests at 0, or mid-range when 0 is outside its limits
    center.addEventListener("click", () => this.setAll((low, high) => (low <= 0 && 0 <= high ? 0 : (low + high) / 2)));
    randomize.addEventListener("click", () => this.setAll((low, high) => low + Math.random() * (high - low)));
  }

  robotChanged(model) {
    this.joints = model.joints.filter((j) => MOVING.has(j.type) && !j.mimic);
    this.touched = false;
    this.build();
  }

  sliderTopic(topic) {
    this.topic = topic;
    this.topicLabel.textContent = topic || "";
    this.build();
  }

  build() {
    const show = Boolean(this.topic) && this.joints.length > 0;
    this.panel.hidden = !show;
    this.ctx.stats.sliders = show ? this.joints.length : 0;
    // the current positions come from /joint_states, read only while the sliders show
    if (show && !this.watching) this.ctx.conn.want("/joint_states");
    if (!show && this.watching) this.ctx.conn.unwant("/joint_states");
    this.watching = show;
    this.inputs.clear();
    this.container.replaceChildren();
    if (!show) return;
    for (const joint of this.joints) {
      const [low, high] = range(joint);
      const input = document.createElement("input");
      const rest = low <= 0 && 0 <= high ? 0 : (low + high) / 2;
      Object.assign(input, { type: "range", min: low, max: high, step: (high - low) / 1000, value: rest });
      input.dataset.joint = joint.name;
      const value = document.createElement("span");
      value.className = "muted";
      const label = document.createElement("label");
      label.append(`${joint.name} `, value, input);
      input.addEventListener("input", () => { this.touched = true; this.changed(); });
      this.inputs.set(joint.name, { input, value });
      this.container.append(label);
    }
    this.showValues();
  }

  showValues() {
    for (const { input, value } of this.inputs.values()) value.textContent = Number(input.value).toFixed(2);
  }

  // The latest /joint_states, to start from what the node publishes.
  onMessage(topic, type, msg) {
    if (topic !== "/joint_states" || this.touched) return;
    msg.name.forEach((name, i) => {
      const entry = this.inputs.get(name);
      if (entry && msg.position[i] !== null && msg.position[i] !== undefined) entry.input.value = msg.position[i];
    });
    this.showValues();
  }

  setAll(position) {
    for (const { input } of this.inputs.values()) input.value = position(Number(input.min), Number(input.max));
    this.touched = true;
    this.changed();
  }

  changed() {
    this.showValues();
    if (this.pending) return;
    this.send();
    this.pending = setTimeout(() => { this.pending = null; this.send(); }, PERIOD_MS);
  }

  send() {
    if (!this.topic) return;
    const name = [...this.inputs.keys()];
    const position = name.map((n) => Number(this.inputs.get(n).input.value));
    this.ctx.conn.publish(this.topic, "sensor_msgs/msg/JointState", { name, position });
    this.ctx.stats.sliderMessages += 1;
  }
}
