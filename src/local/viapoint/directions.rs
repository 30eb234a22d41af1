//! Borderline directions inside the hyperplane perpendicular to a blocked motion (CHS §1.4).
//!
//! In the plane there is one perpendicular direction. In R^n the seed offers two strategies:
//! complete the motion direction to an orthogonal basis (rotating the basis about the motion
//! direction when its lines yield nothing useful), or draw random perpendicular directions —
//! "it is helpful to prefer directions orthogonal to each other and possibly to the axes of the
//! world coordinate frame". The same construction gives the rotation axes perpendicular to a
//! blocked rotation's axis (CHS Lemma 2.2: perpendicular great circles ⇔ perpendicular axes).

use super::options::Directions;
use crate::space::extend_small;
use rand::Rng;
use rand_distr_free::standard_normal;

/// Reusable buffers for [`perpendicular_into`], kept in the search.
#[derive(Debug, Default)]
pub struct DirScratch {
    axes: Vec<usize>,
    v: Vec<f64>,
    a: Vec<f64>,
    b: Vec<f64>,
}

/// Unit vectors spanning the hyperplane perpendicular to the unit vector `u` (dimension
/// `u.len() - 1`), for round `round` of the strategy (round 0 is the first basis; later rounds
/// are the basis rotated about `u`, or fresh random directions).
#[cfg(test)]
pub fn perpendicular(
    u: &[f64],
    strategy: Directions,
    round: u32,
    rng: &mut impl Rng,
) -> Vec<Vec<f64>> {
    let mut flat = Vec::new();
    perpendicular_into(
        u,
        strategy,
        round,
        rng,
        &mut DirScratch::default(),
        &mut flat,
    );
    flat.chunks_exact(u.len().max(1))
        .map(<[f64]>::to_vec)
        .collect()
}

/// Allocation-free form of the perpendicular directions: writes them into `out`, one after
/// the other (`u.len()` numbers each), and returns how many there are.
pub fn perpendicular_into(
    u: &[f64],
    strategy: Directions,
    round: u32,
    rng: &mut impl Rng,
    scratch: &mut DirScratch,
    out: &mut Vec<f64>,
) -> usize {
    out.clear();
    let m = u.len();
    if m < 2 {
        return 0;
    }
    match strategy {
        Directions::Basis {
            axis_preference,
            rotations,
        } => {
            if round > rotations || (round > 0 && m < 3) {
                return 0;
            }
            let count = orthogonal_complement(u, axis_preference, scratch, out);
            if round > 0 {
                // rotate consecutive pairs of the basis by a fraction of a right angle, so that
                // the rounds cover the hyperplane evenly
                let angle = std::f64::consts::FRAC_PI_2 * round as f64 / (rotations as f64 + 1.0);
                let (c, s) = (angle.cos(), angle.sin());
                for k in (0..count.saturating_sub(1)).step_by(2) {
                    scratch.a.clear();
                    scratch.a.extend_from_slice(&out[k * m..(k + 1) * m]);
                    scratch.b.clear();
                    scratch.b.extend_from_slice(&out[(k + 1) * m..(k + 2) * m]);
                    let (a, b) = (&scratch.a, &scratch.b);
                    for i in 0..m {
                        out[k * m + i] = c * a[i] + s * b[i];
                        out[(k + 1) * m + i] = -s * a[i] + c * b[i];
                    }
                }
            }
            count
        }
        Directions::Random { count } => {
            if round > 0 {
                return 0;
            }
            let mut kept = 0;
            for _ in 0..count {
                let v = &mut scratch.v;
                v.clear();
                v.extend((0..m).map(|_| standard_normal(rng)));
                project_out(v, u);
                if normalize(v) {
                    extend_small(out, v);
                    kept += 1;
                }
            }
            kept
        }
    }
}

