//! The exact arm oracle for a **single-joint move** (CHS §1.5 and §2.3.2): moving
//! one revolute joint turns the whole distal part of the chain rigidly about the joint's axis,
//! which stays fixed in the world; a prismatic joint translates it. So the collision intervals
//! of the move are the rotation (translation) intervals of the distal links, as rigid bodies,
//! against the environment **and** the proximal links, which stand still during the move
//! (self-collision becomes a static obstacle). The polyhedra oracle answers exactly that.
//!
//! Per call, for joint `k` moving by `delta` from configuration `q`:
//! - the body frame is the joint's child frame at `q` (its origin lies on the axis);
//! - each distal link with geometry becomes one [`Polyhedra`] robot, its obstacles the
//!   environment's polytopes and the proximal links it is not exempt from (SRDF
//!   `disable_collisions`, the scene's allowed-collision matrix), placed at `q`;
//! - link pairs that keep their relative pose during the move (distal–distal,
//!   proximal–proximal, proximal–environment) collide for the whole move or not at all: they
//!   are tested once, statically (a link against the environment at a pose is remembered per
//!   thread, `STATIC_MEMO`: the pieces of a direct path leave most links where they were);
//! - the answer is the union, in `t ∈ [0, 1]`.
//!
//! Enveloping: every link polytope and environment polytope has a bounding ball; a pair is
//! handed to the polyhedra oracle only if the balls meet (static pairs) or if the ball of the
//! moving link, swept about the axis (the piece of a torus its centre's arc describes) or along
//! it (a capsule), meets the other's ball. Inside the polyhedra oracle, the link's face tree
//! against the obstacles' is culled in cylindrical coordinates about the axis; a pair of faces
//! is solved only if, over its window, neither face stays off the other's plane or outside the
//! prism over it (exact extremes of `α cos φ + β sin φ + γ` over the window), and an edge only
//! if its own cylindrical box reaches the other face's. Everything that survives is solved
//! exactly.
//!
//! Conservative advancement first (`robot::clearance`): a moving link and an obstacle (a proximal
//! link) that a separating plane shows apart stay apart until the turn could carry a vertex
//! across the gap; from both ends of the move, plane after plane, the pair is proved free, and
//! only the window in between, where they come close, is handed to the exact sweep (an oracle
//! whose pairs are all proved free throughout is not asked at all). Static pairs are tested the
//! same way before their exact test. Outside the windows the bodies stay 1e-6 of the scene's
//! size apart, far beyond the exact predicate's slack: the answers do not change.
//!
//! One sweep per move: the oracles a move asks share one set of collision pieces
//! ([`Polyhedra::gather`](crate::oracle::polyhedra::Polyhedra)), so a pair of faces whose
//! window an earlier oracle already found colliding is skipped; the yes/no question
//! ([`ArmOracle::joint_move_free`]) stops at the first piece, the first-hit question
//! ([`ArmOracle::joint_move_first_hit`]) only looks before the earliest piece known. Within a
//! turn, a pair of faces is solved only in the part of its window not yet known to collide
//! (narrowed again after each of its edges): the union is the same, and pairs deep inside a
//! collision get narrow windows that the bounds mostly decide without solving for zeros.
//! [`ArmOracle::with_culling`]`(false)` asks every oracle on its own, every pair in its whole
//! window (the reference).
//!
//! Curved primitives are their circumscribed polytopes ([`super::shapes`]), so the answer
//! contains every true collision.
//!
//! Cost (benches/arm.rs): every oracle is built once, in [`ArmOracle::new`]: one per link
//! against the environment (in the world) and one per self-collision pair (link `a` in `b`'s
//! frame). A static test is a few queries. A move asks the same oracles, the joint's axis and
//! pivot carried into the frame of each (`Polyhedra::turn_about`, CHS §2.3.2): nothing is
//! built per call but a shifted copy of a moving link's faces. Free moves cost about 0.1 ms
//! (median); moves that collide are dominated by long turns of a link through clutter, where
//! the exact sweep of the surviving face pairs is the cost (see the README's § Robot arms for
//! the figures).

use super::arm::Arm;
use super::clearance::{self, Cloud, Move, Pair};
use super::cover::{CoverBall, Outer};
use super::inner::{InnerBall, Solid};
use super::objects::{CollisionObject, ObjectShape};
use super::RobotError;
use crate::fast_hash::FastMap;
use crate::geometry::TriMesh;
use crate::interval::{Interval, IntervalList};
use crate::oracle::polyhedra::{AngleRange, Body, Gather, Gathered, Polyhedra};
use crate::oracle::{CallCounts, CollisionOracle, OracleError};
use crate::robot::urdf::JointKind;
use crate::space::{Change, Motion};
use nalgebra::{Isometry3, Point3, Vector3};
use std::f64::consts::TAU;
use std::sync::Arc;

mod reach;
mod straight;

/// A ball that holds a polytope.
#[derive(Clone, Copy, Debug)]
struct Ball {
    centre: Vector3<f64>,
    radius: f64,
}

impl Ball {
    /// The ball about the centre of the vertices' box (with a relative margin for rounding).
    fn of(mesh: &TriMesh) -> Ball {
        let (lo, hi) = mesh.aabb();
        let centre = (lo.coords + hi.coords) / 2.0;
        let radius = mesh
            .vertices
            .iter()
            .map(|v| (v.coords - centre).norm())
            .fold(0.0, f64::max);
        Ball {
            centre,
            radius: radius * (1.0 + 1e-9) + 1e-12,
        }
    }

    fn placed(&self, pose: &Isometry3<f64>) -> Ball {
        Ball {
            centre: pose * Point3::from(self.centre) - Point3::origin(),
            radius: self.radius,
        }
    }

    fn meets(&self, o: &Ball) -> bool {
        // squares: the sure test and the proofs' pieces run this by the thousand
        let reach = self.radius + o.radius;
        (self.centre - o.centre).norm_squared() <= reach * reach
    }
}

/// A polyhedra oracle's error inside a joint move, as the robot's: an unsupported motion is
/// a bad joint move; an interrupted one stays interrupted ([`crate::deadline::watching`]).
fn joint_move_error(e: OracleError) -> RobotError {
    match e {
        OracleError::Unsupported(message) => RobotError::Config {
            what: "joint move".into(),
            message,
        },
        OracleError::Interrupted => RobotError::Interrupted,
    }
}

/// An obstacle polytope's axis-aligned box in the obstacle's own frame (a primitive's or a
/// mesh's frame, where a box or a shelf board is its own box), with the map from the world
/// into that frame: where the ball of a moving link, swept by a move, stays off it, the link
/// cannot meet the obstacle.
#[derive(Clone, Copy, Debug)]
struct ObstacleBox {
    into: Isometry3<f64>,
    lo: Vector3<f64>,
    hi: Vector3<f64>,
}

impl ObstacleBox {
    /// The box of `local` (the polytope in its own frame) placed at `pose` in the world.
    fn of(local: &TriMesh, pose: &Isometry3<f64>) -> ObstacleBox {
        let (lo, hi) = local.aabb();
        ObstacleBox {
            into: pose.inverse(),
            lo: lo.coords,
            hi: hi.coords,
        }
    }

    /// Whether ball `m` reaches into the box.
    fn meets_ball(&self, m: &Ball) -> bool {
        let c = self.into * Point3::from(m.centre);
        let nearest = c.coords.sup(&self.lo).inf(&self.hi);
        (c.coords - nearest).norm() <= m.radius
    }

