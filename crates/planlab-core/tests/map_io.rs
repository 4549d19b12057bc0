//! Map file formats through the public API: Moving AI `.map`/`.scen`, ROS
//! map_server YAML + PGM, planlab scenario JSON; real files from
//! `shared/data` and property tests that feed the parsers garbage.

use planlab_core::global::GridPos;
use planlab_core::map::io::movingai::{self, ScenRow};
use planlab_core::map::{Cell, MapError, OccupancyGrid};
use proptest::prelude::*;

/// Root of the shared test data, beside the repository clone.
const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/data");

fn read_text(rel: &str) -> String {
    let p = format!("{DATA}/{rel}");
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("cannot read {p}: {e}"))
}

fn read_bytes(rel: &str) -> Vec<u8> {
    let p = format!("{DATA}/{rel}");
    std::fs::read(&p).unwrap_or_else(|e| panic!("cannot read {p}: {e}"))
}

// ---------------------------------------------------------------- Moving AI

const MOVINGAI: [(&str, usize, usize); 4] = [
    ("movingai/dao/arena.map", 49, 49),
    ("movingai/dao/arena2.map", 281, 209),
    ("movingai/maze/maze512-1-0.map", 512, 512),
    ("movingai/random/random512-10-0.map", 512, 512),
];

/// Counts passable and blocked characters of the map body independently of
/// the parser.
fn count_map_chars(text: &str) -> (usize, usize) {
    let body = text.split("\nmap\n").nth(1).expect("map line");
    let free = body
        .chars()
        .filter(|c| matches!(c, '.' | 'G' | 'S'))
        .count();
    let blocked = body
        .chars()
        .filter(|c| matches!(c, '@' | 'O' | 'T' | 'W'))
        .count();
    (free, blocked)
}

#[test]
fn every_shared_movingai_map_and_scen_parses_and_agrees() {
    for (rel, w, h) in MOVINGAI {
        let text = read_text(rel);
        let g = movingai::parse_map(&text).unwrap_or_else(|e| panic!("{rel}: {e}"));
        assert_eq!((g.width(), g.height()), (w, h), "{rel}");
        let (free, blocked) = count_map_chars(&text);
        assert_eq!(g.counts(), (free, blocked, 0), "{rel}");
        assert!(free > 0 && blocked > 0, "{rel}");

        let scen = read_text(&format!("{rel}.scen"));
        let rows = movingai::parse_scen(&scen).unwrap_or_else(|e| panic!("{rel}.scen: {e}"));
        let data_lines = scen
            .lines()
            .skip(1)
            .filter(|l| !l.trim().is_empty())
            .count();
        assert_eq!(rows.len(), data_lines, "{rel}.scen");
        let file_name = rel.rsplit('/').next().unwrap();
        assert!(
            rows.iter().all(|r| r.map.ends_with(file_name)),
            "{rel}.scen"
        );
        movingai::check_scen_against_map(&rows, &g).unwrap_or_else(|e| panic!("{rel}.scen: {e}"));

        // Writing and re-reading gives the same cells.
        let back = movingai::parse_map(&movingai::write_map(&g)).unwrap();
        assert_eq!(back.cells(), g.cells(), "{rel}");
    }
}

#[test]
fn arena_first_query_matches_the_file() {
    let rows = movingai::parse_scen(&read_text("movingai/dao/arena.map.scen")).unwrap();
    assert_eq!(
        rows[0],
        ScenRow {
            bucket: 0,
            map: "maps/dao/arena.map".into(),
            width: 49,
            height: 49,
            start: GridPos::new(1, 11),
            goal: GridPos::new(1, 12),
            optimal: 1.0,
        }
    );
}

#[test]
fn scen_for_the_wrong_map_is_refused() {
    let arena = movingai::parse_map(&read_text("movingai/dao/arena.map")).unwrap();
    let rows = movingai::parse_scen(&read_text("movingai/dao/arena2.map.scen")).unwrap();
    let err = movingai::check_scen_against_map(&rows, &arena).unwrap_err();
    assert!(err.to_string().contains("281×209"), "{err}");
}

