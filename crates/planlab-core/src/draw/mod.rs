//! Renderer-neutral draw lists: what a frame shows, as named layers of a
//! few primitives (polylines, points, discs, segments, cell grids), in
//! world metres.
//!
//! The idea is rapier's debug-render pipeline: the core says *what* to
//! draw (a rollout, its score, whether it was admissible; a mover, its
//! velocity, its class) and a renderer says *how* (colours, widths,
//! markers). Everything that needs planning, sensing or geometry is done
//! here, so a page only paints and toggles layers (ARCHITECTURE.md: the
//! pages compute no path, collision or distance).
//!
//! A [`DrawList`] keeps every number in one `f64` buffer and every grid
//! cell in one byte buffer; its [`Item`]s say which layer and shape each
//! range is, plus two per-item attributes (`tag`, `value`) whose meaning
//! each [`Layer`] documents. That crosses the wasm boundary as three typed
//! arrays ([`DrawList::items_flat`]) whatever the number of rollouts.
//! [`episode`] builds the list of a running [`crate::sim::Episode`],
//! [`trace_frame`] the pose, movers and goals of a past trace row,
//! [`grid_plan`] and [`SearchReplay`] a grid plan and its recorded search,
//! [`apf_run`] a potential-field run and [`arm_episode`] the 7-DOF arm's
//! episode (in 3D shapes).

mod apf;
mod arm;
mod episode;
mod grid;

pub use apf::{apf_run, from_plane_xy, plane_xy, ApfDraw};
pub use arm::arm_episode;
pub use episode::{episode, trace_frame, FanColour, Request};
pub use grid::{
    grid_plan, CellInfo, CellState, GridPlanDraw, OpenEntry, Relaxed, SearchCounters, SearchReplay,
    StepExplanation, StepKind,
};

