//! ROS map_server maps: a YAML metadata file plus a PGM image.
//!
//! ```text
//! image: map.pgm
//! resolution: 0.050000
//! origin: [-10.000000, -10.000000, 0.000000]
//! negate: 0
//! occupied_thresh: 0.65
//! free_thresh: 0.196
//! ```
//!
//! # YAML subset
//! map_server files are flat `key: value` maps, so this module reads that
//! subset itself instead of pulling in a YAML crate (measured for
//! yaml-rust2, the maintained pure-Rust parser: +115 kB to the page's wasm
//! after wasm-opt, over the page's size budget; its current release also
//! needs a newer Rust than the workspace's 1.80, and its tree keeps no line
//! numbers for our errors). The reader is linear in the input (a key set
//! for the duplicate check). It reads `#` comments, plain,
//! `"double"` and `'single'` quoted scalars, `[a, b, c]` flow lists (which may
//! span lines), `- item` block lists under a key, and `---` / `...` markers.
//! Unknown keys are ignored, as map_server does, and nested mappings under
//! unknown keys are skipped. Known keys:
//!
//! | key | required | meaning |
//! |---|---|---|
//! | `image` | yes | image path, relative to the YAML file (not opened here) |
//! | `resolution` | yes | metres per pixel, finite, > 0 and at most 10⁶ |
//! | `origin` | yes | `[x, y, yaw]` of the bottom-left pixel corner, finite; x and y within ±10⁶ m |
//! | `negate` | no (0) | `0`/`1`/`true`/`false`: swap black and white |
//! | `occupied_thresh` | no (0.65) | in \[0, 1\] |
//! | `free_thresh` | no (0.196) | in \[0, 1\], below `occupied_thresh` |
//! | `mode` | no (`trinary`) | `trinary`, `scale` or `raw` |
//!
//! # Pixel classification ([`grid_from_pgm`])
//! With `v` a pixel and `m` the PGM maxval, `p = (m − v)/m` (or `v/m` when
//! `negate`) is the occupancy probability.
//! - **trinary**: occupied if `p > occupied_thresh`, free if
//!   `p < free_thresh`, unknown otherwise — exactly map_server.
//! - **scale**: occupied and free as trinary; map_server turns the
//!   in-between band into costs 1–99, and planlab into **weighted free
//!   cells** (docs/algorithms.md §weights): with
//!   `ratio = (p − free_thresh)/(occupied_thresh − free_thresh)` in \[0, 1\],
//!   the weight is `1 + round(8·ratio)`, the band spread linearly over the
//!   weights 1–[`MAX_WEIGHT`](crate::map::MAX_WEIGHT) (a pale grey just
//!   above `free_thresh` costs as free ground, a dark one just below
//!   `occupied_thresh` nine times as much). PGM has no alpha channel, the
//!   other source of unknown in scale mode, so a scale map has no unknown
//!   cells.
//! - **raw**: the pixel (rescaled to 0–255 when `m ≠ 255`) *is* the ROS
//!   occupancy value, as in nav2: 0–100 is a percentage, thresholded like
//!   `p = v/100` above; anything above 100 (e.g. 255, ROS's −1) is unknown.
//!   `negate` is ignored in raw mode, as in nav2.

use crate::map::{check_dimensions, Cell, MapError, OccupancyGrid, Pose2};
use crate::num::{fmt_num, MAX_PARAM};
use serde::{Deserialize, Serialize};

const YAML_FORMAT: &str = "ROS map yaml";
const PGM_FORMAT: &str = "PGM";

/// Default `occupied_thresh` when the YAML omits it (map_saver's value).
pub const DEFAULT_OCCUPIED_THRESH: f64 = 0.65;
/// Default `free_thresh` when the YAML omits it (map_saver's value).
pub const DEFAULT_FREE_THRESH: f64 = 0.196;

/// How pixel values become occupancy (map_server's `mode`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RosMode {
    /// Occupied / free / unknown by the two thresholds.
    #[default]
    Trinary,
    /// As trinary, with the band between the thresholds as weighted free
    /// cells (see the module docs).
    Scale,
    /// Pixel values are ROS occupancy values 0–100, others unknown.
    Raw,
}

impl RosMode {
    /// The name used in YAML files.
    pub fn as_str(self) -> &'static str {
        match self {
            RosMode::Trinary => "trinary",
            RosMode::Scale => "scale",
            RosMode::Raw => "raw",
        }
    }
}

/// The contents of a map_server YAML file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RosMapMeta {
    /// Image path, relative to the YAML file.
    pub image: String,
    /// Metres per pixel.
    pub resolution: f64,
    /// World pose (m, m, rad) of the bottom-left corner of the image.
    pub origin: Pose2,
    /// Swap the meaning of black and white.
    pub negate: bool,
    /// Occupancy probability (0–1) above which a pixel is occupied.
    pub occupied_thresh: f64,
    /// Occupancy probability (0–1) below which a pixel is free.
    pub free_thresh: f64,
    /// How pixels are interpreted.
    pub mode: RosMode,
}

