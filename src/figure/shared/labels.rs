//! Letters of a polygon (velocity, acceleration, force) placed so that a reader can read
//! them when the polygon is small; and, by the same rules, the letters of a mechanism
//! (joints, pivots, points), which keep a clearance from their point (the joint circle)
//! and off the symbols drawn around it ([`Polygon::keep_off`]).
//!
//! Each letter goes to the first free spot among candidate positions around its point:
//! sixteen directions, in the order preferred direction, ±22.5°, ±45°, … 180° from it,
//! first with its box [`LABEL_GAP`] clear of the point, then at the further [`RINGS`]
//! (1.5, 2, 2.5, 3 times that distance; eight directions and three rings left a crowded
//! force polygon of the template with overlapping names at 40 positions). "Free"
//! means that the letter's estimated box (width [`label_width`], one text height tall)
//! overlaps no letter already placed in the same polygon nor a box kept off, and,
//! preferably, crosses none of the polygon's segments. When no candidate is free, the one with the fewest overlapping
//! letters, then the fewest crossed segments, wins (the earliest on a tie). Letters are
//! placed in the order they are added, so the first ones get their preferred spots.
//!
//! Points that coincide (equal to rounding: closer than [`COINCIDENT`] text heights) get one combined label,
//! their letters joined by `≡` in the order they were added (`p≡b` where the rocker stands
//! still), as textbooks of mechanisms write coincident points of a polygon, instead of
//! letters stacked on each other.
//!
//! A name that cannot sit beside its point (a force too short for its name in a crowded
//! force polygon) is placed with a leader ([`Polygon::name_with_leader`]): it may go
//! further out ([`LEADER_RINGS`]), and a thin line runs from the point to its box. Its
//! candidates are ranked by the letters their box overlaps, then the letters their leader
//! crosses, then the segments their box crosses; letters placed after it keep off its
//! leader as off the polygon's segments.
//! A link number ([`Polygon::circled`]) is a letter in a circle, placed the same way with
//! the circle as its box.
//!
//! Everything here is deterministic: the same polygon gives the same letters in the same
//! places.

use crate::draw::font;
use crate::draw::{Aci, Drawing, Entity, HAlign, LineType, Runs, Shape, VAlign};
use crate::geom::{Point, Vector};

/// Clear space between a point and the nearest edge of its letter's box, in text heights.
pub const LABEL_GAP: f64 = 0.35;
/// Distances tried, as multiples of the nearest distance (the letter's box [`LABEL_GAP`]
/// from its point). The last one bounds how far a letter can move ([`max_distance`]).
pub const RINGS: [f64; 5] = [1.0, 1.5, 2.0, 2.5, 3.0];
/// Points closer than this many text heights share one label: points equal to rounding
/// only (the text height is a fixed fraction of the drawing's size, so this is 1e-9 of the
/// drawing relative). Points that are merely close get letters of their own, placed apart;
/// `≡` on a drawing claims that two points coincide.
pub const COINCIDENT: f64 = 1e-9;
/// Distances tried for a name with a leader ([`Polygon::name_with_leader`]), as multiples
/// of the nearest distance: further out than [`RINGS`], since the leader ties the name to
/// its point.
pub const LEADER_RINGS: [f64; 9] = [1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0, 5.0, 6.0];
/// A leader shorter than this many text heights is not drawn: the name sits beside its
/// point anyway.
pub const LEADER_MIN: f64 = 0.5;
/// Colour of leader lines: grey, so that a leader does not read as a vector.
pub const LEADER_COLOR: Aci = Aci::DARK_GREY;
/// Radius of a link number's circle ([`Polygon::circled`]), in text heights.
pub const CIRCLE_RADIUS: f64 = 0.75;
/// The separator between the letters of coincident points.
pub const SAME_POINT: &str = "≡";
/// Directions tried, in multiples of [`TURN`] from the preferred direction, in order.
const TURNS: [f64; 16] = [0.0, 1.0, -1.0, 2.0, -2.0, 3.0, -3.0, 4.0, -4.0, 5.0, -5.0, 6.0, -6.0, 7.0, -7.0, 8.0];
/// The step between directions tried: 22.5°.
const TURN: f64 = std::f64::consts::PI / 8.0;
/// Directions tried for a name with a leader, in multiples of [`TURN_FINE`]: twice as many,
/// so that a leader can pass between the letters around a crowded point.
const TURNS_FINE: [f64; 32] = [
    0.0, 1.0, -1.0, 2.0, -2.0, 3.0, -3.0, 4.0, -4.0, 5.0, -5.0, 6.0, -6.0, 7.0, -7.0, 8.0, -8.0, 9.0, -9.0, 10.0,
    -10.0, 11.0, -11.0, 12.0, -12.0, 13.0, -13.0, 14.0, -14.0, 15.0, -15.0, 16.0,
];
/// The step between the directions of [`TURNS_FINE`]: 11.25°.
const TURN_FINE: f64 = std::f64::consts::PI / 16.0;

/// An axis-aligned box (an estimated text box), model units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TextBox {
    /// Lower-left corner.
    pub min: Point,
    /// Upper-right corner.
    pub max: Point,
}

impl TextBox {
    /// The box of `text`, `height` high, drawn centred at `centre` (as [`draw_placed`] draws
    /// a label: the middle of its capitals at `centre`), measured in the font it is drawn in
    /// ([`font::measure`]): its advances wide, from its deepest descender to its highest
    /// glyph (at least the cap height) tall.
    pub fn centred(centre: Point, text: &str, height: f64) -> TextBox {
        TextBox::centred_runs(centre, text, &Runs::flat(), height)
    }

    /// [`TextBox::centred`] of a text drawn in its `runs` (a subscript smaller and lowered:
    /// [`font::measure_runs`]).
    pub fn centred_runs(centre: Point, text: &str, runs: &Runs, height: f64) -> TextBox {
        let (half, shift) = TextBox::half_size(text, runs, height);
        TextBox::around(centre - shift, half)
    }

    /// Half the width and half the height of [`TextBox::centred_runs`]'s box, and the shift
    /// from the box's centre to the text's centre (the middle of its capitals).
    fn half_size(text: &str, runs: &Runs, height: f64) -> (Vector, Vector) {
        let e = font::measure_runs(text, runs, height);
        // Box from (baseline − descent) to (baseline + ascent), the baseline half a height
        // under the text's centre.
        let middle = -0.5 * height + 0.5 * (e.ascent - e.descent);
        (Vector::new(0.5 * e.width, 0.5 * (e.ascent + e.descent)), Vector::new(0.0, -middle))
    }

