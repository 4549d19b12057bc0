//! The draw list of a grid plan ([`grid_plan`]: map, inflation, path, key
//! points, feature nodes, start and goal) and of its recorded search played
//! back event by event ([`SearchReplay`]: open and closed cells, the last
//! line checks, the cell being expanded). Points are cell centres in
//! metres, in the frame of the map's [`Shape::Cells`] item.

mod explain;

pub use explain::{OpenEntry, Relaxed, StepExplanation, StepKind};

use super::{grid_frame, DrawList, Layer, Layers, Shape};
use crate::global::{GridPos, SearchEvent};
use crate::map::OccupancyGrid;

/// What a grid plan shows.
#[derive(Debug, Clone, Copy)]
pub struct GridPlanDraw<'a> {
    /// The map planned on.
    pub grid: &'a OccupancyGrid,
    /// Per cell, 1 where inflation blocks a free cell (row-major), if any.
    pub inflation: Option<&'a [u8]>,
    /// The path, start to goal (empty: none).
    pub path: &'a [GridPos],
    /// Key points of the path.
    pub key_points: &'a [GridPos],
    /// Bottom-Up feature nodes.
    pub feature_nodes: &'a [GridPos],
    /// The start cell, once placed.
    pub start: Option<GridPos>,
    /// The goal cell, once placed.
    pub goal: Option<GridPos>,
}

/// The centre of cell `p` in metres, for a grid framed as `frame`.
fn centre(frame: &[f64; 5], p: GridPos) -> [f64; 2] {
    let [_, h, res, ox, oy] = *frame;
    [
        ox + (f64::from(p.col) + 0.5) * res,
        oy + (h - f64::from(p.row) - 0.5) * res,
    ]
}

fn centres(frame: &[f64; 5], cells: &[GridPos]) -> Vec<[f64; 2]> {
    cells.iter().map(|&p| centre(frame, p)).collect()
}

/// The layers of `p` in `layers` ([`Layer::Map`], [`Layer::GlobalPath`],
/// [`Layer::KeyPoints`], [`Layer::Goals`] with the start `tag` 0 and the
/// goal 1, [`Layer::Inflation`], [`Layer::FeatureNodes`], [`Layer::Weights`]), appended to
/// `out`.
pub fn grid_plan(p: &GridPlanDraw<'_>, layers: Layers, out: &mut DrawList) {
    let frame = grid_frame(p.grid);
    let want = |l| layers.has(l);
    if want(Layer::Map) {
        let cells: Vec<u8> = p.grid.cells().iter().map(|&c| c as u8).collect();
        out.grid(Layer::Map, frame, &cells, 0.0, 0.0);
    }
    if want(Layer::GlobalPath) && !p.path.is_empty() {
        let pts = centres(&frame, p.path);
        out.points(Layer::GlobalPath, Shape::Polyline, &pts, 0.0, 0.0);
    }
    if want(Layer::KeyPoints) && !p.key_points.is_empty() {
        let pts = centres(&frame, p.key_points);
        out.points(Layer::KeyPoints, Shape::Points, &pts, 0.0, 0.0);
    }
    if want(Layer::Goals) {
        for (tag, cell) in [(0.0, p.start), (1.0, p.goal)] {
            if let Some(c) = cell {
                out.points(Layer::Goals, Shape::Points, &[centre(&frame, c)], tag, 0.0);
            }
        }
    }
    if let (true, Some(mask)) = (want(Layer::Inflation), p.inflation) {
        out.grid(Layer::Inflation, frame, mask, 0.0, 0.0);
    }
    if want(Layer::FeatureNodes) && !p.feature_nodes.is_empty() {
        let pts = centres(&frame, p.feature_nodes);
        out.points(Layer::FeatureNodes, Shape::Points, &pts, 0.0, 0.0);
    }
    // Last: the highest layer code.
    if let (true, Some(w)) = (want(Layer::Weights), p.grid.weights()) {
        if p.grid.is_weighted() {
            out.grid(Layer::Weights, frame, w, 0.0, 0.0);
        }
    }
}

/// A cell's state in a search played back to some step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum CellState {
    /// Not reached yet.
    Unseen = 0,
    /// In the open set.
    Open,
    /// Expanded.
    Closed,
}

