//! The mechanism as the report's drawings show it: the linkage figure (bodies, joints,
//! traced points) with what a kinematic diagram adds — the links' numbers (1 … n in the
//! solver's order, the frame 0), the driver's angular velocity with its sense, the loads —
//! and its placement on paper at a nice length scale.
//!
//! A four-bar scene comes here as a linkage of three bodies (crank, coupler, rocker), so
//! that every kind's report draws its mechanism with one vocabulary.

use crate::draw::{Bounds, Drawing, HAlign, Shape, VAlign, parts};
use crate::figure::linkage::{self as fig, LinkageFigure};
use crate::figure::shared::labels::{self, TextBox};
use crate::figure::shared::sheet;
use crate::figure::shared::vocab::{self, Sizes, layer_of, layers};
use crate::geom::{Point, Vector, perp};
use crate::solve::linkage::{Anchor, Attach, place};

/// The driver as the diagram marks it: an arc arrow about its pivot.
#[derive(Debug, Clone, PartialEq)]
pub struct DriverMark {
    /// The driven body.
    pub body: usize,
    /// Its pivot (a point of the body at the joint that carries it).
    pub pivot: Anchor,
    /// +1 counter-clockwise, −1 clockwise.
    pub sense: f64,
    /// Its symbol with its value (`ω1 = 20 rad/s`).
    pub symbol: String,
}

/// A load as the diagram marks it: an arrow (not to scale) at its point, along it.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadMark {
    /// Where it acts.
    pub at: Anchor,
    /// Its direction (global; any length).
    pub direction: Vector,
    /// Its name (`F`, `cut`).
    pub name: String,
}

/// The mechanism for the report's drawings.
#[derive(Debug, Clone, PartialEq)]
pub struct Sketch {
    /// Bodies, joints, traced points (model units).
    pub figure: LinkageFigure,
    /// The bodies' names, in the solver's order (link k + 1 is body k).
    pub names: Vec<String>,
    /// The driver, when it turns a body.
    pub driver: Option<DriverMark>,
    /// The loads.
    pub loads: Vec<LoadMark>,
}

/// A mechanism placed on paper: model point p at `origin + p / k_l` (paper mm).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OnPaper {
    /// Model length units per paper millimetre (a nice value).
    pub k_l: f64,
    /// The paper point of the model's origin.
    pub origin: Point,
}

impl OnPaper {
    /// A model point on paper.
    pub fn point(&self, p: Point) -> Point {
        self.origin + p.coords / self.k_l
    }

    /// An anchor of the model as the figure on paper holds it ([`LinkageFigure::on_paper`]):
    /// a body's point scaled, a ground point placed.
    pub fn anchor(&self, a: Anchor) -> Anchor {
        match a.body {
            Attach::Ground => Anchor { body: a.body, local: self.point(Point::from(a.local)).coords },
            Attach::Body(_) => Anchor { body: a.body, local: a.local / self.k_l },
        }
    }
}

impl Sketch {
    /// The smallest box holding every body point over `motion` (model units).
    pub fn extent(&self, motion: &[&[f64]]) -> Option<(Vector, Vector)> {
        let mut b: Option<(Vector, Vector)> = None;
        for q in motion {
            for (i, body) in self.figure.bodies.iter().enumerate() {
                for (_, v) in &body.points {
                    let p = place(q, Attach::Body(i), *v).coords;
                    if p.x.is_finite() && p.y.is_finite() {
                        b = Some(b.map_or((p, p), |(lo, hi)| (lo.inf(&p), hi.sup(&p))));
                    }
                }
            }
        }
        for j in &self.figure.joints {
            if let fig::JointSymbol::Pin { at, .. } = j
                && at.body == Attach::Ground
            {
                b = b.map(|(lo, hi)| (lo.inf(&at.local), hi.sup(&at.local)));
            }
        }
        b
    }
}

