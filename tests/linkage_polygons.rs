//! Velocity and acceleration polygons of a general linkage (figure::linkage_polygon):
//! at every frame of the shaper and of the four-bar written as a linkage, the polygon's
//! points (as drawn, from the pole) close against the solver's point velocities and
//! accelerations, the per-body normal/tangential construction closes with ω and ε from the
//! solver, and the shaper's Coriolis component is 2·ω3 × v_rel; the four-bar-as-linkage's
//! velocity polygon has the points of the four-bar kind's closed form; the image principle:
//! one point constructed per body, the others the vertices of an image similar to the
//! body (a_X − a_R = (−ω² + ε·J)·RX for every point of it).

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

mod common;

use mechdraw::figure::linkage::polygon::polygons;
use mechdraw::figure::shared::polygon::PointPolygon;
use mechdraw::geom::{Vector, perp};
use mechdraw::scene::{self, Scene};
use mechdraw::solve::linkage::{Anchor, Attach, JointKind, Mechanism, Solver, State};

fn linkage(template: &str) -> (Mechanism, Vec<State>) {
    let loaded = scene::load(&common::root().join(template), &[]).unwrap();
    let Scene::Linkage(s) = loaded.scene else { panic!("not a linkage scene") };
    let states = Solver::new(s.mechanism.clone()).unwrap().run(&s.times).unwrap();
    (s.mechanism, states)
}

/// The polygon point named `name`, from the pole (physical units).
fn at(poly: &PointPolygon, name: &str) -> Vector {
    let k = poly.points.iter().position(|p| p.name == name).unwrap_or_else(|| panic!("no point {name}"));
    poly.physical_points()[k + 1]
}

fn anchor(m: &Mechanism, body: &str, point: &str) -> Anchor {
    let i = m.bodies.iter().position(|b| b.name == body).unwrap();
    let local = m.bodies[i].points.iter().find(|(n, _)| n == point).unwrap().1;
    Anchor { body: Attach::Body(i), local }
}

fn close(got: Vector, want: Vector, scale: f64, what: &str) {
    assert!((got - want).norm() <= 1e-12 * scale, "{what}: {got:?} vs {want:?}");
}

#[test]
fn shaper_polygons_close_at_every_frame_with_the_coriolis_component() {
    let (m, states) = linkage("templates/shaper.toml");
    let slide = m.joints.iter().find(|j| j.name == "slide").unwrap().kind.clone();
    let JointKind::Prismatic { point, .. } = slide else { panic!() };
    let rocker = Attach::Body(m.bodies.iter().position(|b| b.name == "rocker").unwrap());
    let mut skipped = 0;
    for st in &states {
        let p = polygons(&m, st);
        let (v, a) = (&p.velocity, &p.acceleration);
        let vs = [("crank", "A"), ("rocker", "B"), ("link", "E")]
            .iter()
            .map(|(b, n)| st.velocity(anchor(&m, b, n)).norm())
            .fold(0.0, f64::max);
        let asc = [("crank", "A"), ("rocker", "B"), ("link", "E")]
            .iter()
            .map(|(b, n)| st.acceleration(anchor(&m, b, n)).norm())
            .fold(0.0, f64::max);
        // Every point's absolute velocity and acceleration.
        for (body, name) in [("crank", "A"), ("rocker", "B"), ("link", "B"), ("link", "E"), ("ram", "E")] {
            let an = anchor(&m, body, name);
            let l = name.to_lowercase();
            close(at(v, &l), st.velocity(an), vs, &format!("v {l} t={}", st.t));
            close(at(a, &format!("{l}′")), st.acceleration(an), asc, &format!("a {l} t={}", st.t));
        }
        // The sliding velocity: a3 → a is v_rel along the guide (rocker O3B).
        let s = st.sliding(&slide).unwrap();
        close(at(v, "a") - at(v, "a3"), s.v_rel, vs, "v_rel");
        let o3b = st.point(anchor(&m, "rocker", "B")) - st.point(anchor(&m, "rocker", "O3"));
        assert!(s.v_rel.perp(&o3b).abs() <= 1e-9 * s.v_rel.norm().max(vs) * o3b.norm());
        // a3 is the rocker's point under A: v = ω3 × O3A (rocker pinned at O3).
        let (_, w3, e3) = st.angular(rocker);
        let o3a = st.point(point) - st.point(anchor(&m, "rocker", "O3"));
        close(at(v, "a3"), perp(o3a) * w3, vs, "v_A3");
        // Coriolis: π→a3' + k (2 ω3 × v_rel) + a_rel = a'.
        let k = at(a, "k") - at(a, "a3′");
        close(k, perp(s.v_rel) * (2.0 * w3), asc, "a_cor");
        assert!((k.norm() - 2.0 * w3.abs() * s.v_rel.norm()).abs() <= 1e-12 * asc);
        close(at(a, "a′") - at(a, "k"), s.a_rel, asc, "a_rel");
        assert!(s.a_rel.perp(&o3b).abs() <= 1e-9 * asc * o3b.norm());
        // The rocker's construction from O3 at the point under the block (the image
        // principle: one point per body, meeting the Coriolis construction there): n then
        // the tangential part ε3 × O3A3 to a3' — left out only when a part vanishes
        // (figure::linkage::polygon::NEGLIGIBLE_REL); b' is then the image's vertex, on
        // π a3' at O3B / O3A3 of it, with no construction of its own.
        assert!(!a.points.iter().any(|p| p.name == "nBO3"), "t={}: B constructed besides A3", st.t);
        close(at(a, "b′"), at(a, "a3′") * (o3b.norm() / o3a.norm()), asc, "b' by the image");
        let vanishes = |x: f64| x <= 1e-9 * asc;
        if !a.points.iter().any(|p| p.name == "nA3O3") {
            assert!(vanishes(w3 * w3 * o3a.norm()) || vanishes(e3.abs() * o3a.norm()), "t={}: no nA3O3", st.t);
            skipped += 1;
            continue;
        }
        close(at(a, "nA3O3"), -o3a * (w3 * w3), asc, "a_A3O3^n");
        close(at(a, "a3′") - at(a, "nA3O3"), perp(o3a) * e3, asc, "a_A3O3^t");
        // The link BE: from b', normal −ω4²·BE then ε4 × BE to e'.
        let link = Attach::Body(m.bodies.iter().position(|b| b.name == "link").unwrap());
        let (_, w4, e4) = st.angular(link);
        let be = st.point(anchor(&m, "link", "E")) - st.point(anchor(&m, "link", "B"));
        close(at(a, "nEB") - at(a, "b′"), -be * (w4 * w4), asc, "a_EB^n");
        close(at(a, "e′") - at(a, "nEB"), perp(be) * e4, asc, "a_EB^t");
    }
    assert!(skipped <= 2, "{skipped} of {} frames without the rocker's construction", states.len());
}

