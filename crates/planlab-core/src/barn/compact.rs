//! The compact text form of BARN worlds: a line per world, the wall once.
//!
//! ```text
//! # comments and blank lines are skipped
//! wall -4.425,0.075 -4.425,0.225 …        (the wall of the worlds below)
//! 1 <225 hex digits> 26,0;26,0;25,0;…     (id, grid, path)
//! ```
//!
//! The grid is the 900 occupied flags (interiors filled) row by row, row 0
//! first, four to a hex digit, most significant bit first. The path is
//! its (row, col) cells, `;`-separated, or `-` when empty. A `wall` line
//! gives the containment wall's centres (x,y in metres, printed so they
//! read back bit for bit) of every world line after it, until the next
//! `wall` line; the 250 public worlds share one.

use std::collections::BTreeSet;
use std::fmt::Write as _;

use super::{BarnError, BarnWorld, GRID};

/// Hex digits of a grid.
const HEX_DIGITS: usize = GRID * GRID / 4;

/// Reads the compact form (see the module doc).
pub fn parse_compact(text: &str) -> Result<Vec<BarnWorld>, BarnError> {
    let mut wall: Option<Vec<[f64; 2]>> = None;
    let mut ids = BTreeSet::new();
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let err = |message: String| BarnError::Compact {
            line: i + 1,
            message,
        };
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split_whitespace().collect();
        if fields[0] == "wall" {
            let centres = fields[1..]
                .iter()
                .map(|f| parse_pair(f, |v| v.parse::<f64>().ok().filter(|v| v.is_finite())))
                .collect::<Option<Vec<_>>>()
                .ok_or_else(|| err("a wall centre is not x,y in metres".into()))?;
            wall = Some(centres);
            continue;
        }
        let [id, hex, path] = fields[..] else {
            return Err(err(format!(
                "expected `id grid path`, got {} fields",
                fields.len()
            )));
        };
        let id: u32 = id
            .parse()
            .map_err(|_| err(format!("world id {id:?} is not a number")))?;
        if !ids.insert(id) {
            return Err(err(format!("world {id} appears twice")));
        }
        let wall = wall
            .clone()
            .ok_or_else(|| err("a world line before any `wall` line".into()))?;
        let cells = parse_cells(hex).map_err(err)?;
        let path = if path == "-" {
            Vec::new()
        } else {
            path.split(';')
                .map(|p| parse_pair(p, |v| v.parse::<i64>().ok()))
                .collect::<Option<Vec<_>>>()
                .ok_or_else(|| err(format!("path {path:?} is not row,col;row,col;…")))?
        };
        out.push(BarnWorld {
            id,
            cells,
            wall,
            path,
        });
    }
    Ok(out)
}

/// Writes `worlds` in the compact form, in their order, with a `wall` line
/// wherever the wall changes (so once when they share it). Parsing the
/// text gives `worlds` back exactly.
pub fn to_compact(worlds: &[BarnWorld]) -> String {
    let mut s = String::from(
        "# BARN worlds, planlab compact form: `wall x,y …` (containment wall of the worlds below),\n\
         # then per world `id grid path`: grid = 30x30 occupied flags, row-major, hex, MSB first;\n\
         # path = row,col;… reference cells (`-` if none).\n",
    );
    let mut wall: Option<&[[f64; 2]]> = None;
    for w in worlds {
        if wall != Some(&w.wall[..]) {
            s.push_str("wall");
            for [x, y] in &w.wall {
                // `{}` prints the shortest text that reads back bit for bit.
                let _ = write!(s, " {x},{y}");
            }
            s.push('\n');
            wall = Some(&w.wall);
        }
        let _ = write!(s, "{} ", w.id);
        let bits: Vec<bool> = w.cells.iter().flatten().copied().collect();
        for nibble in bits.chunks(4) {
            let v = nibble.iter().fold(0u32, |a, &b| (a << 1) | u32::from(b));
            s.push(char::from_digit(v, 16).unwrap_or('0'));
        }
        if w.path.is_empty() {
            s.push_str(" -");
        } else {
            for (k, [r, c]) in w.path.iter().enumerate() {
                let _ = write!(s, "{}{r},{c}", if k == 0 { ' ' } else { ';' });
            }
        }
        s.push('\n');
    }
    s
}

/// `a,b` with both halves parsed by `f`.
fn parse_pair<T>(s: &str, f: impl Fn(&str) -> Option<T>) -> Option<[T; 2]> {
    let (a, b) = s.split_once(',')?;
    Some([f(a)?, f(b)?])
}

/// The 900 flags from their 225 hex digits.
fn parse_cells(hex: &str) -> Result<[[bool; GRID]; GRID], String> {
    if hex.len() != HEX_DIGITS {
        return Err(format!(
            "grid has {} characters, expected {HEX_DIGITS} hex digits",
            hex.len()
        ));
    }
    let mut cells = [[false; GRID]; GRID];
    for (k, ch) in hex.chars().enumerate() {
        let v = ch
            .to_digit(16)
            .ok_or_else(|| format!("grid character {ch:?} is not a hex digit"))?;
        for b in 0..4 {
            let i = 4 * k + b;
            cells[i / GRID][i % GRID] = v & (8 >> b) != 0;
        }
    }
    Ok(cells)
}
