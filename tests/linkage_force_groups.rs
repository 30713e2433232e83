//! Force figures per Assur group (issue 31, seed 003 Figs. 4 and 5 for any linkage): on every
//! linkage template with forces (and triad-driven given masses: a class-3 group), one figure
//! per group of the decomposition in solving order (the driven crank's, each dyad's or
//! triad's), and at every sample each figure closes, its found sides
//! are the solver's reactions on the group's bodies (and a distance driver's force), and its
//! resultant is the reaction between the group's bodies — to 1e-9 of the figure's largest
//! force. The reactions are read from the solver's Lagrange multipliers by the sign
//! conventions of solve::linkage::kinetostatics (revolute ["a.P", "b.P"]: force of a on b;
//! prismatic: force of the guide on the slider), not from the figure's code.

mod common;

use mechdraw::figure::linkage::forces::ForceFigures;
use mechdraw::geom::Vector;
use mechdraw::scene::linkage::LinkageScene;
use mechdraw::scene::{self, Scene};
use mechdraw::solve::linkage::{Attach, Forces, GroupKind, JointKind, Mechanism, Solver, State, decompose};

fn run(template: &str) -> (LinkageScene, Vec<State>, Vec<Forces>) {
    run_with(template, &[])
}

fn run_with(template: &str, set: &[&str]) -> (LinkageScene, Vec<State>, Vec<Forces>) {
    let over: Vec<scene::Override> = set.iter().map(|s| s.parse().unwrap()).collect();
    let loaded = scene::load(&common::root().join("templates").join(template), &over).unwrap();
    let Scene::Linkage(s) = loaded.scene else { panic!("not a linkage scene") };
    let d = s.dynamics.clone().expect("forces");
    let (states, forces) = Solver::new(s.mechanism.clone()).unwrap().run_kinetostatics(&s.times, &d).unwrap();
    (s, states, forces)
}

/// The body number of the figures' names (ground 0, moving bodies from 1).
fn number(a: Attach) -> usize {
    match a {
        Attach::Ground => 0,
        Attach::Body(i) => i + 1,
    }
}

/// The force a reaction's name stands for, from the solver's reactions: `RA` the joint A's
/// reaction (of its first body on its second), `−RA` the opposite, `R32` the force of body 3
/// on body 2 at the joint between them.
fn reaction(mech: &Mechanism, f: &Forces, name: &str) -> Option<Vector> {
    if let Some(rest) = name.strip_prefix('−') {
        return reaction(mech, f, rest).map(|v| -v);
    }
    let rest = name.strip_prefix('R')?;
    if let Some(j) = mech.joints.iter().position(|j| j.name == rest) {
        return Some(f.reactions[j].force);
    }
    let digits: Vec<usize> = rest.chars().map(|c| c.to_digit(10).map(|d| d as usize)).collect::<Option<_>>()?;
    let [by, on] = digits[..] else { return None };
    mech.joints.iter().enumerate().find_map(|(j, joint)| {
        let (first, second) = match joint.kind {
            JointKind::Revolute { a, b } => (a.body, b.body),
            JointKind::Prismatic { point, q1, .. } => (q1.body, point.body),
        };
        let r = f.reactions[j].force;
        if (number(first), number(second)) == (by, on) {
            Some(r)
        } else if (number(second), number(first)) == (by, on) {
            Some(-r)
        } else {
            None
        }
    })
}

/// The linkage templates with forces, and triad-driven given masses (a class-3 group: its
/// figure chains the triad's four bodies).
const TRIAD_MASSES: &[&str] = &[
    "body[0].mass=1",
    "body[1].mass=2",
    "body[2].mass=1",
    "body[3].mass=1.5",
    "body[4].mass=3",
    "body[4].inertia=0.01",
    "dynamics.g=[0.0, -9.81]",
    "time.steps=36",
];

