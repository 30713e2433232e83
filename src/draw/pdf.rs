//! Drawings to one multi-page PDF, through krilla: each page a window of a [`Drawing`]
//! printed at its paper scale ([`Drawing::paper_mm_per_unit`], one paper millimetre per
//! model unit when it has none), so that the page measures true at 100 % print. Text is
//! real text in the bundled DejaVu Sans ([`super::FONT`]), embedded as a subset with
//! its Unicode map, so a reader can search and copy it (`pdftotext` reads `φ1 = 90°` back).
//!
//! It writes what the SVG writer writes, from the same neutral drawing: the same colours,
//! stroke widths, dash pattern, arrowheads and exploded dimensions; text of the same cap
//! height ([`CAP_HEIGHT_EM`]) with the same alignment (widths measured on the font's
//! advances). Output is deterministic: no dates, the same drawings give the same bytes
//! (tested). Nothing here knows a mechanism.

use krilla::Document;
use krilla::color::rgb;
use krilla::geom::{Path, PathBuilder, Point as KPoint, Transform};
use krilla::num::NormalizedF32;
use krilla::page::PageSettings;
use krilla::paint::{Fill, LineCap, LineJoin, Stroke, StrokeDash};
use krilla::text::{Font, GlyphId, KrillaGlyph};
use skrifa::MetadataProvider;

use super::font::{SUB_SHIFT_EM, SUB_SIZE};
use super::parts::{CAP_HEIGHT_EM, arc_sweep, arrow, dash_pattern, explode_dimension};
use super::{Aci, Bounds, Drawing, Entity, HAlign, LineType, RunKind, Shape, VAlign};
use crate::geom::{Point, polar};

/// PDF points per millimetre.
const PT_PER_MM: f64 = 72.0 / 25.4;

/// Errors of the PDF writer.
#[derive(Debug, thiserror::Error)]
pub enum PdfError {
    /// A page would be empty or too large (a window of zero size, or more than the 5 m a PDF
    /// page can hold): `width` × `height` mm.
    #[error("a PDF page cannot be {width} × {height} mm")]
    PageSize {
        /// Width, mm.
        width: f64,
        /// Height, mm.
        height: f64,
    },
    /// The bundled font could not be read (a broken build).
    #[error("the bundled font cannot be read")]
    Font,
    /// krilla refused the document.
    #[error("PDF serialisation failed: {0}")]
    Serialize(String),
}

/// One page: the part of `drawing` inside `window` (model units), printed at the drawing's
/// paper scale.
#[derive(Debug, Clone, Copy)]
pub struct Page<'a> {
    /// The drawing.
    pub drawing: &'a Drawing,
    /// The model-space window that fills the page (a sheet's paper, 0…297 × 0…210 mm).
    pub window: Bounds,
    /// Thinnest stroke on paper, mm (a 0-width polyline draws this).
    pub hairline_mm: f64,
}

/// The pages as one PDF document, in order.
pub fn to_bytes(pages: &[Page<'_>]) -> Result<Vec<u8>, PdfError> {
    let font_data: &'static [u8] = super::FONT;
    let font = Font::new(font_data.into(), 0).ok_or(PdfError::Font)?;
    let metrics = Metrics::new(font_data)?;
    let mut document = Document::new();
    for page in pages {
        let k = page.drawing.paper_mm_per_unit.filter(|k| k.is_finite() && *k > 0.0).unwrap_or(1.0);
        let (w_mm, h_mm) = (page.window.width() * k, page.window.height() * k);
        let size = (w_mm > 0.0 && h_mm > 0.0 && w_mm <= 5000.0 && h_mm <= 5000.0)
            .then(|| PageSettings::from_wh((w_mm * PT_PER_MM) as f32, (h_mm * PT_PER_MM) as f32))
            .flatten()
            .ok_or(PdfError::PageSize { width: w_mm, height: h_mm })?;
        let mut p = document.start_page_with(size);
        let mut surface = p.surface();
        let frame = Frame {
            k: k * PT_PER_MM,
            origin: Point::new(page.window.min.x, page.window.max.y),
            hairline: page.hairline_mm / k,
            dash: dash_pattern(page.window.width().max(page.window.height())),
        };
        for e in &page.drawing.entities {
            entity(&mut surface, page.drawing, e, &frame, &font, &metrics);
        }
        surface.finish();
        p.finish();
    }
    document.finish().map_err(|e| PdfError::Serialize(format!("{e:?}")))
}

/// Model coordinates (y up) to PDF points on the page (y down from the top-left corner).
struct Frame {
    /// Points per model unit.
    k: f64,
    /// The model point at the page's top-left corner.
    origin: Point,
    /// Thinnest stroke, model units.
    hairline: f64,
    /// Dash and gap of dashed lines, model units.
    dash: (f64, f64),
}

impl Frame {
    fn pt(&self, p: Point) -> (f32, f32) {
        ((self.k * (p.x - self.origin.x)) as f32, (self.k * (self.origin.y - p.y)) as f32)
    }
    fn len(&self, l: f64) -> f32 {
        (self.k * l) as f32
    }
}

/// Glyph ids and advances of the bundled font, for placing text as the SVG does.
struct Metrics<'a> {
    font: skrifa::FontRef<'a>,
    upem: f32,
}

