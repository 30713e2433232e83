//! The 6R triad (a class-III Assur group): a rigid triangle A1A2A3 whose vertices move on
//! three circles, A_i on the circle of radius R_i about the ground pivot O_i (seed 000).
//!
//! Three methods, numbers only:
//! - [`pattern`](mod@pattern): the seed's "pattern method", a secant iteration on phi1 with two
//!   circle intersections per step (one assembly mode, chosen by branch).
//! - [`newton`](mod@newton): Newton–Raphson on the three-angle system (phi1, phi2, phi3) from a start,
//!   the seed's analytic reference.
//! - [`modes`]: every assembly mode, from a degree-6 polynomial in tan(phi1/2) whose real
//!   roots are isolated exactly (derivative sequence), then polished by Newton.
//!
//! Conventions: angles in radians, counter-clockwise from +x; phi_i is the direction
//! O_i → A_i. Lengths in the scene's units. The triangle's orientation is the sense in which
//! A1 → A2 → A3 runs ([`Orientation`]).

pub mod modes;
pub mod newton;
pub mod pattern;
mod poly;

use crate::geom::{Point, cross, deg, polar};

pub use modes::{all_modes, modes_with};
pub use newton::{NewtonOptions, NewtonSolution, newton, newton_to};
pub use pattern::{PatternOptions, PatternSolution, pattern};

/// Configurations whose residual (largest of the six constraint errors divided by
/// [`Triad::scale`]) exceeds this are not accepted as solutions.
pub const RESIDUAL_ACCEPT_REL: f64 = 1e-10;

/// A triangle whose doubled area is below this fraction of the squared longest side counts
/// as flat: its two orientations coincide ([`Orientation::Collinear`]).
pub const FLAT_TRIANGLE_REL: f64 = 1e-12;

/// Sense of the triangle A1 → A2 → A3.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Orientation {
    /// A1 → A2 → A3 runs counter-clockwise (A3 lies left of the directed line A1 → A2).
    Ccw,
    /// A1 → A2 → A3 runs clockwise (the mirror image).
    Cw,
    /// The triangle is flat (one side equals the sum of the other two): both senses coincide.
    Collinear,
}

impl Orientation {
    /// The name used in scene files and reports: `ccw`, `cw`, `collinear`.
    pub fn name(self) -> &'static str {
        match self {
            Orientation::Ccw => "ccw",
            Orientation::Cw => "cw",
            Orientation::Collinear => "collinear",
        }
    }

    /// The mirror orientation (collinear stays collinear).
    pub fn mirror(self) -> Orientation {
        match self {
            Orientation::Ccw => Orientation::Cw,
            Orientation::Cw => Orientation::Ccw,
            Orientation::Collinear => Orientation::Collinear,
        }
    }
}

