// The planner's parameter panel, generated from the registry's field list
// (name, unit, default, doc, kind): a slider plus a number box per numeric
// field, a checkbox per boolean, a text box otherwise. Every edit hands the
// whole config (nested again from the dotted names) to `onChange`; the core
// validates it and names a bad field in its error.

import type { FieldInfo, PlannerInfo } from '../shell/planner-info';

type Value = unknown;

function kindOf(f: FieldInfo): NonNullable<FieldInfo['kind']> {
  if (f.kind) return f.kind;
  switch (typeof f.default) {
    case 'number':
      return Number.isInteger(f.default) ? 'int' : 'float';
    case 'boolean':
      return 'bool';
    case 'string':
      return 'string';
    default:
      return 'json';
  }
}

/** A round number ≥ x (1, 2, 5 × 10^k). */
function niceCeil(x: number): number {
  if (!(x > 0)) return 1;
  const p = 10 ** Math.floor(Math.log10(x));
  for (const m of [1, 2, 2.5, 5, 10]) if (m * p >= x) return m * p;
  return 10 * p;
}

/** Slider [min, max, step] around a default (the box takes any value). */
function sliderRange(d: number, kind: 'int' | 'float'): [number, number, number] {
  if (kind === 'int') {
    const hi = Math.max(10, Math.ceil(Math.abs(d) * 3));
    return [d < 0 ? -hi : d >= 1 ? 1 : 0, hi, 1];
  }
  if (d === 0) return [0, 1, 0.005];
  const hi = niceCeil(Math.abs(d) * 3);
  return d > 0 ? [0, hi, hi / 400] : [-hi, 0, hi / 400];
}

function getDotted(obj: Record<string, Value> | undefined, name: string): Value {
  let v: Value = obj;
  for (const k of name.split('.')) {
    if (v === null || typeof v !== 'object') return undefined;
    v = (v as Record<string, Value>)[k];
  }
  return v;
}

function setDotted(obj: Record<string, Value>, name: string, value: Value): void {
  const keys = name.split('.');
  let o = obj;
  for (const k of keys.slice(0, -1)) {
    if (o[k] === null || typeof o[k] !== 'object') o[k] = {};
    o = o[k] as Record<string, Value>;
  }
  o[keys[keys.length - 1]] = value;
}

function fmt(v: number): string {
  if (!Number.isFinite(v)) return String(v);
  const a = Math.abs(v);
  if (a !== 0 && (a < 1e-3 || a >= 1e5)) return v.toExponential(2);
  return String(Number(v.toPrecision(4)));
}

export class ParamPanel {
  private el: HTMLElement;
  private info: PlannerInfo | null = null;
  private values = new Map<string, Value>();
  private onChange: (config: Record<string, Value>) => void;

  constructor(el: HTMLElement, onChange: (config: Record<string, Value>) => void) {
    this.el = el;
    this.onChange = onChange;
  }

  /** The config as the core reads it (nested objects from dotted names). */
  config(): Record<string, Value> {
    const out: Record<string, Value> = {};
    for (const [k, v] of this.values) setDotted(out, k, v);
    return out;
  }

  /** Builds the controls for `info`, with values from `config` (a scenario's
   *  partial config) over the defaults. */
  show(info: PlannerInfo, config: Record<string, Value> = {}): void {
    this.info = info;
    this.values.clear();
    for (const f of info.fields) {
      const v = getDotted(config, f.name);
      this.values.set(f.name, v === undefined ? f.default : v);
    }
    this.render();
  }

  /** Every field back to its default; reports the change. */
  resetDefaults(): void {
    if (!this.info) return;
    for (const f of this.info.fields) this.values.set(f.name, f.default);
    this.render();
    this.onChange(this.config());
  }

  private render(): void {
    this.el.replaceChildren();
    if (!this.info) return;
    if (!this.info.fields.length) {
      const p = document.createElement('p');
      p.className = 'small muted';
      p.textContent = 'This planner has no parameters.';
      this.el.append(p);
      return;
    }
    let group = '';
    for (const f of this.info.fields) {
      const dot = f.name.lastIndexOf('.');
      const g = dot > 0 ? f.name.slice(0, dot) : '';
      if (g !== group) {
        group = g;
        if (g) {
          const h = document.createElement('div');
          h.className = 'param-group';
          h.textContent = g;
          this.el.append(h);
        }
      }
      this.el.append(this.control(f, dot > 0 ? f.name.slice(dot + 1) : f.name));
    }
  }

