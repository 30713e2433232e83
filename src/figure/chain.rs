//! Figure: a dimensional chain as a designer draws it, and the Monte Carlo histogram.
//!
//! The part's features are vertical lines across a horizontal reference axis (the seed's
//! number line, its direction arrowed, the zero point marked). The independent dimensions
//! are linear dimensions above the axis, packed into rows so that no two overlap (interval
//! scheduling: each dimension, widened to its text, goes into the lowest row where it
//! fits). Redundant dimensions are drawn as reference dimensions "(80)" on their own layer;
//! the dependent dimensions are below the axis on layer `DEPENDENT`, in red, with their
//! worst-case tolerance.

use crate::draw::{Aci, DimEnds, DimStyle, Drawing, HAlign, LineType, LinearMarks, ScaleCaption, Shape, VAlign, parts};
use crate::figure::shared::plot::{self, Histogram};
use crate::figure::shared::vocab::{self, Sizes};
use crate::geom::Point;
use crate::solve::chain::graph::{Analysis, fmt_value};
use crate::solve::chain::{Dimension, Form, MonteCarlo, Stack};

/// Largest extent of the chain's features on paper, millimetres: the length scale k_l is
/// the nice value that draws them at most this long (a chain on A4 landscape); text is
/// 3.5 mm high on paper ([`vocab::PAPER_TEXT_MM`]).
pub const CHAIN_MM: f64 = 200.0;
/// Distance between dimension rows, in text heights.
const ROW_GAP: f64 = 2.6;
/// Clear space kept between two dimensions packed on one row, each side, in text heights
/// (text widths themselves come from `draw::parts::text_width`).
const ROW_CLEARANCE: f64 = 0.31;
/// Clear space between a dimension's text and any feature's coordinate (where feature and
/// extension lines run), in text heights.
const TEXT_CLEAR: f64 = 0.4;

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

/// The names the drawing, the report and the JSON give the features, in the order of
/// `analysis.features`. Named form: the scene's own names. Matrix form: `F0` for the zero
/// point, then `F1`, `F2`, … in axis order (increasing x), features not tied to the zero
/// point last, group by group, each group in axis order. The seed gives its features no
/// order of their own (row B lists the bases "in any order", and a feature is known only
/// by the value of a dimension ending there), so the axis is the order a reader checks
/// with a ruler; it also names a feature the same in matrices (2) and (3) wherever the
/// zero point is not involved, since (3) is (2) shifted.
pub fn feature_labels(analysis: &Analysis, form: Form) -> Vec<String> {
    let n = analysis.features.len();
    if form == Form::Named {
        return analysis.features.iter().map(|f| f.name.clone()).collect();
    }
    let group = |i: usize| analysis.untied.iter().position(|g| g.contains(&i)).map_or(0, |g| g + 1);
    let mut order: Vec<usize> = (1..n).collect();
    order.sort_by(|&i, &j| {
        let (a, b) = (&analysis.features[i], &analysis.features[j]);
        group(i).cmp(&group(j)).then(a.x.total_cmp(&b.x)).then(i.cmp(&j))
    });
    let mut labels = vec![String::new(); n];
    if n > 0 {
        labels[0] = "F0".into();
    }
    for (k, i) in order.into_iter().enumerate() {
        labels[i] = format!("F{}", k + 1);
    }
    labels
}

/// The text under a feature's line: its label and coordinate (`F3  x = 42`).
pub fn feature_text(label: &str, x: f64, tied: bool) -> String {
    let suffix = if tied { "" } else { " (not tied)" };
    format!("{label}  x = {}{suffix}", fmt_value(x))
}

