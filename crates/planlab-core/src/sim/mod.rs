//! Fixed-step, seeded, deterministic episodes (SPEC §1, §3): world + robot +
//! local planner → trace and outcome.
