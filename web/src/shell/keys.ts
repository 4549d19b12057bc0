// A page's keyboard shortcuts: a key (lower case; ' ' is Space) runs its
// action unless the user is typing in a field or holds a modifier (those
// shortcuts belong to the browser and the OS).

export function installKeys(actions: Record<string, () => void>): void {
  window.addEventListener('keydown', (ev) => {
    const t = ev.target as HTMLElement | null;
    if (t && (t.tagName === 'INPUT' || t.tagName === 'SELECT' || t.tagName === 'TEXTAREA')) return;
    if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
    const action = actions[ev.key.toLowerCase()];
    if (!action) return;
    // Space would scroll the page as well.
    if (ev.key === ' ') ev.preventDefault();
    action();
  });
}