/// Middle (x) of a dimension text `width` wide whose dimension spans `lo..hi`: as near the
/// middle of the span as lets the text's box keep `clear` off every coordinate in
/// `features` (each feature's line and every extension line run at a feature's coordinate,
/// so no such line then crosses the text, whatever row it is in). Beyond the outermost
/// features there is always room.
/// With `base = Some((x_base, x_end))` the text stays on the end's side of the base (a
/// dimension line run on past its base circle would read as a second dimension).
pub fn text_centre(lo: f64, hi: f64, width: f64, clear: f64, features: &[f64], base: Option<(f64, f64)>) -> f64 {
    let mut xs: Vec<f64> = features.iter().copied().filter(|x| x.is_finite()).collect();
    xs.sort_by(f64::total_cmp);
    let mid = 0.5 * (lo + hi);
    let half = 0.5 * width;
    // Free gaps between the features' clear zones, outermost ones unbounded.
    let mut edges = vec![f64::NEG_INFINITY];
    for x in &xs {
        edges.push(x - clear);
        edges.push(x + clear);
    }
    edges.push(f64::INFINITY);
    let mut best = mid;
    let mut best_d = f64::INFINITY;
    for g in edges.chunks(2) {
        let (mut a, mut b) = (g[0] + half, g[1] - half);
        match base {
            Some((x0, x1)) if x1 >= x0 => a = a.max(x0 + half),
            Some((x0, _)) => b = b.min(x0 - half),
            None => {}
        }
        if a > b {
            continue;
        }
        let c = mid.clamp(a, b);
        let d = (c - mid).abs();
        if d < best_d {
            best = c;
            best_d = d;
        }
    }
    best
}

/// One dimension of the chain drawing before it is put in a row.
struct DimItem {
    /// First definition point's x (the base, for a dimension with one).
    x1: f64,
    /// Second definition point's x (the end).
    x2: f64,
    text: String,
    layer: usize,
    marks: LinearMarks,
}

impl DimItem {
    /// The dimension with its dimension line at height `y`.
    fn shape(&self, y: f64) -> Shape {
        Shape::LinearDimension {
            p1: Point::new(self.x1, 0.0),
            p2: Point::new(self.x2, 0.0),
            line_at: Point::new(0.5 * (self.x1 + self.x2), y),
            angle: 0.0,
            text: self.text.clone(),
            marks: self.marks,
        }
    }
}

/// Least and greatest x of exploded dimension parts (texts by their estimated width).
fn x_extent(parts: &[Shape]) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut add = |x: f64| {
        lo = lo.min(x);
        hi = hi.max(x);
    };
    for s in parts {
        match s {
            Shape::Line { from, to } => {
                add(from.x);
                add(to.x);
            }
            Shape::Circle { center, radius } => {
                add(center.x - radius);
                add(center.x + radius);
            }
            Shape::Filled { points } => points.iter().for_each(|p| add(p.x)),
            Shape::Text { at, height, value, .. } => {
                let w = parts::text_width(value, *height);
                add(at.x - 0.5 * w);
                add(at.x + 0.5 * w);
            }
            _ => {}
        }
    }
    (lo, hi)
}

