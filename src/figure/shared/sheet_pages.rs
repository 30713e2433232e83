//! The printed pages of one position, for any mechanism (issue 31: the mechanism the largest
//! figure, every force figure readable): on the paper asked for, a set of pages per
//! position, each framed with the title block in its lower right corner —
//! 1. the mechanism page: the mechanism in the largest panel the page holds (left of the
//!    table of values, or above it for a long, low mechanism: whichever draws it larger), at a
//!    drafting scale k_l ([`drafting_scale`]: 1, 1.5, 2, 2.5, 4, 5 × 10ᵏ) that fits the whole
//!    motion, the same on every page of a run; the loads and reactions drawn on it;
//! 2. the polygons page: the velocity and the acceleration polygons side by side, each at its
//!    own nice scale on each page ([`sheet::fit`]), centred in its panel;
//! 3. the forces page (with forces): one figure per group in solving order, each at the
//!    coarsest nice k_f that draws it at least [`FORCE_FIGURE_MIN_MM`] long (so at most twice
//!    that), captioned with its k_f and with its own scale bar, packed in rows (or by the
//!    skyline, a column of figures beside a tall one, where rows cannot hold them); a
//!    linkage's table of forces (every applied force, every reaction) packed after them, so
//!    that the mechanism page's table holds the kinematics only.
//!
//! This file knows no mechanism: a kind draws its mechanism and describes its polygons.

use crate::draw::{Bounds, Drawing};
use crate::geom::{Point, Vector};

use crate::figure::shared::forces::{self, ForcePolygon};
use crate::figure::shared::labels::TextBox;
use crate::figure::shared::panels::{Extent, scale_line};
use crate::figure::shared::polygon::{self, PointPolygon};
use crate::figure::shared::sheet::{self, Panel, Paper, SheetLayout, Table, TitleBlock};
use crate::figure::shared::vocab::{
    Scale, Sizes, bar_value, drafting_scale, layer_of, layers, nice_scale, scale_bar, scale_bar_room, scale_text,
};

/// The least length of a force figure on its page (its larger side), paper mm.
pub const FORCE_FIGURE_MIN_MM: f64 = 60.0;
/// Room left around a figure for the letters at its outer points, in letter heights.
pub const LETTER_ROOM: f64 = 1.5;
/// The largest share of the page's height the table under a long mechanism takes.
pub const TABLE_BAND_MAX: f64 = 0.45;

/// Where the mechanism goes on its page: the layout (panel 0 the mechanism's), the length
/// scale, and the paper point of the model's origin.
#[derive(Debug, Clone, PartialEq)]
pub struct MechanismPage {
    /// The page's layout: the mechanism's panel, the table, the title block.
    pub layout: SheetLayout,
    /// k_l: model length units per paper millimetre (a drafting scale).
    pub k_l: f64,
    /// The paper point of the model's origin.
    pub origin: Point,
}

impl MechanismPage {
    /// The page for a mechanism whose motion spans `lo`…`hi` (model units), with `room` paper
    /// mm around it for its symbols and letters (each side), a table of `table_rows` rows and
    /// a title block of `title_cells` cells: the arrangement that draws it at the larger
    /// scale — beside the table (the table in the right column over the title block) or
    /// above it (the table in a band under it, left of the title block).
    pub fn new(paper: Paper, lo: Vector, hi: Vector, room: Vector, table_rows: usize, title_cells: usize) -> Self {
        Self::laid_out(paper, (lo, hi), room, (table_rows, title_cells), None)
    }

    /// [`MechanismPage::new`] with a detail panel of outline `detail` (width, height, paper
    /// mm: its content, as a draftsman sizes a detail view) as panel 1 of the layout: at the
    /// top of the right column over the table (the mechanism's panel then the whole height
    /// left of them) when the column holds both, else at the top right of the mechanism's
    /// panel with the mechanism drawn left of it; whichever draws the mechanism larger (the
    /// column on a tie).
    pub fn with_detail(
        paper: Paper,
        (lo, hi): (Vector, Vector),
        room: Vector,
        (table_rows, title_cells): (usize, usize),
        detail: Vector,
    ) -> Self {
        Self::laid_out(paper, (lo, hi), room, (table_rows, title_cells), Some(detail))
    }

    /// The page, with a detail panel of outline `aside` (none for `None`).
    fn laid_out(
        paper: Paper,
        (lo, hi): (Vector, Vector),
        room: Vector,
        (table_rows, title_cells): (usize, usize),
        aside: Option<Vector>,
    ) -> Self {
        let (sizes, border, right, title) = sheet::page_frame(paper, title_cells);
        let strip = aside.map_or(0.0, |a| a.x);
        // The mechanism's part of a panel (a detail's strip taken off its right).
        let main = |b: Bounds, strip: f64| Bounds { min: b.min, max: Point::new(b.max.x - strip, b.max.y) };
        let extent = (hi - lo).sup(&Vector::new(1e-300, 1e-300));
        let table_h = |sets: usize| (table_rows.div_ceil(sets) + 1) as f64 * sheet::TABLE_ROW * sizes.text;
        let beside = (
            Bounds { min: border.min, max: Point::new(right, border.max.y) },
            Bounds { min: Point::new(right, title.max.y), max: border.max },
        );
        // Above the table: the table in one set of columns, or in two or three side by side
        // (a lower band, a taller panel).
        let above = |sets: usize| {
            let band =
                (table_h(sets) + 1.2 * sizes.text + 1e-9).max(title.height()).min(TABLE_BAND_MAX * border.height());
            (
                Bounds { min: Point::new(border.min.x, border.min.y + band), max: border.max },
                Bounds { min: border.min, max: Point::new(right, border.min.y + band) },
            )
        };
        let scale_in = |panel: Bounds| {
            let area = Panel::of_outline(panel, sizes).area;
            let room = Vector::new(area.width(), area.height()) - 2.0 * room;
            drafting_scale((extent.x / room.x.max(1e-9)).max(extent.y / room.y.max(1e-9)))
        };
        // The arrangements: (the mechanism's panel, the table, the detail's panel).
        let mut arrangements: Vec<(Bounds, Bounds, Option<Bounds>)> = Vec::new();
        // The detail at the top of the right column, the table under it, when both fit.
        if let Some(a) = aside {
            let column = beside.1;
            let foot = column.max.y - a.y;
            let table = Bounds { min: column.min, max: Point::new(column.max.x, foot) };
            let fits =
                a.x <= column.width() + 1e-9 && table.height() >= table_h(1) + 1.2 * sizes.text && table_rows > 0;
            if fits {
                let detail = Bounds { min: Point::new(column.min.x, foot), max: column.max };
                arrangements.push((beside.0, table, Some(detail)));
            }
        }
        // The detail at the top of a strip at the page's right, the table under it, the
        // mechanism's panel left of them down to the title block, when the table fits there.
        if let Some(a) = aside {
            let foot = border.max.y - a.y;
            let table =
                Bounds { min: Point::new(border.max.x - a.x, title.max.y), max: Point::new(border.max.x, foot) };
            let one_set = sheet::TABLE_COLUMN_MIN * sizes.text * 3.0 + 1.2 * sizes.text;
            let fits = table_rows > 0
                && table.width() >= one_set
                && table.height() >= table_h(1) + 1.2 * sizes.text
                && table.min.x > right;
            if fits {
                let panel =
                    Bounds { min: Point::new(border.min.x, title.max.y), max: Point::new(table.min.x, border.max.y) };
                let detail = Bounds { min: Point::new(table.min.x, foot), max: border.max };
                arrangements.push((panel, table, Some(detail)));
            }
        }
        // Beside or above the table, the detail (if any) in a strip at the panel's right.
        for (panel, table) in [beside, above(1), above(2), above(3)] {
            let detail = aside.map(|a| Bounds {
                min: Point::new(panel.max.x - strip, (panel.max.y - a.y).max(panel.min.y)),
                max: panel.max,
            });
            arrangements.push((main(panel, strip), table, detail));
        }
        // The arrangement that draws the mechanism largest; on a tie, the first, or with a
        // detail the one with the largest panel for the mechanism (the room the detail's
        // strip leaves given back to it).
        let area = |b: &Bounds| b.width() * b.height();
        let mut best = arrangements[0];
        let mut k_l = scale_in(best.0);
        for a in &arrangements[1..] {
            let k = scale_in(a.0);
            let larger = aside.is_some() && area(&a.0) > area(&best.0) + 1e-9;
            if k < k_l * (1.0 - 1e-12) || (k <= k_l * (1.0 + 1e-12) && larger) {
                (best, k_l) = (*a, k);
            }
        }
        let (panel, table, detail) = best;
        let outline = Panel::of_outline(panel, sizes);
        let origin = sheet::centre(lo, hi, k_l, outline.area);
        let mut panels = vec![outline];
        panels.extend(detail.map(|b| Panel::of_outline(b, sizes)));
        let layout = SheetLayout { paper, sizes, border, panels, table, title };
        MechanismPage { layout, k_l, origin }
    }

