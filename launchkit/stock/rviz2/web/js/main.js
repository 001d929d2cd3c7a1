// The viewer page: connects to the rviz2 stand-in that served it, builds the view the rviz config
// asks for, and exposes its state as window.__viewer (the tests wait on window.__viewer.stats).
import * as THREE from "three";
import { Connection } from "./connection.js";
import { DISPLAY_FOR_TYPE, makeDisplay } from "./displays.js";
import { ServiceCallerPanel } from "./calls.js";
import { ConsolePanel } from "./console.js";
import { Drive } from "./drive.js";
import { GraphPanel } from "./graph.js";
import { ImagePanel } from "./image.js";
import { JointSliders } from "./joints.js";
import { PanelTabs } from "./panels.js";
import { ParametersPanel } from "./params.js";
import { PlotPanel } from "./plot.js";
import { PublisherPanel } from "./publisher.js";
import { Scene3D } from "./scene.js";
import { TfTree } from "./tf.js";
import { TfTreePanel } from "./tftree.js";
import { TurtlesimPanel } from "./turtlesim.js";

const $ = (id) => document.getElementById(id);

const stats = {
  connected: false, connections: 0, sessionId: null, frames: 0, fps: 0,
  robotLinks: 0, robotLinkCount: 0, firstRobotMs: null, robotName: null, meshesLoaded: 0, meshesFailed: 0,
  scanMessages: 0, scanPoints: 0, odomMessages: 0, tfMessages: 0,
  imageTopic: null, imageFrames: 0, imageFps: 0, twistsSent: 0,
  sliders: 0, sliderMessages: 0, fixedFrame: null, problems: [],
};

const state = { config: null, displays: [], topics: [], rates: {}, watched: null, lastRobotLinks: 0 };
const tf = new TfTree();
const url = `${location.protocol === "https:" ? "wss" : "ws"}://${location.host}/`;

const ctx = {
  stats,
  tf,
  scene: null,
  conn: null,
  fixedFrame: () => stats.fixedFrame || state.config?.fixedFrame || "map",
  problem: (text) => {
    if (!stats.problems.includes(text)) stats.problems.push(text);
    console.warn(text);
  },
  robotChanged: (model) => {
    stats.robotName = model.name;
    state.robotRoot = model.root;
    sliders.robotChanged(model);
  },
};

// The fixed frame of the config, or the root of the robot's tree while that frame does not exist
// (as when nothing publishes `odom` or `map` yet), with a warning.
function resolveFixedFrame() {
  const wanted = state.config?.fixedFrame || "map";
  const select = $("fixed-frame");
  const chosen = select.value && select.value !== "(config)" ? select.value : wanted;
  let frame = chosen;
  let warning = "";
  if (!tf.has(chosen)) {
    const fallback = state.robotRoot && tf.rootOf(state.robotRoot);
    if (fallback && tf.has(fallback)) {
      frame = fallback;
      warning = `Frame [${chosen}] does not exist: showing in [${fallback}]`;
    } else {
      warning = `Frame [${chosen}] does not exist yet`;
    }
  }
  stats.fixedFrame = frame;
  const box = $("frame-warning");
  box.hidden = !warning;
  box.textContent = warning;
}

function refreshFrameChoices() {
  const select = $("fixed-frame");
  const current = select.value;
  const names = tf.names();
  if (select.options.length === names.length + 1) return;
  const wanted = state.config?.fixedFrame || "map";
  select.replaceChildren(new Option(`${wanted} (config)`, "(config)"), ...names.map((n) => new Option(n, n)));
  select.value = current || "(config)";
}

function buildDisplays(config) {
  for (const display of state.displays) {
    display.setEnabled(false);
    ctx.scene.scene.remove(display.root);
  }
  state.displays = [];
  const list = $("displays");
  list.replaceChildren();
  for (const spec of config.displays) addDisplay(spec);
  images.configure(config.displays);
}

