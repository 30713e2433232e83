//! The shaper's quick-return mechanism (seed 002: crank O1A, a block at A sliding on the
//! rocker O3B, link BE, ram point E on a guide) for a ram stroke H and a time ratio K.
//!
//! The textbook construction: at the rocker's extremes the crank is at right angles to it
//! (the rocker tangent to the crank circle), so the rocker swings through ψ = θ =
//! 180°·(K − 1)/(K + 1) and sin(θ/2) = r/d (crank r = O1A, d = O1O3). B swings on the arc
//! of radius l3 = O3B; its extremes are 2·l3·sin(θ/2) apart at the same height, so with the
//! ram's guide parallel to the chord B1B2 the ram point E moves by the same H:
//! l3 = H/(2·sin(θ/2)). One of r and d sets the other. The free choices: the ram's guide
//! height (the textbook's best halves the arc's sagitta, so the link BE tilts least) and the
//! link BE.
//!
//! The design is returned in the frame of `templates/shaper.toml`: O3 at the origin, O1
//! above it at (0, d), the ram's guide y = h, E right of B.

use std::f64::consts::FRAC_PI_2;

use super::{SynthesisError, excess_angle, positive, unit};
use crate::geom::{Point, angle_of};

/// What sets the mechanism's size besides H.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Size {
    /// The crank O1A.
    Crank(f64),
    /// The distance O1O3 between the pivots.
    Ground(f64),
}

/// What the design must do.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Requirement {
    /// Ram stroke H (> 0).
    pub stroke: f64,
    /// Time ratio K > 1.
    pub time_ratio: f64,
    /// The crank or the pivots' distance.
    pub size: Size,
    /// The link BE; `None`: a quarter of the rocker (the seed's 150 for 600).
    pub link: Option<f64>,
    /// The ram guide's height above O3; `None`: the middle of the arc's sagitta,
    /// l3·(1 + cos(θ/2))/2.
    pub ram_height: Option<f64>,
}

/// The shaper that meets the requirement, with its construction.
#[derive(Debug, Clone, PartialEq)]
pub struct Design {
    /// Crank O1A = r.
    pub crank: f64,
    /// Distance O1O3 = d.
    pub ground: f64,
    /// Rocker O3B = l3.
    pub rocker: f64,
    /// Link BE = l4.
    pub link: f64,
    /// The ram guide's height h above O3.
    pub ram_height: f64,
    /// Stroke H.
    pub stroke: f64,
    /// Excess angle θ (= the rocker's swing).
    pub theta: f64,
    /// Rocker pivot O3 (the origin).
    pub o3: Point,
    /// Crank pivot O1 = (0, d).
    pub o1: Point,
    /// The crank pins where the rocker is at its extremes (tangent points), right then left.
    pub a: [Point; 2],
    /// The rocker's tip at the extremes.
    pub b: [Point; 2],
    /// The ram point at the extremes.
    pub e: [Point; 2],
    /// Crank angles at the two extremes, radians.
    pub crank_at: [f64; 2],
    /// The smallest angle between the link BE and the ram's guide normal over the swing
    /// (the transmission angle at E), radians.
    pub gamma_min: f64,
    /// The farthest the block goes from O3 (d + r): the rocker's slot must reach it.
    pub block_reach: f64,
}

