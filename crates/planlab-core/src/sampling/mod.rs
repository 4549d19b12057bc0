//! Sampling-based planners for a disc robot on an occupancy grid
//! (docs/algorithms.md §sampling): RRT, RRT-Connect, RRT*, Informed RRT*,
//! PRM, Lazy PRM* and BIT*.
//!
//! Every planner is a resumable, seeded state machine: [`SamplingPlanner::step`]
//! runs a number of iterations and returns, so a caller with a clock (the
//! CLI, Python, a page) can impose a time budget by stepping in chunks. The
//! result does not depend on the chunking: the same seed and the same total
//! number of iterations give the same tree, the same events and the same
//! path. Coordinates are in cells ([`collision`]); costs are path lengths
//! in cells.

mod bitstar;
pub mod collision;
mod connect;
mod informed;
mod nn;
mod prm;
pub mod shortcut;
mod tree;

pub use collision::{DiscSpace, Point, SpaceError};

use crate::map::OccupancyGrid;
use crate::num::Rng;
use std::sync::Arc;

/// The most iterations one [`SamplingPlanner`] runs in total: a bound on
/// its memory (about a node and ten edges per iteration, a few hundred
/// megabytes at most).
pub const MAX_ITERATIONS: u64 = 2_000_000;

/// The sampling planners.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum SamplingAlgorithm {
    /// RRT (LaValle 1998): grow one tree from the start until it reaches the goal.
    Rrt,
    /// RRT-Connect (Kuffner & LaValle 2000): two trees, greedy connection.
    RrtConnect,
    /// RRT* (Karaman & Frazzoli 2011): RRT with best-parent choice and rewiring.
    #[default]
    RrtStar,
    /// Informed RRT* (Gammell et al. 2014): RRT* sampling only the ellipse
    /// of states that could improve the solution once one exists.
    InformedRrtStar,
    /// PRM (Kavraki et al. 1996): a roadmap of free samples joined to their
    /// nearest neighbours, edges checked at once.
    Prm,
    /// Lazy PRM* (Karaman & Frazzoli 2011 with Bohlin & Kavraki's lazy
    /// edges): k-nearest PRM*, edges checked only on candidate paths.
    PrmStar,
    /// BIT* (Gammell et al. 2015): batches of informed samples searched in
    /// order of potential solution cost, edges checked lazily.
    BitStar,
}

impl SamplingAlgorithm {
    /// Every algorithm with its command-line name.
    pub const ALL: [(SamplingAlgorithm, &'static str); 7] = [
        (SamplingAlgorithm::Rrt, "rrt"),
        (SamplingAlgorithm::RrtConnect, "rrt-connect"),
        (SamplingAlgorithm::RrtStar, "rrt-star"),
        (SamplingAlgorithm::InformedRrtStar, "informed-rrt-star"),
        (SamplingAlgorithm::Prm, "prm"),
        (SamplingAlgorithm::PrmStar, "prm-star"),
        (SamplingAlgorithm::BitStar, "bit-star"),
    ];

    /// The command-line name.
    pub fn name(self) -> &'static str {
        Self::ALL
            .iter()
            .find(|(a, _)| *a == self)
            .map_or("rrt-star", |(_, n)| n)
    }

    /// The algorithm of a command-line name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.iter().find(|(_, n)| *n == name).map(|(a, _)| *a)
    }

    /// Whether it keeps improving its solution (asymptotically optimal);
    /// RRT and RRT-Connect stop at their first path.
    pub fn optimizing(self) -> bool {
        !matches!(self, SamplingAlgorithm::Rrt | SamplingAlgorithm::RrtConnect)
    }

    /// One line for `--help` lists.
    pub fn description(self) -> &'static str {
        match self {
            SamplingAlgorithm::Rrt => "RRT: one random tree from the start, stops at the first path",
            SamplingAlgorithm::RrtConnect => {
                "RRT-Connect: trees from both ends that try to meet, stops at the first path"
            }
            SamplingAlgorithm::RrtStar => {
                "RRT*: random tree that picks the cheapest parent and rewires (asymptotically optimal)"
            }
            SamplingAlgorithm::InformedRrtStar => {
                "Informed RRT*: RRT* sampling only where a shorter path could lie"
            }
            SamplingAlgorithm::Prm => "PRM: random roadmap, nearest neighbours, edges checked at once",
            SamplingAlgorithm::PrmStar => {
                "Lazy PRM*: k-nearest roadmap, edges checked only on candidate paths (asymptotically optimal)"
            }
            SamplingAlgorithm::BitStar => {
                "BIT*: batches of informed samples searched best-first, lazy edges (asymptotically optimal)"
            }
        }
    }
}

