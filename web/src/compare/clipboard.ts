// Copying text to the clipboard: the async API, or the old way where the
// page has no clipboard permission (e.g. served over plain http); the
// compare page's Copy CSV button.

import type { ErrorBanner } from '../shell/dom';

/** The Copy CSV button: copies `csv()` and says how many rows went. */
export function wireCopyCsv(button: HTMLButtonElement, status: HTMLElement, csv: () => string, guard: ErrorBanner['guard']): void {
  button.addEventListener(
    'click',
    guard(async () => {
      const text = csv();
      await copyText(text);
      status.textContent = `Copied ${text.trim().split('\n').length - 1} rows as CSV.`;
      document.body.dataset.copied = String(Number(document.body.dataset.copied ?? 0) + 1);
    }),
  );
}

export async function copyText(text: string): Promise<void> {
  try {
    await navigator.clipboard.writeText(text);
    return;
  } catch {
    // No clipboard permission: the old way.
  }
  const ta = document.createElement('textarea');
  ta.value = text;
  ta.style.position = 'fixed';
  ta.style.opacity = '0';
  document.body.append(ta);
  ta.select();
  const ok = document.execCommand('copy');
  ta.remove();
  if (!ok) throw new Error('the browser refused to copy to the clipboard');
}
