//! Composite shapes (arrows, dimensions) broken into simple ones. Both writers use these,
//! so the DXF dimension blocks and the SVG show the same geometry.

use super::{DimEnds, DimStyle, HAlign, Shape, VAlign};
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
/// Clear space between an angular dimension's arc and the nearest point of its text's box
/// (and between that box and the dimension's rays), in text heights.
pub const ANGULAR_TEXT_GAP: f64 = 0.3;
/// Step by which an angular dimension's text moves out along the bisector while its box
/// still crosses one of the rays, in text heights.
pub const ANGULAR_TEXT_STEP: f64 = 0.1;
/// Cap height of DejaVu Sans, in ems: the SVG writer sets the font size to the text height
/// / 0.73, so a text height is a cap height ([`super::font::CAP_HEIGHT_EM`]).
pub const CAP_HEIGHT_EM: f64 = super::font::CAP_HEIGHT_EM;
/// Depth of descenders (`φ`, `y`) below the baseline, in text heights (DejaVu Sans: 0.24 em
/// ≈ 0.32 cap heights); part of a text's estimated box.
pub const TEXT_DESCENT: f64 = 0.3;
/// Least clear space between a linear dimension's text and each extension line for the
/// text to stay between them, in text heights.
pub const LINEAR_TEXT_FIT_GAP: f64 = 0.1;
/// Clear space between a linear dimension's text placed outside and the extension line it
/// sits beside, in text heights.
pub const LINEAR_TEXT_OUTSIDE_GAP: f64 = 0.5;
/// Shortest dimension line that holds both arrowheads inside the extension lines, in arrow
/// sizes; shorter ones get their arrowheads outside, pointing in.
pub const LINEAR_ARROWS_FIT: f64 = 2.5;
/// Length of the dimension line outside an extension line that carries an arrowhead
/// pointing in, in arrow sizes.
pub const LINEAR_ARROW_STUB: f64 = 2.0;
/// Radius of the open circle at the base of a [`DimEnds::FromBase`] dimension, in arrow
/// sizes (about the seed's "small circle": half an arrowhead across).
pub const BASE_CIRCLE_RADIUS: f64 = 0.3;

/// Width (model units) of `text` drawn `height` high (cap height): the sum of its advances
/// in DejaVu Sans, the font the SVG, PNG and PDF draw it in ([`super::font`]; the DXF leaves
/// the glyphs to the reader's font: see [`widest_text_width`]).
pub fn text_width(text: &str, height: f64) -> f64 {
    super::font::width(text, height)
}

/// [`text_width`] of the text made of `chars` (a text read with some characters replaced,
/// without building it).
pub fn chars_width(chars: impl Iterator<Item = char>, height: f64) -> f64 {
    super::font::measure_chars(chars, height).width
}

/// Advance of a character in LibreCAD's stroke font for the DXF's text style (AZOMIX, see
/// `draw::dxf::TEXT_STYLE`), in ninths of the text height: [`super::dxf::librecad::advance`]
/// (the glyph's right edge plus the letter spacing; the word spacing for a space; a
/// character the font lacks as wide as the stand-in LibreCAD draws).
fn azomix_advance(c: char) -> f64 {
    super::dxf::librecad::advance(c)
}

/// Width (model units) that `text` drawn `height` high takes in the widest of the readers we
/// write for: per character the larger of its DejaVu Sans advance ([`text_width`]: the SVG,
/// PNG and PDF) and its advance in LibreCAD's stroke font (the DXF's text style in LibreCAD:
/// 0.9–1.0 text heights for most letters and digits against DejaVu's 0.8–1.0, and 0.75 for
/// a space against 0.45). Programs that draw the DXF's TEXT with a TrueType font (ezdxf, AutoCAD,
/// Inkscape) stay within DejaVu's widths. A layout that keeps room for a text (a cell, a
/// panel, the gap between a title and the text beside it) measures it with this; where a
/// writer places a text (centring, right alignment), [`text_width`] stays its estimate.
pub fn widest_text_width(text: &str, height: f64) -> f64 {
    let dejavu = 1.0 / CAP_HEIGHT_EM;
    height * text.chars().map(|c| (super::font::glyph(c).advance * dejavu).max(azomix_advance(c) / 9.0)).sum::<f64>()
}

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
    let decade = libm::pow(10f64, libm::log10(target).floor());
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

