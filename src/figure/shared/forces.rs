//! Force figures (seed 003, Figs. 4 and 5 and its last section), typed on named vectors:
//! a force polygon is a chain of named vectors from its pole, head to tail, and its
//! resultants drawn across it (the reactions found from it, or the side that closes it).
//! A mechanism draws one polygon per group it isolates (the four-bar: the dyad's, Fig. 4,
//! and the crank's, Fig. 5, each with its own pole), a table of the magnitudes, and the
//! reactions on the mechanism as named vectors at points, at the same force scale. The code
//! here draws them without knowing which mechanism they come from.
//!
//! Every vector is named. A name goes beside its vector's middle, preferably on the outside
//! of the polygon; a name that finds no free place there (a short vector among others in a
//! small polygon) goes further out with a leader line to its vector's middle
//! ([`crate::figure::shared::labels::Polygon::name_with_leader`]), clear of the other names. A resultant
//! that would lie on a side already drawn (R_B, R_C^t and R_C on one line when the rocker's
//! loads are small) is drawn beside it, parallel, [`OFFSET`] arrowheads away, so both stay
//! visible.

use crate::draw::parts::widest_text_width;
use crate::draw::{Aci, Drawing, Entity, HAlign, LineType, Shape, VAlign};
use crate::geom::{Point, Vector, cross, perp};

use crate::figure::shared::labels::{self, TextBox};
use crate::figure::shared::sheet;
use crate::figure::shared::vocab::{Scale, Sizes, layer_of, layers, unit_or};

/// Colour of the resultants of a polygon (the reactions found from it).
pub const RESULTANT: Aci = Aci::RED;

/// Height of a vector's name in the force polygons, in letter heights.
pub const NAME_HEIGHT: f64 = 0.8;

/// Names within this many letter heights of a polygon's pole (the pole's own letter, the
/// names of the vectors whose middle is that near) stand in a crowd: the four-bar's f, R_An,
/// G_21, F_i21, G_22, F_i22 when R_An is short (issue 31).
pub const CROWD_RADIUS: f64 = 4.0;

/// A name in the crowd about the pole is placed as if this many times its size, and drawn
/// at its size: so it stands at least (CROWD_PAD − 1)/2 of its height (and of its width)
/// off every other name. (1.5 pushed the other names of the four-bar's tall, narrow dyad
/// figure at φ1 = 270° onto its leaders; 1.3 keeps tests/labels_all.rs at 0.)
pub const CROWD_PAD: f64 = 1.3;

/// The least gap between two names of one figure, in letter heights (0.55 mm at
/// the sheets' 2.5 mm letters): short vectors' names away from the pole (the four-bar's
/// G_21 and G_22 at φ1 = 80°, 0.04 mm apart before) stand apart, not touching.
pub const NAME_GAP: f64 = 0.22;

/// How far a resultant lying on a side already drawn is moved beside it, in arrowhead
/// lengths (per step: a second one on the same line goes twice as far).
pub const OFFSET: f64 = 0.5;

/// Two drawn segments lie on one line when the sine of the angle between them is below
/// this, each end of one is within [`OFFSET`]`/2` arrowheads of the other's line, and
/// they share more than half an arrowhead of length.
pub const COLLINEAR_SIN: f64 = 0.05;

/// A named physical vector (N for forces).
#[derive(Debug, Clone, PartialEq)]
pub struct NamedVector {
    /// Its name (`G21`, `RAn` …).
    pub name: String,
    /// The vector, physical units.
    pub v: Vector,
    /// Whether the name is a quantity's symbol and its subscript (`R` + `A`, `F` + `i2`:
    /// drawn R_A, [`labels::Label::quantity`]), not a name the user gave (a load's `gas`,
    /// drawn as written).
    pub quantity: bool,
}

impl NamedVector {
    /// `v` named `name`, a quantity's symbol and its subscript (`RA`, `Fi2`, `G21`).
    pub fn new(name: &str, v: Vector) -> NamedVector {
        NamedVector { name: name.to_string(), v, quantity: true }
    }