impl RosMapMeta {
    /// Metadata describing `grid` (its resolution and origin) with the
    /// default thresholds, trinary mode and the given image path; pair it
    /// with [`write_pgm`] to save a grid.
    pub fn for_grid(grid: &OccupancyGrid, image: impl Into<String>) -> Self {
        Self {
            image: image.into(),
            resolution: grid.resolution(),
            origin: grid.origin(),
            negate: false,
            occupied_thresh: DEFAULT_OCCUPIED_THRESH,
            free_thresh: DEFAULT_FREE_THRESH,
            mode: RosMode::Trinary,
        }
    }

    /// Checks the ranges [`parse_yaml`] enforces: resolution finite and
    /// positive, origin finite, thresholds in \[0, 1\] with free below
    /// occupied, image not empty.
    pub fn validate(&self) -> Result<(), MapError> {
        if self.image.trim().is_empty() {
            return Err(MapError::parse(YAML_FORMAT, 0, "`image` is empty"));
        }
        crate::map::check_frame(self.resolution, self.origin)?;
        for (name, t) in [
            ("occupied_thresh", self.occupied_thresh),
            ("free_thresh", self.free_thresh),
        ] {
            if !(0.0..=1.0).contains(&t) {
                return Err(MapError::parse(
                    YAML_FORMAT,
                    0,
                    format!("`{name}` is {t}; it must be between 0 and 1"),
                ));
            }
        }
        if self.free_thresh >= self.occupied_thresh {
            return Err(MapError::parse(
                YAML_FORMAT,
                0,
                format!(
                    "`free_thresh` ({}) must be below `occupied_thresh` ({})",
                    self.free_thresh, self.occupied_thresh
                ),
            ));
        }
        Ok(())
    }
}

// ------------------------------------------------------------------- YAML

/// A value of the flat YAML subset.
#[derive(Debug, PartialEq)]
enum Value {
    /// A scalar; `quoted` scalars are never numbers or booleans.
    Scalar { text: String, quoted: bool },
    /// A flow or block list of scalars.
    List(Vec<String>),
    /// A nested mapping (only allowed under keys we ignore).
    Nested,
}

/// `line` without its `#` comment (a `#` at the start or after whitespace,
/// outside quotes), trailing whitespace trimmed.
fn strip_comment(line: &str) -> &str {
    let mut in_double = false;
    let mut in_single = false;
    let mut prev_ws = true;
    let mut escaped = false;
    for (i, ch) in line.char_indices() {
        if in_double {
            if escaped {
                escaped = false;
            } else if ch == '\\' {
                escaped = true;
            } else if ch == '"' {
                in_double = false;
            }
        } else if in_single {
            if ch == '\'' {
                if escaped {
                    // Second quote of a `''` pair.
                    escaped = false;
                } else if line[i + 1..].starts_with('\'') {
                    // `''` inside single quotes is an escaped quote.
                    escaped = true;
                } else {
                    in_single = false;
                }
            }
        } else if ch == '#' && prev_ws {
            return line[..i].trim_end();
        } else if ch == '"' && prev_ws {
            in_double = true;
        } else if ch == '\'' && prev_ws {
            in_single = true;
        }
        prev_ws = ch.is_whitespace() || (!in_double && !in_single && matches!(ch, '[' | ','));
    }
    line.trim_end()
}

/// Parses a quoted scalar starting at `s[0]`; returns the text and the rest.
fn parse_quoted(s: &str, line: usize) -> Result<(String, &str), MapError> {
    let mut chars = s.char_indices();
    let quote = match chars.next() {
        Some((_, q @ ('"' | '\''))) => q,
        _ => return Err(MapError::parse(YAML_FORMAT, line, "expected a quote")),
    };
    let mut out = String::new();
    while let Some((i, ch)) = chars.next() {
        if ch == quote {
            if quote == '\'' && s[i + 1..].starts_with('\'') {
                // '' is an escaped single quote.
                chars.next();
                out.push('\'');
                continue;
            }
            return Ok((out, &s[i + 1..]));
        }
        if quote == '"' && ch == '\\' {
            let esc = match chars.next() {
                Some((_, 'n')) => '\n',
                Some((_, 't')) => '\t',
                Some((_, c @ ('"' | '\\' | '/'))) => c,
                Some((_, c)) => {
                    return Err(MapError::parse(
                        YAML_FORMAT,
                        line,
                        format!("unsupported escape \\{c} in a quoted string"),
                    ))
                }
                None => break,
            };
            out.push(esc);
        } else {
            out.push(ch);
        }
    }
    Err(MapError::parse(
        YAML_FORMAT,
        line,
        "quoted string is not closed",
    ))
}

/// A scalar (quoted or plain) that must fill `s`.
fn parse_scalar(s: &str, line: usize) -> Result<Value, MapError> {
    let s = s.trim();
    if s.starts_with('"') || s.starts_with('\'') {
        let (text, rest) = parse_quoted(s, line)?;
        if !rest.trim().is_empty() {
            return Err(MapError::parse(
                YAML_FORMAT,
                line,
                format!("unexpected text after a quoted string: {:?}", rest.trim()),
            ));
        }
        return Ok(Value::Scalar { text, quoted: true });
    }
    Ok(Value::Scalar {
        text: s.to_string(),
        quoted: false,
    })
}

