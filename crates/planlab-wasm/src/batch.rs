//! A Moving AI scenario solved in one call: the unit both the browser (timed
//! with `performance.now()` around [`Batch::solve_all`]) and the native side
//! (`planlab bench scen`, timed with `Instant`)
//! measure, so the wasm-vs-native ratio compares the same Rust code. It
//! lives in the core ([`planlab_core::bench::ScenBatch`]) so the CLI runs
//! exactly the same code.

pub use planlab_core::bench::{ScenBatch as Batch, ScenBatchError as BatchError};

#[cfg(test)]
mod tests {
    use super::*;
    use planlab_core::global::plan::Algorithm;
    use planlab_core::global::plan::GridPlanOptions;
    use planlab_core::map::io::movingai;

    const ARENA: &str = include_str!("../../../assets/maps/arena.map");
    /// Three rows of the Moving AI `arena.map.scen` (buckets 3, 9, 15).
    const SCEN: &str = "version 1\n3\tmaps/dao/arena.map\t49\t49\t1\t10\t11\t19\t13.7279\n9\tmaps/dao/arena.map\t49\t49\t1\t10\t15\t43\t38.799\n15\tmaps/dao/arena.map\t49\t49\t1\t3\t41\t47\t60.5685\n";

    #[test]
    fn solves_every_row_to_the_scenario_optimum() {
        let map = movingai::parse_map(ARENA).unwrap();
        for algorithm in [
            Algorithm::AStar,
            Algorithm::Dijkstra,
            Algorithm::Jps,
            Algorithm::JpsPlus,
        ] {
            let options = GridPlanOptions {
                algorithm,
                ..Default::default()
            };
            let batch = Batch::new(&map, SCEN, &options).unwrap();
            assert_eq!(batch.len(), 3);
            let total = batch.solve_all().unwrap();
            // .scen optima are printed to 4 decimals.
            assert!(
                (total - batch.optimal_sum()).abs() < 3e-4,
                "{algorithm:?}: {total} vs {}",
                batch.optimal_sum()
            );
        }
    }

    #[test]
    fn a_blocked_query_names_its_row() {
        let map = movingai::parse_map(ARENA).unwrap();
        // Row 2 starts on the border wall (0, 0).
        let scen = "version 1\n0\tarena.map\t49\t49\t1\t11\t1\t12\t1\n0\tarena.map\t49\t49\t0\t0\t1\t12\t1\n";
        let err = match Batch::new(&map, scen, &GridPlanOptions::default()) {
            Ok(batch) => batch.solve_all().unwrap_err().to_string(),
            Err(e) => e.to_string(),
        };
        assert!(err.contains('2') && err.contains("(0, 0)"), "{err}");
    }
}
