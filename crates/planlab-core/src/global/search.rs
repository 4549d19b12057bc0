//! Search machinery shared by the fast grid planners ([`super::astar`],
//! [`super::jps`]): fixed-point move costs, a reusable generation-stamped
//! search space, the open list, and the bit-packed lines JPS scans.
//!
//! Costs are integers in units of `1 / STRAIGHT` cell. `DIAG / STRAIGHT` is a
//! convergent of √2 (error 1.6·10⁻¹²), so ties between paths are exact and
//! the integer optimum is the real optimum for any path with fewer than
//! ~400 000 diagonal moves; the reported [`super::Path::cost`] is recomputed
//! in `f64` from the move counts.

use super::{GridPos, Heuristic, Path, PlanError, PlanGrid};
use std::cell::RefCell;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Cost of a straight move, in fixed-point units.
pub(crate) const STRAIGHT: u64 = 470_832;
/// Cost of a diagonal move: round(√2 · STRAIGHT), a convergent of √2.
pub(crate) const DIAG: u64 = 665_857;

/// A cell's search word: `tag (13 bits) | OPEN | g (47 bits) | dir (3 bits)`.
/// The generation tag sits on top so words of earlier searches compare
/// greater than any word of the current one.
const TAG_SHIFT: u32 = 51;
/// Largest generation tag; a fresh word (`u64::MAX`) carries it.
const MAX_TAG: u64 = (1 << (64 - TAG_SHIFT)) - 1;
/// Set while a cell is open (generated, not yet expanded) in the current
/// search; cleared when it is closed.
pub(crate) const OPEN: u64 = 1 << 50;
/// Shift of `g` in a search word.
pub(crate) const G_SHIFT: u32 = 3;
/// Mask of `g` once shifted down.
pub(crate) const G_MASK: u64 = (1 << 47) - 1;
/// Mask of the arrival direction (an index into [`DIRS`]).
pub(crate) const DIR_MASK: u64 = 0b111;
/// The largest padded grid the planners accept: any path then costs less
/// than 2⁴⁷ units (2·10⁸ cells × [`DIAG`] < 2⁴⁷).
pub(crate) const MAX_PADDED_CELLS: usize = 200_000_000;

/// The eight moves `(dx, dy)`, indexed by the direction stored in a search
/// word: straight ones first.
pub(crate) const DIRS: [(isize, isize); 8] = [
    (1, 0),
    (-1, 0),
    (0, 1),
    (0, -1),
    (1, 1),
    (1, -1),
    (-1, 1),
    (-1, -1),
];

/// For each arrival direction (index in [`DIRS`]), the neighbour bits of the
/// five moves that can improve a neighbour: all but the move back to the
/// parent and the two moves beside it. The parent is closed. Each of the
/// two cells beside it is one straight move from the parent, which relaxed
/// it when it was expanded, for less than the path through this cell (a
/// straight move costs less than a diagonal one, and the parent less than
/// this cell, on any weights). Leaving out relaxations that cannot succeed
/// changes nothing the search does (tested trace for trace), and saves
/// three of the eight on most expansions. Not for the start, which has no
/// parent.
pub(crate) const AHEAD: [u8; 8] = {
    let mut out = [0xFF; 8];
    let mut d = 0;
    while d < 8 {
        let (bx, by) = (-DIRS[d].0, -DIRS[d].1);
        let mut o = 0;
        while o < 8 {
            // The parent's offset, and the two moves one step from it.
            if (DIRS[o].0 - bx).abs() + (DIRS[o].1 - by).abs() <= 1 {
                out[d] &= !(1 << o);
            }
            o += 1;
        }
        d += 1;
    }
    out
};

/// Padded-index offset of each move in [`DIRS`].
fn dir_offset(k: usize, stride: usize) -> isize {
    DIRS.get(k).map_or(0, |&(dx, dy)| dy * stride as isize + dx)
}

/// For each padded cell, bit `k` set when the cell one move [`DIRS`]`[k]`
/// away is passable (the border's own bits stay 0: no search expands it).
pub(crate) fn neighbour_bits(free: &[bool], stride: usize) -> Vec<u8> {
    let n = free.len();
    let mut out = vec![0u8; n];
    if n < 2 * stride + 2 {
        return out;
    }
    // Cells stride + 1 .. n − stride − 1 have all eight neighbours in
    // range; one pass per direction over shifted slices, which the compiler
    // vectorises.
    let (lo, hi) = (stride + 1, n - stride - 1);
    for k in 0..DIRS.len() {
        let off = dir_offset(k, stride);
        let from = lo.wrapping_add_signed(off);
        let Some(src) = free.get(from..from + (hi - lo)) else {
            continue;
        };
        if let Some(dst) = out.get_mut(lo..hi) {
            for (d, &f) in dst.iter_mut().zip(src) {
                *d |= u8::from(f) << k;
            }
        }
    }
    out
}

/// Updates the neighbour bits around padded cell `i` after it became
/// passable (`free`) or blocked.
pub(crate) fn set_neighbour_bit(bits: &mut [u8], i: usize, stride: usize, free: bool) {
    for (k, &(dx, dy)) in DIRS.iter().enumerate() {
        // The cell one move `k` away sees `i` one move back.
        let back = dir_index(-dx, -dy);
        let j = i.wrapping_add_signed(dir_offset(k, stride));
        if let Some(b) = bits.get_mut(j) {
            if free {
                *b |= 1 << back;
            } else {
                *b &= !(1 << back);
            }
        }
    }
}

/// The passability of the four straight neighbours `[n, s, w, e]` in a
/// cell's neighbour bits.
#[inline(always)]
pub(crate) fn straight_free(nb: u8) -> [bool; 4] {
    let bit = |dx, dy| nb & 1 << dir_index(dx, dy) != 0;
    [bit(0, -1), bit(0, 1), bit(-1, 0), bit(1, 0)]
}

/// Index in [`DIRS`] of the move `(dx, dy)` (each −1, 0 or 1, not both 0).
#[inline(always)]
pub(crate) const fn dir_index(dx: isize, dy: isize) -> u64 {
    // Straight moves by arithmetic: the scans call this with run-time
    // directions, where the match compiled to a chain of branches.
    if dx == 0 {
        return 2 + (dy < 0) as u64;
    }
    if dy == 0 {
        return (dx < 0) as u64;
    }
    match (dx, dy) {
        (1, 0) => 0,
        (-1, 0) => 1,
        (0, 1) => 2,
        (0, -1) => 3,
        (1, 1) => 4,
        (1, -1) => 5,
        (-1, 1) => 6,
        _ => 7,
    }
}

