//! Four-bar figures (seed 003 and its reference \[8\]): what the graph-analytical method
//! draws for each crank angle — the mechanism with its ground pivots, joints, letters and
//! the coupler curve of M; the velocity polygon (pole p, vectors pa, pb, pm, relative ab);
//! the acceleration polygon (pole π, a′, the normal and tangential components of a_BA and
//! of a_B about C, image points b′, m′); and, with forces, the force polygons of the dyad
//! and of the crank. This file only adapts the four-bar's results to the shared
//! vocabulary: small adapters build the polygons as named points
//! ([`super::polygon::PointPolygon`]) and named vectors
//! ([`super::forces::ForcePolygon`]) from `Kinematics` and `Forces`; the drawing code
//! knows no four-bar field. Every letter is placed by [`super::labels`].
//!
//! # Layout and scales
//! One [`Layout`] is computed per run from every position, so all frames share one window
//! and one set of scales and an animation does not jump. The mechanism panel is as large as
//! the whole motion (all of O1, C, A, B, M over the run); each polygon gets a panel beside
//! it, about as large, holding the polygon at every position. A scale is written as
//! `k_v = 0.01 (m/s)/mm`: one millimetre of the drawing (the model drawn 1:1, so 1 m of an
//! SI scene is 1000 mm) stands for 0.01 m/s. Scales are "nice" numbers (1, 2, 2.5, 5 × 10ᵏ)
//! chosen from the largest polygon over the motion.
//!
//! # Layers
//! [`Layout::base`] holds what is the same at every position (ground pivots, coupler curve,
//! panel titles, scales) on the content layers `MECHANISM`, `COUPLER_CURVE`, `DIMENSIONS`.
//! [`Layout::moving`] draws one position on the content layers `MECHANISM`, `VELOCITY`,
//! `ACCELERATION`, `FORCES`, `CONSTRUCTION`, `TEXT`. An SVG frame is base + moving
//! ([`Layout::frame`]); the DXF ([`crate::figure::animation::Animation::all_positions`], from the run's animation) moves each position's entities onto
//! its own layer `POS_000`…`POS_359`, keeping the content's colour and line type on each
//! entity, so that a CAD user switches positions by layer and tells contents by colour.

use crate::draw::{Bounds, DimStyle, Drawing, HAlign, Shape, VAlign};
use crate::geom::{Point, Vector, perp};
use crate::solve::fourbar::Forces;
use crate::solve::fourbar::{Geometry, Kinematics, Position};

use super::forces::{self, Branch, ForcePolygon, NamedVector, Resultant};
use super::labels::{self, TextBox};
use super::polygon::{self, Direction, NamedPoint, POLE, PointPolygon, Side, SideKind};
pub use super::vocab::{ModelUnits, Scale, Sizes, nice_scale, scale_text};
use super::vocab::{content_drawing, ground, ground_extent, joint, layer_of, layers, link, path, unit_or};

/// Which polygons to draw (from the scene's `outputs`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Show {
    /// The velocity polygon.
    pub velocity: bool,
    /// The acceleration polygon.
    pub acceleration: bool,
    /// The force polygons and the reactions R_A, R_B on the mechanism.
    pub forces: bool,
}

/// Panel placement and scales for one run: computed once from every position.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// The model's units.
    pub units: ModelUnits,
    /// What is drawn.
    pub show: Show,
    /// Sizes of letters, arrows, links and joints.
    pub sizes: Sizes,
    /// Velocity scale and the pole p (when drawn).
    pub velocity: Option<(Scale, Point)>,
    /// Acceleration scale and the pole π (when drawn).
    pub acceleration: Option<(Scale, Point)>,
    /// Force scale and the pole f (when drawn).
    pub forces: Option<(Scale, Point)>,
    /// Lower-left corners and sizes of the panels with their titles:
    /// (title, lower-left, upper-right).
    pub panels: Vec<(String, Point, Point)>,
    /// The fixed window of every frame.
    pub window: Bounds,
}

/// Bounding box of physical vectors.
#[derive(Debug, Clone, Copy)]
struct Extent {
    min: Vector,
    max: Vector,
}

impl Extent {
    fn of(vs: impl IntoIterator<Item = Vector>) -> Option<Extent> {
        let mut e: Option<Extent> = None;
        for v in vs {
            if !(v.x.is_finite() && v.y.is_finite()) {
                continue;
            }
            e = Some(match e {
                None => Extent { min: v, max: v },
                Some(e) => Extent { min: e.min.inf(&v), max: e.max.sup(&v) },
            });
        }
        e
    }
    fn union(a: Option<Extent>, b: Option<Extent>) -> Option<Extent> {
        match (a, b) {
            (Some(a), Some(b)) => Some(Extent { min: a.min.inf(&b.min), max: a.max.sup(&b.max) }),
            (a, None) => a,
            (None, b) => b,
        }
    }
    fn size(&self) -> f64 {
        (self.max - self.min).amax()
    }
}

