//! A loaded arm: the kinematic model, the collision geometry of every link, the link pairs
//! checked for self-collision, and the planning group with the values of all other joints.

use super::cover::{cover, CoverBall};
use super::inner::{inner_balls, InnerBall};
use super::kinematics::{Group, Model};
use super::shapes::Primitive;
use super::srdf::{load_srdf, Srdf};
use super::urdf::{load_urdf, resolve_mesh_path, Geometry};
use super::RobotError;
use crate::geometry::TriMesh;
use crate::mesh_io::MeshError;
use nalgebra::{Isometry3, Point3};
use rayon::prelude::*;
use std::collections::{BTreeSet, HashSet};
use std::path::{Path, PathBuf};

/// Which joints a loaded arm moves.
#[derive(Clone, Debug, PartialEq)]
pub enum GroupChoice {
    /// An SRDF group by name (MoveIt's rules, see [`Model::resolve_group`]).
    Srdf(String),
    /// Joints by name, in this order.
    Joints(Vec<String>),
    /// The first SRDF group (the Panda's `panda_arm`).
    FirstSrdfGroup,
}

/// How to load an arm.
#[derive(Clone, Debug, PartialEq)]
pub struct ArmOptions {
    /// The planning group.
    pub group: GroupChoice,
    /// The exact oracle plans against every link mesh as it is, however many triangles it
    /// has; off (the default), a mesh of more than [`super::shapes::ENVELOPE_ABOVE`] triangles
    /// is planned against its enveloping polytope ([`super::shapes::envelope`]).
    pub exact_meshes: bool,
}

impl Default for ArmOptions {
    fn default() -> Self {
        ArmOptions {
            group: GroupChoice::FirstSrdfGroup,
            exact_meshes: false,
        }
    }
}

/// Where a link shape came from: the independent checker rebuilds its own parry shapes from
/// this, never from the polytope the exact oracle uses.
#[derive(Clone, Debug)]
pub enum ShapeSource {
    /// A mesh file, scaled, in the collision element's frame.
    Mesh {
        /// The resolved file.
        path: PathBuf,
        /// The mesh as read and scaled.
        mesh: TriMesh,
    },
    /// A primitive (exact; its polytope circumscribes it).
    Primitive(Primitive),
}

/// One collision element of a link.
#[derive(Clone, Debug)]
pub struct LinkShape {
    /// The link's index.
    pub link: usize,
    /// The element's pose in the link frame.
    pub origin: Isometry3<f64>,
    /// The shape as described.
    pub source: ShapeSource,
    /// The polytope that contains the shape, in the element's frame: the mesh, or its
    /// envelope (see `envelope_gap`), or a primitive's circumscribed polytope.
    pub polytope: TriMesh,
    /// Where `polytope` is a mesh's envelope ([`super::shapes::envelope`]): how far it stands
    /// off the mesh at most.
    pub envelope_gap: Option<f64>,
    /// Balls inside `polytope`, in the element's frame, for the oracle's sure collision test
    /// ([`super::inner`]); none where the polytope is not closed. Found once per robot load,
    /// not per scene.
    pub inner: Vec<InnerBall>,
    /// Balls whose union holds `polytope`, in the element's frame, for the oracle's cheap
    /// proof of "apart" ([`super::cover`]). Found once per robot load, not per scene.
    pub cover: Vec<CoverBall>,
}

/// A robot arm ready for planning: model, geometry, self-collision pairs, group.
#[derive(Clone, Debug)]
pub struct Arm {
    /// The kinematic tree.
    pub model: Model,
    /// The SRDF (empty if none was given).
    pub srdf: Srdf,
    /// The moving joints.
    pub group: Group,
    /// One value per joint of the model: what joints outside the group keep.
    pub values: Vec<f64>,
    /// Pose of the root link in the world (MoveIt's virtual joint).
    pub base: Isometry3<f64>,
    /// Every collision element of every link.
    pub shapes: Vec<LinkShape>,
    /// Link pairs checked for self-collision (`a < b`, both with geometry, not exempt).
    pub self_pairs: Vec<(usize, usize)>,
    /// The robot's folder (`package://` paths resolve against it).
    pub dir: PathBuf,
    /// What loading found odd but accepted as MoveIt does (an SRDF exempting links the URDF
    /// does not have): for whoever loads the arm to print once.
    pub warnings: Vec<String>,
}