/// The open list: pops the entry of smallest `f`, ties to the largest `g`
/// (the deepest node, which keeps A* from fanning out over equal-cost
/// regions). Entries are never decreased in place; a cell pushed twice
/// leaves a stale entry that the planners skip (lazy deletion).
pub(crate) trait OpenList {
    /// Adds cell `idx` with priority `f` and cost `g`.
    fn push(&mut self, f: u64, g: u64, idx: usize);
    /// Removes the best entry's cell.
    fn pop(&mut self) -> Option<usize>;
    /// The smallest `f` in the list (stale entries included, so a lower
    /// bound on the best live entry's), `None` when it is empty.
    fn min_key(&mut self) -> Option<u64>;
    /// Empties the list, keeping its allocations.
    fn clear(&mut self);
}

/// Tie-break payload: `g >> 16` (ample precision for ordering ties) above
/// the cell index, so a max-order on the `u64` prefers larger `g`.
#[inline(always)]
fn payload(g: u64, idx: usize) -> u64 {
    (g >> 16).min(u32::MAX as u64) << 32 | idx as u64 & 0xFFFF_FFFF
}

/// A binary heap keyed by `(f, g)` packed in one `u128`, for any priorities.
#[derive(Debug, Default)]
pub(crate) struct BinaryQueue(BinaryHeap<u128>);

impl OpenList for BinaryQueue {
    #[inline(always)]
    fn push(&mut self, f: u64, g: u64, idx: usize) {
        // Max-heap: invert f so the smallest f is the largest key.
        self.0.push(((!f as u128) << 64) | payload(g, idx) as u128);
    }

    #[inline(always)]
    fn pop(&mut self) -> Option<usize> {
        self.0.pop().map(|k| (k as u32) as usize)
    }

    #[inline(always)]
    fn min_key(&mut self) -> Option<u64> {
        self.0.peek().map(|&k| !((k >> 64) as u64))
    }

    fn clear(&mut self) {
        self.0.clear();
    }
}

/// Buckets in [`BucketQueue`]'s ring (a power of two).
const RING: usize = 256;

/// An open list for searches whose popped `f` never decreases — A* with a
/// consistent heuristic and weight 1, Dijkstra, JPS, bidirectional A*'s
/// average-potential keys. It pops the smallest `f`, and among equal `f`
/// the entry pushed last (usually the deepest).
///
/// A consistent heuristic bounds how far above the last popped `f` a new
/// entry can land (twice the dearest move for A*: the queue's *span*). The
/// entries within that window sit in a ring of buckets of `2^shift` fixed-
/// point units each, so a push is an append and a pop walks to the next
/// occupied bucket. The distinct `f` values of an A* open list on the
/// Moving AI maps lie thousands of units apart (random512-10-0: 99.8 % of
/// the gaps ≥ 2¹⁴) while the span is ~1.3·10⁶ units, so a bucket of 2¹³
/// units nearly always holds a single `f` and is handed to the
/// top stack whole; one holding several is split, keeping push order. This
/// replaced a radix heap (Ahuja et al. 1990) that moved an entry between
/// buckets 1.6–2.7 times on average. Entries beyond the window (long JPS
/// jumps, a too small span) wait in a binary heap and join the ring, in
/// push order, once the window reaches them.
#[derive(Debug)]
pub(crate) struct BucketQueue {
    /// `f` of the last entry taken out of the buckets.
    last: u64,
    /// Bucket width, log2 (fixed-point units, at most 32).
    shift: u32,
    /// Entries with `f == last` (or, were the heuristic inconsistent,
    /// below it), packed by [`pack`], the next one last.
    top: Vec<u64>,
    /// Bucket `(f >> shift) mod RING` holds the entries of `f` above `last`
    /// with `(f >> shift) − (last >> shift) < RING`, in push order, packed
    /// by [`pack`]: a bucket's entries share every bit of `f` from `shift`
    /// up, so the low 32 bits order them and the bucket's place restores
    /// the rest (one `u64` an entry instead of two).
    ring: Box<[Vec<u64>; RING]>,
    /// Bit `k` set when ring bucket `k` is not empty: the walk to the next
    /// occupied bucket and [`BucketQueue::clear`] read four words instead
    /// of 256 bucket lengths (small searches, such as JPS's few jump points
    /// or a query across a 49 × 49 map, spent a fifth of their time there).
    occupied: [u64; RING / 64],
    /// Entries beyond the ring's window: `(f, push number, cell)`.
    far: BinaryHeap<Reverse<(u64, u64, u64)>>,
    /// Pushes to `far` so far, which orders equal `f` there.
    far_pushes: u64,
}

/// A ring or top entry of [`BucketQueue`]: `f`'s low 32 bits above the cell.
#[inline(always)]
fn pack(f: u64, idx: u64) -> u64 {
    f << 32 | idx & 0xFFFF_FFFF
}

impl Default for BucketQueue {
    fn default() -> Self {
        Self {
            last: 0,
            shift: Self::shift_for(DEFAULT_SPAN),
            top: Vec::new(),
            ring: Box::new(std::array::from_fn(|_| Vec::new())),
            occupied: [0; RING / 64],
            far: BinaryHeap::new(),
            far_pushes: 0,
        }
    }
}

/// The span of A* on a unit grid: `f` grows by at most twice the dearest
/// move (the move's cost plus the estimate's change, which is no larger).
pub(crate) const DEFAULT_SPAN: u64 = 2 * DIAG;

impl BucketQueue {
    /// The smallest bucket width (log2) whose ring covers `span` units;
    /// never below 2¹⁰ units, which keeps the ring walk short, nor above
    /// 2³² (a packed entry keeps 32 bits of `f`; a larger span would only
    /// send more entries through the overflow heap).
    fn shift_for(span: u64) -> u32 {
        let per_bucket = span / RING as u64 + 1;
        (64 - (per_bucket - 1).leading_zeros()).clamp(10, 32)
    }

    /// Empties the list for a search whose `f` grows by at most `span` a
    /// move (larger steps stay correct, through the overflow heap).
    pub fn reset(&mut self, span: u64) {
        self.clear();
        self.shift = Self::shift_for(span);
    }

    /// Ring bucket of `f`, when it lies within the window above `last`.
    #[inline(always)]
    fn slot(&self, f: u64) -> Option<usize> {
        let b = f >> self.shift;
        (b.wrapping_sub(self.last >> self.shift) < RING as u64).then_some(b as usize & (RING - 1))
    }

