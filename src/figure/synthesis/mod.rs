//! The synthesis constructions, drawn as a textbook draws them: what is given (blue), the
//! construction lines and circles (dashed), the mechanism found in one position (solid, its
//! pivots hatched) and in its other required positions (thin grey), every point lettered,
//! every angle dimensioned with its name and value, every length the construction finds
//! written on its segment (`b − a`, `2a`), a caption with the steps and the answer, and the
//! length scale with its bar. One module per task; the [`Construction`] builder here is what
//! they share, on top of the shared vocabulary (figure/shared).
//!
//! Layers: `GIVEN` (the requirement), `CONSTRUCTION` (dashed), `POSITIONS` (the mechanism
//! in its other positions), `FORBIDDEN` (where the pivot must not go, red), `MECHANISM`,
//! `DIMENSIONS`, `TEXT`.

pub mod crank_rocker;
pub mod function;
pub mod motion;
pub mod quick_return;
pub mod slider_crank;

use crate::draw::parts::explode_dimension;
use crate::draw::{Bounds, DimStyle, Drawing, Shape};
use crate::figure::shared::construction::{DIMENSION_RADII, arc_segments, caption, free_direction, length_scale_block};
use crate::figure::shared::labels::{self, TextBox};
use crate::figure::shared::vocab::{self, ModelUnits, Sizes};
use crate::geom::{Point, Vector, angle_of, normalize_angle, perp, polar};

/// Largest extent of a construction on paper, millimetres (it fits A4 with its caption).
pub const FIGURE_MM: f64 = 160.0;

/// Width of a thin line of the other positions, paper millimetres.
const POSITION_WIDTH_MM: f64 = 0.25;

/// Colours and line types of the construction's layers: (name, colour, line type).
mod layer {
    use crate::draw::{Aci, LineType};
    pub const GIVEN: (&str, Aci, LineType) = ("GIVEN", Aci::BLUE, LineType::Continuous);
    pub const CONSTRUCTION: (&str, Aci, LineType) = ("CONSTRUCTION", Aci::DARK_GREY, LineType::Dashed);
    pub const POSITIONS: (&str, Aci, LineType) = ("POSITIONS", Aci::DARK_GREY, LineType::Continuous);
    pub const FORBIDDEN: (&str, Aci, LineType) = ("FORBIDDEN", Aci::RED, LineType::Continuous);
    pub const MECHANISM: (&str, Aci, LineType) = ("MECHANISM", Aci::BLACK, LineType::Continuous);
    pub const DIMENSIONS: (&str, Aci, LineType) = ("DIMENSIONS", Aci::BLACK, LineType::Continuous);
    pub const TEXT: (&str, Aci, LineType) = ("TEXT", Aci::BLACK, LineType::Continuous);
}

/// What a line is drawn as.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    /// The requirement: blue, continuous.
    Given,
    /// A construction line: grey, dashed.
    Construction,
    /// The mechanism in another position: grey, thin.
    Position,
    /// Where the pivot must not go: red.
    Forbidden,
    /// The mechanism: black.
    Mechanism,
}

/// A construction being drawn: the drawing on paper at a nice scale, and everything drawn
/// so far that letters and dimension texts keep off.
#[derive(Debug)]
pub struct Construction {
    d: Drawing,
    /// Sizes on paper.
    pub s: Sizes,
    k_l: f64,
    units: ModelUnits,
    layers: [usize; 7],
    lines: Vec<(Point, Point)>,
    points: Vec<(Point, String)>,
    names: Vec<(Point, String, Vector)>,
    keep_off: Vec<TextBox>,
    /// Angles waiting to be dimensioned once every line is drawn: (vertex, first ray's
    /// point, second's, preferred radius, text).
    angles: Vec<(Point, Point, Point, f64, String)>,
}

