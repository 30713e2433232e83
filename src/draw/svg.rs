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

use svg::Document;
use svg::Node as _;
use svg::node::element::{Circle, Group, Line, Path, Polygon, Polyline, Rectangle, Text};

use super::parts::{arc_sweep, arrow, dash_pattern, explode_dimension};
use super::{Aci, Bounds, Drawing, Entity, HAlign, LineType, Shape, VAlign};
use crate::geom::{Point, polar};

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
    let scaled = v * 1e6;
    if scaled.abs() < 1e12 {
        let floor = scaled.floor();
        let frac = scaled - floor;
        if (frac - 0.5).abs() > 1e-3 {
            let units = (if frac > 0.5 { floor + 1.0 } else { floor }) as i64;
            return fixed6(units);
        }
    }
    let mut s = format!("{v:.6}");
    // Trimmed in place: this is called for every coordinate of every frame.
    let len = s.trim_end_matches('0').trim_end_matches('.').len();
    s.truncate(len);
    if s == "-0" {
        s.remove(0);
    }
    s
}

/// `units`·10⁻⁶ as `num` writes it: trailing zeros and a bare point trimmed, no `-0`.
fn fixed6(units: i64) -> String {
    if units == 0 {
        return "0".to_string();
    }
    let neg = units < 0;
    let u = units.unsigned_abs();
    let (int, mut frac) = (u / 1_000_000, u % 1_000_000);
    let mut s = String::with_capacity(20);
    if neg {
        s.push('-');
    }
    s.push_str(&int.to_string());
    if frac != 0 {
        let mut digits = 6;
        while frac % 10 == 0 {
            frac /= 10;
            digits -= 1;
        }
        s.push('.');
        let f = frac.to_string();
        for _ in f.len()..digits {
            s.push('0');
        }
        s.push_str(&f);
    }
    s
}

fn rgb(c: Aci) -> String {
    let (r, g, b) = c.rgb();
    format!("#{r:02x}{g:02x}{b:02x}")
}

/// Renders `drawing` as an SVG document string.
pub fn to_string(drawing: &Drawing, opts: &SvgOptions) -> String {
    let bounds = opts
        .window
        .or_else(|| drawing.bounds())
        .unwrap_or(Bounds { min: Point::new(0.0, 0.0), max: Point::new(1.0, 1.0) });
    let extent = bounds.width().max(bounds.height()).max(f64::MIN_POSITIVE);
    let margin = opts.margin * extent;
    let paper = opts.paper_mm_per_unit.or(drawing.paper_mm_per_unit).filter(|k| k.is_finite() && *k > 0.0);
    let frame = Frame { k: paper.unwrap_or(1.0), hairline: opts.hairline * extent, dash: dash_pattern(extent) };
    let (x0, y0) = frame.pt(Point::new(bounds.min.x - margin, bounds.max.y + margin));
    let (w, h) = (bounds.width() + 2.0 * margin, bounds.height() + 2.0 * margin);
    let w = frame.len(w.max(extent * 1e-3));
    let h = frame.len(h.max(extent * 1e-3));
    let (width, height) = match paper {
        Some(_) => (format!("{}mm", num(w)), format!("{}mm", num(h))),
        None => {
            let height_px = ((opts.width_px as f64) * h / w).round().max(1.0) as u32;
            (opts.width_px.to_string(), height_px.to_string())
        }
    };

    let mut doc = Document::new()
        .set("viewBox", format!("{} {} {} {}", num(x0), num(y0), num(w), num(h)))
        .set("width", width)
        .set("height", height)
        .set("font-family", FONT_FAMILY)
        .add(
            Rectangle::new()
                .set("x", num(x0))
                .set("y", num(y0))
                .set("width", num(w))
                .set("height", num(h))
                .set("fill", "#ffffff"),
        );

    // Entities in drawing order (later ones on top, as in the DXF), grouped into runs of
    // consecutive entities on one layer: `<g class="layer-NAME">` (a layer may have several).
    let mut run: Option<(usize, Group)> = None;
    for e in &drawing.entities {
        if run.as_ref().is_some_and(|(layer, _)| *layer != e.layer) {
            if let Some((_, g)) = run.take() {
                doc = doc.add(g);
            }
        }
        let (_, g) = run.get_or_insert_with(|| {
            let g = Group::new()
                .set("class", format!("layer-{}", drawing.layers[e.layer].name))
                .set("fill", "none")
                .set("stroke-linecap", "round")
                .set("stroke-linejoin", "round");
            (e.layer, g)
        });
        for node in entity_nodes(drawing, e, &frame) {
            *g = std::mem::take(g).add(node);
        }
    }
    if let Some((_, g)) = run {
        doc = doc.add(g);
    }
    doc.to_string()
}

