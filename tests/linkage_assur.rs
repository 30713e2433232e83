//! The Assur-group route (solve::linkage::assur) against the general Newton route: on
//! every linkage template, on random linkages built from known poses with every dyad
//! kind, through a whole crank turn in both assembly modes, and on a scene that does not
//! decompose; its decomposition named; an unassemblable position reported by group, joint
//! and time.

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

mod common;

use mechdraw::geom::{Point, Vector, rotate};
use mechdraw::scene::{self, Scene};
use mechdraw::solve::expr::Expr;
use mechdraw::solve::linkage::{
    Anchor, AssurSolver, Attach, Body, Driver, DriverTarget, GroupKind, Joint, JointKind, LinkageError, Mechanism,
    Motion, NearSingular, Route, Solver, State,
};

fn linkage(name: &str) -> mechdraw::scene::linkage::LinkageScene {
    let path = common::root().join("templates").join(format!("{name}.toml"));
    let loaded = scene::load(&path, &[]).unwrap();
    let Scene::Linkage(s) = loaded.scene else { panic!("{name} is not a linkage scene") };
    s
}

/// The largest |value| of the x/y coordinates and of the angles over the motion, for
/// relative comparisons (floors: the mechanism's size, 1 rad).
fn scales(states: &[State], pick: impl Fn(&State) -> &[f64], floor: (f64, f64)) -> (f64, f64) {
    let (mut len, mut ang) = floor;
    for s in states {
        for (k, v) in pick(s).iter().enumerate() {
            if k % 3 == 2 {
                ang = ang.max(v.abs());
            } else {
                len = len.max(v.abs());
            }
        }
    }
    (len, ang)
}

/// Positions, velocities and accelerations of the two routes agree to `rel` of each
/// quantity's largest value over the motion, at every sample; returns the largest
/// relative difference.
fn assert_routes_agree(what: &str, a: &[State], b: &[State], length: f64, rel: f64) -> f64 {
    assert_routes_agree_as(what, a, b, length, rel, false)
}

/// [`assert_routes_agree`], body angles compared modulo whole turns when `whole_turns`.
fn assert_routes_agree_as(what: &str, a: &[State], b: &[State], length: f64, rel: f64, whole_turns: bool) -> f64 {
    assert_eq!(a.len(), b.len(), "{what}: sample counts");
    let mut worst: f64 = 0.0;
    for (label, pick) in [
        ("q", (|s: &State| s.q.as_slice()) as fn(&State) -> &[f64]),
        ("q̇", |s: &State| s.qd.as_slice()),
        ("q̈", |s: &State| s.qdd.as_slice()),
    ] {
        let (sl, sa) = scales(b, pick, if label == "q" { (length, 1.0) } else { (1e-300, 1e-300) });
        for (x, y) in a.iter().zip(b) {
            assert_eq!(x.t, y.t);
            for (k, (u, v)) in pick(x).iter().zip(pick(y)).enumerate() {
                let scale = if k % 3 == 2 { sa } else { sl };
                let mut d = (u - v).abs();
                if label == "q" && k % 3 == 2 && whole_turns {
                    // The same pose: Newton may land a body's angle whole turns away.
                    d = (d - std::f64::consts::TAU * (d / std::f64::consts::TAU).round()).abs();
                }
                let d = d / scale;
                worst = worst.max(d);
                assert!(d <= rel, "{what}: {label}[{k}] at t = {}: Assur {u} vs Newton {v} ({d:.2e} relative)", x.t);
            }
        }
    }
    worst
}

fn both_routes(mech: &Mechanism, times: &[f64]) -> (Vec<State>, Vec<State>) {
    let newton = Solver::new(mech.clone()).unwrap().run(times).unwrap();
    let assur = AssurSolver::new(mech.clone()).unwrap().run(times).unwrap();
    (assur, newton)
}

#[test]
fn every_linkage_template_agrees_with_the_general_solver() {
    let dir = common::root().join("templates");
    let mut seen = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        if !text.contains("kind = \"linkage\"") {
            continue;
        }
        let name = path.file_stem().unwrap().to_str().unwrap().to_string();
        let s = linkage(&name);
        let (assur, newton) = both_routes(&s.mechanism, &s.times);
        let worst = assert_routes_agree(&name, &assur, &newton, s.mechanism.length_scale, 1e-10);
        for st in &assur {
            assert!(st.residual <= 1e-13, "{name}: residual {} at t = {}", st.residual, st.t);
            assert!(st.near_singular.is_none(), "{name}: near-singular at t = {}", st.t);
        }
        eprintln!("{name}: largest relative difference {worst:.2e}");
        seen += 1;
    }
    assert!(seen >= 5, "only {seen} linkage templates");
}

