//! Oriented bounding boxes in the table frame and the relations section 4.5.5 reads off them.
//!
//! The dissertation represents every object, and the table, by an oriented bounding box (OBB)
//! and derives the evidence of Tab. 4.1 from pairs of boxes:
//!
//! * **stable** ([`Obb::is_stable`]): some edge of the box is parallel to the table's vertical
//!   axis, i.e. the box stands on one of its faces;
//! * **contact** and **intersect** ([`relation`]): two boxes *touch* when their boundaries meet
//!   but their interiors do not, which section 4.5.5 splits into three cases by the shape of
//!   the set of touching points: a single vertex, co-linear points on an edge, coplanar points
//!   on a facet ([`contact_kind`]); anything else where the boxes meet, including one box
//!   inside the other, is an intersection;
//! * **higher** ([`higher`]): one box is above the other.
//!
//! # Tolerances
//!
//! Poses come from a noisy estimator, so "exactly touching" and "exactly vertical" never
//! happen; every test takes a tolerance from [`Tolerances`]:
//!
//! * two boxes whose gap is at most [`Tolerances::contact`] touch, and so do two boxes that
//!   overlap by at most that much (their penetration depth, the smallest translation that
//!   separates them); a deeper overlap is an intersection;
//! * a box is stable when one of its axes is within [`Tolerances::stable_angle`] of vertical;
//! * one box is higher than another when its centre is higher and, seen from above, their
//!   footprints overlap by more than [`Tolerances::footprint`]. Requiring the overlap is what
//!   makes `higher` mean "above", as in the dissertation's example (Fig. 4.9-b: #5 is higher
//!   than #2, which it hovers over, but not than #1 beside it). Without it, the taller of two
//!   boxes standing side by side would "support" the shorter through rule r10. The footprint
//!   tolerance is twice the contact tolerance by default, so that two neighbours that
//!   interpenetrate within the contact tolerance never count as stacked.
//!
//! # How the relation is computed
//!
//! The separating-axis test on the 15 candidate axes of two boxes (three face normals each,
//! nine edge cross products) gives the penetration depth when the boxes overlap, exactly: the
//! smallest overlap along those axes. When they do not overlap, the largest gap along an axis
//! is only a lower bound of their distance, so when that bound is within the tolerance the
//! exact distance is computed from the features that can realise it (a vertex of one box and
//! the other box, or an edge of each). Containment is checked on the vertices.
//!
//! Everything here is plain arithmetic and square roots (correctly rounded everywhere), so
//! results are identical natively and in WebAssembly.
//!
//! ```
//! use ksmcmc::tabletop::geometry::{relation, Obb, Relation, Tolerances};
//! use nalgebra::{UnitQuaternion, Vector3};
//!
//! let table = Obb::table([1.0, 1.0], 0.05);
//! let cube = |z: f64| Obb::new(Vector3::new(0.0, 0.0, z), UnitQuaternion::identity(), Vector3::new(0.1, 0.1, 0.1));
//! let tol = Tolerances::default();
//! assert_eq!(relation(&cube(0.05), &table, &tol), Relation::Contact); // resting on it
//! assert_eq!(relation(&cube(0.08), &table, &tol), Relation::Apart); // 3 cm above
//! assert_eq!(relation(&cube(0.02), &table, &tol), Relation::Intersect); // 3 cm into it
//! ```

use crate::setting::{check, InvalidSetting};
use nalgebra::{Matrix3, UnitQuaternion, Vector2, Vector3};
use serde::{Deserialize, Serialize};

/// The tolerances of the geometric tests (metres and radians).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Tolerances {
    /// Largest gap at which two boxes still touch, and largest penetration depth at which they
    /// touch rather than intersect (metres; default 0.005).
    pub contact: f64,
    /// Largest angle between a box axis and the vertical for the box to be stable (radians;
    /// default 5 degrees).
    pub stable_angle: f64,
    /// Smallest overlap of two footprints (seen from above, metres) for one box to be higher
    /// than the other (default 0.01, twice the contact tolerance).
    pub footprint: f64,
}

impl Default for Tolerances {
    fn default() -> Self {
        Tolerances { contact: 0.005, stable_angle: 5.0 * std::f64::consts::PI / 180.0, footprint: 0.01 }
    }
}