/// A named group of items a renderer can show or hide as one.
///
/// Items come out in this order (the declaration order), so a layer's
/// items are contiguous. `tag` and `value` are per item.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum Layer {
    /// The static map: one [`Shape::Cells`] item, cell bytes 0 free, 1
    /// occupied, 2 unknown.
    Map = 0,
    /// Cells the robot's scans have swept (fog of war): one
    /// [`Shape::Cells`] item, bytes 1 seen, 0 not; `value` = seen count.
    Seen,
    /// The planner's global path (a grid plan's path): one
    /// [`Shape::Polyline`], cell centres.
    GlobalPath,
    /// Key points: one [`Shape::Points`] item.
    KeyPoints,
    /// The last step's rollouts: a [`Shape::Polyline`] each; `tag` 1
    /// admissible, 0 rejected; `value` what [`Request::fan`] asks for: the
    /// total score (higher is better, the default) or one critic's
    /// normalised value ([`FanColour`]).
    Fan,
    /// The chosen rollout: one [`Shape::Polyline`]; `tag` its index in the
    /// fan.
    Chosen,
    /// The driven positions from [`Request::trail_from`] on: one
    /// [`Shape::Polyline`] (a single point when one row is new); an APF
    /// run's path; the arm's tool path (a [`Shape::Polyline3`]).
    Trail,
    /// Movers now: a [`Shape::Discs`] item each (centre, radius,
    /// velocity); `tag` the mover id, `value` the class the planner gave
    /// it (0 ordinary dynamic, 1 ordinary static, 2 special, NaN none).
    Movers,
    /// The robot: its footprint (a [`Shape::Discs`] or a four-corner
    /// [`Shape::Polygon`], `tag` 0) and its heading (one
    /// [`Shape::Segments`] from the centre to the front edge, `tag` 1).
    Robot,
    /// Goals, a one-point [`Shape::Points`] item each (a
    /// [`Shape::Points3`] for the arm): `tag` 0 the start, 1 the final
    /// goal, 2 the goal the last step steered to with `value` its kind (0
    /// final, 1 intermediate, 2 virtual, 3 temporary).
    Goals,
    /// The last scan's beams, sensor to end point (the hit, or the range
    /// limit): [`Shape::Segments`] items, `tag` 0 for beams without a
    /// return, then `tag` 1 for beams that returned (beam order within).
    LidarRays,
    /// Edges after gap removal: a one-point [`Shape::Points`] item each,
    /// `tag` the type (1 SR, 2 WR, 3 SF, 4 WF).
    LidarEdges,
    /// Obstacle patterns before expansion: a [`Shape::Polyline`] each,
    /// `tag` its index.
    LidarOpsRaw,
    /// Obstacle patterns after expansion (eq 1): a [`Shape::Polyline`]
    /// each, `tag` its index, `value` 1 for the one blocking the goal.
    LidarOps,
    /// Temporary-goal candidates: a one-point [`Shape::Points`] item each,
    /// `tag` the iteration, `value` the cost (m).
    LidarCandidates,
    /// The navigator's target: a one-point [`Shape::Points`] item with
    /// `tag` its kind (0 the goal, 1 temporary, 2 held); while a hold runs,
    /// a [`Shape::Timer`] at the robot too.
    LidarTarget,
    /// Cells free on the map but blocked after inflation: one
    /// [`Shape::Cells`] item, bytes 1 blocked, 0 not.
    Inflation,
    /// Bottom-Up feature nodes: one [`Shape::Points`] item.
    FeatureNodes,
    /// A recorded grid search's cell states (bytes 0 unseen, 1 open, 2
    /// closed): one [`Shape::Cells`] item with them all, or one
    /// [`Shape::CellPatch`] with the cells changed since the last draw.
    SearchCells,
    /// The line checks among the search's last events: a
    /// [`Shape::Segments`] item each, `tag` 1 clear, 0 blocked.
    SearchLines,
    /// The cell the search is expanding: one one-point [`Shape::Points`].
    SearchCurrent,
    /// A force field: one [`Shape::Vectors`] item over a lattice, `tag`
    /// its columns and `value` its rows (row 0 at the bottom).
    Field,
    /// Obstacles of a potential field: a [`Shape::Discs`] item each,
    /// `tag` the id, `value` the range where repulsion ends (m).
    Obstacles,
    /// Predicted (virtual) obstacles: a [`Shape::Discs`] item each (a
    /// [`Shape::Spheres`] in 3D) whose radius is the virtual range; `tag`
    /// the steps ahead (1, 2).
    Predicted,
    /// The last step's sampled candidates: a [`Shape::Segments`] item each
    /// from the point stepped from (a one-point [`Shape::Points3`] in 3D);
    /// `tag` 1 for the chosen one, `value` its cost.
    Candidates,
    /// The arm's links: a [`Shape::Capsules`] item each, `tag` the link
    /// index, `value` 1 for the tool (the last).
    Links,
    /// The moving hand: its ball ([`Shape::Spheres`]) and forearm
    /// ([`Shape::Capsules`]).
    Hand,
    /// The hand's path: [`Shape::Polyline3`] items, `tag` 0 where it went,
    /// 1 its scripted motion.
    HandPath,
    /// The costmap a laser-only robot has built so far
    /// ([`crate::sim::perception`]): one [`Shape::Cells`] item over the
    /// perceived map's frame, bytes the `costmap_2d` costs (0 free, 1–252
    /// the inflation's decay, 253 inscribed, 254 a laser mark, 255 never
    /// seen); `value` the perceived map's revision.
    Costmap,
    /// Traversal weights of a weighted map (docs/algorithms.md §weights):
    /// one [`Shape::Cells`] item over the map's frame, bytes the weight
    /// (1 ordinary … 9); absent on a unit-cost map.
    Weights,
}

impl Layer {
    /// Every layer, in item order.
    pub const ALL: [Layer; 30] = [
        Layer::Map,
        Layer::Seen,
        Layer::GlobalPath,
        Layer::KeyPoints,
        Layer::Fan,
        Layer::Chosen,
        Layer::Trail,
        Layer::Movers,
        Layer::Robot,
        Layer::Goals,
        Layer::LidarRays,
        Layer::LidarEdges,
        Layer::LidarOpsRaw,
        Layer::LidarOps,
        Layer::LidarCandidates,
        Layer::LidarTarget,
        Layer::Inflation,
        Layer::FeatureNodes,
        Layer::SearchCells,
        Layer::SearchLines,
        Layer::SearchCurrent,
        Layer::Field,
        Layer::Obstacles,
        Layer::Predicted,
        Layer::Candidates,
        Layer::Links,
        Layer::Hand,
        Layer::HandPath,
        Layer::Costmap,
        Layer::Weights,
    ];

