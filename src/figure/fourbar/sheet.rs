//! The four-bar on printed sheets (issue 14, item 3; issue 31): per position a set of pages
//! ([`crate::figure::shared::sheet_pages`]) — the mechanism page (the mechanism with its
//! coupler curve in the largest panel, at one drafting scale k_l for the run, with the
//! loads and reactions at the page's force scale, the ω1 arrow and link numbers, and the
//! table of the position's values), the polygons page (the velocity polygon with the
//! directions that locate b, the acceleration polygon, each at its own nice scale), and
//! with forces the forces page (the dyad's figure, seed 003 Fig. 4, and the crank's, Fig. 5,
//! each at its own k_f, at least 60 mm long) — drawn by the same functions as the animation,
//! in paper millimetres. Every scale is printed in its panel's title and in the title block.

use crate::draw::Drawing;
use crate::geom::{Point, Vector, cross, deg};
use crate::solve::fourbar::{ExternalForce, Forces, Geometry, LinkLoad, Position};

use crate::figure::fourbar::{
    CRANK_CAPTION, DYAD_CAPTION, Show, acceleration_polygon, angle_text, crank_polygon, dyad_polygon,
    link_loads_on_mechanism, links_of, mechanism, on_mechanism, velocity_figure,
};
use crate::figure::shared::clear_forces::{self, Symbol};
use crate::figure::shared::forces;
use crate::figure::shared::labels::{Around, TextBox};
use crate::figure::shared::panels::scale_line;
use crate::figure::shared::sheet::{self, Paper, Table, TitleBlock};
use crate::figure::shared::sheet_pages::{
    MechanismPage, forces_page, mechanism_bar, mechanism_force_scale, polygons_page,
};
use crate::figure::shared::vocab::{ModelUnits, Scale, ground, layer_of, layers, length_scale_text, path};

/// The longest force drawn on the mechanism page, as a fraction of the mechanism's drawn
/// size.
pub const MECHANISM_FORCE_FRACTION: f64 = 0.3;

/// What every page set of a run shares: the mechanism page's layout, scale and placement,
/// the coupler curve on paper.
#[derive(Debug, Clone)]
pub struct FourbarSheets {
    /// The paper.
    pub paper: Paper,
    /// The mechanism page (its layout, k_l, the model's origin on paper).
    pub mechanism_page: MechanismPage,
    /// The polygons drawn.
    pub show: Show,
    /// The model's units.
    pub units: ModelUnits,
    /// The scene's name, for the title block.
    pub name: String,
    /// ω1, rad/s, for the title block and the ω1 arrow.
    pub omega1: f64,
    /// The external forces and link loads, drawn on the mechanism where they act.
    pub external: Vec<ExternalForce>,
    /// The link loads.
    pub link_loads: Vec<LinkLoad>,
    /// The coupler curve on paper.
    curve: Vec<Vec<Point>>,
    /// The mechanism's drawn size, paper mm.
    drawn_mm: f64,
}

/// The smallest box holding the finite vectors of `vs`.
fn extent(vs: impl IntoIterator<Item = Vector>) -> Option<(Vector, Vector)> {
    vs.into_iter()
        .filter(|v| v.x.is_finite() && v.y.is_finite())
        .fold(None, |e, v| Some(e.map_or((v, v), |(lo, hi): (Vector, Vector)| (lo.inf(&v), hi.sup(&v)))))
}