/// The estimated box (lower-left and upper-right corners) of an unrotated text `width` wide
/// and `height` high (cap height) whose middle is at `mid` (as drawn with
/// [`VAlign::Middle`]): the caps' height plus [`TEXT_DESCENT`] below the baseline.
pub fn middle_text_box(mid: Point, width: f64, height: f64) -> (Point, Point) {
    (
        Point::new(mid.x - 0.5 * width, mid.y - (0.5 + TEXT_DESCENT) * height),
        Point::new(mid.x + 0.5 * width, mid.y + 0.5 * height),
    )
}

/// Distance from `p` to the axis-aligned box `(min, max)` (0 inside it).
fn point_box_distance(p: Point, (min, max): (Point, Point)) -> f64 {
    let dx = (min.x - p.x).max(p.x - max.x).max(0.0);
    let dy = (min.y - p.y).max(p.y - max.y).max(0.0);
    libm::hypot(dx, dy)
}

/// Whether the segment `a`–`b` meets the axis-aligned box `(min, max)` (Liang–Barsky
/// clipping; touching counts).
fn segment_meets_box(a: Point, b: Point, (min, max): (Point, Point)) -> bool {
    let d = b - a;
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [(-d.x, a.x - min.x), (d.x, max.x - a.x), (-d.y, a.y - min.y), (d.y, max.y - a.y)] {
        if p == 0.0 {
            if q < 0.0 {
                return false;
            }
        } else if p < 0.0 {
            t0 = t0.max(q / p);
        } else {
            t1 = t1.min(q / p);
        }
    }
    t0 <= t1
}

/// Middle of an angular dimension's text (drawn unrotated, [`HAlign::Center`],
/// [`VAlign::Middle`]), as a draughtsman places it: on the bisector of the swept angle, as
/// near the arc as lets the text's whole estimated box ([`middle_text_box`],
/// [`text_width`]) stay [`ANGULAR_TEXT_GAP`] outside the arc's circle, then moved further
/// out by [`ANGULAR_TEXT_STEP`]s while the box (grown by the gap) still crosses one of the
/// dimension's rays as drawn (from the vertex to its point, or past the arc where an
/// extension line reaches it). A text wider than its arc thus sits beyond the arc, never
/// across it, and stays horizontal, so it reads from below. The DXF DIMENSION entity's text
/// mid point is this point.
pub fn angular_text_mid(
    vertex: Point,
    first: Point,
    second: Point,
    radius: f64,
    text: &str,
    style: &DimStyle,
) -> Point {
    let th = style.text_height;
    let a1 = angle_of(first - vertex);
    let sweep = normalize_angle(angle_of(second - vertex) - a1);
    let mid = a1 + 0.5 * sweep;
    let u = Vector::new(libm::cos(mid), libm::sin(mid));
    let w = text_width(text, th);
    let boxed = |d: f64| middle_text_box(vertex + u * d, w, th);
    // Clear of the arc: the box's distance to the vertex grows with d, so bisect. At `hi`
    // the box lies wholly beyond the line at `clear` across the bisector.
    let clear = radius + ANGULAR_TEXT_GAP * th;
    let (mut lo, mut hi) = (0.0, clear + 0.5 * w + (0.5 + TEXT_DESCENT) * th);
    for _ in 0..60 {
        let m = 0.5 * (lo + hi);
        if point_box_distance(vertex, boxed(m)) >= clear {
            hi = m;
        } else {
            lo = m;
        }
    }
    // Clear of the rays: move out until the grown box misses both (it surely does once
    // it is beyond the longer ray).
    let reach = |p: Point| (p - vertex).norm().max(radius + 0.5 * style.arrow_size);
    let rays = [(reach(first), a1), (reach(second), a1 + sweep)].map(|(r, a)| polar(vertex, r, a));
    let g = Vector::new(ANGULAR_TEXT_GAP * th, ANGULAR_TEXT_GAP * th);
    let crosses = |d: f64| {
        let (min, max) = boxed(d);
        rays.iter().any(|end| segment_meets_box(vertex, *end, (min - g, max + g)))
    };
    let step = ANGULAR_TEXT_STEP * th;
    let far = rays.iter().map(|end| (end - vertex).norm()).fold(0.0, f64::max) + w + 2.0 * th;
    // NaN or a zero step gives no steps.
    let steps = if step > 0.0 { ((far / step).ceil().min(1e5)) as usize } else { 0 };
    let mut d = hi;
    for _ in 0..steps {
        if !crosses(d) {
            break;
        }
        d += step;
    }
    vertex + u * d
}

