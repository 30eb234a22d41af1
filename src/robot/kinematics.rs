//! The kinematic tree of a URDF, forward kinematics, and planning groups.
//!
//! `T(child) = T(parent) · origin · motion(value)`: revolute and continuous joints rotate about
//! their axis, prismatic joints translate along it, fixed joints do nothing, a mimic joint
//! follows its master. A **planning group** (CHS §1.5: the DOF groups of an arm are its single
//! joints) picks the moving joints; every other joint keeps a given value.

use super::srdf::{GroupSpec, Srdf};
use super::urdf::{JointKind, Urdf};
use super::RobotError;
use nalgebra::{Isometry3, Quaternion, Translation3, Unit, UnitQuaternion, Vector3};
use std::collections::{HashMap, HashSet};
use std::f64::consts::PI;
use std::path::Path;

/// The kinematic tree: links and joints of a URDF, checked to form one tree.
#[derive(Clone, Debug)]
pub struct Model {
    /// The parsed URDF.
    pub urdf: Urdf,
    /// Index of the root link (the one no joint has as child).
    pub root: usize,
    /// Per link: the index of the joint whose child it is (none for the root).
    pub parent_joint: Vec<Option<usize>>,
    /// Per joint: parent and child link indices.
    pub joint_links: Vec<(usize, usize)>,
    /// Joints in an order where every joint comes after the joint of its parent link
    /// (depth first from the root, children in file order).
    pub order: Vec<usize>,
    /// Per joint: the index of its mimic master, if any.
    pub mimic_master: Vec<Option<usize>>,
    /// Per link: how many joints of [`Self::order`] place it and every link above it (a
    /// prefix of the order: depth first, the joints above a link come before its own).
    pub order_prefix: Vec<usize>,
    /// Per joint of [`Self::order`], how it places its child link.
    placements: Vec<Placement>,
    link_index: HashMap<String, usize>,
    joint_index: HashMap<String, usize>,
}

/// A resolved planning group: the moving joints in root-to-tip order and their bounds.
#[derive(Clone, Debug, PartialEq)]
pub struct Group {
    /// The group's name (the SRDF's, or `"custom"`).
    pub name: String,
    /// Joint indices into [`Model::urdf`]`.joints`.
    pub joints: Vec<usize>,
    /// Lower bound per group joint (continuous joints: −π).
    pub lower: Vec<f64>,
    /// Upper bound per group joint (continuous joints: π).
    pub upper: Vec<f64>,
}

/// How one joint of [`Model::order`] places its child link, resolved once: forward kinematics
/// runs at every moment a sure test or a proof looks at, thousands of times per arm query, so
/// the joint's kind, where its value comes from and which products are by an identity are not
/// looked up per call.
#[derive(Clone, Debug)]
struct Placement {
    parent: usize,
    child: usize,
    origin: Isometry3<f64>,
    /// Whether the origin rotates or shifts: the products by an identity are skipped (they
    /// would give the same bits).
    origin_turns: bool,
    origin_shifts: bool,
    value: Value,
    motion: Motion,
}

/// Where a joint's value comes from.
#[derive(Clone, Copy, Debug)]
enum Value {
    Own(usize),
    /// `multiplier · master + offset`; a fixed master (`None`) stays at 0.
    Mimic {
        master: Option<usize>,
        multiplier: f64,
        offset: f64,
    },
}

/// What a joint's value does to its child.
#[derive(Clone, Copy, Debug)]
enum Motion {
    Fixed,
    /// A rotation about `±z` (this sign), as most arms' joints are: its quaternion is
    /// `(cos, 0, 0, ±sin)` of the half angle, and the product skips the zero terms (the same
    /// bits as the full product).
    TurnZ(f64),
    Turn(Unit<Vector3<f64>>),
    Slide(Vector3<f64>),
}