impl Sketch {
    /// [`Sketch::extent`] at `q` with the ground guides as long as `motion` needs them (a
    /// slider's whole travel): what a diagram of one position draws.
    pub fn extent_with_guides(&self, q: &[f64], motion: &[&[f64]], s: Sizes) -> Option<(Vector, Vector)> {
        let mut b = self.extent(&[q])?;
        let bare = Sizes { slider_length: 0.0, ..s };
        for (a, c) in fig::guide_spans(&self.figure, motion, &bare).into_iter().flatten() {
            for p in [a.coords, c.coords] {
                if p.x.is_finite() && p.y.is_finite() {
                    b = (b.0.inf(&p), b.1.sup(&p));
                }
            }
        }
        Some(b)
    }
}

/// The placement that draws `lo`…`hi` (model units) centred in `area` at the finest drafting
/// scale ([`vocab::drafting_scale`], as the sheets draw a mechanism) leaving `room` paper mm on each side (for symbols and letters).
pub fn fit(lo: Vector, hi: Vector, area: Bounds, room: Vector) -> OnPaper {
    let inner = Vector::new(
        (area.width() - 2.0 * room.x).max(0.3 * area.width()),
        (area.height() - 2.0 * room.y).max(0.3 * area.height()),
    );
    let full = ((hi - lo).x / inner.x).max((hi - lo).y / inner.y);
    let k_l = vocab::drafting_scale(full);
    OnPaper { k_l, origin: sheet::centre(lo, hi, k_l, area) }
}

/// The room a mechanism drawing keeps around its links for symbols and letters, paper mm.
pub fn room(s: Sizes) -> Vector {
    Vector::new(2.5 * s.text + s.slider_length, 2.5 * s.text + s.ground)
}

/// What a mechanism drawing marks besides the links, joints and point names.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Marks {
    /// The links' numbers in circles (the frame's 0 at a ground pivot).
    pub numbers: bool,
    /// The driver's ω with its sense.
    pub driver: bool,
    /// The loads' arrows.
    pub loads: bool,
}

/// Where a mechanism is drawn: its placement on paper, the sizes of its symbols, the area
/// its letters stay in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// The placement.
    pub at: OnPaper,
    /// Sizes of letters and symbols, paper mm.
    pub sizes: Sizes,
    /// The area its letters stay inside (its panel's).
    pub area: Bounds,
}

