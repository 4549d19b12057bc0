//! Prints the LiDAR navigator's decisions step by step (development aid):
//! `cargo run --release -p planlab-core --example lidar_debug -- SCENARIO [PLANNER] [FROM_T] [TO_T]`.
use planlab_core::map::io::scenario::Scenario;
use planlab_core::sim::{Episode, Outcome};

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let text = std::fs::read_to_string(&a[1]).expect("scenario");
    let mut sc = Scenario::from_json(&text).expect("parse");
    if let Some(p) = a.get(2) {
        if let Some(lp) = sc.local_planner.as_mut() {
            lp.name = p.clone();
        }
    }
    let t0: f64 = a.get(3).map_or(0.0, |s| s.parse().unwrap());
    let t1: f64 = a.get(4).map_or(1e9, |s| s.parse().unwrap());
    let grid = sc.inline_grid().unwrap().unwrap();
    let mut ep = Episode::from_scenario(&sc, grid).unwrap();
    ep.set_record_rollouts(true);
    while ep.step() == Outcome::Running {
        let t = ep.time();
        if t < t0 || t > t1 {
            continue;
        }
        let s = ep.state();
        let d = ep.planner_debug();
        let Some(l) = d.lidar.as_ref() else { continue };
        println!(
            "t={t:.1} pose=({:.2},{:.2},{:.2}) v={:.2} kind={:?} target=({:.2},{:.2}) hold={:.1} mode={}",
            s.x, s.y, s.theta, s.v, l.kind, l.target[0], l.target[1], l.hold_remaining, d.mode
        );
        if let Some(b) = l.blocking {
            let op = &l.ops[b];
            println!(
                "   blocking op {b}: {} pts from ({:.2},{:.2}) to ({:.2},{:.2})",
                op.len(),
                op[0][0],
                op[0][1],
                op[op.len() - 1][0],
                op[op.len() - 1][1]
            );
        }
        for c in &l.candidates {
            println!(
                "   cand it{} ({:.2},{:.2}) cost {:.2}",
                c.iteration, c.point[0], c.point[1], c.cost
            );
        }
    }
    println!("{:?} at {:.1}", ep.outcome(), ep.time());
}
