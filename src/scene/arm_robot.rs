//! An arm in its environment, what an arm scene's robot is, and its collision oracle.

use super::fnv::Fnv;
use super::moveit::{placed_objects, CollisionObject};
use crate::fast_hash::FastMap;
use crate::interval::{Interval, IntervalList};
use crate::oracle::{CallCounts, CollisionOracle, OracleError};
use crate::robot::{Arm, ArmOracle, RobotError};
use crate::space::{Change, Motion};
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

/// An arm in its environment: what a [`Robot::Arm`](super::Robot::Arm) scene holds. The arm has its
/// other joints, base and allowed-collision exemptions set; `objects` are the environment as read
/// (exact shapes, for the independent checker and for drawing).
#[derive(Clone, Debug)]
pub struct ArmRobot {
    /// The arm, ready for planning.
    pub arm: Arm,
    /// The environment's collision objects.
    pub objects: Vec<CollisionObject>,
    /// The URDF file.
    pub urdf: PathBuf,
    /// The SRDF file, if any.
    pub srdf: Option<PathBuf>,
    /// The PlanningScene file, if any.
    pub moveit_scene: Option<PathBuf>,
    oracle: Arc<ArmOracle>,
    digest: u64,
}

/// Two arm scenes are equal when what decides their collisions is (the fingerprint's data).
impl PartialEq for ArmRobot {
    fn eq(&self, other: &Self) -> bool {
        self.digest == other.digest
    }
}

impl ArmRobot {
    /// Builds the exact oracle for `arm` among `objects` (once: it is shared by every
    /// [`Scene::oracle`](super::Scene::oracle) call) and the digest of its geometry.
    pub fn new(
        arm: Arm,
        objects: Vec<CollisionObject>,
        urdf: PathBuf,
        srdf: Option<PathBuf>,
        moveit_scene: Option<PathBuf>,
    ) -> Result<ArmRobot, RobotError> {
        // in the world frame once, for the digest and for drawing
        let objects = placed_objects(&objects, &arm)?;
        let oracle = Arc::new(ArmOracle::new(&arm, &objects)?);
        let digest = digest(&arm, &objects);
        Ok(ArmRobot {
            arm,
            objects,
            urdf,
            srdf,
            moveit_scene,
            oracle,
            digest,
        })
    }

    /// The exact single-joint oracle.
    pub fn arm_oracle(&self) -> &Arc<ArmOracle> {
        &self.oracle
    }

    /// A 64-bit digest of everything that decides collisions: link geometry and its origins,
    /// the group's joints, the other joints' values, the base pose, the self-collision pairs
    /// and the environment's polytopes.
    pub fn digest(&self) -> u64 {
        self.digest
    }
}

fn digest(arm: &Arm, objects: &[CollisionObject]) -> u64 {
    let mut h = Fnv::new();
    h.str("arm");
    let names = arm.group_joint_names();
    h.bytes(&(names.len() as u64).to_le_bytes());
    names.iter().for_each(|n| h.str(n));
    h.floats(&arm.values);
    let iso = |h: &mut Fnv, p: &nalgebra::Isometry3<f64>| {
        let t = p.translation.vector;
        let r = p.rotation.coords;
        h.floats(&[t.x, t.y, t.z, r[0], r[1], r[2], r[3]]);
    };
    iso(&mut h, &arm.base);
    for s in &arm.shapes {
        h.bytes(&(s.link as u64).to_le_bytes());
        iso(&mut h, &s.origin);
        h.mesh(&s.polytope);
    }
    for &(a, b) in &arm.self_pairs {
        h.bytes(&(a as u64).to_le_bytes());
        h.bytes(&(b as u64).to_le_bytes());
    }
    // the kinematics: joint origins and axes
    for j in &arm.model.urdf.joints {
        iso(&mut h, &j.origin);
        h.floats(&[j.axis.x, j.axis.y, j.axis.z]);
    }
    for o in objects {
        for (pose, shape) in &o.parts {
            iso(&mut h, pose);
            h.str(&format!("{shape:?}"));
        }
    }
    h.finish()
}