impl Tolerances {
    /// Checks the values: the contact and footprint tolerances in `[0, 0.1]` metres, the angle
    /// in `[0, pi/4]`.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        let Tolerances { contact, stable_angle, footprint } = *self;
        check((0.0..=0.1).contains(&contact), "contact", contact, "metres from 0 to 0.1")?;
        check((0.0..=0.1).contains(&footprint), "footprint", footprint, "metres from 0 to 0.1")?;
        let angle = (0.0..=std::f64::consts::FRAC_PI_4).contains(&stable_angle);
        check(angle, "stable_angle", stable_angle, "radians from 0 to pi/4")
    }
}

/// An oriented box: centre, unit axes (the columns of `axes`) and half extents along them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Obb {
    /// Centre in the table frame.
    pub center: Vector3<f64>,
    /// Rotation from the box frame to the table frame; its columns are the box axes.
    pub axes: Matrix3<f64>,
    /// Half the extent along each axis (positive).
    pub half: Vector3<f64>,
}

/// The 12 edges of a box as pairs of [`Obb::vertex`] indices.
pub const EDGES: [(usize, usize); 12] = {
    let mut edges = [(0, 0); 12];
    let mut n = 0;
    let mut k = 0;
    while k < 3 {
        let mut i = 0;
        while i < 8 {
            if i & (1 << k) == 0 {
                edges[n] = (i, i | (1 << k));
                n += 1;
            }
            i += 1;
        }
        k += 1;
    }
    edges
};

impl Obb {
    /// A box of full extents `size` centred at `center`, rotated by `rotation` (box frame to
    /// table frame).
    pub fn new(center: Vector3<f64>, rotation: UnitQuaternion<f64>, size: Vector3<f64>) -> Obb {
        Obb { center, axes: *rotation.to_rotation_matrix().matrix(), half: size / 2.0 }
    }

    /// The table as a box: its top is the rectangle `[-sx/2, sx/2] x [-sy/2, sy/2]` in the
    /// plane `z = 0`, and it is `thickness` deep.
    pub fn table(size: [f64; 2], thickness: f64) -> Obb {
        Obb {
            center: Vector3::new(0.0, 0.0, -thickness / 2.0),
            axes: Matrix3::identity(),
            half: Vector3::new(size[0] / 2.0, size[1] / 2.0, thickness / 2.0),
        }
    }

    /// Box axis `k` (0, 1 or 2) as a unit vector in the table frame.
    #[inline]
    pub fn axis(&self, k: usize) -> Vector3<f64> {
        self.axes.column(k).into_owned()
    }

    /// Vertex `i` (0 to 7): bit `k` of `i` set means the positive end of axis `k`.
    pub fn vertex(&self, i: usize) -> Vector3<f64> {
        let mut v = self.center;
        for k in 0..3 {
            let s = if i & (1 << k) != 0 { self.half[k] } else { -self.half[k] };
            v += self.axis(k) * s;
        }
        v
    }

    /// All eight vertices.
    pub fn vertices(&self) -> [Vector3<f64>; 8] {
        std::array::from_fn(|i| self.vertex(i))
    }

    /// A point in the box frame (origin at the centre, axes along the box axes).
    #[inline]
    pub fn to_local(&self, p: &Vector3<f64>) -> Vector3<f64> {
        self.axes.tr_mul(&(p - self.center))
    }

    /// Euclidean distance from `p` to the solid box (0 inside).
    pub fn distance_to_point(&self, p: &Vector3<f64>) -> f64 {
        let l = self.to_local(p);
        let excess = Vector3::from_fn(|k, _| (l[k].abs() - self.half[k]).max(0.0));
        excess.norm()
    }

    /// Whether `p` lies in the box grown by `margin` along each axis.
    pub fn contains(&self, p: &Vector3<f64>, margin: f64) -> bool {
        let l = self.to_local(p);
        (0..3).all(|k| l[k].abs() <= self.half[k] + margin)
    }

    /// The box's extent along the table's vertical axis: half its height seen from the side.
    #[inline]
    fn vertical_radius(&self) -> f64 {
        (0..3).map(|k| self.axes[(2, k)].abs() * self.half[k]).sum()
    }

    /// Height of the lowest point.
    pub fn min_z(&self) -> f64 {
        self.center.z - self.vertical_radius()
    }

    /// Height of the highest point.
    pub fn max_z(&self) -> f64 {
        self.center.z + self.vertical_radius()
    }

    /// The cosine of the smallest angle between a box axis and the vertical.
    pub fn vertical_cos(&self) -> f64 {
        (0..3).map(|k| self.axes[(2, k)].abs()).fold(0.0, f64::max)
    }

