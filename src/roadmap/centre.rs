//! Centring a configuration in its free chords: a step towards the medial axis of free space
//! with at most two first-collision calls per direction.
//!
//! A blocked extend stops against an obstacle. In a funnel (OMPL.app's bugtrap: a rod must
//! find the narrow tip of a cone) the next extend from that node is blocked again, because the
//! rod is off the funnel's axis. A sampling planner cannot tell where the middle of the free
//! space around a node is without many state checks. The interval oracle can: the first
//! collision along the line (or turn) through the node in a direction, forwards and backwards,
//! bounds the free section containing the node — the *chord* of free space through it —
//! exactly (CHS §1.2; the same chord as every interval of the line would give, for less: an
//! oracle skips whatever lies beyond the nearest obstacle on each side). Its midpoint is the
//! point of that line farthest from the obstacles on both sides; moving there is a certified free single-group
//! motion. Centring in the directions *across* the blocked motion (translations perpendicular
//! to it, turns about axes perpendicular to it) is the coordinate-wise retraction towards the
//! medial axis of MAPRM (Wilmarth, Amato, Stiller 1999), which runs through narrow passages;
//! in a funnel it lines the robot up with the funnel's axis, so that the retried motion gets
//! farther (`TreeParams::centre`).
//!
//! Only chords bounded on both sides within the reach are centred: a direction open on one
//! side is not narrow, and centring there would only drift.

use crate::deadline::Deadline;
use crate::interval::Interval;
use crate::oracle::{CallCounts, CollisionOracle, CountedOracle, OracleError};
use crate::roadmap::bounce::MAX_TURN;
use crate::space::{Config, Group, GroupKind, Space};

/// Where a blocked stair was going: the direction that is *not* centred.
#[derive(Clone, Debug)]
pub enum Across {
    /// A translation in group `group` (index into the groups) along the unit `dir` (one entry
    /// per coordinate of the group).
    Translation {
        /// Index of the blocked group.
        group: usize,
        /// Unit direction of the blocked translation.
        dir: Vec<f64>,
    },
    /// A turn in group `group` about the unit `axis` (`None` for a planar angle).
    Turn {
        /// Index of the blocked group.
        group: usize,
        /// Unit axis of the blocked turn, for a quaternion group.
        axis: Option<[f64; 3]>,
    },
}

/// Unit vectors perpendicular to the unit `d` and to each other: the coordinate axes made
/// orthogonal to `d` (Gram–Schmidt), those that keep a clear residual, at most `n − 1`.
pub fn perpendiculars(d: &[f64]) -> Vec<Vec<f64>> {
    let n = d.len();
    let mut out: Vec<Vec<f64>> = Vec::new();
    // axes least aligned with d first, for well-conditioned residuals
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| d[a].abs().total_cmp(&d[b].abs()));
    for i in order {
        if out.len() + 1 >= n {
            break;
        }
        let mut v = vec![0.0; n];
        v[i] = 1.0;
        for basis in std::iter::once(d).chain(out.iter().map(|v| v.as_slice())) {
            let dot: f64 = v.iter().zip(basis).map(|(a, b)| a * b).sum();
            v.iter_mut().zip(basis).for_each(|(a, b)| *a -= dot * b);
        }
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if norm > 0.3 {
            v.iter_mut().for_each(|x| *x /= norm);
            out.push(v);
        }
    }
    out
}

fn unit_axes(n: usize) -> Vec<Vec<f64>> {
    (0..n)
        .map(|i| {
            let mut v = vec![0.0; n];
            v[i] = 1.0;
            v
        })
        .collect()
}

fn axis3(v: &[f64]) -> Option<[f64; 3]> {
    (v.len() == 3).then(|| [v[0], v[1], v[2]])
}

/// The free chord through `motion.origin` along `motion` within `clip` (which contains 0), if
/// it is bounded on both sides inside `clip`: `None` when the origin collides or the chord is
/// open on either side (not a narrow direction). Two first-collision calls, forwards and then
/// backwards (only when forwards is bounded), instead of every interval of the whole line:
/// the nearest obstacle on each side is all a chord needs, and an oracle may skip everything
/// beyond it. `motion` is left running forwards (its range changed).
fn bounded_chord(
    oracle: &dyn CollisionOracle,
    motion: &mut crate::space::Motion,
    clip: Interval,
    counts: &mut CallCounts,
) -> Result<Option<Interval>, OracleError> {
    motion.range = Interval {
        lo: 0.0,
        hi: clip.hi,
    };
    let Some(hi) = oracle.first_hit(motion, counts)? else {
        return Ok(None);
    };
    if hi <= 0.0 || hi >= clip.hi {
        return Ok(None);
    }
    reverse(motion);
    motion.range = Interval {
        lo: 0.0,
        hi: -clip.lo,
    };
    let back = oracle.first_hit(motion, counts)?;
    reverse(motion);
    let Some(back) = back else {
        return Ok(None);
    };
    if back <= 0.0 || back >= -clip.lo {
        return Ok(None);
    }
    Ok(Some(Interval { lo: -back, hi }))
}

