//! The grid page's whole-map tools: an empty map to draw on, clearing
//! every wall at once, the seeded generators (maze, rooms, random fill;
//! the core's `map::generate`, so a setting and seed give the map
//! `planlab generate` writes) and the content hash that compares them.
//! Comes with the `grid-search` feature (the grid page's module).

use planlab_core::map::generate::{generate, GenerateConfig};
use planlab_core::map::{Cell, OccupancyGrid};
use wasm_bindgen::prelude::*;

use crate::MapHandle;

#[wasm_bindgen]
impl MapHandle {
    /// An all-free map of `width` × `height` cells, 1 m per cell.
    pub fn empty(width: u32, height: u32) -> Result<MapHandle, JsError> {
        Ok(MapHandle {
            grid: OccupancyGrid::new(width as usize, height as usize)?,
        })
    }

    /// Frees every occupied cell (unknown cells stay unknown); returns how
    /// many changed.
    #[wasm_bindgen(js_name = clearWalls)]
    pub fn clear_walls(&mut self) -> Result<u32, JsError> {
        let (w, h) = (self.grid.width(), self.grid.height());
        let mut changed = 0;
        for row in 0..h {
            for col in 0..w {
                if self.grid.get(col, row) == Some(Cell::Occupied) {
                    self.grid.set(col, row, Cell::Free)?;
                    changed += 1;
                }
            }
        }
        Ok(changed)
    }

    /// The map's content hash (u64 as a decimal string): the `grid hash`
    /// `planlab generate` prints.
    #[wasm_bindgen(js_name = contentHash)]
    pub fn content_hash(&self) -> String {
        self.grid.content_hash().to_string()
    }
}

/// A generated map with the start and goal the generator chose.
#[wasm_bindgen]
#[derive(Clone, Debug)]
pub struct GeneratedGrid {
    map: MapHandle,
    start: [u32; 2],
    goal: [u32; 2],
}

#[wasm_bindgen]
impl GeneratedGrid {
    /// The map (a copy each call).
    pub fn map(&self) -> MapHandle {
        self.map.clone()
    }

    /// Start cell `[col, row]`.
    pub fn start(&self) -> Vec<u32> {
        self.start.to_vec()
    }

    /// Goal cell `[col, row]`.
    pub fn goal(&self) -> Vec<u32> {
        self.goal.to_vec()
    }
}

/// Generates the map `settings` describe (the core's `GenerateConfig` as
/// JSON: `kind`, `width_m`, `height_m`, `resolution`, `seed`,
/// `corridor_m`, `density`, …; missing fields take the CLI's defaults).
#[wasm_bindgen(js_name = generateGrid)]
pub fn generate_grid(settings: &str) -> Result<GeneratedGrid, JsError> {
    let config: GenerateConfig = serde_json::from_str(settings)
        .map_err(|e| JsError::new(&format!("invalid generator settings: {e}")))?;
    let g = generate(&config)?;
    let cell = |(c, r): (usize, usize)| [c as u32, r as u32];
    Ok(GeneratedGrid {
        map: MapHandle { grid: g.grid },
        start: cell(g.start_cell),
        goal: cell(g.goal_cell),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clear_walls_frees_occupied_cells_and_keeps_unknown_ones() {
        let mut m = MapHandle::from_ascii("..#\n#?#\n...").unwrap();
        assert_eq!(m.clear_walls().unwrap(), 3);
        assert_eq!(m.grid().counts(), (8, 0, 1));
        assert_eq!(m.clear_walls().unwrap(), 0, "nothing left to clear");
    }

    #[test]
    fn an_empty_map_is_all_free_at_one_metre_per_cell() {
        let m = MapHandle::empty(30, 18).unwrap();
        assert_eq!((m.width(), m.height(), m.resolution()), (30, 18, 1.0));
        assert_eq!(m.grid().counts(), (30 * 18, 0, 0));
    }

    #[test]
    fn a_generated_grid_is_the_cores_map_with_its_endpoints() {
        let settings = r#"{"kind":"maze","seed":7,"resolution":0.2,"corridor_m":0.6}"#;
        let g = generate_grid(settings).unwrap();
        let core = generate(&serde_json::from_str(settings).unwrap()).unwrap();
        assert_eq!(g.map().content_hash(), core.grid.content_hash().to_string());
        let (s, e) = (core.start_cell, core.goal_cell);
        assert_eq!(g.start(), vec![s.0 as u32, s.1 as u32]);
        assert_eq!(g.goal(), vec![e.0 as u32, e.1 as u32]);
    }
}
