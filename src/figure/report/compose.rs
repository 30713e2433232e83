//! Pages composed of what other figures drew: a drawing placed on a page at its own printed
//! scale (or, when it does not fit, at the next nice scale, its printed `k_l` rewritten so
//! that it still holds), text and tables in panels, and a mechanism in several positions
//! side by side (a triad's assembly modes).

use crate::draw::{Bounds, Drawing, Shape};
use crate::figure::report::page::{self, PageTitle, ReportFrame};
use crate::figure::report::sketch::{self, Marks, OnPaper, Sketch};
use crate::figure::report::table::{self, PaperTable};
use crate::figure::shared::sheet;
use crate::figure::shared::vocab::nice_scale;
use crate::geom::{Point, Vector};

/// How a drawing went onto a page.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placed {
    /// Page mm per model unit.
    pub scale: f64,
    /// Its printed scale's factor: 1 at its own scale, less when reduced.
    pub reduced: f64,
}

/// The box a drawing's strokes and texts cover (texts by their measured boxes).
pub fn extent(d: &Drawing) -> Option<Bounds> {
    let mut b: Option<Bounds> = None;
    let mut add = |lo: Point, hi: Point| {
        b = Some(match b {
            None => Bounds { min: lo, max: hi },
            Some(x) => Bounds {
                min: Point::new(x.min.x.min(lo.x), x.min.y.min(lo.y)),
                max: Point::new(x.max.x.max(hi.x), x.max.y.max(hi.y)),
            },
        })
    };
    for e in &d.entities {
        match &e.shape {
            Shape::Text { .. } => {
                let t = sketch::text_box(&e.shape);
                add(t.min, t.max);
            }
            _ => {
                if let Some(x) = d.bounds_of(std::iter::once(e)) {
                    add(x.min, x.max);
                }
            }
        }
    }
    b
}

/// Places `fig` centred in `area` of the page `d`: at its own paper scale
/// ([`Drawing::paper_mm_per_unit`]) when it fits; else reduced so that its length scale
/// becomes the next nice one that fits, and its texts `k_l = …` rewritten to it (its scale
/// bar, drawn to the figure, still measures true); a drawing without a paper scale is
/// fitted.
pub fn place(d: &mut Drawing, fig: &Drawing, area: Bounds) -> Placed {
    let Some(b) = extent(fig) else { return Placed { scale: 1.0, reduced: 1.0 } };
    let fits = |scale: f64| b.width() * scale <= area.width() + 1e-9 && b.height() * scale <= area.height() + 1e-9;
    let fit = (area.width() / b.width().max(1e-12)).min(area.height() / b.height().max(1e-12));
    let (scale, reduced, k_l) = match fig.paper_mm_per_unit.filter(|k| k.is_finite() && *k > 0.0) {
        Some(k) if fits(k) => (k, 1.0, None),
        Some(k) => {
            let k_l = 1.0 / k;
            let new_k = nice_scale(1.0 / fit);
            (1.0 / new_k, k_l / new_k, Some(new_k))
        }
        None => (fit, 1.0, None),
    };
    let size = Vector::new(b.width(), b.height()) * scale;
    let corner = area.min + (Vector::new(area.width(), area.height()) - size) / 2.0;
    let mut mapped = fig.mapped(scale, corner.coords - b.min.coords * scale);
    if let Some(k) = k_l {
        for e in &mut mapped.entities {
            if let Shape::Text { value, .. } = &mut e.shape
                && let Some(rest) = value.strip_prefix("k_l = ")
            {
                let unit = rest.split_once(' ').map_or("", |(_, u)| u);
                *value = format!("k_l = {} {unit}", page::plain(k));
            }
        }
    }
    d.append(&mapped);
    Placed { scale, reduced }
}

/// What a panel of text holds.
#[derive(Debug, Clone)]
pub enum Block {
    /// Lines, wrapped to the panel.
    Lines(Vec<String>),
    /// A table.
    Table(PaperTable),
}

/// Draws `block` in `area` (a panel's inside).
pub fn block(d: &mut Drawing, area: Bounds, b: &Block, s: crate::figure::shared::vocab::Sizes) {
    match b {
        Block::Lines(lines) => {
            let l = page::sheet_layer(d);
            page::lines(d, l, area, lines, 0.85 * s.text, s);
        }
        Block::Table(t) => {
            table::draw(d, area, t, s);
        }
    }
}

/// A page of a figure over panels of text: the figure's panel as tall as it needs at its
/// scale (at most `max_share` of the content), the blocks side by side under it.
pub fn figure_page(
    frame: &ReportFrame,
    title: &PageTitle,
    fig: &Drawing,
    fig_title: &str,
    blocks: &[(String, Block)],
    max_share: f64,
) -> Drawing {
    let s = frame.sizes;
    let c = frame.content;
    let need = extent(fig).map_or(0.0, |b| b.height() * fig.paper_mm_per_unit.unwrap_or(1.0)) + 4.0 * s.text;
    let h = if blocks.is_empty() { c.height() } else { need.min(max_share * c.height()) };
    let top = Bounds { min: Point::new(c.min.x, c.max.y - h), max: c.max };
    let mut d = frame.page(title);
    let area = page::panel(&mut d, top, fig_title, s);
    place(&mut d, fig, area);
    let rest = Bounds { min: c.min, max: Point::new(c.max.x, top.min.y) };
    for ((t, b), cell) in blocks.iter().zip(page::columns(rest, blocks.len(), 0.0)) {
        let area = page::panel(&mut d, cell, t, s);
        block(&mut d, area, b, s);
    }
    d
}