    /// `stable(object)` of section 4.5.5: some edge is parallel to the vertical axis, within
    /// `angle` radians.
    pub fn is_stable(&self, angle: f64) -> bool {
        self.vertical_cos() >= libm::cos(angle)
    }

    /// The footprint: the convex hull of the box seen from above (counter-clockwise, 4 to 6
    /// corners).
    pub fn footprint(&self) -> Vec<Vector2<f64>> {
        convex_hull(self.vertices().iter().map(|v| Vector2::new(v.x, v.y)).collect())
    }
}

/// How two boxes relate (section 4.5.5).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Relation {
    /// Farther apart than the contact tolerance.
    Apart,
    /// Touching: `contact(a, b)`.
    Contact,
    /// Overlapping by more than the contact tolerance, or one inside the other:
    /// `intersect(a, b)`.
    Intersect,
}

/// The shape of the set of touching points (the three contact cases of section 4.5.5).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ContactKind {
    /// The boxes touch in one point, a vertex of one of them.
    Vertex,
    /// The touching points lie on a line, along an edge.
    Edge,
    /// The touching points span a plane, on a facet.
    Facet,
}

/// The penetration depth of two boxes by the separating-axis test: the smallest overlap of
/// their projections on the 15 candidate axes. Positive: they overlap and must move this far
/// apart to separate (exact). Negative: they are apart, by at least its magnitude.
pub fn penetration(a: &Obb, b: &Obb) -> f64 {
    // B's axes in A's frame, and the centre offset in A's frame (Ericson, Real-Time Collision
    // Detection, 4.4.1).
    let r = a.axes.tr_mul(&b.axes);
    let abs_r = r.map(f64::abs);
    let t = a.axes.tr_mul(&(b.center - a.center));
    let (ea, eb) = (a.half, b.half);
    let mut best = f64::INFINITY;
    for i in 0..3 {
        let rb = eb[0] * abs_r[(i, 0)] + eb[1] * abs_r[(i, 1)] + eb[2] * abs_r[(i, 2)];
        best = best.min(ea[i] + rb - t[i].abs());
    }
    for j in 0..3 {
        let ra = ea[0] * abs_r[(0, j)] + ea[1] * abs_r[(1, j)] + ea[2] * abs_r[(2, j)];
        let d = t[0] * r[(0, j)] + t[1] * r[(1, j)] + t[2] * r[(2, j)];
        best = best.min(ra + eb[j] - d.abs());
    }
    for i in 0..3 {
        let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
        for j in 0..3 {
            let len = (1.0 - r[(i, j)] * r[(i, j)]).max(0.0).sqrt();
            if len < 1e-6 {
                // Parallel edges: the cross product vanishes and the face axes cover it.
                continue;
            }
            let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
            let ra = ea[i1] * abs_r[(i2, j)] + ea[i2] * abs_r[(i1, j)];
            let rb = eb[j1] * abs_r[(i, j2)] + eb[j2] * abs_r[(i, j1)];
            let d = (t[i2] * r[(i1, j)] - t[i1] * r[(i2, j)]).abs();
            best = best.min((ra + rb - d) / len);
        }
    }
    best
}

/// Closest points of segments `p1 q1` and `p2 q2` (Ericson 5.1.9): their distance and the
/// midpoint between the two closest points.
pub fn segment_distance(
    p1: &Vector3<f64>,
    q1: &Vector3<f64>,
    p2: &Vector3<f64>,
    q2: &Vector3<f64>,
) -> (f64, Vector3<f64>) {
    let (d1, d2, r) = (q1 - p1, q2 - p2, p1 - p2);
    let (a, e, f) = (d1.dot(&d1), d2.dot(&d2), d2.dot(&r));
    let clamp = |x: f64| x.clamp(0.0, 1.0);
    let (s, t) = if a <= 1e-300 && e <= 1e-300 {
        (0.0, 0.0)
    } else if a <= 1e-300 {
        (0.0, clamp(f / e))
    } else {
        let c = d1.dot(&r);
        if e <= 1e-300 {
            (clamp(-c / a), 0.0)
        } else {
            let b = d1.dot(&d2);
            let denom = a * e - b * b;
            let mut s = if denom > 1e-12 * a * e { clamp((b * f - c * e) / denom) } else { 0.0 };
            let mut t = (b * s + f) / e;
            if t < 0.0 {
                t = 0.0;
                s = clamp(-c / a);
            } else if t > 1.0 {
                t = 1.0;
                s = clamp((b - c) / a);
            }
            (s, t)
        }
    };
    let (c1, c2) = (p1 + d1 * s, p2 + d2 * t);
    ((c1 - c2).norm(), (c1 + c2) / 2.0)
}

