//! Walking a ray through a grid's cells (Amanatides & Woo, "A Fast Voxel
//! Traversal Algorithm for Ray Tracing", 1987): every cell the ray
//! crosses, in order, with no per-cell rounding.

/// Grid traversal set-up on one axis, for local cell coordinate `l` (cells
/// from the grid's lower-left corner), unit direction component `d` and
/// cell size `res` (m): the step sign, the ray distance between two
/// crossings of this axis's cell boundaries, and the ray distance to the
/// first crossing.
#[inline]
pub fn axis(l: f64, d: f64, res: f64) -> (i64, f64, f64) {
    if d > 0.0 {
        (1, res / d, (l.floor() + 1.0 - l) * res / d)
    } else if d < 0.0 {
        (-1, -res / d, (l - l.floor()) * res / -d)
    } else {
        (0, f64::INFINITY, f64::INFINITY)
    }
}

/// Calls `visit(col, row)` (row 0 at the top, as the grid stores cells)
/// for every cell of a `w` × `h` grid of `res` m cells that the ray from
/// local coordinates (`lx`, `ly`) (cells, y up from the bottom) along the
/// unit direction (`dx`, `dy`) crosses, the start cell first, until the
/// ray leaves the grid, goes past `reach` m, or `visit` returns `false`.
pub fn walk(
    (w, h): (i64, i64),
    res: f64,
    (lx, ly): (f64, f64),
    (dx, dy): (f64, f64),
    reach: f64,
    mut visit: impl FnMut(i64, i64) -> bool,
) {
    let (mut cx, mut cu) = (lx.floor() as i64, ly.floor() as i64);
    let (sx, tdx, mut tmx) = axis(lx, dx, res);
    let (su, tdu, mut tmu) = axis(ly, dy, res);
    loop {
        if cx < 0 || cu < 0 || cx >= w || cu >= h || !visit(cx, h - 1 - cu) {
            return;
        }
        if tmx.min(tmu) > reach {
            return;
        }
        if tmx < tmu {
            cx += sx;
            tmx += tdx;
        } else {
            cu += su;
            tmu += tdu;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_diagonal_ray_visits_each_crossed_cell_once_in_order() {
        let mut seen = Vec::new();
        // From the middle of cell (0, 0) (bottom-left) of a 4 × 4 grid of
        // 1 m cells, 45° up-right, 3 m.
        let d = std::f64::consts::FRAC_1_SQRT_2;
        walk((4, 4), 1.0, (0.5, 0.5), (d, d), 3.0, |c, r| {
            seen.push((c, r));
            true
        });
        // Through the corners: the tie goes to the y step.
        assert_eq!(seen, vec![(0, 3), (0, 2), (1, 2), (1, 1), (2, 1)]);
        let mut n = 0;
        walk((4, 4), 1.0, (0.5, 0.5), (1.0, 0.0), 10.0, |_, _| {
            n += 1;
            n < 2
        });
        assert_eq!(n, 2);
    }
}