/// A page of panels of text, side by side (`columns`) and row by row.
pub fn text_page(frame: &ReportFrame, title: &PageTitle, blocks: &[(String, Block)], columns: usize) -> Drawing {
    let s = frame.sizes;
    let mut d = frame.page(title);
    let n = blocks.len().max(1);
    let cols = columns.clamp(1, n);
    let cells = page::grid(frame.content, n, cols);
    for ((t, b), cell) in blocks.iter().zip(cells) {
        let area = page::panel(&mut d, cell, t, s);
        block(&mut d, area, b, s);
    }
    d
}

/// The letter height of a caption's lines under its panel's title, in letter heights.
const CAPTION_LINE: f64 = 0.85;

/// A panel's caption as its title and the lines under it: the whole caption as the title
/// where it fits the panel's width at the text's height; else the part before its last
/// ` · ` as the title and the rest as lines (wrapped to the panel), so that no caption is
/// cut (a triad's `Mode 1 · ccw · φ1 75.77° φ2 102.23° φ3 117.04°`).
fn caption_parts(caption: &str, cell: Bounds, s: crate::figure::shared::vocab::Sizes) -> (String, Vec<String>) {
    let room = cell.width() - 1.2 * s.text;
    if crate::draw::parts::text_width(caption, s.text) <= room {
        return (caption.to_string(), Vec::new());
    }
    match caption.rsplit_once(" · ") {
        Some((head, rest)) => {
            let width = page::panel_area(cell, true, s).width();
            (head.to_string(), page::wrap(rest, CAPTION_LINE * s.text, width))
        }
        None => (caption.to_string(), Vec::new()),
    }
}

/// A mechanism in several positions (each with its own sketch: a triad's modes are mirror
/// images), each in its own panel with its caption, all at one nice k_l (written in the
/// title block's first cell): a triad's assembly modes.
pub fn positions_page(
    frame: &ReportFrame,
    title: &PageTitle,
    positions: &[(String, &Sketch, Vec<f64>)],
    unit: &str,
) -> Drawing {
    let s = frame.sizes;
    let n = positions.len().max(1);
    let figure_area = |cell: Bounds, lines: &[String]| {
        let mut area = page::panel_area(cell, true, s);
        area.max.y -= lines.len() as f64 * page::LINE_SPACING * CAPTION_LINE * s.text;
        area
    };
    // The room around a sketch for its symbols and letters: a slider's block only where
    // there is one (a triad has none).
    let room = |sk: &Sketch| {
        let sliders = sk.figure.joints.iter().any(|j| matches!(j, crate::figure::linkage::JointSymbol::Slider { .. }));
        sketch::room(s) - Vector::new(if sliders { 0.0 } else { s.slider_length }, 0.0)
    };
    // Of every grid (columns × rows, no row empty), the one whose panels hold every sketch at
    // the finest drafting scale; on a tie the fewer columns (the wider panels, for captions).
    let layout = |cols: usize| {
        let cells = page::grid(frame.content, n, cols);
        // Each panel's title, and what of its caption does not fit there: lines under it.
        let heads: Vec<(String, Vec<String>)> =
            positions.iter().zip(&cells).map(|((caption, ..), cell)| caption_parts(caption, *cell, s)).collect();
        let k_l = positions.iter().zip(&cells).zip(&heads).fold(0.0f64, |k, (((_, sk, q), cell), (_, lines))| {
            let (lo, hi) = sk.extent(&[q.as_slice()]).unwrap_or((Vector::zeros(), Vector::new(1.0, 1.0)));
            k.max(sketch::fit(lo, hi, figure_area(*cell, lines), room(sk)).k_l)
        });
        (k_l, cells, heads)
    };
    let (k_l, cells, heads) = (1..=n)
        .map(layout)
        .reduce(|best, next| if next.0 < best.0 * (1.0 - 1e-9) { next } else { best })
        .unwrap_or_else(|| layout(n));
    let mut title = title.clone();
    title.cells = vec![format!("k_l = {} {unit}/mm", page::plain(k_l)), format!("{} positions", positions.len())];
    let mut d = frame.page(&title);
    for (((_, sk, q), cell), (head, lines)) in positions.iter().zip(cells).zip(&heads) {
        let probe = figure_area(cell, lines);
        let (lo, hi) = sk.extent(&[q.as_slice()]).unwrap_or((Vector::zeros(), Vector::new(1.0, 1.0)));
        let at = OnPaper { k_l, origin: sheet::centre(lo, hi, k_l, probe) };
        let mut area = page::panel(&mut d, cell, head, s);
        if !lines.is_empty() {
            let l = page::sheet_layer(&mut d);
            area.max.y -= page::lines(&mut d, l, area, lines, CAPTION_LINE * s.text, s);
        }
        sketch::draw(
            &mut d,
            sk,
            q,
            &[q.as_slice()],
            sketch::Frame { at, sizes: s, area },
            Marks { numbers: true, ..Marks::default() },
        );
    }
    d
}