    /// The box with half-sizes `half` centred at `centre`.
    fn around(centre: Point, half: Vector) -> TextBox {
        TextBox { min: centre - half, max: centre + half }
    }

    /// Whether the two boxes share interior area (touching edges do not count).
    pub fn overlaps(&self, o: &TextBox) -> bool {
        self.min.x < o.max.x && o.min.x < self.max.x && self.min.y < o.max.y && o.min.y < self.max.y
    }

    /// Whether the segment `a`–`b` passes through the box's interior (clipped by
    /// Liang–Barsky).
    pub fn crosses(&self, a: Point, b: Point) -> bool {
        let d = b - a;
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        for (p, q) in
            [(-d.x, a.x - self.min.x), (d.x, self.max.x - a.x), (-d.y, a.y - self.min.y), (d.y, self.max.y - a.y)]
        {
            if p == 0.0 {
                if q <= 0.0 {
                    return false;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
            }
        }
        t0 < t1
    }
}

/// A candidate's score, lower is better: letters its box overlaps, letters its leader
/// crosses, segments its box crosses, letters its box comes nearer than the polygon's gap
/// to ([`Polygon::apart`]).
type Score = (usize, usize, usize, usize);
/// A segment: its two ends.
pub type Segment = (Point, Point);

/// One letter waiting to be placed.
#[derive(Debug, Clone)]
struct Letter {
    at: Point,
    text: String,
    runs: Runs,
    dir: Vector,
    height: f64,
    color: Option<Aci>,
    /// Extra clear distance from the point (a joint circle's radius).
    clear: f64,
    /// Whether it may go further out, tied to its point by a leader line.
    leader: bool,
    /// Whether it is drawn in a circle (a link number).
    circled: bool,
}

impl Letter {
    /// Half the width and half the height of its box, and the shift from the box's centre
    /// to where its text is drawn (a circle's box is centred on its text).
    fn half(&self) -> (Vector, Vector) {
        if self.circled {
            (Vector::new(CIRCLE_RADIUS * self.height, CIRCLE_RADIUS * self.height), Vector::zeros())
        } else {
            TextBox::half_size(&self.text, &self.runs, self.height)
        }
    }
}

/// A label's text, flat (as the DXF writes it), and its runs: which part the SVG, PNG and
/// PDF draw as a subscript. The figure states it: a point's letter is flat
/// ([`Label::from`] a `&str`: `A`, `O1`, `a′`, user point names as the user spelt them); a
/// quantity's name is its symbol with the rest as subscript ([`Label::quantity`]: `R` +
/// `A`, `n` + `AB`, `F` + `i21`, `ω` + `1`).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Label {
    /// The text, flat.
    pub text: String,
    /// Its runs.
    pub runs: Runs,
}

impl Label {
    /// A quantity's name `name` (a force, a vector component, an angle, a velocity): an
    /// optional sign (`−`), the quantity's symbol (its first character: `R`, `F`, `G`, `M`,
    /// `n`, `a`, `v`, `ω`, `φ`, `π`), then its subscript, which is the rest (a joint's or a
    /// body's name: `A`, `32`, `AB`, `A3O3`, `e1`, `i21`) up to the primes (`′`, `'`) that
    /// end it: `RA` → R_A, `−R32` → −R_32, `nA3O3` → n_A3O3, `FM3'` → F_M3'. A magnitude's
    /// bars stay outside: `|vE|` → |v_E|. A name of one symbol (`G`, `k`, `π`) has no
    /// subscript.
    pub fn quantity(name: &str) -> Label {
        let start = name.strip_prefix(['−', '-', '|']).map_or(0, |rest| name.len() - rest.len());
        let Some(symbol) = name[start..].chars().next() else { return Label::from(name) };
        let from = start + symbol.len_utf8();
        let end = name.trim_end_matches(['′', '\'', '″', '|']).len().max(from);
        Label { text: name.to_string(), runs: Runs::subscript(from..end) }
    }

    /// A dimension's text, `name = value` or a name alone, whose name is a symbol and an
    /// index (`φ1 = 75.77°` → φ_1 = 75.77°, `ψ1` → ψ_1): the index a subscript. Any other
    /// text (`Δφ = 60°`, `90° − θ = 54°`, `30°`) is flat.
    pub fn dimension(text: &str) -> Label {
        let name = text.split(" = ").next().unwrap_or(text);
        let mut chars = name.chars();
        let indexed = chars.next().is_some_and(|c| c.is_alphabetic())
            && chars.clone().next().is_some()
            && chars.all(|c| c.is_ascii_digit());
        if indexed { Label { text: text.to_string(), runs: Label::quantity(name).runs } } else { Label::from(text) }
    }
}

impl Label {
    /// A text of the figure's own marked up with `_` before each subscript (`φ_1 = 90°`,
    /// `m_21 bar AB`): drawn with the subscripts where the writer can, flat without the
    /// marks elsewhere (`φ1 = 90°` in the DXF and in the PDF's text: [`Runs::unmarked`]).
    /// A user's name goes after it with [`Label::then`], never into the markup.
    pub fn marked(markup: &str) -> Label {
        let (text, runs) = Runs::unmarked(markup);
        Label { text, runs }
    }

    /// This label followed by `text` at the base size, as written (a user's name: `gas`,
    /// `my_rod` keeps its `_`).
    pub fn then(mut self, text: &str) -> Label {
        // Bytes after the last run are drawn at the base size.
        self.text.push_str(text);
        self
    }
}

/// An angular dimension with its name's index drawn as a subscript where the writer can
/// ([`Label::dimension`]: `φ1 = 75.77°` → φ_1 = 75.77°); any other shape unchanged. A figure
/// places the dimension with its flat text (as the DXF writes it, the wider of the two) and
/// then sets its runs, so that the text keeps clear in every writer.
pub fn with_dimension_runs(shape: Shape) -> Shape {
    match shape {
        Shape::AngularDimension { vertex, first, second, radius, text, .. } => {
            let runs = Label::dimension(&text).runs;
            Shape::AngularDimension { vertex, first, second, radius, text, runs }
        }
        other => other,
    }
}

impl From<&str> for Label {
    /// A flat label.
    fn from(text: &str) -> Label {
        Label { text: text.to_string(), runs: Runs::flat() }
    }
}

impl From<&String> for Label {
    /// A flat label.
    fn from(text: &String) -> Label {
        Label::from(text.as_str())
    }
}

impl From<String> for Label {
    /// A flat label.
    fn from(text: String) -> Label {
        Label { text, runs: Runs::flat() }
    }
}

