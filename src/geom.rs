//! Small 2-D helpers shared by the scene checks, the solvers and the drawing layer:
//! point and vector types, angles, rotation, circle–circle intersection, and the named
//! numerical tolerances of the whole crate.
//!
//! Conventions: lengths in the scene's units, angles in radians, measured from +x,
//! counter-clockwise positive.

/// A point in the plane (model units).
pub type Point = nalgebra::Point2<f64>;
/// A free vector in the plane (model units, or units per second for velocities).
pub type Vector = nalgebra::Vector2<f64>;

/// Named tolerances. Every comparison against a tolerance in the crate uses one of these
/// (or a value passed in by the caller), never a bare literal.
pub mod tol {
    /// Relative tolerance under which a circle–circle discriminant counts as zero
    /// (tangent circles): `|h²| ≤ TANGENT_REL · r1²` gives a single point.
    pub const TANGENT_REL: f64 = 1e-12;
    /// Relative residual that a converged position solution must reach (constraint
    /// residual divided by the mechanism's characteristic length).
    pub const RESIDUAL_REL: f64 = 1e-12;
    /// Default absolute tolerance of Newton–Raphson iterations on angles (radians).
    pub const NEWTON_ANGLE: f64 = 1e-13;
    /// A length below this, relative to the mechanism's size, counts as zero.
    pub const LENGTH_REL: f64 = 1e-12;
}

/// Point with polar coordinates `(r, angle)` about `center`.
pub fn polar(center: Point, r: f64, angle: f64) -> Point {
    center + Vector::new(r * libm::cos(angle), r * libm::sin(angle))
}

/// Direction angle of `v` in (−π, π]; 0 for the zero vector.
pub fn angle_of(v: Vector) -> f64 {
    libm::atan2(v.y, v.x)
}

/// `angle` reduced to [0, 2π).
pub fn normalize_angle(angle: f64) -> f64 {
    let a = angle.rem_euclid(std::f64::consts::TAU);
    // rem_euclid can return TAU itself for tiny negative inputs.
    if a >= std::f64::consts::TAU { 0.0 } else { a }
}

/// `angle` reduced to (−π, π].
pub fn wrap_pi(angle: f64) -> f64 {
    let a = normalize_angle(angle);
    if a > std::f64::consts::PI { a - std::f64::consts::TAU } else { a }
}

/// `v` rotated counter-clockwise by `angle`.
pub fn rotate(v: Vector, angle: f64) -> Vector {
    let (s, c) = libm::sincos(angle);
    Vector::new(c * v.x - s * v.y, s * v.x + c * v.y)
}

/// `v` rotated by +90° (counter-clockwise): the direction of `ω × r` for ω > 0.
pub fn perp(v: Vector) -> Vector {
    Vector::new(-v.y, v.x)
}

/// z-component of the cross product `a × b`: positive when `b` lies counter-clockwise of `a`.
pub fn cross(a: Vector, b: Vector) -> f64 {
    a.x * b.y - a.y * b.x
}

/// Which side of a directed line a point lies on. Used to name the two intersections of
/// two circles and, through that, the assembly mode of a dyad or a triad.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Side {
    /// Counter-clockwise side of the directed line (from the first centre to the second).
    Left,
    /// Clockwise side.
    Right,
}

impl Side {
    /// The other side.
    pub fn flip(self) -> Side {
        match self {
            Side::Left => Side::Right,
            Side::Right => Side::Left,
        }
    }
}

/// Result of intersecting two circles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CircleIntersection {
    /// The circles do not meet (too far apart, one inside the other, or concentric).
    None,
    /// The circles touch at one point (discriminant zero within [`tol::TANGENT_REL`]).
    Tangent(Point),
    /// Two points: `left` lies to the left of the directed line from the first centre
    /// to the second, `right` to its right.
    Two {
        /// Intersection on the counter-clockwise side of `c1 → c2`.
        left: Point,
        /// Intersection on the clockwise side of `c1 → c2`.
        right: Point,
    },
}

impl CircleIntersection {
    /// The point on `side`; a tangent point serves both sides.
    pub fn on(&self, side: Side) -> Option<Point> {
        match *self {
            CircleIntersection::None => None,
            CircleIntersection::Tangent(p) => Some(p),
            CircleIntersection::Two { left, right } => Some(match side {
                Side::Left => left,
                Side::Right => right,
            }),
        }
    }
}

/// Intersection of the circle (`c1`, `r1`) with the circle (`c2`, `r2`).
///
/// Degenerate input returns fewer points, never NaN: concentric circles give
/// [`CircleIntersection::None`]; a discriminant within [`tol::TANGENT_REL`] of zero
/// (on either side) gives the single tangent point.
pub fn circle_circle(c1: Point, r1: f64, c2: Point, r2: f64) -> CircleIntersection {
    let d_vec = c2 - c1;
    let d2 = d_vec.norm_squared();
    if d2 == 0.0 || !d2.is_finite() {
        return CircleIntersection::None;
    }
    let d = d2.sqrt();
    // Distance from c1 along the centre line to the chord.
    let a = (d2 + r1 * r1 - r2 * r2) / (2.0 * d);
    let h2 = r1 * r1 - a * a;
    let scale = r1.max(r2).max(d);
    let u = d_vec / d;
    let foot = c1 + u * a;
    if h2.abs() <= tol::TANGENT_REL * scale * scale {
        return CircleIntersection::Tangent(foot);
    }
    if h2 < 0.0 {
        return CircleIntersection::None;
    }
    let h = h2.sqrt();
    let n = perp(u);
    CircleIntersection::Two { left: foot + n * h, right: foot - n * h }
}