impl Construction {
    /// A construction of a figure covering `extent` (model units), in `units`.
    pub fn new(extent: Bounds, units: ModelUnits) -> Construction {
        let k_l = vocab::length_scale(extent.width().max(extent.height()).max(f64::MIN_POSITIVE), FIGURE_MM);
        let s = Sizes::on_paper(k_l);
        let mut d = Drawing::new(DimStyle { text_height: 0.85 * s.text, arrow_size: 0.75 * s.text });
        d.paper_mm_per_unit = Some(1.0 / k_l);
        let layers = [
            layer::GIVEN,
            layer::CONSTRUCTION,
            layer::POSITIONS,
            layer::FORBIDDEN,
            layer::MECHANISM,
            layer::DIMENSIONS,
            layer::TEXT,
        ]
        .map(|(n, c, l)| d.layer(n, c, l));
        Construction {
            d,
            s,
            k_l,
            units,
            layers,
            lines: Vec::new(),
            points: Vec::new(),
            names: Vec::new(),
            keep_off: Vec::new(),
            angles: Vec::new(),
        }
    }

    fn layer(&self, style: Style) -> usize {
        match style {
            Style::Given => self.layers[0],
            Style::Construction => self.layers[1],
            Style::Position => self.layers[2],
            Style::Forbidden => self.layers[3],
            Style::Mechanism => self.layers[4],
        }
    }

    fn dimensions(&self) -> usize {
        self.layers[5]
    }

    fn text(&self) -> usize {
        self.layers[6]
    }

    /// A straight line from `a` to `b`.
    pub fn line(&mut self, a: Point, b: Point, style: Style) {
        if (b - a).norm() > 0.0 {
            let layer = self.layer(style);
            self.d.add(layer, Shape::Line { from: a, to: b });
            self.lines.push((a, b));
        }
    }

    /// The line through `a` and `b` produced by `over` (model units) beyond both.
    pub fn line_produced(&mut self, a: Point, b: Point, over: f64, style: Style) {
        let u = (b - a).try_normalize(0.0).unwrap_or(Vector::new(1.0, 0.0));
        self.line(a - u * over, b + u * over, style);
    }

    /// A full circle.
    pub fn circle(&mut self, c: Point, r: f64, style: Style) {
        if r > 0.0 && r.is_finite() {
            let layer = self.layer(style);
            self.d.add(layer, Shape::Circle { center: c, radius: r });
            arc_segments(&mut self.lines, c, r, 0.0, std::f64::consts::TAU);
        }
    }

    /// The arc about `c` from `from` to `to` (points on it or rays), the shorter way round.
    pub fn arc(&mut self, c: Point, r: f64, from: Point, to: Point, style: Style) {
        let (a1, a2) = (angle_of(from - c), angle_of(to - c));
        let sweep = normalize_angle(a2 - a1);
        let (start, sweep) =
            if sweep <= std::f64::consts::PI { (a1, sweep) } else { (a2, std::f64::consts::TAU - sweep) };
        self.arc_ccw(c, r, start, sweep, style);
    }

    /// The arc about `c` from the angle `start` sweeping `sweep` ≥ 0 counter-clockwise.
    pub fn arc_ccw(&mut self, c: Point, r: f64, start: f64, sweep: f64, style: Style) {
        if r > 0.0 && sweep > 0.0 {
            let layer = self.layer(style);
            self.d.add(layer, Shape::Arc { center: c, radius: r, start, end: start + sweep });
            arc_segments(&mut self.lines, c, r, start, sweep);
        }
    }

    /// The shortest arc about `c` through every one of `points` (at radius `r`), widened by
    /// `margin` radians at both ends: a circle's part a construction needs.
    pub fn arc_through(&mut self, c: Point, r: f64, points: &[Point], margin: f64, style: Style) {
        let mut a: Vec<f64> = points.iter().map(|p| normalize_angle(angle_of(*p - c))).collect();
        if a.is_empty() {
            return;
        }
        a.sort_by(f64::total_cmp);
        // The widest gap between neighbours is left out.
        let (mut start, mut gap) = (a[0], a[0] + std::f64::consts::TAU - a[a.len() - 1]);
        for w in a.windows(2) {
            if w[1] - w[0] > gap {
                (start, gap) = (w[1], w[1] - w[0]);
            }
        }
        let sweep = std::f64::consts::TAU - gap;
        self.arc_ccw(c, r, start - margin, sweep + 2.0 * margin, style);
    }

