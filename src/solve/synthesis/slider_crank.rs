//! An offset slider-crank for a stroke H and a time ratio K, by the same construction as
//! the crank-rocker's (the rocker's circle becomes the slider's line): θ = 180°·(K − 1)/(K + 1);
//! the slider's extremes B1, B2 on its guide, H apart; the circle through them on which
//! B1B2 is seen under θ; the crank pivot O on it at the offset e from the guide; then
//! OB1 = b − a (folded), OB2 = b + a (stretched).
//!
//! The crank pivot must lie beyond both extremes (not over the stroke): there the crank
//! would pass the extremes on the two sides of the guide's normal, an arc the textbooks
//! exclude as for the crank-rocker. So a K needs θ < 90° (K < 3) and the offset lies in
//! (0, H·cot θ). The free choice is the offset e ([`Choice::Offset`]) or the one with the
//! largest smallest transmission angle ([`Choice::BestTransmission`]).
//!
//! The design is returned in the frame of the `linkage` template `slider-crank.toml`: the
//! crank pivot O at the origin, the guide parallel to +x at y = −e, the slider to the right
//! of O.

use super::{SynthesisError, best_of, excess_angle, positive, seeing_circle};
use crate::geom::{Point, Side, Vector, angle_of, normalize_angle};

/// What the design must do.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Requirement {
    /// Stroke H of the slider (> 0).
    pub stroke: f64,
    /// Time ratio K > 1.
    pub time_ratio: f64,
    /// The free choice.
    pub choice: Choice,
}

/// The free choice of the crank pivot on its circle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Choice {
    /// The offset e of the crank pivot from the guide (> 0).
    Offset(f64),
    /// The offset with the largest γ_min.
    BestTransmission,
}

/// One offset slider-crank that meets the requirement, with its construction (O at the
/// origin, the guide at y = −e along +x).
#[derive(Debug, Clone, PartialEq)]
pub struct Design {
    /// Crank OA.
    pub a: f64,
    /// Connecting rod AB.
    pub b: f64,
    /// Offset e of O from the guide line.
    pub e: f64,
    /// Stroke H.
    pub stroke: f64,
    /// Crank pivot (the origin).
    pub o: Point,
    /// The slider's extreme with crank and rod folded: OB1 = b − a.
    pub b1: Point,
    /// The slider's extreme with crank and rod stretched: OB2 = b + a.
    pub b2: Point,
    /// The crank pin at B1 (on B1O produced beyond O).
    pub a1: Point,
    /// The crank pin at B2 (on OB2).
    pub a2: Point,
    /// OB1 swung onto OB2 about O: B2E = 2a.
    pub e_point: Point,
    /// Centre of the circle through B1, B2.
    pub centre: Point,
    /// Its radius.
    pub radius: f64,
    /// The end of its diameter from B1 (B2P ⊥ B1B2).
    pub p: Point,
    /// Excess angle θ.
    pub theta: f64,
    /// Smallest transmission angle γ_min = 90° − asin((a + e)/b), radians.
    pub gamma_min: f64,
    /// Crank angles at B1 and at B2, radians.
    pub crank_at: (f64, f64),
    /// Whether, with the crank turning counter-clockwise, the working (longer) stroke runs
    /// from B1 to B2.
    pub working_from_b1: bool,
}

/// The family over the offset e.
#[derive(Debug, Clone, PartialEq)]
pub struct Family {
    /// Samples (e, γ_min in radians), increasing e over (0, e_max).
    pub samples: Vec<(f64, f64)>,
    /// The largest valid offset, H·cot θ.
    pub e_max: f64,
    /// The design with the largest γ_min: (e, γ_min).
    pub best: (f64, f64),
}

/// A synthesis: the design and the family it was chosen from.
#[derive(Debug, Clone, PartialEq)]
pub struct Synthesis {
    /// The design.
    pub design: Design,
    /// The family over e.
    pub family: Family,
}

/// Samples of e charted over the family.
pub const FAMILY_SAMPLES: usize = 401;

/// The design at offset `e` (0 < e < H·cot θ), with the guide on y = 0 from B1 = (0, 0) to
/// B2 = (H, 0), O above, then moved so that O is the origin.
fn at(h: f64, theta: f64, e: f64) -> Option<Design> {
    let (b1, b2) = (Point::new(0.0, 0.0), Point::new(h, 0.0));
    let (m, r) = seeing_circle(b1, b2, theta, Side::Left);
    let dy = e - m.y;
    let s2 = r * r - dy * dy;
    if s2.is_nan() || s2 <= 0.0 {
        return None;
    }
    let o = Point::new(m.x - s2.sqrt(), e);
    if !(o.x < 0.0 && e > 0.0) {
        return None;
    }
    let (r1, r2) = ((b1 - o).norm(), (b2 - o).norm());
    let a = 0.5 * (r2 - r1);
    let b = 0.5 * (r2 + r1);
    let (u1, u2) = ((b1 - o) / r1, (b2 - o) / r2);
    let shift = |p: Point| Point::origin() + (p - o);
    let (a1, a2) = (o - u1 * a, o + u2 * a);
    let crank_at = (angle_of(a1 - o), angle_of(a2 - o));
    let forward = normalize_angle(crank_at.1 - crank_at.0);
    let sin = ((a + e) / b).min(1.0);
    Some(Design {
        a,
        b,
        e,
        stroke: h,
        o: Point::origin(),
        b1: shift(b1),
        b2: shift(b2),
        a1: shift(a1),
        a2: shift(a2),
        e_point: shift(o + u2 * r1),
        centre: shift(m),
        radius: r,
        p: shift(Point::origin() + (m - Point::origin()) * 2.0 - (b1 - Point::origin())),
        theta,
        gamma_min: std::f64::consts::FRAC_PI_2 - libm::asin(sin),
        crank_at,
        working_from_b1: forward > std::f64::consts::PI,
    })
}

