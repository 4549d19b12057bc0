//! Map file formats through the public API: Moving AI `.map`/`.scen`, ROS
//! map_server YAML + PGM, planlab scenario JSON; real files from
//! `tests/data` and property tests that feed the parsers garbage.

use planlab_core::global::GridPos;
use planlab_core::map::io::movingai::{self, ScenRow};
use planlab_core::map::{Cell, MapError, OccupancyGrid};
use proptest::prelude::*;

/// Root of the test data in the repository (`tests/data`).
const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/data");

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
    // Scale: the band is weighted free ground (100 → p 0.61 → weight 8;
    // 205 → p just above free_thresh → weight 1).
    assert_eq!(grid(&m), "##8..\n");
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

// ----------------------------------------------------------------- Scenario

use planlab_core::global::plan::{Algorithm, GridPlanOptions};
use planlab_core::global::{Diagonal, Heuristic};
use planlab_core::scenario::{
    InlineMap, MapFileRef, MapSpec, RowEncoding, Scenario, ScenarioError, ScenarioPoint,
    WorldPoint, SCENARIO_VERSION,
};

const DEMO: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../assets/scenarios/grid-demo.json"
);

#[test]
fn grid_demo_asset_loads_and_is_what_the_docs_say() {
    let text = std::fs::read_to_string(DEMO).unwrap();
    let s = Scenario::from_json(&text).unwrap();
    assert_eq!(s.version, SCENARIO_VERSION);
    let g = s.inline_grid().unwrap().expect("inline map");
    assert_eq!((g.width(), g.height()), (40, 30));
    let (free, occ, unk) = g.counts();
    assert!(occ > 40 && free > 600 && unk > 0, "{free} {occ} {unk}");
    for p in [s.start, s.goal] {
        assert_eq!(g.get(p.col as usize, p.row as usize), Some(Cell::Free));
    }
    // The start's world point is the centre of its cell.
    let w = s.start.world.expect("start has a world point");
    let (x, y) = g.cell_to_world(s.start.col as usize, s.start.row as usize);
    assert!((w.x - x).abs() < 1e-9 && (w.y - y).abs() < 1e-9);
    // Saving it again gives the same file.
    assert_eq!(s.to_json_pretty().unwrap(), text);
}

#[test]
fn grid_demo_is_solvable_with_its_own_settings() {
    let s = Scenario::from_json(&std::fs::read_to_string(DEMO).unwrap()).unwrap();
    let g = s
        .load_grid(&mut |p| Err(format!("no files here: {p}")))
        .unwrap();
    let plan =
        planlab_core::global::plan::plan_on_map(&g, s.start.pos(), s.goal.pos(), &s.grid_planner)
            .unwrap();
    assert_eq!(plan.path.cells.first(), Some(&s.start.pos()));
    assert_eq!(plan.path.cells.last(), Some(&s.goal.pos()));
}

fn minimal(map: &str) -> String {
    format!(
        r#"{{"version": 1, "map": {map}, "start": {{"col": 0, "row": 0}}, "goal": {{"col": 2, "row": 1}}}}"#
    )
}

#[test]
fn scenario_minimal_defaults_and_encodings() {
    let s = Scenario::from_json(&minimal(
        r#"{"width": 3, "height": 2, "cells": ["..#", "?.."]}"#,
    ))
    .unwrap();
    assert_eq!(s.name, "");
    assert_eq!(s.grid_planner, GridPlanOptions::default());
    let g = s.inline_grid().unwrap().unwrap();
    assert_eq!(g.to_ascii(), "..#\n?..\n");
    assert_eq!(g.resolution(), 1.0);
    let r = Scenario::from_json(&minimal(
        r#"{"width": 3, "height": 2, "resolution": 0.5, "origin": {"x": 1, "y": 2, "yaw": 0}, "rle": ["2.#", "?2."]}"#,
    ))
    .unwrap();
    let rg = r.inline_grid().unwrap().unwrap();
    assert_eq!(rg.cells(), g.cells());
    assert_eq!(rg.resolution(), 0.5);
    assert_eq!(rg.origin().y, 2.0);
    assert!(matches!(
        &r.map,
        MapSpec::Inline(InlineMap {
            encoding: RowEncoding::Rle,
            ..
        })
    ));
    // RLE is written back as RLE.
    assert!(r.to_json_pretty().unwrap().contains("\"2.#\""));
}