    /// The same page at `k_l` when it is coarser than the page's own (a report holding one
    /// drafting scale for the mechanism across its pages): the arrangement kept, the motion
    /// `lo`…`hi` centred again.
    pub fn held(mut self, k_l: f64, lo: Vector, hi: Vector) -> Self {
        if k_l > self.k_l {
            self.k_l = k_l;
            self.origin = sheet::centre(lo, hi, k_l, self.layout.panels[0].area);
        }
        self
    }
}

/// The scale bar of the mechanism page's panel: `k_l` model units (`unit`) per paper mm.
pub fn mechanism_bar(d: &mut Drawing, layout: &SheetLayout, k_l: f64, unit: &str) {
    let (s, dims) = (layout.sizes, layer_of(d, layers::DIMENSIONS));
    let value = bar_value(k_l);
    scale_bar(d, dims, layout.panels[0].bar_at(s), value / k_l, &format!("{} {unit}", scale_text(value)), s);
}

/// The layout of the polygons page: `count` panels (1 or 2) side by side over the title
/// block, no table.
pub fn polygons_layout(paper: Paper, count: usize, title_cells: usize) -> SheetLayout {
    let (sizes, border, _, title) = sheet::page_frame(paper, title_cells);
    let n = count.max(1);
    let w = border.width() / n as f64;
    let panels = (0..n)
        .map(|i| {
            let min = Point::new(border.min.x + i as f64 * w, title.max.y);
            Panel::of_outline(Bounds { min, max: Point::new(min.x + w, border.max.y) }, sizes)
        })
        .collect();
    let table = Bounds { min: title.max, max: title.max };
    SheetLayout { paper, sizes, border, panels, table, title }
}

/// The velocity and acceleration polygons of one page, each fitted to its panel.
#[derive(Debug, Clone, PartialEq)]
pub struct PolygonsPage {
    /// The page's layout (a panel per polygon).
    pub layout: SheetLayout,
    /// Each polygon's scale (physical units per paper mm) and pole, velocity first.
    pub places: Vec<(f64, Point)>,
}

impl PolygonsPage {
    /// The page of `polygons` (the velocity polygon, the acceleration polygon, as drawn).
    pub fn new(paper: Paper, polygons: &[&PointPolygon], title_cells: usize) -> PolygonsPage {
        let layout = polygons_layout(paper, polygons.len(), title_cells);
        let room = 2.0 * LETTER_ROOM * layout.sizes.text;
        let places = polygons
            .iter()
            .zip(&layout.panels)
            .map(|(p, panel)| {
                let e =
                    Extent::of(p.physical_points()).unwrap_or(Extent { min: Vector::zeros(), max: Vector::zeros() });
                let area = Vector::new(panel.area.width() - room, panel.area.height() - room);
                let f = sheet::fit(e.sides(), area);
                (f.per_mm, sheet::centre(e.min, e.max, f.per_mm, panel.area))
            })
            .collect();
        PolygonsPage { layout, places }
    }

    /// Draws the polygons in their panels (the drawing in paper mm) on `layers_of[i]`, and
    /// a scale bar under each labelled with `units[i]` (`m/s`).
    pub fn draw(&self, d: &mut Drawing, polygons: &[(&PointPolygon, layers::Layer, &str)]) {
        let s = self.layout.sizes;
        let dims = layer_of(d, layers::DIMENSIONS);
        for (((poly, layer, unit), (per_mm, pole)), panel) in polygons.iter().zip(&self.places).zip(&self.layout.panels)
        {
            let within = TextBox { min: panel.outline.min, max: panel.outline.max };
            let clip = TextBox { min: panel.area.min, max: panel.area.max };
            polygon::draw_within(
                d,
                poly,
                *layer,
                Scale::on_paper(*per_mm, 1.0),
                *pole,
                s,
                &[],
                Some(within),
                Some(clip),
            );
            let value = bar_value(*per_mm);
            scale_bar(d, dims, panel.bar_at(s), value / per_mm, &format!("{} {unit}", scale_text(value)), s);
        }
    }
}

/// The force figures of one page: each figure's cell (caption, area, bar) and scale.
#[derive(Debug, Clone, PartialEq)]
pub struct ForcesPage {
    /// The page's layout: a panel per figure, no table.
    pub layout: SheetLayout,
    /// Each figure's k_f (N per paper mm) and pole.
    pub places: Vec<(f64, Point)>,
}

/// The coarsest nice scale that draws a figure of physical size `size` at least
/// [`FORCE_FIGURE_MIN_MM`] long: its drawn size is then less than twice that.
pub fn force_figure_scale(size: f64) -> f64 {
    if !(size.is_finite() && size > 0.0) {
        return 1.0;
    }
    let raw = size / FORCE_FIGURE_MIN_MM;
    let mag = libm::pow(10f64, libm::log10(raw).floor());
    [5.0, 2.5, 2.0, 1.0].iter().map(|m| m * mag).find(|k| *k <= raw * (1.0 + 1e-12)).unwrap_or(mag)
}