impl Placement {
    fn new(urdf: &Urdf, k: usize, (parent, child): (usize, usize), mimic: Option<usize>) -> Self {
        let j = &urdf.joints[k];
        let value = match (mimic, &j.mimic) {
            (Some(m), Some(mimic)) => Value::Mimic {
                master: urdf.joints[m].kind.is_movable().then_some(m),
                multiplier: mimic.multiplier,
                offset: mimic.offset,
            },
            _ => Value::Own(k),
        };
        let axis = j.axis.into_inner();
        let motion = match j.kind {
            JointKind::Revolute { .. } | JointKind::Continuous => {
                if axis.x == 0.0 && axis.y == 0.0 && axis.z.abs() == 1.0 {
                    Motion::TurnZ(axis.z)
                } else {
                    Motion::Turn(j.axis)
                }
            }
            JointKind::Prismatic { .. } => Motion::Slide(axis),
            JointKind::Fixed => Motion::Fixed,
        };
        Placement {
            parent,
            child,
            origin: j.origin,
            origin_turns: j.origin.rotation != UnitQuaternion::identity(),
            origin_shifts: j.origin.translation.vector != Vector3::zeros(),
            value,
            motion,
        }
    }

    /// The child's pose, `parent · origin · motion(value)`.
    fn place(&self, parent: &Isometry3<f64>, values: &[f64]) -> Isometry3<f64> {
        let mut shift = parent.translation.vector;
        if self.origin_shifts {
            shift += parent.rotation * self.origin.translation.vector;
        }
        let mut turn = parent.rotation;
        if self.origin_turns {
            turn *= self.origin.rotation;
        }
        let value = || match self.value {
            Value::Own(k) => values[k],
            Value::Mimic {
                master,
                multiplier,
                offset,
            } => multiplier * master.map_or(0.0, |m| values[m]) + offset,
        };
        match self.motion {
            Motion::Fixed => {}
            Motion::TurnZ(sign) => {
                let (s, c) = (value() / 2.0).sin_cos();
                let z = sign * s;
                let a = turn.quaternion();
                turn = Unit::new_unchecked(Quaternion::new(
                    a.w * c - a.k * z,
                    a.i * c + a.j * z,
                    a.j * c - a.i * z,
                    a.w * z + a.k * c,
                ));
            }
            Motion::Turn(axis) => turn *= UnitQuaternion::from_axis_angle(&axis, value()),
            Motion::Slide(axis) => shift += turn * (axis * value()),
        }
        Isometry3::from_parts(Translation3::from(shift), turn)
    }
}

impl Model {
    /// Builds the tree and checks it: every joint names existing links, no link has two
    /// parents, exactly one root, no cycle, mimic masters exist and are movable.
    pub fn new(urdf: Urdf, path: &Path) -> Result<Model, RobotError> {
        let invalid = |message: String| RobotError::Invalid {
            path: path.to_path_buf(),
            message,
        };
        let link_index: HashMap<String, usize> = urdf
            .links
            .iter()
            .enumerate()
            .map(|(i, l)| (l.name.clone(), i))
            .collect();
        let joint_index: HashMap<String, usize> = urdf
            .joints
            .iter()
            .enumerate()
            .map(|(i, j)| (j.name.clone(), i))
            .collect();
        let mut parent_joint: Vec<Option<usize>> = vec![None; urdf.links.len()];
        let mut joint_links = Vec::with_capacity(urdf.joints.len());
        for (k, j) in urdf.joints.iter().enumerate() {
            let find = |name: &str| {
                link_index.get(name).copied().ok_or_else(|| {
                    invalid(format!("joint {} names an unknown link {name}", j.name))
                })
            };
            let (p, c) = (find(&j.parent)?, find(&j.child)?);
            if let Some(other) = parent_joint[c] {
                return Err(invalid(format!(
                    "link {} is the child of two joints ({} and {})",
                    j.child, urdf.joints[other].name, j.name
                )));
            }
            parent_joint[c] = Some(k);
            joint_links.push((p, c));
        }
        let roots: Vec<usize> = (0..urdf.links.len())
            .filter(|&l| parent_joint[l].is_none())
            .collect();
        let [root] = roots[..] else {
            if roots.is_empty() {
                return Err(invalid(cycle_message(&urdf, &parent_joint, &joint_links)));
            }
            let names: Vec<&str> = roots.iter().map(|&l| urdf.links[l].name.as_str()).collect();
            return Err(invalid(format!(
                "the links must form one tree; these have no parent joint: {names:?}"
            )));
        };
        // depth-first order from the root; a cycle leaves joints unreached
        let mut children: Vec<Vec<usize>> = vec![Vec::new(); urdf.links.len()];
        for (k, &(p, _)) in joint_links.iter().enumerate() {
            children[p].push(k);
        }
        let mut order = Vec::with_capacity(urdf.joints.len());
        let mut stack: Vec<usize> = children[root].iter().rev().copied().collect();
        while let Some(k) = stack.pop() {
            order.push(k);
            stack.extend(children[joint_links[k].1].iter().rev());
        }
        if order.len() != urdf.joints.len() {
            return Err(invalid(cycle_message(&urdf, &parent_joint, &joint_links)));
        }
        let mut mimic_master = vec![None; urdf.joints.len()];
        for (k, j) in urdf.joints.iter().enumerate() {
            // a fixed joint never moves, whatever it mimics (VAMP's Panda keeps the fingers'
            // <mimic> on fixed joints)
            if let Some(m) = j.mimic.as_ref().filter(|_| j.kind.is_movable()) {
                let master = *joint_index.get(&m.joint).ok_or_else(|| {
                    invalid(format!(
                        "joint {} mimics an unknown joint {}",
                        j.name, m.joint
                    ))
                })?;
                if urdf.joints[master].mimic.is_some() && urdf.joints[master].kind.is_movable() {
                    return Err(invalid(format!(
                        "joint {} mimics {}, which is itself a mimic",
                        j.name, m.joint
                    )));
                }
                mimic_master[k] = Some(master);
            }
        }
        let mut order_prefix = vec![0; urdf.links.len()];
        for (at, &k) in order.iter().enumerate() {
            order_prefix[joint_links[k].1] = at + 1;
        }
        let placements = order
            .iter()
            .map(|&k| Placement::new(&urdf, k, joint_links[k], mimic_master[k]))
            .collect();
        Ok(Model {
            urdf,
            root,
            parent_joint,
            joint_links,
            order,
            mimic_master,
            order_prefix,
            placements,
            link_index,
            joint_index,
        })
    }