    /// Appends to ring bucket `slot`.
    #[inline(always)]
    fn put(&mut self, slot: usize, entry: u64) {
        let slot = slot & (RING - 1);
        let bucket = &mut self.ring[slot];
        // The length is loaded for the push anyway; the bit is only written
        // when a bucket fills, about once in a hundred pushes on A*'s maps.
        if bucket.is_empty() {
            self.occupied[slot / 64] |= 1 << (slot % 64);
        }
        bucket.push(entry);
    }

    /// How many buckets past `last`'s the first occupied one lies,
    /// circularly. (The bits cost 4.5–7 kB of each wasm module, the push
    /// being inlined at every relaxation; walking the 256 bucket lengths
    /// instead made queries on arena's 49 × 49 map 12–30 % slower.)
    fn next_occupied(&self) -> Option<usize> {
        // `usize` arithmetic: on wasm32 `u64` costs more.
        let start = (self.last >> self.shift) as usize & (RING - 1);
        let (w0, b0) = (start / 64, start % 64);
        let words = self.occupied.len();
        // The first word from `start`'s bit up, the others whole, and the
        // first word again below `start`'s bit.
        (0..=words).find_map(|k| {
            let w = (w0 + k) % words;
            let mask = match k {
                0 => u64::MAX << b0,
                k if k == words => !(u64::MAX << b0),
                _ => u64::MAX,
            };
            let bits = self.occupied[w] & mask;
            (bits != 0)
                .then(|| (w * 64 + bits.trailing_zeros() as usize).wrapping_sub(start) & (RING - 1))
        })
    }

    /// Moves the overflow entries the window now reaches into the ring, in
    /// `(f, push)` order.
    fn admit_far(&mut self) {
        while let Some(&Reverse((f, _, idx))) = self.far.peek() {
            let Some(slot) = self.slot(f) else { break };
            self.far.pop();
            self.put(slot, pack(f, idx));
        }
    }

    /// With `top` empty: moves the entries of smallest `f` onto `top`
    /// (making it `last`). `false` when the queue is empty.
    fn refill(&mut self) -> bool {
        loop {
            if let Some(k) = self.next_occupied() {
                // The bucket's number, `f >> shift` of every entry in it.
                let number = (self.last >> self.shift) + k as u64;
                let slot = number as usize & (RING - 1);
                let bucket = &mut self.ring[slot];
                let first = bucket.first().map_or(0, |&e| (e >> 32) as u32);
                let min = if bucket.iter().all(|&e| (e >> 32) as u32 == first) {
                    // The usual case: one `f`, handed over whole.
                    std::mem::swap(bucket, &mut self.top);
                    self.occupied[slot / 64] &= !(1 << (slot % 64));
                    first
                } else {
                    let min = bucket.iter().map(|&e| (e >> 32) as u32).min();
                    let min = min.unwrap_or(first);
                    let top = &mut self.top;
                    bucket.retain(|&e| {
                        let keep = (e >> 32) as u32 != min;
                        if !keep {
                            top.push(e);
                        }
                        keep
                    });
                    min
                };
                // The bucket's bits of `f` with the entries' own below.
                let low_mask = (1u64 << self.shift) - 1;
                self.last = number << self.shift | u64::from(min) & low_mask;
                if k != 0 && !self.far.is_empty() {
                    self.admit_far();
                }
                return true;
            }
            // The ring is empty: jump to the overflow's smallest `f`.
            let Some(&Reverse((f, _, _))) = self.far.peek() else {
                return false;
            };
            self.last = f;
            self.admit_far();
        }
    }
}

impl OpenList for BucketQueue {
    /// `g` is not used: equal `f` pop in reverse push order.
    #[inline(always)]
    fn push(&mut self, f: u64, _g: u64, idx: usize) {
        // Cell indices fit 32 bits (`check_size`).
        let idx = idx as u64;
        if f <= self.last {
            // `f < last` cannot happen with a consistent heuristic; were it
            // to, the entry is still better than every bucketed one.
            self.top.push(pack(f, idx));
        } else if let Some(slot) = self.slot(f) {
            self.put(slot, pack(f, idx));
        } else {
            self.far.push(Reverse((f, self.far_pushes, idx)));
            self.far_pushes += 1;
        }
    }

    #[inline(always)]
    fn pop(&mut self) -> Option<usize> {
        if let Some(e) = self.top.pop() {
            return Some((e as u32) as usize);
        }
        if !self.refill() {
            return None;
        }
        self.top.pop().map(|e| (e as u32) as usize)
    }

    #[inline(always)]
    fn min_key(&mut self) -> Option<u64> {
        (!self.top.is_empty() || self.refill()).then_some(self.last)
    }

    fn clear(&mut self) {
        self.last = 0;
        self.top.clear();
        for (w, bits) in self.occupied.iter_mut().enumerate() {
            let mut b = std::mem::take(bits);
            while b != 0 {
                self.ring[w * 64 + b.trailing_zeros() as usize].clear();
                b &= b - 1;
            }
        }
        self.far.clear();
        self.far_pushes = 0;
    }
}

/// Reusable search buffers, indexed by padded cell.
///
/// Each cell has one 64-bit word (see [`TAG_SHIFT`]): generation tag, open
/// flag, cost `g` and the direction of the move that reached the cell.
/// Every search uses a new, smaller tag, so words left by earlier searches
/// compare greater than any word of the current one: "unseen, or open at a
/// higher cost" is a single comparison ([`SearchSpace::improves`]), and
/// starting a search costs O(1) instead of clearing O(cells). A closed cell
/// lacks [`OPEN`], so it never compares greater and is never reopened (the
/// monotone searches never need to; see [`FixedHeuristic::eval`]). Paths are
/// recovered by walking back along the stored directions, so there is no
/// parent array.
#[derive(Debug, Default)]
pub(crate) struct SearchSpace {
    /// Search word per padded cell.
    pub words: Vec<u64>,
    /// `tag << TAG_SHIFT` of the current search.
    pub tag: u64,
    /// Open list for monotone searches.
    pub buckets: BucketQueue,
    /// Open list for the others (weighted or inconsistent heuristics).
    pub binary: BinaryQueue,
}

impl SearchSpace {
    /// Prepares for a search over `cells` padded cells whose `f` grows by
    /// at most `span` a step when monotone (see [`BucketQueue`]).
    pub fn reset(&mut self, cells: usize, span: u64) {
        if self.words.len() < cells {
            self.words.resize(cells, u64::MAX);
        }
        self.buckets.reset(span);
        self.binary.clear();
        self.tag = next_tag(self.tag, || self.words.fill(u64::MAX));
    }

