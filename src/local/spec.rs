//! Local methods named by spec strings, for the command line, roadmap headers and benchmarks.
//!
//! ```text
//! straight
//! sampled:res=0.01
//! viapoint:depth=deepen-reuse,max=6,beta=0.667,via=2,base=centre-nearest
//! viapoint:beta=0,0.5,0.667,1          (a grid: one spec per value)
//! ```
//!
//! Keys of `viapoint`: `depth` (`N` | `deepen` | `deepen-reuse`), `max` (deepening limit),
//! `beta`, `via` (`N` | `all`), `base` (see [`BasePoint::name`]), `dirs` (`basis` | `axes` |
//! `random:N`), `rotations`, `split` (`true` | `false`), `dodge` (`true` | `false`), `search`
//! (`dfs` | `bfs`), `calls` (`N` | `none`), `seed`.

use super::viapoint::{BasePoint, Depth, Directions, Search, ViaLimit, ViaPoint, ViaPointOptions};
use super::{LocalMethod, StraightLine};
use crate::limits::MIN_SAMPLED_RESOLUTION;
use crate::space::{Space, SpaceKind};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// A local method and its parameters.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum LocalSpec {
    /// [`StraightLine::exact`].
    Straight,
    /// [`StraightLine::sampled`] at a resolution.
    Sampled {
        /// Fraction of the space's extent between checked states.
        resolution: f64,
    },
    /// [`ViaPoint`] with options.
    ViaPoint(ViaPointOptions),
}

impl Default for LocalSpec {
    fn default() -> Self {
        LocalSpec::ViaPoint(ViaPointOptions::default())
    }
}

/// A spec string that does not parse.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("bad local method spec `{spec}`: {reason}")]
pub struct SpecError {
    /// The spec given.
    pub spec: String,
    /// What is wrong with it.
    pub reason: String,
}

/// The via-point planner's keys in a spec string (`viapoint:KEY=VALUE,…`).
const VIAPOINT_KEYS: [&str; 13] = [
    "depth",
    "max",
    "beta",
    "via",
    "base",
    "dirs",
    "rotations",
    "split",
    "dodge",
    "search",
    "calls",
    "seed",
    "sidestep",
];

impl LocalSpec {
    /// The local method roadmaps are learnt with by default: the via-point planner tuned to the
    /// fast end — deepening with re-use up to depth 3, at most 1000 intersect calls per
    /// connection. "By varying the limit on recursion depth, our strategy can be tuned to run as
    /// fast as possible, rarely finding a path, or to be quite effective in path planning for
    /// the cost of increased running time" (CHS §1.6): a roadmap calls its local method
    /// thousands of times and covers the rest itself, while a single query (`viaroad solve`, and
    /// the roadmap's attaching of difficult ends) can afford the planner's full defaults.
    pub fn roadmap_default() -> LocalSpec {
        LocalSpec::ViaPoint(ViaPointOptions {
            depth: Depth::DeepenReuse { max: 3 },
            max_calls: Some(1000),
            ..ViaPointOptions::default()
        })
    }

    /// [`LocalSpec::default`] suited to `space`: what `solve` and the other single-query
    /// planners use unless told otherwise. Where several bodies move, their translation is split
    /// along the axes (`split=true`, see the crate-internal `suited` for why).
    pub fn default_for(space: &Space) -> LocalSpec {
        LocalSpec::ViaPoint(suited(ViaPointOptions::default(), space))
    }

    /// [`LocalSpec::roadmap_default`] suited to `space`, as [`LocalSpec::default_for`]: what
    /// `build`, `solve --roadmap`, the roadmap `solve` grows and Python's `Roadmap.build` learn
    /// with unless told otherwise (a roadmap's queries then use what its file records).
    pub fn roadmap_default_for(space: &Space) -> LocalSpec {
        match LocalSpec::roadmap_default() {
            LocalSpec::ViaPoint(o) => LocalSpec::ViaPoint(suited(o, space)),
            other => other,
        }
    }

