//! One call from a map and options to a planned path: inflation, the chosen
//! planner, key points and Bottom-Up feature nodes. The CLI, the wasm layer
//! and scenarios all go through [`plan_on_map`], so they agree exactly.

use super::astar::{AStar, AStarConfig};
use super::bottom_up::bottom_up_observed;
use super::classic::{Bfs, BidirectionalAStar, Greedy, IdaStar, ThetaStar};
use super::dstar_lite::DStarLitePlanner;
use super::events::ClosedCells;
use super::jps::{Jps, JpsConfig};
use super::keypoints::key_points_observed;
use super::safe_astar::{safety_index, SafeAStar, SafeAStarConfig};
use super::{
    check_weight, Diagonal, Endpoint, GridPlanner, GridPos, Heuristic, ObservedGridPlanner, Path,
    PlanError, PlanGrid, SearchObserver,
};
use crate::map::costmap::inflate;
use crate::map::{Cell, MapError, OccupancyGrid};
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Which grid planner to run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum Algorithm {
    /// A* (docs/algorithms.md §grid), with the chosen heuristic and weight.
    #[default]
    #[serde(rename = "astar")]
    AStar,
    /// Dijkstra: A* with a zero heuristic.
    #[serde(rename = "dijkstra")]
    Dijkstra,
    /// Jump Point Search (8-connected without corner cutting, or 4-connected).
    #[serde(rename = "jps")]
    Jps,
    /// JPS+: Jump Point Search reading jump distances from a table built
    /// once per map (8-connected without corner cutting).
    #[serde(rename = "jps-plus")]
    JpsPlus,
    /// Safe A* of \[S\] §1 (24-neighbourhood, safety term).
    #[serde(rename = "safe-astar")]
    SafeAStar,
    /// Breadth-first search: fewest moves.
    #[serde(rename = "bfs")]
    Bfs,
    /// Greedy best-first search: follows the heuristic alone.
    #[serde(rename = "greedy")]
    Greedy,
    /// Bidirectional A*: from both ends at once.
    #[serde(rename = "bidirectional-astar")]
    BidirectionalAStar,
    /// Iterative-deepening A*: depth-first with a growing f bound.
    #[serde(rename = "ida-star")]
    IdaStar,
    /// Theta*: any-angle paths.
    #[serde(rename = "theta-star")]
    ThetaStar,
    /// D* Lite, run once: a backward search from the goal.
    #[serde(rename = "dstar-lite")]
    DStarLite,
}

impl Algorithm {
    /// Every algorithm with its command-line / JSON name.
    pub const ALL: [(Algorithm, &'static str); 11] = [
        (Algorithm::AStar, "astar"),
        (Algorithm::Dijkstra, "dijkstra"),
        (Algorithm::Jps, "jps"),
        (Algorithm::JpsPlus, "jps-plus"),
        (Algorithm::SafeAStar, "safe-astar"),
        (Algorithm::Bfs, "bfs"),
        (Algorithm::Greedy, "greedy"),
        (Algorithm::BidirectionalAStar, "bidirectional-astar"),
        (Algorithm::IdaStar, "ida-star"),
        (Algorithm::ThetaStar, "theta-star"),
        (Algorithm::DStarLite, "dstar-lite"),
    ];

    /// The command-line / JSON name.
    pub fn name(self) -> &'static str {
        Self::ALL
            .iter()
            .find(|(a, _)| *a == self)
            .map_or("astar", |(_, n)| n)
    }

    /// Whether it returns a shortest path on the grid it searches (with the
    /// default octile heuristic and weight 1). Safe A* trades length for
    /// clearance; BFS minimises moves (shortest only 4-connected); greedy
    /// follows the heuristic; Theta*'s any-angle paths are no longer than
    /// the grid optimum but not the any-angle optimum.
    pub fn optimal(self) -> bool {
        matches!(
            self,
            Algorithm::AStar
                | Algorithm::Dijkstra
                | Algorithm::Jps
                | Algorithm::JpsPlus
                | Algorithm::BidirectionalAStar
                | Algorithm::IdaStar
                | Algorithm::DStarLite
        )
    }

