// The turtlesim panel: the 500 x 500 world of each turtlesim node of the graph (a menu chooses
// when there are several), drawn from the two hidden topics each one publishes
// (launchkit/stock/turtlesim/scene.py says what they hold): /_turtlesim<node>/scene (background,
// turtles, the pen strokes since the last snapshot) and /_turtlesim<node>/trails (a PNG snapshot
// of the trails). Like the other panels it subscribes only while shown; the page shows it when
// the first turtlesim appears. Tests read window.__turtlesim: what was drawn, and pixels.

const SCENE = /^\/_turtlesim(\/.+)\/scene$/;
const TRAILS = (node) => `/_turtlesim${node}/trails`;
// Shell colours of the turtle images (Jazzy chooses one of 11 images at random per turtle).
const SHELLS = ["#6b8e23", "#3c8d5a", "#2e7d8c", "#3b6fb6", "#7b5ea7", "#b35c8a",
  "#c0563b", "#c98a2b", "#8a9a2f", "#4f7f3f", "#5d6d7e"];

// One turtlesim node's picture: its trails as pixels, and what it has drawn into them. Strokes are
// filled pixel by pixel as turtlesim draws them (not anti-aliased), so the trails are the same
// whether they came from a snapshot or were drawn here.
class World {
  constructor(node) {
    this.node = node;
    this.trails = new ImageData(500, 500);
    this.layer = Object.assign(document.createElement("canvas"), { width: 500, height: 500 });
    this.stale = false; // the layer does not show the trails yet
    this.session = null;
    this.snapshot = -1; // the serial of the trails snapshot in the layer
    this.drawn = 0; // strokes drawn into the layer, counted as the node counts them
    this.scene = null;
  }

  reset(session, width = this.trails.width, height = this.trails.height) {
    this.session = session;
    this.snapshot = -1;
    this.drawn = 0;
    this.trails = new ImageData(width, height);
    Object.assign(this.layer, { width, height });
    this.stale = true;
  }

  // A scene: draw the strokes the layer does not have yet. Returns how many were drawn.
  onScene(scene) {
    const [width, height] = scene.size;
    if (scene.session !== this.session || width !== this.trails.width || height !== this.trails.height) {
      this.reset(scene.session, width, height);
    }
    this.scene = scene;
    const count = this.drawStrokes(scene, Math.max(this.drawn, scene.base));
    this.drawn = Math.max(this.drawn, scene.upto);
    return count;
  }

  // A trails snapshot: the trails become it, then the strokes after it are drawn again.
  async onTrails(trails) {
    if (trails.session !== this.session) this.reset(trails.session);
    if (trails.serial <= this.snapshot) return false;
    this.snapshot = trails.serial;
    const image = trails.png ? await loadImage(`data:image/png;base64,${trails.png}`) : null;
    if (trails.serial !== this.snapshot || trails.session !== this.session) return false; // a newer one came meanwhile
    const { width, height } = this.trails;
    if (image) {
      const scratch = Object.assign(document.createElement("canvas"), { width, height });
      const g = scratch.getContext("2d");
      g.drawImage(image, 0, 0);
      this.trails = g.getImageData(0, 0, width, height);
    } else {
      this.trails = new ImageData(width, height);
    }
    this.drawn = trails.upto;
    if (this.scene && this.scene.session === this.session && this.scene.base <= trails.upto) {
      this.drawStrokes(this.scene, trails.upto);
      this.drawn = Math.max(this.drawn, this.scene.upto);
    }
    this.stale = true;
    return true;
  }

  drawStrokes(scene, from) {
    let count = 0;
    for (let i = from; i < scene.upto; i += 1) {
      const stroke = scene.strokes[i - scene.base];
      if (!stroke) continue;
      fillStroke(this.trails, stroke);
      count += 1;
    }
    if (count) this.stale = true;
    return count;
  }

  // The layer to draw: the trails' pixels, copied in when they changed.
  picture() {
    if (this.stale) {
      this.layer.getContext("2d").putImageData(this.trails, 0, 0);
      this.stale = false;
    }
    return this.layer;
  }
}

function loadImage(src) {
  return new Promise((resolve, reject) => {
    const image = new Image();
    image.onload = () => resolve(image);
    image.onerror = () => reject(new Error("a trails snapshot that is not a PNG"));
    image.src = src;
  });
}