    /// The same method searching at least as deep and as long as the via-point planner's
    /// defaults ([`ViaPointOptions::default`]), or `None` when that changes nothing or the
    /// method does not search. A roadmap is learnt with a shallow, cheap method; a query can
    /// afford the deep search where the roadmap did not reach: "by varying the limit on
    /// recursion depth, our strategy can be tuned … to be quite effective in path planning for
    /// the cost of increased running time" (CHS §1.6).
    pub fn deeper(&self) -> Option<LocalSpec> {
        let LocalSpec::ViaPoint(o) = self else {
            return None;
        };
        let full = ViaPointOptions::default();
        let deeper = ViaPointOptions {
            depth: if o.depth.max() >= full.depth.max() {
                o.depth
            } else {
                full.depth
            },
            max_calls: match (o.max_calls, full.max_calls) {
                (Some(a), Some(b)) => Some(a.max(b)),
                _ => None,
            },
            ..o.clone()
        };
        (deeper != *o).then_some(LocalSpec::ViaPoint(deeper))
    }

    /// The same method limited to `calls` intersect calls per connection (CHS §1.3: a budget
    /// keeps it from "excessively long computations"), or with `calls == 0` to the direct
    /// path alone (recursion depth 0: one exact call per DOF group). `None` for a method that
    /// does not search: it is such a check already.
    pub fn budgeted(&self, calls: u64) -> Option<LocalSpec> {
        let LocalSpec::ViaPoint(o) = self else {
            return None;
        };
        Some(LocalSpec::ViaPoint(if calls > 0 {
            ViaPointOptions {
                max_calls: Some(o.max_calls.map_or(calls, |m| m.min(calls))),
                ..o.clone()
            }
        } else {
            ViaPointOptions {
                depth: Depth::Fixed(0),
                ..o.clone()
            }
        }))
    }

    /// Checks what the spec-string parser guarantees, for a spec that did not come from it
    /// (a roadmap file's header): a sampled resolution that is a positive number the limits
    /// allow ([`check_local_spec`]), a finite β ≥ 0, at least one via point
    /// and one random direction.
    pub fn validate(&self) -> Result<(), String> {
        match self {
            LocalSpec::Straight => {}
            LocalSpec::Sampled { resolution } => {
                if !(resolution.is_finite() && *resolution > 0.0) {
                    return Err(format!("res={resolution} is not a positive number"));
                }
            }
            LocalSpec::ViaPoint(o) => {
                if !(o.beta.is_finite() && o.beta >= 0.0) {
                    return Err(format!("beta={} is not a number ≥ 0", o.beta));
                }
                if o.via == ViaLimit::Best(0) {
                    return Err("via must be ≥ 1 or all".into());
                }
                if o.directions == (Directions::Random { count: 0 }) {
                    return Err("dirs=random:0 has no direction".into());
                }
            }
        }
        check_local_spec(self)
    }

    /// Builds the method.
    pub fn build(&self) -> Box<dyn LocalMethod> {
        match self {
            LocalSpec::Straight => Box::new(StraightLine::exact()),
            LocalSpec::Sampled { resolution } => Box::new(StraightLine::sampled(*resolution)),
            LocalSpec::ViaPoint(o) => Box::new(ViaPoint::new(o.clone())),
        }
    }

    /// Parses a spec that may hold grids of values (`beta=0,0.5,1`) and returns one spec per
    /// combination, in the order the values were given (last key varies fastest).
    pub fn parse_grid(s: &str) -> Result<Vec<LocalSpec>, SpecError> {
        let err = |reason: String| SpecError {
            spec: s.to_string(),
            reason,
        };
        let (name, rest) = match s.split_once(':') {
            Some((n, r)) => (n.trim(), r.trim()),
            None => (s.trim(), ""),
        };
        // key=value tokens; a token without '=' adds another value to the previous key
        let mut keys: Vec<(String, Vec<String>)> = Vec::new();
        for tok in rest.split(',').map(str::trim).filter(|t| !t.is_empty()) {
            match tok.split_once('=') {
                Some((k, v)) => keys.push((k.trim().to_string(), vec![v.trim().to_string()])),
                // a knob's name is no knob's value: `calls=1000,split` meant `split=true`, and
                // read as a value of `calls` it would be reported as a bad number of calls
                None if VIAPOINT_KEYS.contains(&tok) => {
                    return Err(err(format!(
                        "`{tok}` needs a value (`{tok}=…`): a word without `=` is another value \
                         of the key before it"
                    )))
                }
                None => match keys.last_mut() {
                    Some((_, vals)) => vals.push(tok.to_string()),
                    None => return Err(err(format!("`{tok}` is not key=value"))),
                },
            }
        }
        let mut combos: Vec<Vec<(String, String)>> = vec![Vec::new()];
        for (k, vals) in &keys {
            combos = combos
                .into_iter()
                .flat_map(|c| {
                    vals.iter().map(move |v| {
                        let mut c = c.clone();
                        c.push((k.clone(), v.clone()));
                        c
                    })
                })
                .collect();
        }
        combos
            .iter()
            .map(|kv| Self::from_pairs(name, kv).map_err(err))
            .collect()
    }