    /// Index of the link called `name`.
    pub fn link(&self, name: &str) -> Option<usize> {
        self.link_index.get(name).copied()
    }

    /// Index of the joint called `name`.
    pub fn joint(&self, name: &str) -> Option<usize> {
        self.joint_index.get(name).copied()
    }

    /// The motion of joint `k` at `value`: a rotation about or a translation along its axis.
    pub fn joint_motion(&self, k: usize, value: f64) -> Isometry3<f64> {
        let j = &self.urdf.joints[k];
        match j.kind {
            JointKind::Revolute { .. } | JointKind::Continuous => Isometry3::from_parts(
                Translation3::identity(),
                UnitQuaternion::from_axis_angle(&j.axis, value),
            ),
            JointKind::Prismatic { .. } => Isometry3::from_parts(
                Translation3::from(j.axis.into_inner() * value),
                UnitQuaternion::identity(),
            ),
            JointKind::Fixed => Isometry3::identity(),
        }
    }

    /// World poses of all links for one value per joint (`values[k]` for joint `k`; fixed
    /// joints' values are ignored, mimic joints take `multiplier · master + offset`), with
    /// the root link at `base`.
    pub fn link_poses(&self, base: &Isometry3<f64>, values: &[f64]) -> Vec<Isometry3<f64>> {
        let mut poses = vec![Isometry3::identity(); self.urdf.links.len()];
        self.link_poses_into(base, values, &mut poses);
        poses
    }

    /// [`Model::link_poses`] into a buffer of one pose per link (no allocation).
    pub fn link_poses_into(
        &self,
        base: &Isometry3<f64>,
        values: &[f64],
        poses: &mut [Isometry3<f64>],
    ) {
        self.link_poses_prefix(base, values, poses, self.order.len());
    }

    /// [`Model::link_poses_into`] for the links the first `joints` joints of [`Self::order`]
    /// place ([`Self::order_prefix`]); the other poses are left as they were. Conservative
    /// advancement asks about one or two links at a time, far fewer joints on a chain.
    pub fn link_poses_prefix(
        &self,
        base: &Isometry3<f64>,
        values: &[f64],
        poses: &mut [Isometry3<f64>],
        joints: usize,
    ) {
        poses[self.root] = *base;
        for step in &self.placements[..joints.min(self.placements.len())] {
            poses[step.child] = step.place(&poses[step.parent], values);
        }
    }