    /// The word of an open cell reached at cost `g` by move `dir`.
    #[inline(always)]
    pub fn open_word(&self, g: u64, dir: u64) -> u64 {
        self.tag | OPEN | g << G_SHIFT | dir
    }

    /// Cost and arrival direction of a cell reached in the current search,
    /// open or closed.
    #[inline(always)]
    pub fn reached(&self, idx: usize) -> Option<(u64, u64)> {
        let w = *self.words.get(idx)?;
        (w >> TAG_SHIFT == self.tag >> TAG_SHIFT).then_some(((w >> G_SHIFT) & G_MASK, w & DIR_MASK))
    }
}

/// The tag (`tag << TAG_SHIFT`) of the search after the one tagged `tag`;
/// calls `forget` (which must set every word to `u64::MAX`) first when the
/// tags are exhausted, or on first use.
fn next_tag(tag: u64, forget: impl FnOnce()) -> u64 {
    let mut tag = tag >> TAG_SHIFT;
    if tag == 0 {
        forget();
        tag = MAX_TAG;
    }
    (tag - 1) << TAG_SHIFT
}

/// The search space of bidirectional A* ([`super::bidir`]): one search word
/// per padded cell and direction (forward, backward) side by side, so the
/// meeting test reads the other direction's word from the cache line it
/// just wrote, and an open list of each kind per direction. Same word
/// layout and generation tags as [`SearchSpace`].
#[derive(Debug, Default)]
pub(crate) struct PairSpace {
    /// Forward and backward search word per padded cell.
    pub words: Vec<[u64; 2]>,
    /// `tag << TAG_SHIFT` of the current search.
    pub tag: u64,
    /// Open lists for monotone searches, forward and backward.
    pub buckets: [BucketQueue; 2],
    /// Open lists for the others.
    pub binary: [BinaryQueue; 2],
}

impl PairSpace {
    /// Prepares for a search over `cells` padded cells.
    pub fn reset(&mut self, cells: usize) {
        if self.words.len() < cells {
            self.words.resize(cells, [u64::MAX; 2]);
        }
        // Keys are 2g + h − h': a move adds at most four times its cost.
        self.buckets
            .iter_mut()
            .for_each(|q| q.reset(2 * DEFAULT_SPAN));
        self.binary.iter_mut().for_each(OpenList::clear);
        self.tag = next_tag(self.tag, || self.words.fill([u64::MAX; 2]));
    }

    /// Whether `word` was written by the current search.
    #[inline(always)]
    pub fn current(tag: u64, word: u64) -> bool {
        word < Self::fresh_below(tag)
    }

    /// The bound under which every word of the search tagged `tag` lies and
    /// no other does: tags count down from search to search (and a wrap
    /// refills every word with `u64::MAX`), so words of earlier searches
    /// compare above it. One comparison per test instead of two shifts.
    #[inline(always)]
    pub fn fresh_below(tag: u64) -> u64 {
        ((tag >> TAG_SHIFT) + 1) << TAG_SHIFT
    }

    /// Cost and arrival direction of a cell reached in direction `side`
    /// (0 forward, 1 backward) in the current search, open or closed.
    #[inline(always)]
    pub fn reached(&self, side: usize, idx: usize) -> Option<(u64, u64)> {
        let w = *self.words.get(idx)?.get(side)?;
        Self::current(self.tag, w).then_some(((w >> G_SHIFT) & G_MASK, w & DIR_MASK))
    }
}

/// Whether `new` (an open word of the current search) improves on the
/// stored word `old`: `old` is from an earlier search, or open now at a
/// higher cost. Directions are ignored.
#[inline(always)]
pub(crate) fn improves(old: u64, new: u64) -> bool {
    // `old`'s bits above the direction exceed `new`'s exactly when `old`
    // exceeds `new` with its direction bits all set.
    old > new | DIR_MASK
}

/// The path through `cells` with its cost on `grid` (in `f64` from the
/// moves, weighted where the grid is).
pub(crate) fn path_of(grid: &PlanGrid, cells: Vec<GridPos>, expanded: usize) -> Path {
    Path {
        cost: if grid.is_weighted() {
            grid.path_cost(&cells)
        } else {
            unit_path_cost(&cells)
        },
        cells,
        expanded,
    }
}

/// The end of every search: `Unreachable` if `t` was not reached, else the
/// walked-back path with its cost.
pub(crate) fn finish(
    grid: &PlanGrid,
    space: &SearchSpace,
    (s, t): (usize, usize),
    reached: bool,
    expanded: usize,
) -> Result<Path, PlanError> {
    if !reached {
        return Err(PlanError::Unreachable { expanded });
    }
    // The walk cannot fail (see `walk_back`); an empty path would be a bug.
    let cells = walk_back(grid, |i| space.reached(i), s, t).unwrap_or_default();
    Ok(path_of(grid, cells, expanded))
}

/// Walks back from `t` to `s` along the stored arrival directions. From a
/// cell `c`, the cells behind it along its direction are visited until one
/// reached in this search with `g + cost ≤ g(c)` (the cost of the moves
/// back to `c`, each its length times the weight of the cell it enters):
/// the cell `c` was
/// reached from lies on that ray and its cost has only decreased since, so
/// the walk always succeeds, every step strictly lowers `g`, and the result
/// costs at most `g(t)`. Cells in start-to-goal order; `None` only if the
/// search space is inconsistent (never, barring a bug).
pub(crate) fn walk_back(
    grid: &PlanGrid,
    reached: impl Fn(usize) -> Option<(u64, u64)>,
    s: usize,
    t: usize,
) -> Option<Vec<GridPos>> {
    let stride = grid.stride();
    let free = |i: usize| grid.padded().get(i).copied().unwrap_or(false);
    let weights = grid.padded_weights();
    let weight = |i: usize| weights.map_or(1, |w| w.get(i).map_or(1, |&v| u64::from(v)));
    let (mut gc, mut dir) = reached(t)?;
    let (mut x, mut y) = xy(t, stride);
    // Padded → map coordinates (the padding is one cell).
    let pos = |x: usize, y: usize| GridPos::new((x - 1) as u32, (y - 1) as u32);
    let offset = |dx: isize, dy: isize| dy * stride as isize + dx;
    // A path of cost g has at most g / STRAIGHT moves: one allocation.
    let mut cells = Vec::with_capacity((gc / STRAIGHT) as usize + 1);
    cells.push(pos(x, y));
    let mut c = t;
    while c != s {
        let (mut dx, mut dy) = DIRS.get(dir as usize).copied()?;
        let cost = if dx != 0 && dy != 0 { DIAG } else { STRAIGHT };
        // Cost of the moves walked back from the cell reached, so far.
        let mut k = 0u64;
        let found = loop {
            let entered = c;
            let mut next = c.wrapping_add_signed(-offset(dx, dy));
            if !free(next) {
                // Jump Point Search follows corridor corners without
                // recording them all: at such a corner the way back turns to
                // the only open side.
                if cost != STRAIGHT {
                    break None;
                }
                let (a, b) = (
                    c.wrapping_add_signed(offset(dy, dx)),
                    c.wrapping_add_signed(-offset(dy, dx)),
                );
                (dx, dy) = match (free(a), free(b)) {
                    (true, false) => (-dy, -dx),
                    (false, true) => (dy, dx),
                    _ => break None,
                };
                next = c.wrapping_add_signed(-offset(dx, dy));
            }
            c = next;
            x = x.wrapping_add_signed(-dx);
            y = y.wrapping_add_signed(-dy);
            k += cost * weight(entered);
            cells.push(pos(x, y));
            if let Some((gq, dq)) = reached(c) {
                if gq + k <= gc {
                    break Some((gq, dq));
                }
            }
        };
        (gc, dir) = found?;
    }
    cells.reverse();
    Some(cells)
}