impl std::fmt::Display for Orientation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Why a triad cannot be solved (bad data, no configuration, or a method that fails).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TriadError {
    /// A length is zero, negative or not finite. Example: `l12 = -5`.
    #[error("{name} = {value} must be a positive length")]
    InvalidLength {
        /// The length's name (`r[0]`, `l12`, ...).
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// A pivot has a coordinate that is not finite. Example: `o1 = [nan, 0]`.
    #[error("{name} must be a point of finite coordinates")]
    InvalidPoint {
        /// The pivot's name (`o1`, `o2`, `o3`).
        name: &'static str,
    },
    /// One side of the triangle is longer than the other two together.
    /// Example: `l12 = 50, l23 = 50, l13 = 120`.
    #[error(
        "{longest} = {value} is longer than the other two sides together ({sum}): the triangle A1A2A3 cannot close"
    )]
    TriangleInequality {
        /// The offending side (`l12`, `l23` or `l13`).
        longest: &'static str,
        /// Its length.
        value: f64,
        /// The sum of the other two sides.
        sum: f64,
    },
    /// Two vertices can never be as far apart as the triangle side between them, whatever
    /// the angles: the four-bar O_i A_i A_j O_j cannot be assembled.
    /// Example: `o1 = [0, 0]`, `o2 = [500, 0]`, `r = [50, 60, 84]`, `l12 = 50`.
    #[error(
        "no configuration exists: {a} (on circle {ra} about {oa}) and {b} (on circle {rb} about {ob}) are always between {min} and {max} apart, so the side {side} = {length} can never fit",
        a = VERTEX_NAMES[pair[0]], b = VERTEX_NAMES[pair[1]], ra = RADIUS_NAMES[pair[0]], rb = RADIUS_NAMES[pair[1]],
        oa = PIVOT_NAMES[pair[0]], ob = PIVOT_NAMES[pair[1]], side = SIDE_NAMES[pair[0] + pair[1] - 1]
    )]
    CannotJoin {
        /// The two vertices, 0-based (`[0, 1]` is A1 and A2: side l12).
        pair: [usize; 2],
        /// The side's length.
        length: f64,
        /// Smallest possible distance of the two vertices.
        min: f64,
        /// Largest possible distance.
        max: f64,
    },
    /// Every pair of vertices can be joined, but never all three at once: A3 misses its
    /// circle for every phi1 (with this orientation, when one was asked for).
    #[error(
        "no configuration exists{}: A1 and A2 can be placed on circles r[0], r[1] with |A1A2| = l12, but A3 then never reaches circle r[2] about o3; the closest it comes is |O3A3| − R3 = {closest_miss:.6} at phi1 = {at_phi1_deg:.3}°{}",
        orientation.map(|o| format!(" with orientation {o}")).unwrap_or_default(),
        if *mirror_modes > 0 { format!(" (the mirror orientation has {}: set orientation = \"both\")", crate::text::counted(*mirror_modes as i64, "configuration", "configurations")) } else { String::new() }
    )]
    NoConfiguration {
        /// The orientation asked for, or `None` for both.
        orientation: Option<Orientation>,
        /// Signed `|O3A3| − R3` closest to zero over a scan of phi1 (model units).
        closest_miss: f64,
        /// Where that happens, degrees.
        at_phi1_deg: f64,
        /// Configurations of the mirror orientation (0 when both were searched).
        mirror_modes: usize,
    },
    /// The closure equations vanish for every phi1: the triad moves (infinitely many
    /// configurations), e.g. a parallelogram-like special geometry.
    #[error("the triad is movable (its closure equation vanishes for every phi1): no isolated configuration")]
    Movable,
    /// Pattern method: circle (A1, l12) does not meet circle (O2, R2) at this phi1, so A2
    /// does not exist. Example: a start angle outside the range where the dyad assembles.
    #[error(
        "pattern method: at phi1 = {phi1_deg:.6}° (iteration {iteration}) the circle of radius l12 about A1 does not meet circle r[1] about o2, so A2 does not exist; choose another pattern.phi1_start_deg"
    )]
    PatternNoIntersection {
        /// Where, degrees.
        phi1_deg: f64,
        /// Secant iteration (0 = the start).
        iteration: usize,
    },
    /// Pattern method: d2 = d1, the secant (eq. 2) cannot be formed (the step is below the
    /// resolution of |O3A3| at this angle).
    #[error(
        "pattern method stalled at phi1 = {phi1_deg:.9}° (iteration {iteration}): d2 = d1 at step {step_deg:e}°, the secant (eq. 2) is undefined; |R3 − d1| = {residual:e}"
    )]
    PatternStalled {
        /// Where, degrees.
        phi1_deg: f64,
        /// Secant iteration.
        iteration: usize,
        /// The step Δφ at that iteration, degrees.
        step_deg: f64,
        /// |R3 − d1| there.
        residual: f64,
    },
    /// Pattern method: the iteration cap was reached before |R3 − d1| < ε.
    #[error(
        "pattern method did not converge in {iterations} iterations: |R3 − d1| = {residual:e} at phi1 = {phi1_deg:.6}°"
    )]
    PatternNotConverged {
        /// Iterations done.
        iterations: usize,
        /// Last |R3 − d1|.
        residual: f64,
        /// Last phi1, degrees.
        phi1_deg: f64,
    },
    /// Newton–Raphson: the Jacobian of the three-angle system is singular (the lines
    /// O1A1, O2A2, O3A3 meet in one point, or a link is aligned with a side).
    #[error(
        "Newton–Raphson: singular Jacobian at phi = ({:.4}°, {:.4}°, {:.4}°) (iteration {iteration}): the links O1A1, O2A2, O3A3 are concurrent or parallel",
        phi_deg[0], phi_deg[1], phi_deg[2]
    )]
    NewtonSingular {
        /// Angles where it happened, degrees.
        phi_deg: [f64; 3],
        /// Iteration.
        iteration: usize,
    },
    /// The drawn assembly mode asked for is not among those found. Example: `mode = 9` for
    /// a triad with 8 modes.
    #[error(
        "mode = {mode}: the triad has {} here, numbered 1 to {count} as the report lists them",
        crate::text::counted(*count as i64, "assembly mode", "assembly modes")
    )]
    NoSuchMode {
        /// The mode asked for (1-based).
        mode: usize,
        /// How many modes were found.
        count: usize,
    },
    /// Newton–Raphson: the iteration cap was reached (or the iterates diverged).
    #[error("Newton–Raphson did not converge in {iterations} iterations (residual {residual:e})")]
    NewtonNotConverged {
        /// Iterations done.
        iterations: usize,
        /// Last residual (relative, see [`Triad::residual`]).
        residual: f64,
    },
}