impl<'a> Metrics<'a> {
    fn new(data: &'a [u8]) -> Result<Metrics<'a>, PdfError> {
        let font = skrifa::FontRef::new(data).map_err(|_| PdfError::Font)?;
        let upem = font
            .metrics(skrifa::instance::Size::unscaled(), skrifa::instance::LocationRef::default())
            .units_per_em as f32;
        Ok(Metrics { font, upem })
    }

    /// One glyph per character (DejaVu Sans needs no shaping for the texts we draw), with
    /// its advance per em; a character the font lacks draws as glyph 0 (.notdef).
    fn glyphs(&self, text: &str) -> Vec<KrillaGlyph> {
        let charmap = self.font.charmap();
        let gm = self.font.glyph_metrics(skrifa::instance::Size::unscaled(), skrifa::instance::LocationRef::default());
        text.char_indices()
            .map(|(i, c)| {
                let gid = charmap.map(c).unwrap_or_default();
                let adv = gm.advance_width(gid).unwrap_or(0.0) / self.upem;
                KrillaGlyph {
                    glyph_id: GlyphId::new(gid.to_u32()),
                    text_range: i..i + c.len_utf8(),
                    x_advance: adv,
                    x_offset: 0.0,
                    y_offset: 0.0,
                    y_advance: 0.0,
                    location: None,
                }
            })
            .collect()
    }
}

fn color(c: Aci) -> rgb::Color {
    let (r, g, b) = c.rgb();
    rgb::Color::new(r, g, b)
}

fn stroke(c: Aci, width: f32, dash: Option<(f32, f32)>) -> Stroke {
    Stroke {
        paint: color(c).into(),
        width,
        miter_limit: 10.0,
        line_cap: LineCap::Round,
        line_join: LineJoin::Round,
        opacity: NormalizedF32::ONE,
        dash: dash.map(|(d, g)| StrokeDash { array: vec![d, g], offset: 0.0 }),
    }
}

fn fill(c: Aci) -> Fill {
    Fill { paint: color(c).into(), opacity: NormalizedF32::ONE, rule: Default::default() }
}

/// A polyline through `points` (closed when asked).
fn polyline(f: &Frame, points: &[Point], closed: bool) -> Option<Path> {
    let mut pb = PathBuilder::new();
    let (first, rest) = points.split_first()?;
    let (x, y) = f.pt(*first);
    pb.move_to(x, y);
    for p in rest {
        let (x, y) = f.pt(*p);
        pb.line_to(x, y);
    }
    if closed {
        pb.close();
    }
    pb.finish()
}

/// A counter-clockwise arc (model angles) as cubic Béziers of at most 90° each.
fn arc(f: &Frame, center: Point, radius: f64, start: f64, sweep: f64) -> Option<Path> {
    let n = ((sweep.abs() / std::f64::consts::FRAC_PI_2).ceil() as usize).max(1);
    let step = sweep / n as f64;
    // Control-arm length of a cubic approximating an arc of `step`.
    let t = 4.0 / 3.0 * libm::tan(step / 4.0);
    let mut pb = PathBuilder::new();
    let (x, y) = f.pt(polar(center, radius, start));
    pb.move_to(x, y);
    for i in 0..n {
        let (a0, a1) = (start + step * i as f64, start + step * (i + 1) as f64);
        let (p0, p3) = (polar(center, radius, a0), polar(center, radius, a1));
        let d0 = crate::geom::Vector::new(-libm::sin(a0), libm::cos(a0)) * (radius * t);
        let d1 = crate::geom::Vector::new(-libm::sin(a1), libm::cos(a1)) * (radius * t);
        let ((x1, y1), (x2, y2), (x3, y3)) = (f.pt(p0 + d0), f.pt(p3 - d1), f.pt(p3));
        pb.cubic_to(x1, y1, x2, y2, x3, y3);
    }
    pb.finish()
}

/// The page transform that turns by `angle` (radians in the page's axes, y down: a positive
/// angle turns clockwise as seen) about `(x, y)`, as krilla's `Transform::from_rotate_at`
/// does in degrees, but computed with `libm` in f64: the same bits on every target (krilla's
/// takes the platform's `f32` sine and cosine).
fn rotation_about(angle: f64, x: f32, y: f32) -> Transform {
    let (s, c) = libm::sincos(angle);
    let (px, py) = (f64::from(x), f64::from(y));
    let (tx, ty) = (px - c * px + s * py, py - s * px - c * py);
    Transform::from_row(c as f32, s as f32, -s as f32, c as f32, tx as f32, ty as f32)
}

fn entity(
    surface: &mut krilla::surface::Surface<'_>,
    drawing: &Drawing,
    e: &Entity,
    f: &Frame,
    font: &Font,
    metrics: &Metrics<'_>,
) {
    let c = drawing.color_of(e);
    let dash = (drawing.linetype_of(e) == LineType::Dashed).then(|| (f.len(f.dash.0), f.len(f.dash.1)));
    let stroked = |surface: &mut krilla::surface::Surface<'_>, path: Option<Path>, width: f64| {
        if let Some(path) = path {
            surface.set_fill(None);
            surface.set_stroke(Some(stroke(c, f.len(width.max(f.hairline)), dash)));
            surface.draw_path(&path);
        }
    };
    let filled = |surface: &mut krilla::surface::Surface<'_>, path: Option<Path>| {
        if let Some(path) = path {
            surface.set_stroke(None);
            surface.set_fill(Some(fill(c)));
            surface.draw_path(&path);
        }
    };
    match &e.shape {
        Shape::Circle { center, radius } => stroked(surface, arc(f, *center, *radius, 0.0, std::f64::consts::TAU), 0.0),
        Shape::Arc { center, radius, start, end } => {
            stroked(surface, arc(f, *center, *radius, *start, arc_sweep(*start, *end)), 0.0)
        }
        Shape::Line { from, to } => stroked(surface, polyline(f, &[*from, *to], false), 0.0),
        Shape::Polyline { points, closed, width } => stroked(surface, polyline(f, points, *closed), *width),
        Shape::Filled { points } => filled(surface, polyline(f, points, true)),
        Shape::Arrow { from, to, head } => {
            if let Some((base, tri)) = arrow(*from, *to, *head) {
                stroked(surface, polyline(f, &[*from, base], false), 0.0);
                filled(surface, polyline(f, &tri, true));
            }
        }
        Shape::Text { at, height, value, runs, halign, valign, rotation } => {
            surface.set_stroke(None);
            surface.set_fill(Some(fill(c)));
            let place = Placing { at: *at, height: *height, halign: *halign, valign: *valign, rotation: *rotation };
            text(surface, f, (font, metrics), (value, runs), place);
        }
        caption @ Shape::ScaleText { .. } => {
            // On the page's paper (a page in paper millimetres says 1).
            if let Some(shape) = caption.scale_text_in(drawing.paper_mm_per_unit) {
                entity(surface, drawing, &Entity { shape, ..e.clone() }, f, font, metrics);
            }
        }
        dim @ (Shape::AngularDimension { .. } | Shape::LinearDimension { .. }) => {
            for part in explode_dimension(dim, &drawing.dim_style) {
                let sub = Entity { layer: e.layer, color: e.color, linetype: Some(LineType::Continuous), shape: part };
                entity(surface, drawing, &sub, f, font, metrics);
            }
        }
    }
}

