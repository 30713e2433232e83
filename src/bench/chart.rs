//! The charts of `mechdraw bench`, drawn from its measurements: speed against accuracy
//! (time per solve, log x, against error, log y; one series per method and problem, each
//! point labelled by its setting) and the triad's basins of attraction. They live with the
//! bench, not in `figure/`, so that figures know nothing of the bench.

use super::Measurement;
use super::basins::{Basin, Strip};
use crate::draw::{Aci, DimStyle, Drawing, HAlign, LineType, Shape, VAlign};
use crate::figure::shared::labels::{Polygon, TextBox};
use crate::geom::{Point, Vector, perp};
use crate::solve::triad::Configuration;

/// Errors below this are drawn on the chart's floor (exact answers have error 0).
pub const ERROR_FLOOR: f64 = 1e-17;

// The charts are drawn in paper millimetres (`paper_mm_per_unit = 1`): a chart 180 mm
// wide, its text 2.5 mm high (the ISO 3098 minimum), prints true at 100 %.
const W: f64 = 180.0;
const H: f64 = 120.0;
const TEXT: f64 = 2.5;
/// Points of one series closer than this (model units) share one label.
const LABEL_MERGE: f64 = 6.0;
/// Radius of a point's marker circle, paper mm.
const MARKER: f64 = 0.9;
/// Width of a series' line, paper mm.
const LINE_WIDTH: f64 = 0.3;
/// Clear space between a point's label and the lines and markers of every series, paper mm.
const CLEAR: f64 = 0.4;
const PALETTE: [Aci; 8] =
    [Aci::BLUE, Aci::RED, Aci::GREEN, Aci::MAGENTA, Aci::ORANGE, Aci::CYAN, Aci::DARK_GREY, Aci(34)];

/// `10^k` written with superscript digits, e.g. `10⁻¹²`.
pub fn power_of_ten(k: i32) -> String {
    const SUP: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let mut s = String::from("10");
    if k < 0 {
        s.push('⁻');
    }
    for d in k.unsigned_abs().to_string().bytes() {
        s.push(SUP[(d - b'0') as usize]);
    }
    s
}

/// Decade range `[floor(log10 min), ceil(log10 max)]`, at least one decade wide.
fn decades(values: impl Iterator<Item = f64>) -> (i32, i32) {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if !lo.is_finite() {
        return (0, 1);
    }
    let (a, b) = (libm::log10(lo).floor() as i32, libm::log10(hi).ceil() as i32);
    (a, b.max(a + 1))
}