    /// One line for `--help` lists.
    pub fn description(self) -> &'static str {
        match self {
            Algorithm::AStar => "A*: cost so far plus estimate to go (optimal)",
            Algorithm::Dijkstra => "Dijkstra: cheapest cell first, no estimate (optimal)",
            Algorithm::Jps => "Jump Point Search: A* that jumps along straight lines (optimal)",
            Algorithm::JpsPlus => {
                "JPS+: Jump Point Search with jump distances precomputed per map (optimal)"
            }
            Algorithm::SafeAStar => "Safe A*: A* that pays to stay away from walls",
            Algorithm::Bfs => "Breadth-first: fewest moves (shortest only 4-connected)",
            Algorithm::Greedy => {
                "Greedy best-first: follows the estimate alone (fast, not optimal)"
            }
            Algorithm::BidirectionalAStar => "Bidirectional A*: searches from both ends (optimal)",
            Algorithm::IdaStar => {
                "IDA*: depth-first with a growing cost bound (optimal, bounded work)"
            }
            Algorithm::ThetaStar => "Theta*: any-angle paths through line-of-sight shortcuts",
            Algorithm::DStarLite => {
                "D* Lite: incremental replanning, searching back from the goal (optimal)"
            }
        }
    }

    /// The paper or textbook it comes from.
    pub fn reference(self) -> &'static str {
        match self {
            Algorithm::AStar => "P. E. Hart, N. J. Nilsson, B. Raphael, \"A Formal Basis for the Heuristic Determination of Minimum Cost Paths\", IEEE Trans. SSC 4(2), 1968",
            Algorithm::Dijkstra => "E. W. Dijkstra, \"A note on two problems in connexion with graphs\", Numerische Mathematik 1, 1959",
            Algorithm::Jps => "D. Harabor, A. Grastien, \"Online Graph Pruning for Pathfinding on Grid Maps\", AAAI 2011; \"Improving Jump Point Search\", ICAPS 2014",
            Algorithm::JpsPlus => "D. Harabor, A. Grastien, \"Improving Jump Point Search\", ICAPS 2014 (JPS+: preprocessed jump distances)",
            Algorithm::SafeAStar => "[S] §1 (docs/algorithms.md §safe-astar): A* with a safety term over a 24-neighbourhood",
            Algorithm::Bfs => "E. F. Moore, \"The shortest path through a maze\", Proc. Int. Symp. Theory of Switching, 1959; Cormen et al., Introduction to Algorithms, §22.2",
            Algorithm::Greedy => "J. E. Doran, D. Michie, \"Experiments with the Graph Traverser program\", Proc. R. Soc. A 294, 1966; Russell & Norvig, AIMA, §3.5.1",
            Algorithm::BidirectionalAStar => "I. Pohl, \"Bi-directional search\", Machine Intelligence 6, 1971; average potential: Ikeda et al. 1994; stopping rule: Goldberg & Harrelson, SODA 2005",
            Algorithm::IdaStar => "R. E. Korf, \"Depth-first iterative-deepening: An optimal admissible tree search\", Artificial Intelligence 27, 1985",
            Algorithm::ThetaStar => "A. Nash, K. Daniel, S. Koenig, A. Felner, \"Theta*: Any-Angle Path Planning on Grids\", AAAI 2007",
            Algorithm::DStarLite => "S. Koenig, M. Likhachev, \"D* Lite\", AAAI 2002",
        }
    }

    /// A plain-language paragraph for a beginner: what it does, when it
    /// fails, what to look at on the canvas.
    pub fn summary(self) -> &'static str {
        match self {
            Algorithm::AStar => "A* grows the search from the start, always expanding the open cell with the smallest f = g + h: the distance walked so far plus a guess of the distance left. With a guess that never overestimates (octile, weight 1) the first time it expands the goal it has the shortest path. A weight above 1 makes it greedier: faster, up to that factor longer. On the canvas the closed cells form a teardrop pointing at the goal; in a dead end (a U-shaped wall facing the goal) it floods the whole pocket before going round.",
            Algorithm::Dijkstra => "Dijkstra's algorithm expands cells in order of their distance from the start, with no guess about the goal. It always finds the shortest path but searches in every direction equally. On the canvas the closed cells grow as a circle-like blob (an octagon on an 8-connected grid) until it touches the goal: compare its expanded count with A*'s on the same query.",
            Algorithm::Jps => "Jump Point Search finds the same shortest paths as A* but does not put every cell on the open list: from each cell it scans along straight lines (and diagonals) and stops only at jump points, where a wall ends and a new direction opens up. On the canvas watch the scan lines shoot across open space and the few jump points that get expanded. It needs uniform move costs and is refused for moves that cut corners.",
            Algorithm::JpsPlus => "JPS+ is Jump Point Search with its scans done in advance: for every cell and each of the eight directions it stores how far a jump goes before it stops at a jump point or a wall, so a search reads one number where JPS scans a line. It expands exactly the jump points JPS expands and finds the same shortest paths; it was 1.2–1.4× faster than JPS on the small arena maps and slower on 512×512 maps, whose table (8 bytes a cell) no longer fits the processor's cache. The table is built on the first query of a map and rebuilt after an edit, so it pays off when many queries share a map. On the canvas the jumps appear as single lines from jump point to jump point.",
            Algorithm::SafeAStar => "Safe A* adds to every step a penalty for walls nearby, so the path keeps clear of obstacles at the price of a little length; it also moves up to two cells at a time (a 24-cell neighbourhood) for smoother turns. The path is not the shortest. On the canvas compare it with A*'s: it runs down the middle of corridors instead of hugging corners.",
            Algorithm::Bfs => "Breadth-first search expands cells in rings: first every cell one move from the start, then two moves, and so on. It finds the path with the fewest moves, which is the shortest path on a 4-connected grid; with diagonals a diagonal step counts as one move although it is √2 long, so the path can be a little longer than the shortest. On the canvas the frontier spreads as an even wave in every direction; it never looks at where the goal is.",
            Algorithm::Greedy => "Greedy best-first search always expands the open cell that looks closest to the goal, ignoring how far it has already walked. It is often very fast in open space but its paths can be much longer than the shortest, and a wall between it and the goal traps it: it fills the pocket in front of the wall before it finds the way round. It always finds a path if one exists. On the canvas watch it dive straight at the goal and then spill along the wall.",
            Algorithm::BidirectionalAStar => "Bidirectional A* runs two A* searches at once, one from the start towards the goal and one from the goal towards the start, and stops when the best path where they meet cannot be beaten by anything still open. It finds the shortest path. On the canvas two teardrops grow towards each other; the path is joined where they meet. It helps most when one end sits in a cluttered pocket the other side would have to flood.",
            Algorithm::IdaStar => "IDA* (iterative-deepening A*) walks depth-first along one path at a time and backtracks whenever f = g + h exceeds a bound; when a round fails, it raises the bound to the smallest f it saw above it and starts again from the start. It keeps almost no memory and finds the shortest path, but on grids it re-visits the same cells in every round, so long queries get slow: this version stops with a \"search limit\" error after 2 million expansions. On the canvas watch the same region light up again and again, a little larger each round.",
            Algorithm::ThetaStar => "Theta* is A* that lets a cell take its grandparent as parent whenever the straight line between them is free, so paths are not tied to the 8 grid directions and turn only at wall corners. The path is never longer than the 8-connected shortest path, though not always the shortest possible line. On the canvas watch the line-of-sight checks (lines from grandparent to new cell) and the long straight path segments.",
            Algorithm::DStarLite => "D* Lite plans backwards from the goal and remembers its work, so when a wall appears or disappears it repairs only the part of the search the change affects instead of starting over: a robot that discovers obstacles while it drives replans cheaply. Run once, it behaves like A* searched from the goal and finds the shortest path. On the canvas paint a wall across the path: only the cells around the change re-expand, far fewer than a fresh A*.",
        }
    }
}

