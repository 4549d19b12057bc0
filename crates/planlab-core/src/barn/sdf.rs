//! Reading a BARN world from its Gazebo SDF 1.6 file.

use std::collections::BTreeMap;

use roxmltree::{Document, Node};

use super::{BarnError, BarnWorld, CELL, GRID, GRID_X0, GRID_Y0, RADIUS, WALL_Y_MAX};

/// How far (m) a cylinder may sit from its grid cell's centre, or its
/// radius from 0.075 m: the files print six decimals.
const TOLERANCE: f64 = 1e-6;

/// Prefix of the names of the obstacle models.
const CYLINDER: &str = "unit_cylinder_";

impl BarnWorld {
    /// Reads world `id` from the bytes of its `world_N.world` file.
    ///
    /// The cylinders are the `<model name='unit_cylinder_K'>` elements of
    /// the `<world>`, each at its own `<pose>` (x y z roll pitch yaw); the
    /// `<state>` section lists them again and must agree (a pose there
    /// differing by more than a micrometre, or a cylinder only there, is
    /// an error). Cylinders with y < [`WALL_Y_MAX`] are the containment
    /// wall; every other one must sit on a grid cell centre.
    ///
    /// The generator's world writer writes no cylinder for an occupied
    /// cell whose 8 neighbours are all occupied (never for a border cell),
    /// so such interiors come back empty. They are filled back: every
    /// 8-connected group of empty cells that reaches no border cell is
    /// occupied. That recovers every left-out cell exactly, and also fills
    /// any free pocket fully enclosed by cylinders, which the file cannot
    /// tell apart from a left-out interior and which no robot can reach
    /// (4-neighbour cylinders touch).
    ///
    /// The path is left empty: set it from [`BarnWorld::path_from_npy`].
    pub fn from_sdf(id: u32, bytes: &[u8]) -> Result<BarnWorld, BarnError> {
        let text = std::str::from_utf8(bytes).map_err(|_| BarnError::NotUtf8 { id })?;
        let doc = Document::parse(text).map_err(|e| BarnError::Xml {
            id,
            message: e.to_string(),
        })?;
        let missing = |element: &str| BarnError::Missing {
            id,
            element: element.to_string(),
        };
        let bad = |model: &str, message: String| BarnError::BadModel {
            id,
            model: model.to_string(),
            message,
        };
        let world = child(doc.root_element(), "world")
            .filter(|_| doc.root_element().has_tag_name("sdf"))
            .ok_or_else(|| missing("sdf><world"))?;

        let mut models: BTreeMap<&str, [f64; 2]> = BTreeMap::new();
        for m in cylinders(world) {
            let name = m.attribute("name").unwrap_or_default();
            let pose = child(m, "pose").ok_or_else(|| missing(&format!("pose> of '{name}'")))?;
            let xy = parse_pose(pose).map_err(|msg| bad(name, msg))?;
            if let Some(r) = radius(m) {
                let r = r.map_err(|msg| bad(name, msg))?;
                if (r - RADIUS).abs() > TOLERANCE {
                    return Err(bad(name, format!("radius {r} m, BARN's are {RADIUS} m")));
                }
            }
            if models.insert(name, xy).is_some() {
                return Err(bad(name, "declared twice".into()));
            }
        }
        if models.is_empty() {
            return Err(BarnError::NoCylinders { id });
        }
        if let Some(state) = child(world, "state") {
            for m in cylinders(state) {
                let name = m.attribute("name").unwrap_or_default();
                let Some(own) = models.get(name) else {
                    return Err(bad(name, "in <state> but not declared".into()));
                };
                if let Some(pose) = child(m, "pose") {
                    let xy = parse_pose(pose).map_err(|msg| bad(name, msg))?;
                    if (xy[0] - own[0]).abs() > TOLERANCE || (xy[1] - own[1]).abs() > TOLERANCE {
                        return Err(bad(
                            name,
                            format!(
                                "<state> pose ({}, {}) differs from the model's ({}, {})",
                                xy[0], xy[1], own[0], own[1]
                            ),
                        ));
                    }
                }
            }
        }

        let mut cells = [[false; GRID]; GRID];
        let mut wall = Vec::new();
        for (name, [x, y]) in models {
            if y < WALL_Y_MAX {
                wall.push([x, y]);
                continue;
            }
            let (r, c) = ((x - GRID_X0) / CELL, (y - GRID_Y0) / CELL);
            let (ri, ci) = (r.round(), c.round());
            let on_grid = (0.0..GRID as f64).contains(&ri) && (0.0..GRID as f64).contains(&ci);
            if !on_grid || (r - ri).abs() * CELL > TOLERANCE || (c - ci).abs() * CELL > TOLERANCE {
                return Err(bad(name, format!("({x}, {y}) is on no grid cell centre")));
            }
            let cell = &mut cells[ri as usize][ci as usize];
            if *cell {
                return Err(bad(name, format!("a second cylinder on cell ({ri}, {ci})")));
            }
            *cell = true;
        }
        wall.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
        fill_interiors(&mut cells);
        Ok(BarnWorld {
            id,
            cells,
            wall,
            path: Vec::new(),
        })
    }
}

