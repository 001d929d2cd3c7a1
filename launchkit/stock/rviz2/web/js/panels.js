// The tab bar over the main area: the 3D view, or one of the rqt tools as a panel (node graph,
// console, plot, parameters, service caller, topic publisher, TF tree). One is shown at a time;
// a panel is told when it is shown and hidden, and subscribes only while shown. The address's
// #name (#graph, #console, ...) opens a panel directly.

export class PanelTabs {
  // `panels`: [{name, title, element, panel}] where panel has show() and hide() (none for 3D).
  constructor(nav, panels, onChange = () => {}) {
    this.panels = panels;
    this.onChange = onChange;
    this.current = null;
    for (const entry of panels) {
      const button = Object.assign(document.createElement("button"), { textContent: entry.title, role: "tab" });
      button.dataset.panel = entry.name;
      button.addEventListener("click", () => this.select(entry.name, true));
      entry.button = button;
      nav.append(button);
    }
    window.addEventListener("hashchange", () => this.fromAddress());
    if (!this.fromAddress()) this.select(panels[0].name);
  }

  fromAddress() {
    const name = decodeURIComponent(location.hash.slice(1));
    if (!this.panels.some((p) => p.name === name)) return false;
    this.select(name);
    return true;
  }

  select(name, remember = false) {
    if (name === this.current) return;
    const previous = this.panels.find((p) => p.name === this.current);
    if (previous?.panel) previous.panel.hide();
    this.current = name;
    for (const entry of this.panels) {
      const shown = entry.name === name;
      entry.element.hidden = !shown;
      entry.button.classList.toggle("active", shown);
      entry.button.setAttribute("aria-selected", String(shown));
    }
    const entry = this.panels.find((p) => p.name === name);
    if (entry.panel) entry.panel.show();
    if (remember) history.replaceState(null, "", `#${name}`);
    this.onChange(name);
  }
}
