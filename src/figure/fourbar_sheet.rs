//! The four-bar on printed sheets (issue 14, item 3): one page per position with the
//! mechanism, the velocity polygon, the acceleration polygon and the force polygons, each
//! in its own panel ([`super::sheet`]), drawn by the same functions as the animation
//! (`figure::fourbar::mechanism`, [`super::polygon::draw`], [`super::forces::draw`] on the
//! four-bar's adapters), in paper millimetres.
//!
//! Scales: the mechanism has one k_l for the whole run (a nice value at which the whole
//! motion, the coupler curve included, fits its panel), so that pages compare; each polygon
//! gets its own nice scale on each page ([`super::sheet::fit`]: it fills about two thirds of
//! its panel, at least half), unlike the animation, whose polygons keep the run's fixed
//! scales. Every scale is printed in its panel's title and in the title block.

use crate::draw::Drawing;
use crate::geom::{Point, Vector, deg};
use crate::solve::fourbar::{Forces, Geometry, Position};

use super::fourbar::{
    Show, acceleration_polygon, angle_text, crank_polygon, dyad_polygon, mechanism, velocity_polygon,
};
use super::sheet::{self, Fit, Paper, SheetLayout, Table, TitleBlock};
use super::vocab::{ModelUnits, Scale, bar_value, ground, layer_of, layers, path, scale_bar, scale_text};
use super::{forces, polygon};

/// Gap between the dyad's force polygon and the crank's on a sheet, in the larger polygon's
/// extents.
const FIGURE_GAP: f64 = 0.15;

/// The scales of one page: physical units per paper millimetre (`None`: not drawn).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PageScales {
    /// k_l, model length units per paper mm (the same on every page of a run).
    pub k_l: f64,
    /// k_v, (length unit/s) per mm.
    pub k_v: Option<f64>,
    /// k_a, (length unit/s²) per mm.
    pub k_a: Option<f64>,
    /// k_f, N per mm.
    pub k_f: Option<f64>,
}

/// What every page of a run shares: the layout, the mechanism's scale and placement, the
/// coupler curve on paper.
#[derive(Debug, Clone)]
pub struct FourbarSheets {
    /// Where everything goes.
    pub layout: SheetLayout,
    /// The polygons drawn (their panels follow the mechanism's in this order).
    pub show: Show,
    /// The model's units.
    pub units: ModelUnits,
    /// k_l: model length units per paper millimetre.
    pub k_l: f64,
    /// The scene's name, for the title block.
    pub name: String,
    /// ω1, rad/s, for the title block.
    pub omega1: f64,
    /// The paper point of the model's origin.
    origin: Point,
    /// The coupler curve on paper.
    curve: Vec<Vec<Point>>,
}

/// The smallest box holding the finite vectors of `vs`.
fn extent(vs: impl IntoIterator<Item = Vector>) -> Option<(Vector, Vector)> {
    vs.into_iter()
        .filter(|v| v.x.is_finite() && v.y.is_finite())
        .fold(None, |e, v| Some(e.map_or((v, v), |(lo, hi): (Vector, Vector)| (lo.inf(&v), hi.sup(&v)))))
}

