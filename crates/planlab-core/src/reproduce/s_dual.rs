//! Experiments of \[S\] Ge & Li 2022 (safe A* + dual-velocity DWA): ids
//! `S-fig6`, `S-tab1`, `S-fig12`.

use super::Experiment;

/// The \[S\] experiments.
pub fn experiments() -> Vec<Experiment> {
    Vec::new()
}