/// The first child element of `n` named `tag`.
fn child<'a, 'i>(n: Node<'a, 'i>, tag: &str) -> Option<Node<'a, 'i>> {
    n.children().find(|c| c.has_tag_name(tag))
}

/// The `unit_cylinder_*` model elements directly under `n`.
fn cylinders<'a, 'i: 'a>(n: Node<'a, 'i>) -> impl Iterator<Item = Node<'a, 'i>> + 'a {
    n.children().filter(|c| {
        c.has_tag_name("model")
            && c.attribute("name")
                .is_some_and(|name| name.starts_with(CYLINDER))
    })
}

/// x and y of a `<pose>`: six finite numbers.
fn parse_pose(pose: Node) -> Result<[f64; 2], String> {
    let text = pose.text().unwrap_or_default();
    let v: Vec<f64> = text
        .split_whitespace()
        .map(|t| t.parse::<f64>().ok().filter(|v| v.is_finite()))
        .collect::<Option<_>>()
        .ok_or_else(|| format!("pose {:?} is not six numbers", text.trim()))?;
    if v.len() != 6 {
        return Err(format!("pose {:?} is not six numbers", text.trim()));
    }
    Ok([v[0], v[1]])
}

/// The collision cylinder's radius, when the model gives one.
fn radius(model: Node) -> Option<Result<f64, String>> {
    let node = model
        .descendants()
        .find(|n| n.has_tag_name("collision"))?
        .descendants()
        .find(|n| n.has_tag_name("cylinder"))
        .and_then(|c| child(c, "radius"))?;
    let text = node.text().unwrap_or_default().trim();
    Some(
        text.parse::<f64>()
            .ok()
            .filter(|r| r.is_finite())
            .ok_or_else(|| format!("radius {text:?} is not a number")),
    )
}

/// Occupies every 8-connected group of free cells that touches no border
/// cell (see [`BarnWorld::from_sdf`]).
pub(super) fn fill_interiors(cells: &mut [[bool; GRID]; GRID]) {
    let mut seen = [[false; GRID]; GRID];
    for start in (0..GRID * GRID).map(|i| (i / GRID, i % GRID)) {
        if cells[start.0][start.1] || seen[start.0][start.1] {
            continue;
        }
        seen[start.0][start.1] = true;
        let (mut group, mut stack, mut border) = (vec![start], vec![start], false);
        while let Some((r, c)) = stack.pop() {
            border |= r == 0 || c == 0 || r == GRID - 1 || c == GRID - 1;
            for nr in r.saturating_sub(1)..=(r + 1).min(GRID - 1) {
                for nc in c.saturating_sub(1)..=(c + 1).min(GRID - 1) {
                    if !cells[nr][nc] && !seen[nr][nc] {
                        seen[nr][nc] = true;
                        group.push((nr, nc));
                        stack.push((nr, nc));
                    }
                }
            }
        }
        if !border {
            for (r, c) in group {
                cells[r][c] = true;
            }
        }
    }
}