#[test]
fn scenario_planner_section_is_typed() {
    let s = Scenario::from_json(
        &minimal(r#"{"width": 3, "height": 2, "cells": ["...", "..."]}"#).replace(
            r#""goal""#,
            r#""grid_planner": {"algorithm": "safe-astar", "heuristic": "euclidean", "weight": 1.5,
            "diagonal": "never", "allow_unknown": true, "inflate_m": 0.2, "keypoints": true,
            "bottom_up_eps": 0.5}, "goal""#,
        ),
    )
    .unwrap();
    let p = s.grid_planner;
    assert_eq!(p.algorithm, Algorithm::SafeAStar);
    assert_eq!(p.heuristic, Heuristic::Euclidean);
    assert_eq!(p.weight, 1.5);
    assert_eq!(p.diagonal, Diagonal::Never);
    assert!(p.allow_unknown && p.keypoints);
    assert_eq!((p.inflate_m, p.bottom_up_eps), (0.2, Some(0.5)));
}

fn scenario_err(text: &str) -> ScenarioError {
    match Scenario::from_json(text) {
        Err(e) => e,
        Ok(s) => panic!("accepted {text}: {s:?}"),
    }
}

#[test]
fn scenario_errors_are_specific() {
    let inline = r#"{"width": 3, "height": 2, "cells": ["...", "..."]}"#;
    let cases: Vec<(String, &str)> =
        vec![
        (
            minimal(inline).replace("\"version\": 1", "\"version\": 2"),
            "version 2 is not supported",
        ),
        (
            minimal(inline).replace("\"version\": 1,", ""),
            "missing field `version`",
        ),
        (
            minimal(inline).replace("\"start\"", "\"strat\""),
            "unknown field `strat`",
        ),
        (
            minimal(inline).replace(
                "\"goal\"",
                "\"grid_planner\": {\"heurisitc\": \"octile\"}, \"goal\"",
            ),
            "unknown field `grid_planner.heurisitc`",
        ),
        (
            minimal(inline).replace(
                "\"goal\"",
                "\"grid_planner\": {\"safe\": {\"epsilom\": 1}}, \"goal\"",
            ),
            "unknown field `grid_planner.safe.epsilom`",
        ),
        (
            minimal(inline).replace(
                "\"goal\"",
                "\"grid_planner\": {\"algorithm\": \"jps\", \"diagonal\": \"always\"}, \"goal\"",
            ),
            "jump point",
        ),
        (
            minimal(inline).replace(
                "\"goal\"",
                "\"grid_planner\": {\"algorithm\": \"wavefront\"}, \"goal\"",
            ),
            "wavefront",
        ),
        (
            minimal(inline).replace("\"goal\"", "\"grid_planner\": {\"weight\": 0.5}, \"goal\""),
            "weight",
        ),
        (
            minimal(inline).replace(
                "\"goal\"",
                "\"grid_planner\": {\"inflate_m\": -1}, \"goal\"",
            ),
            "inflate_m",
        ),
        (
            minimal(inline).replace(
                "\"goal\"",
                "\"grid_planner\": {\"bottom_up_eps\": -1}, \"goal\"",
            ),
            "bottom_up_eps",
        ),
        (
            minimal(r#"{"width": 3, "height": 2, "cells": ["...", ".."]}"#),
            "row 2 has 2 characters",
        ),
        (
            minimal(r#"{"width": 3, "height": 2, "cells": ["...", ".x."]}"#),
            "row 2, column 2",
        ),
        (
            minimal(r#"{"width": 3, "height": 2, "cells": ["..."]}"#),
            "1 rows, expected height 2",
        ),
        (
            minimal(r#"{"width": 3, "height": 2, "rle": ["3.", "4."]}"#),
            "longer than the width",
        ),
        (
            minimal(r#"{"width": 3, "height": 2, "cells": ["...", "..."], "rle": ["3.", "3."]}"#),
            "not both",
        ),
        (minimal(r#"{"width": 3, "height": 2}"#), "needs `cells`"),
        (
            minimal(r#"{"cells": ["...", "..."]}"#),
            "needs `width` and `height`",
        ),
        (
            minimal(r#"{"width": 3, "height": 2, "resolution": -0.1, "cells": ["...", "..."]}"#),
            "resolution",
        ),
        (
            minimal(r#"{"width": 3, "height": 2, "resolution": 0, "cells": ["...", "..."]}"#),
            "resolution",
        ),
        (
            minimal(r#"{"width": 20000, "height": 20000, "rle": []}"#),
            "too large",
        ),
        (
            minimal(r#"{"width": 0, "height": 2, "cells": []}"#),
            "empty",
        ),
        (minimal(r#"{"file": "maps/x.png"}"#), "unknown map format"),
        (
            minimal(r#"{"file": "maps/x.map", "cells": ["..."]}"#),
            "not both",
        ),
        (
            minimal(r#"{"file": "maps/x.map", "resolution": -1}"#),
            "resolution",
        ),
        (
            minimal(r#"{"width": 2, "height": 2, "cells": ["..", ".."]}"#),
            "goal (2, 1) is outside the 2×2 map",
        ),
        (
            minimal(inline).replace(
                r#""col": 0, "row": 0"#,
                r#""col": 0, "row": 0, "world": {"x": 2.5, "y": 0.5}"#,
            ),
            "lies in cell (2, 1)",
        ),
        (
            minimal(inline).replace("\"version\": 1", "\"version\": 1, \"version\": 1"),
            "duplicate field",
        ),
        ("[1, 2]".into(), "a scenario is a JSON object"),
        (
            minimal(inline).replace(r#"{"col": 0, "row": 0}"#, "[0, 0]"),
            "expected an object at `start`",
        ),
        ("{\"version\": 1, ".into(), "EOF"),
        ("{\"version\": 1e400}".into(), "number out of range"),
        ("{\"version\": \"1\"}".into(), "invalid type: string \"1\""),
        ("{\"version\": NaN}".into(), "NaN is not a number JSON allows"),
    ];
    for (text, want) in cases {
        let e = scenario_err(&text).to_string();
        assert!(e.contains(want), "{text}\n  gave: {e}\n  want: {want}");
        assert!(!e.contains('\n'), "one line: {e}");
    }
    let e = scenario_err("{\n  \"version\": 1,\n  \"nmae\": \"x\"\n}");
    assert!(matches!(e, ScenarioError::Json { line: 3, .. }), "{e:?}");
}

#[test]
fn scenario_file_reference_loads_through_the_reader() {
    let text = r#"{"version": 1, "name": "tb3", "map": {"file": "maps/turtlebot3/map.yaml"},
        "start": {"col": 200, "row": 200, "world": {"x": 0.025, "y": -0.825}}, "goal": {"col": 190, "row": 190}}"#;
    let s = Scenario::from_json(text).unwrap();
    assert_eq!(s.inline_grid().unwrap(), None);
    let mut asked = Vec::new();
    let g = s
        .load_grid(&mut |p| {
            asked.push(p.to_string());
            let rel = p.strip_prefix("maps/").ok_or("outside maps/")?;
            std::fs::read(format!("{DATA}/rosmaps/{rel}")).map_err(|e| e.to_string())
        })
        .unwrap();
    assert_eq!(
        asked,
        ["maps/turtlebot3/map.yaml", "maps/turtlebot3/map.pgm"]
    );
    assert_eq!((g.width(), g.height(), g.resolution()), (384, 384, 0.05));
    // A reader failure names the file.
    let e = s.load_grid(&mut |_| Err("gone".into())).unwrap_err();
    assert_eq!(e.to_string(), "cannot read maps/turtlebot3/map.yaml: gone");

    // A Moving AI map with a resolution override.
    let m = Scenario::from_json(
        r#"{"version": 1, "map": {"file": "arena.map", "resolution": 0.1, "origin": {"x": -1, "y": 0, "yaw": 0}},
            "start": {"col": 1, "row": 11}, "goal": {"col": 47, "row": 40}}"#,
    )
    .unwrap();
    let g = m
        .load_grid(&mut |_| Ok(read_bytes("movingai/dao/arena.map")))
        .unwrap();
    assert_eq!((g.width(), g.resolution(), g.origin().x), (49, 0.1, -1.0));
    // Start/goal are checked against the loaded map.
    let mut off = m.clone();
    off.goal = ScenarioPoint::cell(49, 0);
    assert!(off.validate().is_ok(), "not checkable without the file");
    let e = off
        .load_grid(&mut |_| Ok(read_bytes("movingai/dao/arena.map")))
        .unwrap_err();
    assert!(e.to_string().contains("outside the 49×49 map"), "{e}");
}

#[test]
fn scenario_with_inline_grid_picks_encoding_and_validates_on_save() {
    let small = OccupancyGrid::from_ascii("..\n.#\n").unwrap();
    let s = Scenario::new("s", small.clone(), GridPos::new(0, 0), GridPos::new(1, 0));
    assert!(matches!(
        &s.map,
        MapSpec::Inline(InlineMap {
            encoding: RowEncoding::Plain,
            ..
        })
    ));
    let big = OccupancyGrid::new(101, 3).unwrap();
    let s2 = s.clone().with_inline_grid(big.clone());
    assert!(matches!(
        &s2.map,
        MapSpec::Inline(InlineMap {
            encoding: RowEncoding::Rle,
            ..
        })
    ));
    assert!(s2.to_json_pretty().unwrap().contains("\"101.\""));
    assert_eq!(
        Scenario::from_json(&s2.to_json_pretty().unwrap()).unwrap(),
        s2
    );
    // Values only Rust code can produce are caught before writing.
    let mut bad = s.clone();
    bad.grid_planner.inflate_m = f64::NAN;
    assert!(bad.to_json_pretty().is_err());
    let mut bad = s.clone();
    bad.start.world = Some(WorldPoint {
        x: f64::INFINITY,
        y: 0.0,
    });
    assert!(bad.to_json_pretty().is_err());
    let mut bad = s;
    bad.map = MapSpec::File(MapFileRef {
        file: "m.map".into(),
        resolution: Some(f64::NAN),
        origin: None,
    });
    assert!(bad.to_json_pretty().is_err());
}

/// Random planner options that validate.
fn arb_options() -> impl Strategy<Value = GridPlanOptions> {
    (
        prop_oneof![
            Just(Algorithm::AStar),
            Just(Algorithm::Dijkstra),
            Just(Algorithm::Jps),
            Just(Algorithm::SafeAStar)
        ],
        prop_oneof![
            Just(Heuristic::Manhattan),
            Just(Heuristic::Euclidean),
            Just(Heuristic::Octile),
            Just(Heuristic::Chebyshev),
            Just(Heuristic::Zero)
        ],
        1.0f64..5.0,
        prop_oneof![
            Just(Diagonal::Never),
            Just(Diagonal::NoCornerCutting),
            Just(Diagonal::OneSideFree),
            Just(Diagonal::Always)
        ],
        any::<bool>(),
        0.0f64..2.0,
        any::<bool>(),
        proptest::option::of(0.0f64..4.0),
    )
        .prop_map(
            |(
                algorithm,
                heuristic,
                weight,
                mut diagonal,
                allow_unknown,
                inflate_m,
                keypoints,
                bottom_up_eps,
            )| {
                // JPS is defined for the Moving AI move rule only.
                if algorithm == Algorithm::Jps {
                    diagonal = Diagonal::NoCornerCutting;
                }
                GridPlanOptions {
                    algorithm,
                    heuristic,
                    weight,
                    diagonal,
                    allow_unknown,
                    inflate_m,
                    keypoints,
                    bottom_up_eps,
                    ..GridPlanOptions::default()
                }
            },
        )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn scenario_round_trips_losslessly(
        g in arb_grid3(30),
        res in 1e-3f64..10.0, x in -1e6f64..1e6, y in -1e6f64..1e6, yaw in -3.2f64..3.2,
        sc in 0.0f64..1.0, sr in 0.0f64..1.0, gc in 0.0f64..1.0, gr in 0.0f64..1.0,
        with_world in any::<bool>(), rle in any::<bool>(),
        name in "\\PC{0,20}", description in "\\PC{0,60}",
        options in arb_options(),
    ) {
        let g = g.with_frame(res, Pose2 { x, y, yaw }).unwrap();
        let pick = |u: f64, n: usize| ((u * n as f64) as usize).min(n - 1) as u32;
        let start = GridPos::new(pick(sc, g.width()), pick(sr, g.height()));
        let goal = GridPos::new(pick(gc, g.width()), pick(gr, g.height()));
        let mut s = Scenario::new(name, g.clone(), start, goal);
        s.description = description;
        s.grid_planner = options;
        if let MapSpec::Inline(m) = &mut s.map {
            m.encoding = if rle { RowEncoding::Rle } else { RowEncoding::Plain };
        }
        if with_world {
            let (wx, wy) = g.cell_to_world(start.col as usize, start.row as usize);
            s.start.world = Some(WorldPoint { x: wx, y: wy });
        }
        let json = s.to_json_pretty().unwrap();
        let back = Scenario::from_json(&json).unwrap();
        prop_assert_eq!(&back, &s);
        prop_assert_eq!(back.inline_grid().unwrap().unwrap(), g);
        // And the compact form reads the same.
        let compact = serde_json::to_string(&s).unwrap();
        prop_assert_eq!(Scenario::from_json(&compact).unwrap(), s);
    }

    #[test]
    fn scenario_parser_never_panics_on_strings(s in "\\PC{0,300}") {
        let _ = Scenario::from_json(&s);
    }

    #[test]
    fn scenario_parser_never_panics_on_mutated_files(
        cut in 0.0f64..1.0, pos in 0.0f64..1.0, ch in "[\\[\\]{}\",:0-9.#?a-z -]",
    ) {
        let text = std::fs::read_to_string(DEMO).unwrap();
        // Truncations never panic and are errors (the closing brace is lost).
        let floor = |mut i: usize| { while !text.is_char_boundary(i) { i -= 1; } i };
        let n = floor(((text.len() - 2) as f64 * cut) as usize);
        prop_assert!(Scenario::from_json(&text[..n]).is_err());
        // Single-character substitutions never panic.
        let i = floor(((text.len() - 1) as f64 * pos) as usize);
        let end = i + text[i..].chars().next().map_or(1, char::len_utf8);
        let mut mutated = text.clone();
        mutated.replace_range(i..end, &ch);
        let _ = Scenario::from_json(&mutated);
    }
}

#[test]
fn schema_doc_examples_are_valid_scenarios() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
    let doc = std::fs::read_to_string(format!("{root}/docs/scenario-schema.md")).unwrap();
    let blocks: Vec<&str> = doc
        .split("```json\n")
        .skip(1)
        .map(|b| b.split("```").next().unwrap())
        .collect();
    assert_eq!(
        blocks.len(),
        5,
        "smallest, by reference, full example, simulated episode, arm episode"
    );
    // The arm example is an arm scenario, not a grid one.
    let (grid_blocks, arm_block) = blocks.split_at(4);
    planlab_core::scenario::ArmScenario::from_json(arm_block[0])
        .unwrap_or_else(|e| panic!("{e}\n{}", arm_block[0]));
    for block in grid_blocks {
        let s = Scenario::from_json(block).unwrap_or_else(|e| panic!("{e}\n{block}"));
        // File references resolve relative to assets/scenarios/.
        let g = s
            .load_grid(&mut |p| {
                std::fs::read(format!("{root}/assets/scenarios/{p}")).map_err(|e| e.to_string())
            })
            .unwrap_or_else(|e| panic!("{e}\n{block}"));
        assert!(g.width() > 0);
    }
    let demo = std::fs::read_to_string(DEMO).unwrap();
    assert_eq!(blocks[2], demo, "the doc shows the asset verbatim");
}
