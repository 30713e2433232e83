//! Function generation: a four-bar whose output angle ψ generates y = f(x) while its input
//! angle φ follows x, through three precision points, by Freudenstein's equation
//! (Freudenstein 1955; e.g. Norton, *Design of Machinery*, §5.9; Shigley & Uicker §10.x).
//!
//! x and y map linearly onto the angles: φ = φs + (x − x0)·Δφ/Δx, ψ = ψs + (y − y0)·Δψ/Δy,
//! with y0 = f(x0), y1 = f(x1). With the crank pivot O1 at the origin, the rocker pivot C at
//! (d, 0), A = a·(cos φ, sin φ) and B = C + c·(cos ψ, sin ψ), |AB| = b gives
//!
//!   K1·cos ψ − K2·cos φ + K3 = cos(φ − ψ),  K1 = d/a, K2 = d/c, K3 = (a² − b² + c² + d²)/(2ac),
//!
//! linear in K1, K2, K3: three precision points give a 3×3 system. A negative a (or c)
//! means the link points the other way: its length is |a| and its angle φ + 180°. The
//! precision points are Chebyshev's by default, x_j = (x0 + x1)/2 − (x1 − x0)/2·cos((2j − 1)π/6),
//! where the structural error (the generated y less f(x)) vanishes.

use std::f64::consts::PI;

use super::{FourbarClass, SynthesisError, fourbar_class, positive};
use crate::geom::{Point, Side, Vector, cross};

/// What the design must do.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Requirement {
    /// The range of x: [x0, x1], x0 ≠ x1.
    pub x_range: (f64, f64),
    /// The input angles at x0 and at x1 (φs, φf), radians, measured from O1 → C.
    pub input: (f64, f64),
    /// The output angles at y(x0) and at y(x1) (ψs, ψf), radians, measured from +x at C.
    pub output: (f64, f64),
    /// The ground O1C (> 0): the linkage's size.
    pub ground: f64,
    /// The precision points; `None`: Chebyshev's.
    pub precision: Option<[f64; 3]>,
}

/// The function generator.
#[derive(Debug, Clone, PartialEq)]
pub struct Design {
    /// Crank O1A (|a|).
    pub a: f64,
    /// Coupler AB.
    pub b: f64,
    /// Rocker CB (|c|).
    pub c: f64,
    /// Ground O1C.
    pub d: f64,
    /// Freudenstein's K1, K2, K3.
    pub k: [f64; 3],
    /// Added to the input angle φ to get the crank's direction O1 → A (0, or π when a came
    /// out negative).
    pub crank_turn: f64,
    /// Added to the output angle ψ to get the rocker's direction C → B (0 or π).
    pub rocker_turn: f64,
    /// The precision points x_j.
    pub x: [f64; 3],
    /// f(x_j).
    pub y: [f64; 3],
    /// The input angles φ_j there (radians).
    pub phi: [f64; 3],
    /// The output angles ψ_j there (radians).
    pub psi: [f64; 3],
    /// y0 = f(x0), y1 = f(x1).
    pub y_range: (f64, f64),
    /// The side of B relative to A → C at each precision point.
    pub sides: [Side; 3],
    /// The linkage's class.
    pub class: FourbarClass,
}

impl Design {
    /// The input angle φ for `x` (radians): the linear map.
    pub fn phi_of(&self, req: &Requirement, x: f64) -> f64 {
        lerp(req.x_range, req.input, x)
    }

    /// The y that an output angle ψ stands for: the inverse of the linear map of y.
    pub fn y_of_psi(&self, req: &Requirement, psi: f64) -> f64 {
        lerp(req.output, self.y_range, psi)
    }

    /// Crank pivot O1 (the origin).
    pub fn o1(&self) -> Point {
        Point::origin()
    }

    /// Rocker pivot C = (d, 0).
    pub fn pivot_c(&self) -> Point {
        Point::new(self.d, 0.0)
    }

    /// The crank pin A at input angle φ.
    pub fn a_at(&self, phi: f64) -> Point {
        Point::origin() + unit(phi + self.crank_turn) * self.a
    }

    /// The rocker pin B at output angle ψ.
    pub fn b_at(&self, psi: f64) -> Point {
        self.pivot_c() + unit(psi + self.rocker_turn) * self.c
    }
}

fn unit(a: f64) -> Vector {
    Vector::new(libm::cos(a), libm::sin(a))
}

/// The value at `x` of the linear map taking `from.0 → to.0` and `from.1 → to.1`.
fn lerp(from: (f64, f64), to: (f64, f64), x: f64) -> f64 {
    to.0 + (x - from.0) * (to.1 - to.0) / (from.1 - from.0)
}

/// Chebyshev's three precision points over [x0, x1].
pub fn chebyshev(x0: f64, x1: f64) -> [f64; 3] {
    [1.0, 2.0, 3.0].map(|j: f64| 0.5 * (x0 + x1) - 0.5 * (x1 - x0) * libm::cos((2.0 * j - 1.0) * PI / 6.0))
}