impl Arm {
    /// Loads a URDF (meshes resolved relative to its folder) and optionally an SRDF, and
    /// resolves the planning group. Joints outside the group start at 0 (clamped into their
    /// limits); [`Arm::set_joint_values`] sets them from a scene or request.
    pub fn load(urdf: &Path, srdf: Option<&Path>, options: &ArmOptions) -> Result<Arm, RobotError> {
        let model = Model::new(load_urdf(urdf)?, urdf)?;
        let srdf_data = match srdf {
            Some(p) => load_srdf(p)?,
            None => Srdf::default(),
        };
        let srdf_path = srdf.unwrap_or(urdf);
        let group = match &options.group {
            GroupChoice::Srdf(name) => model.resolve_group(&srdf_data, name, srdf_path)?,
            GroupChoice::Joints(names) => model.group_from_names(names, urdf)?,
            GroupChoice::FirstSrdfGroup => {
                let first = srdf_data
                    .groups
                    .first()
                    .ok_or_else(|| RobotError::Invalid {
                        path: srdf_path.to_path_buf(),
                        message:
                            "no planning group: give an SRDF with a <group> or name the joints"
                                .into(),
                    })?;
                model.resolve_group(&srdf_data, &first.name.clone(), srdf_path)?
            }
        };
        // counted before any mesh is read or any polytope built
        let (self_pairs, warnings) = self_pairs(&model, &srdf_data, urdf, srdf_path)?;
        let dir = urdf.parent().map(Path::to_path_buf).unwrap_or_default();
        let mut shapes = Vec::new();
        for (l, link) in model.urdf.links.iter().enumerate() {
            for c in &link.collisions {
                let (source, polytope, envelope_gap) = match &c.geometry {
                    Geometry::Mesh { filename, scale } => {
                        let path = resolve_mesh_path(filename, &dir);
                        let mesh = crate::mesh_io::load_mesh(&path)?;
                        let mesh = scaled(mesh, *scale, &path)?;
                        let around = (!options.exact_meshes)
                            .then(|| super::shapes::envelope(&mesh))
                            .flatten();
                        let gap = around.as_ref().map(|e| e.gap);
                        let polytope = around.map_or_else(|| mesh.clone(), |e| e.polytope);
                        (ShapeSource::Mesh { path, mesh }, polytope, gap)
                    }
                    Geometry::Primitive(p) => {
                        let poly = p.polytope().map_err(|source| MeshError::Geometry {
                            path: urdf.to_path_buf(),
                            source,
                        })?;
                        (ShapeSource::Primitive(*p), poly, None)
                    }
                };
                shapes.push(LinkShape {
                    link: l,
                    origin: c.origin,
                    source,
                    polytope,
                    envelope_gap,
                    inner: Vec::new(),
                    cover: Vec::new(),
                });
            }
        }
        shapes.par_iter_mut().for_each(|s| {
            s.inner = inner_balls(&s.polytope);
            s.cover = cover(&s.polytope);
        });
        let values = model
            .urdf
            .joints
            .iter()
            .map(|j| match j.kind {
                super::urdf::JointKind::Revolute { lower, upper }
                | super::urdf::JointKind::Prismatic { lower, upper } => 0.0f64.clamp(lower, upper),
                _ => 0.0,
            })
            .collect();
        Ok(Arm {
            model,
            srdf: srdf_data,
            group,
            values,
            base: Isometry3::identity(),
            shapes,
            self_pairs,
            dir,
            warnings,
        })
    }

    /// Sets the values of named joints outside the group (a scene's `robot_state`, a request's
    /// start state). Names of group joints are skipped (the group's values come from each
    /// configuration); unknown names are errors.
    pub fn set_joint_values(&mut self, names: &[String], values: &[f64]) -> Result<(), RobotError> {
        if names.len() != values.len() {
            return Err(RobotError::Config {
                what: "joint state".into(),
                message: format!("{} names but {} positions", names.len(), values.len()),
            });
        }
        for (n, &v) in names.iter().zip(values) {
            let k = self.model.joint(n).ok_or_else(|| RobotError::Config {
                what: "joint state".into(),
                message: format!("unknown joint {n}"),
            })?;
            if !(v.is_finite() && v.abs() <= crate::limits::MAX_COORDINATE) {
                return Err(RobotError::Config {
                    what: "joint state".into(),
                    message: format!("joint {n} has the value {}", crate::short::num(v)),
                });
            }
            if !self.group.joints.contains(&k) {
                self.values[k] = v;
            }
        }
        Ok(())
    }