    /// Kebab-case name (what the page's layer table lists).
    pub fn name(self) -> &'static str {
        match self {
            Layer::Map => "map",
            Layer::Seen => "seen",
            Layer::GlobalPath => "global-path",
            Layer::KeyPoints => "key-points",
            Layer::Fan => "fan",
            Layer::Chosen => "chosen",
            Layer::Trail => "trail",
            Layer::Movers => "movers",
            Layer::Robot => "robot",
            Layer::Goals => "goals",
            Layer::LidarRays => "lidar-rays",
            Layer::LidarEdges => "lidar-edges",
            Layer::LidarOpsRaw => "lidar-ops-raw",
            Layer::LidarOps => "lidar-ops",
            Layer::LidarCandidates => "lidar-candidates",
            Layer::LidarTarget => "lidar-target",
            Layer::Inflation => "inflation",
            Layer::FeatureNodes => "feature-nodes",
            Layer::SearchCells => "search-cells",
            Layer::SearchLines => "search-lines",
            Layer::SearchCurrent => "search-current",
            Layer::Field => "field",
            Layer::Obstacles => "obstacles",
            Layer::Predicted => "predicted",
            Layer::Candidates => "candidates",
            Layer::Links => "links",
            Layer::Hand => "hand",
            Layer::HandPath => "hand-path",
            Layer::Costmap => "costmap",
            Layer::Weights => "weights",
        }
    }
}

/// The frame of a [`Shape::Cells`] item of `g`: width, height,
/// resolution, origin x, origin y (the map's yaw is not drawn).
pub(crate) fn grid_frame(g: &crate::map::OccupancyGrid) -> [f64; 5] {
    let o = g.origin();
    [
        g.width() as f64,
        g.height() as f64,
        g.resolution(),
        o.x,
        o.y,
    ]
}

/// A set of layers, one bit per [`Layer`] code (`1 << layer as u8`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Layers(u32);

impl Layers {
    /// No layer.
    pub const NONE: Layers = Layers(0);
    /// Every layer.
    pub const ALL: Layers = Layers((1 << Layer::ALL.len()) - 1);

    /// The set with these bits; bits of no layer are dropped.
    pub fn from_bits(bits: u32) -> Layers {
        Layers(bits & Layers::ALL.0)
    }

    /// The bits.
    pub fn bits(self) -> u32 {
        self.0
    }

    /// This set plus `l`.
    #[must_use]
    pub fn with(self, l: Layer) -> Layers {
        Layers(self.0 | 1 << l as u8)
    }

    /// Whether `l` is in the set.
    pub fn has(self, l: Layer) -> bool {
        self.0 & (1 << l as u8) != 0
    }
}

impl FromIterator<Layer> for Layers {
    fn from_iter<I: IntoIterator<Item = Layer>>(iter: I) -> Layers {
        iter.into_iter().fold(Layers::NONE, Layers::with)
    }
}

/// How an item's numbers are laid out in [`DrawList::data`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum Shape {
    /// An open polyline: `x, y` per vertex.
    Polyline = 0,
    /// A closed polygon: `x, y` per corner.
    Polygon,
    /// Points: `x, y` each.
    Points,
    /// Discs: `x, y, radius, vx, vy` each (centre and radius in m,
    /// velocity in m/s, zero for a still one).
    Discs,
    /// Line segments: `x0, y0, x1, y1` each.
    Segments,
    /// A grid of cells: `width, height, resolution (m), origin x, origin
    /// y, first byte` (origin = the bottom-left corner), its bytes in
    /// [`DrawList::cells`] from `first byte` on, row-major, row 0 at the top.
    Cells,
    /// A countdown at a point: `x, y, left (s), period (s)`.
    Timer,
    /// Some cells of a grid: the [`Shape::Cells`] header, then the
    /// row-major index of each listed cell; their bytes in
    /// [`DrawList::cells`] from `first byte` on, one per index.
    CellPatch,
    /// Vectors at points: `x, y, vx, vy` each.
    Vectors,
    /// An open polyline in space: `x, y, z` per vertex.
    Polyline3,
    /// Points in space: `x, y, z` each.
    Points3,
    /// Balls: `x, y, z, radius` each.
    Spheres,
    /// Capsules (a segment swept by a ball): `ax, ay, az, bx, by, bz,
    /// radius` each.
    Capsules,
}