/// Parses the inside of a flow list `[a, b, c]` (without the brackets).
fn parse_flow_items(inner: &str, line: usize) -> Result<Vec<String>, MapError> {
    let mut items = Vec::new();
    let mut rest = inner.trim();
    if rest.is_empty() {
        return Ok(items);
    }
    loop {
        let (item, after) = if rest.starts_with('"') || rest.starts_with('\'') {
            let (t, after) = parse_quoted(rest, line)?;
            (t, after.trim_start())
        } else {
            let end = rest.find(',').unwrap_or(rest.len());
            let t = rest[..end].trim();
            if t.starts_with('[') || t.starts_with('{') {
                return Err(MapError::parse(
                    YAML_FORMAT,
                    line,
                    "nested lists are not supported",
                ));
            }
            (t.to_string(), &rest[end..])
        };
        items.push(item);
        if after.is_empty() {
            return Ok(items);
        }
        match after.strip_prefix(',') {
            Some(r) => {
                rest = r.trim_start();
                if rest.is_empty() {
                    // A trailing comma is allowed in flow lists.
                    return Ok(items);
                }
            }
            None => {
                return Err(MapError::parse(
                    YAML_FORMAT,
                    line,
                    format!("expected `,` or `]` in a list, found {after:?}"),
                ))
            }
        }
    }
}

/// Splits `key: value` at the first `:` followed by whitespace or the end.
fn split_key(line: &str) -> Option<(&str, &str)> {
    let bytes = line.as_bytes();
    for (i, &b) in bytes.iter().enumerate() {
        if b == b':' && bytes.get(i + 1).map_or(true, |c| c.is_ascii_whitespace()) {
            return Some((line[..i].trim(), &line[i + 1..]));
        }
    }
    None
}

/// The flat YAML subset: `(line, key, value)` in file order.
fn parse_flat_yaml(text: &str) -> Result<Vec<(usize, String, Value)>, MapError> {
    let mut out: Vec<(usize, String, Value)> = Vec::new();
    // Keys seen so far (a set: scanning `out` made the reader quadratic;
    // 160 000 keys took 247 s).
    let mut seen = std::collections::BTreeSet::new();
    // A flow list still open: (line of its key, key, text so far).
    let mut open_list: Option<(usize, String, String)> = None;
    // Whether the last key had an empty value (so indented lines belong to it).
    let mut block_owner = false;
    for (i, raw) in text.split('\n').enumerate() {
        let n = i + 1;
        let line = strip_comment(raw);
        if let Some((kline, key, mut acc)) = open_list.take() {
            acc.push(' ');
            acc.push_str(line.trim());
            if let Some(inner) = acc.strip_suffix(']') {
                let items = parse_flow_items(inner, kline)?;
                out.push((kline, key, Value::List(items)));
            } else {
                open_list = Some((kline, key, acc));
            }
            continue;
        }
        if line.trim().is_empty() {
            continue;
        }
        let indented = line.starts_with([' ', '\t']);
        let trimmed = line.trim();
        if !indented && (trimmed == "---" || trimmed == "..." || trimmed.starts_with('%')) {
            continue;
        }
        if indented {
            if !block_owner {
                return Err(MapError::parse(
                    YAML_FORMAT,
                    n,
                    "unexpected indented line; map_server YAML is a flat list of `key: value` lines",
                ));
            }
            let Some((_, _, value)) = out.last_mut() else {
                return Err(MapError::parse(YAML_FORMAT, n, "unexpected indented line"));
            };
            if let Some(item) = trimmed
                .strip_prefix('-')
                .filter(|r| r.is_empty() || r.starts_with([' ', '\t']))
            {
                let item = match parse_scalar(item, n)? {
                    Value::Scalar { text, .. } => text,
                    _ => String::new(),
                };
                match value {
                    Value::List(items) => items.push(item),
                    Value::Scalar {
                        text,
                        quoted: false,
                    } if text.is_empty() => *value = Value::List(vec![item]),
                    _ => *value = Value::Nested,
                }
            } else {
                *value = Value::Nested;
            }
            continue;
        }
        let Some((key, rest)) = split_key(trimmed) else {
            return Err(MapError::parse(
                YAML_FORMAT,
                n,
                format!("expected `key: value`, found {trimmed:?}"),
            ));
        };
        if key.is_empty() {
            return Err(MapError::parse(YAML_FORMAT, n, "a line has `:` but no key"));
        }
        if !seen.insert(key.to_string()) {
            return Err(MapError::parse(
                YAML_FORMAT,
                n,
                format!("key `{key}` appears twice"),
            ));
        }
        let rest = rest.trim();
        block_owner = rest.is_empty();
        if let Some(list) = rest.strip_prefix('[') {
            if let Some(inner) = list.strip_suffix(']') {
                out.push((n, key.to_string(), Value::List(parse_flow_items(inner, n)?)));
            } else {
                open_list = Some((n, key.to_string(), list.to_string()));
            }
        } else if rest.starts_with('{') {
            out.push((n, key.to_string(), Value::Nested));
        } else {
            out.push((n, key.to_string(), parse_scalar(rest, n)?));
        }
    }
    if let Some((kline, key, _)) = open_list {
        return Err(MapError::parse(
            YAML_FORMAT,
            kline,
            format!("the list for `{key}` has no closing `]`"),
        ));
    }
    Ok(out)
}

