//! A printed page per position (issue 14, item 3): A4 or A3 landscape, drawn in paper
//! millimetres (origin at the sheet's lower-left corner, y up), as a drawing office lays
//! out a sheet: a border (20 mm binding margin on the left, 10 mm elsewhere), a title block
//! in the lower right, a table of the position's values above it, and panels for the
//! figures in a grid on the left, each framed with its title and scale.
//!
//! This file knows no mechanism: a kind fills the title block, the table and the panels
//! (see `fourbar_sheet.rs`). Every figure on a sheet has its own "nice" scale
//! (1, 2, 2.5, 5 × 10ᵏ) chosen by [`fit`] so that it fills about two thirds of its panel
//! and never less than half of it.

use std::str::FromStr;

use crate::draw::{Bounds, DimStyle, Drawing, HAlign, Runs, Shape, VAlign};
use crate::geom::{Point, Vector};

use crate::figure::shared::vocab::{Sizes, content_drawing, nice_scale, scale_bar_room};

/// Thinnest stroke on a sheet, paper mm (frame lines, construction lines, pole circles).
pub const HAIRLINE_MM: f64 = 0.25;

/// The layer of the sheet's own lines and texts (border, title block, table, panel frames).
pub const SHEET_LAYER: crate::figure::shared::vocab::layers::Layer =
    ("SHEET", crate::draw::Aci::BLACK, crate::draw::LineType::Continuous);

/// Fraction of a panel's drawing area a figure should fill (its larger extent): "about two
/// thirds".
pub const TARGET_FILL: f64 = 2.0 / 3.0;

/// Above this fill a figure takes the next coarser nice scale when that still fills at
/// least half of the area (room for its letters).
pub const MAX_FILL: f64 = 0.85;

/// A paper size, landscape.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Paper {
    /// 297 × 210 mm.
    A4,
    /// 420 × 297 mm.
    A3,
}

impl Paper {
    /// Width and height, mm (landscape).
    pub fn size_mm(self) -> Vector {
        match self {
            Paper::A4 => Vector::new(297.0, 210.0),
            Paper::A3 => Vector::new(420.0, 297.0),
        }
    }

    /// `A4`, `A3`.
    pub fn name(self) -> &'static str {
        match self {
            Paper::A4 => "A4",
            Paper::A3 => "A3",
        }
    }

    /// The sheet in paper mm: (0, 0) to its width and height.
    pub fn bounds(self) -> Bounds {
        let s = self.size_mm();
        Bounds { min: Point::origin(), max: Point::new(s.x, s.y) }
    }

    /// Sizes of letters, arrows, links and joints on this paper, mm: 2.5 mm letters on A4,
    /// 3 mm on A3 (ISO 3098's 2.5 and 3.5 mm rows, between them).
    pub fn sizes(self) -> Sizes {
        let t = match self {
            Paper::A4 => 2.5,
            Paper::A3 => 3.0,
        };
        Sizes {
            text: t,
            head: t,
            link: 0.28 * t,
            joint: 0.45 * t,
            ground: 1.2 * t,
            slider_length: 2.5 * t,
            slider_height: 1.4 * t,
        }
    }
}

impl FromStr for Paper {
    type Err = String;
    fn from_str(s: &str) -> Result<Paper, String> {
        match s.to_ascii_lowercase().as_str() {
            "a4" => Ok(Paper::A4),
            "a3" => Ok(Paper::A3),
            _ => Err(format!("unknown paper `{s}`: use a4 (297 × 210 mm) or a3 (420 × 297 mm), landscape")),
        }
    }
}

/// A panel of a sheet: its frame and the area its figure is fitted in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Panel {
    /// The panel's frame (title included).
    pub outline: Bounds,
    /// Where the figure goes: the frame less the title band and a margin of a letter and
    /// a half for the figure's letters.
    pub area: Bounds,
}

