//! A page of the report: the paper (A4 or A3 landscape) in millimetres, origin at its
//! lower-left corner, y up; a border (20 mm binding margin on the left, 10 mm elsewhere);
//! a title block in the lower right corner (the mechanism's name, the part, the scene file,
//! the page's number, a cell or two of the page's own: its scales); the content above it,
//! in panels framed on the sheet's layer with a title each; a strip of notes left of the
//! title block.
//!
//! Every text is measured with [`parts::text_width`] (the bundled font's advances) and
//! shrunk, down to the small letters, to stay inside its cell or panel.

use crate::draw::runs::{Run, RunKind, Runs};
use crate::draw::{Bounds, DimStyle, Drawing, HAlign, Shape, VAlign, parts};
use crate::figure::shared::labels::Label;
use crate::figure::shared::sheet::{Paper, SHEET_LAYER};
use crate::figure::shared::vocab::{self, Sizes, content_drawing};
use crate::geom::{Point, Vector};

/// Thinnest stroke on a page, paper mm.
pub const HAIRLINE_MM: f64 = crate::figure::shared::sheet::HAIRLINE_MM;

/// Width of the title block, paper mm (A4, A3).
fn title_width(paper: Paper) -> f64 {
    match paper {
        Paper::A4 => 110.0,
        Paper::A3 => 140.0,
    }
}

/// Where everything goes on a report page.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReportFrame {
    /// The paper.
    pub paper: Paper,
    /// Sizes of letters and symbols on this paper, mm.
    pub sizes: Sizes,
    /// The border.
    pub border: Bounds,
    /// The title block (lower right).
    pub title: Bounds,
    /// The content: the border's inside above the title block.
    pub content: Bounds,
    /// The strip left of the title block, for notes.
    pub notes: Bounds,
}

/// What the title block of a page says.
#[derive(Debug, Clone, PartialEq)]
pub struct PageTitle {
    /// The mechanism (the scene's name).
    pub name: String,
    /// What it is (`four-bar`, `linkage`, `triad`, `dimensional chain`).
    pub subject: String,
    /// The part of the report on this page (`2  Structural analysis`).
    pub part: String,
    /// The scene file, as given.
    pub file: String,
    /// The page's own cells (its scales), up to two.
    pub cells: Vec<String>,
    /// This page's number (from 1) and the number of pages.
    pub page: (usize, usize),
}

/// Height of a row of the title block, in letter heights.
const ROW: f64 = 2.4;

impl ReportFrame {
    /// The frame of a page on `paper`.
    pub fn new(paper: Paper) -> ReportFrame {
        let size = paper.size_mm();
        let sizes = paper.sizes();
        let border = Bounds { min: Point::new(20.0, 10.0), max: Point::new(size.x - 10.0, size.y - 10.0) };
        let row = ROW * sizes.text;
        let title_h = 1.4 * row + 3.0 * row;
        let title = Bounds {
            min: Point::new(border.max.x - title_width(paper), border.min.y),
            max: Point::new(border.max.x, border.min.y + title_h),
        };
        let content = Bounds { min: Point::new(border.min.x, title.max.y), max: border.max };
        let notes = Bounds { min: border.min, max: Point::new(title.min.x, title.max.y) };
        ReportFrame { paper, sizes, border, title, content, notes }
    }

    /// The page with its border and title block drawn (paper mm, the content layers of
    /// [`content_drawing`] and the sheet's layer).
    pub fn page(&self, title: &PageTitle) -> Drawing {
        self.page_with(title, true)
    }

    /// [`ReportFrame::page`] without the notes strip's frame: for a page whose left panel
    /// runs down to the border beside the title block ([`ReportFrame::tall_left`]).
    pub fn open_page(&self, title: &PageTitle) -> Drawing {
        self.page_with(title, false)
    }

    /// The left column from the border's top down to its bottom, as wide as the notes strip
    /// (beside the title block), and the column above the title block.
    pub fn tall_left(&self) -> (Bounds, Bounds) {
        let left = Bounds { min: self.border.min, max: Point::new(self.title.min.x, self.border.max.y) };
        let right = Bounds { min: Point::new(self.title.min.x, self.title.max.y), max: self.border.max };
        (left, right)
    }