/// Draws the mechanism of `sketch` at `q` (model coordinates) on the page `d` (paper mm)
/// in `frame`, the ground guides as long as `motion` needs them, with `marks`.
pub fn draw(d: &mut Drawing, sketch: &Sketch, q: &[f64], motion: &[&[f64]], frame: Frame, marks: Marks) {
    let Frame { at, sizes: s, area } = frame;
    let paper_fig = sketch.figure.on_paper(at.origin, at.k_l);
    let pq = fig::on_paper(q, at.origin, at.k_l);
    let paper_motion: Vec<Vec<f64>> = motion.iter().map(|m| fig::on_paper(m, at.origin, at.k_l)).collect();
    let mut refs: Vec<&[f64]> = paper_motion.iter().map(Vec::as_slice).collect();
    if refs.is_empty() {
        refs.push(&pq);
    }
    let spans = fig::guide_spans(&paper_fig, &refs, &s);
    let start = d.entities.len();
    let mech = layer_of(d, layers::MECHANISM);
    fig::mechanism(d, mech, &paper_fig, &pq, &spans, &s);
    if marks.numbers {
        // The linkage figure numbers its links for the sheets; the diagram places them itself.
        strip_link_numbers(d, start, s.text);
    }
    if marks == Marks::default() {
        return;
    }
    // Names and the frame's ⓪ kept the numbers' gap apart from each other and from the
    // link numbers (a ⓪ touching a ① read as one mark).
    let gap = NUMBER_GAP * s.text;
    let grown = |b: TextBox| TextBox { min: b.min - Vector::new(gap, gap), max: b.max + Vector::new(gap, gap) };
    let mut letters = labels::Polygon::of_names().apart(gap);
    avoid(d, start, &mut letters);
    // The points' names drawn with the mechanism, as far as the numbers keep from them.
    for e in &d.entities[start.min(d.entities.len())..] {
        if let Shape::Text { .. } = e.shape {
            letters.keep_off(grown(text_box(&e.shape)));
        }
    }
    keep_inside(&mut letters, area);
    // The loads' arrows and the driver's arc first, their names placed last: the numbers
    // keep off the arrows and the arc, the names off the numbers.
    let mut names: Vec<(Point, labels::Label, Vector)> = Vec::new();
    if marks.loads {
        names.extend(load_arrows(d, sketch, (&paper_fig, &pq), at, s, &mut letters));
    }
    if let (true, Some(dm)) = (marks.driver, &sketch.driver) {
        names.push(driver_arc(d, (&paper_fig, &pq), dm, at, start, s, &mut letters));
    }
    if marks.numbers {
        // The numbers: the page's subject, each at its own link.
        number_links(d, (mech, start), &mut letters, &paper_fig, &pq, s);
        let ground = paper_fig.joints.iter().find_map(|j| match j {
            fig::JointSymbol::Pin { at: a, grounded: true, .. } => Some(place(&pq, a.body, a.local)),
            _ => None,
        });
        if let Some(p) = ground {
            let foot = p - Vector::new(0.0, s.joint + s.ground);
            letters.circled(foot, "0", s.text, Vector::new(-1.0, -0.5), 0.8 * s.ground);
        }
    }
    for (p, name, dir) in names {
        letters.letter(p, name, s.text, dir, None);
    }
    letters.draw(d, mech);
}

/// Gap kept between a name, the frame's ⓪ and a link number, in letter heights (a ⓪
/// touching a ① reads as one mark).
const NUMBER_GAP: f64 = 0.5;

/// Draws the loads' arrows of `sketch` (not to scale: a fixed length on paper, the tip at
/// the point or at the edge of the symbol drawn there, a slider's block, on the line of
/// action) on the forces' layer of `d` for the figure on paper `(fig, pq)`, `letters`
/// keeping off them; returns where each name goes (its point, name, side).
fn load_arrows(
    d: &mut Drawing,
    sketch: &Sketch,
    (fig, pq): (&LinkageFigure, &[f64]),
    at: OnPaper,
    s: Sizes,
    letters: &mut labels::Polygon,
) -> Vec<(Point, labels::Label, Vector)> {
    let frc = layer_of(d, layers::FORCES);
    let symbols = crate::figure::linkage::sheet::symbols(fig, pq, s);
    let mut names = Vec::new();
    for load in &sketch.loads {
        let a = at.anchor(load.at);
        let p = place(pq, a.body, a.local);
        let u = vocab::unit_or(load.direction, Vector::new(0.0, -1.0));
        let near = |x: Point| (x - p).norm() <= 1e-9 * (1.0 + p.coords.norm());
        let edge = symbols
            .iter()
            .filter(|x| near(x.at()))
            .map(|x| x.reach(-u) + crate::figure::shared::clear_forces::SYMBOL_GAP * s.head)
            .fold(0.0, f64::max);
        let to = p - u * edge;
        let from = to - u * (6.0 * s.text);
        d.add(frc, Shape::Arrow { from, to, head: s.head });
        letters.segment(from, to);
        names.push((from, labels::Label::from(load.name.as_str()), -u));
    }
    names
}