    /// Exempts the link pair `(a, b)` from self-collision checking (a scene's allowed
    /// collision matrix); unknown names are ignored.
    pub fn allow_pair(&mut self, a: &str, b: &str) {
        if let (Some(x), Some(y)) = (self.model.link(a), self.model.link(b)) {
            let pair = (x.min(y), x.max(y));
            self.self_pairs.retain(|p| *p != pair);
        }
    }

    /// Checks a group configuration's shape: one finite value per group joint.
    pub fn check_config(&self, q: &[f64], what: &str) -> Result<(), RobotError> {
        if q.len() != self.group.dof() {
            return Err(RobotError::Config {
                what: what.into(),
                message: format!(
                    "{} values for a group of {} joints",
                    q.len(),
                    self.group.dof()
                ),
            });
        }
        if let Some(v) = q.iter().find(|v| !v.is_finite()) {
            return Err(RobotError::Config {
                what: what.into(),
                message: format!("the value {v} is not finite"),
            });
        }
        Ok(())
    }

    /// All joint values for group configuration `q` (the others as set).
    pub fn full_values(&self, q: &[f64]) -> Vec<f64> {
        let mut v = self.values.clone();
        for (&k, &x) in self.group.joints.iter().zip(q) {
            v[k] = x;
        }
        v
    }

    /// World poses of all links at group configuration `q` (of the group's length).
    pub fn link_poses(&self, q: &[f64]) -> Vec<Isometry3<f64>> {
        self.model.link_poses(&self.base, &self.full_values(q))
    }

    /// The world pose of frame `name`, as a PlanningScene's `header.frame_id` names it: the
    /// world itself (`""`, `world`, or a virtual joint's parent frame), or a link the group
    /// does not move — the root link where the base puts it, a link below joints outside the
    /// group where their values put it (MotionBenchMaker's Fetch scenes give every object in
    /// `base_link`, the root). A link the group moves would carry an object along (an
    /// attached object, not supported): refused, as is a name that is neither.
    pub fn frame_pose(&self, name: &str) -> Result<Isometry3<f64>, RobotError> {
        let name = name.trim_start_matches('/');
        if name.is_empty()
            || name == "world"
            || self
                .srdf
                .virtual_joints
                .iter()
                .any(|v| v.parent_frame == name)
        {
            return Ok(Isometry3::identity());
        }
        let refuse = |message: String| RobotError::Config {
            what: format!("frame {name:?}"),
            message,
        };
        let l = self.model.link(name).ok_or_else(|| {
            refuse(
                "neither the world nor a link of the robot (objects must be given in one)".into(),
            )
        })?;
        let group_moves = |k: usize| {
            let master = self.model.mimic_master[k].unwrap_or(k);
            self.group.joints.contains(&master)
        };
        if let Some(&k) = self
            .model
            .chain_to(l)
            .iter()
            .rev()
            .find(|&&k| group_moves(k))
        {
            return Err(refuse(format!(
                "the link moves with the planning group's joint {} (objects attached to the \
                 robot are not supported)",
                self.model.urdf.joints[k].name
            )));
        }
        Ok(self.link_poses(&vec![0.0; self.group.dof()])[l])
    }

    /// The group configuration with the named values (every group joint must be named once;
    /// names outside the group are skipped). Used for a request's start and goal.
    pub fn group_config(
        &self,
        names: &[String],
        values: &[f64],
        what: &str,
    ) -> Result<Vec<f64>, RobotError> {
        let mut q = vec![f64::NAN; self.group.dof()];
        for (n, &v) in names.iter().zip(values) {
            if let Some(k) = self.model.joint(n) {
                if let Some(i) = self.group.joints.iter().position(|&g| g == k) {
                    q[i] = v;
                }
            }
        }
        if let Some(i) = q.iter().position(|v| v.is_nan()) {
            return Err(RobotError::Config {
                what: what.into(),
                message: format!(
                    "no value for group joint {}",
                    self.model.urdf.joints[self.group.joints[i]].name
                ),
            });
        }
        self.check_config(&q, what)?;
        Ok(q)
    }

