// The compare page's DOM read-outs: a lane (head and canvas) per planner,
// the lane heads and overlay legend (time and outcome), and the metrics
// table with the winner of each row marked. Everything shown comes from
// the lanes' SimHandles (table.ts formats the `planlab run` metrics).

import { RobotView, type MapInfo } from '../scene/view';
import { LANE_COLOURS, type Lane } from './lane';
import { ROWS, cellText, tableCsv, winners } from './table';
import { describeOutcome, shortOutcome } from '../shell/outcome';

import { hexHash } from '../shell/hash';

export { hexHash };

/** The outcome in words (`speed`: the robot's at the end, m/s). */
export function describe(o: string, speed = 0): string {
  return o === 'reached' ? 'reached the goal' : describeOutcome(o, speed);
}

/** A swatch of a lane's colour. */
function swatch(colour: string, className = 'lane-swatch'): HTMLElement {
  const sw = document.createElement('i');
  sw.className = className;
  sw.style.background = colour;
  return sw;
}

/** A head and a canvas per lane in `root`; returns a view on each, showing
 *  its lane's scene on `map`. */
export function buildLanes(root: HTMLElement, lanes: Lane[], map: MapInfo | null, showPath: boolean): RobotView[] {
  const nodes = lanes.map((lane, i) => {
    const box = document.createElement('div');
    box.className = 'lane';
    box.dataset.planner = lane.name;
    box.style.setProperty('--lane', lane.colour);
    const head = document.createElement('div');
    head.className = 'lane-head';
    const sw = document.createElement('i');
    sw.className = 'lane-swatch';
    const name = document.createElement('b');
    name.textContent = lane.name;
    const state = document.createElement('span');
    state.className = 'lane-state';
    head.append(sw, name, state);
    const wrap = document.createElement('div');
    wrap.className = 'canvas-wrap';
    const canvas = document.createElement('canvas');
    canvas.className = 'lane-canvas';
    canvas.id = `lane-canvas-${i}`;
    canvas.setAttribute('aria-label', `${lane.name} on the scenario`);
    wrap.append(canvas);
    box.append(head, wrap);
    return box;
  });
  root.replaceChildren(...nodes);
  root.dataset.count = String(lanes.length);
  return lanes.map((lane, i) => {
    const v = new RobotView(nodes[i].querySelector('canvas') as HTMLCanvasElement);
    v.scene = lane.scene;
    lane.scene.show.path = showPath;
    lane.scene.show.fog = false;
    if (map) v.setMap(map);
    return v;
  });
}

/** Each lane's head (time, or outcome and time) and the overlay legend. */
export function renderHeads(root: HTMLElement, legend: HTMLElement, lanes: Lane[]): void {
  lanes.forEach((l, i) => {
    const head = root.children[i]?.querySelector('.lane-state');
    if (head) {
      const v = l.running ? 0 : l.sim.state()[3];
      head.textContent = l.running ? `t = ${l.sim.time.toFixed(1)} s` : `${shortOutcome(l.outcome, v)} · ${l.sim.time.toFixed(1)} s`;
      (head as HTMLElement).title = l.running ? 'running' : describe(l.outcome, v);
      (head as HTMLElement).dataset.outcome = l.outcome;
      (head as HTMLElement).dataset.fanColour = l.fanColour;
      if (l.fanColour !== 'total score') head.textContent += ` · fan: ${l.fanColour}`;
    }
  });
  const items = lanes.map((l) => {
    const li = document.createElement('li');
    li.dataset.planner = l.name;
    const t = document.createElement('span');
    t.textContent = `${l.name}${l.running ? '' : ` · ${shortOutcome(l.outcome, l.sim.state()[3])}`}`;
    li.append(swatch(l.colour, ''), t);
    return li;
  });
  legend.replaceChildren(...items);
}

/** The metrics table; winners are marked once `final`. */
export function renderTable(table: HTMLTableElement, lanes: Lane[], final: boolean): void {
  const ms = lanes.map((l) => l.updateMetrics());
  const headRow = document.createElement('tr');
  const corner = document.createElement('th');
  corner.scope = 'col';
  corner.textContent = 'Metric';
  headRow.append(corner);
  for (const l of lanes) {
    const th = document.createElement('th');
    th.scope = 'col';
    th.dataset.planner = l.name;
    th.append(swatch(l.colour), document.createTextNode(l.name));
    headRow.append(th);
  }
  table.tHead?.replaceChildren(headRow);
  const rows: HTMLTableRowElement[] = [];
  const row = (key: string, label: string, title?: string, extra = false) => {
    const tr = document.createElement('tr');
    tr.dataset.metric = key;
    if (extra) tr.className = 'extra';
    const th = document.createElement('th');
    th.scope = 'row';
    th.textContent = label;
    if (title !== undefined) th.title = title;
    tr.append(th);
    rows.push(tr);
    return tr;
  };
  if (lanes.length) {
    for (const r of ROWS) {
      const tr = row(r.key, r.unit ? `${r.label} (${r.unit})` : r.label, r.doc);
      const win = final ? new Set(winners(r, ms)) : new Set<number>();
      ms.forEach((m, i) => {
        const td = document.createElement('td');
        td.dataset.planner = lanes[i].name;
        const v = m[r.key];
        td.dataset.value = v === null ? '' : String(v);
        if (r.key === 'outcome') td.dataset.outcome = m.outcome;
        td.textContent = cellText(r, m);
        if (win.has(i)) {
          td.dataset.win = 'true';
          td.title = 'best in this row';
        }
        tr.append(td);
      });
    }
    const extra: [string, string, (l: Lane) => string][] = [
      ['steps', 'steps', (l) => String(l.sim.steps)],
      ['trace_hash', 'trace hash', (l) => (l.hash ? hexHash(l.hash) : '—')],
    ];
    for (const [key, label, f] of extra) {
      const tr = row(key, label, undefined, true);
      for (const l of lanes) {
        const td = document.createElement('td');
        td.dataset.planner = l.name;
        td.textContent = f(l);
        td.dataset.value = td.textContent;
        tr.append(td);
      }
    }
  }
  table.tBodies[0].replaceChildren(...rows);
  table.dataset.final = String(final);
}

/** The picked planners' colours, in pick order. */
export function laneColour(chosen: string[], name: string): string {
  return LANE_COLOURS[chosen.indexOf(name) % LANE_COLOURS.length];
}

/** The table as CSV (the copy button's), final once `done`. */
export function lanesCsv(lanes: Lane[], done: boolean): string {
  const ms = lanes.map((l) => l.updateMetrics());
  const extra = { steps: lanes.map((l) => l.sim.steps), hashes: lanes.map((l) => hexHash(l.hash)) };
  return tableCsv(
    lanes.map((l) => l.name),
    ms,
    extra,
    done,
  );
}