fn kinds(name: &str) -> Vec<(String, Route)> {
    let s = linkage(name);
    let solver = AssurSolver::new(s.mechanism.clone()).unwrap();
    solver.routes().into_iter().map(|(g, r)| (g.describe(&s.mechanism), r)).collect()
}

#[test]
fn the_templates_decompose_into_their_textbook_groups() {
    use Route::ClosedForm;
    let own = |v: &[(&str, Route)]| v.iter().map(|(s, r)| (s.to_string(), *r)).collect::<Vec<_>>();
    assert_eq!(
        kinds("shaper"),
        own(&[
            ("driven body (angle) (crank)", ClosedForm),
            ("dyad RPR (block, rocker)", ClosedForm),
            ("dyad RRP (link, ram)", ClosedForm)
        ])
    );
    assert_eq!(
        kinds("fourbar-linkage"),
        own(&[("driven body (angle) (crank)", ClosedForm), ("dyad RRR (coupler, rocker)", ClosedForm)])
    );
    assert_eq!(
        kinds("slider-crank"),
        own(&[("driven body (angle) (crank)", ClosedForm), ("dyad RRP (rod, piston)", ClosedForm)])
    );
    let triad = kinds("triad-driven");
    assert_eq!(triad[0], ("driven body (angle) (crank)".to_string(), ClosedForm));
    // The class-III part goes to the triad's degree-6 closed form (seed 000).
    assert_eq!(triad[1], ("triad (triangle, link1, link2, link3)".to_string(), ClosedForm));
    assert_eq!(triad.len(), 2);
}

// --- random linkages from known poses -------------------------------------------------

/// A small deterministic generator (xorshift), so failures reproduce.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
    fn vec(&mut self, r: f64) -> Vector {
        Vector::new(self.range(-r, r), self.range(-r, r))
    }
}

/// A mechanism under construction from known poses: every joint is made to hold at the
/// poses given, so the placement is an exact assembly.
struct Build {
    bodies: Vec<Body>,
    joints: Vec<Joint>,
    drivers: Vec<Driver>,
}

impl Build {
    fn body(&mut self, name: &str, at: Point, angle: f64) -> usize {
        self.bodies.push(Body { name: name.into(), points: vec![], at, angle });
        self.bodies.len() - 1
    }
    fn pose(&self, a: Attach) -> (Point, f64) {
        match a {
            Attach::Ground => (Point::origin(), 0.0),
            Attach::Body(i) => (self.bodies[i].at, self.bodies[i].angle),
        }
    }
    /// The anchor of global point `p` on body `a`.
    fn anchor(&self, a: Attach, p: Point) -> Anchor {
        let (r, phi) = self.pose(a);
        Anchor { body: a, local: rotate(p - r, -phi) }
    }
    fn revolute(&mut self, name: &str, a: Attach, b: Attach, p: Point) {
        let kind = JointKind::Revolute { a: self.anchor(a, p), b: self.anchor(b, p) };
        self.joints.push(Joint { name: name.into(), kind });
    }
    /// A prismatic joint: `slider`'s point `p` on `guide`'s line through `p` along `dir`
    /// (global), its relative angle as placed.
    fn prismatic(&mut self, name: &str, slider: Attach, guide: Attach, p: Point, dir: Vector, back: f64) {
        let (_, ps) = self.pose(slider);
        let (_, pg) = self.pose(guide);
        let q1 = p - dir * back;
        let q2 = q1 + dir * 1.0;
        let kind = JointKind::Prismatic {
            point: self.anchor(slider, p),
            q1: self.anchor(guide, q1),
            q2: self.anchor(guide, q2),
            angle: ps - pg,
        };
        self.joints.push(Joint { name: name.into(), kind });
    }
    fn finish(self) -> Mechanism {
        Mechanism { bodies: self.bodies, joints: self.joints, drivers: self.drivers, length_scale: 10.0 }
    }
}

