//! A planlab robot episode as an MCAP file, the log format of Foxglove and
//! ROS 2 (`ros2 bag` reads and converts MCAP), written with Foxglove's
//! `mcap` crate.
//!
//! [`record_episode`] runs an episode to its end, as `Episode::run` does
//! (the same steps, so the same trace and trace hash), and logs every
//! control period at its simulated time (log time = t, in nanoseconds from
//! 0; the episode has no wall clock). Messages are JSON with Foxglove's
//! well-known schema names, so Foxglove's 3D panel draws them without any
//! set-up; every message is in the `map` frame (the world frame of the
//! scenario: x right, y up, metres):
//!
//! | topic | schema | when |
//! |---|---|---|
//! | `/map` | `foxglove.Grid` (field `occupancy`, uint8: 0 free, 100 occupied, 255 unknown) | once, t = 0 |
//! | `/robot/pose` | `foxglove.PoseInFrame` | every step |
//! | `/robot/footprint` | `foxglove.SceneUpdate` (a cube of the footprint, or a cylinder for a disc robot) | every step |
//! | `/goal` | `foxglove.PoseInFrame` (the goal the planner steers to this step) | every step |
//! | `/plan/global` | `foxglove.PosesInFrame` | every step the planner has a global path |
//! | `/plan/local` | `foxglove.PosesInFrame` (the rollout it chose) | every step it chose one |
//! | `/scan` | `foxglove.LaserScan` | every step of an episode with a laser (a perception section, or a LiDAR planner) |
//! | `/movers` | `foxglove.SceneUpdate` (a cylinder per mover) | every step of an episode with movers |
//!
//! Chunks are not compressed (the crate is built without zstd/lz4, so it
//! builds for wasm32): compress the file if size matters.

use std::collections::BTreeMap;
use std::io::Cursor;

use base64::Engine as _;
use planlab_core::map::{Cell, OccupancyGrid};
// The core's libm functions: the same bits natively and in wasm, so the
// page's file has the CLI's messages.
use planlab_core::num::{atan2, cos, sin};
use planlab_core::sim::{Episode, Outcome};
use planlab_core::world::Footprint;
use serde_json::{json, Value};

/// The topics written, in the order their channels are declared.
pub const TOPICS: [&str; 8] = [
    "/map",
    "/robot/pose",
    "/robot/footprint",
    "/goal",
    "/plan/global",
    "/plan/local",
    "/scan",
    "/movers",
];

/// Why no MCAP file was made.
#[derive(Debug, Clone, PartialEq)]
pub struct McapError(pub String);

impl std::fmt::Display for McapError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "MCAP: {}", self.0)
    }
}

impl std::error::Error for McapError {}

fn err(e: impl std::fmt::Display) -> McapError {
    McapError(e.to_string())
}

