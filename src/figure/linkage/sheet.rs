//! Any linkage on printed sheets (issue 15 §3, issue 31): per position a set of pages
//! ([`crate::figure::shared::sheet_pages`]) — the mechanism page (the mechanism with its
//! traced paths in the largest panel, at one drafting scale k_l for the run, with the loads
//! and reactions at the page's force scale, and the table of the position's values), the
//! polygons page (the velocity and acceleration polygons, each at its own nice scale), and
//! with forces the forces page (one figure per Assur group, or per body when the scene asks,
//! each at its own k_f, at least 60 mm long) — drawn by the same code as the four-bar's
//! sheets and the linkage's frames, in paper millimetres. The title block states t, and φ1
//! and ω1 of an angular driver. With a forces page, the table of forces (every applied
//! force, every reaction) is on it, and the mechanism page's table holds the kinematics, so
//! that the mechanism is drawn large (crank ≥ 25 mm on A4).

use crate::draw::Drawing;
use crate::geom::{Point, Vector, deg};
use crate::solve::linkage::{Attach, Dynamics, Forces, Mechanism, State, place};

use crate::figure::linkage::detail::Detail;
use crate::figure::linkage::forces::{ForceFigures, on_mechanism};
use crate::figure::linkage::frame::{Show, links_of, time_text};
use crate::figure::linkage::polygon::polygons_of;
use crate::figure::linkage::{self as fig, LinkageFigure};
use crate::figure::shared::labels::{Around, TextBox};
use crate::figure::shared::panels::scale_line;
use crate::figure::shared::sheet::{self, Panel, Paper, Table, TitleBlock};
use crate::figure::shared::sheet_pages::{
    MechanismPage, forces_page, mechanism_bar, mechanism_force_scale, polygons_page,
};
use crate::figure::shared::vocab::{
    self, Scale, bar_value, layer_of, layers, length_scale_text, scale_bar, scale_text,
};
use crate::figure::shared::{clear_forces, forces};

/// The longest force drawn on the mechanism page, as a fraction of the mechanism's drawn size.
pub const MECHANISM_FORCE_FRACTION: f64 = 0.3;

/// What every page set of a run shares: the mechanism page, the figure and the traced
/// paths on paper.
#[derive(Debug, Clone)]
pub struct LinkageSheets {
    /// The paper.
    pub paper: Paper,
    /// The mechanism page (its layout, k_l, the model's origin on paper).
    pub mechanism_page: MechanismPage,
    /// What is drawn.
    pub show: Show,
    /// The scene's name, for the title block.
    pub name: String,
    /// The figure on paper.
    paper_figure: LinkageFigure,
    /// The traced paths, on paper.
    paths: Drawing,
    /// The ground guides' spans on paper.
    spans: Vec<Option<(Point, Point)>>,
    /// The force figures drawn.
    figures: ForceFigures,
    /// The mechanism's drawn size, paper mm.
    drawn_mm: f64,
    /// The crank's detail view, when the crank is drawn shorter than 25 mm.
    detail: Option<Detail>,
    /// The figure in model units (for the detail view).
    figure: LinkageFigure,
    /// The ground guides' spans in model units (for the detail view).
    model_spans: Vec<Option<(Point, Point)>>,
}