impl Shape {
    /// Numbers per element (per vertex, point, disc …; the header for
    /// cells).
    pub fn stride(self) -> usize {
        match self {
            Shape::Polyline | Shape::Polygon | Shape::Points => 2,
            Shape::Polyline3 | Shape::Points3 => 3,
            Shape::Discs => 5,
            Shape::Segments | Shape::Timer | Shape::Vectors | Shape::Spheres => 4,
            Shape::Cells | Shape::CellPatch => 6,
            Shape::Capsules => 7,
        }
    }
}

/// One item: a layer, a shape, its numbers `data[start..end]` and two
/// attributes whose meaning the [`Layer`] documents.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Item {
    /// The layer it belongs to.
    pub layer: Layer,
    /// How its numbers are laid out.
    pub shape: Shape,
    /// First index into [`DrawList::data`].
    pub start: usize,
    /// One past the last index.
    pub end: usize,
    /// An integer attribute (id, index, kind, flag).
    pub tag: f64,
    /// A measured attribute (score, class, cost, count).
    pub value: f64,
}

/// Numbers per item in [`DrawList::items_flat`]: `layer, shape, start,
/// end, tag, value`.
pub const ITEM_STRIDE: usize = 6;

/// What a frame shows: items over one number buffer and one cell buffer.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct DrawList {
    /// Every item's numbers, back to back.
    pub data: Vec<f64>,
    /// Cell bytes of the [`Shape::Cells`] items.
    pub cells: Vec<u8>,
    /// The items, in [`Layer`] order.
    pub items: Vec<Item>,
}

impl DrawList {
    /// Empties the list, keeping its buffers.
    pub fn clear(&mut self) {
        self.data.clear();
        self.cells.clear();
        self.items.clear();
    }