impl ForcesPage {
    /// The page of `figures` (one per group, in solving order) with `captions`, and a table of
    /// `table_rows` rows after them, clear of the title block: each figure at the coarsest
    /// nice k_f that draws it [`FORCE_FIGURE_MIN_MM`] long, then, one figure after the other
    /// while the page still holds them, at the next finer one (larger figures where there is
    /// room); the panels then stretched to use the page (none smaller than packed), and each
    /// figure at the finest nice k_f that its final panel holds, the figure and its title
    /// measured in that panel (`fits_panel`).
    ///
    /// The cells are packed in rows from the top left (`pack`), the figures in solving order
    /// when the page holds them so, else in the first other order that it holds; a page that
    /// holds them in rows in no order packs them by the skyline (`pack_skyline`: each cell
    /// where its foot stays highest, so a column of two figures stands beside a tall one and
    /// the table beside them: the shaper's crank and dyads at 5 of its 361 positions on A4).
    /// A page that holds them in neither way draws the largest figure a nice step coarser,
    /// and again, until it does; one that still does not (packed anyway) is not stretched.
    pub fn new(
        paper: Paper,
        figures: &[ForcePolygon],
        captions: &[String],
        title_cells: usize,
        table_rows: usize,
    ) -> ForcesPage {
        let (sizes, border, right, title) = sheet::page_frame(paper, title_cells);
        let extents: Vec<Extent> = figures
            .iter()
            .map(|f| Extent::of(f.physical_points()).unwrap_or(Extent { min: Vector::zeros(), max: Vector::zeros() }))
            .collect();
        let cells = FigureCells { extents: &extents, captions, sizes, border, right, title, table_rows };
        let (mut scales, held) = cells.held_scales();
        // A page that holds its figures is stretched to use the page; one that does not
        // (packed anyway, past the border) stays as packed.
        let mut outlines = match &held {
            Some((_, Packing::Shelves, o)) => {
                let mut o = o.clone();
                fill(&mut o, border, right, title);
                o
            }
            Some((_, Packing::Skyline, o)) => {
                let mut o = o.clone();
                spread_into_free(&mut o, border, right, title);
                o
            }
            None => {
                let mut all = cells.sizes_at(&scales);
                if table_rows > 0 {
                    all.push(table_cell(table_rows, 1, sizes));
                }
                pack_anyway(&all, border)
            }
        };
        // In its final panel a figure may hold a finer scale: the finest it fits there.
        for (i, k) in scales.iter_mut().enumerate() {
            let (Some(o), Some(c)) = (outlines.get(i), captions.get(i)) else { continue };
            if extents[i].size() == 0.0 || !fits_panel(*k, &extents[i], c, *o, sizes) {
                continue;
            }
            while fits_panel(finer_nice(*k), &extents[i], c, *o, sizes) {
                *k = finer_nice(*k);
            }
        }
        let none = Bounds { min: title.max, max: title.max };
        let table =
            if table_rows > 0 && outlines.len() > figures.len() { outlines.pop().unwrap_or(none) } else { none };
        let panels: Vec<Panel> = outlines.iter().map(|b| Panel::of_outline(*b, sizes)).collect();
        let places = scales
            .iter()
            .zip(&extents)
            .zip(&panels)
            .map(|((k, e), p)| (*k, sheet::centre(e.min, e.max, *k, p.area)))
            .collect();
        ForcesPage { layout: SheetLayout { paper, sizes, border, panels, table, title }, places }
    }

    /// Each figure's panel title: its caption and k_f.
    pub fn titles(&self, captions: &[String]) -> Vec<String> {
        captions.iter().zip(&self.places).map(|(c, (k, _))| format!("{c}   {}", scale_line("k_f", *k, "N"))).collect()
    }

    /// Draws the figures in their cells, with a scale bar under each.
    pub fn draw(&self, d: &mut Drawing, figures: &[ForcePolygon]) {
        let s = self.layout.sizes;
        let dims = layer_of(d, layers::DIMENSIONS);
        for ((fig, (k, pole)), panel) in figures.iter().zip(&self.places).zip(&self.layout.panels) {
            let within = TextBox { min: panel.outline.min, max: panel.outline.max };
            forces::draw_within(d, fig, Scale::on_paper(*k, 1.0), *pole, s, &[], Some(within));
            let value = bar_value(*k);
            scale_bar(d, dims, panel.bar_at(s), value / k, &format!("{} N", scale_text(value)), s);
        }
    }
}

/// The scale of the forces drawn on a mechanism page: the nice k_f (N per paper mm) at which
/// the longest of `forces` (where each acts on paper, and the force, N) is at most `longest`
/// paper mm and every arrow's tip stays inside `area`.
pub fn mechanism_force_scale(forces: &[(Point, Vector)], longest: f64, area: Bounds) -> f64 {
    let mut raw: f64 = 0.0;
    for (at, v) in forces {
        let n = v.norm();
        if !(n.is_finite() && n > 0.0) {
            continue;
        }
        raw = raw.max(n / longest);
        // The room from the point to the area's edge along the force.
        let reach = |p: f64, lo: f64, hi: f64, c: f64| {
            if c > 0.0 {
                (hi - p) / c
            } else if c < 0.0 {
                (lo - p) / c
            } else {
                f64::INFINITY
            }
        };
        let t = reach(at.x, area.min.x, area.max.x, v.x).min(reach(at.y, area.min.y, area.max.y, v.y));
        if t > 0.0 && t.is_finite() {
            raw = raw.max(1.0 / t);
        }
    }
    nice_scale(raw)
}

/// The polygons page: each polygon (with its layer, its vectors' unit, its title and its
/// scale's symbol) at its own scale in its panel; `title` makes the title block from the
/// scales' cells.
pub fn polygons_page(
    paper: Paper,
    polys: &[(&PointPolygon, layers::Layer, &str, &str, &str)],
    title: impl Fn(Vec<String>) -> TitleBlock,
) -> Drawing {
    let only: Vec<&_> = polys.iter().map(|p| p.0).collect();
    let page = PolygonsPage::new(paper, &only, 5);
    let mut cells = Vec::new();
    let mut heads = Vec::new();
    for ((_, _, unit, head, symbol), (k, _)) in polys.iter().zip(&page.places) {
        let line = scale_line(symbol, *k, unit);
        heads.push(format!("{head}   {line}"));
        cells.push(line);
    }
    let mut d = sheet::page(&page.layout, &title(cells), &Table::default(), &heads);
    let drawn: Vec<_> = polys.iter().map(|(p, l, u, ..)| (*p, *l, *u)).collect();
    page.draw(&mut d, &drawn);
    d
}

