//! Four-bar figures (seed 003 and its reference \[8\]): what the graph-analytical method
//! draws for each crank angle — the mechanism with its ground pivots, joints, letters and
//! the coupler curve of M; the velocity polygon (pole p, vectors pa, pb, pm, relative ab);
//! the acceleration polygon (pole π, a′, the normal and tangential components of a_BA and
//! of a_B about C, image points b′, m′); and, with forces, the force polygons of the dyad
//! and of the crank. This file only adapts the four-bar's results to the shared
//! vocabulary: small adapters build the polygons as named points
//! ([`crate::figure::shared::polygon::PointPolygon`]) and named vectors
//! ([`crate::figure::shared::forces::ForcePolygon`]) from `Kinematics` and `Forces`; the drawing code
//! knows no four-bar field. Every letter is placed by [`crate::figure::shared::labels`].
//!
//! # Layout and scales
//! One [`Layout`] is computed per run from every position, so all frames share one window
//! and one set of scales and an animation does not jump. The page is real paper: the
//! mechanism is drawn at a length scale k_l (model units per paper millimetre, a nice value
//! 1, 2, 2.5, 5 × 10ᵏ) that makes the whole motion (all of O1, C, A, B, M over the run) at
//! most [`MECHANISM_MM`] long on paper, and the drawing carries `paper_mm_per_unit = 1/k_l`,
//! so the SVG is sized in millimetres and prints true at 100 %. Letters, arrowheads, joints
//! and links are sized in paper millimetres ([`Sizes::on_paper`]: letters 3.5 mm). Each
//! polygon gets a smaller panel in a column beside the mechanism (the force panel under
//! both: the mechanism is the largest figure), holding the polygon at every
//! position, at a scale per printed millimetre: `k_v = 0.01 (m/s)/mm` means that one
//! millimetre measured on the printed page stands for 0.01 m/s. Scales are nice numbers
//! chosen from the largest polygon over the motion. The mechanism panel's title prints k_l
//! (`Mechanism   k_l = 0.002 m/mm`), each polygon's its scale, and every panel has a scale
//! bar (`0 ├──┤ 0.05 m`, `0 ├──┤ 0.5 m/s` …) in a strip under its content. With the
//! template's three polygons the page is about 255 × 265 mm (A3 landscape, or A4 at 80 %).
//!
//! # Layers
//! [`Layout::base`] holds what is the same at every position (ground pivots, coupler curve,
//! panel titles, scales) on the content layers `MECHANISM`, `COUPLER_CURVE`, `DIMENSIONS`.
//! [`Layout::moving`] draws one position on the content layers `MECHANISM`, `VELOCITY`,
//! `ACCELERATION`, `FORCES`, `CONSTRUCTION`, `TEXT`. An SVG frame is base + moving
//! ([`Layout::frame`]); the DXF ([`crate::figure::shared::animation::Animation::all_positions`], from the run's animation) moves each position's entities onto
//! its own layer `POS_000`…`POS_359`, keeping the content's colour and line type on each
//! entity, so that a CAD user switches positions by layer and tells contents by colour.

pub mod centres;
pub mod joukowski;
pub mod sheet;

use crate::draw::{Drawing, Shape};
use crate::geom::{Point, Vector, cross, perp};
use crate::solve::fourbar::{ExternalForce, Forces, Link, LinkLoad};
use crate::solve::fourbar::{Geometry, Kinematics, Position};

use crate::figure::shared::forces::{self, ForcePolygon, NamedVector, Resultant};
use crate::figure::shared::labels::{self, Label};
pub use crate::figure::shared::panels::ScaleChoice;
pub use crate::figure::shared::panels::TABLE_CAPTION;
use crate::figure::shared::panels::{Extent, ForceSpec, PanelFrame, PanelSpec};
use crate::figure::shared::polygon::{Direction, NamedPoint, POLE, PointPolygon, Side, SideKind};
pub use crate::figure::shared::vocab::{ModelUnits, Scale, Sizes, nice_scale, scale_text};
use crate::figure::shared::vocab::{ground, ground_extent, joint, layer_of, layers, link, path, turn_arrow, unit_or};

/// Largest extent of the mechanism's motion on paper, millimetres: k_l is the nice value
/// that draws it at most this long.
pub const MECHANISM_MM: f64 = 150.0;

/// Which polygons to draw (from the scene's `outputs`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Show {
    /// The velocity polygon.
    pub velocity: bool,
    /// The acceleration polygon.
    pub acceleration: bool,
    /// The force polygons (the dyad's and the crank's), the table of magnitudes, and the
    /// reactions R_A, R_B, R_C, R_O and the load F on the mechanism.
    pub forces: bool,
    /// How the frames' polygon scales are chosen (the scene's `[frames] scales`).
    pub scales: ScaleChoice,
}

