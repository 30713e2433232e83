//! The kinematic diagram page: the mechanism at one position drawn to the standard's
//! symbols at a stated nice k_l — links as lines (a plate for three or more joints),
//! revolute joints as circles, the frame's pivots with the support and hatching, ground
//! guides hatched, sliders as blocks, the links numbered 1 … n and the frame 0, the driver's
//! ω with its sense, the loads as arrows (not to scale) — with its scale bar, and beside it
//! the lists of links, joints and loads.

use crate::draw::{Bounds, Drawing, HAlign, Shape};
use crate::figure::linkage as fig;
use crate::figure::report::page::{self, PageTitle, ReportFrame};
use crate::figure::report::sketch::{self, Marks, OnPaper, Sketch};
use crate::figure::shared::labels;
use crate::figure::shared::sheet;
use crate::figure::shared::vocab::{self, Sizes, layer_of, layers};
use crate::geom::{Point, Vector};
use crate::solve::linkage::{Attach, place};

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
    /// The report's drafting scale for the mechanism, when it holds one (the position
    /// pages' k_l, so that the same drawing has the same scale): the diagram is drawn at
    /// the coarser of it and its own ([`scale`]).
    pub held: Option<f64>,
}

/// Where the diagram goes: the wide panel (over the lists) or the tall one (beside them),
/// and its placement at its own finest k_l.
fn arrangement(frame: &ReportFrame, p: &KinematicPage) -> (bool, Bounds, OnPaper) {
    let s = frame.sizes;
    let room = sketch::room(s) + Vector::new(0.0, 2.0 * s.text);
    // Two layouts, the one drawing the mechanism larger kept: a tall panel beside the lists
    // (a four-bar, a shaper), or a wide one over them (a slider-crank's long guide).
    let c = frame.content;
    let (tall, _) = frame.tall_left();
    let split = c.min.y + WIDE_LISTS_SHARE * c.height();
    let wide = Bounds { min: Point::new(c.min.x, split), max: c.max };
    let at_tall = placement(p, page::panel_area(tall, true, s), room, s);
    let at_wide = placement(p, page::panel_area(wide, true, s), room, s);
    let is_wide = at_wide.k_l < at_tall.k_l;
    if is_wide { (true, wide, at_wide) } else { (false, tall, at_tall) }
}

/// The finest drafting scale at which the diagram fits its page (without a held scale).
pub fn scale(frame: &ReportFrame, p: &KinematicPage) -> f64 {
    arrangement(frame, p).2.k_l
}

/// The kinematic diagram page; returns it with its k_l. The diagram's panel runs from the
/// border's top to its bottom beside the title block (the mechanism the page's largest
/// figure); the lists stand in the column above the title block.
pub fn page(frame: &ReportFrame, title: &PageTitle, p: &KinematicPage) -> (Drawing, f64) {
    let s = frame.sizes;
    let c = frame.content;
    let (_, right) = frame.tall_left();
    let split = c.min.y + WIDE_LISTS_SHARE * c.height();
    let (is_wide, left, mut at) = arrangement(frame, p);
    if let Some(k) = p.held.filter(|&k| k > at.k_l) {
        // The held scale is coarser: the same drawing, smaller, centred where it was.
        let mid = page::panel_area(left, true, s);
        let centre = Point::new(0.5 * (mid.min.x + mid.max.x), 0.5 * (mid.min.y + mid.max.y));
        let model = (centre - at.origin) * at.k_l;
        at = OnPaper { k_l: k, origin: centre - model / k };
    }
    let mut title = title.clone();
    let k_text = format!("k_l = {} {}/mm", page::plain(at.k_l), p.unit);
    title.cells = vec![k_text.clone(), p.position.clone()];
    let mut d = if is_wide { frame.page(&title) } else { frame.open_page(&title) };
    let area = page::panel(&mut d, left, &format!("Kinematic diagram at {}   {k_text}", p.position), s);
    sketch::draw(
        &mut d,
        p.sketch,
        p.q,
        p.motion,
        sketch::Frame { at, sizes: s, area },
        Marks { numbers: true, driver: true, loads: true },
    );
    let (lists, symbols) = if is_wide {
        let below = Bounds { min: c.min, max: Point::new(c.max.x, split) };
        let cols = page::columns(below, 2, 0.0);
        (cols[0], Some(cols[1]))
    } else {
        (right, None)
    };
    page::scale_bar_and_notes(
        &mut d,
        area,
        at.k_l,
        p.unit,
        lists,
        "Links, joints and loads",
        &p.lists,
        0.9 * s.text,
        s,
    );
    let legend_area = match symbols {
        Some(b) => page::panel(&mut d, b, "", s),
        None => page::panel_area(lists, true, s),
    };
    legend(&mut d, legend_area, p.sketch, s);
    (d, at.k_l)
}

/// Share of the content's height the lists take under a wide diagram.
const WIDE_LISTS_SHARE: f64 = 0.4;

/// Length of a load's arrow on the diagram (not to scale) with room for its name, in
/// letter heights ([`sketch::draw`] draws the arrow 6 high).
const LOAD_REACH: f64 = 8.0;

