//! Motion generation, constructed: the required positions of the coupler line (given, each
//! its point P_i and its direction), the coupler carrying the chosen moving pivots A and B
//! to A_i, B_i, the chords A1A2 (A2A3) and B1B2 (B2B3) with their perpendicular bisectors
//! meeting at the fixed pivots O1 and C (on the bisector at the chosen distance for two
//! positions), the circles of A and B about them, the four-bar in position 1 (solid) and in
//! the others (thin).

use super::{Construction, Style, deg, extent, len};
use crate::draw::Drawing;
use crate::figure::shared::vocab::ModelUnits;
use crate::geom::Vector;
use crate::solve::synthesis::motion::Design;

/// The construction of `d`.
pub fn construction(d: &Design, units: ModelUnits) -> Drawing {
    let n = d.poses.len();
    let mut pts = vec![d.o_a, d.o_b];
    pts.extend(d.a.iter().chain(&d.b).copied());
    pts.extend(d.poses.iter().map(|p| p.at));
    let size = d.l_ab.max(d.ground);
    let mut c = Construction::new(extent(&pts, 0.1 * size), units);
    // The required positions: the coupler line through P_i in its direction.
    let half = 0.3 * d.l_ab;
    for (i, p) in d.poses.iter().enumerate() {
        let u = Vector::new(libm::cos(p.angle), libm::sin(p.angle));
        c.line(p.at - u * half, p.at + u * half, Style::Given);
        c.point(p.at, &format!("P{}", i + 1), Style::Given);
    }
    // Chords and perpendicular bisectors, for A and for B, to the fixed pivots.
    for (bisectors, pivot) in d.bisectors.iter().zip([d.o_a, d.o_b]) {
        for b in bisectors {
            c.line(b.chord.0, b.chord.1, Style::Construction);
            c.right_angle(b.mid, b.chord.1, b.mid + b.dir);
            let t = (pivot - b.mid).dot(&b.dir);
            let over = 0.15 * size;
            let (from, to) = if t >= 0.0 {
                (b.mid - b.dir * over, pivot + b.dir * over)
            } else {
                (b.mid + b.dir * over, pivot - b.dir * over)
            };
            c.line(from, to, Style::Construction);
        }
    }
    c.arc_through(d.o_a, d.l_in, &d.a, 0.15, Style::Construction);
    c.arc_through(d.o_b, d.l_out, &d.b, 0.15, Style::Construction);
    // The four-bar in each position: the first solid, the others thin.
    for i in (0..n).rev() {
        let style = if i == 0 { Style::Mechanism } else { Style::Position };
        c.link(&[d.o_a, d.a[i]], false, style);
        c.link(&[d.a[i], d.b[i], d.poses[i].at], true, style);
        c.link(&[d.b[i], d.o_b], false, style);
        c.joint(d.a[i], style);
        c.joint(d.b[i], style);
        c.letter(d.a[i], &format!("A{}", i + 1));
        c.letter(d.b[i], &format!("B{}", i + 1));
    }
    c.pivot(d.o_a);
    c.pivot(d.o_b);
    c.letter(d.o_a, "O1");
    c.letter(d.o_b, "C");
    c.finish(&format!("Motion generation through {n} positions"), &caption(d))
}

fn caption(d: &Design) -> Vec<String> {
    let n = d.poses.len();
    let given: Vec<String> = d
        .poses
        .iter()
        .enumerate()
        .map(|(i, p)| format!("P{} ({}, {}) at {}", i + 1, len(p.at.x), len(p.at.y), deg(p.angle)))
        .collect();
    let how = if n == 3 {
        "The fixed pivots are where the perpendicular bisectors of A1A2, A2A3 (B1B2, B2B3) meet"
    } else {
        "The fixed pivots lie on the perpendicular bisectors of A1A2 and B1B2 at the chosen distances"
    };
    let mut lines = vec![
        format!("Given: the coupler line's positions {}; moving pivots A1, B1 chosen.", given.join(", ")),
        format!("{how}."),
        format!(
            "O1 ({}, {}), C ({}, {}); crank O1A = {}, coupler AB = {}, rocker CB = {}, ground O1C = {}; P from B: {} at {} to BA.",
            len(d.o_a.x),
            len(d.o_a.y),
            len(d.o_b.x),
            len(d.o_b.y),
            len(d.l_in),
            len(d.l_ab),
            len(d.l_out),
            len(d.ground),
            len(d.l_bp),
            deg(d.alpha)
        ),
        format!("{}{}.", d.class.describe(), d.gamma_min.map_or(String::new(), |g| format!(", γ_min = {}", deg(g)))),
    ];
    if d.defects.is_empty() {
        lines.push("No branch, order or crank defect.".into());
    }
    lines.extend(d.defects.iter().map(|x| capitalised(&x.describe())));
    lines
}

fn capitalised(s: &str) -> String {
    let mut c = s.chars();
    c.next().map_or_else(String::new, |f| f.to_uppercase().collect::<String>() + c.as_str())
}
