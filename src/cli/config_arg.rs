//! Configurations on the command line: numbers separated by commas or spaces.

use anyhow::Context;

/// Parses `"0.1,0.2"`, `"0.1, 0.2"` or `"0.1 0.2"` into numbers (finiteness and length are
/// the scene's to check, so that errors name the configuration). Spaces may repeat, commas
/// may not: `0.1,,0.1` is refused rather than read as two numbers, since an empty field is
/// more likely a forgotten coordinate than a typo.
pub fn parse_config(flag: &str, s: &str) -> anyhow::Result<Vec<f64>> {
    let fields: Vec<&str> = s.split(',').map(str::trim).collect();
    if fields.len() > 1 {
        if let Some(k) = fields.iter().position(|f| f.is_empty()) {
            anyhow::bail!(
                "{flag} `{s}`: field {} between commas is empty; give every coordinate",
                k + 1
            );
        }
    }
    fields
        .iter()
        .flat_map(|f| f.split_whitespace())
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

#[cfg(test)]
mod tests {
    use super::parse_config;

    #[test]
    fn commas_and_spaces_separate_and_empty_fields_are_refused() {
        assert_eq!(parse_config("--from", "0.1,0.2").unwrap(), vec![0.1, 0.2]);
        assert_eq!(
            parse_config("--from", " 0.1, 0.2 ").unwrap(),
            vec![0.1, 0.2]
        );
        assert_eq!(parse_config("--from", "0.1  0.2").unwrap(), vec![0.1, 0.2]);
        for bad in ["0.1,,0.1", ",0.1,0.2", "0.1,0.2,", "", "x"] {
            assert!(parse_config("--from", bad).is_err(), "{bad}");
        }
    }
}
