//! The critic catalogue: critics by name, each built from its JSON config
//! (its `scale` and own settings, as Nav2's `<critic>.<param>`
//! parameters), so a planner's config can list critics by name (DWB's
//! `critics:`). Adding a critic: its file, and one line in
//! [`CriticCatalogue::standard`] — or, from outside the crate,
//! [`CriticCatalogue::register`].

use std::sync::Arc;

use super::critic::{Clearance, Heading, Twirling, Velocity};
use super::CriticSlot;
use crate::local::ros::critics::{
    BaseObstacle, GoalAlign, GoalDist, GridDistance, HeadingLookahead, InPlaceOscillation,
    Occupancy, Oscillation, OscillationSettings, PathAlign, PathDist, RotateToGoal,
    RotateToGoalSettings, Target,
};
use crate::local::ros::{CostmapParams, Layers};
use crate::local::LocalError;
use crate::params::{parse_config, Params};
use crate::world::{RobotSpec, StaticMap};

/// What a critic may be built from: the robot, the static map and the
/// costmap's inflation settings (what ROS hands a critic plugin).
#[derive(Debug, Clone, Copy)]
pub struct CriticEnv<'a> {
    /// The robot.
    pub robot: &'a RobotSpec,
    /// The static map.
    pub map: &'a StaticMap,
    /// The costmap's inflation layer.
    pub costmap: CostmapParams,
}

impl CriticEnv<'_> {
    /// The costmap layers of this map and robot.
    pub fn layers(&self) -> Result<Layers, LocalError> {
        Layers::new(self.map, self.robot, &self.costmap)
    }
}

/// Builds a critic with its scale from its config (`null`: the defaults);
/// errors name `prefix.field`.
pub type CriticCtor = Arc<
    dyn Fn(&CriticEnv<'_>, &str, &serde_json::Value) -> Result<CriticSlot, LocalError>
        + Send
        + Sync,
>;

/// Critic names and their constructors, in registration order.
#[derive(Clone, Default)]
pub struct CriticCatalogue {
    entries: Vec<(String, CriticCtor)>,
}

impl std::fmt::Debug for CriticCatalogue {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list().entries(self.names()).finish()
    }
}

/// The config of critic `name` read as `P` with its bounds checked.
pub fn critic_config<P: Params>(prefix: &str, value: &serde_json::Value) -> Result<P, LocalError> {
    let p: P = parse_config(prefix, value)?;
    p.check_bounds(prefix)?;
    Ok(p)
}

