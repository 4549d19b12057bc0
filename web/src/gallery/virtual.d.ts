// Build-time copy of assets/gallery.json (see vite.config.ts).
declare module 'virtual:gallery' {
  import type { GalleryEntry } from '../shell/runlink';
  const entries: GalleryEntry[];
  export default entries;
}

// Build-time copy of assets/reproduce-results.jsonl, keyed by id (see vite.config.ts).
declare module 'virtual:reproduce-results' {
  import type { FamilyResult } from './results';
  const results: Record<string, FamilyResult>;
  export default results;
}
