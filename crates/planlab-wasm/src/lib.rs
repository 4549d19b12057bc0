//! wasm-bindgen layer over planlab-core.