/// Draws the driver's arc arrow `dm` about its pivot on the mechanism's layer of `d`
/// (beside the crank, turned on round the pivot until it crosses no name and no line drawn
/// since entity `start`), `letters` keeping off its square; returns where its symbol goes.
fn driver_arc(
    d: &mut Drawing,
    (fig, pq): (&LinkageFigure, &[f64]),
    dm: &DriverMark,
    at: OnPaper,
    start: usize,
    s: Sizes,
    letters: &mut labels::Polygon,
) -> (Point, labels::Label, Vector) {
    let mech = layer_of(d, layers::MECHANISM);
    let pa = at.anchor(dm.pivot);
    let pivot = place(pq, pa.body, pa.local);
    let pin = body_far_point(fig, pq, dm.body, pivot);
    let crank_dir = libm::atan2((pin - pivot).y, (pin - pivot).x);
    let r = 4.0 * s.joint;
    let sweep = 1.6 * dm.sense;
    let from = (0..6)
        .map(|k| crank_dir + (0.35 + 0.25 * std::f64::consts::PI * k as f64) * dm.sense)
        .find(|&from| arc_is_clear(d, start, pivot, r, from, sweep, s.joint))
        .unwrap_or(crank_dir + 0.35 * dm.sense);
    let mid = vocab::turn_arrow(d, mech, pivot, r, from, sweep, s);
    letters.keep_off(TextBox { min: pivot - Vector::new(r, r), max: pivot + Vector::new(r, r) });
    (mid, labels::Label::quantity(&dm.symbol), mid - pivot)
}

/// Removes the circled link numbers drawn since entity `start` (a circle of
/// [`labels::CIRCLE_RADIUS`] letter heights and the number centred in it).
fn strip_link_numbers(d: &mut Drawing, start: usize, height: f64) {
    let r = labels::CIRCLE_RADIUS * height;
    let same = |a: Point, b: Point| (a - b).norm() <= 1e-9 * (1.0 + a.coords.norm());
    let centres: Vec<Point> = d.entities[start.min(d.entities.len())..]
        .iter()
        .filter_map(|e| match e.shape {
            Shape::Circle { center, radius } if (radius - r).abs() <= 1e-9 * r => Some(center),
            _ => None,
        })
        .collect();
    let mut k = 0;
    d.entities.retain(|e| {
        k += 1;
        if k <= start {
            return true;
        }
        match &e.shape {
            Shape::Circle { center, radius } => !((radius - r).abs() <= 1e-9 * r && centres.contains(center)),
            Shape::Text { at, value, .. } => {
                !(value.chars().all(|c| c.is_ascii_digit()) && centres.iter().any(|c| same(*c, *at)))
            }
            _ => true,
        }
    });
}

/// Least clearance from every joint (paper mm, in letter heights) at which a link's number
/// is anchored on its side; a side with none that clear takes its clearest place.
const NUMBER_CLEARANCE: f64 = 4.0;

