//! Pictures: SVG drawings of planar scenes, paths, borderlines and roadmaps.
//!
//! Draws the position plane (x, y) of any scene: discs and polygons as they are, a rigid robot
//! as its footprint at the corners of a path; SE(3) scenes are drawn from above (obstacle
//! meshes projected to the xy-plane, as outlines, and the robot's footprint — the outline of
//! its projection — at the corners of a path).

use crate::geometry::{Polygon, TriMesh};
use crate::local::Borderline;
use crate::roadmap::Roadmap;
use crate::scene::{Body, Obstacle, Robot, Scene};
use crate::space::{Config, SpaceKind};
use nalgebra::{Point2, Rotation2};
use std::fmt::Write as _;
use std::path::Path;

/// An SVG picture of a scene's position plane, built up layer by layer.
pub struct Picture {
    min: [f64; 2],
    max: [f64; 2],
    scale: f64,
    body: String,
}

/// Colours and widths of the layers (one documented place for the stray constants).
mod style {
    pub const OBSTACLE: &str = "#9aa5b1";
    pub const OBSTACLE_EDGE: &str = "#52606d";
    pub const BOUNDS: &str = "#1f2933";
    pub const RAW_PATH: &str = "#e12d39";
    pub const SHORT_PATH: &str = "#0967d2";
    pub const BORDERLINE: &str = "#f0b429";
    pub const VIA_POINT: &str = "#8719e0";
    pub const ROADMAP_EDGE: &str = "#cbd2d9";
    pub const ROADMAP_NODE: &str = "#7b8794";
    pub const ROBOT: &str = "#3ebd93";
    /// One colour per body of a scene of several bodies, in turn.
    pub const BODIES: [&str; 8] = [
        "#3ebd93", "#e12d39", "#0967d2", "#f0b429", "#8719e0", "#c65d21", "#27ab83", "#da127d",
    ];
    /// Picture width in pixels.
    pub const WIDTH: f64 = 800.0;
}

impl Picture {
    /// A blank picture of the scene's position bounds (the first two coordinates).
    pub fn new(scene: &Scene) -> Picture {
        let (lo, hi) = (scene.space.lower(), scene.space.upper());
        let min = [lo[0], lo.get(1).copied().unwrap_or(lo[0])];
        let max = [hi[0], hi.get(1).copied().unwrap_or(hi[0])];
        let span = (max[0] - min[0])
            .max(max[1] - min[1])
            .max(f64::MIN_POSITIVE);
        let mut p = Picture {
            min,
            max,
            scale: style::WIDTH / span,
            body: String::new(),
        };
        p.rect_outline();
        p
    }

    fn x(&self, x: f64) -> f64 {
        (x - self.min[0]) * self.scale
    }

    fn y(&self, y: f64) -> f64 {
        (self.max[1] - y) * self.scale
    }

    fn rect_outline(&mut self) {
        let (w, h) = (self.x(self.max[0]), self.y(self.min[1]));
        let _ = writeln!(
            self.body,
            r#"<rect x="0" y="0" width="{w:.2}" height="{h:.2}" fill="white" stroke="{}" stroke-width="2"/>"#,
            style::BOUNDS
        );
    }

    fn polygon_points(&self, pts: &[Point2<f64>]) -> String {
        pts.iter()
            .map(|p| format!("{:.2},{:.2}", self.x(p.x), self.y(p.y)))
            .collect::<Vec<_>>()
            .join(" ")
    }

    /// Draws the obstacles.
    pub fn obstacles(&mut self, scene: &Scene) -> &mut Self {
        for o in &scene.obstacles {
            match o {
                Obstacle::Disc { centre, radius } => {
                    let _ = writeln!(
                        self.body,
                        r#"<circle cx="{:.2}" cy="{:.2}" r="{:.2}" fill="{}" stroke="{}"/>"#,
                        self.x(centre[0]),
                        self.y(centre[1]),
                        radius * self.scale,
                        style::OBSTACLE,
                        style::OBSTACLE_EDGE
                    );
                }
                Obstacle::Polygon(p) => self.filled(&p.vertices, style::OBSTACLE),
                Obstacle::Mesh(m) => self.mesh_from_above(m, style::OBSTACLE),
            }
        }
        self
    }

