//! The four-bar's frames read as seed 003's figures (issue 14, items 4–6), checked over
//! every position of the template through the library (scene → products → frames): no
//! two texts of a frame overlap, force and reaction names included; every force of the
//! chain is named in every frame; the centroid images c′ lie at the solver's centroid
//! accelerations and at the middles the seed takes them from; the table of magnitudes
//! prints the solver's values; the images of a ternary coupler are closed triangles.

#![allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the library calls"
)]

mod common;

use mechdraw::draw::{Drawing, HAlign, Shape};
use mechdraw::figure::fourbar::{Layout, ModelUnits, Scale, Show};
use mechdraw::figure::shared::polygon::MARK_RADIUS;
use mechdraw::figure::shared::sheet::read_number;
use mechdraw::geom::{Point, Vector};
use mechdraw::run::RunOptions;
use mechdraw::run::products::Picture;
use mechdraw::scene::{self, Override, Scene};
use mechdraw::solve::fourbar::{Motion, MotionSpec, solve_motion};

/// The template (with `set` overrides): its frames as drawn by the run, its motion and its
/// layout (the same as the run's: the layout is a function of the motion).
fn template(set: &[&str]) -> (Vec<Drawing>, MotionSpec, Motion, Layout) {
    let over: Vec<Override> = set.iter().map(|s| s.parse().unwrap()).collect();
    let loaded = scene::load(&common::root().join("templates/fourbar-chebyshev.toml"), &over).unwrap();
    let products = mechdraw::run::products(&loaded, &RunOptions::default()).unwrap();
    let Picture::Motion(a) = &products.picture else { panic!("a four-bar animates") };
    let frames = (0..a.len()).map(|k| a.frame_of(&a.pose(k))).collect();
    let Scene::Fourbar(s) = loaded.scene else { panic!("not a four-bar") };
    let motion = solve_motion(&s.spec).unwrap();
    let show = Show { velocity: true, acceleration: true, forces: true, ..Show::default() };
    let layout = Layout::new(&s.spec.geometry, &motion.positions, Some(&motion.forces), show, ModelUnits::SI);
    (frames, s.spec, motion, layout)
}

use common::{boxes_overlap as overlap, text_boxes as texts};

#[test]
fn no_two_texts_of_a_frame_overlap_over_the_template_motion() {
    let (frames, ..) = template(&[]);
    assert_eq!(frames.len(), 360);
    let mut overlaps = 0;
    let mut examples = Vec::new();
    let mut force_names = 0;
    for (deg, f) in frames.iter().enumerate() {
        let t = texts(f);
        force_names += t.iter().filter(|x| x.layer == "FORCES").count();
        for (i, a) in t.iter().enumerate() {
            for b in &t[..i] {
                if overlap(a, b) {
                    overlaps += 1;
                    if examples.len() < 12 {
                        examples.push(format!("{deg}°: {:?} over {:?}", a.value, b.value));
                    }
                }
            }
        }
    }
    // The force and reaction names (and the table) are among the texts checked.
    assert!(force_names > 360 * 25, "{force_names}");
    assert_eq!(overlaps, 0, "{examples:?}");
}

#[test]
fn every_force_is_named_in_every_frame() {
    let (frames, _, motion, _) = template(&[]);
    for (i, (d, f)) in frames.iter().zip(&motion.forces).enumerate() {
        let deg = motion.positions[i].phi1.to_degrees().round();
        let names: Vec<String> = texts(d)
            .into_iter()
            .filter(|t| t.layer == "FORCES" && t.halign == HAlign::Center)
            .map(|t| t.value)
            .collect();
        let count = |n: &str| names.iter().filter(|x| *x == n).count();
        // The dyad's chain and resultants (Fig. 4), the crank's (Fig. 5): once each; a zero
        // force (F outside its range) is no force and has no name.
        let chain = [
            ("RAn", f.r_a_n),
            ("G21", f.g21),
            ("Fi21", f.fi21),
            ("G22", f.g22),
            ("Fi22", f.fi22),
            ("G3", f.g3),
            ("Fi3", f.fi3),
            ("RCn", f.r_c_n),
            ("RCt", f.r_c_t),
            ("RAt", f.r_a_t),
            ("−RA", -f.r_a),
            ("Fi1", f.fi1),
            ("G1", f.g1),
        ];
        for (n, v) in chain {
            assert!(v.norm() > 0.0, "{deg}°: {n} is zero");
            assert_eq!(count(n), 1, "{deg}°: {n} named {} times in {names:?}", count(n));
        }
        // The reactions: in the polygons and on the mechanism.
        for n in ["RA", "RB", "RC", "RO"] {
            assert_eq!(count(n), 2, "{deg}°: {n} named {} times in {names:?}", count(n));
        }
        // F in the polygon and at M when it acts (80°…280°), nowhere else.
        let acting = (80.0..=280.0).contains(&deg);
        assert_eq!(f.f_ext.norm() > 0.0, acting, "{deg}°");
        assert_eq!(count("F"), if acting { 2 } else { 0 }, "{deg}°: F in {names:?}");
        // The ω1 arrow and the link numbers on the mechanism.
        let mech: Vec<String> = texts(d).into_iter().filter(|t| t.layer == "MECHANISM").map(|t| t.value).collect();
        for n in ["O1", "A", "B", "M", "C", "1", "2", "3", "ω1"] {
            assert!(mech.iter().any(|x| x == n), "{deg}°: no {n} in {mech:?}");
        }
    }
}

