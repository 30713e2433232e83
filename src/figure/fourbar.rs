//! Four-bar figures (seed 003 and its reference \[8\]): what the graph-analytical method
//! draws for each crank angle — the mechanism with its ground pivots, joints, letters and
//! the coupler curve of M; the velocity polygon (pole p, vectors pa, pb, pm, relative ab);
//! the acceleration polygon (pole π, a′, the normal and tangential components of a_BA and
//! of a_B about C, image points b′, m′); and, with forces, the force polygons of the dyad
//! and of the crank (see [`super::forces`]). The polygons' letters are placed by
//! [`super::labels`], so that they stay readable in a small polygon.
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
//! ([`Layout::frame`]); the DXF ([`Layout::animation`]) moves each position's entities onto
//! its own layer `POS_000`…`POS_359`, keeping the content's colour and line type on each
//! entity, so that a CAD user switches positions by layer and tells contents by colour.

use crate::draw::{Aci, Bounds, DimStyle, Drawing, Entity, HAlign, LineType, Shape, VAlign};
use crate::geom::{Point, Vector, perp};
use crate::solve::fourbar::Forces;
use crate::solve::fourbar::{Geometry, Kinematics, Position};

use super::{forces, labels};

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

/// Length unit of the model, for scale texts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModelUnits {
    /// Symbol of the length unit (`m` or `mm`); velocities are in `<unit>/s`.
    pub length: &'static str,
    /// Drawing millimetres per model unit (1000 for metres, 1 for millimetres).
    pub mm_per_unit: f64,
}

impl ModelUnits {
    /// Metres (SI scenes).
    pub const SI: ModelUnits = ModelUnits { length: "m", mm_per_unit: 1000.0 };
    /// Millimetres.
    pub const MM: ModelUnits = ModelUnits { length: "mm", mm_per_unit: 1.0 };
}

/// A drawing scale: `value` physical units per drawing millimetre.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scale {
    /// Physical units (m/s, m/s², N …) per drawing millimetre.
    pub per_mm: f64,
    /// Model units per drawing millimetre (1/`mm_per_unit`).
    unit_per_mm: f64,
}

impl Scale {
    fn new(per_mm: f64, units: ModelUnits) -> Scale {
        Scale { per_mm, unit_per_mm: 1.0 / units.mm_per_unit }
    }
    /// The drawn vector (model units) for a physical vector.
    pub fn draw(&self, v: Vector) -> Vector {
        v * (self.unit_per_mm / self.per_mm)
    }
}

/// A "nice" scale (1, 2, 2.5 or 5 × 10ᵏ) at least `raw`; 1 for a zero or non-finite `raw`.
pub fn nice_scale(raw: f64) -> f64 {
    if !(raw.is_finite() && raw > 0.0) {
        return 1.0;
    }
    let mag = 10f64.powf(raw.log10().floor());
    for m in [1.0, 2.0, 2.5, 5.0, 10.0] {
        if m * mag >= raw * (1.0 - 1e-12) {
            return m * mag;
        }
    }
    10.0 * mag
}