    /// `v` named `name` as the user wrote it (a load's name): drawn flat.
    pub fn as_written(name: &str, v: Vector) -> NamedVector {
        NamedVector { name: name.to_string(), v, quantity: false }
    }

    /// Its name as drawn.
    pub fn label(&self) -> labels::Label {
        if self.quantity { labels::Label::quantity(&self.name) } else { labels::Label::from(&self.name) }
    }
}

/// A resultant drawn across a polygon: from one vertex to another, its name at the
/// fraction `name_at` of its length.
#[derive(Debug, Clone, PartialEq)]
pub struct Resultant {
    /// Its name (`RA`).
    pub name: String,
    /// Start vertex (0 the pole, `i` the end of the chain's `i`-th vector, from 1).
    pub from: usize,
    /// End vertex.
    pub to: usize,
    /// Where along it the name goes (0 at the start, 1 at the end).
    pub name_at: f64,
}

/// A force polygon: a chain of named vectors from the pole, and its resultants.
#[derive(Debug, Clone, PartialEq)]
pub struct ForcePolygon {
    /// The pole's letter (`f`).
    pub pole: String,
    /// The chain, from the pole, head to tail.
    pub chain: Vec<NamedVector>,
    /// Resultants drawn across it.
    pub resultants: Vec<Resultant>,
    /// How many of the chain's last vectors are the unknowns that closing the polygon finds
    /// (the dyad's R_C^t and R_A^t): drawn in [`RESULTANT`] red, as the resultants.
    pub found: usize,
}

impl ForcePolygon {
    /// Vertices of the chain relative to the pole (physical units): the pole, then the end
    /// of each vector; the last is the pole again when the chain closes.
    pub fn vertices(&self) -> Vec<Vector> {
        let mut pts = Vec::with_capacity(self.chain.len() + 1);
        let mut p = Vector::zeros();
        pts.push(p);
        for nv in &self.chain {
            p += nv.v;
            pts.push(p);
        }
        pts
    }

    /// Every point the polygon reaches, relative to the pole (physical units): used to size
    /// its panel over a whole motion.
    pub fn physical_points(&self) -> Vec<Vector> {
        self.vertices()
    }

    /// The resultant named `name` as a physical vector (from its start vertex to its end).
    pub fn resultant(&self, name: &str) -> Option<Vector> {
        let v = self.vertices();
        self.resultants.iter().find(|r| r.name == name).map(|r| v[r.to] - v[r.from])
    }
}

/// Draws `poly` with the pole at `pole`, at `scale`, on the `FORCES` layer: the chain's
/// arrows, the resultants in [`RESULTANT`] red (moved beside a side they would lie on), and
/// every vector's name placed by [`labels::Polygon`] clear of the boxes `keep_off` (texts
/// drawn around it). Returns the names' boxes.
pub fn draw(
    d: &mut Drawing,
    poly: &ForcePolygon,
    scale: Scale,
    pole: Point,
    s: Sizes,
    keep_off: &[TextBox],
) -> Vec<TextBox> {
    draw_within(d, poly, scale, pole, s, keep_off, None)
}