/// Where each moving link's number goes, for the letter placer: anchored at its link —
/// inside a plate (three or more points not in a line) at its centroid; on a bar, along
/// its longest side where it is clearest of the joints and points (its middle when that is
/// [`NUMBER_CLEARANCE`] letters from them), preferably on the side away from the
/// mechanism's middle; at a one-point body's point (a slider's block) beside the block.
/// The placer puts each in a circle beside its anchor, off every line and letter
/// ([`labels::Polygon::circled`]), nearer its own link than any other (up to
/// [`NUMBER_TRIES`] places turned down); each is drawn on `layer` of `d` and kept off by
/// the letters placed after it.
fn number_links(
    d: &mut Drawing,
    (layer, start): (usize, usize),
    letters: &mut labels::Polygon,
    fig: &LinkageFigure,
    pq: &[f64],
    s: Sizes,
) {
    let joints: Vec<Point> = fig
        .joints
        .iter()
        .map(|j| match j {
            fig::JointSymbol::Pin { at, .. } => place(pq, at.body, at.local),
            fig::JointSymbol::Slider { point, .. } => place(pq, point.body, point.local),
        })
        .collect();
    let body_points =
        |i: usize| -> Vec<Point> { fig.bodies[i].points.iter().map(|(_, v)| place(pq, Attach::Body(i), *v)).collect() };
    let all: Vec<Point> = (0..fig.bodies.len()).flat_map(body_points).collect();
    let centre = Point::from(all.iter().map(|p| p.coords).sum::<Vector>() / all.len().max(1) as f64);
    // Clear of the joints and of every named point (a coupler's point on its bar).
    let clearance = |x: Point| joints.iter().chain(&all).map(|j| (j - x).norm()).fold(f64::INFINITY, f64::min);
    let (segments, mut boxes) = drawn(d, start);
    // How far a point is from body b's link (its sides; a block: its point).
    let from_link = |x: Point, b: usize| -> f64 {
        let pts = body_points(b);
        match pts.as_slice() {
            [] => f64::INFINITY,
            [p] => (x - p).norm(),
            _ => pts.windows(2).map(|w| vocab::distance_to_segment(x, w[0], w[1])).fold(f64::INFINITY, f64::min),
        }
    };
    for i in 0..fig.bodies.len() {
        let pts = body_points(i);
        let Some((at, dir, clear)) = number_anchor(&pts, centre, &clearance, s) else { continue };
        let text = (i + 1).to_string();
        // The placer's place for it; where that is nearer another link (a short crank
        // beside the long link it drives), that place is kept off and the next taken.
        // A place on a line or over a letter is never taken for one at its own link.
        let block = pts.len() == 1;
        let mut tried: Vec<TextBox> = Vec::new();
        let (mut first, mut first_clear) = (None, None);
        let chosen = loop {
            let mut trial = letters.clone();
            for b in &tried {
                trial.keep_off(*b);
            }
            trial.circled(at, &text, s.text, dir, clear);
            let Some(p) = trial.place().pop() else { break None };
            let own = from_link(p.centre, i);
            let at_own = block || (0..fig.bodies.len()).all(|b| b == i || from_link(p.centre, b) > own);
            let bx = p.bounds();
            let clear_of = !segments.iter().any(|(a, b)| bx.crosses(*a, *b)) && !boxes.iter().any(|b| b.overlaps(&bx));
            if at_own && clear_of {
                break Some(p);
            }
            if tried.len() >= NUMBER_TRIES {
                break first_clear.or(first).or(Some(p));
            }
            tried.push(bx);
            if clear_of {
                first_clear.get_or_insert(p.clone());
            }
            first.get_or_insert(p);
        };
        if let Some(p) = chosen {
            labels::draw_placed(d, layer, &p, None);
            letters.keep_off(p.bounds());
            boxes.push(p.bounds());
        }
    }
}

/// What is drawn in `d` from entity `start` on, as a link's number must keep off it: every
/// stroke as segments, every text's box.
fn drawn(d: &Drawing, start: usize) -> (Vec<labels::Segment>, Vec<TextBox>) {
    let (mut segments, mut boxes) = (Vec::new(), Vec::new());
    for e in &d.entities[start.min(d.entities.len())..] {
        match &e.shape {
            text @ Shape::Text { .. } => boxes.push(text_box(text)),
            other => segments.extend(labels::strokes(other)),
        }
    }
    (segments, boxes)
}

/// How many places of the placer's a link's number may turn down for being nearer
/// another link than its own ([`number_links`]).
const NUMBER_TRIES: usize = 8;

