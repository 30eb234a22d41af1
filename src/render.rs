//! Pictures: SVG drawings of planar scenes, paths, borderlines and roadmaps.
//!
//! Draws the position plane (x, y) of any scene: discs and polygons as they are, a rigid robot
//! as its footprint at the corners of a path; SE(3) scenes are drawn from above (obstacle
//! meshes projected to the xy-plane, as outlines).

use crate::geometry::{Polygon, TriMesh};
use crate::local::Borderline;
use crate::roadmap::Roadmap;
use crate::scene::{Obstacle, Robot, Scene};
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
        if let (Robot::Polygons(parts), SpaceKind::Se2) = (&scene.robot, scene.space.kind()) {
            for q in path {
                for part in parts {
                    self.robot_at(part, q);
                }
            }
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

    fn robot_at(&mut self, part: &Polygon, q: &[f64]) {
        let r = Rotation2::new(q[2]);
        let pts: Vec<Point2<f64>> = part
            .vertices
            .iter()
            .map(|v| r * v + nalgebra::Vector2::new(q[0], q[1]))
            .collect();
        let pts = self.polygon_points(&pts);
        let _ = writeln!(
            self.body,
            r#"<polygon points="{pts}" fill="{}" fill-opacity="0.25" stroke="{}" stroke-width="0.6"/>"#,
            style::ROBOT,
            style::ROBOT
        );
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

/// Brooks's freeways (issue 14), kept apart from the local method's layers.
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
