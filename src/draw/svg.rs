//! SVG writer: the same content as the DXF, for browsers and golden images.
//!
//! The model's y axis points up (as in CAD); SVG's points down. The flip happens in one
//! place, `Frame::pt`. The viewBox is fitted to the drawing's bounds with a margin.
//! Line widths, dash lengths and font sizes follow the model units, so the SVG is to scale.
//!
//! A drawing with a paper scale ([`Drawing::paper_mm_per_unit`], or
//! [`SvgOptions::paper_mm_per_unit`]) is written on paper: every coordinate and length is
//! multiplied by the paper millimetres per model unit, the viewBox is in paper millimetres and
//! the page is `width="…mm" height="…mm"`, so that printing at 100 % gives the stated scales
//! and a ruler measures them. Without one, the page is [`SvgOptions::width_px`] pixels wide.

use std::io::Write;

use super::parts::{arc_sweep, arrow, dash_pattern, explode_dimension};
use super::{Aci, Bounds, Drawing, Entity, HAlign, LineType, RunKind, Runs, Shape, VAlign, font};
use crate::geom::{Point, polar};

#[cfg(test)]
mod reference;

/// Font family written into SVG text; the bundled DejaVu Sans (assets/fonts) renders it in
/// golden images, browsers fall back to any sans-serif.
pub const FONT_FAMILY: &str = "DejaVu Sans, sans-serif";

/// How the SVG is framed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SvgOptions {
    /// Width attribute in pixels; the height follows the aspect ratio.
    pub width_px: u32,
    /// Margin around the content, as a fraction of the larger extent.
    pub margin: f64,
    /// Thinnest stroke, as a fraction of the larger extent (a 0-width polyline draws this).
    pub hairline: f64,
    /// Fixed model-space window (lower-left, upper-right) instead of the drawing's bounds:
    /// frames of an animation share one window so the picture doesn't jump.
    pub window: Option<Bounds>,
    /// Paper millimetres per model unit, overriding the drawing's own
    /// [`Drawing::paper_mm_per_unit`] (the frames of an animation take the base's).
    pub paper_mm_per_unit: Option<f64>,
}

impl Default for SvgOptions {
    fn default() -> Self {
        SvgOptions { width_px: 1000, margin: 0.05, hairline: 0.0015, window: None, paper_mm_per_unit: None }
    }
}

/// Maps model coordinates to SVG user units (y flipped, scaled to paper) and fixes number
/// formatting.
struct Frame {
    /// SVG user units per model unit: paper mm per model unit, or 1 without a paper scale.
    k: f64,
    /// The paper scale (paper mm per model unit), if the SVG is on paper: the medium of
    /// [`Shape::ScaleText`].
    paper: Option<f64>,
    /// Stroke width of a hairline, model units.
    hairline: f64,
    /// Dash and gap of dashed lines, model units (the DXF writer's DASHED pattern).
    dash: (f64, f64),
}

impl Frame {
    /// The single y flip of the writer.
    fn pt(&self, p: Point) -> (f64, f64) {
        (self.k * p.x, -self.k * p.y)
    }
    /// A model length in SVG user units.
    fn len(&self, l: f64) -> f64 {
        self.k * l
    }
}

/// Fixed, deterministic number formatting: 6 significant decimals trimmed — exactly what
/// `format!("{v:.6}")` trimmed gives. Every coordinate of every frame goes through here, so
/// the common case skips the exact decimal expansion: v·10⁶ is rounded as an integer when it
/// is small enough and its fraction is far enough from ½ that the product's rounding error
/// (≤ 2⁻⁵² of it) cannot change the result; anything else takes `format!`.
pub fn num(v: f64) -> String {
    let mut s = Vec::with_capacity(16);
    push_num(&mut s, v);
    utf8(s)
}

/// The writer's bytes as a String: they are UTF-8 (ASCII, and text copied from `&str`s
/// whole), so the lossy branch is never taken.
fn utf8(bytes: Vec<u8>) -> String {
    String::from_utf8(bytes).unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned())
}

/// Appends [`num`]`(v)` to `out` without allocating in the common case.
fn push_num(out: &mut Vec<u8>, v: f64) {
    let scaled = v * 1e6;
    if scaled.abs() < 1e12 {
        let floor = scaled.floor();
        let frac = scaled - floor;
        if (frac - 0.5).abs() > 1e-3 {
            let units = (if frac > 0.5 { floor + 1.0 } else { floor }) as i64;
            push_fixed6(out, units);
            return;
        }
    }
    let start = out.len();
    // Writing into a Vec cannot fail.
    let _ = write!(out, "{v:.6}");
    // Trimmed in place: trailing zeros, then a bare point, and no `-0`.
    while out.len() > start && out.last() == Some(&b'0') {
        out.pop();
    }
    if out.len() > start && out.last() == Some(&b'.') {
        out.pop();
    }
    if &out[start..] == b"-0" {
        out.remove(start);
    }
}