/// The same line or turn, run the other way: `t ↦ −t`.
fn reverse(motion: &mut crate::space::Motion) {
    use crate::space::Change;
    match &mut motion.change {
        Change::Linear(delta) => delta.iter_mut().for_each(|d| *d = -*d),
        // about the opposite axis: the oracles take turns by a positive angle
        Change::Rotation { axis, .. } | Change::BodyRotation { axis, .. } => {
            axis.iter_mut().for_each(|a| *a = -*a)
        }
    }
}

/// One centring round from the free configuration `q`: for every group in turn, every
/// direction across `across` (see the [module](self)), the free chord of the line or turn
/// through the current configuration (first-collision calls), and a move to its midpoint when
/// the chord is bounded on both sides within `reach` (a distance, for lines) or `turn_reach`
/// (in turns, at most [`MAX_TURN`], for turns). Returns the configurations reached (`q`
/// excluded), each joined to the one before by a certified free single-group motion. Stops
/// early when `deadline` has passed.
#[allow(clippy::too_many_arguments)]
pub fn centre_round(
    space: &Space,
    oracle: &dyn CollisionOracle,
    groups: &[Group],
    q: &[f64],
    across: &Across,
    reach: f64,
    turn_reach: f64,
    counts: &mut CallCounts,
    deadline: &Deadline,
) -> Result<Vec<Config>, OracleError> {
    let mut corners: Vec<Config> = Vec::new();
    let mut current = q.to_vec();
    let turn = turn_reach.clamp(0.0, MAX_TURN);
    // the direction a blocked translation took, as a 3-D axis for the turns across it
    let blocked_dir: Option<[f64; 3]> = match across {
        Across::Translation { dir, .. } => axis3(dir),
        Across::Turn { .. } => None,
    };
    for (gi, g) in groups.iter().enumerate() {
        let motions: Vec<(crate::space::Motion, Interval)> = match g.kind {
            GroupKind::Linear => {
                let dirs = match across {
                    Across::Translation { group, dir } if *group == gi => perpendiculars(dir),
                    _ => unit_axes(g.len()),
                };
                dirs.iter()
                    .map(|d| {
                        (
                            space.line_through(&current, g, d),
                            Interval {
                                lo: -reach,
                                hi: reach,
                            },
                        )
                    })
                    .collect()
            }
            GroupKind::Quaternion => {
                let axes: Vec<[f64; 3]> = match across {
                    Across::Turn {
                        group,
                        axis: Some(a),
                    } if *group == gi => {
                        perpendiculars(a).iter().filter_map(|v| axis3(v)).collect()
                    }
                    _ => match blocked_dir {
                        // turns about the blocked direction and across it
                        Some(d) => std::iter::once(d)
                            .chain(perpendiculars(&d).iter().filter_map(|v| axis3(v)))
                            .collect(),
                        None => vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
                    },
                };
                axes.into_iter()
                    .map(|a| {
                        (
                            space.turn_through(&current, g, a),
                            Interval {
                                lo: -turn,
                                hi: turn,
                            },
                        )
                    })
                    .collect()
            }
            GroupKind::Angle => match across {
                Across::Turn { group, .. } if *group == gi => Vec::new(),
                _ => vec![(
                    space.turn_through(&current, g, [0.0, 0.0, 1.0]),
                    Interval {
                        lo: -turn,
                        hi: turn,
                    },
                )],
            },
        };
        for (template, clip) in motions {
            if deadline.expired() {
                return Ok(corners);
            }
            // the line / turn through the configuration reached so far in this round
            let mut motion = template;
            motion.origin.clone_from(&current);
            // only the chord within the reach is asked about: cheaper on big meshes
            let Some(chord) = bounded_chord(oracle, &mut motion, clip, counts)? else {
                continue;
            };
            let t = 0.5 * (chord.lo + chord.hi);
            if t == 0.0 {
                continue;
            }
            let mut next = motion.at(t);
            if g.kind != GroupKind::Linear {
                space.normalize(&mut next);
            }
            if next != current {
                corners.push(next.clone());
                current = next;
            }
        }
    }
    Ok(corners)
}