thread_local! {
    static SPACE: RefCell<SearchSpace> = RefCell::new(SearchSpace::default());
    static PAIR: RefCell<PairSpace> = RefCell::new(PairSpace::default());
}

/// As [`with_space`], with this thread's [`PairSpace`].
pub(crate) fn with_pair_space<R>(f: impl FnOnce(&mut PairSpace) -> R) -> R {
    PAIR.with(|cell| match cell.try_borrow_mut() {
        Ok(mut space) => f(&mut space),
        Err(_) => f(&mut PairSpace::default()),
    })
}

/// Runs `f` with this thread's search space (a fresh one if it is already in
/// use, e.g. a planner called from inside another planner's callback).
pub(crate) fn with_space<R>(f: impl FnOnce(&mut SearchSpace) -> R) -> R {
    SPACE.with(|cell| match cell.try_borrow_mut() {
        Ok(mut space) => f(&mut space),
        Err(_) => f(&mut SearchSpace::default()),
    })
}

/// Refuses grids whose padded cell count does not fit the `u32` indices.
pub(crate) fn check_size(grid: &PlanGrid) -> Result<(), PlanError> {
    // A simple path enters each cell once, so the weights' sum bounds its
    // cost in moves of DIAG (a unit grid: the cell count, as before).
    if grid.padded().len() > MAX_PADDED_CELLS || grid.weight_total() > MAX_PADDED_CELLS as u64 {
        return Err(PlanError::InvalidConfig(format!(
            "a {}×{} grid is too large for the grid planners",
            grid.width(),
            grid.height()
        )));
    }
    Ok(())
}

/// A heuristic in fixed-point units, multiplied by a weight ≥ 1.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FixedHeuristic {
    kind: Heuristic,
    weight: f64,
}

impl FixedHeuristic {
    pub fn new(kind: Heuristic, weight: f64) -> Self {
        Self { kind, weight }
    }

    /// Estimate for absolute offsets `dx`, `dy` in cells. Exact integer
    /// arithmetic where possible; otherwise rounded down, which keeps an
    /// admissible heuristic admissible.
    #[inline(always)]
    pub fn eval(&self, dx: usize, dy: usize) -> u64 {
        let (dx, dy) = (dx as u64, dy as u64);
        let (lo, hi) = if dx < dy { (dx, dy) } else { (dy, dx) };
        let h = match self.kind {
            Heuristic::Octile => STRAIGHT * hi + (DIAG - STRAIGHT) * lo,
            Heuristic::Manhattan => STRAIGHT * (dx + dy),
            Heuristic::Chebyshev => STRAIGHT * hi,
            Heuristic::Zero => 0,
            // Rounding down a consistent estimate keeps it consistent when
            // move costs are integers (DIAG ≥ √2·STRAIGHT).
            Heuristic::Euclidean => {
                let (fx, fy) = (dx as f64, dy as f64);
                ((fx * fx + fy * fy).sqrt() * STRAIGHT as f64) as u64
            }
        };
        if self.weight == 1.0 {
            h
        } else {
            // Float-to-int casts saturate, so huge weights cannot wrap.
            (h as f64 * self.weight) as u64
        }
    }
}

/// A heuristic in fixed-point units; the planners are monomorphised over it
/// so the common octile and zero cases compile to straight-line integer code.
pub(crate) trait Estimate: Copy {
    /// Whether `f` never decreases along a search with this estimate
    /// (consistent, weight 1), so the bucket queue applies.
    const MONOTONE: bool;

    /// Whether bidirectional A* gets a copy of its loop without the
    /// weighted-cost branch for unit grids: only the default octile
    /// estimate, so the other estimates do not grow the wasm modules (A*
    /// has such a copy for every estimate).
    const UNIT_COPY: bool = false;

    /// Estimate for absolute offsets `dx`, `dy` in cells.
    fn h(&self, dx: usize, dy: usize) -> u64;

    /// An estimate from [`Estimate::h`] back in cells, without the weight
    /// (what [`super::SearchEvent::Open`] reports).
    #[inline(always)]
    fn unweighted_cells(&self, h: u64) -> f64 {
        cells(h)
    }
}

/// A fixed-point cost in cells.
#[inline(always)]
pub(crate) fn cells(cost: u64) -> f64 {
    cost as f64 / STRAIGHT as f64
}

/// Exact octile distance, weight 1.
#[derive(Clone, Copy, Debug)]
pub(crate) struct OctileEstimate;

impl Estimate for OctileEstimate {
    const MONOTONE: bool = true;
    const UNIT_COPY: bool = true;
    #[inline(always)]
    fn h(&self, dx: usize, dy: usize) -> u64 {
        let (lo, hi) = if dx < dy { (dx, dy) } else { (dy, dx) };
        STRAIGHT * hi as u64 + (DIAG - STRAIGHT) * lo as u64
    }
}

/// Always 0 (Dijkstra).
#[derive(Clone, Copy, Debug)]
pub(crate) struct ZeroEstimate;

impl Estimate for ZeroEstimate {
    const MONOTONE: bool = true;
    #[inline(always)]
    fn h(&self, _dx: usize, _dy: usize) -> u64 {
        0
    }
}

impl Estimate for FixedHeuristic {
    const MONOTONE: bool = false;
    #[inline(always)]
    fn h(&self, dx: usize, dy: usize) -> u64 {
        self.eval(dx, dy)
    }