/// The collision oracle of an arm scene (wrapped in [`crate::oracle::Bounded`] by
/// [`Scene::oracle`](super::Scene::oracle)): single-joint motions exactly, configurations
/// statically.
///
/// Answers of single-joint moves are kept: the via-point search asks about a
/// fifth of its moves again, the same question bit for bit (the same joint over its whole range
/// from the same base point, say), and such a repeat is answered with the kept answer, which
/// is the answer (`tests/arm_plan.rs` compares with an oracle that keeps nothing). A kept
/// answer that the move is free also answers the other questions about it
/// (`Answers::free`). Static checks of configurations are kept too, by their bits.
pub struct ArmCollision {
    oracle: Arc<ArmOracle>,
    answers: Option<Mutex<Answers>>,
}

/// A single-joint move by its bits: only the same move gets a kept answer.
#[derive(Hash, PartialEq, Eq)]
struct Key {
    joint: usize,
    q0: Vec<u64>,
    amount: u64,
}

/// Kept answers of one oracle, per question, in the move's own parameter (`t ∈ [0, 1]` of
/// `q0 + t · amount · e_joint`); forgotten all at once when [`Answers::CAPACITY`] is reached
/// (a bound on memory: a planner's repeats come soon after the first question).
#[derive(Default)]
struct Answers {
    intervals: FastMap<Key, IntervalList>,
    free: FastMap<Key, bool>,
    first_hit: FastMap<Key, Option<f64>>,
    /// Static checks by the configuration's bits: a workcell's queries start from the same
    /// home pose, each query checks it again, and a static check near contact (a grasp pose
    /// beside its object) costs several single-joint moves.
    states: FastMap<Vec<u64>, bool>,
    /// Straight motions of several joints by the bits of both ends: proved free or not.
    straight: FastMap<Vec<u64>, bool>,
}

impl Answers {
    const CAPACITY: usize = 1 << 14;

    fn len(&self) -> usize {
        self.intervals.len()
            + self.free.len()
            + self.first_hit.len()
            + self.states.len()
            + self.straight.len()
    }

    /// Whether the move is free, as far as any kept answer about it says: the three questions
    /// agree on that (empty intervals, yes, no first hit — `tests/arm_oracle.rs` holds the arm
    /// oracle to it), so a query's yes/no question after the learner asked the intervals of
    /// the same move, or the intervals of a move shortening found free, costs no sweep.
    fn free(&self, key: &Key) -> Option<bool> {
        self.free
            .get(key)
            .copied()
            .or_else(|| self.intervals.get(key).map(IntervalList::is_empty))
            .or_else(|| self.first_hit.get(key).map(Option::is_none))
    }
}

/// One question about a single-joint move: where its kept answers live, and what the kept
/// answers of the other questions say of it ([`Answers::free`]). Only what all three agree on
/// is taken from another question: that the move is free (and for yes/no, that it is not),
/// never where a collision lies.
struct Question<T> {
    own: fn(&mut Answers) -> &mut FastMap<Key, T>,
    from_free: fn(bool) -> Option<T>,
}

impl ArmCollision {
    /// The oracle answering with `oracle`, keeping its answers.
    pub fn new(oracle: Arc<ArmOracle>) -> Self {
        ArmCollision {
            oracle,
            answers: Some(Mutex::new(Answers::default())),
        }
    }

    /// Switches keeping answers on or off (on by default). Off, every question is answered
    /// by the arm oracle: the reference of the tests.
    pub fn with_kept_answers(mut self, on: bool) -> Self {
        self.answers = on.then(|| Mutex::new(Answers::default()));
        self
    }

    /// The kept answer to question `q` about this move (its own, or what another question's
    /// kept answer implies), or `ask`'s, kept.
    fn kept<T: Clone>(
        &self,
        q: Question<T>,
        q0: &[f64],
        joint: usize,
        amount: f64,
        ask: impl FnOnce() -> Result<T, RobotError>,
    ) -> Result<T, OracleError> {
        let key = Key {
            joint,
            q0: q0.iter().map(|v| v.to_bits()).collect(),
            amount: amount.to_bits(),
        };
        self.remember(
            q.own,
            key,
            |kept, key| kept.free(key).and_then(q.from_free),
            ask,
        )
        .map_err(Self::oracle_error)
    }

    /// Whether configuration `q` collides: the kept answer, or the arm oracle's, kept.
    fn static_hit(&self, q: &[f64], counts: &mut CallCounts) -> Result<bool, RobotError> {
        let key = q.iter().map(|v| v.to_bits()).collect();
        self.remember(
            |a| &mut a.states,
            key,
            |_, _| None,
            || self.oracle.collides(q, counts),
        )
    }

