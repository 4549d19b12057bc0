//! Moving AI Lab grid benchmark files: `.map` and `.scen`
//! (N. Sturtevant, "Benchmarks for Grid-Based Pathfinding", 2012).
//!
//! # `.map`
//! ```text
//! type octile
//! height 4
//! width 5
//! map
//! .....
//! .@@..
//! ..T..
//! .....
//! ```
//! `height` and `width` may come in either order; `type` is optional and its
//! value is not checked (every published set says `octile`). `.` `G` `S` are
//! passable (`S` is swamp: passable, and planlab gives it no extra cost), `@`
//! `O` `T` `W` are blocked. Rows are the map's rows top to bottom, `x` =
//! column, `y` = row. CRLF line ends, trailing whitespace on any line and
//! trailing blank lines are tolerated; anything else after the last row is an
//! error. The grid gets resolution 1 m and origin (0, 0).
//!
//! # `.scen`
//! A `version 1` (or `version 1.0`) line, then one row per query with nine
//! fields separated by tabs or spaces: bucket, map name, map width, map
//! height, start x, start y, goal x, goal y, optimal length. A file without a
//! version line is accepted when its first line is already a valid row (some
//! tools strip it); any other version is refused. Blank lines are skipped.
//! Optimal lengths assume 8-connectivity, diagonal cost √2 and no corner
//! cutting.

use crate::map::GridPos;
use crate::map::{check_dimensions, Cell, MapError, OccupancyGrid};
use serde::{Deserialize, Serialize};

const MAP_FORMAT: &str = "Moving AI map";
const SCEN_FORMAT: &str = "Moving AI scenario";

/// Lines of `text` with their 1-based numbers, CR and trailing whitespace
/// removed (files written on Windows or by hand end lines in `\r` or spaces).
fn numbered_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.split('\n')
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim_end()))
}

/// Parses a header number (`height 49`).
fn header_number(value: &str, key: &str, line: usize) -> Result<u64, MapError> {
    let value = value.trim();
    if value.is_empty() {
        return Err(MapError::parse(
            MAP_FORMAT,
            line,
            format!("`{key}` needs a number"),
        ));
    }
    value.parse::<u64>().map_err(|_| {
        MapError::parse(
            MAP_FORMAT,
            line,
            format!("`{key}` must be a whole number, got {value:?}"),
        )
    })
}