/// Panels, scales and what the four-bar draws on its mechanism, for one run: computed once
/// from every position ([`PanelFrame`] places the panels).
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// What is drawn.
    pub show: Show,
    /// The panels, scales and poles.
    pub frame: PanelFrame,
    /// The crank's angular velocity (rad/s, CCW positive) for the ω1 arrow
    /// ([`Layout::with_drive`]); without it the arrow follows the sign of the kinematics'.
    pub omega1: Option<f64>,
    /// The external forces on the coupler, drawn on the mechanism where they act
    /// ([`Layout::with_drive`]).
    pub external: Vec<ExternalForce>,
    /// The link loads, drawn where they act ([`Layout::with_link_loads`]).
    pub link_loads: Vec<LinkLoad>,
    /// What every frame shares ([`Layout::base`]), for each frame's letters to keep off
    /// ([`Layout::with_backdrop`]).
    pub backdrop: Option<Drawing>,
}

/// Where a polygon is drawn: its scale and its pole.
pub type Place = (Scale, Point);

/// Caption of the dyad's force polygon.
pub const DYAD_CAPTION: &str = "Dyad 2–3 (Fig. 4)";
/// Caption of the crank's force polygon.
pub const CRANK_CAPTION: &str = "Crank 1 (Fig. 5)";

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
        let mechanism = Extent::of(pts.chain([geom.o1.coords, geom.c.coords]))
            .unwrap_or(Extent { min: Vector::zeros(), max: Vector::new(1.0, 1.0) });
        let size = mechanism.size().max(geom.l1.max(geom.l_bc));
        let kins: Vec<(&Position, &Kinematics)> = positions.iter().filter_map(|p| Some((p, p.kin.as_ref()?))).collect();
        let show = Show {
            velocity: show.velocity && !kins.is_empty(),
            acceleration: show.acceleration && !kins.is_empty(),
            forces: show.forces && forces.is_some_and(|f| !f.is_empty()),
            scales: show.scales,
        };
        // Each polygon's extent at each position (frame k draws positions[k]).
        let per_position = |poly: &dyn Fn(&Position, &Kinematics) -> PointPolygon| -> Vec<Option<Extent>> {
            positions.iter().map(|p| p.kin.as_ref().and_then(|k| Extent::of(poly(p, k).physical_points()))).collect()
        };
        let velocity = show.velocity.then(|| per_position(&|_, k| velocity_polygon(k)));
        let acceleration = show.acceleration.then(|| per_position(&|p, k| acceleration_polygon(p, geom.c, k)));
        let force_spec = forces.filter(|_| show.forces).map(|fs| {
            let moment_unit = format!("N·{}", units.length);
            let extent =
                |poly: fn(&Forces) -> ForcePolygon| fs.iter().map(|f| Extent::of(poly(f).physical_points())).collect();
            ForceSpec {
                figures: vec![
                    (DYAD_CAPTION.to_string(), extent(dyad_polygon)),
                    (CRANK_CAPTION.to_string(), extent(crank_polygon)),
                ],
                rows: fs.iter().flat_map(|f| magnitudes(f, &moment_unit)).collect(),
                row_count: MAGNITUDE_ROWS,
                on_mechanism: positions
                    .iter()
                    .zip(fs)
                    .flat_map(|(pos, f)| on_mechanism(geom, pos, f, &[]).into_iter().map(|(at, nv)| (at, nv.v)))
                    .collect(),
            }
        });
        let frame = PanelFrame::new(&PanelSpec {
            units,
            mechanism,
            size,
            mechanism_mm: MECHANISM_MM,
            polygon_mm: None,
            // Room for the ground symbols and letters around the mechanism.
            pad: |s| (3.5 * s.joint + 1.6 * s.text, 2.0 * s.joint),
            position_text: "φ1 = 359.999°".to_string(),
            velocity,
            acceleration,
            forces: force_spec,
            scales: show.scales,
        });
        Layout { show, frame, omega1: None, external: Vec::new(), link_loads: Vec::new(), backdrop: None }
    }

    /// The layout with the crank's angular velocity `omega1` (rad/s, CCW positive: the ω1
    /// arrow's sense) and the scene's external forces (drawn on the mechanism at the force
    /// scale where and when they act).
    pub fn with_drive(mut self, omega1: f64, external: &[ExternalForce]) -> Layout {
        self.omega1 = Some(omega1);
        self.external = external.to_vec();
        self
    }

    /// The layout with the scene's link loads (drawn on the mechanism at the force scale
    /// where and when they act: `F1` on the crank, `F2` on the coupler, `F3` on the rocker).
    pub fn with_link_loads(mut self, loads: &[LinkLoad]) -> Layout {
        self.link_loads = loads.to_vec();
        self
    }

    /// The layout with what every frame shares drawn once ([`Layout::base`]): each frame's
    /// letters keep clear of it (the coupler curve, the ground symbols, the titles).
    pub fn with_backdrop(mut self, base: &Drawing) -> Layout {
        self.backdrop = Some(base.clone());
        self
    }

    /// What every frame shares: the ground pivots with their hatch symbols (their letters
    /// move with the links, see [`Layout::moving`]), the coupler
    /// curve of M (`curve`: runs of consecutive positions; a gap in the motion breaks it),
    /// the panel titles with the scales, each panel's scale bar, and the captions of the
    /// force figures.
    pub fn base(&self, geom: &Geometry, curve: &[Vec<Point>]) -> Drawing {
        let mut d = self.frame.paper_drawing();
        let mech = layer_of(&d, layers::MECHANISM);
        let cc = layer_of(&d, layers::COUPLER_CURVE);
        for run in curve {
            path(&mut d, cc, run.clone());
        }
        for p in [geom.o1, geom.c] {
            ground(&mut d, mech, p, self.frame.sizes);
        }
        self.frame.draw_titles(&mut d);
        d
    }

    /// One position on the content layers: the mechanism (with R_A, R_B, R_C, R_O and the
    /// acting loads when forces are shown), the crank-angle text, the polygons asked for, and
    /// with forces the table of magnitudes; `k` is the position's index in the run (or the
    /// nearest's, for one between them), for the polygons' scales.
    pub fn moving(&self, k: usize, geom: &Geometry, pos: &Position, force: Option<&Forces>) -> Drawing {
        let mut d = self.frame.paper_drawing();
        let s = self.frame.sizes;
        // φ_1 where the writer can draw a subscript, `φ1` in the DXF (the viewer's slider label
        // is the animation's own, flat).
        let position = Label::marked(&format!("φ_1 = {}°", angle_text(pos.phi1.to_degrees())));
        self.frame.draw_position_text(&mut d, position);
        // The reactions and the loads drawn on the mechanism, for its letters to keep off.
        let arrows = match (force, self.frame.mechanism_forces) {
            (Some(f), Some(scale)) => {
                let links = links_of(geom, pos);
                let inside = Point::from((geom.o1.coords + pos.a.coords + pos.b.coords + geom.c.coords) / 4.0);
                let mut acting = on_mechanism(geom, pos, f, &self.external);
                acting.extend(link_loads_on_mechanism(geom, pos, &self.link_loads));
                forces::arrows_on_mechanism(&acting, scale, &links, inside, s)
            }
            _ => Vec::new(),
        };
        let omega1 = self.omega1.or_else(|| pos.kin.map(|k| cross(pos.a - geom.o1, k.v_a)));
        forces::draw_on_mechanism(&mut d, &arrows, s);
        let (ll, ur) = self.frame.mechanism_panel();
        let within = Some(labels::TextBox { min: ll, max: ur });
        let _ = mechanism(
            &mut d,
            geom,
            pos,
            &arrows,
            omega1,
            s,
            labels::Around { backdrop: self.backdrop.as_ref(), within },
        );
        let kin = pos.kin.as_ref();
        let velocity = kin.map(|k| velocity_figure(pos, geom.c, k));
        let acceleration = kin.map(|k| acceleration_polygon(pos, geom.c, k));
        let moment_unit = format!("N·{}", self.frame.units.length);
        let figures = force.map(|f| ([dyad_polygon(f), crank_polygon(f)], magnitudes(f, &moment_unit)));
        let figures = figures.as_ref().map(|(p, m)| (&p[..], &m[..]));
        self.frame.draw_polygons(&mut d, k, velocity.as_ref(), acceleration.as_ref(), figures);
        d
    }

    /// The velocity and acceleration polygons' scales and poles at position `k` of the run
    /// (`pos`), as [`Layout::moving`] draws them.
    pub fn polygon_places(&self, k: usize, pos: &Position) -> (Option<Place>, Option<Place>) {
        let Some(kin) = pos.kin.as_ref() else { return (None, None) };
        let k_l = self.frame.k_l;
        let v =
            self.frame.velocity.as_ref().map(|s| s.place(k, Extent::of(velocity_polygon(kin).physical_points()), k_l));
        let a = self
            .frame
            .acceleration
            .as_ref()
            .map(|s| s.place(k, Extent::of(acceleration_polygon(pos, pos.c, kin).physical_points()), k_l));
        (v, a)
    }

    /// The force figures' (the dyad's, the crank's) scales and poles at position `k` with
    /// forces `f`, as [`Layout::moving`] draws them.
    pub fn force_places(&self, k: usize, f: &Forces) -> Vec<Place> {
        let Some(cells) = &self.frame.forces else { return Vec::new() };
        [dyad_polygon(f), crank_polygon(f)]
            .iter()
            .zip(&cells.figures)
            .map(|(p, slot)| slot.place(k, Extent::of(p.physical_points()), self.frame.k_l))
            .collect()
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

/// The links as segments: crank O1A, coupler AB and BM, rocker CB.
fn links_of(geom: &Geometry, pos: &Position) -> [(Point, Point); 4] {
    [(geom.o1, pos.a), (pos.a, pos.b), (pos.b, pos.m), (geom.c, pos.b)]
}

/// Radius of the ω1 arrow about O1, in joint radii.
const OMEGA_RADIUS: f64 = 3.5;
/// The ω1 arrow's arc: from 30° to 150° above O1 (clear of the ground symbol below).
const OMEGA_ARC_DEG: (f64, f64) = (30.0, 150.0);

/// Links (wide polylines), joints (circles), the ω1 arrow at O1 (when `omega1` is known:
/// its sign gives the sense), the link numbers 1, 2, 3 in circles, and the letters O1, C, A,
/// B, M, the numbers, ω1 and the names of the forces `arrows` drawn on the mechanism, all
/// placed by one [`labels::Polygon`]: clear of each other, the joints, the ground symbols,
/// and preferably off the links and the arrows. Returns the boxes of the placed texts, for
/// later texts to keep off.
pub(crate) fn mechanism(
    d: &mut Drawing,
    geom: &Geometry,
    pos: &Position,
    arrows: &[forces::ForceArrow],
    omega1: Option<f64>,
    s: Sizes,
    around: labels::Around<'_>,
) -> Vec<labels::TextBox> {
    let mech = layer_of(d, layers::MECHANISM);
    let frc = layer_of(d, layers::FORCES);
    let straight = (geom.alpha - std::f64::consts::PI).abs() < 1e-9;
    link(d, mech, vec![geom.o1, pos.a], false, None, s);
    link(d, mech, vec![pos.a, pos.b, pos.m], !straight, None, s);
    link(d, mech, vec![geom.c, pos.b], false, None, s);
    for p in [pos.a, pos.b] {
        joint(d, mech, p, s);
    }
    d.add(mech, Shape::Circle { center: pos.m, radius: 0.6 * s.joint });
    let mut letters = labels::Polygon::of_names();
    let links = links_of(geom, pos);
    for (a, b) in links.iter().chain(arrows.iter().map(|a| &a.arrow)) {
        letters.segment(*a, *b);
    }
    for a in arrows.iter().filter(|a| a.arrow.0 != a.at) {
        letters.segment(a.at, a.arrow.0);
    }
    for g in [ground_extent(geom.o1, s), ground_extent(geom.c, s)] {
        letters.keep_off(g);
    }
    // The ω1 arrow: an arc above O1, its head in the sense of rotation.
    let omega_mid = omega1.filter(|w| *w != 0.0 && w.is_finite()).map(|w| {
        let (a0, a1) = (OMEGA_ARC_DEG.0.to_radians(), OMEGA_ARC_DEG.1.to_radians());
        let (from, sweep) = if w > 0.0 { (a0, a1 - a0) } else { (a1, a0 - a1) };
        let r = OMEGA_RADIUS * s.joint;
        let mid = turn_arrow(d, mech, geom.o1, r, from, sweep, s);
        // The arc for the letters, as chords.
        let at = |t: f64| geom.o1 + Vector::new(libm::cos(from + t * sweep), libm::sin(from + t * sweep)) * r;
        for i in 0..6 {
            letters.segment(at(i as f64 / 6.0), at((i + 1) as f64 / 6.0));
        }
        mid
    });
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
    // Link numbers beside the middles of the crank, of AB and of the rocker, outwards.
    let inside = Point::from((geom.o1.coords + pos.a.coords + pos.b.coords + geom.c.coords) / 4.0);
    for (number, (p, q)) in [("1", links[0]), ("2", links[1]), ("3", links[3])] {
        let mid = p + (q - p) * 0.5;
        let mut n = perp(unit_or(q - p, Vector::new(1.0, 0.0)));
        if n.dot(&(mid - inside)) < 0.0 {
            n = -n;
        }
        letters.circled(mid, number, s.text, n, 0.5 * s.link);
    }
    if let Some(mid) = omega_mid {
        letters.letter(mid, Label::quantity("ω1"), s.text, mid - geom.o1, None);
    }
    for a in arrows {
        let v = a.arrow.1 - a.arrow.0;
        letters.letter(a.arrow.1, a.force.label(), s.text, v, None);
    }
    // Clear of everything drawn so far and around.
    letters.keep_off_drawing(d);
    letters.around(around);
    // Letters and numbers on the mechanism's layer, force names on the forces' layer.
    let placed = letters.place();
    let on_mechanism = placed.len() - arrows.len();
    for (i, p) in placed.iter().enumerate() {
        let layer = if i < on_mechanism { mech } else { frc };
        labels::draw_placed(d, layer, p, Some(crate::draw::LineType::Continuous));
    }
    placed.iter().map(labels::Placed::bounds).collect()
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
        marks: vec![],
    }
}