// A pen stroke as turtlesim draws it: the pen's width, square ends; every pixel whose centre is
// inside is set to the pen's colour.
function fillStroke(pixels, [x0, y0, x1, y1, r, g, b, width]) {
  const length = Math.hypot(x1 - x0, y1 - y0);
  const [ux, uy] = length > 0 ? [(x1 - x0) / length, (y1 - y0) / length] : [1, 0];
  const half = width / 2;
  const left = Math.max(0, Math.floor(Math.min(x0, x1) - width));
  const right = Math.min(pixels.width - 1, Math.ceil(Math.max(x0, x1) + width));
  const top = Math.max(0, Math.floor(Math.min(y0, y1) - width));
  const bottom = Math.min(pixels.height - 1, Math.ceil(Math.max(y0, y1) + width));
  const data = pixels.data;
  for (let py = top; py <= bottom; py += 1) {
    for (let px = left; px <= right; px += 1) {
      const dx = px + 0.5 - x0;
      const dy = py + 0.5 - y0;
      const along = dx * ux + dy * uy;
      const across = Math.abs(dy * ux - dx * uy);
      if (along < -half || along > length + half || across > half) continue;
      const at = (py * pixels.width + px) * 4;
      data[at] = r;
      data[at + 1] = g;
      data[at + 2] = b;
      data[at + 3] = 255;
    }
  }
}

// A turtle seen from above, heading along +x, about as big as Jazzy's 45-pixel images.
function drawTurtle(g, image) {
  const shell = SHELLS[image % SHELLS.length];
  g.fillStyle = "#9ccc65";
  for (const [x, y] of [[9, 11], [9, -11], [-9, 11], [-9, -11]]) {
    g.beginPath();
    g.ellipse(x, y, 5, 4, 0, 0, 2 * Math.PI);
    g.fill();
  }
  g.beginPath();
  g.moveTo(-14, 0);
  g.lineTo(-20, 2);
  g.lineTo(-20, -2);
  g.fill();
  g.beginPath();
  g.ellipse(17, 0, 6, 5, 0, 0, 2 * Math.PI);
  g.fill();
  g.fillStyle = shell;
  g.strokeStyle = "#1b3b12";
  g.lineWidth = 1.5;
  g.beginPath();
  g.ellipse(0, 0, 15, 12, 0, 0, 2 * Math.PI);
  g.fill();
  g.stroke();
  g.beginPath();
  g.moveTo(-7, -6); g.lineTo(7, -6); g.lineTo(7, 6); g.lineTo(-7, 6); g.closePath();
  g.stroke();
  g.fillStyle = "#000";
  for (const y of [-2.5, 2.5]) {
    g.beginPath();
    g.arc(20, y, 1.2, 0, 2 * Math.PI);
    g.fill();
  }
}

export class TurtlesimPanel {
  // `root`: the panel's element; `appeared()` is called when the first turtlesim appears.
  constructor(ctx, root, appeared = () => {}) {
    this.ctx = ctx;
    this.appeared = appeared;
    this.worlds = new Map(); // node name -> World
    this.wanted = new Set(); // the topics this panel subscribes to (while shown)
    this.current = null;
    this.open = false;
    this.seen = false;
    this.pending = false;
    // node: the one chosen; drawn: the one whose world the last frame drew (null: none yet)
    this.stats = { scenes: 0, snapshots: 0, strokes: 0, frames: 0, node: null, drawn: null, turtles: [], background: null };

    const bar = Object.assign(document.createElement("div"), { className: "panel-bar" });
    this.title = Object.assign(document.createElement("span"), { id: "turtlesim-title", textContent: "no turtlesim runs" });
    this.select = Object.assign(document.createElement("select"), { id: "turtlesim-node", title: "which turtlesim node", hidden: true });
    this.select.addEventListener("change", () => this.choose(this.select.value));
    bar.append(this.title, this.select);
    const stage = Object.assign(document.createElement("div"), { className: "turtlesim-stage" });
    this.canvas = Object.assign(document.createElement("canvas"), { id: "turtlesim-canvas", width: 500, height: 500 });
    this.canvas.setAttribute("aria-label", "the turtlesim world");
    stage.append(this.canvas);
    root.append(bar, stage);

    window.__turtlesim = {
      stats: this.stats,
      // [r, g, b, a] of the picture's pixel (x, y), in the world's pixels (y down)
      pixel: (x, y) => [...this.canvas.getContext("2d").getImageData(x, y, 1, 1).data],
      choose: (node) => this.choose(node),
      nodes: () => [...this.worlds.keys()],
    };
  }