/// Appends `units`·10⁻⁶ as [`num`] writes it: trailing zeros and a bare point trimmed, no `-0`.
fn push_fixed6(out: &mut Vec<u8>, units: i64) {
    if units == 0 {
        out.push(b'0');
        return;
    }
    if units < 0 {
        out.push(b'-');
    }
    let u = units.unsigned_abs();
    let (int, mut frac) = (u / 1_000_000, u % 1_000_000);
    push_u64(out, int);
    if frac != 0 {
        let mut digits = 6;
        while frac % 10 == 0 {
            frac /= 10;
            digits -= 1;
        }
        // `digits` decimals, leading zeros kept.
        let mut buf = [b'0'; 6];
        for i in (0..digits).rev() {
            buf[i] = b'0' + (frac % 10) as u8;
            frac /= 10;
        }
        out.push(b'.');
        out.extend_from_slice(&buf[..digits]);
    }
}

/// Appends the decimal digits of `n`.
fn push_u64(out: &mut Vec<u8>, mut n: u64) {
    let mut buf = [0u8; 20];
    let mut i = buf.len();
    loop {
        i -= 1;
        buf[i] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    out.extend_from_slice(&buf[i..]);
}

/// `#rrggbb`.
fn rgb(c: Aci) -> [u8; 7] {
    const HEX: &[u8; 16] = b"0123456789abcdef";
    let (r, g, b) = c.rgb();
    let mut s = [b'#'; 7];
    for (i, v) in [r, g, b].into_iter().enumerate() {
        s[1 + 2 * i] = HEX[usize::from(v >> 4)];
        s[2 + 2 * i] = HEX[usize::from(v & 15)];
    }
    s
}

/// Appends `s` escaped as XML text content: `&`, `<`, `>`.
fn push_text(out: &mut Vec<u8>, s: &str) {
    push_escaped(out, s, false);
}

/// Appends `s` escaped for an attribute value in double quotes: `&`, `<`, `>`, `"`, `'`.
fn push_attr_value(out: &mut Vec<u8>, s: &str) {
    push_escaped(out, s, true);
}

fn push_escaped(out: &mut Vec<u8>, s: &str, quotes: bool) {
    let s = s.as_bytes();
    let mut plain = 0;
    for (i, &b) in s.iter().enumerate() {
        let esc = match b {
            b'&' => "&amp;",
            b'<' => "&lt;",
            b'>' => "&gt;",
            b'"' if quotes => "&quot;",
            b'\'' if quotes => "&apos;",
            _ => continue,
        };
        out.extend_from_slice(&s[plain..i]);
        out.extend_from_slice(esc.as_bytes());
        plain = i + 1;
    }
    out.extend_from_slice(&s[plain..]);
}

/// Writes elements into one buffer. Attributes are written in the order of their names
/// (byte order), as the `svg` crate this replaced wrote them, so that the bytes did not change.
struct Out<'a> {
    s: &'a mut Vec<u8>,
}

impl Out<'_> {
    /// ` name="value"` with `value` escaped.
    fn attr(&mut self, name: &str, value: &str) {
        self.s.push(b' ');
        self.s.extend_from_slice(name.as_bytes());
        self.s.extend_from_slice(b"=\"");
        push_attr_value(self.s, value);
        self.s.push(b'"');
    }
    /// ` name="number"`.
    fn num(&mut self, name: &str, v: f64) {
        push_attr_num(self.s, name, v);
    }
    /// A new child line: `\n<name`.
    fn open(&mut self, name: &str) {
        self.s.extend_from_slice(b"\n<");
        self.s.extend_from_slice(name.as_bytes());
    }
    /// `x,y` (the `points` of polylines and polygons), after a space unless first.
    fn points(&mut self, f: &Frame, points: impl IntoIterator<Item = Point>) {
        self.s.extend_from_slice(b" points=\"");
        for (i, p) in points.into_iter().enumerate() {
            if i > 0 {
                self.s.push(b' ');
            }
            let (x, y) = f.pt(p);
            push_num(self.s, x);
            self.s.push(b',');
            push_num(self.s, y);
        }
        self.s.push(b'"');
    }
}

/// Renders `drawing` as an SVG document string.
pub fn to_string(drawing: &Drawing, opts: &SvgOptions) -> String {
    let mut s = Vec::with_capacity(256 + 160 * drawing.entities.len());
    write_into(&mut s, drawing, opts);
    utf8(s)
}