/// An orthonormal basis of the complement of the unit vector `u`, by Gram–Schmidt over the world
/// axes — least aligned with `u` first when `axis_preference`, in index order otherwise.
/// Appends the vectors to `out` (flat) and returns their number.
fn orthogonal_complement(
    u: &[f64],
    axis_preference: bool,
    scratch: &mut DirScratch,
    out: &mut Vec<f64>,
) -> usize {
    let m = u.len();
    let axes = &mut scratch.axes;
    axes.clear();
    axes.extend(0..m);
    if axis_preference {
        axes.sort_by(|&i, &j| u[i].abs().total_cmp(&u[j].abs()));
    }
    let start = out.len();
    let mut count = 0;
    for &i in axes.iter() {
        if count == m - 1 {
            break;
        }
        let v = &mut scratch.v;
        v.clear();
        v.resize(m, 0.0);
        v[i] = 1.0;
        project_out(v, u);
        for k in 0..count {
            project_out(v, &out[start + k * m..start + (k + 1) * m]);
        }
        if v.iter().map(|x| x * x).sum::<f64>() > 1e-12 && normalize(v) {
            extend_small(out, v);
            count += 1;
        }
    }
    count
}

fn project_out(v: &mut [f64], u: &[f64]) {
    let d: f64 = v.iter().zip(u).map(|(a, b)| a * b).sum();
    v.iter_mut().zip(u).for_each(|(a, b)| *a -= d * b);
}

fn normalize(v: &mut [f64]) -> bool {
    let n = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    if n > 1e-12 && n.is_finite() {
        v.iter_mut().for_each(|x| *x /= n);
        true
    } else {
        false
    }
}

/// A standard normal deviate by the Box–Muller transform (avoids a dependency on `rand_distr`).
mod rand_distr_free {
    use rand::Rng;

    pub fn standard_normal(rng: &mut impl Rng) -> f64 {
        let u1: f64 = 1.0 - rng.random::<f64>(); // (0, 1]
        let u2: f64 = rng.random();
        (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    fn dot(a: &[f64], b: &[f64]) -> f64 {
        a.iter().zip(b).map(|(x, y)| x * y).sum()
    }

    #[test]
    fn plane_has_one_perpendicular() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0);
        let s = Directions::Basis {
            axis_preference: true,
            rotations: 1,
        };
        let d = perpendicular(&[0.6, 0.8], s, 0, &mut rng);
        assert_eq!(d.len(), 1);
        assert!(dot(&d[0], &[0.6, 0.8]).abs() < 1e-15);
        assert!(perpendicular(&[0.6, 0.8], s, 1, &mut rng).is_empty());
    }

    #[test]
    fn bases_are_orthonormal_and_prefer_axes() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0);
        let u = [0.0, 0.0, 1.0, 0.0];
        for round in 0..3 {
            let s = Directions::Basis {
                axis_preference: true,
                rotations: 2,
            };
            let b = perpendicular(&u, s, round, &mut rng);
            assert_eq!(b.len(), 3);
            for (i, x) in b.iter().enumerate() {
                assert!(dot(x, &u).abs() < 1e-12);
                assert!((dot(x, x) - 1.0).abs() < 1e-12);
                for y in &b[i + 1..] {
                    assert!(dot(x, y).abs() < 1e-12);
                }
            }
            if round == 0 {
                // axis preference: the world axes other than z themselves
                assert!(b
                    .iter()
                    .all(|x| x.iter().filter(|c| c.abs() > 0.5).count() == 1));
            }
        }
    }

    #[test]
    fn random_directions_are_perpendicular() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
        let u = [1.0 / 3f64.sqrt(); 3];
        let d = perpendicular(&u, Directions::Random { count: 5 }, 0, &mut rng);
        assert_eq!(d.len(), 5);
        assert!(d
            .iter()
            .all(|x| dot(x, &u).abs() < 1e-12 && (dot(x, x) - 1.0).abs() < 1e-12));
    }
}
