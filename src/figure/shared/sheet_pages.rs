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
//!    that), captioned with its k_f and with its own scale bar, packed in rows; a linkage's
//!    table of forces (every applied force, every reaction) packed after them, so that the mechanism page's table holds the kinematics only.
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
        Self::laid_out(paper, (lo, hi), room, (table_rows, title_cells), 0.0)
    }

    /// [`MechanismPage::new`] with a detail panel `width` mm wide at the right of the
    /// mechanism's panel, as high as it (panel 1 of the layout): the mechanism drawn in what
    /// is left, at the scale that fits it there.
    pub fn with_detail(
        paper: Paper,
        (lo, hi): (Vector, Vector),
        room: Vector,
        (table_rows, title_cells): (usize, usize),
        width: f64,
    ) -> Self {
        Self::laid_out(paper, (lo, hi), room, (table_rows, title_cells), width)
    }

    /// The page, with `aside` mm at the right of the mechanism's panel for a detail panel
    /// (none for 0).
    fn laid_out(
        paper: Paper,
        (lo, hi): (Vector, Vector),
        room: Vector,
        (table_rows, title_cells): (usize, usize),
        aside: f64,
    ) -> Self {
        let (sizes, border, right, title) = sheet::page_frame(paper, title_cells);
        // The mechanism's part of a panel (the detail's strip taken off its right).
        let main = |b: Bounds| Bounds { min: b.min, max: Point::new(b.max.x - aside, b.max.y) };
        let extent = (hi - lo).sup(&Vector::new(1e-300, 1e-300));
        let beside = (
            Bounds { min: border.min, max: Point::new(right, border.max.y) },
            Bounds { min: Point::new(right, title.max.y), max: border.max },
        );
        // Above the table: the table in one set of columns, or in two or three side by side
        // (a lower band, a taller panel).
        let above = |sets: usize| {
            let table_h =
                (table_rows.div_ceil(sets) + 1) as f64 * sheet::TABLE_ROW * sizes.text + 1.2 * sizes.text + 1e-9;
            let band = table_h.max(title.height()).min(TABLE_BAND_MAX * border.height());
            (
                Bounds { min: Point::new(border.min.x, border.min.y + band), max: border.max },
                Bounds { min: border.min, max: Point::new(right, border.min.y + band) },
            )
        };
        let scale_in = |panel: Bounds| {
            let area = Panel::of_outline(main(panel), sizes).area;
            let room = Vector::new(area.width(), area.height()) - 2.0 * room;
            drafting_scale((extent.x / room.x.max(1e-9)).max(extent.y / room.y.max(1e-9)))
        };
        // The arrangement that draws the mechanism largest; beside the table on a tie.
        let (mut panel, mut table) = beside;
        let mut k_l = scale_in(beside.0);
        for sets in [1, 2, 3] {
            let (p, t) = above(sets);
            let k = scale_in(p);
            if k < k_l * (1.0 - 1e-12) {
                (panel, table, k_l) = (p, t, k);
            }
        }
        let outline = Panel::of_outline(main(panel), sizes);
        let origin = sheet::centre(lo, hi, k_l, outline.area);
        let mut panels = vec![outline];
        if aside > 0.0 {
            let strip = Bounds { min: Point::new(panel.max.x - aside, panel.min.y), max: panel.max };
            panels.push(Panel::of_outline(strip, sizes));
        }
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
    /// `table_rows` rows after them, packed in rows from the top left, clear of the title
    /// block: each figure at the coarsest nice k_f that
    /// draws it [`FORCE_FIGURE_MIN_MM`] long, then, one figure after the other while the
    /// page still holds them, at the next finer one (larger figures where there is room).
    /// (The panels are not stretched to the page: stretching them with finer scales drew
    /// the shaper's dyad 4–5 out of its panel at t = 0.7472 s, tests/sheet_sizes.rs.)
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
        let mut scales: Vec<f64> = extents.iter().map(|e| force_figure_scale(e.size())).collect();
        let cell = |k: f64, e: &Extent, caption: &str| cell_size(k, e, caption, sizes);
        let cells_at = |scales: &[f64]| -> Vec<Vector> {
            scales.iter().zip(&extents).zip(captions).map(|((k, e), c)| cell(*k, e, c)).collect()
        };
        // The figures, then the table (when it has rows) as one more cell, in one to three
        // sets of columns: the first arrangement the page holds.
        let pack_at = |scales: &[f64]| {
            let cells = cells_at(scales);
            if table_rows == 0 {
                return pack(&cells, border, right, title);
            }
            (1..=3).find_map(|sets| {
                let mut all = cells.clone();
                all.push(table_cell(table_rows, sets, sizes));
                pack(&all, border, right, title)
            })
        };
        let mut outlines = pack_at(&scales);
        if outlines.is_some() {
            loop {
                let mut grown = false;
                for i in 0..scales.len() {
                    let finer = finer_nice(scales[i]);
                    if extents[i].size() == 0.0 {
                        continue;
                    }
                    let mut trial = scales.clone();
                    trial[i] = finer;
                    if let Some(o) = pack_at(&trial) {
                        scales = trial;
                        outlines = Some(o);
                        grown = true;
                    }
                }
                if !grown {
                    break;
                }
            }
        }
        let mut outlines = outlines.unwrap_or_else(|| {
            let mut cells = cells_at(&scales);
            if table_rows > 0 {
                cells.push(table_cell(table_rows, 1, sizes));
            }
            pack_anyway(&cells, border)
        });
        let table = if table_rows > 0 && outlines.len() > figures.len() {
            outlines.pop().unwrap_or(Bounds { min: title.max, max: title.max })
        } else {
            Bounds { min: title.max, max: title.max }
        };
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

#[cfg(test)]
mod tests {
    use super::*;

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
