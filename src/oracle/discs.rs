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
    /// The planar case laid out for a vectorised loop: blocks of [`LANES`] discs,
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

/// The (b, e) of the planar discs that the line `o + t·d` meets (`b² ≥ a e`, with the names
/// of [`Discs::for_each_hit`]), gathered in ball order into the fronts of `bs` and `es` without
/// a branch per disc (about every other block has a hit, so a branch mispredicts); returns how
/// many. `bs` and `es` hold at least `LANES · blocks.len()` numbers (the AVX2 twin wants
/// one block more).
#[inline(always)]
fn gather_met(
    blocks: &[Block],
    o: [f64; 2],
    d: [f64; 2],
    a: f64,
    bs: &mut [f64],
    es: &mut [f64],
) -> usize {
    let mut n = 0;
    for blk in blocks {
        let (mut b, mut e, mut meets) = ([0.0; LANES], [0.0; LANES], [false; LANES]);
        for k in 0..LANES {
            let (w0, w1) = (o[0] - blk.x[k], o[1] - blk.y[k]);
            b[k] = d[0] * w0 + d[1] * w1;
            e[k] = w0 * w0 + w1 * w1 - blk.r2[k];
            meets[k] = b[k] * b[k] >= a * e[k];
        }
        for k in 0..LANES {
            bs[n] = b[k];
            es[n] = e[k];
            n += usize::from(meets[k]);
        }
    }
    n
}

/// The roots of the gathered discs (`b² ≥ a e`), overwriting `(b, e)` with `(lo, hi)`: the
/// arithmetic of [`Discs::for_each_hit`] without its branches, so that it vectorises.
#[inline(always)]
fn solve_gathered(a: f64, bs: &mut [f64], es: &mut [f64]) {
    for (b, e) in bs.iter_mut().zip(es.iter_mut()) {
        let disc = (*b * *b - a * *e).max(0.0);
        let q = -(*b + disc.sqrt().copysign(*b));
        let (t1, t2) = (q / a, *e / q);
        let zero = q == 0.0;
        *b = if zero { 0.0 } else { t1.min(t2) };
        *e = if zero { 0.0 } else { t1.max(t2) };
    }
}

/// Gathers and solves the planar discs a line meets (see [`gather_met`]), leaving their
/// `(lo, hi)` in the fronts of `bs` and `es`; returns how many.
#[inline(always)]
fn planar_roots(
    blocks: &[Block],
    o: [f64; 2],
    d: [f64; 2],
    a: f64,
    bs: &mut [f64],
    es: &mut [f64],
) -> usize {
    let n = gather_met(blocks, o, d, a, bs, es);
    solve_gathered(a, &mut bs[..n], &mut es[..n]);
    n
}