/// What letters placed into a drawing keep clear of besides what the drawing holds: what is
/// drawn elsewhere on the same frame (its shared part: paths, titles), and the panel they stay
/// inside.
#[derive(Debug, Clone, Copy, Default)]
pub struct Around<'a> {
    /// Drawn elsewhere on the same page or frame: its strokes and texts are kept off.
    pub backdrop: Option<&'a Drawing>,
    /// The panel the letters stay inside.
    pub within: Option<TextBox>,
}

/// A placed label: where its text's centre goes, and what is drawn with it.
#[derive(Debug, Clone, PartialEq)]
pub struct Placed {
    /// Centre of the text (and of its circle).
    pub centre: Point,
    /// The text, flat.
    pub text: String,
    /// Its runs (which part is a subscript).
    pub runs: Runs,
    /// Its height.
    pub height: f64,
    /// Entity colour, or the layer's.
    pub color: Option<Aci>,
    /// A leader line from the point to the box's edge, when drawn.
    pub leader: Option<(Point, Point)>,
    /// Whether a circle of [`CIRCLE_RADIUS`] heights surrounds the text.
    pub circled: bool,
}

impl Placed {
    /// The box it covers: the text's estimated box, or the circle's square.
    pub fn bounds(&self) -> TextBox {
        if self.circled {
            let r = CIRCLE_RADIUS * self.height;
            TextBox::around(self.centre, Vector::new(r, r))
        } else {
            TextBox::centred_runs(self.centre, &self.text, &self.runs, self.height)
        }
    }
}

/// The letters of one polygon and the segments they should keep off; [`Polygon::draw`]
/// places and draws them.
#[derive(Debug, Clone, Default)]
pub struct Polygon {
    letters: Vec<Letter>,
    segments: Vec<(Point, Point)>,
    obstacles: Vec<TextBox>,
    merge: bool,
    /// The box every label should stay inside (its panel), when set.
    within: Option<TextBox>,
    /// The least gap between two letters' boxes (drawing units; 0: touching allowed).
    gap: f64,
}

impl Polygon {
    /// Letters at the polygon's points: coincident points share one label.
    pub fn of_points() -> Polygon {
        Polygon { merge: true, ..Polygon::default() }
    }

    /// Names beside the polygon's sides (force polygons): never combined.
    pub fn of_names() -> Polygon {
        Polygon { merge: false, ..Polygon::default() }
    }

    /// The letters placed at least `gap` apart (drawing units, box to box): a letter
    /// closer than that to one placed before counts as overlapping it.
    pub fn apart(mut self, gap: f64) -> Polygon {
        self.gap = gap.max(0.0);
        self
    }

    /// A letter `text` (`height` high, entity colour `color` or the layer's) for the point
    /// `at`, preferably on the side `dir` (any length; zero means above).
    pub fn letter(&mut self, at: Point, text: impl Into<Label>, height: f64, dir: Vector, color: Option<Aci>) {
        let Label { text, runs } = text.into();
        self.push(Letter { at, text, runs, dir, height, color, clear: 0.0, leader: false, circled: false });
    }

    /// A name for the point `at` (a short force's middle) that may go up to
    /// [`LEADER_RINGS`] out, preferably on the side `dir`, with a leader line from `at` to
    /// its box when it does not sit beside the point.
    pub fn name_with_leader(
        &mut self,
        at: Point,
        text: impl Into<Label>,
        height: f64,
        dir: Vector,
        color: Option<Aci>,
    ) {
        let Label { text, runs } = text.into();
        self.push(Letter { at, text, runs, dir, height, color, clear: 0.0, leader: true, circled: false });
    }

    /// A link number `text` in a circle of [`CIRCLE_RADIUS`] heights, for the point `at`
    /// (a link's middle), keeping `clear` more than [`LABEL_GAP`] from it (half the link's
    /// width), preferably on the side `dir`.
    pub fn circled(&mut self, at: Point, text: &str, height: f64, dir: Vector, clear: f64) {
        let runs = Runs::flat();
        self.push(Letter {
            at,
            text: text.to_string(),
            runs,
            dir,
            height,
            color: None,
            clear,
            leader: false,
            circled: true,
        });
    }

    /// A letter `text` for the point `at` that keeps `clear` (model units, such as a joint
    /// circle's radius) more than [`LABEL_GAP`] between the point and its box, preferably
    /// on the side `dir`.
    pub fn letter_clear(&mut self, at: Point, text: impl Into<Label>, height: f64, dir: Vector, clear: f64) {
        let Label { text, runs } = text.into();
        self.push(Letter { at, text, runs, dir, height, color: None, clear, leader: false, circled: false });
    }

    fn push(&mut self, l: Letter) {
        if !l.text.is_empty() && l.at.x.is_finite() && l.at.y.is_finite() {
            self.letters.push(l);
        }
    }

    /// A box letters must not overlap (a symbol: a ground support, a slider's block).
    pub fn keep_off(&mut self, b: TextBox) {
        self.obstacles.push(b);
    }

    /// The box every label should stay inside (its panel): a candidate reaching out of it
    /// scores as if it overlapped a letter.
    pub fn keep_within(&mut self, b: TextBox) {
        self.within = Some(b);
    }

    /// Whether `bx` leaves the box labels should stay inside.
    fn outside(&self, bx: &TextBox) -> bool {
        self.within
            .is_some_and(|w| bx.min.x < w.min.x || bx.min.y < w.min.y || bx.max.x > w.max.x || bx.max.y > w.max.y)
    }