    /// The items of layer `l`.
    pub fn layer(&self, l: Layer) -> impl Iterator<Item = &Item> + '_ {
        self.items.iter().filter(move |i| i.layer == l)
    }

    /// An item's numbers.
    pub fn numbers(&self, item: &Item) -> &[f64] {
        &self.data[item.start..item.end]
    }

    /// A [`Shape::Cells`] or [`Shape::CellPatch`] item's bytes (empty for
    /// other shapes).
    pub fn cell_bytes(&self, item: &Item) -> &[u8] {
        let h = self.numbers(item);
        let n = match item.shape {
            Shape::Cells => h[0] as usize * h[1] as usize,
            Shape::CellPatch => h.len() - 6,
            _ => return &[],
        };
        let first = h[5] as usize;
        &self.cells[first..first + n]
    }

    /// Every item as `layer, shape, start, end, tag, value` ([`ITEM_STRIDE`]
    /// numbers each), for the wasm boundary.
    pub fn items_flat(&self) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.items.len() * ITEM_STRIDE);
        for i in &self.items {
            out.extend_from_slice(&[
                f64::from(i.layer as u8),
                f64::from(i.shape as u8),
                i.start as f64,
                i.end as f64,
                i.tag,
                i.value,
            ]);
        }
        out
    }

    /// Adds an item over `numbers`.
    pub fn push(
        &mut self,
        layer: Layer,
        shape: Shape,
        numbers: impl IntoIterator<Item = f64>,
        tag: f64,
        value: f64,
    ) {
        debug_assert!(
            !matches!(self.items.last(), Some(i) if i.layer as u8 > layer as u8),
            "items must come in layer order ({} after a later layer)",
            layer.name()
        );
        let start = self.data.len();
        self.data.extend(numbers);
        self.items.push(Item {
            layer,
            shape,
            start,
            end: self.data.len(),
            tag,
            value,
        });
    }

    /// Adds a polyline, polygon or point set through `points`.
    pub fn points(
        &mut self,
        layer: Layer,
        shape: Shape,
        points: &[[f64; 2]],
        tag: f64,
        value: f64,
    ) {
        self.push(layer, shape, points.iter().flatten().copied(), tag, value);
    }

    /// Adds a grid of cells: `frame` is `width, height, resolution, origin
    /// x, origin y`.
    pub fn grid(&mut self, layer: Layer, frame: [f64; 5], cells: &[u8], tag: f64, value: f64) {
        let first = self.cells.len() as f64;
        self.cells.extend_from_slice(cells);
        let [w, h, res, x, y] = frame;
        self.push(layer, Shape::Cells, [w, h, res, x, y, first], tag, value);
    }

    /// Adds some cells of a grid framed like [`DrawList::grid`]: `patch`
    /// holds (row-major index, byte) pairs.
    pub fn patch(&mut self, layer: Layer, frame: [f64; 5], patch: &[(usize, u8)], tag: f64) {
        let first = self.cells.len() as f64;
        self.cells.extend(patch.iter().map(|&(_, b)| b));
        let [w, h, res, x, y] = frame;
        let head = [w, h, res, x, y, first];
        let indexes = patch.iter().map(|&(k, _)| k as f64);
        self.push(
            layer,
            Shape::CellPatch,
            head.into_iter().chain(indexes),
            tag,
            0.0,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layers_are_bits_in_item_order() {
        for (i, l) in Layer::ALL.iter().enumerate() {
            assert_eq!(*l as usize, i, "{}", l.name());
        }
        let s: Layers = [Layer::Fan, Layer::Robot].into_iter().collect();
        assert!(s.has(Layer::Fan) && s.has(Layer::Robot) && !s.has(Layer::Map));
        assert_eq!(Layers::from_bits(u32::MAX), Layers::ALL);
        assert_eq!(Layers::from_bits(s.bits()), s);
        let names: std::collections::HashSet<_> = Layer::ALL.iter().map(|l| l.name()).collect();
        assert_eq!(names.len(), Layer::ALL.len());
    }

    #[test]
    fn items_flatten_with_their_ranges() {
        let mut d = DrawList::default();
        d.grid(Layer::Map, [2.0, 1.0, 0.5, -1.0, -2.0], &[1, 2], 0.0, 7.0);
        d.points(
            Layer::GlobalPath,
            Shape::Polyline,
            &[[0.0, 1.0], [2.0, 3.0]],
            0.0,
            0.0,
        );
        d.patch(
            Layer::SearchCells,
            [2.0, 1.0, 0.5, -1.0, -2.0],
            &[(1, 2)],
            0.0,
        );
        let flat = d.items_flat();
        assert_eq!(flat.len(), 3 * ITEM_STRIDE);
        assert_eq!(&flat[..ITEM_STRIDE], &[0.0, 5.0, 0.0, 6.0, 0.0, 7.0]);
        assert_eq!(
            &flat[ITEM_STRIDE..2 * ITEM_STRIDE],
            &[2.0, 0.0, 6.0, 10.0, 0.0, 0.0]
        );
        assert_eq!(d.cell_bytes(&d.items[0]), &[1, 2]);
        assert!(d.cell_bytes(&d.items[1]).is_empty());
        assert_eq!(d.numbers(&d.items[1]), &[0.0, 1.0, 2.0, 3.0]);
        // A patch: the header with its first byte, then the indexes.
        assert_eq!(
            d.numbers(&d.items[2]),
            &[2.0, 1.0, 0.5, -1.0, -2.0, 2.0, 1.0]
        );
        assert_eq!(d.cell_bytes(&d.items[2]), &[2]);
        d.clear();
        assert!(d.items.is_empty() && d.data.is_empty() && d.cells.is_empty());
    }

    // The order check is a debug assertion (a slip in drawing code, never
    // input), so only a build with debug assertions can show it.
    #[cfg(debug_assertions)]
    #[test]
    #[should_panic(expected = "layer order")]
    fn an_item_of_an_earlier_layer_after_a_later_one_is_refused() {
        let mut d = DrawList::default();
        d.points(Layer::Goals, Shape::Points, &[[0.0, 0.0]], 0.0, 0.0);
        d.points(Layer::Map, Shape::Points, &[[0.0, 0.0]], 0.0, 0.0);
    }
}