    /// The joints from the root down to link `l`, root first.
    pub fn chain_to(&self, mut l: usize) -> Vec<usize> {
        let mut chain = Vec::new();
        while let Some(k) = self.parent_joint[l] {
            chain.push(k);
            l = self.joint_links[k].0;
        }
        chain.reverse();
        chain
    }

    /// Resolves the SRDF group `name` (MoveIt's rules: a chain brings the joints between its
    /// base and tip links; a link brings its parent joint; subgroups bring theirs), keeping
    /// the movable, non-mimic joints in tree order (root to tip for a chain).
    pub fn resolve_group(
        &self,
        srdf: &Srdf,
        name: &str,
        srdf_path: &Path,
    ) -> Result<Group, RobotError> {
        let invalid = |message: String| RobotError::Invalid {
            path: srdf_path.to_path_buf(),
            message,
        };
        let mut members = vec![false; self.urdf.joints.len()];
        let groups: HashMap<&str, &GroupSpec> =
            srdf.groups.iter().map(|g| (g.name.as_str(), g)).collect();
        let mut pending = vec![name];
        let mut visited: HashSet<&str> = HashSet::new();
        while let Some(g) = pending.pop() {
            if !visited.insert(g) {
                continue;
            }
            let spec = groups
                .get(g)
                .ok_or_else(|| invalid(format!("no group called {g}")))?;
            for (base, tip) in &spec.chains {
                let b = self
                    .link(base)
                    .ok_or_else(|| invalid(format!("chain base {base} is not a link")))?;
                let t = self
                    .link(tip)
                    .ok_or_else(|| invalid(format!("chain tip {tip} is not a link")))?;
                let to_tip = self.chain_to(t);
                let to_base = self.chain_to(b);
                if !to_tip.starts_with(&to_base) {
                    return Err(invalid(format!(
                        "chain tip {tip} is not below its base {base}"
                    )));
                }
                to_tip[to_base.len()..]
                    .iter()
                    .for_each(|&k| members[k] = true);
            }
            for j in &spec.joints {
                let k = self
                    .joint(j)
                    .ok_or_else(|| invalid(format!("group {name}: unknown joint {j}")))?;
                members[k] = true;
            }
            for l in &spec.links {
                let i = self
                    .link(l)
                    .ok_or_else(|| invalid(format!("group {name}: unknown link {l}")))?;
                if let Some(k) = self.parent_joint[i] {
                    members[k] = true;
                }
            }
            pending.extend(spec.subgroups.iter().map(String::as_str));
        }
        let joints: Vec<usize> = self
            .order
            .iter()
            .copied()
            .filter(|&k| {
                members[k]
                    && self.urdf.joints[k].kind.is_movable()
                    && self.mimic_master[k].is_none()
            })
            .collect();
        if joints.is_empty() {
            return Err(invalid(format!("group {name} has no movable joint")));
        }
        check_group_size(name, joints.len()).map_err(invalid)?;
        Ok(self.group_of(name, joints))
    }

    /// A group of the named joints, in the order given (each must be movable, not a mimic,
    /// and named once).
    pub fn group_from_names(&self, names: &[String], path: &Path) -> Result<Group, RobotError> {
        check_group_size("custom", names.len()).map_err(|message| RobotError::Invalid {
            path: path.to_path_buf(),
            message,
        })?;
        let mut joints = Vec::with_capacity(names.len());
        for n in names {
            let k = self.joint(n).ok_or_else(|| RobotError::Invalid {
                path: path.to_path_buf(),
                message: format!("unknown joint {n}"),
            })?;
            if !self.urdf.joints[k].kind.is_movable()
                || self.mimic_master[k].is_some()
                || joints.contains(&k)
            {
                return Err(RobotError::Invalid {
                    path: path.to_path_buf(),
                    message: format!("joint {n} is fixed, a mimic joint or named twice"),
                });
            }
            joints.push(k);
        }
        if joints.is_empty() {
            return Err(RobotError::Invalid {
                path: path.to_path_buf(),
                message: "a group needs at least one joint".into(),
            });
        }
        Ok(self.group_of("custom", joints))
    }