/// Whether the coupler A–B–M is a ternary plate (M off the line AB), so that its images
/// abm and a′b′m′ are triangles.
fn ternary(pos: &Position) -> bool {
    let (ab, bm) = (pos.b - pos.a, pos.m - pos.b);
    cross(ab, bm).abs() > 1e-9 * ab.norm() * bm.norm()
}

/// The velocity polygon as the graph-analytical construction draws it: the polygon of
/// [`velocity_polygon`] with the directions that locate b dashed (⊥AB through a, for v_BA;
/// ⊥BC through p, for v_B), and the image abm of a ternary coupler closed (am).
fn velocity_figure(pos: &Position, c_pivot: Point, k: &Kinematics) -> PointPolygon {
    let (a, b, m) = (1, 2, 3);
    let mut poly = velocity_polygon(k);
    poly.directions = vec![
        Direction { through: a, dir: perp(pos.b - pos.a), reaches: b },
        Direction { through: POLE, dir: perp(pos.b - c_pivot), reaches: b },
    ];
    if ternary(pos) {
        poly.sides.push(Side { from: a, to: m, kind: SideKind::Image });
    }
    poly
}

/// The acceleration polygon as the graph-analytical construction draws it:
/// π → a′ (a_A); from a′ the normal component a_BA^n (parallel to BA) to n_BA, then the
/// tangential direction (perpendicular to AB, dashed) to b′; from π the normal component
/// of a_B about C (parallel to BC) to n_BC, then the tangential direction (perpendicular to
/// BC, dashed) to b′; π → b′, π → m′, the image a′b′m′ of the coupler (closed when it is a
/// ternary plate); and the images of the centroids (seed Fig. 1, from which the inertia
/// forces come): c1′ (middle of πa′), c21′ (of a′b′), c22′ (of b′m′), c3′ (of πb′), marked,
/// with π → c21′ and π → c22′.
pub(crate) fn acceleration_polygon(pos: &Position, c_pivot: Point, k: &Kinematics) -> PointPolygon {
    let (a1, b1, m1, n_ba, n_bc) = (1, 2, 3, 4, 5);
    let (c1, c21, c22, c3) = (6, 7, 8, 9);
    let side = |from, to, kind| Side { from, to, kind };
    let mut sides = vec![
        side(a1, n_ba, SideKind::Vector),
        side(POLE, n_bc, SideKind::Vector),
        side(n_ba, b1, SideKind::Component),
        side(n_bc, b1, SideKind::Component),
        side(POLE, a1, SideKind::Vector),
        side(POLE, b1, SideKind::Vector),
        side(POLE, m1, SideKind::Vector),
        side(a1, b1, SideKind::Image),
        side(b1, m1, SideKind::Image),
    ];
    if ternary(pos) {
        sides.push(side(a1, m1, SideKind::Image));
    }
    sides.push(side(POLE, c21, SideKind::Vector));
    sides.push(side(POLE, c22, SideKind::Vector));
    let point = |name: &str, from, v| NamedPoint { name: name.into(), from, v };
    PointPolygon {
        pole: "π".into(),
        pole_away: vec![a1, b1],
        // The points first, then the ends of the normal components, then the centroids.
        points: vec![
            point("a′", POLE, k.a_a),
            point("b′", POLE, k.a_b),
            point("m′", POLE, k.a_m),
            point("nBA", a1, k.a_ba_n),
            point("nBC", POLE, k.a_bc_n),
            point("c1′", POLE, k.a_g1),
            point("c21′", POLE, k.a_g21),
            point("c22′", POLE, k.a_g22),
            point("c3′", POLE, k.a_g3),
        ],
        // Tangential directions: ⊥AB through n_BA, ⊥BC through n_BC.
        directions: vec![
            Direction { through: n_ba, dir: perp(pos.b - pos.a), reaches: b1 },
            Direction { through: n_bc, dir: perp(pos.b - c_pivot), reaches: b1 },
        ],
        // Components: normal parts solid, tangential parts as dashed arrows; then the
        // accelerations of the points and the image of the coupler: a′b′ (a_BA) and b′m′.
        sides,
        marks: vec![c1, c21, c22, c3],
    }
}

