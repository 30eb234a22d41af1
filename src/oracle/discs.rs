//! A point among discs (balls in R^n): the seed's own experiment (CHS Appendix A.1).
//!
//! The collision set of a straight motion `o + t·d` with a closed ball `|x - c| ≤ r` is the
//! solution set of one quadratic inequality in `t`, hence at most one interval per ball; the
//! answer is the union over all balls.

use super::{CallCounts, CollisionOracle, OracleError, Workspace};
use crate::interval::{Interval, IntervalList};
use crate::space::{Change, Motion};

/// Closed balls in R^n (discs for n = 2) as obstacles for a point robot.
#[derive(Clone, Debug, PartialEq)]
pub struct Discs {
    dim: usize,
    /// Centres, `dim` coordinates each, flattened.
    centres: Vec<f64>,
    radii: Vec<f64>,
    /// The planar case laid out for a vectorised loop (issue 11): blocks of [`LANES`] discs,
    /// each block centre xs, centre ys, squared radii; the last block is padded with discs
    /// of squared radius −∞, which no line meets.
    planar: Option<Vec<Block>>,
}

/// Discs per block of the planar layout: four doubles fill an AVX register, two SSE ones.
const LANES: usize = 4;

/// Discs met that the planar loop gathers before it solves them (a multiple of [`LANES`]).
const BATCH: usize = 16 * LANES;

/// [`LANES`] planar discs: centre x, centre y, squared radius.
#[derive(Clone, Debug, PartialEq)]
struct Block {
    x: [f64; LANES],
    y: [f64; LANES],
    r2: [f64; LANES],
}

impl Discs {
    /// Balls with the given centres (all of dimension `dim`) and radii. The caller (the scene
    /// loader) has checked that every radius is non-negative and every number finite.
    pub fn new(dim: usize, centres: &[Vec<f64>], radii: &[f64]) -> Discs {
        debug_assert_eq!(centres.len(), radii.len());
        debug_assert!(centres.iter().all(|c| c.len() == dim));
        let planar = (dim == 2).then(|| {
            centres
                .chunks(LANES)
                .zip(radii.chunks(LANES))
                .map(|(cs, rs)| {
                    let mut b = Block {
                        x: [0.0; LANES],
                        y: [0.0; LANES],
                        r2: [f64::NEG_INFINITY; LANES],
                    };
                    for (k, (c, r)) in cs.iter().zip(rs).enumerate() {
                        b.x[k] = c[0];
                        b.y[k] = c[1];
                        b.r2[k] = r * r;
                    }
                    b
                })
                .collect()
        });
        Discs {
            dim,
            centres: centres.iter().flatten().copied().collect(),
            radii: radii.to_vec(),
            planar,
        }
    }

    /// Number of balls.
    pub fn len(&self) -> usize {
        self.radii.len()
    }

    /// Whether there are no balls.
    pub fn is_empty(&self) -> bool {
        self.radii.is_empty()
    }

    /// Centre of ball `i`.
    pub fn centre(&self, i: usize) -> &[f64] {
        &self.centres[i * self.dim..(i + 1) * self.dim]
    }

    /// Radius of ball `i`.
    pub fn radius(&self, i: usize) -> f64 {
        self.radii[i]
    }