/// A crank (driven by its angle, ω = 1.3 rad/s; for a chain of odd length a slider driven
/// along a ground line by a distance) and a chain of dyads of the given kinds,
/// each hung on the crank or the dyad before it and the ground, placed at random poses.
fn random_chain(rng: &mut Rng, kinds: &[&str]) -> Mechanism {
    let mut m = Build { bodies: vec![], joints: vec![], drivers: vec![] };
    let phi0 = rng.range(0.0, 6.0);
    let crank = m.body("crank", Point::origin(), phi0);
    if kinds.len().is_multiple_of(2) {
        m.revolute("O", Attach::Ground, Attach::Body(crank), Point::origin());
        m.drivers.push(Driver {
            name: "O".into(),
            target: DriverTarget::JointAngle(0),
            law: Expr::parse(&format!("{phi0} + 1.3*t")).unwrap(),
        });
    } else {
        // A driven slider instead of a crank: on a ground line through the origin, pushed
        // by a distance law; the line on the slider or on the ground.
        let a = rng.range(0.0, std::f64::consts::TAU);
        let d = Vector::new(a.cos(), a.sin());
        let back = rng.range(0.5, 1.0);
        if rng.next() < 0.5 {
            m.prismatic("O", Attach::Body(crank), Attach::Ground, Point::origin(), d, back);
        } else {
            m.prismatic("O", Attach::Ground, Attach::Body(crank), Point::origin(), d, back);
        }
        m.drivers.push(Driver {
            name: "O".into(),
            target: DriverTarget::JointDistance(0),
            law: Expr::parse(&format!("{back} + 0.8*sin(2*t)")).unwrap(),
        });
    }
    // The known body the next dyad hangs on, and a point of it.
    let mut last = Attach::Body(crank);
    let mut last_point = Point::new(phi0.cos() * 1.5, phi0.sin() * 1.5);
    for (k, kind) in kinds.iter().enumerate() {
        let letters: Vec<bool> = kind.chars().map(|c| c == 'P').collect();
        let p1 = last_point; // joint j1 on `last`
        let p2 = p1 + rng.vec(2.0) + Vector::new(3.0, 0.5); // joint j2
        let p3 = p2 + rng.vec(2.0) + Vector::new(1.5, -2.5); // joint j3 on the ground
        let b1 = m.body(&format!("b{k}1"), p1 + rng.vec(1.0), rng.range(-3.0, 3.0));
        let b2 = m.body(&format!("b{k}2"), p2 + rng.vec(1.0), rng.range(-3.0, 3.0));
        let dir = |rng: &mut Rng| {
            let a = rng.range(0.0, std::f64::consts::TAU);
            Vector::new(a.cos(), a.sin())
        };
        let (j1, j2, j3) = (format!("J{k}1"), format!("J{k}2"), format!("J{k}3"));
        if letters[0] {
            let d = dir(rng);
            m.prismatic(&j1, Attach::Body(b1), last, p1, d, rng.range(-1.0, 1.0));
        } else {
            m.revolute(&j1, last, Attach::Body(b1), p1);
        }
        if letters[1] {
            let d = dir(rng);
            // Either body may carry the line.
            if rng.next() < 0.5 {
                m.prismatic(&j2, Attach::Body(b2), Attach::Body(b1), p2, d, rng.range(-1.0, 1.0));
            } else {
                m.prismatic(&j2, Attach::Body(b1), Attach::Body(b2), p2, d, rng.range(-1.0, 1.0));
            }
        } else {
            m.revolute(&j2, Attach::Body(b1), Attach::Body(b2), p2);
        }
        if letters[2] {
            let d = dir(rng);
            if rng.next() < 0.5 {
                m.prismatic(&j3, Attach::Body(b2), Attach::Ground, p3, d, rng.range(-1.0, 1.0));
            } else {
                m.prismatic(&j3, Attach::Ground, Attach::Body(b2), p3, d, rng.range(-1.0, 1.0));
            }
        } else {
            m.revolute(&j3, Attach::Body(b2), Attach::Ground, p3);
        }
        last = Attach::Body(b2);
        last_point = p2 + rng.vec(1.0);
    }
    m.finish()
}

#[test]
fn random_linkages_of_every_dyad_kind_agree_with_the_general_solver() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let times: Vec<f64> = (0..=40).map(|k| k as f64 * 0.002).collect();
    // Chains of odd length start from a driven slider, of even length from a crank.
    let chains: [&[&str]; 8] = [
        &["RRR"],
        &["RRP", "RPR"],
        &["PRP", "RPP"],
        &["RPR", "RRR", "RRP"],
        &["PRR", "PPR"],
        &["RRP", "PRP", "RPP", "RPR"],
        &["PRP"],
        &["RPP", "PRR", "RRP"],
    ];
    let mut solved = 0;
    let mut kinds_seen = std::collections::BTreeSet::new();
    for (c, chain) in chains.iter().enumerate() {
        for trial in 0..8 {
            let mech = random_chain(&mut rng, chain);
            let assur = AssurSolver::new(mech.clone()).unwrap();
            for (g, route) in assur.routes() {
                assert_eq!(route, Route::ClosedForm, "chain {chain:?}: {}", g.describe(&mech));
                if let GroupKind::Dyad(k) = g.kind {
                    kinds_seen.insert(k.name());
                }
            }
            // Random poses may sit near a dead point: compare where the general solver
            // finds a well-conditioned motion.
            let Ok(newton) = Solver::new(mech.clone()).unwrap().run(&times) else { continue };
            if newton.iter().any(|s| s.near_singular.is_some()) {
                continue;
            }
            // Nor where Newton leaves the branch between two samples 2 ms apart (an angle
            // jumping by more than 0.5 rad: a step from a poor prediction near a fold),
            // which the closed forms, keeping the nearest root, do not follow.
            let jumps = newton.windows(2).any(|w| {
                (2..w[0].q.len()).step_by(3).any(|k| {
                    let d = (w[1].q[k] - w[0].q[k]).abs();
                    (d - std::f64::consts::TAU * (d / std::f64::consts::TAU).round()).abs() > 0.5
                })
            });
            if jumps {
                continue;
            }
            let ours = AssurSolver::new(mech.clone()).unwrap().run(&times).unwrap();
            // From a random placement the general solver's Newton sometimes lands an angle
            // whole turns away between two samples (same pose): compare angles modulo 2π.
            assert_routes_agree_as(&format!("chain {c} {chain:?} trial {trial}"), &ours, &newton, 10.0, 1e-10, true);
            solved += 1;
        }
    }
    assert_eq!(kinds_seen.into_iter().collect::<Vec<_>>(), ["PRP", "RPP", "RPR", "RRP", "RRR"]);
    eprintln!("{solved} of 64 random linkages compared");
    assert!(solved >= 40, "only {solved} of 64 random linkages compared");
}

