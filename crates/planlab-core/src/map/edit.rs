//! Editing a grid with shapes in world metres: freehand brush strokes,
//! rectangles and discs, rasterised into cells. The robot page sends these
//! as JSON (`{"op": "rect", "a": [x, y], "b": [x, y], "cell": "occupied"}`)
//! and the episode is rebuilt on the edited grid (see
//! [`crate::sim::Episode::edited`]).

use serde::{Deserialize, Serialize};

use super::{Cell, MapError, OccupancyGrid};
use crate::geom::segment_distance2;

/// Longest brush stroke accepted, in points (a pointer sample each).
pub const MAX_STROKE_POINTS: usize = 100_000;

/// One shape painted into the grid.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "op", rename_all = "kebab-case", deny_unknown_fields)]
pub enum MapEdit {
    /// Freehand brush: every cell whose centre lies within `radius` of the
    /// polyline through `points`. Radii under half a cell diagonal are
    /// raised to it, so a stroke is an unbroken (4-connected) wall.
    Stroke {
        /// Pointer samples, world metres.
        points: Vec<[f64; 2]>,
        /// Brush radius, m.
        radius: f64,
        /// What to paint.
        cell: Cell,
    },
    /// Every cell overlapping the axis-aligned rectangle with opposite
    /// corners `a` and `b`.
    Rect {
        /// One corner, world metres.
        a: [f64; 2],
        /// The opposite corner, world metres.
        b: [f64; 2],
        /// What to paint.
        cell: Cell,
    },
    /// Every cell whose centre lies within `radius` of `centre`, and the
    /// cell containing `centre`.
    Disc {
        /// Centre, world metres.
        centre: [f64; 2],
        /// Radius, m.
        radius: f64,
        /// What to paint.
        cell: Cell,
    },
}

fn bad(msg: String) -> MapError {
    MapError::InvalidParameter(msg)
}

fn check_point(what: &str, p: [f64; 2]) -> Result<(), MapError> {
    if p[0].is_finite() && p[1].is_finite() {
        Ok(())
    } else {
        Err(bad(format!(
            "{what} ({}, {}): must be a finite point (m)",
            p[0], p[1]
        )))
    }
}

fn check_radius(what: &str, r: f64) -> Result<(), MapError> {
    if r.is_finite() && r >= 0.0 {
        Ok(())
    } else {
        Err(bad(format!("{what} {r} m: must be a finite number ≥ 0")))
    }
}

/// Grid-local frame helper: cell boxes and centres in metres from the
/// origin, `up` counted from the bottom row.
struct Frame {
    w: usize,
    h: usize,
    res: f64,
    ox: f64,
    oy: f64,
}

impl Frame {
    fn of(grid: &OccupancyGrid) -> Result<Frame, MapError> {
        let o = grid.origin();
        if o.yaw != 0.0 {
            return Err(bad(format!(
                "map origin yaw {} rad: shapes are drawn on unrotated maps only",
                o.yaw
            )));
        }
        Ok(Frame {
            w: grid.width(),
            h: grid.height(),
            res: grid.resolution(),
            ox: o.x,
            oy: o.y,
        })
    }

    /// Column / up-row range of cells meeting the world box
    /// `[x0, x1] × [y0, y1]`, clipped to the map (empty when off it).
    fn span(&self, x0: f64, y0: f64, x1: f64, y1: f64) -> (usize, usize, usize, usize) {
        let clip = |v: f64, n: usize| v.max(0.0).min(n as f64) as usize;
        let c0 = clip(((x0 - self.ox) / self.res).floor(), self.w);
        let c1 = clip(((x1 - self.ox) / self.res).floor() + 1.0, self.w);
        let u0 = clip(((y0 - self.oy) / self.res).floor(), self.h);
        let u1 = clip(((y1 - self.oy) / self.res).floor() + 1.0, self.h);
        (c0, c1, u0, u1)
    }

    fn centre(&self, col: usize, up: usize) -> [f64; 2] {
        [
            self.ox + (col as f64 + 0.5) * self.res,
            self.oy + (up as f64 + 0.5) * self.res,
        ]
    }
}

