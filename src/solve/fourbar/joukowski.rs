//! Joukowski's lever: the balancing moment Me1 from the velocity polygon alone, as a
//! graphical check of the reactions route ([`super::forces`]).
//!
//! The velocity polygon is turned 90° clockwise about its pole p: each point's image is
//! `rot(v) = (v_y, −v_x)`, v its velocity. Every load is applied at the image of its point
//! of application, with its own direction: the weights G and inertia forces F_i at the
//! images of the centroids (c1, c21, c22, c3: the midpoints of pa, ab, bm, p c = p b/2,
//! the velocity field of a rigid link being affine), the external forces at the images of
//! their points (a, b, m). An inertia moment M_i of a link is replaced by a couple of two
//! forces ±M_i/l² · perp(link) at its two joints (for the coupler at A and B, for the rocker
//! at B and C, for the crank at A and O1), as the textbooks do.
//!
//! The moment of a force F applied at `rot(v)` about the pole is
//! `rot(v) × F = v_y·F_y + v_x·F_x = F · v`: the power of F. The lever's moments about the
//! pole sum to the power of all the loads, inertia forces included, and d'Alembert's
//! principle (ideal joints: the reactions do no work) gives
//!
//! ```text
//! Me1·ω1 + Σ M_p(F_i) = 0   ⇒   Me1_J = −Σ M_p(F_i) / ω1
//! ```
//!
//! with Me1 counter-clockwise positive (design.md §4), ω1 in rad/s and the arms in the
//! velocity unit (m/s in an SI scene: M_p in W = N·m/s, Me1_J in N·m; mm/s in a mm scene:
//! N·mm).
//!
//! A standing crank (ω1 = 0, a static analysis, with ε1 or without) has no velocity
//! polygon: every image is the pole and the quotient is 0/0. The lever is then drawn with
//! virtual velocities, the polygon of the crank turning at 1 rad/s in the same position
//! (every velocity is ω1 times its value there, so the images are the real ones scaled by
//! 1/ω1 wherever ω1 ≠ 0), and the loads of the real state (ε1's inertia forces, the
//! weights, the external loads); the principle of virtual work gives
//! `Me1 = −Σ F_i·v_i*` (per rad/s of the virtual crank speed): the statics' Me1 without
//! dividing by zero. Me1 is equivalently a balancing force F_b = Me1/l1² · perp(A − O1) at A (its
//! moment about O1 is Me1); on the lever at a it closes the sum: Σ M_p + M_p(F_b) = 0.

use super::Geometry;
use super::kinematics::{Kinematics, Position};
use super::kinetostatics::{Dynamics, ForcePoint, Link, loads};
use crate::geom::{self, Vector, cross, perp};

/// The velocity polygon's turn: 90° clockwise, `(x, y) → (y, −x)`.
pub fn rotate(v: Vector) -> Vector {
    Vector::new(v.y, -v.x)
}

/// One load on the lever.
#[derive(Debug, Clone, PartialEq)]
pub struct LeverForce {
    /// Its name (`G21`, `Fi3`, `F`, `FM2`, …).
    pub name: String,
    /// Name of the image point it is applied at (`a`, `c21`, …; `p` for a point at rest).
    pub at: &'static str,
    /// The image point, relative to the pole: the turned velocity of the point of
    /// application (velocity units).
    pub image: Vector,
    /// The force, N, its own direction.
    pub force: Vector,
    /// Its moment about the pole, `image × force` = its power: N·(length unit)/s.
    pub moment: f64,
}

