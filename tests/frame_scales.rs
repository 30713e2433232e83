//! Frames readable at every position (issue 31, item 2): with the default scales per frame,
//! at every position of every template that animates polygons, every polygon and every force
//! figure spans at least half of its panel's drawing area (and stays inside it, but for a
//! resultant drawn beside a side it would lie on: up to two arrowheads out), and each
//! frame's printed scale measures true: the longest vector drawn from a polygon's pole,
//! measured on the frame's paper and multiplied by the scale printed in its title, is the
//! solver's largest velocity (acceleration) of the polygon's points drawn from the pole, to
//! 1e-9 (both polygons of the four-bar and of every linkage). After a change (the live
//! page), each polygon keeps its earlier scale until it would leave its panel or fill less
//! than half of it. With
//! `[frames] scales = "fixed"` one scale serves the whole run.

mod common;

use mechdraw::draw::{Drawing, Shape};
use mechdraw::figure::fourbar::{Layout, ModelUnits, Show};
use mechdraw::figure::linkage::LinkageFigure;
use mechdraw::figure::linkage::frame::{LinkageFrames, RunForces, Show as LinkageShow};
use mechdraw::figure::shared::panels::{PanelFrame, ScaleChoice, Slot};
use mechdraw::geom::{Point, Vector};
use mechdraw::scene::linkage::MeasureTarget;
use mechdraw::scene::{self, Scene};
use mechdraw::solve::fourbar::solve_motion;
use mechdraw::solve::linkage::Solver;

/// The points drawn on `layer` (ends of arrows and lines) inside `area` grown by a tenth.
fn drawn_extent(d: &Drawing, layer: &str, area: mechdraw::draw::Bounds) -> Option<(Point, Point)> {
    let l = d.layers.iter().position(|x| x.name == layer)?;
    let (gx, gy) = (0.1 * area.width(), 0.1 * area.height());
    let inside =
        |p: Point| p.x >= area.min.x - gx && p.x <= area.max.x + gx && p.y >= area.min.y - gy && p.y <= area.max.y + gy;
    let mut e: Option<(Point, Point)> = None;
    // Leader lines (grey) tie names to their vectors: not part of the figure.
    let leader = Some(mechdraw::figure::shared::labels::LEADER_COLOR);
    for ent in d.entities.iter().filter(|x| x.layer == l && x.color != leader) {
        if let Shape::Arrow { from, to, .. } | Shape::Line { from, to } = ent.shape {
            for p in [from, to].into_iter().filter(|p| inside(*p)) {
                e = Some(match e {
                    None => (p, p),
                    Some((lo, hi)) => {
                        (Point::new(lo.x.min(p.x), lo.y.min(p.y)), Point::new(hi.x.max(p.x), hi.y.max(p.y)))
                    }
                });
            }
        }
    }
    e
}

/// The scale printed after `symbol = ` in the text of `d` starting with `title`.
fn printed(d: &Drawing, title: &str, symbol: &str) -> f64 {
    let text = d
        .entities
        .iter()
        .find_map(|e| match e.shape.scale_text_in(None).as_ref().unwrap_or(&e.shape) {
            Shape::Text { value, .. } if value.starts_with(title) => Some(value.clone()),
            _ => None,
        })
        .unwrap_or_else(|| panic!("no text {title}"));
    text.split(&format!("{symbol} = ")).nth(1).unwrap().split_whitespace().next().unwrap().parse().unwrap()
}

/// The fill of `slot`'s area by the polygon drawn on `layer` in `d`: its tighter direction.
/// The figure stays inside the area, but for a resultant drawn beside a side it would lie
/// on (at most two arrowheads out).
fn fill(d: &Drawing, layer: &str, slot: &Slot) -> f64 {
    let (lo, hi) = drawn_extent(d, layer, slot.area).expect("a drawn polygon");
    let a = slot.area;
    let out = 2.0 * d.dim_style.arrow_size;
    let inside = lo.x >= a.min.x - out && hi.x <= a.max.x + out && lo.y >= a.min.y - out && hi.y <= a.max.y + out;
    assert!(inside, "outside its area: {lo:?} {hi:?} {a:?}");
    ((hi.x - lo.x) / a.width()).max((hi.y - lo.y) / a.height())
}

