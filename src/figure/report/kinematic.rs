//! The kinematic diagram page: the mechanism at one position drawn to the standard's
//! symbols at a stated nice k_l — links as lines (a plate for three or more joints),
//! revolute joints as circles, the frame's pivots with the support and hatching, ground
//! guides hatched, sliders as blocks, the links numbered 1 … n and the frame 0, the driver's
//! ω with its sense, the loads as arrows (not to scale) — with its scale bar, and beside it
//! the lists of links, joints and loads.

use crate::draw::{Bounds, Drawing};
use crate::figure::report::page::{self, PageTitle, ReportFrame};
use crate::figure::report::sketch::{self, Marks, OnPaper, Sketch};
use crate::geom::{Point, Vector};

/// What the kinematic diagram page shows.
#[derive(Debug, Clone)]
pub struct KinematicPage<'a> {
    /// The mechanism.
    pub sketch: &'a Sketch,
    /// The position drawn (x, y, φ per body, model units).
    pub q: &'a [f64],
    /// Every position of the motion (for the guides' lengths).
    pub motion: &'a [&'a [f64]],
    /// Which position it is (`φ1 = 0°`).
    pub position: String,
    /// The length unit (`mm`, `m`).
    pub unit: &'a str,
    /// The lists beside the diagram: links, joints, loads.
    pub lists: Vec<String>,
}

/// Share of the content's width the diagram's panel takes.
const DIAGRAM_SHARE: f64 = 0.68;

/// The kinematic diagram page; returns it with its k_l.
pub fn page(frame: &ReportFrame, title: &PageTitle, p: &KinematicPage) -> (Drawing, f64) {
    let s = frame.sizes;
    let c = frame.content;
    let split = c.min.x + DIAGRAM_SHARE * c.width();
    let left = Bounds { min: c.min, max: Point::new(split, c.max.y) };
    let right = Bounds { min: Point::new(split, c.min.y), max: c.max };
    let (lo, hi) = p.sketch.extent(&[p.q]).unwrap_or((Vector::zeros(), Vector::new(1.0, 1.0)));
    // The panel's area, its title and its scale bar's strip known before the scale.
    let probe = page::panel_area(left, true, s);
    let at: OnPaper = sketch::fit(lo, hi, probe, sketch::room(s) + Vector::new(0.0, 2.0 * s.text));
    let mut title = title.clone();
    let k_text = format!("k_l = {} {}/mm", page::plain(at.k_l), p.unit);
    title.cells = vec![k_text.clone(), p.position.clone()];
    let mut d = frame.page(&title);
    let area = page::panel(&mut d, left, &format!("Kinematic diagram at {}   {k_text}", p.position), s);
    sketch::draw(
        &mut d,
        p.sketch,
        p.q,
        p.motion,
        sketch::Frame { at, sizes: s, area },
        Marks { numbers: true, driver: true, loads: true },
    );
    page::scale_bar_and_notes(
        &mut d,
        area,
        at.k_l,
        p.unit,
        right,
        "Links, joints and loads",
        &p.lists,
        0.9 * s.text,
        s,
    );
    (d, at.k_l)
}