    /// The page, with or without the notes strip's frame.
    fn page_with(&self, title: &PageTitle, notes: bool) -> Drawing {
        let s = self.sizes;
        let mut d = content_drawing(DimStyle { text_height: s.text, arrow_size: s.head });
        d.paper_mm_per_unit = Some(1.0);
        let l = sheet_layer(&mut d);
        rect(&mut d, l, self.border, 0.5);
        if notes {
            rect(&mut d, l, self.notes, 0.0);
        }
        let tb = self.title;
        rect(&mut d, l, tb, 0.5);
        let row = ROW * s.text;
        let pad = 0.8 * s.text;
        let name_bottom = tb.max.y - 1.4 * row;
        let mid = 0.5 * (tb.min.x + tb.max.x);
        let hline = |d: &mut Drawing, y: f64| {
            d.add(l, Shape::Line { from: Point::new(tb.min.x, y), to: Point::new(tb.max.x, y) })
        };
        hline(&mut d, name_bottom);
        // The name row: the name large at the left, the subject at the right.
        let name_y = 0.5 * (tb.max.y + name_bottom);
        let subject_w = parts::text_width(&title.subject, s.text);
        let name_room = tb.width() - 3.0 * pad - subject_w;
        text_in(&mut d, l, Point::new(tb.min.x + pad, name_y), 1.4 * s.text, name_room, &title.name, HAlign::Left, s);
        text(&mut d, l, Point::new(tb.max.x - pad, name_y), s.text, &title.subject, HAlign::Right);
        // The part, across the block.
        let part_y = name_bottom - 0.5 * row;
        hline(&mut d, name_bottom - row);
        text_in(
            &mut d,
            l,
            Point::new(tb.min.x + pad, part_y),
            1.1 * s.text,
            tb.width() - 2.0 * pad,
            &title.part,
            HAlign::Left,
            s,
        );
        // Two rows of two cells: the file and the page; the page's own cells.
        let file = std::path::Path::new(&title.file)
            .file_name()
            .map_or(title.file.clone(), |f| f.to_string_lossy().into_owned());
        let mut cells = vec![format!("scene {file}"), format!("page {} of {}", title.page.0, title.page.1)];
        cells.extend(title.cells.iter().take(2).cloned());
        if cells.len() == 2 {
            cells.push(format!("{} landscape", self.paper.name()));
            cells.push("print at 100 %".into());
        }
        for r in 0..2 {
            let top = name_bottom - (r + 1) as f64 * row;
            if r == 0 {
                hline(&mut d, top - row);
            }
            d.add(l, Shape::Line { from: Point::new(mid, top), to: Point::new(mid, top - row) });
            for c in 0..2 {
                if let Some(v) = cells.get(2 * r + c) {
                    let x = if c == 0 { tb.min.x } else { mid } + pad;
                    text_in(
                        &mut d,
                        l,
                        Point::new(x, top - 0.5 * row),
                        0.9 * s.text,
                        0.5 * tb.width() - 2.0 * pad,
                        v,
                        HAlign::Left,
                        s,
                    );
                }
            }
        }
        d
    }
}

/// The sheet's layer of `d` (created where new).
pub fn sheet_layer(d: &mut Drawing) -> usize {
    d.layer(SHEET_LAYER.0, SHEET_LAYER.1, SHEET_LAYER.2)
}

/// A rectangle on layer `l`: a closed polyline (the panels the readers and the tests know).
pub fn rect(d: &mut Drawing, l: usize, b: Bounds, width: f64) {
    let points = vec![b.min, Point::new(b.max.x, b.min.y), b.max, Point::new(b.min.x, b.max.y)];
    d.add(l, Shape::Polyline { points, closed: true, width });
}

/// A text, its middle at `at`'s height: flat (a `&str`) or with its subscripts (a
/// [`Label`]).
pub fn text(d: &mut Drawing, l: usize, at: Point, height: f64, value: impl Into<Label>, halign: HAlign) {
    let Label { text: value, runs } = value.into();
    d.add(l, Shape::Text { runs, at, height, value, halign, valign: VAlign::Middle, rotation: 0.0 });
}