/// [`planar_roots`] with AVX2 intrinsics: four discs per instruction where the default
/// target has two, and the discs met packed to the front of the buffers by a permutation
/// looked up from the comparison mask instead of one store per disc (that scalar gather was
/// half of a call). The same IEEE operations lane by lane, in the same order and
/// without fused multiply-adds, so the same bits (`planar_avx2_equals_portable` checks it).
/// `bs` and `es` hold at least `LANES · (blocks.len() + 1)` numbers (a packed store writes
/// all four lanes).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn planar_roots_avx2(
    blocks: &[Block],
    o: [f64; 2],
    d: [f64; 2],
    a: f64,
    bs: &mut [f64],
    es: &mut [f64],
) -> usize {
    use std::arch::x86_64::*;
    /// For each 4-bit mask of discs met, the 32-bit lanes that move the met doubles to the
    /// front in order.
    const PACK: [[i32; 8]; 16] = {
        let mut t = [[0; 8]; 16];
        let mut m = 0;
        while m < 16 {
            let (mut j, mut w): (i32, usize) = (0, 0);
            while j < 4 {
                if m & (1 << j) != 0 {
                    t[m][2 * w] = 2 * j;
                    t[m][2 * w + 1] = 2 * j + 1;
                    w += 1;
                }
                j += 1;
            }
            m += 1;
        }
        t
    };
    /// For each 4-bit mask, how many discs it says are met.
    const MET: [usize; 16] = [0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4];
    assert!(bs.len() >= LANES * (blocks.len() + 1) && es.len() >= LANES * (blocks.len() + 1));
    let (o0, o1) = (_mm256_set1_pd(o[0]), _mm256_set1_pd(o[1]));
    let (d0, d1, av) = (
        _mm256_set1_pd(d[0]),
        _mm256_set1_pd(d[1]),
        _mm256_set1_pd(a),
    );
    let mut n = 0;
    for blk in blocks {
        // SAFETY: each array of a block holds LANES = 4 doubles
        let (x, y, r2) = unsafe {
            (
                _mm256_loadu_pd(blk.x.as_ptr()),
                _mm256_loadu_pd(blk.y.as_ptr()),
                _mm256_loadu_pd(blk.r2.as_ptr()),
            )
        };
        let (w0, w1) = (_mm256_sub_pd(o0, x), _mm256_sub_pd(o1, y));
        let b = _mm256_add_pd(_mm256_mul_pd(d0, w0), _mm256_mul_pd(d1, w1));
        let e = _mm256_sub_pd(
            _mm256_add_pd(_mm256_mul_pd(w0, w0), _mm256_mul_pd(w1, w1)),
            r2,
        );
        let meets = _mm256_cmp_pd::<_CMP_GE_OQ>(_mm256_mul_pd(b, b), _mm256_mul_pd(av, e));
        let mask = _mm256_movemask_pd(meets) as usize;
        // SAFETY: PACK's rows hold 8 lanes
        let perm = unsafe { _mm256_loadu_si256(PACK[mask].as_ptr().cast()) };
        let pb = _mm256_castps_pd(_mm256_permutevar8x32_ps(_mm256_castpd_ps(b), perm));
        let pe = _mm256_castps_pd(_mm256_permutevar8x32_ps(_mm256_castpd_ps(e), perm));
        let (sb, se) = (&mut bs[n..n + LANES], &mut es[n..n + LANES]);
        // SAFETY: both slices hold LANES = 4 doubles (checked by the slicing)
        unsafe {
            _mm256_storeu_pd(sb.as_mut_ptr(), pb);
            _mm256_storeu_pd(se.as_mut_ptr(), pe);
        }
        // (a table: without the `popcnt` feature `count_ones` is a dozen instructions)
        n += MET[mask];
    }
    // (solving whole vectors, stale lanes included, instead of a scalar tail was tried: slower)
    solve_gathered(a, &mut bs[..n], &mut es[..n]);
    n
}

/// [`planar_roots`] on the best instruction set this CPU has (checked once per process by the
/// standard library's cached feature detection).
fn planar_roots_dispatch(
    blocks: &[Block],
    o: [f64; 2],
    d: [f64; 2],
    a: f64,
    bs: &mut [f64],
    es: &mut [f64],
) -> usize {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, checked just above; nothing else is required.
        return unsafe { planar_roots_avx2(blocks, o, d, a, bs, es) };
    }
    planar_roots(blocks, o, d, a, bs, es)
}