impl Panel {
    /// The panel framed by `outline`, for letters of `sizes`: its figure's area is the
    /// frame less a title band of 2.2 letter heights at the top, a margin of 1.5 letter
    /// heights on every side (for the figure's letters) and, at the foot, the strip of its
    /// scale bar ([`Panel::bar_at`]).
    pub fn of_outline(outline: Bounds, sizes: Sizes) -> Panel {
        let (band, margin) = (2.2 * sizes.text, 1.5 * sizes.text);
        let area = Bounds {
            min: outline.min + Vector::new(margin, margin + scale_bar_room(sizes)),
            max: outline.max - Vector::new(margin, band + 0.5 * margin),
        };
        Panel { outline, area }
    }

    /// The left end of the panel's scale bar: in the strip at its foot, clear of the frame.
    pub fn bar_at(&self, sizes: Sizes) -> Point {
        let h = sizes.small_text();
        Point::new(self.outline.min.x + 2.5 * h, self.outline.min.y + 0.5 * sizes.text + 0.5 * scale_bar_room(sizes))
    }
}

/// Where everything goes on a sheet.
#[derive(Debug, Clone, PartialEq)]
pub struct SheetLayout {
    /// The paper.
    pub paper: Paper,
    /// Sizes of the drawn details, mm.
    pub sizes: Sizes,
    /// The border.
    pub border: Bounds,
    /// The panels, row by row from the top left.
    pub panels: Vec<Panel>,
    /// The value table's box (right column, above the title block).
    pub table: Bounds,
    /// The title block's box (lower right).
    pub title: Bounds,
}

/// Rows of the title block: its name row, then the other cells two per row.
fn title_rows(cells: usize) -> usize {
    1 + cells.div_ceil(2)
}

/// The border, the right column's left edge and the title block of a page on `paper` with
/// `title_cells` cells besides the title block's name row: (sizes, border, right, title).
pub(crate) fn page_frame(paper: Paper, title_cells: usize) -> (Sizes, Bounds, f64, Bounds) {
    let size = paper.size_mm();
    let sizes = paper.sizes();
    let border = Bounds { min: Point::new(20.0, 10.0), max: Point::new(size.x - 10.0, size.y - 10.0) };
    let column = match paper {
        Paper::A4 => 100.0,
        Paper::A3 => 130.0,
    };
    let row = 2.4 * sizes.text;
    let title_h = 1.4 * row + (title_rows(title_cells) - 1) as f64 * row;
    let right = border.max.x - column;
    let title = Bounds { min: Point::new(right, border.min.y), max: Point::new(border.max.x, border.min.y + title_h) };
    (sizes, border, right, title)
}

impl SheetLayout {
    /// The layout of a sheet on `paper` with `panels` panels (1 or 2 in a row, more in two
    /// columns) and a title block of `title_cells` cells besides its name row.
    pub fn new(paper: Paper, panels: usize, title_cells: usize) -> SheetLayout {
        let (sizes, border, right, title) = page_frame(paper, title_cells);
        let table = Bounds { min: Point::new(right, title.max.y), max: border.max };
        let n = panels.max(1);
        let cols = if n <= 2 { n } else { 2 };
        let rows = n.div_ceil(cols);
        let (w, h) = ((right - border.min.x) / cols as f64, (border.max.y - border.min.y) / rows as f64);
        let panels = (0..n)
            .map(|i| {
                let (r, c) = (i / cols, i % cols);
                let min = Point::new(border.min.x + c as f64 * w, border.max.y - (r + 1) as f64 * h);
                Panel::of_outline(Bounds { min, max: min + Vector::new(w, h) }, sizes)
            })
            .collect();
        SheetLayout { paper, sizes, border, panels, table, title }
    }
}

/// What the title block says.
#[derive(Debug, Clone, PartialEq)]
pub struct TitleBlock {
    /// The drawing's name (the scene's name), in large letters.
    pub name: String,
    /// What it shows (`four-bar`), beside the name.
    pub subject: String,
    /// The position (`φ_1 = 90°`, `t = 0.25 s`), the first cell, in larger letters. The
    /// position and the cells are marked up with `_` before a subscript
    /// ([`crate::draw::Runs::underscored`]: the `_` is not drawn).
    pub position: String,
    /// Further cells (`ω_1 = 20 rad/s`, `k_l = 0.002 m/mm`, …), two per row.
    pub cells: Vec<String>,
    /// This sheet's number (from 1) and the number of sheets.
    pub sheet: (usize, usize),
}

