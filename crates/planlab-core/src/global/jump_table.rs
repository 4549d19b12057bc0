//! The jump distances of JPS+ (Harabor & Grastien 2014, "Improving Jump
//! Point Search", §JPS+): for every cell and each of the eight moves, how
//! far the jump that [`super::jps`] would scan goes before it stops, so a
//! search with the table reads one number where online JPS scans a line.
//!
//! Entry `k` of a cell, for the move [`DIRS`]`[k]`, is a signed step count:
//! `+d` when the jump stops at a *jump point* `d` steps away, `−d` when the
//! `d`-th step is blocked (so `d − 1` steps are free). A straight jump stops
//! where [`super::search::Lines`] would: at a blocked cell or at a cell with
//! a forced neighbour for that direction. A diagonal jump stops at the first
//! cell from which a straight jump along either component stops at a jump
//! point, or where the diagonal move is illegal (no corner cutting: both
//! cells beside the move must be free). The goal is not in the table: a
//! search checks it against the distances (see [`super::jps`]).
//!
//! Entries are stored as `i8`, 8 bytes a cell: the 512×512 maps' tables
//! are half as large as with `i16` and miss the cache less (maze512-1-0:
//! 12–24 % less time a query). A jump of more than 127 steps before its
//! stop is stored as `CONTINUE`, and read on from the entry 127 steps
//! ahead, which holds the same jump 127 steps shorter.
//!
//! The table is a function of the map alone, built in one sweep per
//! direction (each entry from its successor's) on the first JPS+ query and
//! kept with the [`PlanGrid`]; an edit drops it and the next query rebuilds
//! it, which is what makes JPS+ the choice for a map that many queries
//! share and online JPS the choice for a map that changes between queries.

use super::search::DIRS;
use super::{PlanError, PlanGrid};

/// The largest padded grid a table is built for: 8 bytes a cell, so 32 MiB.
pub(crate) const MAX_TABLE_CELLS: usize = 1 << 22;
/// Steps must fit an `i16`.
const MAX_SIDE: usize = i16::MAX as usize;

/// Signed jump distances per padded cell and move (see the module docs).
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct JumpTable {
    /// Steps as `i8`, 8 bytes a cell (half the `i16` table, so more of it
    /// stays in cache); [`CONTINUE`] chains a longer jump.
    entries: Vec<[i8; 8]>,
    /// Index offset of each move's step.
    steps: [isize; 8],
}

/// An entry for a jump that runs more than [`CHAIN`] steps before it stops:
/// the jump goes on from the cell `CHAIN` steps ahead, whose entry continues
/// it.
const CONTINUE: i8 = i8::MIN;
/// Steps a [`CONTINUE`] entry stands for.
const CHAIN: i16 = 127;

/// One more step in the same sense: `+d → +(d+1)`, `−d → −(d+1)`.
#[inline]
fn extend(e: i16) -> i16 {
    if e > 0 {
        e + 1
    } else {
        e - 1
    }
}

impl JumpTable {
    /// Whether `grid` is small enough for a table (a one-line error if not).
    pub(crate) fn check(grid: &PlanGrid) -> Result<(), PlanError> {
        let padded = grid.padded().len();
        if padded > MAX_TABLE_CELLS || grid.stride() > MAX_SIDE || grid.height() + 2 > MAX_SIDE {
            return Err(PlanError::InvalidConfig(format!(
                "a {}×{} grid is too large for the JPS+ jump table (at most {} cells with the \
                 border, {} MiB); use jps, which needs no table",
                grid.width(),
                grid.height(),
                MAX_TABLE_CELLS,
                (MAX_TABLE_CELLS * 8) >> 20
            )));
        }
        Ok(())
    }

