// The console panel (rqt_console): the log lines every node sends on /rosout
// (rcl_interfaces/msg/Log), newest last, with filters by severity, by node and by text, and a
// pause that holds new lines back (they are shown on resume). /rosout is subscribed while the
// panel is open; publishers that keep their last lines (transient local) send the last 10 again.

const LEVELS = [
  // [level, name] as rcl_interfaces/msg/Log's constants
  [10, "Debug"], [20, "Info"], [30, "Warn"], [40, "Error"], [50, "Fatal"],
];
const KEEP = 20000; // lines kept, as rqt_console's default limit
const SHOWN = 2000; // rows in the table at most (the newest matching ones)

function levelName(level) {
  let name = "Unknown";
  for (const [value, label] of LEVELS) if (level >= value) name = label;
  return name;
}

function clock(stamp) {
  const date = new Date(stamp * 1000);
  return `${date.toTimeString().slice(0, 8)}.${String(date.getMilliseconds()).padStart(3, "0")}`;
}

export class ConsolePanel {
  constructor(ctx, root, topic = "/rosout") {
    this.ctx = ctx;
    this.topic = topic;
    this.lines = []; // {n, stamp, level, name, msg, file, function, line}
    this.held = []; // lines received while paused
    this.count = 0;
    this.paused = false;
    this.levels = new Set(LEVELS.map(([value]) => value));
    this.node = "";
    this.search = "";
    this.open = false;

    const bar = document.createElement("div");
    bar.className = "panel-bar";
    for (const [value, label] of LEVELS) {
      const box = Object.assign(document.createElement("input"), { type: "checkbox", checked: true });
      box.dataset.level = String(value);
      box.addEventListener("change", () => {
        if (box.checked) this.levels.add(value);
        else this.levels.delete(value);
        this.renderAll();
      });
      const wrap = document.createElement("label");
      wrap.className = `sev-${label.toLowerCase()}`;
      wrap.append(box, ` ${label}`);
      bar.append(wrap);
    }
    this.nodeSelect = Object.assign(document.createElement("select"), { id: "console-node", title: "only this node's lines" });
    this.nodeSelect.append(new Option("all nodes", ""));
    this.nodeSelect.addEventListener("change", () => { this.node = this.nodeSelect.value; this.renderAll(); });
    this.searchBox = Object.assign(document.createElement("input"), { type: "search", id: "console-search", placeholder: "search messages" });
    this.searchBox.addEventListener("input", () => { this.search = this.searchBox.value.toLowerCase(); this.renderAll(); });
    this.pauseButton = Object.assign(document.createElement("button"), { id: "console-pause", textContent: "Pause" });
    this.pauseButton.addEventListener("click", () => this.setPaused(!this.paused));
    const clear = Object.assign(document.createElement("button"), { id: "console-clear", textContent: "Clear" });
    clear.addEventListener("click", () => { this.lines = []; this.held = []; this.renderAll(); });
    this.status = Object.assign(document.createElement("span"), { className: "muted", id: "console-status" });
    bar.append(this.nodeSelect, this.searchBox, this.pauseButton, clear, this.status);

    const scroller = document.createElement("div");
    scroller.className = "table-scroll";
    this.table = document.createElement("table");
    this.table.id = "console-table";
    this.table.className = "log-table";
    this.table.createTHead().insertRow().append(
      ...["#", "Severity", "Node", "Stamp", "Message", "Location"].map((t) => Object.assign(document.createElement("th"), { textContent: t })),
    );
    this.body = this.table.createTBody();
    scroller.append(this.table);
    this.scroller = scroller;
    root.append(bar, scroller);
    ctx.conn.on("msg", (message) => {
      if (message.topic === this.topic && message.type === "rcl_interfaces/msg/Log") this.receive(message.msg);
    });
  }

  show() {
    if (this.open) return;
    this.open = true;
    this.ctx.conn.want(this.topic);
    this.renderAll();
  }

  hide() {
    if (!this.open) return;
    this.open = false;
    this.ctx.conn.unwant(this.topic);
  }

  setPaused(paused) {
    this.paused = paused;
    this.pauseButton.textContent = paused ? "Resume" : "Pause";
    this.pauseButton.classList.toggle("active", paused);
    if (!paused) {
      const held = this.held;
      this.held = [];
      for (const line of held) this.add(line);
      this.renderAll();
    }
    this.showStatus();
  }

  receive(log) {
    this.count += 1;
    const line = { n: this.count, ...log };
    if (this.paused) {
      this.held.push(line);
      this.showStatus();
      return;
    }
    this.add(line);
    if (this.matches(line)) {
      this.body.append(this.row(line));
      while (this.body.rows.length > SHOWN) this.body.deleteRow(0);
      this.scroller.scrollTop = this.scroller.scrollHeight;
    }
    this.showStatus();
  }

  add(line) {
    this.lines.push(line);
    if (this.lines.length > KEEP) this.lines.splice(0, this.lines.length - KEEP);
    if (![...this.nodeSelect.options].some((o) => o.value === line.name)) {
      const names = [...new Set([...[...this.nodeSelect.options].slice(1).map((o) => o.value), line.name])].sort();
      const current = this.nodeSelect.value;
      this.nodeSelect.replaceChildren(new Option("all nodes", ""), ...names.map((n) => new Option(n, n)));
      this.nodeSelect.value = current;
    }
  }

  matches(line) {
    let level = 0;
    for (const [value] of LEVELS) if (line.level >= value) level = value;
    if (!this.levels.has(level)) return false;
    if (this.node && line.name !== this.node) return false;
    return !this.search || line.msg.toLowerCase().includes(this.search);
  }

  row(line) {
    const row = document.createElement("tr");
    const level = levelName(line.level);
    row.className = `sev-${level.toLowerCase()}`;
    row.dataset.level = String(line.level);
    const cells = [line.n, level, line.name, clock(line.stamp), line.msg, `${line.file}:${line.function}:${line.line}`];
    for (const text of cells) row.insertCell().textContent = String(text);
    row.cells[4].title = line.msg;
    return row;
  }

  renderAll() {
    if (!this.open) return;
    const shown = this.lines.filter((line) => this.matches(line)).slice(-SHOWN);
    this.body.replaceChildren(...shown.map((line) => this.row(line)));
    this.scroller.scrollTop = this.scroller.scrollHeight;
    this.showStatus();
  }

  showStatus() {
    const held = this.paused ? ` · paused, ${this.held.length} new held back` : "";
    this.status.textContent = `${this.body.rows.length} of ${this.lines.length} lines shown${held}`;
  }
}