  // The topic list changed: follow the turtlesims that appeared, forget the ones that went.
  topicsChanged(topics) {
    const nodes = new Set();
    for (const { name } of topics) {
      const match = SCENE.exec(name);
      if (match) nodes.add(match[1]);
    }
    for (const node of nodes) if (!this.worlds.has(node)) this.worlds.set(node, new World(node));
    for (const node of [...this.worlds.keys()]) if (!nodes.has(node)) this.worlds.delete(node);
    const names = [...this.worlds.keys()].sort();
    this.select.replaceChildren(...names.map((n) => new Option(n, n)));
    this.select.hidden = names.length < 2;
    if (!this.worlds.has(this.current)) this.current = names[0] || null;
    if (this.current) this.select.value = this.current;
    this.stats.node = this.current;
    this.follow();
    this.requestRender();
    if (names.length && !this.seen) {
      this.seen = true;
      this.appeared();
    }
  }

  // Subscribe to the topics of every turtlesim while the panel is shown, and to none otherwise.
  follow() {
    const wanted = new Set();
    if (this.open) for (const node of this.worlds.keys()) wanted.add(`/_turtlesim${node}/scene`).add(TRAILS(node));
    for (const topic of wanted) if (!this.wanted.has(topic)) this.ctx.conn.want(topic);
    for (const topic of this.wanted) if (!wanted.has(topic)) this.ctx.conn.unwant(topic);
    this.wanted = wanted;
  }

  onMessage(topic, type, msg) {
    if (type !== "std_msgs/msg/String" || !this.wanted.has(topic)) return;
    const scene = SCENE.exec(topic);
    const node = scene ? scene[1] : topic.slice("/_turtlesim".length, -"/trails".length);
    const world = this.worlds.get(node);
    if (!world) return;
    let body;
    try {
      body = JSON.parse(msg.data);
    } catch {
      this.ctx.problem(`turtlesim: ${topic} is not JSON`);
      return;
    }
    if (scene) {
      this.stats.scenes += 1;
      this.stats.strokes += world.onScene(body);
      this.requestRender();
    } else {
      world.onTrails(body).then((applied) => {
        if (applied) this.stats.snapshots += 1;
        this.requestRender();
      }, (error) => this.ctx.problem(`turtlesim: ${error.message}`));
    }
  }

  choose(node) {
    if (!this.worlds.has(node)) return;
    this.current = node;
    this.select.value = node;
    this.stats.node = node;
    this.requestRender();
  }

  show() {
    this.open = true;
    this.follow();
    this.requestRender();
  }

  hide() {
    this.open = false;
    this.follow();
  }

  requestRender() {
    if (this.pending || !this.open) return;
    this.pending = true;
    requestAnimationFrame(() => {
      this.pending = false;
      this.render();
    });
  }

  render() {
    const world = this.worlds.get(this.current);
    const scene = world?.scene;
    const g = this.canvas.getContext("2d");
    this.title.textContent = !world ? "no turtlesim runs" : this.select.hidden ? world.node : "";
    if (!scene) {
      g.fillStyle = "#202124";
      g.fillRect(0, 0, this.canvas.width, this.canvas.height);
      this.stats.drawn = null;
      return;
    }
    const [width, height] = scene.size;
    if (this.canvas.width !== width || this.canvas.height !== height) Object.assign(this.canvas, { width, height });
    const [r, gr, b] = scene.background;
    g.fillStyle = `rgb(${r}, ${gr}, ${b})`;
    g.fillRect(0, 0, width, height);
    g.drawImage(world.picture(), 0, 0);
    const bottom = (height - 1) / scene.meter; // y grows up in the world, down in the picture
    for (const turtle of scene.turtles) {
      g.save();
      g.translate(turtle.x * scene.meter, (bottom - turtle.y) * scene.meter);
      g.rotate(-turtle.theta);
      drawTurtle(g, turtle.image);
      g.restore();
    }
    Object.assign(this.stats, {
      frames: this.stats.frames + 1,
      drawn: world.node,
      turtles: scene.turtles,
      background: scene.background,
    });
  }
}