/// What a cell holds at the replay's step (hovering it shows this).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CellInfo {
    /// Its state.
    pub state: CellState,
    /// Cost from the start of its latest open event (NaN: none).
    pub g: f64,
    /// Heuristic of its latest open event (NaN: none).
    pub h: f64,
    /// `g + weight·h`.
    pub f: f64,
    /// The cell its latest open event came from.
    pub parent: Option<GridPos>,
    /// 1-based step of its first open event.
    pub opened_at: Option<usize>,
    /// 1-based step of its close event.
    pub closed_at: Option<usize>,
}

/// The search's counters at a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SearchCounters {
    /// Events applied.
    pub step: usize,
    /// Events in the recording.
    pub events: usize,
    /// Cells expanded so far.
    pub expanded: usize,
    /// Size of the open set.
    pub open: usize,
    /// f of the last expanded cell (NaN before the first).
    pub f: f64,
    /// Line checks so far.
    pub lines: usize,
}

/// "No event" in the per-cell and per-event indexes.
const NONE: u32 = u32::MAX;
/// Line checks among this many last events are drawn.
const RECENT_LINES: usize = 48;
/// The expanding cell is looked for among this many last events.
const RECENT_CLOSE: usize = 64;

/// A recorded search played back: events applied one by one to per-cell
/// states, forward or back, so a page can play, pause, step and scrub.
/// Applying or undoing an event touches one cell and [`SearchReplay::draw`]
/// sends only the cells touched since the last draw, so a frame costs the
/// events it plays, not the map size. The counters are prefix arrays built
/// once, read at any step in O(1).
#[derive(Debug, Clone)]
pub struct SearchReplay {
    frame: [f64; 5],
    w: usize,
    h: usize,
    events: Vec<SearchEvent>,
    weight: f64,
    step: usize,
    state: Vec<u8>,
    last_open: Vec<u32>,
    first_open: Vec<u32>,
    closed_at: Vec<u32>,
    /// Per event: what it overwrote (restored by stepping back).
    prev_index: Vec<u32>,
    prev_state: Vec<u8>,
    expanded_at: Vec<u32>,
    open_at: Vec<u32>,
    f_at: Vec<f64>,
    lines_at: Vec<u32>,
    dirty: Vec<u32>,
    all_dirty: bool,
}

impl SearchReplay {
    /// The replay of `events` (a search on `grid`) at step 0; f = g +
    /// `weight`·h.
    pub fn new(grid: &OccupancyGrid, events: Vec<SearchEvent>, weight: f64) -> SearchReplay {
        let (w, h) = (grid.width(), grid.height());
        let n = events.len();
        let mut r = SearchReplay {
            frame: grid_frame(grid),
            w,
            h,
            events,
            weight,
            step: 0,
            state: vec![0; w * h],
            last_open: vec![NONE; w * h],
            first_open: vec![NONE; w * h],
            closed_at: vec![NONE; w * h],
            prev_index: vec![NONE; n],
            prev_state: vec![0; n],
            expanded_at: Vec::with_capacity(n + 1),
            open_at: Vec::with_capacity(n + 1),
            f_at: Vec::with_capacity(n + 1),
            lines_at: Vec::with_capacity(n + 1),
            dirty: Vec::new(),
            all_dirty: true,
        };
        r.count();
        r
    }

    /// The prefix counters, by a dry run over a scratch state.
    fn count(&mut self) {
        let mut st = vec![CellState::Unseen; self.w * self.h];
        let mut f_of = vec![f64::NAN; self.w * self.h];
        let (mut expanded, mut open, mut lines, mut f) = (0u32, 0u32, 0u32, f64::NAN);
        self.expanded_at.push(0);
        self.open_at.push(0);
        self.f_at.push(f);
        self.lines_at.push(0);
        for i in 0..self.events.len() {
            match self.events[i] {
                SearchEvent::Open { g, h, .. } => {
                    let k = self.index(i);
                    if st[k] != CellState::Open {
                        open += 1;
                    }
                    st[k] = CellState::Open;
                    f_of[k] = g + self.weight * h;
                }
                SearchEvent::Close { .. } => {
                    let k = self.index(i);
                    if st[k] == CellState::Open {
                        open -= 1;
                    }
                    st[k] = CellState::Closed;
                    expanded += 1;
                    f = f_of[k];
                }
                SearchEvent::Line { .. } => lines += 1,
            }
            self.expanded_at.push(expanded);
            self.open_at.push(open);
            self.f_at.push(f);
            self.lines_at.push(lines);
        }
    }

