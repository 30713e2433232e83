//! The title page: what the report is about (the mechanism, its kind, the scene file), the
//! data it was computed from (lengths, masses, ω1, loads, with units), the contents with
//! their pages, and the fields a student fills in by hand (name, group, date, the
//! teacher's signature), as ruled blank lines.

use crate::draw::{Bounds, Drawing, HAlign, Shape};
use crate::figure::report::page::{self, PageTitle, ReportFrame};
use crate::figure::report::table::{self, PaperTable};

use crate::geom::Point;

/// What the title page says.
#[derive(Debug, Clone)]
pub struct TitlePage {
    /// The heading (`Graph-analytical analysis of a planar mechanism`).
    pub heading: String,
    /// The mechanism in a line (`four-bar fourbar-chebyshev (crank-rocker, seed 003)`).
    pub subject: String,
    /// The data table: quantity, symbol, value, unit.
    pub data: PaperTable,
    /// The contents: (part, first page).
    pub contents: Vec<(String, usize)>,
}

/// The fields left blank for the student and the teacher.
pub const FIELDS: [&str; 5] = ["Student", "Group", "Date", "Checked by", "Mark"];

/// The title page.
pub fn page(frame: &ReportFrame, title: &PageTitle, t: &TitlePage) -> Drawing {
    let s = frame.sizes;
    let c = frame.content;
    let mut d = frame.page(title);
    let l = page::sheet_layer(&mut d);
    // The heading over the whole width.
    let head_h = 2.0 * s.text;
    let top = c.max.y - 2.0 * head_h;
    page::text_in(
        &mut d,
        l,
        Point::new(c.min.x + s.text, top + head_h),
        head_h,
        c.width() - 2.0 * s.text,
        &t.heading,
        HAlign::Left,
        s,
    );
    page::text_in(
        &mut d,
        l,
        Point::new(c.min.x + s.text, top - 0.2 * head_h),
        1.2 * s.text,
        c.width() - 2.0 * s.text,
        &t.subject,
        HAlign::Left,
        s,
    );
    let body = Bounds { min: c.min, max: Point::new(c.max.x, top - 1.5 * head_h) };
    let [left, right] = match page::columns(body, 2, 0.0).as_slice() {
        [a, b] => [*a, *b],
        _ => [body, body],
    };
    let left = Bounds { max: Point::new(left.min.x + 0.6 * body.width(), left.max.y), ..left };
    let right = Bounds { min: Point::new(left.max.x, right.min.y), ..right };
    let data_area = page::panel(&mut d, left, "Data", s);
    table::draw(&mut d, data_area, &t.data, s);
    let [contents, fields] = match page::rows(right, 2, 0.0).as_slice() {
        [a, b] => [*a, *b],
        _ => [right, right],
    };
    let area = page::panel(&mut d, contents, "Contents", s);
    let toc: Vec<String> = t.contents.iter().map(|(part, first)| format!("{first:>3}   {part}")).collect();
    page::lines(&mut d, l, area, &toc, 0.9 * s.text, s);
    let area = page::panel(&mut d, fields, "", s);
    let rows = page::rows(area, FIELDS.len(), 0.0);
    for (name, row) in FIELDS.iter().zip(rows) {
        let y = row.min.y + 0.35 * row.height();
        page::text(&mut d, l, Point::new(row.min.x, y + 0.5 * s.text), s.text, *name, HAlign::Left);
        let x0 = row.min.x + crate::draw::parts::text_width("Checked by", s.text) + 1.5 * s.text;
        d.add(l, Shape::Line { from: Point::new(x0, y), to: Point::new(row.max.x, y) });
    }
    d
}