    /// A thick arc (the forbidden arc): a wide polyline along it.
    pub fn thick_arc(&mut self, c: Point, r: f64, start: f64, sweep: f64, style: Style) {
        let n = 48;
        let points: Vec<Point> = (0..=n).map(|k| polar(c, r, start + sweep * k as f64 / n as f64)).collect();
        let layer = self.layer(style);
        vocab::link(&mut self.d, layer, points, false, None, self.s);
        arc_segments(&mut self.lines, c, r, start, sweep);
    }

    /// A link through `points`: wide for the mechanism, thin for another position.
    pub fn link(&mut self, points: &[Point], closed: bool, style: Style) {
        let layer = self.layer(style);
        let s = match style {
            Style::Mechanism => self.s,
            _ => Sizes { link: POSITION_WIDTH_MM * self.k_l, ..self.s },
        };
        vocab::link(&mut self.d, layer, points.to_vec(), closed, None, s);
        let n = points.len();
        let segs = if closed { n } else { n.saturating_sub(1) };
        for k in 0..segs {
            self.lines.push((points[k], points[(k + 1) % n]));
        }
    }

    /// A slider's block at `p` on a guide along the unit direction `u`.
    pub fn slider(&mut self, p: Point, u: Vector, style: Style) {
        let layer = self.layer(style);
        let (hl, hh) = vocab::slider(&mut self.d, layer, p, u, self.s);
        let n = perp(u);
        let corners = [p - u * hl - n * hh, p + u * hl - n * hh, p + u * hl + n * hh, p - u * hl + n * hh];
        for k in 0..4 {
            self.lines.push((corners[k], corners[(k + 1) % 4]));
        }
    }

    /// A guide fixed to the ground from `a` to `b` (hatched on its right-hand side).
    pub fn guide(&mut self, a: Point, b: Point) {
        let layer = self.layer(Style::Mechanism);
        vocab::guide(&mut self.d, layer, a, b, self.s);
        self.lines.push((a, b));
        // The hatch's band under the guide, for letters to keep off.
        let u = (b - a).try_normalize(0.0).unwrap_or(Vector::new(1.0, 0.0));
        let down = -perp(u);
        let (near, far) = (0.5 * self.s.slider_height, 0.5 * self.s.slider_height + 0.6 * self.s.ground);
        let corners = [a + down * near, b + down * near, a + down * far - u * self.s.ground, b + down * far];
        let (mut min, mut max) = (corners[0], corners[0]);
        for p in corners {
            min = Point::new(min.x.min(p.x), min.y.min(p.y));
            max = Point::new(max.x.max(p.x), max.y.max(p.y));
        }
        self.keep_off.push(TextBox { min, max });
    }

    /// A joint (a small circle) at `p`.
    pub fn joint(&mut self, p: Point, style: Style) {
        let layer = self.layer(style);
        let s = if style == Style::Mechanism { self.s } else { Sizes { joint: 0.7 * self.s.joint, ..self.s } };
        vocab::joint(&mut self.d, layer, p, s);
    }

    /// A ground pivot at `p`.
    pub fn pivot(&mut self, p: Point) {
        let layer = self.layer(Style::Mechanism);
        vocab::ground(&mut self.d, layer, p, self.s);
        self.keep_off.push(vocab::ground_extent(p, self.s));
    }

    /// A point of the construction (a small dot) with its letter.
    pub fn point(&mut self, p: Point, name: &str, style: Style) {
        let layer = self.layer(style);
        self.d.add(layer, Shape::Circle { center: p, radius: 0.3 * self.s.joint });
        self.letter(p, name);
    }

