//! Velocity and acceleration polygons, typed on named points: a pole and points reached
//! from it (each by a physical vector from the pole or from an earlier point), the sides
//! to draw between them, and the construction lines of the graph-analytical method. Any
//! mechanism describes its polygons this way (the four-bar does in its figure); the code
//! here draws them without knowing which mechanism they come from.
//!
//! Points are numbered: [`POLE`] (0) is the pole, `i + 1` the `i`-th of
//! [`PointPolygon::points`]. The letters are placed by [`crate::figure::shared::labels`], so that they stay
//! readable in a small polygon.

use crate::draw::{Drawing, Shape};
use crate::geom::{Point, Vector};

use crate::figure::shared::labels;
use crate::figure::shared::vocab::{self, Scale, Sizes, layer_of, layers, unit_or, vector};

/// Radius of a marked point's dot ([`PointPolygon::marks`]), in joint radii.
pub const MARK_RADIUS: f64 = 0.35;

/// The number of the pole among a polygon's points.
pub const POLE: usize = 0;

/// A named point of a polygon: its letter and where it is.
#[derive(Debug, Clone, PartialEq)]
pub struct NamedPoint {
    /// The letter (`a`, `b'`, `nBA` …).
    pub name: String,
    /// The point it is reached from ([`POLE`] for a velocity or acceleration of a point;
    /// another point for a component: n_BA is reached from a′ by a_BA^n).
    pub from: usize,
    /// The physical vector (m/s, m/s² …) from `from` to this point. Its letter sits on the
    /// side away from `from`.
    pub v: Vector,
}

/// How a side of a polygon is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SideKind {
    /// A vector: an arrow on the polygon's layer.
    Vector,
    /// A component found by construction (a tangential acceleration): a dashed arrow on
    /// the construction layer.
    Component,
    /// A line without arrowhead (the image of a link, such as a′b′).
    Image,
}

/// A side of a polygon: from one point to another.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Side {
    /// Start point's number.
    pub from: usize,
    /// End point's number.
    pub to: usize,
    /// How it is drawn.
    pub kind: SideKind,
}

/// A construction line: the known direction of an unknown component, drawn dashed through a
/// point along `dir`, reaching a little past the point it finds (`reaches`) on both sides.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Direction {
    /// The point the line passes through.
    pub through: usize,
    /// Its direction (any length; model directions such as ⊥AB).
    pub dir: Vector,
    /// The point found on it.
    pub reaches: usize,
}

/// A velocity or acceleration polygon.
#[derive(Debug, Clone, PartialEq)]
pub struct PointPolygon {
    /// The pole's letter (`p`, `π`).
    pub pole: String,
    /// The points whose directions the pole's letter points away from.
    pub pole_away: Vec<usize>,
    /// The named points, in the order their letters are placed (the first get their
    /// preferred places).
    pub points: Vec<NamedPoint>,
    /// Construction lines, drawn first.
    pub directions: Vec<Direction>,
    /// Sides, drawn in order.
    pub sides: Vec<Side>,
    /// Points marked with a dot (images of centroids, which no side ends at); their letters
    /// may go further out with a leader ([`labels::Polygon::name_with_leader`]).
    pub marks: Vec<usize>,
}

impl PointPolygon {
    /// Every point relative to the pole (physical units), the pole first: for sizing a
    /// panel over a whole motion.
    pub fn physical_points(&self) -> Vec<Vector> {
        let mut out: Vec<Vector> = Vec::with_capacity(self.points.len() + 1);
        out.push(Vector::zeros());
        for p in &self.points {
            let v = if p.from == POLE { p.v } else { out[p.from] + p.v };
            out.push(v);
        }
        out
    }

