// Trace hashes as people see them: every page prints the hex form that
// `planlab run` prints (the wasm handles give the u64 in decimal).

/** The trace hash (decimal u64) as 16 hex digits, as `planlab run` prints it. */
export function hexHash(dec: string | null): string {
  if (!dec) return '';
  try {
    return BigInt(dec).toString(16).padStart(16, '0');
  } catch {
    return dec;
  }
}