impl std::str::FromStr for Algorithm {
    type Err = PlanError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .iter()
            .find(|(_, n)| n.eq_ignore_ascii_case(s))
            .map(|(a, _)| *a)
            .ok_or_else(|| {
                let names: Vec<&str> = Self::ALL.iter().map(|(_, n)| *n).collect();
                PlanError::InvalidConfig(format!(
                    "unknown algorithm {s:?}; expected one of {}",
                    names.join(", ")
                ))
            })
    }
}

/// Everything that shapes a grid plan besides the map and the endpoints.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct GridPlanOptions {
    /// Planner to run.
    pub algorithm: Algorithm,
    /// A* / JPS heuristic (ignored by Dijkstra; safe A* has its own).
    pub heuristic: Heuristic,
    /// A* heuristic weight, ≥ 1 (1 = optimal).
    pub weight: f64,
    /// Diagonal move rule.
    pub diagonal: Diagonal,
    /// Treat unknown cells as free.
    pub allow_unknown: bool,
    /// Grow obstacles by this radius before planning, metres (0 = off).
    pub inflate_m: f64,
    /// Also extract key points (\[T\] §3.2.1) on the inflated map.
    pub keypoints: bool,
    /// Also run Bottom-Up segmentation (\[S\] §4.1) with this maximum error,
    /// in cells; `None` = off.
    pub bottom_up_eps: Option<f64>,
    /// Safe A* parameters (used when `algorithm` is safe A*).
    pub safe: SafeAStarConfig,
}

