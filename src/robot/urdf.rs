//! URDF: the links, joints and collision elements of a robot (ROS's Unified Robot Description
//! Format, read as urdfdom reads it).
//!
//! Read: `<link>` with its `<collision>` elements (`<origin xyz rpy>`, `<geometry>` with
//! `<mesh filename scale>`, `<box size>`, `<cylinder radius length>`, `<sphere radius>`);
//! `<joint>` of type revolute, continuous, prismatic or fixed, with `<origin>`, `<parent>`,
//! `<child>`, `<axis>` (default `1 0 0`), `<limit lower upper>` (urdfdom's default 0) and
//! `<mimic joint multiplier offset>`. Visual and inertial elements, materials, transmissions
//! and Gazebo tags are ignored. Floating and planar joints are refused: they are not arm joints.
//! A URDF of more than [`crate::limits::MAX_URDF_ELEMENTS`] links and joints, or more than
//! [`crate::limits::MAX_COLLISION_ELEMENTS`] collision elements, is refused before any is read.

use super::shapes::Primitive;
use super::{parse_number, parse_numbers, RobotError};
use nalgebra::{Isometry3, Translation3, Unit, UnitQuaternion, Vector3};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// A parsed URDF: links and joints in file order.
#[derive(Clone, Debug)]
pub struct Urdf {
    /// The robot's name.
    pub name: String,
    /// Links in file order.
    pub links: Vec<Link>,
    /// Joints in file order.
    pub joints: Vec<Joint>,
}

/// One link: a name and its collision elements (in the link's frame).
#[derive(Clone, Debug)]
pub struct Link {
    /// The link's name.
    pub name: String,
    /// The `<collision>` elements.
    pub collisions: Vec<Collision>,
}

/// One `<collision>` element: a shape placed in the link's frame.
#[derive(Clone, Debug)]
pub struct Collision {
    /// Pose of the shape in the link frame (`<origin>`).
    pub origin: Isometry3<f64>,
    /// The shape.
    pub geometry: Geometry,
}

/// The shape of a collision element.
#[derive(Clone, Debug, PartialEq)]
pub enum Geometry {
    /// A mesh file, `filename` as written (`package://…`, `file://…` or a relative path) and
    /// the per-axis `scale`.
    Mesh {
        /// The file name as written in the URDF.
        filename: String,
        /// Per-axis scale (default 1 1 1).
        scale: [f64; 3],
    },
    /// A box, cylinder or sphere.
    Primitive(Primitive),
}

/// What a joint lets its child do relative to its parent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum JointKind {
    /// Rotation about the axis within `[lower, upper]` radians.
    Revolute {
        /// Lower limit (rad).
        lower: f64,
        /// Upper limit (rad).
        upper: f64,
    },
    /// Rotation about the axis without limits.
    Continuous,
    /// Translation along the axis within `[lower, upper]` metres.
    Prismatic {
        /// Lower limit (m).
        lower: f64,
        /// Upper limit (m).
        upper: f64,
    },
    /// No motion.
    Fixed,
}

impl JointKind {
    /// Whether the joint has a degree of freedom.
    pub fn is_movable(self) -> bool {
        !matches!(self, JointKind::Fixed)
    }
}

/// A joint that follows another: `value = multiplier · master + offset` (URDF `<mimic>`).
#[derive(Clone, Debug, PartialEq)]
pub struct Mimic {
    /// Name of the master joint.
    pub joint: String,
    /// Factor (default 1).
    pub multiplier: f64,
    /// Offset (default 0).
    pub offset: f64,
}

/// One joint: `T(child) = T(parent) · origin · motion(value)`.
#[derive(Clone, Debug)]
pub struct Joint {
    /// The joint's name.
    pub name: String,
    /// Its type and limits.
    pub kind: JointKind,
    /// Name of the parent link.
    pub parent: String,
    /// Name of the child link.
    pub child: String,
    /// The child frame at value 0, in the parent's frame.
    pub origin: Isometry3<f64>,
    /// The unit axis of rotation or translation, in the joint frame.
    pub axis: Unit<Vector3<f64>>,
    /// `<mimic>`, if the joint follows another.
    pub mimic: Option<Mimic>,
}

/// Reads and parses a URDF file.
pub fn load_urdf(path: &Path) -> Result<Urdf, RobotError> {
    let text = crate::mesh_io::read_input_text(path)?;
    parse_urdf(&text, path)
}