// --- branch continuity -----------------------------------------------------------------

/// The Chebyshev four-bar as a linkage with its coupler and rocker placed in `mode`
/// (+1: B above the line AC as in the template, −1: mirrored).
fn fourbar(mode: f64) -> (Mechanism, Vec<f64>) {
    let mut s = linkage("fourbar-linkage");
    if mode < 0.0 {
        // At φ1 = 0, A = (0.04, 0), C = (0.08, 0): the mirrored B is below the axis.
        s.mechanism.bodies[1].angle = -s.mechanism.bodies[1].angle;
        s.mechanism.bodies[2].angle = -s.mechanism.bodies[2].angle;
    }
    (s.mechanism, s.times)
}

#[test]
fn each_assembly_mode_is_kept_through_a_whole_crank_turn() {
    for mode in [1.0, -1.0] {
        let (mech, times) = fourbar(mode);
        let (assur, newton) = both_routes(&mech, &times);
        assert_routes_agree(&format!("mode {mode}"), &assur, &newton, mech.length_scale, 1e-10);
        // B = coupler point (0.10, 0) stays on its side of the line A → C all turn long.
        let b = Anchor { body: Attach::Body(1), local: Vector::new(0.10, 0.0) };
        let a = Anchor { body: Attach::Body(1), local: Vector::zeros() };
        let c = Point::new(0.08, 0.0);
        for st in &assur {
            let (pa, pb) = (st.point(a), st.point(b));
            let side = mechdraw::geom::cross(c - pa, pb - pa);
            assert!(side * mode > 0.0, "mode {mode}: B changed side at t = {}", st.t);
        }
        // After one turn the mechanism is back where it started.
        let (first, last) = (&assur[0], &assur[assur.len() - 1]);
        let turn = std::f64::consts::TAU;
        for k in [3, 4, 5, 6, 7, 8] {
            let d = last.q[k] - first.q[k];
            let d = if k % 3 == 2 { (d / turn).round() * turn - d } else { d };
            assert!(d.abs() <= 1e-12, "q[{k}] after a turn: {d:e}");
        }
    }
}

// --- what cannot be assembled, and what does not decompose ------------------------------

#[test]
fn an_unassemblable_position_is_reported_by_group_joint_and_time() {
    // The four-bar with a crank of 0.15 (its pin A reaches 0.23 from C: the coupler and the
    // rocker, 0.10 each, cannot close at B past φ1 ≈ 47°). The crank pin is moved along the
    // crank so that the placement at t = 0 still assembles.
    let s = linkage("fourbar-linkage");
    let mut mech = s.mechanism.clone();
    let crank_pin = Vector::new(0.15, 0.0);
    if let JointKind::Revolute { a, .. } = &mut mech.joints[1].kind {
        a.local = crank_pin;
    }
    // φ1 = 30° at t = 0: A = 0.15·(cos 30°, sin 30°), 0.12 from C.
    mech.drivers[0].law = Expr::parse("pi/6 + 20*t").unwrap();
    mech.bodies[0].angle = std::f64::consts::FRAC_PI_6;
    let a0 = Point::new(0.15 * 30f64.to_radians().cos(), 0.15 * 30f64.to_radians().sin());
    mech.bodies[1].at = a0;
    let times: Vec<f64> = (0..=100).map(|k| k as f64 * 0.001).collect();
    let err = AssurSolver::new(mech.clone()).unwrap().run(&times).unwrap_err();
    match &err {
        LinkageError::GroupCannotAssemble { group, joint, t, why } => {
            assert_eq!(group, "dyad RRR (coupler, rocker)");
            assert_eq!(joint, "B");
            // |A − C| = 0.2 when 0.0289 − 0.024·cos φ1 = 0.04 ... i.e. cos φ1 = −0.4625 ≥ φ1 = 117.5°:
            // first failing sample.
            let phi = |t: f64| std::f64::consts::FRAC_PI_6 + 20.0 * t;
            let dist = |t: f64| {
                let a = Vector::new(0.15 * phi(t).cos(), 0.15 * phi(t).sin());
                (a - Vector::new(0.08, 0.0)).norm()
            };
            let first = times.iter().copied().find(|&t| dist(t) > 0.2).unwrap();
            assert_eq!(*t, first, "{err}");
            assert!(why.starts_with("driver `crank` = "), "{err}");
        }
        other => panic!("expected GroupCannotAssemble, got {other}"),
    }
    assert!(err.to_string().contains("joint `B` cannot close"), "{err}");
}

