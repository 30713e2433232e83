//! The crank-rocker for ψ and K, constructed: the rocker CB in its extremes CB1, CB2 (given,
//! the swing ψ dimensioned at C), the chord B1B2 with B2P ⊥ B1B2 and ∠B2B1P = 90° − θ, the
//! circle k on the diameter B1P (centre O), the crank pivot O1 on it seeing B1B2 under θ,
//! the arc O1B1 swung onto O1B2 to E (B2E = 2a), the crank circle, on the far circle the
//! forbidden arc FG with CB1 and CB2 produced, and the mechanism at the stretched extreme
//! (solid) and at the folded one (thin).

use super::{Construction, Style, angle_text, deg, extent, len};
use crate::draw::Drawing;
use crate::figure::shared::vocab::ModelUnits;
use crate::geom::{Point, Vector, angle_of, normalize_angle};
use crate::solve::synthesis::crank_rocker::{Circle, Design};
use crate::solve::synthesis::time_ratio;

/// The construction of `d`; `choice` says how the crank pivot was chosen (a caption line).
pub fn construction(d: &Design, choice: &str, units: ModelUnits) -> Drawing {
    let mut pts = vec![d.o1, d.pivot_c, d.b1, d.b2, d.p, d.a1, d.a2];
    pts.extend([d.centre + Vector::new(d.radius, d.radius), d.centre - Vector::new(d.radius, d.radius)]);
    if let Some((f, g)) = d.forbidden {
        pts.extend([f, g]);
    }
    let mut c = Construction::new(extent(&pts, 0.05 * d.c), units);
    let r_dim = 0.35 * d.c;
    // Given: the rocker in its extremes and its swing.
    c.line(d.pivot_c, d.b1, Style::Given);
    c.line(d.pivot_c, d.b2, Style::Given);
    c.angle(d.pivot_c, d.b1, d.b2, r_dim, &format!("ψ = {}", angle_text(d.psi)));
    // θ's construction: the chord, B2P ⊥ B1B2, B1P at 90° − θ, the circle k on B1P.
    c.line(d.b1, d.b2, Style::Construction);
    c.line(d.b2, d.p, Style::Construction);
    c.line(d.b1, d.p, Style::Construction);
    c.right_angle(d.b2, d.b1, d.p);
    let r90 = (0.3 * (d.p - d.b1).norm()).min(0.5 * (d.b2 - d.b1).norm());
    c.angle(d.b1, d.b2, d.p, r90, &format!("90° − θ = {}", angle_text(std::f64::consts::FRAC_PI_2 - d.theta)));
    c.circle(d.centre, d.radius, Style::Construction);
    c.point(d.centre, "O", Style::Construction);
    c.point(d.p, "P", Style::Construction);
    c.name(d.centre + Vector::new(0.0, d.radius), "k", Vector::new(0.0, 1.0));
    if let Some((f, g)) = d.forbidden {
        forbidden_arc(&mut c, d, f, g);
    }
    // O1 sees B1B2 under θ; O1B1 = b − a, O1B2 = b + a; B1 swung about O1 onto O1B2 at E.
    c.line(d.o1, d.b1, Style::Construction);
    c.line(d.o1, d.b2, Style::Construction);
    c.angle(d.o1, d.b1, d.b2, 0.45 * (d.b1 - d.o1).norm(), &format!("θ = {}", angle_text(d.theta)));
    c.arc(d.o1, (d.b1 - d.o1).norm(), d.b1, d.e, Style::Construction);
    c.point(d.e, "E", Style::Construction);
    c.segment_name(d.o1, d.b1, "b − a");
    c.segment_name(d.e, d.b2, "2a");
    c.circle(d.o1, d.a, Style::Construction);
    // The mechanism at the folded extreme (thin) and at the stretched one (solid).
    c.link(&[d.o1, d.a1, d.b1], false, Style::Position);
    c.joint(d.a1, Style::Position);
    c.link(&[d.o1, d.a2, d.b2, d.pivot_c], false, Style::Mechanism);
    c.joint(d.a2, Style::Mechanism);
    c.joint(d.b2, Style::Mechanism);
    c.joint(d.b1, Style::Position);
    c.pivot(d.o1);
    c.pivot(d.pivot_c);
    for (p, n) in [(d.o1, "O1"), (d.pivot_c, "C"), (d.b1, "B1"), (d.b2, "B2"), (d.a1, "A1"), (d.a2, "A2")] {
        c.letter(p, n);
    }
    let title = format!("Crank-rocker for ψ = {}, K = {}", deg(d.psi), len(time_ratio(d.theta)));
    c.finish(&title, &caption(d, choice))
}

/// The arc FG of the far circle where O1 must not lie, and the rocker lines CB1, CB2
/// produced to F and G.
fn forbidden_arc(c: &mut Construction, d: &Design, f: Point, g: Point) {
    c.line(d.b1, f, Style::Construction);
    c.line(d.b2, g, Style::Construction);
    // The arc between F and G that does not hold B1 and B2.
    let (af, ag) = (angle_of(f - d.centre), angle_of(g - d.centre));
    let ab = angle_of(d.b1 - d.centre);
    let sweep = normalize_angle(ag - af);
    let (start, sweep) =
        if normalize_angle(ab - af) < sweep { (ag, std::f64::consts::TAU - sweep) } else { (af, sweep) };
    c.thick_arc(d.centre, d.radius, start, sweep, Style::Forbidden);
    c.point(f, "F", Style::Forbidden);
    c.point(g, "G", Style::Forbidden);
}

/// The caption: the requirement, the steps and the answer.
fn caption(d: &Design, choice: &str) -> Vec<String> {
    let k = time_ratio(d.theta);
    let mut lines = vec![
        format!("Given: rocker CB = c = {}, swing ψ = {}, time ratio K = {}; {choice}.", len(d.c), deg(d.psi), len(k)),
        format!(
            "θ = 180°·(K − 1)/(K + 1) = {}; circle k through B1, B2 sees B1B2 under θ (B2P ⊥ B1B2, ∠B2B1P = 90° − θ).",
            deg(d.theta)
        ),
        format!(
            "O1 on k: O1B1 = b − a = {}, O1B2 = b + a = {}, B2E = 2a ⇒ crank O1A = a = {}, coupler AB = b = {}, ground O1C = d = {}.",
            len((d.b1 - d.o1).norm()),
            len((d.b2 - d.o1).norm()),
            len(d.a),
            len(d.b),
            len(d.d)
        ),
        format!(
            "{}; γ_min = {}; crank turning counter-clockwise: working stroke B{} → B{} over {} of crank, return over {}.",
            d.class.describe(),
            deg(d.gamma_min),
            if d.working_from_b1 { 1 } else { 2 },
            if d.working_from_b1 { 2 } else { 1 },
            deg(std::f64::consts::PI + d.theta),
            deg(std::f64::consts::PI - d.theta)
        ),
    ];
    if d.circle == Circle::Far {
        lines.push("O1 must not lie on the arc FG between CB1 and CB2 produced: there the crank passes B1 and B2 on different assembly modes.".into());
    }
    lines
}
