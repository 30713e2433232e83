//! Tables on a report page: a header row over a rule, rows of texts, columns as wide as
//! their widest text (measured with the bundled font), numbers right-aligned; a table
//! longer than its area continues in a second or third set of columns beside the first,
//! and its letters shrink (down to the small letters) until it fits.
//!
//! A cell is a [`Label`]: flat (a point's name `O1A`, a user's load `gas`, a number), or a
//! quantity's name with its subscripts (`m_21 bar AB`, `φ_1 [°]`: [`Label::marked`]), drawn
//! with them in the SVG and the PDF and measured as drawn ([`font::measure_runs`]).

use crate::draw::{Bounds, Drawing, HAlign, Shape, font};
use crate::figure::report::page::{sheet_layer, text};
use crate::figure::shared::labels::Label;
use crate::figure::shared::vocab::Sizes;
use crate::geom::Point;

/// How a column's texts align.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Align {
    /// Left (names, units).
    Left,
    /// Right (numbers).
    Right,
}

/// A table: column headings and rows of texts (each row as many as the header), each with
/// its subscripts.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PaperTable {
    /// Column headings.
    pub header: Vec<Label>,
    /// How each column aligns.
    pub align: Vec<Align>,
    /// The rows.
    pub rows: Vec<Vec<Label>>,
}

impl PaperTable {
    /// A table with these headings (flat `&str`s or [`Label`]s) and alignments and no rows.
    pub fn new<H: Clone + Into<Label>>(header: &[H], align: &[Align]) -> PaperTable {
        PaperTable { header: header.iter().cloned().map(Into::into).collect(), align: align.to_vec(), rows: Vec::new() }
    }

    /// Adds a row: flat texts (`String`s) or [`Label`]s.
    pub fn row<C: Into<Label>>(&mut self, cells: Vec<C>) {
        self.rows.push(cells.into_iter().map(Into::into).collect());
    }
}

/// Width of a cell's text drawn `h` high, its subscripts as drawn.
fn cell_width(l: &Label, h: f64) -> f64 {
    font::measure_runs(&l.text, &l.runs, h).width
}

/// Height of a table's row, in letter heights.
const ROW: f64 = 1.75;
/// Room between columns, in letter heights.
const COLUMN_GAP: f64 = 1.2;
/// Room between sets of columns, in letter heights.
const SET_GAP: f64 = 3.0;
/// Least room between the header's lowest stroke (a subscript, a descender) and the rule
/// under it, in letter heights.
const RULE_GAP: f64 = 0.15;

/// Widths of the columns of `rows` (header included) at letter height `h`.
fn widths(t: &PaperTable, h: f64) -> Vec<f64> {
    (0..t.header.len())
        .map(|c| {
            std::iter::once(&t.header[c])
                .chain(t.rows.iter().filter_map(|r| r.get(c)))
                .map(|v| cell_width(v, h))
                .fold(0.0, f64::max)
        })
        .collect()
}

/// How a table is laid out in an area: letter height, sets of columns, rows per set.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TableFit {
    /// Letter height, mm.
    pub height: f64,
    /// Sets of columns side by side.
    pub sets: usize,
    /// Rows in each set (the header repeated in each).
    pub per_set: usize,
    /// Width of one set, mm.
    pub set_width: f64,
}

impl TableFit {
    /// The space the table takes: (width, height), mm.
    pub fn size(&self) -> (f64, f64) {
        let sets = self.sets as f64;
        (sets * self.set_width + (sets - 1.0) * SET_GAP * self.height, (self.per_set + 1) as f64 * ROW * self.height)
    }
}

/// The largest letters (at most `s.text`, at least the small letters) and fewest sets of
/// columns (up to 3) at which `t` fits `area`; at the small letters in three sets when
/// nothing fits (its last rows then run off the area: the caller's area is too small).
pub fn fit(t: &PaperTable, area: Bounds, s: Sizes) -> TableFit {
    let n = t.rows.len().max(1);
    let candidates = [s.text, 0.9 * s.text, s.small_text()];
    for &h in &candidates {
        for sets in 1..=3usize {
            let per_set = n.div_ceil(sets);
            let w = widths(t, h);
            let set_width = w.iter().sum::<f64>() + COLUMN_GAP * h * (w.len().saturating_sub(1)) as f64;
            let f = TableFit { height: h, sets, per_set, set_width };
            let (tw, th) = f.size();
            if tw <= area.width() && th <= area.height() {
                return f;
            }
        }
    }
    let h = s.small_text();
    let w = widths(t, h);
    TableFit {
        height: h,
        sets: 3,
        per_set: n.div_ceil(3),
        set_width: w.iter().sum::<f64>() + COLUMN_GAP * h * (w.len().saturating_sub(1)) as f64,
    }
}

