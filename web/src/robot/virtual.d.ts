// Build-time list of the robot presets (see vite.config.ts).
declare module 'virtual:robot-presets' {
  const presets: { file: string; name: string; description: string; planner: string }[];
  export default presets;
}