/// A finite-or-not number from a YAML scalar (validation comes later).
fn yaml_number(v: &Value, key: &str, line: usize) -> Result<f64, MapError> {
    match v {
        Value::Scalar {
            text,
            quoted: false,
        } => text.parse::<f64>().map_err(|_| {
            MapError::parse(
                YAML_FORMAT,
                line,
                format!("`{key}` must be a number, got {text:?}"),
            )
        }),
        _ => Err(MapError::parse(
            YAML_FORMAT,
            line,
            format!("`{key}` must be a number"),
        )),
    }
}

/// Parses a map_server YAML file and validates it (see the module docs).
///
/// ```
/// use planlab_core::map::io::ros;
/// let meta = ros::parse_yaml("image: map.pgm\nresolution: 0.05\norigin: [-10, -10, 0]\n").unwrap();
/// assert_eq!(meta.image, "map.pgm");
/// assert_eq!(meta.origin.x, -10.0);
/// assert_eq!(meta.free_thresh, 0.196);
/// ```
pub fn parse_yaml(text: &str) -> Result<RosMapMeta, MapError> {
    // A UTF-8 byte-order mark (Windows editors write one) is not part of
    // the first key.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let entries = parse_flat_yaml(text)?;
    let mut image = None;
    let mut resolution = None;
    let mut origin = None;
    let mut negate = false;
    let mut occupied_thresh = DEFAULT_OCCUPIED_THRESH;
    let mut free_thresh = DEFAULT_FREE_THRESH;
    let mut mode = RosMode::Trinary;
    let mut thresh_lines = (0, 0);
    for (n, key, value) in &entries {
        let n = *n;
        match key.as_str() {
            "image" => match value {
                Value::Scalar { text, .. } if !text.trim().is_empty() => image = Some(text.clone()),
                _ => {
                    return Err(MapError::parse(
                        YAML_FORMAT,
                        n,
                        "`image` must be a file name",
                    ))
                }
            },
            "resolution" => {
                let r = yaml_number(value, key, n)?;
                if !(r.is_finite() && r > 0.0 && r <= MAX_PARAM) {
                    return Err(MapError::parse(
                        YAML_FORMAT,
                        n,
                        format!(
                            "`resolution` is {}; it must be a finite number > 0 and at most {} (metres per pixel)",
                            fmt_num(r),
                            fmt_num(MAX_PARAM)
                        ),
                    ));
                }
                resolution = Some(r);
            }
            "origin" => {
                let Value::List(items) = value else {
                    return Err(MapError::parse(
                        YAML_FORMAT,
                        n,
                        "`origin` must be a list [x, y, yaw]",
                    ));
                };
                if items.len() != 3 {
                    return Err(MapError::parse(
                        YAML_FORMAT,
                        n,
                        format!(
                            "`origin` has {} numbers, expected 3: [x, y, yaw]",
                            items.len()
                        ),
                    ));
                }
                let mut xyz = [0.0; 3];
                for (i, (slot, item)) in xyz.iter_mut().zip(items).enumerate() {
                    let v = item.trim().parse::<f64>().map_err(|_| {
                        MapError::parse(
                            YAML_FORMAT,
                            n,
                            format!("`origin` entry {item:?} is not a number"),
                        )
                    })?;
                    if !v.is_finite() {
                        return Err(MapError::parse(
                            YAML_FORMAT,
                            n,
                            format!("`origin` entry {item} is not finite"),
                        ));
                    }
                    // x and y are distances (the yaw an angle).
                    if i < 2 && v.abs() > MAX_PARAM {
                        return Err(MapError::parse(
                            YAML_FORMAT,
                            n,
                            format!(
                                "`origin` entry {} is out of range: x and y must be within ±{} m",
                                fmt_num(v),
                                fmt_num(MAX_PARAM)
                            ),
                        ));
                    }
                    *slot = v;
                }
                origin = Some(Pose2 {
                    x: xyz[0],
                    y: xyz[1],
                    yaw: xyz[2],
                });
            }
            "negate" => {
                let text = match value {
                    Value::Scalar { text, .. } => text.to_ascii_lowercase(),
                    _ => String::new(),
                };
                negate = match text.as_str() {
                    "0" | "false" | "no" | "off" => false,
                    "1" | "true" | "yes" | "on" => true,
                    _ => {
                        return Err(MapError::parse(
                            YAML_FORMAT,
                            n,
                            format!("`negate` must be 0 or 1, got {text:?}"),
                        ))
                    }
                };
            }
            "occupied_thresh" => {
                occupied_thresh = yaml_number(value, key, n)?;
                thresh_lines.0 = n;
            }
            "free_thresh" => {
                free_thresh = yaml_number(value, key, n)?;
                thresh_lines.1 = n;
            }
            "mode" => {
                let text = match value {
                    Value::Scalar { text, .. } => text.to_ascii_lowercase(),
                    _ => String::new(),
                };
                mode = match text.as_str() {
                    "trinary" => RosMode::Trinary,
                    "scale" => RosMode::Scale,
                    "raw" => RosMode::Raw,
                    _ => {
                        return Err(MapError::parse(
                            YAML_FORMAT,
                            n,
                            format!("`mode` must be trinary, scale or raw, got {text:?}"),
                        ))
                    }
                };
            }
            // map_server ignores keys it does not know; so do we.
            _ => {}
        }
    }
    let last = text.split('\n').count();
    let image = image.ok_or_else(|| MapError::parse(YAML_FORMAT, 0, "missing `image`"))?;
    let resolution =
        resolution.ok_or_else(|| MapError::parse(YAML_FORMAT, 0, "missing `resolution`"))?;
    let origin = origin.ok_or_else(|| MapError::parse(YAML_FORMAT, 0, "missing `origin`"))?;
    for (name, t, line) in [
        ("occupied_thresh", occupied_thresh, thresh_lines.0),
        ("free_thresh", free_thresh, thresh_lines.1),
    ] {
        if !(0.0..=1.0).contains(&t) {
            return Err(MapError::parse(
                YAML_FORMAT,
                line,
                format!("`{name}` is {t}; it must be between 0 and 1"),
            ));
        }
    }
    if free_thresh >= occupied_thresh {
        return Err(MapError::parse(
            YAML_FORMAT,
            thresh_lines.1.max(thresh_lines.0).min(last),
            format!(
                "`free_thresh` ({free_thresh}) must be below `occupied_thresh` ({occupied_thresh})"
            ),
        ));
    }
    let meta = RosMapMeta {
        image,
        resolution,
        origin,
        negate,
        occupied_thresh,
        free_thresh,
        mode,
    };
    meta.validate()?;
    Ok(meta)
}