    fn filled(&mut self, pts: &[Point2<f64>], fill: &str) {
        let pts = self.polygon_points(pts);
        let _ = writeln!(
            self.body,
            r#"<polygon points="{pts}" fill="{fill}" fill-opacity="0.8" stroke="{}" stroke-width="0.5"/>"#,
            style::OBSTACLE_EDGE
        );
    }

    fn mesh_from_above(&mut self, m: &TriMesh, fill: &str) {
        for i in 0..m.triangles.len() {
            let t = m.triangle(i);
            let pts: Vec<Point2<f64>> = t.iter().map(|v| Point2::new(v.x, v.y)).collect();
            let pts = self.polygon_points(&pts);
            let _ = writeln!(
                self.body,
                r#"<polygon points="{pts}" fill="{fill}" fill-opacity="0.15" stroke="none"/>"#
            );
        }
    }

    /// Draws a path as a polyline through the positions of its corners; for a planar rigid
    /// robot also its footprint at every corner.
    pub fn path(&mut self, scene: &Scene, path: &[Config], shortened: bool) -> &mut Self {
        if path.is_empty() {
            return self;
        }
        if let Robot::Bodies(bodies) = &scene.robot {
            return self.bodies_path(bodies, path, shortened);
        }
        match (&scene.robot, scene.space.kind()) {
            (Robot::Polygons(parts), SpaceKind::Se2) => {
                for q in path {
                    for part in parts {
                        self.robot_at(part, q);
                    }
                }
            }
            (Robot::Mesh(mesh), SpaceKind::Se3) => {
                let shadow = Shadow::of(mesh);
                for q in path {
                    self.shadow_at(&shadow, q);
                }
            }
            _ => {}
        }
        let (colour, width, dash) = if shortened {
            (style::SHORT_PATH, 2.5, "")
        } else {
            (style::RAW_PATH, 1.5, r#" stroke-dasharray="6,3""#)
        };
        let pts: Vec<Point2<f64>> = path.iter().map(|q| Point2::new(q[0], q[1])).collect();
        let pts = self.polygon_points(&pts);
        let _ = writeln!(
            self.body,
            r#"<polyline points="{pts}" fill="none" stroke="{colour}" stroke-width="{width}"{dash}/>"#
        );
        for q in [&path[0], &path[path.len() - 1]] {
            let _ = writeln!(
                self.body,
                r#"<circle cx="{:.2}" cy="{:.2}" r="5" fill="{colour}"/>"#,
                self.x(q[0]),
                self.y(q[1])
            );
        }
        self
    }

    /// Several bodies along a path: each body in its own colour at every corner, the trace of
    /// its reference point, and its name at the start.
    fn bodies_path(&mut self, bodies: &[Body], path: &[Config], shortened: bool) -> &mut Self {
        let dash = if shortened {
            ""
        } else {
            r#" stroke-dasharray="6,3""#
        };
        let mut labels = String::new();
        for (i, body) in bodies.iter().enumerate() {
            let colour = style::BODIES[i % style::BODIES.len()];
            let poses: Vec<&[f64]> = path
                .iter()
                .filter(|q| q.len() >= 3 * i + 3)
                .map(|q| &q[3 * i..3 * i + 3])
                .collect();
            for q in &poses {
                for part in &body.parts {
                    self.part_at(part, q, colour, 0.12);
                }
            }
            let pts: Vec<Point2<f64>> = poses.iter().map(|q| Point2::new(q[0], q[1])).collect();
            let pts = self.polygon_points(&pts);
            let _ = writeln!(
                self.body,
                r#"<polyline points="{pts}" fill="none" stroke="{colour}" stroke-width="2"{dash}/>"#
            );
            if let (Some(first), Some(last)) = (poses.first(), poses.last()) {
                for part in &body.parts {
                    self.part_at(part, last, colour, 0.5);
                }
                let _ = writeln!(
                    labels,
                    r#"<text x="{:.2}" y="{:.2}" font-size="16" font-weight="bold" font-family="sans-serif" text-anchor="middle" fill="{colour}">{}</text>"#,
                    self.x(first[0]),
                    self.y(first[1]) + 5.0,
                    xml_escape(&body.name)
                );
            }
        }
        self.body.push_str(&labels);
        self
    }

    fn part_at(&mut self, part: &Polygon, q: &[f64], colour: &str, opacity: f64) {
        let r = Rotation2::new(q[2]);
        let pts: Vec<Point2<f64>> = part
            .vertices
            .iter()
            .map(|v| r * v + nalgebra::Vector2::new(q[0], q[1]))
            .collect();
        let pts = self.polygon_points(&pts);
        let _ = writeln!(
            self.body,
            r#"<polygon points="{pts}" fill="{colour}" fill-opacity="{opacity}" stroke="{colour}" stroke-width="0.6"/>"#,
        );
    }

    fn robot_at(&mut self, part: &Polygon, q: &[f64]) {
        self.part_at(part, q, style::ROBOT, 0.25);
    }

    /// Draws the projection of an SE(3) robot placed at `q` onto the xy-plane: its triangles
    /// filled inside one group whose opacity applies to the union, so the drawing is the
    /// footprint's exact outline, evenly tinted.
    fn shadow_at(&mut self, shadow: &Shadow, q: &[f64]) {
        let r = crate::space::rotation::quat_from_slice(&q[3..7]);
        let placed: Vec<Point2<f64>> = shadow
            .points
            .iter()
            .map(|v| {
                let w = r * v;
                Point2::new(w.x + q[0], w.y + q[1])
            })
            .collect();
        let _ = writeln!(
            self.body,
            r#"<g opacity="0.3" fill="{0}" stroke="{0}" stroke-width="0.6" stroke-linejoin="round">"#,
            style::ROBOT
        );
        match &shadow.triangles {
            Some(tris) => {
                for t in tris {
                    let pts = self.polygon_points(&t.map(|i| placed[i]));
                    let _ = writeln!(self.body, r#"<polygon points="{pts}"/>"#);
                }
            }
            None => {
                let pts = self.polygon_points(&convex_hull(&placed));
                let _ = writeln!(self.body, r#"<polygon points="{pts}"/>"#);
            }
        }
        let _ = writeln!(self.body, "</g>");
    }

    /// Draws the free sections of borderlines the planner asked about (straight lines in the
    /// position plane only) and the via points it took from them.
    pub fn borderlines(&mut self, lines: &[Borderline]) -> &mut Self {
        for b in lines {
            if let crate::space::Change::Linear(d) = &b.motion.change {
                if d.len() >= 2 && d[..2].iter().any(|v| *v != 0.0) {
                    for s in b.free.iter() {
                        let (p, q) = (b.motion.at(s.lo), b.motion.at(s.hi));
                        let _ = writeln!(
                            self.body,
                            r#"<line x1="{:.2}" y1="{:.2}" x2="{:.2}" y2="{:.2}" stroke="{}" stroke-width="1" stroke-opacity="0.7"/>"#,
                            self.x(p[0]),
                            self.y(p[1]),
                            self.x(q[0]),
                            self.y(q[1]),
                            style::BORDERLINE
                        );
                    }
                }
            }
            for v in &b.via_points {
                let _ = writeln!(
                    self.body,
                    r#"<circle cx="{:.2}" cy="{:.2}" r="3" fill="{}"/>"#,
                    self.x(v[0]),
                    self.y(v[1]),
                    style::VIA_POINT
                );
            }
        }
        self
    }

    /// Draws a roadmap: every edge along its corners, every node as a dot.
    pub fn roadmap(&mut self, roadmap: &Roadmap) -> &mut Self {
        for (e, edge) in roadmap.edges().iter().enumerate() {
            let pts: Vec<Point2<f64>> = roadmap
                .edge_path(e, edge.a)
                .iter()
                .map(|q| Point2::new(q[0], q[1]))
                .collect();
            let pts = self.polygon_points(&pts);
            let _ = writeln!(
                self.body,
                r#"<polyline points="{pts}" fill="none" stroke="{}" stroke-width="0.6"/>"#,
                style::ROADMAP_EDGE
            );
        }
        for n in roadmap.nodes() {
            let _ = writeln!(
                self.body,
                r#"<circle cx="{:.2}" cy="{:.2}" r="1.5" fill="{}"/>"#,
                self.x(n[0]),
                self.y(n[1]),
                style::ROADMAP_NODE
            );
        }
        self
    }

    /// The SVG document.
    pub fn to_svg(&self) -> String {
        let (w, h) = (self.x(self.max[0]), self.y(self.min[1]));
        format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w:.0}\" height=\"{h:.0}\" viewBox=\"-5 -5 {:.2} {:.2}\">\n{}</svg>\n",
            w + 10.0,
            h + 10.0,
            self.body
        )
    }

    /// Writes the SVG document to `path`.
    pub fn save(&self, path: &Path) -> std::io::Result<()> {
        std::fs::write(path, self.to_svg())
    }
}

/// Brooks's freeways, kept apart from the local method's layers.
impl Picture {
    /// Draws generalized cones: each as a faint trapezoid about its spine, the spine as a line
    /// (`viaroad render --freeways`).
    pub fn freeways(&mut self, fw: &crate::global::cones::Freeways) -> &mut Self {
        const CONE: &str = "#f9703e";
        const SPINE: &str = "#cb4e35";
        for c in fw.cones() {
            let perp = [-c.dir[1], c.dir[0]];
            let side = |s: f64, k: f64| {
                let p = c.point(s);
                let r = c.radius(s) * k;
                Point2::new(p[0] + perp[0] * r, p[1] + perp[1] * r)
            };
            let pts = [
                side(c.lo, 1.0),
                side(c.hi, 1.0),
                side(c.hi, -1.0),
                side(c.lo, -1.0),
            ];
            let pts = self.polygon_points(&pts);
            let _ = writeln!(
                self.body,
                r#"<polygon points="{pts}" fill="{CONE}" fill-opacity="0.06" stroke="none"/>"#
            );
            let [a, b] = c.spine();
            let _ = writeln!(
                self.body,
                r#"<line x1="{:.2}" y1="{:.2}" x2="{:.2}" y2="{:.2}" stroke="{SPINE}" stroke-width="0.8"/>"#,
                self.x(a[0]),
                self.y(a[1]),
                self.x(b[0]),
                self.y(b[1]),
            );
        }
        self
    }
}

/// Most triangles drawn per footprint of an SE(3) robot: beyond it (the alpha puzzle's tube)
/// the footprint is drawn as the convex hull of the projected vertices, so that the SVG stays
/// small.
const MAX_SHADOW_TRIANGLES: usize = 1500;

/// What an SE(3) robot's footprint is drawn from: its vertices (body frame) and the triangles
/// whose projection can have area whatever the orientation (`None`: draw the hull).
struct Shadow {
    points: Vec<nalgebra::Point3<f64>>,
    triangles: Option<Vec<[usize; 3]>>,
}

impl Shadow {
    fn of(mesh: &TriMesh) -> Shadow {
        // a triangle of zero area projects to nothing in any direction
        let tris: Vec<[usize; 3]> = mesh
            .triangles
            .iter()
            .map(|t| t.map(|i| i as usize))
            .filter(|t| {
                let [a, b, c] = t.map(|i| mesh.vertices[i]);
                (b - a).cross(&(c - a)).norm() > 0.0
            })
            .collect();
        Shadow {
            points: mesh.vertices.clone(),
            triangles: (tris.len() <= MAX_SHADOW_TRIANGLES).then_some(tris),
        }
    }
}

/// The convex hull of points, counter-clockwise (Andrew's monotone chain).
fn convex_hull(points: &[Point2<f64>]) -> Vec<Point2<f64>> {
    let mut p: Vec<Point2<f64>> = points.to_vec();
    p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let cross = |o: Point2<f64>, a: Point2<f64>, b: Point2<f64>| {
        (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x)
    };
    let mut hull: Vec<Point2<f64>> = Vec::with_capacity(2 * p.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &Point2<f64>>> = if pass == 0 {
            Box::new(p.iter())
        } else {
            Box::new(p.iter().rev())
        };
        for &q in iter {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0
            {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    hull
}

/// `s` with the characters XML gives meaning to escaped (body names are the user's text).
fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hull_of_a_square_with_inner_points() {
        let pts: Vec<Point2<f64>> = [
            [0.0, 0.0],
            [1.0, 0.0],
            [0.5, 0.5],
            [1.0, 1.0],
            [0.0, 1.0],
            [0.2, 0.7],
        ]
        .iter()
        .map(|p| Point2::new(p[0], p[1]))
        .collect();
        let h = convex_hull(&pts);
        assert_eq!(h.len(), 4);
        let area: f64 = (0..h.len())
            .map(|i| {
                let (a, b) = (h[i], h[(i + 1) % h.len()]);
                a.x * b.y - b.x * a.y
            })
            .sum::<f64>()
            / 2.0;
        assert!(
            (area - 1.0).abs() < 1e-12,
            "counter-clockwise, area 1: {area}"
        );
    }

    #[test]
    fn se3_footprints_are_drawn_at_every_corner_where_the_robot_is() {
        let scene = Scene::load(
            &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cube-into-box.toml"),
        )
        .unwrap();
        // the unit cube at (2, 2) upright, then at (-1, 0) turned 45° about z
        let path = vec![
            vec![2.0, 2.0, 2.5, 0.0, 0.0, 0.0, 1.0],
            vec![
                -1.0,
                0.0,
                2.5,
                0.0,
                0.0,
                (std::f64::consts::PI / 8.0).sin(),
                (std::f64::consts::PI / 8.0).cos(),
            ],
        ];
        let mut p = Picture::new(&scene);
        p.path(&scene, &path, true);
        let svg = p.to_svg();
        assert_eq!(svg.matches("<g opacity=").count(), 2);
        // every drawn vertex of a footprint lies on the projected cube at its corner: within
        // half a side (upright) or half a diagonal (turned) of the centre, in picture units
        let scale = style::WIDTH / 6.0;
        let groups: Vec<&str> = svg.split("<g opacity=").skip(1).collect();
        for (g, (centre, reach)) in groups
            .iter()
            .zip([([2.0, 2.0], 0.5), ([-1.0, 0.0], 0.5 * 2f64.sqrt())])
        {
            let body = &g[..g.find("</g>").unwrap()];
            let mut far = 0.0f64;
            let mut n = 0;
            for poly in body.split("points=\"").skip(1) {
                for xy in poly[..poly.find('"').unwrap()].split_whitespace() {
                    let (x, y) = xy.split_once(',').unwrap();
                    let (x, y): (f64, f64) = (x.parse().unwrap(), y.parse().unwrap());
                    let (wx, wy) = (x / scale - 3.0, 3.0 - y / scale);
                    far = far.max((wx - centre[0]).abs().max((wy - centre[1]).abs()));
                    n += 1;
                }
            }
            assert!(n > 0);
            assert!((far - reach).abs() < 0.02, "{far} vs {reach}");
        }
    }
}