    fn from_pairs(name: &str, kv: &[(String, String)]) -> Result<LocalSpec, String> {
        match name {
            "straight" => {
                if let Some((k, _)) = kv.first() {
                    return Err(format!("straight takes no parameters (got {k})"));
                }
                Ok(LocalSpec::Straight)
            }
            "sampled" => {
                let mut resolution = crate::oracle::sampled::OMPL_DEFAULT_RESOLUTION;
                for (k, v) in kv {
                    match k.as_str() {
                        "res" | "resolution" => resolution = parse_num(k, v)?,
                        _ => return Err(format!("unknown key `{k}` for sampled")),
                    }
                }
                if resolution <= 0.0 {
                    return Err("res must be positive".into());
                }
                Ok(LocalSpec::Sampled { resolution })
            }
            "viapoint" | "via" => Self::via_point_from_pairs(kv),
            _ => Err(format!(
                "unknown method `{name}`; expected straight, sampled or viapoint"
            )),
        }
    }

    /// The via-point planner's options from its `key=value` pairs, over the defaults.
    fn via_point_from_pairs(kv: &[(String, String)]) -> Result<LocalSpec, String> {
        let mut o = ViaPointOptions::default();
        let mut depth_kind: Option<String> = None;
        let mut max: Option<u32> = None;
        for (k, v) in kv {
            match k.as_str() {
                "depth" => depth_kind = Some(v.clone()),
                "max" => max = Some(parse_int(k, v)? as u32),
                "beta" => {
                    o.beta =
                        parse_fraction(v).ok_or_else(|| format!("beta={v} is not a number"))?;
                    if o.beta < 0.0 {
                        return Err("beta must be ≥ 0".into());
                    }
                }
                "via" => {
                    o.via = match v.as_str() {
                        "all" => ViaLimit::All,
                        _ => match parse_int(k, v)? {
                            0 => return Err("via must be ≥ 1 or all".into()),
                            n => ViaLimit::Best(n as usize),
                        },
                    }
                }
                "base" => {
                    o.base_point = BasePoint::from_name(v).ok_or_else(|| {
                        let names: Vec<&str> = BasePoint::ALL.iter().map(|b| b.name()).collect();
                        format!("base={v}; expected one of {}", names.join(", "))
                    })?
                }
                "dirs" => {
                    o.directions = match v.as_str() {
                        "axes" => Directions::Basis {
                            axis_preference: true,
                            rotations: rotations_of(&o.directions),
                        },
                        "basis" => Directions::Basis {
                            axis_preference: false,
                            rotations: rotations_of(&o.directions),
                        },
                        r => match r.strip_prefix("random:") {
                            Some(n) => Directions::Random {
                                count: parse_int(k, n)?.max(1) as u32,
                            },
                            None => {
                                return Err(format!("dirs={v}; expected axes, basis or random:N"))
                            }
                        },
                    }
                }
                "rotations" => {
                    let r = parse_int(k, v)? as u32;
                    if let Directions::Basis { rotations, .. } = &mut o.directions {
                        *rotations = r;
                    }
                }
                "split" => o.split_axes = parse_bool(k, v)?,
                "dodge" => o.dodge_other_groups = parse_bool(k, v)?,
                "search" => {
                    o.search = match v.as_str() {
                        "dfs" | "depth-first" => Search::DepthFirst,
                        "bfs" | "breadth-first" => Search::BreadthFirst,
                        _ => return Err(format!("search={v}; expected dfs or bfs")),
                    }
                }
                "calls" => {
                    o.max_calls = if v == "none" {
                        None
                    } else {
                        Some(parse_int(k, v)?)
                    }
                }
                "seed" => o.seed = parse_int(k, v)?,
                "sidestep" => {
                    o.sidestep = if v == "none" {
                        None
                    } else {
                        let s = parse_num(k, v)?;
                        if s <= 0.0 {
                            return Err(format!("sidestep={v}; expected a positive share or none"));
                        }
                        Some(s)
                    }
                }
                _ => return Err(format!("unknown key `{k}` for viapoint")),
            }
        }
        let default_max = o.depth.max();
        o.depth = match depth_kind.as_deref() {
            None => match o.depth {
                Depth::Fixed(_) => o.depth,
                Depth::Deepen { .. } => Depth::Deepen {
                    max: max.unwrap_or(default_max),
                },
                Depth::DeepenReuse { .. } => Depth::DeepenReuse {
                    max: max.unwrap_or(default_max),
                },
            },
            Some("deepen") => Depth::Deepen {
                max: max.unwrap_or(default_max),
            },
            Some("deepen-reuse") | Some("reuse") => Depth::DeepenReuse {
                max: max.unwrap_or(default_max),
            },
            Some(n) => Depth::Fixed(
                n.parse::<u32>()
                    .map_err(|_| format!("depth={n}; expected a number, deepen or deepen-reuse"))?,
            ),
        };
        Ok(LocalSpec::ViaPoint(o))
    }
}