    fn group_of(&self, name: &str, joints: Vec<usize>) -> Group {
        let (lower, upper) = joints
            .iter()
            .map(|&k| match self.urdf.joints[k].kind {
                JointKind::Revolute { lower, upper } | JointKind::Prismatic { lower, upper } => {
                    (lower, upper)
                }
                JointKind::Continuous | JointKind::Fixed => (-PI, PI),
            })
            .unzip();
        Group {
            name: name.to_string(),
            joints,
            lower,
            upper,
        }
    }
}

/// Refuses a planning group of more joints than a joint space takes
/// ([`crate::space::joints::MAX_JOINTS`]) as soon as its joints are counted: the arm's
/// geometry and oracles are built after the group, and a chain of thousands of joints would
/// take gigabytes before the joint space refused it.
fn check_group_size(name: &str, joints: usize) -> Result<(), String> {
    let max = crate::space::joints::MAX_JOINTS;
    if joints > max {
        return Err(format!(
            "group {name} has {joints} joints: a joint space needs 2 to {max} joints"
        ));
    }
    Ok(())
}

/// Names a cycle of the links' parent relation, e.g. "the joints form a cycle through links
/// a → b → a (joints j, k)", parent before child. Each link has at most one parent joint, so
/// walking up from any link either reaches a root or enters a cycle; every link is walked once.
fn cycle_message(
    urdf: &Urdf,
    parent_joint: &[Option<usize>],
    joint_links: &[(usize, usize)],
) -> String {
    const SHOWN: usize = 12;
    // 0: not seen, 1: on the current walk, 2: leads to a root or to a cycle already walked
    let mut state = vec![0u8; parent_joint.len()];
    for start in 0..parent_joint.len() {
        let mut walk = Vec::new();
        let mut l = start;
        loop {
            if state[l] == 2 {
                break;
            }
            if state[l] == 1 {
                let from = walk.iter().position(|&x| x == l).unwrap_or(0);
                let mut cycle: Vec<usize> = walk[from..].to_vec();
                cycle.reverse();
                let n = cycle.len();
                let mut links: Vec<&str> = cycle
                    .iter()
                    .take(SHOWN)
                    .map(|&x| urdf.links[x].name.as_str())
                    .collect();
                let mut joints: Vec<&str> = cycle
                    .iter()
                    .skip(1)
                    .chain(std::iter::once(&cycle[0]))
                    .take(SHOWN)
                    .filter_map(|&x| parent_joint[x])
                    .map(|k| urdf.joints[k].name.as_str())
                    .collect();
                let all = if n > SHOWN {
                    links.push("…");
                    joints.push("…");
                    format!(", {n} links in all")
                } else {
                    String::new()
                };
                links.push(urdf.links[cycle[0]].name.as_str());
                return format!(
                    "the joints form a cycle through links {} (joints {}{all})",
                    links.join(" → "),
                    joints.join(", ")
                );
            }
            state[l] = 1;
            walk.push(l);
            match parent_joint[l] {
                Some(k) => l = joint_links[k].0,
                None => break,
            }
        }
        for &x in &walk {
            state[x] = 2;
        }
    }
    "the joints form a cycle".into()
}

impl Group {
    /// Number of joints (degrees of freedom).
    pub fn dof(&self) -> usize {
        self.joints.len()
    }

    /// Whether `q` lies within the bounds (componentwise, closed).
    pub fn in_bounds(&self, q: &[f64]) -> bool {
        q.len() == self.dof()
            && q.iter()
                .zip(self.lower.iter().zip(&self.upper))
                .all(|(v, (lo, hi))| *lo <= *v && *v <= *hi)
    }