/// Appends the SVG document of `drawing` to `s` (the bytes of [`to_string`]).
pub fn write_into(s: &mut Vec<u8>, drawing: &Drawing, opts: &SvgOptions) {
    let bounds = opts
        .window
        .or_else(|| drawing.bounds())
        .unwrap_or(Bounds { min: Point::new(0.0, 0.0), max: Point::new(1.0, 1.0) });
    let extent = bounds.width().max(bounds.height()).max(f64::MIN_POSITIVE);
    let margin = opts.margin * extent;
    let paper = opts.paper_mm_per_unit.or(drawing.paper_mm_per_unit).filter(|k| k.is_finite() && *k > 0.0);
    let frame = Frame { k: paper.unwrap_or(1.0), paper, hairline: opts.hairline * extent, dash: dash_pattern(extent) };
    let (x0, y0) = frame.pt(Point::new(bounds.min.x - margin, bounds.max.y + margin));
    let (w, h) = (bounds.width() + 2.0 * margin, bounds.height() + 2.0 * margin);
    let w = frame.len(w.max(extent * 1e-3));
    let h = frame.len(h.max(extent * 1e-3));
    let mut o = Out { s };

    // <svg font-family height viewBox width xmlns>
    o.s.extend_from_slice(b"<svg");
    o.attr("font-family", FONT_FAMILY);
    let paper_size = |o: &mut Out<'_>, name: &str, v: f64| {
        o.s.push(b' ');
        o.s.extend_from_slice(name.as_bytes());
        o.s.extend_from_slice(b"=\"");
        push_num(o.s, v);
        o.s.extend_from_slice(b"mm\"");
    };
    match paper {
        Some(_) => paper_size(&mut o, "height", h),
        None => {
            let height_px = ((opts.width_px as f64) * h / w).round().max(1.0) as u32;
            o.s.extend_from_slice(b" height=\"");
            push_u64(o.s, u64::from(height_px));
            o.s.push(b'"');
        }
    }
    o.s.extend_from_slice(b" viewBox=\"");
    for (i, v) in [x0, y0, w, h].into_iter().enumerate() {
        if i > 0 {
            o.s.push(b' ');
        }
        push_num(o.s, v);
    }
    o.s.push(b'"');
    match paper {
        Some(_) => paper_size(&mut o, "width", w),
        None => {
            o.s.extend_from_slice(b" width=\"");
            push_u64(o.s, u64::from(opts.width_px));
            o.s.push(b'"');
        }
    }
    o.s.extend_from_slice(b" xmlns=\"http://www.w3.org/2000/svg\">");
    // The background: <rect fill height width x y/>
    o.open("rect");
    o.attr("fill", "#ffffff");
    o.num("height", h);
    o.num("width", w);
    o.num("x", x0);
    o.num("y", y0);
    o.s.extend_from_slice(b"/>");

    // Entities in drawing order (later ones on top, as in the DXF), grouped into runs of
    // consecutive entities on one layer: `<g class="layer-NAME">` (a layer may have several).
    // A group's `>` waits for its first child: a group with none is written `<g …/>`.
    let mut run: Option<usize> = None;
    let mut empty = false;
    let close = |o: &mut Out<'_>, empty: bool| o.s.extend_from_slice(if empty { b"/>" } else { &b"\n</g>"[..] });
    for e in &drawing.entities {
        if run != Some(e.layer) {
            if run.is_some() {
                close(&mut o, empty);
            }
            o.open("g");
            o.s.extend_from_slice(b" class=\"layer-");
            push_attr_value(o.s, &drawing.layers[e.layer].name);
            o.s.extend_from_slice(b"\" fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\"");
            run = Some(e.layer);
            empty = true;
        }
        entity(&mut o, drawing, e, &frame, &mut empty);
    }
    if run.is_some() {
        close(&mut o, empty);
    }
    o.s.extend_from_slice(b"\n</svg>");
}

/// The frames of an animation without rewriting their shared part: the SVG of a drawing
/// `base` followed by a drawing `moving`, both written by [`to_string`] with the same
/// options (so with the same header). It is `base_svg` without its closing tag, then
/// `moving_svg` after its header (the `<svg>` line and the background `<rect>` line): the
/// writer's output for base's entities then moving's, as long as base's last entity and
/// moving's first are on different layers (else the writer would put them in one group).
/// `None` when the two headers differ (then write the frame whole).
pub fn splice(base_svg: &str, moving_svg: &str) -> Option<String> {
    let (head, tail) = splice_parts(base_svg, moving_svg)?;
    let mut out = String::with_capacity(head.len() + tail.len());
    out.push_str(head);
    out.push_str(tail);
    Some(out)
}

/// The closing tag of an SVG document as [`to_string`] writes it.
const CLOSE: &str = "</svg>";