#[test]
fn an_rpr_dyad_whose_guide_cannot_reach_the_pin_is_reported_by_group_joint_and_time() {
    // The shaper's crank and rocker with the rocker's guide 200 mm off its pivot O3: the
    // block's pin A must lie on it, so |A − O3| ≥ 200, and |A − O3|² = 125² + 300² +
    // 2·300·125·sin φ1 falls below 200² for sin φ1 < −0.875 (φ1 in 241°…299°). At t = 0
    // (φ1 = 0, A = (125, 300)) the rocker's angle θ has −125·sin θ + 300·cos θ = 200:
    // θ = 29.4°.
    let theta = (200.0_f64 / 325.0).acos() - 125.0_f64.atan2(300.0);
    let text = format!(
        r#"kind = "linkage"
name = "offset-guide"
units = "mm"
time = {{ from = 0.0, to = 1.0, steps = 360 }}
[ground]
points = {{ O3 = [0.0, 0.0], O1 = [0.0, 300.0] }}
[[body]]
name = "crank"
points = {{ O1 = [0.0, 0.0], A = [125.0, 0.0] }}
at = [0.0, 300.0]
angle_deg = 0.0
[[body]]
name = "block"
points = {{ A = [0.0, 0.0] }}
at = [125.0, 300.0]
angle_deg = {deg}
[[body]]
name = "rocker"
points = {{ O3 = [0.0, 0.0], L1 = [0.0, 200.0], L2 = [600.0, 200.0] }}
at = [0.0, 0.0]
angle_deg = {deg}
[[joint]]
name = "O1"
revolute = ["ground.O1", "crank.O1"]
[[joint]]
name = "A"
revolute = ["crank.A", "block.A"]
[[joint]]
name = "slide"
prismatic = {{ point = "block.A", line = ["rocker.L1", "rocker.L2"] }}
[[joint]]
name = "O3"
revolute = ["ground.O3", "rocker.O3"]
[[driver]]
joint = "O1"
law = "2*pi*t"
"#,
        deg = theta.to_degrees()
    );
    let Scene::Linkage(s) = scene::parse(&text, "offset-guide.toml", &[]).unwrap() else { panic!("a linkage") };
    let solver = AssurSolver::new(s.mechanism.clone()).unwrap();
    assert!(solver.routes().iter().any(|(g, r)| g.kind == GroupKind::Dyad(mechdraw::solve::linkage::DyadKind::Rpr)
        && *r == Route::ClosedForm));
    let reach = |t: f64| {
        let phi = 2.0 * std::f64::consts::PI * t;
        (125.0 * phi.cos()).hypot(300.0 + 125.0 * phi.sin())
    };
    let first = s.times.iter().copied().find(|&t| reach(t) < 200.0).unwrap();
    // Positions only (the sweep), and with the rates (the sweep with rates): the same report.
    for err in [solver.clone().run_positions(&s.times).unwrap_err(), solver.clone().run(&s.times).unwrap_err()] {
        match &err {
            LinkageError::GroupCannotAssemble { group, joint, t, .. } => {
                assert_eq!(group, "dyad RPR (block, rocker)", "{err}");
                assert_eq!(joint, "slide", "{err}");
                assert_eq!(*t, first, "{err}");
            }
            other => panic!("expected GroupCannotAssemble, got {other}"),
        }
        assert!(err.to_string().contains("passes"), "{err}");
    }
    // Up to there both routes agree.
    let before: Vec<f64> = s.times.iter().copied().take_while(|&t| t < first).collect();
    let (assur, newton) = both_routes(&s.mechanism, &before);
    assert_routes_agree("offset guide", &assur, &newton, s.mechanism.length_scale, 1e-10);
}