    fn unweighted_cells(&self, h: u64) -> f64 {
        cells(h) / self.weight
    }
}

/// Path cost in cells of a cell-by-cell path: 1 per straight move, √2 per
/// diagonal move.
pub(crate) fn unit_path_cost(cells: &[GridPos]) -> f64 {
    let diagonal = cells
        .windows(2)
        .filter(|w| w[0].col != w[1].col && w[0].row != w[1].row)
        .count();
    let straight = cells.len().saturating_sub(1) - diagonal;
    straight as f64 + diagonal as f64 * std::f64::consts::SQRT_2
}

/// The one-cell answer for `start == goal`.
pub(crate) fn trivial_path(start: GridPos) -> Path {
    Path {
        cells: vec![start],
        cost: 0.0,
        expanded: 0,
    }
}

/// Padded cell index → padded `(x, y)`.
#[inline(always)]
pub(crate) fn xy(idx: usize, stride: usize) -> (usize, usize) {
    // 32-bit division is markedly faster; indices fit (see `check_size`).
    let (i, s) = (idx as u32, stride as u32);
    ((i % s) as usize, (i / s) as usize)
}

/// Bit-packed passability of a padded grid along one orientation (rows or
/// columns), with the stop masks straight jumps scan, 64 cells per word
/// (Harabor & Grastien 2014, "block-based" JPS).
///
/// Bit `pos` of line `l` in `free` is set when the cell at position `pos` of
/// line `l` is passable. Bit `pos` of `fwd` is set where a jump moving to
/// increasing positions must stop: the cell is blocked, or it has a forced
/// neighbour — the cell beside it in an adjacent line is passable while the
/// one beside its predecessor (`pos − 1`) is blocked. `bwd` is the same for
/// decreasing positions (successor `pos + 1`). The masks are a function of
/// three adjacent lines, recomputed locally on every edit; they hold no
/// jump distances (this is online JPS, not JPS+).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct Lines {
    /// Words per line.
    words: usize,
    /// Number of lines.
    count: usize,
    /// `count × words` blocks, line-major.
    blocks: Vec<LineWord>,
}

/// 64 cells of a line: passability and both stop masks side by side, so a
/// scan touches one cache line per word.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[repr(align(32))]
struct LineWord {
    free: u64,
    fwd: u64,
    bwd: u64,
}

impl Lines {
    /// `count` all-blocked lines of `len` cells.
    fn new(count: usize, len: usize) -> Self {
        let words = len.div_ceil(64);
        let blocked = LineWord {
            free: 0,
            fwd: !0,
            bwd: !0,
        };
        Self {
            words,
            count,
            blocks: vec![blocked; words * count],
        }
    }

    fn set_free_bit(&mut self, line: usize, pos: usize, free: bool) {
        if let Some(w) = self.blocks.get_mut(line * self.words + pos / 64) {
            if free {
                w.free |= 1 << (pos % 64);
            } else {
                w.free &= !(1 << (pos % 64));
            }
        }
    }

    #[inline]
    fn free_word(&self, line: usize, k: usize) -> u64 {
        self.blocks.get(line * self.words + k).map_or(0, |w| w.free)
    }

    /// Recomputes the stop masks of word `k` of `line`.
    fn refresh(&mut self, line: usize, k: usize) {
        if k >= self.words || line >= self.count {
            return;
        }
        let c = self.free_word(line, k);
        let (mut fwd, mut bwd) = (!c, !c);
        // Edge lines are never scanned; they keep "stop everywhere free".
        if line > 0 && line + 1 < self.count {
            for side in [line - 1, line + 1] {
                let w = self.free_word(side, k);
                let before = match k.checked_sub(1) {
                    Some(j) => self.free_word(side, j) >> 63,
                    None => 0,
                };
                let after = if k + 1 < self.words {
                    self.free_word(side, k + 1) << 63
                } else {
                    0
                };
                fwd |= w & !((w << 1) | before);
                bwd |= w & !((w >> 1) | after);
            }
        }
        if let Some(w) = self.blocks.get_mut(line * self.words + k) {
            w.fwd = fwd;
            w.bwd = bwd;
        }
    }

    fn refresh_all(&mut self) {
        for line in 0..self.count {
            for k in 0..self.words {
                self.refresh(line, k);
            }
        }
    }

    /// Straight jump from `pos` towards increasing positions along `line`:
    /// the first position `s > pos` that is `target`, or where `fwd` stops,
    /// if passable (`None` when the jump runs into an obstacle).
    #[inline(always)]
    pub fn jump_forward(&self, line: usize, pos: usize, target: usize) -> Option<usize> {
        let base = line * self.words;
        let blocks = self.blocks.get(base..base + self.words)?;
        let start = pos + 1;
        let mut k = start / 64;
        let mut w = blocks.get(k)?;
        let mut m = w.fwd & (!0u64 << (start % 64));
        while m == 0 {
            k += 1;
            w = blocks.get(k)?;
            m = w.fwd;
        }
        let b = m.trailing_zeros();
        let stop = k * 64 + b as usize;
        if target > pos && target < stop {
            Some(target)
        } else if (w.free >> b) & 1 == 1 {
            Some(stop)
        } else {
            None
        }
    }

    /// As [`Lines::jump_forward`], towards decreasing positions.
    #[inline(always)]
    pub fn jump_backward(&self, line: usize, pos: usize, target: usize) -> Option<usize> {
        let base = line * self.words;
        let blocks = self.blocks.get(base..base + self.words)?;
        let start = pos.checked_sub(1)?;
        let mut k = start / 64;
        let mut w = blocks.get(k)?;
        let mut m = w.bwd & (!0u64 >> (63 - start % 64));
        while m == 0 {
            k = k.checked_sub(1)?;
            w = blocks.get(k)?;
            m = w.bwd;
        }
        let b = 63 - m.leading_zeros();
        let stop = k * 64 + b as usize;
        if target < pos && target > stop {
            Some(target)
        } else if (w.free >> b) & 1 == 1 {
            Some(stop)
        } else {
            None
        }
    }
}

/// The padded grid's [`Lines`] by rows (line = y, position = x) and by
/// columns (line = x, position = y).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct LineBits {
    pub rows: Lines,
    pub cols: Lines,
}