/// The via-point planner's options `o` suited to `space`: where several bodies move, their
/// translation is split along the axes (`split=true`, CHS A.1.1). The seed's translation group
/// moves every body at once, each along its own straight vector, so a direct motion carries a
/// cube diagonally across the rim of its box and a square diagonally into a wall; a via point
/// must then be found for each body's corner. Split along x, y and z, every motion is a
/// staircase: all bodies move along x, then along y, then along z, so a cube goes over its box
/// and then straight down, and a square follows a corridor's axis. On the shipped scenes of
/// several bodies (both cube scenes, the swaps of 2 and 3 squares, the movers in a room) grown
/// roadmaps connected with fewer calls split than unsplit, and three cubes only split.
fn suited(o: ViaPointOptions, space: &Space) -> ViaPointOptions {
    match space.kind() {
        SpaceKind::Se2Bodies(_) | SpaceKind::Se3Bodies(_) => ViaPointOptions {
            split_axes: true,
            ..o
        },
        _ => o,
    }
}

/// `v`, the value of key `k`, as a finite number.
fn parse_num(k: &str, v: &str) -> Result<f64, String> {
    v.parse::<f64>()
        .ok()
        .filter(|x| x.is_finite())
        .ok_or_else(|| format!("{k}={v} is not a number"))
}

/// `v`, the value of key `k`, as a whole number.
fn parse_int(k: &str, v: &str) -> Result<u64, String> {
    v.parse::<u64>()
        .map_err(|_| format!("{k}={v} is not a whole number"))
}

/// `v`, the value of key `k`, as `true` or `false`.
fn parse_bool(k: &str, v: &str) -> Result<bool, String> {
    v.parse::<bool>()
        .map_err(|_| format!("{k}={v} is not true or false"))
}

fn rotations_of(d: &Directions) -> u32 {
    match d {
        Directions::Basis { rotations, .. } => *rotations,
        Directions::Random { .. } => 1,
    }
}

/// `0.667`, or a fraction such as `2/3`.
fn parse_fraction(v: &str) -> Option<f64> {
    match v.split_once('/') {
        Some((a, b)) => {
            let (a, b) = (a.trim().parse::<f64>().ok()?, b.trim().parse::<f64>().ok()?);
            (b != 0.0).then(|| a / b).filter(|x| x.is_finite())
        }
        None => v.parse::<f64>().ok().filter(|x| x.is_finite()),
    }
}