impl TitleBlock {
    /// Cells besides the name row, the sheet number included.
    pub fn cell_count(&self) -> usize {
        self.cells.len() + 2
    }
}

/// A table of values: a header and rows of texts, the first column a name, the last a
/// unit, numbers between them right-aligned.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Table {
    /// Column headings.
    pub header: Vec<String>,
    /// Rows, each as many cells as the header.
    pub rows: Vec<Vec<String>>,
    /// How each row's name (its first cell) is drawn: a quantity's symbol with its
    /// subscript (`RAn` as R_An, [`crate::figure::shared::labels::Label::quantity`]), a
    /// point's or a user's load name flat. A row past its end reads its cells as `_`
    /// markup ([`Runs::underscored`]), as the header does.
    pub names: Vec<Runs>,
}

impl Table {
    /// The rows whose `keep` holds, with their names' runs, under the same header.
    pub fn filter(&self, keep: impl Fn(&[String]) -> bool) -> Table {
        let mut t = Table { header: self.header.clone(), rows: Vec::new(), names: Vec::new() };
        for (i, r) in self.rows.iter().enumerate() {
            if keep(r) {
                t.rows.push(r.clone());
                t.names.push(self.names.get(i).cloned().unwrap_or_else(|| Runs::underscored(&r[0])));
            }
        }
        t
    }
}

/// A number as plain decimals rounded to `digits` significant digits (at least 1), trailing
/// zeros dropped, no exponent (`360.555` for 360.5551275 at 6; a whole number keeps all its
/// digits: `12000`).
pub fn significant(v: f64, digits: u32) -> String {
    if !v.is_finite() {
        return "–".into();
    }
    if v == 0.0 {
        return "0".into();
    }
    let decimals = (f64::from(digits.max(1)) - 1.0 - libm::floor(libm::log10(v.abs()))).clamp(0.0, 20.0) as usize;
    let s = format!("{v:.decimals$}");
    let s = if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.').to_string() } else { s };
    if s == "-0" { "0".into() } else { s }
}

/// A number for a drawing with `digits` significant digits and no e-notation: plain
/// decimals from 10⁻³ to 10⁶ ([`significant`]), else a power of ten written as the page
/// writes it (`1.32·10⁻¹⁰`, `2.5·10⁷`).
pub fn scientific(v: f64, digits: u32) -> String {
    if !v.is_finite() || v == 0.0 || (1e-3..1e6).contains(&v.abs()) {
        return significant(v, digits);
    }
    let mut exp = libm::floor(libm::log10(v.abs()));
    let mut mantissa = significant(v / libm::pow(10.0, exp), digits);
    // 9.999 rounded to 10: one more power of ten.
    if mantissa.trim_start_matches('-').starts_with("10") {
        exp += 1.0;
        mantissa = significant(v / libm::pow(10.0, exp), digits);
    }
    const SUPERSCRIPT: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let e = exp as i64;
    let mut power: String =
        e.unsigned_abs().to_string().chars().map(|c| SUPERSCRIPT[(c as u8 - b'0') as usize]).collect();
    if e < 0 {
        power.insert(0, '⁻');
    }
    format!("{mantissa}·10{power}")
}

/// A number for a drawing: 4 significant digits (what a graphical construction is read to;
/// a value of 1000 or more to the unit: 1833229), in decimals, never with an exponent,
/// trailing zeros kept so that columns align, a negative one with the minus sign −
/// (U+2212, as typeset; [`read_number`] reads it back).
pub fn number(v: f64) -> String {
    if !v.is_finite() {
        return "–".to_string();
    }
    if v == 0.0 {
        return "0".to_string();
    }
    let mag = libm::log10(v.abs()).floor();
    let decimals = (3.0 - mag).clamp(0.0, 20.0) as usize;
    let s = format!("{v:.decimals$}");
    if s.trim_start_matches('-').chars().all(|c| c == '0' || c == '.') { "0".to_string() } else { typeset_minus(s) }
}

