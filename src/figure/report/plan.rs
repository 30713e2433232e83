//! The plan of positions: the mechanism's positions of the plan superimposed at one k_l
//! (the first drawn whole with its names, the others in thin lines), each numbered at the
//! point that names it (the crank pin), the traced points' paths, the extreme (dead)
//! positions dashed in red and named, the strokes between them dimensioned, and the
//! working and return strokes with the time ratio K written beside the plan.

use crate::draw::{Aci, Bounds, Drawing, Entity, LineType, Shape};
use crate::figure::linkage as fig;
use crate::figure::report::page::{self, PageTitle, ReportFrame};
use crate::figure::report::sketch::{self, Marks, Sketch};
use crate::figure::shared::labels;
use crate::figure::shared::vocab::{Sizes, layer_of, layers};
use crate::geom::{Point, Vector};
use crate::solve::linkage::{Anchor, Attach, place};

/// A dimension on the plan, between two model points (a stroke H) or an angle at a vertex
/// (the crank's working angle, the rocker's swing).
#[derive(Debug, Clone, PartialEq)]
pub enum PlanDimension {
    /// A distance along `direction` between `from` and `to`, labelled `text`.
    Stroke {
        /// One extreme (model).
        from: Point,
        /// The other (model).
        to: Point,
        /// The text (`H = 500 mm`).
        text: String,
    },
    /// The angle at `vertex` from the ray to `first` counter-clockwise to the ray to
    /// `second`, labelled `text`.
    Angle {
        /// The vertex (model).
        vertex: Point,
        /// A point on the first ray.
        first: Point,
        /// A point on the second ray.
        second: Point,
        /// The text (`θ = 192.4°`).
        text: String,
    },
}

/// What the plan page shows.
#[derive(Debug, Clone)]
pub struct PlanPage<'a> {
    /// The mechanism.
    pub sketch: &'a Sketch,
    /// Every position of the motion (the paths, the guides).
    pub motion: &'a [&'a [f64]],
    /// The plan's positions in order: (number, coordinates).
    pub plan: Vec<(String, Vec<f64>)>,
    /// The extreme positions: (name, coordinates).
    pub dead: Vec<(String, Vec<f64>)>,
    /// The point the positions are numbered at (the crank pin).
    pub numbered: Option<Anchor>,
    /// Dimensions of the strokes and angles.
    pub dimensions: Vec<PlanDimension>,
    /// Lines beside the plan: the strokes, K, the positions' drive values.
    pub notes: Vec<String>,
    /// The length unit.
    pub unit: &'a str,
}

/// Share of the content's width the plan's panel takes.
const PLAN_SHARE: f64 = 0.7;

/// Draws a position in thin lines: each body's outline, its joints as small circles.
fn thin(d: &mut Drawing, layer: usize, f: &fig::LinkageFigure, q: &[f64], color: Aci, linetype: LineType, s: Sizes) {
    for (i, b) in f.bodies.iter().enumerate() {
        let pts: Vec<Point> = b.points.iter().map(|(_, v)| place(q, Attach::Body(i), *v)).collect();
        if pts.len() >= 2 {
            let closed = pts.len() >= 3;
            d.push(Entity {
                layer,
                color: Some(color),
                linetype: Some(linetype),
                shape: Shape::Polyline { points: pts, closed, width: 0.0 },
            });
        }
    }
    for j in &f.joints {
        if let fig::JointSymbol::Pin { at, .. } = j {
            let p = place(q, at.body, at.local);
            d.push(Entity {
                layer,
                color: Some(color),
                linetype: Some(LineType::Continuous),
                shape: Shape::Circle { center: p, radius: 0.5 * s.joint },
            });
        }
    }
}