/// Formats a scale value compactly (`0.01`, `2.5`, `2e-05`).
pub fn scale_text(v: f64) -> String {
    if v != 0.0 && (v.abs() < 1e-3 || v.abs() >= 1e5) {
        let s = format!("{v:e}");
        return s;
    }
    let s = format!("{v:.6}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// Content layers: name, colour, line type.
pub(crate) mod layers {
    use crate::draw::{Aci, LineType};
    /// Links, joints, ground, letters.
    pub const MECHANISM: (&str, Aci, LineType) = ("MECHANISM", Aci::BLACK, LineType::Continuous);
    /// The coupler curve of M.
    pub const COUPLER_CURVE: (&str, Aci, LineType) = ("COUPLER_CURVE", Aci::CYAN, LineType::Continuous);
    /// Velocity polygon.
    pub const VELOCITY: (&str, Aci, LineType) = ("VELOCITY", Aci::GREEN, LineType::Continuous);
    /// Acceleration polygon.
    pub const ACCELERATION: (&str, Aci, LineType) = ("ACCELERATION", Aci::BLUE, LineType::Continuous);
    /// Force polygons and reactions on the mechanism.
    pub const FORCES: (&str, Aci, LineType) = ("FORCES", Aci::MAGENTA, LineType::Continuous);
    /// Construction lines (components, directions), dashed.
    pub const CONSTRUCTION: (&str, Aci, LineType) = ("CONSTRUCTION", Aci::DARK_GREY, LineType::Dashed);
    /// Titles and scales.
    pub const DIMENSIONS: (&str, Aci, LineType) = ("DIMENSIONS", Aci::BLACK, LineType::Continuous);
    /// Per-position text (the crank angle).
    pub const TEXT: (&str, Aci, LineType) = ("TEXT", Aci::BLACK, LineType::Continuous);
    /// Every content layer, in drawing order (later on top).
    pub const ALL: [(&str, Aci, LineType); 8] =
        [COUPLER_CURVE, CONSTRUCTION, VELOCITY, ACCELERATION, FORCES, MECHANISM, DIMENSIONS, TEXT];
}

/// A drawing with the content layers created in drawing order.
pub(crate) fn content_drawing(dim: DimStyle) -> Drawing {
    let mut d = Drawing::new(dim);
    for (name, color, lt) in layers::ALL {
        d.layer(name, color, lt);
    }
    d
}

/// Index of a content layer in a [`content_drawing`].
pub(crate) fn layer_of(d: &Drawing, l: (&str, Aci, LineType)) -> usize {
    d.layers.iter().position(|x| x.name == l.0).unwrap_or(0)
}

/// Sizes of drawn details, model units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sizes {
    /// Cap height of letters.
    pub text: f64,
    /// Arrowhead length.
    pub head: f64,
    /// Width of link polylines.
    pub link: f64,
    /// Radius of joint circles.
    pub joint: f64,
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

/// Points of the velocity polygon relative to the pole p: a, b, m (physical).
fn velocity_points(k: &Kinematics) -> [Vector; 4] {
    [Vector::zeros(), k.v_a, k.v_b, k.v_m]
}

/// Points of the acceleration polygon relative to the pole π: a′, n_BA, b′, m′, n_BC.
fn acceleration_points(k: &Kinematics) -> [Vector; 6] {
    [Vector::zeros(), k.a_a, k.a_a + k.a_ba_n, k.a_b, k.a_m, k.a_bc_n]
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
        let sizes = Sizes { text: 0.032 * size, head: 0.03 * size, link: 0.009 * size, joint: 0.013 * size };
        // Room for the ground symbols and letters around the mechanism.
        let pad = 3.5 * sizes.joint + 1.6 * sizes.text;
        let mech_min = Point::from(mech.min) - Vector::new(pad, pad + 2.0 * sizes.joint);
        let mech_max = Point::from(mech.max) + Vector::new(pad, pad);
        let target_mm = size * units.mm_per_unit;

        let kins: Vec<&Kinematics> = positions.iter().filter_map(|p| p.kin.as_ref()).collect();
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
            let e = kins.iter().map(|k| Extent::of(velocity_points(k))).fold(None, Extent::union);
            let (s, e) = scale_for(e);
            polys.push((format!("Velocity polygon   k_v = {} ({}/s)/mm", scale_text(s.per_mm), units.length), s, e, 0));
        }
        if show.acceleration {
            let e = kins.iter().map(|k| Extent::of(acceleration_points(k))).fold(None, Extent::union);
            let (s, e) = scale_for(e);
            polys.push((
                format!("Acceleration polygon   k_a = {} ({}/s²)/mm", scale_text(s.per_mm), units.length),
                s,
                e,
                1,
            ));
        }
        if show.forces {
            let e =
                forces.unwrap_or(&[]).iter().map(|f| Extent::of(forces::polygon_points(f))).fold(None, Extent::union);
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
            if run.len() >= 2 {
                d.add(cc, Shape::Polyline { points: run.clone(), closed: false, width: 0.0 });
            }
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
        mechanism(&mut d, geom, pos, s);
        if let (Some(k), Some((scale, pole))) = (pos.kin.as_ref(), self.velocity) {
            velocity_polygon(&mut d, k, scale, pole, s);
        }
        if let (Some(k), Some((scale, pole))) = (pos.kin.as_ref(), self.acceleration) {
            acceleration_polygon(&mut d, pos, geom.c, k, scale, pole, s);
        }
        if let (Some(f), Some((scale, pole))) = (force, self.forces) {
            forces::polygons(&mut d, f, scale, pole, s);
            forces::reactions_on_mechanism(&mut d, pos, f, scale, s);
        }
        d
    }

    /// One animation frame: `base` with `moving` on top.
    pub fn frame(&self, base: &Drawing, moving: &Drawing) -> Drawing {
        let mut d = base.clone();
        append(&mut d, moving, |name| name.to_string(), false);
        d
    }

    /// The whole motion in one drawing (for the DXF): `base` on its content layers, and each
    /// position's entities on its own layer (`(layer name, moving drawing)`), with the
    /// content's colour and line type kept on every entity.
    pub fn animation<'a>(
        &self,
        base: &Drawing,
        positions: impl IntoIterator<Item = (&'a str, &'a Drawing)>,
    ) -> Drawing {
        let mut d = base.clone();
        for (layer, moving) in positions {
            append(&mut d, moving, |_| layer.to_string(), true);
        }
        d
    }
}