/// The height at which `value` fits `room` mm: `height`, or less down to the small letters
/// of `s` (a longer text is cut to fit, with an ellipsis).
pub fn fitted(value: &str, height: f64, room: f64, s: Sizes) -> (f64, String) {
    let w = parts::text_width(value, height);
    if w <= room {
        return (height, value.to_string());
    }
    let h = (height * room / w).max(s.small_text().min(height));
    if parts::text_width(value, h) <= room {
        return (h, value.to_string());
    }
    let mut cut: String = value.to_string();
    while !cut.is_empty() && parts::text_width(&format!("{cut}…"), h) > room {
        cut.pop();
    }
    (h, format!("{cut}…"))
}

/// A text fitted into `room` mm ([`fitted`]), its middle at `at`'s height; its scales'
/// symbols drawn as the sheets draw them ([`symbols`]) unless it had to be cut.
#[allow(clippy::too_many_arguments)]
pub fn text_in(d: &mut Drawing, l: usize, at: Point, height: f64, room: f64, value: &str, halign: HAlign, s: Sizes) {
    let (h, v) = fitted(value, height, room, s);
    if v == value {
        text(d, l, at, h, symbols(&v), halign);
    } else {
        text(d, l, at, h, &v, halign);
    }
}

/// The scales' symbols that [`symbols`] draws with a subscript: `k_l`, `k_F`, `k_f`, `k_v`,
/// `k_a`.
const SCALE_INDICES: &str = "lFfva";

/// The angles and their rates that [`symbols`] draws with their index as a subscript
/// (`φ1`, `ω1`, `ε2`, `ψ3`, `θ1`, `γ_min`).
const INDEXED_GREEK: &str = "φψωεθγ";

/// `value` with the report's quantity symbols drawn as the sheets draw them: the scales'
/// (`k_l = 15 mm/mm`, `k_F`: the index a subscript in SVG and PDF, the `_` kept in the DXF's
/// flat text) and the angles' and rates' (`φ1 = 90°`, `ω1`, `γ_min`: what follows the
/// letter a subscript, the text as written). Every other `_` and digit is drawn as written
/// (a scene's or a body's name: `my_rod`, `O1`). Measured flat, the text is never narrower
/// than drawn.
pub fn symbols(value: &str) -> Label {
    let mut runs = Vec::new();
    let alone = |c: Option<char>| !c.is_some_and(char::is_alphanumeric);
    for (i, c) in value.char_indices() {
        if !alone(value[..i].chars().next_back()) {
            continue;
        }
        let rest = &value[i + c.len_utf8()..];
        // The index's start (after any `_`) and end, in `value`.
        let index = if c == 'k' {
            let mut after = rest.chars();
            match (after.next(), after.next(), after.next()) {
                (Some('_'), Some(x), next) if SCALE_INDICES.contains(x) && alone(next) => {
                    Some((i + 2, i + 2 + x.len_utf8()))
                }
                _ => None,
            }
        } else if INDEXED_GREEK.contains(c) {
            let from = i + c.len_utf8() + usize::from(rest.starts_with('_'));
            let len = value[from..].find(|x: char| !x.is_alphanumeric()).unwrap_or(value.len() - from);
            let marked = rest.starts_with('_');
            let digits = value[from..from + len].chars().all(|x| x.is_ascii_digit());
            (len > 0 && (marked || digits)).then_some((from, from + len))
        } else {
            None
        };
        let Some((from, end)) = index else { continue };
        let letter_end = i + c.len_utf8();
        runs.push(Run { end: letter_end, kind: RunKind::Base });
        if from > letter_end {
            runs.push(Run { end: from, kind: RunKind::Flat });
        }
        runs.push(Run { end, kind: RunKind::Sub });
    }
    Label { text: value.to_string(), runs: Runs(runs) }
}

/// A framed panel with its `title` in a band at its top: returns the area inside the band
/// and a margin of a letter's height, for the panel's figure ([`panel_area`]).
pub fn panel(d: &mut Drawing, outline: Bounds, title: &str, s: Sizes) -> Bounds {
    let l = sheet_layer(d);
    rect(d, l, outline, 0.0);
    if !title.is_empty() {
        let at = Point::new(outline.min.x + 0.6 * s.text, outline.max.y - 0.5 * TITLE_BAND * s.text);
        text_in(d, l, at, s.text, outline.width() - 1.2 * s.text, title, HAlign::Left, s);
    }
    panel_area(outline, !title.is_empty(), s)
}

/// Height of a panel's title band, in letter heights.
const TITLE_BAND: f64 = 2.2;