impl Discs {
    /// Balls with the given centres (all of dimension `dim`) and radii. The caller (the scene
    /// loader) has checked that every radius is non-negative and every number finite.
    pub fn new(dim: usize, centres: &[Vec<f64>], radii: &[f64]) -> Discs {
        debug_assert_eq!(centres.len(), radii.len());
        debug_assert!(centres.iter().all(|c| c.len() == dim));
        let planar = (dim == 2).then(|| {
            // blocks in order of the centres' x: a line then meets the discs roughly in the
            // order of its parameter (reversed when it runs towards −x), so that the hits come
            // nearly sorted and the insertion sort that merges them rarely moves one (issue
            // 11: its mispredictions were a tenth of `bench discs`); the union does not depend
            // on the order
            let mut order: Vec<usize> = (0..centres.len()).collect();
            order.sort_by(|&i, &j| centres[i][0].total_cmp(&centres[j][0]));
            let centres: Vec<&Vec<f64>> = order.iter().map(|&i| &centres[i]).collect();
            let radii: Vec<f64> = order.iter().map(|&i| radii[i]).collect();
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
            Change::Rotation { .. } | Change::BodyRotation { .. } => Err(OracleError::Unsupported(
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
        if let Some(blocks) = &self.planar {
            // the seed's planar case: all discs met gathered and solved at once in a buffer
            // of the workspace (no batches, nothing zeroed per call), then clipped; the same
            // arithmetic and ball order as `for_each_hit`, so the same answer bit for bit
            let len = LANES * (blocks.len() + 1);
            if ws.numbers.len() < 2 * len {
                ws.numbers.resize(2 * len, 0.0);
            }
            let (bs, es) = ws.numbers[..2 * len].split_at_mut(len);
            let a = d[0] * d[0] + d[1] * d[1];
            let (o, d) = ([motion.origin[0], motion.origin[1]], [d[0], d[1]]);
            let n = planar_roots_dispatch(blocks, o, d, a, bs, es);
            let range = motion.range;
            hits.extend(
                bs[..n]
                    .iter()
                    .zip(&es[..n])
                    .filter_map(|(&lo, &hi)| (Interval { lo, hi }).meet(&range)),
            );
            if d[0] < 0.0 {
                hits.reverse();
            }
            out.set_from_unsorted(hits);
            return Ok(());
        }
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
    /// the motion to clip it (the answer is the same set either way).
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

    /// The planar layout (gathered, solved in one go, compiled for AVX2 where the CPU has it)
    /// against the generic n-dimensional loop on the same discs: the same intervals bit for
    /// bit, on segments, on lines and on lines narrowed to a range, with tangent and
    /// degenerate motions among them.
    #[test]
    fn planar_layout_equals_generic_loop_bit_for_bit() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(12);
        for n in [0, 1, 3, 4, 5, 50, 130] {
            let centres: Vec<Vec<f64>> = (0..n)
                .map(|_| vec![rng.random_range(0.0..1.0), rng.random_range(0.0..1.0)])
                .collect();
            let radii: Vec<f64> = (0..n).map(|_| rng.random_range(0.0..0.2)).collect();
            let planar = Discs::new(2, &centres, &radii);
            let generic = Discs {
                planar: None,
                ..planar.clone()
            };
            let mut ws = Workspace::new();
            for i in 0..200 {
                let o = vec![rng.random_range(-0.2..1.2), rng.random_range(-0.2..1.2)];
                let mut d = vec![rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)];
                if i % 7 == 0 && n > 0 {
                    // tangent to a disc: along the x axis, touching its top
                    let (c, r) = (&centres[i % n], radii[i % n]);
                    d = vec![1.0, 0.0];
                    let o = vec![c[0] - 0.5, c[1] + r];
                    let m = Motion::segment(o, Change::Linear(d.clone()));
                    let (mut got, mut want) = (IntervalList::new(), IntervalList::new());
                    let c = &mut CallCounts::default();
                    planar.intervals_into(&m, &mut got, &mut ws, c).unwrap();
                    generic.intervals_into(&m, &mut want, &mut ws, c).unwrap();
                    assert_eq!(bits(&got), bits(&want));
                }
                let mut motions = vec![
                    Motion::segment(o.clone(), Change::Linear(d.clone())),
                    Motion::line(o.clone(), Change::Linear(d.clone())),
                ];
                motions.push(motions[1].with_range(Interval { lo: -0.3, hi: 0.7 }));
                for m in &motions {
                    let (mut got, mut want) = (IntervalList::new(), IntervalList::new());
                    let c = &mut CallCounts::default();
                    planar.intervals_into(m, &mut got, &mut ws, c).unwrap();
                    generic.intervals_into(m, &mut want, &mut ws, c).unwrap();
                    assert_eq!(bits(&got), bits(&want), "{n} discs, {m:?}");
                }
            }
        }
    }

    fn bits(l: &IntervalList) -> Vec<(u64, u64)> {
        l.iter()
            .map(|iv| (iv.lo.to_bits(), iv.hi.to_bits()))
            .collect()
    }

    /// The AVX2 build of the planar roots against the portable one: the same count and bits.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn planar_avx2_equals_portable() {
        use rand::{Rng, SeedableRng};
        if !std::arch::is_x86_feature_detected!("avx2") {
            return;
        }
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(13);
        let centres: Vec<Vec<f64>> = (0..61)
            .map(|_| vec![rng.random_range(0.0..1.0), rng.random_range(0.0..1.0)])
            .collect();
        let radii: Vec<f64> = (0..61).map(|_| rng.random_range(0.0..0.3)).collect();
        let discs = Discs::new(2, &centres, &radii);
        let blocks = discs.planar.as_ref().unwrap();
        let len = LANES * (blocks.len() + 1);
        let mut met = 0;
        for _ in 0..500 {
            let o = [rng.random_range(-0.2..1.2), rng.random_range(-0.2..1.2)];
            let d = [rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)];
            let a = d[0] * d[0] + d[1] * d[1];
            let (mut b1, mut e1, mut b2, mut e2) = (
                vec![0.0; len],
                vec![0.0; len],
                vec![0.0; len],
                vec![0.0; len],
            );
            let n1 = planar_roots(blocks, o, d, a, &mut b1, &mut e1);
            // SAFETY: AVX2 checked at the top of the test
            let n2 = unsafe { planar_roots_avx2(blocks, o, d, a, &mut b2, &mut e2) };
            assert_eq!(n1, n2);
            met += n1;
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&b1[..n1]), bits(&b2[..n2]));
            assert_eq!(bits(&e1[..n1]), bits(&e2[..n2]));
        }
        assert!(met > 1000, "the lines met too few discs to compare: {met}");
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
