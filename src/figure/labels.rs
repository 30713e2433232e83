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
//! Everything here is deterministic: the same polygon gives the same letters in the same
//! places.

use crate::draw::parts::text_width;
use crate::draw::{Aci, Drawing, Entity, HAlign, LineType, Shape, VAlign};
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
/// The separator between the letters of coincident points.
pub const SAME_POINT: &str = "≡";
/// Directions tried, in multiples of [`TURN`] from the preferred direction, in order.
const TURNS: [f64; 16] = [0.0, 1.0, -1.0, 2.0, -2.0, 3.0, -3.0, 4.0, -4.0, 5.0, -5.0, 6.0, -6.0, 7.0, -7.0, 8.0];
/// The step between directions tried: 22.5°.
const TURN: f64 = std::f64::consts::PI / 8.0;

/// An axis-aligned box (an estimated text box), model units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TextBox {
    /// Lower-left corner.
    pub min: Point,
    /// Upper-right corner.
    pub max: Point,
}

impl TextBox {
    /// The estimated box of `text`, `height` high, centred at `centre`: [`label_width`] wide,
    /// one height tall.
    pub fn centred(centre: Point, text: &str, height: f64) -> TextBox {
        TextBox::around(centre, TextBox::half_size(text, height))
    }

    /// Half the width and half the height of [`TextBox::centred`]'s box.
    fn half_size(text: &str, height: f64) -> Vector {
        Vector::new(0.5 * label_width(text, height), 0.5 * height)
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

/// One letter waiting to be placed.
#[derive(Debug, Clone)]
struct Letter {
    at: Point,
    text: String,
    dir: Vector,
    height: f64,
    color: Option<Aci>,
    /// Extra clear distance from the point (a joint circle's radius).
    clear: f64,
}

/// The letters of one polygon and the segments they should keep off; [`Polygon::draw`]
/// places and draws them.
#[derive(Debug, Clone, Default)]
pub struct Polygon {
    letters: Vec<Letter>,
    segments: Vec<(Point, Point)>,
    obstacles: Vec<TextBox>,
    merge: bool,
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

    /// A letter `text` (`height` high, entity colour `color` or the layer's) for the point
    /// `at`, preferably on the side `dir` (any length; zero means above).
    pub fn letter(&mut self, at: Point, text: &str, height: f64, dir: Vector, color: Option<Aci>) {
        self.push(Letter { at, text: text.to_string(), dir, height, color, clear: 0.0 });
    }

    /// A letter `text` for the point `at` that keeps `clear` (model units, such as a joint
    /// circle's radius) more than [`LABEL_GAP`] between the point and its box, preferably
    /// on the side `dir`.
    pub fn letter_clear(&mut self, at: Point, text: &str, height: f64, dir: Vector, clear: f64) {
        self.push(Letter { at, text: text.to_string(), dir, height, color: None, clear });
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

    /// A segment of the polygon that letters should not cover.
    pub fn segment(&mut self, a: Point, b: Point) {
        if a.x.is_finite() && a.y.is_finite() && b.x.is_finite() && b.y.is_finite() {
            self.segments.push((a, b));
        }
    }

    /// The labels: (centre, text, height, colour), after combining coincident points.
    pub fn place(&self) -> Vec<(Point, String, f64, Option<Aci>)> {
        let letters = if self.merge { combine(&self.letters) } else { self.letters.clone() };
        let mut boxes: Vec<TextBox> = Vec::with_capacity(letters.len());
        let mut out = Vec::with_capacity(letters.len());
        for l in &letters {
            let mut best: Option<((usize, usize), Point, TextBox)> = None;
            let half = TextBox::half_size(&l.text, l.height);
            for c in candidates_clear(l.at, &l.text, l.height, l.dir, l.clear) {
                let bx = TextBox::around(c, half);
                let hits = boxes.iter().chain(&self.obstacles).filter(|b| b.overlaps(&bx)).count();
                let crossed = self.segments.iter().filter(|(a, b)| bx.crosses(*a, *b)).count();
                let score = (hits, crossed);
                if best.as_ref().is_none_or(|(s, _, _)| score < *s) {
                    best = Some((score, c, bx));
                }
                if score == (0, 0) {
                    break;
                }
            }
            if let Some((_, c, bx)) = best {
                boxes.push(bx);
                out.push((c, l.text.clone(), l.height, l.color));
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
        let boxes = placed.iter().map(|(at, value, height, _)| TextBox::centred(*at, value, *height)).collect();
        for (at, value, height, color) in placed {
            let shape =
                Shape::Text { at, height, value, halign: HAlign::Center, valign: VAlign::Middle, rotation: 0.0 };
            d.push(Entity { layer, color, linetype, shape });
        }
        boxes
    }
}

/// Letters whose points lie within [`COINCIDENT`] heights of an earlier letter's point join
/// that letter's label (`a≡b`), which keeps the earlier letter's place and direction.
fn combine(letters: &[Letter]) -> Vec<Letter> {
    let mut out: Vec<Letter> = Vec::with_capacity(letters.len());
    for l in letters {
        match out.iter_mut().find(|o| (o.at - l.at).norm() < COINCIDENT * o.height.min(l.height)) {
            Some(o) => {
                o.text.push_str(SAME_POINT);
                o.text.push_str(&l.text);
                if o.dir.norm() == 0.0 {
                    o.dir = l.dir;
                }
            }
            None => out.push(l.clone()),
        }
    }
    out
}

/// Estimated width of a label: [`text_width`], with [`SAME_POINT`] as wide as `=` (DejaVu
/// Sans draws both 1716 font units wide; `text_width` would count it as an average letter,
/// and a combined label `a≡b≡m` would print over its neighbours).
pub fn label_width(text: &str, height: f64) -> f64 {
    text_width(&text.replace(SAME_POINT, "="), height)
}

/// Unit vector of `v`, or `fallback` for a zero or non-finite `v`.
fn unit(v: Vector, fallback: Vector) -> Vector {
    let n = v.norm();
    if n > 0.0 && n.is_finite() { v / n } else { fallback }
}

/// Candidate centres for `text` at `at`, in the order they are tried (see the module docs).
pub fn candidates(at: Point, text: &str, height: f64, dir: Vector) -> impl Iterator<Item = Point> {
    candidates_clear(at, text, height, dir, 0.0)
}

/// [`candidates`] for a letter whose box keeps `clear` more from its point.
fn candidates_clear(at: Point, text: &str, height: f64, dir: Vector, clear: f64) -> impl Iterator<Item = Point> {
    let u0 = unit(dir, Vector::new(0.0, 1.0));
    let base = u0.y.atan2(u0.x);
    let (hw, hh) = (0.5 * label_width(text, height), 0.5 * height);
    // Lazy: most letters take their first candidate, so the directions are not computed
    // ahead (a run places some ten thousand letters).
    RINGS.into_iter().flat_map(move |ring| {
        TURNS.into_iter().map(move |turn| {
            let a = base + turn * TURN;
            let u = Vector::new(a.cos(), a.sin());
            // From the box's centre to its edge along u.
            let reach = (hw / u.x.abs().max(1e-12)).min(hh / u.y.abs().max(1e-12));
            at + u * (ring * (LABEL_GAP * height + clear + reach))
        })
    })
}

/// The farthest a label's centre can be from its point: the last ring in the worst
/// direction.
pub fn max_distance(text: &str, height: f64) -> f64 {
    let (hw, hh) = (0.5 * label_width(text, height), 0.5 * height);
    RINGS[RINGS.len() - 1] * (LABEL_GAP * height + hw.hypot(hh))
}

#[cfg(test)]
mod tests {
    use super::*;

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
            p.letter(Point::new(0.4 * i as f64, 0.0), s, h, Vector::new(0.0, 1.0), None);
        }
        p.segment(Point::new(0.0, 0.0), Point::new(0.8, 0.0));
        let placed = p.place();
        assert_eq!(placed.len(), 3);
        let boxes: Vec<TextBox> = placed.iter().map(|(c, t, h, _)| TextBox::centred(*c, t, *h)).collect();
        for i in 0..3 {
            for j in 0..i {
                assert!(!boxes[i].overlaps(&boxes[j]), "{i} {j}: {placed:?}");
            }
            assert!(!boxes[i].crosses(Point::new(0.0, 0.0), Point::new(0.8, 0.0)));
        }
        // The first keeps its preferred place: straight above, LABEL_GAP clear.
        assert!((placed[0].0 - Point::new(0.0, (LABEL_GAP + 0.5) * h)).norm() < 1e-12);
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
        let texts: Vec<&str> = placed.iter().map(|l| l.1.as_str()).collect();
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
            assert!(p.coords.norm() <= max_distance("nBA", 1.0) + 1e-12);
        }
    }

    #[test]
    fn a_mechanism_letter_keeps_its_clearance_and_off_kept_boxes() {
        // A joint of radius 0.5 at the origin: the letter's box starts LABEL_GAP + 0.5 from
        // it, straight above when nothing is in the way.
        let mut p = Polygon::of_names();
        p.letter_clear(Point::new(0.0, 0.0), "A", 1.0, Vector::new(0.0, 1.0), 0.5);
        let placed = p.place();
        assert!((placed[0].0 - Point::new(0.0, LABEL_GAP + 0.5 + 0.5)).norm() < 1e-12);
        // A symbol above the joint: the letter goes elsewhere, clear of it.
        let symbol = TextBox { min: Point::new(-2.0, 0.2), max: Point::new(2.0, 3.0) };
        let mut q = Polygon::of_names();
        q.keep_off(symbol);
        q.letter_clear(Point::new(0.0, 0.0), "A", 1.0, Vector::new(0.0, 1.0), 0.5);
        let (c, t, h, _) = &q.place()[0];
        assert!(!TextBox::centred(*c, t, *h).overlaps(&symbol), "{c:?}");
        assert!(c.coords.norm() >= LABEL_GAP + 0.5 + 0.5 - 1e-12);
    }
}