/// How a planner is set up.
#[derive(Clone, Debug, PartialEq)]
pub struct SamplingOptions {
    /// Which planner.
    pub algorithm: SamplingAlgorithm,
    /// Seed of the planner's random stream.
    pub seed: u64,
    /// Longest edge a tree grows at a time (RRT family, PRM's connection
    /// distance), cells; `None`: a tenth of the map's diagonal, at least 2.
    pub range: Option<f64>,
    /// Probability of sampling the goal (RRT, RRT*, Informed RRT*).
    pub goal_bias: f64,
    /// Probability that a uniform sample is moved to the centre of its cell
    /// (every planner). On a grid, the corridors one cell wide that a disc
    /// of less than half a cell can pass leave it a tube a few tenths of a
    /// cell wide around the cells' centre line, which uniform samples
    /// almost never hit; a segment between two centres of such a corridor
    /// runs down that line. The other samples stay uniform, so the
    /// planners keep their guarantees.
    pub centre_bias: f64,
    /// Samples per batch (BIT*).
    pub batch_size: usize,
    /// Keep the event log (off for benchmarks).
    pub record_events: bool,
}

impl Default for SamplingOptions {
    fn default() -> Self {
        Self {
            algorithm: SamplingAlgorithm::default(),
            seed: 0,
            range: None,
            goal_bias: 0.05,
            centre_bias: 0.5,
            batch_size: 100,
            record_events: false,
        }
    }
}

/// Why a planner cannot be set up.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SamplingError {
    /// The free space could not be built.
    #[error(transparent)]
    Space(#[from] SpaceError),
    /// An endpoint's disc overlaps a blocked cell or leaves the map.
    #[error("{which} ({x}, {y}) is in collision for a disc of radius {radius} cells")]
    InCollision {
        /// "start" or "goal".
        which: &'static str,
        /// x, cells.
        x: f64,
        /// y, cells.
        y: f64,
        /// The disc's radius.
        radius: f64,
    },
    /// An option is out of range.
    #[error("{0}")]
    BadOption(String),
}

/// What a planner did, for watching the tree grow (a page replays the log).
/// Node ids index the planner's points; coordinates are cells.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Event {
    /// A random sample was drawn.
    Sample {
        /// x, cells.
        x: f32,
        /// y, cells.
        y: f32,
    },
    /// A node joined the tree or roadmap.
    Node {
        /// Its id.
        node: u32,
        /// x, cells.
        x: f32,
        /// y, cells.
        y: f32,
    },
    /// An edge was added (trees: parent → child).
    Edge {
        /// One end (a tree's parent).
        from: u32,
        /// The other end (a tree's child).
        to: u32,
    },
    /// A lazy edge turned out to collide and was removed (Lazy PRM*).
    RemoveEdge {
        /// One end.
        from: u32,
        /// The other end.
        to: u32,
    },
    /// The two trees of RRT-Connect met along the edge `a — b`.
    Connect {
        /// The node of the tree grown from the start.
        a: u32,
        /// The node of the tree grown from the goal.
        b: u32,
    },
    /// A node changed parent.
    Rewire {
        /// The node.
        node: u32,
        /// Its old parent.
        old_parent: u32,
        /// Its new parent.
        new_parent: u32,
    },
    /// A node left the tree (BIT*'s pruning).
    Prune {
        /// The node.
        node: u32,
    },
    /// A better solution was found.
    Solution {
        /// The iteration that found it (1-based).
        iteration: u64,
        /// Its cost, cells.
        cost: f64,
    },
}