/// Parses URDF text; `path` names the file in errors.
pub fn parse_urdf(text: &str, path: &Path) -> Result<Urdf, RobotError> {
    let doc = super::robot_xml(text, path)?;
    let invalid = |message: String| RobotError::Invalid {
        path: path.to_path_buf(),
        message,
    };
    let root = doc.root_element();
    let name = root.attribute("name").unwrap_or("").to_string();
    // counted before anything is built: everything after (the tree, the self-collision pairs,
    // the link geometry) grows with these
    let (mut elements, mut collisions) = (0, 0);
    for n in root.children() {
        if n.has_tag_name("link") || n.has_tag_name("joint") {
            elements += 1;
            collisions += n.children().filter(|c| c.has_tag_name("collision")).count();
        }
    }
    let (max, max_collisions) = (
        crate::limits::MAX_URDF_ELEMENTS,
        crate::limits::MAX_COLLISION_ELEMENTS,
    );
    if elements > max {
        return Err(invalid(format!(
            "{elements} links and joints: more than the {max} viaroad reads from a robot"
        )));
    }
    if collisions > max_collisions {
        return Err(invalid(format!(
            "{collisions} collision elements: more than the {max_collisions} viaroad reads \
             from a robot"
        )));
    }
    let mut links = Vec::new();
    let mut joints = Vec::new();
    for node in root.children().filter(|n| n.is_element()) {
        match node.tag_name().name() {
            "link" => links.push(parse_link(node).map_err(invalid)?),
            "joint" => joints.push(parse_joint(node).map_err(invalid)?),
            _ => {}
        }
    }
    let mut seen = HashMap::new();
    for l in &links {
        if seen.insert(l.name.as_str(), ()).is_some() {
            return Err(invalid(format!("link {} is defined twice", l.name)));
        }
    }
    let mut seen_joints = HashMap::new();
    for j in &joints {
        if seen_joints.insert(j.name.as_str(), ()).is_some() {
            return Err(invalid(format!("joint {} is defined twice", j.name)));
        }
    }
    if links.is_empty() {
        return Err(invalid("the robot has no links".into()));
    }
    Ok(Urdf {
        name,
        links,
        joints,
    })
}

fn required<'a>(node: roxmltree::Node<'a, '_>, attr: &str) -> Result<&'a str, String> {
    node.attribute(attr).ok_or_else(|| {
        format!(
            "<{}> (line {}) has no {attr} attribute",
            node.tag_name().name(),
            node.document().text_pos_at(node.range().start).row
        )
    })
}

fn child<'a, 'i>(node: roxmltree::Node<'a, 'i>, tag: &str) -> Option<roxmltree::Node<'a, 'i>> {
    node.children().find(|n| n.has_tag_name(tag))
}

fn number(node: roxmltree::Node, attr: &str, default: Option<f64>) -> Result<f64, String> {
    match node.attribute(attr) {
        Some(t) => parse_number(t).ok_or_else(|| {
            format!(
                "<{} {attr}=\"{t}\">: not a finite number",
                node.tag_name().name()
            )
        }),
        None => default.ok_or_else(|| format!("<{}> has no {attr}", node.tag_name().name())),
    }
}

fn vector3(node: roxmltree::Node, attr: &str, default: [f64; 3]) -> Result<[f64; 3], String> {
    match node.attribute(attr) {
        Some(t) => parse_numbers::<3>(t).ok_or_else(|| {
            format!(
                "<{} {attr}=\"{t}\">: not three finite numbers",
                node.tag_name().name()
            )
        }),
        None => Ok(default),
    }
}

/// `<origin xyz rpy>`: translation, then the fixed-axis rotation roll about x, pitch about y,
/// yaw about z (`R = Rz(yaw) Ry(pitch) Rx(roll)`, URDF's convention). Identity when absent.
fn origin(parent: roxmltree::Node) -> Result<Isometry3<f64>, String> {
    let Some(o) = child(parent, "origin") else {
        return Ok(Isometry3::identity());
    };
    let [x, y, z] = vector3(o, "xyz", [0.0; 3])?;
    let [r, p, yaw] = vector3(o, "rpy", [0.0; 3])?;
    Ok(Isometry3::from_parts(
        Translation3::new(x, y, z),
        UnitQuaternion::from_euler_angles(r, p, yaw),
    ))
}

fn parse_link(node: roxmltree::Node) -> Result<Link, String> {
    let name = required(node, "name")?.to_string();
    let mut collisions = Vec::new();
    for c in node.children().filter(|n| n.has_tag_name("collision")) {
        let origin = origin(c).map_err(|e| format!("link {name}: {e}"))?;
        let g = child(c, "geometry")
            .ok_or_else(|| format!("link {name}: a <collision> without <geometry>"))?;
        let shape = g
            .children()
            .find(|n| n.is_element())
            .ok_or_else(|| format!("link {name}: an empty <geometry>"))?;
        let geometry = parse_geometry(shape).map_err(|e| format!("link {name}: {e}"))?;
        collisions.push(Collision { origin, geometry });
    }
    Ok(Link { name, collisions })
}

