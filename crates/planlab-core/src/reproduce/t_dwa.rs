//! Experiments of \[T\] Wu 2022 ch. 3 (improved DWA + A* fusion): ids
//! `T-fig3-2`, `T-fig3-11`, `T-fig3-13a`, `T-fig3-13b`, `T-tab3-2`.

use super::Experiment;

/// The \[T\] experiments.
pub fn experiments() -> Vec<Experiment> {
    Vec::new()
}