/// Where and how a text is placed: [`Shape::Text`]'s fields but its value and runs.
struct Placing {
    at: Point,
    height: f64,
    halign: HAlign,
    valign: VAlign,
    rotation: f64,
}

/// Draws a text in its runs (the fill set): base runs at the font size of its cap height,
/// subscripts [`SUB_SIZE`] times it on a baseline [`SUB_SHIFT_EM`] ems lower, one glyph run
/// each; flat-only runs not drawn. The text a reader extracts is the letters drawn: `RA` for
/// R_A, `kv = 2` for k_v = 2, `φ1` for φ_1 (the `_` is only the DXF's). Aligned on the width of what is drawn, as [`super::font::measure_runs`] measures it.
fn text(
    surface: &mut krilla::surface::Surface<'_>,
    f: &Frame,
    (font, metrics): (&Font, &Metrics<'_>),
    (value, runs): (&str, &super::Runs),
    p: Placing,
) {
    let size = f.len(p.height / CAP_HEIGHT_EM);
    // (text, its glyphs, size, rise) per drawn run.
    let parts: Vec<(&str, Vec<KrillaGlyph>, f32, f32)> = runs
        .split(value)
        .filter_map(|(part, kind)| {
            let (scale, rise) = match kind {
                RunKind::Base => (1.0, 0.0),
                RunKind::Sub => (SUB_SIZE as f32, SUB_SHIFT_EM as f32),
                RunKind::Flat => return None,
            };
            Some((part, metrics.glyphs(part), scale * size, rise * size))
        })
        .collect();
    let width: f32 = parts.iter().map(|(_, g, sz, _)| g.iter().map(|g| g.x_advance).sum::<f32>() * sz).sum();
    let dx = match p.halign {
        HAlign::Left => 0.0,
        HAlign::Center => -0.5 * width,
        HAlign::Right => -width,
    };
    let dy = f.len(match p.valign {
        VAlign::Baseline => 0.0,
        VAlign::Middle => 0.5 * p.height,
        VAlign::Top => p.height,
    });
    let (x, y) = f.pt(p.at);
    // Rotated about the insertion point, counter-clockwise on the page (y is down).
    let turn = p.rotation != 0.0;
    if turn {
        surface.push_transform(&rotation_about(-p.rotation, x, y));
    }
    let mut pen = x + dx;
    for (part, glyphs, sz, rise) in &parts {
        surface.draw_glyphs(KPoint::from_xy(pen, y + dy + rise), glyphs, font.clone(), part, *sz, false);
        pen += glyphs.iter().map(|g| g.x_advance).sum::<f32>() * sz;
    }
    if turn {
        surface.pop();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::draw::DimStyle;

    fn page_drawing() -> Drawing {
        let mut d = Drawing::new(DimStyle { text_height: 2.5, arrow_size: 2.5 });
        d.add(0, Shape::Line { from: Point::new(10.0, 10.0), to: Point::new(100.0, 10.0) });
        d.add(0, Shape::Circle { center: Point::new(50.0, 50.0), radius: 10.0 });
        d.text(0, Point::new(20.0, 100.0), 5.0, "φ1 = 90°");
        d.paper_mm_per_unit = Some(1.0);
        d
    }

    /// Our rotation is krilla's (to f32 rounding), turned the same way about the same point.
    #[test]
    fn a_rotation_about_a_point_is_krillas() {
        for (deg, x, y) in [(30.0f32, 10.0f32, 20.0f32), (-90.0, 0.0, 0.0), (137.5, -42.0, 118.25), (0.0, 5.0, 5.0)] {
            let ours = rotation_about(f64::from(deg).to_radians(), x, y);
            let theirs = Transform::from_rotate_at(deg, x, y);
            let pairs = [
                (ours.sx(), theirs.sx()),
                (ours.ky(), theirs.ky()),
                (ours.kx(), theirs.kx()),
                (ours.sy(), theirs.sy()),
                (ours.tx(), theirs.tx()),
                (ours.ty(), theirs.ty()),
            ];
            for (a, b) in pairs {
                assert!((a - b).abs() <= 1e-5 * (1.0 + x.abs() + y.abs()), "{deg}° at ({x}, {y}): {a} vs {b}");
            }
        }
    }

    #[test]
    fn pages_are_deterministic() {
        let d = page_drawing();
        let window = Bounds { min: Point::new(0.0, 0.0), max: Point::new(297.0, 210.0) };
        let page = Page { drawing: &d, window, hairline_mm: 0.25 };
        let a = to_bytes(&[page, page]).unwrap();
        let b = to_bytes(&[page, page]).unwrap();
        assert_eq!(a, b, "the same drawing gives the same bytes");
        let s = String::from_utf8_lossy(&a);
        assert!(s.starts_with("%PDF-"));
        // Page count, size and text are read back with poppler in tests/sheets.rs.
    }

    #[test]
    fn an_empty_window_is_refused() {
        let d = page_drawing();
        let window = Bounds { min: Point::new(0.0, 0.0), max: Point::new(0.0, 210.0) };
        assert!(matches!(to_bytes(&[Page { drawing: &d, window, hairline_mm: 0.25 }]), Err(PdfError::PageSize { .. })));
    }
}