#[test]
fn movingai_error_messages_are_one_readable_line() {
    let mut text = read_text("movingai/dao/arena.map");
    // Drop one character from the third map row (file line 7).
    let start = text.match_indices('\n').nth(5).unwrap().0 + 1;
    text.remove(start);
    let e = movingai::parse_map(&text).unwrap_err();
    assert_eq!(
        e.to_string(),
        "Moving AI map parse error at line 7: row has 48 characters, expected 49"
    );
    let e = movingai::parse_scen("version 1\n0 m 3 3 0 0 1 1 fast\n").unwrap_err();
    assert_eq!(
        e.to_string(),
        "Moving AI scenario parse error at line 2: optimal length must be a number, got \"fast\""
    );
}

/// A random grid of free/occupied cells.
fn arb_grid(max: usize) -> impl Strategy<Value = OccupancyGrid> {
    (1..=max, 1..=max).prop_flat_map(|(w, h)| {
        proptest::collection::vec(prop_oneof![Just(Cell::Free), Just(Cell::Occupied)], w * h)
            .prop_map(move |cells| OccupancyGrid::from_cells(w, h, cells).unwrap())
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn movingai_parsers_never_panic_on_strings(s in "\\PC{0,200}") {
        let _ = movingai::parse_map(&s);
        let _ = movingai::parse_scen(&s);
    }

    #[test]
    fn movingai_parsers_never_panic_on_near_valid_text(
        h in 0u64..6, w in 0u64..6, body in "[.@TGSOW \\r\\nx]{0,60}", tail in "[0-9 \\t.a-z-]{0,40}"
    ) {
        let text = format!("type octile\nheight {h}\nwidth {w}\nmap\n{body}");
        if let Ok(g) = movingai::parse_map(&text) {
            prop_assert_eq!((g.width() as u64, g.height() as u64), (w, h));
        }
        let _ = movingai::parse_scen(&format!("version 1\n{tail}"));
    }

    #[test]
    fn movingai_map_round_trips(g in arb_grid(24)) {
        let text = movingai::write_map(&g);
        let back = movingai::parse_map(&text).unwrap();
        prop_assert_eq!(back.cells(), g.cells());
        prop_assert_eq!((back.width(), back.height()), (g.width(), g.height()));
        // CRLF and trailing spaces do not change the result.
        let crlf = text.replace('\n', "  \r\n");
        let crlf_grid = movingai::parse_map(&crlf).unwrap();
        prop_assert_eq!(crlf_grid.cells(), g.cells());
    }

    #[test]
    fn movingai_map_truncations_are_errors(g in arb_grid(12), cut in 0.0f64..1.0) {
        let text = movingai::write_map(&g);
        // Cut strictly inside the body or header, never at the very end.
        let n = ((text.len() - 1) as f64 * cut) as usize;
        let short = &text[..n];
        // The cut always loses at least the final newline and the last
        // cell, so some row (or the header) is incomplete.
        prop_assert!(movingai::parse_map(short).is_err(), "accepted {:?}", short);
    }

    #[test]
    fn scen_rows_round_trip(
        rows in proptest::collection::vec(
            (0u32..100, "[a-z0-9/._-]{1,12}", 1u32..600, 1u32..600, 0.0f64..1.0, 0.0f64..1.0, 0.0f64..1.0, 0.0f64..1.0, 0.0f64..5000.0, any::<bool>()),
            0..20)
    ) {
        let mut text = String::from("version 1\n");
        let mut expect = Vec::new();
        for (bucket, map, w, h, sx, sy, gx, gy, opt, tabs) in rows {
            let start = GridPos::new((sx * w as f64) as u32 % w, (sy * h as f64) as u32 % h);
            let goal = GridPos::new((gx * w as f64) as u32 % w, (gy * h as f64) as u32 % h);
            let sep = if tabs { "\t" } else { "  " };
            text.push_str(&[bucket.to_string(), map.clone(), w.to_string(), h.to_string(),
                start.col.to_string(), start.row.to_string(), goal.col.to_string(),
                goal.row.to_string(), format!("{opt}")].join(sep));
            text.push('\n');
            expect.push(ScenRow { bucket, map, width: w, height: h, start, goal, optimal: opt });
        }
        prop_assert_eq!(movingai::parse_scen(&text).unwrap(), expect);
    }
}

#[test]
fn movingai_huge_header_is_too_large() {
    let r = movingai::parse_map("type octile\nheight 20000\nwidth 20000\nmap\n....\n");
    assert!(
        matches!(
            r,
            Err(MapError::TooLarge {
                cells: 400_000_000,
                ..
            })
        ),
        "{r:?}"
    );
}

// ---------------------------------------------------------------------- ROS

use planlab_core::map::io::ros::{self, Pgm, RosMapMeta, RosMode};
use planlab_core::map::Pose2;

/// Finds where the raster of a P5 file starts by reading its header by hand
/// (four whitespace-separated fields, `#` comments to end of line).
fn p5_raster(bytes: &[u8]) -> &[u8] {
    let mut fields = 0;
    let mut i = 0;
    while fields < 4 {
        if bytes[i] == b'#' {
            while bytes[i] != b'\n' {
                i += 1;
            }
        } else if bytes[i].is_ascii_whitespace() {
            i += 1;
        } else {
            while !bytes[i].is_ascii_whitespace() {
                i += 1;
            }
            fields += 1;
        }
    }
    &bytes[i + 1..]
}

#[test]
fn turtlebot3_map_loads_with_the_file_counts() {
    let yaml = read_text("rosmaps/turtlebot3/map.yaml");
    let pgm = read_bytes("rosmaps/turtlebot3/map.pgm");
    let meta = ros::parse_yaml(&yaml).unwrap();
    assert_eq!(meta.image, "map.pgm");
    assert_eq!(meta.resolution, 0.05);
    assert_eq!(
        meta.origin,
        Pose2 {
            x: -10.0,
            y: -10.0,
            yaw: 0.0
        }
    );
    assert!(!meta.negate);
    assert_eq!((meta.occupied_thresh, meta.free_thresh), (0.65, 0.196));
    assert_eq!(meta.mode, RosMode::Trinary);

    let image = ros::parse_pgm(&pgm).unwrap();
    assert_eq!((image.width, image.height, image.maxval), (384, 384, 255));
    let grid = ros::grid_from_pgm(&meta, &image).unwrap();
    assert_eq!((grid.width(), grid.height()), (384, 384));
    assert_eq!(grid.resolution(), 0.05);
    assert_eq!(grid.origin().x, -10.0);
    assert_eq!(grid.origin().y, -10.0);

    let raster = p5_raster(&pgm);
    assert_eq!(raster.len(), 384 * 384);
    let count = |v: u8| raster.iter().filter(|&&b| b == v).count();
    let (free, occ, unk) = (count(254), count(0), count(205));
    assert_eq!(free + occ + unk, 384 * 384, "the file only has 3 values");
    assert_eq!(grid.counts(), (free, occ, unk));
    // The first raster byte is the top-left pixel.
    let expect = match raster[0] {
        254 => Cell::Free,
        0 => Cell::Occupied,
        _ => Cell::Unknown,
    };
    assert_eq!(grid.get(0, 0), Some(expect));

    // Saving reproduces the raster byte for byte and the metadata exactly.
    let saved = ros::write_pgm(&grid);
    assert_eq!(p5_raster(&saved), raster);
    let meta_back = ros::parse_yaml(&ros::write_yaml(&meta)).unwrap();
    assert_eq!(meta_back, meta);
    let (_, again) = ros::read_map(&ros::write_yaml(&meta), &saved).unwrap();
    assert_eq!(again, grid);
}

fn meta(image: &str) -> RosMapMeta {
    RosMapMeta::for_grid(&OccupancyGrid::new(1, 1).unwrap(), image)
}

#[test]
fn yaml_variants_and_validation() {
    let m = ros::parse_yaml(
        "# saved by hand\nimage: \"my map.pgm\"  # quoted\nresolution: 0.1\norigin:\n  - 1.5\n  - -2\n  - 0.25\nnegate: true\nmode: scale\nfree_thresh: 0.2\noccupied_thresh: 0.7\nextra: {a: 1}\n",
    )
    .unwrap();
    assert_eq!(m.image, "my map.pgm");
    assert_eq!(
        m.origin,
        Pose2 {
            x: 1.5,
            y: -2.0,
            yaw: 0.25
        }
    );
    assert!(m.negate);
    assert_eq!(m.mode, RosMode::Scale);
    assert_eq!((m.free_thresh, m.occupied_thresh), (0.2, 0.7));

    let base = "image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n";
    let line_of = |extra: &str| match ros::parse_yaml(&format!("{base}{extra}")) {
        Err(MapError::Parse { line, .. }) => line,
        other => panic!("{extra:?}: expected a parse error, got {other:?}"),
    };
    assert_eq!(line_of("free_thresh: 0.7\n"), 4); // free ≥ occupied (0.65)
    assert_eq!(line_of("occupied_thresh: 1.5\n"), 4);
    assert_eq!(line_of("free_thresh: -0.1\n"), 4);
    assert_eq!(line_of("free_thresh: nan\n"), 4);
    assert_eq!(line_of("negate: maybe\n"), 4);
    assert_eq!(line_of("mode: fancy\n"), 4);
    assert_eq!(line_of("image: other.pgm\n"), 4);
    for bad in [
        "image: m.pgm\nresolution: 0\norigin: [0, 0, 0]\n",
        "image: m.pgm\nresolution: -0.05\norigin: [0, 0, 0]\n",
        "image: m.pgm\nresolution: inf\norigin: [0, 0, 0]\n",
        "image: m.pgm\nresolution: 0.05\norigin: [0, nan, 0]\n",
        "image: m.pgm\nresolution: 0.05\norigin: [0, 0]\n",
        "image: m.pgm\nresolution: 0.05\norigin: 3\n",
        "resolution: 0.05\norigin: [0, 0, 0]\n",
        "image: m.pgm\norigin: [0, 0, 0]\n",
        "image: m.pgm\nresolution: 0.05\n",
        "image: \"\"\nresolution: 0.05\norigin: [0, 0, 0]\n",
        "image: m.pgm\nresolution: \"0.05\"\norigin: [0, 0, 0]\n",
    ] {
        assert!(ros::parse_yaml(bad).is_err(), "accepted {bad:?}");
    }
    let msg =
        ros::parse_yaml("image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nfree_thresh: 0.9\n")
            .unwrap_err()
            .to_string();
    assert_eq!(
        msg,
        "ROS map yaml parse error at line 4: `free_thresh` (0.9) must be below `occupied_thresh` (0.65)"
    );
}

#[test]
fn pgm_p2_p5_16bit_and_comments() {
    let p2 = ros::parse_pgm(b"P2\n# c1\n3 2 # c2\n# c3\n9\n0 1 2\n3 4 9\n").unwrap();
    assert_eq!(
        p2,
        Pgm {
            width: 3,
            height: 2,
            maxval: 9,
            pixels: vec![0, 1, 2, 3, 4, 9]
        }
    );
    let p5 = ros::parse_pgm(b"P5 2 1 65535\n\x01\x02\xff\xfe").unwrap();
    assert_eq!(p5.pixels, vec![0x0102, 0xfffe]);
    let p5 = ros::parse_pgm(b"P5\n2 2\n255\n\x00\x0a\xff\x10trailing").unwrap();
    assert_eq!(p5.pixels, vec![0, 10, 255, 16]);
}

#[test]
fn pgm_errors() {
    for (bad, what) in [
        (&b"P5\n2 2\n255\n\x00\x01\x02"[..], "truncated"),
        (b"P5\n2 2\n255", "no image data"),
        (b"P5\n2 2\n", "maxval"),
        (b"P5\n2", "height"),
        (b"P2\n2 2\n9\n1 2 3", "truncated"),
        (b"P2\n2 1\n9\n1 10", "above maxval"),
        (b"P5\n1 1\n100\n\x65", "above maxval"),
        (b"P2\n2 1\n9\n1 x", "pixel value"),
        (b"P5\n2 2\n0\n\x00\x00\x00\x00", "maxval"),
        (b"P5\n2 2\n70000\n", "maxval"),
        (b"P6\n2 2\n255\n", "PPM"),
        (b"\x89PNG\r\n\x1a\n", "PNG"),
        (b"", "P5 or P2"),
        (b"P52 2 255\n", "P5 or P2"),
        (b"P5\n2x 2\n255\n", "after the width"),
        (b"P5\n99999999999999999999999 2\n255\n", "too large"),
    ] {
        let e = ros::parse_pgm(bad).unwrap_err().to_string();
        assert!(e.contains(what), "{bad:?}: {e}");
    }
    assert!(matches!(
        ros::parse_pgm(b"P5\n20000 20000\n255\n\x00"),
        Err(MapError::TooLarge {
            cells: 400_000_000,
            ..
        })
    ));
    assert!(matches!(
        ros::parse_pgm(b"P2\n0 5\n255\n"),
        Err(MapError::Empty { .. })
    ));
}

#[test]
fn pgm_modes_and_negate() {
    let pgm = Pgm {
        width: 5,
        height: 1,
        maxval: 255,
        pixels: vec![0, 50, 100, 205, 254],
    };
    let grid = |m: &RosMapMeta| ros::grid_from_pgm(m, &pgm).unwrap().to_ascii();
    let mut m = meta("m.pgm");
    assert_eq!(grid(&m), "##??.\n");
    m.mode = RosMode::Scale;
    assert_eq!(grid(&m), "##??.\n");
    m.negate = true;
    m.mode = RosMode::Trinary;
    // p = v/255: 0 → 0 free, 50 → 0.196 (just ≥ 0.196) unknown, 100 → 0.39
    // unknown, 205 → 0.80 occupied, 254 occupied.
    assert_eq!(grid(&m), ".??##\n");
    m.mode = RosMode::Raw;
    // Raw: 0 free, 50 → 0.5 unknown, 100 occupied, >100 unknown.
    assert_eq!(grid(&m), ".?#??\n");
    // A 16-bit image is scaled by its maxval.
    let wide = Pgm {
        width: 2,
        height: 1,
        maxval: 1000,
        pixels: vec![0, 1000],
    };
    m.negate = false;
    m.mode = RosMode::Trinary;
    assert_eq!(ros::grid_from_pgm(&m, &wide).unwrap().to_ascii(), "#.\n");
    // Inconsistent hand-built images are errors, not panics.
    let short = Pgm {
        width: 3,
        height: 1,
        maxval: 255,
        pixels: vec![0],
    };
    assert!(matches!(
        ros::grid_from_pgm(&m, &short),
        Err(MapError::SizeMismatch { .. })
    ));
    let zero = Pgm {
        width: 1,
        height: 1,
        maxval: 0,
        pixels: vec![0],
    };
    assert!(ros::grid_from_pgm(&m, &zero).is_err());
    m.resolution = -1.0;
    assert!(ros::grid_from_pgm(&m, &pgm).is_err());
}

#[test]
fn yaml_writer_quotes_awkward_image_names() {
    for name in [
        "a b.pgm",
        "x: y.pgm",
        "#h.pgm",
        "q\"uote.pgm",
        "-lead.pgm",
        " pad.pgm ",
        "c:\\maps\\m.pgm",
        "é.pgm",
    ] {
        let m = meta(name);
        let back = ros::parse_yaml(&ros::write_yaml(&m)).unwrap();
        assert_eq!(back.image, name);
    }
}

/// A random grid with all three states.
fn arb_grid3(max: usize) -> impl Strategy<Value = OccupancyGrid> {
    (1..=max, 1..=max).prop_flat_map(|(w, h)| {
        proptest::collection::vec(
            prop_oneof![Just(Cell::Free), Just(Cell::Occupied), Just(Cell::Unknown)],
            w * h,
        )
        .prop_map(move |cells| OccupancyGrid::from_cells(w, h, cells).unwrap())
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn ros_parsers_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..300), s in "\\PC{0,200}") {
        let _ = ros::parse_pgm(&bytes);
        let _ = ros::parse_yaml(&s);
        let _ = ros::parse_yaml(&String::from_utf8_lossy(&bytes));
    }

    #[test]
    fn pgm_with_random_header_and_body_never_panics(
        magic in prop_oneof![Just("P5"), Just("P2")],
        w in 0u64..8, h in 0u64..8, maxval in 0u64..70000,
        sep in "[ \\n\\t#a]{1,4}",
        body in proptest::collection::vec(any::<u8>(), 0..100),
    ) {
        let mut bytes = format!("{magic}{sep}{w} {h}{sep}{maxval}\n").into_bytes();
        bytes.extend(body);
        if let Ok(p) = ros::parse_pgm(&bytes) {
            prop_assert_eq!(p.pixels.len() as u64, w * h);
            prop_assert!(p.pixels.iter().all(|&v| v <= p.maxval));
        }
    }

    #[test]
    fn yaml_with_random_values_never_panics(
        key in prop_oneof![Just("image"), Just("resolution"), Just("origin"), Just("negate"),
            Just("mode"), Just("free_thresh"), Just("occupied_thresh"), Just("other")],
        value in "[\\[\\]{}'\"#:, a-z0-9.-]{0,20}",
    ) {
        let _ = ros::parse_yaml(&format!("image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n{key}: {value}\n"));
        let _ = ros::parse_yaml(&format!("{key}: {value}\n  - {value}\n"));
    }

    #[test]
    fn pgm_and_yaml_round_trip(
        g in arb_grid3(20),
        res in 0.001f64..10.0,
        x in -1e4f64..1e4, y in -1e4f64..1e4, yaw in -3.2f64..3.2,
        ascii in any::<bool>(),
    ) {
        let g = g.with_frame(res, Pose2 { x, y, yaw }).unwrap();
        let meta = RosMapMeta::for_grid(&g, "map.pgm");
        let yaml = ros::write_yaml(&meta);
        let mut pgm = ros::write_pgm(&g);
        if ascii {
            // Re-encode as P2 to exercise the ASCII reader on the same pixels.
            let p = ros::parse_pgm(&pgm).unwrap();
            let mut t = format!("P2\n{} {}\n255\n", p.width, p.height);
            for row in p.pixels.chunks(p.width) {
                let line: Vec<String> = row.iter().map(|v| v.to_string()).collect();
                t.push_str(&line.join(" "));
                t.push('\n');
            }
            pgm = t.into_bytes();
        }
        let (m2, g2) = ros::read_map(&yaml, &pgm).unwrap();
        prop_assert_eq!(m2, meta);
        prop_assert_eq!(g2, g);
    }

    #[test]
    fn pgm_truncations_are_errors(g in arb_grid3(12), cut in 0.0f64..1.0) {
        let bytes = ros::write_pgm(&g);
        let n = ((bytes.len() - 1) as f64 * cut) as usize;
        prop_assert!(ros::parse_pgm(&bytes[..n]).is_err());
    }

    #[test]
    fn yaml_truncations_never_panic_and_short_ones_fail(cut in 0usize..200) {
        let yaml = ros::write_yaml(&meta("map.pgm"));
        let n = cut.min(yaml.len());
        let r = ros::parse_yaml(&yaml[..n]);
        // Without the origin line (the fourth) the file is incomplete.
        let origin_end = yaml.find("origin").unwrap() + "origin: [0.0, 0.0, 0.0]".len();
        if n < origin_end {
            prop_assert!(r.is_err());
        }
    }
}