/// Joukowski's lever at one position.
#[derive(Debug, Clone, PartialEq)]
pub struct Lever {
    /// The image points of the turned polygon relative to the pole p: `p`, `a`, `b`, `m`
    /// and the centroids' images `c1`, `c21`, `c22`, `c3` (velocity units).
    pub points: Vec<(&'static str, Vector)>,
    /// The loads in order: weights, inertia forces, external forces, the couples of the
    /// inertia moments.
    pub forces: Vec<LeverForce>,
    /// Σ M_p(F_i), N·(length unit)/s.
    pub moment: f64,
    /// Me1_J = −Σ M_p / ω, N·(length unit), counter-clockwise positive, ω the
    /// [`Lever::crank_speed`]; `None` when ω1 is not finite.
    pub me1: Option<f64>,
    /// The crank speed the polygon is drawn for, rad/s: ω1, or 1 for a standing crank
    /// (ω1 = 0: virtual velocities, see the module's docs).
    pub crank_speed: f64,
    /// The balancing force at A equivalent to Me1_J (perpendicular to O1A), N.
    pub balancing: Option<LeverForce>,
}

/// Joukowski's lever at `pos` for the crank turning at `omega1` (rad/s): the loads of
/// [`loads`] (with `dynamics`), applied at the images of their points.
pub fn lever(geom: &Geometry, pos: &Position, kin: &Kinematics, dynamics: &Dynamics, omega1: f64) -> Lever {
    let l = loads(geom, pos, kin, dynamics);
    // A standing crank: the virtual velocities of the crank turning at 1 rad/s (the loads
    // stay the real state's). The position is assembled and not singular (`kin` exists),
    // so its kinematics at any crank speed exist too.
    let virtual_kin = (omega1 == 0.0).then(|| super::kinematics::kinematics(geom, pos, 1.0).ok()).flatten();
    let (kin, crank_speed) = match &virtual_kin {
        Some(k) => (k, 1.0),
        None => (kin, omega1),
    };
    let (v_a, v_b, v_m) = (kin.v_a, kin.v_b, kin.v_m);
    // Centroids: midpoints of O1A, AB, BM, CB (O1 and C at rest), plus ω × offset for a
    // centroid the scene puts off the middle (the offset term only then: bit-identical
    // images for homogeneous bars).
    let off = |v_mid: Vector, mid: crate::geom::Point, g: crate::geom::Point, w: f64| {
        if g == mid { v_mid } else { v_mid + perp(g - mid) * w }
    };
    let (w1, w2, w3) = (kin.omega1, kin.omega2, kin.omega3);
    let v_c1 = off(v_a * 0.5, geom.o1 + (pos.a - geom.o1) * 0.5, l.g1_at, w1);
    let v_c21 = off((v_a + v_b) * 0.5, pos.a + (pos.b - pos.a) * 0.5, l.g21_at, w2);
    let v_c22 = off((v_b + v_m) * 0.5, pos.b + (pos.m - pos.b) * 0.5, l.g22_at, w2);
    let v_c3 = off(v_b * 0.5, geom.c + (pos.b - geom.c) * 0.5, l.g3_at, w3);
    let points = vec![
        ("p", Vector::zeros()),
        ("a", rotate(v_a)),
        ("b", rotate(v_b)),
        ("m", rotate(v_m)),
        ("c1", rotate(v_c1)),
        ("c21", rotate(v_c21)),
        ("c22", rotate(v_c22)),
        ("c3", rotate(v_c3)),
    ];
    let mut forces = Vec::new();
    let mut push = |name: String, at: &'static str, v: Vector, force: Vector| {
        let image = rotate(v);
        forces.push(LeverForce { name, at, image, force, moment: cross(image, force) });
    };
    for (name, at, v, f) in [
        ("G1", "c1", v_c1, l.w1),
        ("G21", "c21", v_c21, l.w21),
        ("G22", "c22", v_c22, l.w22),
        ("G3", "c3", v_c3, l.w3),
        ("Fi1", "c1", v_c1, l.fi1),
        ("Fi21", "c21", v_c21, l.fi21),
        ("Fi22", "c22", v_c22, l.fi22),
        ("Fi3", "c3", v_c3, l.fi3),
    ] {
        if f != Vector::zeros() {
            push(name.to_string(), at, v, f);
        }
    }
    let phi1_deg = geom::deg(pos.phi1);
    let acting: Vec<_> = dynamics.forces.iter().filter(|f| f.range.is_none_or(|r| r.contains_deg(phi1_deg))).collect();
    for (k, f) in acting.iter().enumerate() {
        let name = if acting.len() == 1 { "F".to_string() } else { format!("F{}", k + 1) };
        let (at, v) = match f.at {
            ForcePoint::A => ("a", v_a),
            ForcePoint::B => ("b", v_b),
            ForcePoint::M => ("m", v_m),
        };
        push(name, at, v, f.value);
    }
    // Loads at any point of any link, at the images of their points; a torque T on a link
    // as the couple of the inertia moments below (its power is T·ω).
    let mut torques = [0.0; 4];
    let acting = dynamics.loads.iter().filter(|f| f.range.is_none_or(|r| r.contains_deg(phi1_deg)));
    for (k, f) in acting.enumerate() {
        let (p, _) = f.link.ends(geom, pos);
        let at = p + f.link.to_world(geom, pos, f.at);
        let (w, _) = f.link.motion(kin);
        let v_p = match f.link {
            Link::Crank | Link::Rocker => Vector::zeros(),
            Link::Ab | Link::Bm => v_a,
        };
        let base = if f.link == Link::Bm { pos.a } else { p };
        if f.force != Vector::zeros() {
            push(format!("L{}", k + 1), "load", v_p + perp(at - base) * w, f.force);
        }
        torques[f.link.index()] += f.torque / dynamics.length_unit_m;
    }
    // Inertia moments as couples at the links' joints: +F at the second joint, −F at the
    // first, F = M/|r|²·perp(r), r from the first joint to the second: moment r × F = M.
    let couple = |m: f64, r: Vector| perp(r) * (m / r.norm_squared());
    let m2 = l.mi21 + l.mi22 + torques[Link::Ab.index()] + torques[Link::Bm.index()];
    if m2 != 0.0 {
        let f = couple(m2, pos.b - pos.a);
        push("FM2".into(), "b", v_b, f);
        push("FM2'".into(), "a", v_a, -f);
    }
    let m3 = l.mi3 + torques[Link::Rocker.index()];
    if m3 != 0.0 {
        let f = couple(m3, pos.b - geom.c);
        push("FM3".into(), "b", v_b, f);
        push("FM3'".into(), "p", Vector::zeros(), -f);
    }
    let m1 = l.mi1 + torques[Link::Crank.index()];
    if m1 != 0.0 {
        let f = couple(m1, pos.a - geom.o1);
        push("FM1".into(), "a", v_a, f);
        push("FM1'".into(), "p", Vector::zeros(), -f);
    }
    // Summed in a fixed order: the same lever gives the same number.
    let moment: f64 = forces.iter().map(|f| f.moment).sum();
    let me1 = (crank_speed != 0.0 && crank_speed.is_finite()).then(|| -moment / crank_speed);
    let balancing = me1.map(|me1| {
        let r1 = pos.a - geom.o1;
        let force = perp(r1) * (me1 / r1.norm_squared());
        let image = rotate(v_a);
        LeverForce { name: "Fb".into(), at: "a", image, force, moment: cross(image, force) }
    });
    Lever { points, forces, moment, me1, crank_speed, balancing }
}