/// The dyad's force polygon (seed Fig. 4), chain from the pole f in the seed's order
/// (eq. 5): R_A^n, G21, F_i21, G22, F_i22, F, G3, F_i3, R_C^n, then R_C^t (along BC) and
/// R_A^t (along AB), which close it at the intersection point `int` (vertex 10). In it, R_A
/// runs from `int` to the end of R_A^n, R_C from the end of F_i3 to `int`, and R_B (seed
/// eq. 7) from the end of F to `int`; R_B and R_C are often nearly the same segment (a
/// light rocker): the resultants are drawn beside a side they would lie on
/// ([`forces::draw`]) and their names start from different places along them.
pub fn dyad_polygon(f: &Forces) -> ForcePolygon {
    let nv = NamedVector::new;
    // A load on the rocker (F3, from the link loads) joins the chain after Fi3, when any.
    let f3 = usize::from(f.f3_ext != Vector::zeros());
    let (p_ran, p_f, p_fi3, int) = (1, 6, 8 + f3, 10 + f3);
    let resultant = |name: &str, from, to, name_at| Resultant { name: name.into(), from, to, name_at };
    let mut chain = vec![
        nv("RAn", f.r_a_n),
        nv("G21", f.g21),
        nv("Fi21", f.fi21),
        nv("G22", f.g22),
        nv("Fi22", f.fi22),
        nv("F", f.f_ext),
        nv("G3", f.g3),
        nv("Fi3", f.fi3),
    ];
    if f3 == 1 {
        chain.push(nv("F3", f.f3_ext));
    }
    chain.extend([nv("RCn", f.r_c_n), nv("RCt", f.r_c_t), nv("RAt", f.r_a_t)]);
    ForcePolygon {
        pole: "f".into(),
        chain,
        resultants: vec![
            resultant("RA", int, p_ran, 0.5),
            resultant("RB", p_f, int, 0.7),
            resultant("RC", p_fi3, int, 0.3),
        ],
        // R_C^t and R_A^t close it.
        found: 2,
    }
}