/// Parses a Moving AI `.map` file.
///
/// The grid has resolution 1 m per cell and origin (0, 0). Dimensions are
/// checked with [`check_dimensions`] before any cell storage is allocated.
///
/// ```
/// use planlab_core::map::{io::movingai, Cell};
/// let g = movingai::parse_map("type octile\nheight 2\nwidth 3\nmap\n.@.\nT..\n").unwrap();
/// assert_eq!((g.width(), g.height()), (3, 2));
/// assert_eq!(g.get(1, 0), Some(Cell::Occupied));
/// assert_eq!(g.get(0, 1), Some(Cell::Occupied));
/// ```
pub fn parse_map(text: &str) -> Result<OccupancyGrid, MapError> {
    // Trailing blank lines and spaces carry nothing; dropping them first makes
    // a truncated file report "N rows, expected H" instead of an empty row.
    let text = text.trim_end();
    if text.is_empty() {
        return Err(MapError::parse(MAP_FORMAT, 0, "file is empty"));
    }
    let mut lines = numbered_lines(text);
    let mut height: Option<u64> = None;
    let mut width: Option<u64> = None;
    let mut last_line = 0;
    let mut any_header = false;
    // Header: key/value lines until `map`.
    loop {
        let Some((n, line)) = lines.next() else {
            let missing = match (height, width) {
                (None, _) => "`height`",
                (_, None) => "`width`",
                _ => "the `map` line",
            };
            return Err(MapError::parse(
                MAP_FORMAT,
                last_line,
                format!("file ends before the header is complete: missing {missing}"),
            ));
        };
        last_line = n;
        let line = line.trim_start();
        if line.is_empty() {
            continue;
        }
        let (key, value) = match line.split_once(char::is_whitespace) {
            Some((k, v)) => (k, v),
            None => (line, ""),
        };
        let first = !any_header;
        any_header = true;
        match key {
            "type" => {
                if value.trim().is_empty() {
                    return Err(MapError::parse(
                        MAP_FORMAT,
                        n,
                        "`type` needs a value (usually `octile`)",
                    ));
                }
            }
            "height" => height = Some(header_number(value, "height", n)?),
            "width" => width = Some(header_number(value, "width", n)?),
            "map" if value.trim().is_empty() => break,
            // Nothing of the header read yet: some other file. Its bytes
            // are not echoed (a binary file would fill the banner with
            // escapes).
            _ if first => {
                return Err(MapError::parse(
                    MAP_FORMAT,
                    n,
                    "not a Moving AI map: the first line should be `type octile`, then `height H`, `width W` and `map`",
                ))
            }
            _ if line.chars().any(char::is_control) => {
                return Err(MapError::parse(
                    MAP_FORMAT,
                    n,
                    "a header line holds control characters (not a text map?); expected `type`, `height`, `width` or `map`",
                ))
            }
            _ => {
                return Err(MapError::parse(
                    MAP_FORMAT,
                    n,
                    format!(
                        "unexpected header line {:?}; expected `type`, `height`, `width` or `map`",
                        truncate(line)
                    ),
                ))
            }
        }
    }
    let (Some(h), Some(w)) = (height, width) else {
        return Err(MapError::parse(
            MAP_FORMAT,
            last_line,
            format!(
                "header has no `{}` line before `map`",
                if height.is_none() { "height" } else { "width" }
            ),
        ));
    };
    let n_cells = check_dimensions(w, h)?;
    // Cannot overflow: check_dimensions bounds w·h, hence w and h.
    let (w, h) = (w as usize, h as usize);
    // Capacity bounded by the text so a lying header cannot make us reserve
    // more memory than the input itself.
    let mut cells = Vec::with_capacity(n_cells.min(text.len()));
    let mut rows = 0usize;
    for (n, line) in lines.by_ref() {
        if rows == h {
            if line.trim().is_empty() {
                continue;
            }
            return Err(MapError::parse(
                MAP_FORMAT,
                n,
                format!("unexpected content after the {h} map rows the header announced"),
            ));
        }
        let mut count = 0usize;
        for ch in line.chars() {
            count += 1;
            if count > w {
                break;
            }
            cells.push(match ch {
                '.' | 'G' | 'S' => Cell::Free,
                '@' | 'O' | 'T' | 'W' => Cell::Occupied,
                other => {
                    return Err(MapError::parse(
                        MAP_FORMAT,
                        n,
                        format!(
                            "unexpected character {other:?} in column {}; expected one of . G S @ O T W",
                            count
                        ),
                    ))
                }
            });
        }
        if count != w {
            let got = line.chars().count();
            return Err(MapError::parse(
                MAP_FORMAT,
                n,
                format!("row has {got} characters, expected {w}"),
            ));
        }
        rows += 1;
    }
    if rows != h {
        return Err(MapError::parse(
            MAP_FORMAT,
            last_line_number(text),
            format!("file has {rows} map rows, expected {h}"),
        ));
    }
    OccupancyGrid::from_cells(w, h, cells)
}

/// Number of the last line of `text` (1-based).
fn last_line_number(text: &str) -> usize {
    text.split('\n').count()
}

/// First 40 characters of a line for an error message.
fn truncate(s: &str) -> String {
    let mut out: String = s.chars().take(40).collect();
    if s.chars().nth(40).is_some() {
        out.push('…');
    }
    out
}