#[test]
fn fourbar_as_linkage_has_the_fourbar_polygon_points() {
    let (m, states) = linkage("templates/fourbar-linkage.toml");
    let w1 = 20.0;
    let mut skipped = 0;
    for st in &states {
        let p = polygons(&m, st);
        let v = &p.velocity;
        let names: Vec<&str> = v.points.iter().map(|p| p.name.as_str()).collect();
        assert_eq!(names, ["a", "b", "m"], "the four-bar's points, o1 and c at the pole");
        // Closed form (the four-bar kind's loop equations): v_A = ω1 × O1A, and B from
        // v_B = v_A + ω2 × AB = ω3 × CB; M on AB extended: v_M = v_A + ω2 × AM.
        let phi1 = w1 * st.t;
        let a = Vector::new(0.04 * phi1.cos(), 0.04 * phi1.sin());
        let va = perp(a) * w1;
        let b = st.point(anchor(&m, "coupler", "B")).coords;
        let c = Vector::new(0.08, 0.0);
        let (ab, cb) = (b - a, b - c);
        // va + w2 perp(ab) = w3 perp(cb): two scalar equations.
        let (pa, pc) = (perp(ab), perp(cb));
        let det = -pa.x * pc.y + pa.y * pc.x;
        let w2 = (va.x * pc.y - va.y * pc.x) / det;
        let vb = va + pa * w2;
        let vm = va + perp(ab * 2.0) * w2;
        let scale = va.norm().max(vb.norm()).max(vm.norm());
        // The solver's Newton tolerance against the closed form: 1e-9 relative.
        close(at(v, "a"), va, scale * 1e3, "v_A");
        close(at(v, "b"), vb, scale * 1e3, "v_B");
        close(at(v, "m"), vm, scale * 1e3, "v_M");
        // The coupler's construction from A (its first point): nBA = a' − ω2²·AB.
        let acc = &p.acceleration;
        let (_, w2s, e2) = st.angular(Attach::Body(1));
        if !acc.points.iter().any(|p| p.name == "nBA") {
            // Left out only when a part vanishes (figure::linkage_polygon::NEGLIGIBLE_REL).
            let largest = acc.points.iter().filter(|p| p.from == 0).map(|p| p.v.norm()).fold(0.0, f64::max);
            let l = ab.norm();
            assert!(w2s * w2s * l <= 1e-9 * largest || e2.abs() * l <= 1e-9 * largest, "t={}: no nBA", st.t);
            skipped += 1;
            continue;
        }
        close(at(acc, "nBA") - at(acc, "a′"), -ab * (w2s * w2s), at(acc, "a′").norm(), "a_BA^n");
    }
    assert!(skipped <= 2, "{skipped} of {} frames without the coupler's construction", states.len());
}

#[test]
fn one_point_is_constructed_per_body_and_the_others_follow_by_the_image() {
    let (m, states) = linkage("templates/fourbar-linkage.toml");
    let coupler = m.bodies.iter().position(|b| b.name == "coupler").unwrap();
    for st in states.iter().step_by(7) {
        let p = polygons(&m, st);
        let a = &p.acceleration;
        let names: Vec<&str> = a.points.iter().map(|p| p.name.as_str()).collect();
        // B from A on the coupler (nBA) and from C on the rocker (nBC): the two tangential
        // directions meet at b'; M is the image's third vertex, not constructed.
        assert!(names.contains(&"nBA") && names.contains(&"nBC"), "{names:?}");
        assert!(!names.iter().any(|n| n.starts_with("nM")), "{names:?}");
        // The image a'b'm' is similar to ABM: the same complex factor −ω² + ε·J for both sides.
        let (_, w, e) = st.angular(Attach::Body(coupler));
        let pt = |n: &str| st.point(anchor(&m, "coupler", n));
        let (ab, am) = (pt("B") - pt("A"), pt("M") - pt("A"));
        let scale = at(a, "a′").norm().max(at(a, "m′").norm());
        close(at(a, "b′") - at(a, "a′"), -ab * (w * w) + perp(ab) * e, scale, "a'b'");
        close(at(a, "m′") - at(a, "a′"), -am * (w * w) + perp(am) * e, scale, "a'm'");
        // The velocity polygon shows the directions that locate b: ⊥AB through a, ⊥CB through p.
        let v = &p.velocity;
        let dirs: Vec<(usize, usize)> = v.directions.iter().map(|d| (d.through, d.reaches)).collect();
        let idx = |n: &str| v.points.iter().position(|p| p.name == n).unwrap() + 1;
        assert!(dirs.contains(&(idx("a"), idx("b"))) && dirs.contains(&(0, idx("b"))), "{dirs:?}");
    }
}