/// How a linear dimension is laid out ([`linear_layout`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearLayout {
    /// Foot of the first extension line on the dimension line.
    pub f1: Point,
    /// Foot of the second extension line on the dimension line.
    pub f2: Point,
    /// Unit vector along which the text reads (the measuring direction, or its opposite
    /// when [`linear_text_flipped`]).
    pub reading: Vector,
    /// Unit vector from the dimension line up to the text (left of `reading`).
    pub up: Vector,
    /// Text insertion point: middle of its baseline ([`HAlign::Center`], [`VAlign::Baseline`]).
    pub text_at: Point,
    /// Rotation of the text, radians counter-clockwise.
    pub rotation: f64,
    /// Middle of the text, half a text height above `text_at` (the DXF DIMENSION entity's
    /// text mid point, group 11/21).
    pub text_mid: Point,
    /// Estimated width of the text ([`text_width`]), model units.
    pub text_width: f64,
    /// Whether the text sits between the extension lines; if not, it sits beside the
    /// extension line at the end the text reads towards, on the dimension line's extension.
    pub text_inside: bool,
    /// Whether the arrowheads sit between the extension lines; if not, they sit outside,
    /// pointing in, each on a stub of the dimension line [`LINEAR_ARROW_STUB`] long.
    pub arrows_inside: bool,
}

/// The layout of a linear dimension (see [`Shape::LinearDimension`]), as ISO 129 and
/// AutoCAD's "best fit" place it. The text is centred [`LINEAR_TEXT_LIFT`] above the
/// dimension line when its estimated width plus [`LINEAR_TEXT_FIT_GAP`] on each side fits
/// between the extension lines; otherwise it goes beyond the extension line at the end it
/// reads towards, [`LINEAR_TEXT_OUTSIDE_GAP`] clear of it, over an extension of the dimension
/// line. Independently, the arrowheads point out from the middle when the dimension line is
/// at least [`LINEAR_ARROWS_FIT`] arrow sizes long, else they sit outside pointing in.
pub fn linear_layout(p1: Point, p2: Point, line_at: Point, angle: f64, text: &str, style: &DimStyle) -> LinearLayout {
    linear_layout_placed(p1, p2, line_at, angle, text, None, style)
}

/// [`linear_layout`] with the text's middle at `text_along` (see
/// [`super::LinearMarks::text_along`]) when given; `text_inside` then says whether the placed box
/// lies between the extension lines.
pub fn linear_layout_placed(
    p1: Point,
    p2: Point,
    line_at: Point,
    angle: f64,
    text: &str,
    text_along: Option<f64>,
    style: &DimStyle,
) -> LinearLayout {
    let th = style.text_height;
    let u = Vector::new(libm::cos(angle), libm::sin(angle));
    let n = perp(u);
    let foot = |p: &Point| p + n * (line_at - p).dot(&n);
    let (f1, f2) = (foot(&p1), foot(&p2));
    let (rotation, reading, up) =
        if linear_text_flipped(angle) { (angle + std::f64::consts::PI, -u, -n) } else { (angle, u, n) };
    let len = (f2 - f1).norm();
    let w = text_width(text, th);
    let arrows_inside = len >= LINEAR_ARROWS_FIT * style.arrow_size;
    let (text_inside, on_line) = match text_along {
        // Placed by the caller, `s` along the dimension line from the first foot.
        Some(s) => {
            let l2 = (f2 - f1).dot(&reading);
            (s - 0.5 * w >= l2.min(0.0) && s + 0.5 * w <= l2.max(0.0), f1 + reading * s)
        }
        None if w + 2.0 * LINEAR_TEXT_FIT_GAP * th <= len => (true, Point::from((f1.coords + f2.coords) / 2.0)),
        // Beyond the foot the text reads towards.
        None => {
            let end = if (f2 - f1).dot(&reading) >= 0.0 { f2 } else { f1 };
            (false, end + reading * (LINEAR_TEXT_OUTSIDE_GAP * th + 0.5 * w))
        }
    };
    let text_at = on_line + up * (LINEAR_TEXT_LIFT * th);
    LinearLayout {
        f1,
        f2,
        reading,
        up,
        text_at,
        rotation,
        text_mid: text_at + up * (0.5 * th),
        text_width: w,
        text_inside,
        arrows_inside,
    }
}