#[test]
fn a_mechanism_that_does_not_decompose_is_solved_by_newton() {
    // The four-bar driven by its coupler's angle: no body is set by the driver alone and
    // no two bodies close, so the three form one general group.
    let s = linkage("fourbar-linkage");
    let mut mech = s.mechanism.clone();
    let phi2 = mech.bodies[1].angle;
    mech.drivers[0] = Driver {
        name: "coupler".into(),
        target: DriverTarget::BodyAngle(1),
        law: Expr::parse(&format!("{phi2} + 0.05*sin(3*t)")).unwrap(),
    };
    let solver = AssurSolver::new(mech.clone()).unwrap();
    let routes = solver.routes();
    assert_eq!(routes.len(), 1);
    assert_eq!(routes[0].0.kind, GroupKind::General);
    assert_eq!(routes[0].1, Route::Newton);
    assert_eq!(routes[0].0.bodies, vec![0, 1, 2]);
    let times: Vec<f64> = (0..=60).map(|k| k as f64 * 0.01).collect();
    let (assur, newton) = both_routes(&mech, &times);
    assert_routes_agree("coupler-driven four-bar", &assur, &newton, mech.length_scale, 1e-10);
}

#[test]
fn positions_only_match_the_full_route() {
    let s = linkage("shaper");
    let full = AssurSolver::new(s.mechanism.clone()).unwrap().run(&s.times).unwrap();
    let pos = AssurSolver::new(s.mechanism.clone()).unwrap().run_positions(&s.times).unwrap();
    for (a, q) in full.iter().zip(&pos) {
        for (u, v) in a.q.iter().zip(q) {
            assert!((u - v).abs() <= 1e-12 * 600.0, "t = {}: {u} vs {v}", a.t);
        }
    }
}

#[test]
fn forces_on_the_assur_route_equal_the_general_solvers() {
    for name in ["shaper-forces", "slider-crank"] {
        let s = linkage(name);
        let d = s.dynamics.clone().unwrap();
        let (sa, fa) = AssurSolver::new(s.mechanism.clone()).unwrap().run_kinetostatics(&s.times, &d).unwrap();
        let (_, fb) = Solver::new(s.mechanism.clone()).unwrap().run_kinetostatics(&s.times, &d).unwrap();
        let big = fb
            .iter()
            .flat_map(|f| f.reactions.iter().map(|r| r.force.norm()).chain(f.drivers.iter().map(|v| v.abs())))
            .fold(0.0, f64::max);
        for ((st, a), b) in sa.iter().zip(&fa).zip(&fb) {
            for (ra, rb) in a.reactions.iter().zip(&b.reactions) {
                assert!((ra.force - rb.force).norm() <= 1e-10 * big, "{name} t = {}: {ra:?} vs {rb:?}", st.t);
            }
            for (da, db) in a.drivers.iter().zip(&b.drivers) {
                assert!((da - db).abs() <= 1e-10 * big, "{name} t = {}: driver {da} vs {db}", st.t);
            }
            assert!(a.power_residual <= 1e-9, "{name} t = {}: power residual {:e}", st.t, a.power_residual);
        }
    }
}

#[test]
fn a_time_step_too_coarse_for_newton_keeps_every_dyad_on_its_branch() {
    // The shaper sampled every 2.78 s (2.8 crank turns between samples): the prediction is
    // useless, each dyad keeps the branch it had; every sample equals the closed form.
    use mechdraw::bench::reference::shaper::{Y_RAM, closed_form};
    let mut s = linkage("shaper");
    s.times = (0..=360).map(|k| k as f64 * 1000.0 / 360.0).collect();
    let states = AssurSolver::new(s.mechanism.clone()).unwrap().run(&s.times).unwrap();
    let e = s.anchor("ram.E").unwrap();
    for st in &states {
        let ([xe, ve, _], _) = closed_form(st.t);
        let p = st.point(e);
        assert!((p.x - xe).abs() <= 1e-9 && (p.y - Y_RAM).abs() <= 1e-9, "t = {}: x_E {} vs {xe}", st.t, p.x);
        assert!((st.velocity(e).x - ve).abs() <= 1e-9 * 2000.0, "t = {}", st.t);
    }
}

// --- the sweep ---------------------------------------------------------------------------

/// `positions_into` (group by group over all the steps) against `step_positions` at each
/// time in turn, and `motion_into` against `step`: the same q (q̇, q̈, iterations,
/// near-singular reports), bit for bit, or the same error after the same steps.
fn assert_sweep_is_stepping(what: &str, mech: &Mechanism, times: &[f64]) {
    assert_motion_is_stepping(what, mech, times);
    let mut stepping = AssurSolver::new(mech.clone()).unwrap();
    let mut stepped = Vec::new();
    let mut stepped_err = None;
    for &t in times {
        match stepping.step_positions(t) {
            Ok(()) => stepped.extend_from_slice(stepping.q()),
            Err(e) => {
                stepped_err = Some(e.to_string());
                break;
            }
        }
    }
    let mut swept = Vec::new();
    let swept_err =
        AssurSolver::new(mech.clone()).unwrap().positions_into(times, &mut swept).err().map(|e| e.to_string());
    assert_eq!(swept_err, stepped_err, "{what}");
    assert_eq!(swept.len(), stepped.len(), "{what}");
    for (i, (a, b)) in swept.iter().zip(&stepped).enumerate() {
        assert_eq!(
            a.to_bits(),
            b.to_bits(),
            "{what}: step {}, q[{}]: {a} vs {b}",
            i / mech.bodies.len() / 3,
            i % (3 * mech.bodies.len())
        );
    }
}