/// The finest drafting scale at which the mechanism at `p.q` (its guides as long as the
/// motion needs), with its loads' arrows, fits `area` leaving `room`; centred.
fn placement(p: &KinematicPage, area: Bounds, room: Vector, s: Sizes) -> OnPaper {
    let (lo, hi) = p.sketch.extent_with_guides(p.q, p.motion, s).unwrap_or((Vector::zeros(), Vector::new(1.0, 1.0)));
    let mut at = sketch::fit(lo, hi, area, room);
    let inner = Vector::new(area.width() - 2.0 * room.x, area.height() - 2.0 * room.y);
    for _ in 0..8 {
        // The loads' tails at this scale, in model units.
        let (mut a, mut b) = (lo, hi);
        for load in &p.sketch.loads {
            let at_point = place(p.q, load.at.body, load.at.local).coords;
            let u = vocab::unit_or(load.direction, Vector::new(0.0, -1.0));
            let tail = at_point - u * (LOAD_REACH * s.text * at.k_l);
            (a, b) = (a.inf(&tail), b.sup(&tail));
        }
        let size = (b - a) / at.k_l;
        if size.x <= inner.x.max(0.3 * area.width()) && size.y <= inner.y.max(0.3 * area.height()) {
            return OnPaper { k_l: at.k_l, origin: sheet::centre(a, b, at.k_l, area) };
        }
        at.k_l = vocab::coarser_drafting_scale(at.k_l);
    }
    at
}

/// The symbols the diagram uses, each drawn with what it means, from the bottom of `area`
/// (the lists' panel) up: the joints, the frame's pivot, a slider on a guide and a ground
/// guide where the mechanism has them, a link's number, the driver's sense, a load.
fn legend(d: &mut Drawing, area: Bounds, sk: &Sketch, s: Sizes) {
    let sliders = sk.figure.joints.iter().filter(|j| matches!(j, fig::JointSymbol::Slider { .. })).count();
    let ground_guides = sk
        .figure
        .joints
        .iter()
        .filter(|j| matches!(j, fig::JointSymbol::Slider { q1, .. } if q1.body == Attach::Ground))
        .count();
    type Row = (&'static str, fn(&mut Drawing, usize, Point, Sizes));
    let mut rows: Vec<Row> = vec![
        ("revolute joint (lower pair, p₅)", |d, l, p, s| vocab::joint(d, l, p, s)),
        ("pivot on the frame 0 (hatched)", |d, l, p, s| vocab::ground(d, l, p + Vector::new(0.0, 0.5 * s.ground), s)),
    ];
    if sliders > 0 {
        rows.push(("slider on its guide (prismatic pair, p₅)", |d, l, p, s| {
            let u = Vector::new(1.0, 0.0);
            d.add(l, Shape::Line { from: p - u * (1.2 * s.slider_length), to: p + u * (1.2 * s.slider_length) });
            vocab::slider(d, l, p, u, s);
        }));
    }
    if ground_guides > 0 {
        rows.push(("guide fixed to the frame", |d, l, p, s| {
            let u = Vector::new(1.0, 0.0);
            vocab::guide(d, l, p - u * (1.4 * s.slider_length), p + u * (1.4 * s.slider_length), s);
        }));
    }
    rows.push(("link number", |d, l, p, s| {
        let placed = labels::Placed {
            centre: p,
            text: "1".into(),
            runs: Default::default(),
            height: s.text,
            color: None,
            leader: None,
            circled: true,
        };
        labels::draw_placed(d, l, &placed, None);
    }));
    if sk.driver.is_some() {
        rows.push(("the driver's sense of rotation", |d, l, p, s| {
            vocab::turn_arrow(d, l, p, 1.6 * s.joint + 0.3 * s.text, 0.3, 2.2, s);
        }));
    }
    if !sk.loads.is_empty() {
        rows.push(("load (direction only, not to scale)", |d, l, p, s| {
            let u = Vector::new(1.0, 0.0);
            let f = layer_of(d, layers::FORCES);
            let _ = l;
            d.add(
                f,
                Shape::Arrow {
                    from: p - u * (1.4 * s.slider_length),
                    to: p + u * (1.4 * s.slider_length),
                    head: s.head,
                },
            );
        }));
    }
    let step = 2.6 * s.text;
    let mech = layer_of(d, layers::MECHANISM);
    let sheet = page::sheet_layer(d);
    let x_symbol = area.min.x + 2.2 * s.slider_length;
    let x_text = area.min.x + 4.8 * s.slider_length;
    for (k, (what, draw)) in rows.iter().rev().enumerate() {
        let y = area.min.y + (k as f64 + 0.6) * step;
        draw(d, mech, Point::new(x_symbol, y), s);
        page::text(d, sheet, Point::new(x_text, y), 0.9 * s.text, *what, HAlign::Left);
    }
    let y = area.min.y + (rows.len() as f64 + 0.4) * step;
    page::text(d, sheet, Point::new(area.min.x, y), s.text, "Symbols", HAlign::Left);
}