/// A dimension broken into lines, arcs, filled arrowheads and its text; any other shape
/// is returned unchanged.
pub fn explode_dimension(shape: &Shape, style: &DimStyle) -> Vec<Shape> {
    let mut out = Vec::new();
    match shape {
        Shape::AngularDimension { vertex, first, second, radius, text, runs } => {
            let parts = angular_parts(*vertex, *first, *second, *radius, (text, runs), style);
            out.extend(parts.extensions.into_iter().flatten());
            out.push(Shape::Arc {
                center: *vertex,
                radius: *radius,
                start: parts.start,
                end: parts.start + parts.sweep,
            });
            out.extend(parts.heads.into_iter().flatten());
            out.push(parts.text);
        }
        Shape::LinearDimension { .. } => explode_linear_into(shape, style, &mut out),
        other => out.push(other.clone()),
    }
    out
}

/// An angular dimension's parts, as [`explode_dimension`] draws them.
struct AngularParts {
    /// Extension lines from the first and second ray points out past the arc, when the arc
    /// lies beyond them.
    extensions: [Option<Shape>; 2],
    /// Direction of the first ray, radians.
    start: f64,
    /// Counter-clockwise sweep from the first ray to the second, in [0, 2π).
    sweep: f64,
    /// The arrowheads at the arc's start and end (none where the arc has no length).
    heads: [Option<Shape>; 2],
    /// The text, placed by [`angular_text_mid`].
    text: Shape,
}

fn angular_parts(
    vertex: Point,
    first: Point,
    second: Point,
    radius: f64,
    (text, runs): (&str, &super::Runs),
    style: &DimStyle,
) -> AngularParts {
    let asz = style.arrow_size;
    let a1 = angle_of(first - vertex);
    let a2 = angle_of(second - vertex);
    let sweep = normalize_angle(a2 - a1);
    // Extension lines from the ray points out to the arc when the arc lies beyond them.
    let extension = |p: Point, a: f64| {
        let d = (p - vertex).norm();
        (d < radius).then(|| Shape::Line { from: polar(vertex, d, a), to: polar(vertex, radius + 0.5 * asz, a) })
    };
    // Arrowheads tangent to the arc, pointing at its ends.
    let step = (asz / radius).min(0.4 * sweep.max(1e-9));
    let head = |from: f64, to: f64| {
        arrow(polar(vertex, radius, from), polar(vertex, radius, to), asz)
            .map(|(_, tri)| Shape::Filled { points: tri.to_vec() })
    };
    AngularParts {
        extensions: [extension(first, a1), extension(second, a2)],
        start: a1,
        sweep,
        heads: [head(a1 + step, a1), head(a1 + sweep - step, a1 + sweep)],
        text: Shape::Text {
            runs: runs.clone(),
            at: angular_text_mid(vertex, first, second, radius, text, style),
            height: style.text_height,
            value: text.to_string(),
            halign: HAlign::Center,
            valign: VAlign::Middle,
            rotation: 0.0,
        },
    }
}

/// An angular dimension split into two parts, the first sweeping `first` radians from the
/// first ray (a DXF writer writes an angle of 180° or more so, each part a 2-line angular
/// DIMENSION under 180°, the only angular kind LibreCAD draws): the first part's shapes
/// (the first extension line, the arc from the first ray to the split, the arrowhead at its
/// start and the whole dimension's text) and the second's (the second extension line, the
/// arc on to the second ray, the arrowhead at its end), so that the two together draw
/// exactly what [`explode_dimension`] draws; and the point where the arc is split. `None`
/// for a shape that is not an angular dimension.
pub fn explode_angular_split(shape: &Shape, first: f64, style: &DimStyle) -> Option<([Vec<Shape>; 2], Point)> {
    let Shape::AngularDimension { vertex, first: ray, second, radius, text, runs } = shape else { return None };
    let parts = angular_parts(*vertex, *ray, *second, *radius, (text, runs), style);
    let mid = parts.start + first;
    let arc = |start: f64, end: f64| Shape::Arc { center: *vertex, radius: *radius, start, end };
    let [e1, e2] = parts.extensions;
    let [h1, h2] = parts.heads;
    let mut one: Vec<Shape> = e1.into_iter().collect();
    one.push(arc(parts.start, mid));
    one.extend(h1);
    one.push(parts.text);
    let mut two: Vec<Shape> = e2.into_iter().collect();
    two.push(arc(mid, parts.start + parts.sweep));
    two.extend(h2);
    Some(([one, two], polar(*vertex, *radius, mid)))
}