/// Appends `src`'s entities to `dst`, on the layers named by `rename(src layer name)`.
/// With `keep_style`, each entity gets its source layer's colour and line type as its own.
fn append(dst: &mut Drawing, src: &Drawing, rename: impl Fn(&str) -> String, keep_style: bool) {
    let map: Vec<usize> = src
        .layers
        .iter()
        .map(|l| {
            let (color, lt) = if keep_style { (Aci::BLACK, LineType::Continuous) } else { (l.color, l.linetype) };
            dst.layer(&rename(&l.name), color, lt)
        })
        .collect();
    dst.entities.reserve(src.entities.len());
    for e in &src.entities {
        let (color, linetype) =
            if keep_style { (Some(src.color_of(e)), Some(src.linetype_of(e))) } else { (e.color, e.linetype) };
        dst.entities.push(Entity { layer: map[e.layer], color, linetype, shape: e.shape.clone() });
    }
}

/// Angle in degrees for labels: integers without decimals, else up to 3 decimals.
pub fn angle_text(deg: f64) -> String {
    let r = (deg * 1000.0).round() / 1000.0;
    let s = format!("{r:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".to_string() } else { s.to_string() }
}

/// A centred letter at `at`, nudged along `dir` (unit or zero) so it clears a line end.
pub(crate) fn label(d: &mut Drawing, layer: usize, at: Point, h: f64, s: &str, dir: Vector) {
    let n = dir.norm();
    let u = if n > 0.0 && n.is_finite() { dir / n } else { Vector::zeros() };
    // Wider names sit further out sideways (about 0.6 letter heights per character).
    let chars = s.chars().count().max(1) as f64;
    let nudge = 0.8 * h + 0.3 * h * (chars - 1.0) * u.x.abs();
    d.add(
        layer,
        Shape::Text {
            at: at + u * nudge,
            height: h,
            value: s.to_string(),
            halign: HAlign::Center,
            valign: VAlign::Middle,
            rotation: 0.0,
        },
    );
}

/// A vector arrow from `from` by `v` (drawn units) with a letter at its tip; nothing for a
/// vector shorter than a hundredth of the arrowhead.
pub(crate) fn vector(d: &mut Drawing, layer: usize, from: Point, v: Vector, name: &str, s: Sizes) {
    if v.norm().is_nan() || v.norm() <= 0.01 * s.head {
        return;
    }
    d.add(layer, Shape::Arrow { from, to: from + v, head: s.head });
    if !name.is_empty() {
        label(d, layer, from + v, s.text, name, v);
    }
}