impl LineBits {
    /// Lines of a padded `stride × padded_height` grid whose padded cell
    /// `(x, y)` is passable when `free[y * stride + x]`.
    pub fn new(free: &[bool], stride: usize, padded_height: usize) -> Self {
        let mut rows = Lines::new(padded_height, stride);
        let mut cols = Lines::new(stride, padded_height);
        for (i, _) in free.iter().enumerate().filter(|(_, &f)| f) {
            let (x, y) = (i % stride, i / stride);
            rows.set_free_bit(y, x, true);
            cols.set_free_bit(x, y, true);
        }
        rows.refresh_all();
        cols.refresh_all();
        Self { rows, cols }
    }

    /// Sets padded cell `(x, y)` passable or blocked, and refreshes the stop
    /// masks it affects (the words around it in its line and both
    /// neighbouring lines).
    pub fn set(&mut self, x: usize, y: usize, free: bool) {
        self.rows.set_free_bit(y, x, free);
        self.cols.set_free_bit(x, y, free);
        for (lines, line, pos) in [(&mut self.rows, y, x), (&mut self.cols, x, y)] {
            for l in line.saturating_sub(1)..=line + 1 {
                for k in pos.saturating_sub(1) / 64..=(pos + 1) / 64 {
                    lines.refresh(l, k);
                }
            }
        }
    }
}

/// The four straight moves out of padded cell `$i`: `$relax!(j, dx, dy,
/// cost, dir)` for each whose cell is free (`$n`, `$s`, `$w`, `$e`: north
/// at `$up`, south at `$down`, west, east), with `dx` and `dy` the literals
/// −1, 0 or +1. Shared by A* and bidirectional A*, which differ in what a
/// relaxation does.
macro_rules! straight_moves {
    ($relax:ident, $i:expr, ($up:expr, $down:expr), [$n:expr, $s:expr, $w:expr, $e:expr]) => {
        if $n {
            $relax!($up, 0, -1, $crate::global::search::STRAIGHT, 3);
        }
        if $s {
            $relax!($down, 0, 1, $crate::global::search::STRAIGHT, 2);
        }
        if $w {
            $relax!($i - 1, -1, 0, $crate::global::search::STRAIGHT, 1);
        }
        if $e {
            $relax!($i + 1, 1, 0, $crate::global::search::STRAIGHT, 0);
        }
    };
}
pub(crate) use straight_moves;