/// The forces page: each figure (with its caption) at its own k_f in its cell, and `table`
/// (the forces' values, when it has rows) after them.
pub fn forces_page(
    paper: Paper,
    figures: &[ForcePolygon],
    captions: &[String],
    title: TitleBlock,
    table: &Table,
) -> Drawing {
    let page = ForcesPage::new(paper, figures, captions, title.cells.len() + 2, table.rows.len());
    let mut d = sheet::page(&page.layout, &title, table, &page.titles(captions));
    page.draw(&mut d, figures);
    d
}

/// How a forces page's cells are packed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Packing {
    /// In rows from the top left ([`pack`]), stretched by [`fill`].
    Shelves,
    /// Each where its foot stays highest ([`pack_skyline`]), stretched by
    /// [`spread_into_free`].
    Skyline,
}

/// A page that holds its cells: the figures' order, the packing, the cells (the figures'
/// in their own order, the table's last).
type Held = (Vec<usize>, Packing, Vec<Bounds>);

/// The cells of a forces page's figures and table, and the page they go on.
struct FigureCells<'a> {
    /// Each figure's physical extent, N.
    extents: &'a [Extent],
    /// Each figure's caption.
    captions: &'a [String],
    sizes: Sizes,
    border: Bounds,
    /// The title block's left edge.
    right: f64,
    title: Bounds,
    /// The rows of the forces' table (none: no table cell).
    table_rows: usize,
}

impl FigureCells<'_> {
    /// Each figure's cell at `scales`.
    fn sizes_at(&self, scales: &[f64]) -> Vec<Vector> {
        scales.iter().zip(self.extents).zip(self.captions).map(|((k, e), c)| cell_size(*k, e, c, self.sizes)).collect()
    }

    /// The figures at `scales` in `order`, then the table (when it has rows) as one more cell
    /// in one to three sets of columns, packed by `packing`: the first arrangement the page
    /// holds, the cells back in the figures' order (the table last).
    fn pack_in(&self, order: &[usize], scales: &[f64], packing: Packing) -> Option<Vec<Bounds>> {
        let (border, right, title) = (self.border, self.right, self.title);
        let pack_with = |all: &[Vector]| match packing {
            Packing::Shelves => pack(all, border, right, title),
            Packing::Skyline => pack_skyline(all, border, right, title),
        };
        let cells = self.sizes_at(scales);
        let mut all: Vec<Vector> = order.iter().map(|&i| cells[i]).collect();
        let packed = if self.table_rows == 0 {
            pack_with(&all)
        } else {
            (1..=3).find_map(|sets| {
                all.push(table_cell(self.table_rows, sets, self.sizes));
                let p = pack_with(&all);
                all.pop();
                p
            })
        }?;
        let mut out = packed.clone();
        for (j, &i) in order.iter().enumerate() {
            out[i] = packed[j];
        }
        Some(out)
    }

    /// The first order and packing that holds the figures at `scales`: in rows in solving
    /// order, in rows in another order, then by the skyline in each order.
    fn pack_any(&self, orders: &[Vec<usize>], scales: &[f64]) -> Option<Held> {
        [Packing::Shelves, Packing::Skyline].into_iter().find_map(|packing| {
            orders.iter().find_map(|order| self.pack_in(order, scales, packing).map(|o| (order.clone(), packing, o)))
        })
    }

    /// The figures' scales and the page that holds them: each at its least-size scale
    /// ([`force_figure_scale`]); when no packing holds them, the largest drawn a nice step
    /// coarser until one does (never figures off the paper); when one held them at once,
    /// each figure a nice step finer while the page, packed the same way, still holds them.
    fn held_scales(&self) -> (Vec<f64>, Option<Held>) {
        let n = self.extents.len();
        let mut scales: Vec<f64> = self.extents.iter().map(|e| force_figure_scale(e.size())).collect();
        let orders = figure_orders(n);
        let mut held = self.pack_any(&orders, &scales);
        let mut coarsened = 0;
        while held.is_none() && coarsened < COARSENED_STEPS_PER_FIGURE * n {
            let drawn = |i: usize| {
                let d = self.extents[i].sides() / scales[i];
                d.x * d.y
            };
            let Some(largest) =
                (0..n).filter(|&i| self.extents[i].size() > 0.0).max_by(|&i, &j| drawn(i).total_cmp(&drawn(j)))
            else {
                break;
            };
            scales[largest] = coarser_nice(scales[largest]);
            held = self.pack_any(&orders, &scales);
            coarsened += 1;
        }
        if let (Some((order, packing, outlines)), 0) = (&mut held, coarsened) {
            self.grow(order, *packing, &mut scales, outlines);
        }
        (scales, held)
    }

    /// Larger figures where there is room: each figure a nice step finer, again and again,
    /// while the page packed in `order` by `packing` still holds them (`outlines` the cells).
    fn grow(&self, order: &[usize], packing: Packing, scales: &mut Vec<f64>, outlines: &mut Vec<Bounds>) {
        loop {
            let mut grown = false;
            for i in 0..scales.len() {
                if self.extents[i].size() == 0.0 {
                    continue;
                }
                let mut trial = scales.clone();
                trial[i] = finer_nice(scales[i]);
                if let Some(o) = self.pack_in(order, &trial, packing) {
                    *scales = trial;
                    *outlines = o;
                    grown = true;
                }
            }
            if !grown {
                return;
            }
        }
    }
}

/// The orders a forces page tries its `n` figures in: solving order first, then every
/// other permutation while there are few enough ([`REORDERED_FIGURES_MAX`]) to try them all.
fn figure_orders(n: usize) -> Vec<Vec<usize>> {
    let identity: Vec<usize> = (0..n).collect();
    let mut orders = vec![identity.clone()];
    if n > REORDERED_FIGURES_MAX {
        return orders;
    }
    // Heap's algorithm, the identity left out (it is first already).
    let mut a = identity.clone();
    let mut c = vec![0usize; n];
    let mut i = 1;
    while i < n {
        if c[i] < i {
            if i % 2 == 0 {
                a.swap(0, i);
            } else {
                a.swap(c[i], i);
            }
            orders.push(a.clone());
            c[i] += 1;
            i = 1;
        } else {
            c[i] = 0;
            i += 1;
        }
    }
    orders
}

/// The most force figures on one page whose orders are all tried (6! = 720 packings).
const REORDERED_FIGURES_MAX: usize = 6;

/// The most steps a forces page coarsens its figures by (per figure, on the average) before
/// it draws them packed anyway.
const COARSENED_STEPS_PER_FIGURE: usize = 3;

/// The next coarser nice scale than `k` (1, 2, 2.5, 5 × 10ᵏ).
fn coarser_nice(k: f64) -> f64 {
    let mag = libm::pow(10f64, libm::log10(k).floor());
    [1.0, 2.0, 2.5, 5.0, 10.0].iter().map(|m| m * mag).find(|x| *x > k * (1.0 + 1e-9)).unwrap_or(2.0 * k)
}