/// Draws the chart of the measurements that have an error. Series are keyed by
/// `problem / method`, points joined in the order given.
pub fn speed_accuracy_chart(title: &str, ms: &[Measurement]) -> Drawing {
    let mut d = Drawing::new(DimStyle { text_height: TEXT, arrow_size: 2.0 });
    d.paper_mm_per_unit = Some(1.0);
    let axes = d.layer("AXES", Aci::BLACK, LineType::Continuous);
    let grid = d.layer("GRID", Aci::LIGHT_GREY, LineType::Continuous);
    let data = d.layer("DATA", Aci::BLACK, LineType::Continuous);
    let labels = d.layer("LABELS", Aci::DARK_GREY, LineType::Continuous);
    let pts: Vec<&Measurement> = ms.iter().filter(|m| m.error.is_some() && m.ns_per_solve > 0.0).collect();
    let (x0, x1) = decades(pts.iter().map(|m| m.ns_per_solve));
    let (y0, y1) = decades(pts.iter().map(|m| m.error.unwrap_or(1.0).max(ERROR_FLOOR)));
    let px = |ns: f64| W * (libm::log10(ns) - x0 as f64) / (x1 - x0) as f64;
    let py = |e: f64| H * (libm::log10(e.max(ERROR_FLOOR)) - y0 as f64) / (y1 - y0) as f64;

    // Frame, decade grid and labels.
    d.add(
        axes,
        Shape::Polyline {
            points: vec![Point::new(0.0, 0.0), Point::new(W, 0.0), Point::new(W, H), Point::new(0.0, H)],
            closed: true,
            width: 0.0,
        },
    );
    let label = |at: Point, value: String, h: HAlign, v: VAlign| Shape::Text {
        runs: crate::draw::Runs::flat(),
        at,
        height: TEXT,
        value,
        halign: h,
        valign: v,
        rotation: 0.0,
    };
    for k in x0..=x1 {
        let x = px(crate::geom::powi(10.0, k));
        d.add(grid, Shape::Line { from: Point::new(x, 0.0), to: Point::new(x, H) });
        d.add(axes, label(Point::new(x, -2.0), power_of_ten(k), HAlign::Center, VAlign::Top));
    }
    for k in y0..=y1 {
        let y = H * (k - y0) as f64 / (y1 - y0) as f64;
        d.add(grid, Shape::Line { from: Point::new(0.0, y), to: Point::new(W, y) });
        d.add(axes, label(Point::new(-2.0, y), power_of_ten(k), HAlign::Right, VAlign::Middle));
    }
    d.add(axes, label(Point::new(W / 2.0, -9.0), "time per solve [ns]".into(), HAlign::Center, VAlign::Top));
    d.add(
        axes,
        Shape::Text {
            runs: crate::draw::Runs::flat(),
            at: Point::new(-16.0, H / 2.0),
            height: TEXT,
            value: "error (relative)".into(),
            halign: HAlign::Center,
            valign: VAlign::Baseline,
            rotation: std::f64::consts::FRAC_PI_2,
        },
    );
    d.add(
        axes,
        Shape::Text {
            runs: crate::draw::Runs::flat(),
            at: Point::new(W / 2.0, H + 5.0),
            height: 1.4 * TEXT,
            value: title.into(),
            halign: HAlign::Center,
            valign: VAlign::Baseline,
            rotation: 0.0,
        },
    );

    // Series in order of first appearance.
    let mut keys: Vec<(String, String)> = Vec::new();
    for m in &pts {
        let k = (m.problem.clone(), m.method.clone());
        if !keys.contains(&k) {
            keys.push(k);
        }
    }
    // Every point's label is placed by the letter placer, all series together: off the
    // other labels, the point markers and the margins, and (preferably) off every series' lines.
    let mut names = Polygon::of_names();
    // Inside the frame: the margins (tick labels, title, legend) are kept off.
    let m = 20.0;
    for (min, max) in
        [((-m, -m), (W + m, 0.0)), ((-m, H), (W + m, H + m)), ((-m, -m), (0.0, H + m)), ((W, -m), (W + m, H + m))]
    {
        names.keep_off(TextBox { min: Point::new(min.0, min.1), max: Point::new(max.0, max.1) });
    }
    // Each series: its colour, its points, its labels.
    type Series = (Aci, Vec<Point>, Vec<(Point, String)>);
    let series: Vec<Series> = keys
        .iter()
        .enumerate()
        .map(|(i, (problem, method))| {
            let color = PALETTE[i % PALETTE.len()];
            let series: Vec<&&Measurement> =
                pts.iter().filter(|m| &m.problem == problem && &m.method == method).collect();
            let points: Vec<Point> =
                series.iter().map(|m| Point::new(px(m.ns_per_solve), py(m.error.unwrap_or(1.0)))).collect();
            let labels = point_labels(&points, &series);
            (color, points, labels)
        })
        .collect();
    for (_, points, _) in &series {
        // A line is drawn LINE_WIDTH wide: a label keeps CLEAR from its edges (the placer
        // tests boxes against its centre line and the two lines CLEAR off its edges).
        let off = 0.5 * LINE_WIDTH + CLEAR;
        for w in points.windows(2) {
            let v = w[1] - w[0];
            // (A zero-length piece gives NaN offsets, which the placer leaves out.)
            let n = perp(v) * (off / v.norm());
            names.segment(w[0], w[1]);
            names.segment(w[0] + n, w[1] + n);
            names.segment(w[0] - n, w[1] - n);
        }
        let r = Vector::new(MARKER + CLEAR, MARKER + CLEAR);
        for p in points {
            names.keep_off(TextBox { min: p - r, max: p + r });
        }
    }
    for (color, _, groups) in &series {
        for (p, text) in groups {
            names.letter(*p, text, 0.65 * TEXT, Vector::new(1.0, 1.0), Some(*color));
        }
    }
    for (i, ((problem, method), (color, points, _))) in keys.iter().zip(&series).enumerate() {
        let color = *color;
        if points.len() > 1 {
            d.add_colored(data, color, Shape::Polyline { points: points.clone(), closed: false, width: LINE_WIDTH });
        }
        for p in points {
            d.add_colored(data, color, Shape::Circle { center: *p, radius: MARKER });
        }
        // Legend to the right of the plot.
        let y = H - 4.0 - 5.0 * i as f64;
        d.add_colored(data, color, Shape::Line { from: Point::new(W + 6.0, y), to: Point::new(W + 12.0, y) });
        d.add_colored(data, color, Shape::Circle { center: Point::new(W + 9.0, y), radius: MARKER });
        d.add(labels, label(Point::new(W + 14.0, y), format!("{problem}: {method}"), HAlign::Left, VAlign::Middle));
    }
    // The labels last, over the lines they keep off.
    names.draw(&mut d, labels);
    d
}

