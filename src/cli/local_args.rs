//! Command-line choice of the local method: a spec string plus shortcuts for the via-point
//! planner's main knobs.

use anyhow::Context;
use clap::Args;
use viaroad::local::viapoint::{Depth, ViaLimit};
use viaroad::local::LocalSpec;

/// How to pick the local method.
#[derive(Args, Clone, Debug)]
pub struct LocalArgs {
    /// `straight`, `viapoint`, `sampled`, or a full spec such as
    /// `viapoint:depth=deepen-reuse,beta=2/3,via=2` (see docs/planning.md). Default: the
    /// via-point planner — searching deep for `solve` and `render`, shallow
    /// (`viapoint:max=3,calls=1000`) for roadmaps.
    #[arg(long)]
    pub local: Option<String>,
    /// Valuation exponent β of V_β(d, l) = d / l^β (via-point planner).
    #[arg(long, help_heading = "Tuning")]
    pub beta: Option<String>,
    /// Via points tried per borderline: a number or `all`.
    #[arg(long, help_heading = "Tuning")]
    pub via: Option<String>,
    /// Recursion limit: a number (fixed), `deepen`, or `deepen-reuse`.
    #[arg(long, help_heading = "Tuning")]
    pub depth: Option<String>,
}

impl LocalArgs {
    /// Whether any of the flags was given (else the command picks its own default method).
    pub fn given(&self) -> bool {
        self.local.is_some() || self.beta.is_some() || self.via.is_some() || self.depth.is_some()
    }

    /// The spec the flags name; `default` when `--local` is not given.
    pub fn spec_or(&self, default: LocalSpec) -> anyhow::Result<LocalSpec> {
        let mut spec: LocalSpec = match &self.local {
            Some(s) => s.parse().context("--local")?,
            None => default,
        };
        if let LocalSpec::ViaPoint(o) = &mut spec {
            if let Some(b) = &self.beta {
                let s: LocalSpec = format!("viapoint:beta={b}").parse().context("--beta")?;
                if let LocalSpec::ViaPoint(p) = s {
                    o.beta = p.beta;
                }
            }
            if let Some(v) = &self.via {
                o.via = match v.as_str() {
                    "all" => ViaLimit::All,
                    n => ViaLimit::Best(n.parse::<usize>().ok().filter(|k| *k > 0).with_context(
                        || format!("--via {n}: expected a positive number or `all`"),
                    )?),
                };
            }
            if let Some(d) = &self.depth {
                let max = o.depth.max();
                o.depth = match d.as_str() {
                    "deepen" => Depth::Deepen { max },
                    "deepen-reuse" => Depth::DeepenReuse { max },
                    n => Depth::Fixed(n.parse().with_context(|| {
                        format!("--depth {n}: expected a number, deepen or deepen-reuse")
                    })?),
                };
            }
        } else if self.beta.is_some() || self.via.is_some() || self.depth.is_some() {
            anyhow::bail!("--beta, --via and --depth apply to the via-point method only");
        }
        viaroad::local::check_local_spec(&spec)
            .map_err(anyhow::Error::msg)
            .context("--local")?;
        Ok(spec)
    }
}
