// Build-time copy of assets/gallery.json (see vite.config.ts).
declare module 'virtual:gallery' {
  import type { GalleryEntry } from '../shell/runlink';
  const entries: GalleryEntry[];
  export default entries;
}
