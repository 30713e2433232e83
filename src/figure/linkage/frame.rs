//! The graph-analytical frame of any linkage (issue 15 §2, §3): the mechanism with the
//! paths of its traced points in the first panel and, through the shared
//! [`PanelFrame`] (the four-bar's frames are drawn by the same code), its velocity polygon
//! and acceleration polygon ([`crate::figure::linkage::polygon`]: Coriolis components at moving
//! guides), and with forces one force polygon per moving body
//! ([`crate::figure::linkage::forces`]), the table of magnitudes, and the reactions and loads drawn
//! on the mechanism at the force scale.
//!
//! Scales are fixed for the run (chosen from every position), so that the animation does
//! not jump; each is printed in its panel's title and drawn as a scale bar.

use crate::draw::Drawing;
use crate::geom::{Point, Vector};
use crate::solve::linkage::{Attach, Dynamics, Forces, Mechanism, State, place};

use crate::figure::linkage::forces::{ForceFigures, magnitudes, on_mechanism};
use crate::figure::linkage::polygon::{LinkagePolygons, polygons_of};
use crate::figure::linkage::{self as fig, LinkageFigure};
use crate::figure::shared::forces::{self, ForcePolygon};
use crate::figure::shared::labels::{Around, TextBox};
use crate::figure::shared::panels::{Extent, ForceSpec, PanelFrame, PanelSpec, ScaleChoice};
use crate::figure::shared::vocab::{layer_of, layers};

/// Largest extent of the mechanism's motion on paper, millimetres: the mechanism the largest
/// figure of the frame (a linkage's motion is long: the shaper's 950 mm at 1:5).
pub const MECHANISM_MM: f64 = 200.0;
/// The size of a polygon's panel on paper, millimetres.
pub const POLYGON_MM: f64 = 120.0;

/// What a linkage frame shows beside its mechanism (the scene's `[polygons]` table).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Show {
    /// The velocity polygon.
    pub velocity: bool,
    /// The acceleration polygon.
    pub acceleration: bool,
    /// The force polygons, the table and the forces on the mechanism (with dynamics).
    pub forces: bool,
    /// The points the polygons show, by name (`None`: every joint point).
    pub points: Option<Vec<String>>,
    /// One force figure per moving body instead of one per Assur group.
    pub per_body: bool,
    /// How the frames' polygon scales are chosen (the scene's `[frames] scales`).
    pub scales: ScaleChoice,
}

impl Default for Show {
    fn default() -> Show {
        Show {
            velocity: true,
            acceleration: true,
            forces: true,
            points: None,
            per_body: false,
            scales: ScaleChoice::default(),
        }
    }
}

/// The forces of a run: the dynamics and the forces at each state.
#[derive(Debug, Clone, Copy)]
pub struct RunForces<'a> {
    /// Masses, gravity, loads.
    pub dynamics: &'a Dynamics,
    /// One per state.
    pub forces: &'a [Forces],
}

/// The frames of one run: the panels and scales, the guides' spans, what is shown.
#[derive(Debug, Clone)]
pub struct LinkageFrames {
    /// Panels, scales, poles.
    pub frame: PanelFrame,
    /// What is drawn.
    pub show: Show,
    /// Each ground guide's drawn span ([`fig::guide_spans`]).
    pub spans: Vec<Option<(Point, Point)>>,
    /// N·m to the moment unit of the table (1000 in a mm scene).
    moment_per_nm: f64,
    /// The force figures drawn.
    figures: ForceFigures,
    /// What every frame shares (for the letters of each to keep off), once drawn.
    backdrop: Option<Drawing>,
}

/// Every body point and guide end over the motion.
fn mechanism_extent(fig: &LinkageFigure, motion: &[&[f64]], spans: &[Option<(Point, Point)>]) -> Option<Extent> {
    let points = motion.iter().flat_map(|q| {
        fig.bodies
            .iter()
            .enumerate()
            .flat_map(move |(i, b)| b.points.iter().map(move |(_, v)| place(q, Attach::Body(i), *v).coords))
    });
    let ends = spans.iter().flatten().flat_map(|(a, b)| [a.coords, b.coords]);
    Extent::of(points.chain(ends))
}

/// The position's text: `t = 0.2500 s`.
pub fn time_text(t: f64) -> String {
    format!("t = {t:.4} s")
}