/// The four diagonal moves whose bit is set in `$nb` (neighbour bits with
/// the corner rule already applied, see [`neighbour_bits`] and
/// `astar::moves_allowed`); the rest as in [`straight_moves`].
macro_rules! diagonal_moves {
    ($relax:ident, $nb:expr, ($up:expr, $down:expr)) => {
        if $nb & 1 << 7 != 0 {
            $relax!($up - 1, -1, -1, $crate::global::search::DIAG, 7);
        }
        if $nb & 1 << 5 != 0 {
            $relax!($up + 1, 1, -1, $crate::global::search::DIAG, 5);
        }
        if $nb & 1 << 6 != 0 {
            $relax!($down - 1, -1, 1, $crate::global::search::DIAG, 6);
        }
        if $nb & 1 << 4 != 0 {
            $relax!($down + 1, 1, 1, $crate::global::search::DIAG, 4);
        }
    };
}
pub(crate) use diagonal_moves;

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn pair_space_counts_only_this_searchs_words_as_current_across_a_tag_wrap() {
        // Words of every cost, direction and open bit, written by the search
        // tagged `tag`.
        let written = |tag: u64| {
            [0, 1, G_MASK]
                .into_iter()
                .flat_map(move |g| [0, OPEN].map(move |open| tag | open | g << G_SHIFT | DIR_MASK))
        };
        let mut space = PairSpace::default();
        space.reset(4);
        let mut previous = space.tag;
        let mut wraps = 0;
        // Past the wrap, where every word is forgotten and tags restart.
        for _ in 0..MAX_TAG + 2 {
            space.reset(4);
            let tag = space.tag;
            assert!(written(tag).all(|w| PairSpace::current(tag, w)));
            // Tags count down; at the wrap the words are forgotten instead
            // (the next line), so no word of the previous search is left.
            if tag < previous {
                assert!(written(previous).all(|w| !PairSpace::current(tag, w)));
            } else {
                wraps += 1;
            }
            assert!(space
                .words
                .iter()
                .flatten()
                .all(|&w| !PairSpace::current(tag, w)));
            space.words[0] = [tag | OPEN, tag | G_MASK << G_SHIFT];
            previous = tag;
        }
        assert_eq!(wraps, 1);
    }

    #[test]
    fn move_macros_pass_each_moves_own_direction_index_and_offset() {
        let stride = 10usize;
        let i = 55usize;
        let (up, down) = (i - stride, i + stride);
        let mut seen = Vec::new();
        macro_rules! record {
            ($j:expr, $dx:expr, $dy:expr, $cost:expr, $dir:expr) => {{
                let (dx, dy): (isize, isize) = ($dx, $dy);
                seen.push(($j, dx, dy, $cost, $dir));
            }};
        }
        straight_moves!(record, i, (up, down), [true, true, true, true]);
        diagonal_moves!(record, 0xF0u8, (up, down));
        assert_eq!(seen.len(), 8);
        for (j, dx, dy, cost, dir) in seen {
            assert_eq!(dir, dir_index(dx, dy), "({dx}, {dy})");
            assert_eq!(j as isize, i as isize + dy * stride as isize + dx);
            assert_eq!(DIRS[dir as usize], (dx, dy));
            assert_eq!(cost, if dx != 0 && dy != 0 { DIAG } else { STRAIGHT });
        }
    }

    /// Replays `ops` (`Some(step)`: push at `f = last popped + step`;
    /// `None`: pop) on a [`BucketQueue`] of span `span` and on the order it
    /// promises — smallest `f`, then the latest push — and compares every
    /// pop and `min_key`.
    fn replay_bucket_queue(q: &mut BucketQueue, span: u64, ops: &[Option<u64>]) {
        q.reset(span);
        // Reference: (f, push number) of the entries waiting.
        let mut want: Vec<(u64, usize)> = Vec::new();
        let (mut last, mut pushes) = (0u64, 0usize);
        for op in ops {
            match *op {
                Some(step) => {
                    let f = last + step;
                    q.push(f, 0, pushes);
                    want.push((f, pushes));
                    pushes += 1;
                }
                None => {
                    let best = want
                        .iter()
                        .enumerate()
                        .min_by_key(|(_, &(f, n))| (f, std::cmp::Reverse(n)))
                        .map(|(k, &e)| (k, e));
                    assert_eq!(q.min_key(), best.map(|(_, (f, _))| f));
                    let got = q.pop();
                    assert_eq!(got, best.map(|(_, (_, n))| n));
                    if let Some((k, (f, _))) = best {
                        want.remove(k);
                        last = f;
                    }
                }
            }
        }
    }

    proptest! {
        #[test]
        fn bucket_queue_pops_smallest_f_latest_push_first(
            span_exp in 10u32..24,
            ops in prop::collection::vec(
                prop_oneof![
                    // Steps within the span, steps sharing a bucket, equal
                    // keys, and jumps far beyond the span.
                    3 => (0u64..3_000_000).prop_map(Some),
                    2 => (0u64..4).prop_map(|k| Some(k * 1000)),
                    1 => (0u64..1u64 << 40).prop_map(Some),
                    4 => Just(None),
                ],
                0..400,
            ),
            split in 0usize..400,
        ) {
            // Two searches on one queue: the second starts with whatever
            // the first left in the buckets.
            let mut q = BucketQueue::default();
            let (a, b) = ops.split_at(split.min(ops.len()));
            replay_bucket_queue(&mut q, 1 << span_exp, a);
            replay_bucket_queue(&mut q, 1 << span_exp, b);
        }
    }

    /// Every padded cell's neighbour bits against its eight neighbours read
    /// one by one.
    fn assert_neighbour_bits(grid: &PlanGrid) {
        let (free, stride, bits) = (grid.padded(), grid.stride(), grid.neighbours());
        assert_eq!(bits.len(), free.len());
        for y in 1..free.len() / stride - 1 {
            for x in 1..stride - 1 {
                let i = y * stride + x;
                for (k, &(dx, dy)) in DIRS.iter().enumerate() {
                    let j = (i as isize + dy * stride as isize + dx) as usize;
                    assert_eq!(bits[i] >> k & 1 == 1, free[j], "cell ({x}, {y}) move {k}");
                }
            }
        }
    }

    #[test]
    fn neighbour_bits_match_the_grid_before_and_after_edits() {
        // Sizes around the vectorised passes' chunks, pseudo-random walls.
        for (w, h) in [(1, 1), (2, 3), (7, 5), (33, 17), (64, 9)] {
            let mut state = (w * 31 + h) as u64;
            let mut coin = move || {
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                state >> 61 < 3
            };
            let mut grid = PlanGrid::from_fn(w, h, |_, _| coin());
            assert_neighbour_bits(&grid);
            for k in 0..(w * h * 2) {
                let (c, r) = ((k * 7) % w, (k * 13) % h);
                let free = !grid.is_free(c as i64, r as i64);
                grid.set_free(c, r, free);
            }
            assert_neighbour_bits(&grid);
        }
    }

    #[test]
    fn bucket_queue_clears_between_searches_and_keeps_order_after_overflow() {
        let mut q = BucketQueue::default();
        q.reset(DEFAULT_SPAN);
        // Far beyond the window first, then in it: the window entries pop
        // first; equal far keys in push order reversed.
        q.push(1 << 40, 0, 1);
        q.push(1 << 40, 0, 2);
        q.push(5, 0, 3);
        assert_eq!(q.pop(), Some(3));
        assert_eq!(q.pop(), Some(2));
        assert_eq!(q.pop(), Some(1));
        assert_eq!(q.pop(), None);
        q.push(7, 0, 4);
        q.clear();
        assert_eq!(q.min_key(), None);
        q.push(9, 0, 5);
        assert_eq!(q.pop(), Some(5));
    }

    /// Reference straight jump, one cell at a time, over a `bool` grid of
    /// lines (`grid[line][pos]`).
    fn naive(
        grid: &[Vec<bool>],
        line: usize,
        pos: usize,
        fwd: bool,
        target: usize,
    ) -> Option<usize> {
        let mut s = pos;
        loop {
            let back = s;
            s = if fwd { s + 1 } else { s.checked_sub(1)? };
            if s >= grid[line].len() || !grid[line][s] {
                return None;
            }
            if s == target {
                return Some(s);
            }
            for side in [line - 1, line + 1] {
                if grid[side][s] && !grid[side][back] {
                    return Some(s);
                }
            }
        }
    }

    #[test]
    fn jumps_match_cell_by_cell_jumps_before_and_after_edits() {
        // Deterministic pseudo-random grids of 150 × 7 padded cells (3 words
        // per row), blocked all round like a padded grid.
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut rnd = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let (stride, height) = (150usize, 7usize);
        for density in [2u64, 5, 20, 50] {
            let mut free: Vec<bool> = (0..stride * height)
                .map(|i| {
                    let (x, y) = (i % stride, i / stride);
                    x > 0 && y > 0 && x + 1 < stride && y + 1 < height && rnd() % 100 >= density
                })
                .collect();
            let mut bits = LineBits::new(&free, stride, height);
            for round in 0..2 {
                let rows: Vec<Vec<bool>> = (0..height)
                    .map(|y| (0..stride).map(|x| free[y * stride + x]).collect())
                    .collect();
                let cols: Vec<Vec<bool>> = (0..stride)
                    .map(|x| (0..height).map(|y| free[y * stride + x]).collect())
                    .collect();
                for (lines, grid) in [(&bits.rows, &rows), (&bits.cols, &cols)] {
                    for line in 1..grid.len() - 1 {
                        for pos in 1..grid[line].len() - 1 {
                            let target = if pos % 3 == 0 {
                                (pos * 7) % grid[line].len()
                            } else {
                                usize::MAX
                            };
                            let msg =
                                format!("round {round} line {line} pos {pos} target {target}");
                            assert_eq!(
                                lines.jump_forward(line, pos, target),
                                naive(grid, line, pos, true, target),
                                "forward {msg}"
                            );
                            assert_eq!(
                                lines.jump_backward(line, pos, target),
                                naive(grid, line, pos, false, target),
                                "backward {msg}"
                            );
                        }
                    }
                }
                // Edit some interior cells, across word boundaries too.
                for _ in 0..60 {
                    let x = 1 + (rnd() as usize) % (stride - 2);
                    let y = 1 + (rnd() as usize) % (height - 2);
                    let f = rnd() % 2 == 0;
                    free[y * stride + x] = f;
                    bits.set(x, y, f);
                }
            }
            assert_eq!(bits, LineBits::new(&free, stride, height));
        }
    }

    #[test]
    fn fixed_costs_approximate_sqrt2() {
        let ratio = DIAG as f64 / STRAIGHT as f64;
        assert!((ratio - std::f64::consts::SQRT_2).abs() < 1e-11);
        let h = FixedHeuristic::new(Heuristic::Octile, 1.0);
        assert_eq!(h.eval(3, 5), 2 * STRAIGHT + 3 * DIAG);
    }
}