    /// The L2 diagonal of the bounds: OMPL's `getMaximumExtent` for a real vector space, the
    /// unit of its motion-check resolution.
    pub fn max_extent(&self) -> f64 {
        self.lower
            .iter()
            .zip(&self.upper)
            .map(|(l, u)| (u - l).powi(2))
            .sum::<f64>()
            .sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::robot::urdf::parse_urdf;
    use nalgebra::{Point3, Vector3};

    fn model(text: &str) -> Result<Model, RobotError> {
        let p = Path::new("t.urdf");
        Model::new(parse_urdf(text, p)?, p)
    }

    const TWO_LINK: &str = r#"<robot name="planar">
        <link name="base"/><link name="l1"/><link name="l2"/><link name="tool"/>
        <joint name="j1" type="continuous"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/></joint>
        <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="1 0 0"/><axis xyz="0 0 1"/><limit lower="-2" upper="2"/></joint>
        <joint name="t" type="fixed"><parent link="l2"/><child link="tool"/><origin xyz="0.5 0 0"/></joint>
        <joint name="p" type="prismatic"><parent link="tool"/><child link="slide"/><axis xyz="1 0 0"/><limit lower="0" upper="0.2"/></joint>
        <link name="slide"/>
    </robot>"#;

    /// A prefix of the order places a link and every link above it exactly as the whole order
    /// does, bit for bit, on the Panda (fixed joints, a mimic finger) at random values.
    #[test]
    fn a_prefix_places_each_link_as_the_whole_order_does() {
        use rand::{Rng, SeedableRng};
        let arm = crate::robot::arm::tests::panda();
        let m = &arm.model;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let base = Isometry3::translation(0.1, -0.2, 0.3);
        let mut prefix = vec![Isometry3::identity(); m.urdf.links.len()];
        for _ in 0..50 {
            let values: Vec<f64> = (0..m.urdf.joints.len())
                .map(|_| rng.random_range(-3.0..3.0))
                .collect();
            let all = m.link_poses(&base, &values);
            for l in 0..m.urdf.links.len() {
                prefix.fill(Isometry3::identity());
                m.link_poses_prefix(&base, &values, &mut prefix, m.order_prefix[l]);
                let mut above = Some(l);
                while let Some(k) = above {
                    assert_eq!(prefix[k], all[k], "link {k} above {l}");
                    above = m.parent_joint[k].map(|j| m.joint_links[j].0);
                }
            }
        }
    }

    /// The prepared placements give the bits of the full products `parent · origin ·
    /// motion(value)`, for turns about `±z` and other axes, slides, fixed joints and a mimic.
    #[test]
    fn placements_give_the_bits_of_the_full_products() {
        use rand::{Rng, SeedableRng};
        let varied = model(
            r#"<robot name="varied">
            <link name="a"/><link name="b"/><link name="c"/><link name="d"/><link name="e"/>
            <joint name="down" type="continuous"><parent link="a"/><child link="b"/>
              <origin xyz="0.1 0 0.2" rpy="0.3 0 0"/><axis xyz="0 0 -1"/></joint>
            <joint name="tilted" type="revolute"><parent link="b"/><child link="c"/>
              <origin xyz="0 0.4 0"/><axis xyz="1 1 0"/><limit lower="-2" upper="2"/></joint>
            <joint name="slide" type="prismatic"><parent link="c"/><child link="d"/>
              <origin rpy="0 1.2 0"/><axis xyz="0 1 0"/><limit lower="0" upper="1"/></joint>
            <joint name="follow" type="revolute"><parent link="d"/><child link="e"/>
              <axis xyz="0 0 1"/><limit lower="-2" upper="2"/><mimic joint="down" multiplier="-0.5" offset="0.1"/></joint>
            </robot>"#,
        )
        .unwrap();
        let panda = crate::robot::arm::tests::panda().model;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        for m in [&varied, &panda] {
            for _ in 0..50 {
                let values: Vec<f64> = (0..m.urdf.joints.len())
                    .map(|_| rng.random_range(-3.0..3.0))
                    .collect();
                let base = Isometry3::translation(0.3, 0.1, -0.2);
                let poses = m.link_poses(&base, &values);
                let mut full = vec![Isometry3::identity(); m.urdf.links.len()];
                full[m.root] = base;
                for &k in &m.order {
                    let (p, c) = m.joint_links[k];
                    let j = &m.urdf.joints[k];
                    let value = match (m.mimic_master[k], &j.mimic) {
                        (Some(master), Some(mimic)) => {
                            mimic.multiplier * values[master] + mimic.offset
                        }
                        _ => values[k],
                    };
                    let frame = full[p] * j.origin;
                    full[c] = match j.kind {
                        JointKind::Prismatic { .. } => Isometry3::from_parts(
                            Translation3::from(
                                frame.translation.vector
                                    + frame.rotation * (j.axis.into_inner() * value),
                            ),
                            frame.rotation,
                        ),
                        JointKind::Fixed => frame,
                        _ => Isometry3::from_parts(
                            frame.translation,
                            frame.rotation * UnitQuaternion::from_axis_angle(&j.axis, value),
                        ),
                    };
                }
                assert_eq!(poses, full);
            }
        }
    }

    #[test]
    fn planar_two_link_forward_kinematics_matches_the_closed_form() {
        let m = model(TWO_LINK).unwrap();
        for (a, b, s) in [(0.0, 0.0, 0.0), (0.4, -1.3, 0.1), (3.0, 2.0, 0.2)] {
            let mut v = vec![0.0; 4];
            v[m.joint("j1").unwrap()] = a;
            v[m.joint("j2").unwrap()] = b;
            v[m.joint("p").unwrap()] = s;
            let poses = m.link_poses(&Isometry3::identity(), &v);
            let tool = poses[m.link("tool").unwrap()] * Point3::origin();
            let expect = Point3::new(
                a.cos() + 0.5 * (a + b).cos(),
                a.sin() + 0.5 * (a + b).sin(),
                0.0,
            );
            assert!((tool - expect).norm() < 1e-12);
            let slide = poses[m.link("slide").unwrap()] * Point3::origin();
            let dir = Vector3::new((a + b).cos(), (a + b).sin(), 0.0);
            assert!((slide - (expect + s * dir)).norm() < 1e-12);
        }
    }

    #[test]
    fn malformed_trees_are_errors() {
        for bad in [
            // two roots
            r#"<robot><link name="a"/><link name="b"/></robot>"#,
            // unknown link
            r#"<robot><link name="a"/><joint name="j" type="fixed"><parent link="a"/><child link="x"/></joint></robot>"#,
            // two parents
            r#"<robot><link name="a"/><link name="b"/><link name="c"/>
               <joint name="j" type="fixed"><parent link="a"/><child link="c"/></joint>
               <joint name="k" type="fixed"><parent link="b"/><child link="c"/></joint>
               <joint name="m" type="fixed"><parent link="a"/><child link="b"/></joint></robot>"#,
            // cycle (and then no root)
            r#"<robot><link name="a"/><link name="b"/>
               <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
               <joint name="k" type="fixed"><parent link="b"/><child link="a"/></joint></robot>"#,
            // mimic of an unknown joint
            r#"<robot><link name="a"/><link name="b"/><joint name="j" type="continuous"><parent link="a"/><child link="b"/><mimic joint="z"/></joint></robot>"#,
        ] {
            assert!(model(bad).is_err(), "accepted {bad}");
        }
    }

    #[test]
    fn groups_resolve_chains_joints_links_and_subgroups() {
        let m = model(TWO_LINK).unwrap();
        let srdf = crate::robot::srdf::parse_srdf(
            r#"<robot><group name="arm"><chain base_link="base" tip_link="l2"/></group>
               <group name="tool"><link name="slide"/></group>
               <group name="all"><group name="tool"/><group name="arm"/></group>
               <group name="bad"><chain base_link="l2" tip_link="base"/></group></robot>"#,
            Path::new("t.srdf"),
        )
        .unwrap();
        let p = Path::new("t.srdf");
        let arm = m.resolve_group(&srdf, "arm", p).unwrap();
        let names = |g: &Group| -> Vec<&str> {
            g.joints
                .iter()
                .map(|&k| m.urdf.joints[k].name.as_str())
                .collect()
        };
        assert_eq!(names(&arm), ["j1", "j2"]);
        assert_eq!(arm.lower, [-PI, -2.0]);
        assert_eq!(
            names(&m.resolve_group(&srdf, "all", p).unwrap()),
            ["j1", "j2", "p"]
        );
        assert!(m.resolve_group(&srdf, "bad", p).is_err());
        assert!(m.resolve_group(&srdf, "none", p).is_err());
        assert!(m.group_from_names(&["t".into()], p).is_err());
        assert!(m.group_from_names(&["j2".into(), "j2".into()], p).is_err());
    }
}