/// The area a panel framed by `outline` leaves its figure: the frame less a margin of a
/// letter's height and, when `titled`, the title's band.
pub fn panel_area(outline: Bounds, titled: bool, s: Sizes) -> Bounds {
    let m = s.text;
    let top = if titled { TITLE_BAND * s.text + 0.3 * m } else { m };
    Bounds { min: outline.min + Vector::new(m, m), max: outline.max - Vector::new(m, top) }
}

/// Lines of text from the top of `area` down, `height` high, each wrapped at its spaces to
/// the width (a word longer than the width is fitted on its own line); lines that do not fit
/// in the height are left out. Returns the height they took, mm.
pub fn lines(d: &mut Drawing, l: usize, area: Bounds, lines: &[String], height: f64, s: Sizes) -> f64 {
    let step = LINE_SPACING * height;
    let wrapped: Vec<String> = lines.iter().flat_map(|line| wrap(line, height, area.width())).collect();
    let fit = ((area.height() / step).floor() as usize).min(wrapped.len());
    for (k, line) in wrapped.iter().take(fit).enumerate() {
        let y = area.max.y - (k as f64 + 0.5) * step;
        text_in(d, l, Point::new(area.min.x, y), height, area.width(), line, HAlign::Left, s);
    }
    fit as f64 * step
}

/// `line` broken at its spaces into lines at most `width` mm wide at letter height
/// `height`; a continuation is indented by two spaces, as the first line's own indent.
pub fn wrap(line: &str, height: f64, width: f64) -> Vec<String> {
    if parts::text_width(line, height) <= width {
        return vec![line.to_string()];
    }
    let indent: String = line.chars().take_while(|c| *c == ' ').collect();
    let more = format!("{indent}  ");
    let mut out: Vec<String> = Vec::new();
    let mut cur = indent.clone();
    for word in line.split(' ').filter(|w| !w.is_empty()) {
        let bare = cur.trim().is_empty();
        let candidate = if bare { format!("{cur}{word}") } else { format!("{cur} {word}") };
        if bare || parts::text_width(&candidate, height) <= width {
            cur = candidate;
        } else {
            out.push(cur);
            cur = format!("{more}{word}");
        }
    }
    out.push(cur);
    out
}

/// A number as plain decimals (no exponent, as a drawing writes it): up to ten significant
/// digits, trailing zeros dropped (`0.0005`, `2.5`, `1500`).
pub fn plain(v: f64) -> String {
    significant(v, 10)
}

pub use crate::figure::shared::sheet::{scientific, significant};

/// Distance between lines of text, in letter heights.
pub const LINE_SPACING: f64 = 1.8;

/// `n` cells of `area`, `cols` to a row, row by row from the top (no gaps).
pub fn grid(area: Bounds, n: usize, cols: usize) -> Vec<Bounds> {
    let cols = cols.max(1);
    rows(area, n.max(1).div_ceil(cols), 0.0).into_iter().flat_map(|r| columns(r, cols, 0.0)).collect()
}

/// The area split into `n` columns side by side, `gap` mm apart.
pub fn columns(area: Bounds, n: usize, gap: f64) -> Vec<Bounds> {
    let n = n.max(1);
    let w = (area.width() - gap * (n - 1) as f64) / n as f64;
    (0..n)
        .map(|i| {
            let x = area.min.x + i as f64 * (w + gap);
            Bounds { min: Point::new(x, area.min.y), max: Point::new(x + w, area.max.y) }
        })
        .collect()
}

/// The area split into `n` rows, from the top, `gap` mm apart.
pub fn rows(area: Bounds, n: usize, gap: f64) -> Vec<Bounds> {
    let n = n.max(1);
    let h = (area.height() - gap * (n - 1) as f64) / n as f64;
    (0..n)
        .map(|i| {
            let top = area.max.y - i as f64 * (h + gap);
            Bounds { min: Point::new(area.min.x, top - h), max: Point::new(area.max.x, top) }
        })
        .collect()
}