/// The ground symbol under a fixed pivot: a support triangle, a base line and hatch strokes.
fn ground(d: &mut Drawing, layer: usize, p: Point, s: Sizes) {
    let r = s.joint;
    let h = 2.6 * r;
    let base_y = p.y - h;
    d.add(
        layer,
        Shape::Polyline {
            points: vec![p, Point::new(p.x - 1.4 * r, base_y), Point::new(p.x + 1.4 * r, base_y)],
            closed: true,
            width: 0.0,
        },
    );
    let half = 2.6 * r;
    d.add(layer, Shape::Line { from: Point::new(p.x - half, base_y), to: Point::new(p.x + half, base_y) });
    let n = 6;
    for i in 0..n {
        let x = p.x - half + (i as f64 + 0.5) * (2.0 * half / n as f64);
        d.add(layer, Shape::Line { from: Point::new(x, base_y), to: Point::new(x - 0.8 * r, base_y - 0.8 * r) });
    }
    d.add(layer, Shape::Circle { center: p, radius: r });
}

/// Links (wide polylines), joints (circles), letters A, B, M.
fn mechanism(d: &mut Drawing, geom: &Geometry, pos: &Position, s: Sizes) {
    let mech = layer_of(d, layers::MECHANISM);
    let w = s.link;
    let straight = (geom.alpha - std::f64::consts::PI).abs() < 1e-9;
    d.add(mech, Shape::Polyline { points: vec![geom.o1, pos.a], closed: false, width: w });
    d.add(mech, Shape::Polyline { points: vec![pos.a, pos.b, pos.m], closed: !straight, width: w });
    d.add(mech, Shape::Polyline { points: vec![geom.c, pos.b], closed: false, width: w });
    for p in [pos.a, pos.b] {
        d.add(mech, Shape::Circle { center: p, radius: s.joint });
    }
    d.add(mech, Shape::Circle { center: pos.m, radius: 0.6 * s.joint });
    // Letters outside the linkage: A away from O1, B away from the mid-point of A and C,
    // M along B→M.
    let off = 1.8 * s.joint;
    let ua = unit_or(pos.a - geom.o1, Vector::new(0.0, 1.0));
    label(d, mech, pos.a + ua * off, s.text, "A", ua);
    // The pivots' letters opposite to their links, so no link runs over them, but never
    // down into the ground symbol.
    let level = |v: Vector, fallback: Vector| unit_or(Vector::new(v.x, v.y.max(0.0)), fallback);
    let uo = level(unit_or(geom.o1 - pos.a, Vector::zeros()), Vector::new(-1.0, 0.0));
    label(d, mech, geom.o1 + uo * (1.8 * s.joint), s.text, "O1", uo);
    let uc = level(unit_or(geom.c - pos.b, Vector::zeros()), Vector::new(1.0, 0.0));
    label(d, mech, geom.c + uc * (1.8 * s.joint), s.text, "C", uc);
    let mid_ac = Point::from((pos.a.coords + geom.c.coords) / 2.0);
    let ub = unit_or(pos.b - mid_ac, Vector::new(0.0, 1.0));
    label(d, mech, pos.b + ub * off, s.text, "B", ub);
    let um = unit_or(pos.m - pos.b, Vector::new(1.0, 0.0));
    let um = unit_or(um + perp(um) * 0.6, um);
    label(d, mech, pos.m + um * off, s.text, "M", um);
}

fn unit_or(v: Vector, fallback: Vector) -> Vector {
    let n = v.norm();
    if n > 0.0 && n.is_finite() { v / n } else { fallback }
}

/// The velocity polygon: pole p; pa, pb, pm; the relative velocity ab (v_BA) and bm. The
/// letters are placed by [`labels::Polygon`] so that they stay apart in a small polygon.
fn velocity_polygon(d: &mut Drawing, k: &Kinematics, scale: Scale, pole: Point, s: Sizes) {
    let l = layer_of(d, layers::VELOCITY);
    let (a, b, m) = (pole + scale.draw(k.v_a), pole + scale.draw(k.v_b), pole + scale.draw(k.v_m));
    let mut letters = labels::Polygon::of_points();
    // pa, pb, pm, then the relative velocities: v_BA from a to b, v_MB from b to m (the
    // image of the coupler).
    for (from, to) in [(pole, a), (pole, b), (pole, m), (a, b), (b, m)] {
        vector(d, l, from, to - from, "", s);
        letters.segment(from, to);
    }
    d.add(l, Shape::Circle { center: pole, radius: 0.25 * s.joint });
    letters.letter(pole, "p", s.text, -(a - pole) - (b - pole), None);
    for (at, name) in [(a, "a"), (b, "b"), (m, "m")] {
        letters.letter(at, name, s.text, at - pole, None);
    }
    letters.draw(d, l);
}