/// A link's number's anchor, preferred side and clearance ([`number_links`]) for a body
/// whose points on paper are `pts`.
fn number_anchor(
    pts: &[Point],
    centre: Point,
    clearance: &dyn Fn(Point) -> f64,
    s: Sizes,
) -> Option<(Point, Vector, f64)> {
    let r = labels::CIRCLE_RADIUS * s.text;
    match pts {
        [] => None,
        // A block: clear of it along its guide too (half its length).
        [p] => Some((*p, Vector::new(-1.0, 1.0), 0.5 * s.slider_length)),
        _ => {
            let n = pts.len();
            // Twice the plate's area: points in a line (a coupler ABM) make a bar.
            let area2: f64 = (0..n)
                .map(|k| {
                    let (a, b) = (pts[k], pts[(k + 1) % n]);
                    a.x * b.y - b.x * a.y
                })
                .sum();
            let c = Point::from(pts.iter().map(|p| p.coords).sum::<Vector>() / n as f64);
            if n >= 3 && area2.abs() > 4.0 * (2.0 * r) * (2.0 * r) {
                return Some((c, Vector::new(0.0, 1.0), 0.0));
            }
            let (a, b) = pts
                .windows(2)
                .map(|w| (w[0], w[1]))
                .max_by(|x, y| (x.1 - x.0).norm().total_cmp(&(y.1 - y.0).norm()))?;
            let along = [0.5, 0.38, 0.62, 0.28, 0.72].map(|t| a + (b - a) * t);
            let at = along.iter().copied().find(|x| clearance(*x) >= NUMBER_CLEARANCE * s.text).unwrap_or_else(|| {
                along.iter().copied().fold(along[0], |m, x| if clearance(x) > clearance(m) { x } else { m })
            });
            let mut nrm = perp(vocab::unit_or(b - a, Vector::new(1.0, 0.0)));
            if nrm.dot(&(at - centre)) < 0.0 {
                nrm = -nrm;
            }
            Some((at, nrm, 0.5 * s.link))
        }
    }
}

/// The point of body `b` (on paper at `pq`) farthest from `from`: a crank's pin seen from
/// its pivot.
fn body_far_point(fig: &LinkageFigure, pq: &[f64], b: usize, from: Point) -> Point {
    fig.bodies
        .get(b)
        .into_iter()
        .flat_map(|body| body.points.iter().map(|(_, v)| place(pq, Attach::Body(b), *v)))
        .fold(from + Vector::new(1.0, 0.0), |best, p| if (p - from).norm() > (best - from).norm() { p } else { best })
}

/// Keeps `letters` inside `area`: four wide boxes around it that they must not overlap.
pub fn keep_inside(letters: &mut labels::Polygon, area: Bounds) {
    let big = 1e4 * (area.width() + area.height()).max(1.0);
    let (lo, hi) = (area.min, area.max);
    for b in [
        TextBox { min: Point::new(lo.x - big, lo.y - big), max: Point::new(lo.x, hi.y + big) },
        TextBox { min: Point::new(hi.x, lo.y - big), max: Point::new(hi.x + big, hi.y + big) },
        TextBox { min: Point::new(lo.x - big, lo.y - big), max: Point::new(hi.x + big, lo.y) },
        TextBox { min: Point::new(lo.x - big, hi.y), max: Point::new(hi.x + big, hi.y + big) },
    ] {
        letters.keep_off(b);
    }
}

/// Adds what is drawn in `d` from entity `start` on to `letters` as what its letters keep
/// off: every stroke as segments (circles and arcs as chords), every text's box, the
/// dimensions as drawn.
pub fn avoid(d: &Drawing, start: usize, letters: &mut labels::Polygon) {
    for e in &d.entities[start.min(d.entities.len())..] {
        match &e.shape {
            dim @ (Shape::AngularDimension { .. } | Shape::LinearDimension { .. }) => {
                for part in parts::explode_dimension(dim, &d.dim_style) {
                    avoid_shape(&part, letters);
                }
            }
            other => avoid_shape(other, letters),
        }
    }
}