impl Default for GridPlanOptions {
    fn default() -> Self {
        Self {
            algorithm: Algorithm::AStar,
            heuristic: Heuristic::Octile,
            weight: 1.0,
            diagonal: Diagonal::NoCornerCutting,
            allow_unknown: false,
            inflate_m: 0.0,
            keypoints: false,
            bottom_up_eps: None,
            safe: SafeAStarConfig::default(),
        }
    }
}

/// Changes to a map's or scenario's grid plan options: the `planlab plan`
/// flags, the Python `plan` keywords. `None` / `false` keep the value.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GridPlanOverrides {
    /// Planner to run.
    pub algorithm: Option<Algorithm>,
    /// A* / JPS heuristic.
    pub heuristic: Option<Heuristic>,
    /// A* heuristic weight.
    pub weight: Option<f64>,
    /// Diagonal move rule.
    pub diagonal: Option<Diagonal>,
    /// Inflation radius, metres (checked: finite, ≥ 0).
    pub inflate_m: Option<f64>,
    /// Also treat unknown cells as free.
    pub allow_unknown: bool,
    /// Also extract key points.
    pub keypoints: bool,
    /// Bottom-Up maximum error, cells.
    pub bottom_up_eps: Option<f64>,
    /// Safe A* ε.
    pub epsilon: Option<f64>,
}

impl GridPlanOptions {
    /// These options with `o` applied. The inflation radius is checked
    /// here (`InvalidConfig("inflate …")`, the caller names its flag); the
    /// other values when a planner is built from the options.
    pub fn overridden(mut self, o: &GridPlanOverrides) -> Result<GridPlanOptions, PlanError> {
        if let Some(a) = o.algorithm {
            self.algorithm = a;
        }
        if let Some(h) = o.heuristic {
            self.heuristic = h;
        }
        if let Some(w) = o.weight {
            self.weight = w;
        }
        if let Some(d) = o.diagonal {
            self.diagonal = d;
        }
        if let Some(r) = o.inflate_m {
            if !(r.is_finite() && r >= 0.0) {
                return Err(PlanError::InvalidConfig(format!(
                    "inflate {}: must be a finite number ≥ 0 (metres)",
                    crate::num::fmt_num(r)
                )));
            }
            self.inflate_m = r;
        }
        self.allow_unknown |= o.allow_unknown;
        self.keypoints |= o.keypoints;
        if o.bottom_up_eps.is_some() {
            self.bottom_up_eps = o.bottom_up_eps;
        }
        if let Some(eps) = o.epsilon {
            self.safe.epsilon = eps;
        }
        Ok(self)
    }
}

/// A plan with everything the CLI and the page show.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GridPlan {
    /// The path; `cost` in cells.
    pub path: Path,
    /// Path length in metres: the cells' polyline length × resolution
    /// (cost × resolution on a unit-cost map, where the two agree; on
    /// weighted cells the cost is weighted and the length is not).
    pub length_m: f64,
    /// Key points, when asked for (else empty).
    pub keypoints: Vec<GridPos>,
    /// Bottom-Up feature nodes, when asked for (else empty).
    pub feature_nodes: Vec<GridPos>,
    /// Expanded cells in order, when recording was asked for (else empty).
    pub expanded_cells: Vec<GridPos>,
    /// Safety index per path node, for safe A* (else empty).
    pub safety: Vec<f64>,
    /// What the caller should know about this plan, e.g. that breadth-first
    /// search ignored the map's cell weights (else `None`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

