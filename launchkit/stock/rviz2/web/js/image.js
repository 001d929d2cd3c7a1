// The image panel: camera topics (sensor_msgs Image and CompressedImage) drawn on a canvas. The
// topic is subscribed only while the panel shows it.

const IMAGE_TYPES = ["sensor_msgs/msg/Image", "sensor_msgs/msg/CompressedImage"];

function toRgba(header, bytes) {
  const { width, height, step, encoding } = header;
  const out = new Uint8ClampedArray(width * height * 4);
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const little = !header.bigendian;
  let channels;
  let order = [0, 1, 2];
  if (encoding === "rgb8" || encoding === "8UC3") channels = 3;
  else if (encoding === "bgr8") { channels = 3; order = [2, 1, 0]; }
  else if (encoding === "rgba8" || encoding === "8UC4") channels = 4;
  else if (encoding === "bgra8") { channels = 4; order = [2, 1, 0]; }
  else if (encoding === "mono8" || encoding === "8UC1") channels = 1;
  else if (encoding === "mono16" || encoding === "16UC1" || encoding === "32FC1") channels = 0;
  else throw new Error(`image encoding ${encoding} is not supported`);
  if (channels > 0) {
    for (let y = 0; y < height; y++) {
      let src = y * step;
      let dst = y * width * 4;
      for (let x = 0; x < width; x++, src += channels, dst += 4) {
        if (channels === 1) {
          out[dst] = out[dst + 1] = out[dst + 2] = bytes[src];
        } else {
          out[dst] = bytes[src + order[0]];
          out[dst + 1] = bytes[src + order[1]];
          out[dst + 2] = bytes[src + order[2]];
        }
        out[dst + 3] = 255;
      }
    }
    return out;
  }
  // depth images: scale the finite range to grey
  const float = encoding === "32FC1";
  const size = float ? 4 : 2;
  const values = new Float32Array(width * height);
  let low = Infinity;
  let high = -Infinity;
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      const at = y * step + x * size;
      const v = float ? view.getFloat32(at, little) : view.getUint16(at, little);
      values[y * width + x] = v;
      if (Number.isFinite(v) && v > 0) { low = Math.min(low, v); high = Math.max(high, v); }
    }
  }
  const span = high > low ? high - low : 1;
  values.forEach((v, i) => {
    const grey = Number.isFinite(v) && v > 0 ? 255 * (1 - (v - low) / span) : 0;
    out[i * 4] = out[i * 4 + 1] = out[i * 4 + 2] = grey;
    out[i * 4 + 3] = 255;
  });
  return out;
}

export class ImagePanel {
  constructor(ctx, panel, select, canvas, rateLabel) {
    this.ctx = ctx;
    this.panel = panel;
    this.select = select;
    this.canvas = canvas;
    this.rateLabel = rateLabel;
    this.topic = null; // the topic shown (subscribed) now
    this.configured = []; // Image displays of the config: [{topic, enabled}]
    this.known = [];
    this.times = [];
    select.addEventListener("change", () => this.show(select.value || null));
  }

  // The config's Image and Camera displays; the first enabled one is shown.
  configure(displays) {
    this.configured = displays.filter((d) => d.class === "Image" || d.class === "Camera");
    const first = this.configured.find((d) => d.enabled && d.topic);
    this.refreshChoices();
    this.show(first ? first.topic : null);
  }

  topicsChanged(topics) {
    this.known = topics.filter((t) => IMAGE_TYPES.includes(t.type)).map((t) => t.name);
    this.refreshChoices();
  }

  refreshChoices() {
    const choices = [...new Set([...this.configured.map((d) => d.topic).filter(Boolean), ...this.known])];
    this.panel.hidden = choices.length === 0;
    const current = this.topic || "";
    this.select.replaceChildren(new Option("(none)", ""), ...choices.map((t) => new Option(t, t)));
    this.select.value = current;
  }

  // Show `topic` (null: none); only the shown topic is subscribed.
  show(topic) {
    if (topic === this.topic) return;
    if (this.topic) this.ctx.conn.unwant(this.topic);
    this.topic = topic;
    this.times = [];
    this.ctx.stats.imageTopic = topic;
    this.ctx.stats.imageFps = 0;
    if (topic) this.ctx.conn.want(topic);
    this.select.value = topic || "";
    this.rateLabel.textContent = "";
    this.canvas.hidden = !topic;
  }

  async onImage(header, bytes) {
    if (header.topic !== this.topic) return;
    const started = performance.now();
    try {
      if (header.format !== undefined) {
        const type = header.format.includes("png") ? "image/png" : "image/jpeg";
        const bitmap = await createImageBitmap(new Blob([bytes], { type }));
        this.canvas.width = bitmap.width;
        this.canvas.height = bitmap.height;
        this.canvas.getContext("2d").drawImage(bitmap, 0, 0);
      } else {
        const rgba = toRgba(header, bytes);
        this.canvas.width = header.width;
        this.canvas.height = header.height;
        this.canvas.getContext("2d").putImageData(new ImageData(rgba, header.width, header.height), 0, 0);
      }
    } catch (error) {
      this.ctx.problem(`Image ${header.topic}: ${error.message}`);
      return;
    }
    const now = performance.now();
    this.ctx.stats.imageDrawMs = Math.round((now - started) * 10) / 10;
    this.times.push(now);
    while (this.times.length && now - this.times[0] > 2000) this.times.shift();
    const fps = this.times.length > 1 ? ((this.times.length - 1) * 1000) / (now - this.times[0]) : 0;
    this.ctx.stats.imageFrames += 1;
    this.ctx.stats.imageFps = Math.round(fps * 10) / 10;
    this.rateLabel.textContent = `${this.ctx.stats.imageFps} fps`;
  }
}