/// What [`splice`] appends to `base_svg` (without its closing tag): `moving_svg`'s elements,
/// after its header and before its closing tag. `None` when the headers differ.
pub fn spliced_part<'a>(base_svg: &str, moving_svg: &'a str) -> Option<&'a str> {
    splice_parts(base_svg, moving_svg)?.1.strip_suffix(CLOSE)
}

/// The two pieces of [`splice`]'s frame, borrowed: `base_svg` without its closing tag, and
/// `moving_svg` after its header; the frame is the one followed by the other (a writer can
/// put them in a file one after the other without building the frame).
pub fn splice_parts<'b, 'm>(base_svg: &'b str, moving_svg: &'m str) -> Option<(&'b str, &'m str)> {
    let header_end = |s: &str| -> Option<usize> {
        let first = s.find('\n')?;
        Some(first + 1 + s[first + 1..].find('\n')? + 1)
    };
    let (hb, hm) = (header_end(base_svg)?, header_end(moving_svg)?);
    if base_svg[..hb] != moving_svg[..hm] || !base_svg.ends_with(CLOSE) || !moving_svg.ends_with(CLOSE) {
        return None;
    }
    Some((&base_svg[..base_svg.len() - CLOSE.len()], &moving_svg[hm..]))
}

/// Writes `drawing` as SVG to `out`.
pub fn write(drawing: &Drawing, opts: &SvgOptions, mut out: impl Write) -> std::io::Result<()> {
    out.write_all(to_string(drawing, opts).as_bytes())
}

/// Appends the elements of one entity to the open group (`empty`: the group's `>` is not
/// written yet).
fn entity(o: &mut Out<'_>, drawing: &Drawing, e: &Entity, f: &Frame, empty: &mut bool) {
    let color = rgb(drawing.color_of(e));
    // ASCII.
    let color = std::str::from_utf8(&color).unwrap_or_default();
    let dashed = drawing.linetype_of(e) == LineType::Dashed;
    // Each child starts its own line; the group's `>` comes before the first.
    let mut child = |o: &mut Out<'_>, name: &str| {
        if std::mem::take(empty) {
            o.s.push(b'>');
        }
        o.open(name);
    };
    // The stroke attributes (stroke, stroke-dasharray, stroke-width), after any attribute
    // whose name sorts before `stroke` and before any that sorts after.
    let stroke = |o: &mut Out<'_>, w: f64| {
        o.attr("stroke", color);
        if dashed {
            o.s.extend_from_slice(b" stroke-dasharray=\"");
            push_num(o.s, f.len(f.dash.0));
            o.s.push(b' ');
            push_num(o.s, f.len(f.dash.1));
            o.s.push(b'"');
        }
        o.num("stroke-width", f.len(w.max(f.hairline)));
    };
    let line = |o: &mut Out<'_>, from: Point, to: Point| {
        let (x1, y1) = f.pt(from);
        let (x2, y2) = f.pt(to);
        stroke(o, 0.0);
        o.num("x1", x1);
        o.num("x2", x2);
        o.num("y1", y1);
        o.num("y2", y2);
        o.s.extend_from_slice(b"/>");
    };
    match &e.shape {
        Shape::Circle { center, radius } => {
            let (x, y) = f.pt(*center);
            child(o, "circle");
            o.num("cx", x);
            o.num("cy", y);
            o.num("r", f.len(*radius));
            stroke(o, 0.0);
            o.s.extend_from_slice(b"/>");
        }
        Shape::Arc { center, radius, start, end } => {
            child(o, "path");
            o.s.extend_from_slice(b" d=\"");
            arc_path(o.s, f, *center, *radius, *start, *end);
            o.s.push(b'"');
            stroke(o, 0.0);
            o.s.extend_from_slice(b"/>");
        }
        Shape::Line { from, to } => {
            child(o, "line");
            line(o, *from, *to);
        }
        Shape::Polyline { points, closed, width } => {
            child(o, if *closed { "polygon" } else { "polyline" });
            o.points(f, points.iter().copied());
            stroke(o, *width);
            o.s.extend_from_slice(b"/>");
        }
        Shape::Filled { points } => {
            child(o, "polygon");
            o.attr("fill", color);
            o.points(f, points.iter().copied());
            o.s.extend_from_slice(b" stroke=\"none\"/>");
        }
        Shape::Arrow { from, to, head } => {
            if let Some((base, tri)) = arrow(*from, *to, *head) {
                child(o, "line");
                line(o, *from, base);
                child(o, "polygon");
                o.attr("fill", color);
                o.points(f, tri);
                o.s.extend_from_slice(b" stroke=\"none\"/>");
            }
        }
        Shape::Text { at, height, value, runs, halign, valign, rotation } => {
            child(o, "text");
            text(o, f, *at, *height, (value, runs), *halign, *valign, *rotation, color);
        }
        caption @ Shape::ScaleText { .. } => {
            if let Some(shape) = caption.scale_text_in(f.paper) {
                entity(o, drawing, &Entity { shape, ..e.clone() }, f, empty);
            }
        }
        dim @ (Shape::AngularDimension { .. } | Shape::LinearDimension { .. }) => {
            for part in explode_dimension(dim, &drawing.dim_style) {
                let sub = Entity { layer: e.layer, color: e.color, linetype: Some(LineType::Continuous), shape: part };
                entity(o, drawing, &sub, f, empty);
            }
        }
    }
}