/// The crank's force polygon (seed Fig. 5), with its own pole f1 (the seed's pRAn): the
/// load of the coupler on the crank −R_A, then F_i1 and G1; R_O closes it back to the pole
/// (seed eq. 8: −R_A + F_i1 + G1 + R_O = 0).
pub fn crank_polygon(f: &Forces) -> ForcePolygon {
    let nv = NamedVector::new;
    let mut chain = vec![nv("−RA", -f.r_a), nv("Fi1", f.fi1), nv("G1", f.g1)];
    // A load on the crank (F1, from the link loads), when any.
    if f.f1_ext != Vector::zeros() {
        chain.push(nv("F1", f.f1_ext));
    }
    let from = chain.len();
    ForcePolygon {
        pole: "f1".into(),
        chain,
        resultants: vec![Resultant { name: "RO".into(), from, to: 0, name_at: 0.5 }],
        found: 0,
    }
}

/// The number of rows of [`magnitudes`].
const MAGNITUDE_ROWS: usize = 9;

/// The table of magnitudes: |R_A^n|, |R_A^t|, |R_C^n|, |R_C^t|, |R_A|, |R_B|, |R_C|, |R_O|
/// in N, and Me1 (signed, CCW positive) in `moment_unit`.
fn magnitudes(f: &Forces, moment_unit: &str) -> Vec<forces::Magnitude> {
    let row = forces::Magnitude::new;
    let mut rows: Vec<forces::Magnitude> = [
        ("RAn", f.r_a_n),
        ("RAt", f.r_a_t),
        ("RCn", f.r_c_n),
        ("RCt", f.r_c_t),
        ("RA", f.r_a),
        ("RB", f.r_b),
        ("RC", f.r_c),
        ("RO", f.r_o),
    ]
    .iter()
    .map(|(n, v)| row(n, v.norm(), "N"))
    .collect();
    rows.push(row("Me1", f.me1, moment_unit));
    rows
}