/// Writes a grid as a Moving AI `.map`: `.` free, `@` occupied.
///
/// The format has no "unknown"; unknown cells are written as `@` (blocked),
/// the conservative choice and what planners do with unknown by default.
/// Resolution and origin are not stored.
pub fn write_map(grid: &OccupancyGrid) -> String {
    let (w, h) = (grid.width(), grid.height());
    let mut s = String::with_capacity(48 + (w + 1) * h);
    s.push_str(&format!("type octile\nheight {h}\nwidth {w}\nmap\n"));
    for row in grid.cells().chunks(w.max(1)) {
        for c in row {
            s.push(match c {
                Cell::Free => '.',
                Cell::Occupied | Cell::Unknown => '@',
            });
        }
        s.push('\n');
    }
    s
}

/// One query of a `.scen` file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ScenRow {
    /// Bucket (groups queries of similar optimal length).
    pub bucket: u32,
    /// Map file name as written in the file (may include a directory).
    pub map: String,
    /// Map width in cells.
    pub width: u32,
    /// Map height in cells.
    pub height: u32,
    /// Start cell (x = column, y = row from the top).
    pub start: GridPos,
    /// Goal cell.
    pub goal: GridPos,
    /// Optimal path length in cells (8-connected, √2 diagonals, no corner
    /// cutting).
    pub optimal: f64,
}

/// Parses one nine-field scenario row.
fn parse_scen_row(line: &str, n: usize) -> Result<ScenRow, MapError> {
    let fields: Vec<&str> = line.split_whitespace().collect();
    if fields.len() != 9 {
        return Err(MapError::parse(
            SCEN_FORMAT,
            n,
            format!(
                "row has {} fields, expected 9 (bucket, map, width, height, start x, start y, goal x, goal y, optimal length)",
                fields.len()
            ),
        ));
    }
    let int = |i: usize, name: &str| -> Result<u32, MapError> {
        let f = fields.get(i).copied().unwrap_or("");
        f.parse::<u32>().map_err(|_| {
            MapError::parse(
                SCEN_FORMAT,
                n,
                format!("{name} must be a whole number ≥ 0, got {:?}", truncate(f)),
            )
        })
    };
    let bucket = int(0, "bucket")?;
    let map = fields.get(1).copied().unwrap_or("").to_string();
    let width = int(2, "map width")?;
    let height = int(3, "map height")?;
    let start = GridPos::new(int(4, "start x")?, int(5, "start y")?);
    let goal = GridPos::new(int(6, "goal x")?, int(7, "goal y")?);
    let opt_text = fields.get(8).copied().unwrap_or("");
    let optimal = opt_text.parse::<f64>().map_err(|_| {
        MapError::parse(
            SCEN_FORMAT,
            n,
            format!(
                "optimal length must be a number, got {:?}",
                truncate(opt_text)
            ),
        )
    })?;
    if !(optimal.is_finite() && optimal >= 0.0) {
        return Err(MapError::parse(
            SCEN_FORMAT,
            n,
            format!("optimal length must be a finite number ≥ 0, got {opt_text}"),
        ));
    }
    for (what, p) in [("start", start), ("goal", goal)] {
        if p.col >= width || p.row >= height {
            return Err(MapError::parse(
                SCEN_FORMAT,
                n,
                format!(
                    "{what} ({}, {}) is outside the {width}×{height} map named on the same row",
                    p.col, p.row
                ),
            ));
        }
    }
    Ok(ScenRow {
        bucket,
        map,
        width,
        height,
        start,
        goal,
        optimal,
    })
}

/// Parses a Moving AI `.scen` file (see the module docs for the layout).
///
/// ```
/// use planlab_core::map::io::movingai;
/// let rows = movingai::parse_scen("version 1\n0\tarena.map\t49\t49\t1\t11\t1\t12\t1\n").unwrap();
/// assert_eq!(rows.len(), 1);
/// assert_eq!((rows[0].start.col, rows[0].start.row), (1, 11));
/// assert_eq!(rows[0].optimal, 1.0);
/// ```
pub fn parse_scen(text: &str) -> Result<Vec<ScenRow>, MapError> {
    let mut rows = Vec::new();
    let mut first = true;
    for (n, line) in numbered_lines(text) {
        let line = line.trim_start();
        if line.is_empty() {
            continue;
        }
        if first {
            first = false;
            if let Some(v) = line.strip_prefix("version") {
                let v = v.trim();
                if v == "1" || v == "1.0" {
                    continue;
                }
                return Err(MapError::parse(
                    SCEN_FORMAT,
                    n,
                    format!(
                        "unsupported version {:?}; only version 1 is read",
                        truncate(v)
                    ),
                ));
            }
        }
        rows.push(parse_scen_row(line, n)?);
    }
    Ok(rows)
}