impl LinkageSheets {
    /// The sheets of a run over `states` on `paper`; `show` as the frames' (the forces page
    /// only when `forces`); `table_rows` the most rows of a position's table over the run,
    /// kinematics and forces ([`row_counts`]): the forces' rows go on the forces page when
    /// there is one; `held` a drafting scale to draw the mechanism at when it is coarser
    /// than the page's own ([`MechanismPage::held`]: the report's one k_l for the mechanism).
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        paper: Paper,
        name: &str,
        mech: &Mechanism,
        figure: &LinkageFigure,
        states: &[State],
        show: Show,
        forces: bool,
        table_rows: (usize, usize),
        held: Option<f64>,
    ) -> LinkageSheets {
        let show = Show { forces: show.forces && forces, ..show };
        let table_rows = if show.forces { table_rows.0 } else { table_rows.0 + table_rows.1 };
        let s = paper.sizes();
        let motion: Vec<&[f64]> = states.iter().map(|st| st.q.as_slice()).collect();
        // What is drawn: every body point over the motion and the ground guides over their
        // travel (no far-away ground point that only fixes a guide's direction).
        let model_spans = fig::guide_spans(figure, &motion, &s);
        let spans = &model_spans;
        let pts = motion.iter().flat_map(|q| {
            figure
                .bodies
                .iter()
                .enumerate()
                .flat_map(move |(i, b)| b.points.iter().map(move |(_, v)| place(q, Attach::Body(i), *v).coords))
        });
        let (lo, hi) = pts
            .chain(spans.iter().flatten().flat_map(|(a, b)| [a.coords, b.coords]))
            .filter(|v| v.x.is_finite() && v.y.is_finite())
            .fold(None, |e: Option<(Vector, Vector)>, v| Some(e.map_or((v, v), |(lo, hi)| (lo.inf(&v), hi.sup(&v)))))
            .unwrap_or((Vector::zeros(), Vector::new(1.0, 1.0)));
        // Room for the letters, the ground symbols and the sliders' blocks around the links.
        let sliders = figure.joints.iter().any(|j| matches!(j, fig::JointSymbol::Slider { .. }));
        let (sl, sh) = if sliders { (s.slider_length, s.slider_height) } else { (1.0, 0.0) };
        let room = Vector::new(2.0 * s.text + sl, s.text + s.ground + 0.5 * sh);
        let mut page = MechanismPage::new(paper, lo, hi, room, table_rows, 6);
        if let Some(k) = held {
            page = page.held(k, lo, hi);
        }
        // A crank drawn shorter than 25 mm gets a detail view beside the mechanism.
        let detail = Detail::needed(figure, page.k_l, s);
        if let Some(detail) = &detail {
            let size = detail.panel_size(s, figure.units);
            page = MechanismPage::with_detail(paper, (lo, hi), room, (table_rows, 6), size);
            if let Some(k) = held {
                page = page.held(k, lo, hi);
            }
        }
        let (origin, k_l) = (page.origin, page.k_l);
        let paper_figure = figure.on_paper(origin, k_l);
        let paper_motion: Vec<Vec<f64>> = motion.iter().map(|q| fig::on_paper(q, origin, k_l)).collect();
        let paper_refs: Vec<&[f64]> = paper_motion.iter().map(Vec::as_slice).collect();
        let spans = fig::guide_spans(&paper_figure, &paper_refs, &s);
        let mut paths = Drawing::new(crate::draw::DimStyle { text_height: s.text, arrow_size: s.head });
        let tl = fig::trajectory_layer(&mut paths);
        fig::trajectories(&mut paths, tl, &paper_figure, &paper_refs);
        let figures = ForceFigures::new(mech, show.per_body);
        let drawn_mm = (hi - lo).amax() / k_l;
        LinkageSheets {
            paper,
            mechanism_page: page,
            show,
            name: name.to_string(),
            paper_figure,
            paths,
            spans,
            figures,
            drawn_mm,
            detail,
            figure: figure.clone(),
            model_spans,
        }
    }

    /// k_l, model length units per paper millimetre.
    pub fn k_l(&self) -> f64 {
        self.mechanism_page.k_l
    }

    /// How many pages a position has.
    pub fn per_position(&self) -> usize {
        1 + usize::from(self.show.velocity || self.show.acceleration) + usize::from(self.show.forces)
    }

    /// The pages of one position: `table` its values, `first` the number of its first page
    /// and `total` the run's pages: (`mechanism`, `polygons`, `forces`; each drawing in paper
    /// mm).
    pub fn pages(
        &self,
        mech: &Mechanism,
        state: &State,
        force: Option<(&Dynamics, &Forces)>,
        table: &Table,
        (first, total): (usize, usize),
    ) -> Vec<(&'static str, Drawing)> {
        // t, and φ1 and ω1 of an angular driver (the diagrams are drawn against φ1).
        let mut driver = Vec::new();
        if let Some((d, body)) = mech.angular_driver() {
            let n = match body {
                Attach::Body(i) => i + 1,
                Attach::Ground => 0,
            };
            let phi = deg(d.law.eval(state.t).value).rem_euclid(360.0);
            driver.push(format!("φ_{n} = {}°", crate::figure::fourbar::angle_text(phi)));
            driver.push(format!("ω_{n} = {} rad/s", sheet::number(state.angular(body).1)));
        }
        let title = |cells: Vec<String>, n: usize| {
            let mut all = driver.clone();
            all.extend(cells);
            TitleBlock {
                name: self.name.clone(),
                subject: "linkage".to_string(),
                position: time_text(state.t),
                cells: all,
                sheet: (first + n, total),
            }
        };
        let (values, force_rows) = split_table(table);
        let on_mechanism_page = if self.show.forces { &values } else { table };
        let mut pages = vec![("mechanism", self.mechanism_sheet(mech, state, force, on_mechanism_page, &title))];
        let units = self.paper_figure.units;
        if self.show.velocity || self.show.acceleration {
            let polys = polygons_of(mech, state, self.show.points.as_deref());
            let len = units.length;
            let (vu, au) = (format!("{len}/s"), format!("{len}/s²"));
            let mut shown: Vec<(&_, layers::Layer, &str, &str, &str)> = Vec::new();
            if self.show.velocity {
                shown.push((&polys.velocity, layers::VELOCITY, &vu, "Velocity polygon", "k_v"));
            }
            if self.show.acceleration {
                shown.push((&polys.acceleration, layers::ACCELERATION, &au, "Acceleration polygon", "k_a"));
            }
            let n = pages.len();
            pages.push(("polygons", polygons_page(self.paper, &shown, |cells| title(cells, n))));
        }
        if let (true, Some((dynamics, f))) = (self.show.forces, force) {
            let figures = self.figures.polygons(mech, dynamics, state, f);
            let captions = self.figures.captions(mech);
            let n = pages.len();
            pages.push(("forces", forces_page(self.paper, &figures, &captions, title(Vec::new(), n), &force_rows)));
        }
        pages
    }

    /// The mechanism page.
    fn mechanism_sheet(
        &self,
        mech: &Mechanism,
        state: &State,
        force: Option<(&Dynamics, &Forces)>,
        table: &Table,
        title: &dyn Fn(Vec<String>, usize) -> TitleBlock,
    ) -> Drawing {
        let (k_l, origin) = (self.k_l(), self.mechanism_page.origin);
        let layout = &self.mechanism_page.layout;
        let s = layout.sizes;
        let q = fig::on_paper(&state.q, origin, k_l);
        // The loads and reactions on the mechanism, at this page's force scale.
        let acting: Vec<_> = force
            .filter(|_| self.show.forces)
            .map(|(dynamics, f)| {
                on_mechanism(mech, dynamics, state, f)
                    .into_iter()
                    .map(|(at, nv)| (origin + at.coords / k_l, nv))
                    .collect()
            })
            .unwrap_or_default();
        let k_f = (!acting.is_empty()).then(|| {
            let at: Vec<(Point, Vector)> = acting.iter().map(|(p, nv): &(Point, _)| (*p, nv.v)).collect();
            mechanism_force_scale(&at, MECHANISM_FORCE_FRACTION * self.drawn_mm, layout.panels[0].area)
        });
        let k_l_text = length_scale_text(k_l, self.paper_figure.units);
        let mut heading = format!("Mechanism   {k_l_text}");
        let mut cells = vec![k_l_text];
        if let Some(k) = k_f {
            heading.push_str(&format!(", forces {}", scale_line("k_f", k, "N")));
            cells.push(format!("forces {}", scale_line("k_f", k, "N")));
        }
        let units = self.paper_figure.units;
        let mut headings = vec![heading];
        headings.extend(self.detail.as_ref().map(|dt| dt.caption(units)));
        let mut d = sheet::page(layout, &title(cells, 0), table, &headings);
        mechanism_bar(&mut d, layout, k_l, units.length);
        d.append(&self.paths);
        let arrows = match k_f {
            Some(k) => {
                let links = links_of(&self.paper_figure, &q);
                let pts: Vec<Point> = links.iter().flat_map(|(a, b)| [*a, *b]).collect();
                let inside = Point::from(pts.iter().map(|p| p.coords).sum::<Vector>() / pts.len().max(1) as f64);
                let mut arrows = forces::arrows_on_mechanism(&acting, Scale::on_paper(k, 1.0), &links, inside, s);
                // Clear of the links, the guides and the joints' symbols.
                let mut strokes = links.clone();
                for (a, b) in self.spans.iter().flatten() {
                    strokes.extend(clear_forces::guide_strokes(*a, *b, s));
                }
                let panel = layout.panels[0].area;
                clear_forces::place(
                    &mut arrows,
                    &strokes,
                    &symbols(&self.paper_figure, &q, s),
                    Some((panel.min, panel.max)),
                    s,
                );
                arrows
            }
            None => Vec::new(),
        };
        forces::draw_on_mechanism(&mut d, &arrows, s);
        let mech_layer = layer_of(&d, layers::MECHANISM);
        let outline = layout.panels[0].outline;
        let within = TextBox { min: outline.min, max: outline.max };
        let around = Around { backdrop: None, within: Some(within) };
        let omega = self.paper_figure.crank.map(|(b, _)| state.angular(Attach::Body(b)).1);
        let mark = self.detail.as_ref().map(|dt| dt.mark(&mut d, mech_layer, &q, k_l));
        fig::mechanism_with_forces(&mut d, mech_layer, &self.paper_figure, &q, &self.spans, &arrows, omega, &s, around);
        if let (Some(dt), Some(mark), Some(panel)) = (&self.detail, mark, layout.panels.get(1)) {
            self.draw_detail(&mut d, dt, mark, within, panel, state, omega);
        }
        d
    }

    /// The crank's detail view in `panel`, its region `mark` (centre, radius) lettered on
    /// the main view (inside `within`).
    #[allow(clippy::too_many_arguments)]
    fn draw_detail(
        &self,
        d: &mut Drawing,
        dt: &Detail,
        mark: (Point, f64),
        within: TextBox,
        panel: &Panel,
        state: &State,
        omega: Option<f64>,
    ) {
        let s = self.mechanism_page.layout.sizes;
        let (mech, paths) = (layer_of(d, layers::MECHANISM), fig::trajectory_layer(d));
        dt.letter_on(d, mech, mark, within, s);
        let dims = layer_of(d, layers::DIMENSIONS);
        let value = bar_value(dt.k);
        let label = format!("{} {}", scale_text(value), self.paper_figure.units.length);
        scale_bar(d, dims, panel.bar_at(s), value / dt.k, &label, s);
        dt.draw(d, (mech, paths), &self.figure, &state.q, &self.model_spans, panel, omega, s);
    }
}