/// `motion_into` against `step` at each time in turn (each state read from a copy, so
/// that reading it changes nothing of the stepping).
fn assert_motion_is_stepping(what: &str, mech: &Mechanism, times: &[f64]) {
    let mut stepping = AssurSolver::new(mech.clone()).unwrap();
    let mut stepped: Vec<State> = Vec::new();
    let mut stepped_err = None;
    for &t in times {
        match stepping.step(t) {
            Ok(()) => stepped.push(stepping.clone().state()),
            Err(e) => {
                stepped_err = Some(e.to_string());
                break;
            }
        }
    }
    let mut m = Motion::default();
    let swept_err = AssurSolver::new(mech.clone()).unwrap().motion_into(times, &mut m).err().map(|e| e.to_string());
    assert_eq!(swept_err, stepped_err, "{what}, with rates");
    let n = 3 * mech.bodies.len();
    assert_eq!(m.q.len(), stepped.len() * n, "{what}, with rates");
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    for (k, st) in stepped.iter().enumerate() {
        let at = k * n..(k + 1) * n;
        assert_eq!(bits(&m.q[at.clone()]), bits(&st.q), "{what}: q at step {k}");
        assert_eq!(bits(&m.qd[at.clone()]), bits(&st.qd), "{what}: q̇ at step {k}");
        assert_eq!(bits(&m.qdd[at]), bits(&st.qdd), "{what}: q̈ at step {k}");
        assert_eq!(m.iterations[k], st.iterations, "{what}: iterations at step {k}");
        let near = |n: Option<&NearSingular>| n.map(|n| (n.t.to_bits(), n.pivot.to_bits(), n.constraints.clone()));
        let swept_near = m.near.iter().find(|(at, _)| *at == k).map(|(_, n)| n);
        assert_eq!(near(swept_near), near(st.near_singular.as_ref()), "{what}: near-singular at step {k}");
    }
}

#[test]
fn a_sweep_gives_the_bits_of_stepping() {
    for name in ["fourbar-linkage", "shaper", "shaper-forces", "slider-crank", "triad-driven"] {
        let s = linkage(name);
        assert_sweep_is_stepping(name, &s.mechanism, &s.times);
        // Uneven steps (the linear prediction's ratio), and a repeated time.
        let mut times = s.times.clone();
        times.insert(3, times[3]);
        times.insert(10, 0.5 * (times[9] + times[10]));
        assert_sweep_is_stepping(&format!("{name}, uneven"), &s.mechanism, &times);
    }
    for mode in [1.0, -1.0] {
        let (mech, times) = fourbar(mode);
        assert_sweep_is_stepping(&format!("four-bar mode {mode}"), &mech, &times);
    }
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let times: Vec<f64> = (0..=40).map(|k| k as f64 * 0.002).collect();
    for chain in [&["RRR"][..], &["RRP", "RPR"], &["PRP", "RPP"], &["RPR", "RRR", "RRP"], &["RPP", "PRR", "RRP"]] {
        for trial in 0..6 {
            let mech = random_chain(&mut rng, chain);
            assert_sweep_is_stepping(&format!("{chain:?} trial {trial}"), &mech, &times);
        }
    }
}