impl Event {
    /// The event as flat numbers: a kind (0 sample, 1 node, 2 edge,
    /// 3 remove edge, 4 connect, 5 rewire, 6 prune, 7 solution), three ids
    /// and two coordinates (unused ones 0; a solution's iteration is the
    /// first id, saturated at `u32::MAX`, and its cost the first number).
    pub fn flat(&self) -> (u8, [u32; 3], [f64; 2]) {
        match *self {
            Event::Sample { x, y } => (0, [0; 3], [x as f64, y as f64]),
            Event::Node { node, x, y } => (1, [node, 0, 0], [x as f64, y as f64]),
            Event::Edge { from, to } => (2, [from, to, 0], [0.0; 2]),
            Event::RemoveEdge { from, to } => (3, [from, to, 0], [0.0; 2]),
            Event::Connect { a, b } => (4, [a, b, 0], [0.0; 2]),
            Event::Rewire {
                node,
                old_parent,
                new_parent,
            } => (5, [node, old_parent, new_parent], [0.0; 2]),
            Event::Prune { node } => (6, [node, 0, 0], [0.0; 2]),
            Event::Solution { iteration, cost } => (
                7,
                [u32::try_from(iteration).unwrap_or(u32::MAX), 0, 0],
                [cost, 0.0],
            ),
        }
    }
}

/// What every planner shares: the space, the random stream, the counters,
/// the best solution and the log.
#[derive(Debug, Clone)]
pub(crate) struct Common {
    pub(crate) space: Arc<DiscSpace>,
    pub(crate) rng: Rng,
    pub(crate) start: Point,
    pub(crate) goal: Point,
    pub(crate) range: f64,
    pub(crate) goal_bias: f64,
    pub(crate) centre_bias: f64,
    pub(crate) iteration: u64,
    pub(crate) best: f64,
    pub(crate) path: Vec<Point>,
    pub(crate) solutions: Vec<(u64, f64)>,
    pub(crate) events: Option<Vec<Event>>,
}

/// Relative margin below which a new cost does not count as an improvement
/// (so rounding never records a "better" equal path).
const IMPROVEMENT: f64 = 1e-9;

impl Common {
    pub(crate) fn log(&mut self, e: Event) {
        if let Some(ev) = &mut self.events {
            ev.push(e);
        }
    }

    pub(crate) fn log_node(&mut self, node: u32, p: Point) {
        self.log(Event::Node {
            node,
            x: p[0] as f32,
            y: p[1] as f32,
        });
    }

    pub(crate) fn log_sample(&mut self, p: Point) {
        self.log(Event::Sample {
            x: p[0] as f32,
            y: p[1] as f32,
        });
    }

    /// Whether `cost` beats the best solution.
    pub(crate) fn improves(&self, cost: f64) -> bool {
        cost.is_finite() && cost < self.best * (1.0 - IMPROVEMENT)
    }

    /// Whether the best path is as short as the straight line from start to
    /// goal: nothing can beat it, and the informed set (an ellipse with
    /// those foci) has collapsed to that segment, where sampling more only
    /// piles points on one line.
    pub(crate) fn optimal(&self) -> bool {
        self.best <= dist(self.start, self.goal) * (1.0 + IMPROVEMENT)
    }

    /// Records a better solution (the caller checked [`Common::improves`]).
    pub(crate) fn solved(&mut self, cost: f64, path: Vec<Point>) {
        self.best = cost;
        self.path = path;
        self.solutions.push((self.iteration, cost));
        self.log(Event::Solution {
            iteration: self.iteration,
            cost,
        });
    }

    /// A uniform point of the box of allowed centres, moved to the centre
    /// of its cell with probability `centre_bias`.
    pub(crate) fn uniform(&mut self) -> Point {
        let (lo, hi) = self.space.bounds();
        let p = [self.rng.range(lo[0], hi[0]), self.rng.range(lo[1], hi[1])];
        if self.centre_bias > 0.0 && self.rng.uniform() < self.centre_bias {
            [
                (p[0].floor() + 0.5).clamp(lo[0], hi[0]),
                (p[1].floor() + 0.5).clamp(lo[1], hi[1]),
            ]
        } else {
            p
        }
    }
}

pub(crate) fn dist(a: Point, b: Point) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// The point `range` from `from` towards `to`, or `to` when closer.
pub(crate) fn steer(from: Point, to: Point, range: f64) -> Point {
    let d = dist(from, to);
    if d <= range {
        to
    } else {
        let t = range / d;
        [
            from[0] + (to[0] - from[0]) * t,
            from[1] + (to[1] - from[1]) * t,
        ]
    }
}