fn parse_geometry(shape: roxmltree::Node) -> Result<Geometry, String> {
    let positive = |v: f64, what: &str| {
        if v > 0.0 {
            Ok(v)
        } else {
            Err(format!("{what} must be positive, not {v}"))
        }
    };
    Ok(match shape.tag_name().name() {
        "mesh" => {
            let scale = vector3(shape, "scale", [1.0; 3])?;
            if scale.contains(&0.0) {
                return Err("a mesh scale of 0 flattens the mesh".into());
            }
            Geometry::Mesh {
                filename: required(shape, "filename")?.to_string(),
                scale,
            }
        }
        "box" => {
            let size = vector3(shape, "size", [0.0; 3])?;
            for s in size {
                positive(s, "box size")?;
            }
            Geometry::Primitive(Primitive::Box { size })
        }
        "cylinder" => Geometry::Primitive(Primitive::Cylinder {
            radius: positive(number(shape, "radius", None)?, "cylinder radius")?,
            length: positive(number(shape, "length", None)?, "cylinder length")?,
        }),
        "sphere" => Geometry::Primitive(Primitive::Sphere {
            radius: positive(number(shape, "radius", None)?, "sphere radius")?,
        }),
        other => return Err(format!("unknown geometry <{other}>")),
    })
}

fn parse_joint(node: roxmltree::Node) -> Result<Joint, String> {
    let name = required(node, "name")?.to_string();
    let at = |e: String| format!("joint {name}: {e}");
    let ty = required(node, "type").map_err(at)?;
    let limit = child(node, "limit");
    let limits = || -> Result<(f64, f64), String> {
        let (lower, upper) = match limit {
            Some(l) => (
                number(l, "lower", Some(0.0))?,
                number(l, "upper", Some(0.0))?,
            ),
            None => return Err("a revolute or prismatic joint needs a <limit>".into()),
        };
        if lower > upper {
            return Err(format!(
                "lower limit {} exceeds upper limit {}",
                crate::short::num(lower),
                crate::short::num(upper)
            ));
        }
        Ok((lower, upper))
    };
    let kind = match ty {
        "revolute" => {
            let (lower, upper) = limits().map_err(at)?;
            JointKind::Revolute { lower, upper }
        }
        "continuous" => JointKind::Continuous,
        "prismatic" => {
            let (lower, upper) = limits().map_err(at)?;
            JointKind::Prismatic { lower, upper }
        }
        "fixed" => JointKind::Fixed,
        other => {
            return Err(at(format!(
                "joint type {other:?} is not supported (revolute, continuous, prismatic, fixed)"
            )))
        }
    };
    let link_of = |tag: &str| -> Result<String, String> {
        let n = child(node, tag).ok_or_else(|| at(format!("no <{tag}>")))?;
        required(n, "link").map(str::to_string).map_err(at)
    };
    let parent = link_of("parent")?;
    let child_link = link_of("child")?;
    let origin = origin(node).map_err(at)?;
    let raw_axis = match child(node, "axis") {
        Some(a) => vector3(a, "xyz", [1.0, 0.0, 0.0]).map_err(at)?,
        None => [1.0, 0.0, 0.0],
    };
    let axis = match Unit::try_new(Vector3::from(raw_axis), 1e-12) {
        Some(a) => a,
        None if !kind.is_movable() => Vector3::x_axis(),
        None => return Err(at("the axis is the zero vector".into())),
    };
    let mimic = match child(node, "mimic") {
        Some(m) => Some(Mimic {
            joint: required(m, "joint").map_err(at)?.to_string(),
            multiplier: number(m, "multiplier", Some(1.0)).map_err(at)?,
            offset: number(m, "offset", Some(0.0)).map_err(at)?,
        }),
        None => None,
    };
    Ok(Joint {
        name,
        kind,
        parent,
        child: child_link,
        origin,
        axis,
        mimic,
    })
}