/// `s` with a leading hyphen-minus, as Rust formats a negative number, written as the minus
/// sign − (U+2212): a drawing's numbers are typeset, as a textbook prints them.
pub fn typeset_minus(s: String) -> String {
    match s.strip_prefix('-') {
        Some(rest) => format!("−{rest}"),
        None => s,
    }
}

/// A number as a drawing prints it ([`number`], a plot's tick), read back: the minus sign −
/// read as `-`. `None` when `text` is not a number.
pub fn read_number(text: &str) -> Option<f64> {
    text.trim().replacen('−', "-", 1).parse().ok()
}

/// A figure's scale on a sheet: physical units per paper millimetre, and the fraction of
/// its panel's area the figure's larger extent fills at that scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fit {
    /// Physical units (m, m/s, N …) per paper millimetre: a nice value.
    pub per_mm: f64,
    /// The fraction of the area the figure fills in its tighter direction.
    pub fill: f64,
}

/// The scale for a figure of physical `extent` (width, height) in a panel `area` (paper
/// mm): the finest nice scale (1, 2, 2.5, 5 × 10ᵏ) at which it fits, which fills between
/// half and all of the area; the next coarser one when that fills more than [`MAX_FILL`]
/// and the coarser still fills at least half. A zero extent gets scale 1.
pub fn fit(extent: Vector, area: Vector) -> Fit {
    let first = finest(extent, area);
    let coarser = nice_scale(first.per_mm * (1.0 + 1e-9));
    let full = first.fill * first.per_mm;
    if first.fill > MAX_FILL && full / coarser >= 0.5 {
        return Fit { per_mm: coarser, fill: full / coarser };
    }
    first
}

/// The finest nice scale at which a figure of physical `extent` fits `area` (it fills more
/// than half of it): for a figure whose letters are already allowed for in `area`.
pub fn finest(extent: Vector, area: Vector) -> Fit {
    let full = (extent.x / area.x).max(extent.y / area.y);
    if !(full.is_finite() && full > 0.0) {
        return Fit { per_mm: 1.0, fill: 0.0 };
    }
    let per_mm = nice_scale(full);
    Fit { per_mm, fill: full / per_mm }
}

/// The fill of `area` (its tighter direction) by a figure of physical `extent` at `per_mm`
/// (physical units per paper mm; `area` in paper mm).
pub fn fill(extent: Vector, area: Vector, per_mm: f64) -> f64 {
    (extent.x / area.x).max(extent.y / area.y) / per_mm
}

/// The least fill of its area a figure keeps from frame to frame before it takes a finer
/// scale ([`frame_scales`]): half.
pub const MIN_FRAME_FILL: f64 = 0.5;

/// The scale of a figure at each frame of an animation (issue 31: every polygon readable at
/// every position), physical units per paper mm, for the figure's physical size `extents[k]`
/// (width, height; `None` or zero where nothing is drawn) at frame `k` in an area `area`
/// (paper mm): each frame keeps the previous frame's scale while the figure fills between
/// [`MIN_FRAME_FILL`] and all of the area at it, and else takes [`fit`]'s (a nice scale at
/// which it fills between half and all of it). The scale so changes in steps, and only
/// when it must (hysteresis: a figure that grows and shrinks a little about a step does not
/// make the animation flicker); a frame with nothing to draw keeps the last scale (1 before
/// any). The live page and the frames use this one choice ([`scale_near`] between frames).
pub fn frame_scales(extents: &[Option<Vector>], area: Vector) -> Vec<f64> {
    held_scales(&[], extents, area)
}

/// [`frame_scales`] after an earlier run of the same motion drawn at `previous[k]` at frame
/// `k` (the live page's picture before a field's slider moved; `None` or missing where it
/// drew nothing): each frame keeps its earlier scale while the figure fills between
/// [`MIN_FRAME_FILL`] and all of the area at it, so a polygon visibly grows and shrinks as
/// a length or a load changes, and takes another only when it would leave its area or
/// shrink under half of it; a frame without an earlier scale follows the frame before it,
/// as [`frame_scales`] does.
pub fn held_scales(previous: &[Option<f64>], extents: &[Option<Vector>], area: Vector) -> Vec<f64> {
    let mut out = Vec::with_capacity(extents.len());
    let mut last: Option<f64> = None;
    for (k, e) in extents.iter().enumerate() {
        let before = previous.get(k).copied().flatten().or(last);
        let scale = scale_near(before, *e, area);
        last = Some(scale);
        out.push(scale);
    }
    out
}