    /// The same robot planning for the SRDF's group `name` (a MoveIt request's `group_name`):
    /// the joints outside it keep their values, the base and the exempt pairs stay.
    pub fn with_srdf_group(&self, name: &str) -> Result<Arm, RobotError> {
        let group = self.model.resolve_group(&self.srdf, name, &self.dir)?;
        Ok(Arm {
            group,
            ..self.clone()
        })
    }

    /// Whether group joint `i` has limits (revolute or prismatic, not continuous): the joints
    /// whose values MoveIt moves onto a limit they pass (see
    /// [`crate::scene::moveit::MotionPlanRequest::ends`]).
    pub fn is_bounded(&self, i: usize) -> bool {
        !matches!(
            self.model.urdf.joints[self.group.joints[i]].kind,
            super::urdf::JointKind::Continuous
        )
    }

    /// Names of the group's joints, in group order.
    pub fn group_joint_names(&self) -> Vec<&str> {
        self.group
            .joints
            .iter()
            .map(|&k| self.model.urdf.joints[k].name.as_str())
            .collect()
    }
}

/// Pairs of link indices, `a < b`.
type LinkPairs = Vec<(usize, usize)>;

/// The link pairs checked for self-collision: links with collision elements, `a < b` in link
/// order, that the SRDF does not exempt; refused beyond [`crate::limits::MAX_SELF_PAIRS`]
/// before they are listed (the oracle builds one exact oracle per pair). Links the SRDF exempts
/// but the URDF lacks are skipped with a warning, as MoveIt's SRDF reader skips them (VAMP's
/// Fetch SRDF exempts the wheels its trimmed URDF leaves out).
fn self_pairs(
    model: &Model,
    srdf: &Srdf,
    urdf_path: &Path,
    srdf_path: &Path,
) -> Result<(LinkPairs, Vec<String>), RobotError> {
    let links = &model.urdf.links;
    let has_geometry = |l: usize| !links[l].collisions.is_empty();
    let mut exempt = HashSet::new();
    let mut unknown = BTreeSet::new();
    for (a, b) in &srdf.disabled_collisions {
        match (model.link(a), model.link(b)) {
            (Some(x), Some(y)) => {
                exempt.insert((x.min(y), x.max(y)));
            }
            (x, y) => {
                for (name, found) in [(a, x), (b, y)] {
                    if found.is_none() {
                        unknown.insert(name.as_str());
                    }
                }
            }
        }
    }
    let with_geometry: Vec<usize> = (0..links.len()).filter(|&l| has_geometry(l)).collect();
    let n = with_geometry.len();
    let exempt_among = exempt
        .iter()
        .filter(|&&(a, b)| a != b && has_geometry(a) && has_geometry(b))
        .count();
    let count = n * n.saturating_sub(1) / 2 - exempt_among;
    let max = crate::limits::MAX_SELF_PAIRS;
    if count > max {
        return Err(RobotError::Invalid {
            path: urdf_path.to_path_buf(),
            message: format!(
                "{n} links with collision geometry make {count} self-collision pairs the SRDF \
                 does not exempt: more than the {max} viaroad checks"
            ),
        });
    }
    let mut pairs = Vec::with_capacity(count);
    for (i, &a) in with_geometry.iter().enumerate() {
        for &b in &with_geometry[i + 1..] {
            if !exempt.contains(&(a, b)) {
                pairs.push((a, b));
            }
        }
    }
    let mut warnings = Vec::new();
    if !unknown.is_empty() {
        const SHOWN: usize = 12;
        let mut names: Vec<&str> = unknown.iter().take(SHOWN).copied().collect();
        if unknown.len() > SHOWN {
            names.push("…");
        }
        warnings.push(format!(
            "{}: <disable_collisions> names {} link(s) the URDF does not have, ignored as MoveIt \
             ignores them: {}",
            srdf_path.display(),
            unknown.len(),
            names.join(", ")
        ));
    }
    Ok((pairs, warnings))
}