/// The frames of an animation without rewriting their shared part: the SVG of a drawing
/// `base` followed by a drawing `moving`, both written by [`to_string`] with the same
/// options (so with the same header). It is `base_svg` without its closing tag, then
/// `moving_svg` after its header (the `<svg>` line and the background `<rect>` line): the
/// writer's output for base's entities then moving's, as long as base's last entity and
/// moving's first are on different layers (else the writer would put them in one group).
/// `None` when the two headers differ (then write the frame whole).
pub fn splice(base_svg: &str, moving_svg: &str) -> Option<String> {
    const CLOSE: &str = "</svg>";
    let header_end = |s: &str| -> Option<usize> {
        let first = s.find('\n')?;
        Some(first + 1 + s[first + 1..].find('\n')? + 1)
    };
    let (hb, hm) = (header_end(base_svg)?, header_end(moving_svg)?);
    if base_svg[..hb] != moving_svg[..hm] || !base_svg.ends_with(CLOSE) {
        return None;
    }
    let head = &base_svg[..base_svg.len() - CLOSE.len()];
    let mut out = String::with_capacity(head.len() + moving_svg.len() - hm);
    out.push_str(head);
    out.push_str(&moving_svg[hm..]);
    Some(out)
}

/// Writes `drawing` as SVG to `out`.
pub fn write(drawing: &Drawing, opts: &SvgOptions, mut out: impl Write) -> std::io::Result<()> {
    out.write_all(to_string(drawing, opts).as_bytes())
}