impl FourbarSheets {
    /// The sheets of a run on `paper`: `positions` the assembled positions, `curve` the
    /// coupler curve (runs of points, model units), `show` the polygons asked for.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        paper: Paper,
        name: &str,
        omega1: f64,
        geom: &Geometry,
        positions: &[Position],
        curve: &[Vec<Point>],
        show: Show,
        units: ModelUnits,
    ) -> FourbarSheets {
        let panels = 1 + [show.velocity, show.acceleration, show.forces].iter().filter(|s| **s).count();
        // Title cells: φ1, ω1, k_l, a scale per polygon, the sheet number.
        let layout = SheetLayout::new(paper, panels, 3 + panels);
        let s = layout.sizes;
        let pts = positions.iter().flat_map(|p| [p.a.coords, p.b.coords, p.m.coords]);
        let (lo, hi) =
            extent(pts.chain([geom.o1.coords, geom.c.coords]).chain(curve.iter().flatten().map(|p| p.coords)))
                .unwrap_or((Vector::zeros(), Vector::new(1.0, 1.0)));
        // Room for the letters around the links and the ground symbols under the pivots.
        let area = layout.panels[0].area;
        let room = Vector::new(3.0 * s.text, 3.0 * s.text + 2.0 * s.ground);
        let Fit { per_mm: k_l, .. } = sheet::finest(hi - lo, Vector::new(area.width(), area.height()) - room);
        let origin = sheet::centre(lo, hi, k_l, area) + Vector::new(0.0, s.ground);
        let to_paper = |p: &Point| origin + p.coords / k_l;
        let curve = curve.iter().map(|run| run.iter().map(to_paper).collect()).collect();
        FourbarSheets { layout, show, units, k_l, name: name.to_string(), omega1, origin, curve }
    }

    /// A model point on paper.
    fn paper(&self, p: Point) -> Point {
        self.origin + p.coords / self.k_l
    }

    /// The page of one position: `table` its values, `sheet` its number (from 1) and the
    /// number of pages. Returns the drawing (paper mm, [`Drawing::paper_mm_per_unit`] 1)
    /// and the page's scales.
    pub fn page(
        &self,
        geom: &Geometry,
        pos: &Position,
        force: Option<&Forces>,
        table: &Table,
        sheet: (usize, usize),
    ) -> (Drawing, PageScales) {
        let len = self.units.length;
        let mut panels = self.layout.panels.iter().skip(1);
        let mut fitted = |on: bool, pts: Option<Vec<Vector>>| -> Option<(Fit, Point)> {
            let panel = if on { panels.next() } else { None }?;
            let (lo, hi) = extent(pts?)?;
            let f = sheet::fit(hi - lo, Vector::new(panel.area.width(), panel.area.height()));
            Some((f, sheet::centre(lo, hi, f.per_mm, panel.area)))
        };
        let kin = pos.kin.as_ref();
        let vel = fitted(self.show.velocity, kin.map(|k| velocity_polygon(k).physical_points()));
        let acc = fitted(self.show.acceleration, kin.map(|k| acceleration_polygon(pos, geom.c, k).physical_points()));
        // The dyad's polygon (Fig. 4) and the crank's (Fig. 5) side by side at one scale: the
        // crank's shifted right of the dyad's by `crank_shift` (physical units).
        let crank_shift = force.and_then(|f| {
            let (lo_d, hi_d) = extent(dyad_polygon(f).physical_points())?;
            let (lo_c, hi_c) = extent(crank_polygon(f).physical_points())?;
            let gap = FIGURE_GAP * (hi_d - lo_d).amax().max((hi_c - lo_c).amax());
            Some(Vector::new(hi_d.x - lo_c.x + gap, hi_d.y - hi_c.y))
        });
        let both = force.map(|f| {
            let shift = crank_shift.unwrap_or_else(Vector::zeros);
            let crank = crank_polygon(f).physical_points().into_iter().map(|v| v + shift);
            dyad_polygon(f).physical_points().into_iter().chain(crank).collect()
        });
        let frc = fitted(self.show.forces, both);
        let scales = PageScales {
            k_l: self.k_l,
            k_v: vel.map(|(f, _)| f.per_mm),
            k_a: acc.map(|(f, _)| f.per_mm),
            k_f: frc.map(|(f, _)| f.per_mm),
        };

        let k_texts: Vec<(&str, Option<f64>, String)> = vec![
            ("k_v", scales.k_v, format!("({len}/s)/mm")),
            ("k_a", scales.k_a, format!("({len}/s²)/mm")),
            ("k_f", scales.k_f, "N/mm".to_string()),
        ];
        let shown = [self.show.velocity, self.show.acceleration, self.show.forces];
        let scale_cell = |n: &str, v: Option<f64>, u: &str| match v {
            Some(v) => format!("{n} = {} {u}", scale_text(v)),
            None => format!("{n} –"),
        };
        let k_l_text = format!("k_l = {} {len}/mm", scale_text(self.k_l));
        let mut titles = vec![format!("Mechanism   {k_l_text}")];
        let mut cells = vec![format!("ω1 = {} rad/s", angle_text(self.omega1)), k_l_text.clone()];
        for (((n, v, u), on), title) in
            k_texts.iter().zip(shown).zip(["Velocity polygon", "Acceleration polygon", "Force polygons"])
        {
            if on {
                titles.push(format!("{title}   {}", scale_cell(n, *v, u)));
                cells.push(scale_cell(n, *v, u));
            }
        }
        let title = TitleBlock {
            name: self.name.clone(),
            subject: "four-bar".to_string(),
            position: format!("φ1 = {}°", angle_text(deg(pos.phi1))),
            cells,
            sheet,
        };
        let mut d = sheet::page(&self.layout, &title, table, &titles);
        let s = self.layout.sizes;

        // The mechanism at k_l, with its coupler curve.
        let cc = layer_of(&d, layers::COUPLER_CURVE);
        for run in &self.curve {
            path(&mut d, cc, run.clone());
        }
        let on_paper = Geometry {
            o1: self.paper(geom.o1),
            c: self.paper(geom.c),
            l1: geom.l1 / self.k_l,
            l_ab: geom.l_ab / self.k_l,
            l_bm: geom.l_bm / self.k_l,
            l_bc: geom.l_bc / self.k_l,
            ..*geom
        };
        let mech = layer_of(&d, layers::MECHANISM);
        for p in [on_paper.o1, on_paper.c] {
            ground(&mut d, mech, p, s);
        }
        let p = Position {
            a: self.paper(pos.a),
            b: self.paper(pos.b),
            m: self.paper(pos.m),
            c: on_paper.c,
            kin: None,
            ..*pos
        };
        let _ = mechanism(&mut d, &on_paper, &p, &[], Some(self.omega1), s);

        // Each polygon at its own scale, centred in its panel.
        if let (Some(k), Some((f, pole))) = (kin, vel) {
            polygon::draw(&mut d, &velocity_polygon(k), layers::VELOCITY, Scale::on_paper(f.per_mm, 1.0), pole, s);
        }
        if let (Some(k), Some((f, pole))) = (kin, acc) {
            let poly = acceleration_polygon(pos, geom.c, k);
            polygon::draw(&mut d, &poly, layers::ACCELERATION, Scale::on_paper(f.per_mm, 1.0), pole, s);
        }
        if let (Some(fs), Some((f, pole))) = (force, frc) {
            let scale = Scale::on_paper(f.per_mm, 1.0);
            let names = forces::draw(&mut d, &dyad_polygon(fs), scale, pole, s, &[]);
            let crank_pole = pole + scale.draw(crank_shift.unwrap_or_else(Vector::zeros));
            forces::draw(&mut d, &crank_polygon(fs), scale, crank_pole, s, &names);
        }

        // A scale bar at the foot of every panel: the mechanism's in the scene's length unit,
        // each polygon's at this page's scale.
        let dims = layer_of(&d, layers::DIMENSIONS);
        let mut panels = self.layout.panels.iter();
        let per_mm = [
            (true, Some(self.k_l), len.to_string()),
            (self.show.velocity, scales.k_v, format!("{len}/s")),
            (self.show.acceleration, scales.k_a, format!("{len}/s²")),
            (self.show.forces, scales.k_f, "N".to_string()),
        ];
        for (on, k, unit) in per_mm {
            let panel = if on { panels.next() } else { None };
            if let (Some(panel), Some(k)) = (panel, k) {
                let value = bar_value(k);
                scale_bar(&mut d, dims, panel.bar_at(s), value / k, &format!("{} {unit}", scale_text(value)), s);
            }
        }
        (d, scales)
    }
}