    /// Dimension of the space the balls live in.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Calls `hit(lo, hi)` with the unclipped parameter interval of every ball that the line
    /// `o + t·d` meets (`d ≠ 0`), in ball order, and stops early if `hit` returns `false`.
    /// Solves `|o + t·d − c|² ≤ r²`, i.e. `a t² + 2 b t + e ≤ 0`, with the numerically stable
    /// root formula.
    fn for_each_hit(&self, o: &[f64], d: &[f64], mut hit: impl FnMut(f64, f64) -> bool) {
        let a: f64 = d.iter().map(|x| x * x).sum();
        let mut solve = |b: f64, e: f64| -> bool {
            let disc = b * b - a * e;
            if disc < 0.0 {
                return true;
            }
            let q = -(b + disc.sqrt().copysign(b));
            let (t1, t2) = if q == 0.0 { (0.0, 0.0) } else { (q / a, e / q) };
            hit(t1.min(t2), t1.max(t2))
        };
        // the roots of gathered discs met (b² ≥ a e), overwriting (b, e) with (lo, hi): the
        // arithmetic of `solve` without its branches, so the compiler vectorises it
        let roots = |bs: &mut [f64], es: &mut [f64], hit: &mut dyn FnMut(f64, f64) -> bool| {
            for (b, e) in bs.iter_mut().zip(es.iter_mut()) {
                let disc = (*b * *b - a * *e).max(0.0);
                let q = -(*b + disc.sqrt().copysign(*b));
                let (t1, t2) = (q / a, *e / q);
                let zero = q == 0.0;
                *b = if zero { 0.0 } else { t1.min(t2) };
                *e = if zero { 0.0 } else { t1.max(t2) };
            }
            bs.iter().zip(es.iter()).all(|(lo, hi)| hit(*lo, *hi))
        };
        if let Some(blocks) = &self.planar {
            // the seed's planar case: the discriminants of a block of discs at once, without
            // branches (so the compiler vectorises them); the (b, e) of the discs met are
            // gathered in ball order, again without branches (about every other block has a
            // hit, so a branch per block or disc mispredicts), and solved in batches; the
            // arithmetic is the same as for one disc at a time, so are the answers
            let (o0, o1, d0, d1) = (o[0], o[1], d[0], d[1]);
            let (mut bs, mut es, mut n) = ([0.0; BATCH], [0.0; BATCH], 0);
            for blk in blocks {
                let (mut b, mut e, mut meets) = ([0.0; LANES], [0.0; LANES], [false; LANES]);
                for k in 0..LANES {
                    let (w0, w1) = (o0 - blk.x[k], o1 - blk.y[k]);
                    b[k] = d0 * w0 + d1 * w1;
                    e[k] = w0 * w0 + w1 * w1 - blk.r2[k];
                    meets[k] = b[k] * b[k] >= a * e[k];
                }
                for k in 0..LANES {
                    bs[n] = b[k];
                    es[n] = e[k];
                    n += usize::from(meets[k]);
                }
                if n > BATCH - LANES {
                    if !roots(&mut bs[..n], &mut es[..n], &mut hit) {
                        return;
                    }
                    n = 0;
                }
            }
            roots(&mut bs[..n], &mut es[..n], &mut hit);
            return;
        }
        let n = self.dim;
        for (c, &r) in self.centres.chunks_exact(n).zip(&self.radii) {
            let (mut b, mut e) = (0.0, 0.0);
            for k in 0..n {
                let w = o[k] - c[k];
                b += d[k] * w;
                e += w * w;
            }
            if !solve(b, e - r * r) {
                return;
            }
        }
    }

    /// Whether the static point `q` lies in some ball.
    fn contains_point(&self, q: &[f64]) -> bool {
        self.centres
            .chunks_exact(self.dim)
            .zip(&self.radii)
            .any(|(c, r)| q.iter().zip(c).map(|(x, y)| (x - y) * (x - y)).sum::<f64>() <= r * r)
    }

    fn linear_delta<'m>(&self, motion: &'m Motion) -> Result<&'m [f64], OracleError> {
        match &motion.change {
            Change::Linear(d) if d.len() == self.dim && motion.origin.len() == self.dim => Ok(d),
            Change::Linear(d) => Err(OracleError::Unsupported(format!(
                "a {}-coordinate motion among {}-dimensional discs",
                d.len(),
                self.dim
            ))),
            Change::Rotation { .. } => Err(OracleError::Unsupported(
                "a rotation of a point robot".into(),
            )),
        }
    }
}

