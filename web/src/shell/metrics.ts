// The metrics of a run as `SimHandle.metricsJson()` gives them: the robot
// page's metric cards and the compare page's table read the same fields.

/** What `SimHandle.metricsJson()` returns (the fields of `planlab run --json`). */
export interface Metrics {
  outcome: string;
  time_s: number;
  path_length_m: number;
  min_clearance_m: number;
  mean_clearance_m: number;
  total_turn_rad: number;
  max_turn_rad: number;
  speed_drops: number;
  temp_goal_switches: number;
  mean_tracking_error_m: number | null;
  max_tracking_error_m: number | null;
  tracking_error_var_m2: number | null;
  load_ok_share: number | null;
  /** Present after a collision: what with, and whether the robot was at
   *  rest (`SimHandle.collision` words it). */
  collision?: { with: 'wall' | 'mover' | 'non-finite'; id?: number; at_rest?: boolean };
}
