//! templates/triad-driven.toml: the seed-000 triad whose pivot O1 rides on a crank (a
//! class-III mechanism). Where O1 is at (15, 30) — at t = 0 and again after a full crank
//! turn at t = 1 s — the configuration must be the seed's: the six triad equations hold
//! and phi1 = 75.77° (the seed's assembly mode, kept along the whole turn).

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

mod common;

use mechdraw::geom::Point;
use mechdraw::scene::{self, Scene};
use mechdraw::solve::linkage::{Attach, Solver};

#[test]
fn triad_on_a_crank_passes_through_the_seed_configuration() {
    let loaded = scene::load(&common::root().join("templates/triad-driven.toml"), &[]).unwrap();
    let Scene::Linkage(s) = loaded.scene else { panic!("not a linkage scene") };
    let states = Solver::new(s.mechanism.clone()).unwrap().run(&s.times).unwrap();
    let (o1, a1, a2, a3) = (
        s.anchor("crank.O1").unwrap(),
        s.anchor("triangle.A1").unwrap(),
        s.anchor("triangle.A2").unwrap(),
        s.anchor("triangle.A3").unwrap(),
    );
    let (o2, o3) = (Point::new(90.0, 20.0), Point::new(150.0, 40.0));
    let link1 = Attach::Body(1);
    for st in [&states[0], &states[states.len() - 1]] {
        let p_o1 = st.point(o1);
        assert!((p_o1 - Point::new(15.0, 30.0)).norm() <= 1e-9, "t = {}: O1 = {p_o1:?}", st.t);
        let (p1, p2, p3) = (st.point(a1), st.point(a2), st.point(a3));
        // The six equations of the triad (seed 000): A_i on its circle, the triangle's sides.
        let eqs = [
            ((p1 - p_o1).norm(), 50.0),
            ((p2 - o2).norm(), 60.0),
            ((p3 - o3).norm(), 84.0),
            ((p2 - p1).norm(), 50.0),
            ((p3 - p2).norm(), 50.0),
            ((p3 - p1).norm(), 92.0),
        ];
        for (k, (got, want)) in eqs.iter().enumerate() {
            assert!((got - want).abs() <= 1e-10, "t = {}: equation {k}: {got} vs {want}", st.t);
        }
        let phi1 = mechdraw::geom::normalize_angle(st.angular(link1).0).to_degrees();
        // The seed reports phi1 = 75.77° (secant iteration to 1e-5); to 0.005°.
        assert!((phi1 - 75.77).abs() <= 0.005, "t = {}: phi1 = {phi1}", st.t);
        // The angle of O1A1 agrees with the link's body angle.
        let dir = (p1 - p_o1).y.atan2((p1 - p_o1).x).to_degrees();
        assert!((dir - phi1).abs() < 1e-9);
        eprintln!("t = {}: phi1 = {phi1:.6}°, A1 = {p1:?}, A2 = {p2:?}, A3 = {p3:?}", st.t);
    }
    // In between, O1 really moved: the crank turns once.
    let mid = &states[states.len() / 2];
    assert!((mid.point(o1) - Point::new(15.0, 20.0)).norm() <= 1e-9);
    assert!(states.iter().all(|st| st.residual <= 1e-12));
}