/// [`draw`], the names inside `within` (the figure's panel) where they can be.
pub fn draw_within(
    d: &mut Drawing,
    poly: &ForcePolygon,
    scale: Scale,
    pole: Point,
    s: Sizes,
    keep_off: &[TextBox],
    within: Option<TextBox>,
) -> Vec<TextBox> {
    let l = layer_of(d, layers::FORCES);
    let mut names = labels::Polygon::of_names().apart(NAME_GAP * s.text);
    for b in keep_off {
        names.keep_off(*b);
    }
    if let Some(w) = within {
        names.keep_within(w);
    }
    let pts: Vec<Point> = poly.vertices().into_iter().map(|v| pole + scale.draw(v)).collect();
    let centroid = Point::from(pts.iter().map(|p| p.coords).sum::<Vector>() / pts.len() as f64);
    crate::figure::shared::vocab::pole(d, l, pole, s);
    // The pole's letter, and the names about it: in the crowd ([`CROWD_RADIUS`]), placed
    // larger than drawn ([`CROWD_PAD`]), so that they stand apart.
    names.letter(pole, &poly.pole, CROWD_PAD * s.text, pole - centroid, None);
    // Every segment drawn so far, for resultants to keep off.
    let mut drawn: Vec<(Point, Point)> = Vec::new();
    // The names: (drawn segment, name, force, where along it, colour).
    type Named = ((Point, Point), labels::Label, Vector, f64, Option<Aci>);
    let mut named: Vec<Named> = Vec::new();
    let first_found = poly.chain.len().saturating_sub(poly.found);
    for (i, nv) in poly.chain.iter().enumerate() {
        let seg = (pts[i], pts[i + 1]);
        let color = (i >= first_found).then_some(RESULTANT);
        if arrow(d, l, color, seg, s) {
            drawn.push(seg);
        }
        names.segment(seg.0, seg.1);
        named.push((seg, nv.label(), nv.v, 0.5, color));
    }
    for r in &poly.resultants {
        let seg = (pts[r.from], pts[r.to]);
        let placed = beside(seg, &drawn, centroid, s);
        if arrow(d, l, Some(RESULTANT), placed, s) {
            drawn.push(placed);
        }
        names.segment(placed.0, placed.1);
        let v = pts[r.to] - pts[r.from];
        named.push((placed, labels::Label::quantity(&r.name), v, r.name_at, Some(RESULTANT)));
    }
    // The shortest vectors' names first: they have the fewest places beside them (a long
    // vector's name finds room anywhere along it).
    named.sort_by(|a, b| (a.0.1 - a.0.0).norm().total_cmp(&(b.0.1 - b.0.0).norm()));
    for (seg, text, v, at, color) in named {
        name(&mut names, seg, text, v, (at, pole), centroid, color, s);
    }
    // Off everything drawn so far (this figure's arrows, the other figures, texts).
    names.keep_off_drawing(d);
    let mut boxes = Vec::new();
    for mut p in names.place() {
        // The crowd's names drawn at their size, their leaders to their boxes as drawn.
        for h in [s.text, NAME_HEIGHT * s.text] {
            if (p.height - CROWD_PAD * h).abs() <= 1e-9 * h {
                p.height = h;
                let bx = p.bounds();
                p.leader = p.leader.map(|(from, _)| (from, edge_towards(&bx, from)));
            }
        }
        boxes.push(p.bounds());
        labels::draw_placed(d, l, &p, Some(LineType::Continuous));
    }
    boxes
}

/// The point of the edge of `bx` on the line from its centre to `at` (outside it).
fn edge_towards(bx: &TextBox, at: Point) -> Point {
    let c = Point::from((bx.min.coords + bx.max.coords) / 2.0);
    let (half, v) = ((bx.max - bx.min) / 2.0, at - c);
    let t = (half.x / v.x.abs().max(1e-300)).min(half.y / v.y.abs().max(1e-300)).min(1.0);
    c + v * t
}

/// An arrow on `layer` in `color` (or the layer's); `false` (nothing drawn) for a vector
/// too short to see.
fn arrow(d: &mut Drawing, layer: usize, color: Option<Aci>, (from, to): (Point, Point), s: Sizes) -> bool {
    let len = (to - from).norm();
    if len.is_nan() || len <= 0.01 * s.head {
        return false;
    }
    d.push(Entity { layer, color, linetype: None, shape: Shape::Arrow { from, to, head: s.head } });
    true
}