#[test]
fn one_figure_per_group_closes_at_the_solvers_reactions() {
    let mut runs: Vec<(String, &[&str])> = common::template_paths()
        .iter()
        .filter(|t| std::fs::read_to_string(t).unwrap().contains("kind = \"linkage\""))
        .filter_map(|t| {
            let name = t.file_name().unwrap().to_string_lossy().to_string();
            let loaded = scene::load(t, &[]).unwrap();
            matches!(&loaded.scene, Scene::Linkage(s) if s.dynamics.is_some()).then_some((name, &[][..]))
        })
        .collect();
    assert!(runs.len() >= 2, "{runs:?}");
    runs.push(("triad-driven.toml".to_string(), TRIAD_MASSES));
    for (template, set) in &runs {
        let template = template.as_str();
        let (s, states, forces) = run_with(template, set);
        let mech = &s.mechanism;
        let dynamics = s.dynamics.as_ref().unwrap();
        let groups = decompose(mech);
        let figures = ForceFigures::new(mech, false);
        let captions = figures.captions(mech);
        assert_eq!(captions.len(), groups.len(), "{template}: {captions:?}");
        // The driven crank's figure first, then the dyads by their bodies and kind.
        assert!(matches!(groups[0].kind, GroupKind::Driven(_)) && captions[0] == "Crank 1 (driver)", "{captions:?}");
        for (g, c) in groups.iter().zip(&captions).skip(1) {
            let list: Vec<String> = g.bodies.iter().map(|b| (b + 1).to_string()).collect();
            match g.kind {
                GroupKind::Dyad(k) => assert_eq!(*c, format!("Dyad {} ({})", list.join("–"), k.name())),
                GroupKind::Triad => assert_eq!(*c, format!("Triad {}", list.join("–"))),
                _ => panic!("{template}: {g:?}"),
            }
        }
        let mut checked = 0;
        for (state, f) in states.iter().zip(&forces) {
            for poly in figures.polygons(mech, dynamics, state, f) {
                let largest = poly.chain.iter().map(|nv| nv.v.norm()).fold(0.0, f64::max);
                let tol = 1e-9 * largest.max(1e-300);
                let v = poly.vertices();
                assert!(v.last().unwrap().norm() <= tol, "{template} t = {}: {} does not close", state.t, poly.pole);
                assert!(poly.found >= 1, "{template}: {} finds nothing", poly.pole);
                for nv in &poly.chain[poly.chain.len() - poly.found..] {
                    if nv.name.starts_with("Fe") {
                        continue;
                    }
                    let want = reaction(mech, f, &nv.name).unwrap_or_else(|| panic!("{template}: {}", nv.name));
                    assert!(
                        (nv.v - want).norm() <= tol,
                        "{template} t = {}: {} {:?} vs {want:?}",
                        state.t,
                        nv.name,
                        nv.v
                    );
                    checked += 1;
                }
                for r in &poly.resultants {
                    let want = reaction(mech, f, &r.name).unwrap_or_else(|| panic!("{template}: {}", r.name));
                    let got = poly.resultant(&r.name).unwrap();
                    assert!((got - want).norm() <= tol, "{template} t = {}: {} {got:?} vs {want:?}", state.t, r.name);
                    checked += 1;
                }
            }
        }
        // Every found reaction of every group at every sample.
        assert!(checked >= states.len() * (groups.len() * 2), "{template}: {checked}");
    }
}

#[test]
fn per_body_figures_stay_a_choice() {
    let (s, states, forces) = run("slider-crank.toml");
    let mech = &s.mechanism;
    let figures = ForceFigures::new(mech, true);
    assert_eq!(figures.captions(mech), ["Crank 1", "Rod 2", "Piston 3"]);
    let polys = figures.polygons(mech, s.dynamics.as_ref().unwrap(), &states[30], &forces[30]);
    assert_eq!(polys.len(), 3);
    // And the scene chooses them by name; a wrong name is refused with the choices.
    let text = std::fs::read_to_string(common::root().join("templates/slider-crank.toml")).unwrap();
    let bodies = format!("{text}\n[polygons]\nforce_figures = \"bodies\"\n");
    let Scene::Linkage(b) = scene::parse(&bodies, "t.toml", &[]).unwrap() else { panic!() };
    assert!(b.polygons.per_body);
    let wrong = format!("{text}\n[polygons]\nforce_figures = \"links\"\n");
    let e = scene::parse(&wrong, "t.toml", &[]).unwrap_err().to_string();
    assert!(e.contains("polygons.force_figures") && e.contains("\"groups\"") && e.contains("\"bodies\""), "{e}");
}
