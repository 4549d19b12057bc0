//! The native side of the sampling trace check: the core's own runs give
//! the hashes in `common/sampling_trace.rs`, which the wasm test
//! (`sampling.rs`, in the browser) expects from `SamplingRun`.
#![cfg(not(target_arch = "wasm32"))]

#[path = "common/sampling_trace.rs"]
mod trace;

use planlab_core::map::OccupancyGrid;
use planlab_core::sampling::{cell_centre, plan_on_grid, SamplingAlgorithm, SamplingOptions};

#[test]
fn native_core_runs_give_the_shared_trace_hashes() {
    let grid = OccupancyGrid::from_ascii(trace::MAP).unwrap();
    for (name, iterations, expected) in trace::RUNS {
        let options = SamplingOptions {
            algorithm: SamplingAlgorithm::from_name(name).unwrap(),
            seed: trace::SEED,
            record_events: true,
            ..SamplingOptions::default()
        };
        let p = plan_on_grid(
            &grid,
            0.4,
            false,
            cell_centre(trace::START.0, trace::START.1),
            cell_centre(trace::GOAL.0, trace::GOAL.1),
            &options,
            iterations,
        )
        .unwrap();
        assert!(p.best_cost().is_some(), "{name} finds a path");
        let (mut kinds, mut ids, mut nums) = (Vec::new(), Vec::new(), Vec::new());
        for e in p.events() {
            let (k, i, n) = e.flat();
            kinds.push(k);
            ids.extend_from_slice(&i);
            nums.extend_from_slice(&n);
        }
        let path: Vec<f64> = p.path().iter().flat_map(|q| [q[0], q[1]]).collect();
        let h = trace::trace_hash(&kinds, &ids, &nums, &path);
        assert_eq!(
            h, expected,
            "{name}: the core's trace hash is {h:#018x}, common/sampling_trace.rs says {expected:#018x}"
        );
    }
}