/// The shortest step a tree takes when a collision cuts its extension
/// short, cells.
const MIN_STEP: f64 = 0.25;

/// Where a tree at `from` grows towards `q`: the point `range` along (or
/// `q`), cut short before the first collision when the disc cannot go all
/// the way, so that trees creep along walls and through clutter instead of
/// discarding every long extension that clips an obstacle. `None` when the
/// step would be shorter than [`MIN_STEP`] (or zero).
pub(crate) fn extend_free(space: &DiscSpace, from: Point, q: Point, range: f64) -> Option<Point> {
    let target = steer(from, q, range);
    if target == from {
        return None;
    }
    if space.segment_free(from, target) {
        return Some(target);
    }
    let cut = space.free_prefix(from, target);
    (dist(from, cut) >= MIN_STEP && space.segment_free(from, cut)).then_some(cut)
}

/// The length of a polyline, cells.
pub fn path_cost(path: &[Point]) -> f64 {
    path.windows(2).map(|w| dist(w[0], w[1])).sum()
}

/// One planner's own state.
#[derive(Debug, Clone)]
enum Engine {
    Tree(tree::TreePlanner),
    Connect(connect::ConnectPlanner),
    Prm(prm::PrmPlanner),
    Bit(bitstar::BitStar),
}

/// A sampling planner between two points of a [`DiscSpace`], stepped from
/// outside.
#[derive(Debug, Clone)]
pub struct SamplingPlanner {
    algorithm: SamplingAlgorithm,
    common: Common,
    engine: Engine,
}

impl SamplingPlanner {
    /// A planner from `start` to `goal` (cell coordinates) in `space`.
    /// Both discs must be free; the options must be in range.
    pub fn new(
        space: Arc<DiscSpace>,
        start: Point,
        goal: Point,
        options: &SamplingOptions,
    ) -> Result<Self, SamplingError> {
        for (which, p) in [("start", start), ("goal", goal)] {
            if !space.point_free(p) {
                return Err(SamplingError::InCollision {
                    which,
                    x: p[0],
                    y: p[1],
                    radius: space.radius(),
                });
            }
        }
        let diagonal = (space.width() as f64).hypot(space.height() as f64);
        let range = match options.range {
            None => (0.1 * diagonal).max(2.0),
            Some(r) if r.is_finite() && r > 0.0 => r,
            Some(r) => {
                return Err(SamplingError::BadOption(format!(
                    "range {r}: must be a positive number of cells"
                )))
            }
        };
        if !(0.0..1.0).contains(&options.goal_bias) {
            return Err(SamplingError::BadOption(format!(
                "goal bias {}: must be in [0, 1)",
                options.goal_bias
            )));
        }
        if !(0.0..=1.0).contains(&options.centre_bias) {
            return Err(SamplingError::BadOption(format!(
                "centre bias {}: must be in [0, 1]",
                options.centre_bias
            )));
        }
        if !(1..=100_000).contains(&options.batch_size) {
            return Err(SamplingError::BadOption(format!(
                "batch size {}: must be 1 to 100000",
                options.batch_size
            )));
        }
        let mut common = Common {
            space,
            rng: Rng::new(options.seed),
            start,
            goal,
            range,
            goal_bias: options.goal_bias,
            centre_bias: options.centre_bias,
            iteration: 0,
            best: f64::INFINITY,
            path: Vec::new(),
            solutions: Vec::new(),
            events: options.record_events.then(Vec::new),
        };
        let engine = match options.algorithm {
            SamplingAlgorithm::Rrt => {
                Engine::Tree(tree::TreePlanner::new(&mut common, tree::Variant::Rrt))
            }
            SamplingAlgorithm::RrtStar => {
                Engine::Tree(tree::TreePlanner::new(&mut common, tree::Variant::Star))
            }
            SamplingAlgorithm::InformedRrtStar => {
                Engine::Tree(tree::TreePlanner::new(&mut common, tree::Variant::Informed))
            }
            SamplingAlgorithm::RrtConnect => {
                Engine::Connect(connect::ConnectPlanner::new(&mut common))
            }
            SamplingAlgorithm::Prm => Engine::Prm(prm::PrmPlanner::new(&mut common, false)),
            SamplingAlgorithm::PrmStar => Engine::Prm(prm::PrmPlanner::new(&mut common, true)),
            SamplingAlgorithm::BitStar => {
                Engine::Bit(bitstar::BitStar::new(&mut common, options.batch_size))
            }
        };
        Ok(Self {
            algorithm: options.algorithm,
            common,
            engine,
        })
    }

