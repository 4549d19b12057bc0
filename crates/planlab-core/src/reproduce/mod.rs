//! The papers' experiments (SPEC §7): presets, runs and the relation each
//! must show, for `planlab reproduce` and the page's gallery.