/// The Euclidean distance between two solid boxes (0 if they meet).
pub fn distance(a: &Obb, b: &Obb) -> f64 {
    if penetration(a, b) >= 0.0 {
        return 0.0;
    }
    // Apart: the closest pair of points is realised by a vertex of one box and the other box,
    // or by an edge of each.
    let (va, vb) = (a.vertices(), b.vertices());
    let mut best = f64::INFINITY;
    for v in &va {
        best = best.min(b.distance_to_point(v));
    }
    for v in &vb {
        best = best.min(a.distance_to_point(v));
    }
    for &(i, j) in &EDGES {
        for &(k, l) in &EDGES {
            best = best.min(segment_distance(&va[i], &va[j], &vb[k], &vb[l]).0);
        }
    }
    best
}

/// Whether every vertex of `inner` lies in `outer` (within a rounding margin).
fn inside(inner: &Obb, outer: &Obb) -> bool {
    let margin = 1e-9 * (1.0 + outer.half.max());
    inner.vertices().iter().all(|v| outer.contains(v, margin))
}

/// How boxes `a` and `b` relate: apart, in contact or intersecting (section 4.5.5), within the
/// contact tolerance (see the module documentation). Symmetric in `a` and `b`.
pub fn relation(a: &Obb, b: &Obb, tol: &Tolerances) -> Relation {
    let depth = penetration(a, b);
    if depth > tol.contact || (depth >= 0.0 && (inside(a, b) || inside(b, a))) {
        return Relation::Intersect;
    }
    if depth >= 0.0 {
        return Relation::Contact;
    }
    if -depth > tol.contact {
        return Relation::Apart;
    }
    if distance(a, b) <= tol.contact {
        Relation::Contact
    } else {
        Relation::Apart
    }
}

/// The touching points of two boxes in contact: vertices of either box within the contact
/// tolerance of the other, and the closest points of edge pairs within it.
pub fn contact_points(a: &Obb, b: &Obb, tol: &Tolerances) -> Vec<Vector3<f64>> {
    let (va, vb) = (a.vertices(), b.vertices());
    let mut points = Vec::new();
    points.extend(va.iter().filter(|v| b.distance_to_point(v) <= tol.contact));
    points.extend(vb.iter().filter(|v| a.distance_to_point(v) <= tol.contact));
    for &(i, j) in &EDGES {
        for &(k, l) in &EDGES {
            let (d, mid) = segment_distance(&va[i], &va[j], &vb[k], &vb[l]);
            if d <= tol.contact {
                points.push(mid);
            }
        }
    }
    points
}

/// Which of the three contact cases of section 4.5.5 applies to two touching boxes; `None` if
/// they are apart or intersect.
///
/// The touching points ([`contact_points`]) are a single vertex when they all lie within twice
/// the contact tolerance of each other, co-linear (an edge) when they lie within twice the
/// tolerance of the line through the two farthest apart, and coplanar (a facet) otherwise.
pub fn contact_kind(a: &Obb, b: &Obb, tol: &Tolerances) -> Option<ContactKind> {
    if relation(a, b, tol) != Relation::Contact {
        return None;
    }
    let points = contact_points(a, b, tol);
    let spread = 2.0 * tol.contact.max(1e-9);
    // The two points farthest apart.
    let mut far = (0.0, 0, 0);
    for i in 0..points.len() {
        for j in i + 1..points.len() {
            let d = (points[i] - points[j]).norm();
            if d > far.0 {
                far = (d, i, j);
            }
        }
    }
    if far.0 <= spread {
        return Some(ContactKind::Vertex);
    }
    let (p, u) = (points[far.1], (points[far.2] - points[far.1]) / far.0);
    let off_line = points.iter().map(|q| (q - p - u * (q - p).dot(&u)).norm()).fold(0.0, f64::max);
    Some(if off_line <= spread { ContactKind::Edge } else { ContactKind::Facet })
}

/// The convex hull of points in the plane, counter-clockwise, without repeated or collinear
/// points (Andrew's monotone chain).
pub fn convex_hull(mut pts: Vec<Vector2<f64>>) -> Vec<Vector2<f64>> {
    pts.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let cross =
        |o: &Vector2<f64>, a: &Vector2<f64>, b: &Vector2<f64>| (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
    let mut hull: Vec<Vector2<f64>> = Vec::with_capacity(pts.len() + 1);
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &Vector2<f64>>> =
            if pass == 0 { Box::new(pts.iter()) } else { Box::new(pts.iter().rev()) };
        for p in iter {
            while hull.len() >= start + 2 && cross(&hull[hull.len() - 2], &hull[hull.len() - 1], p) <= 0.0 {
                hull.pop();
            }
            hull.push(*p);
        }
        hull.pop();
    }
    hull
}