fn entity_nodes(drawing: &Drawing, e: &Entity, f: &Frame) -> Vec<Box<dyn svg::Node>> {
    let color = rgb(drawing.color_of(e));
    let dashed = drawing.linetype_of(e) == LineType::Dashed;
    let mut nodes: Vec<Box<dyn svg::Node>> = Vec::new();
    let stroke = |w: f64| -> (String, String) { (color.clone(), num(f.len(w.max(f.hairline)))) };
    let (dash, gap) = (num(f.len(f.dash.0)), num(f.len(f.dash.1)));
    let styled = |mut el: svg::node::element::Element, w: f64| {
        let (c, sw) = stroke(w);
        el.assign("stroke", c);
        el.assign("stroke-width", sw);
        if dashed {
            el.assign("stroke-dasharray", format!("{dash} {gap}"));
        }
        el
    };
    match &e.shape {
        Shape::Circle { center, radius } => {
            let (x, y) = f.pt(*center);
            let el: svg::node::element::Element =
                Circle::new().set("cx", num(x)).set("cy", num(y)).set("r", num(f.len(*radius))).into();
            nodes.push(Box::new(styled(el, 0.0)));
        }
        Shape::Arc { center, radius, start, end } => {
            let el: svg::node::element::Element =
                Path::new().set("d", arc_path(f, *center, *radius, *start, *end)).into();
            nodes.push(Box::new(styled(el, 0.0)));
        }
        Shape::Line { from, to } => {
            let (x1, y1) = f.pt(*from);
            let (x2, y2) = f.pt(*to);
            let el: svg::node::element::Element =
                Line::new().set("x1", num(x1)).set("y1", num(y1)).set("x2", num(x2)).set("y2", num(y2)).into();
            nodes.push(Box::new(styled(el, 0.0)));
        }
        Shape::Polyline { points, closed, width } => {
            let pts = points.iter().map(|p| {
                let (x, y) = f.pt(*p);
                format!("{},{}", num(x), num(y))
            });
            let pts = pts.collect::<Vec<_>>().join(" ");
            let el: svg::node::element::Element = if *closed {
                Polygon::new().set("points", pts).into()
            } else {
                Polyline::new().set("points", pts).into()
            };
            nodes.push(Box::new(styled(el, *width)));
        }
        Shape::Filled { points } => {
            let pts = points.iter().map(|p| {
                let (x, y) = f.pt(*p);
                format!("{},{}", num(x), num(y))
            });
            nodes.push(Box::new(
                Polygon::new()
                    .set("points", pts.collect::<Vec<_>>().join(" "))
                    .set("fill", color.clone())
                    .set("stroke", "none"),
            ));
        }
        Shape::Arrow { from, to, head } => {
            if let Some((base, tri)) = arrow(*from, *to, *head) {
                let (x1, y1) = f.pt(*from);
                let (x2, y2) = f.pt(base);
                let el: svg::node::element::Element =
                    Line::new().set("x1", num(x1)).set("y1", num(y1)).set("x2", num(x2)).set("y2", num(y2)).into();
                nodes.push(Box::new(styled(el, 0.0)));
                let pts: Vec<String> = tri
                    .iter()
                    .map(|p| {
                        let (x, y) = f.pt(*p);
                        format!("{},{}", num(x), num(y))
                    })
                    .collect();
                nodes.push(Box::new(
                    Polygon::new().set("points", pts.join(" ")).set("fill", color.clone()).set("stroke", "none"),
                ));
            }
        }
        Shape::Text { at, height, value, halign, valign, rotation } => {
            nodes.push(Box::new(text_node(f, *at, *height, value, *halign, *valign, *rotation, &color)));
        }
        dim @ (Shape::AngularDimension { .. } | Shape::LinearDimension { .. }) => {
            for part in explode_dimension(dim, &drawing.dim_style) {
                let sub = Entity { layer: e.layer, color: e.color, linetype: Some(LineType::Continuous), shape: part };
                nodes.extend(entity_nodes(drawing, &sub, f));
            }
        }
    }
    nodes
}

#[allow(clippy::too_many_arguments)]
fn text_node(
    f: &Frame,
    at: Point,
    height: f64,
    value: &str,
    halign: HAlign,
    valign: VAlign,
    rotation: f64,
    color: &str,
) -> Text {
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
    let mut t = Text::new(value)
        .set("x", num(x))
        .set("y", num(y))
        .set("font-size", num(size))
        .set("text-anchor", anchor)
        .set("fill", color)
        .set("stroke", "none");
    if dy != 0.0 {
        t = t.set("dy", num(dy));
    }
    if rotation != 0.0 {
        // SVG rotates clockwise in its y-down frame: negate.
        t = t.set("transform", format!("rotate({} {} {})", num(-rotation.to_degrees()), num(x), num(y)));
    }
    t
}

fn arc_path(f: &Frame, center: Point, radius: f64, start: f64, end: f64) -> String {
    // Counter-clockwise from start to end, wrapping through 0 when end < start (as in DXF).
    let sweep = arc_sweep(start, end);
    // SVG arcs cannot draw a full circle in one command: split into two halves.
    let n = if sweep.abs() > std::f64::consts::PI { 2 } else { 1 };
    let mut d = String::new();
    let (sx, sy) = f.pt(polar(center, radius, start));
    d.push_str(&format!("M{},{}", num(sx), num(sy)));
    for i in 1..=n {
        let a = start + sweep * i as f64 / n as f64;
        let (x, y) = f.pt(polar(center, radius, a));
        // Counter-clockwise in the model = sweep-flag 0 in SVG's flipped frame.
        let r = num(f.len(radius));
        d.push_str(&format!(" A{r},{r} 0 0 0 {},{}", num(x), num(y)));
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::draw::DimStyle;

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
}