/// Why [`plan_on_map`] failed.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum GridPlanError {
    /// The planner refused or found no path.
    #[error(transparent)]
    Plan(#[from] PlanError),
    /// Inflation refused its radius.
    #[error(transparent)]
    Map(#[from] MapError),
    /// The endpoint is free on the map but inside the inflated obstacles.
    #[error(
        "{which} ({col}, {row}) is within {} m of an obstacle: blocked after inflation", crate::num::fmt_num(*.inflate_m)
    )]
    BlockedByInflation {
        /// Start or goal.
        which: Endpoint,
        /// Column.
        col: u32,
        /// Row.
        row: u32,
        /// The inflation radius, metres.
        inflate_m: f64,
    },
}

/// The planner `options` ask for, boxed as the return type of the function
/// it is used in (`dyn GridPlanner` or `dyn ObservedGridPlanner`).
macro_rules! boxed_planner {
    ($options:expr) => {{
        let options = $options;
        // Only A* reads the weight, but a NaN is a mistake whichever planner runs.
        check_weight(options.weight)?;
        Ok(match options.algorithm {
            Algorithm::AStar => Box::new(AStar::new(AStarConfig {
                heuristic: options.heuristic,
                weight: options.weight,
                diagonal: options.diagonal,
            })?),
            Algorithm::Dijkstra => Box::new(AStar::dijkstra(options.diagonal)),
            Algorithm::Jps => Box::new(Jps::new(JpsConfig {
                heuristic: options.heuristic,
                diagonal: options.diagonal,
                preprocess: false,
            })?),
            // Always octile, as Dijkstra is always zero: the heuristic is
            // not one of its settings.
            Algorithm::JpsPlus => Box::new(Jps::new(JpsConfig {
                heuristic: Heuristic::Octile,
                diagonal: options.diagonal,
                preprocess: true,
            })?),
            Algorithm::SafeAStar => Box::new(SafeAStar::new(options.safe)?),
            Algorithm::Bfs => Box::new(Bfs {
                diagonal: options.diagonal,
            }),
            Algorithm::Greedy => Box::new(Greedy {
                diagonal: options.diagonal,
                heuristic: options.heuristic,
            }),
            Algorithm::BidirectionalAStar => Box::new(BidirectionalAStar {
                diagonal: options.diagonal,
                heuristic: options.heuristic,
            }),
            Algorithm::IdaStar => Box::new(IdaStar {
                diagonal: options.diagonal,
                heuristic: options.heuristic,
            }),
            Algorithm::ThetaStar => Box::new(ThetaStar {
                diagonal: options.diagonal,
            }),
            Algorithm::DStarLite => Box::new(DStarLitePlanner {
                diagonal: options.diagonal,
            }),
        })
    }};
}

/// Builds the boxed planner `options` ask for.
pub fn build_planner(options: &GridPlanOptions) -> Result<Box<dyn GridPlanner>, PlanError> {
    boxed_planner!(options)
}

/// As [`build_planner`], a planner whose search can be watched (the grid
/// page's recorded searches; `planlab plan` with the expanded cells).
pub fn build_observed_planner(
    options: &GridPlanOptions,
) -> Result<Box<dyn ObservedGridPlanner>, PlanError> {
    boxed_planner!(options)
}

/// The passability grid `options` imply: unknown cells per
/// `allow_unknown`, obstacles grown by `inflate_m`.
pub fn plan_grid_for(
    grid: &OccupancyGrid,
    options: &GridPlanOptions,
) -> Result<PlanGrid, GridPlanError> {
    if options.inflate_m == 0.0 {
        return Ok(PlanGrid::new(grid, options.allow_unknown));
    }
    let inflated = inflate(grid, options.inflate_m)?;
    Ok(PlanGrid::new(&inflated, options.allow_unknown))
}