/// The image point named `name` of `lever` (relative to the pole), if it has one.
pub fn image_point(lever: &Lever, name: &str) -> Option<Vector> {
    lever.points.iter().find(|(n, _)| *n == name).map(|(_, v)| *v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Side;
    use crate::solve::fourbar::{CrankRange, ExternalForce, forces, kinematics, position};

    fn template() -> (Geometry, Dynamics) {
        let g = super::super::test_template();
        let d = Dynamics {
            length_unit_m: 1.0,
            gravity: Vector::new(0.0, -9.8),
            m1: 0.05,
            m21: 0.125,
            m22: 0.125,
            m3: 0.125,
            forces: vec![ExternalForce {
                at: ForcePoint::M,
                value: Vector::new(0.0, -50.0),
                range: Some(CrankRange { from_deg: 80.0, to_deg: 280.0 }),
            }],
            links: Default::default(),
            loads: Vec::new(),
        };
        (g, d)
    }

    #[test]
    fn a_moment_about_the_pole_is_the_power_of_the_force() {
        let v = Vector::new(0.3, -1.7);
        let f = Vector::new(-2.0, 5.0);
        assert!((cross(rotate(v), f) - f.dot(&v)).abs() < 1e-15);
        // Clockwise: +x turns to −y.
        assert_eq!(rotate(Vector::new(1.0, 0.0)), Vector::new(0.0, -1.0));
    }

    #[test]
    fn the_lever_gives_the_reactions_routes_me1_and_the_balancing_force_closes_it() {
        let (g, d) = template();
        let mut worst = 0.0f64;
        let mut largest = 0.0f64;
        for k in 0..360 {
            let p = position(&g, f64::from(k).to_radians(), Side::Left).unwrap();
            let kin = kinematics(&g, &p, 20.0).unwrap();
            let me1 = forces(&g, &p, &kin, &d).unwrap().me1;
            let lever = lever(&g, &p, &kin, &d, 20.0);
            worst = worst.max((lever.me1.unwrap() - me1).abs());
            largest = largest.max(me1.abs());
            let b = lever.balancing.as_ref().unwrap();
            assert!((lever.moment + b.moment).abs() <= 1e-12 * lever.moment.abs().max(1.0), "{k}°");
            // F_b's moment about O1 is Me1.
            assert!((cross(p.a - g.o1, b.force) - lever.me1.unwrap()).abs() < 1e-12, "{k}°");
        }
        assert!(worst <= 1e-9 * largest, "worst {worst} of {largest}");
    }

    /// Issue 28 item 3: at ω1 = 0 the lever gave Me1 = −0/0 = NaN. With virtual velocities
    /// it gives the statics' Me1 (the reactions route, which divides by nothing), with and
    /// without a crank's angular acceleration, at every position.
    #[test]
    fn a_standing_crank_gives_the_statics_me1_by_virtual_velocities() {
        use crate::solve::fourbar::kinematics_eps;
        let (g, d) = template();
        for eps1 in [0.0, 150.0] {
            let mut largest = 0.0f64;
            let mut worst = 0.0f64;
            for k in 0..360 {
                let p = position(&g, f64::from(k).to_radians(), Side::Left).unwrap();
                let kin = kinematics_eps(&g, &p, 0.0, eps1).unwrap();
                let me1 = forces(&g, &p, &kin, &d).unwrap().me1;
                let lever = lever(&g, &p, &kin, &d, 0.0);
                assert_eq!(lever.crank_speed, 1.0);
                let j = lever.me1.unwrap();
                assert!(j.is_finite(), "{k}°");
                worst = worst.max((j - me1).abs());
                largest = largest.max(me1.abs());
                // The balancing force still closes the lever.
                let b = lever.balancing.as_ref().unwrap();
                assert!((lever.moment + b.moment).abs() <= 1e-12 * lever.moment.abs().max(1.0), "{k}°");
            }
            assert!(largest > 0.1, "the loads act: Me1 up to {largest} N·m");
            assert!(worst <= 1e-9 * largest, "ε1 = {eps1}: worst {worst} of {largest}");
        }
    }
}
