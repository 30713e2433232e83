//! Force figures of the four-bar (seed 003, Figs. 4 and 5 and its last section): the
//! force polygon of the RRR dyad, the crank's polygon with R_O, and the reactions R_A and
//! R_B drawn at A and B on the mechanism, all at the force scale k_f.
//!
//! The dyad's polygon is the seed's chain, from the pole f: R_A^n, G21, F_i21, G22, F_i22,
//! F, G3, F_i3, R_C^n, then R_C^t (along BC) and R_A^t (along AB), which close it at the
//! intersection point `int` (seed eq. 5). In it, R_A runs from `int` to the end of R_A^n,
//! R_C from the end of F_i3 to `int`, and R_B (seed eq. 7) from the end of F to `int`.
//! The crank's polygon (Fig. 5) starts at the end of R_A^n: −R_A (to `int`), F_i1, G1, and
//! R_O back to the start. Each vector is an arrow with its name beside its middle,
//! preferably on the outside of the polygon, placed clear of the other names by
//! [`super::labels`].

use crate::draw::{Aci, Drawing, Entity, Shape};
use crate::geom::{Point, Vector, perp};
use crate::solve::fourbar::Forces;
use crate::solve::fourbar::Position;

use super::fourbar::{Scale, Sizes, layer_of, layers, vector};
use super::labels;

/// Colour of the resultant reactions R_A, R_B, R_C inside the dyad's polygon.
const RESULTANT: Aci = Aci::RED;
/// Colour of the crank's polygon (F_i1, G1, R_O).
const CRANK: Aci = Aci::ORANGE;

/// A vector shorter than this many letter heights gets no name: at the run's force scale
/// the small weights crowd together, and their names would print over each other.
const MIN_LABELLED: f64 = 0.6;

/// Height of a vector's name in the force polygons, in letter heights.
const NAME_HEIGHT: f64 = 0.8;

