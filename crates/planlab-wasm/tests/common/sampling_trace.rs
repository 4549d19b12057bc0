//! What the native and the wasm sampling tests share: the map, the runs,
//! the hash of a run's events and path, and the hashes the native core
//! gives (`sampling_native.rs` checks them against the core, `sampling.rs`
//! against the wasm `SamplingRun`; a hash here that the core does not
//! produce fails the native test).

/// Two rooms joined by a gap, a pillar in the right room (ASCII, 1 m/cell).
pub const MAP: &str = "
......................
......................
..........#...........
..........#.....##....
..........#.....##....
..........#...........
......................
..........#...........
..........#...........
..........#...........
";

/// Start and goal cells.
pub const START: (u32, u32) = (1, 8);
pub const GOAL: (u32, u32) = (20, 1);
/// The seed of every run.
pub const SEED: u64 = 11;

/// (planner, iterations, FNV-1a hash of its events and path) as the native
/// core gives them with the default options, a 0.4-cell disc and [`SEED`].
pub const RUNS: [(&str, u64, u64); 3] = [
    ("rrt-star", 600, 0x6765_c208_6eeb_f032),
    ("rrt-connect", 600, 0x53b9_7045_4266_864b),
    ("bit-star", 600, 0x1019_8712_1463_ede2),
];

/// FNV-1a over the event columns (kind byte, ids and numbers little-endian)
/// and the path's coordinates.
pub fn trace_hash(kinds: &[u8], ids: &[u32], nums: &[f64], path: &[f64]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |bytes: &[u8]| {
        for &b in bytes {
            h ^= u64::from(b);
            h = h.wrapping_mul(0x0100_0000_01b3);
        }
    };
    eat(kinds);
    for i in ids {
        eat(&i.to_le_bytes());
    }
    for x in nums.iter().chain(path) {
        eat(&x.to_bits().to_le_bytes());
    }
    h
}