/// The scale and pole of the velocity (`which` 0) or acceleration (1) polygon at position
/// `k` (each frame has its own).
fn place(layout: &Layout, k: usize, pos: &mechdraw::solve::fourbar::Position, which: usize) -> (Scale, Point) {
    let (v, a) = layout.polygon_places(k, pos);
    [v, a][which].unwrap()
}

#[test]
fn centroid_images_lie_at_the_solvers_centroid_accelerations() {
    let (frames, spec, motion, layout) = template(&[]);
    let s = layout.frame.sizes;
    for (i, (d, pos)) in frames.iter().zip(&motion.positions).enumerate() {
        let (sa, pole) = place(&layout, i, pos, 1);
        let k = pos.kin.unwrap();
        let acc = d.layers.iter().position(|l| l.name == "ACCELERATION").unwrap();
        let marks: Vec<Point> = d
            .entities
            .iter()
            .filter_map(|e| match e.shape {
                Shape::Circle { center, radius }
                    if e.layer == acc && (radius - MARK_RADIUS * s.joint).abs() < 1e-15 =>
                {
                    Some(center)
                }
                _ => None,
            })
            .collect();
        assert_eq!(marks.len(), 4, "{:?}", pos.phi1.to_degrees());
        let at = |v: Vector| pole + sa.draw(v);
        // The seed's construction: c1′ the middle of πa′ (G1 the middle of O1A), c21′ of a′b′,
        // c22′ of b′m′, c3′ of πb′ (G3 the middle of CB, C fixed); from the drawn a′, b′, m′.
        let (a1, b1, m1) = (at(k.a_a), at(k.a_b), at(k.a_m));
        let mid = |p: Point, q: Point| p + (q - p) * 0.5;
        let drawn_size = (a1 - pole).norm().max((b1 - pole).norm()).max((m1 - pole).norm());
        for (mark, solver, construction) in [
            (marks[0], k.a_g1, mid(pole, a1)),
            (marks[1], k.a_g21, mid(a1, b1)),
            (marks[2], k.a_g22, mid(b1, m1)),
            (marks[3], k.a_g3, mid(pole, b1)),
        ] {
            // Physical: the mark read back at k_a is the solver's centroid acceleration.
            let read = (mark - pole) * (sa.per_mm / layout.frame.k_l);
            assert!((read - solver).norm() <= 1e-9 * solver.norm().max(1.0), "{read:?} vs {solver:?}");
            assert!((mark - construction).norm() <= 1e-9 * drawn_size, "{mark:?} vs {construction:?}");
        }
        // Each has its letter.
        let names: Vec<String> = texts(d).into_iter().filter(|t| t.layer == "ACCELERATION").map(|t| t.value).collect();
        for n in ["c1′", "c21′", "c22′", "c3′"] {
            assert!(names.iter().any(|x| x.split('≡').any(|p| p == n)), "no {n} in {names:?}");
        }
    }
    let _ = spec;
}