/// The link loads acting at `pos` where they act: `F1` on the crank, `F2` on the coupler,
/// `F3` on the rocker (their sums are the force polygons' F1, F and F3).
fn link_loads_on_mechanism(geom: &Geometry, pos: &Position, loads: &[LinkLoad]) -> Vec<(Point, NamedVector)> {
    let phi1_deg = pos.phi1.to_degrees();
    loads
        .iter()
        .filter(|l| l.force != Vector::zeros() && l.range.is_none_or(|r| r.contains_deg(phi1_deg)))
        .map(|l| {
            let (p, _) = l.link.ends(geom, pos);
            let name = match l.link {
                Link::Crank => "F1",
                Link::Ab | Link::Bm => "F2",
                Link::Rocker => "F3",
            };
            (p + l.link.to_world(geom, pos, l.at), NamedVector::new(name, l.force))
        })
        .collect()
}

/// The forces drawn on the mechanism (seed, last section; design.md §4's conventions): R_A
/// at A (of the crank on the coupler), R_B at B (of the rocker on the coupler), R_C at C (of
/// the ground on the rocker), R_O at O1 (of the ground on the crank), and each external
/// force where it acts when it acts (`F`; `F1`, `F2` … when there are several).
fn on_mechanism(geom: &Geometry, pos: &Position, f: &Forces, external: &[ExternalForce]) -> Vec<(Point, NamedVector)> {
    let mut out = vec![
        (pos.a, NamedVector::new("RA", f.r_a)),
        (pos.b, NamedVector::new("RB", f.r_b)),
        (geom.c, NamedVector::new("RC", f.r_c)),
        (geom.o1, NamedVector::new("RO", f.r_o)),
    ];
    let phi1_deg = pos.phi1.to_degrees();
    for (i, e) in external.iter().enumerate() {
        if e.range.is_none_or(|r| r.contains_deg(phi1_deg)) {
            let name = if external.len() == 1 { "F".to_string() } else { format!("F{}", i + 1) };
            out.push((e.at.at(pos), NamedVector::new(&name, e.value)));
        }
    }
    out
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::draw::HAlign;
    use crate::geom::{cross, polar};

    /// The template's Chebyshev four-bar (design.md §3).
    pub(crate) fn chebyshev() -> Geometry {
        crate::solve::fourbar::test_template()
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
            omega1,
            eps1: 0.0,
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
        let frames = [0usize, 90, 180].iter().map(|&i| lay.frame(&base, &lay.moving(i, &g, &pos[i], None))).collect();
        (lay, frames)
    }

    #[test]
    fn polygons_are_drawn_at_their_scale_beside_the_mechanism() {
        let show = Show { velocity: true, acceleration: true, forces: false, ..Show::default() };
        let (lay, frames) = run(show);
        let g = chebyshev();
        let p = closed_form(&g, 0.0, 20.0);
        let k = p.kin.unwrap();
        let (sv, pole) = lay.frame.velocity.as_ref().unwrap().place(
            0,
            Extent::of(velocity_polygon(&k).physical_points()),
            lay.frame.k_l,
        );
        // v_A = ω1·l1 = 0.8 m/s; its arrow is 0.8 / k_v paper mm long = 0.8 / k_v · k_l m.
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
        assert!((pa.norm() - 0.8 / sv.per_mm * lay.frame.k_l).abs() < 1e-12, "{} {}", pa.norm(), sv.per_mm);
        // k_l is nice, prints in the mechanism's title (on paper; 1:1, in m/mm, in the DXF's
        // millimetres), and the drawing is on its paper.
        assert_eq!(lay.frame.panels[0].0.on_paper(), format!("Mechanism   k_l = {} m/mm", scale_text(lay.frame.k_l)));
        assert_eq!(lay.frame.panels[0].0.text(1000.0), "Mechanism   k_l = 0.001 m/mm");
        assert_eq!(d.paper_mm_per_unit, Some(1.0 / lay.frame.k_l));
        // Letters are 3.5 mm on paper.
        assert!((lay.frame.sizes.text / lay.frame.k_l - 3.5).abs() < 1e-12);
        assert!((pa.normalize() - k.v_a.normalize()).norm() < 1e-12);
        // Panels do not overlap the mechanism panel.
        let mech = &lay.frame.panels[0];
        for p in &lay.frame.panels[1..] {
            let disjoint = p.1.x >= mech.2.x || p.2.x <= mech.1.x || p.1.y >= mech.2.y || p.2.y <= mech.1.y;
            assert!(disjoint, "{p:?} overlaps {mech:?}");
        }
        // The scale is nice and the largest polygon is about as large as the mechanism.
        let m = sv.per_mm / libm::pow(10f64, libm::log10(sv.per_mm).floor());
        assert!([1.0, 2.0, 2.5, 5.0].iter().any(|n| (m - n).abs() < 1e-9), "{}", sv.per_mm);
        // Every frame lies inside the shared window.
        for f in &frames {
            let b = f.bounds().unwrap();
            let w = lay.frame.window;
            let slack = 0.02 * w.width();
            assert!(b.min.x >= w.min.x - slack && b.max.x <= w.max.x + slack && b.min.y >= w.min.y - slack);
            assert!(b.max.y <= w.max.y + slack, "{b:?} vs {w:?}");
        }
    }

    #[test]
    fn positions_only_draws_no_polygon() {
        let (lay, frames) = run(Show::default());
        assert!(lay.frame.velocity.is_none() && lay.frame.acceleration.is_none() && lay.frame.panels.len() == 1);
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
        let show = Show { velocity: true, acceleration: true, forces: true, ..Show::default() };
        let lay = Layout::new(&scene.spec.geometry, &motion.positions, Some(&motion.forces), show, ModelUnits::SI);
        (scene.spec.geometry, motion, lay)
    }

    /// The letters of each polygon in a drawn position: (polygon, centre, text, height),
    /// polygon 0 velocity, 1 acceleration, 2 force (the force panel's texts only).
    fn polygon_letters(lay: &Layout, d: &Drawing) -> Vec<(usize, Point, String, f64, crate::draw::Runs)> {
        let force_panel = lay.frame.panels.iter().find(|p| p.0.on_paper().starts_with("Force")).cloned();
        let (vel, acc, frc) =
            (layer_of(d, layers::VELOCITY), layer_of(d, layers::ACCELERATION), layer_of(d, layers::FORCES));
        d.entities
            .iter()
            .filter_map(|e| match &e.shape {
                // Letters and names are centred on their place (the table's texts are not).
                Shape::Text { at, height, value, runs, halign: HAlign::Center, .. } => {
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
                    Some((poly, *at, value.clone(), *height, runs.clone()))
                }
                _ => None,
            })
            .collect()
    }

    #[test]
    fn polygon_letters_never_overlap_over_the_template_motion() {
        use crate::figure::shared::labels::TextBox;
        let (g, motion, lay) = template_motion();
        assert_eq!(motion.positions.len(), 360);
        let mut overlaps = [0usize; 3];
        let mut examples = Vec::new();
        let mut first_bad = None;
        for (i, pos) in motion.positions.iter().enumerate() {
            let d = lay.moving(i, &g, pos, Some(&motion.forces[i]));
            let letters = polygon_letters(&lay, &d);
            for (j, a) in letters.iter().enumerate() {
                for b in &letters[..j] {
                    let (ba, bb) =
                        (TextBox::centred_runs(a.1, &a.2, &a.4, a.3), TextBox::centred_runs(b.1, &b.2, &b.4, b.3));
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
            let f = lay.frame(&base, &lay.moving(deg, &g, &motion.positions[deg], Some(&motion.forces[deg])));
            let opts = crate::draw::svg::SvgOptions { window: Some(lay.frame.window), ..Default::default() };
            let png = crate::draw::raster::to_png(&crate::draw::svg::to_string(&f, &opts), 1400).unwrap();
            let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target");
            std::fs::write(dir.join("labels-overlap.png"), png).unwrap();
        }
        assert_eq!(overlaps, [0, 0, 0], "{examples:?}");
    }

    #[test]
    fn polygon_letters_stay_near_their_points_over_the_template_motion() {
        use crate::figure::shared::labels::{COINCIDENT, SAME_POINT, max_distance, max_leader_distance};
        let (g, motion, lay) = template_motion();
        let force_panel = lay.frame.panels.iter().find(|p| p.0.on_paper().starts_with("Force")).cloned().unwrap();
        let mut checked = 0;
        for (i, pos) in motion.positions.iter().enumerate() {
            let k = pos.kin.unwrap();
            let k_l = lay.frame.k_l;
            let (sv, pv) =
                lay.frame.velocity.as_ref().unwrap().place(i, Extent::of(velocity_polygon(&k).physical_points()), k_l);
            let acc = acceleration_polygon(pos, g.c, &k);
            let (sa, pa) = lay.frame.acceleration.as_ref().unwrap().place(i, Extent::of(acc.physical_points()), k_l);
            let d = lay.moving(i, &g, pos, Some(&motion.forces[i]));
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
            for (poly, at, text, h, runs) in polygon_letters(&lay, &d) {
                // Force names and the centroids' letters may go further out, with a leader.
                let leader = poly == 2 || text.starts_with('c') || text.starts_with('n');
                let reach = if leader { max_leader_distance(&text, &runs, h) } else { max_distance(&text, &runs, h) }
                    + COINCIDENT * h
                    + 1e-9 * h;
                for name in text.split(SAME_POINT) {
                    let dist = match (poly, name) {
                        (0, "p") => (at - pv).norm(),
                        (0, "a") => (at - (pv + sv.draw(k.v_a))).norm(),
                        (0, "b") => (at - (pv + sv.draw(k.v_b))).norm(),
                        (0, "m") => (at - (pv + sv.draw(k.v_m))).norm(),
                        (1, "π") => (at - pa).norm(),
                        (1, "a′") => (at - (pa + sa.draw(k.a_a))).norm(),
                        (1, "b′") => (at - (pa + sa.draw(k.a_b))).norm(),
                        (1, "m′") => (at - (pa + sa.draw(k.a_m))).norm(),
                        (1, "nBA") => (at - (pa + sa.draw(k.a_a + k.a_ba_n))).norm(),
                        (1, "nBC") => (at - (pa + sa.draw(k.a_bc_n))).norm(),
                        (1, "c1′") => (at - (pa + sa.draw(k.a_g1))).norm(),
                        (1, "c21′") => (at - (pa + sa.draw(k.a_g21))).norm(),
                        (1, "c22′") => (at - (pa + sa.draw(k.a_g22))).norm(),
                        (1, "c3′") => (at - (pa + sa.draw(k.a_g3))).norm(),
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
            f1_ext: Vector::zeros(),
            f3_ext: Vector::zeros(),
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
            let poly = dyad_polygon(&f);
            let v = poly.vertices();
            let scale = f.r_a.norm().max(1.0);
            assert!(v[11].norm() < 1e-12 * scale, "chain does not close at {deg}°");
            // R_A drawn from int to the end of R_A^n; R_B from the end of F to int; R_C from
            // the end of F_i3 to int.
            for (name, reaction) in [("RA", f.r_a), ("RB", f.r_b), ("RC", f.r_c)] {
                assert!((poly.resultant(name).unwrap() - reaction).norm() < 1e-12 * scale, "{name} at {deg}°");
            }
            // The crank's polygon closes with R_O.
            let crank = crank_polygon(&f);
            assert!((crank.resultant("RO").unwrap() - f.r_o).norm() < 1e-12 * scale, "R_O at {deg}°");
        }
    }
}