    /// Whether ball `m` moved by `mv` can come within `margin` of the box: the box of the arc
    /// (or segment) its centre runs along, in the obstacle's frame and grown by its radius and
    /// the margin, meets the box.
    fn may_meet(&self, mv: &Move, m: &Ball, margin: f64) -> bool {
        let c = self.into * Point3::from(m.centre);
        let (lo, hi) = match mv {
            Move::Turn { pivot, axis, angle } => {
                let p = self.into * Point3::from(*pivot);
                let a = self.into.rotation * axis;
                let range = AngleRange::new(angle.min(0.0), angle.max(0.0));
                let b = range.arc_box(&(c - p), &a);
                (b.lo + p.coords, b.hi + p.coords)
            }
            Move::Slide { offset } => {
                let end = c.coords + self.into.rotation * offset;
                (c.coords.inf(&end), c.coords.sup(&end))
            }
        };
        let grow = m.radius + margin;
        (0..3).all(|k| lo[k] - grow <= self.hi[k] && hi[k] + grow >= self.lo[k])
    }
}

/// Whether ball `m`, moved by `mv` (a piece of a torus for a turn, a capsule for a slide),
/// can meet the fixed ball `o`.
fn may_meet(mv: &Move, m: &Ball, o: &Ball) -> bool {
    let reach = m.radius + o.radius;
    match mv {
        Move::Turn {
            pivot: origin,
            axis,
            angle,
        } => {
            // m's centre runs on an arc of the circle of radius rm about the axis; the
            // squared distance to o's centre is dh² + rm² + ro² − 2 rm ro cos(θ − θo),
            // smallest at θ = θo if the arc reaches it, else at an end of the arc
            let (pm, po) = (m.centre - origin, o.centre - origin);
            let (hm, ho) = (axis.dot(&pm), axis.dot(&po));
            let (rad_m, rad_o) = (pm - axis * hm, po - axis * ho);
            let (rm, ro) = (rad_m.norm(), rad_o.norm());
            let reach = reach * (1.0 + 1e-9) + 1e-12;
            // the closest the two circles about the axis come: no angle brings them nearer
            if (hm - ho).powi(2) + (rm - ro).powi(2) > reach * reach {
                return false;
            }
            if angle.abs() >= TAU || rm <= 1e-12 || ro <= 1e-12 {
                return true;
            }
            let u = rad_m / rm;
            let v = axis.cross(&u);
            let theta_o = rad_o.dot(&v).atan2(rad_o.dot(&u));
            let delta = (angle.signum() * theta_o).rem_euclid(TAU);
            let best_cos = if delta <= angle.abs() {
                1.0
            } else {
                delta.cos().max((delta - angle.abs()).cos())
            };
            let d2 = (hm - ho).powi(2) + rm * rm + ro * ro - 2.0 * rm * ro * best_cos;
            d2.max(0.0).sqrt() <= reach
        }
        Move::Slide { offset } => {
            let len2 = offset.norm_squared();
            let t = if len2 > 0.0 {
                ((o.centre - m.centre).dot(offset) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (m.centre + offset * t - o.centre).norm() <= reach
        }
    }
}

/// What [`ArmOracle::prepare`] hands on: link poses and balls at `q`, the distal links, the
/// joint's child link and how the distal part sweeps.
struct Prepared {
    poses: Vec<Isometry3<f64>>,
    balls: Vec<Option<Ball>>,
    distal: Vec<bool>,
    child: usize,
    sweep: Move,
}

/// How far apart, in units of an oracle's distance tolerance, conservative advancement must
/// prove a pair before it leaves their exact sweep out (1e-6 of the scene's size: far beyond
/// the slack with which the exact predicate reports contacts).
const CLEARANCE_PER_TOLERANCE: f64 = 1e5;

/// Moments of a single-joint move the sure test looks at before a yes/no question goes to the
/// exact sweep ([`ArmOracle::joint_move_free`]): the end, the middle, the quarters. Each costs
/// about a microsecond; the sweep of a blocked stair near an obstacle tens to hundreds.
const SURE_MOVE_SAMPLES: usize = 4;

impl Prepared {
    /// The world pivot and axis of the move (for a slide: the child frame's origin and the
    /// offset).
    fn pivot_axis(&self) -> (Vector3<f64>, Vector3<f64>) {
        match &self.sweep {
            Move::Turn { pivot, axis, .. } => (*pivot, *axis),
            Move::Slide { offset } => (self.poses[self.child].translation.vector, *offset),
        }
    }
}

/// Exact collision intervals of single-joint moves of one arm in one scene.
#[derive(Clone)]
pub struct ArmOracle {
    arm: Arm,
    /// Environment polytopes in the world frame, with their balls.
    environment: Vec<(TriMesh, Ball)>,
    /// Per link: its collision polytopes (merged) in the link frame, with their ball.
    link_meshes: Vec<Option<(TriMesh, Ball)>>,
    /// Per self-collision pair `(a, b)`: link `a` as the robot among link `b`, both in their
    /// own frames, built once (a static test places `a` at `pose_b⁻¹ · pose_a`).
    pair_oracles: FastMap<(usize, usize), Arc<Polyhedra>>,
    /// Per link with geometry: the link (in its frame) among the whole environment, built once.
    env_oracles: Vec<Option<Arc<Polyhedra>>>,
    /// Per link and per environment polytope: its vertices, for conservative advancement
    /// ([`clearance`]) ahead of the exact sweep.
    link_clouds: Vec<Option<Cloud>>,
    env_clouds: Vec<Option<Cloud>>,
    /// Whether the link oracles of a move share what they find ([`ArmOracle::with_culling`]).
    culling: bool,
    /// Per link: balls inside its polytopes, in the link frame ([`super::inner`]).
    inner: Vec<Vec<InnerBall>>,
    /// Per environment part, its true shape where the sure test can measure it: a straight
    /// motion's proof asks it where a link's cover reaches deep into the part
    /// ([`Self::surely_meets_obstacle`]).
    solids: Vec<Option<Solid>>,
    /// Whether [`Self::collides`] tries the sure test first ([`ArmOracle::with_sure_test`]).
    sure_test: bool,
    /// Per environment polytope: its box in its own frame, with the map from the world into
    /// that frame ([`ObstacleBox`]).
    env_boxes: Vec<ObstacleBox>,
    /// Per link: balls whose union holds its polytope, in the link frame ([`super::cover`]).
    covers: Vec<Vec<CoverBall>>,
    /// Per environment polytope: a convex shape that holds it ([`super::cover::Outer`]).
    outers: Vec<Outer>,
    /// Whether the covers prove pairs apart before the separating planes
    /// ([`ArmOracle::with_covers`]).
    use_covers: bool,
    /// This oracle's key in the thread's memo of static link tests ([`STATIC_MEMO`]): unique
    /// per construction, so that no other oracle's answers are ever read.
    id: u64,
    /// Per link, how fast its points may move per unit of each joint's rate
    /// ([`ArmOracle::straight_free`]).
    reach: reach::Reach,
    /// Per link, the environment polytopes it can meet in some configuration
    /// ([`reach::reachable_obstacles`]).
    reachable: Vec<Vec<u32>>,
    /// Per link with inner balls, the obstacles of [`Self::reachable`] whose true shape the
    /// sure test ([`super::inner`]) can measure, each with its ball, side by side: the sure
    /// test walks these lists whole at every free moment a motion is asked at, and the
    /// polytopes they would be read beside are large.
    sure_obstacles: Vec<Vec<(Ball, Solid)>>,
}

/// The sure test's inner balls in the world, each link's placed when first asked for (most
/// links meet no obstacle), in buffers the thread keeps ([`PLACED`]).
struct PlacedBalls<'a> {
    inner: &'a [Vec<InnerBall>],
    poses: &'a [Isometry3<f64>],
    balls: Vec<(Point3<f64>, f64)>,
    /// Per link, where its balls are in `balls` once placed.
    at: Vec<Option<(u32, u32)>>,
}

/// [`PlacedBalls`]' buffers: the balls, and per link where its balls are.
type PlacedBuffers = (Vec<(Point3<f64>, f64)>, Vec<Option<(u32, u32)>>);

thread_local! {
    /// [`PlacedBalls`]' buffers, reused: the sure test runs before every static test.
    static PLACED: std::cell::RefCell<PlacedBuffers> =
        const { std::cell::RefCell::new((Vec::new(), Vec::new())) };
}

impl<'a> PlacedBalls<'a> {
    /// Runs `f` with the balls of links at `poses`, none placed yet.
    fn with<R>(
        inner: &'a [Vec<InnerBall>],
        poses: &'a [Isometry3<f64>],
        f: impl FnOnce(&mut PlacedBalls<'a>) -> R,
    ) -> R {
        let (mut balls, mut at) = PLACED.with(|p| std::mem::take(&mut *p.borrow_mut()));
        balls.clear();
        at.clear();
        at.resize(inner.len(), None);
        let mut placed = PlacedBalls {
            inner,
            poses,
            balls,
            at,
        };
        let r = f(&mut placed);
        PLACED.with(|p| *p.borrow_mut() = (placed.balls, placed.at));
        r
    }

    /// Where link `l`'s balls are in [`Self::balls`] (placed now if they were not).
    fn of(&mut self, l: usize) -> std::ops::Range<usize> {
        if let Some((from, to)) = self.at[l] {
            return from as usize..to as usize;
        }
        let from = self.balls.len();
        let pose = &self.poses[l];
        self.balls
            .extend(self.inner[l].iter().map(|b| (pose * b.centre, b.radius)));
        self.at[l] = Some((from as u32, self.balls.len() as u32));
        from..self.balls.len()
    }
}

/// Entries after which [`STATIC_MEMO`] starts afresh (a few hundred kilobytes).
const STATIC_MEMO_LIMIT: usize = 8192;

/// A static link test's key: the oracle's id, the link, the bits of the link's pose.
type StaticKey = (u64, u32, [u64; 7]);

thread_local! {
    /// Links tested against the environment at a pose, remembered per thread: a move asks
    /// every link it does not move, and the pieces of a direct path share most of them (a move
    /// of joint `k` leaves links `0..k` where the move of joint `k − 1` before it left them), as
    /// do the moves from one configuration. Keyed by the oracle's id, the link and the pose's
    /// bits, so an answer read is the answer the test would give; only the work changes.
    static STATIC_MEMO: std::cell::RefCell<FastMap<StaticKey, bool>> =
        std::cell::RefCell::new(FastMap::default());
}

/// The ids of [`ArmOracle`]s.
static NEXT_ID: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

impl std::fmt::Debug for ArmOracle {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ArmOracle")
            .field("links", &self.link_meshes.len())
            .field("environment", &self.environment.len())
            .field("self_pairs", &self.pair_oracles.len())
            .finish()
    }
}

/// Link `l`'s cloud, if it has geometry.
fn l_cloud(clouds: &[Option<Cloud>], l: usize) -> Option<&Cloud> {
    clouds.get(l).and_then(Option::as_ref)
}

/// A mesh moved rigidly.
fn placed(mesh: &TriMesh, pose: &Isometry3<f64>) -> TriMesh {
    TriMesh {
        vertices: mesh.vertices.iter().map(|v| pose * v).collect(),
        triangles: mesh.triangles.clone(),
    }
}

/// Several meshes as one (one rigid body).
fn merged(meshes: impl IntoIterator<Item = TriMesh>) -> Option<TriMesh> {
    let mut out: Option<TriMesh> = None;
    for m in meshes {
        match &mut out {
            None => out = Some(m),
            Some(o) => {
                let base = o.vertices.len() as u32;
                o.vertices.extend(m.vertices);
                o.triangles
                    .extend(m.triangles.iter().map(|t| t.map(|i| i + base)));
            }
        }
    }
    out
}

/// The SE(3) configuration `[x, y, z, qx, qy, qz, qw]` of a pose (OMPL's order).
fn se3(pose: &Isometry3<f64>) -> Vec<f64> {
    let t = pose.translation.vector;
    let q = pose.rotation.coords;
    vec![t.x, t.y, t.z, q[0], q[1], q[2], q[3]]
}

/// The scene's collision objects placed in the world (curved primitives circumscribed): each
/// part's mesh with its ball, its exact solid where it has one (for the sure test), its box and
/// the outer shape that holds it (for the covers).
fn place_objects(arm: &Arm, objects: &[CollisionObject]) -> Result<PlacedObjects, RobotError> {
    let mut environment = Vec::new();
    let mut solids = Vec::new();
    let mut env_boxes = Vec::new();
    let mut outers = Vec::new();
    for o in objects {
        let what = || format!("collision object {}", o.id);
        let at = arm.frame_pose(&o.frame).map_err(|e| RobotError::Config {
            what: what(),
            message: e.to_string(),
        })?;
        for (pose, shape) in &o.parts {
            let local = match shape {
                ObjectShape::Primitive(p) => p.polytope().map_err(|e| RobotError::Config {
                    what: what(),
                    message: e.to_string(),
                })?,
                ObjectShape::Mesh(m) => m.clone(),
            };
            let in_world = at * pose;
            let world = placed(&local, &in_world);
            let ball = Ball::of(&world);
            environment.push((world, ball));
            env_boxes.push(ObstacleBox::of(&local, &in_world));
            let primitive = match shape {
                ObjectShape::Primitive(p) => Some(p),
                ObjectShape::Mesh(_) => None,
            };
            outers.push(Outer::of(primitive, &local, &in_world));
            solids.push(primitive.and_then(|p| Solid::of(p, &in_world)));
        }
    }
    Ok((environment, solids, env_boxes, outers))
}

/// [`ArmOracle::sure_obstacles`]: per link with inner balls, the obstacles in its reach whose
/// true shape the sure test can measure, with their balls.
fn sure_obstacles(
    reachable: &[Vec<u32>],
    inner: &[Vec<InnerBall>],
    environment: &[(TriMesh, Ball)],
    solids: &[Option<Solid>],
) -> Vec<Vec<(Ball, Solid)>> {
    reachable
        .iter()
        .zip(inner)
        .map(|(near, inner)| {
            if inner.is_empty() {
                return Vec::new();
            }
            near.iter()
                .filter_map(|&i| Some((environment[i as usize].1, solids[i as usize]?)))
                .collect()
        })
        .collect()
}

/// [`place_objects`]' answer: the polytopes with their balls, the exact solids, the boxes and
/// the outer shapes, one of each per part.
type PlacedObjects = (
    Vec<(TriMesh, Ball)>,
    Vec<Option<Solid>>,
    Vec<ObstacleBox>,
    Vec<Outer>,
);

/// Each link's inner balls (found at load) in its link's frame, largest first, for the sure
/// test.
fn inner_balls(arm: &Arm) -> Vec<Vec<InnerBall>> {
    (0..arm.model.urdf.links.len())
        .map(|l| {
            let mut balls: Vec<InnerBall> = arm
                .shapes
                .iter()
                .filter(|s| s.link == l)
                .flat_map(|s| {
                    s.inner.iter().map(|b| InnerBall {
                        centre: s.origin * b.centre,
                        radius: b.radius,
                    })
                })
                .collect();
            balls.sort_by(|a, b| b.radius.total_cmp(&a.radius));
            balls
        })
        .collect()
}

/// Each link's cover (its elements' covers, found at load) in its link's frame.
fn link_covers(arm: &Arm) -> Vec<Vec<CoverBall>> {
    (0..arm.model.urdf.links.len())
        .map(|l| {
            arm.shapes
                .iter()
                .filter(|s| s.link == l)
                .flat_map(|s| {
                    s.cover.iter().map(|b| CoverBall {
                        centre: s.origin * b.centre,
                        radius: b.radius * (1.0 + 1e-12),
                    })
                })
                .collect()
        })
        .collect()
}

impl ArmOracle {
    /// The oracle of `arm` (with its group, other joint values, base and exempt pairs as set)
    /// among the scene's collision objects (curved primitives circumscribed).
    pub fn new(arm: &Arm, objects: &[CollisionObject]) -> Result<ArmOracle, RobotError> {
        let (environment, solids, env_boxes, outers) = place_objects(arm, objects)?;
        let link_meshes = (0..arm.model.urdf.links.len())
            .map(|l| {
                merged(
                    arm.shapes
                        .iter()
                        .filter(|s| s.link == l)
                        .map(|s| placed(&s.polytope, &s.origin)),
                )
                .map(|m| {
                    let b = Ball::of(&m);
                    (m, b)
                })
            })
            .collect();
        let link_meshes: Vec<Option<(TriMesh, Ball)>> = link_meshes;
        // each link's body and the environment's built once (a link is the moving body of its
        // environment oracle and of some self pairs, the still one of others: the same body)
        // (the mesh once as a moving body, once as the still one of a pair: one copy per link)
        type Built = (Arc<TriMesh>, Arc<Vec<TriMesh>>, Arc<Body>);
        let bodies: Vec<Option<Built>> = link_meshes
            .iter()
            .map(|m| {
                m.as_ref().map(|(m, _)| {
                    let body = Body::new(std::slice::from_ref(m));
                    (
                        Arc::new(m.clone()),
                        Arc::new(vec![m.clone()]),
                        Arc::new(body),
                    )
                })
            })
            .collect();
        let mut pair_oracles = FastMap::default();
        for &(a, b) in &arm.self_pairs {
            if let (Some((ma, _, ba)), Some((_, still, bb))) = (&bodies[a], &bodies[b]) {
                pair_oracles.insert(
                    (a, b),
                    Arc::new(Polyhedra::of_bodies(
                        Arc::clone(ma),
                        Body::clone(ba),
                        Arc::clone(still),
                        Arc::clone(bb),
                    )),
                );
            }
        }
        let env_meshes: Arc<Vec<TriMesh>> =
            Arc::new(environment.iter().map(|(m, _)| m.clone()).collect());
        let env_body = Arc::new(Body::new(&env_meshes));
        let env_oracles = bodies
            .iter()
            .map(|b| {
                b.as_ref()
                    .filter(|_| !env_meshes.is_empty())
                    .map(|(m, _, body)| {
                        Arc::new(Polyhedra::of_bodies(
                            Arc::clone(m),
                            Body::clone(body),
                            Arc::clone(&env_meshes),
                            Arc::clone(&env_body),
                        ))
                    })
            })
            .collect();
        let link_clouds = link_meshes
            .iter()
            .map(|m| m.as_ref().and_then(|(m, _)| Cloud::of(&m.vertices)))
            .collect();
        let env_clouds = environment
            .iter()
            .map(|(m, _)| Cloud::of(&m.vertices))
            .collect();
        let inner = inner_balls(arm);
        let covers = link_covers(arm);
        let reach = reach::reach_of(
            &arm.model,
            link_meshes.iter().map(|m| m.as_ref().map(|(mesh, _)| mesh)),
        );
        let mid: Vec<f64> = (0..arm.group.dof())
            .map(|i| (arm.group.lower[i] + arm.group.upper[i]) / 2.0)
            .collect();
        let reachable = reach::reachable_obstacles(
            &arm.model,
            &reach,
            &link_meshes
                .iter()
                .map(|m| m.as_ref().map(|(_, b)| (b.centre, b.radius)))
                .collect::<Vec<_>>(),
            &arm.link_poses(&mid),
            &environment
                .iter()
                .map(|(_, b)| (b.centre, b.radius))
                .collect::<Vec<_>>(),
        );
        let sure_obstacles = sure_obstacles(&reachable, &inner, &environment, &solids);
        Ok(ArmOracle {
            solids,
            arm: arm.clone(),
            reach,
            reachable,
            sure_obstacles,
            inner,
            sure_test: true,
            env_boxes,
            covers,
            outers,
            use_covers: true,
            environment,
            link_meshes,
            pair_oracles,
            env_oracles,
            link_clouds,
            env_clouds,
            culling: true,
            id: NEXT_ID.fetch_add(1, std::sync::atomic::Ordering::Relaxed),
        })
    }

    /// The arm.
    pub fn arm(&self) -> &Arm {
        &self.arm
    }

    /// Whether links `a` and `b` (a self-collision pair) meet at these link poses (unless a
    /// separating plane shows them apart first).
    fn pair_meets(
        &self,
        a: usize,
        b: usize,
        poses: &[Isometry3<f64>],
        counts: &mut CallCounts,
    ) -> bool {
        self.pair_oracles.get(&(a, b)).is_some_and(|o| {
            self.cover_to_link(a, &poses[a], b, &poses[b])
                <= o.tolerance() * CLEARANCE_PER_TOLERANCE
                && !self.apart(
                    l_cloud(&self.link_clouds, a),
                    &poses[a],
                    l_cloud(&self.link_clouds, b),
                    &poses[b],
                    o,
                )
                && o.collides(&se3(&(poses[b].inverse() * poses[a])), counts)
        })
    }

    /// Whether link `l` at `pose` meets the environment (when its ball meets an obstacle's
    /// and no separating plane shows it apart from every such obstacle).
    fn in_environment(
        &self,
        l: usize,
        pose: &Isometry3<f64>,
        ball: &Ball,
        counts: &mut CallCounts,
    ) -> bool {
        let t = pose.translation.vector;
        let r = pose.rotation.coords;
        let key = (
            self.id,
            l as u32,
            [t.x, t.y, t.z, r[0], r[1], r[2], r[3]].map(f64::to_bits),
        );
        if let Some(hit) = STATIC_MEMO.with(|m| m.borrow().get(&key).copied()) {
            return hit;
        }
        let hit = self.link_in_environment(l, pose, ball, counts);
        STATIC_MEMO.with(|m| {
            let mut m = m.borrow_mut();
            if m.len() >= STATIC_MEMO_LIMIT {
                m.clear();
            }
            m.insert(key, hit);
        });
        hit
    }

    /// [`Self::in_environment`], asked.
    fn link_in_environment(
        &self,
        l: usize,
        pose: &Isometry3<f64>,
        ball: &Ball,
        counts: &mut CallCounts,
    ) -> bool {
        let Some(o) = &self.env_oracles[l] else {
            return false;
        };
        let margin = o.tolerance() * CLEARANCE_PER_TOLERANCE;
        let near = |(i, (_, b)): &(usize, &(TriMesh, Ball))| {
            b.meets(ball)
                && self.cover_to_obstacle(l, pose, *i) <= margin
                && !self.apart(
                    l_cloud(&self.link_clouds, l),
                    pose,
                    self.env_clouds[*i].as_ref(),
                    &Isometry3::identity(),
                    o,
                )
        };
        self.environment.iter().enumerate().any(|e| near(&e)) && o.collides(&se3(pose), counts)
    }

    /// A lower bound on the distance from link `l` at `pose` to obstacle `i`: the least distance
    /// from a ball of the link's cover to the obstacle's outer shape ([`super::cover`]); 0
    /// with the covers off or without a cover.
    fn cover_to_obstacle(&self, l: usize, pose: &Isometry3<f64>, i: usize) -> f64 {
        self.placed_cover_to_obstacle(l, |_, b| pose * b.centre, i)
    }

    /// [`Self::cover_to_obstacle`] with the cover's balls' world centres given by `centre`
    /// (ball index, ball): a straight motion's pieces place each link's cover once, for every
    /// obstacle and link they ask it against ([`straight`]).
    fn placed_cover_to_obstacle(
        &self,
        l: usize,
        centre: impl Fn(usize, &CoverBall) -> Point3<f64>,
        i: usize,
    ) -> f64 {
        let balls = &self.covers[l];
        if !self.use_covers || balls.is_empty() {
            return 0.0;
        }
        let outer = &self.outers[i];
        balls
            .iter()
            .enumerate()
            .map(|(k, b)| outer.distance(&centre(k, b)) - b.radius)
            .fold(f64::INFINITY, f64::min)
    }

    /// A lower bound on the distance between links `a` and `b` at these poses: the least
    /// distance between balls of their covers; 0 with the covers off or without covers.
    fn cover_to_link(
        &self,
        a: usize,
        pose_a: &Isometry3<f64>,
        b: usize,
        pose_b: &Isometry3<f64>,
    ) -> f64 {
        self.placed_cover_to_link(a, |_, x| pose_a * x.centre, b, |_, y| pose_b * y.centre)
    }

    /// [`Self::cover_to_link`] with the covers' balls' world centres given by `centre_a` and
    /// `centre_b` (ball index, ball), as [`Self::placed_cover_to_obstacle`].
    fn placed_cover_to_link(
        &self,
        a: usize,
        centre_a: impl Fn(usize, &CoverBall) -> Point3<f64>,
        b: usize,
        centre_b: impl Fn(usize, &CoverBall) -> Point3<f64>,
    ) -> f64 {
        let (ca, cb) = (&self.covers[a], &self.covers[b]);
        if !self.use_covers || ca.is_empty() || cb.is_empty() {
            return 0.0;
        }
        let mut least = f64::INFINITY;
        for (i, x) in ca.iter().enumerate() {
            let px = centre_a(i, x);
            for (j, y) in cb.iter().enumerate() {
                least = least.min((px - centre_b(j, y)).norm() - x.radius - y.radius);
            }
        }
        least
    }

    /// Whether conservative advancement's clouds (with culling on) show two bodies more than
    /// the oracle's clearance margin apart.
    fn apart(
        &self,
        a: Option<&Cloud>,
        pose_a: &Isometry3<f64>,
        b: Option<&Cloud>,
        pose_b: &Isometry3<f64>,
        o: &Polyhedra,
    ) -> bool {
        match (a, b) {
            (Some(a), Some(b)) if self.culling => clearance::apart(
                a,
                pose_a,
                b,
                pose_b,
                o.tolerance() * CLEARANCE_PER_TOLERANCE,
            ),
            _ => false,
        }
    }

    fn exempt(&self, a: usize, b: usize) -> bool {
        let pair = (a.min(b), a.max(b));
        !self.arm.self_pairs.contains(&pair)
    }

    /// Link balls placed at these link poses.
    fn balls(&self, poses: &[Isometry3<f64>]) -> Vec<Option<Ball>> {
        self.link_meshes
            .iter()
            .zip(poses)
            .map(|(m, p)| m.as_ref().map(|(_, b)| b.placed(p)))
            .collect()
    }

    /// Whether group configuration `q` collides (self or environment; bounds not checked).
    pub fn collides(&self, q: &[f64], counts: &mut CallCounts) -> Result<bool, RobotError> {
        self.arm.check_config(q, "configuration")?;
        counts.state_checks += 1;
        let poses = self.arm.link_poses(q);
        let balls = self.balls(&poses);
        if self.sure_test && self.surely_collides_at(&poses, &balls) {
            return Ok(true);
        }
        for &(a, b) in &self.arm.self_pairs {
            if let (Some(ba), Some(bb)) = (&balls[a], &balls[b]) {
                if ba.meets(bb) && self.pair_meets(a, b, &poses, counts) {
                    return Ok(true);
                }
            }
        }
        // link by link: a merged body with one open mesh would lose containment for all
        for (l, b) in balls.iter().enumerate() {
            if let Some(b) = b {
                if self.in_environment(l, &poses[l], b, counts) {
                    return Ok(true);
                }
            }
        }
        Ok(false)
    }

    /// Whether group configuration `q` surely collides (the sure test of [`super::inner`]
    /// alone, a few hundred flops): `true` only where [`Self::collides`] is `true`; `false` for
    /// a configuration it cannot place.
    pub fn surely_collides(&self, q: &[f64]) -> bool {
        if !self.sure_test || self.arm.check_config(q, "configuration").is_err() {
            return false;
        }
        let poses = self.arm.link_poses(q);
        let balls = self.balls(&poses);
        self.surely_collides_at(&poses, &balls)
    }

    /// A moment `t` at which moving group joint `joint` by `delta` from `q` surely collides
    /// ([`Self::surely_collides`]), looked for at the move's end and then at halving steps
    /// ([`SURE_MOVE_SAMPLES`] moments): a stair that runs into an obstacle is refused in a few
    /// microseconds instead of by the exact sweep, which would find the same collision. `None`
    /// where the samples find nothing (the move may still collide) or the sure test is off.
    fn surely_collides_along(&self, q: &[f64], joint: usize, delta: f64) -> Option<f64> {
        if !self.sure_test || joint >= q.len() || !delta.is_finite() {
            return None;
        }
        let mut moved = q.to_vec();
        let mut at = |t: f64| {
            moved[joint] = q[joint] + t * delta;
            self.surely_collides(&moved)
        };
        if at(1.0) {
            return Some(1.0);
        }
        let mut k = 2;
        let mut asked = 1;
        while asked < SURE_MOVE_SAMPLES {
            for i in (1..k).step_by(2) {
                let t = i as f64 / k as f64;
                if at(t) {
                    return Some(t);
                }
                asked += 1;
            }
            k *= 2;
        }
        None
    }

    /// The sure test ([`super::inner`]): a link's inner ball reaching into an obstacle's true
    /// shape, or two links' inner balls overlapping. `true` only where [`Self::collides`]'
    /// exact test finds a collision too.
    fn surely_collides_at(&self, poses: &[Isometry3<f64>], balls: &[Option<Ball>]) -> bool {
        self.surely_collides_with(poses, balls, true)
    }

    /// [`Self::surely_collides_at`], the self pairs too or not (`self_pairs`): a straight
    /// motion between free configurations rarely brings one link into another, and its proof
    /// finds that anyway, so its moments skip the pairs' inner balls.
    fn surely_collides_with(
        &self,
        poses: &[Isometry3<f64>],
        balls: &[Option<Ball>],
        self_pairs: bool,
    ) -> bool {
        PlacedBalls::with(&self.inner, poses, |placed| {
            // the links far from the root first: where a moment collides it is mostly the hand
            // or a finger that is in an obstacle (planning instructions: -2.4 %)
            for (l, ball) in balls.iter().enumerate().rev() {
                let Some(ball) = ball else { continue };
                for (ob, solid) in &self.sure_obstacles[l] {
                    // the link's own ball holds its inner balls: if it misses the true shape,
                    // so do they (one placement instead of one per inner ball)
                    if ball.meets(ob) && solid.meets(&ball.centre.into(), ball.radius) {
                        let mine = placed.of(l);
                        if placed.balls[mine].iter().any(|(c, r)| solid.meets(c, *r)) {
                            return true;
                        }
                    }
                }
            }
            self_pairs
                && self
                    .arm
                    .self_pairs
                    .iter()
                    .any(|&(a, b)| self.inner_balls_meet(placed, balls, a, b))
        })
    }

    /// Whether link `l` at `pose` surely reaches into environment part `i`: one of its inner
    /// balls meets the part's true shape (the sure test of one pair: a collision found, never
    /// a guess; `false` where the part has no such shape).
    fn surely_meets_obstacle(&self, l: usize, pose: &Isometry3<f64>, i: usize) -> bool {
        let Some(solid) = &self.solids[i] else {
            return false;
        };
        self.inner[l]
            .iter()
            .any(|b| solid.meets(&(pose * b.centre), b.radius))
    }

    /// Whether links `a` and `b`'s inner balls overlap (the sure test of a self pair).
    fn inner_balls_meet(
        &self,
        placed: &mut PlacedBalls,
        balls: &[Option<Ball>],
        a: usize,
        b: usize,
    ) -> bool {
        if self.inner[a].is_empty() || self.inner[b].is_empty() {
            return false;
        }
        let (Some(ball_a), Some(around)) = (&balls[a], &balls[b]) else {
            return false;
        };
        if !ball_a.meets(around) {
            return false;
        }
        // only a's inner balls that reach into b's ball can meet b's inner balls
        let reaching = |(ca, r): &(Point3<f64>, f64)| {
            let reach = r + around.radius;
            (ca.coords - around.centre).norm_squared() <= reach * reach
        };
        let ra = placed.of(a);
        if !placed.balls[ra.clone()].iter().any(reaching) {
            return false;
        }
        let rb = placed.of(b);
        placed.balls[ra]
            .iter()
            .filter(|x| reaching(x))
            .any(|(ca, ra)| {
                placed.balls[rb.clone()]
                    .iter()
                    .any(|(cb, rb)| (ca - cb).norm_squared() < (ra + rb) * (ra + rb))
            })
    }

    /// What both ways of answering a joint move share: input checks, the distal links, and the
    /// pairs the move keeps (answered statically: `Err` carries the whole of `[0, 1]`).
    fn prepare(
        &self,
        q: &[f64],
        joint: usize,
        delta: f64,
        counts: &mut CallCounts,
    ) -> Result<Result<Prepared, IntervalList>, RobotError> {
        self.arm.check_config(q, "configuration")?;
        let unsupported = |m: String| RobotError::Config {
            what: "joint move".into(),
            message: m,
        };
        let model = &self.arm.model;
        let k = *self
            .arm
            .group
            .joints
            .get(joint)
            .ok_or_else(|| unsupported(format!("no group joint {joint}")))?;
        if !delta.is_finite() {
            return Err(unsupported(format!("the move {delta} is not finite")));
        }
        if (0..model.urdf.joints.len()).any(|m| model.mimic_master[m] == Some(k)) {
            return Err(unsupported(format!(
                "joint {} drives a mimic joint: its distal part does not move rigidly",
                model.urdf.joints[k].name
            )));
        }
        counts.segment_calls += 1;
        let poses = self.arm.link_poses(q);
        // the distal links: the subtree below joint k
        let child = model.joint_links[k].1;
        let mut distal = vec![false; model.urdf.links.len()];
        distal[child] = true;
        for &j in &model.order {
            let (p, c) = model.joint_links[j];
            if distal[p] {
                distal[c] = true;
            }
        }
        let balls = self.balls(&poses);
        let whole = || IntervalList::single(Interval::UNIT);
        // pairs whose relative pose the move keeps: all of [0, 1] or nothing
        for &(a, b) in &self.arm.self_pairs {
            if distal[a] != distal[b] {
                continue;
            }
            if let (Some(ba), Some(bb)) = (&balls[a], &balls[b]) {
                if ba.meets(bb) && self.pair_meets(a, b, &poses, counts) {
                    return Ok(Err(whole()));
                }
            }
        }
        for l in (0..balls.len()).filter(|&l| !distal[l]) {
            if let Some(b) = &balls[l] {
                if self.in_environment(l, &poses[l], b, counts) {
                    return Ok(Err(whole()));
                }
            }
        }
        let frame = poses[child];
        let axis = frame.rotation * model.urdf.joints[k].axis.into_inner();
        let sweep = match model.urdf.joints[k].kind {
            JointKind::Revolute { .. } | JointKind::Continuous => Move::Turn {
                pivot: frame.translation.vector,
                axis,
                angle: delta,
            },
            JointKind::Prismatic { .. } => Move::Slide {
                offset: axis * delta,
            },
            JointKind::Fixed => return Err(unsupported("a fixed joint does not move".into())),
        };
        Ok(Ok(Prepared {
            poses,
            balls,
            distal,
            child,
            sweep,
        }))
    }

    /// The collision intervals, in `t ∈ [0, 1]`, of moving group joint `joint` (an index into
    /// the group) by `delta` from `q`: `q(t) = q + t · delta · e_joint`.
    ///
    /// Every moving link is asked with the oracles built once in [`ArmOracle::new`]: against
    /// the environment in the world, against each proximal link in that link's frame (or the
    /// proximal link turning the other way in the moving link's frame), the joint axis and its
    /// pivot carried into that frame ([`Polyhedra::turn_about`], CHS §2.3.2). Nothing is built
    /// per call but a shifted copy of a link's faces. The oracles share what they find: a
    /// pair of faces whose window an earlier oracle already found colliding is skipped.
    pub fn joint_move(
        &self,
        q: &[f64],
        joint: usize,
        delta: f64,
        counts: &mut CallCounts,
    ) -> Result<IntervalList, RobotError> {
        if !self.culling {
            return self.joint_move_separately(q, joint, delta, counts);
        }
        self.gathered(q, joint, delta, Gather::All, counts, |g| g.to_list())
    }

    /// Whether moving group joint `joint` by `delta` from `q` is free of collision: the
    /// yes/no question of the local method, [`ArmOracle::joint_move`] stopping at the first
    /// collision piece any link finds.
    pub fn joint_move_free(
        &self,
        q: &[f64],
        joint: usize,
        delta: f64,
        counts: &mut CallCounts,
    ) -> Result<bool, RobotError> {
        if !self.culling {
            return Ok(self
                .joint_move_separately(q, joint, delta, counts)?
                .is_empty());
        }
        self.gathered(q, joint, delta, Gather::Any, counts, |g| {
            g.first().is_none()
        })
    }

    /// The first `t ∈ [0, 1]` at which moving group joint `joint` by `delta` from `q` collides
    /// (`None`: the move is free): what a planner that walks along the move until it hits needs.
    /// Once some link's piece is known, later links are only asked about the window before it.
    pub fn joint_move_first_hit(
        &self,
        q: &[f64],
        joint: usize,
        delta: f64,
        counts: &mut CallCounts,
    ) -> Result<Option<f64>, RobotError> {
        if !self.culling {
            let all = self.joint_move_separately(q, joint, delta, counts)?;
            return Ok(all.iter().next().map(|iv| iv.lo));
        }
        self.gathered(q, joint, delta, Gather::First, counts, |g| g.first())
    }

    /// Switches the sure test of [`Self::collides`] ([`super::inner`]) on or off: the same
    /// verdicts either way, only slower off (the reference the tests compare with). On by
    /// default.
    pub fn with_sure_test(mut self, on: bool) -> ArmOracle {
        self.sure_test = on;
        self
    }

    /// Switches the outer sphere covers ([`super::cover`]) on or off: pairs they prove apart
    /// skip the separating planes (static tests and straight motions). The same verdicts
    /// either way, only slower off. On by default.
    pub fn with_covers(mut self, on: bool) -> ArmOracle {
        self.use_covers = on;
        self
    }

    /// Switches the sharing between link oracles (skipped windows, early stops) on or off.
    /// Off, every link oracle answers the whole move on its own, each pair of faces solved in
    /// its whole window (not only where the move is not yet known to collide), and the answers
    /// are merged: the reference the tests and `benches/arm.rs` compare the shared answer
    /// with. On by default.
    pub fn with_culling(mut self, on: bool) -> ArmOracle {
        self.culling = on;
        self
    }

    /// The links of a move and the oracles they ask, in one gathered sweep
    /// ([`Polyhedra::gather`]); `finish` reads the answer.
    fn gathered<R>(
        &self,
        q: &[f64],
        joint: usize,
        delta: f64,
        mode: Gather,
        counts: &mut CallCounts,
        finish: impl FnOnce(&Gathered<'_>) -> R,
    ) -> Result<R, RobotError> {
        let p = self.prepare(q, joint, delta, counts)?;
        // yes/no: before the first exact sweep (a pair that conservative advancement left
        // unproved), a moment of the move that the sure test shows colliding answers at once
        let mut sure_asked = mode != Gather::Any;
        Polyhedra::gather(mode, |g| {
            let p = match p {
                Ok(p) => p,
                Err(_) => {
                    g.add(Interval::UNIT);
                    return Ok(finish(g));
                }
            };
            let (pivot_w, axis_w) = p.pivot_axis();
            // link at `rel` in a frame `into` (world → frame), turning (sliding) with the
            // distal part, or against it when the distal link is the obstacle (`sign` −1)
            let ask = |o: &Polyhedra,
                       rel: &Isometry3<f64>,
                       into: &Isometry3<f64>,
                       sign: f64,
                       window: Interval,
                       g: &mut Gathered<'_>,
                       counts: &mut CallCounts|
             -> Result<(), RobotError> {
                let v = into.rotation * axis_w;
                match p.sweep {
                    Move::Turn { .. } => {
                        let c = into * Point3::from(pivot_w);
                        g.turn_about(
                            o,
                            &se3(rel),
                            [c.x, c.y, c.z],
                            [v.x, v.y, v.z],
                            sign * delta,
                            window,
                            counts,
                        )
                    }
                    Move::Slide { .. } => {
                        let d = v * sign;
                        g.slide(o, &se3(rel), [d.x, d.y, d.z], window, counts)
                    }
                }
                .map_err(joint_move_error)
            };
            self.each_oracle(&p, |o, rel, into, sign, window| {
                if !sure_asked {
                    sure_asked = true;
                    if let Some(t) = self.surely_collides_along(q, joint, delta) {
                        g.add(Interval { lo: t, hi: t });
                        return Ok(false);
                    }
                }
                ask(o, &rel, &into, sign, window, g, counts)?;
                Ok(!g.done())
            })?;
            Ok(finish(g))
        })
    }

    /// Calls `f(oracle, pose, into, sign, window)` for every oracle a moving link must ask
    /// (the environment, with the swept link ball meeting some obstacle's; each proximal link
    /// it is not exempt from, with the balls meeting): the robot placed at `pose` in the frame
    /// `into` maps the world to, turning with the move (`sign` 1) or against it (−1, the
    /// moving link is the obstacle), in the part `window` of `[0, 1]` that conservative
    /// advancement could not prove free ([`clearance`]; with culling off, all of it, and
    /// an oracle proved free throughout is not asked). Stops when `f` answers `false`.
    fn each_oracle(
        &self,
        p: &Prepared,
        mut f: impl FnMut(
            &Polyhedra,
            Isometry3<f64>,
            Isometry3<f64>,
            f64,
            Interval,
        ) -> Result<bool, RobotError>,
    ) -> Result<(), RobotError> {
        let Prepared {
            poses,
            balls,
            distal,
            sweep,
            ..
        } = p;
        for l in (0..balls.len()).filter(|&l| distal[l]) {
            let Some(ball) = &balls[l] else {
                continue;
            };
            let cloud = self.link_clouds[l].as_ref().filter(|_| self.culling);
            let reach = cloud.map(|_| sweep.reach(&ball.centre, ball.radius));
            // the part of the move in which link `l` may meet a body `still` at `at`
            let window = |still: Option<&Cloud>, at: Isometry3<f64>, margin: f64| match (
                cloud, reach, still,
            ) {
                (Some(moving), Some(reach), Some(still)) => {
                    let pair = Pair {
                        moving,
                        from: poses[l],
                        still,
                        at,
                    };
                    clearance::unproved(&pair, sweep, reach, margin)
                }
                _ => Some(Interval::UNIT),
            };
            if let Some(o) = &self.env_oracles[l] {
                let margin = o.tolerance() * CLEARANCE_PER_TOLERANCE;
                let mut hull: Option<Interval> = None;
                for (i, (_, b)) in self.environment.iter().enumerate() {
                    if !may_meet(sweep, ball, b) {
                        continue;
                    }
                    if self.culling && !self.env_boxes[i].may_meet(sweep, ball, margin) {
                        continue;
                    }
                    // the watched deadline per pair as well as inside the exact sweeps: a
                    // pair's planes take microseconds, and a race's losing side stops at once
                    if crate::deadline::watched_expired() {
                        return Err(RobotError::Interrupted);
                    }
                    if let Some(w) =
                        window(self.env_clouds[i].as_ref(), Isometry3::identity(), margin)
                    {
                        hull = Some(hull.map_or(w, |h| Interval {
                            lo: h.lo.min(w.lo),
                            hi: h.hi.max(w.hi),
                        }));
                    }
                    if hull == Some(Interval::UNIT) {
                        break;
                    }
                }
                if let Some(w) = hull {
                    if !f(o, poses[l], Isometry3::identity(), 1.0, w)? {
                        return Ok(());
                    }
                }
            }
            for m in (0..balls.len()).filter(|&m| !distal[m] && !self.exempt(l, m)) {
                let Some(bm) = &balls[m] else {
                    continue;
                };
                if !may_meet(sweep, ball, bm) {
                    continue;
                }
                let Some(o) = self.pair_oracles.get(&(l.min(m), l.max(m))) else {
                    continue;
                };
                let margin = o.tolerance() * CLEARANCE_PER_TOLERANCE;
                if crate::deadline::watched_expired() {
                    return Err(RobotError::Interrupted);
                }
                let Some(w) = window(self.link_clouds[m].as_ref(), poses[m], margin) else {
                    continue;
                };
                let go = if l < m {
                    let into = poses[m].inverse();
                    f(o, into * poses[l], into, 1.0, w)?
                } else {
                    let into = poses[l].inverse();
                    f(o, into * poses[m], into, -1.0, w)?
                };
                if !go {
                    return Ok(());
                }
            }
        }
        Ok(())
    }

    /// [`ArmOracle::joint_move`] without sharing: every link oracle answers the whole move on
    /// its own, the answers merged.
    fn joint_move_separately(
        &self,
        q: &[f64],
        joint: usize,
        delta: f64,
        counts: &mut CallCounts,
    ) -> Result<IntervalList, RobotError> {
        let p = match self.prepare(q, joint, delta, counts)? {
            Ok(p) => p,
            Err(whole) => return Ok(whole),
        };
        let (pivot_w, axis_w) = p.pivot_axis();
        let mut answer = IntervalList::new();
        self.each_oracle(&p, |o, rel, into, sign, _| {
            let v = into.rotation * axis_w;
            let r = match p.sweep {
                Move::Turn { .. } => {
                    let c = into * Point3::from(pivot_w);
                    Polyhedra::gather_unclipped(Gather::All, |g| {
                        g.turn_about(
                            o,
                            &se3(&rel),
                            [c.x, c.y, c.z],
                            [v.x, v.y, v.z],
                            sign * delta,
                            Interval::UNIT,
                            counts,
                        )?;
                        Ok(g.to_list())
                    })
                }
                Move::Slide { .. } => {
                    let d = v * sign;
                    o.intervals(
                        &Motion::segment(
                            se3(&rel),
                            Change::Linear(vec![d.x, d.y, d.z, 0.0, 0.0, 0.0, 0.0]),
                        ),
                        counts,
                    )
                }
            }
            .map_err(joint_move_error)?;
            answer = answer.union(&r);
            Ok(true)
        })?;
        Ok(answer)
    }

    /// [`ArmOracle::joint_move`] the way it was first answered: one [`Polyhedra`] built per
    /// call and moving link, its body expressed in the joint's child frame, among the culled
    /// environment and proximal links. Slow (milliseconds a move); kept as the reference the
    /// tests and `benches/arm.rs` compare the pivoted answer with.
    pub fn joint_move_rebuilt(
        &self,
        q: &[f64],
        joint: usize,
        delta: f64,
        counts: &mut CallCounts,
    ) -> Result<IntervalList, RobotError> {
        let p = match self.prepare(q, joint, delta, counts)? {
            Ok(p) => p,
            Err(whole) => return Ok(whole),
        };
        let Prepared {
            poses,
            balls,
            distal,
            child,
            sweep,
        } = p;
        let frame = poses[child];
        let change = match &sweep {
            Move::Turn { axis, angle, .. } => Change::Rotation {
                axis: [axis.x, axis.y, axis.z],
                angle: *angle,
            },
            Move::Slide { offset: d } => Change::Linear(vec![d.x, d.y, d.z, 0.0, 0.0, 0.0, 0.0]),
        };
        // the moving part, link by link, in the joint's child frame at q
        let motion = Motion::segment(se3(&frame), change);
        let to_frame = frame.inverse();
        let mut answer = IntervalList::new();
        let solve = |o: &Polyhedra, motion: &Motion, counts: &mut CallCounts| {
            o.intervals(motion, counts).map_err(joint_move_error)
        };
        for l in (0..balls.len()).filter(|&l| distal[l]) {
            let (Some((mesh, _)), Some(ball)) = (&self.link_meshes[l], &balls[l]) else {
                continue;
            };
            let near_env = self
                .environment
                .iter()
                .any(|(_, b)| may_meet(&sweep, ball, b));
            let mut obstacles: Vec<TriMesh> = Vec::new();
            if l == child {
                // the link's frame is the joint frame: the cached oracle answers the move
                if near_env {
                    if let Some(o) = &self.env_oracles[l] {
                        answer = answer.union(&solve(o, &motion, counts)?);
                    }
                }
            } else if near_env {
                obstacles.extend(
                    self.environment
                        .iter()
                        .filter(|(_, b)| may_meet(&sweep, ball, b))
                        .map(|(m, _)| m.clone()),
                );
            }
            for m in (0..balls.len()).filter(|&m| !distal[m] && !self.exempt(l, m)) {
                if let (Some((mesh_m, _)), Some(bm)) = (&self.link_meshes[m], &balls[m]) {
                    if may_meet(&sweep, ball, bm) {
                        obstacles.push(placed(mesh_m, &poses[m]));
                    }
                }
            }
            if obstacles.is_empty() {
                continue;
            }
            let body = placed(mesh, &(to_frame * poses[l]));
            answer = answer.union(&solve(&Polyhedra::new(body, obstacles), &motion, counts)?);
        }
        Ok(answer)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Unit, UnitQuaternion};
    use rand::{Rng, SeedableRng};

    /// Vectors with coordinates uniform in `[-1, 1)`, from a seeded stream.
    fn random_vectors(seed: u64) -> impl FnMut() -> Vector3<f64> {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        move || {
            Vector3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            )
        }
    }

    /// The swept-ball cull never rules out a pair whose balls meet somewhere along the arc
    /// (sampled finely), and rules out most pairs that never come near.
    #[test]
    fn arc_cull_is_conservative() {
        let mut v = random_vectors(3);
        let (mut culled, mut meets) = (0, 0);
        for _ in 0..3000 {
            let axis = Unit::new_normalize(v());
            let origin = v();
            let m = Ball {
                centre: v(),
                radius: 0.1,
            };
            let o = Ball {
                centre: v(),
                radius: 0.1,
            };
            let angle = 8.0 * (v().x);
            let sweep = Move::Turn {
                pivot: origin,
                axis: axis.into_inner(),
                angle,
            };
            let touched = (0..=2000).any(|k| {
                let phi = angle * k as f64 / 2000.0;
                let c = UnitQuaternion::from_axis_angle(&axis, phi) * (m.centre - origin) + origin;
                (c - o.centre).norm() <= m.radius + o.radius
            });
            let may = may_meet(&sweep, &m, &o);
            assert!(may || !touched, "{axis:?} {origin:?} {angle}");
            meets += usize::from(touched);
            culled += usize::from(!may);
        }
        assert!(meets > 50 && culled > 1000, "{meets} {culled}");
    }

    /// The swept ball against an obstacle's box in its own frame: never ruled out where the
    /// ball, turned or slid (sampled finely), comes within the margin of the box; most pairs
    /// that stay away ruled out.
    #[test]
    fn obstacle_box_cull_is_conservative() {
        let mut v = random_vectors(4);
        let margin = 1e-3;
        let (mut culled, mut meets) = (0, 0);
        for k in 0..3000 {
            let pose = Isometry3::new(v(), v() * 3.0);
            let half = v().abs() * 0.3 + Vector3::repeat(0.01);
            let local = TriMesh::cuboid([half.x, half.y, half.z]).unwrap();
            let obstacle = ObstacleBox::of(&local, &pose);
            let m = Ball {
                centre: v(),
                radius: 0.05,
            };
            let (sweep, at): (Move, Box<dyn Fn(f64) -> Vector3<f64>>) = if k % 3 == 0 {
                let offset = v();
                let c = m.centre;
                (Move::Slide { offset }, Box::new(move |t| c + offset * t))
            } else {
                let axis = Unit::new_normalize(v());
                let pivot = v();
                let angle = 8.0 * v().x;
                let c = m.centre;
                let turn = Move::Turn {
                    pivot,
                    axis: axis.into_inner(),
                    angle,
                };
                let at = move |t: f64| {
                    UnitQuaternion::from_axis_angle(&axis, angle * t) * (c - pivot) + pivot
                };
                (turn, Box::new(at))
            };
            let touched = (0..=2000).any(|i| {
                let p = pose.inverse() * Point3::from(at(i as f64 / 2000.0));
                let out = (p.coords.abs() - half).map(|d| d.max(0.0));
                out.norm() <= m.radius + margin
            });
            let may = obstacle.may_meet(&sweep, &m, margin);
            assert!(may || !touched, "{sweep:?} {pose:?} {half:?}");
            meets += usize::from(touched);
            culled += usize::from(!may);
        }
        assert!(meets > 100 && culled > 1000, "{meets} {culled}");
    }
}