    /// Every point as drawn with the pole at `pole` at `scale`, the pole first.
    pub fn drawn_points(&self, scale: Scale, pole: Point) -> Vec<Point> {
        let mut out: Vec<Point> = Vec::with_capacity(self.points.len() + 1);
        out.push(pole);
        for p in &self.points {
            let at = out[p.from] + scale.draw(p.v);
            out.push(at);
        }
        out
    }
}

/// Draws `poly` on `layer` (its construction lines and components on `CONSTRUCTION`) with
/// the pole at `pole`, at `scale`.
pub fn draw(d: &mut Drawing, poly: &PointPolygon, layer: layers::Layer, scale: Scale, pole: Point, s: Sizes) {
    draw_keeping_off(d, poly, layer, scale, pole, s, &[]);
}

/// [`draw`], its letters kept off the texts `keep_off` (a panel's title, say).
pub fn draw_keeping_off(
    d: &mut Drawing,
    poly: &PointPolygon,
    layer: layers::Layer,
    scale: Scale,
    pole: Point,
    s: Sizes,
    keep_off: &[labels::TextBox],
) {
    draw_within(d, poly, layer, scale, pole, s, keep_off, None, None);
}

/// [`draw_keeping_off`], its letters inside `within` (its panel) where they can be, its
/// construction lines cut at the edges of `clip` (the panel's drawing area: off its title
/// and its scale bar).
#[allow(clippy::too_many_arguments)]
pub fn draw_within(
    d: &mut Drawing,
    poly: &PointPolygon,
    layer: layers::Layer,
    scale: Scale,
    pole: Point,
    s: Sizes,
    keep_off: &[labels::TextBox],
    within: Option<labels::TextBox>,
    clip: Option<labels::TextBox>,
) {
    let l = layer_of(d, layer);
    let c = layer_of(d, layers::CONSTRUCTION);
    let pts = poly.drawn_points(scale, pole);
    let mut letters = labels::Polygon::of_points();
    for b in keep_off {
        letters.keep_off(*b);
    }
    if let Some(w) = within {
        letters.keep_within(w);
    }
    // Directions: full dashed lines through their point, reaching a little past the point
    // found on both sides.
    let reach = 4.0 * s.head;
    for dir in &poly.directions {
        let (n, found) = (pts[dir.through], pts[dir.reaches]);
        let u = unit_or(dir.dir, Vector::new(1.0, 0.0));
        let t0 = (found - n).dot(&u);
        let (lo, hi) = (t0.min(0.0) - reach, t0.max(0.0) + reach);
        let Some((from, to)) = clipped((n + u * lo, n + u * hi), clip) else { continue };
        d.add(c, Shape::Line { from, to });
        letters.segment(from, to);
    }
    for side in &poly.sides {
        let (from, to) = (pts[side.from], pts[side.to]);
        match side.kind {
            SideKind::Vector => vector(d, l, from, to - from, s),
            SideKind::Component => vector(d, c, from, to - from, s),
            SideKind::Image => d.add(l, Shape::Line { from, to }),
        }
        letters.segment(from, to);
    }
    for &m in &poly.marks {
        d.add(l, Shape::Circle { center: pts[m], radius: MARK_RADIUS * s.joint });
    }
    vocab::pole(d, l, pole, s);
    let mut away = poly.pole_away.iter().map(|&i| pole - pts[i]);
    let first = away.next().unwrap_or_else(Vector::zeros);
    letters.letter(pole, &poly.pole, s.text, away.fold(first, |acc, v| acc + v), None);
    // Off everything drawn so far (this polygon's lines, the other panels' figures, texts).
    letters.keep_off_drawing(d);
    for (i, p) in poly.points.iter().enumerate() {
        let at = pts[i + 1];
        // A centroid's image, and a construction's point (where a component starts: n_BA,
        // the Coriolis k), may take its letter further out with a leader.
        let construction = poly.sides.iter().any(|s| s.kind == SideKind::Component && s.from == i + 1);
        if construction {
            // A component's name: n_BA, k (Coriolis).
            letters.name_with_leader(at, labels::Label::quantity(&p.name), s.text, at - pts[p.from], None);
        } else if poly.marks.contains(&(i + 1)) {
            letters.name_with_leader(at, &p.name, s.text, at - pts[p.from], None);
        } else {
            letters.letter(at, &p.name, s.text, at - pts[p.from], None);
        }
    }
    letters.draw(d, l);
}

