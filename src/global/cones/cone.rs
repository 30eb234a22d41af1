//! Generalized cones from pairs of obstacle edges, pruned where obstacles cut them (Brooks §2).

/// A point of the plane.
pub type P = [f64; 2];

/// An obstacle edge with the side it faces: free space is where `n · x > c`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Edge {
    /// First end.
    pub a: P,
    /// Second end.
    pub b: P,
    /// Unit outward normal, pointing into the free side.
    pub n: P,
    /// Offset of the edge's line: `n · a`.
    pub c: f64,
}

impl Edge {
    /// The edge from `a` to `b` whose free side is on the right of that direction (the
    /// outside of a counter-clockwise polygon); `None` if it has no length.
    pub fn new(a: P, b: P) -> Option<Edge> {
        let e = [b[0] - a[0], b[1] - a[1]];
        let l = e[0].hypot(e[1]);
        if !(l > 0.0 && l.is_finite()) {
            return None;
        }
        let n = [e[1] / l, -e[0] / l];
        Some(Edge {
            a,
            b,
            n,
            c: dot(n, a),
        })
    }

    /// Signed distance of `x` from the edge's line, positive on the free side.
    pub fn side(&self, x: P) -> f64 {
        dot(self.n, x) - self.c
    }
}

pub(crate) fn dot(a: P, b: P) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// A generalized cone with a straight spine and symmetric linear radius (Brooks §2.2 with
/// `b_l = b_r` and `s_l = s_r`: the cone between two edge lines is symmetric about their
/// bisector).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cone {
    /// The two defining edges (indices into the freeway map's edges).
    pub edges: (usize, usize),
    /// The spine point of parameter 0.
    pub origin: P,
    /// Unit direction of the spine.
    pub dir: P,
    /// Spine parameter range `[lo, hi]`.
    pub lo: f64,
    /// Upper end of the spine parameter range.
    pub hi: f64,
    /// Radius at parameter 0: `r(s) = r0 + slope · s`.
    pub r0: f64,
    /// Change of radius per unit of spine (`|slope| < 1`; 0 for parallel edges).
    pub slope: f64,
}

impl Cone {
    /// The spine point of parameter `s`.
    pub fn point(&self, s: f64) -> P {
        [
            self.origin[0] + s * self.dir[0],
            self.origin[1] + s * self.dir[1],
        ]
    }

    /// The radius at spine parameter `s`.
    pub fn radius(&self, s: f64) -> f64 {
        self.r0 + self.slope * s
    }

    /// The smallest radius over `[a, b]` (linear: at an end).
    pub fn min_radius(&self, a: f64, b: f64) -> f64 {
        self.radius(a).min(self.radius(b))
    }

    /// The spine parameter of the foot of `x` on the spine's line.
    pub fn param(&self, x: P) -> f64 {
        dot(self.dir, [x[0] - self.origin[0], x[1] - self.origin[1]])
    }

    /// The spine as a segment.
    pub fn spine(&self) -> [P; 2] {
        [self.point(self.lo), self.point(self.hi)]
    }
}

/// The parameter range `[t0, t1] ⊆ [0, 1]` of `a + t (b − a)` inside all half-planes
/// `g · x ≤ h` (Cyrus–Beck).
fn clip(a: P, b: P, planes: &[(P, f64)]) -> Option<(f64, f64)> {
    let d = [b[0] - a[0], b[1] - a[1]];
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    for &(g, h) in planes {
        let k = dot(g, d);
        let rest = h - dot(g, a);
        if k == 0.0 {
            if rest < 0.0 {
                return None;
            }
        } else if k > 0.0 {
            hi = hi.min(rest / k);
        } else {
            lo = lo.max(rest / k);
        }
        if lo > hi {
            return None;
        }
    }
    Some((lo, hi))
}

/// The candidate cone of two edges (Brooks §2.1): the free sides must face each other
/// (`n₁ · n₂ < 0`) and each edge must have a vertex on the free side of the other. The spine
/// is the bisector of the region on the free side of both, `(n₁ − n₂) · x = c₁ − c₂`; its extent
/// is the projection of those vertices, cut where the radius would vanish.
pub fn candidate(edges: &[Edge], i: usize, j: usize) -> Option<(Cone, [(f64, f64); 2])> {
    let (e1, e2) = (&edges[i], &edges[j]);
    if dot(e1.n, e2.n) >= 0.0 {
        return None;
    }
    let free2 = [e1.a, e1.b].map(|v| e2.side(v) > 0.0);
    let free1 = [e2.a, e2.b].map(|v| e1.side(v) > 0.0);
    if !(free2.iter().any(|&f| f) && free1.iter().any(|&f| f)) {
        return None;
    }
    let m = [e1.n[0] - e2.n[0], e1.n[1] - e2.n[1]];
    let mm = dot(m, m);
    if mm < 1e-24 {
        return None;
    }
    let q = [
        (e1.a[0] + e1.b[0] + e2.a[0] + e2.b[0]) / 4.0,
        (e1.a[1] + e1.b[1] + e2.a[1] + e2.b[1]) / 4.0,
    ];
    let k = ((e1.c - e2.c) - dot(m, q)) / mm;
    let origin = [q[0] + k * m[0], q[1] + k * m[1]];
    let ml = mm.sqrt();
    let dir = [-m[1] / ml, m[0] / ml];
    let r0 = e1.side(origin);
    let slope = dot(e1.n, dir);
    let param = |v: P| dot(dir, [v[0] - origin[0], v[1] - origin[1]]);
    let span = |vs: [P; 2], keep: [bool; 2]| {
        let mut r = (f64::INFINITY, f64::NEG_INFINITY);
        for (v, k) in vs.iter().zip(keep) {
            if k {
                let s = param(*v);
                r = (r.0.min(s), r.1.max(s));
            }
        }
        r
    };
    let s1 = span([e1.a, e1.b], free2);
    let s2 = span([e2.a, e2.b], free1);
    let (mut lo, mut hi) = (s1.0.min(s2.0), s1.1.max(s2.1));
    if slope.abs() > 1e-12 {
        let apex = -r0 / slope;
        if slope > 0.0 {
            lo = lo.max(apex);
        } else {
            hi = hi.min(apex);
        }
    } else if r0 <= 0.0 {
        return None;
    }
    if hi.is_nan() || lo.is_nan() || hi <= lo {
        return None;
    }
    let cone = Cone {
        edges: (i, j),
        origin,
        dir,
        lo,
        hi,
        r0,
        slope,
    };
    // the defining edges' own spine ranges (what a slice must include part of)
    let own = |e: &Edge| {
        let (a, b) = (param(e.a), param(e.b));
        (a.min(b), a.max(b))
    };
    Some((cone, [own(e1), own(e2)]))
}

