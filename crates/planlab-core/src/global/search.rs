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
use std::collections::BinaryHeap;

/// Cost of a straight move, in fixed-point units.
pub(crate) const STRAIGHT: u64 = 470_832;
/// Cost of a diagonal move: round(√2 · STRAIGHT), a convergent of √2.
pub(crate) const DIAG: u64 = 665_857;

/// Bits of a cell's search word above the cost: a 16-bit generation tag.
const TAG_SHIFT: u32 = 48;
/// Set while a cell is open (generated, not yet expanded) in the current
/// search; cleared when it is closed.
pub(crate) const OPEN: u64 = 1 << 47;
/// Mask of the cost `g` in a search word.
pub(crate) const G_MASK: u64 = OPEN - 1;
/// The largest padded grid the planners accept: any path then costs less
/// than [`G_MASK`] (≤ 2·10⁸ cells × [`DIAG`] < 2⁴⁷).
pub(crate) const MAX_PADDED_CELLS: usize = 200_000_000;

/// An open-list entry: smallest `f` first, ties to the largest `g` (deepest
/// node), which keeps A* from fanning out over equal-cost regions. `tie` is
/// `g >> 16` (the tie-break needs no more precision), keeping the entry at
/// 16 bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Entry {
    pub f: u64,
    pub tie: u32,
    pub idx: u32,
}

impl Entry {
    #[inline(always)]
    pub fn new(f: u64, g: u64, idx: usize) -> Self {
        Self {
            f,
            tie: (g >> 16) as u32,
            idx: idx as u32,
        }
    }
}

impl Ord for Entry {
    #[inline]
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        // BinaryHeap is a max-heap: reverse f, keep the tie-break.
        other.f.cmp(&self.f).then(self.tie.cmp(&other.tie))
    }
}

impl PartialOrd for Entry {
    #[inline]
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

/// Reusable search buffers, indexed by padded cell.
///
/// Each cell has one 64-bit word: `tag << 48 | OPEN? | g`. Every search
/// uses a new, smaller `tag`, so words left by earlier searches compare
/// greater than any word of the current one: "unseen or reachable more
/// cheaply" is a single `old > new` comparison, and starting a search costs
/// O(1) instead of clearing O(cells). A closed cell lacks [`OPEN`], so it
/// never compares greater and is never reopened (the heuristics are
/// consistent in integer units; see [`FixedHeuristic::eval`]).
#[derive(Debug, Default)]
pub(crate) struct SearchSpace {
    /// Search word per padded cell.
    pub g: Vec<u64>,
    /// Predecessor per padded cell (Jump Point Search only; A* walks back
    /// along decreasing `g` instead).
    pub parent: Vec<u32>,
    /// `tag << 48` of the current search.
    pub tag: u64,
    /// The open list (lazy deletion).
    pub open: BinaryHeap<Entry>,
}

impl SearchSpace {
    /// Prepares for a search over `cells` padded cells.
    pub fn reset(&mut self, cells: usize, with_parents: bool) {
        if self.g.len() < cells {
            self.g.resize(cells, u64::MAX);
        }
        if with_parents && self.parent.len() < cells {
            self.parent.resize(cells, 0);
        }
        self.open.clear();
        let mut tag = self.tag >> TAG_SHIFT;
        if tag == 0 {
            // Tags exhausted (or first use): forget every earlier search.
            self.g.fill(u64::MAX);
            tag = 0xFFFF;
        }
        self.tag = (tag - 1) << TAG_SHIFT;
    }

    /// The word that opens a cell at cost `g` in the current search.
    #[inline(always)]
    pub fn open_word(&self, g: u64) -> u64 {
        self.tag | OPEN | g
    }