impl Layout {
    /// The layout for a run: `positions` are the assembled positions (in order),
    /// `forces[i]` the forces at `positions[i]` when `show.forces`.
    pub fn new(
        geom: &Geometry,
        positions: &[Position],
        forces: Option<&[Forces]>,
        show: Show,
        units: ModelUnits,
    ) -> Layout {
        // Mechanism extent over the motion.
        let pts = positions.iter().flat_map(|p| [p.a.coords, p.b.coords, p.m.coords]);
        let mech = Extent::of(pts.chain([geom.o1.coords, geom.c.coords]))
            .unwrap_or(Extent { min: Vector::zeros(), max: Vector::new(1.0, 1.0) });
        let size = mech.size().max(geom.l1.max(geom.l_bc)).max(f64::MIN_POSITIVE);
        let sizes = Sizes::for_length(size);
        // Room for the ground symbols and letters around the mechanism.
        let pad = 3.5 * sizes.joint + 1.6 * sizes.text;
        let mech_min = Point::from(mech.min) - Vector::new(pad, pad + 2.0 * sizes.joint);
        let mech_max = Point::from(mech.max) + Vector::new(pad, pad);
        let target_mm = size * units.mm_per_unit;

        let kins: Vec<(&Position, &Kinematics)> = positions.iter().filter_map(|p| Some((p, p.kin.as_ref()?))).collect();
        let show = Show {
            velocity: show.velocity && !kins.is_empty(),
            acceleration: show.acceleration && !kins.is_empty(),
            forces: show.forces && forces.is_some_and(|f| !f.is_empty()),
        };
        let scale_for = |e: Option<Extent>| -> (Scale, Extent) {
            let e = e.unwrap_or(Extent { min: Vector::zeros(), max: Vector::zeros() });
            (Scale::new(nice_scale(e.size() / target_mm), units), e)
        };
        // Panels: (title, physical extent, scale) for each polygon shown.
        let mut polys: Vec<(String, Scale, Extent, usize)> = Vec::new();
        if show.velocity {
            let e =
                kins.iter().map(|(_, k)| Extent::of(velocity_polygon(k).physical_points())).fold(None, Extent::union);
            let (s, e) = scale_for(e);
            polys.push((format!("Velocity polygon   k_v = {} ({}/s)/mm", scale_text(s.per_mm), units.length), s, e, 0));
        }
        if show.acceleration {
            let e = kins
                .iter()
                .map(|(p, k)| Extent::of(acceleration_polygon(p, geom.c, k).physical_points()))
                .fold(None, Extent::union);
            let (s, e) = scale_for(e);
            polys.push((
                format!("Acceleration polygon   k_a = {} ({}/s²)/mm", scale_text(s.per_mm), units.length),
                s,
                e,
                1,
            ));
        }
        if show.forces {
            let e = forces
                .unwrap_or(&[])
                .iter()
                .map(|f| Extent::of(force_polygon(f).physical_points()))
                .fold(None, Extent::union);
            let (s, e) = scale_for(e);
            polys.push((format!("Force polygons   k_f = {} N/mm", scale_text(s.per_mm),), s, e, 2));
        }

        // Grid: up to three panels in a row, four as 2 × 2.
        let title_room = 2.6 * sizes.text;
        let gap = 0.12 * size;
        let mut boxes: Vec<(String, Vector)> = vec![("Mechanism".to_string(), mech_max - mech_min)];
        for (title, s, e, _) in &polys {
            boxes.push((title.clone(), s.draw(e.max - e.min) + Vector::new(2.0 * sizes.text, 2.0 * sizes.text)));
        }
        let cols = if boxes.len() == 4 { 2 } else { boxes.len() };
        let rows = boxes.len().div_ceil(cols);
        let mut col_w = vec![0.0f64; cols];
        let mut row_h = vec![0.0f64; rows];
        for (i, (_, b)) in boxes.iter().enumerate() {
            col_w[i % cols] = col_w[i % cols].max(b.x);
            row_h[i / cols] = row_h[i / cols].max(b.y + title_room);
        }
        // Cell i's upper-left corner; row 0 on top, the mechanism's at its own lower-left.
        let mut panels = Vec::new();
        let mut origins = Vec::new();
        for (i, (title, b)) in boxes.iter().enumerate() {
            let (r, c) = (i / cols, i % cols);
            let x = mech_min.x + col_w[..c].iter().sum::<f64>() + gap * c as f64;
            let top = mech_min.y + row_h[0] - row_h[..r].iter().sum::<f64>() - gap * r as f64 - title_room + title_room;
            let y_top = top - title_room;
            let lower_left = Point::new(x, y_top - b.y);
            origins.push(lower_left);
            panels.push((title.clone(), lower_left, Point::new(x + b.x, y_top + title_room)));
        }
        // The mechanism panel must sit where the mechanism is: shift everything so.
        let shift = mech_min - origins[0];
        for p in panels.iter_mut() {
            p.1 += shift;
            p.2 += shift;
        }
        let mut velocity = None;
        let mut acceleration = None;
        let mut force = None;
        for (j, (_, s, e, kind)) in polys.iter().enumerate() {
            let ll = origins[j + 1] + shift + Vector::new(sizes.text, sizes.text);
            let pole = ll - s.draw(e.min);
            match kind {
                0 => velocity = Some((*s, pole)),
                1 => acceleration = Some((*s, pole)),
                _ => force = Some((*s, pole)),
            }
        }
        let mut window = Bounds { min: panels[0].1, max: panels[0].2 };
        for p in &panels {
            window.min = Point::new(window.min.x.min(p.1.x), window.min.y.min(p.1.y));
            window.max = Point::new(window.max.x.max(p.2.x), window.max.y.max(p.2.y));
        }
        Layout { units, show, sizes, velocity, acceleration, forces: force, panels, window }
    }