/// The data of a 6R triad: pivots, radii, triangle sides.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Triad {
    /// Ground pivots O1, O2, O3.
    pub o: [Point; 3],
    /// Radii R1 = O1A1, R2 = O2A2, R3 = O3A3.
    pub r: [f64; 3],
    /// Side A1A2.
    pub l12: f64,
    /// Side A2A3.
    pub l23: f64,
    /// Side A1A3.
    pub l13: f64,
}

/// One configuration (assembly mode) of the triad.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Configuration {
    /// phi1, phi2, phi3: directions O_i → A_i, radians in [0, 2π).
    pub phi: [f64; 3],
    /// The vertices A1, A2, A3.
    pub a: [Point; 3],
    /// Sense of the triangle A1 → A2 → A3.
    pub orientation: Orientation,
    /// Largest of the six constraint errors (A_i on circle i, three sides) divided by
    /// [`Triad::scale`].
    pub residual: f64,
}

impl Configuration {
    /// phi1, phi2, phi3 in degrees, in [0, 360).
    pub fn phi_deg(&self) -> [f64; 3] {
        self.phi.map(deg)
    }
}

const PIVOT_NAMES: [&str; 3] = ["o1", "o2", "o3"];
const RADIUS_NAMES: [&str; 3] = ["r[0]", "r[1]", "r[2]"];
const VERTEX_NAMES: [&str; 3] = ["A1", "A2", "A3"];
/// Sides by `i + j − 1` of their 0-based vertices: A1A2, A1A3, A2A3.
const SIDE_NAMES: [&str; 3] = ["l12", "l13", "l23"];

impl Triad {
    /// A checked triad: finite pivots, positive lengths, a triangle that closes.
    pub fn new(o: [Point; 3], r: [f64; 3], l12: f64, l23: f64, l13: f64) -> Result<Triad, TriadError> {
        for (p, name) in o.iter().zip(PIVOT_NAMES) {
            if !(p.x.is_finite() && p.y.is_finite()) {
                return Err(TriadError::InvalidPoint { name });
            }
        }
        for (v, name) in r.iter().copied().zip(RADIUS_NAMES).chain([(l12, "l12"), (l23, "l23"), (l13, "l13")]) {
            if !(v.is_finite() && v > 0.0) {
                return Err(TriadError::InvalidLength { name, value: v });
            }
        }
        for (name, v, a, b) in [("l12", l12, l23, l13), ("l23", l23, l12, l13), ("l13", l13, l12, l23)] {
            if v > (a + b) * (1.0 + crate::geom::tol::LENGTH_REL) {
                return Err(TriadError::TriangleInequality { longest: name, value: v, sum: a + b });
            }
        }
        Ok(Triad { o, r, l12, l23, l13 })
    }

    /// Characteristic length: the largest of the radii, the sides and the pivot distances.
    /// Residuals and tolerances are relative to it.
    pub fn scale(&self) -> f64 {
        let [o1, o2, o3] = self.o;
        [
            self.r[0],
            self.r[1],
            self.r[2],
            self.l12,
            self.l23,
            self.l13,
            (o2 - o1).norm(),
            (o3 - o1).norm(),
            (o3 - o2).norm(),
        ]
        .into_iter()
        .fold(0.0, f64::max)
    }

    /// The vertices A_i = O_i + R_i·(cos phi_i, sin phi_i).
    pub fn vertices(&self, phi: [f64; 3]) -> [Point; 3] {
        [polar(self.o[0], self.r[0], phi[0]), polar(self.o[1], self.r[1], phi[1]), polar(self.o[2], self.r[2], phi[2])]
    }

    /// Largest of the six constraint errors at the vertices `a` (|O_iA_i| − R_i and
    /// |A_iA_j| − l_ij), divided by [`Triad::scale`].
    pub fn residual(&self, a: &[Point; 3]) -> f64 {
        let e = [
            (a[0] - self.o[0]).norm() - self.r[0],
            (a[1] - self.o[1]).norm() - self.r[1],
            (a[2] - self.o[2]).norm() - self.r[2],
            (a[1] - a[0]).norm() - self.l12,
            (a[2] - a[1]).norm() - self.l23,
            (a[2] - a[0]).norm() - self.l13,
        ];
        e.iter().fold(0.0_f64, |m, v| m.max(v.abs())) / self.scale()
    }

