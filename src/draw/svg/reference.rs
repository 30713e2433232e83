//! The SVG writer as it was first written, on the `svg` crate's element tree: the
//! reference the direct writer ([`super::write_into`]) is compared with byte for byte
//! (tests only; the `svg` crate is a dev-dependency).

use svg::Document;
use svg::Node as _;
use svg::node::element::{Circle, Group, Line, Path, Polygon, Polyline, Rectangle, Text};

use super::{FONT_FAMILY, Frame, SvgOptions, num};
use crate::draw::parts::{arc_sweep, arrow, dash_pattern, explode_dimension};
use crate::draw::{Aci, Bounds, Drawing, Entity, HAlign, LineType, RunKind, Runs, Shape, VAlign, font};
use crate::geom::{Point, polar};
use svg::node::Blob;

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
    let frame = Frame { k: paper.unwrap_or(1.0), paper, hairline: opts.hairline * extent, dash: dash_pattern(extent) };
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
        if run.as_ref().is_some_and(|(layer, _)| *layer != e.layer)
            && let Some((_, g)) = run.take()
        {
            doc = doc.add(g);
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
        Shape::Text { at, height, value, runs, halign, valign, rotation } => {
            nodes.push(Box::new(text_node(f, *at, *height, (value, runs), *halign, *valign, *rotation, &color)));
        }
        caption @ Shape::ScaleText { .. } => {
            if let Some(shape) = caption.scale_text_in(f.paper) {
                nodes.extend(entity_nodes(drawing, &Entity { shape, ..e.clone() }, f));
            }
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
    (value, runs): (&str, &Runs),
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
    let mut t = if runs.is_flat() {
        Text::new(value)
    } else {
        // The runs' markup as the element's only child.
        let mut t = Text::new("");
        if let Some(c) = t.get_children_mut() {
            c.clear();
        }
        t.add(Blob::new(runs_markup(value, runs, size)))
    };
    t = t
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

/// A text's runs as `<tspan>`s (a subscript smaller and lowered by `dy`, the base text
/// after it raised back), with no white space between them.
fn runs_markup(value: &str, runs: &Runs, size: f64) -> String {
    let esc = |s: &str| s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;");
    let shift = font::SUB_SHIFT_EM * size;
    let (mut out, mut lowered) = (String::new(), false);
    for (part, kind) in runs.split(value) {
        match (kind, lowered) {
            (RunKind::Flat, _) => {}
            (RunKind::Sub, false) => {
                out += &format!(
                    r#"<tspan dy="{}" font-size="{}">{}</tspan>"#,
                    num(shift),
                    num(font::SUB_SIZE * size),
                    esc(part)
                );
                lowered = true;
            }
            (RunKind::Sub, true) => {
                out += &format!(r#"<tspan font-size="{}">{}</tspan>"#, num(font::SUB_SIZE * size), esc(part))
            }
            (RunKind::Base, true) => {
                out += &format!(r#"<tspan dy="{}" xml:space="preserve">{}</tspan>"#, num(-shift), esc(part));
                lowered = false;
            }
            (RunKind::Base, false) => out += &esc(part),
        }
    }
    out
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