/// The mechanism's symbols at `q` (paper mm) that the forces keep clear of
/// ([`clear_forces::place`]): every joint's circle, every slider's block, every pivot's
/// ground symbol.
pub fn symbols(figure: &LinkageFigure, q: &[f64], s: vocab::Sizes) -> Vec<clear_forces::Symbol> {
    let mut out = Vec::new();
    for j in &figure.joints {
        match j {
            fig::JointSymbol::Pin { at, grounded, .. } => {
                let p = fig::anchor_at(q, *at);
                out.push(clear_forces::Symbol::Circle { at: p, r: s.joint });
                if *grounded {
                    out.push(clear_forces::ground_block(p, s));
                }
            }
            fig::JointSymbol::Slider { point, q1, q2, .. } => {
                let dir = fig::anchor_at(q, *q2) - fig::anchor_at(q, *q1);
                let len = dir.norm();
                if len > 0.0 {
                    let p = fig::anchor_at(q, *point);
                    out.push(clear_forces::Symbol::Block {
                        at: p,
                        centre: p,
                        dir: dir / len,
                        half: (0.5 * s.slider_length, 0.5 * s.slider_height),
                    });
                }
            }
        }
    }
    out
}

/// Whether a row of a position's table is a force's or a moment's (its unit N or N·…).
fn is_force_row(row: &[String]) -> bool {
    row.last().is_some_and(|u| u == "N" || u.starts_with("N·"))
}

/// A position's table split: its kinematics' rows, and its forces' (every applied force,
/// every reaction, the drivers' forces), each under the same header.
pub fn split_table(table: &Table) -> (Table, Table) {
    (table.filter(|r| !is_force_row(r)), table.filter(is_force_row))
}

/// The rows of a position's table: (kinematics, forces), for [`LinkageSheets::new`].
pub fn row_counts(table: &Table) -> (usize, usize) {
    let forces = table.rows.iter().filter(|r| is_force_row(r)).count();
    (table.rows.len() - forces, forces)
}