/// Whether a plain YAML scalar would read back as the same string.
fn plain_safe(s: &str) -> bool {
    !s.is_empty()
        && s.trim() == s
        && !s.contains([
            ':', '#', '\n', '\r', '\t', ',', '[', ']', '{', '}', '"', '\'',
        ])
        && !s.starts_with(['-', '?', '!', '&', '*', '|', '>', '%', '@', '`'])
}

/// Writes a map_server YAML file for `meta` (numbers round-trip exactly).
pub fn write_yaml(meta: &RosMapMeta) -> String {
    let image = if plain_safe(&meta.image) {
        meta.image.clone()
    } else {
        let mut q = String::from("\"");
        for ch in meta.image.chars() {
            match ch {
                '"' => q.push_str("\\\""),
                '\\' => q.push_str("\\\\"),
                '\n' => q.push_str("\\n"),
                '\t' => q.push_str("\\t"),
                c => q.push(c),
            }
        }
        q.push('"');
        q
    };
    let o = meta.origin;
    format!(
        "image: {image}\nmode: {}\nresolution: {:?}\norigin: [{:?}, {:?}, {:?}]\nnegate: {}\noccupied_thresh: {:?}\nfree_thresh: {:?}\n",
        meta.mode.as_str(),
        meta.resolution,
        o.x,
        o.y,
        o.yaw,
        u8::from(meta.negate),
        meta.occupied_thresh,
        meta.free_thresh
    )
}

// -------------------------------------------------------------------- PGM

/// A greyscale PGM image.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Pgm {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// The largest pixel value (1–65535), from the header.
    pub maxval: u16,
    /// Row-major pixels, top row first; each ≤ `maxval`.
    pub pixels: Vec<u16>,
}

/// A byte cursor over a PGM header that tracks the line number.
struct Cursor<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: usize,
}

impl Cursor<'_> {
    /// Skips whitespace and `#` comments.
    fn skip_space(&mut self) {
        while let Some(&b) = self.bytes.get(self.pos) {
            if b == b'#' {
                while let Some(&c) = self.bytes.get(self.pos) {
                    if c == b'\n' {
                        break;
                    }
                    self.pos += 1;
                }
            } else if b.is_ascii_whitespace() {
                if b == b'\n' {
                    self.line += 1;
                }
                self.pos += 1;
            } else {
                break;
            }
        }
    }

    /// Reads a decimal number after optional whitespace and comments.
    fn number(&mut self, what: &str) -> Result<u64, MapError> {
        self.skip_space();
        let start = self.pos;
        let mut v: u64 = 0;
        while let Some(&b) = self.bytes.get(self.pos) {
            if !b.is_ascii_digit() {
                break;
            }
            v = v
                .checked_mul(10)
                .and_then(|v| v.checked_add(u64::from(b - b'0')))
                .ok_or_else(|| {
                    MapError::parse(PGM_FORMAT, self.line, format!("{what} is too large"))
                })?;
            self.pos += 1;
        }
        if self.pos == start {
            return Err(match self.bytes.get(self.pos) {
                None => MapError::parse(
                    PGM_FORMAT,
                    self.line,
                    format!("file ends before the {what}"),
                ),
                Some(&b) => MapError::parse(
                    PGM_FORMAT,
                    self.line,
                    format!("expected the {what}, found {:?}", char::from(b)),
                ),
            });
        }
        if let Some(&b) = self.bytes.get(self.pos) {
            if !(b.is_ascii_whitespace() || b == b'#') {
                return Err(MapError::parse(
                    PGM_FORMAT,
                    self.line,
                    format!("unexpected {:?} after the {what}", char::from(b)),
                ));
            }
        }
        Ok(v)
    }
}