    /// Every stroke of `shapes` ([`strokes`]) as a segment letters should not cover.
    pub fn keep_off_shapes<'a>(&mut self, shapes: impl IntoIterator<Item = &'a Shape>) {
        for shape in shapes {
            for (a, b) in strokes(shape) {
                self.segment(a, b);
            }
        }
    }

    /// Everything drawn in `d` so far: its strokes as segments letters should not cover,
    /// its texts as boxes they must not overlap.
    pub fn keep_off_drawing(&mut self, d: &Drawing) {
        self.keep_off_shapes(d.entities.iter().map(|e| &e.shape));
        // A circled number's box is its circle's square.
        let circles: Vec<(Point, f64)> = d
            .entities
            .iter()
            .filter_map(|e| match e.shape {
                Shape::Circle { center, radius } => Some((center, radius)),
                _ => None,
            })
            .collect();
        for e in &d.entities {
            if let Shape::Text { at, height, .. } = &e.shape {
                let r = CIRCLE_RADIUS * height;
                if circles.iter().any(|(c, cr)| c == at && (cr - r).abs() <= 1e-12 * r) {
                    self.keep_off(TextBox::around(*at, Vector::new(r, r)));
                    continue;
                }
            }
            if let Some(c) = crate::draw::text_corners(&e.shape) {
                let min = c.iter().fold(c[0], |m, p| Point::new(m.x.min(p.x), m.y.min(p.y)));
                let max = c.iter().fold(c[0], |m, p| Point::new(m.x.max(p.x), m.y.max(p.y)));
                self.keep_off(TextBox { min, max });
            }
        }
    }

    /// Keeps the letters clear of what `around` holds ([`Around`]).
    pub fn around(&mut self, around: Around<'_>) {
        if let Some(b) = around.backdrop {
            self.keep_off_drawing(b);
        }
        if let Some(w) = around.within {
            self.keep_within(w);
        }
    }

    /// A segment of the polygon that letters should not cover.
    pub fn segment(&mut self, a: Point, b: Point) {
        if a.x.is_finite() && a.y.is_finite() && b.x.is_finite() && b.y.is_finite() {
            self.segments.push((a, b));
        }
    }

    /// The labels, in the order added, after combining coincident points.
    ///
    /// Each candidate's score is counted only as far as it can still beat the best so far
    /// (the first candidate with the lowest score wins, so a candidate that cannot be lower
    /// is dropped as soon as that is known), and a segment is tested against a candidate's
    /// box only when their bounding boxes overlap (a segment whose bounding box lies on or
    /// outside an edge of the box cannot pass through its interior: [`TextBox::crosses`]
    /// says no for it, rounding included).
    pub fn place(&self) -> Vec<Placed> {
        let letters: std::borrow::Cow<'_, [Letter]> =
            if self.merge { combine(&self.letters).into() } else { self.letters.as_slice().into() };
        // What a letter's box must not overlap, and what its leader should not cross: the
        // boxes kept off, then the letters placed so far (counted, so the order is free).
        let mut blockers: Vec<TextBox> = Vec::with_capacity(self.obstacles.len() + letters.len());
        blockers.extend_from_slice(&self.obstacles);
        // What a letter's box should not cross: the polygon's segments, then the leaders
        // drawn so far, each with its bounding box.
        let mut lines: Vec<(Segment, TextBox)> = Vec::with_capacity(self.segments.len() + letters.len());
        lines.extend(self.segments.iter().map(|&s| (s, segment_box(s))));
        // Those near the letter being placed.
        let (mut near_blockers, mut near_lines) = (Vec::new(), Vec::new());
        // The letters placed so far grown by the gap (none without one).
        let mut spaced: Vec<TextBox> = Vec::new();
        let mut out = Vec::with_capacity(letters.len());
        for l in letters.iter() {
            let mut best: Option<(Score, Point, TextBox, Option<Segment>)> = None;
            let (half, shift) = l.half();
            let rings: &[f64] = if l.leader { &LEADER_RINGS } else { &RINGS };
            // Every candidate's box and leader lie inside `reach` (with room for rounding):
            // what lies wholly outside it is neither overlapped nor crossed by any of them.
            let reach = candidates_reach(l.at, half, l.height, l.clear, rings);
            let apart = |b: &TextBox| {
                b.max.x < reach.min.x || b.min.x > reach.max.x || b.max.y < reach.min.y || b.min.y > reach.max.y
            };
            near_blockers.clear();
            near_blockers.extend(blockers.iter().filter(|b| !apart(b)));
            near_lines.clear();
            near_lines.extend(lines.iter().filter(|(_, b)| !apart(b)).copied());
            let (blockers_near, lines_near): (&[TextBox], &[(Segment, TextBox)]) = (&near_blockers, &near_lines);
            for c in candidates_in(l.at, half, l.height, l.dir, l.clear, l.leader) {
                let bx = TextBox::around(c, half);
                let bound = best.as_ref().map(|(s, ..)| *s);
                // Overlapped letters counted only until the candidate has lost.
                let most_hits = bound.map_or(usize::MAX, |s| s.0);
                let mut hits = usize::from(self.outside(&bx));
                for b in blockers_near {
                    if b.overlaps(&bx) {
                        hits += 1;
                        if hits > most_hits {
                            break;
                        }
                    }
                }
                if hits > most_hits {
                    continue;
                }
                let leader = if l.leader { leader_line(l.at, c, half, l.height) } else { None };
                // A box is tested against the leader only when their bounding boxes overlap
                // (as the segments below).
                let through = leader.map_or(0, |(a, b)| {
                    let sb = segment_box((a, b));
                    blockers_near.iter().filter(|x| sb.overlaps(x) && x.crosses(a, b)).count()
                });
                // More segments than the box may cross and still win (as many as the best
                // when nearness may decide).
                let limit = match bound {
                    Some(s) if (hits, through) > (s.0, s.1) => continue,
                    Some(s) if (hits, through) == (s.0, s.1) => s.2 + usize::from(s.3 > 0),
                    _ => usize::MAX,
                };
                let mut crossed = 0;
                for &((a, b), ref sb) in lines_near {
                    if sb.overlaps(&bx) && bx.crosses(a, b) {
                        crossed += 1;
                        if crossed >= limit {
                            break;
                        }
                    }
                }
                if crossed >= limit {
                    continue;
                }
                // Letters nearer than the gap: counted only on a tie of the rest.
                let near = spaced.iter().filter(|b| b.overlaps(&bx)).count();
                if bound.is_some_and(|s| (hits, through, crossed, near) >= s) {
                    continue;
                }
                let score = (hits, through, crossed, near);
                best = Some((score, c, bx, leader));
                if score == (0, 0, 0, 0) {
                    break;
                }
            }
            if let Some((_, c, bx, leader)) = best {
                blockers.push(bx);
                if self.gap > 0.0 {
                    let g = Vector::new(self.gap, self.gap);
                    spaced.push(TextBox { min: bx.min - g, max: bx.max + g });
                }
                lines.extend(leader.map(|s| (s, segment_box(s))));
                out.push(Placed {
                    centre: c + shift,
                    text: l.text.clone(),
                    runs: l.runs.clone(),
                    height: l.height,
                    color: l.color,
                    leader,
                    circled: l.circled,
                });
            }
        }
        out
    }

    /// Places the letters and adds them to `d` on `layer` as centred texts: a polygon's
    /// letters take the layer's style; names beside sides (force polygons) carry their
    /// colour (when given) and a continuous line type on the entity. Returns the letters'
    /// boxes (for letters drawn later to keep off).
    pub fn draw(&self, d: &mut Drawing, layer: usize) -> Vec<TextBox> {
        let linetype = if self.merge { None } else { Some(LineType::Continuous) };
        let placed = self.place();
        let bounds = placed.iter().map(Placed::bounds).collect();
        for p in placed {
            push_placed(d, layer, p, linetype);
        }
        bounds
    }
}