/// A linear dimension broken into lines, arrowheads (and the base circle) and its text as
/// its marks ask ([`super::LinearMarks`]).
fn explode_linear_into(shape: &Shape, style: &DimStyle, out: &mut Vec<Shape>) {
    let asz = style.arrow_size;
    let th = style.text_height;
    match shape {
        Shape::LinearDimension { p1, p2, line_at, angle, text, marks } => {
            let lay = linear_layout_placed(*p1, *p2, *line_at, *angle, text, marks.text_along, style);
            let (f1, f2) = (lay.f1, lay.f2);
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
            // Outward along the dimension line at each foot (f1 back, f2 on, when they meet).
            let u = Vector::new(libm::cos(*angle), libm::sin(*angle));
            let out1 = if (f1 - f2).dot(&u) > 0.0 { u } else { -u };
            // How far the dimension line runs on past each foot: under an outside text, and
            // under outside arrowheads.
            let mut beyond = [0.0f64; 2];
            if marks.text_along.is_some() {
                // Under the placed text, wherever it is.
                let half = 0.5 * lay.text_width;
                beyond[0] = ((lay.text_at - f1).dot(&out1) + half).max(0.0);
                beyond[1] = ((lay.text_at - f2).dot(&-out1) + half).max(0.0);
            } else if !lay.text_inside {
                let k = if out1.dot(&lay.reading) > 0.0 { 0 } else { 1 };
                beyond[k] = LINEAR_TEXT_OUTSIDE_GAP * th + lay.text_width;
            }
            let from_base = marks.ends == DimEnds::FromBase;
            if !lay.arrows_inside {
                // A base circle needs no stub; an arrowhead pointing in does.
                let k0 = if from_base { 1 } else { 0 };
                for b in &mut beyond[k0..] {
                    *b = b.max(LINEAR_ARROW_STUB * asz);
                }
            }
            let r = BASE_CIRCLE_RADIUS * asz;
            // From the base circle's rim (towards the end), unless the line runs on past it.
            let from =
                if from_base && beyond[0] == 0.0 { f1 - out1 * r.min((f2 - f1).norm()) } else { f1 + out1 * beyond[0] };
            let to = f2 - out1 * beyond[1];
            out.push(Shape::Line { from, to });
            if from_base {
                out.push(Shape::Circle { center: f1, radius: r });
            } else if lay.arrows_inside {
                let mid = Point::from((f1.coords + f2.coords) / 2.0);
                arrow_shapes(mid, f1, asz, out);
            } else {
                arrow_shapes(f1 + out1 * (LINEAR_ARROW_STUB * asz), f1, asz, out);
            }
            if lay.arrows_inside {
                let mid = Point::from((f1.coords + f2.coords) / 2.0);
                arrow_shapes(mid, f2, asz, out);
            } else {
                arrow_shapes(f2 - out1 * (LINEAR_ARROW_STUB * asz), f2, asz, out);
            }
            // Text above the dimension line, upright when read from below or the right.
            out.push(Shape::Text {
                runs: super::Runs::flat(),
                at: lay.text_at,
                height: th,
                value: text.clone(),
                halign: HAlign::Center,
                valign: VAlign::Baseline,
                rotation: lay.rotation,
            });
        }
        other => out.push(other.clone()),
    }
}

#[cfg(test)]
#[allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the code under test calls"
)]
mod tests {
    use super::*;
    use crate::draw::LinearMarks;

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
            runs: Default::default(),
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

    /// The exploded text of a dimension: insertion point and rotation.
    fn exploded_text(dim: &Shape, style: &DimStyle) -> (Point, f64) {
        explode_dimension(dim, style)
            .into_iter()
            .find_map(|s| match s {
                Shape::Text { at, rotation, .. } => Some((at, rotation)),
                _ => None,
            })
            .unwrap()
    }