/// A `<text …>` element's attributes, content and end (its `<text` is written).
#[allow(clippy::too_many_arguments)]
fn text(
    o: &mut Out<'_>,
    f: &Frame,
    at: Point,
    height: f64,
    (value, runs): (&str, &Runs),
    halign: HAlign,
    valign: VAlign,
    rotation: f64,
    color: &str,
) {
    let (x, y) = f.pt(at);
    let anchor = match halign {
        HAlign::Left => "start",
        HAlign::Center => "middle",
        HAlign::Right => "end",
    };
    // Cap height ≈ 0.73 em for DejaVu Sans: font-size = height / 0.73. Vertical alignment is
    // done with an explicit shift (dominant-baseline is not rendered alike everywhere).
    let size = f.len(height) / 0.73;
    let dy = f.len(match valign {
        VAlign::Baseline => 0.0,
        VAlign::Middle => 0.5 * height,
        VAlign::Top => height,
    });
    // dy fill font-size stroke text-anchor transform x y
    if dy != 0.0 {
        o.num("dy", dy);
    }
    o.attr("fill", color);
    o.num("font-size", size);
    o.s.extend_from_slice(b" stroke=\"none\"");
    o.attr("text-anchor", anchor);
    if rotation != 0.0 {
        // SVG rotates clockwise in its y-down frame: negate.
        o.s.extend_from_slice(b" transform=\"rotate(");
        push_num(o.s, -rotation.to_degrees());
        o.s.push(b' ');
        push_num(o.s, x);
        o.s.push(b' ');
        push_num(o.s, y);
        o.s.extend_from_slice(b")\"");
    }
    o.num("x", x);
    o.num("y", y);
    // The content on its own line.
    o.s.extend_from_slice(b">\n");
    if runs.is_flat() {
        push_text(o.s, value);
    } else {
        push_runs(o.s, value, runs, size);
    }
    o.s.extend_from_slice(b"\n</text>");
}

/// Appends a text's runs drawn at `size` (the base font size, SVG units): a subscript as a
/// `<tspan>` [`font::SUB_SIZE`] times smaller, lowered by `dy` = [`font::SUB_SHIFT_EM`]
/// ems, and the base text after it in a `<tspan>` raised back; flat-only runs left out. No
/// white space between the runs (a reader would draw it as a space). `dy` rather than
/// `baseline-shift`: rsvg, resvg and Chromium place it alike. The raised-back run keeps its
/// spaces (`xml:space="preserve"`): rsvg drops a tspan's leading space (`k_v = 1` drawn
/// `kv= 1`), resvg and Chromium do not.
fn push_runs(out: &mut Vec<u8>, value: &str, runs: &Runs, size: f64) {
    let shift = font::SUB_SHIFT_EM * size;
    let mut lowered = false;
    for (part, kind) in runs.split(value) {
        match kind {
            RunKind::Flat => {}
            RunKind::Sub => {
                out.extend_from_slice(b"<tspan");
                if !lowered {
                    push_attr_num(out, "dy", shift);
                }
                push_attr_num(out, "font-size", font::SUB_SIZE * size);
                out.push(b'>');
                push_text(out, part);
                out.extend_from_slice(b"</tspan>");
                lowered = true;
            }
            RunKind::Base if lowered => {
                out.extend_from_slice(b"<tspan");
                push_attr_num(out, "dy", -shift);
                out.extend_from_slice(b" xml:space=\"preserve\">");
                push_text(out, part);
                out.extend_from_slice(b"</tspan>");
                lowered = false;
            }
            RunKind::Base => push_text(out, part),
        }
    }
}

/// Appends ` name="value"` with the number written as everywhere in the SVG.
fn push_attr_num(out: &mut Vec<u8>, name: &str, v: f64) {
    out.push(b' ');
    out.extend_from_slice(name.as_bytes());
    out.extend_from_slice(b"=\"");
    push_num(out, v);
    out.push(b'"');
}