/// Synthesises the function generator for `f`.
pub fn synthesise(req: &Requirement, f: &dyn Fn(f64) -> f64) -> Result<Design, SynthesisError> {
    let d = positive("the ground O1C", req.ground)?;
    let (x0, x1) = req.x_range;
    if !(x0.is_finite() && x1.is_finite() && x0 != x1) {
        return Err(SynthesisError::Function {
            what: format!("range [{x0}, {x1}] of x must be two different finite numbers"),
        });
    }
    let angles = [req.input.0, req.input.1, req.output.0, req.output.1];
    if !angles.iter().all(|v| v.is_finite()) || req.input.0 == req.input.1 || req.output.0 == req.output.1 {
        return Err(SynthesisError::Function {
            what: "angle ranges must be finite and of non-zero span (input and output)".into(),
        });
    }
    let value = |x: f64| -> Result<f64, SynthesisError> {
        let y = f(x);
        if y.is_finite() {
            Ok(y)
        } else {
            Err(SynthesisError::Function { what: format!("is not finite at x = {x} (f = {y})") })
        }
    };
    let y_range = (value(x0)?, value(x1)?);
    if y_range.0 == y_range.1 {
        return Err(SynthesisError::Function {
            what: format!("takes the same value {} at both ends of the range: no output range to map onto", y_range.0),
        });
    }
    let x = req.precision.unwrap_or_else(|| chebyshev(x0, x1));
    let (lo, hi) = (x0.min(x1), x0.max(x1));
    for (i, xi) in x.iter().enumerate() {
        if !(xi.is_finite() && *xi >= lo && *xi <= hi) {
            return Err(SynthesisError::PrecisionPointOutside { index: i + 1, x: *xi, from: x0, to: x1 });
        }
    }
    let y = [value(x[0])?, value(x[1])?, value(x[2])?];
    let phi = x.map(|xi| lerp(req.x_range, req.input, xi));
    let psi = y.map(|yi| lerp(y_range, req.output, yi));
    let k = solve3(&phi, &psi)?;
    let (a_s, c_s) = (d / k[0], d / k[1]);
    let b2 = a_s * a_s + c_s * c_s + d * d - 2.0 * a_s * c_s * k[2];
    if !(b2 > 0.0 && b2.is_finite() && a_s.is_finite() && c_s.is_finite()) {
        return Err(SynthesisError::NoCoupler { b2 });
    }
    let crank_turn = if a_s < 0.0 { PI } else { 0.0 };
    let rocker_turn = if c_s < 0.0 { PI } else { 0.0 };
    let (a, b, c) = (a_s.abs(), b2.sqrt(), c_s.abs());
    let mut design = Design {
        a,
        b,
        c,
        d,
        k,
        crank_turn,
        rocker_turn,
        x,
        y,
        phi,
        psi,
        y_range,
        sides: [Side::Left; 3],
        class: fourbar_class(a, b, c, d),
    };
    design.sides = [0, 1, 2].map(|j| {
        let (pa, pb) = (design.a_at(phi[j]), design.b_at(psi[j]));
        if cross(design.pivot_c() - pa, pb - pa) > 0.0 { Side::Left } else { Side::Right }
    });
    Ok(design)
}

/// Freudenstein's 3×3 system [cos ψ, −cos φ, 1]·K = cos(φ − ψ), by Cramer's rule with a
/// scaled determinant test.
fn solve3(phi: &[f64; 3], psi: &[f64; 3]) -> Result<[f64; 3], SynthesisError> {
    let row = |j: usize| [libm::cos(psi[j]), -libm::cos(phi[j]), 1.0];
    let m = [row(0), row(1), row(2)];
    let r = [0, 1, 2].map(|j| libm::cos(phi[j] - psi[j]));
    let det3 = |m: &[[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let det = det3(&m);
    if det.abs() <= 1e-12 {
        return Err(SynthesisError::SingularPrecision {
            why: format!("determinant {det:.3e}: two precision points give the same equation"),
        });
    }
    let mut k = [0.0; 3];
    for (col, kc) in k.iter_mut().enumerate() {
        let mut mc = m;
        for j in 0..3 {
            mc[j][col] = r[j];
        }
        *kc = det3(&mc) / det;
    }
    Ok(k)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chebyshev_points_of_one_to_two() {
        let x = chebyshev(1.0, 2.0);
        for (xi, e) in x.iter().zip([1.0669872981077806, 1.5, 1.9330127018922194]) {
            assert!((xi - e).abs() < 1e-15, "{xi}");
        }
    }

    #[test]
    fn the_linkage_closes_at_the_precision_points() {
        let req = Requirement {
            x_range: (1.0, 2.0),
            input: (45f64.to_radians(), 105f64.to_radians()),
            output: (135f64.to_radians(), 225f64.to_radians()),
            ground: 1.0,
            precision: None,
        };
        let d = synthesise(&req, &|x: f64| libm::log10(x)).unwrap();
        for j in 0..3 {
            let (a, b) = (d.a_at(d.phi[j]), d.b_at(d.psi[j]));
            assert!(((b - a).norm() - d.b).abs() < 1e-12, "{j}: {}", (b - a).norm());
        }
    }

    #[test]
    fn a_precision_point_outside_the_range_is_refused() {
        let req = Requirement {
            x_range: (1.0, 2.0),
            input: (0.5, 1.5),
            output: (2.0, 3.0),
            ground: 1.0,
            precision: Some([1.1, 1.5, 2.5]),
        };
        assert!(matches!(synthesise(&req, &|x| x * x), Err(SynthesisError::PrecisionPointOutside { index: 3, .. })));
    }
}