/// Degrees to radians.
pub fn rad(deg: f64) -> f64 {
    deg.to_radians()
}

/// Radians to degrees.
pub fn deg(rad: f64) -> f64 {
    rad.to_degrees()
}

/// `x` to the integer power `n`, by binary powering (square and multiply from the low bit;
/// `n < 0` gives `1 / x^|n|`): the same bits on every target. `f64::powi` leaves its
/// rounding unspecified (an LLVM intrinsic, expanded inline or calling the platform's
/// `__powidf2`), so the crate calls this one (clippy.toml forbids `f64::powi`).
pub fn powi(x: f64, n: i32) -> f64 {
    let mut base = x;
    let mut e = n.unsigned_abs();
    let mut acc = 1.0;
    loop {
        if e & 1 == 1 {
            acc *= base;
        }
        e >>= 1;
        if e == 0 {
            break;
        }
        base *= base;
    }
    if n < 0 { 1.0 / acc } else { acc }
}

/// `|a − b| ≤ rel · max(|a|, |b|, floor)`: relative comparison with an absolute floor.
pub fn close(a: f64, b: f64, rel: f64, floor: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs()).max(floor)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_points_are_on_both_circles_and_sides_are_named() {
        let c1 = Point::new(0.0, 0.0);
        let c2 = Point::new(4.0, 0.0);
        match circle_circle(c1, 5.0, c2, 3.0) {
            CircleIntersection::Two { left, right } => {
                for p in [left, right] {
                    assert!(((p - c1).norm() - 5.0).abs() < 1e-12);
                    assert!(((p - c2).norm() - 3.0).abs() < 1e-12);
                }
                assert!(cross(c2 - c1, left - c1) > 0.0);
                assert!(cross(c2 - c1, right - c1) < 0.0);
                // 3-4-5 triangle: the points are (4, ±3).
                assert!((left - Point::new(4.0, 3.0)).norm() < 1e-12);
            }
            other => panic!("expected two points, got {other:?}"),
        }
    }

    #[test]
    fn tangent_and_disjoint_circles_give_fewer_points() {
        let c1 = Point::new(1.0, 1.0);
        let c2 = Point::new(4.0, 5.0); // distance 5
        assert_eq!(circle_circle(c1, 2.0, c2, 3.0), CircleIntersection::Tangent(Point::new(2.2, 2.6)));
        assert_eq!(circle_circle(c1, 1.0, c2, 3.0), CircleIntersection::None);
        assert_eq!(circle_circle(c1, 1.0, c1, 1.0), CircleIntersection::None);
        // internally tangent
        assert!(matches!(circle_circle(c1, 8.0, c2, 3.0), CircleIntersection::Tangent(_)));
    }

    #[test]
    fn powi_multiplies_out_and_inverts() {
        // Values with few significant bits: every product is exact, whatever the order.
        for x in [0.0, -0.0, 1.5, -2.25, 10.0, 0.5, -7.0] {
            let mut product = 1.0;
            for n in 0..6 {
                assert_eq!(powi(x, n), product, "{x}^{n}");
                product *= x;
            }
        }
        assert_eq!(powi(2.0, -3), 0.125);
        assert_eq!(powi(-2.0, 3), -8.0);
        assert_eq!(powi(10.0, 22), 1e22);
        assert_eq!(powi(0.0, -1), f64::INFINITY);
        assert_eq!(powi(10.0, 400), f64::INFINITY);
        assert_eq!(powi(2.0, i32::MIN), 0.0);
    }

    /// The same algorithm as Rust's `compiler-builtins` and libgcc's `__powidf2`, which
    /// `f64::powi` calls where LLVM does not expand it: the change to `powi` moved no output.
    #[test]
    #[allow(clippy::disallowed_methods, reason = "the platform's powi, compared with ours")]
    fn powi_gives_the_bits_of_the_platforms_powi() {
        let mut x = 0.123_456_789_f64;
        for i in 0..2000 {
            x = (x * 7.3 + 0.37).fract() * 20.0 - 10.0;
            let n = (i % 41) - 20;
            let platform = std::hint::black_box(x).powi(std::hint::black_box(n));
            assert_eq!(powi(x, n).to_bits(), platform.to_bits(), "{x}^{n}");
        }
    }

    #[test]
    fn angles_normalise() {
        assert_eq!(normalize_angle(-0.0), 0.0);
        assert!((normalize_angle(-std::f64::consts::FRAC_PI_2) - 1.5 * std::f64::consts::PI).abs() < 1e-15);
        assert!((wrap_pi(1.5 * std::f64::consts::PI) + std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        assert!((rotate(Vector::new(1.0, 0.0), std::f64::consts::FRAC_PI_2) - Vector::new(0.0, 1.0)).norm() < 1e-15);
    }
}