/// Checks one frame: every slot's polygon fills half to all of its area, and the printed
/// scales are the slots' scales for this frame. Returns the printed (k_v, k_a).
fn check_frame(what: &str, d: &Drawing, frame: &PanelFrame, k: usize) -> (Option<f64>, Option<f64>) {
    let scales = frame.scales_at(k);
    let mut out = (None, None);
    for (slot, layer, title, symbol, stored, into) in [
        (&frame.velocity, "VELOCITY", "Velocity polygon", "k_v", scales.k_v, &mut out.0),
        (&frame.acceleration, "ACCELERATION", "Acceleration polygon", "k_a", scales.k_a, &mut out.1),
    ] {
        let Some(slot) = slot else { continue };
        let f = fill(d, layer, slot);
        assert!((0.5 - 1e-9..=1.05).contains(&f), "{what} frame {k}: {layer} fills {f:.3} of its panel");
        let k_printed = printed(d, title, symbol);
        assert_eq!(Some(k_printed), stored, "{what} frame {k}: {title}");
        *into = Some(k_printed);
    }
    if let Some(cells) = &frame.forces {
        for (slot, k_f) in cells.figures.iter().zip(&scales.k_f) {
            assert_eq!(printed(d, &slot.title, "k_f"), *k_f, "{what} frame {k}: {}", slot.title);
            let f = fill(d, "FORCES", slot);
            assert!((0.5 - 1e-9..=1.05).contains(&f), "{what} frame {k}: {} fills {f:.3}", slot.title);
        }
    }
    out
}

/// The longest arrow from `pole` on `layer`, paper mm.
fn longest_from(d: &Drawing, layer: &str, pole: Point) -> f64 {
    let l = d.layers.iter().position(|x| x.name == layer).unwrap();
    let paper = d.paper_mm_per_unit.unwrap();
    d.entities
        .iter()
        .filter(|e| e.layer == l)
        .filter_map(|e| match e.shape {
            Shape::Arrow { from, to, .. } if (from - pole).norm() < 1e-9 * (to - from).norm() => {
                Some((to - from).norm())
            }
            _ => None,
        })
        .fold(0.0, f64::max)
        * paper
}

#[test]
fn the_four_bar_frames_fill_their_panels_at_printed_scales_that_measure_true() {
    let loaded = scene::load(&common::root().join("templates/fourbar-chebyshev.toml"), &[]).unwrap();
    let Scene::Fourbar(s) = loaded.scene else { panic!() };
    let motion = solve_motion(&s.spec).unwrap();
    let show = Show { velocity: true, acceleration: true, forces: true, scales: ScaleChoice::PerFrame };
    let lay = Layout::new(&s.spec.geometry, &motion.positions, Some(&motion.forces), show, ModelUnits::SI);
    let mut steps = 0;
    let mut last = None;
    for (k, pos) in motion.positions.iter().enumerate() {
        let d = lay.moving(k, &s.spec.geometry, pos, Some(&motion.forces[k]));
        let (k_v, k_a) = check_frame("four-bar", &d, &lay.frame, k);
        // Measured: the longest velocity from p is the largest of |v_A|, |v_B|, |v_M|.
        let kin = pos.kin.unwrap();
        let (v, a) = lay.polygon_places(k, pos);
        let (pv, pa) = (v.unwrap().1, a.unwrap().1);
        let v_max = [kin.v_a, kin.v_b, kin.v_m].iter().map(|v| v.norm()).fold(0.0, f64::max);
        let measured = longest_from(&d, "VELOCITY", pv) * k_v.unwrap();
        assert!((measured - v_max).abs() <= 1e-9 * v_max, "frame {k}: {measured} vs {v_max}");
        let a_max = [kin.a_a, kin.a_b, kin.a_m, kin.a_g21, kin.a_g22].iter().map(|v| v.norm()).fold(0.0, f64::max);
        let measured = longest_from(&d, "ACCELERATION", pa) * k_a.unwrap();
        assert!((measured - a_max).abs() <= 1e-9 * a_max, "frame {k}: {measured} vs {a_max}");
        steps += usize::from(last.is_some_and(|l| l != (k_v, k_a)));
        last = Some((k_v, k_a));
    }
    // The scales change in steps, not at every frame.
    assert!(steps > 0 && steps < 60, "{steps} changes over {} frames", motion.positions.len());
    // Fixed: one scale for the run.
    let show = Show { scales: ScaleChoice::Fixed, ..show };
    let lay = Layout::new(&s.spec.geometry, &motion.positions, Some(&motion.forces), show, ModelUnits::SI);
    let first = lay.frame.scales_at(0);
    assert!(first.k_v.is_some());
    assert_eq!(lay.frame.scales_at(200), first);
}