    /// Map index of event `i`'s cell (off-map cells clamp; searches never
    /// send them).
    fn index(&self, i: usize) -> usize {
        let p = match self.events[i] {
            SearchEvent::Open { cell, .. } | SearchEvent::Close { cell } => cell,
            SearchEvent::Line { from, .. } => from,
        };
        let c = (p.col as usize).min(self.w - 1);
        let r = (p.row as usize).min(self.h - 1);
        r * self.w + c
    }

    /// Whether event `i` opens (true) or closes (false) a cell, and the
    /// cell's map index; `None` for a line check.
    fn cell_event(&self, i: usize) -> Option<(bool, usize)> {
        let open = match self.events[i] {
            SearchEvent::Open { .. } => true,
            SearchEvent::Close { .. } => false,
            SearchEvent::Line { .. } => return None,
        };
        Some((open, self.index(i)))
    }

    fn apply(&mut self, i: usize) {
        let Some((open, k)) = self.cell_event(i) else {
            return;
        };
        self.prev_state[i] = self.state[k];
        if open {
            self.prev_index[i] = self.last_open[k];
            self.last_open[k] = i as u32;
            if self.first_open[k] == NONE {
                self.first_open[k] = i as u32;
            }
            self.state[k] = CellState::Open as u8;
        } else {
            self.prev_index[i] = self.closed_at[k];
            self.closed_at[k] = i as u32;
            self.state[k] = CellState::Closed as u8;
        }
        self.dirty.push(k as u32);
    }

    fn undo(&mut self, i: usize) {
        let Some((open, k)) = self.cell_event(i) else {
            return;
        };
        self.state[k] = self.prev_state[i];
        if open {
            self.last_open[k] = self.prev_index[i];
            if self.first_open[k] == i as u32 {
                self.first_open[k] = NONE;
            }
        } else {
            self.closed_at[k] = self.prev_index[i];
        }
        self.dirty.push(k as u32);
    }

    /// Events in the recording.
    pub fn len(&self) -> usize {
        self.events.len()
    }

    /// Whether it has none.
    pub fn is_empty(&self) -> bool {
        self.events.is_empty()
    }

    /// Events applied: 0 (nothing) … [`SearchReplay::len`] (all).
    pub fn step(&self) -> usize {
        self.step
    }

    /// Whether every event is applied.
    pub fn done(&self) -> bool {
        self.step >= self.events.len()
    }

    /// Moves to `step` (clamped to 0…len), forward or back.
    pub fn seek(&mut self, step: usize) {
        let to = step.min(self.events.len());
        if self.step.abs_diff(to) > to {
            // Replaying from the start is cheaper than undoing most of the way.
            self.reset();
        }
        while self.step < to {
            self.apply(self.step);
            self.step += 1;
        }
        while self.step > to {
            self.step -= 1;
            self.undo(self.step);
        }
    }

    /// Back to step 0, every cell unseen.
    pub fn reset(&mut self) {
        self.state.fill(0);
        self.last_open.fill(NONE);
        self.first_open.fill(NONE);
        self.closed_at.fill(NONE);
        self.step = 0;
        self.dirty.clear();
        self.all_dirty = true;
    }

    /// The counters at `step` (clamped).
    pub fn counters_at(&self, step: usize) -> SearchCounters {
        let s = step.min(self.events.len());
        SearchCounters {
            step: s,
            events: self.events.len(),
            expanded: self.expanded_at[s] as usize,
            open: self.open_at[s] as usize,
            f: self.f_at[s],
            lines: self.lines_at[s] as usize,
        }
    }

    /// The counters at the current step.
    pub fn counters(&self) -> SearchCounters {
        self.counters_at(self.step)
    }

