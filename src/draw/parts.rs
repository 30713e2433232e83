//! Composite shapes (arrows, dimensions) broken into simple ones. Both writers use these,
//! so the DXF dimension blocks and the SVG show the same geometry.

use super::{DimStyle, HAlign, Shape, VAlign};
use crate::geom::{Point, Vector, angle_of, normalize_angle, perp, polar};

/// Half-width of an arrowhead relative to its length.
pub const ARROW_HALF_WIDTH: f64 = 0.2;

/// The shaft end and the filled head triangle of an arrow from `from` to `to` with a head
/// of length `head` (shortened to half the vector on short vectors). `None` for a
/// zero-length vector (nothing to draw).
pub fn arrow(from: Point, to: Point, head: f64) -> Option<(Point, [Point; 3])> {
    let v = to - from;
    let len = v.norm();
    if len == 0.0 || !len.is_finite() {
        return None;
    }
    let h = head.min(0.5 * len);
    let u = v / len;
    let base = to - u * h;
    let n = perp(u) * (h * ARROW_HALF_WIDTH);
    Some((base, [to, base + n, base - n]))
}

fn arrow_shapes(from: Point, to: Point, head: f64, out: &mut Vec<Shape>) {
    if let Some((_, tri)) = arrow(from, to, head) {
        out.push(Shape::Filled { points: tri.to_vec() });
    }
}

/// A dimension broken into lines, arcs, filled arrowheads and its text; any other shape
/// is returned unchanged.
pub fn explode_dimension(shape: &Shape, style: &DimStyle) -> Vec<Shape> {
    let mut out = Vec::new();
    let asz = style.arrow_size;
    let th = style.text_height;
    match shape {
        Shape::AngularDimension { vertex, first, second, radius, text } => {
            let a1 = angle_of(first - vertex);
            let a2 = angle_of(second - vertex);
            let sweep = normalize_angle(a2 - a1);
            // Extension lines from the ray points out to the arc when the arc lies beyond them.
            for (p, a) in [(first, a1), (second, a2)] {
                let d = (p - vertex).norm();
                if d < *radius {
                    out.push(Shape::Line { from: polar(*vertex, d, a), to: polar(*vertex, radius + 0.5 * asz, a) });
                }
            }
            out.push(Shape::Arc { center: *vertex, radius: *radius, start: a1, end: a1 + sweep });
            // Arrowheads tangent to the arc, pointing at its ends.
            let step = (asz / radius).min(0.4 * sweep.max(1e-9));
            let p_start = polar(*vertex, *radius, a1);
            let p_end = polar(*vertex, *radius, a1 + sweep);
            arrow_shapes(polar(*vertex, *radius, a1 + step), p_start, asz, &mut out);
            arrow_shapes(polar(*vertex, *radius, a1 + sweep - step), p_end, asz, &mut out);
            let mid = a1 + 0.5 * sweep;
            out.push(Shape::Text {
                at: polar(*vertex, radius + 0.6 * th, mid),
                height: th,
                value: text.clone(),
                halign: HAlign::Center,
                valign: VAlign::Middle,
                rotation: 0.0,
            });
        }
        Shape::LinearDimension { p1, p2, line_at, angle, text } => {
            let u = Vector::new(angle.cos(), angle.sin());
            let n = perp(u);
            // Feet of the extension lines on the dimension line.
            let foot = |p: &Point| p + n * (line_at - p).dot(&n);
            let (f1, f2) = (foot(p1), foot(p2));
            for (p, f) in [(p1, f1), (p2, f2)] {
                let d = f - p;
                let len = d.norm();
                if len > 0.0 {
                    // Gap at the feature, overshoot past the dimension line.
                    let dir = d / len;
                    out.push(Shape::Line { from: p + dir * (0.3 * asz).min(len), to: f + dir * 0.6 * asz });
                }
            }
            out.push(Shape::Line { from: f1, to: f2 });
            let mid = Point::from((f1.coords + f2.coords) / 2.0);
            arrow_shapes(mid, f1, asz, &mut out);
            arrow_shapes(mid, f2, asz, &mut out);
            // Text above the dimension line, upright when read from below or the right.
            let mut rot = *angle;
            let mut up = n;
            if normalize_angle(rot) > std::f64::consts::FRAC_PI_2 && normalize_angle(rot) <= 1.5 * std::f64::consts::PI
            {
                rot += std::f64::consts::PI;
                up = -n;
            }
            out.push(Shape::Text {
                at: mid + up * (0.5 * th),
                height: th,
                value: text.clone(),
                halign: HAlign::Center,
                valign: VAlign::Baseline,
                rotation: rot,
            });
        }
        other => out.push(other.clone()),
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arrow_head_points_at_the_tip_and_is_shortened_on_short_vectors() {
        let (base, tri) = arrow(Point::new(0.0, 0.0), Point::new(10.0, 0.0), 2.0).unwrap();
        assert_eq!(tri[0], Point::new(10.0, 0.0));
        assert!((base - Point::new(8.0, 0.0)).norm() < 1e-12);
        let (base, _) = arrow(Point::new(0.0, 0.0), Point::new(1.0, 0.0), 2.0).unwrap();
        assert!((base.x - 0.5).abs() < 1e-12);
        assert!(arrow(Point::new(1.0, 1.0), Point::new(1.0, 1.0), 2.0).is_none());
    }

    #[test]
    fn angular_dimension_arc_sweeps_counter_clockwise_from_first_to_second() {
        let style = DimStyle { text_height: 1.0, arrow_size: 1.0 };
        let dim = Shape::AngularDimension {
            vertex: Point::new(0.0, 0.0),
            first: Point::new(5.0, 0.0),
            second: Point::new(0.0, -5.0),
            radius: 10.0,
            text: "270°".into(),
        };
        let arc = explode_dimension(&dim, &style)
            .into_iter()
            .find_map(|s| match s {
                Shape::Arc { start, end, .. } => Some((start, end)),
                _ => None,
            })
            .unwrap();
        assert!((arc.1 - arc.0 - 1.5 * std::f64::consts::PI).abs() < 1e-12);
    }
}