/// The JSON Schema of each Foxglove schema used: the fields planlab fills,
/// written out here from Foxglove's schema reference (names, types and
/// units are Foxglove's).
fn schema(name: &str) -> Value {
    let num = json!({"type": "number"});
    let time = json!({"type": "object", "properties": {"sec": {"type": "integer"}, "nsec": {"type": "integer"}}});
    let vec3 = json!({"type": "object", "properties": {"x": num, "y": num, "z": num}});
    let quat = json!({"type": "object", "properties": {"x": num, "y": num, "z": num, "w": num}});
    let pose = json!({"type": "object", "properties": {"position": vec3, "orientation": quat}});
    let color = json!({"type": "object", "properties": {"r": num, "g": num, "b": num, "a": num}});
    let props = match name {
        "foxglove.PoseInFrame" => {
            json!({"timestamp": time, "frame_id": {"type": "string"}, "pose": pose})
        }
        "foxglove.PosesInFrame" => json!({
            "timestamp": time, "frame_id": {"type": "string"},
            "poses": {"type": "array", "items": pose}
        }),
        "foxglove.LaserScan" => json!({
            "timestamp": time, "frame_id": {"type": "string"}, "pose": pose,
            "start_angle": num, "end_angle": num,
            "ranges": {"type": "array", "items": num},
            "intensities": {"type": "array", "items": num}
        }),
        "foxglove.Grid" => json!({
            "timestamp": time, "frame_id": {"type": "string"}, "pose": pose,
            "column_count": {"type": "integer"},
            "cell_size": {"type": "object", "properties": {"x": num, "y": num}},
            "row_stride": {"type": "integer"}, "cell_stride": {"type": "integer"},
            "fields": {"type": "array", "items": {"type": "object", "properties": {
                "name": {"type": "string"}, "offset": {"type": "integer"}, "type": {"type": "integer"}
            }}},
            "data": {"type": "string", "contentEncoding": "base64"}
        }),
        // SceneUpdate: the entities with the primitives planlab uses.
        _ => json!({
            "deletions": {"type": "array", "items": {"type": "object"}},
            "entities": {"type": "array", "items": {"type": "object", "properties": {
                "timestamp": time, "frame_id": {"type": "string"}, "id": {"type": "string"},
                "lifetime": time, "frame_locked": {"type": "boolean"},
                "cubes": {"type": "array", "items": {"type": "object", "properties": {"pose": pose, "size": vec3, "color": color}}},
                "cylinders": {"type": "array", "items": {"type": "object", "properties": {
                    "pose": pose, "size": vec3, "bottom_scale": num, "top_scale": num, "color": color
                }}}
            }}}
        }),
    };
    json!({"title": name, "type": "object", "properties": props})
}

/// The schema of each topic in [`TOPICS`].
fn topic_schema(topic: &str) -> &'static str {
    match topic {
        "/map" => "foxglove.Grid",
        "/robot/pose" | "/goal" => "foxglove.PoseInFrame",
        "/plan/global" | "/plan/local" => "foxglove.PosesInFrame",
        "/scan" => "foxglove.LaserScan",
        _ => "foxglove.SceneUpdate",
    }
}

fn stamp(t: f64) -> Value {
    let ns = nanos(t);
    json!({"sec": ns / 1_000_000_000, "nsec": ns % 1_000_000_000})
}

/// Simulated time in nanoseconds (times are ≥ 0 and bounded by the
/// scenario's limits).
fn nanos(t: f64) -> u64 {
    (t.max(0.0) * 1e9).round() as u64
}

fn pose(x: f64, y: f64, yaw: f64) -> Value {
    json!({
        "position": {"x": x, "y": y, "z": 0.0},
        "orientation": {"x": 0.0, "y": 0.0, "z": sin(yaw / 2.0), "w": cos(yaw / 2.0)}
    })
}

fn poses(t: f64, pts: &[[f64; 2]]) -> Value {
    // Each pose faces the next point (the last keeps its predecessor's).
    let mut yaw = 0.0;
    let list: Vec<Value> = pts
        .iter()
        .enumerate()
        .map(|(i, p)| {
            if let Some(q) = pts.get(i + 1) {
                yaw = atan2(q[1] - p[1], q[0] - p[0]);
            }
            pose(p[0], p[1], yaw)
        })
        .collect();
    json!({"timestamp": stamp(t), "frame_id": "map", "poses": list})
}

/// The map as a `foxglove.Grid`: row 0 of the message is the bottom row
/// (the grid's origin is its bottom-left corner, as in ROS).
fn grid_message(grid: &OccupancyGrid) -> Value {
    let (w, h) = (grid.width(), grid.height());
    let mut data = Vec::with_capacity(w * h);
    for r in (0..h).rev() {
        for &c in &grid.cells()[r * w..(r + 1) * w] {
            data.push(match c {
                Cell::Free => 0u8,
                Cell::Occupied => 100,
                Cell::Unknown => 255,
            });
        }
    }
    let o = grid.origin();
    json!({
        "timestamp": stamp(0.0),
        "frame_id": "map",
        "pose": pose(o.x, o.y, o.yaw),
        "column_count": w,
        "cell_size": {"x": grid.resolution(), "y": grid.resolution()},
        "row_stride": w,
        "cell_stride": 1,
        // type 1: UINT8 in Foxglove's NumericType.
        "fields": [{"name": "occupancy", "offset": 0, "type": 1}],
        "data": base64::engine::general_purpose::STANDARD.encode(&data),
    })
}

