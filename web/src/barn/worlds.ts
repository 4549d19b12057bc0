// The BARN worlds the site serves (assets/barn/worlds.txt, fetched as
// ./barn/worlds.txt) as the page lists them: id, difficulty class, optimal
// time and cylinder count, all computed by the core (`barnWorlds`).

import { barnWorlds } from '../../pkg/planlab_wasm.js';

/** Where the build puts the worlds file (vite's public dir is assets/). */
export const WORLDS_URL = './barn/worlds.txt';

export interface WorldInfo {
  id: number;
  difficulty: 'easy' | 'medium' | 'hard';
  /** OT: the reference path's length at 2 m/s, s. */
  optimal_time: number;
  cylinders: number;
}

export class Worlds {
  readonly text: string;
  readonly list: WorldInfo[];
  private readonly byId: Map<number, WorldInfo>;

  constructor(text: string) {
    this.text = text;
    this.list = JSON.parse(barnWorlds(text)) as WorldInfo[];
    this.byId = new Map(this.list.map((w) => [w.id, w]));
  }

  static async fetch(): Promise<Worlds> {
    const r = await fetch(WORLDS_URL);
    if (!r.ok) throw new Error(`${WORLDS_URL}: HTTP ${r.status}`);
    return new Worlds(await r.text());
  }

  get(id: number): WorldInfo | undefined {
    return this.byId.get(id);
  }

  /** The worlds of class `difficulty` ('' for every class). */
  of(difficulty: string): WorldInfo[] {
    return difficulty ? this.list.filter((w) => w.difficulty === difficulty) : this.list;
  }

  /** The first world of the class after `id` (wrapping round). */
  next(id: number, difficulty: string): WorldInfo {
    const l = this.of(difficulty);
    return l.find((w) => w.id > id) ?? l[0];
  }

  /** A random world of the class (page-side randomness: the run itself is
   *  seeded by the Seed field). */
  random(difficulty: string): WorldInfo {
    const l = this.of(difficulty);
    return l[Math.floor(Math.random() * l.length)];
  }
}