/// Synthesises the shaper.
pub fn synthesise(req: &Requirement) -> Result<Design, SynthesisError> {
    let h = positive("the stroke H", req.stroke)?;
    let theta = excess_angle(req.time_ratio)?;
    let half = 0.5 * theta;
    let (crank, ground) = match req.size {
        Size::Crank(r) => {
            let r = positive("the crank O1A", r)?;
            (r, r / libm::sin(half))
        }
        Size::Ground(d) => {
            let d = positive("the distance O1O3", d)?;
            (d * libm::sin(half), d)
        }
    };
    let rocker = h / (2.0 * libm::sin(half));
    let sag = rocker * (1.0 - libm::cos(half));
    let ram_height = match req.ram_height {
        Some(y) if y.is_finite() => y,
        Some(y) => return Err(SynthesisError::Length { what: "the ram guide's height", value: y }),
        None => rocker - 0.5 * sag,
    };
    let link = match req.link {
        Some(l) => positive("the link BE", l)?,
        None => 0.25 * rocker,
    };
    let o3 = Point::origin();
    let o1 = Point::new(0.0, ground);
    // The rocker's directions at the extremes: right (90° − θ/2), then left.
    let dirs = [FRAC_PI_2 - half, FRAC_PI_2 + half];
    let b = dirs.map(|t| o3 + unit(t) * rocker);
    // Over the swing B's height runs from l3·cos(θ/2) to l3: the link must reach the guide.
    let reach_needed = (ram_height - rocker * libm::cos(half)).abs().max((ram_height - rocker).abs());
    if link < reach_needed {
        return Err(SynthesisError::OutOfFamily {
            what: "the link BE",
            value: link,
            why: format!(
                "B's height runs over {:.6}…{:.6} during the swing and the ram's guide is at {ram_height:.6}: the link cannot reach it",
                rocker * libm::cos(half),
                rocker
            ),
            valid: format!("BE ≥ {reach_needed:.6}, or a guide height nearer the arc"),
        });
    }
    let e = b.map(|p| Point::new(p.x + (link * link - (ram_height - p.y) * (ram_height - p.y)).sqrt(), ram_height));
    // The tangent points: A on O3B at distance d·cos(θ/2) from O3.
    let a = dirs.map(|t| o3 + unit(t) * (ground * libm::cos(half)));
    let crank_at = a.map(|p| angle_of(p - o1));
    // The link's largest tilt from the guide's normal over the swing: B at the top or at the
    // ends of the arc.
    let tilt = |y: f64| libm::asin(((ram_height - y) / link).clamp(-1.0, 1.0)).abs();
    let gamma_min = FRAC_PI_2 - tilt(rocker).max(tilt(rocker * libm::cos(half)));
    Ok(Design {
        crank,
        ground,
        rocker,
        link,
        ram_height,
        stroke: h,
        theta,
        o3,
        o1,
        a,
        b,
        e,
        crank_at,
        gamma_min,
        block_reach: ground + crank,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_seed_shaper_comes_back_from_its_stroke_and_time_ratio() {
        // design.md §3: r = 125, O1O3 = 300, l3 = 600: θ = 2·asin(125/300), H = 500.
        let theta = 2.0 * libm::asin(125.0 / 300.0);
        let k = super::super::time_ratio(theta);
        let req = Requirement {
            stroke: 500.0,
            time_ratio: k,
            size: Size::Crank(125.0),
            link: Some(150.0),
            ram_height: Some(600.0),
        };
        let d = synthesise(&req).unwrap();
        assert!((d.ground - 300.0).abs() < 1e-12 * 300.0, "{}", d.ground);
        assert!((d.rocker - 600.0).abs() < 1e-12 * 600.0, "{}", d.rocker);
        assert!((d.e[0].x - d.e[1].x - 500.0).abs() < 1e-9);
        // The same from the pivots' distance.
        let by_ground = synthesise(&Requirement { size: Size::Ground(300.0), ..req }).unwrap();
        assert!((by_ground.crank - 125.0).abs() < 1e-12 * 125.0);
    }

    #[test]
    fn the_swinging_guide_bar_exercise_gives_its_published_crank() {
        // 杨可桢, 机械设计基础, exercise 2-8: a swinging guide-bar mechanism, l = 100 mm between
        // the pivots, K = 1.4: θ = 30° and the crank l1 = 100·sin 15° = 25.88 ("26 mm").
        let req =
            Requirement { stroke: 100.0, time_ratio: 1.4, size: Size::Ground(100.0), link: None, ram_height: None };
        let d = synthesise(&req).unwrap();
        assert!((d.theta.to_degrees() - 30.0).abs() < 1e-12);
        assert!((d.crank - 25.881904510252074).abs() < 1e-12);
        assert_eq!(format!("{:.0}", d.crank), "26");
    }

    #[test]
    fn a_link_too_short_for_the_guide_is_refused() {
        let req = Requirement {
            stroke: 500.0,
            time_ratio: 1.75,
            size: Size::Crank(125.0),
            link: Some(10.0),
            ram_height: None,
        };
        assert!(matches!(synthesise(&req), Err(SynthesisError::OutOfFamily { what: "the link BE", .. })));
    }
}
