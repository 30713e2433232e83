//! Figure: a dimensional chain as a designer draws it, and the Monte Carlo histogram.
//!
//! The part's features are vertical lines across a horizontal reference axis (the seed's
//! number line, its direction arrowed, the zero point marked). The independent dimensions
//! are linear dimensions above the axis, packed into rows so that no two overlap (interval
//! scheduling: each dimension, widened to its text, goes into the lowest row where it
//! fits). Redundant dimensions are drawn as reference dimensions "(80)" on their own layer;
//! the dependent dimensions are below the axis on layer `DEPENDENT`, in red, with their
//! worst-case tolerance.

use crate::draw::{Aci, DimStyle, Drawing, HAlign, LineType, Shape, VAlign, parts};
use crate::figure::plot::{self, Histogram};
use crate::geom::Point;
use crate::solve::chain::graph::{Analysis, fmt_value};
use crate::solve::chain::{Dimension, MonteCarlo, Stack};

/// Text height as a fraction of the chain's length.
const TEXT_FRACTION: f64 = 1.0 / 60.0;
/// Distance between dimension rows, in text heights.
const ROW_GAP: f64 = 2.6;
/// Approximate width of one character, in text heights (for packing the rows).
const CHAR_WIDTH: f64 = 0.62;

/// A dependent dimension to draw below the axis.
#[derive(Debug, Clone, PartialEq)]
pub struct DependentMark {
    /// Coordinate of its left end (b_l).
    pub left_x: f64,
    /// Coordinate of its right end (b_p).
    pub right_x: f64,
    /// Text, e.g. `Z1 = 17 ±0.3`.
    pub text: String,
}

/// The tolerance of a dimension as written on a drawing: `±0.1`, `+0.1/-0.05`, or nothing.
pub fn tolerance_text(d: &Dimension) -> String {
    if d.upper == 0.0 && d.lower == 0.0 {
        String::new()
    } else if (d.upper + d.lower).abs() < 1e-15 {
        format!(" ±{}", fmt_value(d.upper))
    } else {
        format!(" {:+}/{}", d.upper, fmt_value(d.lower)).replace("+-", "-")
    }
}

/// Packs intervals `[a, b]` into rows, the drafting rule: shorter dimensions nearer the
/// part, longer ones outside. Intervals are taken shortest first and each goes into the
/// lowest row where it overlaps nothing (touching end to end is allowed, as in a chain of
/// dimensions). Returns the row of each interval.
pub fn pack_rows(intervals: &[(f64, f64)]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..intervals.len()).collect();
    let len = |i: usize| intervals[i].1 - intervals[i].0;
    order.sort_by(|&i, &j| len(i).total_cmp(&len(j)).then(intervals[i].0.total_cmp(&intervals[j].0)));
    let mut rows: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut row = vec![0; intervals.len()];
    for i in order {
        let (a, b) = intervals[i];
        let free = |r: &Vec<(f64, f64)>| r.iter().all(|&(c, d)| b <= c || d <= a);
        match rows.iter().position(free) {
            Some(r) => {
                row[i] = r;
                rows[r].push((a, b));
            }
            None => {
                row[i] = rows.len();
                rows.push(vec![(a, b)]);
            }
        }
    }
    row
}

