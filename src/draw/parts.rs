//! Composite shapes (arrows, dimensions) broken into simple ones. Both writers use these,
//! so the DXF dimension blocks and the SVG show the same geometry.

use super::{DimStyle, HAlign, Shape, VAlign};
use crate::geom::{Point, Vector, angle_of, normalize_angle, perp, polar};

/// Half-width of an arrowhead relative to its length.
pub const ARROW_HALF_WIDTH: f64 = 0.2;
/// Gap between a linear dimension's feature point and its extension line, in arrow sizes
/// (DXF `$DIMEXO`).
pub const EXT_LINE_GAP: f64 = 0.3;
/// Overshoot of extension lines past the dimension line, in arrow sizes (DXF `$DIMEXE`).
pub const EXT_LINE_OVERSHOOT: f64 = 0.6;
/// Baseline of a linear dimension's text above its dimension line, in text heights
/// (DXF `$DIMGAP`).
pub const LINEAR_TEXT_LIFT: f64 = 0.5;
/// Middle of an angular dimension's text outside its arc, in text heights.
pub const ANGULAR_TEXT_LIFT: f64 = 0.6;

/// Whether a linear dimension measured along `angle` (radians) has its text turned by half
/// a turn to stay readable (read from below or from the right): directions in (90°, 270°].
pub fn linear_text_flipped(angle: f64) -> bool {
    let a = normalize_angle(angle);
    a > std::f64::consts::FRAC_PI_2 && a <= 1.5 * std::f64::consts::PI
}

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

/// Dash and gap lengths (model units) of the DASHED line type for a drawing whose larger
/// extent is `extent`: a dash of about 1.8 % of the extent rounded down to 1, 2 or 5 times
/// a power of ten (so the DXF LTYPE table holds a readable number), the gap half the dash.
/// Both writers use it, so SVG and DXF dashes match. A non-positive or non-finite extent
/// gives the pattern of a 100-unit drawing.
pub fn dash_pattern(extent: f64) -> (f64, f64) {
    let extent = if extent.is_finite() && extent > 0.0 { extent } else { 100.0 };
    let target = 0.018 * extent;
    let decade = 10f64.powf(target.log10().floor());
    let mantissa = target / decade;
    let step = if mantissa >= 5.0 {
        5.0
    } else if mantissa >= 2.0 {
        2.0
    } else {
        1.0
    };
    let dash = step * decade;
    (dash, 0.5 * dash)
}

/// Counter-clockwise sweep (radians) of the arc from `start` to `end`, in [0, 2π]: `end`
/// below `start` wraps around; equal angles give 0, a difference that is a non-zero multiple
/// of 2π gives a full turn.
pub fn arc_sweep(start: f64, end: f64) -> f64 {
    let sweep = normalize_angle(end - start);
    if sweep == 0.0 && end != start { std::f64::consts::TAU } else { sweep }
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
                at: polar(*vertex, radius + ANGULAR_TEXT_LIFT * th, mid),
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
                    out.push(Shape::Line {
                        from: p + dir * (EXT_LINE_GAP * asz).min(len),
                        to: f + dir * EXT_LINE_OVERSHOOT * asz,
                    });
                }
            }
            out.push(Shape::Line { from: f1, to: f2 });
            let mid = Point::from((f1.coords + f2.coords) / 2.0);
            arrow_shapes(mid, f1, asz, &mut out);
            arrow_shapes(mid, f2, asz, &mut out);
            // Text above the dimension line, upright when read from below or the right.
            let (rot, up) = if linear_text_flipped(*angle) { (angle + std::f64::consts::PI, -n) } else { (*angle, n) };
            out.push(Shape::Text {
                at: mid + up * (LINEAR_TEXT_LIFT * th),
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
    fn arc_sweep_wraps_through_zero_and_keeps_full_turns() {
        use std::f64::consts::{PI, TAU};
        assert!((arc_sweep(0.0, PI / 2.0) - PI / 2.0).abs() < 1e-15);
        // 300° to 40°: counter-clockwise through 0°, 100°.
        assert!((arc_sweep(300f64.to_radians(), 40f64.to_radians()) - 100f64.to_radians()).abs() < 1e-12);
        assert_eq!(arc_sweep(1.0, 1.0), 0.0);
        assert_eq!(arc_sweep(0.0, TAU), TAU);
    }

    #[test]
    fn dash_pattern_is_a_round_fraction_of_the_extent() {
        // 1.8 % of 100 = 1.8 → 1; of 200 = 3.6 → 2; of 300 = 5.4 → 5; of 1 = 0.018 → 0.01.
        assert_eq!(dash_pattern(100.0), (1.0, 0.5));
        assert_eq!(dash_pattern(200.0), (2.0, 1.0));
        assert_eq!(dash_pattern(300.0), (5.0, 2.5));
        assert!((dash_pattern(1.0).0 - 0.01).abs() < 1e-15);
        assert_eq!(dash_pattern(f64::NAN), dash_pattern(100.0));
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
