// The small page plumbing every page shares: element lookup, error text and
// the error banner with its guard, so each page wires them the same way.

/** The element with `id`; a page missing one is a build mistake, so throw. */
export function el<T extends HTMLElement = HTMLElement>(id: string): T {
  const e = document.getElementById(id);
  if (!e) throw new Error(`page is missing #${id}`);
  return e as T;
}

/** A readable message from anything thrown (wasm `JsError`s are `Error`s). */
export function messageOf(e: unknown): string {
  if (e instanceof Error) return e.message;
  if (typeof e === 'string') return e;
  try {
    return JSON.stringify(e);
  } catch {
    return String(e);
  }
}

export interface ErrorBanner {
  showError(text: string): void;
  clearError(): void;
  /** Wraps an event handler so anything it throws (or rejects with) lands
   *  in the banner instead of the console. */
  guard<A extends unknown[]>(fn: (...args: A) => void | Promise<void>): (...args: A) => void;
}

/** The page's error banner (`error`, with `body[data-error]` set while
 *  shown; `onShow` runs after each message shown); also catches uncaught
 *  errors and rejections. */
export function errorBanner(error: HTMLElement, body: HTMLElement, onShow?: () => void): ErrorBanner {
  const showError = (text: string): void => {
    error.textContent = text;
    error.title = text;
    error.hidden = false;
    body.dataset.error = 'true';
    onShow?.();
  };
  const clearError = (): void => {
    error.hidden = true;
    error.textContent = '';
    delete body.dataset.error;
  };
  window.addEventListener('error', (ev) => showError(`Unexpected error: ${messageOf(ev.error ?? ev.message)}`));
  window.addEventListener('unhandledrejection', (ev) => showError(`Unexpected error: ${messageOf(ev.reason)}`));
  const guard =
    <A extends unknown[]>(fn: (...args: A) => void | Promise<void>) =>
    (...args: A): void => {
      try {
        const r = fn(...args);
        if (r instanceof Promise) r.catch((e) => showError(messageOf(e)));
      } catch (e) {
        showError(messageOf(e));
      }
    };
  return { showError, clearError, guard };
}