/// The next finer nice scale than `k` (1, 2, 2.5, 5 × 10ᵏ).
fn finer_nice(k: f64) -> f64 {
    let mag = libm::pow(10f64, libm::log10(k).floor());
    [5.0, 2.5, 2.0, 1.0, 0.5].iter().map(|m| m * mag).find(|x| *x < k * (1.0 - 1e-9)).unwrap_or(0.5 * k)
}

/// The outline a force figure of physical extent `e` takes at `k` with its caption and k_f
/// as title: the drawn figure, room for its names, the title band and the bar strip.
fn cell_size(k: f64, e: &Extent, caption: &str, sizes: Sizes) -> Vector {
    let drawn = e.sides() / k;
    let room = 2.0 * LETTER_ROOM * sizes.text;
    let title = format!("{caption}   {}", scale_line("k_f", k, "N"));
    // Panel::of_outline's margins: 1.5 letters each side, 2.95 letters of title band, the bar
    // strip at the foot.
    let w = (drawn.x + room + 3.0 * sizes.text)
        .max(crate::draw::parts::widest_text_width(&title, sizes.text) + 1.2 * sizes.text);
    let h = drawn.y + room + 2.95 * sizes.text + 1.5 * sizes.text + scale_bar_room(sizes);
    Vector::new(w, h)
}

/// Whether a force figure of physical extent `e` drawn at `k` fits the panel framed by
/// `outline` as [`Panel::of_outline`] lays it out: the drawn figure with room for its names
/// inside the panel's area, its title (caption and k_f) across the panel's width.
fn fits_panel(k: f64, e: &Extent, caption: &str, outline: Bounds, sizes: Sizes) -> bool {
    let area = Panel::of_outline(outline, sizes).area;
    let drawn = e.sides() / k;
    let room = 2.0 * LETTER_ROOM * sizes.text;
    let title = format!("{caption}   {}", scale_line("k_f", k, "N"));
    let title_w = crate::draw::parts::widest_text_width(&title, sizes.text) + 1.2 * sizes.text;
    drawn.x + room <= area.width() + 1e-9 && drawn.y + room <= area.height() + 1e-9 && title_w <= outline.width() + 1e-9
}

/// The cell of a table of `rows` rows (and a header) in `sets` sets of three columns side by
/// side, as [`sheet::table_sets`] lays it out.
fn table_cell(rows: usize, sets: usize, s: Sizes) -> Vector {
    let pad = 0.6 * s.text;
    let w = sets as f64 * sheet::TABLE_COLUMN_MIN * s.text * 3.0 + 2.0 * pad + 1e-6;
    let h = (rows.div_ceil(sets) + 1) as f64 * sheet::TABLE_ROW * s.text + 2.0 * pad + 1e-6;
    Vector::new(w, h)
}

/// Cells of `sizes` in rows from the top left of `border`, a row whose foot comes down to the
/// title block (its top at `title.max.y`) ending left of it (at `right`); `None` when they do
/// not fit.
fn pack(sizes: &[Vector], border: Bounds, right: f64, title: Bounds) -> Option<Vec<Bounds>> {
    let mut out = Vec::with_capacity(sizes.len());
    let (mut x, mut top, mut row_h) = (border.min.x, border.max.y, 0.0f64);
    let mut row_start = 0;
    for (i, size) in sizes.iter().enumerate() {
        if size.x > border.width() {
            return None;
        }
        if x > border.min.x && x + size.x > border.max.x {
            top -= row_h;
            x = border.min.x;
            row_h = 0.0;
            row_start = i;
        }
        row_h = row_h.max(size.y);
        out.push(Bounds { min: Point::new(x, top - size.y), max: Point::new(x + size.x, top) });
        x += size.x;
        // The row so far must clear the title block where it comes down to it.
        if top - row_h < title.max.y - 1e-9 && out[row_start..].iter().any(|b| b.max.x > right + 1e-9) {
            return None;
        }
        if top - row_h < border.min.y - 1e-9 {
            return None;
        }
    }
    Some(out)
}

/// Stretches packed cells (rows from the top left, as [`pack`] lays them) to use the page:
/// each row's cells as tall as its tallest, its spare width shared among its cells, and
/// the last row down to the border's foot (or to the title block's top where it stands over
/// it), for cells that [`pack`] laid out on the page. No cell gets smaller than it was
/// packed: a row that would stays as packed.
/// No page with a third of it empty beside uneven panels (the four-bar's forces page).
fn fill(cells: &mut [Bounds], border: Bounds, right: f64, title: Bounds) {
    let mut rows: Vec<(f64, Vec<usize>)> = Vec::new();
    for (i, c) in cells.iter().enumerate() {
        match rows.iter_mut().find(|(top, _)| (top - c.max.y).abs() <= 1e-9) {
            Some((_, members)) => members.push(i),
            None => rows.push((c.max.y, vec![i])),
        }
    }
    // The cells may come in another order than packed (the figures' own): rows from the
    // top, each from the left.
    rows.sort_by(|a, b| b.0.total_cmp(&a.0));
    for (_, members) in &mut rows {
        members.sort_by(|&i, &j| cells[i].min.x.total_cmp(&cells[j].min.x));
    }
    let n = rows.len();
    for (r, (top, members)) in rows.iter().enumerate() {
        let foot = if r + 1 == n {
            border.min.y
        } else {
            members.iter().map(|&i| cells[i].min.y).fold(f64::INFINITY, f64::min)
        };
        // A row that comes down to the title block ends left of it.
        let over_title = foot < title.max.y - 1e-9;
        let (foot, end) = if r + 1 == n {
            // The last row: beside the title block down to the border, else over it.
            let clears = members.iter().all(|&i| cells[i].max.x <= right + 1e-9);
            if clears { (border.min.y, right) } else { (title.max.y, border.max.x) }
        } else {
            (foot, if over_title { right } else { border.max.x })
        };
        let used: f64 = members.iter().map(|&i| cells[i].width()).sum();
        let spread = |end: f64, foot_of: &dyn Fn(f64) -> f64| -> Vec<Bounds> {
            let spare = (end - border.min.x - used).max(0.0) / members.len() as f64;
            let mut x = border.min.x;
            members
                .iter()
                .map(|&i| {
                    let w = cells[i].width() + spare;
                    let b = Bounds { min: Point::new(x, foot_of(x + w)), max: Point::new(x + w, *top) };
                    x += w;
                    b
                })
                .collect()
        };
        // The last row across the whole width, its cells over the title block ending at its
        // top, when none of them gets shorter than it was packed (the four-bar's two tall
        // figures), else as above.
        let across = (r + 1 == n)
            .then(|| spread(border.max.x, &|x_end| if x_end <= right + 1e-9 { border.min.y } else { title.max.y }));
        let keeps = |a: &[Bounds]| {
            members
                .iter()
                .zip(a)
                .all(|(&i, b)| b.height() >= cells[i].height() - 1e-9 && b.width() >= cells[i].width() - 1e-9)
        };
        let placed = match across {
            Some(a) if keeps(&a) => a,
            _ => spread(end, &|_| foot),
        };
        // A row that would get a cell smaller than it was packed (packed past the border or
        // into the title block: a page that does not hold its figures) stays as packed.
        if !keeps(&placed) {
            continue;
        }
        for (&i, b) in members.iter().zip(placed) {
            cells[i] = b;
        }
    }
}

