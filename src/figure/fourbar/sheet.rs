//! The four-bar on printed sheets (issue 14, item 3): one page per position with the
//! mechanism, the velocity polygon, the acceleration polygon and the force polygons, each
//! in its own panel ([`crate::figure::shared::sheet`]), drawn by the same functions as the animation
//! (`figure::fourbar::mechanism`, [`crate::figure::shared::polygon::draw`], [`crate::figure::shared::forces::draw`] on the
//! four-bar's adapters), in paper millimetres.
//!
//! Scales: the mechanism has one k_l for the whole run (a nice value at which the whole
//! motion, the coupler curve included, fits its panel), so that pages compare; each polygon
//! gets its own nice scale on each page ([`crate::figure::shared::sheet::fit`]: it fills about two thirds of
//! its panel, at least half), unlike the animation, whose polygons keep the run's fixed
//! scales. Every scale is printed in its panel's title and in the title block.

use crate::draw::Drawing;
use crate::geom::{Point, Vector, deg};
use crate::solve::fourbar::{Forces, Geometry, Position};

use crate::figure::fourbar::{
    Show, acceleration_polygon, angle_text, crank_polygon, dyad_polygon, mechanism, velocity_polygon,
};
use crate::figure::shared::sheet::{self, Fit, Paper, SheetLayout, Table, TitleBlock};
pub use crate::figure::shared::sheet_polygons::PageScales;
use crate::figure::shared::sheet_polygons::{self, PageFit, PagePolygons, Shown};
use crate::figure::shared::vocab::{ModelUnits, ground, layer_of, layers, path};

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
        let kin = pos.kin.as_ref();
        let velocity = kin.map(velocity_polygon);
        let acceleration = kin.map(|k| acceleration_polygon(pos, geom.c, k));
        let figures = force.map(|f| [dyad_polygon(f), crank_polygon(f)]);
        let polys = PagePolygons {
            velocity: velocity.as_ref(),
            acceleration: acceleration.as_ref(),
            forces: figures.as_ref().map(|f| &f[..]),
        };
        let shown =
            Shown { velocity: self.show.velocity, acceleration: self.show.acceleration, forces: self.show.forces };
        let fit = PageFit::new(&self.layout, shown, polys);
        let scales = fit.scales(self.k_l);
        let (titles, scale_cells) = sheet_polygons::titles(&scales, shown, self.units);
        let mut cells = vec![format!("ω1 = {} rad/s", angle_text(self.omega1))];
        cells.extend(scale_cells);
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

        // Each polygon at its own scale, centred in its panel, and the scale bars.
        fit.draw(&mut d, polys, s);
        sheet_polygons::scale_bars(&mut d, &self.layout, &scales, shown, self.units);
        (d, scales)
    }
}
