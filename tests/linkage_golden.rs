//! Golden images of the shaper: one frame (t = 0.125 s, crank at 45°: bodies, joints, the
//! slider on the rocker, the ram on its hatched guide, ground pivots, names, and the path
//! of E), and the displacement diagram of the ram point E (sE against φ1, the seed's Fig. 9
//! as a textbook draws it).

mod common;

use mechdraw::draw::svg::{SvgOptions, to_string};
use mechdraw::figure::linkage::{LinkageFigure, frame, guide_spans, paper_style};
use mechdraw::scene::linkage::MeasureTarget;
use mechdraw::scene::{self, Scene};
use mechdraw::solve::linkage::Solver;

#[test]
fn shaper_frame_045_golden_png() {
    let loaded = scene::load(&common::root().join("templates/shaper.toml"), &[]).unwrap();
    let Scene::Linkage(s) = loaded.scene else { panic!() };
    let states = Solver::new(s.mechanism.clone()).unwrap().run(&s.times).unwrap();
    let motion: Vec<&[f64]> = states.iter().map(|st| st.q.as_slice()).collect();
    // The figure as the linkage run builds it: the point names, the measured points traced.
    let traced = s.measures.iter().filter_map(|m| if let MeasureTarget::Point(a) = m.target { Some(a) } else { None });
    let fig = LinkageFigure::new(&s.mechanism, |a| s.point_name(a), traced.collect());
    let style = paper_style(&fig, &motion);
    let spans = guide_spans(&fig, &motion, &style);
    let d = frame(&fig, &motion, &states[45].q, &spans, &style);
    common::assert_golden_png("linkage/shaper_frame_045.png", &to_string(&d, &SvgOptions::default()));
}

#[test]
fn shaper_e_displacement_diagram_golden_png() {
    let loaded = scene::load(&common::root().join("templates/shaper.toml"), &[]).unwrap();
    let p = mechdraw::run::products(&loaded, &mechdraw::run::RunOptions::default()).unwrap();
    let d = &p.diagrams.iter().find(|d| d.stem == "E.x").expect("the E.x diagram").drawing;
    // As the run writes it (run::bytes: the SVG writer's default options).
    common::assert_golden_png("linkage/shaper_E_displacement.png", &to_string(d, &SvgOptions::default()));
}