function addDisplay(spec) {
  const display = makeDisplay(ctx, spec);
  const item = document.createElement("li");
  const box = document.createElement("input");
  box.type = "checkbox";
  const label = document.createElement("label");
  label.append(box, ` ${spec.name || spec.class}`);
  if (spec.topic) label.append(Object.assign(document.createElement("span"), { className: "muted", textContent: ` ${spec.topic}` }));
  item.append(label);
  $("displays").append(item);
  if (display) {
    state.displays.push(display);
    box.checked = spec.enabled;
    box.addEventListener("change", () => display.setEnabled(box.checked));
    display.setEnabled(spec.enabled);
  } else if (spec.class === "Image" || spec.class === "Camera") {
    box.checked = spec.enabled;
    box.addEventListener("change", () => images.show(box.checked ? spec.topic : null));
    images.checkbox = box;
  } else {
    box.disabled = true;
    label.title = "not supported by the launchkit viewer";
    label.append(Object.assign(document.createElement("span"), { className: "muted", textContent: " (not supported)" }));
  }
  return display;
}

function renderTopics() {
  const body = $("topics").tBodies[0];
  body.replaceChildren();
  for (const topic of state.topics) {
    const row = body.insertRow();
    const name = row.insertCell();
    name.textContent = topic.name;
    const kind = DISPLAY_FOR_TYPE[topic.type];
    const shown = state.displays.some((d) => d.topics().includes(topic.name));
    if (kind && !shown) {
      const add = Object.assign(document.createElement("button"), { textContent: "+", title: `add a ${kind} display` });
      add.addEventListener("click", (event) => {
        event.stopPropagation();
        addDisplay({ class: kind, name: kind, enabled: true, topic: topic.name, options: {} });
        renderTopics();
      });
      name.prepend(add, " ");
    }
    const type = row.insertCell();
    type.textContent = topic.type.split("/").pop();
    type.title = topic.type;
    const rate = state.rates[topic.name];
    row.insertCell().textContent = rate === undefined ? "–" : rate.toFixed(1);
    row.title = "click: show its rate and its last message";
    if (topic.name === state.watched) row.className = "watched";
    row.addEventListener("click", () => watch(topic.name));
  }
}

// Watch one topic from the list (rate and last message, like `ros2 topic hz/echo`).
function watch(name) {
  if (state.watched) ctx.conn.unwant(state.watched);
  state.watched = state.watched === name ? null : name;
  $("echo").hidden = !state.watched;
  $("echo").textContent = state.watched ? `${state.watched}: waiting for a message…` : "";
  if (state.watched) ctx.conn.want(state.watched);
  renderTopics();
}

function onMessage(message) {
  const { topic, type, msg } = message;
  if (type === "tf2_msgs/msg/TFMessage") {
    stats.tfMessages += 1;
    tools.tf.observe(topic, msg.transforms);
    let changed = false;
    for (const t of msg.transforms) {
      if (t.t.every((v) => v !== null) && t.q.every((v) => v !== null)) changed = tf.set(t.parent, t.child, t.t, t.q) || changed;
    }
    if (changed) ctx.scene.requestRender();
  }
  for (const display of state.displays) if (display.enabled && display.topics().includes(topic)) display.onMessage(topic, type, msg);
  sliders.onMessage(topic, type, msg);
  tools.turtlesim.onMessage(topic, type, msg);
  if (topic === state.watched) {
    const shown = type === "std_msgs/msg/String" && msg.data.length > 2000 ? { data: msg.data.slice(0, 2000) + "…" } : msg.fields || msg;
    $("echo").textContent = `${topic} (${type})\n${JSON.stringify(shown, null, 1)}`;
  }
}

function onHello(hello) {
  stats.connections += 1;
  const newServer = stats.sessionId !== hello.sessionId;
  stats.sessionId = hello.sessionId;
  if (newServer) {
    // a new (restarted) server: forget its predecessor's transforms and robot, and draw again
    tf.clear();
    tools.tf.clear();
    for (const display of state.displays) display.reset();
    stats.robotLinks = 0;
    if (ctx.scene) ctx.scene.requestRender();
  }
  if (!state.config || JSON.stringify(state.config) !== JSON.stringify(hello.config)) {
    state.config = hello.config;
    if (!ctx.scene) {
      ctx.scene = new Scene3D($("scene"), hello.config.background, hello.config.frameRate, stats);
      ctx.scene.onFrame(frameUpdate);
    }
    buildDisplays(hello.config);
  }
  document.title = `launchkit viewer · ${location.host}`;
}

function frameUpdate() {
  refreshFrameChoices();
  resolveFixedFrame();
  for (const display of state.displays) if (display.enabled) display.update();
  if (stats.robotLinks > 0 && stats.firstRobotMs === null) stats.firstRobotMs = Math.round(performance.now());
}