impl MapEdit {
    /// Checks the numbers: finite points, radii ≥ 0, 1 to
    /// [`MAX_STROKE_POINTS`] stroke points.
    pub fn validate(&self) -> Result<(), MapError> {
        match self {
            MapEdit::Stroke { points, radius, .. } => {
                if points.is_empty() || points.len() > MAX_STROKE_POINTS {
                    return Err(bad(format!(
                        "stroke with {} points: needs 1 to {MAX_STROKE_POINTS}",
                        points.len()
                    )));
                }
                for (i, p) in points.iter().enumerate() {
                    check_point(&format!("stroke point {i}"), *p)?;
                }
                check_radius("brush radius", *radius)
            }
            MapEdit::Rect { a, b, .. } => {
                check_point("rectangle corner a", *a)?;
                check_point("rectangle corner b", *b)
            }
            MapEdit::Disc { centre, radius, .. } => {
                check_point("disc centre", *centre)?;
                check_radius("disc radius", *radius)
            }
        }
    }

    /// Paints the shape into `grid` (parts off the map are ignored) and
    /// returns how many cells changed.
    pub fn apply(&self, grid: &mut OccupancyGrid) -> Result<usize, MapError> {
        self.validate()?;
        let f = Frame::of(grid)?;
        let mut changed = 0;
        let mut paint = |grid: &mut OccupancyGrid, col: usize, up: usize, cell: Cell| {
            let row = f.h - 1 - up;
            if grid.get(col, row) != Some(cell) && grid.set(col, row, cell).is_ok() {
                changed += 1;
            }
        };
        match self {
            MapEdit::Stroke {
                points,
                radius,
                cell,
            } => {
                let r = radius.max(0.5 * std::f64::consts::SQRT_2 * f.res) + 1e-9 * f.res;
                let r2 = r * r;
                let segs: Vec<([f64; 2], [f64; 2])> = if points.len() == 1 {
                    vec![(points[0], points[0])]
                } else {
                    points.windows(2).map(|w| (w[0], w[1])).collect()
                };
                for (a, b) in segs {
                    let (c0, c1, u0, u1) = f.span(
                        a[0].min(b[0]) - r,
                        a[1].min(b[1]) - r,
                        a[0].max(b[0]) + r,
                        a[1].max(b[1]) + r,
                    );
                    for up in u0..u1 {
                        for col in c0..c1 {
                            if segment_distance2(f.centre(col, up), a, b) <= r2 {
                                paint(grid, col, up, *cell);
                            }
                        }
                    }
                }
            }
            MapEdit::Rect { a, b, cell } => {
                let (x0, x1) = (a[0].min(b[0]), a[0].max(b[0]));
                let (y0, y1) = (a[1].min(b[1]), a[1].max(b[1]));
                let (c0, c1, u0, u1) = f.span(x0, y0, x1, y1);
                for up in u0..u1 {
                    for col in c0..c1 {
                        paint(grid, col, up, *cell);
                    }
                }
            }
            MapEdit::Disc {
                centre,
                radius,
                cell,
            } => {
                let r2 = radius * radius;
                let (c0, c1, u0, u1) = f.span(
                    centre[0] - radius,
                    centre[1] - radius,
                    centre[0] + radius,
                    centre[1] + radius,
                );
                for up in u0..u1 {
                    for col in c0..c1 {
                        let p = f.centre(col, up);
                        let (dx, dy) = (p[0] - centre[0], p[1] - centre[1]);
                        if dx * dx + dy * dy <= r2 {
                            paint(grid, col, up, *cell);
                        }
                    }
                }
                if let Some((col, row)) = grid.world_to_cell(centre[0], centre[1]) {
                    paint(grid, col, f.h - 1 - row, *cell);
                }
            }
        }
        Ok(changed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::Pose2;

    fn grid(w: usize, h: usize) -> OccupancyGrid {
        OccupancyGrid::new(w, h)
            .unwrap()
            .with_frame(0.5, Pose2::default())
            .unwrap()
    }

    #[test]
    fn rect_covers_the_cells_it_overlaps() {
        let mut g = grid(8, 6);
        let e = MapEdit::Rect {
            a: [2.9, 0.6],
            b: [1.1, 1.4],
            cell: Cell::Occupied,
        };
        // Columns 2..=5 (x 1.0–3.0), up-rows 1..=2 (y 0.5–1.5).
        assert_eq!(e.apply(&mut g).unwrap(), 8);
        assert_eq!(g.get(2, 4), Some(Cell::Occupied));
        assert_eq!(g.get(5, 3), Some(Cell::Occupied));
        assert_eq!(g.get(6, 3), Some(Cell::Free));
        // Painting again changes nothing; erasing restores.
        assert_eq!(e.apply(&mut g).unwrap(), 0);
        let erase = MapEdit::Rect {
            a: [2.9, 0.6],
            b: [1.1, 1.4],
            cell: Cell::Free,
        };
        assert_eq!(erase.apply(&mut g).unwrap(), 8);
        assert_eq!(g.counts().1, 0);
    }

    #[test]
    fn disc_is_round_and_clipped() {
        let mut g = grid(20, 20);
        let e = MapEdit::Disc {
            centre: [5.0, 5.0],
            radius: 2.0,
            cell: Cell::Occupied,
        };
        let n = e.apply(&mut g).unwrap();
        // Area π r² = 12.57 m² = 50.3 cells of 0.25 m².
        assert!((44..=56).contains(&n), "{n}");
        let (c, r) = g.world_to_cell(5.0 + 1.9, 5.0).unwrap();
        assert_eq!(g.get(c, r), Some(Cell::Occupied));
        let (c, r) = g.world_to_cell(5.0 + 1.5, 5.0 + 1.5).unwrap();
        assert_eq!(g.get(c, r), Some(Cell::Free));
        // Partly off the map: no error, only the cells on it.
        let edge = MapEdit::Disc {
            centre: [0.0, 0.0],
            radius: 1.0,
            cell: Cell::Occupied,
        };
        assert!(edge.apply(&mut g).unwrap() > 0);
        // A tiny disc still paints its own cell.
        let dot = MapEdit::Disc {
            centre: [8.1, 8.1],
            radius: 0.0,
            cell: Cell::Occupied,
        };
        assert_eq!(dot.apply(&mut grid(20, 20)).unwrap(), 1);
    }

    #[test]
    fn stroke_is_an_unbroken_wall() {
        let mut g = grid(20, 20);
        let e = MapEdit::Stroke {
            points: vec![[0.3, 0.3], [9.7, 9.7]],
            radius: 0.0,
            cell: Cell::Occupied,
        };
        e.apply(&mut g).unwrap();
        // Diagonal through cell centres: 4-connected, so from each painted
        // cell the next diagonal one is reached through a painted side cell.
        for k in 0..19 {
            let row = 19 - k;
            assert_eq!(g.get(k, row), Some(Cell::Occupied));
            let side = g.get(k + 1, row) == Some(Cell::Occupied)
                || g.get(k, row - 1) == Some(Cell::Occupied);
            assert!(side, "gap after cell {k}");
        }
        // A thicker brush paints more.
        let mut g2 = grid(20, 20);
        let thick = MapEdit::Stroke {
            points: vec![[0.3, 5.0], [9.7, 5.0]],
            radius: 0.6,
            cell: Cell::Occupied,
        };
        let n = thick.apply(&mut g2).unwrap();
        assert_eq!(n, 20 * 2);
    }

    #[test]
    fn bad_numbers_are_errors_not_panics() {
        let mut g = grid(4, 4);
        for e in [
            MapEdit::Stroke {
                points: vec![],
                radius: 0.1,
                cell: Cell::Occupied,
            },
            MapEdit::Stroke {
                points: vec![[f64::NAN, 0.0]],
                radius: 0.1,
                cell: Cell::Occupied,
            },
            MapEdit::Disc {
                centre: [1.0, 1.0],
                radius: f64::INFINITY,
                cell: Cell::Occupied,
            },
            MapEdit::Rect {
                a: [0.0, f64::NEG_INFINITY],
                b: [1.0, 1.0],
                cell: Cell::Occupied,
            },
        ] {
            assert!(matches!(
                e.apply(&mut g),
                Err(MapError::InvalidParameter(_))
            ));
        }
        assert_eq!(g.counts().1, 0);
        let json: MapEdit =
            serde_json::from_str(r#"{"op":"disc","centre":[1,1],"radius":0.5,"cell":"occupied"}"#)
                .unwrap();
        assert!(matches!(json, MapEdit::Disc { .. }));
    }
}