/// The slices of `cone` that no obstacle edge cuts (Brooks §2.1, Fig. 2): every edge is
/// clipped against the cone (shrunk by `margin` so that the defining edges and their
/// neighbours at the shared vertices do not count) and the clipped part projected on the
/// spine; what is left of `[lo, hi]` are the slices, and those that include part of both
/// defining edges (and are longer than `100 × margin`: slivers between two cuts carry no
/// path) are kept.
pub fn prune(
    cone: &Cone,
    own: [(f64, f64); 2],
    edges: &[Edge],
    boxes: &[[f64; 4]],
    margin: f64,
) -> Vec<Cone> {
    let perp = [-cone.dir[1], cone.dir[0]];
    let rho = 1.0 - 1e-9;
    let x0 = cone.origin;
    let g3 = [
        perp[0] - cone.slope * rho * cone.dir[0],
        perp[1] - cone.slope * rho * cone.dir[1],
    ];
    let g4 = [
        -perp[0] - cone.slope * rho * cone.dir[0],
        -perp[1] - cone.slope * rho * cone.dir[1],
    ];
    let planes = [
        (cone.dir, dot(cone.dir, x0) + cone.hi - margin),
        (
            [-cone.dir[0], -cone.dir[1]],
            -dot(cone.dir, x0) - cone.lo - margin,
        ),
        (g3, dot(g3, x0) + cone.r0 * rho - margin),
        (g4, dot(g4, x0) + cone.r0 * rho - margin),
    ];
    // the cone's box, for a quick rejection of far edges
    let corners = [
        cone.point(cone.lo),
        cone.point(cone.hi),
        [
            cone.point(cone.lo)[0] + perp[0] * cone.radius(cone.lo),
            cone.point(cone.lo)[1] + perp[1] * cone.radius(cone.lo),
        ],
        [
            cone.point(cone.lo)[0] - perp[0] * cone.radius(cone.lo),
            cone.point(cone.lo)[1] - perp[1] * cone.radius(cone.lo),
        ],
        [
            cone.point(cone.hi)[0] + perp[0] * cone.radius(cone.hi),
            cone.point(cone.hi)[1] + perp[1] * cone.radius(cone.hi),
        ],
        [
            cone.point(cone.hi)[0] - perp[0] * cone.radius(cone.hi),
            cone.point(cone.hi)[1] - perp[1] * cone.radius(cone.hi),
        ],
    ];
    let bx = corners.iter().fold(
        [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ],
        |b, p| {
            [
                b[0].min(p[0]),
                b[1].min(p[1]),
                b[2].max(p[0]),
                b[3].max(p[1]),
            ]
        },
    );
    let mut cut: Vec<(f64, f64)> = Vec::new();
    for (k, e) in edges.iter().enumerate() {
        let b = boxes[k];
        if b[0] > bx[2] || b[2] < bx[0] || b[1] > bx[3] || b[3] < bx[1] {
            continue;
        }
        if let Some((t0, t1)) = clip(e.a, e.b, &planes) {
            let at = |t: f64| {
                [
                    e.a[0] + t * (e.b[0] - e.a[0]),
                    e.a[1] + t * (e.b[1] - e.a[1]),
                ]
            };
            let (s0, s1) = (cone.param(at(t0)), cone.param(at(t1)));
            cut.push((s0.min(s1), s0.max(s1)));
        }
    }
    cut.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut slices = Vec::new();
    let mut at = cone.lo;
    for (lo, hi) in cut.into_iter().chain(std::iter::once((cone.hi, cone.hi))) {
        if lo > at {
            slices.push((at, lo.min(cone.hi)));
        }
        at = at.max(hi);
    }
    let meets = |s: (f64, f64), o: (f64, f64)| s.0 < o.1 && o.0 < s.1;
    slices
        .into_iter()
        .filter(|&s| s.1 - s.0 > 100.0 * margin && meets(s, own[0]) && meets(s, own[1]))
        .map(|(lo, hi)| Cone { lo, hi, ..*cone })
        .collect()
}