/// A mesh scaled per axis; a negative scale mirrors it, so the triangles are turned to keep
/// them outward.
fn scaled(mesh: TriMesh, scale: [f64; 3], path: &Path) -> Result<TriMesh, RobotError> {
    if scale == [1.0; 3] {
        return Ok(mesh);
    }
    let flip = scale.iter().filter(|s| **s < 0.0).count() % 2 == 1;
    let vertices = mesh
        .vertices
        .iter()
        .map(|v| Point3::new(v.x * scale[0], v.y * scale[1], v.z * scale[2]))
        .collect();
    let triangles = mesh
        .triangles
        .iter()
        .map(|t| if flip { [t[0], t[2], t[1]] } else { *t })
        .collect();
    TriMesh::new(vertices, triangles).map_err(|source| {
        RobotError::Input(MeshError::Geometry {
            path: path.to_path_buf(),
            source,
        })
    })
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// The shipped Panda (`scenes/arms/panda`), for unit tests.
    pub(crate) fn panda() -> Arm {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/arms/panda");
        Arm::load(
            &dir.join("panda.urdf"),
            Some(&dir.join("panda.srdf")),
            &ArmOptions::default(),
        )
        .unwrap()
    }

    #[test]
    fn panda_loads_with_its_group_pairs_and_meshes() {
        let arm = panda();
        assert_eq!(
            arm.group_joint_names(),
            (1..=7)
                .map(|i| format!("panda_joint{i}"))
                .collect::<Vec<_>>()
        );
        assert_eq!(arm.model.urdf.links.len(), 13);
        assert_eq!(arm.shapes.len(), 11);
        // 11 links with geometry → 55 pairs, 34 disabled by the SRDF (as OMPL's peer counts)
        assert_eq!(arm.self_pairs.len(), 55 - 34);
        assert!((arm.group.max_extent() - 13.41653372).abs() < 1e-6);
        // every collision mesh bounds a solid except link6.obj (586 unmatched edges): the
        // checker tests it as a surface only
        for s in &arm.shapes {
            let name = &arm.model.urdf.links[s.link].name;
            assert_eq!(s.polytope.is_closed(), name != "panda_link6", "{name}");
        }
    }

    #[test]
    fn panda_link_frames_match_the_ompl_peer() {
        // `ompl_peer arminfo` (urdfdom + its own FK) at the "ready" start of table_pick 1
        let arm = panda();
        let poses = arm.link_poses(&[0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785]);
        let expect = [
            ("panda_link3", [-0.2233567572, 0.0, 0.5565346931]),
            ("panda_link4", [-0.164997225, 0.0, 0.6148477705]),
            ("panda_link5", [0.2190195701, 0.0, 0.6972695583]),
            ("panda_link7", [0.3070195701, 0.0, 0.6972695583]),
            ("panda_link8", [0.3070195701, 0.0, 0.5902695583]),
            (
                "panda_leftfinger",
                [0.3070454507, -0.06499999485, 0.5318695583],
            ),
            (
                "panda_rightfinger",
                [0.3069936894, 0.06499999484, 0.5318695583],
            ),
            ("panda_grasptarget", [0.3070195701, 0.0, 0.4852695583]),
        ];
        for (name, p) in expect {
            let t = poses[arm.model.link(name).unwrap()].translation.vector;
            let d = (t - nalgebra::Vector3::from(p)).norm();
            assert!(d < 1e-8, "{name}: {t:?} vs {p:?}");
        }
    }

    #[test]
    fn group_configs_need_every_group_joint() {
        let arm = panda();
        let names: Vec<String> = (1..=7).map(|i| format!("panda_joint{i}")).collect();
        let q = arm.group_config(&names, &[0.1; 7], "start").unwrap();
        assert_eq!(q, [0.1; 7]);
        assert!(arm.group_config(&names[..6], &[0.1; 6], "start").is_err());
        assert!(arm.check_config(&[0.0; 6], "q").is_err());
        assert!(arm.check_config(&[f64::NAN; 7], "q").is_err());
        let mut arm = arm;
        assert!(arm.set_joint_values(&["nope".into()], &[0.0]).is_err());
        assert!(arm
            .set_joint_values(&["panda_finger_joint1".into()], &[0.065])
            .is_ok());
    }
}