/// The cells in rows from the top left, whether or not they fit.
fn pack_anyway(sizes: &[Vector], border: Bounds) -> Vec<Bounds> {
    let (mut x, mut top, mut row_h) = (border.min.x, border.max.y, 0.0f64);
    sizes
        .iter()
        .map(|size| {
            if x > border.min.x && x + size.x > border.max.x {
                top -= row_h;
                x = border.min.x;
                row_h = 0.0;
            }
            row_h = row_h.max(size.y);
            let b = Bounds { min: Point::new(x, top - size.y), max: Point::new(x + size.x, top) };
            x += size.x;
            b
        })
        .collect()
}

/// Cells of `sizes` packed by the skyline from the top of `border`: each, in turn, at the
/// left end of a stretch of the skyline (the feet of the cells above, or the border's top)
/// where its foot comes highest (leftmost on a tie), inside the border and clear of the
/// title block (its top at `title.max.y`, its left edge at `right`): a column of two figures
/// beside a tall one, the table beside or under them. `None` when they do not fit.
fn pack_skyline(sizes: &[Vector], border: Bounds, right: f64, title: Bounds) -> Option<Vec<Bounds>> {
    const EPS: f64 = 1e-9;
    // The skyline: stretches (x from, x to, the level free below), left to right.
    let mut sky: Vec<(f64, f64, f64)> = vec![(border.min.x, border.max.x, border.max.y)];
    let mut out = Vec::with_capacity(sizes.len());
    for size in sizes {
        let mut best: Option<(f64, f64)> = None;
        for &(x, _, _) in &sky {
            let end = x + size.x;
            if end > border.max.x + EPS {
                break;
            }
            let top =
                sky.iter().filter(|s| s.0 < end - EPS && s.1 > x + EPS).map(|s| s.2).fold(f64::INFINITY, f64::min);
            let foot = top - size.y;
            let off_title = end <= right + EPS || foot >= title.max.y - EPS;
            if foot >= border.min.y - EPS && off_title && best.is_none_or(|(f, _)| foot > f + EPS) {
                best = Some((foot, x));
            }
        }
        let (foot, x) = best?;
        let end = x + size.x;
        out.push(Bounds { min: Point::new(x, foot), max: Point::new(end, foot + size.y) });
        // The stretches under the cell cut away, the cell's foot put in their place.
        let mut next: Vec<(f64, f64, f64)> = Vec::with_capacity(sky.len() + 2);
        for &(a, b, level) in &sky {
            if b <= x + EPS || a >= end - EPS {
                next.push((a, b, level));
                continue;
            }
            if a < x - EPS {
                next.push((a, x, level));
            }
            if b > end + EPS {
                next.push((end, b, level));
            }
        }
        next.push((x, end, foot));
        next.sort_by(|p, q| p.0.total_cmp(&q.0));
        sky.clear();
        for s in next {
            match sky.last_mut() {
                Some(last) if (last.2 - s.2).abs() <= EPS => last.1 = s.1,
                _ => sky.push(s),
            }
        }
    }
    Some(out)
}