impl CollisionOracle for Discs {
    fn intervals(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<IntervalList, OracleError> {
        let mut out = IntervalList::new();
        self.intervals_into(motion, &mut out, &mut Workspace::new(), counts)?;
        Ok(out)
    }

    fn intervals_into(
        &self,
        motion: &Motion,
        out: &mut IntervalList,
        ws: &mut Workspace,
        counts: &mut CallCounts,
    ) -> Result<(), OracleError> {
        let d = self.linear_delta(motion)?;
        counts.pairs_tested += self.radii.len() as u64;
        out.clear();
        if d.iter().all(|x| *x == 0.0) {
            if self.contains_point(&motion.origin) {
                out.push(motion.range);
            }
            return Ok(());
        }
        let hits = &mut ws.hits;
        hits.clear();
        self.for_each_hit(&motion.origin, d, |lo, hi| {
            if let Some(iv) = (Interval { lo, hi }).meet(&motion.range) {
                hits.push(iv);
            }
            true
        });
        out.set_from_unsorted(hits);
        Ok(())
    }

    fn collides(&self, q: &[f64], counts: &mut CallCounts) -> bool {
        counts.pairs_tested += self.radii.len() as u64;
        self.contains_point(q)
    }

    /// Analytic: a whole line costs what a segment does, so [`super::Bounded`] need not copy
    /// the motion to clip it (the answer is the same set either way, issue 11).
    fn prefers_unclipped(&self) -> bool {
        true
    }

    fn motion_is_free(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<bool, OracleError> {
        let d = self.linear_delta(motion)?;
        counts.pairs_tested += self.radii.len() as u64;
        if d.iter().all(|x| *x == 0.0) {
            return Ok(!self.contains_point(&motion.origin));
        }
        let mut free = true;
        self.for_each_hit(&motion.origin, d, |lo, hi| {
            free = (Interval { lo, hi }).meet(&motion.range).is_none();
            free
        });
        Ok(free)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segment_through_a_disc_centre() {
        let discs = Discs::new(2, &[vec![0.5, 0.5]], &[0.1]);
        let m = Motion::segment(vec![0.0, 0.5], Change::Linear(vec![1.0, 0.0]));
        let l = discs.intervals(&m, &mut CallCounts::default()).unwrap();
        assert_eq!(l.len(), 1);
        assert!(
            (l.as_slice()[0].lo - 0.4).abs() < 1e-15 && (l.as_slice()[0].hi - 0.6).abs() < 1e-15
        );
        assert!(!discs
            .motion_is_free(&m, &mut CallCounts::default())
            .unwrap());
    }

    #[test]
    fn tangent_line_touches_in_one_point() {
        let discs = Discs::new(2, &[vec![0.0, 1.0]], &[1.0]);
        let m = Motion::line(vec![-3.0, 0.0], Change::Linear(vec![1.0, 0.0]));
        let l = discs.intervals(&m, &mut CallCounts::default()).unwrap();
        assert_eq!(l.len(), 1);
        assert!((l.as_slice()[0].lo - 3.0).abs() < 1e-12);
        assert!(l.as_slice()[0].length() < 1e-7);
    }

    #[test]
    fn rotation_is_unsupported() {
        let discs = Discs::new(2, &[], &[]);
        let m = Motion::segment(
            vec![0.0, 0.0],
            Change::Rotation {
                axis: [0.0, 0.0, 1.0],
                angle: 1.0,
            },
        );
        assert!(discs.intervals(&m, &mut CallCounts::default()).is_err());
    }

    /// The batched planar loop (more hits than one batch holds, padded last block) against
    /// each disc asked alone: the same intervals, bit for bit, and the same free verdict.
    #[test]
    fn batched_planar_hits_equal_one_disc_at_a_time() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        for n in [1, 3, 4, 5, 63, 64, 65, 130, 201] {
            let centres: Vec<Vec<f64>> = (0..n)
                .map(|_| vec![rng.random_range(-0.2..1.2), rng.random_range(-0.05..0.05)])
                .collect();
            let radii: Vec<f64> = (0..n).map(|_| rng.random_range(0.0..0.1)).collect();
            let all = Discs::new(2, &centres, &radii);
            for _ in 0..20 {
                let o = vec![rng.random_range(-0.5..0.0), rng.random_range(-0.1..0.1)];
                let d = vec![1.0, rng.random_range(-0.1..0.1)];
                let m = Motion::segment(o, Change::Linear(d));
                let mut single = Vec::new();
                for (c, r) in centres.iter().zip(&radii) {
                    let one = Discs::new(2, std::slice::from_ref(c), &[*r]);
                    let l = one.intervals(&m, &mut CallCounts::default()).unwrap();
                    single.extend_from_slice(l.as_slice());
                }
                let mut want = IntervalList::new();
                want.set_from_unsorted(&mut single);
                let got = all.intervals(&m, &mut CallCounts::default()).unwrap();
                assert_eq!(got, want, "{n} discs");
                let free = all.motion_is_free(&m, &mut CallCounts::default()).unwrap();
                assert_eq!(free, want.is_empty(), "{n} discs");
            }
        }
    }
}