    fn dim_style(&self) -> DimStyle {
        DimStyle { text_height: self.sizes.text, arrow_size: self.sizes.head }
    }

    /// What every frame shares: the ground pivots with their hatch symbols (their letters
    /// move with the links, see [`Layout::moving`]), the coupler
    /// curve of M (`curve`: runs of consecutive positions; a gap in the motion breaks it),
    /// the panel titles with the scales.
    pub fn base(&self, geom: &Geometry, curve: &[Vec<Point>]) -> Drawing {
        let mut d = content_drawing(self.dim_style());
        let mech = layer_of(&d, layers::MECHANISM);
        let dims = layer_of(&d, layers::DIMENSIONS);
        let cc = layer_of(&d, layers::COUPLER_CURVE);
        for run in curve {
            path(&mut d, cc, run.clone());
        }
        for p in [geom.o1, geom.c] {
            ground(&mut d, mech, p, self.sizes);
        }
        for (title, _ll, ur) in &self.panels {
            let at = Point::new(_ll.x, ur.y - 1.2 * self.sizes.text);
            d.add(
                dims,
                Shape::Text {
                    at,
                    height: self.sizes.text,
                    value: title.clone(),
                    halign: HAlign::Left,
                    valign: VAlign::Baseline,
                    rotation: 0.0,
                },
            );
        }
        d
    }

    /// One position on the content layers: the mechanism (with R_A, R_B when forces are
    /// shown), the crank-angle text, and the polygons asked for.
    pub fn moving(&self, geom: &Geometry, pos: &Position, force: Option<&Forces>) -> Drawing {
        let mut d = content_drawing(self.dim_style());
        let s = self.sizes;
        let text = layer_of(&d, layers::TEXT);
        let (ll, ur) = (self.panels[0].1, self.panels[0].2);
        d.add(
            text,
            Shape::Text {
                at: Point::new(ur.x, ur.y - 1.2 * s.text),
                height: s.text,
                value: format!("φ1 = {}°", angle_text(pos.phi1.to_degrees())),
                halign: HAlign::Right,
                valign: VAlign::Baseline,
                rotation: 0.0,
            },
        );
        let _ = ll;
        // The reactions R_A, R_B drawn on the mechanism, for its letters to keep off.
        let (reacts, arrows) = match (force, self.forces) {
            (Some(f), Some((scale, _))) => {
                let r = reactions(pos, f);
                let arrows: Vec<(Point, Point)> = r.iter().map(|(at, nv)| (*at, *at + scale.draw(nv.v))).collect();
                (r.to_vec(), arrows)
            }
            _ => (Vec::new(), Vec::new()),
        };
        let placed = mechanism(&mut d, geom, pos, &arrows, s);
        if let (Some(k), Some((scale, pole))) = (pos.kin.as_ref(), self.velocity) {
            polygon::draw(&mut d, &velocity_polygon(k), layers::VELOCITY, scale, pole, s);
        }
        if let (Some(k), Some((scale, pole))) = (pos.kin.as_ref(), self.acceleration) {
            polygon::draw(&mut d, &acceleration_polygon(pos, geom.c, k), layers::ACCELERATION, scale, pole, s);
        }
        if let (Some(f), Some((scale, pole))) = (force, self.forces) {
            forces::draw(&mut d, &force_polygon(f), scale, pole, s);
            forces::reactions_on_mechanism(&mut d, &reacts, scale, s, &placed.0, &placed.1);
        }
        d
    }

    /// One animation frame: `base` with `moving` on top.
    pub fn frame(&self, base: &Drawing, moving: &Drawing) -> Drawing {
        let mut d = base.clone();
        d.append(moving);
        d
    }
}

/// Angle in degrees for labels: integers without decimals, else up to 3 decimals.
pub fn angle_text(deg: f64) -> String {
    let r = (deg * 1000.0).round() / 1000.0;
    let s = format!("{r:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".to_string() } else { s.to_string() }
}