/// Plans from `start` to `goal` on `grid` as `options` say
/// ([`plan_on_map_recording`] also returns the expanded cells).
///
/// ```
/// use planlab_core::global::plan::{plan_on_map, Algorithm, GridPlanOptions};
/// use planlab_core::global::GridPos;
/// use planlab_core::map::OccupancyGrid;
/// let map = OccupancyGrid::from_ascii("
/// .....
/// .###.
/// .#...
/// ").unwrap();
/// let opts = GridPlanOptions { algorithm: Algorithm::Jps, keypoints: true, ..Default::default() };
/// let plan = plan_on_map(&map, GridPos::new(0, 1), GridPos::new(4, 1), &opts).unwrap();
/// // No corner cutting: round the walls through the top row.
/// assert_eq!(plan.path.cost, 6.0);
/// assert_eq!(plan.keypoints, vec![GridPos::new(0, 1), GridPos::new(0, 0), GridPos::new(4, 0), GridPos::new(4, 1)]);
/// ```
pub fn plan_on_map(
    grid: &OccupancyGrid,
    start: GridPos,
    goal: GridPos,
    options: &GridPlanOptions,
) -> Result<GridPlan, GridPlanError> {
    let planner = build_planner(options)?;
    check_bottom_up(options)?;
    let plan_grid = plan_grid_for(grid, options)?;
    plan_plain(grid, &plan_grid, planner.as_ref(), start, goal, options)
}

/// [`plan_on_map`] on a passability grid built beforehand, so many queries
/// on one map (the Python package's `plan`, a benchmark) build it once.
/// `plan_grid` must be [`plan_grid_for`]`(grid, options)`; the result is
/// then exactly [`plan_on_map`]'s.
pub fn plan_on_plan_grid(
    grid: &OccupancyGrid,
    plan_grid: &PlanGrid,
    start: GridPos,
    goal: GridPos,
    options: &GridPlanOptions,
) -> Result<GridPlan, GridPlanError> {
    let planner = build_planner(options)?;
    check_bottom_up(options)?;
    plan_plain(grid, plan_grid, planner.as_ref(), start, goal, options)
}

/// The unobserved plan: search, then key points, Bottom-Up and safety.
fn plan_plain(
    grid: &OccupancyGrid,
    plan_grid: &PlanGrid,
    planner: &dyn GridPlanner,
    start: GridPos,
    goal: GridPos,
    options: &GridPlanOptions,
) -> Result<GridPlan, GridPlanError> {
    plan_with(grid, plan_grid, start, goal, options, &mut (), |_| {
        planner.plan(plan_grid, start, goal)
    })
}

/// As [`plan_on_map`], with the expanded cells in `expanded_cells`, in
/// expansion order (for drawing the search).
pub fn plan_on_map_recording(
    grid: &OccupancyGrid,
    start: GridPos,
    goal: GridPos,
    options: &GridPlanOptions,
) -> Result<GridPlan, GridPlanError> {
    let mut expanded = Vec::new();
    let mut plan =
        plan_on_map_observed(grid, start, goal, options, &mut ClosedCells(&mut expanded))?;
    plan.expanded_cells = expanded;
    Ok(plan)
}

/// As [`plan_on_map`], reporting every search event to `obs`: the
/// planner's opens, closes and line tests, then the segment checks of key
/// points and Bottom-Up. `expanded_cells` stays empty (the events hold them).
pub fn plan_on_map_observed(
    grid: &OccupancyGrid,
    start: GridPos,
    goal: GridPos,
    options: &GridPlanOptions,
    obs: &mut impl SearchObserver,
) -> Result<GridPlan, GridPlanError> {
    let planner = build_observed_planner(options)?;
    check_bottom_up(options)?;
    let plan_grid = plan_grid_for(grid, options)?;
    plan_on_grid_observed(
        grid,
        &plan_grid,
        planner.as_ref(),
        start,
        goal,
        options,
        obs,
    )
}

