//! Configurations on the command line: numbers separated by commas or spaces.

use anyhow::Context;

/// Parses `"0.1,0.2"` or `"0.1 0.2"` into numbers (finiteness and length are the scene's to
/// check, so that errors name the configuration).
pub fn parse_config(flag: &str, s: &str) -> anyhow::Result<Vec<f64>> {
    s.split(|c: char| c == ',' || c.is_whitespace())
        .filter(|t| !t.is_empty())
        .map(|t| {
            t.parse::<f64>()
                .with_context(|| format!("{flag}: `{t}` is not a number"))
        })
        .collect::<anyhow::Result<Vec<f64>>>()
        .and_then(|v| {
            if v.is_empty() {
                anyhow::bail!("{flag}: no coordinates given")
            }
            Ok(v)
        })
}
