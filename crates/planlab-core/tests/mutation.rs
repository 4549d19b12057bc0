//! Stable stand-in for the `cargo fuzz` targets (`fuzz/`), so CI runs them
//! without nightly: every target of `fuzz_targets/mod.rs` is run on its
//! seed corpus and on seeded mutations of it (bit flips, interesting bytes
//! and numbers, deletions, duplications, splices). Deterministic: the RNG
//! is seeded, nothing reads a clock, and a failure names the target, the
//! iteration and the seed file, and writes the input to
//! `target/mutation-failures/` for replay.
//!
//! `PLANLAB_MUTATION_ITERS` sets the mutations per target (default 2000, a
//! few seconds in all); the executions are printed per target.
//! `PLANLAB_WRITE_SEEDS=DIR` also writes each target's seeds to DIR/TARGET
//! (how `scripts/fuzz.sh` seeds cargo fuzz).

mod fuzz_targets;

use fuzz_targets::{seed_files, Target, TARGETS};
use planlab_core::num::Rng;

/// Numbers and tokens that have broken parsers: extremes, signs, special
/// floats, counts at integer limits.
const TOKENS: &[&[u8]] = &[
    b"1e308",
    b"-1e308",
    b"1e9",
    b"0",
    b"-0",
    b"-1",
    b"NaN",
    b"inf",
    b"4294967295",
    b"18446744073709551616",
    b"99999999999",
    b"0.0000001",
    b"\"",
    b"'",
    b"[",
    b"]",
    b"{",
    b"}",
    b":",
    b",",
    b"\n",
    b"\n  ",
    b"#",
    b"- ",
    b"null",
    b"true",
];

const BYTES: &[u8] = b"\0\x01\x7f\x80\xff \t\r\n09.-+eE:#[]{}\"',PG@";

fn mutate(rng: &mut Rng, input: &[u8], other: &[u8]) -> Vec<u8> {
    let mut v = input.to_vec();
    let pick = |rng: &mut Rng, n: usize| (rng.next_u64() % n.max(1) as u64) as usize;
    let rounds = 1 + pick(rng, 4);
    for _ in 0..rounds {
        let at = pick(rng, v.len() + 1);
        match pick(rng, 8) {
            0 if !v.is_empty() => {
                let i = at.min(v.len() - 1);
                v[i] ^= 1 << pick(rng, 8);
            }
            1 if !v.is_empty() => {
                let i = at.min(v.len() - 1);
                v[i] = BYTES[pick(rng, BYTES.len())];
            }
            2 => {
                let t = TOKENS[pick(rng, TOKENS.len())];
                // Replace the number (or word) at `at` when there is one.
                let end = (at..v.len())
                    .find(|&i| !(v[i].is_ascii_alphanumeric() || v[i] == b'.' || v[i] == b'-'))
                    .unwrap_or(v.len());
                v.splice(at..end, t.iter().copied());
            }
            3 if !v.is_empty() => {
                let len = 1 + pick(rng, 64.min(v.len()));
                let end = (at + len).min(v.len());
                v.drain(at.min(end)..end);
            }
            4 if !v.is_empty() => {
                let start = at.min(v.len() - 1);
                let end = (start + 1 + pick(rng, 256)).min(v.len());
                let chunk = v[start..end].to_vec();
                let reps = 1 + pick(rng, 8);
                for _ in 0..reps {
                    v.splice(end..end, chunk.iter().copied());
                }
            }
            5 if !other.is_empty() => {
                let s = pick(rng, other.len());
                let e = (s + 1 + pick(rng, 512)).min(other.len());
                v.splice(at..at, other[s..e].iter().copied());
            }
            6 => v.insert(at, BYTES[pick(rng, BYTES.len())]),
            _ => v.truncate(at),
        }
    }
    v
}

fn iterations() -> usize {
    std::env::var("PLANLAB_MUTATION_ITERS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2000)
}

/// Runs `t.run` on `input`; a panic is reported with the input saved.
fn run_one(t: &Target, input: &[u8], what: &str) {
    let r = std::panic::catch_unwind(|| (t.run)(input));
    if r.is_err() {
        let dir = fuzz_targets::repo_root().join("target/mutation-failures");
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join(format!("{}-{}", t.name, what.replace(['/', ' '], "_")));
        std::fs::write(&file, input).unwrap();
        panic!(
            "{} panicked on {what}; input saved to {}",
            t.name,
            file.display()
        );
    }
}

fn mutate_target(t: &Target) {
    let seeds = seed_files(t);
    assert!(!seeds.is_empty(), "{}: no seeds", t.name);
    for (name, bytes) in &seeds {
        run_one(t, bytes, &format!("seed {name}"));
    }
    // scripts/fuzz.sh seeds cargo fuzz's corpus from the same files.
    if let Ok(dir) = std::env::var("PLANLAB_WRITE_SEEDS") {
        let dir = std::path::Path::new(&dir).join(t.name);
        std::fs::create_dir_all(&dir).unwrap();
        for (i, (_, bytes)) in seeds.iter().enumerate() {
            std::fs::write(dir.join(format!("seed-{i}")), bytes).unwrap();
        }
    }
    // One stream per target, so adding a target leaves the others' inputs.
    let mut rng = Rng::new(
        0x1414
            ^ t.name
                .bytes()
                .fold(0u64, |h, b| h.wrapping_mul(31) ^ u64::from(b)),
    );
    let n = iterations();
    for i in 0..n {
        let (name, input) = &seeds[i % seeds.len()];
        let other = &seeds[(rng.next_u64() % seeds.len() as u64) as usize].1;
        let m = mutate(&mut rng, input, other);
        run_one(t, &m, &format!("iteration {i} from {name}"));
    }
    println!("{}: {} executions", t.name, seeds.len() + n);
}

fn target(name: &str) -> &'static Target {
    TARGETS.iter().find(|t| t.name == name).unwrap()
}

#[test]
fn mutation_movingai_map() {
    mutate_target(target("movingai_map"));
}

#[test]
fn mutation_movingai_scen() {
    mutate_target(target("movingai_scen"));
}

#[test]
fn mutation_ros_yaml() {
    mutate_target(target("ros_yaml"));
}

#[test]
fn mutation_pgm() {
    mutate_target(target("pgm"));
}

#[test]
fn mutation_scenario_json() {
    mutate_target(target("scenario_json"));
}

#[test]
fn mutation_scenario_set() {
    mutate_target(target("scenario_set"));
}

#[test]
fn mutation_scenario_sim() {
    mutate_target(target("scenario_sim"));
}

#[test]
fn mutation_arm_model() {
    mutate_target(target("arm_model"));
}

#[test]
fn mutation_arm_scenario() {
    mutate_target(target("arm_scenario"));
}

#[test]
fn mutation_predictor() {
    mutate_target(target("predictor"));
}

#[test]
fn every_target_has_a_mutation_test() {
    let src = include_str!("mutation.rs");
    for t in TARGETS {
        assert!(
            src.contains(&format!("mutate_target(target(\"{}\"))", t.name)),
            "{} has no test",
            t.name
        );
    }
}