/// The name of the drawn segment `from`–`to` (the physical vector `v`: a zero force is not
/// named) for `names`, at the fraction `at` of its length, preferably on the side away from
/// `inside`; a name that cannot sit beside its vector (a short one in a crowd) goes further
/// out with a leader ([`labels::Polygon::name_with_leader`]). A name whose vector's middle
/// is within [`CROWD_RADIUS`] letters of the `pole` is in its crowd: placed outward from
/// the pole, as if [`CROWD_PAD`] times its size.
#[allow(clippy::too_many_arguments)]
fn name(
    names: &mut labels::Polygon,
    (from, to): (Point, Point),
    text: labels::Label,
    v: Vector,
    (at, pole): (f64, Point),
    inside: Point,
    color: Option<Aci>,
    s: Sizes,
) {
    if v.norm().is_nan() || v.norm() == 0.0 {
        return;
    }
    let seg = to - from;
    let len = seg.norm();
    let mid = from + seg * at;
    let h = NAME_HEIGHT * s.text;
    // Outwards: across the segment, away from the polygon's centre (from the centre when
    // the segment is too short to have a direction).
    let mut n = if len > 0.0 { perp(seg / len) } else { unit_or(mid - inside, Vector::new(0.0, 1.0)) };
    if n.dot(&(mid - inside)) < 0.0 {
        n = -n;
    }
    if (mid - pole).norm() <= CROWD_RADIUS * s.text {
        // Outward from the pole: on the vector's side away from it, leaning away.
        let out = unit_or(mid - pole, n);
        let across = if n.dot(&out) < 0.0 { -n } else { n };
        names.name_with_leader(mid, text, CROWD_PAD * h, across + out, color);
        return;
    }
    names.name_with_leader(mid, text, h, n, color);
}

/// Where to draw the resultant `seg` so that it lies on none of the segments `drawn`:
/// itself when it lies on none, else moved parallel by 1, 2, 3 or 4 × [`OFFSET`] arrowheads,
/// first to the side away from `inside`, then to the other.
fn beside(seg: (Point, Point), drawn: &[(Point, Point)], inside: Point, s: Sizes) -> (Point, Point) {
    let step = OFFSET * s.head;
    moved_off(seg, drawn, inside, (step, step), |a, b| on_one_line(a, b, s) || on_one_line(b, a, s))
}

/// `seg` itself when it lies on none of `drawn` (by `lies_on`), else moved parallel by
/// `first`, then by `first` plus 1, 2, 3 `step`s, to the side away from `inside`, then to
/// the other, until it lies on none (the last try on the first side when every place is
/// taken).
fn moved_off(
    seg: (Point, Point),
    drawn: &[(Point, Point)],
    inside: Point,
    (first, step): (f64, f64),
    lies_on: impl Fn((Point, Point), (Point, Point)) -> bool,
) -> (Point, Point) {
    let v = seg.1 - seg.0;
    let len = v.norm();
    let clear = |x: (Point, Point)| !drawn.iter().any(|o| lies_on(x, *o));
    if len.is_nan() || len == 0.0 || clear(seg) {
        return seg;
    }
    let u = v / len;
    let mut n = perp(u);
    if n.dot(&(seg.0 + v * 0.5 - inside)) < 0.0 {
        n = -n;
    }
    for side in [n, -n] {
        for k in 0..4 {
            let off = side * (first + step * k as f64);
            let moved = (seg.0 + off, seg.1 + off);
            if clear(moved) {
                return moved;
            }
        }
    }
    let off = n * (first + 4.0 * step);
    (seg.0 + off, seg.1 + off)
}

/// Whether the arrow `a` runs over the line `b` drawn `width` wide (a link, another arrow):
/// the stretch of `a` within `width`/2 of `b`'s line and beside `b` is longer than an
/// arrowhead.
pub fn runs_over(a: (Point, Point), b: (Point, Point), width: f64, s: Sizes) -> bool {
    let (v, w) = (a.1 - a.0, b.1 - b.0);
    let (la, lb) = (v.norm(), w.norm());
    if la.is_nan() || lb.is_nan() || la == 0.0 || lb == 0.0 {
        return false;
    }
    let u = w / lb;
    // Along `a` (t in [0, 1]): the distance across `b`'s line and the place along it, both
    // linear in t; keep the t where |across| ≤ width/2 and 0 ≤ along ≤ |b|.
    let (across0, across1) = (cross(u, a.0 - b.0), cross(u, v));
    let (along0, along1) = ((a.0 - b.0).dot(&u), v.dot(&u));
    let mut range = (0.0f64, 1.0f64);
    for (c0, c1, lo, hi) in [(across0, across1, -0.5 * width, 0.5 * width), (along0, along1, 0.0, lb)] {
        if c1.abs() < 1e-300 {
            if c0 < lo || c0 > hi {
                return false;
            }
        } else {
            let (t0, t1) = ((lo - c0) / c1, (hi - c0) / c1);
            range = (range.0.max(t0.min(t1)), range.1.min(t0.max(t1)));
        }
    }
    (range.1 - range.0) * la > s.head
}