    /// Whether the triangle is flat (its two orientations coincide).
    pub fn is_flat(&self) -> bool {
        let longest = self.l12.max(self.l23).max(self.l13);
        twice_area(self.l12, self.l23, self.l13) <= FLAT_TRIANGLE_REL * longest * longest
    }

    /// Sense of the triangle with vertices `a` (flat triads are always collinear).
    pub fn orientation_of(&self, a: &[Point; 3]) -> Orientation {
        if self.is_flat() {
            Orientation::Collinear
        } else if cross(a[1] - a[0], a[2] - a[0]) > 0.0 {
            Orientation::Ccw
        } else {
            Orientation::Cw
        }
    }

    /// The configuration with angles `phi` (normalised to [0, 2π)), its orientation and
    /// residual.
    pub fn configuration(&self, phi: [f64; 3]) -> Configuration {
        let phi = phi.map(crate::geom::normalize_angle);
        let a = self.vertices(phi);
        Configuration { phi, a, orientation: self.orientation_of(&a), residual: self.residual(&a) }
    }

    /// Checks that every pair of vertices can be as far apart as its side, for some angles.
    pub fn check_pairs(&self) -> Result<(), TriadError> {
        for (i, j, length) in [(0, 1, self.l12), (1, 2, self.l23), (0, 2, self.l13)] {
            let d = (self.o[j] - self.o[i]).norm();
            let (ri, rj) = (self.r[i], self.r[j]);
            let min = (d - ri - rj).max(ri - d - rj).max(rj - d - ri).max(0.0);
            let max = d + ri + rj;
            let slack = crate::geom::tol::LENGTH_REL * self.scale();
            if length < min - slack || length > max + slack {
                return Err(TriadError::CannotJoin { pair: [i, j], length, min, max });
            }
        }
        Ok(())
    }

    /// The vertex angle at A1 (between A1→A2 and A1→A3), radians in [0, π], and
    /// `(cos, sin)` of it, from the three sides (accurate for flat and needle triangles).
    pub(crate) fn angle_at_a1(&self) -> (f64, f64) {
        let (a, b, c) = (self.l12, self.l13, self.l23);
        let cos = ((a * a + b * b - c * c) / (2.0 * a * b)).clamp(-1.0, 1.0);
        let sin = (twice_area(a, b, c) / (a * b)).clamp(0.0, 1.0);
        (cos, sin)
    }
}

/// Twice the area of a triangle with sides `a`, `b`, `c` (Kahan's stable Heron formula);
/// 0 for a flat or impossible triangle.
fn twice_area(a: f64, b: f64, c: f64) -> f64 {
    let mut s = [a, b, c];
    s.sort_by(|x, y| y.total_cmp(x));
    let [a, b, c] = s;
    let p = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
    if p > 0.0 { 0.5 * p.sqrt() } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    pub(crate) fn seed() -> Triad {
        Triad::new(
            [Point::new(15.0, 30.0), Point::new(90.0, 20.0), Point::new(150.0, 40.0)],
            [50.0, 60.0, 84.0],
            50.0,
            50.0,
            92.0,
        )
        .unwrap()
    }

    #[test]
    fn heron_is_stable_and_flat_triangles_are_detected() {
        assert!((twice_area(3.0, 4.0, 5.0) - 12.0).abs() < 1e-12);
        assert_eq!(twice_area(1.0, 2.0, 3.0), 0.0);
        let t = Triad { l12: 1.0, l23: 2.0, l13: 3.0, ..seed() };
        assert!(t.is_flat());
        assert!(!seed().is_flat());
    }

    #[test]
    fn bad_data_is_named() {
        let s = seed();
        assert_eq!(Triad::new(s.o, s.r, -1.0, 50.0, 92.0), Err(TriadError::InvalidLength { name: "l12", value: -1.0 }));
        assert!(matches!(
            Triad::new(s.o, s.r, 50.0, 50.0, 120.0),
            Err(TriadError::TriangleInequality { longest: "l13", .. })
        ));
        let far = Triad::new([s.o[0], Point::new(500.0, 0.0), s.o[2]], s.r, 50.0, 50.0, 92.0).unwrap();
        assert!(matches!(far.check_pairs(), Err(TriadError::CannotJoin { pair: [0, 1], .. })));
        assert!(s.check_pairs().is_ok());
    }
}
