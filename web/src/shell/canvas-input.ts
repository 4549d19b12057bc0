// Canvas pan and zoom, the same on every map page: the wheel zooms about
// the pointer, a right, middle or Alt+left drag pans, the context menu
// stays shut. One gesture can move several views (the compare page keeps
// its planners' views together).

/** What a gesture moves. */
export interface Zoomable {
  zoomAt(x: number, y: number, factor: number): void;
  panBy(dx: number, dy: number): void;
}

/** Whether a press starts a pan rather than a tool's gesture. */
export function isPanPress(ev: PointerEvent): boolean {
  return ev.button === 1 || ev.button === 2 || (ev.button === 0 && ev.altKey);
}

/**
 * Pan and zoom on the canvases under `root` (a canvas, or an element
 * holding several): `views(canvas)` says which views a gesture on that
 * canvas moves (null: not one of ours); `after` runs after each move.
 * Install it before the page's own pointer handlers: a pan's pointer
 * events go no further.
 */
export function panZoom(root: HTMLElement, views: (canvas: HTMLCanvasElement) => Zoomable[] | null, after?: () => void): void {
  const canvasOf = (ev: Event): HTMLCanvasElement | null => {
    const t = ev.target;
    return t instanceof HTMLCanvasElement && views(t) ? t : null;
  };
  let from: { x: number; y: number; canvas: HTMLCanvasElement } | null = null;
  root.addEventListener('pointerdown', (ev) => {
    const canvas = canvasOf(ev);
    if (!canvas || !isPanPress(ev)) return;
    from = { x: ev.clientX, y: ev.clientY, canvas };
    canvas.classList.add('panning');
    canvas.setPointerCapture(ev.pointerId);
    ev.preventDefault();
    ev.stopImmediatePropagation();
  });
  root.addEventListener('pointermove', (ev) => {
    if (!from) return;
    for (const v of views(from.canvas) ?? []) v.panBy(ev.clientX - from.x, ev.clientY - from.y);
    from.x = ev.clientX;
    from.y = ev.clientY;
    after?.();
    ev.stopImmediatePropagation();
  });
  const end = (ev: PointerEvent) => {
    if (!from) return;
    from.canvas.classList.remove('panning');
    if (from.canvas.hasPointerCapture(ev.pointerId)) from.canvas.releasePointerCapture(ev.pointerId);
    from = null;
  };
  root.addEventListener('pointerup', end);
  root.addEventListener('pointercancel', end);
  root.addEventListener('contextmenu', (ev) => {
    if (canvasOf(ev)) ev.preventDefault();
  });
  root.addEventListener(
    'wheel',
    (ev) => {
      const canvas = canvasOf(ev);
      if (!canvas) return;
      ev.preventDefault();
      const r = canvas.getBoundingClientRect();
      const f = Math.exp(-ev.deltaY * 0.0015);
      for (const v of views(canvas) ?? []) v.zoomAt(ev.clientX - r.left, ev.clientY - r.top, f);
      after?.();
    },
    { passive: false },
  );
}