/// The scale of a figure of physical size `extent` in `area` (paper mm) after a frame drawn
/// at `previous` (see [`frame_scales`]): `previous` while the figure fills between
/// [`MIN_FRAME_FILL`] and all of the area at it, else [`fit`]'s.
pub fn scale_near(previous: Option<f64>, extent: Option<Vector>, area: Vector) -> f64 {
    let drawable = extent.filter(|e| e.x.is_finite() && e.y.is_finite() && e.x.max(e.y) > 0.0);
    match (previous, drawable) {
        (Some(k), None) => k,
        (None, None) => 1.0,
        (Some(k), Some(e)) if (MIN_FRAME_FILL..=1.0).contains(&fill(e, area, k)) => k,
        (_, Some(e)) => fit(e, area).per_mm,
    }
}

/// Where to put a figure's origin (its pole) so that the figure spanning `min`…`max`
/// (physical units, relative to the origin) at `per_mm` is centred in `area`.
pub fn centre(min: Vector, max: Vector, per_mm: f64, area: Bounds) -> Point {
    let mid = Point::from((area.min.coords + area.max.coords) / 2.0);
    mid - (min + max) / (2.0 * per_mm)
}

/// The sheet's fixed part on a drawing of its own: the border, the panel frames with their
/// `titles`, the title block and the table. Figures are drawn onto it.
pub fn page(layout: &SheetLayout, title: &TitleBlock, table: &Table, titles: &[String]) -> Drawing {
    let s = layout.sizes;
    let mut d = content_drawing(DimStyle { text_height: s.text, arrow_size: s.head });
    d.paper_mm_per_unit = Some(1.0);
    let l = d.layer(SHEET_LAYER.0, SHEET_LAYER.1, SHEET_LAYER.2);
    let rect = |d: &mut Drawing, b: Bounds, width: f64| {
        let points = vec![b.min, Point::new(b.max.x, b.min.y), b.max, Point::new(b.min.x, b.max.y)];
        d.add(l, Shape::Polyline { points, closed: true, width });
    };
    // Titles and cells are the sheet's own texts, marked up with `_` before a subscript
    // (`k_v`, `φ_1`: Runs::underscored); the name is the user's, drawn as written.
    let text = |d: &mut Drawing, at: Point, height: f64, (value, runs): (&str, Runs), halign: HAlign| {
        d.add(
            l,
            Shape::Text { runs, at, height, value: value.to_string(), halign, valign: VAlign::Middle, rotation: 0.0 },
        );
    };
    rect(&mut d, layout.border, 0.5);
    for (i, p) in layout.panels.iter().enumerate() {
        rect(&mut d, p.outline, 0.0);
        if let Some(t) = titles.get(i) {
            let at = Point::new(p.outline.min.x + 0.6 * s.text, p.outline.max.y - 1.1 * s.text);
            // A title wider than its panel (a scale in (mm/s²)/mm) in smaller letters, down
            // to the small text's height.
            let room = p.outline.width() - 1.2 * s.text;
            let runs = Runs::underscored(t);
            let width = crate::draw::font::measure_runs(t, &runs, s.text).width;
            let h = if width > room { (s.text * room / width).max(s.small_text()) } else { s.text };
            text(&mut d, at, h, (t, runs), HAlign::Left);
        }
    }
    // Title block: the name row, then two cells per row.
    let tb = layout.title;
    rect(&mut d, tb, 0.5);
    let row = 2.4 * s.text;
    let name_bottom = tb.max.y - 1.4 * row;
    let pad = 0.8 * s.text;
    d.add(l, Shape::Line { from: Point::new(tb.min.x, name_bottom), to: Point::new(tb.max.x, name_bottom) });
    let name_y = (tb.max.y + name_bottom) / 2.0;
    text(&mut d, Point::new(tb.min.x + pad, name_y), 1.4 * s.text, (&title.name, Runs::flat()), HAlign::Left);
    text(&mut d, Point::new(tb.max.x - pad, name_y), s.text, (&title.subject, Runs::flat()), HAlign::Right);
    let mut cells: Vec<(String, f64)> = vec![(title.position.clone(), 1.2 * s.text)];
    cells.extend(title.cells.iter().map(|c| (c.clone(), 0.9 * s.text)));
    cells.push((format!("sheet {} of {} · {}", title.sheet.0, title.sheet.1, layout.paper.name()), 0.8 * s.text));
    let mid_x = (tb.min.x + tb.max.x) / 2.0;
    let rows = cells.len().div_ceil(2);
    for r in 0..rows {
        let top = name_bottom - r as f64 * row;
        if r + 1 < rows {
            d.add(l, Shape::Line { from: Point::new(tb.min.x, top - row), to: Point::new(tb.max.x, top - row) });
        }
        d.add(l, Shape::Line { from: Point::new(mid_x, top), to: Point::new(mid_x, top - row) });
        for c in 0..2 {
            if let Some((value, h)) = cells.get(2 * r + c) {
                let x = if c == 0 { tb.min.x } else { mid_x } + pad;
                text(&mut d, Point::new(x, top - row / 2.0), *h, (value, Runs::underscored(value)), HAlign::Left);
            }
        }
    }
    table_into(&mut d, l, layout.table, table, s);
    d
}