/// The pages of one position.
pub struct PositionPages {
    /// `mechanism`, `polygons`, `forces`, with each page's drawing (paper mm).
    pub pages: Vec<(&'static str, Drawing)>,
}

impl FourbarSheets {
    /// The sheets of a run on `paper`: `positions` the assembled positions, `curve` the
    /// coupler curve (runs of points, model units), `show` the polygons asked for, `table_rows`
    /// the rows of the mechanism page's table.
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
        table_rows: usize,
    ) -> FourbarSheets {
        let s = paper.sizes();
        let pts = positions.iter().flat_map(|p| [p.a.coords, p.b.coords, p.m.coords]);
        let (lo, hi) =
            extent(pts.chain([geom.o1.coords, geom.c.coords]).chain(curve.iter().flatten().map(|p| p.coords)))
                .unwrap_or((Vector::zeros(), Vector::new(1.0, 1.0)));
        // Room for the letters and link numbers around the links, the ground symbols under
        // the pivots.
        let room = Vector::new(2.0 * s.text + 1.0, 2.0 * s.text + s.ground);
        let page = MechanismPage::new(paper, lo, hi, room, table_rows, 5);
        let to_paper = |p: &Point| page.origin + p.coords / page.k_l;
        let curve = curve.iter().map(|run| run.iter().map(to_paper).collect()).collect();
        let drawn_mm = (hi - lo).amax() / page.k_l;
        FourbarSheets {
            paper,
            mechanism_page: page,
            show,
            units,
            name: name.to_string(),
            omega1,
            external: Vec::new(),
            link_loads: Vec::new(),
            curve,
            drawn_mm,
        }
    }

    /// The sheets with the scene's external forces and link loads (drawn on the mechanism).
    pub fn with_loads(mut self, external: &[ExternalForce], link_loads: &[LinkLoad]) -> FourbarSheets {
        self.external = external.to_vec();
        self.link_loads = link_loads.to_vec();
        self
    }

    /// k_l, model length units per paper millimetre.
    pub fn k_l(&self) -> f64 {
        self.mechanism_page.k_l
    }

    /// A model point on paper.
    fn paper(&self, p: Point) -> Point {
        self.mechanism_page.origin + p.coords / self.k_l()
    }

    /// How many pages a position has.
    pub fn per_position(&self) -> usize {
        1 + usize::from(self.show.velocity || self.show.acceleration) + usize::from(self.show.forces)
    }

    /// The pages of one position: `table` its values, `first` the number of its first page
    /// and `total` the run's pages.
    pub fn pages(
        &self,
        geom: &Geometry,
        pos: &Position,
        force: Option<&Forces>,
        table: &Table,
        (first, total): (usize, usize),
    ) -> PositionPages {
        // Title block cells: `_` before a subscript (sheet::TitleBlock).
        let position = format!("φ_1 = {}°", angle_text(deg(pos.phi1)));
        let omega = format!("ω_1 = {} rad/s", angle_text(self.omega1));
        let title = |cells: Vec<String>, n: usize| TitleBlock {
            name: self.name.clone(),
            subject: "four-bar".to_string(),
            position: position.clone(),
            cells,
            sheet: (first + n, total),
        };
        let mut pages = vec![("mechanism", self.mechanism_sheet(geom, pos, force, table, &title, &omega))];
        let kin = pos.kin.as_ref();
        if let (true, Some(k)) = (self.show.velocity || self.show.acceleration, kin) {
            let velocity = velocity_figure(pos, geom.c, k);
            let acceleration = acceleration_polygon(pos, geom.c, k);
            let len = self.units.length;
            let (vu, au) = (format!("{len}/s"), format!("{len}/s²"));
            let mut polys: Vec<(&_, layers::Layer, &str, &str, &str)> = Vec::new();
            if self.show.velocity {
                polys.push((&velocity, layers::VELOCITY, &vu, "Velocity polygon", "k_v"));
            }
            if self.show.acceleration {
                polys.push((&acceleration, layers::ACCELERATION, &au, "Acceleration polygon", "k_a"));
            }
            let n = pages.len();
            let with_omega = |cells: Vec<String>| title(std::iter::once(omega.clone()).chain(cells).collect(), n);
            pages.push(("polygons", polygons_page(self.paper, &polys, with_omega)));
        }
        if let (true, Some(f)) = (self.show.forces, force) {
            let figures = [dyad_polygon(f), crank_polygon(f)];
            let captions = [DYAD_CAPTION.to_string(), CRANK_CAPTION.to_string()];
            let n = pages.len();
            pages.push((
                "forces",
                forces_page(self.paper, &figures, &captions, title(vec![omega.clone()], n), &Table::default()),
            ));
        }
        PositionPages { pages }
    }

