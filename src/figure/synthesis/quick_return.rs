//! The shaper's quick return for H and K, constructed: the pivots O3 and O1 (d apart), the
//! crank circle (radius r), the rocker's extremes O3B1, O3B2 tangent to it at A1, A2 (right
//! angles at A1, A2; θ at O3 and the return stroke's crank angle 180° − θ at O1), B's arc
//! (radius l3) with the chord B1B2 = H, the ram's guide with E1, E2 (H dimensioned) and the
//! links B1E1, B2E2; the mechanism at one extreme (solid) and at the other (thin).

use super::{Construction, Style, angle_text, deg, extent, len};
use crate::draw::Drawing;
use crate::figure::shared::vocab::ModelUnits;
use crate::geom::{Point, Vector};
use crate::solve::synthesis::quick_return::Design;
use crate::solve::synthesis::time_ratio;

/// The construction of `d`.
pub fn construction(d: &Design, units: ModelUnits) -> Drawing {
    let pts = [d.o3, d.o1, d.b[0], d.b[1], d.e[0], d.e[1], Point::new(0.0, d.rocker), Point::new(0.0, d.ram_height)];
    let mut c = Construction::new(extent(&pts, 0.08 * d.rocker), units);
    let ([a1, a2], [b1, b2], [e1, e2]) = (d.a, d.b, d.e);
    // The ram's guide and its stroke (given).
    let y = d.ram_height;
    c.guide(Point::new(b2.x - 0.1 * d.rocker, y), Point::new(e1.x + 0.1 * d.rocker, y));
    c.distance(e2, e1, 3.0 * c.s.text, &format!("H = {}", len(d.stroke)));
    // The crank circle and the pivots' distance.
    c.circle(d.o1, d.crank, Style::Construction);
    c.line(d.o3, d.o1, Style::Construction);
    c.distance(d.o3, d.o1, 0.5 * d.rocker * libm::sin(0.5 * d.theta).min(0.5), &format!("d = {}", len(d.ground)));
    // The rocker's extremes, tangent to the crank circle: right angles at A1, A2.
    for (a, b) in [(a1, b1), (a2, b2)] {
        c.line(d.o3, b, Style::Construction);
        c.line(d.o1, a, Style::Construction);
        c.right_angle(a, d.o1, d.o3);
    }
    c.angle(d.o3, b1, b2, 0.78 * d.rocker, &format!("θ = {}", angle_text(d.theta)));
    c.angle(d.o1, a1, a2, 0.8 * d.crank, &format!("180° − θ = {}", angle_text(std::f64::consts::PI - d.theta)));
    // B's arc and the chord B1B2 = H.
    c.arc(d.o3, d.rocker, b1, b2, Style::Construction);
    c.line(b1, b2, Style::Construction);
    c.segment_name(b2, b1, "B1B2 = H");
    // The mechanism at the first extreme (solid) and the second (thin).
    c.link(&[d.o1, a2], false, Style::Position);
    c.link(&[d.o3, b2, e2], false, Style::Position);
    c.joint(a2, Style::Position);
    c.joint(b2, Style::Position);
    c.slider(e2, Vector::new(1.0, 0.0), Style::Position);
    c.joint(e2, Style::Position);
    c.link(&[d.o1, a1], false, Style::Mechanism);
    c.link(&[d.o3, b1, e1], false, Style::Mechanism);
    c.joint(a1, Style::Mechanism);
    c.joint(b1, Style::Mechanism);
    c.slider(e1, Vector::new(1.0, 0.0), Style::Mechanism);
    c.joint(e1, Style::Mechanism);
    c.pivot(d.o3);
    c.pivot(d.o1);
    for (p, n) in [(d.o3, "O3"), (d.o1, "O1"), (a1, "A1"), (a2, "A2"), (b1, "B1"), (b2, "B2"), (e1, "E1"), (e2, "E2")] {
        c.letter(p, n);
    }
    let k = time_ratio(d.theta);
    let mut lines = vec![
        format!("Given: ram stroke H = {}, time ratio K = {}.", len(d.stroke), len(k)),
        format!(
            "θ = 180°·(K − 1)/(K + 1) = {} = the rocker's swing; at the extremes the crank is ⊥ to the rocker: sin(θ/2) = r/d.",
            deg(d.theta)
        ),
        format!(
            "crank O1A = r = {}, O1O3 = d = {}, rocker O3B = l3 = H/(2·sin(θ/2)) = {}, link BE = {}, ram guide at {} above O3.",
            len(d.crank),
            len(d.ground),
            len(d.rocker),
            len(d.link),
            len(d.ram_height)
        ),
        format!(
            "Working stroke over {} of crank, return over {}; smallest transmission angle at E {}.",
            deg(std::f64::consts::PI + d.theta),
            deg(std::f64::consts::PI - d.theta),
            deg(d.gamma_min)
        ),
    ];
    if d.block_reach > d.rocker {
        lines.push(format!(
            "The block reaches {} from O3, beyond the rocker O3B = {}: the slot must run past B.",
            len(d.block_reach),
            len(d.rocker)
        ));
    }
    c.finish(&format!("Quick-return shaper for H = {}, K = {}", len(d.stroke), len(k)), &lines)
}