macro_rules! critic_params {
    ($(#[$a:meta])* $name:ident { scale = $scale:expr $(; $f:ident: $t:ty = $d:expr, $u:literal [$($b:tt)*] $doc:literal)* }) => {
        crate::params::params! {
            $(#[$a])*
            #[derive(Debug, Clone, Copy, PartialEq)]
            pub struct $name {
                pub scale: f64 = $scale, "1" [>= 0.0] label "weight" "weight of the critic's cost";
                $(pub $f: $t = $d, $u [$($b)*] $doc;)*
            }
        }
    };
}

critic_params!(
    /// A critic with only a scale (Nav2's default scale 1).
    ScaleOnly { scale = 1.0 }
);
critic_params!(
    /// \[T\] eq 3-3's clearance critic.
    DistParams { scale = 0.2; cap: f64 = 1.0, "m" [> 0.0] "clearance saturates here" }
);
critic_params!(
    /// BaseObstacle (scale: nav2_params.yaml's 0.02).
    BaseObstacleParams { scale = 0.02; sum_scores: bool = false, "bool" [] "sum the costs of every pose (else the last pose's)" }
);
critic_params!(
    /// PathDist / PathAlign (scale: nav2_params.yaml's 32).
    PathParams { scale = 32.0; forward_point_distance: f64 = 0.325, "m" [>= 0.0, <= 100.0] "PathAlign's look-ahead point (PathDist ignores it)" }
);
critic_params!(
    /// GoalDist / GoalAlign (scale: nav2_params.yaml's 24).
    GoalParams { scale = 24.0; forward_point_distance: f64 = 0.325, "m" [>= 0.0, <= 100.0] "GoalAlign's look-ahead point (GoalDist ignores it)" }
);
critic_params!(
    /// RotateToGoal (scale: nav2_params.yaml's 32).
    RotateToGoalParams { scale = 32.0;
        xy_goal_tolerance: f64 = 0.2, "m" [>= 0.0]
            "the critic acts within this distance of the goal (Nav2 shares it with its goal checker: planlab's default goal tolerance 0.2, Nav2's 0.25)";
        trans_stopped_velocity: f64 = 0.25, "m/s" [>= 0.0] "below this speed the robot counts as stopped";
        slowing_factor: f64 = 5.0, "s²/m²" [>= 0.0] "weight of the squared speed while slowing";
        lookahead_time: f64 = -1.0, "s" [>= -1.0, <= 100.0] "time the heading is read at (negative: the last pose)";
        path_length_tolerance: f64 = 1.0, "m" [>= 0.0] "the remaining plan must be at most this long" }
);
critic_params!(
    /// Oscillation (its score is 0 or illegal, so the scale does nothing).
    OscillationParams { scale = 1.0;
        oscillation_reset_dist: f64 = 0.05, "m" [>= -1.0] "moving this far clears the flags (negative: off)";
        oscillation_reset_angle: f64 = 0.2, "rad" [>= -1.0] "turning this far clears the flags (negative: off)";
        x_only_threshold: f64 = 0.05, "m/s" [>= -1.0] "turn and strafe flags only at |v| up to this (negative: always)" }
);
critic_params!(
    /// base_local_planner's path distance (pdist_scale 0.6).
    MbPathParams { scale = 0.6 }
);
critic_params!(
    /// base_local_planner's goal distance (gdist_scale 0.8).
    MbGoalParams { scale = 0.8 }
);
critic_params!(
    /// base_local_planner's occupancy cost (occdist_scale 0.01).
    MbOccParams { scale = 0.01 }
);
critic_params!(
    /// base_local_planner's in-place rotation choice (a tie-break scale).
    MbHeadingParams { scale = 1e-9; heading_lookahead: f64 = 0.325, "m" [>= 0.0, <= 100.0] "how far ahead of a rotation's end pose the goal distance is read" }
);
critic_params!(
    /// base_local_planner's in-place oscillation flags.
    MbOscillationParams { scale = 1.0; oscillation_reset_dist: f64 = 0.05, "m" [>= 0.0] "moving this far clears the flags" }
);

/// A constructor from a closure over the config type `P`.
fn ctor<P: Params + 'static>(
    build: impl Fn(&CriticEnv<'_>, &P) -> Result<Box<dyn super::Critic>, LocalError>
        + Send
        + Sync
        + 'static,
    scale: impl Fn(&P) -> f64 + Send + Sync + 'static,
) -> CriticCtor {
    Arc::new(move |env, prefix, value| {
        let p: P = critic_config(prefix, value)?;
        Ok(CriticSlot {
            critic: build(env, &p)?,
            weight: scale(&p),
        })
    })
}

impl CriticCatalogue {
    /// An empty catalogue.
    pub fn new() -> Self {
        Self::default()
    }

    /// The built-in critics: the DWA papers', Nav2 DWB's and
    /// base_local_planner's (move_base).
    pub fn standard() -> Self {
        let mut c = Self::new();
        let radius = |env: &CriticEnv<'_>| env.robot.footprint.circumscribed_radius();
        c.register(
            "heading",
            ctor(|_, _| Ok(Box::new(Heading)), |p: &ScaleOnly| p.scale),
        );
        c.register(
            "dist",
            ctor(
                |_, p: &DistParams| Ok(Box::new(Clearance { cap: p.cap })),
                |p| p.scale,
            ),
        );
        c.register(
            "velocity",
            ctor(|_, _| Ok(Box::new(Velocity)), |p: &ScaleOnly| p.scale),
        );
        c.register(
            "Twirling",
            ctor(
                |_, _| Ok(Box::new(Twirling::named("Twirling"))),
                |p: &ScaleOnly| p.scale,
            ),
        );
        c.register(
            "BaseObstacle",
            ctor(
                |e, p: &BaseObstacleParams| {
                    Ok(Box::new(BaseObstacle::new(e.layers()?, p.sum_scores)))
                },
                |p| p.scale,
            ),
        );
        c.register(
            "PathDist",
            ctor(
                |_, _: &PathParams| Ok(Box::new(PathDist::default())),
                |p| p.scale,
            ),
        );
        c.register(
            "GoalDist",
            ctor(
                |_, _: &GoalParams| Ok(Box::new(GoalDist::default())),
                |p| p.scale,
            ),
        );
        c.register(
            "PathAlign",
            ctor(
                |_, p: &PathParams| Ok(Box::new(PathAlign::new(p.forward_point_distance))),
                |p| p.scale,
            ),
        );
        c.register(
            "GoalAlign",
            ctor(
                |_, p: &GoalParams| Ok(Box::new(GoalAlign::new(p.forward_point_distance))),
                |p| p.scale,
            ),
        );
        c.register(
            "RotateToGoal",
            ctor(
                |_, p: &RotateToGoalParams| {
                    Ok(Box::new(RotateToGoal::new(RotateToGoalSettings {
                        xy_goal_tolerance: p.xy_goal_tolerance,
                        trans_stopped_velocity: p.trans_stopped_velocity,
                        slowing_factor: p.slowing_factor,
                        lookahead_time: p.lookahead_time,
                        path_length_tolerance: p.path_length_tolerance,
                    })))
                },
                |p| p.scale,
            ),
        );
        c.register(
            "Oscillation",
            ctor(
                |_, p: &OscillationParams| {
                    Ok(Box::new(Oscillation::new(OscillationSettings {
                        oscillation_reset_dist: p.oscillation_reset_dist,
                        oscillation_reset_angle: p.oscillation_reset_angle,
                        x_only_threshold: p.x_only_threshold,
                    })))
                },
                |p| p.scale,
            ),
        );
        c.register(
            "move_base.path_dist",
            ctor(
                move |e, _: &MbPathParams| {
                    Ok(Box::new(GridDistance::new(
                        e.layers()?,
                        Target::Path,
                        radius(e),
                    )))
                },
                |p| p.scale,
            ),
        );
        c.register(
            "move_base.goal_dist",
            ctor(
                move |e, _: &MbGoalParams| {
                    Ok(Box::new(GridDistance::new(
                        e.layers()?,
                        Target::Goal,
                        radius(e),
                    )))
                },
                |p| p.scale,
            ),
        );
        c.register(
            "move_base.occ_cost",
            ctor(
                |e, _: &MbOccParams| Ok(Box::new(Occupancy::new(e.layers()?, e.robot.footprint))),
                |p| p.scale,
            ),
        );
        c.register(
            "move_base.heading_lookahead",
            ctor(
                move |e, p: &MbHeadingParams| {
                    Ok(Box::new(HeadingLookahead::new(
                        e.layers()?,
                        p.heading_lookahead,
                        radius(e),
                    )))
                },
                |p| p.scale,
            ),
        );
        c.register(
            "move_base.oscillation",
            ctor(
                |_, p: &MbOscillationParams| {
                    Ok(Box::new(InPlaceOscillation::new(p.oscillation_reset_dist)))
                },
                |p| p.scale,
            ),
        );
        c
    }

    /// Adds (or replaces) the critic `name`.
    pub fn register(&mut self, name: impl Into<String>, ctor: CriticCtor) -> &mut Self {
        let name = name.into();
        match self.entries.iter_mut().find(|(n, _)| *n == name) {
            Some(e) => e.1 = ctor,
            None => self.entries.push((name, ctor)),
        }
        self
    }

    /// The registered names, in order.
    pub fn names(&self) -> Vec<&str> {
        self.entries.iter().map(|(n, _)| n.as_str()).collect()
    }

    /// Builds critic `name` from `config` (errors name `prefix.name.field`;
    /// an unknown name lists the known ones).
    pub fn build(
        &self,
        name: &str,
        env: &CriticEnv<'_>,
        prefix: &str,
        config: &serde_json::Value,
    ) -> Result<CriticSlot, LocalError> {
        let at = format!("{prefix}.{name}");
        match self.entries.iter().find(|(n, _)| n == name) {
            Some((_, ctor)) => ctor(env, &at, config),
            None => Err(LocalError::InvalidParameter(format!(
                "{prefix}: unknown critic `{}` (known: {})",
                crate::text::one_line(name),
                self.names().join(", ")
            ))),
        }
    }
}