    /// Runs up to `iterations` more iterations (fewer when the planner is
    /// [done](SamplingPlanner::done) or reaches [`MAX_ITERATIONS`]); returns
    /// how many ran. An iteration is one sample (RRT family, PRM) or one
    /// edge taken from BIT*'s queue (or the start of its next batch).
    pub fn step(&mut self, iterations: u64) -> u64 {
        let mut ran = 0;
        while ran < iterations && !self.done() && self.common.iteration < MAX_ITERATIONS {
            self.common.iteration += 1;
            match &mut self.engine {
                Engine::Tree(t) => t.iterate(&mut self.common),
                Engine::Connect(c) => c.iterate(&mut self.common),
                Engine::Prm(p) => p.iterate(&mut self.common),
                Engine::Bit(b) => b.iterate(&mut self.common),
            }
            ran += 1;
        }
        ran
    }

    /// Whether stepping can change nothing more: RRT and RRT-Connect once
    /// they have a path (they do not optimise), any planner once its path
    /// is the straight line from start to goal, or the iteration limit.
    pub fn done(&self) -> bool {
        (!self.algorithm.optimizing() && self.common.best.is_finite())
            || self.common.optimal()
            || self.common.iteration >= MAX_ITERATIONS
    }

    /// The algorithm.
    pub fn algorithm(&self) -> SamplingAlgorithm {
        self.algorithm
    }

    /// The space it plans in.
    pub fn space(&self) -> &Arc<DiscSpace> {
        &self.common.space
    }

    /// Iterations run so far.
    pub fn iterations(&self) -> u64 {
        self.common.iteration
    }

    /// The cost of the best path so far, cells.
    pub fn best_cost(&self) -> Option<f64> {
        self.common.best.is_finite().then_some(self.common.best)
    }

    /// The iteration that found the first path.
    pub fn first_solution_iteration(&self) -> Option<u64> {
        self.common.solutions.first().map(|s| s.0)
    }

    /// Every improvement: (iteration, cost), costs strictly decreasing.
    pub fn solutions(&self) -> &[(u64, f64)] {
        &self.common.solutions
    }

    /// The best path so far, start to goal (empty before the first).
    pub fn path(&self) -> &[Point] {
        &self.common.path
    }

    /// The points the planner holds (tree or roadmap nodes, BIT*'s samples).
    pub fn node_count(&self) -> usize {
        match &self.engine {
            Engine::Tree(t) => t.len(),
            Engine::Connect(c) => c.len(),
            Engine::Prm(p) => p.len(),
            Engine::Bit(b) => b.len(),
        }
    }

    /// The event log so far (empty unless recorded).
    pub fn events(&self) -> &[Event] {
        self.common.events.as_deref().unwrap_or(&[])
    }

    /// Takes the events logged since the last call, leaving the log empty.
    pub fn take_events(&mut self) -> Vec<Event> {
        self.common
            .events
            .as_mut()
            .map(std::mem::take)
            .unwrap_or_default()
    }
}

/// The centre of cell `(col, row)`.
pub fn cell_centre(col: u32, row: u32) -> Point {
    [col as f64 + 0.5, row as f64 + 0.5]
}

/// One planning run on a grid, for callers without a clock: builds the
/// space, runs `iterations` and returns the planner.
pub fn plan_on_grid(
    grid: &OccupancyGrid,
    radius: f64,
    allow_unknown: bool,
    start: Point,
    goal: Point,
    options: &SamplingOptions,
    iterations: u64,
) -> Result<SamplingPlanner, SamplingError> {
    let space = Arc::new(DiscSpace::new(grid, radius, allow_unknown)?);
    let mut planner = SamplingPlanner::new(space, start, goal, options)?;
    planner.step(iterations);
    Ok(planner)
}
