//! Text helpers for error messages.

/// `s` with its control characters escaped (`\n` as `\\n`, …), so a
/// message quoting user input (a JSON key with an escaped newline, a
/// planner name) stays one line in the CLI and on the page.
///
/// ```
/// use planlab_core::text::one_line;
/// assert_eq!(one_line("unknown field `a\nb`"), "unknown field `a\\nb`");
/// assert_eq!(one_line("plain"), "plain");
/// ```
pub fn one_line(s: &str) -> String {
    if !s.chars().any(char::is_control) {
        return s.to_string();
    }
    s.chars()
        .map(|c| {
            if c.is_control() {
                c.escape_default().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}
