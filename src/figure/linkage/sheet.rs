//! Any linkage on printed sheets (issue 15 §3): one page per position with the mechanism
//! (its traced paths, at one k_l for the run), the velocity polygon, the acceleration
//! polygon and the force polygons (one per body), each in its own panel
//! ([`crate::figure::shared::sheet`]), drawn by the same code as the four-bar's sheets
//! ([`crate::figure::shared::sheet_polygons`]: each polygon at its own nice scale on each page) and the
//! linkage's frames ([`crate::figure::linkage::mechanism`], [`crate::figure::linkage::polygon`],
//! [`crate::figure::linkage::forces`]), in paper millimetres.

use crate::draw::Drawing;
use crate::geom::{Point, Vector};
use crate::solve::linkage::{Attach, Dynamics, Forces, Mechanism, State, place};

use crate::figure::linkage::forces::ForceFigures;
use crate::figure::linkage::frame::{Show, time_text};
use crate::figure::linkage::polygon::polygons_of;
use crate::figure::linkage::{self as fig, LinkageFigure};
use crate::figure::shared::sheet::{self, Fit, Paper, SheetLayout, Table, TitleBlock};
use crate::figure::shared::sheet_polygons::{self, PageFit, PagePolygons, PageScales, Shown};
use crate::figure::shared::vocab::{layer_of, layers};

/// What every page of a run shares: the layout, the mechanism's scale and placement, the
/// figure and the traced paths on paper.
#[derive(Debug, Clone)]
pub struct LinkageSheets {
    /// Where everything goes.
    pub layout: SheetLayout,
    /// What is drawn.
    pub show: Show,
    /// k_l: model length units per paper millimetre.
    pub k_l: f64,
    /// The scene's name, for the title block.
    pub name: String,
    /// The paper point of the model's origin.
    origin: Point,
    /// The figure on paper.
    paper_figure: LinkageFigure,
    /// The traced paths, on paper.
    paths: Drawing,
    /// The ground guides' spans on paper.
    spans: Vec<Option<(Point, Point)>>,
    /// The force figures drawn.
    figures: ForceFigures,
}

impl LinkageSheets {
    /// The sheets of a run over `states` on `paper`; `show` as the frames' (the force panel
    /// only when `forces`).
    pub fn new(
        paper: Paper,
        name: &str,
        mech: &Mechanism,
        figure: &LinkageFigure,
        states: &[State],
        show: Show,
        forces: bool,
    ) -> LinkageSheets {
        let show = Show { forces: show.forces && forces, ..show };
        let shown = shown(&show);
        // Title cells: t, k_l, a scale per polygon, the sheet number.
        let layout = SheetLayout::new(paper, 1 + shown.count(), 3 + shown.count());
        let s = layout.sizes;
        let motion: Vec<&[f64]> = states.iter().map(|st| st.q.as_slice()).collect();
        let pts = motion.iter().flat_map(|q| {
            figure
                .bodies
                .iter()
                .enumerate()
                .flat_map(move |(i, b)| b.points.iter().map(move |(_, v)| place(q, Attach::Body(i), *v).coords))
        });
        let (lo, hi) = pts
            .filter(|v| v.x.is_finite() && v.y.is_finite())
            .fold(None, |e: Option<(Vector, Vector)>, v| Some(e.map_or((v, v), |(lo, hi)| (lo.inf(&v), hi.sup(&v)))))
            .unwrap_or((Vector::zeros(), Vector::new(1.0, 1.0)));
        // Room for the letters and the ground symbols and guides around the links.
        let area = layout.panels[0].area;
        let room = Vector::new(3.0 * s.text + 2.0 * s.slider_length, 3.0 * s.text + 2.0 * s.ground);
        let Fit { per_mm: k_l, .. } = sheet::finest(hi - lo, Vector::new(area.width(), area.height()) - room);
        let origin = sheet::centre(lo, hi, k_l, area) + Vector::new(0.0, s.ground);
        let paper_figure = figure.on_paper(origin, k_l);
        let paper_motion: Vec<Vec<f64>> = motion.iter().map(|q| fig::on_paper(q, origin, k_l)).collect();
        let paper_refs: Vec<&[f64]> = paper_motion.iter().map(Vec::as_slice).collect();
        let spans = fig::guide_spans(&paper_figure, &paper_refs, &s);
        let mut paths = Drawing::new(crate::draw::DimStyle { text_height: s.text, arrow_size: s.head });
        let tl = fig::trajectory_layer(&mut paths);
        fig::trajectories(&mut paths, tl, &paper_figure, &paper_refs);
        let figures = ForceFigures::new(mech, show.per_body);
        LinkageSheets { layout, show, k_l, name: name.to_string(), origin, paper_figure, paths, spans, figures }
    }

    /// The page of one position: `table` its values, `sheet` its number (from 1) and the
    /// number of pages. Returns the drawing (paper mm, [`Drawing::paper_mm_per_unit`] 1)
    /// and the page's scales.
    pub fn page(
        &self,
        mech: &Mechanism,
        state: &State,
        force: Option<(&Dynamics, &Forces)>,
        table: &Table,
        sheet: (usize, usize),
    ) -> (Drawing, PageScales) {
        let shown = shown(&self.show);
        let polys =
            (shown.velocity || shown.acceleration).then(|| polygons_of(mech, state, self.show.points.as_deref()));
        let figures: Option<Vec<_>> =
            force.filter(|_| shown.forces).map(|(dynamics, f)| self.figures.polygons(mech, dynamics, state, f));
        let page_polys = PagePolygons {
            velocity: polys.as_ref().filter(|_| shown.velocity).map(|p| &p.velocity),
            acceleration: polys.as_ref().filter(|_| shown.acceleration).map(|p| &p.acceleration),
            forces: figures.as_deref(),
        };
        let fit = PageFit::new(&self.layout, shown, page_polys);
        let scales = fit.scales(self.k_l);
        let (titles, cells) = sheet_polygons::titles(&scales, shown, self.paper_figure.units);
        let title = TitleBlock {
            name: self.name.clone(),
            subject: "linkage".to_string(),
            position: time_text(state.t),
            cells,
            sheet,
        };
        let mut d = sheet::page(&self.layout, &title, table, &titles);
        let s = self.layout.sizes;
        d.append(&self.paths);
        let q = fig::on_paper(&state.q, self.origin, self.k_l);
        let mech_layer = layer_of(&d, layers::MECHANISM);
        fig::mechanism(&mut d, mech_layer, &self.paper_figure, &q, &self.spans, &s);
        fit.draw(&mut d, page_polys, s);
        sheet_polygons::scale_bars(&mut d, &self.layout, &scales, shown, self.paper_figure.units);
        (d, scales)
    }
}

fn shown(show: &Show) -> Shown {
    Shown { velocity: show.velocity, acceleration: show.acceleration, forces: show.forces }
}
