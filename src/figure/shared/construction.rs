//! What a drawn construction shares (the triad's Fig. 3, the synthesis constructions):
//! letters placed in the free direction around a point, circles and dimensions that
//! letters keep off, angular dimensions placed where their text is free, captions, and the
//! length-scale block under a figure.

use crate::draw::parts::explode_dimension;
use crate::draw::{DimStyle, Drawing, HAlign, Shape, VAlign};
use crate::figure::shared::labels::{self, TextBox};
use crate::figure::shared::vocab::{self, ModelUnits, Sizes};
use crate::geom::{Point, Vector, normalize_angle, polar};

/// Chords a circle is cut into for the letter placer (3.75° each).
pub const CIRCLE_CHORDS: usize = 96;

/// Direction (radians) in the middle of the widest gap between the `occupied` directions.
pub fn free_direction(occupied: &[f64]) -> f64 {
    let mut a: Vec<f64> = occupied.iter().map(|&x| normalize_angle(x)).collect();
    if a.is_empty() {
        return std::f64::consts::FRAC_PI_4;
    }
    a.sort_by(f64::total_cmp);
    let mut best = (0.0, 0.0);
    for i in 0..a.len() {
        let next = if i + 1 < a.len() { a[i + 1] } else { a[0] + std::f64::consts::TAU };
        let gap = next - a[i];
        if gap > best.0 {
            best = (gap, a[i] + 0.5 * gap);
        }
    }
    best.1
}

/// The arc of radius `r` about `c` from `start` sweeping `sweep` (radians, ≥ 0) as chords,
/// for texts to keep off.
pub fn arc_segments(lines: &mut Vec<(Point, Point)>, c: Point, r: f64, start: f64, sweep: f64) {
    let n = ((sweep / std::f64::consts::TAU * CIRCLE_CHORDS as f64).ceil() as usize).max(1);
    let mut prev = polar(c, r, start);
    for k in 1..=n {
        let p = polar(c, r, start + sweep * k as f64 / n as f64);
        lines.push((prev, p));
        prev = p;
    }
}

/// Everything a dimension draws (lines, arc, arrowheads, text) as segments and boxes that
/// letters keep off.
pub fn keep_letters_off_dimension(letters: &mut labels::Polygon, dim: &Shape, style: &DimStyle) {
    for part in explode_dimension(dim, style) {
        match part {
            Shape::Line { from, to } => letters.segment(from, to),
            Shape::Arc { center, radius, start, end } => {
                let mut arc = Vec::new();
                arc_segments(&mut arc, center, radius, start, normalize_angle(end - start));
                arc.into_iter().for_each(|(a, b)| letters.segment(a, b));
            }
            Shape::Filled { points } => {
                let (mut min, mut max) = (points[0], points[0]);
                for p in &points {
                    min = Point::new(min.x.min(p.x), min.y.min(p.y));
                    max = Point::new(max.x.max(p.x), max.y.max(p.y));
                }
                letters.keep_off(TextBox { min, max });
            }
            Shape::Text { at, height, value, .. } => letters.keep_off(TextBox::centred(at, &value, height)),
            _ => {}
        }
    }
}

/// The box of a dimension's text.
pub fn dimension_text_box(dim: &Shape, style: &DimStyle) -> Option<TextBox> {
    explode_dimension(dim, style).into_iter().find_map(|part| {
        // The text as drawn (its descenders: φ), turned with it.
        let c = crate::draw::text_corners(&part)?;
        let min = c.iter().fold(c[0], |m, q| Point::new(m.x.min(q.x), m.y.min(q.y)));
        let max = c.iter().fold(c[0], |m, q| Point::new(m.x.max(q.x), m.y.max(q.y)));
        Some(TextBox { min, max })
    })
}

/// Radii tried for an angular dimension, as multiples of its preferred radius, in order:
/// the first whose text overlaps no earlier dimension's text and crosses no line is drawn,
/// else the first that overlaps the fewest texts, then crosses the fewest lines.
pub const DIMENSION_RADII: [f64; 20] =
    [1.0, 0.85, 1.15, 0.7, 1.3, 0.55, 1.45, 0.45, 1.6, 1.75, 1.9, 2.05, 2.2, 2.4, 2.6, 2.8, 3.0, 3.3, 3.6, 4.0];

/// The dimension `dim_at(radius)` at the first of [`DIMENSION_RADII`] × `preferred` whose
/// text overlaps none of `texts` and crosses none of `lines` (else the least crowded).
pub fn place_dimension(
    dim_at: impl Fn(f64) -> Shape,
    preferred: f64,
    style: &DimStyle,
    texts: &[TextBox],
    lines: &[(Point, Point)],
) -> Shape {
    let crowding = |dim: &Shape| {
        dimension_text_box(dim, style).map_or((0, 0), |b| {
            (texts.iter().filter(|o| o.overlaps(&b)).count(), lines.iter().filter(|(u, v)| b.crosses(*u, *v)).count())
        })
    };
    let mut best: Option<((usize, usize), Shape)> = None;
    for k in DIMENSION_RADII {
        let dim = dim_at(k * preferred);
        let score = crowding(&dim);
        if best.as_ref().is_none_or(|(b, _)| score < *b) {
            best = Some((score, dim));
        }
        if score == (0, 0) {
            break;
        }
    }
    best.map_or_else(|| dim_at(preferred), |(_, dim)| dim)
}

/// Left-aligned lines from `top_left` (the first line's baseline) downwards, 1.8 heights
/// apart: each flat (a `String`) or with its subscripts (a [`labels::Label`]: φ_1).
pub fn caption<L: Clone + Into<labels::Label>>(
    d: &mut Drawing,
    layer: usize,
    top_left: Point,
    lines: &[L],
    height: f64,
) {
    let mut y = top_left.y;
    for line in lines {
        let labels::Label { text: value, runs } = line.clone().into();
        d.add(
            layer,
            Shape::Text {
                runs,
                at: Point::new(top_left.x, y),
                height,
                value,
                halign: HAlign::Left,
                valign: VAlign::Baseline,
                rotation: 0.0,
            },
        );
        y -= 1.8 * height;
    }
}

/// The scale lines a figure prints, and its scale bar under them: `k_l = 2 mm/mm`, then
/// `0 ├──┤ 50 mm`, from `top_left` (the k_l line's baseline) down.
pub fn length_scale_block(d: &mut Drawing, layer: usize, top_left: Point, k_l: f64, units: ModelUnits, s: Sizes) {
    d.scale_text(layer, top_left, s.small_text(), vocab::length_caption("", k_l, units));
    let value = vocab::bar_value(k_l);
    let at = top_left + Vector::new(2.0 * s.small_text(), -2.0 * s.small_text());
    vocab::scale_bar(d, layer, at, value, &format!("{} {}", vocab::scale_text(value), units.length), s);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn free_direction_is_the_middle_of_the_widest_gap() {
        let d = free_direction(&[0.0, std::f64::consts::FRAC_PI_2]);
        assert!((d - 1.25 * std::f64::consts::PI).abs() < 1e-12);
        let d = free_direction(&[0.1]);
        assert!((normalize_angle(d) - (0.1 + std::f64::consts::PI)).abs() < 1e-12);
    }
}