/// The header of a PGM: what [`parse_pgm`] reads before the pixels.
struct PgmHeader<'a> {
    ascii: bool,
    width: u64,
    height: u64,
    maxval: u16,
    /// Positioned just after maxval.
    cur: Cursor<'a>,
}

/// Reads the magic number, width, height and maxval.
fn pgm_header(bytes: &[u8]) -> Result<PgmHeader<'_>, MapError> {
    let magic = bytes.get(..2).unwrap_or(bytes);
    let ascii =
        match magic {
            b"P5" => false,
            b"P2" => true,
            _ if bytes.starts_with(b"\x89PNG") => return Err(MapError::parse(
                PGM_FORMAT,
                1,
                "this is a PNG image; only PGM (P5 or P2) maps are supported — convert it to PGM",
            )),
            [b'P', b'1' | b'3' | b'4' | b'6'] => {
                return Err(MapError::parse(
                    PGM_FORMAT,
                    1,
                    "this is a PBM/PPM image; only greyscale PGM (P5 or P2) is supported",
                ))
            }
            _ => {
                return Err(MapError::parse(
                    PGM_FORMAT,
                    1,
                    "not a PGM image: the file must start with P5 or P2",
                ))
            }
        };
    let mut cur = Cursor {
        bytes,
        pos: 2,
        line: 1,
    };
    if let Some(&b) = bytes.get(2) {
        if !(b.is_ascii_whitespace() || b == b'#') {
            return Err(MapError::parse(
                PGM_FORMAT,
                1,
                "not a PGM image: the file must start with P5 or P2",
            ));
        }
    }
    let width = cur.number("width")?;
    let height = cur.number("height")?;
    let maxval = cur.number("maxval")?;
    if maxval == 0 || maxval > 65535 {
        return Err(MapError::parse(
            PGM_FORMAT,
            cur.line,
            format!("maxval is {maxval}; it must be between 1 and 65535"),
        ));
    }
    let maxval = maxval as u16;
    Ok(PgmHeader {
        ascii,
        width,
        height,
        maxval,
        cur,
    })
}

/// Whether `bytes` stop inside a PGM header: the magic number is P5 or P2
/// and the bytes end before maxval is read. A reader that read only a
/// prefix of a file tells "the header is longer than I read" from any
/// other fault (not a PGM, dimensions too large …) by this.
pub fn pgm_header_is_cut(bytes: &[u8]) -> bool {
    if !matches!(bytes.get(..2), Some(b"P5" | b"P2")) {
        return false;
    }
    let mut cur = Cursor {
        bytes,
        pos: 2,
        line: 1,
    };
    for what in ["width", "height", "maxval"] {
        if cur.number(what).is_err() {
            return cur.pos >= bytes.len();
        }
    }
    false
}

/// Bytes a PGM file beyond its header may hold per pixel in ASCII (P2):
/// `65535` and a separator, with room for spacing and short comments.
pub const P2_BYTES_PER_PIXEL: u64 = 16;

/// The longest PGM header (magic, sizes, maxval and comments) readers
/// accept before the pixels: callers read this much to learn the size.
pub const PGM_HEADER_MAX_BYTES: usize = 64 * 1024;

/// How many bytes of a PGM file a reader needs, from its header (`bytes`
/// holds at least the header; up to [`PGM_HEADER_MAX_BYTES`] is enough):
/// for P5 exactly the header plus width × height × bytes per pixel (bytes
/// after the last pixel are ignored); for P2, whose spacing and comments
/// are free-form, a cap of [`P2_BYTES_PER_PIXEL`] a pixel (a longer P2 file
/// is for the caller to refuse, not to cut). Checks the dimensions first,
/// so a caller never allocates for a file that lies about its size.
pub fn pgm_byte_limit(bytes: &[u8]) -> Result<u64, MapError> {
    let h = pgm_header(bytes)?;
    let n = check_dimensions(h.width, h.height)? as u64;
    let per_pixel = if h.ascii {
        P2_BYTES_PER_PIXEL
    } else if h.maxval > 255 {
        2
    } else {
        1
    };
    // +1: the single whitespace byte between maxval and the raster.
    Ok(h.cur.pos as u64 + 1 + n * per_pixel)
}

