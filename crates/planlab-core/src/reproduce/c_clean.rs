//! Experiments of \[C\] Zhang et al. 2020 (cleaning-robot DWA): ids `C-tab3`,
//! `C-tab5`.

use super::Experiment;

/// The \[C\] experiments.
pub fn experiments() -> Vec<Experiment> {
    Vec::new()
}