    /// The mechanism page.
    fn mechanism_sheet(
        &self,
        geom: &Geometry,
        pos: &Position,
        force: Option<&Forces>,
        table: &Table,
        title: &dyn Fn(Vec<String>, usize) -> TitleBlock,
        omega: &str,
    ) -> Drawing {
        let k_l = self.k_l();
        let page = &self.mechanism_page;
        let s = page.layout.sizes;
        let on_paper = Geometry {
            o1: self.paper(geom.o1),
            c: self.paper(geom.c),
            l1: geom.l1 / k_l,
            l_ab: geom.l_ab / k_l,
            l_bm: geom.l_bm / k_l,
            l_bc: geom.l_bc / k_l,
            ..*geom
        };
        let p = Position {
            a: self.paper(pos.a),
            b: self.paper(pos.b),
            m: self.paper(pos.m),
            c: on_paper.c,
            kin: None,
            ..*pos
        };
        // The loads and reactions on the mechanism, at this page's force scale.
        let acting: Vec<_> = force
            .filter(|_| self.show.forces)
            .map(|f| {
                let mut a = on_mechanism(geom, pos, f, &self.external);
                a.extend(link_loads_on_mechanism(geom, pos, &self.link_loads));
                a.into_iter().map(|(at, nv)| (self.paper(at), nv)).collect()
            })
            .unwrap_or_default();
        let area = page.layout.panels[0].area;
        let k_f = (!acting.is_empty()).then(|| {
            let at: Vec<(Point, Vector)> = acting.iter().map(|(p, nv)| (*p, nv.v)).collect();
            mechanism_force_scale(&at, MECHANISM_FORCE_FRACTION * self.drawn_mm, area)
        });
        let len = self.units.length;
        let k_l_text = length_scale_text(k_l, self.units);
        let mut heading = format!("Mechanism   {k_l_text}");
        let mut cells = vec![omega.to_string(), k_l_text];
        if let Some(k) = k_f {
            heading.push_str(&format!(", forces {}", scale_line("k_f", k, "N")));
            cells.push(format!("forces {}", scale_line("k_f", k, "N")));
        }
        let _ = len;
        let mut d = sheet::page(&page.layout, &title(cells, 0), table, &[heading]);
        mechanism_bar(&mut d, &page.layout, k_l, self.units.length);
        let cc = layer_of(&d, layers::COUPLER_CURVE);
        for run in &self.curve {
            path(&mut d, cc, run.clone());
        }
        let mech = layer_of(&d, layers::MECHANISM);
        for q in [on_paper.o1, on_paper.c] {
            ground(&mut d, mech, q, s);
        }
        let arrows = match k_f {
            Some(k) => {
                let links = links_of(&on_paper, &p);
                let inside = Point::from((on_paper.o1.coords + p.a.coords + p.b.coords + on_paper.c.coords) / 4.0);
                let mut arrows = forces::arrows_on_mechanism(&acting, Scale::on_paper(k, 1.0), &links, inside, s);
                // Clear of the links and the joints' symbols (the pivots' ground symbols).
                let mut symbols: Vec<Symbol> =
                    [on_paper.o1, p.a, p.b, on_paper.c].iter().map(|&at| Symbol::Circle { at, r: s.joint }).collect();
                symbols.extend([on_paper.o1, on_paper.c].map(|at| clear_forces::ground_block(at, s)));
                let panel = page.layout.panels[0].area;
                clear_forces::place(&mut arrows, &links, &symbols, Some((panel.min, panel.max)), s);
                arrows
            }
            None => Vec::new(),
        };
        forces::draw_on_mechanism(&mut d, &arrows, s);
        let omega1 = Some(self.omega1).filter(|w| *w != 0.0).or_else(|| pos.kin.map(|k| cross(pos.a - geom.o1, k.v_a)));
        let outline = page.layout.panels[0].outline;
        let within = Some(TextBox { min: outline.min, max: outline.max });
        let _ = mechanism(&mut d, &on_paper, &p, &arrows, omega1, s, Around { backdrop: None, within });
        d
    }
}