    /// The letter `name` for the point `p` (placed at the end, in the widest free direction
    /// around it).
    pub fn letter(&mut self, p: Point, name: &str) {
        self.points.push((p, name.to_string()));
    }

    /// A name beside the middle of the segment `a`–`b` (a length the construction finds:
    /// `b − a`, `2a`), on its left.
    pub fn segment_name(&mut self, a: Point, b: Point, name: &str) {
        let u = (b - a).try_normalize(0.0).unwrap_or(Vector::new(1.0, 0.0));
        self.names.push((a + 0.5 * (b - a), name.to_string(), perp(u)));
    }

    /// A name near `p`, preferably on the side `dir` (a circle's name).
    pub fn name(&mut self, p: Point, name: &str, dir: Vector) {
        self.names.push((p, name.to_string(), dir));
    }

    /// The angle at `vertex` between the rays to `a` and to `b` (the smaller one), drawn as
    /// an angular dimension with `text`, at about `radius` from the vertex: placed when the
    /// drawing is finished, clear of everything drawn by then ([`Construction::finish`]).
    pub fn angle(&mut self, vertex: Point, a: Point, b: Point, radius: f64, text: &str) {
        let sweep = normalize_angle(angle_of(b - vertex) - angle_of(a - vertex));
        let (first, second) = if sweep <= std::f64::consts::PI { (a, b) } else { (b, a) };
        self.angles.push((vertex, first, second, radius, text.to_string()));
    }

    /// The drawing as its ink lies: every dimension exploded into its lines, arcs,
    /// arrowheads and text, for letters and other dimensions to keep clear of.
    fn ink(&self) -> Drawing {
        let mut ink = self.d.clone();
        ink.entities = Vec::with_capacity(self.d.entities.len());
        for e in &self.d.entities {
            match &e.shape {
                dim @ (Shape::AngularDimension { .. } | Shape::LinearDimension { .. }) => {
                    for part in explode_dimension(dim, &self.d.dim_style) {
                        ink.push(crate::draw::Entity { shape: part, ..e.clone() });
                    }
                }
                _ => ink.push(e.clone()),
            }
        }
        ink
    }