/// Whether the drawn segments `a` and `b` lie on one line over a common stretch (see
/// [`COLLINEAR_SIN`]).
pub fn on_one_line(a: (Point, Point), b: (Point, Point), s: Sizes) -> bool {
    let (va, vb) = (a.1 - a.0, b.1 - b.0);
    let (la, lb) = (va.norm(), vb.norm());
    if !(la > 0.0 && lb > 0.0) {
        return false;
    }
    let u = va / la;
    if cross(u, vb / lb).abs() > COLLINEAR_SIN {
        return false;
    }
    let tol = 0.5 * OFFSET * s.head;
    if cross(u, b.0 - a.0).abs() > tol || cross(u, b.1 - a.0).abs() > tol {
        return false;
    }
    let (t0, t1) = ((b.0 - a.0).dot(&u), (b.1 - a.0).dot(&u));
    let shared = t0.max(t1).min(la) - t0.min(t1).max(0.0);
    shared > 0.5 * s.head
}

/// One row of a table of magnitudes: a name, a value, its unit.
#[derive(Debug, Clone, PartialEq)]
pub struct Magnitude {
    /// The name (`RA`, `Me1`).
    pub name: String,
    /// The value (a force's magnitude; a moment signed, CCW positive).
    pub value: f64,
    /// Its unit (`N`, `N·m`).
    pub unit: String,
    /// Whether the name is a quantity's symbol and its subscript (`R` + `An`, `M` + `e1`:
    /// drawn R_An, M_e1, [`labels::Label::quantity`]), not a name the user gave (a load's
    /// `gas`, drawn as written), as [`NamedVector::quantity`].
    pub quantity: bool,
}

impl Magnitude {
    /// A row named by a quantity's symbol and subscript (`RAn`, `Fi2`, `Me1`).
    pub fn new(name: &str, value: f64, unit: &str) -> Magnitude {
        Magnitude { name: name.to_string(), value, unit: unit.to_string(), quantity: true }
    }

    /// A row named `name` as the user wrote it (a load's name): drawn flat.
    pub fn as_written(name: &str, value: f64, unit: &str) -> Magnitude {
        Magnitude { quantity: false, ..Magnitude::new(name, value, unit) }
    }

    /// Its name as drawn.
    pub fn label(&self) -> labels::Label {
        if self.quantity { labels::Label::quantity(&self.name) } else { labels::Label::from(&self.name) }
    }
}

/// The text of a value in a table of magnitudes: 4 significant digits as the sheets print
/// them ([`sheet::number`]: `52.37 N`, `−1.490 N·m`, `241779 N·mm`); below 5e-4 (rounding
/// noise of a force that vanishes) `0`.
pub fn magnitude_text(value: f64, unit: &str) -> String {
    let v = if value.abs() < 5e-4 { 0.0 } else { value };
    format!("{} {unit}", sheet::number(v))
}

/// Height of a table's rows' text, in letter heights.
pub const TABLE_TEXT: f64 = 0.8;
/// Row pitch of a table, in its text heights.
pub const TABLE_PITCH: f64 = 1.5;

/// The size (width, height) of a table of `count` rows as [`table`] draws it, wide enough
/// for every row of `rows` (the rows of every position of a motion).
pub fn table_size(rows: &[Magnitude], count: usize, s: Sizes) -> Vector {
    let h = TABLE_TEXT * s.text;
    // Room for the texts as the widest reader draws them.
    let name_w = rows.iter().map(|r| widest_text_width(&r.name, h)).fold(0.0, f64::max);
    let value_w = rows.iter().map(|r| widest_text_width(&magnitude_text(r.value, &r.unit), h)).fold(0.0, f64::max);
    Vector::new(name_w + 1.5 * h + value_w, TABLE_PITCH * h * count as f64)
}

