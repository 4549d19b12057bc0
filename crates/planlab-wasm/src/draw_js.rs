//! The core's draw lists across the JavaScript boundary: `{data, items,
//! cells}` typed arrays ([`draw_arrays`]). `planlab-wasm-arm` compiles this
//! same file (by path), so both modules hand out one shape.

use planlab_core::draw::DrawList;
use wasm_bindgen::prelude::*;

#[wasm_bindgen(typescript_custom_section)]
const DRAW_ARRAYS: &str = r#"
/** A draw list as typed arrays (planlab_core::draw). */
export interface DrawArrays {
  data: Float64Array;
  items: Float64Array;
  cells: Uint8Array;
}
"#;

/// A draw list as `{data, items, cells}` typed arrays.
pub(crate) fn draw_arrays(d: &DrawList) -> Result<js_sys::Object, JsError> {
    let o = js_sys::Object::new();
    let set = |k: &str, v: &JsValue| {
        js_sys::Reflect::set(&o, &JsValue::from_str(k), v)
            .map(|_| ())
            .map_err(|_| JsError::new("cannot build the draw list object"))
    };
    set("data", &js_sys::Float64Array::from(&d.data[..]).into())?;
    set(
        "items",
        &js_sys::Float64Array::from(&d.items_flat()[..]).into(),
    )?;
    set("cells", &js_sys::Uint8Array::from(&d.cells[..]).into())?;
    Ok(o)
}