/// A mechanism page's scale bar at its panel's lower left (`area` in paper mm, the figure at
/// `k_l` model units per paper mm, `unit` the model's) and its right-hand panel of text lines
/// titled `title`, each line `line_height` high: the kinematic diagram's and the plan's shared
/// furniture.
#[allow(clippy::too_many_arguments)]
pub fn scale_bar_and_notes(
    d: &mut Drawing,
    area: Bounds,
    k_l: f64,
    unit: &str,
    right: Bounds,
    title: &str,
    lines_: &[String],
    line_height: f64,
    s: Sizes,
) {
    let dims = vocab::layer_of(d, vocab::layers::DIMENSIONS);
    let value = vocab::bar_value(k_l);
    vocab::scale_bar(
        d,
        dims,
        Point::new(area.min.x + 2.0 * s.text, area.min.y + 0.5 * s.text),
        value / k_l,
        &format!("{} {unit}", plain(value)),
        s,
    );
    let notes = panel(d, right, title, s);
    let l = sheet_layer(d);
    lines(d, l, notes, lines_, line_height, s);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantity_symbols_are_subscripted_and_users_names_kept() {
        let parts =
            |l: &Label| -> Vec<(String, RunKind)> { l.runs.split(&l.text).map(|(p, k)| (p.to_string(), k)).collect() };
        let subs = |v: &str| -> Vec<String> {
            let l = symbols(v);
            assert_eq!(l.text, v, "the text stays as written");
            parts(&l).into_iter().filter(|(_, k)| *k == RunKind::Sub).map(|(p, _)| p).collect()
        };
        assert_eq!(subs("groups: k_l = 15 mm/mm, k_F = 2 N/mm"), ["l", "F"]);
        assert_eq!(subs("Position 3: φ1 = 90°, ω1 = 6.283 rad/s; γ_min = 23°"), ["1", "1", "min"]);
        // A user's name, a longer word, a symbol glued to a word, a point: as written.
        for flat in ["my_rod", "k_lever = 2", "ak_l = 1", "k_x = 1", "O1A", "Δφ = 60°", "aφ1"] {
            assert!(symbols(flat).runs.is_flat(), "{flat}");
        }
    }

    #[test]
    fn numbers_on_paper_have_no_e_notation() {
        assert_eq!(significant(360.5551275463989, 6), "360.555");
        assert_eq!(significant(std::f64::consts::TAU, 6), "6.28319");
        assert_eq!(significant(12000.0, 3), "12000");
        assert_eq!(scientific(1.3210e-10, 3), "1.32·10⁻¹⁰");
        assert_eq!(scientific(2.777, 4), "2.777");
        assert_eq!(scientific(-2.5e7, 3), "-2.5·10⁷");
        assert_eq!(scientific(9.9996e-5, 3), "1·10⁻⁴");
        assert_eq!(scientific(0.0, 3), "0");
    }

    #[test]
    fn the_frame_keeps_the_title_block_and_the_content_inside_the_border() {
        for paper in [Paper::A4, Paper::A3] {
            let f = ReportFrame::new(paper);
            let size = paper.size_mm();
            assert_eq!((f.border.max.x, f.border.max.y), (size.x - 10.0, size.y - 10.0));
            assert!(f.title.min.x > f.border.min.x && f.title.max.y < f.border.max.y);
            assert_eq!(f.content.min.y, f.title.max.y);
            assert!(f.content.height() > 0.7 * f.border.height(), "{paper:?}");
        }
    }

    #[test]
    fn lines_wrap_at_spaces_and_numbers_are_plain() {
        let w = wrap("  one two three four five six", 2.5, 25.0);
        assert!(w.len() > 1 && w[0].starts_with("  one") && w[1].starts_with("    "), "{w:?}");
        assert!(w.iter().all(|l| parts::text_width(l, 2.5) <= 25.0 + 1e-9), "{w:?}");
        assert_eq!(plain(0.0005), "0.0005");
        assert_eq!(plain(2.5), "2.5");
        assert_eq!(plain(1500.0), "1500");
        assert_eq!(plain(-0.25), "-0.25");
    }

    #[test]
    fn a_long_text_shrinks_then_is_cut_to_its_room() {
        let s = Paper::A4.sizes();
        let (h, v) = fitted("short", s.text, 100.0, s);
        assert_eq!((h, v.as_str()), (s.text, "short"));
        let long = "a very long title that cannot possibly fit into twenty millimetres";
        let (h, v) = fitted(long, s.text, 20.0, s);
        assert!(h >= s.small_text() - 1e-12 && parts::text_width(&v, h) <= 20.0 && v.ends_with('…'));
    }
}