/// Adds a placed label to `d` on `layer`: its text centred at its place, its leader line
/// and its circle (in the label's colour, with `linetype` on each entity).
pub fn draw_placed(d: &mut Drawing, layer: usize, p: &Placed, linetype: Option<LineType>) {
    push_placed(d, layer, p.clone(), linetype);
}

/// [`draw_placed`], the label's text moved into the drawing.
fn push_placed(d: &mut Drawing, layer: usize, p: Placed, linetype: Option<LineType>) {
    let color = p.color;
    if let Some((from, to)) = p.leader {
        let color = Some(LEADER_COLOR);
        d.push(Entity { layer, color, linetype: Some(LineType::Continuous), shape: Shape::Line { from, to } });
    }
    if p.circled {
        let shape = Shape::Circle { center: p.centre, radius: CIRCLE_RADIUS * p.height };
        d.push(Entity { layer, color, linetype, shape });
    }
    let shape = Shape::Text {
        runs: p.runs,
        at: p.centre,
        height: p.height,
        value: p.text,
        halign: HAlign::Center,
        valign: VAlign::Middle,
        rotation: 0.0,
    };
    d.push(Entity { layer, color, linetype, shape });
}

/// The leader from `at` to the edge of the box of half-sizes `half` centred at `centre`
/// (along the line between them), or `None` when shorter than [`LEADER_MIN`] heights.
fn leader_line(at: Point, centre: Point, half: Vector, height: f64) -> Option<(Point, Point)> {
    let v = at - centre;
    // From the centre to the box's edge towards `at`.
    let t = (half.x / v.x.abs().max(1e-300)).min(half.y / v.y.abs().max(1e-300));
    if t >= 1.0 {
        return None;
    }
    let edge = centre + v * t;
    ((at - edge).norm() >= LEADER_MIN * height).then_some((at, edge))
}

/// Of the texts `candidates` (in order of preference), the first whose box (as drawn:
/// [`crate::draw::text_corners`]) overlaps no text and is crossed by no stroke of `d` (but
/// those on the layers `breakable`, which [`break_around`] interrupts under it) and stays
/// inside `within`; else the one with the fewest such conflicts (the first on a tie). `None`
/// for no candidate. For a text that has a few good places (a diagram's label).
pub fn first_free(d: &Drawing, candidates: Vec<Shape>, within: Option<TextBox>, breakable: &[usize]) -> Option<Shape> {
    let mut p = Polygon::of_names();
    let mut solid = d.clone();
    solid.entities.retain(|e| !breakable.contains(&e.layer));
    p.keep_off_drawing(&solid);
    let conflicts = |shape: &Shape| -> usize {
        let Some(c) = crate::draw::text_corners(shape) else { return usize::MAX };
        let min = c.iter().fold(c[0], |m, q| Point::new(m.x.min(q.x), m.y.min(q.y)));
        let max = c.iter().fold(c[0], |m, q| Point::new(m.x.max(q.x), m.y.max(q.y)));
        let bx = TextBox { min, max };
        let outside = within.is_some_and(|w| min.x < w.min.x || min.y < w.min.y || max.x > w.max.x || max.y > w.max.y);
        p.obstacles.iter().filter(|o| o.overlaps(&bx)).count()
            + p.segments.iter().filter(|(a, b)| bx.crosses(*a, *b)).count()
            + usize::from(outside)
    };
    let mut best: Option<(usize, Shape)> = None;
    for c in candidates {
        let n = conflicts(&c);
        if n == 0 {
            return Some(c);
        }
        if best.as_ref().is_none_or(|(b, _)| n < *b) {
            best = Some((n, c));
        }
    }
    best.map(|(_, c)| c)
}

/// Breaks the thin lines and circles on `layer` of `d` where they pass through one of
/// `boxes` grown by `gap` (a drafting convention: a construction line or a grid line is
/// interrupted where a text is written over it, ISO 129-1's "not crossed by any line"): a
/// line becomes the pieces outside the boxes, a circle the arcs outside them (to 0.5°).
pub fn break_around(d: &mut Drawing, layer: usize, boxes: &[TextBox], gap: f64) {
    if boxes.is_empty() {
        return;
    }
    let grown: Vec<TextBox> = boxes
        .iter()
        .map(|b| TextBox { min: b.min - Vector::new(gap, gap), max: b.max + Vector::new(gap, gap) })
        .collect();
    let inside = |p: Point| grown.iter().any(|b| p.x > b.min.x && p.x < b.max.x && p.y > b.min.y && p.y < b.max.y);
    let mut out = Vec::with_capacity(d.entities.len());
    for e in std::mem::take(&mut d.entities) {
        let pieces: Option<Vec<Shape>> = match (&e.shape, e.layer == layer) {
            (Shape::Line { from, to }, true) if grown.iter().any(|b| b.crosses(*from, *to)) => {
                // Sampled finely along the line, the runs outside every box kept.
                let n = 400;
                let at = |k: usize| *from + (*to - *from) * (k as f64 / n as f64);
                Some(
                    runs(n, |k| !inside(at(k)))
                        .into_iter()
                        .map(|(i, j)| Shape::Line { from: at(i), to: at(j) })
                        .collect(),
                )
            }
            (Shape::Circle { center, radius }, true) => {
                let n = 720;
                let angle = |k: usize| std::f64::consts::TAU * k as f64 / n as f64;
                let at = |k: usize| *center + Vector::new(libm::cos(angle(k)), libm::sin(angle(k))) * *radius;
                let keep = runs(n, |k| !inside(at(k)));
                (keep.len() != 1 || keep[0] != (0, n)).then(|| {
                    keep.into_iter()
                        .map(|(i, j)| Shape::Arc { center: *center, radius: *radius, start: angle(i), end: angle(j) })
                        .collect()
                })
            }
            _ => None,
        };
        match pieces {
            Some(p) => out.extend(p.into_iter().map(|shape| Entity { shape, ..e.clone() })),
            None => out.push(e),
        }
    }
    d.entities = out;
}

/// The runs `(first, last)` of consecutive samples `0..=n` for which `keep` holds (a run
/// of one sample dropped).
fn runs(n: usize, keep: impl Fn(usize) -> bool) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start: Option<usize> = None;
    for k in 0..=n {
        match (keep(k), start) {
            (true, None) => start = Some(k),
            (false, Some(s)) => {
                if k - 1 > s {
                    out.push((s, k - 1));
                }
                start = None;
            }
            _ => {}
        }
    }
    if let Some(s) = start
        && n > s
    {
        out.push((s, n));
    }
    out
}