/// Checks that every scenario row fits `grid`: same width and height, start
/// and goal on the map and on passable cells.
///
/// Rows are numbered from 1 in error messages (the `n`-th query, not the
/// file line, which is no longer known here).
pub fn check_scen_against_map(rows: &[ScenRow], grid: &OccupancyGrid) -> Result<(), MapError> {
    for (i, r) in rows.iter().enumerate() {
        let q = i + 1;
        if r.width as usize != grid.width() || r.height as usize != grid.height() {
            return Err(MapError::parse(
                SCEN_FORMAT,
                0,
                format!(
                    "query {q} is for a {}×{} map but the map is {}×{}",
                    r.width,
                    r.height,
                    grid.width(),
                    grid.height()
                ),
            ));
        }
        for (what, p) in [("start", r.start), ("goal", r.goal)] {
            match grid.get(p.col as usize, p.row as usize) {
                None => {
                    return Err(MapError::parse(
                        SCEN_FORMAT,
                        0,
                        format!(
                            "query {q}: {what} ({}, {}) is outside the {}×{} map",
                            p.col,
                            p.row,
                            grid.width(),
                            grid.height()
                        ),
                    ))
                }
                Some(Cell::Free) => {}
                Some(_) => {
                    return Err(MapError::parse(
                        SCEN_FORMAT,
                        0,
                        format!(
                        "query {q}: {what} ({}, {}) is on a blocked cell; is this the right map?",
                        p.col, p.row
                    ),
                    ))
                }
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_header_in_either_order_with_crlf() {
        let g = parse_map("type octile\r\nwidth 3\r\nheight 2\r\nmap\r\n.GS\r\n@OT\r\n\r\n\r\n")
            .unwrap();
        assert_eq!((g.width(), g.height()), (3, 2));
        assert_eq!(g.counts(), (3, 3, 0));
        assert_eq!(g.get(2, 0), Some(Cell::Free));
        assert_eq!(g.get(0, 1), Some(Cell::Occupied));
    }

    #[test]
    fn tolerates_trailing_whitespace_and_no_final_newline() {
        let g = parse_map("type octile  \nheight 1\t\nwidth 2 \nmap \n.W  ").unwrap();
        assert_eq!(g.cells(), &[Cell::Free, Cell::Occupied]);
    }

    fn err_line(r: Result<OccupancyGrid, MapError>) -> usize {
        match r {
            Err(MapError::Parse { line, .. }) => line,
            other => panic!("expected a parse error, got {other:?}"),
        }
    }

    #[test]
    fn reports_line_numbers() {
        let hdr = "type octile\nheight 2\nwidth 3\nmap\n";
        assert_eq!(err_line(parse_map(&format!("{hdr}...\n..\n"))), 6);
        assert_eq!(err_line(parse_map(&format!("{hdr}...\n.x.\n"))), 6);
        assert_eq!(err_line(parse_map(&format!("{hdr}...\n"))), 5);
        assert_eq!(err_line(parse_map(&format!("{hdr}...\n...\n...\n"))), 7);
        assert_eq!(
            err_line(parse_map("type octile\nheight x\nwidth 3\nmap\n")),
            2
        );
        assert_eq!(err_line(parse_map("type octile\nheight 2\nmap\n")), 3);
        assert_eq!(err_line(parse_map("")), 0);
        let msg = parse_map(&format!("{hdr}....\n...\n"))
            .unwrap_err()
            .to_string();
        assert_eq!(
            msg,
            "Moving AI map parse error at line 5: row has 4 characters, expected 3"
        );
    }

    #[test]
    fn refuses_huge_header_before_allocating() {
        let r = parse_map("type octile\nheight 20000\nwidth 20000\nmap\n");
        assert!(matches!(r, Err(MapError::TooLarge { .. })), "{r:?}");
        let r = parse_map("type octile\nheight 0\nwidth 5\nmap\n");
        assert!(matches!(r, Err(MapError::Empty { .. })), "{r:?}");
        let r = parse_map("type octile\nheight 99999999999999999999\nwidth 5\nmap\n");
        assert!(matches!(r, Err(MapError::Parse { line: 2, .. })), "{r:?}");
    }

    #[test]
    fn write_then_parse_round_trips_and_unknown_becomes_blocked() {
        let g = OccupancyGrid::from_ascii(".#?\n#..\n").unwrap();
        let text = write_map(&g);
        assert_eq!(text, "type octile\nheight 2\nwidth 3\nmap\n.@@\n@..\n");
        let back = parse_map(&text).unwrap();
        assert_eq!(back.to_ascii(), ".##\n#..\n");
    }

    #[test]
    fn scen_rows_tabs_spaces_and_versions() {
        let rows = parse_scen(
            "version 1.0\n\n0\ta.map\t4\t3\t0\t1\t3\t2\t3.5\n2 a.map 4 3 1 1 2 2 1.41421356\n",
        )
        .unwrap();
        assert_eq!(rows.len(), 2);
        assert_eq!(rows[1].bucket, 2);
        assert_eq!(rows[0].goal, GridPos::new(3, 2));
        assert_eq!(rows[0].optimal, 3.5);
        // No version line.
        assert_eq!(parse_scen("0 a.map 4 3 0 1 3 2 3.5\n").unwrap().len(), 1);
        assert!(parse_scen("version 2\n0 a.map 4 3 0 1 3 2 3.5\n").is_err());
    }

    #[test]
    fn scen_rejects_bad_rows_with_line_numbers() {
        let line_of = |t: &str| match parse_scen(t) {
            Err(MapError::Parse { line, .. }) => line,
            other => panic!("expected a parse error, got {other:?}"),
        };
        assert_eq!(line_of("version 1\n0 a 4 3 0 1 3 2 NaN\n"), 2);
        assert_eq!(line_of("version 1\n0 a 4 3 0 1 3 2 -1\n"), 2);
        assert_eq!(line_of("version 1\n0 a 4 3 0 1 3 2 inf\n"), 2);
        assert_eq!(
            line_of("version 1\n0 a 4 3 0 1 3 2 1\n0 a 4 3 0 x 3 2 1\n"),
            3
        );
        assert_eq!(line_of("version 1\n0 a 4 3 0 1 3 2\n"), 2);
        assert_eq!(line_of("version 1\n0 a 4 3 0 1 3 2 1 9\n"), 2);
        assert_eq!(line_of("version 1\n0 a 4 3 4 1 3 2 1\n"), 2);
        assert_eq!(line_of("version 1\n-1 a 4 3 0 1 3 2 1\n"), 2);
    }

    #[test]
    fn scen_checked_against_map() {
        let g = OccupancyGrid::from_ascii("...\n.#.\n").unwrap();
        let ok = parse_scen("version 1\n0 m 3 2 0 0 2 1 2.41421356\n").unwrap();
        assert_eq!(check_scen_against_map(&ok, &g), Ok(()));
        let wrong_size = parse_scen("version 1\n0 m 3 3 0 0 2 1 1\n").unwrap();
        assert!(check_scen_against_map(&wrong_size, &g).is_err());
        let blocked = parse_scen("version 1\n0 m 3 2 0 0 1 1 1\n").unwrap();
        assert!(check_scen_against_map(&blocked, &g).is_err());
        // Rows built by hand can still point off the map.
        let mut off = ok.clone();
        off[0].start = GridPos::new(3, 0);
        assert!(check_scen_against_map(&off, &g).is_err());
    }
}