/// The part of the segment inside `clip` (Liang–Barsky), `None` when it has none; the
/// segment itself without a clip.
fn clipped((a, b): (Point, Point), clip: Option<labels::TextBox>) -> Option<(Point, Point)> {
    let Some(c) = clip else { return Some((a, b)) };
    let d = b - a;
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [(-d.x, a.x - c.min.x), (d.x, c.max.x - a.x), (-d.y, a.y - c.min.y), (d.y, c.max.y - a.y)] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
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
    (t0 < t1).then(|| (a + d * t0, a + d * t1))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figure::shared::vocab::{ModelUnits, content_drawing};

    /// A triangle polygon: p → a, p → b, a → b, with b also reached as a component.
    fn triangle() -> PointPolygon {
        PointPolygon {
            pole: "p".into(),
            pole_away: vec![1, 2],
            points: vec![
                NamedPoint { name: "a".into(), from: POLE, v: Vector::new(2.0, 0.0) },
                NamedPoint { name: "b".into(), from: 1, v: Vector::new(0.0, 1.0) },
            ],
            directions: vec![Direction { through: 1, dir: Vector::new(0.0, 3.0), reaches: 2 }],
            sides: vec![
                Side { from: POLE, to: 1, kind: SideKind::Vector },
                Side { from: 1, to: 2, kind: SideKind::Component },
                Side { from: POLE, to: 2, kind: SideKind::Image },
            ],
            marks: vec![],
        }
    }

    #[test]
    fn points_are_reached_from_their_points_at_the_scale() {
        let poly = triangle();
        let phys = poly.physical_points();
        assert_eq!(phys, vec![Vector::zeros(), Vector::new(2.0, 0.0), Vector::new(2.0, 1.0)]);
        // 0.5 units per drawn mm, model in mm: a vector of 2 is 4 mm long.
        let scale = Scale::new(0.5, ModelUnits::MM);
        let drawn = poly.drawn_points(scale, Point::new(10.0, 10.0));
        assert_eq!(drawn, vec![Point::new(10.0, 10.0), Point::new(14.0, 10.0), Point::new(14.0, 12.0)]);
    }

    #[test]
    fn sides_are_drawn_by_their_kind_with_one_letter_per_point() {
        let poly = triangle();
        let s = Sizes::for_length(10.0);
        let mut d = content_drawing(crate::draw::DimStyle { text_height: s.text, arrow_size: s.head });
        let scale = Scale::new(0.5, ModelUnits::MM);
        draw(&mut d, &poly, layers::VELOCITY, scale, Point::new(0.0, 0.0), s);
        let (vel, con) = (layer_of(&d, layers::VELOCITY), layer_of(&d, layers::CONSTRUCTION));
        let on =
            |layer: usize, f: fn(&Shape) -> bool| d.entities.iter().filter(|e| e.layer == layer && f(&e.shape)).count();
        assert_eq!(on(vel, |s| matches!(s, Shape::Arrow { .. })), 1);
        assert_eq!(on(con, |s| matches!(s, Shape::Arrow { .. })), 1);
        assert_eq!(on(con, |s| matches!(s, Shape::Line { .. })), 1);
        assert_eq!(on(vel, |s| matches!(s, Shape::Line { .. })), 1);
        let texts: Vec<&str> = d
            .entities
            .iter()
            .filter_map(|e| match &e.shape {
                Shape::Text { value, .. } => Some(value.as_str()),
                _ => None,
            })
            .collect();
        assert_eq!(texts, ["p", "a", "b"]);
    }
}