/// A table of magnitudes with its upper-left corner at `top_left`, `width` wide: one row
/// per magnitude, the name left, `value unit` right-aligned, on the `FORCES` layer.
pub fn table(d: &mut Drawing, rows: &[Magnitude], top_left: Point, width: f64, s: Sizes) {
    let l = layer_of(d, layers::FORCES);
    let h = TABLE_TEXT * s.text;
    for (i, r) in rows.iter().enumerate() {
        let y = top_left.y - TABLE_PITCH * h * (i as f64 + 1.0) + 0.25 * h;
        // The name as a quantity is written (R_An, M_e1), the value flat.
        let name = r.label();
        for (x, value, runs, halign) in [
            (top_left.x, name.text, name.runs, HAlign::Left),
            (top_left.x + width, magnitude_text(r.value, &r.unit), crate::draw::Runs::flat(), HAlign::Right),
        ] {
            let shape = Shape::Text {
                runs,
                at: Point::new(x, y),
                height: h,
                value,
                halign,
                valign: VAlign::Baseline,
                rotation: 0.0,
            };
            d.push(Entity { layer: l, color: None, linetype: Some(LineType::Continuous), shape });
        }
    }
}

/// A force drawn on the mechanism: the named vector acting at a point, where its arrow is
/// drawn (moved off a link it would lie on), for the letter placer.
#[derive(Debug, Clone, PartialEq)]
pub struct ForceArrow {
    /// The point it acts at.
    pub at: Point,
    /// The force.
    pub force: NamedVector,
    /// The drawn arrow: tail and tip (model units).
    pub arrow: (Point, Point),
}

/// The arrows of `forces` acting at points of the mechanism at `scale` (seed, last section):
/// each from its point, or, when it would run over one of the `links` (R_A along the
/// crank) or an arrow placed before it ([`runs_over`] them drawn a link's width plus an
/// arrowhead's wide), moved beside it by 1.5 joint radii plus [`OFFSET`]
/// arrowheads (and further by [`OFFSET`] steps when that place is taken), to the side away
/// from the mechanism's centre `inside`. Forces too short to see are left out.
pub fn arrows_on_mechanism(
    forces: &[(Point, NamedVector)],
    scale: Scale,
    links: &[(Point, Point)],
    inside: Point,
    s: Sizes,
) -> Vec<ForceArrow> {
    let mut out = Vec::new();
    let mut drawn = links.to_vec();
    // A link's width and an arrowhead's, either side.
    let band = s.link + 2.0 * crate::draw::parts::ARROW_HALF_WIDTH * s.head;
    for (at, nv) in forces {
        let v = scale.draw(nv.v);
        let len = v.norm();
        if len.is_nan() || len <= 0.01 * s.head {
            continue;
        }
        let steps = (1.5 * s.joint + OFFSET * s.head, OFFSET * s.head);
        let arrow = moved_off((*at, *at + v), &drawn, inside, steps, |a, b| runs_over(a, b, band, s));
        drawn.push(arrow);
        out.push(ForceArrow { at: *at, force: nv.clone(), arrow });
    }
    out
}

/// Draws the arrows of [`arrows_on_mechanism`] on the `FORCES` layer, a moved one with a
/// thin connector from its point to its tail; their names are placed with the mechanism's
/// letters (see the four-bar's figure).
pub fn draw_on_mechanism(d: &mut Drawing, arrows: &[ForceArrow], s: Sizes) {
    let l = layer_of(d, layers::FORCES);
    for a in arrows {
        if a.arrow.0 != a.at {
            d.add(l, Shape::Line { from: a.at, to: a.arrow.0 });
        }
        d.add(l, Shape::Arrow { from: a.arrow.0, to: a.arrow.1, head: s.head });
    }
}

#[cfg(test)]
#[allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the code under test calls"
)]
mod tests {
    use super::*;
    use crate::figure::shared::vocab::{ModelUnits, content_drawing};