impl FromStr for LocalSpec {
    type Err = SpecError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let mut all = Self::parse_grid(s)?;
        if all.len() != 1 {
            return Err(SpecError {
                spec: s.into(),
                reason: format!(
                    "names {} methods (a grid); give one value per key",
                    all.len()
                ),
            });
        }
        Ok(all.remove(0))
    }
}

impl fmt::Display for LocalSpec {
    /// The canonical spec string, naming every parameter; parsing it gives the same spec.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LocalSpec::Straight => write!(f, "straight"),
            LocalSpec::Sampled { resolution } => write!(f, "sampled:res={resolution}"),
            LocalSpec::ViaPoint(o) => {
                let (depth, max) = match o.depth {
                    Depth::Fixed(k) => (k.to_string(), None),
                    Depth::Deepen { max } => ("deepen".to_string(), Some(max)),
                    Depth::DeepenReuse { max } => ("deepen-reuse".to_string(), Some(max)),
                };
                write!(f, "viapoint:depth={depth}")?;
                if let Some(m) = max {
                    write!(f, ",max={m}")?;
                }
                write!(f, ",beta={}", o.beta)?;
                match o.via {
                    ViaLimit::All => write!(f, ",via=all")?,
                    ViaLimit::Best(n) => write!(f, ",via={n}")?,
                }
                write!(f, ",base={}", o.base_point.name())?;
                match o.directions {
                    Directions::Basis {
                        axis_preference,
                        rotations,
                    } => write!(
                        f,
                        ",dirs={},rotations={rotations}",
                        if axis_preference { "axes" } else { "basis" }
                    )?,
                    Directions::Random { count } => write!(f, ",dirs=random:{count}")?,
                }
                write!(f, ",split={},dodge={}", o.split_axes, o.dodge_other_groups)?;
                write!(
                    f,
                    ",search={}",
                    match o.search {
                        Search::DepthFirst => "dfs",
                        Search::BreadthFirst => "bfs",
                    }
                )?;
                match o.max_calls {
                    None => write!(f, ",calls=none")?,
                    Some(c) => write!(f, ",calls={c}")?,
                }
                write!(f, ",seed={}", o.seed)?;
                match o.sidestep {
                    Some(s) => write!(f, ",sidestep={s}"),
                    None => Ok(()),
                }
            }
        }
    }
}