/// Resolves a mesh file name of a URDF: `package://pkg/a/b.obj` is tried as
/// `ROBOT_DIR/pkg/a/b.obj`, then with leading components dropped (`ROBOT_DIR/a/b.obj`, …),
/// since a robot folder usually *is* the package; `file:///abs` is taken as it is; any other
/// name is relative to the robot folder. The first existing candidate wins; if none exists,
/// the first candidate is returned so that the error names it.
pub fn resolve_mesh_path(filename: &str, robot_dir: &Path) -> PathBuf {
    if let Some(rest) = filename.strip_prefix("package://") {
        let parts: Vec<&str> = rest.split('/').filter(|p| !p.is_empty()).collect();
        let candidates: Vec<PathBuf> = (0..parts.len())
            .map(|skip| {
                parts[skip..]
                    .iter()
                    .fold(robot_dir.to_path_buf(), |p, c| p.join(c))
            })
            .collect();
        return candidates
            .iter()
            .find(|c| c.is_file())
            .or(candidates.first())
            .cloned()
            .unwrap_or_else(|| robot_dir.to_path_buf());
    }
    if let Some(abs) = filename.strip_prefix("file://") {
        return PathBuf::from(abs);
    }
    robot_dir.join(filename)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Urdf, RobotError> {
        parse_urdf(text, Path::new("test.urdf"))
    }

    #[test]
    fn reads_joints_origins_axes_and_geometry() {
        let u = parse(
            r#"<robot name="r">
              <link name="a"><collision><origin xyz="0 0 1" rpy="0 0 1.5707963267948966"/>
                <geometry><cylinder radius="0.1" length="0.5"/></geometry></collision></link>
              <link name="b"><collision><geometry><mesh filename="package://p/m.stl" scale="2 2 2"/></geometry></collision></link>
              <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
                <origin xyz="1 2 3"/><axis xyz="0 0 2"/><limit lower="-1" upper="1.5"/></joint>
            </robot>"#,
        )
        .unwrap();
        assert_eq!(u.name, "r");
        assert_eq!(u.links.len(), 2);
        let j = &u.joints[0];
        assert_eq!(
            j.kind,
            JointKind::Revolute {
                lower: -1.0,
                upper: 1.5
            }
        );
        assert_eq!(j.axis.into_inner(), Vector3::z());
        assert_eq!(j.origin.translation.vector, Vector3::new(1.0, 2.0, 3.0));
        let c = &u.links[0].collisions[0];
        // rpy yaw = π/2 turns x into y
        let x = c.origin.rotation * Vector3::x();
        assert!((x - Vector3::y()).norm() < 1e-12);
        assert_eq!(
            c.geometry,
            Geometry::Primitive(Primitive::Cylinder {
                radius: 0.1,
                length: 0.5
            })
        );
        assert_eq!(
            u.links[1].collisions[0].geometry,
            Geometry::Mesh {
                filename: "package://p/m.stl".into(),
                scale: [2.0; 3]
            }
        );
    }

    #[test]
    fn rpy_is_fixed_axis_roll_pitch_yaw() {
        // URDF: R = Rz(yaw) Ry(pitch) Rx(roll); check on a vector against explicit matrices
        let (r, p, y) = (0.3, -0.7, 1.1);
        let q = UnitQuaternion::from_euler_angles(r, p, y);
        let rx = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), r);
        let ry = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), p);
        let rz = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), y);
        let v = Vector3::new(0.2, -1.0, 0.5);
        assert!((q * v - rz * (ry * (rx * v))).norm() < 1e-12);
    }

    #[test]
    fn bad_input_is_an_error_not_a_panic() {
        let cases = [
            "<robot",                                             // not XML
            "<notrobot/>",                                        // wrong root
            "<robot/>",                                           // no links
            r#"<robot><link name="a"/><link name="a"/></robot>"#, // duplicate
            r#"<robot><link name="a"/><link name="b"/><joint name="j" type="floating"><parent link="a"/><child link="b"/></joint></robot>"#,
            r#"<robot><link name="a"/><link name="b"/><joint name="j" type="revolute"><parent link="a"/><child link="b"/></joint></robot>"#,
            r#"<robot><link name="a"/><link name="b"/><joint name="j" type="revolute"><parent link="a"/><child link="b"/><limit lower="2" upper="1"/></joint></robot>"#,
            r#"<robot><link name="a"/><link name="b"/><joint name="j" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 0 0"/></joint></robot>"#,
            r#"<robot><link name="a"/><link name="b"/><joint name="j" type="fixed"><parent link="a"/><child link="b"/><origin xyz="NaN 0 0"/></joint></robot>"#,
            r#"<robot><link name="a"><collision><geometry><sphere radius="-1"/></geometry></collision></link></robot>"#,
            r#"<robot><link name="a"><collision><geometry><box size="1 1"/></geometry></collision></link></robot>"#,
            r#"<robot><link name="a"><collision><geometry><capsule radius="1" length="1"/></geometry></collision></link></robot>"#,
        ];
        for c in cases {
            assert!(parse(c).is_err(), "accepted {c}");
        }
    }

    #[test]
    fn package_paths_resolve_inside_the_robot_folder() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/arms/panda");
        let p = resolve_mesh_path("package://meshes/collision/link0.obj", &dir);
        assert!(p.is_file(), "{p:?}");
        let p = resolve_mesh_path(
            "package://franka_description/meshes/collision/link0.obj",
            &dir,
        );
        assert!(p.is_file(), "{p:?}");
        let missing = resolve_mesh_path("package://x/none.obj", &dir);
        assert_eq!(missing, dir.join("x/none.obj"));
    }
}