fn cylinder(x: f64, y: f64, radius: f64, height: f64, rgba: [f64; 4]) -> Value {
    json!({
        "pose": pose(x, y, 0.0),
        "size": {"x": 2.0 * radius, "y": 2.0 * radius, "z": height},
        "bottom_scale": 1.0, "top_scale": 1.0,
        "color": {"r": rgba[0], "g": rgba[1], "b": rgba[2], "a": rgba[3]}
    })
}

fn entity(t: f64, id: String, cubes: Vec<Value>, cylinders: Vec<Value>) -> Value {
    json!({
        "timestamp": stamp(t), "frame_id": "map", "id": id,
        "lifetime": {"sec": 0, "nsec": 0}, "frame_locked": false, "metadata": [],
        "arrows": [], "cubes": cubes, "spheres": [], "cylinders": cylinders,
        "lines": [], "triangles": [], "texts": [], "models": []
    })
}

/// The MCAP writer with one channel per topic.
struct Log<'a> {
    w: mcap::Writer<&'a mut Cursor<Vec<u8>>>,
    channels: BTreeMap<&'static str, u16>,
    seq: u32,
}

impl Log<'_> {
    fn put(&mut self, topic: &str, t: f64, msg: &Value) -> Result<(), McapError> {
        let id = self.channels[topic];
        self.seq += 1;
        let header = mcap::records::MessageHeader {
            channel_id: id,
            sequence: self.seq,
            log_time: nanos(t),
            publish_time: nanos(t),
        };
        let bytes = serde_json::to_vec(msg).map_err(err)?;
        self.w.write_to_known_channel(&header, &bytes).map_err(err)
    }

    /// Everything about the episode's current step.
    fn step(&mut self, ep: &Episode) -> Result<(), McapError> {
        let t = ep.time();
        let s = ep.state();
        let at = json!({"timestamp": stamp(t), "frame_id": "map", "pose": pose(s.x, s.y, s.theta)});
        self.put("/robot/pose", t, &at)?;
        let body = [0.2, 0.45, 0.9, 0.8];
        let (cubes, cyls) = match ep.robot().footprint {
            Footprint::Circle { radius } => (vec![], vec![cylinder(s.x, s.y, radius, 0.2, body)]),
            Footprint::Rectangle { length, width } => (
                vec![json!({
                    "pose": pose(s.x, s.y, s.theta),
                    "size": {"x": length, "y": width, "z": 0.2},
                    "color": {"r": body[0], "g": body[1], "b": body[2], "a": body[3]}
                })],
                vec![],
            ),
        };
        let robot = json!({"deletions": [], "entities": [entity(t, "robot".into(), cubes, cyls)]});
        self.put("/robot/footprint", t, &robot)?;
        let dbg = ep.planner_debug();
        let g = if dbg.current_goal.iter().all(|v| v.is_finite()) && ep.steps() > 0 {
            dbg.current_goal
        } else {
            ep.goal()
        };
        let goal = json!({"timestamp": stamp(t), "frame_id": "map", "pose": pose(g[0], g[1], 0.0)});
        self.put("/goal", t, &goal)?;
        if !dbg.global_path.is_empty() {
            self.put("/plan/global", t, &poses(t, &dbg.global_path))?;
        }
        if let Some(r) = dbg.chosen.and_then(|i| dbg.rollouts.get(i)) {
            if !r.points.is_empty() {
                self.put("/plan/local", t, &poses(t, &r.points))?;
            }
        }
        if let Some(scan) = laser(ep) {
            self.put("/scan", t, &scan)?;
        }
        let movers = ep.movers_now();
        if !movers.is_empty() {
            let entities: Vec<Value> = movers
                .iter()
                .map(|(id, radius, m)| {
                    let c = cylinder(m.pos[0], m.pos[1], *radius, 1.7, [0.95, 0.55, 0.1, 0.8]);
                    entity(t, format!("mover-{id}"), vec![], vec![c])
                })
                .collect();
            self.put(
                "/movers",
                t,
                &json!({"deletions": [], "entities": entities}),
            )?;
        }
        Ok(())
    }
}

