// The registry's planner list as the pages receive it from wasm
// (`planners()`): name, paper, summary and every config field. Shared by
// the robot page's parameter panel and the compare page's picks and help.

export interface FieldInfo {
  name: string;
  unit: string;
  /** Its name in plain words (`heading weight α`); `name` is the config's. */
  label?: string;
  default: unknown;
  doc: string;
  /** Added by the wasm layer from the default's JSON type. */
  kind?: 'int' | 'float' | 'bool' | 'string' | 'json';
}

export interface PlannerInfo {
  name: string;
  paper: string;
  summary: string;
  /** Plain words for a beginner (core `planners::plain_words`). */
  plain?: string;
  fields: FieldInfo[];
}