/// The plan page; returns it with its k_l.
pub fn page(frame: &ReportFrame, title: &PageTitle, p: &PlanPage) -> (Drawing, f64) {
    let s = frame.sizes;
    let c = frame.content;
    let split = c.min.x + PLAN_SHARE * c.width();
    let left = Bounds { min: c.min, max: Point::new(split, c.max.y) };
    let right = Bounds { min: Point::new(split, c.min.y), max: c.max };
    let (lo, hi) = p.sketch.extent(p.motion).unwrap_or((Vector::zeros(), Vector::new(1.0, 1.0)));
    let probe = page::panel_area(left, true, s);
    let at = sketch::fit(lo, hi, probe, sketch::room(s) + Vector::new(2.0 * s.text, 3.0 * s.text));
    let k_text = format!("k_l = {} {}/mm", page::plain(at.k_l), p.unit);
    let mut title = title.clone();
    title.cells = vec![k_text.clone(), format!("{} positions", p.plan.len())];
    let mut d = frame.page(&title);
    let area = page::panel(&mut d, left, &format!("Plan of positions   {k_text}"), s);
    let paper_fig = p.sketch.figure.on_paper(at.origin, at.k_l);
    let paper_motion: Vec<Vec<f64>> = p.motion.iter().map(|q| fig::on_paper(q, at.origin, at.k_l)).collect();
    let refs: Vec<&[f64]> = paper_motion.iter().map(Vec::as_slice).collect();
    let start = d.entities.len();
    let paths = layer_of(&d, layers::COUPLER_CURVE);
    fig::trajectories(&mut d, paths, &paper_fig, &refs);
    let mech = layer_of(&d, layers::MECHANISM);
    for (_, q) in p.plan.iter().skip(1) {
        thin(&mut d, mech, &paper_fig, &fig::on_paper(q, at.origin, at.k_l), Aci::DARK_GREY, LineType::Continuous, s);
    }
    for (_, q) in &p.dead {
        thin(&mut d, mech, &paper_fig, &fig::on_paper(q, at.origin, at.k_l), Aci::RED, LineType::Dashed, s);
    }
    if let Some((_, q0)) = p.plan.first() {
        sketch::draw(&mut d, p.sketch, q0, p.motion, sketch::Frame { at, sizes: s, area }, Marks::default());
    }
    let dims = layer_of(&d, layers::DIMENSIONS);
    // The dimensions' texts, the positions' numbers and the extremes' names placed together,
    // clear of every line drawn.
    let mut letters = labels::Polygon::of_names();
    let mut dim_letters = labels::Polygon::of_names();
    for dim in &p.dimensions {
        dimension(&mut d, dims, dim, at, &mut dim_letters, s);
    }
    sketch::avoid(&d, start, &mut dim_letters);
    sketch::keep_inside(&mut dim_letters, area);
    dim_letters.draw(&mut d, dims);
    sketch::avoid(&d, start, &mut letters);
    sketch::keep_inside(&mut letters, area);
    if let Some(a) = p.numbered.map(|a| at.anchor(a)) {
        let centre = |q: &[f64]| place(&fig::on_paper(q, at.origin, at.k_l), a.body, a.local);
        let mid = p.plan.iter().map(|(_, q)| centre(q).coords).fold(Vector::zeros(), |m, v| m + v)
            / p.plan.len().max(1) as f64;
        for (name, q) in &p.plan {
            let pt = centre(q);
            letters.letter(pt, name, s.small_text(), pt.coords - mid, None);
        }
        for (name, q) in &p.dead {
            let pt = centre(q);
            letters.name_with_leader(pt, name, s.small_text(), pt.coords - mid, Some(Aci::RED));
        }
    }
    letters.draw(&mut d, mech);
    page::scale_bar_and_notes(
        &mut d,
        area,
        at.k_l,
        p.unit,
        right,
        "Positions, strokes, time ratio",
        &p.notes,
        0.85 * s.text,
        s,
    );
    (d, at.k_l)
}

/// A dimension of the plan, on paper: its lines and arrowheads drawn, its text given to
/// `letters` (placed with the plan's numbers, clear of every line).
fn dimension(
    d: &mut Drawing,
    layer: usize,
    dim: &PlanDimension,
    at: sketch::OnPaper,
    letters: &mut labels::Polygon,
    s: Sizes,
) {
    let head = |d: &mut Drawing, tip: Point, dir: Vector| {
        let u = crate::figure::shared::vocab::unit_or(dir, Vector::new(1.0, 0.0));
        let base = tip - u * s.head;
        let n = crate::geom::perp(u) * (s.head * crate::draw::parts::ARROW_HALF_WIDTH);
        d.add(layer, Shape::Filled { points: vec![tip, base + n, base - n] });
    };
    match dim {
        PlanDimension::Stroke { from, to, text } => {
            let (a, b) = (at.point(*from), at.point(*to));
            let u = crate::figure::shared::vocab::unit_or(b - a, Vector::new(1.0, 0.0));
            // The dimension line three letters off the stroke, on its left, with extension lines.
            let n = crate::geom::perp(u) * (3.0 * s.text);
            let (a2, b2) = (a + n, b + n);
            for (p, q) in [(a, a2), (b, b2)] {
                d.add(layer, Shape::Line { from: p + n * 0.15, to: q + n * 0.2 });
            }
            d.add(layer, Shape::Line { from: a2, to: b2 });
            head(d, a2, a2 - b2);
            head(d, b2, b2 - a2);
            letters.segment(a2, b2);
            letters.letter(Point::from((a2.coords + b2.coords) / 2.0), text, s.text, n, None);
        }
        PlanDimension::Angle { vertex, first, second, text } => {
            let (v, f1, f2) = (at.point(*vertex), at.point(*first), at.point(*second));
            let r = 0.7 * (f1 - v).norm().min((f2 - v).norm()).max(4.0 * s.text);
            let (a1, a2) = (libm::atan2((f1 - v).y, (f1 - v).x), libm::atan2((f2 - v).y, (f2 - v).x));
            let sweep = crate::draw::parts::arc_sweep(a1, a2);
            d.add(layer, Shape::Arc { center: v, radius: r, start: a1, end: a1 + sweep });
            let tangent = |a: f64| Vector::new(-libm::sin(a), libm::cos(a));
            head(d, v + Vector::new(libm::cos(a1), libm::sin(a1)) * r, -tangent(a1));
            head(d, v + Vector::new(libm::cos(a1 + sweep), libm::sin(a1 + sweep)) * r, tangent(a1 + sweep));
            let mid = a1 + 0.5 * sweep;
            let on = v + Vector::new(libm::cos(mid), libm::sin(mid)) * r;
            letters.letter(on, text, s.text, on - v, None);
        }
    }
}
