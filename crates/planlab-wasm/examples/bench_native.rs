//! Native timing of [`planlab_wasm::batch::Batch`], the counterpart of the
//! browser figure in `scripts/bench-wasm.mjs`.
//!
//! `cargo run --release -p planlab-wasm --example bench_native -- MAP SCEN [REPS] [ALGORITHM] [INNER]`
//! prints one JSON line: rows, total cost, optimal sum and per-rep times;
//! each rep solves the whole scenario INNER times (default 1), so small maps
//! give timed blocks long enough to measure.

use planlab_core::global::plan::GridPlanOptions;
use planlab_core::map::io::movingai;
use planlab_wasm::batch::Batch;
use std::time::Instant;

fn main() {
    if let Err(e) = run() {
        eprintln!("bench_native: {e}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (map_path, scen_path) = match (args.first(), args.get(1)) {
        (Some(m), Some(s)) => (m, s),
        _ => return Err("usage: bench_native MAP SCEN [REPS] [ALGORITHM] [INNER]".into()),
    };
    let reps: usize = args.get(2).map_or(Ok(5), |s| s.parse())?;
    let inner: usize = args.get(4).map_or(Ok(1), |s| s.parse())?;
    let mut options = GridPlanOptions::default();
    if let Some(a) = args.get(3) {
        options.algorithm = a.parse()?;
    }
    let map = movingai::parse_map(&std::fs::read_to_string(map_path)?)?;
    let batch = Batch::new(&map, &std::fs::read_to_string(scen_path)?, &options)?;
    // One untimed pass warms caches, as the browser side does.
    let total = batch.solve_all()?;
    let mut times_ms = Vec::with_capacity(reps);
    for _ in 0..reps {
        let t0 = Instant::now();
        let mut t = 0.0;
        for _ in 0..inner.max(1) {
            t = batch.solve_all()?;
        }
        times_ms.push(t0.elapsed().as_secs_f64() * 1e3);
        if (t - total).abs() > 1e-9 {
            return Err("non-deterministic total cost".into());
        }
    }
    let line = serde_json::json!({
        "rows": batch.len(),
        "inner": inner.max(1),
        "total_cost": total,
        "optimal_sum": batch.optimal_sum(),
        "times_ms": times_ms,
    });
    println!("{line}");
    Ok(())
}