impl LinkageFrames {
    /// The frames of a run over `states` (with `forces` when the scene has dynamics).
    pub fn new(
        fig: &LinkageFigure,
        mech: &Mechanism,
        states: &[State],
        forces: Option<RunForces>,
        show: Show,
    ) -> LinkageFrames {
        let units = fig.units;
        let motion: Vec<&[f64]> = states.iter().map(|s| s.q.as_slice()).collect();
        // Guides' spans at the provisional style (the slider's length only pads them).
        let provisional = fig::paper_style(fig, &motion);
        let spans = fig::guide_spans(fig, &motion, &provisional);
        let mechanism = mechanism_extent(fig, &motion, &spans)
            .unwrap_or(Extent { min: Vector::zeros(), max: Vector::new(1.0, 1.0) });
        let only = show.points.as_deref();
        let polys: Vec<LinkagePolygons> = if show.velocity || show.acceleration {
            states.iter().map(|s| polygons_of(mech, s, only)).collect()
        } else {
            Vec::new()
        };
        let velocity = show.velocity.then(|| polys.iter().map(|p| Extent::of(p.velocity.physical_points())).collect());
        let acceleration =
            show.acceleration.then(|| polys.iter().map(|p| Extent::of(p.acceleration.physical_points())).collect());
        let moment_unit = format!("N·{}", units.length);
        let moment_per_nm = 1000.0 / units.mm_per_unit;
        let force_figures = ForceFigures::new(mech, show.per_body);
        let force_spec = forces.filter(|_| show.forces).map(|rf| {
            let polygons: Vec<Vec<ForcePolygon>> =
                states.iter().zip(rf.forces).map(|(s, f)| force_figures.polygons(mech, rf.dynamics, s, f)).collect();
            let figures = force_figures
                .captions(mech)
                .into_iter()
                .enumerate()
                .map(|(i, caption)| (caption, polygons.iter().map(|p| Extent::of(p[i].physical_points())).collect()))
                .collect();
            let rows: Vec<_> =
                rf.forces.iter().flat_map(|f| magnitudes(mech, f, &moment_unit, moment_per_nm)).collect();
            let row_count = rf.forces.first().map_or(0, |f| magnitudes(mech, f, &moment_unit, moment_per_nm).len());
            let on_mech = states
                .iter()
                .zip(rf.forces)
                .flat_map(|(s, f)| on_mechanism(mech, rf.dynamics, s, f).into_iter().map(|(at, nv)| (at, nv.v)))
                .collect();
            ForceSpec { figures, rows, row_count, on_mechanism: on_mech }
        });
        let position_text = states.iter().map(|s| time_text(s.t)).max_by_key(|t| t.chars().count()).unwrap_or_default();
        let frame = PanelFrame::new(&PanelSpec {
            units,
            mechanism,
            size: mechanism.size(),
            mechanism_mm: MECHANISM_MM,
            polygon_mm: Some(POLYGON_MM),
            pad: |s| (3.5 * s.joint + 1.6 * s.text, 2.0 * s.joint),
            position_text,
            velocity,
            acceleration,
            forces: force_spec,
            scales: show.scales,
        });
        let spans = fig::guide_spans(fig, &motion, &frame.sizes);
        let show = Show {
            velocity: frame.velocity.is_some(),
            acceleration: frame.acceleration.is_some(),
            forces: frame.forces.is_some(),
            ..show
        };
        let mut out = LinkageFrames { frame, show, spans, moment_per_nm, figures: force_figures, backdrop: None };
        let motion: Vec<&[f64]> = states.iter().map(|s| s.q.as_slice()).collect();
        out.backdrop = Some(out.base(fig, &motion));
        out
    }

    /// What every frame shares: the traced points' paths, the panels' titles with their
    /// scales, the scale bars, the force figures' captions.
    pub fn base(&self, fig: &LinkageFigure, motion: &[&[f64]]) -> Drawing {
        let mut d = self.frame.paper_drawing();
        let tl = fig::trajectory_layer(&mut d);
        fig::trajectories(&mut d, tl, fig, motion);
        self.frame.draw_titles(&mut d);
        d
    }

    /// One position: the time, the mechanism (with the reactions and the acting loads when
    /// forces are shown), the polygons, the force figures and the table.
    pub fn moving(
        &self,
        k: usize,
        fig: &LinkageFigure,
        mech: &Mechanism,
        state: &State,
        force: Option<(&Dynamics, &Forces)>,
    ) -> Drawing {
        let mut d = self.frame.paper_drawing();
        let s = self.frame.sizes;
        self.frame.draw_position_text(&mut d, time_text(state.t));
        let force = force.filter(|_| self.show.forces);
        let arrows = match (force, self.frame.mechanism_forces) {
            (Some((dynamics, f)), Some(scale)) => {
                let links = links_of(fig, &state.q);
                let pts: Vec<Point> = links.iter().flat_map(|(a, b)| [*a, *b]).collect();
                let inside = Point::from(pts.iter().map(|p| p.coords).sum::<Vector>() / pts.len().max(1) as f64);
                forces::arrows_on_mechanism(&on_mechanism(mech, dynamics, state, f), scale, &links, inside, s)
            }
            _ => Vec::new(),
        };
        forces::draw_on_mechanism(&mut d, &arrows, s);
        let layer = layer_of(&d, layers::MECHANISM);
        let (ll, ur) = self.frame.mechanism_panel();
        let around = Around { backdrop: self.backdrop.as_ref(), within: Some(TextBox { min: ll, max: ur }) };
        let omega = fig.crank.map(|(b, _)| state.angular(Attach::Body(b)).1);
        fig::mechanism_with_forces(&mut d, layer, fig, &state.q, &self.spans, &arrows, omega, &s, around);
        let polys = (self.show.velocity || self.show.acceleration)
            .then(|| polygons_of(mech, state, self.show.points.as_deref()));
        let moment_unit = format!("N·{}", self.frame.units.length);
        let figures: Option<(Vec<ForcePolygon>, _)> = force.map(|(dynamics, f)| {
            let polys = self.figures.polygons(mech, dynamics, state, f);
            (polys, magnitudes(mech, f, &moment_unit, self.moment_per_nm))
        });
        let figures = figures.as_ref().map(|(p, m)| (&p[..], &m[..]));
        let vel = polys.as_ref().filter(|_| self.show.velocity).map(|p| &p.velocity);
        let acc = polys.as_ref().filter(|_| self.show.acceleration).map(|p| &p.acceleration);
        self.frame.draw_polygons(&mut d, k, vel, acc, figures);
        d
    }
}

/// The bodies' outlines as segments at `q`, for force arrows to keep off.
pub(crate) fn links_of(fig: &LinkageFigure, q: &[f64]) -> Vec<(Point, Point)> {
    let mut out = Vec::new();
    for (i, b) in fig.bodies.iter().enumerate() {
        let pts: Vec<Point> = b.points.iter().map(|(_, v)| place(q, Attach::Body(i), *v)).collect();
        let n = pts.len();
        let sides = if n >= 3 { n } else { n.saturating_sub(1) };
        for k in 0..sides {
            out.push((pts[k], pts[(k + 1) % n]));
        }
    }
    out
}