#[test]
fn a_sweep_stops_where_stepping_fails_and_resumes_as_stepping_does() {
    // The four-bar whose crank carries A out of the coupler's and rocker's reach (see
    // an_unassemblable_position_is_reported_by_group_joint_and_time).
    let s = linkage("fourbar-linkage");
    let mut mech = s.mechanism.clone();
    if let JointKind::Revolute { a, .. } = &mut mech.joints[1].kind {
        a.local = Vector::new(0.15, 0.0);
    }
    mech.drivers[0].law = Expr::parse("pi/6 + 20*t").unwrap();
    mech.bodies[0].angle = std::f64::consts::FRAC_PI_6;
    mech.bodies[1].at = Point::new(0.15 * 30f64.to_radians().cos(), 0.15 * 30f64.to_radians().sin());
    let times: Vec<f64> = (0..=100).map(|k| k as f64 * 0.001).collect();
    assert_sweep_is_stepping("unassemblable four-bar", &mech, &times);
    // A law that is not finite part way (log of a negative number from t = 0.05 on).
    let mut mech = s.mechanism.clone();
    mech.drivers[0].law = Expr::parse("20*t + 0*log(0.05 - t)").unwrap();
    assert_sweep_is_stepping("law not finite", &mech, &times);
    // Sweeps after a resume (its first step predicted from the state's rates) continue
    // as steps from it do: by a solver new but for the state, and by one that has swept a
    // whole motion before (every group's branch set: the first step is swept too).
    for shaper in [false, true] {
        let (mech, times) = if shaper { (linkage("shaper").mechanism, linkage("shaper").times) } else { fourbar(1.0) };
        let start = AssurSolver::new(mech.clone()).unwrap().run(&times[..1]).unwrap().remove(0);
        let mut used = AssurSolver::new(mech.clone()).unwrap();
        used.run(&times).unwrap();
        for (what, mut a) in [("new", AssurSolver::new(mech.clone()).unwrap()), ("used", used)] {
            a.resume(&start);
            let mut b = a.clone();
            let mut swept = Vec::new();
            a.positions_into(&times[1..], &mut swept).unwrap();
            let mut stepped = Vec::new();
            for &t in &times[1..] {
                b.step_positions(t).unwrap();
                stepped.extend_from_slice(b.q());
            }
            assert!(swept.iter().zip(&stepped).all(|(x, y)| x.to_bits() == y.to_bits()), "{what}, shaper {shaper}");
            assert_eq!(swept.len(), stepped.len());
            // With the rates too.
            a.resume(&start);
            b.resume(&start);
            let mut m = Motion::default();
            a.motion_into(&times[1..], &mut m).unwrap();
            let mut q = Vec::new();
            for &t in &times[1..] {
                b.step(t).unwrap();
                q.extend_from_slice(b.q());
            }
            assert!(m.q.iter().zip(&q).all(|(x, y)| x.to_bits() == y.to_bits()), "{what}, shaper {shaper}, rates");
            assert_eq!(m.q.len(), q.len());
        }
    }
    let (mech, times) = fourbar(1.0);
    // And a sweep in two parts is one sweep.
    let mut halves = Vec::new();
    let mut c = AssurSolver::new(mech.clone()).unwrap();
    c.positions_into(&times[..150], &mut halves).unwrap();
    c.positions_into(&times[150..], &mut halves).unwrap();
    let mut whole = Vec::new();
    AssurSolver::new(mech).unwrap().positions_into(&times, &mut whole).unwrap();
    assert!(halves.iter().zip(&whole).all(|(x, y)| x.to_bits() == y.to_bits()) && halves.len() == whole.len());
}

#[test]
fn positions_only_states_carry_each_steps_q_residual_and_iterations() {
    // Swept: the q of run_positions, bit for bit, each with its residual.
    let s = linkage("shaper");
    let states = AssurSolver::new(s.mechanism.clone()).unwrap().run_positions_states(&s.times).unwrap();
    let pos = AssurSolver::new(s.mechanism.clone()).unwrap().run_positions(&s.times).unwrap();
    let mut check = Solver::new(s.mechanism.clone()).unwrap();
    assert_eq!(states.len(), s.times.len());
    for ((st, q), &t) in states.iter().zip(&pos).zip(&s.times) {
        assert_eq!(st.t, t);
        assert!(st.q.iter().zip(q).all(|(a, b)| a.to_bits() == b.to_bits()), "t = {t}");
        assert!(st.qd.iter().chain(&st.qdd).all(|&v| v == 0.0));
        let worst = check.residuals(st).unwrap().iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        assert!(st.residual <= 1e-12 && worst <= 1e-9, "t = {t}: {} {worst:e}", st.residual);
        assert_eq!(st.iterations, 0);
    }
    // Stepped (a group Newton solves): each step's own iterations, as step and state give.
    let mut mech = linkage("fourbar-linkage").mechanism;
    let phi2 = mech.bodies[1].angle;
    mech.drivers[0] = Driver {
        name: "coupler".into(),
        target: DriverTarget::BodyAngle(1),
        law: Expr::parse(&format!("{phi2} + 0.05*sin(3*t)")).unwrap(),
    };
    let times: Vec<f64> = (0..=60).map(|k| k as f64 * 0.01).collect();
    let states = AssurSolver::new(mech.clone()).unwrap().run_positions_states(&times).unwrap();
    let mut stepping = AssurSolver::new(mech).unwrap();
    for (st, &t) in states.iter().zip(&times) {
        stepping.step_positions(t).unwrap();
        let want = stepping.state();
        assert_eq!(st.iterations, want.iterations, "t = {t}");
        assert!(st.q.iter().zip(&want.q).all(|(a, b)| a.to_bits() == b.to_bits()), "t = {t}");
    }
    assert!(states.iter().any(|st| st.iterations > 0));
}