    /// The cell of the last applied close event among the last few: the
    /// one being expanded.
    pub fn expanding(&self) -> Option<GridPos> {
        let from = self.step.saturating_sub(RECENT_CLOSE);
        self.events[from..self.step]
            .iter()
            .rev()
            .find_map(|e| match *e {
                SearchEvent::Close { cell } => Some(cell),
                _ => None,
            })
    }

    /// What cell (`col`, `row`) holds at the current step; `None` off the
    /// map.
    pub fn info(&self, col: usize, row: usize) -> Option<CellInfo> {
        if col >= self.w || row >= self.h {
            return None;
        }
        let k = row * self.w + col;
        let (mut g, mut h, mut parent) = (f64::NAN, f64::NAN, None);
        if let Some(&SearchEvent::Open {
            g: eg,
            h: eh,
            parent: p,
            ..
        }) = self.events.get(self.last_open[k] as usize)
        {
            (g, h, parent) = (eg, eh, p);
        }
        let at = |i: u32| {
            if i == NONE {
                None
            } else {
                Some(i as usize + 1)
            }
        };
        Some(CellInfo {
            state: match self.state[k] {
                1 => CellState::Open,
                2 => CellState::Closed,
                _ => CellState::Unseen,
            },
            g,
            h,
            f: g + self.weight * h,
            parent,
            opened_at: at(self.first_open[k]),
            closed_at: at(self.closed_at[k]),
        })
    }

