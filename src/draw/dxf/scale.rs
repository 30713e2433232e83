//! Model units to millimetres: the drawing scaled about the origin before it is written, so
//! that every DXF mechdraw writes is in millimetres (a scene in metres is written × 1000),
//! and its texts written with the characters the text style's font has
//! ([`super::librecad::for_azomix`]). Figures keep drawing in model units; only the
//! writer's output changes.

use super::librecad::{for_azomix, lacks_glyphs};
use crate::draw::{DimStyle, Drawing, Entity, LinearMarks, Shape};
use crate::geom::Point;

/// Whether [`scaled`] changes `shape` at a scale of 1: a scale caption (written as TEXT),
/// a text with characters the DXF's font lacks.
pub(super) fn changes(shape: &Shape) -> bool {
    match shape {
        Shape::ScaleText { .. } => true,
        Shape::Text { value, .. } => lacks_glyphs(value),
        Shape::AngularDimension { text, .. } | Shape::LinearDimension { text, .. } => lacks_glyphs(text),
        _ => false,
    }
}

/// `d` with every coordinate, length, width, text height and dimension size multiplied by
/// `k` (> 0), every [`Shape::ScaleText`] a TEXT stating its scale per millimetre of the
/// DXF (a model unit is `k` of them), and every text [`for_azomix`]; angles, layers and
/// colours unchanged.
pub(super) fn scaled(d: &Drawing, k: f64) -> Drawing {
    let p = |q: &Point| Point::from(q.coords * k);
    let shape = |s: &Shape| match s {
        Shape::Circle { center, radius } => Shape::Circle { center: p(center), radius: radius * k },
        Shape::Arc { center, radius, start, end } => {
            Shape::Arc { center: p(center), radius: radius * k, start: *start, end: *end }
        }
        Shape::Line { from, to } => Shape::Line { from: p(from), to: p(to) },
        Shape::Polyline { points, closed, width } => {
            Shape::Polyline { points: points.iter().map(p).collect(), closed: *closed, width: width * k }
        }
        Shape::Filled { points } => Shape::Filled { points: points.iter().map(p).collect() },
        Shape::Arrow { from, to, head } => Shape::Arrow { from: p(from), to: p(to), head: head * k },
        Shape::Text { at, height, value, halign, valign, rotation, .. } => Shape::Text {
            runs: crate::draw::Runs::flat(),
            at: p(at),
            height: height * k,
            value: for_azomix(value).into_owned(),
            halign: *halign,
            valign: *valign,
            rotation: *rotation,
        },
        // A scale caption says the scale of the DXF's millimetres.
        Shape::ScaleText { at, height, caption, halign, valign, rotation } => Shape::Text {
            runs: crate::draw::Runs::flat(),
            at: p(at),
            height: height * k,
            value: for_azomix(&caption.text(k)).into_owned(),
            halign: *halign,
            valign: *valign,
            rotation: *rotation,
        },
        Shape::AngularDimension { vertex, first, second, radius, text, runs } => Shape::AngularDimension {
            vertex: p(vertex),
            first: p(first),
            second: p(second),
            radius: radius * k,
            text: for_azomix(text).into_owned(),
            runs: runs.clone(),
        },
        Shape::LinearDimension { p1, p2, line_at, angle, text, marks } => {
            let text = for_azomix(text).into_owned();
            // The text's place along the line is a length too.
            let marks = LinearMarks { text_along: marks.text_along.map(|s| s * k), ..*marks };
            Shape::LinearDimension { p1: p(p1), p2: p(p2), line_at: p(line_at), angle: *angle, text, marks }
        }
    };
    Drawing {
        layers: d.layers.clone(),
        entities: d
            .entities
            .iter()
            .map(|e| Entity { layer: e.layer, color: e.color, linetype: e.linetype, shape: shape(&e.shape) })
            .collect(),
        dim_style: DimStyle { text_height: d.dim_style.text_height * k, arrow_size: d.dim_style.arrow_size * k },
        paper_mm_per_unit: d.paper_mm_per_unit.map(|p| p / k),
    }
}