    /// Every angle dimensioned, in the order asked for, each at the first of
    /// [`DIMENSION_RADII`] × its preferred radius where its text overlaps no text or symbol
    /// and no stroke crosses it, and its own arc and lines cross no text: against
    /// everything drawn, the dimensions placed before it included. An angle whose text
    /// names a value (`90° − θ = 54°`) and fits nowhere is tried with its name alone
    /// (`90° − θ`, the caption states what it follows from); else the least crowded place
    /// is taken (fewest overlaps, then fewest crossings).
    fn place_angles(&mut self) {
        let style = self.d.dim_style;
        for (vertex, first, second, radius, text) in std::mem::take(&mut self.angles) {
            let ink = self.ink();
            let mut strokes = Vec::new();
            let mut boxes = self.keep_off.clone();
            for e in &ink.entities {
                strokes.extend(labels::strokes(&e.shape));
                boxes.extend(corners_box(&e.shape));
            }
            let crowding = |dim: &Shape| {
                let parts = explode_dimension(dim, &style);
                let own: Vec<(Point, Point)> = parts.iter().flat_map(labels::strokes).collect();
                let Some(tb) = parts.iter().find_map(corners_box) else { return (0, 0) };
                let over = boxes.iter().filter(|b| b.overlaps(&tb)).count()
                    + boxes.iter().filter(|b| own.iter().any(|(u, v)| b.crosses(*u, *v))).count();
                (over, strokes.iter().filter(|(u, v)| tb.crosses(*u, *v)).count())
            };
            // The full text (`90° − θ = 54°`) where it fits, else the angle's name alone
            // (`90° − θ`: its value follows from the caption's), else the least crowded.
            let short = text.split(" = ").next().unwrap_or(&text).to_string();
            let texts = if short != text { vec![text.clone(), short] } else { vec![text.clone()] };
            // Placed with its flat text (the DXF's, the wider), then `φ1` drawn with its index
            // a subscript where the writer can (labels::with_dimension_runs).
            let dim_at = |r: f64, t: &str| Shape::AngularDimension {
                vertex,
                first,
                second,
                radius: r,
                text: t.to_string(),
                runs: Default::default(),
            };
            let mut best: Option<((usize, usize), Shape)> = None;
            'texts: for t in &texts {
                for k in DIMENSION_RADII {
                    let dim = dim_at(k * radius, t);
                    let score = crowding(&dim);
                    if best.as_ref().is_none_or(|(b, _)| score < *b) {
                        best = Some((score, dim));
                    }
                    if score == (0, 0) {
                        break 'texts;
                    }
                }
            }
            let layer = self.dimensions();
            let dim = best.map_or_else(|| dim_at(radius, &text), |(_, dim)| dim);
            self.d.add(layer, labels::with_dimension_runs(dim));
        }
    }

    /// A right-angle mark at `vertex` between the rays to `a` and to `b`.
    pub fn right_angle(&mut self, vertex: Point, a: Point, b: Point) {
        let size = 1.2 * self.s.text;
        let (u, v) = ((a - vertex).normalize() * size, (b - vertex).normalize() * size);
        let layer = self.dimensions();
        self.d.add(
            layer,
            Shape::Polyline { points: vec![vertex + u, vertex + u + v, vertex + v], closed: false, width: 0.0 },
        );
    }

    /// A linear dimension of the distance between `a` and `b` along their line, its line
    /// `offset` (model units) to the left of a → b.
    pub fn distance(&mut self, a: Point, b: Point, offset: f64, text: &str) {
        let u = (b - a).normalize();
        let at = a + perp(u) * offset;
        let dim = Shape::LinearDimension {
            p1: a,
            p2: b,
            line_at: at,
            angle: angle_of(u),
            text: text.to_string(),
            marks: Default::default(),
        };
        let layer = self.dimensions();
        self.d.add(layer, dim);
    }

    /// The finished drawing: the letters placed clear of every line, symbol and dimension,
    /// the title above, the caption below, the length scale and its bar under it.
    pub fn finish(mut self, title: &str, lines: &[String]) -> Drawing {
        self.place_angles();
        let text = self.text();
        let mut letters = labels::Polygon::of_points();
        letters.keep_off_drawing(&self.ink());
        for b in &self.keep_off {
            letters.keep_off(*b);
        }
        for (a, b) in &self.lines {
            letters.segment(*a, *b);
        }
        let near = 1e-9 * self.k_l * FIGURE_MM;
        for (p, name) in &self.points {
            let dir = free_direction(&occupied_directions(&self.lines, *p, near));
            letters.letter_clear(*p, name, self.s.text, Vector::new(libm::cos(dir), libm::sin(dir)), self.s.joint);
        }
        letters.draw(&mut self.d, text);
        let mut names = labels::Polygon::of_names();
        names.keep_off_drawing(&self.ink());
        for b in &self.keep_off {
            names.keep_off(*b);
        }
        for (a, b) in &self.lines {
            names.segment(*a, *b);
        }
        for (p, name, dir) in &self.names {
            names.name_with_leader(*p, name, 0.85 * self.s.text, *dir, None);
        }
        names.draw(&mut self.d, text);
        if let Some(b) = self.d.bounds() {
            let at = Point::new(b.min.x, b.max.y + 1.5 * self.s.text);
            self.d.text(text, at, 1.2 * self.s.text, title);
            let top = Point::new(b.min.x, b.min.y - 2.0 * self.s.text);
            let small = 0.8 * self.s.text;
            // The caption wrapped to the figure's width (at least CAPTION_MM of paper).
            let width = b.width().max(CAPTION_MM * self.k_l);
            let lines: Vec<String> = lines.iter().flat_map(|l| wrap(l, small, width)).collect();
            let lines = lines.as_slice();
            caption(&mut self.d, text, top, lines, small);
            let below = top - Vector::new(0.0, 1.8 * small * lines.len() as f64);
            length_scale_block(&mut self.d, text, below, self.k_l, self.units, self.s);
        }
        self.d
    }
}