    /// The answer kept under `key` in the map `own` picks, else what `implied` reads from the
    /// other kept answers, else `ask`'s, kept (all answers are forgotten at once when
    /// [`Answers::CAPACITY`] is reached). Without kept answers, `ask`'s.
    fn remember<K: std::hash::Hash + Eq, T: Clone>(
        &self,
        own: fn(&mut Answers) -> &mut FastMap<K, T>,
        key: K,
        implied: impl FnOnce(&Answers, &K) -> Option<T>,
        ask: impl FnOnce() -> Result<T, RobotError>,
    ) -> Result<T, RobotError> {
        let Some(answers) = &self.answers else {
            return ask();
        };
        // a poisoned lock only means another thread panicked while holding it: the map is
        // consistent (inserts and clears are single calls)
        let lock = || answers.lock().unwrap_or_else(|e| e.into_inner());
        {
            let mut kept = lock();
            if let Some(a) = own(&mut kept).get(&key) {
                return Ok(a.clone());
            }
            if let Some(a) = implied(&kept, &key) {
                return Ok(a);
            }
        }
        let a = ask()?;
        let mut kept = lock();
        if kept.len() >= Answers::CAPACITY {
            *kept = Answers::default();
        }
        own(&mut kept).insert(key, a.clone());
        Ok(a)
    }

    /// The arm oracle's error as the scene oracle's: interrupted stays interrupted
    /// ([`crate::deadline::watching`]), anything else is a motion the arm cannot answer.
    fn oracle_error(e: RobotError) -> OracleError {
        match e {
            RobotError::Interrupted => OracleError::Interrupted,
            e => OracleError::Unsupported(e.to_string()),
        }
    }

    /// What a motion asks of the arm: a static check, or one joint moving from a
    /// configuration by an amount over the parameter range.
    fn resolve(motion: &Motion) -> Result<Move, OracleError> {
        let Change::Linear(delta) = &motion.change else {
            return Err(OracleError::Unsupported(
                "an arm moves its joints, not a rigid-body rotation".into(),
            ));
        };
        let mut moving = delta.iter().enumerate().filter(|(_, d)| **d != 0.0);
        let first = moving.next();
        let range = motion.range;
        if moving.next().is_some() {
            if !(range.lo.is_finite() && range.hi.is_finite()) {
                return Err(OracleError::Unsupported(
                    "an unbounded motion of several joints".into(),
                ));
            }
            let at = |t: f64| -> Vec<f64> {
                motion
                    .origin
                    .iter()
                    .zip(delta)
                    .map(|(q, d)| q + t * d)
                    .collect()
            };
            return Ok(Move::Straight {
                q0: at(range.lo),
                q1: at(range.hi),
            });
        }
        let Some((j, &d)) = first else {
            return Ok(Move::Static(motion.origin.clone()));
        };
        if !(range.lo.is_finite() && range.hi.is_finite()) {
            return Err(OracleError::Unsupported(
                "an unbounded joint motion (the scene's bounds clip lines to the joint limits)"
                    .into(),
            ));
        }
        let mut q0 = motion.origin.clone();
        q0[j] += range.lo * d;
        let span = range.hi - range.lo;
        if span == 0.0 {
            return Ok(Move::Static(q0));
        }
        Ok(Move::Joint {
            q0,
            joint: j,
            amount: span * d,
        })
    }