    /// The table of a padded `stride`-wide bitmap (`free[i]`: passable).
    /// Callers check the size first ([`JumpTable::check`]).
    pub(crate) fn new(free: &[bool], stride: usize) -> Self {
        let n = free.len();
        let height = n / stride.max(1);
        let mut entries = vec![[-1i16; 8]; n];
        let is_free = |x: isize, y: isize| -> bool {
            x >= 0
                && y >= 0
                && (x as usize) < stride
                && (y as usize) < height
                && free[y as usize * stride + x as usize]
        };
        // Straight moves: a cell `p` entered along (dx, dy) stops the jump
        // when it is blocked or when a cell beside it is free while the one
        // beside its predecessor is blocked (a forced neighbour).
        let stops = |x: isize, y: isize, dx: isize, dy: isize| -> bool {
            if !is_free(x, y) {
                return true;
            }
            let (sx, sy) = (dy, dx);
            [1isize, -1].iter().any(|&s| {
                is_free(x + s * sx, y + s * sy) && !is_free(x + s * sx - dx, y + s * sy - dy)
            })
        };
        // Each entry depends on the next cell's along the move, so cells are
        // visited against the move's direction.
        let order = |d: isize, len: usize| -> Vec<isize> {
            let v: Vec<isize> = (0..len as isize).collect();
            if d > 0 {
                v.into_iter().rev().collect()
            } else {
                v
            }
        };
        let straight = |entries: &mut Vec<[i16; 8]>, k: usize| {
            let (dx, dy) = DIRS[k];
            for y in order(dy, height) {
                for x in order(dx, stride) {
                    let (nx, ny) = (x + dx, y + dy);
                    let e = if stops(nx, ny, dx, dy) {
                        if is_free(nx, ny) {
                            1
                        } else {
                            -1
                        }
                    } else {
                        extend(entries[ny as usize * stride + nx as usize][k])
                    };
                    entries[y as usize * stride + x as usize][k] = e;
                }
            }
        };
        for k in 0..4 {
            straight(&mut entries, k);
        }
        for (k, &(dx, dy)) in DIRS.iter().enumerate().skip(4) {
            let (kx, ky) = (dir_of(dx, 0), dir_of(0, dy));
            for y in order(dy, height) {
                for x in 0..stride as isize {
                    let (nx, ny) = (x + dx, y + dy);
                    let legal = is_free(nx, y) && is_free(x, ny) && is_free(nx, ny);
                    let e = if !legal {
                        -1
                    } else {
                        let next = entries[ny as usize * stride + nx as usize];
                        if next[kx] > 0 || next[ky] > 0 {
                            1
                        } else {
                            extend(next[k])
                        }
                    };
                    entries[y as usize * stride + x as usize][k] = e;
                }
            }
        }
        // Entries past CHAIN steps become CONTINUE: the entry CHAIN steps
        // ahead along the same move is the same jump's, CHAIN steps shorter
        // (each entry is built from its successor's).
        let narrow = |e: i16| -> i8 {
            if e.unsigned_abs() > CHAIN as u16 {
                CONTINUE
            } else {
                e as i8
            }
        };
        let steps = DIRS.map(|(dx, dy)| dy * stride as isize + dx);
        Self {
            entries: entries.iter().map(|e| e.map(narrow)).collect(),
            steps,
        }
    }

    /// The signed distance of the jump from padded cell `i` along move `k`
    /// (−1, "blocked at once", off the table).
    #[inline(always)]
    pub(crate) fn get(&self, i: usize, k: usize) -> i16 {
        let e = self.read(i, k);
        if e != CONTINUE {
            return i16::from(e);
        }
        self.chained(i, k)
    }

    /// Entry `k` of padded cell `i` as stored (−1 off the table).
    #[inline(always)]
    fn read(&self, i: usize, k: usize) -> i8 {
        self.entries
            .get(i)
            .and_then(|e| e.get(k))
            .copied()
            .unwrap_or(-1)
    }

    /// [`JumpTable::get`] for a [`CONTINUE`] entry; out of line, as long
    /// jumps are rare and every jump site would otherwise carry the loop.
    #[cold]
    #[inline(never)]
    fn chained(&self, i: usize, k: usize) -> i16 {
        let mut e = CONTINUE;
        let step = self.steps.get(k).copied().unwrap_or(0) * CHAIN as isize;
        let (mut at, mut ahead) = (i, 0i16);
        while e == CONTINUE {
            at = at.wrapping_add_signed(step);
            ahead += CHAIN;
            e = self.read(at, k);
        }
        let e = i16::from(e);
        if e > 0 {
            e + ahead
        } else {
            e - ahead
        }
    }
}

/// Index in [`DIRS`] of a move.
fn dir_of(dx: isize, dy: isize) -> usize {
    DIRS.iter().position(|&d| d == (dx, dy)).unwrap_or(0)
}