/// Largest angle a chord of a circle or an arc stands for in [`strokes`]: 5° (the chord
/// is then within 0.1 % of the radius of the arc).
const CHORD: f64 = std::f64::consts::PI / 36.0;

/// The strokes of a drawn shape as straight segments, as a reader draws them: a line; a
/// polyline's sides (a wide one's two edges, half its width either side); an arrow's shaft
/// and its head's sides; a filled shape's outline; circles and arcs as chords of at most 5°.
/// Texts and dimensions give none (a dimension's text is placed by its own rules).
pub fn strokes(shape: &Shape) -> Vec<Segment> {
    let ring = |c: Point, r: f64, start: f64, sweep: f64| {
        let n = ((sweep.abs() / CHORD).ceil() as usize).max(1);
        let at = |k: usize| {
            let a = start + sweep * k as f64 / n as f64;
            c + Vector::new(libm::cos(a), libm::sin(a)) * r
        };
        (0..n).map(|k| (at(k), at(k + 1))).collect::<Vec<_>>()
    };
    let closed = |pts: &[Point]| (0..pts.len()).map(|i| (pts[i], pts[(i + 1) % pts.len()])).collect::<Vec<_>>();
    match shape {
        Shape::Circle { center, radius } => ring(*center, *radius, 0.0, std::f64::consts::TAU),
        Shape::Arc { center, radius, start, end } => {
            ring(*center, *radius, *start, crate::draw::parts::arc_sweep(*start, *end))
        }
        Shape::Line { from, to } => vec![(*from, *to)],
        Shape::Polyline { points, closed: c, width } => {
            let sides: Vec<Segment> =
                if *c && points.len() > 2 { closed(points) } else { points.windows(2).map(|w| (w[0], w[1])).collect() };
            if *width <= 0.0 {
                return sides;
            }
            // The band's two edges.
            sides
                .into_iter()
                .flat_map(|(a, b)| {
                    let n = crate::geom::perp(unit(b - a, Vector::new(1.0, 0.0))) * (0.5 * width);
                    [(a + n, b + n), (a - n, b - n)]
                })
                .collect()
        }
        Shape::Filled { points } => closed(points),
        Shape::Arrow { from, to, head } => match crate::draw::parts::arrow(*from, *to, *head) {
            Some((base, tri)) => {
                let mut out = vec![(*from, base)];
                out.extend(closed(&tri));
                out
            }
            None => vec![(*from, *to)],
        },
        Shape::Text { .. }
        | Shape::ScaleText { .. }
        | Shape::AngularDimension { .. }
        | Shape::LinearDimension { .. } => Vec::new(),
    }
}

/// The bounding box of a segment.
fn segment_box((a, b): Segment) -> TextBox {
    TextBox { min: Point::new(a.x.min(b.x), a.y.min(b.y)), max: Point::new(a.x.max(b.x), a.y.max(b.y)) }
}

/// Letters whose points lie within [`COINCIDENT`] heights of an earlier letter's point join
/// that letter's label (`a≡b`), which keeps the earlier letter's place and direction.
fn combine(letters: &[Letter]) -> Vec<Letter> {
    let mut out: Vec<Letter> = Vec::with_capacity(letters.len());
    for l in letters {
        match out.iter_mut().find(|o| (o.at - l.at).norm() < COINCIDENT * o.height.min(l.height)) {
            Some(o) => {
                let (joined, runs) = join(&o.text, &o.runs, &l.text, &l.runs);
                (o.text, o.runs) = (joined, runs);
                if o.dir.norm() == 0.0 {
                    o.dir = l.dir;
                }
            }
            None => out.push(l.clone()),
        }
    }
    out
}

/// `a≡b`: the texts of two coincident points joined by [`SAME_POINT`], each keeping its
/// runs.
fn join(a: &str, a_runs: &Runs, b: &str, b_runs: &Runs) -> (String, Runs) {
    let mut text = String::with_capacity(a.len() + SAME_POINT.len() + b.len());
    let mut runs = Vec::new();
    for (part, kind) in a_runs.split(a) {
        text.push_str(part);
        runs.push(crate::draw::Run { end: text.len(), kind });
    }
    text.push_str(SAME_POINT);
    for (part, kind) in b_runs.split(b) {
        text.push_str(part);
        runs.push(crate::draw::Run { end: text.len(), kind });
    }
    let runs = Runs(runs);
    (text, if runs.is_flat() { Runs::flat() } else { runs })
}

/// Width of a label `height` high: its advances in the font it is drawn in
/// ([`font::width`]).
pub fn label_width(text: &str, height: f64) -> f64 {
    font::width(text, height)
}

/// Unit vector of `v`, or `fallback` for a zero or non-finite `v`.
fn unit(v: Vector, fallback: Vector) -> Vector {
    let n = v.norm();
    if n > 0.0 && n.is_finite() { v / n } else { fallback }
}

/// Candidate centres for `text` at `at`, in the order they are tried (see the module docs).
pub fn candidates(at: Point, text: &str, height: f64, dir: Vector) -> impl Iterator<Item = Point> {
    let (half, shift) = TextBox::half_size(text, &Runs::flat(), height);
    candidates_in(at, half, height, dir, 0.0, false).map(move |c| c + shift)
}

/// Candidate centres for a box of half-sizes `half` whose edge keeps `clear` more than
/// [`LABEL_GAP`] from `at`, at the distances [`RINGS`] (a name with a leader: [`LEADER_RINGS`],
/// in twice as many directions).
fn candidates_in(
    at: Point,
    half: Vector,
    height: f64,
    dir: Vector,
    clear: f64,
    leader: bool,
) -> impl Iterator<Item = Point> {
    let u0 = unit(dir, Vector::new(0.0, 1.0));
    let base = libm::atan2(u0.y, u0.x);
    let (hw, hh) = (half.x, half.y);
    // Names with a leader go further out and try twice as many directions.
    let (rings, turns, turn): (&[f64], &[f64], f64) =
        if leader { (&LEADER_RINGS, &TURNS_FINE, TURN_FINE) } else { (&RINGS, &TURNS, TURN) };
    // Lazy: most letters take their first candidate, so the directions are not computed
    // ahead (a run places some ten thousand letters); each direction (and its reach) is
    // computed once, on the first ring, and kept for the others.
    let mut dirs = [(Vector::zeros(), 0.0); TURNS_FINE.len()];
    let mut known = 0;
    rings.iter().flat_map(move |&ring| (0..turns.len()).map(move |i| (ring, i))).map(move |(ring, i)| {
        if i == known {
            let a = base + turns[i] * turn;
            let u = Vector::new(libm::cos(a), libm::sin(a));
            // From the box's centre to its edge along u.
            let reach = (hw / u.x.abs().max(1e-12)).min(hh / u.y.abs().max(1e-12));
            dirs[i] = (u, reach);
            known += 1;
        }
        let (u, reach) = dirs[i];
        at + u * (ring * (LABEL_GAP * height + clear + reach))
    })
}