/// Links (wide polylines), joints (circles), letters O1, C, A, B, M placed by
/// [`labels::Polygon`] clear of the joints, the links, the ground symbols and the arrows
/// `arrows` drawn on the mechanism (the reactions). Returns what later letters should keep
/// off: the letters' and the ground symbols' boxes, and the links.
pub(crate) fn mechanism(
    d: &mut Drawing,
    geom: &Geometry,
    pos: &Position,
    arrows: &[(Point, Point)],
    s: Sizes,
) -> (Vec<TextBox>, Vec<(Point, Point)>) {
    let mech = layer_of(d, layers::MECHANISM);
    let straight = (geom.alpha - std::f64::consts::PI).abs() < 1e-9;
    link(d, mech, vec![geom.o1, pos.a], false, None, s);
    link(d, mech, vec![pos.a, pos.b, pos.m], !straight, None, s);
    link(d, mech, vec![geom.c, pos.b], false, None, s);
    for p in [pos.a, pos.b] {
        joint(d, mech, p, s);
    }
    d.add(mech, Shape::Circle { center: pos.m, radius: 0.6 * s.joint });
    let mut letters = labels::Polygon::of_names();
    let links = [(geom.o1, pos.a), (pos.a, pos.b), (pos.b, pos.m), (geom.c, pos.b)];
    for (a, b) in links.iter().chain(arrows) {
        letters.segment(*a, *b);
    }
    let grounds = [ground_extent(geom.o1, s), ground_extent(geom.c, s)];
    for g in grounds {
        letters.keep_off(g);
    }
    // Preferred sides, outside the linkage: A away from O1, the pivots opposite to their
    // links (but not down into the ground symbol), B away from the mid-point of A and C,
    // M along B→M turned a little.
    let ua = unit_or(pos.a - geom.o1, Vector::new(0.0, 1.0));
    letters.letter_clear(pos.a, "A", s.text, ua, s.joint);
    let level = |v: Vector, fallback: Vector| unit_or(Vector::new(v.x, v.y.max(0.0)), fallback);
    let uo = level(unit_or(geom.o1 - pos.a, Vector::zeros()), Vector::new(-1.0, 0.0));
    letters.letter_clear(geom.o1, "O1", s.text, uo, s.joint);
    let uc = level(unit_or(geom.c - pos.b, Vector::zeros()), Vector::new(1.0, 0.0));
    letters.letter_clear(geom.c, "C", s.text, uc, s.joint);
    let mid_ac = Point::from((pos.a.coords + geom.c.coords) / 2.0);
    let ub = unit_or(pos.b - mid_ac, Vector::new(0.0, 1.0));
    letters.letter_clear(pos.b, "B", s.text, ub, s.joint);
    let um = unit_or(pos.m - pos.b, Vector::new(1.0, 0.0));
    let um = unit_or(um + perp(um) * 0.6, um);
    letters.letter_clear(pos.m, "M", s.text, um, s.joint);
    let mut boxes = letters.draw(d, mech);
    boxes.extend(grounds);
    (boxes, links.to_vec())
}

/// The velocity polygon: pole p; pa, pb, pm; the relative velocity ab (v_BA) and bm (the
/// image of the coupler).
pub(crate) fn velocity_polygon(k: &Kinematics) -> PointPolygon {
    let (a, b, m) = (1, 2, 3);
    let vector = |from, to| Side { from, to, kind: SideKind::Vector };
    PointPolygon {
        pole: "p".into(),
        pole_away: vec![a, b],
        points: vec![
            NamedPoint { name: "a".into(), from: POLE, v: k.v_a },
            NamedPoint { name: "b".into(), from: POLE, v: k.v_b },
            NamedPoint { name: "m".into(), from: POLE, v: k.v_m },
        ],
        directions: vec![],
        sides: vec![vector(POLE, a), vector(POLE, b), vector(POLE, m), vector(a, b), vector(b, m)],
    }
}

/// The acceleration polygon as the graph-analytical construction draws it:
/// π → a′ (a_A); from a′ the normal component a_BA^n (parallel to BA) to n_BA, then the
/// tangential direction (perpendicular to AB, dashed) to b′; from π the normal component
/// of a_B about C (parallel to BC) to n_BC, then the tangential direction (perpendicular to
/// BC, dashed) to b′; π → b′, π → m′, and the image a′b′m′ of the coupler.
pub(crate) fn acceleration_polygon(pos: &Position, c_pivot: Point, k: &Kinematics) -> PointPolygon {
    let (a1, b1, m1, n_ba, n_bc) = (1, 2, 3, 4, 5);
    let side = |from, to, kind| Side { from, to, kind };
    PointPolygon {
        pole: "π".into(),
        pole_away: vec![a1, b1],
        // The points first, then the ends of the normal components.
        points: vec![
            NamedPoint { name: "a'".into(), from: POLE, v: k.a_a },
            NamedPoint { name: "b'".into(), from: POLE, v: k.a_b },
            NamedPoint { name: "m'".into(), from: POLE, v: k.a_m },
            NamedPoint { name: "nBA".into(), from: a1, v: k.a_ba_n },
            NamedPoint { name: "nBC".into(), from: POLE, v: k.a_bc_n },
        ],
        // Tangential directions: ⊥AB through n_BA, ⊥BC through n_BC.
        directions: vec![
            Direction { through: n_ba, dir: perp(pos.b - pos.a), reaches: b1 },
            Direction { through: n_bc, dir: perp(pos.b - c_pivot), reaches: b1 },
        ],
        // Components: normal parts solid, tangential parts as dashed arrows; then the
        // accelerations of the points and the image of the coupler: a′b′ (a_BA) and b′m′.
        sides: vec![
            side(a1, n_ba, SideKind::Vector),
            side(POLE, n_bc, SideKind::Vector),
            side(n_ba, b1, SideKind::Component),
            side(n_bc, b1, SideKind::Component),
            side(POLE, a1, SideKind::Vector),
            side(POLE, b1, SideKind::Vector),
            side(POLE, m1, SideKind::Vector),
            side(a1, b1, SideKind::Image),
            side(b1, m1, SideKind::Image),
        ],
    }
}