    #[test]
    fn angular_text_box_stays_outside_the_arc_and_off_the_rays() {
        let style = DimStyle { text_height: 2.0, arrow_size: 1.5 };
        let th = style.text_height;
        let vertex = Point::new(3.0, -1.0);
        for radius in [1.0, 4.0, 10.0, 40.0] {
            for (a1, a2) in [(0.0, 20.0), (0.0, 75.77), (30.0, 150.0), (100.0, 260.0), (200.0, 350.0), (300.0, 30.0)] {
                for text in ["5°", "75.77°", "φ1 = 75.77°", "a much wider text = 123.45°"] {
                    let (a1, a2) = (f64::to_radians(a1), f64::to_radians(a2));
                    let (first, second) = (polar(vertex, 30.0, a1), polar(vertex, 25.0, a2));
                    let dim = Shape::AngularDimension {
                        vertex,
                        first,
                        second,
                        radius,
                        text: text.into(),
                        runs: Default::default(),
                    };
                    let (at, rotation) = exploded_text(&dim, &style);
                    assert_eq!(rotation, 0.0);
                    let bx = middle_text_box(at, text_width(text, th), th);
                    // Nearest point of the box to the vertex: clear of the arc's circle.
                    let gap = point_box_distance(vertex, bx) - radius;
                    assert!(gap >= ANGULAR_TEXT_GAP * th - 1e-9, "{text} r={radius}: gap {gap}");
                    // Neither ray (link) crosses the box.
                    for p in [first, second] {
                        assert!(!segment_meets_box(vertex, p, bx), "{text} r={radius} crosses a ray");
                    }
                    // The DXF DIMENSION's text mid point is the exploded text's.
                    assert_eq!(angular_text_mid(vertex, first, second, radius, text, &style), at);
                }
            }
        }
    }

    #[test]
    fn angular_text_sits_on_the_bisector_near_the_arc_when_it_fits() {
        // A short text on a wide arc: on the bisector (45°), less than a text height and a
        // half beyond the arc.
        let style = DimStyle { text_height: 1.0, arrow_size: 1.0 };
        let v = Point::new(0.0, 0.0);
        let at = angular_text_mid(v, Point::new(50.0, 0.0), Point::new(0.0, 50.0), 20.0, "5°", &style);
        assert!((angle_of(at - v) - std::f64::consts::FRAC_PI_4).abs() < 1e-12);
        assert!(at.coords.norm() < 21.5);
    }

    /// Text box of a linear dimension's exploded text, in the (reading, up) frame about the
    /// first foot: (along-from, along-to, up-from, up-to).
    fn linear_text_span(lay: &LinearLayout, th: f64) -> (f64, f64, f64, f64) {
        let x = (lay.text_at - lay.f1).dot(&lay.reading);
        let y = (lay.text_at - lay.f1).dot(&lay.up);
        (x - 0.5 * lay.text_width, x + 0.5 * lay.text_width, y - TEXT_DESCENT * th, y + th)
    }

    #[test]
    fn linear_text_that_fits_is_centred_between_the_extension_lines() {
        let style = DimStyle { text_height: 2.0, arrow_size: 1.8 };
        for angle in [0.0, 0.7, 2.0, 3.5, -1.2] {
            let u = Vector::new(f64::cos(angle), f64::sin(angle));
            let p1 = Point::new(5.0, 7.0);
            let p2 = p1 + u * 40.0;
            let line_at = p1 + perp(u) * 6.0;
            let dim = Shape::LinearDimension {
                p1,
                p2,
                line_at,
                angle,
                text: "40 ±0.1".into(),
                marks: LinearMarks::default(),
            };
            let (at, rotation) = exploded_text(&dim, &style);
            let lay = linear_layout(p1, p2, line_at, angle, "40 ±0.1", &style);
            assert!(lay.text_inside && lay.arrows_inside);
            // As before: the middle of the dimension line, LINEAR_TEXT_LIFT above it.
            let mid = Point::from((lay.f1.coords + lay.f2.coords) / 2.0);
            assert!((at - (mid + lay.up * (LINEAR_TEXT_LIFT * 2.0))).norm() < 1e-12);
            assert_eq!(rotation, lay.rotation);
            assert!((lay.text_mid - (at + lay.up * 1.0)).norm() < 1e-12);
            // The dimension line runs from foot to foot only.
            let lines: Vec<_> = explode_dimension(&dim, &style)
                .into_iter()
                .filter_map(|s| match s {
                    Shape::Line { from, to } => Some((from, to)),
                    _ => None,
                })
                .collect();
            assert!(lines.contains(&(lay.f1, lay.f2)));
        }
    }