/// The dyad's chain as (name, vector), in the seed's order (eq. 5).
pub fn dyad_chain(f: &Forces) -> [(&'static str, Vector); 11] {
    [
        ("RAn", f.r_a_n),
        ("G21", f.g21),
        ("Fi21", f.fi21),
        ("G22", f.g22),
        ("Fi22", f.fi22),
        ("F", f.f_ext),
        ("G3", f.g3),
        ("Fi3", f.fi3),
        ("RCn", f.r_c_n),
        ("RCt", f.r_c_t),
        ("RAt", f.r_a_t),
    ]
}

/// Vertices of the dyad's chain relative to the pole f (physical units, 12 points: the
/// pole, the end of each vector; the last returns to the pole when the polygon closes).
fn chain_vertices(f: &Forces) -> Vec<Vector> {
    let mut pts = Vec::with_capacity(12);
    let mut p = Vector::zeros();
    pts.push(p);
    for (_, v) in dyad_chain(f) {
        p += v;
        pts.push(p);
    }
    pts
}

/// Every point the force polygons reach, relative to the pole (physical units): the chain
/// and the crank's polygon. Used to size the force panel over the whole motion.
pub fn polygon_points(f: &Forces) -> Vec<Vector> {
    let mut pts = chain_vertices(f);
    let int = pts[10];
    pts.push(int + f.fi1);
    pts.push(int + f.fi1 + f.g1);
    pts
}

/// The dyad's force polygon and the crank's polygon with the pole at `pole`. The names are
/// placed by [`labels::Polygon`]: beside their vectors, apart from each other.
pub fn polygons(d: &mut Drawing, f: &Forces, scale: Scale, pole: Point, s: Sizes) {
    let l = layer_of(d, layers::FORCES);
    let mut names = labels::Polygon::of_names();
    let pts: Vec<Point> = chain_vertices(f).into_iter().map(|v| pole + scale.draw(v)).collect();
    let centroid = Point::from(pts.iter().map(|p| p.coords).sum::<Vector>() / pts.len() as f64);
    d.add(l, Shape::Circle { center: pole, radius: 0.25 * s.joint });
    names.letter(pole, "f", s.text, pole - centroid, None);
    for (i, (name, _)) in dyad_chain(f).iter().enumerate() {
        arrow_named(d, &mut names, l, None, (pts[i], pts[i + 1]), name, 0.5, centroid, s);
    }
    let int = pts[10];
    let p_ran = pts[1];
    let p_f = pts[6];
    let p_fi3 = pts[8];
    // Resultants: R_A = int → end of R_A^n; R_B = end of F → int; R_C = end of F_i3 → int.
    // R_B and R_C are often nearly the same segment (a light rocker): their names start
    // from different places along it.
    arrow_named(d, &mut names, l, Some(RESULTANT), (int, p_ran), "RA", 0.5, centroid, s);
    arrow_named(d, &mut names, l, Some(RESULTANT), (p_f, int), "RB", 0.7, centroid, s);
    arrow_named(d, &mut names, l, Some(RESULTANT), (p_fi3, int), "RC", 0.3, centroid, s);
    // The crank (seed Fig. 5): from int, F_i1 then G1; R_O closes back to the end of R_A^n.
    let p_fi1 = int + scale.draw(f.fi1);
    let p_g1 = p_fi1 + scale.draw(f.g1);
    let crank_centroid = Point::from((p_ran.coords + int.coords + p_fi1.coords + p_g1.coords) / 4.0);
    arrow_named(d, &mut names, l, Some(CRANK), (int, p_fi1), "Fi1", 0.5, crank_centroid, s);
    arrow_named(d, &mut names, l, Some(CRANK), (p_fi1, p_g1), "G1", 0.5, crank_centroid, s);
    arrow_named(d, &mut names, l, Some(CRANK), (p_g1, p_ran), "RO", 0.5, crank_centroid, s);
    names.draw(d, l);
}

/// An arrow from `from` to `to`, and its `name` for `names` at the fraction `at` of its
/// length, preferably on the side away from `inside`; nothing for a vector too short to see,
/// no name for one shorter than [`MIN_LABELLED`].
#[allow(clippy::too_many_arguments)]
fn arrow_named(
    d: &mut Drawing,
    names: &mut labels::Polygon,
    layer: usize,
    color: Option<Aci>,
    (from, to): (Point, Point),
    name: &str,
    at: f64,
    inside: Point,
    s: Sizes,
) {
    let v = to - from;
    let len = v.norm();
    if len.is_nan() || len <= 0.01 * s.head {
        return;
    }
    d.push(Entity { layer, color, linetype: None, shape: Shape::Arrow { from, to, head: s.head } });
    names.segment(from, to);
    if len < MIN_LABELLED * s.text {
        return;
    }
    let mid = from + v * at;
    let mut n = perp(v / len);
    if n.dot(&(mid - inside)) < 0.0 {
        n = -n;
    }
    names.letter(mid, name, NAME_HEIGHT * s.text, n, color);
}

/// R_A at A and R_B at B on the mechanism, at the force scale (seed, last section): the
/// arrows turn with the reactions as the crank turns.
pub fn reactions_on_mechanism(d: &mut Drawing, pos: &Position, f: &Forces, scale: Scale, s: Sizes) {
    let l = layer_of(d, layers::FORCES);
    vector(d, l, pos.a, scale.draw(f.r_a), "RA", s);
    vector(d, l, pos.b, scale.draw(f.r_b), "RB", s);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figure::fourbar::tests::{chebyshev, closed_form};
    use crate::figure::fourbar::{Layout, ModelUnits, Show};
    use crate::geom::cross;

    /// Forces for the figure tests, by the seed's route written out here (not the library's
    /// solver): inertia of the bars, moments about B for the normal components, the
    /// intersection of the two bar directions for the tangential ones.
    pub(crate) fn seed_route(pos: &Position, g: &crate::solve::fourbar::Geometry) -> Forces {
        let k = pos.kin.unwrap();
        let (m1, m21, m22, m3, gr) = (0.05, 0.125, 0.125, 0.125, 9.8);
        let w = |m: f64| Vector::new(0.0, -m * gr);
        let f_ext =
            if (80.0..=280.0).contains(&pos.phi1.to_degrees()) { Vector::new(0.0, -50.0) } else { Vector::zeros() };
        let (fi21, fi22, fi3, fi1) = (-k.a_g21 * m21, -k.a_g22 * m22, -k.a_g3 * m3, -k.a_g1 * m1);
        let (mi21, mi22, mi3) = (
            -m21 * g.l_ab * g.l_ab / 12.0 * k.eps2,
            -m22 * g.l_bm * g.l_bm / 12.0 * k.eps2,
            -m3 * g.l_bc * g.l_bc / 12.0 * k.eps3,
        );
        let (c21, c22, c3) = (
            Point::from((pos.a.coords + pos.b.coords) / 2.0),
            Point::from((pos.b.coords + pos.m.coords) / 2.0),
            Point::from((pos.b.coords + g.c.coords) / 2.0),
        );
        // Moments about B of link 2 (without R_B): R_A^n ⊥ AB.
        let u2 = (pos.b - pos.a) / g.l_ab;
        let n2 = perp(u2);
        let mom2 = cross(c21 - pos.b, w(m21) + fi21)
            + cross(c22 - pos.b, w(m22) + fi22)
            + cross(pos.m - pos.b, f_ext)
            + mi21
            + mi22;
        // cross(A − B, s·n2) + mom2 = 0
        let s2 = -mom2 / cross(pos.a - pos.b, n2);
        let r_a_n = n2 * s2;
        let u3 = (pos.b - g.c) / g.l_bc;
        let n3 = perp(u3);
        let mom3 = cross(c3 - pos.b, w(m3) + fi3) + mi3;
        let s3 = -mom3 / cross(g.c - pos.b, n3);
        let r_c_n = n3 * s3;
        let rest = r_a_n + w(m21) + fi21 + w(m22) + fi22 + f_ext + w(m3) + fi3 + r_c_n;
        // rest + t3·u3 + t2·u2 = 0
        let det = cross(u3, u2);
        let t3 = cross(-rest, u2) / det;
        let t2 = cross(u3, -rest) / det;
        let (r_c_t, r_a_t) = (u3 * t3, u2 * t2);
        let r_a = r_a_n + r_a_t;
        let r_b = -(r_a + w(m21) + fi21 + w(m22) + fi22 + f_ext);
        let r_o = r_a - fi1 - w(m1);
        Forces {
            g21: w(m21),
            g22: w(m22),
            g3: w(m3),
            g1: w(m1),
            fi21,
            fi22,
            fi3,
            fi1,
            mi21,
            mi22,
            mi3,
            mi1: 0.0,
            f_ext,
            r_a_n,
            r_a_t,
            r_c_n,
            r_c_t,
            r_a,
            r_b,
            r_c: r_c_n + r_c_t,
            r_o,
            me1: 0.0,
        }
    }

    #[test]
    fn the_chain_closes_and_the_resultants_are_the_reactions() {
        let g = chebyshev();
        for deg in [0.0f64, 90.0, 180.0, 271.0] {
            let pos = closed_form(&g, deg.to_radians(), 20.0);
            let f = seed_route(&pos, &g);
            let v = chain_vertices(&f);
            let scale = f.r_a.norm().max(1.0);
            assert!(v[11].norm() < 1e-12 * scale, "chain does not close at {deg}°");
            // R_A drawn from int to the end of R_A^n; R_B from the end of F to int.
            assert!(((v[1] - v[10]) - f.r_a).norm() < 1e-12 * scale);
            assert!(((v[10] - v[6]) - f.r_b).norm() < 1e-12 * scale);
            assert!(((v[10] - v[8]) - f.r_c).norm() < 1e-12 * scale);
        }
    }

    #[test]
    fn preview_force_frames_for_people() {
        let g = chebyshev();
        let pos: Vec<Position> = (0..360).map(|i| closed_form(&g, (i as f64).to_radians(), 20.0)).collect();
        let forces: Vec<Forces> = pos.iter().map(|p| seed_route(p, &g)).collect();
        let show = Show { velocity: true, acceleration: true, forces: true };
        let lay = Layout::new(&g, &pos, Some(&forces), show, ModelUnits::SI);
        let base = lay.base(&g, &[pos.iter().map(|p| p.m).collect()]);
        let opts = crate::draw::svg::SvgOptions { window: Some(lay.window), ..Default::default() };
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target");
        for n in [0usize, 90, 180] {
            let f = lay.frame(&base, &lay.moving(&g, &pos[n], Some(&forces[n])));
            let svg = crate::draw::svg::to_string(&f, &opts);
            let png = crate::draw::raster::to_png(&svg, 1400).unwrap();
            std::fs::write(dir.join(format!("forces-preview-{n}.png")), png).unwrap();
        }
    }
}