/// The table in `b`: the header in a first row with a line under it, the rows below, text
/// sized to the rows (at most 0.9 letter height).
fn table_into(d: &mut Drawing, l: usize, b: Bounds, table: &Table, s: Sizes) {
    let ncols = table.header.len();
    if ncols == 0 || b.width() <= 0.0 || b.height() <= 0.0 {
        return;
    }
    let pad = 0.6 * s.text;
    let sets = table_sets(b, table.rows.len(), ncols, s);
    let per_set = table.rows.len().div_ceil(sets).max(1);
    let n = per_set + 1;
    let row = ((b.height() - 2.0 * pad) / n as f64).min(2.0 * s.text);
    let h = (0.5 * row).min(0.9 * s.text);
    // Columns: the name and the unit a little wider than the numbers.
    let weights: Vec<f64> = (0..ncols)
        .map(|c| {
            if c == 0 {
                1.0
            } else if c + 1 == ncols {
                1.2
            } else {
                1.25
            }
        })
        .collect();
    let total: f64 = weights.iter().sum();
    let set_w = (b.width() - 2.0 * pad) / sets as f64;
    let top = b.max.y - pad;
    for set in 0..sets {
        let x0 = b.min.x + pad + set as f64 * set_w;
        let mut edges = vec![x0];
        for w in &weights {
            edges.push(edges.last().copied().unwrap_or(0.0) + (set_w - pad) * w / total);
        }
        let cell = |d: &mut Drawing, r: usize, c: usize, value: &str, runs: Runs| {
            let y = top - (r as f64 + 0.5) * row;
            let numeric = c > 0 && c + 1 < ncols;
            let (x, halign) =
                if numeric { (edges[c + 1] - 1.2 * pad, HAlign::Right) } else { (edges[c] + 0.3 * pad, HAlign::Left) };
            d.add(
                l,
                Shape::Text {
                    // `RA` in the first column: R with A as a subscript.
                    runs,
                    at: Point::new(x, y),
                    height: h,
                    value: value.to_string(),
                    halign,
                    valign: VAlign::Middle,
                    rotation: 0.0,
                },
            );
        };
        for (c, v) in table.header.iter().enumerate() {
            cell(d, 0, c, v, Runs::underscored(v));
        }
        d.add(l, Shape::Line { from: Point::new(x0, top - row), to: Point::new(x0 + set_w - pad, top - row) });
        for (r, cells) in table.rows.iter().enumerate().skip(set * per_set).take(per_set) {
            for (c, v) in cells.iter().enumerate().take(ncols) {
                let runs = match table.names.get(r) {
                    Some(runs) if c == 0 => runs.clone(),
                    _ => Runs::underscored(v),
                };
                cell(d, r - set * per_set + 1, c, v, runs);
            }
        }
    }
}