    #[test]
    fn linear_text_that_does_not_fit_goes_beside_an_extension_line() {
        let style = DimStyle { text_height: 2.0, arrow_size: 1.8 };
        let th = style.text_height;
        for angle in [0.0, 0.7, 2.0, 3.5, -1.2, std::f64::consts::PI] {
            for (len, arrows_inside) in [(8.0, true), (2.0, false), (0.0, false)] {
                let u = Vector::new(f64::cos(angle), f64::sin(angle));
                let p1 = Point::new(-3.0, 2.0);
                let p2 = p1 + u * len;
                let line_at = p1 - perp(u) * 4.0;
                let text = "Z1 = 17 ±0.3";
                let dim =
                    Shape::LinearDimension { p1, p2, line_at, angle, text: text.into(), marks: LinearMarks::default() };
                let lay = linear_layout(p1, p2, line_at, angle, text, &style);
                assert!(!lay.text_inside);
                assert_eq!(lay.arrows_inside, arrows_inside, "len {len}");
                let (at, _) = exploded_text(&dim, &style);
                assert_eq!(at, lay.text_at);
                // Along the reading direction, the box lies wholly beyond both feet, clear
                // of the extension lines by LINEAR_TEXT_OUTSIDE_GAP.
                let (x0, x1, _, _) = linear_text_span(&lay, th);
                let x2 = (lay.f2 - lay.f1).dot(&lay.reading);
                let nearest = x0.min(x1).min((x0 - x2).abs()).min((x1 - x2).abs());
                let outside = (x0 >= 0.0 && x0 >= x2) || (x1 <= 0.0 && x1 <= x2);
                assert!(outside, "angle {angle} len {len}: box {x0}..{x1}, feet 0 and {x2}");
                assert!(nearest >= LINEAR_TEXT_OUTSIDE_GAP * th - 1e-9);
                // Arrowheads: tips at the feet, bases outside when they do not fit.
                let heads: Vec<[Point; 3]> = explode_dimension(&dim, &style)
                    .into_iter()
                    .filter_map(|s| match s {
                        Shape::Filled { points } => Some([points[0], points[1], points[2]]),
                        _ => None,
                    })
                    .collect();
                assert_eq!(heads.len(), if len == 0.0 && arrows_inside { 0 } else { 2 });
                for h in heads {
                    let base = Point::from((h[1].coords + h[2].coords) / 2.0);
                    let (tip, base) = ((h[0] - lay.f1).dot(&lay.reading), (base - lay.f1).dot(&lay.reading));
                    assert!(tip.abs() < 1e-9 || (tip - x2).abs() < 1e-9);
                    let base_inside = base > x2.min(0.0) + 1e-9 && base < x2.max(0.0) - 1e-9;
                    assert_eq!(base_inside, arrows_inside);
                }
            }
        }
    }

    /// `dim` (a linear dimension) with `marks`, exploded.
    fn with_marks(dim: &Shape, marks: LinearMarks, style: &DimStyle) -> Vec<Shape> {
        let Shape::LinearDimension { p1, p2, line_at, angle, text, .. } = dim.clone() else { panic!("not linear") };
        explode_dimension(&Shape::LinearDimension { p1, p2, line_at, angle, text, marks }, style)
    }

    #[test]
    fn a_dimension_from_its_base_has_a_circle_at_the_base_and_one_arrowhead_at_the_end() {
        let style = DimStyle { text_height: 2.0, arrow_size: 1.8 };
        // Both signs, long (arrowhead inside) and short (arrowhead outside, pointing in).
        for (base, end) in [(10.0, 50.0), (50.0, 10.0), (0.0, 3.0), (3.0, 0.0)] {
            let dim = Shape::LinearDimension {
                p1: Point::new(base, 0.0),
                p2: Point::new(end, 0.0),
                line_at: Point::new(0.0, 7.0),
                angle: 0.0,
                text: "40".into(),
                marks: LinearMarks::default(),
            };
            let marks = LinearMarks { ends: DimEnds::FromBase, text_along: None };
            let parts = with_marks(&dim, marks, &style);
            let circles: Vec<(Point, f64)> = parts
                .iter()
                .filter_map(|s| match s {
                    Shape::Circle { center, radius } => Some((*center, *radius)),
                    _ => None,
                })
                .collect();
            assert_eq!(circles, [(Point::new(base, 7.0), BASE_CIRCLE_RADIUS * 1.8)]);
            let heads: Vec<&Vec<Point>> = parts
                .iter()
                .filter_map(|s| match s {
                    Shape::Filled { points } => Some(points),
                    _ => None,
                })
                .collect();
            assert_eq!(heads.len(), 1);
            assert_eq!(heads[0][0], Point::new(end, 7.0));
            // The head points from the base side towards the end when it fits, from
            // beyond the end back at it when it does not.
            let back = heads[0][1].x - end;
            let fits = (end - base).abs() >= LINEAR_ARROWS_FIT * 1.8;
            assert_eq!(back.signum() == (base - end).signum(), fits, "{base} -> {end}");
        }
    }