/// A box holding every candidate box of [`candidates_in`] (same arguments) and every
/// leader from `at` to one of them, with room for rounding: the nearest ray from a box's
/// centre to its edge is at most its half-diagonal long.
fn candidates_reach(at: Point, half: Vector, height: f64, clear: f64, rings: &[f64]) -> TextBox {
    let ring = rings.iter().fold(0.0f64, |a, &r| a.max(r));
    let r = ring * (LABEL_GAP * height + clear + libm::hypot(half.x, half.y));
    let slack = 1e-6 * (r + half.x + half.y) + 1e-9 * (at.x.abs() + at.y.abs());
    let d = Vector::new(r + half.x + slack, r + half.y + slack);
    TextBox { min: at - d, max: at + d }
}

/// The farthest a label's centre can be from its point: the last ring in the worst
/// direction.
pub fn max_distance(text: &str, runs: &Runs, height: f64) -> f64 {
    let (half, shift) = TextBox::half_size(text, runs, height);
    RINGS[RINGS.len() - 1] * (LABEL_GAP * height + libm::hypot(half.x, half.y)) + shift.norm()
}

/// The farthest a name with a leader ([`Polygon::name_with_leader`]) can be from its point.
pub fn max_leader_distance(text: &str, runs: &Runs, height: f64) -> f64 {
    let (half, shift) = TextBox::half_size(text, runs, height);
    LEADER_RINGS[LEADER_RINGS.len() - 1] * (LABEL_GAP * height + libm::hypot(half.x, half.y)) + shift.norm()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::draw::parts::text_width;

    /// The subscripts of a label, in order.
    fn subs(l: &Label) -> Vec<&str> {
        l.runs.split(&l.text).filter(|(_, k)| *k == crate::draw::RunKind::Sub).map(|(s, _)| s).collect()
    }

    #[test]
    fn a_quantitys_subscript_and_a_dimensions_index() {
        assert_eq!(subs(&Label::quantity("RAn")), ["An"]);
        assert_eq!(subs(&Label::quantity("−R32")), ["32"]);
        assert_eq!(subs(&Label::quantity("|vE|")), ["E"]);
        assert_eq!(subs(&Label::quantity("G")), Vec::<&str>::new());
        // A dimension: a symbol and an index before ` = `; anything else flat.
        let phi = Label::dimension("φ1 = 75.77°");
        assert_eq!((phi.text.as_str(), subs(&phi)), ("φ1 = 75.77°", vec!["1"]));
        assert_eq!(subs(&Label::dimension("ψ1")), ["1"]);
        for flat in ["Δφ = 60°", "90° − θ = 54°", "θ = 31°", "30°", "φ = 40.00°", "1 = 2"] {
            assert!(Label::dimension(flat).runs.is_flat(), "{flat}");
        }
    }

    #[test]
    fn a_marked_text_then_a_users_name_as_written() {
        let m = Label::marked("m_2 (").then("my_rod").then(")");
        assert_eq!((m.text.as_str(), subs(&m)), ("m2 (my_rod)", vec!["2"]));
        assert!(Label::marked("g").runs.is_flat());
    }

    #[test]
    fn a_box_is_crossed_only_by_segments_through_it() {
        let b = TextBox { min: Point::new(0.0, 0.0), max: Point::new(2.0, 1.0) };
        assert!(b.crosses(Point::new(-1.0, 0.5), Point::new(3.0, 0.5)));
        assert!(b.crosses(Point::new(1.0, 0.5), Point::new(1.0, 0.6)));
        assert!(!b.crosses(Point::new(-1.0, 1.5), Point::new(3.0, 1.5)));
        assert!(!b.crosses(Point::new(-1.0, -1.0), Point::new(-0.1, 2.0)));
        // Touching an edge does not count.
        assert!(!b.crosses(Point::new(-1.0, 1.0), Point::new(3.0, 1.0)));
        assert!(b.overlaps(&TextBox { min: Point::new(1.9, 0.9), max: Point::new(3.0, 2.0) }));
        assert!(!b.overlaps(&TextBox { min: Point::new(2.0, 0.0), max: Point::new(3.0, 2.0) }));
    }

    #[test]
    fn letters_of_nearby_points_do_not_overlap() {
        // Three points a third of a letter height apart on a line: the naive placement
        // (all above) would stack them.
        let h = 1.0;
        let mut p = Polygon::of_points();
        for (i, s) in ["a", "b", "m"].iter().enumerate() {
            p.letter(Point::new(0.4 * i as f64, 0.0), *s, h, Vector::new(0.0, 1.0), None);
        }
        p.segment(Point::new(0.0, 0.0), Point::new(0.8, 0.0));
        let placed = p.place();
        assert_eq!(placed.len(), 3);
        let boxes: Vec<TextBox> = placed.iter().map(Placed::bounds).collect();
        for i in 0..3 {
            for j in 0..i {
                assert!(!boxes[i].overlaps(&boxes[j]), "{i} {j}: {placed:?}");
            }
            assert!(!boxes[i].crosses(Point::new(0.0, 0.0), Point::new(0.8, 0.0)));
        }
        // The first keeps its preferred place: straight above, LABEL_GAP clear.
        assert!((placed[0].centre - Point::new(0.0, (LABEL_GAP + 0.5) * h)).norm() < 1e-12);
    }

    #[test]
    fn coincident_points_share_one_label() {
        // p and b equal to rounding (as 0.1 + 0.2 and 0.3): one label p≡b. c only close to a
        // (0.1 letter heights): its own letter, not "a≡c" (≡ claims the points coincide).
        let mut p = Polygon::of_points();
        p.letter(Point::new(0.3, 0.0), "p", 1.0, Vector::new(-1.0, 0.0), None);
        p.letter(Point::new(0.1 + 0.2, 0.0), "b", 1.0, Vector::new(1.0, 0.0), None);
        p.letter(Point::new(3.0, 0.0), "a", 1.0, Vector::new(1.0, 0.0), None);
        p.letter(Point::new(3.1, 0.0), "c", 1.0, Vector::new(1.0, 0.0), None);
        let placed = p.place();
        let texts: Vec<&str> = placed.iter().map(|l| l.text.as_str()).collect();
        assert_eq!(texts, ["p≡b", "a", "c"]);
        // Names beside sides are never combined.
        let mut q = Polygon::of_names();
        q.letter(Point::new(0.0, 0.0), "RB", 1.0, Vector::new(1.0, 0.0), None);
        q.letter(Point::new(0.0, 0.0), "RC", 1.0, Vector::new(1.0, 0.0), None);
        assert_eq!(q.place().len(), 2);
    }

    #[test]
    fn candidates_start_in_the_preferred_direction_and_stay_within_reach() {
        let c: Vec<Point> = candidates(Point::new(0.0, 0.0), "nBA", 1.0, Vector::new(2.0, 0.0)).collect();
        assert_eq!(c.len(), TURNS.len() * RINGS.len());
        let w = text_width("nBA", 1.0);
        assert!((c[0] - Point::new(LABEL_GAP + 0.5 * w, 0.0)).norm() < 1e-12);
        for p in &c {
            assert!(p.coords.norm() <= max_distance("nBA", &Runs::flat(), 1.0) + 1e-12);
        }
    }

    #[test]
    fn a_mechanism_letter_keeps_its_clearance_and_off_kept_boxes() {
        // A joint of radius 0.5 at the origin: the letter's box starts LABEL_GAP + 0.5 from
        // it, straight above when nothing is in the way.
        let mut p = Polygon::of_names();
        p.letter_clear(Point::new(0.0, 0.0), "A", 1.0, Vector::new(0.0, 1.0), 0.5);
        let placed = p.place();
        assert!((placed[0].centre - Point::new(0.0, LABEL_GAP + 0.5 + 0.5)).norm() < 1e-12);
        // A symbol above the joint: the letter goes elsewhere, clear of it.
        let symbol = TextBox { min: Point::new(-2.0, 0.2), max: Point::new(2.0, 3.0) };
        let mut q = Polygon::of_names();
        q.keep_off(symbol);
        q.letter_clear(Point::new(0.0, 0.0), "A", 1.0, Vector::new(0.0, 1.0), 0.5);
        let Placed { centre: c, .. } = &q.place()[0];
        assert!(!q.place()[0].bounds().overlaps(&symbol), "{c:?}");
        assert!(c.coords.norm() >= LABEL_GAP + 0.5 + 0.5 - 1e-12);
    }

    /// The placer as first written (every candidate's score counted in full, every segment
    /// clipped): the reference for [`Polygon::place`].
    fn place_in_full(p: &Polygon) -> Vec<Placed> {
        let letters = if p.merge { combine(&p.letters) } else { p.letters.clone() };
        let mut boxes: Vec<TextBox> = Vec::new();
        let mut leaders: Vec<(Point, Point)> = Vec::new();
        let mut out = Vec::new();
        for l in &letters {
            let mut best: Option<(Score, Point, TextBox, Option<Segment>)> = None;
            let (half, shift) = l.half();
            for c in candidates_in(l.at, half, l.height, l.dir, l.clear, l.leader) {
                let bx = TextBox::around(c, half);
                let leader = if l.leader { leader_line(l.at, c, half, l.height) } else { None };
                let hits =
                    boxes.iter().chain(&p.obstacles).filter(|b| b.overlaps(&bx)).count() + usize::from(p.outside(&bx));
                let through =
                    leader.map_or(0, |(a, b)| boxes.iter().chain(&p.obstacles).filter(|x| x.crosses(a, b)).count());
                let crossed = p.segments.iter().chain(&leaders).filter(|(a, b)| bx.crosses(*a, *b)).count();
                let g = Vector::new(p.gap, p.gap);
                let near = if p.gap > 0.0 {
                    boxes.iter().filter(|b| TextBox { min: b.min - g, max: b.max + g }.overlaps(&bx)).count()
                } else {
                    0
                };
                let score = (hits, through, crossed, near);
                if best.as_ref().is_none_or(|(s, ..)| score < *s) {
                    best = Some((score, c, bx, leader));
                }
                if score == (0, 0, 0, 0) {
                    break;
                }
            }
            if let Some((_, c, bx, leader)) = best {
                boxes.push(bx);
                leaders.extend(leader);
                let (text, runs, height, color, circled) =
                    (l.text.clone(), l.runs.clone(), l.height, l.color, l.circled);
                out.push(Placed { centre: c + shift, text, runs, height, color, leader, circled });
            }
        }
        out
    }

    #[test]
    fn the_placer_places_as_when_every_score_was_counted_in_full() {
        use rand::{RngExt, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(16);
        let mut crowded = 0;
        for case in 0..800 {
            let p = if case % 2 == 0 { Polygon::of_points() } else { Polygon::of_names() };
            // A third of them with a gap between letters (force figures' names).
            let mut p = p.apart(if case % 3 == 0 { 0.1 } else { 0.0 });
            // Points on a small grid (so segments touch box edges exactly) and anywhere.
            // Crowded, and spread out (so that most of the polygon is far from a letter).
            let spread = [1.0, 1.0, 4.0, 12.0][case % 4];
            let pt = |rng: &mut rand_chacha::ChaCha8Rng| {
                if rng.random_range(0..2) == 0 {
                    Point::new(rng.random_range(-4..4) as f64 * 0.5, rng.random_range(-4..4) as f64 * 0.5) * spread
                } else {
                    Point::new(rng.random_range(-3.0..3.0), rng.random_range(-3.0..3.0)) * spread
                }
            };
            let n = rng.random_range(1..25);
            let points: Vec<Point> = (0..n).map(|_| pt(&mut rng)).collect();
            for w in points.windows(2) {
                p.segment(w[0], w[1]);
            }
            for _ in 0..rng.random_range(0..4) {
                let (a, b) = (pt(&mut rng), pt(&mut rng));
                let min = Point::new(a.x.min(b.x), a.y.min(b.y));
                p.keep_off(TextBox { min, max: Point::new(a.x.max(b.x), a.y.max(b.y)) });
            }
            for (i, &at) in points.iter().enumerate() {
                let dir = Vector::new(rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0));
                let text = ["a", "b", "m", "RB", "R12", "Fi3"][i % 6];
                match rng.random_range(0..4) {
                    0 => p.letter(at, text, 0.5, dir, None),
                    1 => p.name_with_leader(at, text, 0.5, dir, Some(Aci::RED)),
                    2 => p.circled(at, "3", 0.5, dir, 0.1),
                    _ => p.letter_clear(at, text, 0.5, dir, 0.2),
                }
            }
            let placed = p.place();
            assert_eq!(placed, place_in_full(&p), "case {case}");
            crowded += usize::from(placed.iter().any(|l| l.leader.is_some()));
        }
        assert!(crowded > 50, "{crowded}");
    }
}
