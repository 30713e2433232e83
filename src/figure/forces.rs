//! Force figures (seed 003, Figs. 4 and 5 and its last section), typed on named vectors:
//! a force polygon is a chain of named vectors from the pole f, head to tail, which closes
//! at the pole when the forces balance; resultants drawn across it (the reactions found
//! from it); and branches — further polygons that start at one of its vertices and close
//! back on another (the crank's polygon with R_O). Reactions on the mechanism are named
//! vectors at points, at the same force scale. Any mechanism describes its forces this way
//! (the four-bar does in its figure); the code here draws them without knowing which
//! mechanism they come from.
//!
//! Each vector is an arrow with its name beside its middle, preferably on the outside of
//! the polygon, placed clear of the other names by [`super::labels`].

use crate::draw::{Aci, Drawing, Entity, Shape};
use crate::geom::{Point, Vector, perp};

use super::labels::{self, TextBox};
use super::vocab::{self, Scale, Sizes, layer_of, layers, vector};

/// Colour of the resultants inside a polygon (the reactions found from it).
const RESULTANT: Aci = Aci::RED;
/// Colour of a branch polygon (the crank's F_i1, G1, R_O).
const BRANCH: Aci = Aci::ORANGE;

/// A vector shorter than this many letter heights gets no name: at the run's force scale
/// the small weights crowd together, and their names would print over each other.
const MIN_LABELLED: f64 = 0.6;

/// Height of a vector's name in the force polygons, in letter heights.
const NAME_HEIGHT: f64 = 0.8;

/// A named physical vector (N for forces).
#[derive(Debug, Clone, PartialEq)]
pub struct NamedVector {
    /// Its name (`G21`, `RAn` …).
    pub name: String,
    /// The vector, physical units.
    pub v: Vector,
}

impl NamedVector {
    /// `v` named `name`.
    pub fn new(name: &str, v: Vector) -> NamedVector {
        NamedVector { name: name.to_string(), v }
    }
}

/// A resultant drawn across a polygon: from one vertex to another, its name at the
/// fraction `name_at` of its length (resultants along nearly the same segment keep their
/// names apart by starting them from different places).
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

/// A further polygon starting at a vertex of the chain: `vectors` head to tail, then
/// `closing` from the last end back to the vertex `closes_at`.
#[derive(Debug, Clone, PartialEq)]
pub struct Branch {
    /// Start vertex.
    pub from: usize,
    /// The known vectors.
    pub vectors: Vec<NamedVector>,
    /// The name of the closing vector (the unknown found by closing it: R_O).
    pub closing: String,
    /// The vertex it closes on.
    pub closes_at: usize,
}

/// A force polygon: a chain of named vectors from the pole, its resultants and branches.
#[derive(Debug, Clone, PartialEq)]
pub struct ForcePolygon {
    /// The pole's letter (`f`).
    pub pole: String,
    /// The chain, from the pole, head to tail.
    pub chain: Vec<NamedVector>,
    /// Resultants drawn across it.
    pub resultants: Vec<Resultant>,
    /// Branch polygons.
    pub branches: Vec<Branch>,
}

impl ForcePolygon {
    /// Vertices of the chain relative to the pole (physical units): the pole, then the end
    /// of each vector; the last is the pole again when the polygon closes.
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

    /// Every point the polygon reaches, relative to the pole (physical units): the chain's
    /// vertices and the ends of the branches' vectors. Used to size the force panel over a
    /// whole motion.
    pub fn physical_points(&self) -> Vec<Vector> {
        let mut pts = self.vertices();
        for b in &self.branches {
            let mut p = pts[b.from];
            for nv in &b.vectors {
                p += nv.v;
                pts.push(p);
            }
        }
        pts
    }
}

/// Draws `poly` with the pole at `pole`, at `scale`, on the `FORCES` layer. The names are
/// placed by [`labels::Polygon`]: beside their vectors, apart from each other.
pub fn draw(d: &mut Drawing, poly: &ForcePolygon, scale: Scale, pole: Point, s: Sizes) {
    let l = layer_of(d, layers::FORCES);
    let mut names = labels::Polygon::of_names();
    let pts: Vec<Point> = poly.vertices().into_iter().map(|v| pole + scale.draw(v)).collect();
    let centroid = Point::from(pts.iter().map(|p| p.coords).sum::<Vector>() / pts.len() as f64);
    vocab::pole(d, l, pole, s);
    names.letter(pole, &poly.pole, s.text, pole - centroid, None);
    for (i, nv) in poly.chain.iter().enumerate() {
        arrow_named(d, &mut names, l, None, (pts[i], pts[i + 1]), &nv.name, 0.5, centroid, s);
    }
    for r in &poly.resultants {
        arrow_named(d, &mut names, l, Some(RESULTANT), (pts[r.from], pts[r.to]), &r.name, r.name_at, centroid, s);
    }
    for b in &poly.branches {
        // The branch's own centre: the closing vertex, the start, and each end.
        let mut ends = Vec::with_capacity(b.vectors.len());
        let mut p = pts[b.from];
        for nv in &b.vectors {
            p += scale.draw(nv.v);
            ends.push(p);
        }
        let sum = ends.iter().fold(pts[b.closes_at].coords + pts[b.from].coords, |acc, e| acc + e.coords);
        let centre = Point::from(sum / (ends.len() + 2) as f64);
        let mut start = pts[b.from];
        for (nv, end) in b.vectors.iter().zip(&ends) {
            arrow_named(d, &mut names, l, Some(BRANCH), (start, *end), &nv.name, 0.5, centre, s);
            start = *end;
        }
        arrow_named(d, &mut names, l, Some(BRANCH), (start, pts[b.closes_at]), &b.closing, 0.5, centre, s);
    }
    names.draw(d, l);
}