/// Appends an arc's path data: counter-clockwise from `start` to `end`.
fn arc_path(d: &mut Vec<u8>, f: &Frame, center: Point, radius: f64, start: f64, end: f64) {
    // Counter-clockwise from start to end, wrapping through 0 when end < start (as in DXF).
    let sweep = arc_sweep(start, end);
    // SVG arcs cannot draw a full circle in one command: split into two halves.
    let n = if sweep.abs() > std::f64::consts::PI { 2 } else { 1 };
    let (sx, sy) = f.pt(polar(center, radius, start));
    d.push(b'M');
    push_num(d, sx);
    d.push(b',');
    push_num(d, sy);
    for i in 1..=n {
        let a = start + sweep * i as f64 / n as f64;
        let (x, y) = f.pt(polar(center, radius, a));
        // Counter-clockwise in the model = sweep-flag 0 in SVG's flipped frame.
        let r = f.len(radius);
        d.extend_from_slice(b" A");
        push_num(d, r);
        d.push(b',');
        push_num(d, r);
        d.extend_from_slice(b" 0 0 0 ");
        push_num(d, x);
        d.push(b',');
        push_num(d, y);
    }
}

#[cfg(test)]
#[allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the code under test calls"
)]
mod tests {
    use super::*;
    use crate::draw::{DimStyle, LinearMarks};