    fn answer(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<IntervalList, OracleError> {
        let range = motion.range;
        match Self::resolve(motion)? {
            Move::Static(q) => {
                let hit = self.static_hit(&q, counts).map_err(Self::oracle_error)?;
                Ok(if hit {
                    IntervalList::single(range)
                } else {
                    IntervalList::new()
                })
            }
            Move::Straight { .. } => Err(only_yes_no()),
            Move::Joint { q0, joint, amount } => {
                let hits = self.kept(
                    Question {
                        own: |a| &mut a.intervals,
                        from_free: |free| free.then(IntervalList::new),
                    },
                    &q0,
                    joint,
                    amount,
                    || self.oracle.joint_move(&q0, joint, amount, counts),
                )?;
                let span = range.hi - range.lo;
                let mapped: Vec<Interval> = hits
                    .iter()
                    .map(|iv| Interval {
                        lo: range.lo + iv.lo * span,
                        hi: range.lo + iv.hi * span,
                    })
                    .collect();
                Ok(IntervalList::from_unsorted(mapped).into_clipped(range))
            }
        }
    }
}

/// A motion as the arm sees it.
enum Move {
    /// Nothing moves: a static check of this configuration.
    Static(Vec<f64>),
    /// Group joint `joint` moves by `amount` from `q0` over the whole parameter range.
    Joint {
        q0: Vec<f64>,
        joint: usize,
        amount: f64,
    },
    /// Several joints move at once, straight from `q0` to `q1`: certified free or not
    /// ([`ArmOracle::straight_free`]), no intervals.
    Straight { q0: Vec<f64>, q1: Vec<f64> },
}

/// What the arm answers of a motion of several joints: only whether it is proved free.
fn only_yes_no() -> OracleError {
    OracleError::Unsupported(
        "an arm motion of several joints at once is only certified free or not (CHS §1.5: \
         intervals are asked one joint at a time)"
            .into(),
    )
}

impl CollisionOracle for ArmCollision {
    fn intervals(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<IntervalList, OracleError> {
        // the arm oracle counts its own calls; here only its pair tests are kept, the caller
        // (CountedOracle) counts the call
        let mut own = CallCounts::default();
        let r = self.answer(motion, &mut own);
        counts.pairs_tested += own.pairs_tested;
        r
    }

    /// The yes/no question stops at the first collision any link finds
    /// ([`ArmOracle::joint_move_free`]).
    fn motion_is_free(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<bool, OracleError> {
        let mut own = CallCounts::default();
        let r = match Self::resolve(motion) {
            Ok(Move::Joint { q0, joint, amount }) => self.kept(
                Question {
                    own: |a| &mut a.free,
                    from_free: Some,
                },
                &q0,
                joint,
                amount,
                || self.oracle.joint_move_free(&q0, joint, amount, &mut own),
            ),
            Ok(Move::Static(q)) => self
                .static_hit(&q, &mut own)
                .map(|hit| !hit)
                .map_err(Self::oracle_error),
            Ok(Move::Straight { q0, q1 }) => {
                let key = q0.iter().chain(&q1).map(|v| v.to_bits()).collect();
                self.remember(
                    |a| &mut a.straight,
                    key,
                    |_, _| None,
                    || self.oracle.straight_free(&q0, &q1, &mut own),
                )
                .map_err(Self::oracle_error)
            }
            Err(e) => Err(e),
        };
        counts.pairs_tested += own.pairs_tested;
        r
    }

    /// Only the window before the earliest piece found is searched further
    /// ([`ArmOracle::joint_move_first_hit`]).
    fn first_collision(
        &self,
        motion: &Motion,
        counts: &mut CallCounts,
    ) -> Result<Option<f64>, OracleError> {
        let mut own = CallCounts::default();
        let range = motion.range;
        let r = match Self::resolve(motion) {
            Ok(Move::Joint { q0, joint, amount }) => self
                .kept(
                    Question {
                        own: |a| &mut a.first_hit,
                        from_free: |free| free.then_some(None),
                    },
                    &q0,
                    joint,
                    amount,
                    || {
                        self.oracle
                            .joint_move_first_hit(&q0, joint, amount, &mut own)
                    },
                )
                .map(|t| {
                    t.map(|t| (range.lo + t * (range.hi - range.lo)).clamp(range.lo, range.hi))
                }),
            Ok(Move::Static(q)) => self
                .static_hit(&q, &mut own)
                .map(|hit| hit.then_some(range.lo))
                .map_err(Self::oracle_error),
            Ok(Move::Straight { .. }) => Err(only_yes_no()),
            Err(e) => Err(e),
        };
        counts.pairs_tested += own.pairs_tested;
        r
    }

    fn collides(&self, q: &[f64], counts: &mut CallCounts) -> bool {
        let mut own = CallCounts::default();
        // a configuration of the wrong shape cannot be placed: it counts as collision
        let hit = self.static_hit(q, &mut own).unwrap_or(true);
        counts.pairs_tested += own.pairs_tested;
        hit
    }

    fn surely_collides(&self, q: &[f64]) -> Option<bool> {
        Some(self.oracle.surely_collides(q))
    }
}