/// Parses a binary (P5) or ASCII (P2) PGM image.
///
/// P5 pixels take one byte when maxval ≤ 255, else two bytes big-endian.
/// Header comments (`#`) are allowed between fields; dimensions are checked
/// with [`check_dimensions`] before the pixel buffer is allocated, and every
/// pixel must be ≤ maxval. Bytes after the last pixel are ignored.
pub fn parse_pgm(bytes: &[u8]) -> Result<Pgm, MapError> {
    let PgmHeader {
        ascii,
        width,
        height,
        maxval,
        mut cur,
    } = pgm_header(bytes)?;
    let n = check_dimensions(width, height)?;
    let (width, height) = (width as usize, height as usize);
    let mut pixels;
    if ascii {
        // Every ASCII pixel takes at least two bytes ("0 "), so the input
        // bounds the capacity even if the header lies.
        pixels = Vec::with_capacity(n.min(bytes.len() / 2 + 1));
        for i in 0..n {
            let v = match cur.number("pixel value") {
                Ok(v) => v,
                Err(MapError::Parse { .. }) if cur.pos >= bytes.len() => {
                    return Err(MapError::parse(
                        PGM_FORMAT,
                        cur.line,
                        format!("image data is truncated: {i} of {n} pixels present"),
                    ))
                }
                Err(e) => return Err(e),
            };
            if v > u64::from(maxval) {
                return Err(MapError::parse(
                    PGM_FORMAT,
                    cur.line,
                    format!("pixel {i} has value {v}, above maxval {maxval}"),
                ));
            }
            pixels.push(v as u16);
        }
    } else {
        // Exactly one whitespace byte separates maxval from the raster.
        match bytes.get(cur.pos) {
            Some(b) if b.is_ascii_whitespace() => cur.pos += 1,
            _ => {
                return Err(MapError::parse(
                    PGM_FORMAT,
                    cur.line,
                    "file ends after the header: no image data",
                ))
            }
        }
        let bpp = if maxval > 255 { 2 } else { 1 };
        let data = bytes.get(cur.pos..).unwrap_or(&[]);
        let need = n.saturating_mul(bpp);
        if data.len() < need {
            return Err(MapError::parse(
                PGM_FORMAT,
                0,
                format!(
                    "image data is truncated: {width}×{height} pixels need {need} bytes, found {}",
                    data.len()
                ),
            ));
        }
        pixels = Vec::with_capacity(n);
        if bpp == 1 {
            pixels.extend(data.iter().take(n).map(|&b| u16::from(b)));
        } else {
            pixels.extend(
                data.chunks_exact(2)
                    .take(n)
                    .map(|c| u16::from_be_bytes([c[0], c[1]])),
            );
        }
        if let Some((i, v)) = pixels.iter().enumerate().find(|(_, &v)| v > maxval) {
            return Err(MapError::parse(
                PGM_FORMAT,
                0,
                format!(
                    "pixel {i} (column {}, row {}) has value {v}, above maxval {maxval}",
                    i % width,
                    i / width
                ),
            ));
        }
    }
    Ok(Pgm {
        width,
        height,
        maxval,
        pixels,
    })
}

/// Classifies one pixel per the module docs.
#[inline]
fn classify(meta: &RosMapMeta, maxval: f64, v: u16) -> Cell {
    let v = f64::from(v);
    let p = match meta.mode {
        RosMode::Trinary | RosMode::Scale => {
            if meta.negate {
                v / maxval
            } else {
                (maxval - v) / maxval
            }
        }
        RosMode::Raw => {
            let r = (v * 255.0 / maxval).round();
            if r > 100.0 {
                return Cell::Unknown;
            }
            r / 100.0
        }
    };
    if p > meta.occupied_thresh {
        Cell::Occupied
    } else if p < meta.free_thresh || meta.mode == RosMode::Scale {
        Cell::Free
    } else {
        Cell::Unknown
    }
}

/// The traversal weight of a pixel of a scale-mode map (module docs); 1
/// outside the band between the thresholds and in the other modes.
#[inline]
fn scale_weight(meta: &RosMapMeta, maxval: f64, v: u16) -> u8 {
    if meta.mode != RosMode::Scale {
        return 1;
    }
    let v = f64::from(v);
    let p = if meta.negate {
        v / maxval
    } else {
        (maxval - v) / maxval
    };
    if !(p >= meta.free_thresh && p <= meta.occupied_thresh) {
        return 1;
    }
    // validate() keeps free_thresh < occupied_thresh: no division by 0.
    let ratio = (p - meta.free_thresh) / (meta.occupied_thresh - meta.free_thresh);
    let top = f64::from(crate::map::MAX_WEIGHT - 1);
    1 + (ratio.clamp(0.0, 1.0) * top).round() as u8
}

/// Builds the occupancy grid of a map_server map from its metadata and
/// image, with the metadata's resolution and origin (see the module docs for
/// the classification).
pub fn grid_from_pgm(meta: &RosMapMeta, pgm: &Pgm) -> Result<OccupancyGrid, MapError> {
    meta.validate()?;
    let n = check_dimensions(pgm.width as u64, pgm.height as u64)?;
    if pgm.pixels.len() != n {
        return Err(MapError::SizeMismatch {
            width: pgm.width as u64,
            height: pgm.height as u64,
            expected: n as u64,
            got: pgm.pixels.len() as u64,
        });
    }
    if pgm.maxval == 0 {
        return Err(MapError::parse(PGM_FORMAT, 0, "maxval is 0"));
    }
    let maxval = f64::from(pgm.maxval);
    let cells = pgm
        .pixels
        .iter()
        .map(|&v| classify(meta, maxval, v.min(pgm.maxval)))
        .collect();
    let grid = OccupancyGrid::from_cells(pgm.width, pgm.height, cells)?
        .with_frame(meta.resolution, meta.origin)?;
    if meta.mode != RosMode::Scale {
        return Ok(grid);
    }
    let weights = pgm
        .pixels
        .iter()
        .map(|&v| scale_weight(meta, maxval, v.min(pgm.maxval)))
        .collect();
    grid.with_weights(weights)
}