    /// A weight held by two ropes: W down, then the ropes' forces T1, T2 close the triangle;
    /// a resultant T1 + T2 drawn across it, and a short force P.
    fn hanging_weight() -> ForcePolygon {
        ForcePolygon {
            pole: "f".into(),
            chain: vec![
                NamedVector::new("W", Vector::new(0.0, -10.0)),
                NamedVector::new("P", Vector::new(0.05, 0.0)),
                NamedVector::new("T1", Vector::new(3.95, 5.0)),
                NamedVector::new("T2", Vector::new(-4.0, 5.0)),
            ],
            resultants: vec![Resultant { name: "T".into(), from: 2, to: 4, name_at: 0.5 }],
            found: 0,
        }
    }

    fn drawing(s: Sizes) -> Drawing {
        content_drawing(crate::draw::DimStyle { text_height: s.text, arrow_size: s.head })
    }

    fn arrows(d: &Drawing) -> Vec<(Point, Point)> {
        d.entities
            .iter()
            .filter_map(|e| match e.shape {
                Shape::Arrow { from, to, .. } => Some((from, to)),
                _ => None,
            })
            .collect()
    }

    #[test]
    fn the_chain_runs_head_to_tail_and_closes_at_the_pole() {
        let poly = hanging_weight();
        let v = poly.vertices();
        assert_eq!(v[1], Vector::new(0.0, -10.0));
        assert!((v[4] - Vector::zeros()).norm() < 1e-12);
        assert!((poly.resultant("T").unwrap() - Vector::new(-0.05, 10.0)).norm() < 1e-12);
    }

    #[test]
    fn every_vector_is_an_arrow_with_its_name() {
        let poly = hanging_weight();
        let s = Sizes::for_length(100.0);
        let mut d = drawing(s);
        // 0.1 N per drawn mm: W is 100 mm long, far longer than a letter; P 0.5 mm.
        draw(&mut d, &poly, Scale::new(0.1, ModelUnits::MM), Point::new(0.0, 0.0), s, &[]);
        let a = arrows(&d);
        // W, P, T1, T2, the resultant T.
        assert_eq!(a.len(), 5);
        assert_eq!(a[0], (Point::new(0.0, 0.0), Point::new(0.0, -100.0)));
        let mut names: Vec<&str> = d
            .entities
            .iter()
            .filter_map(|e| match &e.shape {
                Shape::Text { value, .. } => Some(value.as_str()),
                _ => None,
            })
            .collect();
        names.sort_unstable();
        assert_eq!(names, ["P", "T", "T1", "T2", "W", "f"]);
    }

    #[test]
    fn names_of_a_crowd_of_short_vectors_go_out_with_leaders() {
        // Eight vectors a tenth of a letter long around one point, then a long one back: at
        // most two names fit beside the crowd; the others go further out, each with a leader
        // from its vector's middle, no two names overlapping.
        let s = Sizes::for_length(100.0);
        let mut chain: Vec<NamedVector> = (0..8)
            .map(|i| {
                let a = i as f64 * std::f64::consts::FRAC_PI_4;
                NamedVector::new(&format!("G{i}"), Vector::new(a.cos(), a.sin()) * 0.03)
            })
            .collect();
        chain.push(NamedVector::new("R", Vector::new(30.0, 0.0)));
        let poly = ForcePolygon { pole: "f".into(), chain, resultants: vec![], found: 0 };
        let mut d = drawing(s);
        let boxes = draw(&mut d, &poly, Scale::new(0.1, ModelUnits::MM), Point::new(0.0, 0.0), s, &[]);
        assert_eq!(boxes.len(), 10);
        for (i, a) in boxes.iter().enumerate() {
            for b in &boxes[..i] {
                assert!(!a.overlaps(b), "{a:?} {b:?}");
            }
        }
        let leaders: Vec<(Point, Point)> = d
            .entities
            .iter()
            .filter_map(|e| match e.shape {
                Shape::Line { from, to } => Some((from, to)),
                _ => None,
            })
            .collect();
        assert!(leaders.len() >= 4, "{leaders:?}");
        // Each leader starts at a short vector's middle and ends on a name's box.
        let mids: Vec<Point> = {
            let v = poly.vertices();
            (0..8).map(|i| Point::from((v[i] + v[i + 1]) * 0.5 / 0.1)).collect()
        };
        for (from, to) in leaders {
            assert!(mids.iter().any(|m| (from - m).norm() < 1e-9), "{from:?}");
            let on_edge = boxes.iter().any(|b| {
                let inside = to.x >= b.min.x - 1e-9
                    && to.x <= b.max.x + 1e-9
                    && to.y >= b.min.y - 1e-9
                    && to.y <= b.max.y + 1e-9;
                let edge =
                    [to.x - b.min.x, b.max.x - to.x, to.y - b.min.y, b.max.y - to.y].iter().any(|d| d.abs() < 1e-9);
                inside && edge
            });
            assert!(on_edge, "{to:?}");
        }
    }