    #[test]
    fn y_is_flipped_once_and_viewbox_fits_content() {
        let mut d = Drawing::new(DimStyle { text_height: 1.0, arrow_size: 1.0 });
        d.add(0, Shape::Line { from: Point::new(0.0, 0.0), to: Point::new(10.0, 20.0) });
        let s = to_string(&d, &SvgOptions { margin: 0.0, ..Default::default() });
        assert!(s.contains(r#"y2="-20""#), "{s}");
        assert!(s.contains(r#"viewBox="0 -20 10 20""#), "{s}");
    }

    #[test]
    fn entities_keep_drawing_order_across_layers() {
        let mut d = Drawing::new(DimStyle { text_height: 1.0, arrow_size: 1.0 });
        let (a, b) = (d.layer("A", Aci::RED, LineType::Continuous), d.layer("B", Aci::BLUE, LineType::Continuous));
        let line = |x: f64| Shape::Line { from: Point::new(x, 0.0), to: Point::new(x, 1.0) };
        d.add(a, line(1.0));
        d.add(b, line(2.0));
        d.add(a, line(3.0));
        let s = to_string(&d, &SvgOptions::default());
        let pos = |x: &str| s.find(&format!(r#"x1="{x}""#)).unwrap();
        assert!(pos("1") < pos("2") && pos("2") < pos("3"), "{s}");
        assert_eq!(s.matches(r#"class="layer-A""#).count(), 2);
    }

    #[test]
    fn a_paper_scale_sizes_the_page_in_mm() {
        // A 0.1 m line at 500 paper mm per metre (k_l = 0.002 m/mm) is 50 mm on paper.
        let mut d = Drawing::new(DimStyle { text_height: 0.01, arrow_size: 0.01 });
        d.add(0, Shape::Line { from: Point::new(0.0, 0.0), to: Point::new(0.1, 0.0) });
        d.text(0, Point::new(0.0, 0.02), 0.007, "A");
        d.paper_mm_per_unit = Some(500.0);
        let s = to_string(&d, &SvgOptions { margin: 0.0, ..Default::default() });
        assert!(s.contains(r#"x2="50""#), "{s}");
        assert!(s.contains(r#"width="50mm""#), "{s}");
        // Text 3.5 mm high on paper: font-size 3.5 / 0.73.
        assert!(s.contains(&format!(r#"font-size="{}""#, num(3.5 / 0.73))), "{s}");
        // The options' scale wins over the drawing's.
        let s = to_string(&d, &SvgOptions { margin: 0.0, paper_mm_per_unit: Some(1000.0), ..Default::default() });
        assert!(s.contains(r#"width="100mm""#), "{s}");
    }

    /// The reference: `format!("{v:.6}")` trimmed, as `num` was written first.
    fn num_by_format(v: f64) -> String {
        let mut s = format!("{v:.6}");
        let len = s.trim_end_matches('0').trim_end_matches('.').len();
        s.truncate(len);
        if s == "-0" {
            s.remove(0);
        }
        s
    }

    #[test]
    fn the_fast_path_writes_what_format_writes() {
        use rand::{RngExt, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let mut values = vec![
            0.0,
            -0.0,
            0.5e-6,
            -0.5e-6,
            1.5e-6,
            2.5e-6,
            0.4999999e-6,
            1e-7,
            -1e-7,
            123.4565,
            0.1,
            0.7,
            1e6,
            -1e6,
            999_999.999_999_5,
            1e5 + 0.0000005,
            2.0f64.powi(20) + 0.25,
        ];
        for _ in 0..400_000 {
            let mag = 10f64.powf(rng.random_range(-9.0..7.0));
            let v: f64 = rng.random_range(-1.0..1.0) * mag;
            values.push(v);
            // Near the ties of the sixth decimal.
            let tie = ((v * 1e6).floor() + 0.5) / 1e6;
            values.extend([tie, f64::from_bits(tie.to_bits() + 1), f64::from_bits(tie.to_bits().saturating_sub(1))]);
        }
        for v in values {
            assert_eq!(num(v), num_by_format(v), "{v:e}");
        }
    }

    #[test]
    fn numbers_are_fixed_format() {
        assert_eq!(num(1.0), "1");
        assert_eq!(num(-0.0000001), "0");
        assert_eq!(num(2.5), "2.5");
        assert_eq!(num(1.0 / 3.0), "0.333333");
    }

    /// A drawing with every kind of entity, on layers in and out of order, dashed and
    /// coloured, with text that needs escaping, a layer whose only entity writes nothing
    /// (a zero-length arrow) and dimensions.
    fn every_kind() -> Drawing {
        let mut d = Drawing::new(DimStyle { text_height: 2.5, arrow_size: 2.0 });
        let a = d.layer("A&<\"'>", Aci::RED, LineType::Dashed);
        let b = d.layer("B", Aci::BLUE, LineType::Continuous);
        let c = d.layer("EMPTY", Aci::BLACK, LineType::Continuous);
        let p = Point::new;
        d.add(a, Shape::Circle { center: p(1.25, -3.5), radius: 4.0 });
        d.add(a, Shape::Arc { center: p(0.0, 0.0), radius: 3.0, start: 0.3, end: 5.9 });
        d.add(b, Shape::Arc { center: p(2.0, 1.0), radius: 1.0 / 3.0, start: 2.0, end: 1.0 });
        d.add(b, Shape::Line { from: p(0.1, 0.2), to: p(-7.0, 1e-9) });
        d.add_colored(
            b,
            Aci::GREEN,
            Shape::Polyline { points: vec![p(0.0, 0.0), p(1.0, 2.0), p(3.0, -1.0)], closed: false, width: 0.0 },
        );
        d.add(a, Shape::Polyline { points: vec![p(0.0, 0.0), p(1.0, 2.0), p(3.0, -1.0)], closed: true, width: 0.7 });
        d.add(c, Shape::Arrow { from: p(1.0, 1.0), to: p(1.0, 1.0), head: 1.0 });
        d.add(b, Shape::Filled { points: vec![p(0.0, 0.0), p(1.0, 0.0), p(0.5, 0.8)] });
        d.add(b, Shape::Arrow { from: p(-1.0, -1.0), to: p(5.0, 2.0), head: 1.5 });
        for (i, (h, v)) in
            [(HAlign::Left, VAlign::Baseline), (HAlign::Center, VAlign::Middle), (HAlign::Right, VAlign::Top)]
                .into_iter()
                .enumerate()
        {
            d.add(
                a,
                Shape::Text {
                    runs: crate::draw::Runs::flat(),
                    at: p(i as f64, 2.0 * i as f64),
                    height: 2.5,
                    value: ["x < y & \"z\" > 'w'", "", "φ1 = 75.77°"][i].into(),
                    halign: h,
                    valign: v,
                    rotation: [0.0, 0.5, -1.25][i],
                },
            );
        }
        d.add(
            b,
            Shape::AngularDimension {
                vertex: p(0.0, 0.0),
                first: p(5.0, 0.0),
                second: p(0.0, 5.0),
                radius: 4.0,
                text: "90°".into(),
                runs: Default::default(),
            },
        );
        d.add(
            a,
            Shape::LinearDimension {
                p1: p(0.0, 0.0),
                p2: p(10.0, 3.0),
                line_at: p(0.0, -4.0),
                angle: 0.0,
                text: "10 ±0.1".into(),
                marks: LinearMarks::default(),
            },
        );
        d.add(c, Shape::Arrow { from: p(3.0, 3.0), to: p(3.0, 3.0), head: 1.0 });
        d
    }

    #[test]
    fn the_direct_writer_writes_what_the_svg_element_tree_wrote() {
        let d = every_kind();
        let windows = [None, Some(Bounds { min: Point::new(-20.0, -20.0), max: Point::new(30.0, 10.0) })];
        for window in windows {
            for paper in [None, Some(0.5)] {
                let opts = SvgOptions { window, paper_mm_per_unit: paper, ..SvgOptions::default() };
                assert_eq!(to_string(&d, &opts), reference::to_string(&d, &opts), "{opts:?}");
            }
        }
        // No entities: the header and the background only.
        let empty = Drawing::new(DimStyle { text_height: 1.0, arrow_size: 1.0 });
        assert_eq!(to_string(&empty, &SvgOptions::default()), reference::to_string(&empty, &SvgOptions::default()));
    }

    /// Every template's drawings (picture or every position's frame, sheets, diagrams,
    /// printed pages) written by both writers.
    #[test]
    fn every_template_is_written_as_the_svg_element_tree_wrote_it() {
        use crate::run::products::Picture;
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("templates");
        let mut paths: Vec<_> = std::fs::read_dir(&root).unwrap().map(|e| e.unwrap().path()).collect();
        paths.retain(|p| p.extension().is_some_and(|e| e == "toml"));
        assert!(paths.len() >= 7);
        for path in paths {
            let text = std::fs::read_to_string(&path).unwrap();
            // Fewer positions and samples, as in tests/run_products.rs; printed pages where
            // the kind has them.
            let kind = text.lines().find_map(|l| l.strip_prefix("kind = ")).unwrap().trim_matches('"');
            let set: &[&str] = match kind {
                "fourbar" => &["phi1_deg.step=30"],
                "linkage" => &["time.steps=12"],
                "chain" => &["stackup.samples=20000"],
                _ => &[],
            };
            let over: Vec<crate::scene::Override> = set.iter().map(|s| s.parse().unwrap()).collect();
            let loaded = crate::scene::load(&path, &over).unwrap();
            let sheets = matches!(kind, "fourbar" | "linkage").then_some(crate::figure::shared::sheet::Paper::A4);
            let opts = crate::run::RunOptions { sheets, ..Default::default() };
            let p = crate::run::products(&loaded, &opts).unwrap();
            let mut drawings: Vec<(Drawing, SvgOptions)> = Vec::new();
            match &p.picture {
                Picture::Still(d) => drawings.push((d.clone(), SvgOptions::default())),
                Picture::Motion(a) => {
                    let poses = a.poses();
                    let opts = SvgOptions {
                        window: Some(a.window(&poses)),
                        paper_mm_per_unit: a.base.paper_mm_per_unit,
                        ..SvgOptions::default()
                    };
                    drawings.extend(poses.iter().map(|pose| (a.frame_of(pose), opts)));
                }
            }
            drawings.extend(p.sheets.iter().map(|s| (s.drawing.clone(), SvgOptions::default())));
            drawings.extend(p.diagrams.iter().map(|s| (s.drawing.clone(), SvgOptions::default())));
            drawings.extend(p.pages.iter().map(|s| {
                (
                    s.drawing.clone(),
                    SvgOptions {
                        margin: 0.0,
                        window: Some(s.window),
                        paper_mm_per_unit: Some(1.0),
                        ..SvgOptions::default()
                    },
                )
            }));
            assert!(!drawings.is_empty());
            for (i, (d, opts)) in drawings.iter().enumerate() {
                let (direct, tree) = (to_string(d, opts), reference::to_string(d, opts));
                let first = direct.lines().zip(tree.lines()).find(|(a, b)| a != b);
                assert!(direct == tree, "{}: drawing {i}: {first:?}", path.display());
            }
        }
    }

    /// An independent parse: usvg reads the direct writer's SVG back (escaped text and
    /// layer names included) and finds every element drawn.
    #[test]
    fn usvg_reads_back_every_kind_of_element() {
        use resvg::usvg;
        let d = every_kind();
        let s = to_string(&d, &SvgOptions::default());
        let mut db = usvg::fontdb::Database::new();
        db.load_font_data(crate::draw::raster::FONT.to_vec());
        let opts = usvg::Options { fontdb: std::sync::Arc::new(db), ..usvg::Options::default() };
        let tree = usvg::Tree::from_str(&s, &opts).expect("usvg parses the writer's SVG");
        fn walk(g: &usvg::Group, paths: &mut usize, texts: &mut Vec<String>) {
            for n in g.children() {
                match n {
                    usvg::Node::Group(g) => walk(g, paths, texts),
                    usvg::Node::Path(_) => *paths += 1,
                    usvg::Node::Text(t) => texts.push(t.chunks().iter().map(|c| c.text().to_string()).collect()),
                    usvg::Node::Image(_) => {}
                }
            }
        }
        let (mut paths, mut texts) = (0, Vec::new());
        walk(tree.root(), &mut paths, &mut texts);
        // The XML as written: one element per line after the header, and what usvg makes of it.
        let count = |tag: &str| s.lines().filter(|l| l.starts_with(tag)).count();
        let drawn = count("<rect")
            + count("<circle")
            + count("<path")
            + count("<line")
            + count("<polyline")
            + count("<polygon");
        assert!(drawn >= 12, "{s}");
        assert_eq!(paths, drawn, "{s}");
        assert!(texts.iter().any(|t| t.contains("x < y & \"z\" > 'w'")), "{texts:?}");
        assert!(texts.iter().any(|t| t.contains("φ1 = 75.77°")), "{texts:?}");
        assert!(texts.iter().any(|t| t.contains("10 ±0.1")), "{texts:?}");
    }
}
