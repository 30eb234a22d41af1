//! Convex hulls (of points given inline in a scene, of a robot's curved primitives) and the
//! check that a polygon is simple. (Footprints of OMPL.app's 2D prism meshes come from
//! [`super::footprint`].)

use crate::geometry::{GeometryError, Polygon, TriMesh};
use nalgebra::{Point2, Point3};

/// The convex hull of points in the plane (Andrew's monotone chain), counter-clockwise,
/// collinear points dropped. Fails if the points span no area.
pub fn convex_hull_2d(points: &[Point2<f64>]) -> Result<Polygon, GeometryError> {
    if let Some(i) = points
        .iter()
        .position(|p| !(p.x.is_finite() && p.y.is_finite()))
    {
        return Err(GeometryError::NotFinite(i));
    }
    let mut p = points.to_vec();
    p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    p.dedup();
    if p.len() < 3 {
        return Err(GeometryError::DegeneratePolygon);
    }
    let turn = |o: Point2<f64>, a: Point2<f64>, b: Point2<f64>| (a - o).perp(&(b - o));
    let mut hull: Vec<Point2<f64>> = Vec::with_capacity(2 * p.len());
    for pass in [p.clone(), p.iter().rev().copied().collect()] {
        let start = hull.len();
        for q in pass {
            while hull.len() >= start + 2
                && turn(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0
            {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop(); // the last point starts the other chain
    }
    Polygon::new(hull)
}

/// The convex hull of points in space as a closed, outward-oriented triangle mesh. Fails if
/// the points are coplanar (no volume) or fewer than four.
pub fn convex_hull_3d(points: &[Point3<f64>]) -> Result<TriMesh, GeometryError> {
    if let Some(i) = points
        .iter()
        .position(|p| !p.coords.iter().all(|c| c.is_finite()))
    {
        return Err(GeometryError::NotFinite(i));
    }
    if points.len() < 4 {
        return Err(GeometryError::Empty);
    }
    let (vertices, mut triangles) =
        parry3d_f64::transformation::try_convex_hull(points).map_err(|_| GeometryError::Empty)?;
    let volume: f64 = triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|k| vertices[k as usize].coords);
            a.dot(&b.cross(&c)) / 6.0
        })
        .sum();
    let (lo, hi) = points
        .iter()
        .fold((points[0].coords, points[0].coords), |(lo, hi), p| {
            (lo.inf(&p.coords), hi.sup(&p.coords))
        });
    if volume.abs() <= 1e-12 * (hi - lo).norm().powi(3) {
        return Err(GeometryError::Empty);
    }
    if volume < 0.0 {
        triangles.iter_mut().for_each(|t| t.swap(1, 2));
    }
    TriMesh::new(vertices, triangles)
}

/// Whether no two non-adjacent edges of the polygon meet (touching counts as meeting).
pub fn is_simple(polygon: &Polygon) -> bool {
    let n = polygon.vertices.len();
    let orient = |a: Point2<f64>, b: Point2<f64>, c: Point2<f64>| (b - a).perp(&(c - a));
    let on_segment = |a: Point2<f64>, b: Point2<f64>, p: Point2<f64>| {
        p.x >= a.x.min(b.x) && p.x <= a.x.max(b.x) && p.y >= a.y.min(b.y) && p.y <= a.y.max(b.y)
    };
    let meet = |(a, b): (Point2<f64>, Point2<f64>), (c, d): (Point2<f64>, Point2<f64>)| {
        let (d1, d2) = (orient(c, d, a), orient(c, d, b));
        let (d3, d4) = (orient(a, b, c), orient(a, b, d));
        if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
            && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
        {
            return true;
        }
        (d1 == 0.0 && on_segment(c, d, a))
            || (d2 == 0.0 && on_segment(c, d, b))
            || (d3 == 0.0 && on_segment(a, b, c))
            || (d4 == 0.0 && on_segment(a, b, d))
    };
    for i in 0..n {
        for j in i + 1..n {
            let adjacent = j == i + 1 || (i == 0 && j == n - 1);
            if adjacent {
                // adjacent edges share a vertex; they must not fold back onto each other
                let v = &polygon.vertices;
                let (p, shared, q) = if j == i + 1 {
                    (v[i], v[j], v[(j + 1) % n])
                } else {
                    (v[1], v[0], v[n - 1])
                };
                if orient(shared, p, q) == 0.0 && (p - shared).dot(&(q - shared)) > 0.0 {
                    return false;
                }
                continue;
            }
            if meet(polygon.edge(i), polygon.edge(j)) {
                return false;
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hull_2d_drops_interior_and_collinear_points() {
        let pts = [
            (0.0, 0.0),
            (1.0, 0.0),
            (2.0, 0.0),
            (2.0, 2.0),
            (0.0, 2.0),
            (1.0, 1.0),
        ]
        .map(|(x, y)| Point2::new(x, y));
        let h = convex_hull_2d(&pts).unwrap();
        assert_eq!(h.vertices.len(), 4);
        assert!((h.area() - 4.0).abs() < 1e-12);
        assert!(convex_hull_2d(&pts[..3]).is_err());
    }

    #[test]
    fn hull_3d_is_closed_and_outward() {
        let pts: Vec<Point3<f64>> = (0..8)
            .map(|i| Point3::new((i & 1) as f64, ((i >> 1) & 1) as f64, (i >> 2) as f64))
            .chain([Point3::new(0.5, 0.5, 0.5)])
            .collect();
        let m = convex_hull_3d(&pts).unwrap();
        assert!(m.is_closed());
        assert!((m.volume() - 1.0).abs() < 1e-9);
        let flat: Vec<Point3<f64>> = pts.iter().map(|p| Point3::new(p.x, p.y, 0.0)).collect();
        assert!(convex_hull_3d(&flat).is_err());
    }

    #[test]
    fn bow_tie_is_not_simple() {
        let bow = Polygon {
            vertices: [(0.0, 0.0), (1.0, 1.0), (1.0, 0.0), (0.0, 1.0)]
                .map(|(x, y)| Point2::new(x, y))
                .to_vec(),
        };
        assert!(!is_simple(&bow));
        let square = Polygon::rectangle([0.0, 0.0], [1.0, 1.0]).unwrap();
        assert!(is_simple(&square));
    }
}
