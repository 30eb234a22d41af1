//! Simple polygons in the plane.

use super::GeometryError;
use nalgebra::{Point2, Vector2};

/// A simple polygon (not necessarily convex), vertices counter-clockwise.
#[derive(Clone, Debug, PartialEq)]
pub struct Polygon {
    /// Vertices in counter-clockwise order; the last connects back to the first.
    pub vertices: Vec<Point2<f64>>,
}

impl Polygon {
    /// A polygon from vertices in either orientation (clockwise input is reversed). Rejects
    /// NaN, fewer than three vertices and zero area.
    pub fn new(mut vertices: Vec<Point2<f64>>) -> Result<Polygon, GeometryError> {
        if let Some(i) = vertices
            .iter()
            .position(|v| !(v.x.is_finite() && v.y.is_finite()))
        {
            return Err(GeometryError::NotFinite(i));
        }
        if vertices.len() < 3 {
            return Err(GeometryError::DegeneratePolygon);
        }
        let area = signed_area(&vertices);
        if area == 0.0 {
            return Err(GeometryError::DegeneratePolygon);
        }
        if area < 0.0 {
            vertices.reverse();
        }
        Ok(Polygon { vertices })
    }

    /// The axis-aligned rectangle `centre ± half_extents`.
    pub fn rectangle(centre: [f64; 2], half_extents: [f64; 2]) -> Result<Polygon, GeometryError> {
        if !half_extents.iter().all(|h| h.is_finite() && *h > 0.0) {
            return Err(GeometryError::NotPositive("rectangle half extents"));
        }
        let [cx, cy] = centre;
        let [hx, hy] = half_extents;
        Polygon::new(vec![
            Point2::new(cx - hx, cy - hy),
            Point2::new(cx + hx, cy - hy),
            Point2::new(cx + hx, cy + hy),
            Point2::new(cx - hx, cy + hy),
        ])
    }

    /// The polygon moved by `offset`.
    pub fn translated(mut self, offset: Vector2<f64>) -> Polygon {
        self.vertices.iter_mut().for_each(|v| *v += offset);
        self
    }

    /// Edge `i`, from vertex `i` to vertex `i + 1` (cyclically).
    pub fn edge(&self, i: usize) -> (Point2<f64>, Point2<f64>) {
        (
            self.vertices[i],
            self.vertices[(i + 1) % self.vertices.len()],
        )
    }

    /// Area (positive).
    pub fn area(&self) -> f64 {
        signed_area(&self.vertices)
    }

    /// Largest distance of a vertex from the origin.
    pub fn radius(&self) -> f64 {
        self.vertices
            .iter()
            .map(|v| v.coords.norm())
            .fold(0.0, f64::max)
    }
}

fn signed_area(v: &[Point2<f64>]) -> f64 {
    let n = v.len();
    0.5 * (0..n)
        .map(|i| {
            let (a, b) = (v[i], v[(i + 1) % n]);
            a.x * b.y - b.x * a.y
        })
        .sum::<f64>()
}