/// The height of a table row on a sheet, in letter heights: its text 0.9 letters high.
pub const TABLE_ROW: f64 = 1.8;
/// The least width of one set of a table's columns, in letter heights per column.
pub const TABLE_COLUMN_MIN: f64 = 7.0;

/// Into how many sets of columns side by side a table of `rows` rows and `ncols` columns is
/// split in the box `b` so that its rows keep [`TABLE_ROW`] letters of height (one set when
/// it fits, at most as many as the box's width holds).
pub fn table_sets(b: Bounds, rows: usize, ncols: usize, s: Sizes) -> usize {
    let pad = 0.6 * s.text;
    let fits = |sets: usize| (rows.div_ceil(sets) + 1) as f64 * TABLE_ROW * s.text <= b.height() - 2.0 * pad + 1e-9;
    let most = ((b.width() - 2.0 * pad) / (TABLE_COLUMN_MIN * s.text * ncols as f64)).floor().max(1.0) as usize;
    (1..=most).find(|&k| fits(k)).unwrap_or(most)
}

#[cfg(test)]
#[allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the code under test calls"
)]
mod tests {
    use super::*;

    #[test]
    fn fit_fills_between_half_and_the_whole_area_with_a_nice_scale() {
        let area = Vector::new(80.0, 70.0);
        for i in 0..2000 {
            // Extents over six decades, both shapes.
            let e = 10f64.powf(-3.0 + i as f64 * 0.003);
            for extent in [Vector::new(e, 0.3 * e), Vector::new(0.2 * e, e)] {
                let f = fit(extent, area);
                let fill = (extent.x / f.per_mm / area.x).max(extent.y / f.per_mm / area.y);
                assert!((fill - f.fill).abs() < 1e-12);
                assert!((0.5..=1.0 + 1e-12).contains(&fill), "{extent:?}: fill {fill}");
                let m = f.per_mm / 10f64.powf(f.per_mm.log10().floor());
                assert!([1.0, 2.0, 2.5, 5.0].iter().any(|n| (m - n).abs() < 1e-9), "{}", f.per_mm);
            }
        }
        assert_eq!(fit(Vector::zeros(), area).per_mm, 1.0);
    }

    #[test]
    fn frame_scales_step_only_when_the_figure_leaves_half_to_all_of_its_area() {
        let area = Vector::new(100.0, 80.0);
        // A figure breathing between 60 and 95 units wide: one scale throughout (it fills
        // 0.6–0.95 of the area at 1 unit/mm).
        let breathing: Vec<Option<Vector>> =
            (0..40).map(|k| Some(Vector::new(77.5 + 17.5 * (k as f64 * 0.5).sin(), 10.0))).collect();
        let k = frame_scales(&breathing, area);
        assert!(k.iter().all(|&x| x == k[0]), "{k:?}");
        // A figure growing from 10 to 1000 units: steps up, always filling half to all.
        let growing: Vec<Option<Vector>> =
            (0..200).map(|i| Some(Vector::new(10.0 * 10f64.powf(i as f64 / 100.0), 5.0))).collect();
        let k = frame_scales(&growing, area);
        for (e, k) in growing.iter().zip(&k) {
            let f = fill(e.unwrap(), area, *k);
            assert!((MIN_FRAME_FILL..=1.0).contains(&f), "{e:?} at {k}: fill {f}");
        }
        let steps = k.windows(2).filter(|w| w[0] != w[1]).count();
        assert!((3..=8).contains(&steps), "{steps} steps over two decades: {k:?}");
        // Nothing to draw keeps the last scale.
        assert_eq!(frame_scales(&[Some(Vector::new(50.0, 1.0)), None, Some(Vector::zeros())], area), vec![1.0; 3]);
        assert_eq!(frame_scales(&[None], area), vec![1.0]);
        // Coming down from a coarser scale, a figure keeps it while it fills half the area
        // (fit alone would take the finer one at once).
        let size = Vector::new(130.0, 1.0);
        let e = Some(size);
        assert_eq!(fit(size, area).per_mm, 2.0);
        assert_eq!(scale_near(Some(2.5), e, area), 2.5);
        assert_eq!(scale_near(Some(5.0), e, area), 2.0);
    }

