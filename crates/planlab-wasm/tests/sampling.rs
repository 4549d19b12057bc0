//! The sampling planners across the wasm boundary (`wasm-pack test
//! --headless --chrome`): the same seed gives the same events and path as
//! the native core (the hashes `sampling_native.rs` checks against the
//! core), stepped in chunks; bad input is a one-line `JsError`.
#![cfg(target_arch = "wasm32")]

#[path = "common/sampling_trace.rs"]
mod trace;

use planlab_wasm::{sampling_algorithms, MapHandle, SamplingRun};
use wasm_bindgen::{JsCast, JsValue};
use wasm_bindgen_test::*;

wasm_bindgen_test_configure!(run_in_browser);

fn message(err: wasm_bindgen::JsError) -> String {
    let v: JsValue = err.into();
    let e: js_sys::Error = v.dyn_into().expect("a JS Error object");
    e.message().into()
}

fn run(map: &MapHandle, name: &str, radius_m: Option<f64>) -> Result<SamplingRun, String> {
    SamplingRun::new(
        map,
        name,
        trace::START.0,
        trace::START.1,
        trace::GOAL.0,
        trace::GOAL.1,
        radius_m,
        trace::SEED as f64,
        false,
    )
    .map_err(message)
}

#[wasm_bindgen_test]
fn chunked_wasm_runs_give_the_native_cores_trace_hashes() {
    let map = MapHandle::from_ascii(trace::MAP).unwrap();
    for (name, iterations, expected) in trace::RUNS {
        let mut r = run(&map, name, None).unwrap();
        let (mut kinds, mut ids, mut nums) = (Vec::new(), Vec::new(), Vec::new());
        // Uneven chunks, events taken between them: as the page steps
        // against a time budget.
        let mut left = iterations as u32;
        let mut chunk = 1;
        while left > 0 {
            let ran = r.step(chunk.min(left));
            let ev = r.take_events();
            assert_eq!(ev.kinds().len(), ev.length() as usize);
            assert_eq!(ev.ids().len(), 3 * ev.length() as usize);
            assert_eq!(ev.nums().len(), 2 * ev.length() as usize);
            kinds.extend(ev.kinds());
            ids.extend(ev.ids());
            nums.extend(ev.nums());
            if ran == 0 {
                break;
            }
            left -= ran;
            chunk = chunk * 3 % 97 + 1;
        }
        let path = r.path(false);
        assert_eq!(
            trace::trace_hash(&kinds, &ids, &nums, &path),
            expected,
            "{name}: the wasm run's events and path differ from the native core's"
        );
        // Every improvement is a solution event, with its path kept.
        let sols = r.solutions();
        let solution_events = kinds.iter().filter(|&&k| k == 7).count();
        assert_eq!(sols.len(), 2 * solution_events);
        assert!(sols
            .chunks(2)
            .collect::<Vec<_>>()
            .windows(2)
            .all(|w| w[1][1] < w[0][1]));
        assert_eq!(r.solution_path(solution_events as u32 - 1), path);
        assert!(r.solution_path(solution_events as u32).is_empty());
        assert!((r.path_cost(false) - sols[sols.len() - 1]).abs() < 1e-9);
        assert!(r.path_cost(true) <= r.path_cost(false) + 1e-9);
    }
}

#[wasm_bindgen_test]
fn bad_sampling_input_is_a_one_line_error() {
    let map = MapHandle::from_ascii(trace::MAP).unwrap();
    let big = run(&map, "rrt-star", Some(6.0)).err().unwrap();
    assert!(big.starts_with("robot radius 6 m:"), "{big}");
    let unknown = run(&map, "rrt-sharp", None).err().unwrap();
    assert!(unknown.contains("unknown sampling planner"), "{unknown}");
    let walled = SamplingRun::new(&map, "rrt", 10, 3, 20, 1, None, 0.0, false)
        .err()
        .map(message)
        .unwrap();
    assert!(
        walled.starts_with("the start (cell 10, 3) is too close"),
        "{walled}"
    );
    let seed = SamplingRun::new(&map, "rrt", 1, 8, 20, 1, None, 1.5, false)
        .err()
        .map(message)
        .unwrap();
    assert!(seed.starts_with("seed 1.5:"), "{seed}");
    for m in [big, unknown, walled, seed] {
        assert!(!m.contains('\n'), "{m}");
    }
}

#[wasm_bindgen_test]
fn sampling_algorithms_lists_every_core_planner_with_its_reference() {
    let v = sampling_algorithms().unwrap();
    let arr: js_sys::Array = v.dyn_into().unwrap();
    assert_eq!(arr.length(), 7);
    let first = arr.get(0);
    let name = js_sys::Reflect::get(&first, &"name".into()).unwrap();
    assert_eq!(name.as_string().as_deref(), Some("rrt"));
    let reference = js_sys::Reflect::get(&first, &"reference".into()).unwrap();
    assert!(reference.as_string().unwrap().contains("LaValle"));
}