/// The chain drawing: the `dimensions` of the chain that `analysis` was made of, the
/// dependent dimensions to mark, and the length unit for the axis label (`mm`).
pub fn chain(dimensions: &[Dimension], analysis: &Analysis, dependents: &[DependentMark], units: &str) -> Drawing {
    let xs: Vec<f64> = analysis.features.iter().map(|f| f.x).collect();
    let xmin = xs.iter().cloned().fold(f64::INFINITY, f64::min);
    let xmax = xs.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let span = (xmax - xmin).max(f64::EPSILON.sqrt());
    let th = span * TEXT_FRACTION;
    let gap = ROW_GAP * th;
    let mut dr = Drawing::new(DimStyle { text_height: th, arrow_size: 0.9 * th });
    let axis = dr.layer("AXIS", Aci::DARK_GREY, LineType::Continuous);
    let features = dr.layer("FEATURES", Aci::LIGHT_GREY, LineType::Continuous);
    let names = dr.layer("FEATURE_NAMES", Aci::BLACK, LineType::Continuous);
    let dims_layer = dr.layer("DIMENSIONS", Aci::BLUE, LineType::Continuous);
    let redundant_layer = dr.layer("REDUNDANT", Aci::MAGENTA, LineType::Continuous);
    let dep_layer = dr.layer("DEPENDENT", Aci::RED, LineType::Continuous);

    // Independent (and redundant) dimensions above the axis.
    let x_of = |f: usize| analysis.features[analysis.node_of[f]].x;
    let mut items: Vec<(f64, f64, String, bool)> = Vec::new();
    for (i, d) in dimensions.iter().enumerate() {
        let (a, b) = (x_of(d.from), x_of(d.to));
        let value = fmt_value(d.nominal.abs());
        let text = if analysis.in_tree[i] { format!("{value}{}", tolerance_text(d)) } else { format!("({value})") };
        items.push((a.min(b), a.max(b), text, !analysis.in_tree[i]));
    }
    // A dimension's span in x with its text where the dimension puts it (between the
    // extension lines, or beside one when it does not fit), half a character clear.
    // Arrowheads outside the extension lines sit on stubs of the dimension line.
    let style = dr.dim_style;
    let widen = |a: f64, b: f64, text: &str| {
        let lay = parts::linear_layout(Point::new(a, 0.0), Point::new(b, 0.0), Point::new(a, 1.0), 0.0, text, &style);
        let half = 0.5 * lay.text_width + 0.5 * CHAR_WIDTH * th;
        let stub = if lay.arrows_inside { 0.0 } else { parts::LINEAR_ARROW_STUB * style.arrow_size };
        ((a - stub).min(lay.text_at.x - half), (b + stub).max(lay.text_at.x + half))
    };
    let intervals: Vec<(f64, f64)> = items.iter().map(|(a, b, t, _)| widen(*a, *b, t)).collect();
    let rows = pack_rows(&intervals);
    let n_rows = rows.iter().max().map_or(0, |r| r + 1);
    let dep_intervals: Vec<(f64, f64)> =
        dependents.iter().map(|m| widen(m.left_x.min(m.right_x), m.left_x.max(m.right_x), &m.text)).collect();
    let dep_rows = pack_rows(&dep_intervals);
    let n_dep_rows = dep_rows.iter().max().map_or(0, |r| r + 1);

    let top = gap * (n_rows as f64 + 0.4);
    let bottom = -gap * (n_dep_rows as f64 + 0.4);

    // The reference axis with its direction, and the zero point.
    let margin = 0.06 * span;
    dr.add(axis, Shape::Arrow { from: Point::new(xmin - margin, 0.0), to: Point::new(xmax + margin, 0.0), head: th });
    dr.add(axis, Shape::Circle { center: Point::new(0.0, 0.0), radius: 0.35 * th });
    dr.add(
        axis,
        Shape::Text {
            at: Point::new(xmax + margin + 0.5 * th, 0.0),
            height: th,
            value: format!("x [{units}]"),
            halign: HAlign::Left,
            valign: VAlign::Middle,
            rotation: 0.0,
        },
    );

    // Feature lines and their names below them.
    for f in &analysis.features {
        dr.add(features, Shape::Line { from: Point::new(f.x, bottom), to: Point::new(f.x, top) });
        let name = if f.tied { f.name.clone() } else { format!("{} (not tied)", f.name) };
        dr.add(
            names,
            Shape::Text {
                at: Point::new(f.x, bottom - 0.4 * th),
                height: 0.8 * th,
                value: name,
                halign: HAlign::Right,
                valign: VAlign::Middle,
                rotation: std::f64::consts::FRAC_PI_2,
            },
        );
    }

    for ((a, b, text, redundant), row) in items.into_iter().zip(rows) {
        let layer = if redundant { redundant_layer } else { dims_layer };
        let y = gap * (row as f64 + 1.0) - 0.4 * gap;
        dr.add(
            layer,
            Shape::LinearDimension {
                p1: Point::new(a, 0.0),
                p2: Point::new(b, 0.0),
                line_at: Point::new(0.5 * (a + b), y),
                angle: 0.0,
                text,
            },
        );
    }
    for (m, row) in dependents.iter().zip(dep_rows) {
        let y = -gap * (row as f64 + 1.0) + 0.2 * gap;
        let (a, b) = (m.left_x.min(m.right_x), m.left_x.max(m.right_x));
        dr.add(
            dep_layer,
            Shape::LinearDimension {
                p1: Point::new(a, 0.0),
                p2: Point::new(b, 0.0),
                line_at: Point::new(0.5 * (a + b), y),
                angle: 0.0,
                text: m.text.clone(),
            },
        );
    }
    dr
}

/// The Monte Carlo histogram of one dependent dimension, with the mean, the worst-case
/// limits and the spec limits marked.
pub fn histogram(
    z: &str,
    label: &str,
    units: &str,
    distribution: &str,
    mc: &MonteCarlo,
    stack: &Stack,
    spec: Option<[f64; 2]>,
) -> Drawing {
    let (x0, bin_width, counts) = mc.histogram.clone();
    let mut markers = vec![
        (mc.mean, "mean".to_string()),
        (stack.mean - stack.worst_case, "WC min".to_string()),
        (stack.mean + stack.worst_case, "WC max".to_string()),
    ];
    if let Some([lsl, usl]) = spec {
        markers.push((lsl, "LSL".into()));
        markers.push((usl, "USL".into()));
    }
    plot::histogram(&Histogram {
        title: format!("{z} = {label}: Monte Carlo, {} samples, {distribution}", mc.samples),
        x_label: format!("{z} [{units}]"),
        x0,
        bin_width,
        counts,
        markers,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packed_rows_never_overlap_and_chained_dimensions_share_a_row() {
        let iv = [(0.0, 10.0), (10.0, 20.0), (5.0, 15.0), (0.0, 30.0), (20.0, 25.0)];
        let rows = pack_rows(&iv);
        assert_eq!(rows[0], rows[1]); // end to end: one row
        for i in 0..iv.len() {
            for j in 0..i {
                if rows[i] == rows[j] {
                    assert!(iv[i].1 <= iv[j].0 || iv[j].1 <= iv[i].0, "{i} and {j} overlap in row {}", rows[i]);
                }
            }
        }
        assert_eq!(rows[3], 2); // the longest outside
    }

    #[test]
    fn tolerance_text_reads_like_a_drawing() {
        let mut d = Dimension { name: "w".into(), from: 0, to: 1, nominal: 10.0, upper: 0.1, lower: -0.1 };
        assert_eq!(tolerance_text(&d), " ±0.1");
        d.lower = -0.05;
        assert_eq!(tolerance_text(&d), " +0.1/-0.05");
        d.upper = 0.0;
        d.lower = 0.0;
        assert_eq!(tolerance_text(&d), "");
    }
}
