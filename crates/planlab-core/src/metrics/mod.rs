//! Episode metrics (SPEC §4, §7): time, path length, clearance, turning,
//! speed drops, tracking error, wheel-load share.