    #[test]
    fn held_scales_keep_an_earlier_runs_scale_while_the_figure_fills_half_to_all_of_its_area() {
        let area = Vector::new(100.0, 80.0);
        let e = |w: f64| Some(Vector::new(w, 1.0));
        let same = |w: f64| vec![e(w); 6];
        // An earlier run drew a figure 200 units wide at 2.5 units/mm (fill 0.8). Shrunk to
        // 130 units it keeps 2.5 (fill 0.52), where a fresh run takes 2 (fill 0.65): the
        // student sees it shrink.
        let before = frame_scales(&same(200.0), area);
        assert_eq!(before, vec![2.5; 6]);
        let prev: Vec<Option<f64>> = before.iter().copied().map(Some).collect();
        assert_eq!(held_scales(&prev, &same(130.0), area), vec![2.5; 6]);
        assert_eq!(frame_scales(&same(130.0), area), vec![2.0; 6]);
        // Grown to 240 units (fill 0.96) it is held; to 260 it would leave the area:
        // re-chosen (5 units/mm, fill 0.52).
        assert_eq!(held_scales(&prev, &same(240.0), area), vec![2.5; 6]);
        assert_eq!(held_scales(&prev, &same(260.0), area), vec![5.0; 6]);
        // Shrunk under half (120 units, fill 0.48): re-chosen (2 units/mm, fill 0.6).
        assert_eq!(held_scales(&prev, &same(120.0), area), vec![2.0; 6]);
        // Each frame its own earlier scale; a frame without one follows the frame before.
        let prev = [Some(2.5), Some(1.0), None, Some(2.0)];
        assert_eq!(held_scales(&prev, &[e(130.0), e(90.0), e(60.0), e(110.0)], area), vec![2.5, 1.0, 1.0, 2.0]);
        // No earlier run: the frame-to-frame choice.
        assert_eq!(held_scales(&[], &same(130.0), area), frame_scales(&same(130.0), area));
    }

    #[test]
    fn numbers_have_four_significant_digits() {
        assert_eq!(number(0.123456), "0.1235");
        assert_eq!(number(-12.3456), "−12.35");
        assert_eq!(number(1490.04), "1490");
        assert_eq!(number(20.0), "20.00");
        assert_eq!(number(0.0), "0");
        assert_eq!(number(-1e-7), "−0.0000001000");
        assert_eq!(number(-1833229.4), "−1833229");
        assert_eq!(number(529411.765), "529412");
        assert_eq!(number(f64::NAN), "–");
        for v in [-12.3456, -1e-7, -1833229.4, 529411.765] {
            let back = read_number(&number(v)).unwrap_or(f64::NAN);
            assert!((back - v).abs() <= 5e-4 * v.abs(), "{v} -> {back}");
        }
        assert_eq!(read_number("m"), None);
    }

    #[test]
    fn the_layout_keeps_inside_the_border_and_panels_apart() {
        for paper in [Paper::A4, Paper::A3] {
            let lay = SheetLayout::new(paper, 4, 6);
            let b = lay.border;
            let inside = |x: &Bounds| {
                x.min.x >= b.min.x - 1e-9
                    && x.min.y >= b.min.y - 1e-9
                    && x.max.x <= b.max.x + 1e-9
                    && x.max.y <= b.max.y + 1e-9
            };
            assert!(inside(&lay.title) && inside(&lay.table));
            for (i, p) in lay.panels.iter().enumerate() {
                assert!(inside(&p.outline) && p.area.width() > 50.0 && p.area.height() > 50.0, "{paper:?} {p:?}");
                assert!(p.outline.max.x <= lay.table.min.x + 1e-9);
                for q in &lay.panels[..i] {
                    let apart = p.outline.min.x >= q.outline.max.x - 1e-9
                        || q.outline.min.x >= p.outline.max.x - 1e-9
                        || p.outline.min.y >= q.outline.max.y - 1e-9
                        || q.outline.min.y >= p.outline.max.y - 1e-9;
                    assert!(apart);
                }
            }
        }
        assert_eq!("A3".parse::<Paper>(), Ok(Paper::A3));
        assert!("letter".parse::<Paper>().is_err());
    }
}