    /// Cost of a cell reached in the current search, open or closed.
    #[inline(always)]
    pub fn g_of(&self, idx: usize) -> Option<u64> {
        let w = *self.g.get(idx)?;
        (w & !(OPEN | G_MASK) == self.tag).then_some(w & G_MASK)
    }
}

thread_local! {
    static SPACE: RefCell<SearchSpace> = RefCell::new(SearchSpace::default());
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
    if grid.padded().len() > MAX_PADDED_CELLS {
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
    #[inline]
    pub fn eval(&self, dx: usize, dy: usize) -> u64 {
        let (dx, dy) = (dx as u64, dy as u64);
        let (lo, hi) = if dx < dy { (dx, dy) } else { (dy, dx) };
        let h = match self.kind {
            Heuristic::Octile => STRAIGHT * hi + (DIAG - STRAIGHT) * lo,
            Heuristic::Manhattan => STRAIGHT * (dx + dy),
            Heuristic::Chebyshev => STRAIGHT * hi,
            Heuristic::Zero => 0,
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
    /// Estimate for absolute offsets `dx`, `dy` in cells.
    fn h(&self, dx: usize, dy: usize) -> u64;
}

/// Exact octile distance, weight 1.
#[derive(Clone, Copy, Debug)]
pub(crate) struct OctileEstimate;

impl Estimate for OctileEstimate {
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
    #[inline(always)]
    fn h(&self, _dx: usize, _dy: usize) -> u64 {
        0
    }
}

impl Estimate for FixedHeuristic {
    #[inline]
    fn h(&self, dx: usize, dy: usize) -> u64 {
        self.eval(dx, dy)
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
#[inline]
pub(crate) fn xy(idx: usize, stride: usize) -> (usize, usize) {
    // 32-bit division is markedly faster; indices fit (see `check_size`).
    let (i, s) = (idx as u32, stride as u32);
    ((i % s) as usize, (i / s) as usize)
}

/// Bit-packed passability, by rows and by columns, of a padded grid: bit
/// `x` of row line `y` (and bit `y` of column line `x`) is set when padded
/// cell `(x, y)` is passable. Jump Point Search scans these 64 cells at a
/// time (Harabor & Grastien 2014, "block-based" JPS).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct LineBits {
    /// Words per row line.
    pub row_words: usize,
    /// `padded height × row_words` words.
    pub rows: Vec<u64>,
    /// Words per column line.
    pub col_words: usize,
    /// `stride × col_words` words.
    pub cols: Vec<u64>,
}

impl LineBits {
    /// All-blocked lines for a padded `stride × padded_height` grid.
    pub fn new(stride: usize, padded_height: usize) -> Self {
        let row_words = stride.div_ceil(64);
        let col_words = padded_height.div_ceil(64);
        Self {
            row_words,
            rows: vec![0; row_words * padded_height],
            col_words,
            cols: vec![0; col_words * stride],
        }
    }

    /// Sets padded cell `(x, y)` passable or blocked.
    pub fn set(&mut self, x: usize, y: usize, free: bool) {
        let (ri, rb) = (y * self.row_words + x / 64, x % 64);
        let (ci, cb) = (x * self.col_words + y / 64, y % 64);
        if let (Some(r), Some(c)) = (self.rows.get_mut(ri), self.cols.get_mut(ci)) {
            if free {
                *r |= 1 << rb;
                *c |= 1 << cb;
            } else {
                *r &= !(1 << rb);
                *c &= !(1 << cb);
            }
        }
    }
}

/// Scans line `line` forward (increasing position) from `pos` for the first
/// position `s > pos` where a straight jump stops: a blocked cell (→ `None`),
/// the `target` position, or a cell with a forced neighbour — a passable cell
/// in an adjacent line whose predecessor (`s − 1`) there is blocked.
///
/// `line` must be an interior line (it has lines on both sides) and the last
/// position of every line must be blocked, which the padding guarantees.
#[inline]
pub(crate) fn scan_forward(
    lines: &[u64],
    words: usize,
    line: usize,
    pos: usize,
    target: usize,
) -> Option<usize> {
    let base = line * words;
    let prev = lines.get(base.checked_sub(words)?..base)?;
    let cur = lines.get(base..base + words)?;
    let next = lines.get(base + words..base + 2 * words)?;
    let start = pos + 1;
    let mut k = start / 64;
    let mut mask = !0u64 << (start % 64);
    // Bit 63 of the previous word, shifted in as bit 0 of this one.
    let (mut carry_p, mut carry_n) = match k.checked_sub(1) {
        Some(j) => (prev.get(j)? >> 63, next.get(j)? >> 63),
        None => (0, 0),
    };
    let target_word = target / 64;
    while let (Some(&p), Some(&c), Some(&n)) = (prev.get(k), cur.get(k), next.get(k)) {
        let forced = (p & !((p << 1) | carry_p)) | (n & !((n << 1) | carry_n));
        let mut stop = (forced | !c) & mask;
        if k == target_word {
            stop |= (1u64 << (target % 64)) & mask;
        }
        if stop != 0 {
            let b = stop.trailing_zeros();
            return if (c >> b) & 1 == 1 {
                Some(k * 64 + b as usize)
            } else {
                None
            };
        }
        carry_p = p >> 63;
        carry_n = n >> 63;
        mask = !0;
        k += 1;
    }
    None
}

/// As [`scan_forward`], towards decreasing positions: the last `s < pos`
/// that is blocked (→ `None`), `target`, or has a forced neighbour (a
/// passable adjacent cell whose successor `s + 1` there is blocked).
#[inline]
pub(crate) fn scan_backward(
    lines: &[u64],
    words: usize,
    line: usize,
    pos: usize,
    target: usize,
) -> Option<usize> {
    let base = line * words;
    let prev = lines.get(base.checked_sub(words)?..base)?;
    let cur = lines.get(base..base + words)?;
    let next = lines.get(base + words..base + 2 * words)?;
    let start = pos.checked_sub(1)?;
    let mut k = start / 64;
    let mut mask = !0u64 >> (63 - start % 64);
    // Bit 0 of the next word, shifted in as bit 63 of this one.
    let (mut carry_p, mut carry_n) = match (prev.get(k + 1), next.get(k + 1)) {
        (Some(&p), Some(&n)) => (p << 63, n << 63),
        _ => (0, 0),
    };
    let target_word = target / 64;
    loop {
        let (Some(&p), Some(&c), Some(&n)) = (prev.get(k), cur.get(k), next.get(k)) else {
            return None;
        };
        let forced = (p & !((p >> 1) | carry_p)) | (n & !((n >> 1) | carry_n));
        let mut stop = (forced | !c) & mask;
        if k == target_word {
            stop |= (1u64 << (target % 64)) & mask;
        }
        if stop != 0 {
            let b = 63 - stop.leading_zeros();
            return if (c >> b) & 1 == 1 {
                Some(k * 64 + b as usize)
            } else {
                None
            };
        }
        carry_p = p << 63;
        carry_n = n << 63;
        mask = !0;
        k = k.checked_sub(1)?;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
    fn scans_match_cell_by_cell_jumps() {
        // Deterministic pseudo-random lines of 150 cells (3 words), blocked
        // at both ends like the padded grid.
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut rnd = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let (len, nlines) = (150usize, 5usize);
        for density in [2u64, 5, 20, 50] {
            let grid: Vec<Vec<bool>> = (0..nlines)
                .map(|_| {
                    (0..len)
                        .map(|p| p != 0 && p != len - 1 && rnd() % 100 >= density)
                        .collect()
                })
                .collect();
            let words = len.div_ceil(64);
            let mut lines = vec![0u64; words * nlines];
            for (l, row) in grid.iter().enumerate() {
                for (p, &f) in row.iter().enumerate() {
                    if f {
                        lines[l * words + p / 64] |= 1 << (p % 64);
                    }
                }
            }
            for line in 1..nlines - 1 {
                for pos in 1..len - 1 {
                    let target = if pos % 3 == 0 {
                        (pos * 7) % len
                    } else {
                        usize::MAX
                    };
                    assert_eq!(
                        scan_forward(&lines, words, line, pos, target),
                        naive(&grid, line, pos, true, target),
                        "forward line {line} pos {pos} target {target}"
                    );
                    assert_eq!(
                        scan_backward(&lines, words, line, pos, target),
                        naive(&grid, line, pos, false, target),
                        "backward line {line} pos {pos} target {target}"
                    );
                }
            }
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