/// A series' point labels: its settings, points closer than [`LABEL_MERGE`] sharing one
/// label ("tol=1e-12, 1e-15") at the first of them, so that labels of coinciding points do
/// not pile up.
fn point_labels(points: &[Point], series: &[&&Measurement]) -> Vec<(Point, String)> {
    let mut groups: Vec<(Point, String)> = Vec::new();
    for (p, m) in points.iter().zip(series) {
        match groups.last_mut() {
            Some((q, text)) if (p - *q).norm() < LABEL_MERGE => {
                let value = m.setting.split_once('=').map_or(m.setting.as_str(), |(_, v)| v);
                text.push_str(", ");
                text.push_str(value);
            }
            _ => groups.push((*p, m.setting.clone())),
        }
    }
    groups
}

/// Width of the basin strips, model units (360° of start angle).
const BASIN_W: f64 = 180.0;
/// Height of one strip.
const STRIP_H: f64 = 8.0;
/// Gap between strips.
const STRIP_GAP: f64 = 5.0;
const MODE_COLORS: [Aci; 8] =
    [Aci::BLUE, Aci::ORANGE, Aci::GREEN, Aci::MAGENTA, Aci::CYAN, Aci(34), Aci::YELLOW, Aci(190)];

fn basin_color(b: Basin) -> Aci {
    match b {
        Basin::Mode(k) => MODE_COLORS[k % MODE_COLORS.len()],
        Basin::NoStart => Aci::LIGHT_GREY,
        Basin::Failed => Aci::BLACK,
        Basin::Stray => Aci::RED,
    }
}