/// As [`plan_on_map_observed`] with the planning grid (`plan_grid_for(map,
/// options)`) and the planner (`build_observed_planner(options)`) already
/// built: for callers that keep both between plans and edit the grid cell
/// by cell (the grid page's session), so a replan costs about the search
/// alone.
pub fn plan_on_grid_observed<O: SearchObserver + ?Sized>(
    map: &OccupancyGrid,
    plan_grid: &PlanGrid,
    planner: &dyn ObservedGridPlanner,
    start: GridPos,
    goal: GridPos,
    options: &GridPlanOptions,
    obs: &mut O,
) -> Result<GridPlan, GridPlanError> {
    check_bottom_up(options)?;
    plan_with(map, plan_grid, start, goal, options, obs, |obs| {
        // The plain search when nobody listens: full speed, no virtual calls.
        if obs.enabled() {
            planner.plan_observed(plan_grid, start, goal, &mut &mut *obs)
        } else {
            planner.plan(plan_grid, start, goal)
        }
    })
}

/// Checks the endpoints on `plan_grid`, runs `search`, then adds key
/// points, Bottom-Up nodes (their segment checks reported to `obs`) and
/// safety indices.
fn plan_with<O: SearchObserver + ?Sized>(
    map: &OccupancyGrid,
    plan_grid: &PlanGrid,
    start: GridPos,
    goal: GridPos,
    options: &GridPlanOptions,
    obs: &mut O,
    search: impl FnOnce(&mut O) -> Result<Path, PlanError>,
) -> Result<GridPlan, GridPlanError> {
    if let Err(e) = plan_grid.check_endpoints(start, goal) {
        // Say "blocked after inflation" or "unknown" rather than a bare
        // "inside an obstacle" when the raw map has the endpoint free or
        // unknown.
        if let PlanError::Blocked { which, col, row } = e {
            let raw = map.get(col as usize, row as usize);
            if raw == Some(Cell::Unknown) && !options.allow_unknown {
                return Err(PlanError::UnknownCell { which, col, row }.into());
            }
            let raw_free = raw.is_some_and(|c| c.passable(options.allow_unknown));
            if raw_free && options.inflate_m > 0.0 {
                return Err(GridPlanError::BlockedByInflation {
                    which,
                    col,
                    row,
                    inflate_m: options.inflate_m,
                });
            }
        }
        return Err(e.into());
    }
    let path = search(obs)?;
    let keypoints = if options.keypoints {
        key_points_observed(plan_grid, &path.cells, options.diagonal, obs)
    } else {
        Vec::new()
    };
    let feature_nodes = match options.bottom_up_eps {
        Some(eps) => bottom_up_observed(plan_grid, &path.cells, eps, options.diagonal, obs)?,
        None => Vec::new(),
    };
    let safety = if options.algorithm == Algorithm::SafeAStar {
        safety_index(plan_grid, &path.cells, options.safe.window_radius)
    } else {
        Vec::new()
    };
    let weighted = plan_grid.is_weighted();
    Ok(GridPlan {
        length_m: if weighted {
            Path::polyline_length(&path.cells) * map.resolution()
        } else {
            path.cost * map.resolution()
        },
        path,
        keypoints,
        feature_nodes,
        expanded_cells: Vec::new(),
        safety,
        note: weights_note(options.algorithm, weighted).map(str::to_string),
    })
}

/// What a plan on weighted cells should say about `algorithm`: breadth-
/// first search counts moves, so it cannot honour weights by definition,
/// and greedy best-first never looks at the cost so far.
pub fn weights_note(algorithm: Algorithm, weighted: bool) -> Option<&'static str> {
    match (weighted, algorithm) {
        (true, Algorithm::Bfs) => Some(
            "breadth-first search ignores cell weights (it finds the fewest moves); \
             the cost shown is that path's weighted cost",
        ),
        (true, Algorithm::Greedy) => Some(
            "greedy best-first ignores cell weights while searching (it follows the \
             estimate alone); the cost shown is that path's weighted cost",
        ),
        _ => None,
    }
}

/// Bottom-Up's maximum error must be a finite number ≥ 0.
fn check_bottom_up(options: &GridPlanOptions) -> Result<(), GridPlanError> {
    match options.bottom_up_eps {
        Some(eps) if !(eps.is_finite() && eps >= 0.0) => Err(PlanError::InvalidConfig(format!(
            "Bottom-Up maximum error {eps} must be a finite number ≥ 0 (cells)"
        ))
        .into()),
        _ => Ok(()),
    }
}