/// The acceleration polygon as the graph-analytical construction draws it:
/// π → a′ (a_A); from a′ the normal component a_BA^n (parallel to BA) to n_BA, then the
/// tangential direction (perpendicular to AB, dashed) to b′; from π the normal component
/// of a_B about C (parallel to BC) to n_BC, then the tangential direction (perpendicular to
/// BC, dashed) to b′; π → b′, π → m′, and the image a′b′m′ of the coupler.
fn acceleration_polygon(
    d: &mut Drawing,
    pos: &Position,
    c_pivot: Point,
    k: &Kinematics,
    scale: Scale,
    pole: Point,
    s: Sizes,
) {
    let l = layer_of(d, layers::ACCELERATION);
    let c = layer_of(d, layers::CONSTRUCTION);
    let a1 = pole + scale.draw(k.a_a);
    let n_ba = a1 + scale.draw(k.a_ba_n);
    let b1 = pole + scale.draw(k.a_b);
    let n_bc = pole + scale.draw(k.a_bc_n);
    let m1 = pole + scale.draw(k.a_m);
    // Tangential directions: full dashed lines through n_BA ⊥ AB and n_BC ⊥ BC, reaching a
    // little past b′ on both sides.
    let reach = 4.0 * s.head;
    let mut letters = labels::Polygon::of_points();
    for (n, dir) in [(n_ba, perp(pos.b - pos.a)), (n_bc, perp(pos.b - c_pivot))] {
        let u = unit_or(dir, Vector::new(1.0, 0.0));
        let t0 = (b1 - n).dot(&u);
        let (lo, hi) = (t0.min(0.0) - reach, t0.max(0.0) + reach);
        d.add(c, Shape::Line { from: n + u * lo, to: n + u * hi });
        letters.segment(n + u * lo, n + u * hi);
    }
    // Components: normal parts solid, tangential parts as dashed arrows.
    vector(d, l, a1, n_ba - a1, "", s);
    vector(d, l, pole, n_bc - pole, "", s);
    vector(d, c, n_ba, b1 - n_ba, "", s);
    vector(d, c, n_bc, b1 - n_bc, "", s);
    vector(d, l, pole, a1 - pole, "", s);
    vector(d, l, pole, b1 - pole, "", s);
    vector(d, l, pole, m1 - pole, "", s);
    // Image of the coupler: a′b′ (a_BA) and b′m′.
    d.add(l, Shape::Line { from: a1, to: b1 });
    d.add(l, Shape::Line { from: b1, to: m1 });
    d.add(l, Shape::Circle { center: pole, radius: 0.25 * s.joint });
    for (from, to) in [(a1, n_ba), (pole, n_bc), (n_ba, b1), (n_bc, b1), (pole, a1), (pole, b1), (pole, m1), (a1, b1)] {
        letters.segment(from, to);
    }
    letters.segment(b1, m1);
    // The points first, then the ends of the normal components.
    letters.letter(pole, "π", s.text, -(a1 - pole) - (b1 - pole), None);
    for (at, name) in [(a1, "a'"), (b1, "b'"), (m1, "m'")] {
        letters.letter(at, name, s.text, at - pole, None);
    }
    letters.letter(n_ba, "nBA", s.text, n_ba - a1, None);
    letters.letter(n_bc, "nBC", s.text, n_bc - pole, None);
    letters.draw(d, l);
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

    #[test]
    fn preview_frames_for_people() {
        // Writes target/fourbar-preview-*.png to look at while developing.
        let (lay, frames) = run(Show { velocity: true, acceleration: true, forces: false });
        let opts = crate::draw::svg::SvgOptions { window: Some(lay.window), ..Default::default() };
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target");
        for (f, n) in frames.iter().zip([0, 90, 180]) {
            let svg = crate::draw::svg::to_string(f, &opts);
            let png = crate::draw::raster::to_png(&svg, 1200).unwrap();
            std::fs::write(dir.join(format!("fourbar-preview-{n}.png")), png).unwrap();
        }
    }
}