    #[test]
    fn a_resultant_on_a_side_is_drawn_beside_it() {
        // T runs from the end of P back to the pole: along W (backwards) within 0.5 mm.
        let poly = hanging_weight();
        let s = Sizes::for_length(100.0);
        let mut d = drawing(s);
        draw(&mut d, &poly, Scale::new(0.1, ModelUnits::MM), Point::new(0.0, 0.0), s, &[]);
        let t = arrows(&d)[4];
        // Parallel to its true place (from (0.5, −100) to (0, 0)), OFFSET arrowheads or more away.
        let true_seg = (Point::new(0.5, -100.0), Point::new(0.0, 0.0));
        let u = (true_seg.1 - true_seg.0).normalize();
        let off = cross(u, t.0 - true_seg.0);
        assert!(off.abs() >= OFFSET * s.head - 1e-9, "{off}");
        assert!((cross(u, t.1 - true_seg.0) - off).abs() < 1e-9);
        assert!(!on_one_line(t, (Point::new(0.0, 0.0), Point::new(0.0, -100.0)), s));
    }

    #[test]
    fn a_force_along_a_link_is_moved_off_it() {
        let s = Sizes::for_length(100.0);
        let scale = Scale::new(1.0, ModelUnits::MM);
        let link = (Point::new(0.0, 0.0), Point::new(40.0, 0.0));
        // Along the link (towards its other end) and across it.
        let along = (Point::new(40.0, 0.0), NamedVector::new("RA", Vector::new(-30.0, 0.0)));
        let across = (Point::new(40.0, 0.0), NamedVector::new("RB", Vector::new(0.0, 30.0)));
        let a = arrows_on_mechanism(&[along, across], scale, &[link], Point::new(20.0, -10.0), s);
        assert_eq!(a[1].arrow, (Point::new(40.0, 0.0), Point::new(40.0, 30.0)));
        let moved = a[0].arrow;
        assert!((moved.0.y - (1.5 * s.joint + OFFSET * s.head)).abs() < 1e-12, "{moved:?}");
        assert!((moved.1 - moved.0 - Vector::new(-30.0, 0.0)).norm() < 1e-12);
        let original = (Point::new(40.0, 0.0), Point::new(10.0, 0.0));
        assert!(runs_over(original, link, s.link, s) && !runs_over(moved, link, s.link, s));
        // A force a few degrees off the link still runs over it: moved too.
        let skew = (Point::new(40.0, 0.0), NamedVector::new("RA", Vector::new(-30.0, 1.5)));
        let b = arrows_on_mechanism(&[skew], scale, &[link], Point::new(20.0, -10.0), s);
        assert_ne!(b[0].arrow.0, Point::new(40.0, 0.0));
    }

    #[test]
    fn magnitudes_print_with_three_decimals() {
        assert_eq!(magnitude_text(52.3714, "N"), "52.37 N");
        assert_eq!(magnitude_text(-1.49, "N·m"), "−1.490 N·m");
        assert_eq!(magnitude_text(241779.383, "N·mm"), "241779 N·mm");
        assert_eq!(magnitude_text(-1e-5, "N"), "0 N");
    }
}