/// Synthesises the offset slider-crank.
pub fn synthesise(req: &Requirement) -> Result<Synthesis, SynthesisError> {
    let h = positive("the stroke H", req.stroke)?;
    let theta = excess_angle(req.time_ratio)?;
    if theta >= std::f64::consts::FRAC_PI_2 {
        return Err(SynthesisError::OutOfFamily {
            what: "the time ratio K",
            value: req.time_ratio,
            why: format!(
                "θ = {:.4}° ≥ 90°: the crank pivot would have to lie over the stroke, where the crank passes the extremes on opposite sides",
                theta.to_degrees()
            ),
            valid: "K < 3 for an offset slider-crank".into(),
        });
    }
    let e_max = h / libm::tan(theta);
    let n = FAMILY_SAMPLES;
    let samples: Vec<(f64, f64)> = (1..n)
        .filter_map(|k| {
            let e = e_max * k as f64 / n as f64;
            at(h, theta, e).map(|d| (e, d.gamma_min))
        })
        .collect();
    let gamma = |e: f64| at(h, theta, e).map_or(f64::NEG_INFINITY, |d| d.gamma_min);
    let best = best_of(&gamma, 1e-9 * e_max, (1.0 - 1e-9) * e_max, 64);
    let e = match req.choice {
        Choice::Offset(e) => e,
        Choice::BestTransmission => best.0,
    };
    let design = at(h, theta, e).filter(|_| e.is_finite() && e > 0.0 && e < e_max).ok_or_else(|| {
        SynthesisError::OutOfFamily {
            what: "the offset e",
            value: e,
            why: "the crank pivot at this offset would not lie beyond both extremes of the stroke".into(),
            valid: format!("0 < e < H·cot θ = {e_max:.6}"),
        }
    })?;
    Ok(Synthesis { design, family: Family { samples, e_max, best } })
}

impl Design {
    /// The guide's unit direction (+x) and a point on it.
    pub fn guide(&self) -> (Point, Vector) {
        (Point::new(0.0, -self.e), Vector::new(1.0, 0.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The slider's x at crank angle φ (closed form of the offset slider-crank).
    fn slider_x(d: &Design, phi: f64) -> f64 {
        let (ax, ay) = (d.a * libm::cos(phi), d.a * libm::sin(phi));
        ax + (d.b * d.b - (ay + d.e) * (ay + d.e)).sqrt()
    }

    #[test]
    fn the_construction_gives_back_h_and_k_by_the_closed_form() {
        for choice in [Choice::Offset(10.0), Choice::Offset(25.0), Choice::BestTransmission] {
            let s = synthesise(&Requirement { stroke: 50.0, time_ratio: 1.2, choice }).unwrap();
            let d = &s.design;
            // The textbook closed form: H = √((l+r)² − e²) − √((l−r)² − e²).
            let (sum, diff) = (d.b + d.a, d.b - d.a);
            let h = (sum * sum - d.e * d.e).sqrt() - (diff * diff - d.e * d.e).sqrt();
            assert!((h - 50.0).abs() < 1e-12 * 50.0, "{choice:?}: H = {h}");
            let theta = libm::asin(d.e / (d.b - d.a)) - libm::asin(d.e / (d.b + d.a));
            assert!((super::super::time_ratio(theta) - 1.2).abs() < 1e-12, "{choice:?}");
            // The extremes' crank angles give B1 and B2.
            assert!((slider_x(d, d.crank_at.0) - d.b1.x).abs() < 1e-9);
            assert!((slider_x(d, d.crank_at.1) - d.b2.x).abs() < 1e-9);
        }
    }

    #[test]
    fn an_offset_beyond_the_family_and_k_of_3_are_refused() {
        let r = |k: f64, choice| synthesise(&Requirement { stroke: 50.0, time_ratio: k, choice });
        let e_max = 50.0 / libm::tan(std::f64::consts::PI * 0.2 / 2.2);
        assert!(matches!(r(1.2, Choice::Offset(e_max * 1.01)), Err(SynthesisError::OutOfFamily { .. })));
        assert!(matches!(r(3.0, Choice::BestTransmission), Err(SynthesisError::OutOfFamily { .. })));
        assert!(matches!(r(0.9, Choice::BestTransmission), Err(SynthesisError::TimeRatio { .. })));
    }
}