function setConnected(connected) {
  stats.connected = connected;
  const box = $("connection");
  box.className = `state ${connected ? "ok" : "down"}`;
  box.textContent = connected ? `connected to ${location.host}` : "disconnected: reconnecting…";
  $("banner").hidden = connected;
  $("banner").textContent = "The launch is not running: reconnecting…";
}

const images = new ImagePanel(ctx, $("image-panel"), $("image-topic"), $("image"), $("image-rate"));
const sliders = new JointSliders(ctx, $("joints-panel"), $("joints"), $("joints-topic"), $("joints-center"), $("joints-randomize"));
ctx.conn = new Connection(url, {
  hello: onHello,
  topics: (m) => { state.topics = m.topics; images.topicsChanged(m.topics); tools.turtlesim.topicsChanged(m.topics); renderTopics(); },
  rates: (m) => { state.rates = m.rates; renderTopics(); },
  sliders: (m) => sliders.sliderTopic(m.topic),
  msg: onMessage,
  image: (header, bytes) => images.onImage(header, bytes),
  error: (m) => ctx.problem(`server: ${m.message}`),
  state: setConnected,
});
const topicsOf = () => state.topics;
const tools = {
  graph: new GraphPanel(ctx, $("graph-panel")),
  console: new ConsolePanel(ctx, $("console-panel")),
  plot: new PlotPanel(ctx, $("plot-panel"), topicsOf),
  params: new ParametersPanel(ctx, $("params-panel")),
  services: new ServiceCallerPanel(ctx, $("services-panel")),
  publisher: new PublisherPanel(ctx, $("publisher-panel"), topicsOf),
  tf: new TfTreePanel(ctx, $("tf-panel")),
  // the first turtlesim to appear takes the page from the 3D view to its panel
  turtlesim: new TurtlesimPanel(ctx, $("turtlesim-panel"), () => { if (tabs.current === "view") tabs.select("turtlesim"); }),
};
const tabs = new PanelTabs($("tabs"), [
  { name: "view", title: "3D view", element: $("view") },
  { name: "graph", title: "Node graph", element: $("graph-panel"), panel: tools.graph },
  { name: "console", title: "Console", element: $("console-panel"), panel: tools.console },
  { name: "plot", title: "Plot", element: $("plot-panel"), panel: tools.plot },
  { name: "params", title: "Parameters", element: $("params-panel"), panel: tools.params },
  { name: "services", title: "Service caller", element: $("services-panel"), panel: tools.services },
  { name: "publisher", title: "Topic publisher", element: $("publisher-panel"), panel: tools.publisher },
  { name: "tf", title: "TF tree", element: $("tf-panel"), panel: tools.tf },
  { name: "turtlesim", title: "turtlesim", element: $("turtlesim-panel"), panel: tools.turtlesim },
]);
// driving keys belong to the 3D view: typing arrows in another panel moves nothing
ctx.drivingKeys = () => tabs.current === "view";
const cmdVel = new URLSearchParams(location.search).get("cmd_vel") || "/cmd_vel";
new Drive(ctx, $("drive-pad"), $("drive-speed"), $("drive-topic"), cmdVel);
// the view needs transforms whatever displays show
ctx.conn.want("/tf");
ctx.conn.want("/tf_static");
ctx.conn.start();

// For tests and the benchmark: the page's state and a few probes of what it draws.
window.__viewer = {
  stats,
  // the canvas point (CSS pixels) where a frame's origin is drawn now
  project(frame) {
    const pose = tf.lookup(ctx.fixedFrame(), frame);
    if (!pose || !ctx.scene) return null;
    return ctx.scene.project(new THREE.Vector3().setFromMatrixPosition(pose));
  },
  sample: (points) => ctx.scene.sample(points),
  background: () => state.config?.background,
  wanted: () => ctx.conn.wantedTopics(),
  rates: () => ({ ...state.rates }), // as measured by the server, for the topics shown
  showImage: (topic) => { if (images.checkbox) images.checkbox.checked = Boolean(topic); images.show(topic); },
  // the rqt panels: which is shown, and each one's state as a person would read it
  panel: () => tabs.current,
  showPanel: (name) => tabs.select(name),
  tools,
  setDisplay(name, on) {
    const display = state.displays.find((d) => d.spec.name === name);
    if (display) display.setEnabled(on);
  },
};