#[test]
fn the_table_of_magnitudes_prints_the_solvers_values() {
    let (frames, _, motion, layout) = template(&[]);
    let ff = layout.frame.forces.as_ref().unwrap();
    for (d, f) in frames.iter().zip(&motion.forces) {
        let t = texts(d);
        // Rows: a left-aligned name and a right-aligned "value unit" on one baseline.
        // The value and half a unit of its last printed digit (sheet::number: 4 significant
        // digits, whole numbers in full).
        let value_of = |name: &str| -> (f64, String, f64) {
            let n = t
                .iter()
                .find(|x| x.value == name && x.halign == HAlign::Left && x.at.x == ff.table_at.x)
                .unwrap_or_else(|| panic!("no row {name}"));
            let v = t.iter().find(|x| x.halign == HAlign::Right && x.at.y == n.at.y).unwrap();
            let (num, unit) = v.value.split_once(' ').unwrap();
            let decimals = num.split_once('.').map_or(0, |(_, f)| f.len());
            (read_number(num).unwrap(), unit.to_string(), 0.5 * 10f64.powi(-(decimals as i32)))
        };
        // |R| from the components, independently of the table's own arithmetic.
        let mag = |v: Vector| v.x.hypot(v.y);
        for (name, want) in [
            ("RAn", mag(f.r_a_n)),
            ("RAt", mag(f.r_a_t)),
            ("RCn", mag(f.r_c_n)),
            ("RCt", mag(f.r_c_t)),
            ("RA", mag(f.r_a)),
            ("RB", mag(f.r_b)),
            ("RC", mag(f.r_c)),
            ("RO", mag(f.r_o)),
        ] {
            let (got, unit, half) = value_of(name);
            assert_eq!(unit, "N");
            assert!((got - want).abs() <= half * (1.0 + 1e-9), "{name}: {got} vs {want}");
            assert!(half <= 5e-4 * want.abs().max(1.0), "{name}: {got} printed to fewer than 4 significant digits");
        }
        let (me1, unit, half) = value_of("Me1");
        assert_eq!(unit, "N·m");
        assert!((me1 - f.me1).abs() <= half * (1.0 + 1e-9), "Me1: {me1} vs {}", f.me1);
    }
}

#[test]
fn a_ternary_couplers_images_are_closed_triangles() {
    // M off the line AB (α = 150°): the velocity image abm and the acceleration image a′b′m′
    // are triangles, all three sides drawn.
    let (frames, _, motion, layout) = template(&["alpha_deg=150", "phi1_deg.step=45"]);
    for (i, (d, pos)) in frames.iter().zip(&motion.positions).enumerate() {
        let k = pos.kin.unwrap();
        for (which, layer, [a, b, m]) in
            [(0, "VELOCITY", [k.v_a, k.v_b, k.v_m]), (1, "ACCELERATION", [k.a_a, k.a_b, k.a_m])]
        {
            let (scale, pole) = place(&layout, i, pos, which);
            let l = d.layers.iter().position(|x| x.name == layer).unwrap();
            let at = |v: Vector| pole + scale.draw(v);
            let segs: Vec<(Point, Point)> = d
                .entities
                .iter()
                .filter(|e| e.layer == l)
                .filter_map(|e| match e.shape {
                    Shape::Line { from, to } | Shape::Arrow { from, to, .. } => Some((from, to)),
                    _ => None,
                })
                .collect();
            let near = |p: Point, q: Point| (p - q).norm() < 1e-9;
            let joined = |p: Point, q: Point| {
                segs.iter().any(|(f, t)| (near(*f, p) && near(*t, q)) || (near(*f, q) && near(*t, p)))
            };
            for (p, q, side) in [(a, b, "ab"), (b, m, "bm"), (a, m, "am")] {
                assert!(joined(at(p), at(q)), "{layer} at {}°: no side {side}", pos.phi1.to_degrees());
            }
        }
    }
}

#[test]
fn the_velocity_polygon_shows_the_directions_that_locate_b() {
    // ⊥AB through a, ⊥BC through p: dashed lines through b on the construction layer.
    let (frames, spec, motion, layout) = template(&["phi1_deg.step=30"]);
    for (i, (d, pos)) in frames.iter().zip(&motion.positions).enumerate() {
        let (sv, pole) = place(&layout, i, pos, 0);
        let k = pos.kin.unwrap();
        let (a, b) = (pole + sv.draw(k.v_a), pole + sv.draw(k.v_b));
        let con = d.layers.iter().position(|x| x.name == "CONSTRUCTION").unwrap();
        let lines: Vec<(Point, Point)> = d
            .entities
            .iter()
            .filter(|e| e.layer == con)
            .filter_map(|e| match e.shape {
                Shape::Line { from, to } => Some((from, to)),
                _ => None,
            })
            .collect();
        let cross = |u: Vector, v: Vector| u.x * v.y - u.y * v.x;
        let through = |p: Point, q: Point, dir: Vector| {
            lines.iter().any(|(f, t)| {
                let u = (t - f).normalize();
                cross(u, dir.normalize()).abs() < 1e-9
                    && cross(u, p - f).abs() < 1e-9 * (t - f).norm()
                    && cross(u, q - f).abs() < 1e-9 * (t - f).norm()
            })
        };
        let perp = |v: Vector| Vector::new(-v.y, v.x);
        assert!(through(a, b, perp(pos.b - pos.a)), "no ⊥AB through a and b at {}°", pos.phi1.to_degrees());
        assert!(
            through(pole, b, perp(pos.b - spec.geometry.c)),
            "no ⊥BC through p and b at {}°",
            pos.phi1.to_degrees()
        );
    }
}