#[test]
fn every_linkage_frame_fills_its_panels_at_printed_scales_that_measure_true() {
    for t in common::template_paths() {
        let loaded = scene::load(&t, &[]).unwrap();
        let Scene::Linkage(s) = loaded.scene else { continue };
        let stem = t.file_stem().unwrap().to_string_lossy().to_string();
        let mech = &s.mechanism;
        let (states, forces) = match &s.dynamics {
            Some(d) => {
                let (st, f) = Solver::new(mech.clone()).unwrap().run_kinetostatics(&s.times, d).unwrap();
                (st, Some(f))
            }
            None => (Solver::new(mech.clone()).unwrap().run(&s.times).unwrap(), None),
        };
        let traced = s
            .measures
            .iter()
            .filter_map(|m| match m.target {
                MeasureTarget::Point(a) => Some(a),
                MeasureTarget::Body(_) => None,
            })
            .collect();
        let fig = LinkageFigure::new(mech, |a| s.point_name(a), traced);
        let run_forces =
            s.dynamics.as_ref().zip(forces.as_deref()).map(|(dynamics, forces)| RunForces { dynamics, forces });
        let frames = LinkageFrames::new(&fig, mech, &states, run_forces, LinkageShow::default());
        for (k, st) in states.iter().enumerate() {
            let force = s.dynamics.as_ref().zip(forces.as_ref().map(|f| &f[k]));
            let d = frames.moving(k, &fig, mech, st, force);
            let (k_v, k_a) = check_frame(&stem, &d, &frames.frame, k);
            // Measured: the longest velocity (acceleration) from the pole is the largest of
            // the points drawn from it.
            let poly = mechdraw::figure::linkage::polygon::polygons(mech, st);
            for (p, slot, layer, printed) in [
                (&poly.velocity, &frames.frame.velocity, "VELOCITY", k_v),
                (&poly.acceleration, &frames.frame.acceleration, "ACCELERATION", k_a),
            ] {
                let largest = p.points.iter().filter(|p| p.from == 0).map(|p| p.v.norm()).fold(0.0, f64::max);
                let extent = mechdraw::figure::shared::panels::Extent::of(p.physical_points());
                let (_, pole) = slot.as_ref().unwrap().place(k, extent, frames.frame.k_l);
                let measured = longest_from(&d, layer, pole) * printed.unwrap();
                assert!(
                    (measured - largest).abs() <= 1e-9 * largest.max(1e-300),
                    "{stem} frame {k}: {layer} {measured} vs {largest}"
                );
            }
        }
        let _ = Vector::zeros();
    }
}

#[test]
fn after_a_change_each_polygon_keeps_its_scale_until_it_would_leave_or_shrink_under_half_its_panel() {
    // The live page's choice (PanelFrame::hold): the four-bar at ω1 = 20 rad/s, then at 23
    // (velocities 1.15 times, accelerations 1.3225 times, the forces changed).
    let path = common::root().join("templates/fourbar-chebyshev.toml");
    let layout = |omega1: &str| {
        let over = ["phi1_deg.step=10".parse().unwrap(), format!("omega1={omega1}").parse().unwrap()];
        let Scene::Fourbar(s) = scene::load(&path, &over).unwrap().scene else { panic!() };
        let motion = solve_motion(&s.spec).unwrap();
        let show = Show { velocity: true, acceleration: true, forces: true, scales: ScaleChoice::PerFrame };
        let lay = Layout::new(&s.spec.geometry, &motion.positions, Some(&motion.forces), show, ModelUnits::SI);
        (s, motion, lay)
    };
    let (_, first, lay0) = layout("20.0");
    let before: Vec<_> = (0..first.positions.len()).map(|k| lay0.frame.scales_at(k)).collect();
    let (s, motion, mut lay) = layout("23.0");
    let fresh: Vec<_> = (0..motion.positions.len()).map(|k| lay.frame.scales_at(k)).collect();
    lay.frame.hold(&before);
    let (mut kept, mut fresh_kept) = (0, 0);
    for (k, pos) in motion.positions.iter().enumerate() {
        let d = lay.moving(k, &s.spec.geometry, pos, Some(&motion.forces[k]));
        // Every polygon and force figure fills half to all of its panel, its printed scale
        // the one held.
        check_frame("held", &d, &lay.frame, k);
        let now = lay.frame.scales_at(k);
        for (layer, slot, was, is, fresh) in [
            ("VELOCITY", &lay.frame.velocity, before[k].k_v, now.k_v, fresh[k].k_v),
            ("ACCELERATION", &lay.frame.acceleration, before[k].k_a, now.k_a, fresh[k].k_a),
        ] {
            let (was, is) = (was.unwrap(), is.unwrap());
            fresh_kept += usize::from(fresh == Some(was));
            if was == is {
                kept += 1;
                continue;
            }
            // Re-chosen only where at the earlier scale it would have left its panel or
            // filled less than half of it.
            let at_was = fill(&d, layer, slot.as_ref().unwrap()) * is / was;
            assert!(
                !(0.5 + 1e-9..=1.0 - 1e-9).contains(&at_was),
                "frame {k}: {layer} re-chosen ({was} → {is}) though it fills {at_was:.3} at {was}"
            );
        }
    }
    assert!(kept > fresh_kept, "{kept} scales held, a fresh run keeps {fresh_kept}");
}