/// The directions (radians) of every line of `lines` through or ending at `p` (within
/// `near`), pointing away from `p`.
fn occupied_directions(lines: &[(Point, Point)], p: Point, near: f64) -> Vec<f64> {
    let mut occupied = Vec::new();
    for (a, b) in lines {
        let ab = *b - *a;
        let len = ab.norm();
        if len == 0.0 {
            continue;
        }
        let t = (p - *a).dot(&ab) / (len * len);
        let off = (p - (*a + ab * t)).norm();
        if off > near || !(-1e-9..=1.0 + 1e-9).contains(&t) {
            continue;
        }
        if t > 1e-9 {
            occupied.push(angle_of(-ab));
        }
        if t < 1.0 - 1e-9 {
            occupied.push(angle_of(ab));
        }
    }
    occupied
}

/// The axis-aligned box of a text as drawn (turned with it), `None` for another shape.
fn corners_box(shape: &Shape) -> Option<TextBox> {
    let c = crate::draw::text_corners(shape)?;
    let min = c.iter().fold(c[0], |m, q| Point::new(m.x.min(q.x), m.y.min(q.y)));
    let max = c.iter().fold(c[0], |m, q| Point::new(m.x.max(q.x), m.y.max(q.y)));
    Some(TextBox { min, max })
}

/// The narrowest a caption is wrapped to, paper millimetres.
pub const CAPTION_MM: f64 = 150.0;

/// `line` broken at spaces into lines no wider than `width` (model units) in text
/// `height` high (measured with the bundled font's advances); a word wider than `width`
/// stays whole on its own line. Continuation lines are indented by two spaces.
pub fn wrap(line: &str, height: f64, width: f64) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    let mut current = String::new();
    for word in line.split(' ') {
        let candidate = if current.is_empty() { word.to_string() } else { format!("{current} {word}") };
        if !current.is_empty() && crate::draw::parts::text_width(&candidate, height) > width {
            out.push(std::mem::take(&mut current));
            current = format!("  {word}");
        } else {
            current = candidate;
        }
    }
    if !current.is_empty() {
        out.push(current);
    }
    out
}

/// The bounding box of `points`, widened by `margin` on every side.
pub fn extent(points: &[Point], margin: f64) -> Bounds {
    let (mut min, mut max) = (points[0], points[0]);
    for p in points {
        min = Point::new(min.x.min(p.x), min.y.min(p.y));
        max = Point::new(max.x.max(p.x), max.y.max(p.y));
    }
    let m = Vector::new(margin, margin);
    Bounds { min: min - m, max: max + m }
}

/// A length as a caption writes it: 4 significant decimals after the point at most,
/// trailing zeros dropped (`43.2308`, `80`).
pub fn len(v: f64) -> String {
    let s = format!("{v:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.to_string() }
}

/// An angle in degrees as a caption writes it (`36°`, `24.6243°`).
pub fn deg(rad: f64) -> String {
    format!("{}°", len(rad.to_degrees()))
}

/// A signed angle in degrees as a dimension writes it: two decimals at most, in
/// (−180°, 180°] (`−36.58°`).
pub fn signed_angle_text(rad: f64) -> String {
    let d = crate::geom::wrap_pi(rad).to_degrees();
    let s = format!("{d:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    format!("{}°", if s == "-0" { "0" } else { s }.replace('-', "−"))
}

/// An angle in degrees as a dimension on the drawing writes it: two decimals at most
/// (`36°`, `16.36°`), in [0°, 360°).
pub fn angle_text(rad: f64) -> String {
    let d = rad.to_degrees().rem_euclid(360.0);
    let s = format!("{d:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    format!("{}°", if s == "360" { "0" } else { s })
}