/// The basins chart: one horizontal strip per method over start phi1 ∈ [0°, 360°),
/// coloured by the assembly mode each start converges to (legend: the modes' angles and
/// orientation), light grey where the start triangle does not exist, black where the
/// method fails by name, red for a result that is no mode.
pub fn basins_chart(title: &str, strips: &[Strip], modes: &[Configuration]) -> Drawing {
    let mut d = Drawing::new(DimStyle { text_height: TEXT, arrow_size: 2.0 });
    d.paper_mm_per_unit = Some(1.0);
    let axes = d.layer("AXES", Aci::BLACK, LineType::Continuous);
    let fill = d.layer("BASINS", Aci::BLACK, LineType::Continuous);
    let text = |at: Point, value: String, halign: HAlign, valign: VAlign| Shape::Text {
        runs: crate::draw::Runs::flat(),
        at,
        height: TEXT,
        value,
        halign,
        valign,
        rotation: 0.0,
    };
    let rect = |x0: f64, x1: f64, y0: f64, y1: f64| Shape::Filled {
        points: vec![Point::new(x0, y0), Point::new(x1, y0), Point::new(x1, y1), Point::new(x0, y1)],
    };
    let top = strips.len() as f64 * (STRIP_H + STRIP_GAP);
    for (i, strip) in strips.iter().enumerate() {
        let y0 = top - (i as f64 + 1.0) * (STRIP_H + STRIP_GAP);
        let n = strip.outcomes.len().max(1);
        let dx = BASIN_W / n as f64;
        let mut k = 0;
        while k < strip.outcomes.len() {
            let b = strip.outcomes[k];
            let mut e = k + 1;
            while e < strip.outcomes.len() && strip.outcomes[e] == b {
                e += 1;
            }
            d.add_colored(fill, basin_color(b), rect(k as f64 * dx, e as f64 * dx, y0, y0 + STRIP_H));
            k = e;
        }
        d.add(
            axes,
            Shape::Polyline {
                points: vec![
                    Point::new(0.0, y0),
                    Point::new(BASIN_W, y0),
                    Point::new(BASIN_W, y0 + STRIP_H),
                    Point::new(0.0, y0 + STRIP_H),
                ],
                closed: true,
                width: 0.0,
            },
        );
        d.add(axes, text(Point::new(0.0, y0 + STRIP_H + 1.0), strip.method.clone(), HAlign::Left, VAlign::Baseline));
    }
    // Start-angle axis under the strips.
    for deg in (0..=360).step_by(45) {
        let x = BASIN_W * deg as f64 / 360.0;
        d.add(axes, Shape::Line { from: Point::new(x, -STRIP_GAP + 1.0), to: Point::new(x, -STRIP_GAP - 0.5) });
        d.add(axes, text(Point::new(x, -STRIP_GAP - 1.5), format!("{deg}°"), HAlign::Center, VAlign::Top));
    }
    d.add(axes, Shape::Line { from: Point::new(0.0, -STRIP_GAP + 1.0), to: Point::new(BASIN_W, -STRIP_GAP + 1.0) });
    d.add(axes, text(Point::new(BASIN_W / 2.0, -STRIP_GAP - 7.0), "start phi1".into(), HAlign::Center, VAlign::Top));
    d.add(
        axes,
        Shape::Text {
            runs: crate::draw::Runs::flat(),
            at: Point::new(BASIN_W / 2.0, top + 4.0),
            height: 1.4 * TEXT,
            value: title.into(),
            halign: HAlign::Center,
            valign: VAlign::Baseline,
            rotation: 0.0,
        },
    );
    // Legend to the right.
    let mut entries: Vec<(Aci, String)> = modes
        .iter()
        .enumerate()
        .map(|(k, m)| {
            let p = m.phi_deg();
            (
                basin_color(Basin::Mode(k)),
                format!("mode {}: phi = ({:.2}°, {:.2}°, {:.2}°), {}", k + 1, p[0], p[1], p[2], m.orientation),
            )
        })
        .collect();
    entries.push((basin_color(Basin::NoStart), "no start triangle at this phi1".into()));
    entries.push((basin_color(Basin::Failed), "named failure (stalled, no intersection, ...)".into()));
    entries.push((basin_color(Basin::Stray), "converged to no mode (never expected)".into()));
    for (i, (c, label)) in entries.into_iter().enumerate() {
        let y = top - 4.0 - 5.0 * i as f64;
        d.add_colored(fill, c, rect(BASIN_W + 6.0, BASIN_W + 10.0, y - 1.5, y + 1.5));
        d.add(axes, text(Point::new(BASIN_W + 12.0, y), label, HAlign::Left, VAlign::Middle));
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn powers_of_ten_use_superscripts() {
        assert_eq!(power_of_ten(-12), "10⁻¹²");
        assert_eq!(power_of_ten(3), "10³");
        assert_eq!(power_of_ten(0), "10⁰");
    }

    /// Measurements from a `methods.csv` of `mechdraw bench` (error = max(residual, distance)).
    fn measurements(csv: &str) -> Vec<Measurement> {
        csv.lines()
            .skip(1)
            .map(|l| {
                let f: Vec<&str> = l.split(',').collect();
                let num = |i: usize| f[i].parse::<f64>().expect("a number");
                Measurement::new(f[0], f[1], f[2], num(3), num(5), num(6))
            })
            .collect()
    }

    /// No point label of the chart overlaps another label or a point's marker, none leaves
    /// the frame, and none crosses a series' line: on the published run (idle machine) and on
    /// a run on a busy machine, whose scattered times cross the series (the labels of the
    /// four-bar's and the shaper's Assur rows touched when placed by a fixed offset).
    #[test]
    fn point_labels_keep_off_each_other_the_markers_and_the_lines() {
        for (run, csv) in
            [("idle", include_str!("testdata/methods-idle.csv")), ("busy", include_str!("testdata/methods-busy.csv"))]
        {
            let ms = measurements(csv);
            let d = speed_accuracy_chart("t", &ms);
            let labels = d.layers.iter().position(|l| l.name == "LABELS").expect("a LABELS layer");
            let data = d.layers.iter().position(|l| l.name == "DATA").expect("a DATA layer");
            let (mut boxes, mut lines, mut markers) = (Vec::new(), Vec::new(), Vec::new());
            for e in &d.entities {
                match &e.shape {
                    Shape::Text { at, value, height, halign: HAlign::Center, .. } if e.layer == labels => {
                        boxes.push((value.clone(), TextBox::centred(*at, value, *height)));
                    }
                    Shape::Polyline { points, .. } if e.layer == data => {
                        lines.extend(points.windows(2).map(|w| (w[0], w[1])));
                    }
                    Shape::Circle { center, radius } if e.layer == data && center.x < W => {
                        let r = Vector::new(*radius, *radius);
                        markers.push(TextBox { min: center - r, max: center + r });
                    }
                    _ => {}
                }
            }
            let settings = ms.iter().filter(|m| m.error.is_some()).count();
            assert!(
                boxes.len() >= 20 && markers.len() == settings,
                "{run}: {} labels, {} markers",
                boxes.len(),
                markers.len()
            );
            for (i, (text, b)) in boxes.iter().enumerate() {
                for (other, o) in &boxes[..i] {
                    assert!(!b.overlaps(o), "{run}: `{text}` overlaps `{other}`");
                }
                for m in &markers {
                    assert!(!b.overlaps(m), "{run}: `{text}` covers a point");
                }
                // The box grown by the clearance, less rounding: clear of every line's edge.
                let g = Vector::new(CLEAR + 0.5 * LINE_WIDTH - 1e-9, CLEAR + 0.5 * LINE_WIDTH - 1e-9);
                let grown = TextBox { min: b.min - g, max: b.max + g };
                for &(p, q) in &lines {
                    assert!(!grown.crosses(p, q), "{run}: `{text}` within the clearance of the line {p:?}–{q:?}");
                }
                assert!(
                    b.min.x >= 0.0 && b.max.x <= W && b.min.y >= 0.0 && b.max.y <= H,
                    "{run}: `{text}` leaves the frame"
                );
            }
        }
    }

    #[test]
    fn decades_cover_the_data() {
        assert_eq!(decades([3.0, 2500.0].into_iter()), (0, 4));
        assert_eq!(decades([1e-13, 1e-13].into_iter()), (-13, -12));
        assert_eq!(decades(std::iter::empty()), (0, 1));
    }
}
