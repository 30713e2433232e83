//! The offset slider-crank for H and K, constructed: the guide with the slider's extremes
//! B1, B2 (given, H dimensioned), B2P ⊥ B1B2 and ∠B2B1P = 90° − θ, the circle k on B1P, the
//! line parallel to the guide at the offset e meeting k at the crank pivot O1, θ at P,
//! O1B1 swung onto O1B2 at E (B2E = 2a), the crank circle, and the mechanism at the
//! stretched extreme (solid) and at the folded one (thin).

use super::{Construction, Style, angle_text, deg, extent, len};
use crate::draw::Drawing;
use crate::figure::shared::vocab::ModelUnits;
use crate::geom::{Point, Vector};
use crate::solve::synthesis::slider_crank::Design;
use crate::solve::synthesis::time_ratio;

/// The construction of `d`; `choice` says how the offset was chosen (a caption line).
pub fn construction(d: &Design, choice: &str, units: ModelUnits) -> Drawing {
    let r = Vector::new(d.radius, d.radius);
    let pts = [d.o, d.b1, d.b2, d.p, d.a1, d.a2, d.centre + r, d.centre - r];
    let mut c = Construction::new(extent(&pts, 0.05 * d.stroke), units);
    // Given: the guide and the stroke.
    let ends = (Point::new(d.a1.x.min(d.o.x) - 0.1 * d.stroke, d.b1.y), Point::new(d.b2.x + 0.15 * d.stroke, d.b2.y));
    c.guide(ends.0, ends.1);
    c.distance(d.b1, d.b2, -4.5 * c.s.text, &format!("H = {}", len(d.stroke)));
    // θ's construction and the circle k.
    c.line(d.b2, d.p, Style::Construction);
    c.line(d.b1, d.p, Style::Construction);
    c.right_angle(d.b2, d.b1, d.p);
    let r90 = (0.3 * (d.p - d.b1).norm()).min(0.6 * d.stroke);
    c.angle(d.b1, d.b2, d.p, r90, &format!("90° − θ = {}", angle_text(std::f64::consts::FRAC_PI_2 - d.theta)));
    c.circle(d.centre, d.radius, Style::Construction);
    c.point(d.centre, "O", Style::Construction);
    c.point(d.p, "P", Style::Construction);
    c.name(d.centre + Vector::new(0.0, d.radius), "k", Vector::new(0.0, 1.0));
    // The offset line and the offset.
    // (through O1 and a little beyond: over the rod and the slider it would only crowd them)
    let off = (Point::new(ends.0.x, d.o.y), Point::new((d.o.x + 0.3 * d.stroke).min(ends.1.x), d.o.y));
    c.line(off.0, off.1, Style::Construction);
    let foot = Point::new(d.o.x, d.b1.y);
    c.distance(foot, d.o, 2.0 * c.s.text + d.a, &format!("e = {}", len(d.e)));
    // θ at P (every point of k, O1 too, sees B1B2 under θ: at O1 the angle is small and
    // crowded by the crank, the rod and the slider), the swing of O1B1 onto O1B2, the crank
    // circle.
    c.angle(d.p, d.b1, d.b2, 0.3 * (d.p - d.b2).norm(), &format!("θ = {}", angle_text(d.theta)));
    c.line(d.o, d.b1, Style::Construction);
    c.line(d.o, d.b2, Style::Construction);
    c.arc(d.o, (d.b1 - d.o).norm(), d.b1, d.e_point, Style::Construction);
    c.point(d.e_point, "E", Style::Construction);
    // O1B1 = b − a is too short beside the crank circle, the joint A and B1's block for its
    // name: the caption states it.
    c.segment_name(d.e_point, d.b2, "2a");
    c.circle(d.o, d.a, Style::Construction);
    // The mechanism at both extremes.
    let along = Vector::new(1.0, 0.0);
    c.link(&[d.o, d.a1, d.b1], false, Style::Position);
    c.joint(d.a1, Style::Position);
    c.slider(d.b1, along, Style::Position);
    c.joint(d.b1, Style::Position);
    c.link(&[d.o, d.a2, d.b2], false, Style::Mechanism);
    c.joint(d.a2, Style::Mechanism);
    c.slider(d.b2, along, Style::Mechanism);
    c.joint(d.b2, Style::Mechanism);
    c.pivot(d.o);
    for (p, n) in [(d.o, "O1"), (d.b1, "B1"), (d.b2, "B2"), (d.a1, "A1"), (d.a2, "A2")] {
        c.letter(p, n);
    }
    let k = time_ratio(d.theta);
    let lines = vec![
        format!("Given: stroke H = {}, time ratio K = {}; {choice}.", len(d.stroke), len(k)),
        format!(
            "θ = 180°·(K − 1)/(K + 1) = {}; circle k through B1, B2 sees B1B2 under θ; O1 on k at the offset e from the guide.",
            deg(d.theta)
        ),
        format!(
            "O1B1 = b − a = {}, O1B2 = b + a = {}, B2E = 2a ⇒ crank O1A = a = {}, rod AB = b = {}.",
            len((d.b1 - d.o).norm()),
            len((d.b2 - d.o).norm()),
            len(d.a),
            len(d.b)
        ),
        format!(
            "γ_min = 90° − asin((a + e)/b) = {}; crank turning counter-clockwise: working stroke B{} → B{}.",
            deg(d.gamma_min),
            if d.working_from_b1 { 1 } else { 2 },
            if d.working_from_b1 { 2 } else { 1 }
        ),
    ];
    c.finish(&format!("Offset slider-crank for H = {}, K = {}", len(d.stroke), len(k)), &lines)
}