/// The force polygons of seed 003 (Figs. 4 and 5). The dyad's chain from the pole f, in
/// the seed's order (eq. 5): R_A^n, G21, F_i21, G22, F_i22, F, G3, F_i3, R_C^n, then R_C^t
/// (along BC) and R_A^t (along AB), which close it at the intersection point `int`
/// (vertex 10). In it, R_A runs from `int` to the end of R_A^n, R_C from the end of F_i3 to
/// `int`, and R_B (seed eq. 7) from the end of F to `int`; R_B and R_C are often nearly the
/// same segment (a light rocker), so their names start from different places along it. The
/// crank's polygon (Fig. 5) starts at `int` (−R_A): F_i1, G1, and R_O back to the end of
/// R_A^n.
pub(crate) fn force_polygon(f: &Forces) -> ForcePolygon {
    let nv = NamedVector::new;
    let (p_ran, p_f, p_fi3, int) = (1, 6, 8, 10);
    let resultant = |name: &str, from, to, name_at| Resultant { name: name.into(), from, to, name_at };
    ForcePolygon {
        pole: "f".into(),
        chain: vec![
            nv("RAn", f.r_a_n),
            nv("G21", f.g21),
            nv("Fi21", f.fi21),
            nv("G22", f.g22),
            nv("Fi22", f.fi22),
            nv("F", f.f_ext),
            nv("G3", f.g3),
            nv("Fi3", f.fi3),
            nv("RCn", f.r_c_n),
            nv("RCt", f.r_c_t),
            nv("RAt", f.r_a_t),
        ],
        resultants: vec![
            resultant("RA", int, p_ran, 0.5),
            resultant("RB", p_f, int, 0.7),
            resultant("RC", p_fi3, int, 0.3),
        ],
        branches: vec![Branch {
            from: int,
            vectors: vec![nv("Fi1", f.fi1), nv("G1", f.g1)],
            closing: "RO".into(),
            closes_at: p_ran,
        }],
    }
}

