//! A scene's free space as generalized cones: the cones, their crossings and the robot's radius
//! function, and the orientations a cone allows; what the search walks and
//! [`Freeways::build`] fills.

use super::cone::{Cone, Edge};
use super::radius::{AngleSet, RadiusFunction};

/// A spine intersection: cone `a` at parameter `sa` meets cone `b` at `sb`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossing {
    /// First cone.
    pub a: usize,
    /// Its spine parameter.
    pub sa: f64,
    /// Second cone.
    pub b: usize,
    /// Its spine parameter.
    pub sb: f64,
}

/// A scene's free space as generalized cones: what does not depend on the query (Brooks §4:
/// "up to this stage the algorithm is independent of the object").
#[derive(Clone, Debug)]
pub struct Freeways {
    pub(super) edges: Vec<Edge>,
    pub(super) cones: Vec<Cone>,
    pub(super) crossings: Vec<Crossing>,
    pub(super) radius: RadiusFunction,
    /// Length that counts as touching (a millionth of the scene's extent).
    pub(super) margin: f64,
    /// Whether configurations carry an orientation (SE(2)) or not (R²).
    pub(super) oriented: bool,
    /// Cone candidates examined before pruning.
    pub(super) candidates: usize,
}

impl Freeways {
    /// The cones (freeways).
    pub fn cones(&self) -> &[Cone] {
        &self.cones
    }

    /// The obstacle edges and walls the cones were built from.
    pub fn edges(&self) -> &[Edge] {
        &self.edges
    }

    /// The spine intersections (the graph's nodes before orientations).
    pub fn crossings(&self) -> &[Crossing] {
        &self.crossings
    }

    /// Edge pairs that passed Brooks's two tests (before pruning).
    pub fn candidates(&self) -> usize {
        self.candidates
    }

    /// The robot's radius function.
    pub fn radius_function(&self) -> &RadiusFunction {
        &self.radius
    }

    /// Orientations at which the robot, its reference point moving along the spine of `cone`
    /// from parameter `a` to `b`, stays inside the cone (Brooks §3.2, per stretch: see the
    /// module notes). For a point robot every orientation, wherever the spine is.
    pub fn legal(&self, cone: &Cone, a: f64, b: f64) -> AngleSet {
        let (smin, smax) = (a.min(b), a.max(b));
        let d = self.radius.reach();
        let ahead = cone.hi - smax - self.margin;
        let behind = smin - cone.lo - self.margin;
        let side = cone.min_radius((smin - d).max(cone.lo), (smax + d).min(cone.hi)) - self.margin;
        if smin < cone.lo || smax > cone.hi || side < 0.0 {
            return AngleSet::empty();
        }
        let psi = cone.dir[1].atan2(cone.dir[0]);
        let h = std::f64::consts::FRAC_PI_2;
        self.radius
            .orientations_within(psi, ahead)
            .intersection(
                &self
                    .radius
                    .orientations_within(psi + std::f64::consts::PI, behind),
            )
            .intersection(&self.radius.orientations_within(psi + h, side))
            .intersection(&self.radius.orientations_within(psi - h, side))
    }
}