  private control(f: FieldInfo, short: string): HTMLElement {
    const kind = kindOf(f);
    const wrap = document.createElement('div');
    wrap.className = 'param';
    wrap.dataset.field = f.name;
    // The plain name on the panel; the config name (and in the doc the
    // paper's symbol) in the tooltip, so a paper's table can still be matched.
    const shown = f.label || short;
    wrap.title = `${f.label ? `${f.label} — ` : ''}${f.name}: ${f.doc}${f.unit ? ` [${f.unit}]` : ''} (paper: ${JSON.stringify(f.default)})`;
    const label = document.createElement('div');
    label.className = 'label';
    const name = document.createElement('b');
    name.textContent = shown;
    name.style.fontWeight = '500';
    const unit = document.createElement('span');
    unit.className = 'unit';
    unit.textContent = f.unit && f.unit !== '1' ? f.unit : '';
    label.append(name, unit);
    const markChanged = () => {
      wrap.dataset.changed = String(JSON.stringify(this.values.get(f.name)) !== JSON.stringify(f.default));
    };
    const id = `param-${f.name.replace(/[^a-zA-Z0-9_-]/g, '-')}`;

    if (kind === 'bool') {
      wrap.classList.add('bool');
      const l = document.createElement('label');
      l.className = 'check';
      const box = document.createElement('input');
      box.type = 'checkbox';
      box.id = id;
      box.checked = this.values.get(f.name) === true;
      box.addEventListener('change', () => {
        this.values.set(f.name, box.checked);
        markChanged();
        this.onChange(this.config());
      });
      box.setAttribute('aria-label', `${shown} (${f.name})`);
      l.append(box, ` ${shown}`);
      wrap.append(l);
      markChanged();
      return wrap;
    }

    wrap.append(label);
    if (kind === 'int' || kind === 'float') {
      const d = typeof f.default === 'number' ? f.default : 0;
      const [min, max, step] = sliderRange(d, kind);
      const range = document.createElement('input');
      range.type = 'range';
      range.min = String(min);
      range.max = String(max);
      range.step = String(step);
      range.setAttribute('aria-label', `${shown} (${f.name}) slider`);
      const box = document.createElement('input');
      box.type = 'number';
      box.id = id;
      box.step = kind === 'int' ? '1' : 'any';
      box.setAttribute('aria-label', `${shown} (${f.name})`);
      const cur = this.values.get(f.name);
      const v = typeof cur === 'number' ? cur : d;
      range.value = String(v);
      box.value = fmt(v);
      range.addEventListener('input', () => {
        const x = Number(range.value);
        box.value = fmt(x);
        this.values.set(f.name, x);
        markChanged();
        this.onChange(this.config());
      });
      box.addEventListener('input', () => {
        // An empty or malformed box sends null; the core names the field.
        const x = box.value.trim() === '' ? Number.NaN : Number(box.value);
        if (Number.isFinite(x)) range.value = String(x);
        this.values.set(f.name, Number.isFinite(x) ? x : null);
        markChanged();
        this.onChange(this.config());
      });
      wrap.append(range, box);
    } else {
      const box = document.createElement('input');
      box.type = 'text';
      box.id = id;
      box.style.gridColumn = '1 / -1';
      const cur = this.values.get(f.name);
      box.value = kind === 'string' && typeof cur === 'string' ? cur : JSON.stringify(cur);
      box.addEventListener('change', () => {
        let v: Value = box.value;
        if (kind === 'json') {
          try {
            v = JSON.parse(box.value);
          } catch {
            v = box.value; // the core refuses it with the field's name
          }
        }
        this.values.set(f.name, v);
        markChanged();
        this.onChange(this.config());
      });
      wrap.append(box);
    }
    markChanged();
    return wrap;
  }
}