/// How far two convex polygons overlap: the smallest overlap of their projections on their
/// edge normals (positive: the overlap depth; negative: they are apart by at least that much).
pub fn polygon_overlap(a: &[Vector2<f64>], b: &[Vector2<f64>]) -> f64 {
    let mut best = f64::INFINITY;
    for poly in [a, b] {
        for i in 0..poly.len() {
            let e = poly[(i + 1) % poly.len()] - poly[i];
            let len = e.norm();
            if len < 1e-12 {
                continue;
            }
            let n = Vector2::new(-e.y, e.x) / len;
            let range = |p: &[Vector2<f64>]| {
                p.iter()
                    .map(|q| q.dot(&n))
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| (lo.min(x), hi.max(x)))
            };
            let ((alo, ahi), (blo, bhi)) = (range(a), range(b));
            best = best.min((ahi - blo).min(bhi - alo));
        }
    }
    best
}

/// `higher(a, b)` of section 4.5.5: `a`'s centre is higher than `b`'s and their footprints
/// overlap by more than [`Tolerances::footprint`] (so `a` is above `b`, see the module
/// documentation). Antisymmetric: `higher(a, b)` and `higher(b, a)` are never both true.
pub fn higher(a: &Obb, b: &Obb, tol: &Tolerances) -> bool {
    a.center.z > b.center.z && polygon_overlap(&a.footprint(), &b.footprint()) > tol.footprint
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube_at(x: f64, y: f64, z: f64, s: f64) -> Obb {
        Obb::new(Vector3::new(x, y, z), UnitQuaternion::identity(), Vector3::new(s, s, s))
    }

    #[test]
    fn edges_are_the_twelve_unit_steps() {
        let mut seen = std::collections::BTreeSet::new();
        for (i, j) in EDGES {
            assert_eq!((i ^ j).count_ones(), 1);
            assert!(seen.insert((i, j)));
        }
        assert_eq!(seen.len(), 12);
    }

    #[test]
    fn segment_distance_cases() {
        let v = |x, y, z| Vector3::new(x, y, z);
        // Crossing segments 1 apart in z.
        let (d, m) = segment_distance(&v(-1., 0., 0.), &v(1., 0., 0.), &v(0., -1., 1.), &v(0., 1., 1.));
        assert!((d - 1.0).abs() < 1e-12 && (m - v(0., 0., 0.5)).norm() < 1e-12);
        // Parallel, offset.
        let (d, _) = segment_distance(&v(0., 0., 0.), &v(1., 0., 0.), &v(0.5, 2., 0.), &v(3., 2., 0.));
        assert!((d - 2.0).abs() < 1e-12);
        // Endpoint to endpoint.
        let (d, _) = segment_distance(&v(0., 0., 0.), &v(1., 0., 0.), &v(2., 0., 0.), &v(3., 0., 0.));
        assert!((d - 1.0).abs() < 1e-12);
    }

    #[test]
    fn penetration_of_axis_aligned_cubes() {
        let a = cube_at(0.0, 0.0, 0.0, 1.0);
        assert!((penetration(&a, &cube_at(0.9, 0.0, 0.0, 1.0)) - 0.1).abs() < 1e-12);
        assert!((penetration(&a, &cube_at(1.2, 0.0, 0.0, 1.0)) + 0.2).abs() < 1e-12);
        // Diagonal neighbours: the axis test sees 0.1, the true distance is 0.1 * sqrt(3).
        let b = cube_at(1.1, 1.1, 1.1, 1.0);
        assert!((penetration(&a, &b) + 0.1).abs() < 1e-12);
        assert!((distance(&a, &b) - 0.1 * 3f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn hull_of_a_tilted_box_has_six_corners() {
        let q = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(0.9, 0.3, 0.2, 0.1));
        let b = Obb::new(Vector3::zeros(), q, Vector3::new(0.3, 0.2, 0.1));
        let h = b.footprint();
        assert_eq!(h.len(), 6);
        // Counter-clockwise: positive signed area.
        let area: f64 = (0..h.len()).map(|i| h[i].perp(&h[(i + 1) % h.len()])).sum::<f64>() / 2.0;
        assert!(area > 0.0);
    }
}
