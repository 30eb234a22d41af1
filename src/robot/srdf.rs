//! SRDF: MoveIt's semantic description of a robot — planning groups, link pairs exempt from
//! self-collision checking, and the virtual joint that places the robot in the world.
//!
//! Read: `<group name>` with `<chain base_link tip_link>`, `<joint name>`, `<link name>` and
//! `<group name>` (subgroup) members; `<disable_collisions link1 link2>`; `<virtual_joint
//! name type parent_frame child_link>`. Group states, end effectors and passive joints are
//! ignored (a passive joint is simply not moved by a planning group of arm joints). A
//! `<disable_collisions>` naming a link the URDF lacks is skipped with a warning, as MoveIt's
//! SRDF reader skips it ([`crate::robot::Arm::warnings`]).

use super::RobotError;
use std::path::Path;

/// A parsed SRDF.
#[derive(Clone, Debug, Default)]
pub struct Srdf {
    /// Planning groups in file order.
    pub groups: Vec<GroupSpec>,
    /// Link pairs never checked against each other (`<disable_collisions>`).
    pub disabled_collisions: Vec<(String, String)>,
    /// Virtual joints: where the robot's root link hangs in the world.
    pub virtual_joints: Vec<VirtualJoint>,
}

/// A `<virtual_joint>`: the frame its child link (the robot's root) is placed in. A
/// PlanningScene may give objects in that frame, which is the planning frame.
#[derive(Clone, Debug, PartialEq)]
pub struct VirtualJoint {
    /// `name`.
    pub name: String,
    /// `parent_frame` (`world`, `odom_combined`, …).
    pub parent_frame: String,
    /// `child_link`.
    pub child_link: String,
}

/// A planning group as written: its members, resolved against the URDF by
/// [`crate::robot::Model::resolve_group`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GroupSpec {
    /// The group's name.
    pub name: String,
    /// `<chain base_link tip_link>` members.
    pub chains: Vec<(String, String)>,
    /// `<joint name>` members.
    pub joints: Vec<String>,
    /// `<link name>` members (each brings its parent joint).
    pub links: Vec<String>,
    /// `<group name>` members (subgroups).
    pub subgroups: Vec<String>,
}

/// Reads and parses an SRDF file.
pub fn load_srdf(path: &Path) -> Result<Srdf, RobotError> {
    let text = crate::mesh_io::read_input_text(path)?;
    parse_srdf(&text, path)
}

/// Parses SRDF text; `path` names the file in errors.
pub fn parse_srdf(text: &str, path: &Path) -> Result<Srdf, RobotError> {
    let doc = super::robot_xml(text, path)?;
    let invalid = |message: String| RobotError::Invalid {
        path: path.to_path_buf(),
        message,
    };
    let root = doc.root_element();
    let attr = |n: roxmltree::Node, a: &str| -> Result<String, RobotError> {
        n.attribute(a).map(str::to_string).ok_or_else(|| {
            invalid(format!(
                "<{}> (line {}) has no {a} attribute",
                n.tag_name().name(),
                doc.text_pos_at(n.range().start).row
            ))
        })
    };
    let mut srdf = Srdf::default();
    let mut group_names = std::collections::HashSet::new();
    for node in root.children().filter(|n| n.is_element()) {
        match node.tag_name().name() {
            "group" => {
                let mut g = GroupSpec {
                    name: attr(node, "name")?,
                    ..GroupSpec::default()
                };
                for m in node.children().filter(|n| n.is_element()) {
                    match m.tag_name().name() {
                        "chain" => g.chains.push((attr(m, "base_link")?, attr(m, "tip_link")?)),
                        "joint" => g.joints.push(attr(m, "name")?),
                        "link" => g.links.push(attr(m, "name")?),
                        "group" => g.subgroups.push(attr(m, "name")?),
                        _ => {}
                    }
                }
                if !group_names.insert(g.name.clone()) {
                    return Err(invalid(format!("group {} is defined twice", g.name)));
                }
                srdf.groups.push(g);
            }
            "disable_collisions" => srdf
                .disabled_collisions
                .push((attr(node, "link1")?, attr(node, "link2")?)),
            "virtual_joint" => srdf.virtual_joints.push(VirtualJoint {
                name: attr(node, "name")?,
                parent_frame: attr(node, "parent_frame")?,
                child_link: attr(node, "child_link")?,
            }),
            _ => {}
        }
    }
    Ok(srdf)
}

impl Srdf {
    /// The group called `name`.
    pub fn group(&self, name: &str) -> Option<&GroupSpec> {
        self.groups.iter().find(|g| g.name == name)
    }

    /// Whether the SRDF exempts the pair `(a, b)` (in either order) from collision checking.
    pub fn is_disabled(&self, a: &str, b: &str) -> bool {
        self.disabled_collisions
            .iter()
            .any(|(x, y)| (x == a && y == b) || (x == b && y == a))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_groups_and_disabled_pairs() {
        let s = parse_srdf(
            r#"<robot name="r">
                <virtual_joint name="v" type="fixed" parent_frame="world" child_link="a"/>
                <group name="arm"><chain base_link="a" tip_link="c"/></group>
                <group name="hand"><link name="h"/><joint name="f"/></group>
                <group name="both"><group name="arm"/><group name="hand"/></group>
                <disable_collisions link1="a" link2="b" reason="Adjacent"/>
            </robot>"#,
            Path::new("t.srdf"),
        )
        .unwrap();
        assert_eq!(s.groups.len(), 3);
        assert_eq!(s.group("arm").unwrap().chains, [("a".into(), "c".into())]);
        assert_eq!(s.group("both").unwrap().subgroups, ["arm", "hand"]);
        assert!(s.is_disabled("b", "a"));
        assert!(!s.is_disabled("a", "c"));
        assert_eq!(
            s.virtual_joints,
            [VirtualJoint {
                name: "v".into(),
                parent_frame: "world".into(),
                child_link: "a".into()
            }]
        );
    }

    #[test]
    fn bad_input_is_an_error() {
        for c in [
            "<robot",
            "<srdf/>",
            r#"<robot><group/></robot>"#,
            r#"<robot><disable_collisions link1="a"/></robot>"#,
            r#"<robot><group name="g"/><group name="g"/></robot>"#,
        ] {
            assert!(parse_srdf(c, Path::new("t.srdf")).is_err(), "accepted {c}");
        }
    }
}