    /// The search layers in `layers` at the current step, appended to
    /// `out`: [`Layer::SearchCells`] (every cell after a reset or on the
    /// first draw, else a [`Shape::CellPatch`] of the cells changed since
    /// the last draw, which this draw takes), [`Layer::SearchLines`] (the
    /// line checks among the last 48 events) and [`Layer::SearchCurrent`].
    pub fn draw(&mut self, layers: Layers, out: &mut DrawList) {
        if layers.has(Layer::SearchCells) {
            if self.all_dirty {
                out.grid(Layer::SearchCells, self.frame, &self.state, 0.0, 0.0);
            } else {
                let patch: Vec<(usize, u8)> = self
                    .dirty
                    .iter()
                    .map(|&k| (k as usize, self.state[k as usize]))
                    .collect();
                out.patch(Layer::SearchCells, self.frame, &patch, 0.0);
            }
            self.all_dirty = false;
            self.dirty.clear();
        }
        if layers.has(Layer::SearchLines) {
            let recent = &self.events[self.step.saturating_sub(RECENT_LINES)..self.step];
            for clear in [false, true] {
                let segs: Vec<f64> = recent
                    .iter()
                    .filter_map(|e| match *e {
                        SearchEvent::Line { from, to, clear: c } if c == clear => Some((from, to)),
                        _ => None,
                    })
                    .flat_map(|(a, b)| {
                        let ([x0, y0], [x1, y1]) = (centre(&self.frame, a), centre(&self.frame, b));
                        [x0, y0, x1, y1]
                    })
                    .collect();
                if !segs.is_empty() {
                    let tag = f64::from(u8::from(clear));
                    out.push(Layer::SearchLines, Shape::Segments, segs, tag, 0.0);
                }
            }
        }
        if let (true, Some(c)) = (layers.has(Layer::SearchCurrent), self.expanding()) {
            let p = centre(&self.frame, c);
            out.points(Layer::SearchCurrent, Shape::Points, &[p], 0.0, 0.0);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::{Cell, Pose2};

    fn pos(col: u32, row: u32) -> GridPos {
        GridPos { col, row }
    }

    /// A 4 × 3 map, 0.5 m cells, origin (1, 2), a wall at (1, 1).
    fn grid() -> OccupancyGrid {
        let mut g = OccupancyGrid::new(4, 3)
            .and_then(|g| {
                g.with_frame(
                    0.5,
                    Pose2 {
                        x: 1.0,
                        y: 2.0,
                        yaw: 0.0,
                    },
                )
            })
            .unwrap();
        g.set(1, 1, Cell::Occupied).unwrap();
        g
    }

    #[test]
    fn a_path_of_n_cells_is_a_polyline_of_n_cell_centres_in_metres() {
        let g = grid();
        let path = [pos(0, 2), pos(1, 2), pos(2, 1), pos(3, 0)];
        let p = GridPlanDraw {
            grid: &g,
            inflation: None,
            path: &path,
            key_points: &[],
            feature_nodes: &[],
            start: Some(pos(0, 2)),
            goal: Some(pos(3, 0)),
        };
        let mut d = DrawList::default();
        grid_plan(&p, Layers::ALL, &mut d);
        let item = d.layer(Layer::GlobalPath).next().expect("a path item");
        assert_eq!(item.shape, Shape::Polyline);
        // Row 2 is the bottom row: y = 2 + 0.25; row 0 the top: 2 + 1.25.
        assert_eq!(
            d.numbers(item),
            &[1.25, 2.25, 1.75, 2.25, 2.25, 2.75, 2.75, 3.25]
        );
        for (i, (a, b)) in path.iter().zip(d.numbers(item).chunks(2)).enumerate() {
            let (x, y) = g.cell_to_world(a.col as usize, a.row as usize);
            assert_eq!([x, y], [b[0], b[1]], "point {i}");
        }
        let goals: Vec<_> = d.layer(Layer::Goals).collect();
        assert_eq!(goals.len(), 2);
        assert_eq!(
            (goals[0].tag, d.numbers(goals[0])),
            (0.0, &[1.25, 2.25][..])
        );
        assert_eq!(
            (goals[1].tag, d.numbers(goals[1])),
            (1.0, &[2.75, 3.25][..])
        );
        let map = d.layer(Layer::Map).next().expect("the map");
        assert_eq!(d.numbers(map)[..5], [4.0, 3.0, 0.5, 1.0, 2.0]);
        assert_eq!(d.cell_bytes(map)[4 + 1], 1, "the wall at (1, 1)");
        assert_eq!(d.cell_bytes(map).iter().filter(|&&b| b == 1).count(), 1);
        // None of the absent layers get an item.
        assert_eq!(d.layer(Layer::KeyPoints).count(), 0);
        assert_eq!(d.layer(Layer::Inflation).count(), 0);
        assert_eq!(d.layer(Layer::FeatureNodes).count(), 0);
    }

    #[test]
    fn grid_plan_layers_come_only_when_asked_in_layer_order() {
        let g = grid();
        let mask = [0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0];
        let kp = [pos(0, 0), pos(3, 2)];
        let p = GridPlanDraw {
            grid: &g,
            inflation: Some(&mask),
            path: &kp,
            key_points: &kp,
            feature_nodes: &kp[..1],
            start: None,
            goal: Some(pos(3, 2)),
        };
        let mut d = DrawList::default();
        grid_plan(&p, Layers::ALL, &mut d);
        let order: Vec<Layer> = d.items.iter().map(|i| i.layer).collect();
        use Layer::*;
        assert_eq!(
            order,
            [Map, GlobalPath, KeyPoints, Goals, Inflation, FeatureNodes]
        );
        let infl = d.layer(Inflation).next().unwrap();
        assert_eq!(d.cell_bytes(infl), &mask);
        let kpi = d.layer(KeyPoints).next().unwrap();
        assert_eq!(
            (kpi.shape, d.numbers(kpi)),
            (Shape::Points, &[1.25, 3.25, 2.75, 2.25][..])
        );
        assert_eq!(d.layer(Goals).next().unwrap().tag, 1.0, "the goal alone");
        let mut only = DrawList::default();
        grid_plan(&p, Layers::NONE.with(GlobalPath), &mut only);
        assert_eq!(only.items.len(), 1);
        assert!(only.cells.is_empty());
    }

    fn events() -> Vec<SearchEvent> {
        vec![
            SearchEvent::Open {
                cell: pos(0, 0),
                parent: None,
                g: 0.0,
                h: 3.0,
            },
            SearchEvent::Close { cell: pos(0, 0) },
            SearchEvent::Open {
                cell: pos(1, 0),
                parent: Some(pos(0, 0)),
                g: 1.0,
                h: 2.0,
            },
            SearchEvent::Line {
                from: pos(0, 0),
                to: pos(3, 0),
                clear: false,
            },
            SearchEvent::Open {
                cell: pos(1, 0),
                parent: Some(pos(0, 0)),
                g: 0.5,
                h: 2.0,
            },
            SearchEvent::Close { cell: pos(1, 0) },
            SearchEvent::Line {
                from: pos(1, 0),
                to: pos(3, 2),
                clear: true,
            },
        ]
    }

    #[test]
    fn replay_counts_and_steps_back_to_what_it_was() {
        let mut r = SearchReplay::new(&grid(), events(), 2.0);
        assert_eq!(r.len(), 7);
        let end = r.counters_at(7);
        assert_eq!((end.expanded, end.open, end.lines), (2, 0, 2));
        assert_eq!(end.f, 0.5 + 2.0 * 2.0, "f of the last expanded, weighted");
        let mid = r.counters_at(3);
        assert_eq!((mid.expanded, mid.open, mid.lines), (1, 1, 0));
        assert!(r.counters_at(0).f.is_nan());
        r.seek(5);
        let i = r.info(1, 0).unwrap();
        assert_eq!(i.state, CellState::Open);
        assert_eq!(
            (i.g, i.parent, i.opened_at, i.closed_at),
            (0.5, Some(pos(0, 0)), Some(3), None)
        );
        assert_eq!(r.expanding(), Some(pos(0, 0)));
        r.seek(99);
        assert!(r.done());
        assert_eq!(r.info(1, 0).unwrap().state, CellState::Closed);
        assert_eq!(r.expanding(), Some(pos(1, 0)));
        r.seek(4);
        let back = r.info(1, 0).unwrap();
        assert_eq!(
            (back.state, back.g, back.closed_at),
            (CellState::Open, 1.0, None)
        );
        r.seek(0);
        assert_eq!(r.info(0, 0).unwrap().state, CellState::Unseen);
        assert_eq!(r.info(0, 0).unwrap().opened_at, None);
        assert_eq!(r.info(4, 0), None, "off the map");
    }

    #[test]
    fn replay_draws_every_cell_once_then_only_the_changed_ones() {
        let mut r = SearchReplay::new(&grid(), events(), 1.0);
        let layers = Layers::NONE
            .with(Layer::SearchCells)
            .with(Layer::SearchLines)
            .with(Layer::SearchCurrent);
        r.seek(2);
        let mut d = DrawList::default();
        r.draw(layers, &mut d);
        let full = d.layer(Layer::SearchCells).next().unwrap();
        assert_eq!(full.shape, Shape::Cells);
        assert_eq!(d.cell_bytes(full)[..2], [CellState::Closed as u8, 0]);
        let cur = d.layer(Layer::SearchCurrent).next().unwrap();
        assert_eq!(d.numbers(cur), &[1.25, 3.25], "(0, 0)'s centre");
        assert_eq!(d.layer(Layer::SearchLines).count(), 0);

        r.seek(7);
        d.clear();
        r.draw(layers, &mut d);
        let patch = d.layer(Layer::SearchCells).next().unwrap();
        assert_eq!(patch.shape, Shape::CellPatch);
        // Events 2, 4 and 5 touch cell 1 (open, open, close); the last
        // state is sent for each.
        assert_eq!(&d.numbers(patch)[6..], &[1.0, 1.0, 1.0]);
        assert_eq!(d.cell_bytes(patch), &[2, 2, 2]);
        let lines: Vec<_> = d.layer(Layer::SearchLines).collect();
        assert_eq!(lines.iter().map(|l| l.tag).collect::<Vec<_>>(), [0.0, 1.0]);
        assert_eq!(d.numbers(lines[0]), &[1.25, 3.25, 2.75, 3.25]);
        assert_eq!(d.numbers(lines[1]), &[1.75, 3.25, 2.75, 2.25]);

        // Nothing played since: an empty patch.
        d.clear();
        r.draw(layers, &mut d);
        let none = d.layer(Layer::SearchCells).next().unwrap();
        assert!(d.cell_bytes(none).is_empty());
        // A reset sends the whole grid again.
        r.reset();
        d.clear();
        r.draw(layers, &mut d);
        let again = d.layer(Layer::SearchCells).next().unwrap();
        assert_eq!(again.shape, Shape::Cells);
        assert!(d.cell_bytes(again).iter().all(|&b| b == 0));
    }
}