/// Parses a YAML text and its PGM bytes into a grid in one call.
pub fn read_map(yaml: &str, pgm: &[u8]) -> Result<(RosMapMeta, OccupancyGrid), MapError> {
    let meta = parse_yaml(yaml)?;
    let grid = grid_from_pgm(&meta, &parse_pgm(pgm)?)?;
    Ok((meta, grid))
}

/// Writes `grid` as a binary P5 PGM the way map_saver does: 254 free,
/// 0 occupied, 205 unknown (which read back through [`grid_from_pgm`] with
/// the default thresholds).
pub fn write_pgm(grid: &OccupancyGrid) -> Vec<u8> {
    let header = format!(
        "P5\n# CREATOR: planlab\n{} {}\n255\n",
        grid.width(),
        grid.height()
    );
    let mut out = Vec::with_capacity(header.len() + grid.cells().len());
    out.extend_from_slice(header.as_bytes());
    out.extend(grid.cells().iter().map(|c| match c {
        Cell::Free => 254u8,
        Cell::Occupied => 0,
        Cell::Unknown => 205,
    }));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comment_stripping_respects_quotes_and_words() {
        assert_eq!(strip_comment("a: b # c"), "a: b");
        assert_eq!(strip_comment("# all"), "");
        assert_eq!(strip_comment("image: map#1.pgm"), "image: map#1.pgm");
        assert_eq!(strip_comment("image: \"a # b\" # c"), "image: \"a # b\"");
        assert_eq!(
            strip_comment("image: 'it''s # x' # c"),
            "image: 'it''s # x'"
        );
    }

    #[test]
    fn flat_yaml_forms() {
        let e = parse_flat_yaml(
            "---\n# c\na: 1\nb: [1, 2,\n  3]\nc:\n  - x\n  - 'y'\nd:\n  e: 1\nf: \"q\\\"\"\n...\n",
        )
        .unwrap();
        assert_eq!(e.len(), 5);
        assert_eq!(
            e[1].2,
            Value::List(vec!["1".into(), "2".into(), "3".into()])
        );
        assert_eq!(e[2].2, Value::List(vec!["x".into(), "y".into()]));
        assert_eq!(e[3].2, Value::Nested);
        assert_eq!(
            e[4].2,
            Value::Scalar {
                text: "q\"".into(),
                quoted: true
            }
        );
        assert!(parse_flat_yaml("a: 1\n  b: 2\n").is_err());
        assert!(parse_flat_yaml("a: 1\na: 2\n").is_err());
        assert!(parse_flat_yaml("a: [1, 2\n").is_err());
        assert!(parse_flat_yaml("just words\n").is_err());
        assert!(parse_flat_yaml("a: \"open\n").is_err());
    }

    #[test]
    fn classification_follows_map_server() {
        let mut meta = RosMapMeta::for_grid(&OccupancyGrid::new(1, 1).unwrap(), "m.pgm");
        assert_eq!(classify(&meta, 255.0, 254), Cell::Free);
        assert_eq!(classify(&meta, 255.0, 0), Cell::Occupied);
        assert_eq!(classify(&meta, 255.0, 205), Cell::Unknown);
        meta.negate = true;
        assert_eq!(classify(&meta, 255.0, 254), Cell::Occupied);
        assert_eq!(classify(&meta, 255.0, 0), Cell::Free);
        meta.mode = RosMode::Raw;
        assert_eq!(classify(&meta, 255.0, 0), Cell::Free);
        assert_eq!(classify(&meta, 255.0, 100), Cell::Occupied);
        assert_eq!(classify(&meta, 255.0, 50), Cell::Unknown);
        assert_eq!(classify(&meta, 255.0, 255), Cell::Unknown);
    }

    #[test]
    fn scale_mode_turns_the_grey_band_into_weights() {
        // Default thresholds 0.196 / 0.65: 254 free, 0 occupied; between
        // them p = (255 − v)/255 spreads over the weights 1–9.
        let pgm = b"P2
6 1
255
254 0 150 100 90 205
";
        let yaml = |mode: &str| {
            format!(
                "image: m.pgm
resolution: 0.1
origin: [0, 0, 0]
mode: {mode}
"
            )
        };
        let (_, g) = read_map(&yaml("scale"), pgm).unwrap();
        assert_eq!(g.cells()[..2], [Cell::Free, Cell::Occupied]);
        assert!(g.cells()[2..].iter().all(|&c| c == Cell::Free));
        // v = 150: p = 0.4118, ratio = 0.475 → 1 + round(3.80) = 5;
        // v = 100: p = 0.6078, ratio = 0.907 → 8; v = 90: p = 0.647 → 9;
        // v = 205 (map_saver's unknown grey): p just above free_thresh → 1.
        let weights: Vec<u8> = (0..6).map(|c| g.weight(c, 0)).collect();
        assert_eq!(weights, [1, 1, 5, 8, 9, 1]);
        // Trinary: the same band is unknown and nothing is weighted.
        let (_, t) = read_map(&yaml("trinary"), pgm).unwrap();
        assert!(!t.is_weighted());
        assert_eq!(t.cells()[2], Cell::Unknown);
    }
}