/// R_A at A and R_B at B on the mechanism (seed, last section).
fn reactions(pos: &Position, f: &Forces) -> [(Point, NamedVector); 2] {
    [(pos.a, NamedVector::new("RA", f.r_a)), (pos.b, NamedVector::new("RB", f.r_b))]
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::geom::{Side, cross, polar};

    /// The template's Chebyshev four-bar (design.md §3).
    pub(crate) fn chebyshev() -> Geometry {
        Geometry {
            o1: Point::new(0.0, 0.0),
            c: Point::new(0.08, 0.0),
            l1: 0.04,
            l_ab: 0.10,
            l_bm: 0.10,
            alpha: std::f64::consts::PI,
            l_bc: 0.10,
            branch: Side::Left,
        }
    }

    /// Positions and kinematics by a closed form written here for the figure tests only
    /// (the library's solver is tested on its own): B from two circles, derivatives of the
    /// loop closure by differentiating twice.
    pub(crate) fn closed_form(g: &Geometry, phi1: f64, omega1: f64) -> Position {
        let a = polar(g.o1, g.l1, phi1);
        let ac = g.c - a;
        let d = ac.norm();
        let x = (d * d + g.l_ab * g.l_ab - g.l_bc * g.l_bc) / (2.0 * d);
        let h = (g.l_ab * g.l_ab - x * x).sqrt();
        let u = ac / d;
        let b = a + u * x + perp(u) * h; // left of A→C
        let m = b + crate::geom::rotate((a - b) / g.l_ab * g.l_bm, g.alpha);
        // Velocities: ω2 × AB − ω3 × CB = −v_A.
        let va = perp(a - g.o1) * omega1;
        let (rab, rcb) = (b - a, b - g.c);
        // Solve [perp(rab), -perp(rcb)] [w2, w3]^T = -va.
        let (c1, c2) = (perp(rab), -perp(rcb));
        let det = cross(c1, c2);
        let w2 = cross(-va, c2) / det;
        let w3 = cross(c1, -va) / det;
        let aa = -(a - g.o1) * omega1 * omega1;
        let rhs = -aa + rab * w2 * w2 - rcb * w3 * w3;
        let e2 = cross(rhs, c2) / det;
        let e3 = cross(c1, rhs) / det;
        let vb = va + perp(rab) * w2;
        let rbm = m - b;
        let vm = vb + perp(rbm) * w2;
        let a_ba_n = -rab * w2 * w2;
        let a_ba_t = perp(rab) * e2;
        let a_bc_n = -rcb * w3 * w3;
        let a_bc_t = perp(rcb) * e3;
        let ab = aa + a_ba_n + a_ba_t;
        let am = ab - rbm * w2 * w2 + perp(rbm) * e2;
        let kin = Kinematics {
            omega2: w2,
            omega3: w3,
            eps2: e2,
            eps3: e3,
            v_a: va,
            v_b: vb,
            v_m: vm,
            v_ba: vb - va,
            a_a: aa,
            a_b: ab,
            a_m: am,
            a_ba_n,
            a_ba_t,
            a_bc_n,
            a_bc_t,
            a_g1: aa / 2.0,
            a_g21: (aa + ab) / 2.0,
            a_g22: (ab + am) / 2.0,
            a_g3: ab / 2.0,
        };
        Position { phi1, a, b, m, c: g.c, kin: Some(kin) }
    }

    #[test]
    fn the_test_closed_form_closes_the_loop() {
        let g = chebyshev();
        for i in 0..36 {
            let p = closed_form(&g, (i as f64 * 10.0).to_radians(), 20.0);
            assert!(((p.b - p.a).norm() - g.l_ab).abs() < 1e-14);
            assert!(((p.b - g.c).norm() - g.l_bc).abs() < 1e-14);
            let k = p.kin.unwrap();
            // The acceleration polygon closes both ways: a_B = a_A + a_BA = a_BC^n + a_BC^t.
            assert!((k.a_b - (k.a_bc_n + k.a_bc_t)).norm() < 1e-9 * k.a_b.norm().max(1.0));
        }
    }

    fn run(show: Show) -> (Layout, Vec<Drawing>) {
        let g = chebyshev();
        let pos: Vec<Position> = (0..360).map(|i| closed_form(&g, (i as f64).to_radians(), 20.0)).collect();
        let lay = Layout::new(&g, &pos, None, show, ModelUnits::SI);
        let curve = vec![pos.iter().map(|p| p.m).collect::<Vec<_>>()];
        let base = lay.base(&g, &curve);
        let frames = [0usize, 90, 180].iter().map(|&i| lay.frame(&base, &lay.moving(&g, &pos[i], None))).collect();
        (lay, frames)
    }

    #[test]
    fn polygons_are_drawn_at_their_scale_beside_the_mechanism() {
        let show = Show { velocity: true, acceleration: true, forces: false };
        let (lay, frames) = run(show);
        let g = chebyshev();
        let p = closed_form(&g, 0.0, 20.0);
        let k = p.kin.unwrap();
        let (sv, pole) = lay.velocity.unwrap();
        // v_A = ω1·l1 = 0.8 m/s; its arrow is 0.8 / k_v mm long = 0.8 / k_v / 1000 m.
        let d = &frames[0];
        let vel = layer_of(d, layers::VELOCITY);
        let pa = d
            .entities
            .iter()
            .filter(|e| e.layer == vel)
            .find_map(|e| match e.shape {
                Shape::Arrow { from, to, .. } if from == pole => Some(to - from),
                _ => None,
            })
            .unwrap();
        assert!((pa.norm() - 0.8 / sv.per_mm / 1000.0).abs() < 1e-12, "{} {}", pa.norm(), sv.per_mm);
        assert!((pa.normalize() - k.v_a.normalize()).norm() < 1e-12);
        // Panels do not overlap the mechanism panel.
        let mech = &lay.panels[0];
        for p in &lay.panels[1..] {
            let disjoint = p.1.x >= mech.2.x || p.2.x <= mech.1.x || p.1.y >= mech.2.y || p.2.y <= mech.1.y;
            assert!(disjoint, "{p:?} overlaps {mech:?}");
        }
        // The scale is nice and the largest polygon is about as large as the mechanism.
        let m = sv.per_mm / 10f64.powf(sv.per_mm.log10().floor());
        assert!([1.0, 2.0, 2.5, 5.0].iter().any(|n| (m - n).abs() < 1e-9), "{}", sv.per_mm);
        // Every frame lies inside the shared window.
        for f in &frames {
            let b = f.bounds().unwrap();
            let w = lay.window;
            let slack = 0.02 * w.width();
            assert!(b.min.x >= w.min.x - slack && b.max.x <= w.max.x + slack && b.min.y >= w.min.y - slack);
            assert!(b.max.y <= w.max.y + slack, "{b:?} vs {w:?}");
        }
    }

    #[test]
    fn positions_only_draws_no_polygon() {
        let (lay, frames) = run(Show::default());
        assert!(lay.velocity.is_none() && lay.acceleration.is_none() && lay.panels.len() == 1);
        let d = &frames[0];
        let vel = layer_of(d, layers::VELOCITY);
        assert!(!d.entities.iter().any(|e| e.layer == vel));
    }

    /// The template's whole motion through the public API (scene file → solver → layout),
    /// with forces.
    fn template_motion() -> (Geometry, crate::solve::fourbar::Motion, Layout) {
        let file = concat!(env!("CARGO_MANIFEST_DIR"), "/templates/fourbar-chebyshev.toml");
        let text = std::fs::read_to_string(file).unwrap();
        let crate::scene::Scene::Fourbar(scene) = crate::scene::parse(&text, file, &[]).unwrap() else {
            panic!("not a four-bar scene")
        };
        let motion = crate::solve::fourbar::solve_motion(&scene.spec).unwrap();
        let show = Show { velocity: true, acceleration: true, forces: true };
        let lay = Layout::new(&scene.spec.geometry, &motion.positions, Some(&motion.forces), show, ModelUnits::SI);
        (scene.spec.geometry, motion, lay)
    }

    /// The letters of each polygon in a drawn position: (polygon, centre, text, height),
    /// polygon 0 velocity, 1 acceleration, 2 force (the force panel's texts only).
    fn polygon_letters(lay: &Layout, d: &Drawing) -> Vec<(usize, Point, String, f64)> {
        let force_panel = lay.panels.iter().find(|p| p.0.starts_with("Force")).cloned();
        let (vel, acc, frc) =
            (layer_of(d, layers::VELOCITY), layer_of(d, layers::ACCELERATION), layer_of(d, layers::FORCES));
        d.entities
            .iter()
            .filter_map(|e| match &e.shape {
                Shape::Text { at, height, value, .. } => {
                    let poly = if e.layer == vel {
                        0
                    } else if e.layer == acc {
                        1
                    } else if e.layer == frc
                        && force_panel.as_ref().is_some_and(|p| at.x >= p.1.x && at.x <= p.2.x && at.y <= p.2.y)
                    {
                        2
                    } else {
                        return None;
                    };
                    Some((poly, *at, value.clone(), *height))
                }
                _ => None,
            })
            .collect()
    }

    #[test]
    fn polygon_letters_never_overlap_over_the_template_motion() {
        use super::super::labels::TextBox;
        let (g, motion, lay) = template_motion();
        assert_eq!(motion.positions.len(), 360);
        let mut overlaps = [0usize; 3];
        let mut examples = Vec::new();
        let mut first_bad = None;
        for (i, pos) in motion.positions.iter().enumerate() {
            let d = lay.moving(&g, pos, Some(&motion.forces[i]));
            let letters = polygon_letters(&lay, &d);
            for (j, a) in letters.iter().enumerate() {
                for b in &letters[..j] {
                    let (ba, bb) = (TextBox::centred(a.1, &a.2, a.3), TextBox::centred(b.1, &b.2, b.3));
                    if a.0 == b.0 && ba.overlaps(&bb) {
                        overlaps[a.0] += 1;
                        first_bad.get_or_insert(i);
                        if examples.len() < 10 {
                            examples.push(format!("{}°: {} over {}", i, a.2, b.2));
                        }
                    }
                }
            }
        }
        eprintln!("overlapping letter pairs (velocity, acceleration, force): {overlaps:?}; {examples:?}");
        if let Some(deg) = first_bad {
            // The first frame with overlapping letters, to look at: target/labels-overlap.png.
            let base = lay.base(&g, &[motion.positions.iter().map(|p| p.m).collect()]);
            let f = lay.frame(&base, &lay.moving(&g, &motion.positions[deg], Some(&motion.forces[deg])));
            let opts = crate::draw::svg::SvgOptions { window: Some(lay.window), ..Default::default() };
            let png = crate::draw::raster::to_png(&crate::draw::svg::to_string(&f, &opts), 1400).unwrap();
            let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target");
            std::fs::write(dir.join("labels-overlap.png"), png).unwrap();
        }
        assert_eq!(overlaps, [0, 0, 0], "{examples:?}");
    }

    #[test]
    fn polygon_letters_stay_near_their_points_over_the_template_motion() {
        use super::super::labels::{COINCIDENT, SAME_POINT, max_distance};
        let (g, motion, lay) = template_motion();
        let (sv, pv) = lay.velocity.unwrap();
        let (sa, pa) = lay.acceleration.unwrap();
        let force_panel = lay.panels.iter().find(|p| p.0.starts_with("Force")).cloned().unwrap();
        let mut checked = 0;
        for (i, pos) in motion.positions.iter().enumerate() {
            let k = pos.kin.unwrap();
            let d = lay.moving(&g, pos, Some(&motion.forces[i]));
            let frc = layer_of(&d, layers::FORCES);
            // The force polygons' sides, for their names.
            let sides: Vec<(Point, Point)> = d
                .entities
                .iter()
                .filter_map(|e| match e.shape {
                    Shape::Arrow { from, to, .. } if e.layer == frc && from.x >= force_panel.1.x => Some((from, to)),
                    _ => None,
                })
                .collect();
            for (poly, at, text, h) in polygon_letters(&lay, &d) {
                let reach = max_distance(&text, h) + COINCIDENT * h + 1e-9 * h;
                for name in text.split(SAME_POINT) {
                    let dist = match (poly, name) {
                        (0, "p") => (at - pv).norm(),
                        (0, "a") => (at - (pv + sv.draw(k.v_a))).norm(),
                        (0, "b") => (at - (pv + sv.draw(k.v_b))).norm(),
                        (0, "m") => (at - (pv + sv.draw(k.v_m))).norm(),
                        (1, "π") => (at - pa).norm(),
                        (1, "a'") => (at - (pa + sa.draw(k.a_a))).norm(),
                        (1, "b'") => (at - (pa + sa.draw(k.a_b))).norm(),
                        (1, "m'") => (at - (pa + sa.draw(k.a_m))).norm(),
                        (1, "nBA") => (at - (pa + sa.draw(k.a_a + k.a_ba_n))).norm(),
                        (1, "nBC") => (at - (pa + sa.draw(k.a_bc_n))).norm(),
                        (2, _) => sides
                            .iter()
                            .map(|&(a, b)| {
                                let v = b - a;
                                let t = ((at - a).dot(&v) / v.norm_squared()).clamp(0.0, 1.0);
                                (at - (a + v * t)).norm()
                            })
                            .fold(f64::INFINITY, f64::min),
                        _ => panic!("unexpected letter {name} in polygon {poly}"),
                    };
                    assert!(dist <= reach, "{i}°: {name} is {dist} from its point, more than {reach}");
                    checked += 1;
                }
            }
        }
        // Every velocity and acceleration letter at least, and the force names.
        assert!(checked > 360 * 10, "{checked}");
    }

    /// Forces for the figure tests, by the seed's route written out here (not the library's
    /// solver): inertia of the bars, moments about B for the normal components, the
    /// intersection of the two bar directions for the tangential ones.
    pub(crate) fn seed_route(pos: &Position, g: &Geometry) -> Forces {
        let k = pos.kin.unwrap();
        let (m1, m21, m22, m3, gr) = (0.05, 0.125, 0.125, 0.125, 9.8);
        let w = |m: f64| Vector::new(0.0, -m * gr);
        let f_ext =
            if (80.0..=280.0).contains(&pos.phi1.to_degrees()) { Vector::new(0.0, -50.0) } else { Vector::zeros() };
        let (fi21, fi22, fi3, fi1) = (-k.a_g21 * m21, -k.a_g22 * m22, -k.a_g3 * m3, -k.a_g1 * m1);
        let (mi21, mi22, mi3) = (
            -m21 * g.l_ab * g.l_ab / 12.0 * k.eps2,
            -m22 * g.l_bm * g.l_bm / 12.0 * k.eps2,
            -m3 * g.l_bc * g.l_bc / 12.0 * k.eps3,
        );
        let (c21, c22, c3) = (
            Point::from((pos.a.coords + pos.b.coords) / 2.0),
            Point::from((pos.b.coords + pos.m.coords) / 2.0),
            Point::from((pos.b.coords + g.c.coords) / 2.0),
        );
        // Moments about B of link 2 (without R_B): R_A^n ⊥ AB.
        let u2 = (pos.b - pos.a) / g.l_ab;
        let n2 = perp(u2);
        let mom2 = cross(c21 - pos.b, w(m21) + fi21)
            + cross(c22 - pos.b, w(m22) + fi22)
            + cross(pos.m - pos.b, f_ext)
            + mi21
            + mi22;
        // cross(A − B, s·n2) + mom2 = 0
        let s2 = -mom2 / cross(pos.a - pos.b, n2);
        let r_a_n = n2 * s2;
        let u3 = (pos.b - g.c) / g.l_bc;
        let n3 = perp(u3);
        let mom3 = cross(c3 - pos.b, w(m3) + fi3) + mi3;
        let s3 = -mom3 / cross(g.c - pos.b, n3);
        let r_c_n = n3 * s3;
        let rest = r_a_n + w(m21) + fi21 + w(m22) + fi22 + f_ext + w(m3) + fi3 + r_c_n;
        // rest + t3·u3 + t2·u2 = 0
        let det = cross(u3, u2);
        let t3 = cross(-rest, u2) / det;
        let t2 = cross(u3, -rest) / det;
        let (r_c_t, r_a_t) = (u3 * t3, u2 * t2);
        let r_a = r_a_n + r_a_t;
        let r_b = -(r_a + w(m21) + fi21 + w(m22) + fi22 + f_ext);
        let r_o = r_a - fi1 - w(m1);
        Forces {
            g21: w(m21),
            g22: w(m22),
            g3: w(m3),
            g1: w(m1),
            fi21,
            fi22,
            fi3,
            fi1,
            mi21,
            mi22,
            mi3,
            mi1: 0.0,
            f_ext,
            r_a_n,
            r_a_t,
            r_c_n,
            r_c_t,
            r_a,
            r_b,
            r_c: r_c_n + r_c_t,
            r_o,
            me1: 0.0,
        }
    }

    #[test]
    fn the_chain_closes_and_the_resultants_are_the_reactions() {
        let g = chebyshev();
        for deg in [0.0f64, 90.0, 180.0, 271.0] {
            let pos = closed_form(&g, deg.to_radians(), 20.0);
            let f = seed_route(&pos, &g);
            let poly = force_polygon(&f);
            let v = poly.vertices();
            let scale = f.r_a.norm().max(1.0);
            assert!(v[11].norm() < 1e-12 * scale, "chain does not close at {deg}°");
            // R_A drawn from int to the end of R_A^n; R_B from the end of F to int; R_C from
            // the end of F_i3 to int.
            for r in &poly.resultants {
                let reaction = match r.name.as_str() {
                    "RA" => f.r_a,
                    "RB" => f.r_b,
                    "RC" => f.r_c,
                    other => panic!("unexpected resultant {other}"),
                };
                assert!(((v[r.to] - v[r.from]) - reaction).norm() < 1e-12 * scale, "{} at {deg}°", r.name);
            }
            // The crank's polygon closes with R_O.
            let b = &poly.branches[0];
            let end = b.vectors.iter().fold(v[b.from], |p, nv| p + nv.v);
            assert_eq!(b.closing, "RO");
            assert!(((v[b.closes_at] - end) - f.r_o).norm() < 1e-12 * scale, "R_O at {deg}°");
        }
    }
}