/// The laser scan of this step, when the episode has one: the perception
/// section's (BARN), else the LiDAR navigator's. Out-of-range beams are
/// written as the range limit plus one metre's worth of "nothing" — JSON
/// has no infinity — i.e. as `max_range + 1`, which Foxglove drops as
/// beyond the sensor's range.
fn laser(ep: &Episode) -> Option<Value> {
    let finite = |r: f64, max: f64| if r.is_finite() { r } else { max + 1.0 };
    if let Some(p) = ep.perception() {
        let s = p.scan();
        if s.ranges.is_empty() {
            return None;
        }
        let n = s.ranges.len();
        return Some(json!({
            "timestamp": stamp(ep.time()), "frame_id": "map",
            "pose": pose(s.pose[0], s.pose[1], s.pose[2]),
            "start_angle": s.angle_min,
            "end_angle": s.angle_min + s.angle_increment * (n - 1) as f64,
            "ranges": s.ranges.iter().map(|&r| finite(r, s.max_range)).collect::<Vec<_>>(),
            "intensities": []
        }));
    }
    let l = ep.planner_debug().lidar.as_ref()?;
    let n = l.ranges.len();
    if n == 0 {
        return None;
    }
    // The navigator's beams cover the full turn, beam 0 straight ahead.
    let step = std::f64::consts::TAU / n as f64;
    Some(json!({
        "timestamp": stamp(ep.time()), "frame_id": "map",
        "pose": pose(l.pose[0], l.pose[1], l.pose[2]),
        "start_angle": 0.0,
        "end_angle": step * (n - 1) as f64,
        "ranges": l.ranges.iter().zip(&l.returns).map(|(&r, &hit)| if hit { r } else { l.max_range + 1.0 }).collect::<Vec<_>>(),
        "intensities": []
    }))
}

/// Runs `ep` to its end as `Episode::run` does and returns the run as an
/// MCAP file (module doc) and the outcome. The episode records its
/// rollouts meanwhile (for `/plan/local`); that changes nothing in its
/// trace.
pub fn record_episode(ep: &mut Episode) -> Result<(Vec<u8>, Outcome), McapError> {
    ep.set_record_rollouts(true);
    let mut out = Cursor::new(Vec::new());
    {
        let opts = mcap::WriteOptions::new()
            .compression(None)
            .profile("")
            .library("planlab");
        let mut w = opts.create(&mut out).map_err(err)?;
        let mut channels = BTreeMap::new();
        let mut schemas: BTreeMap<&str, u16> = BTreeMap::new();
        for topic in TOPICS {
            let name = topic_schema(topic);
            let sid = match schemas.get(name) {
                Some(&id) => id,
                None => {
                    let data = serde_json::to_vec(&schema(name)).map_err(err)?;
                    let id = w.add_schema(name, "jsonschema", &data).map_err(err)?;
                    schemas.insert(name, id);
                    id
                }
            };
            let cid = w
                .add_channel(sid, topic, "json", &BTreeMap::new())
                .map_err(err)?;
            channels.insert(topic, cid);
        }
        let mut log = Log {
            w,
            channels,
            seq: 0,
        };
        log.put("/map", 0.0, &grid_message(ep.map().grid()))?;
        log.step(ep)?;
        while ep.outcome() == Outcome::Running {
            ep.step();
            log.step(ep)?;
        }
        log.w.finish().map_err(err)?;
    }
    Ok((out.into_inner(), ep.outcome()))
}