/// Draws `t` from the top-left corner of `area` on the sheet's layer, laid out by [`fit`];
/// returns the box it took.
pub fn draw(d: &mut Drawing, area: Bounds, t: &PaperTable, s: Sizes) -> Bounds {
    let f = fit(t, area, s);
    let l = sheet_layer(d);
    let h = f.height;
    let w = widths(t, h);
    let row = ROW * h;
    let header_descent = t.header.iter().map(|l| font::measure_runs(&l.text, &l.runs, h).descent).fold(0.0, f64::max);
    for set in 0..f.sets {
        let x0 = area.min.x + set as f64 * (f.set_width + SET_GAP * h);
        let mut edges = vec![x0];
        for cw in &w {
            edges.push(edges.last().copied().unwrap_or(x0) + cw + COLUMN_GAP * h);
        }
        let cell = |d: &mut Drawing, r: usize, c: usize, v: &Label| {
            let y = area.max.y - (r as f64 + 0.5) * row;
            let align = t.align.get(c).copied().unwrap_or(Align::Left);
            let (x, ha) = match align {
                Align::Left => (edges[c], HAlign::Left),
                Align::Right => (edges[c] + w[c], HAlign::Right),
            };
            text(d, l, Point::new(x, y), h, v.clone(), ha);
        };
        for (c, v) in t.header.iter().enumerate() {
            cell(d, 0, c, v);
        }
        // The rule under the header at the row's foot, lower where a heading's subscript or
        // descender reaches it (`φ_1 [°]`: the text's middle at half the row, its baseline
        // half a letter under that).
        let reach = area.max.y - 0.5 * row - 0.5 * h - header_descent - RULE_GAP * h;
        let rule = (area.max.y - row).min(reach);
        d.add(l, Shape::Line { from: Point::new(x0, rule), to: Point::new(x0 + f.set_width, rule) });
        for (k, cells) in t.rows.iter().skip(set * f.per_set).take(f.per_set).enumerate() {
            for (c, v) in cells.iter().enumerate().take(t.header.len()) {
                cell(d, k + 1, c, v);
            }
        }
    }
    let (tw, th) = f.size();
    Bounds { min: Point::new(area.min.x, area.max.y - th), max: Point::new(area.min.x + tw, area.max.y) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figure::shared::sheet::Paper;

    fn table(n: usize) -> PaperTable {
        let mut t = PaperTable::new(&["quantity", "value", "unit"], &[Align::Left, Align::Right, Align::Left]);
        for k in 0..n {
            t.row(vec![format!("length l{k}"), format!("{}.25", 10 * k), "mm".into()]);
        }
        t
    }

    #[test]
    fn a_long_table_takes_sets_of_columns_before_smaller_letters() {
        let s = Paper::A4.sizes();
        let area = Bounds { min: Point::new(0.0, 0.0), max: Point::new(200.0, 60.0) };
        let short = fit(&table(5), area, s);
        assert_eq!((short.height, short.sets), (s.text, 1));
        let long = fit(&table(25), area, s);
        assert!(long.sets > 1, "{long:?}");
        let (w, h) = long.size();
        assert!(w <= 200.0 && h <= 60.0);
        let mut d = Drawing::new(crate::draw::DimStyle { text_height: 2.5, arrow_size: 2.5 });
        let used = draw(&mut d, area, &table(25), s);
        assert!(used.max.x <= 200.0 + 1e-9 && used.min.y >= -1e-9);
        let texts = d.entities.iter().filter(|e| matches!(e.shape, Shape::Text { .. })).count();
        assert_eq!(texts, 25 * 3 + 3 * long.sets);
    }
}
