//! Function generation, drawn: the four-bar at its three precision points (the first solid,
//! the others thin), the input's range Δφ at O1 and the output's Δψ at C with the first
//! precision point's angles φ1, ψ1 (both from the ground line O1C), and under it Chebyshev's
//! spacing as the textbook constructs it: a half circle over the range of x, the regular
//! hexagon's vertices at 150°, 90°, 30° projected onto the diameter at the precision points
//! x1, x2, x3.

use super::{Construction, Style, angle_text, deg, len, signed_angle_text};
use crate::draw::{Bounds, Drawing};
use crate::figure::shared::vocab::ModelUnits;
use crate::geom::{Point, Vector};
use crate::solve::synthesis::function::{Design, Requirement};

/// The construction of `d` for `req`; `function` is the text of f(x).
pub fn construction(d: &Design, req: &Requirement, function: &str, units: ModelUnits) -> Drawing {
    let a: Vec<Point> = (0..3).map(|j| d.a_at(d.phi[j])).collect();
    let b: Vec<Point> = (0..3).map(|j| d.b_at(d.psi[j])).collect();
    let (o1, cp) = (d.o1(), d.pivot_c());
    let mut pts = vec![o1, cp];
    pts.extend(a.iter().chain(&b).copied());
    let size = d.a.max(d.b).max(d.c).max(d.d);
    // Room for Chebyshev's half circle under the mechanism.
    let ext = super::extent(&pts, 0.1 * size);
    let cheb_r = 0.35 * ext.width();
    let cheb_centre = Point::new(ext.min.x + cheb_r + 0.1 * size, ext.min.y - 0.25 * size - cheb_r);
    let ext = Bounds { min: Point::new(ext.min.x, cheb_centre.y - 0.2 * size), max: ext.max };
    let mut c = Construction::new(ext, units);
    let ahead = |p: Point| p + (cp - o1).normalize() * (0.3 * size);
    c.line(o1, ahead(cp), Style::Construction);
    for j in (0..3).rev() {
        let style = if j == 0 { Style::Mechanism } else { Style::Position };
        c.link(&[o1, a[j], b[j], cp], false, style);
        c.joint(a[j], style);
        c.joint(b[j], style);
        c.letter(a[j], &format!("A{}", j + 1));
        c.letter(b[j], &format!("B{}", j + 1));
    }
    // The ranges (from x0 to x1) and the first precision point's angles.
    let (as_, af) = (d.a_at(req.input.0), d.a_at(req.input.1));
    let (bs, bf) = (d.b_at(req.output.0), d.b_at(req.output.1));
    c.arc_through(o1, d.a, &[as_, af], 0.0, Style::Given);
    c.arc_through(cp, d.c, &[bs, bf], 0.0, Style::Given);
    c.angle(o1, as_, af, 1.15 * d.a, &format!("Δφ = {}", angle_text((req.input.1 - req.input.0).abs())));
    c.angle(cp, bs, bf, 1.15 * d.c, &format!("Δψ = {}", angle_text((req.output.1 - req.output.0).abs())));
    // The first precision point's angles named on the figure, their values in the caption
    // (the sectors at the pivots are crowded by the other positions' links).
    c.angle(o1, ahead(cp), a[0], 0.4 * d.a, "φ1");
    c.angle(cp, ahead(cp), b[0], 0.4 * d.c, "ψ1");
    c.pivot(o1);
    c.pivot(cp);
    c.letter(o1, "O1");
    c.letter(cp, "C");
    chebyshev(&mut c, d, req, cheb_centre, cheb_r);
    c.finish(&format!("Function generator for y = {function}"), &caption(d, req, function))
}

fn caption(d: &Design, req: &Requirement, function: &str) -> Vec<String> {
    vec![
        format!(
            "Given: y = {function} for x from xs = {} to xf = {}; φ from {} to {}, ψ from {} to {}; ground O1C = {}.",
            len(req.x_range.0),
            len(req.x_range.1),
            deg(req.input.0),
            deg(req.input.1),
            deg(req.output.0),
            deg(req.output.1),
            len(d.d)
        ),
        format!(
            "Precision points x = {}, {}, {} (y = {}, {}, {}); Freudenstein: K1·cos ψ − K2·cos φ + K3 = cos(φ − ψ).",
            len(d.x[0]),
            len(d.x[1]),
            len(d.x[2]),
            len(d.y[0]),
            len(d.y[1]),
            len(d.y[2])
        ),
        format!(
            "K1 = d/a = {}, K2 = d/c = {}, K3 = {} ⇒ crank O1A = {}, coupler AB = {}, rocker CB = {}; {}.",
            len(d.k[0]),
            len(d.k[1]),
            len(d.k[2]),
            len(d.a),
            len(d.b),
            len(d.c),
            d.class.describe()
        ),
        format!(
            "Crank angle = φ{}, rocker angle = ψ{}, both from O1C (φ1 = {}, ψ1 = {} at the first precision point); the structural error over the range is charted in the diagrams.",
            turn(d.crank_turn),
            turn(d.rocker_turn),
            signed_angle_text(d.phi[0] + d.crank_turn),
            signed_angle_text(d.psi[0] + d.rocker_turn)
        ),
    ]
}

/// ` + 180°` for a half turn, nothing for none.
fn turn(t: f64) -> &'static str {
    if t != 0.0 { " + 180°" } else { "" }
}

/// Chebyshev's spacing: the half circle over [xs, xf] drawn with diameter 2·`r` about
/// `centre`, the hexagon's vertices projected onto the diameter.
fn chebyshev(c: &mut Construction, d: &Design, req: &Requirement, centre: Point, r: f64) {
    let (x0, x1) = req.x_range;
    let left = centre - Vector::new(r, 0.0);
    let right = centre + Vector::new(r, 0.0);
    c.line(left, right, Style::Given);
    c.arc_ccw(centre, r, 0.0, std::f64::consts::PI, Style::Construction);
    c.point(left, "xs", Style::Given);
    c.point(right, "xf", Style::Given);
    let mut vertices: Vec<Point> = Vec::new();
    for j in 0..3 {
        let t = (d.x[j] - x0) / (x1 - x0);
        let on_axis = left + (right - left) * t;
        let ang = libm::acos(((on_axis - centre).x / r).clamp(-1.0, 1.0));
        let v = centre + Vector::new(libm::cos(ang), libm::sin(ang)) * r;
        c.line(v, on_axis, Style::Construction);
        c.line(centre, v, Style::Construction);
        c.point(on_axis, &format!("x{}", j + 1), Style::Given);
        vertices.push(v);
    }
    // Two sides of the hexagon (its vertical sides are the projections at x1 and x3).
    c.link(&vertices, false, Style::Position);
    c.angle(centre, right, vertices[2], 0.3 * r, &angle_text(std::f64::consts::PI / 6.0));
    c.name(centre + Vector::new(0.0, 1.1 * r), "Chebyshev spacing", Vector::new(0.0, 1.0));
}