/// Stretches cells packed by [`pack_skyline`] into the free room beside and under them: each
/// cell's right edge out to the next cell on its right (or the border, or the title block's
/// left edge where the cell comes down beside it), then each cell's foot down to the next
/// cell under it (or the border's foot, or the title block's top where the cell stands over
/// it). No cell gets smaller, none overlaps another.
fn spread_into_free(cells: &mut [Bounds], border: Bounds, right: f64, title: Bounds) {
    const EPS: f64 = 1e-9;
    for i in 0..cells.len() {
        let c = cells[i];
        let mut end = if c.min.y < title.max.y - EPS { right } else { border.max.x };
        for (j, b) in cells.iter().enumerate() {
            if j != i && b.min.y < c.max.y - EPS && b.max.y > c.min.y + EPS && b.min.x >= c.max.x - EPS {
                end = end.min(b.min.x);
            }
        }
        cells[i].max.x = end.max(c.max.x);
    }
    for i in 0..cells.len() {
        let c = cells[i];
        let mut foot = if c.max.x > right + EPS { title.max.y } else { border.min.y };
        for (j, b) in cells.iter().enumerate() {
            if j != i && b.min.x < c.max.x - EPS && b.max.x > c.min.x + EPS && b.max.y <= c.min.y + EPS {
                foot = foot.max(b.max.y);
            }
        }
        cells[i].min.y = foot.min(c.min.y);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coarser_and_finer_nice_scales_step_through_the_series() {
        let series = [0.5, 1.0, 2.0, 2.5, 5.0, 10.0, 20.0, 25.0, 50.0];
        for w in series.windows(2) {
            assert!((coarser_nice(w[0]) - w[1]).abs() <= 1e-12 * w[1], "{} → {}", w[0], coarser_nice(w[0]));
            assert!((finer_nice(w[1]) - w[0]).abs() <= 1e-12 * w[1], "{} → {}", w[1], finer_nice(w[1]));
        }
    }

    #[test]
    fn a_page_tries_its_figures_in_solving_order_first_then_every_other_order() {
        for n in 0..=REORDERED_FIGURES_MAX + 1 {
            let orders = figure_orders(n);
            assert_eq!(orders[0], (0..n).collect::<Vec<_>>());
            let want = if n > REORDERED_FIGURES_MAX { 1 } else { (1..=n).product::<usize>() };
            assert_eq!(orders.len(), want, "{n} figures");
            let distinct: std::collections::BTreeSet<&Vec<usize>> = orders.iter().collect();
            assert_eq!(distinct.len(), orders.len(), "{n} figures: an order twice");
        }
    }

    #[test]
    fn a_force_figure_is_drawn_one_to_two_minimum_lengths_long() {
        for i in 0..2000 {
            let size = libm::pow(10.0, -2.0 + i as f64 * 0.004);
            let k = force_figure_scale(size);
            let drawn = size / k;
            assert!((FORCE_FIGURE_MIN_MM - 1e-9..2.0 * FORCE_FIGURE_MIN_MM + 1e-9).contains(&drawn), "{size}: {drawn}");
            let m = k / libm::pow(10.0, libm::log10(k).floor());
            assert!([1.0, 2.0, 2.5, 5.0].iter().any(|n| (m - n).abs() < 1e-9), "{k}");
        }
    }

    /// A closed triangle of forces `w` × `h` N (its extent).
    fn triangle(w: f64, h: f64) -> ForcePolygon {
        use crate::figure::shared::forces::NamedVector;
        let chain = vec![
            NamedVector::new("F1", Vector::new(w, 0.0)),
            NamedVector::new("F2", Vector::new(-w, h)),
            NamedVector::new("R3", Vector::new(0.0, -h)),
        ];
        ForcePolygon { pole: "f".into(), chain, resultants: Vec::new(), found: 0 }
    }

    /// Figure sets from one to more than a page holds, of every shape: tall, wide, square.
    fn figure_sets() -> Vec<Vec<ForcePolygon>> {
        let mut out = Vec::new();
        for n in 1..=9 {
            for shape in 0..4 {
                let set = (0..n)
                    .map(|i| {
                        let a = 1.0 + 0.37 * ((i * 7 + shape * 3) % 5) as f64;
                        match shape {
                            0 => triangle(10.0 * a, 40.0),
                            1 => triangle(40.0, 10.0 * a),
                            2 => triangle(25.0 * a, 25.0),
                            _ => triangle(3.0 + 50.0 * (i % 2) as f64, 20.0 * a),
                        }
                    })
                    .collect();
                out.push(set);
            }
        }
        out
    }

    /// The cells of `set`'s figures at their least-size scales on `paper`.
    fn least_cells(set: &[ForcePolygon], paper: Paper) -> Vec<Vector> {
        set.iter()
            .map(|f| {
                let e = Extent::of(f.physical_points()).unwrap();
                cell_size(force_figure_scale(e.size()), &e, "Dyad 2–3 (RRR)", paper.sizes())
            })
            .collect()
    }

    #[test]
    fn stretching_never_makes_a_cell_smaller_than_it_was_packed() {
        for paper in [Paper::A4, Paper::A3] {
            let (_, border, right, title) = sheet::page_frame(paper, 6);
            for set in figure_sets() {
                // As packed (or packed anyway, past the border, when the page does not hold
                // them): sizes of every kind of figure cell.
                let mut sizes: Vec<Vector> = least_cells(&set, paper);
                // And the forces' table after them (a linkage's), in the last row.
                if set.len() % 2 == 1 {
                    sizes.push(table_cell(14 + set.len(), 1, paper.sizes()));
                }
                // (A page that does not hold them is not stretched: ForcesPage::new.)
                let Some(packed) = pack(&sizes, border, right, title) else { continue };
                let mut cells = packed.clone();
                fill(&mut cells, border, right, title);
                for (c, p) in cells.iter().zip(&packed) {
                    assert!(c.width() >= p.width() - 1e-9 && c.height() >= p.height() - 1e-9, "{c:?} < {p:?}");
                }
                assert_laid_out(&cells, border, title);
            }
        }
    }

    #[test]
    fn every_force_figure_is_drawn_inside_its_final_panel_at_the_k_f_its_title_prints() {
        for paper in [Paper::A4, Paper::A3] {
            for set in figure_sets() {
                let captions: Vec<String> =
                    (0..set.len()).map(|i| format!("Dyad {}–{} (RRP)", 2 * i + 2, 2 * i + 3)).collect();
                let rows = if set.len() % 2 == 1 { 14 + set.len() } else { 0 };
                let page = ForcesPage::new(paper, &set, &captions, 4, rows);
                let s = page.layout.sizes;
                // The forces' table (a linkage's) beside or over the title block, never on it.
                let (t, tb) = (page.layout.table, page.layout.title);
                let on_title =
                    (t.max.x.min(tb.max.x) - t.min.x.max(tb.min.x)).min(t.max.y.min(tb.max.y) - t.min.y.max(tb.min.y));
                let border = page.layout.border;
                let held = page.layout.panels.iter().all(|p| {
                    p.outline.min.x >= border.min.x - 1e-9
                        && p.outline.max.x <= border.max.x + 1e-9
                        && p.outline.min.y >= border.min.y - 1e-9
                });
                // Every page holds its figures: one that cannot at their least-size scales
                // draws the largest coarser.
                assert!(held, "{} figures on {}: a panel past the border", set.len(), paper.name());
                assert!(rows == 0 || on_title <= 1e-9, "the table {t:?} on the title block {tb:?}");
                for ((f, (k, pole)), panel) in set.iter().zip(&page.places).zip(&page.layout.panels) {
                    // (How small a figure gets on a crowded page is bounded on the templates'
                    // pages, tests/sheet_sizes.rs: 60 mm but at 5 positions, never under 50.)
                    // Every vertex drawn inside the panel's area, LETTER_ROOM letters from its
                    // edges.
                    let room = LETTER_ROOM * s.text - 1e-9;
                    for v in f.vertices() {
                        let p = pole + v / *k;
                        let a = panel.area;
                        assert!(
                            p.x >= a.min.x + room
                                && p.x <= a.max.x - room
                                && p.y >= a.min.y + room
                                && p.y <= a.max.y - room,
                            "{p:?} outside {a:?} at k_f = {k} ({} figures on {})",
                            set.len(),
                            paper.name()
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn the_skyline_keeps_cells_apart_inside_the_border_and_off_the_title_block_and_stretching_shrinks_none() {
        for paper in [Paper::A4, Paper::A3] {
            let (_, border, right, title) = sheet::page_frame(paper, 6);
            let mut packed_sets = 0;
            for set in figure_sets() {
                let mut sizes: Vec<Vector> = least_cells(&set, paper);
                sizes.push(table_cell(14 + set.len(), 1 + set.len() % 3, paper.sizes()));
                let Some(packed) = pack_skyline(&sizes, border, right, title) else { continue };
                packed_sets += 1;
                let mut cells = packed.clone();
                spread_into_free(&mut cells, border, right, title);
                for ((c, p), size) in cells.iter().zip(&packed).zip(&sizes) {
                    assert!((p.width() - size.x).abs() <= 1e-9 && (p.height() - size.y).abs() <= 1e-9, "{p:?}");
                    assert!(c.min.x <= p.min.x + 1e-9 && c.min.y <= p.min.y + 1e-9, "{c:?} < {p:?}");
                    assert!(c.max.x >= p.max.x - 1e-9 && c.max.y >= p.max.y - 1e-9, "{c:?} < {p:?}");
                }
                assert_laid_out(&cells, border, title);
            }
            assert!(packed_sets >= 10, "{packed_sets} sets packed on {}", paper.name());
        }
    }

    /// Cells inside the border, off the title block, none on another.
    fn assert_laid_out(cells: &[Bounds], border: Bounds, title: Bounds) {
        for (i, c) in cells.iter().enumerate() {
            assert!(overlap(c, &title) <= 1e-9, "{c:?} over the title block {title:?}");
            assert!(c.min.x >= border.min.x - 1e-9 && c.max.x <= border.max.x + 1e-9, "{c:?}");
            assert!(c.min.y >= border.min.y - 1e-9 && c.max.y <= border.max.y + 1e-9, "{c:?}");
            for b in &cells[i + 1..] {
                assert!(overlap(c, b) <= 1e-9, "{c:?} overlaps {b:?}");
            }
        }
    }

    /// How far two boxes overlap (their overlap's smaller side; ≤ 0 when apart).
    fn overlap(a: &Bounds, b: &Bounds) -> f64 {
        (a.max.x.min(b.max.x) - a.min.x.max(b.min.x)).min(a.max.y.min(b.max.y) - a.min.y.max(b.min.y))
    }

    #[test]
    fn a_column_of_two_figures_beside_a_tall_one_holds_what_rows_cannot_at_60_mm() {
        // The shaper's forces page at t = 0.5694 s on A4: the crank's and dyad 2–3's figures
        // about 1500 N wide (k_f = 20 N/mm, 75 mm), dyad 4–5's 577 × 500 N (k_f = 5 N/mm,
        // 115 mm: the next nice scale, 10, would draw it 57.7 mm), and a table of 19 rows.
        let set = [triangle(1500.0, 900.0), triangle(1480.0, 716.0), triangle(577.0, 500.0)];
        let captions: Vec<String> =
            ["Crank 1 (driver)", "Dyad 2–3 (RPR)", "Dyad 4–5 (RRP)"].iter().map(|c| c.to_string()).collect();
        let (sizes, border, right, title) = sheet::page_frame(Paper::A4, 6);
        let extents: Vec<Extent> = set.iter().map(|f| Extent::of(f.physical_points()).unwrap()).collect();
        let cells = FigureCells { extents: &extents, captions: &captions, sizes, border, right, title, table_rows: 19 };
        let least: Vec<f64> = extents.iter().map(|e| force_figure_scale(e.size())).collect();
        let orders = figure_orders(3);
        // In rows they fit in no order (the page drew dyad 4–5 at 57 mm before).
        assert!(orders.iter().all(|o| cells.pack_in(o, &least, Packing::Shelves).is_none()));
        let (_, held) = cells.held_scales();
        assert_eq!(held.map(|h| h.1), Some(Packing::Skyline));
        let page = ForcesPage::new(Paper::A4, &set, &captions, 6, 19);
        for ((k, _), e) in page.places.iter().zip(&extents) {
            assert!(e.size() / k >= FORCE_FIGURE_MIN_MM - 1e-9, "{} mm at k_f = {k}", e.size() / k);
        }
        let mut all: Vec<Bounds> = page.layout.panels.iter().map(|p| p.outline).collect();
        all.push(page.layout.table);
        for (i, a) in all.iter().enumerate() {
            assert!(overlap(a, &page.layout.title) <= 1e-9, "{a:?} over the title block");
            for b in &all[i + 1..] {
                assert!(overlap(a, b) <= 1e-9, "{a:?} overlaps {b:?}");
            }
        }
    }

    #[test]
    fn a_detail_panel_is_as_large_as_its_content_and_the_room_it_leaves_goes_to_the_mechanism_and_the_table() {
        // triad-driven on A4: 154.7 × 95.2 mm of motion, its crank's detail 77.5 × 84.9 mm,
        // a table of 7 rows.
        let (lo, hi) = (Vector::new(-20.0, -10.0), Vector::new(134.7, 85.2));
        let room = Vector::new(6.0, 5.5);
        let detail = Vector::new(77.5, 84.9);
        let plain = MechanismPage::new(Paper::A4, lo, hi, room, 7, 6);
        for (rows, size) in [(7, detail), (7, Vector::new(60.0, 70.0)), (30, detail), (7, Vector::new(95.0, 120.0))] {
            let page = MechanismPage::with_detail(Paper::A4, (lo, hi), room, (rows, 6), size);
            let l = &page.layout;
            let (main, dt) = (l.panels[0].outline, l.panels[1].outline);
            // The detail's panel its content's size, not a strip the page's height.
            assert!((dt.height() - size.y).abs() <= 1e-9 && dt.width() >= size.x - 1e-9, "{dt:?} for {size:?}");
            // Nothing on anything else, everything inside the border.
            let all = [main, dt, l.table, l.title];
            for (i, a) in all.iter().enumerate() {
                assert!(a.min.x >= l.border.min.x - 1e-9 && a.max.x <= l.border.max.x + 1e-9, "{a:?}");
                assert!(a.min.y >= l.border.min.y - 1e-9 && a.max.y <= l.border.max.y + 1e-9, "{a:?}");
                for b in &all[i + 1..] {
                    assert!(overlap(a, b) <= 1e-9, "{a:?} on {b:?}");
                }
            }
            // The table holds its rows where it is.
            let table_h = (rows + 1) as f64 * sheet::TABLE_ROW * l.sizes.text + 1.2 * l.sizes.text;
            let sets = sheet::table_sets(l.table, rows, 3, l.sizes);
            assert!(((rows.div_ceil(sets) + 1) as f64 * sheet::TABLE_ROW * l.sizes.text) <= l.table.height(), "{rows}");
            assert!(sets == 1 || l.table.height() < table_h, "{rows} rows in {sets} sets");
        }
        // Here the mechanism keeps its scale and gets a taller panel than it had with the
        // detail a strip the page's height (151 mm), the table under the detail.
        let page = MechanismPage::with_detail(Paper::A4, (lo, hi), room, (7, 6), detail);
        assert_eq!(page.k_l, plain.k_l);
        assert!(page.layout.panels[0].outline.height() > 160.0, "{:?}", page.layout.panels[0].outline);
        assert!(page.layout.table.max.y <= page.layout.panels[1].outline.min.y + 1e-9);
        assert!(page.layout.table.min.x >= page.layout.panels[1].outline.min.x - 1e-9);
    }

    #[test]
    fn a_long_low_mechanism_goes_above_its_table() {
        // 715 × 220 mm of motion (a slider-crank) on A4: above the table it is drawn at 1:4,
        // beside it at 1:5.
        let page = MechanismPage::new(
            Paper::A4,
            Vector::new(-110.0, -110.0),
            Vector::new(605.0, 110.0),
            Vector::new(8.0, 8.0),
            12,
            4,
        );
        assert_eq!(page.k_l, 4.0);
        assert!(page.layout.panels[0].outline.width() > 250.0);
        // A tall one beside it.
        // A tall one beside it: the Chebyshev four-bar (m), crank 0.04 m at 1:1.5, 26.7 mm.
        let page = MechanismPage::new(
            Paper::A4,
            Vector::new(-0.04, -0.04),
            Vector::new(0.174, 0.196),
            Vector::new(8.0, 8.0),
            30,
            4,
        );
        assert!(page.layout.panels[0].outline.width() < 170.0, "{:?}", page.layout.panels[0]);
        assert!((page.k_l - 0.0015).abs() < 1e-15, "{}", page.k_l);
    }
}
