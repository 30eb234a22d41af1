//! Numbers and configurations as human messages print them: `{}` of an `f64` writes every
//! digit of 10³⁰⁰, and `{:?}` writes 10¹⁵ as `1000000000000000.0`, so a message about a
//! typo'd coordinate would be hundreds of characters wide. Here magnitudes of 10⁶ and more,
//! and below 10⁻⁴, switch to exponent notation.
//!
//! Every form is still the shortest that reads back to the same `f64`, so nothing is lost; but
//! files and JSON meant to be read back keep their own formats (`{:?}`, serde).

use std::fmt;

/// `x` in short form (module doc): `0.5`, `-3`, `1e300`, `1.2345e-7`, `NaN`, `inf`.
pub fn num(x: f64) -> Num {
    Num(x)
}

/// A configuration (or any list of numbers) in short form: `[1e300, 0.5]`.
pub fn config(q: &[f64]) -> Config<'_> {
    Config(q)
}

/// See [`num`].
#[derive(Clone, Copy, Debug)]
pub struct Num(pub f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        let a = x.abs();
        if x.is_finite() && x != 0.0 && !(1e-4..1e6).contains(&a) {
            write!(f, "{x:e}")
        } else if x == 0.0 {
            // the sign of a zero says nothing to a reader
            f.write_str("0")
        } else {
            write!(f, "{x}")
        }
    }
}

/// See [`config`].
#[derive(Clone, Copy, Debug)]
pub struct Config<'a>(pub &'a [f64]);

impl fmt::Display for Config<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("[")?;
        for (i, x) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            write!(f, "{}", Num(*x))?;
        }
        f.write_str("]")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn huge_and_tiny_numbers_are_printed_in_exponent_notation() {
        assert_eq!(num(1e300).to_string(), "1e300");
        assert_eq!(num(-1e300).to_string(), "-1e300");
        assert_eq!(num(1e6).to_string(), "1e6");
        assert_eq!(num(12345678.9).to_string(), "1.23456789e7");
        assert_eq!(num(1.5e-7).to_string(), "1.5e-7");
        assert_eq!(
            num(f64::MIN_POSITIVE).to_string(),
            "2.2250738585072014e-308"
        );
    }

    #[test]
    fn everyday_numbers_are_printed_plainly() {
        assert_eq!(num(0.5).to_string(), "0.5");
        assert_eq!(num(-3.0).to_string(), "-3");
        assert_eq!(num(999999.5).to_string(), "999999.5");
        assert_eq!(num(1e-4).to_string(), "0.0001");
        assert_eq!(num(0.0).to_string(), "0");
        assert_eq!(num(-0.0).to_string(), "0");
        assert_eq!(num(f64::NAN).to_string(), "NaN");
        assert_eq!(num(f64::NEG_INFINITY).to_string(), "-inf");
    }

    #[test]
    fn short_forms_read_back_to_the_same_number() {
        for x in [1e300, 0.1 + 0.2, 12345678.9, 1.5e-7, -2.5, 1e-300] {
            assert_eq!(num(x).to_string().parse::<f64>().unwrap(), x);
        }
    }

    #[test]
    fn configurations_are_lists_of_short_numbers() {
        assert_eq!(config(&[1e300, 0.5, -0.0]).to_string(), "[1e300, 0.5, 0]");
        assert_eq!(config(&[]).to_string(), "[]");
    }
}