/// The chain drawing: the `dimensions` of the chain that `analysis` was made of, the
/// dependent dimensions to mark, the features' `labels` ([`feature_labels`]) and the length
/// unit for the axis label (`mm`).
///
/// Each independent (and redundant) dimension is drawn in seed 001's notation
/// ([`DimEnds::FromBase`]): a small circle at its base, an arrowhead at its end, so the
/// matrix's row B and the sign of row W read off the drawing. Dependent dimensions Z =
/// [b_l, b_p] have no base and keep an arrowhead at each end. Every text keeps clear of
/// every feature's coordinate ([`text_centre`]), so no extension or feature line crosses
/// it; rows are packed on the dimensions' whole drawn extent (line, stubs, circle, text).
/// Each is a [`Shape::LinearDimension`] carrying its marks and its text's place: the DXF
/// writes it as a DIMENSION whose block holds the notation (or, exploded, as its lines,
/// circle, arrowhead and text), the SVG draws the same parts (docs/chain.md, docs/dxf.md).
pub fn chain(
    dimensions: &[Dimension],
    analysis: &Analysis,
    dependents: &[DependentMark],
    labels: &[String],
    units: &str,
) -> Drawing {
    let xs: Vec<f64> = analysis.features.iter().map(|f| f.x).collect();
    let xmin = xs.iter().cloned().fold(f64::INFINITY, f64::min);
    let xmax = xs.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let span = (xmax - xmin).max(f64::EPSILON.sqrt());
    let k_l = vocab::length_scale(span, CHAIN_MM);
    let sizes = Sizes::on_paper(k_l);
    let th = sizes.text;
    let gap = ROW_GAP * th;
    let mut dr = Drawing::new(DimStyle { text_height: th, arrow_size: 0.9 * th });
    dr.paper_mm_per_unit = Some(1.0 / k_l);
    let axis = dr.layer("AXIS", Aci::DARK_GREY, LineType::Continuous);
    let features = dr.layer("FEATURES", Aci::LIGHT_GREY, LineType::Continuous);
    let names = dr.layer("FEATURE_NAMES", Aci::BLACK, LineType::Continuous);
    let dims_layer = dr.layer("DIMENSIONS", Aci::BLUE, LineType::Continuous);
    let redundant_layer = dr.layer("REDUNDANT", Aci::MAGENTA, LineType::Continuous);
    let dep_layer = dr.layer("DEPENDENT", Aci::RED, LineType::Continuous);
    let style = dr.dim_style;
    let clear = TEXT_CLEAR * th;

    // Independent (and redundant) dimensions above the axis, from base to end.
    let x_of = |f: usize| analysis.features[analysis.node_of[f]].x;
    let item = |x1: f64, x2: f64, text: String, layer: usize, ends: DimEnds| {
        let w = parts::text_width(&text, th);
        let base = (ends == DimEnds::FromBase).then_some((x1, x2));
        let t = text_centre(x1.min(x2), x1.max(x2), w, clear, &xs, base);
        DimItem { x1, x2, text, layer, marks: LinearMarks { ends, text_along: Some(t - x1) } }
    };
    let above: Vec<DimItem> = dimensions
        .iter()
        .enumerate()
        .map(|(i, d)| {
            let value = fmt_value(d.nominal.abs());
            let (text, layer) = if analysis.in_tree[i] {
                (format!("{value}{}", tolerance_text(d)), dims_layer)
            } else {
                (format!("({value})"), redundant_layer)
            };
            item(x_of(d.from), x_of(d.to), text, layer, DimEnds::FromBase)
        })
        .collect();
    let below: Vec<DimItem> = dependents
        .iter()
        .map(|m| item(m.left_x.min(m.right_x), m.left_x.max(m.right_x), m.text.clone(), dep_layer, DimEnds::Arrows))
        .collect();
    // Rows packed on what each dimension draws, ROW_CLEARANCE apart.
    let rows_of = |items: &[DimItem]| {
        let intervals: Vec<(f64, f64)> = items
            .iter()
            .map(|it| {
                let (a, b) = x_extent(&parts::explode_dimension(&it.shape(1.0), &style));
                (a - ROW_CLEARANCE * th, b + ROW_CLEARANCE * th)
            })
            .collect();
        pack_rows(&intervals)
    };
    let rows = rows_of(&above);
    let n_rows = rows.iter().max().map_or(0, |r| r + 1);
    let dep_rows = rows_of(&below);
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
            runs: crate::draw::Runs::flat(),
            at: Point::new(xmax + margin + 0.5 * th, 0.0),
            height: th,
            value: format!("x [{units}]"),
            halign: HAlign::Left,
            valign: VAlign::Middle,
            rotation: 0.0,
        },
    );

    // Feature lines and, below them, each feature's label and coordinate.
    let mut lowest = bottom;
    for (i, f) in analysis.features.iter().enumerate() {
        dr.add(features, Shape::Line { from: Point::new(f.x, bottom), to: Point::new(f.x, top) });
        let label = labels.get(i).map_or(f.name.as_str(), String::as_str);
        let value = feature_text(label, f.x, f.tied);
        // Reading up to just below the feature's line, inserted at its lower end (the
        // drawing's bounds count a text by its unrotated box from the insertion point).
        let h = 0.8 * th;
        let w = parts::text_width(&value, h);
        lowest = lowest.min(bottom - 0.4 * th - w);
        dr.add(
            names,
            Shape::Text {
                runs: crate::draw::Runs::flat(),
                at: Point::new(f.x, bottom - 0.4 * th - w),
                height: h,
                value,
                halign: HAlign::Left,
                valign: VAlign::Middle,
                rotation: std::f64::consts::FRAC_PI_2,
            },
        );
    }

    for (it, row) in above.iter().zip(rows) {
        let y = gap * (row as f64 + 1.0) - 0.4 * gap;
        dr.add(it.layer, it.shape(y));
    }
    for (it, row) in below.iter().zip(dep_rows) {
        let y = -gap * (row as f64 + 1.0) + 0.2 * gap;
        dr.add(it.layer, it.shape(y));
    }
    // The length scale and its bar under the feature names, at the axis's start.
    let at = Point::new(xmin - margin, lowest - 1.5 * th);
    let caption = ScaleCaption::new("k_l = ", k_l, format!(" {units}/mm"), 1.0 / k_l);
    dr.scale_text(axis, at, sizes.small_text(), caption);
    let value = vocab::bar_value(k_l);
    let bar_at = at + Point::new(2.0 * sizes.small_text(), -2.0 * sizes.small_text()).coords;
    vocab::scale_bar(&mut dr, axis, bar_at, value, &format!("{} {units}", vocab::scale_text(value)), sizes);
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
    fn text_keeps_off_every_feature_and_stays_on_the_end_side_of_its_base() {
        let xs = [-38.0, 0.0, 25.0, 42.0, 122.0, 177.0, 187.0, 202.0, 222.0];
        let (w, clear) = (24.0, 2.0);
        let clear_of_all = |c: f64| xs.iter().all(|x| (c - 0.5 * w) >= x + clear || (c + 0.5 * w) <= x - clear);
        // Fits between 42 and 122: centred.
        assert_eq!(text_centre(42.0, 122.0, w, clear, &xs, None), 82.0);
        // 187..202 is too narrow, and so is 202..222: beyond 222 on the end's side.
        let c = text_centre(187.0, 202.0, w, clear, &xs, Some((187.0, 202.0)));
        assert!(clear_of_all(c) && c - 0.5 * w >= 222.0 + clear - 1e-9, "{c}");
        // Without a base it may go to the nearer side (before 177).
        let c = text_centre(187.0, 202.0, w, clear, &xs, None);
        assert!(clear_of_all(c) && c + 0.5 * w <= 177.0 - clear + 1e-9, "{c}");
        // A negative dimension (base 222, end 122) keeps its text left of the base.
        let c = text_centre(122.0, 222.0, w, clear, &xs, Some((222.0, 122.0)));
        assert!(clear_of_all(c) && c + 0.5 * w <= 222.0, "{c}");
    }

    #[test]
    fn features_are_named_f0_at_the_zero_point_then_along_the_axis() {
        use crate::solve::chain::graph::Feature;
        let f = |name: &str, x: f64| Feature { name: name.into(), aliases: vec![], x, tied: true };
        let mut a = crate::solve::chain::analyse(&crate::solve::chain::Chain {
            form: Form::Matrix,
            features: vec!["0".into()],
            dimensions: vec![],
            dependent: vec![],
        });
        a.features = vec![f("0", 0.0), f("80", 42.0), f("-38", -38.0), f("25", 25.0)];
        assert_eq!(feature_labels(&a, Form::Matrix), ["F0", "F3", "F1", "F2"]);
        assert_eq!(feature_labels(&a, Form::Named), ["0", "80", "-38", "25"]);
        assert_eq!(feature_text("F3", 42.0, true), "F3  x = 42");
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