/// An arrow from `from` to `to`, and its `name` for `names` at the fraction `at` of its
/// length, preferably on the side away from `inside`; nothing for a vector too short to see,
/// no name for one shorter than [`MIN_LABELLED`].
#[allow(clippy::too_many_arguments)]
fn arrow_named(
    d: &mut Drawing,
    names: &mut labels::Polygon,
    layer: usize,
    color: Option<Aci>,
    (from, to): (Point, Point),
    name: &str,
    at: f64,
    inside: Point,
    s: Sizes,
) {
    let v = to - from;
    let len = v.norm();
    if len.is_nan() || len <= 0.01 * s.head {
        return;
    }
    d.push(Entity { layer, color, linetype: None, shape: Shape::Arrow { from, to, head: s.head } });
    names.segment(from, to);
    if len < MIN_LABELLED * s.text {
        return;
    }
    let mid = from + v * at;
    let mut n = perp(v / len);
    if n.dot(&(mid - inside)) < 0.0 {
        n = -n;
    }
    names.letter(mid, name, NAME_HEIGHT * s.text, n, color);
}

/// Reactions drawn on the mechanism (seed, last section): each named vector at its point,
/// at the force scale, on the `FORCES` layer, its name at its tip placed by
/// [`labels::Polygon`] clear of the boxes `keep_off` (the mechanism's letters and symbols)
/// and preferably off the segments `avoid` (its links); the arrows turn with the reactions
/// as the mechanism moves.
pub fn reactions_on_mechanism(
    d: &mut Drawing,
    reactions: &[(Point, NamedVector)],
    scale: Scale,
    s: Sizes,
    keep_off: &[TextBox],
    avoid: &[(Point, Point)],
) {
    let l = layer_of(d, layers::FORCES);
    let mut names = labels::Polygon::of_names();
    for b in keep_off {
        names.keep_off(*b);
    }
    for (a, b) in avoid {
        names.segment(*a, *b);
    }
    for (at, nv) in reactions {
        let v = scale.draw(nv.v);
        if v.norm().is_nan() || v.norm() <= 0.01 * s.head {
            continue;
        }
        vector(d, l, *at, v, s);
        names.segment(*at, *at + v);
        names.letter(*at + v, &nv.name, s.text, v, None);
    }
    names.draw(d, l);
}
#[cfg(test)]
mod tests {
    use super::*;
    use crate::figure::vocab::{ModelUnits, content_drawing};

    /// A weight held by two ropes: W down, then the ropes' forces T1, T2 close the triangle;
    /// a resultant T1 + T2 drawn across it; a branch from the end of W back to the pole.
    fn hanging_weight() -> ForcePolygon {
        ForcePolygon {
            pole: "f".into(),
            chain: vec![
                NamedVector::new("W", Vector::new(0.0, -10.0)),
                NamedVector::new("T1", Vector::new(4.0, 5.0)),
                NamedVector::new("T2", Vector::new(-4.0, 5.0)),
            ],
            resultants: vec![Resultant { name: "T".into(), from: 1, to: 3, name_at: 0.5 }],
            branches: vec![Branch {
                from: 1,
                vectors: vec![NamedVector::new("P", Vector::new(3.0, 0.0))],
                closing: "Q".into(),
                closes_at: 0,
            }],
        }
    }

    #[test]
    fn the_chain_runs_head_to_tail_and_closes_at_the_pole() {
        let poly = hanging_weight();
        let v = poly.vertices();
        assert_eq!(v, vec![Vector::zeros(), Vector::new(0.0, -10.0), Vector::new(4.0, -5.0), Vector::zeros()]);
        // The branch's end is reached from its start vertex.
        assert_eq!(poly.physical_points()[4], Vector::new(3.0, -10.0));
    }

    #[test]
    fn every_vector_is_an_arrow_with_its_name() {
        let poly = hanging_weight();
        let s = Sizes::for_length(100.0);
        let mut d = content_drawing(crate::draw::DimStyle { text_height: s.text, arrow_size: s.head });
        // 0.1 N per drawn mm: W is 100 mm long, far longer than a letter.
        draw(&mut d, &poly, Scale::new(0.1, ModelUnits::MM), Point::new(0.0, 0.0), s);
        let arrows: Vec<(Point, Point)> = d
            .entities
            .iter()
            .filter_map(|e| match e.shape {
                Shape::Arrow { from, to, .. } => Some((from, to)),
                _ => None,
            })
            .collect();
        // W, T1, T2, the resultant T, the branch's P and its closing Q.
        assert_eq!(arrows.len(), 6);
        assert_eq!(arrows[0], (Point::new(0.0, 0.0), Point::new(0.0, -100.0)));
        assert_eq!(arrows[3], (Point::new(0.0, -100.0), Point::new(0.0, 0.0)));
        assert_eq!(arrows[5], (Point::new(30.0, -100.0), Point::new(0.0, 0.0)));
        let mut names: Vec<&str> = d
            .entities
            .iter()
            .filter_map(|e| match &e.shape {
                Shape::Text { value, .. } => Some(value.as_str()),
                _ => None,
            })
            .collect();
        names.sort_unstable();
        assert_eq!(names, ["P", "Q", "T", "T1", "T2", "W", "f"]);
    }
}