/// Refuses a local method that could not finish a motion: the sampled method below
/// [`MIN_SAMPLED_RESOLUTION`].
pub fn check_local_spec(spec: &LocalSpec) -> Result<(), String> {
    match spec {
        LocalSpec::Sampled { resolution }
            if resolution.is_nan() || *resolution < MIN_SAMPLED_RESOLUTION =>
        {
            Err(format!(
                "sampled:res={resolution:?} is below the smallest resolution \
                 {MIN_SAMPLED_RESOLUTION:e}: a motion would be checked at more than \
                 {:e} states",
                (1.0 / MIN_SAMPLED_RESOLUTION).round()
            ))
        }
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_round_trips() {
        for s in [
            "straight",
            "sampled:res=0.02",
            "viapoint:depth=deepen-reuse,beta=2/3,via=2",
            "viapoint:depth=9,via=all,base=centre-first,search=bfs,calls=none",
            "viapoint:dirs=random:4,split=true,seed=7",
            "viapoint:split=true,sidestep=0.5",
        ] {
            let spec: LocalSpec = s.parse().unwrap();
            let again: LocalSpec = spec.to_string().parse().unwrap();
            assert_eq!(spec, again, "{s}");
        }
    }

    #[test]
    fn grids_expand() {
        let all = LocalSpec::parse_grid("viapoint:beta=0,0.5,1,via=2,all").unwrap();
        assert_eq!(all.len(), 6);
        assert!("viapoint:beta=0,1".parse::<LocalSpec>().is_err());
    }

    /// A knob written as a flag is named as such, not read as a value of the key before it.
    #[test]
    fn a_knob_without_a_value_is_named() {
        let e = "viapoint:calls=1000,split"
            .parse::<LocalSpec>()
            .unwrap_err();
        assert!(e.reason.contains("`split` needs a value"), "{}", e.reason);
        assert!("viapoint:calls=1000,split=true"
            .parse::<LocalSpec>()
            .is_ok());
    }

    #[test]
    fn deeper_and_budgeted_variants() {
        let shallow = LocalSpec::roadmap_default();
        let Some(LocalSpec::ViaPoint(deep)) = shallow.deeper() else {
            panic!("the roadmap default searches less deep than the defaults");
        };
        assert_eq!(deep.depth, Depth::DeepenReuse { max: 6 });
        assert_eq!(deep.max_calls, Some(5000));
        assert_eq!(LocalSpec::default().deeper(), None, "already as deep");
        assert_eq!(LocalSpec::Straight.deeper(), None);
        let Some(LocalSpec::ViaPoint(quick)) = shallow.budgeted(32) else {
            panic!("a via-point spec has a budgeted variant");
        };
        assert_eq!(
            (quick.depth, quick.max_calls),
            (Depth::DeepenReuse { max: 3 }, Some(32))
        );
        let Some(LocalSpec::ViaPoint(bigger)) = shallow.budgeted(1 << 20) else {
            panic!("a via-point spec has a budgeted variant");
        };
        assert_eq!(
            bigger.max_calls,
            Some(1000),
            "a budget never raises the method's own"
        );
        let Some(LocalSpec::ViaPoint(direct)) = shallow.budgeted(0) else {
            panic!("a via-point spec has a budgeted variant");
        };
        assert_eq!(direct.depth, Depth::Fixed(0));
        assert_eq!(LocalSpec::Sampled { resolution: 0.01 }.budgeted(5), None);
    }

    /// Several bodies get their translation split along the axes, by default and in roadmaps;
    /// one body keeps the seed's defaults.
    #[test]
    fn defaults_split_the_translation_of_several_bodies() {
        let split = |spec: LocalSpec| match spec {
            LocalSpec::ViaPoint(o) => o.split_axes,
            _ => panic!("the defaults are the via-point planner"),
        };
        let several = [
            Space::se2_bodies(3, [0.0; 2], [4.0; 2], 1.0).unwrap(),
            Space::se3_bodies(2, [0.0; 3], [4.0; 3], 1.0).unwrap(),
        ];
        for space in &several {
            assert!(split(LocalSpec::default_for(space)), "{}", space.kind());
            assert!(
                split(LocalSpec::roadmap_default_for(space)),
                "{}",
                space.kind()
            );
        }
        let one = [
            Space::se2([0.0; 2], [4.0; 2], 1.0).unwrap(),
            Space::se3([0.0; 3], [4.0; 3], 1.0).unwrap(),
            Space::euclidean(vec![0.0; 2], vec![1.0; 2]).unwrap(),
        ];
        for space in &one {
            assert_eq!(LocalSpec::default_for(space), LocalSpec::default());
            assert_eq!(
                LocalSpec::roadmap_default_for(space),
                LocalSpec::roadmap_default()
            );
        }
    }

    #[test]
    fn validate_refuses_what_the_parser_refuses() {
        for s in [
            "straight",
            "sampled:res=0.02",
            "viapoint:via=all,dirs=random:3",
        ] {
            assert_eq!(s.parse::<LocalSpec>().unwrap().validate(), Ok(()), "{s}");
        }
        let via = |f: fn(&mut ViaPointOptions)| {
            let mut o = ViaPointOptions::default();
            f(&mut o);
            LocalSpec::ViaPoint(o)
        };
        for bad in [
            LocalSpec::Sampled { resolution: -1.0 },
            LocalSpec::Sampled {
                resolution: f64::NAN,
            },
            LocalSpec::Sampled { resolution: 1e-300 },
            via(|o| o.beta = -0.5),
            via(|o| o.beta = f64::INFINITY),
            via(|o| o.via = ViaLimit::Best(0)),
            via(|o| o.directions = Directions::Random { count: 0 }),
        ] {
            assert!(bad.validate().is_err(), "{bad:?}");
        }
    }

    #[test]
    fn bad_specs_say_why() {
        for s in [
            "curved",
            "viapoint:beta=x",
            "viapoint:via=0",
            "sampled:res=-1",
            "viapoint:foo=1",
            "straight:x=1",
        ] {
            assert!(s.parse::<LocalSpec>().is_err(), "{s}");
        }
    }
}