/// [`avoid`] for one shape.
fn avoid_shape(shape: &Shape, letters: &mut labels::Polygon) {
    match shape {
        Shape::Line { from, to } | Shape::Arrow { from, to, .. } => letters.segment(*from, *to),
        Shape::Polyline { points, closed, .. } => {
            for w in points.windows(2) {
                letters.segment(w[0], w[1]);
            }
            if *closed && let (Some(a), Some(b)) = (points.last(), points.first()) {
                letters.segment(*a, *b);
            }
        }
        Shape::Filled { points } => {
            for (k, a) in points.iter().enumerate() {
                letters.segment(*a, points[(k + 1) % points.len()]);
            }
        }
        Shape::Circle { center, radius } => {
            chords(letters, *center, *radius, 0.0, std::f64::consts::TAU);
            // A circled link number's circle is its label's square: no letter in it.
            letters.keep_off(TextBox {
                min: center - Vector::new(*radius, *radius),
                max: center + Vector::new(*radius, *radius),
            });
        }
        Shape::Arc { center, radius, start, end } => {
            chords(letters, *center, *radius, *start, parts::arc_sweep(*start, *end))
        }
        Shape::Text { .. } => letters.keep_off(text_box(shape)),
        _ => {}
    }
}

/// Whether the arc about `c` of radius `r` from `from` sweeping `sweep` keeps `gap` (paper
/// mm) off every text and line drawn since entity `start` other than those through `c`
/// itself (the crank, the pivot's circle).
fn arc_is_clear(d: &Drawing, start: usize, c: Point, r: f64, from: f64, sweep: f64, gap: f64) -> bool {
    let n = 24;
    let pts: Vec<Point> = (0..=n)
        .map(|k| {
            let a = from + sweep * k as f64 / n as f64;
            c + Vector::new(libm::cos(a), libm::sin(a)) * r
        })
        .collect();
    let near_segment = |a: Point, b: Point| {
        // A line ending at the pivot (the crank, the pivot's symbol's sides) is the pivot's.
        if (a - c).norm() < 0.5 * r || (b - c).norm() < 0.5 * r {
            return false;
        }
        pts.iter().any(|p| vocab::distance_to_segment(*p, a, b) < gap)
    };
    d.entities[start..].iter().all(|e| match &e.shape {
        Shape::Text { .. } => {
            let b = text_box(&e.shape);
            !pts.iter()
                .any(|p| p.x > b.min.x - gap && p.x < b.max.x + gap && p.y > b.min.y - gap && p.y < b.max.y + gap)
        }
        Shape::Line { from, to } => !near_segment(*from, *to),
        Shape::Polyline { points, .. } => !points.windows(2).any(|w| near_segment(w[0], w[1])),
        _ => true,
    })
}

/// The arc as 16 chords a turn.
fn chords(letters: &mut labels::Polygon, c: Point, r: f64, start: f64, sweep: f64) {
    let n = ((sweep.abs() / (std::f64::consts::TAU / 16.0)).ceil() as usize).max(1);
    let at = |k: usize| {
        let a = start + sweep * k as f64 / n as f64;
        c + Vector::new(libm::cos(a), libm::sin(a)) * r
    };
    for k in 0..n {
        letters.segment(at(k), at(k + 1));
    }
}

/// The box a text shape covers (its width measured with the bundled font; from a third of
/// its height under the baseline to its cap height), unrotated texts; a rotated text's box
/// is its extent around the insertion point.
pub fn text_box(shape: &Shape) -> TextBox {
    let Shape::Text { at, height, value, halign, valign, rotation, .. } = shape else {
        return TextBox { min: Point::origin(), max: Point::origin() };
    };
    let w = parts::text_width(value, *height);
    if *rotation != 0.0 {
        let r = w + *height;
        return TextBox { min: at - Vector::new(r, r), max: at + Vector::new(r, r) };
    }
    let x0 = match halign {
        HAlign::Left => at.x,
        HAlign::Center => at.x - 0.5 * w,
        HAlign::Right => at.x - w,
    };
    let base = match valign {
        VAlign::Baseline => at.y,
        VAlign::Middle => at.y - 0.5 * height,
        VAlign::Top => at.y - height,
    };
    TextBox { min: Point::new(x0, base - 0.3 * height), max: Point::new(x0 + w, base + 1.05 * height) }
}
