// Files in and out of a page: saving a Blob behind a temporary link, and
// files dropped on an element.

/** Saves `data` as a download named `name`. */
export function download(name: string, data: Blob | string, type = 'application/octet-stream'): void {
  const blob = typeof data === 'string' ? new Blob([data], { type }) : data;
  const url = URL.createObjectURL(blob);
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  a.rel = 'noopener';
  a.style.display = 'none';
  document.body.append(a);
  a.click();
  a.remove();
  // Revoking at once can cancel the download in some browsers.
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}

/** Calls `open` with the files dropped on `el` (highlighted with the class
 *  `dropping` while files are dragged over it). */
export function onFileDrop(el: HTMLElement, open: (files: File[]) => void): void {
  const over = (ev: DragEvent) => {
    if (!ev.dataTransfer?.types.includes('Files')) return;
    ev.preventDefault();
    ev.dataTransfer.dropEffect = 'copy';
    el.classList.add('dropping');
  };
  el.addEventListener('dragenter', over);
  el.addEventListener('dragover', over);
  el.addEventListener('dragleave', () => el.classList.remove('dropping'));
  el.addEventListener('drop', (ev) => {
    el.classList.remove('dropping');
    const picked = Array.from(ev.dataTransfer?.files ?? []);
    if (!picked.length) return;
    ev.preventDefault();
    open(picked);
  });
}