    #[test]
    fn a_placed_text_sits_where_asked_with_the_dimension_line_run_on_under_it() {
        let style = DimStyle { text_height: 2.0, arrow_size: 1.8 };
        let dim = Shape::LinearDimension {
            p1: Point::new(10.0, 0.0),
            p2: Point::new(20.0, 0.0),
            line_at: Point::new(0.0, 5.0),
            angle: 0.0,
            text: "10 ±0.1".into(),
            marks: LinearMarks::default(),
        };
        let w = text_width("10 ±0.1", 2.0);
        for along in [5.0, 30.0, -12.0] {
            let marks = LinearMarks { ends: DimEnds::FromBase, text_along: Some(along) };
            let parts = with_marks(&dim, marks, &style);
            let (at, _) = parts
                .iter()
                .find_map(|s| match s {
                    Shape::Text { at, rotation, .. } => Some((*at, *rotation)),
                    _ => None,
                })
                .unwrap();
            assert!((at - Point::new(10.0 + along, 5.0 + LINEAR_TEXT_LIFT * 2.0)).norm() < 1e-12);
            // The dimension line (the horizontal one) spans the text and the feet (from the
            // base circle's rim).
            let (lo, hi) = parts
                .iter()
                .find_map(|s| match s {
                    Shape::Line { from, to } if from.y == to.y => Some((from.x.min(to.x), from.x.max(to.x))),
                    _ => None,
                })
                .unwrap();
            let (t0, t1) = (10.0 + along - 0.5 * w, 10.0 + along + 0.5 * w);
            let rim = 10.0 + BASE_CIRCLE_RADIUS * 1.8;
            assert!(lo <= t0.min(rim) + 1e-9 && hi >= t1.max(20.0) - 1e-9, "{along}: {lo}..{hi}");
            let lay = linear_layout_placed(
                Point::new(10.0, 0.0),
                Point::new(20.0, 0.0),
                Point::new(0.0, 5.0),
                0.0,
                "10 ±0.1",
                Some(along),
                &style,
            );
            assert_eq!(lay.text_inside, along == 5.0 && w <= 10.0);
        }
    }

    #[test]
    fn the_widest_width_holds_librecads_drawing_and_the_dejavu_estimate() {
        // LibreCAD 2.2's page of the triad's modes sheet: "k_l = 5 mm/mm", 12.5 high from
        // x = 0, inked to x = 149.09 mm; its font's advances less the last letter spacing
        // (1 of 9 units) give 149.11.
        let azomix: f64 = "k_l = 5 mm/mm".chars().map(azomix_advance).sum();
        assert!(((azomix - 1.0) * 12.5 / 9.0 - 149.09).abs() < 0.1, "{azomix}");
        assert!(widest_text_width("k_l = 5 mm/mm", 12.5) >= 149.09);
        // Never narrower than the DejaVu estimate, nor than LibreCAD's font, per character.
        for text in ["Mode 1 · counter-clockwise · drawn in Fig. 3", "φ1 = 359.999°", "±0.1", "W", " "] {
            let w = widest_text_width(text, 2.0);
            assert!(w >= text_width(text, 2.0) - 1e-12, "{text}");
            assert!(w >= text.chars().map(azomix_advance).sum::<f64>() * 2.0 / 9.0 - 1e-12, "{text}");
        }
        // A space: LibreCAD's word spacing, 0.75 heights (DejaVu's is 0.435).
        assert!((widest_text_width(" ", 1.0) - 0.75).abs() < 1e-12);
    }

    #[test]
    fn text_width_is_exact_for_dejavu_digits_and_signs() {
        // "25 ±0.1": 4 digits (1303 units), space and point (651), ± (1716), 2048 units an em.
        let em = (4.0 * 1303.0 + 2.0 * 651.0 + 1716.0) / 2048.0;
        assert!((text_width("25 ±0.1", CAP_HEIGHT_EM) - em).abs() < 1e-12);
    }
}
