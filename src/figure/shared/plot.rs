//! Diagrams: quantities against a parameter (phi1, t), and histograms, as a neutral
//! [`Drawing`] (axes, ticks, units, title, legend) that the SVG writer turns into a
//! picture. Shared by every mechanism kind.
//!
//! The plot is drawn in abstract "paper millimetres": a frame [`PLOT_WIDTH`] ×
//! [`PLOT_HEIGHT`] with its lower-left corner at the origin, text and tick labels around
//! it. Axis ranges are chosen by [`nice_ticks`]: ticks at 1, 2, 2.5 or 5 × 10ᵏ (for an x
//! axis labelled in degrees, multiples of 15°, 30°, 45°, 90° … instead), and the y range
//! widened to the ticks just outside the data, so every sample lies inside the frame.
//! A constant series gets a range around its value (never a division by zero); non-finite
//! samples break a curve into separate polylines and are never drawn.
//!
//! Layers: `PLOT_FRAME` (frame and ticks), `PLOT_GRID` (light grid), `PLOT_TEXT` (title,
//! labels, numbers, legend), `PLOT_DATA` (the curves, one colour per series; bars).

use crate::draw::parts::text_width;
use crate::draw::runs::{Run, RunKind, Runs};
use crate::draw::{Aci, DimStyle, Drawing, HAlign, LineType, Shape, VAlign};
use crate::figure::shared::labels::{Label, TextBox, first_free};
use crate::geom::Point;

/// One curve of a diagram.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend label (e.g. `omega2`).
    pub label: String,
    /// Abscissae, same length as `y`.
    pub x: Vec<f64>,
    /// Ordinates; non-finite values break the curve (never drawn).
    pub y: Vec<f64>,
}

/// A line diagram: one or more series against a common x axis.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagram {
    /// Title above the plot (e.g. `Angular velocity of the coupler`).
    pub title: String,
    /// x-axis label with unit (e.g. `φ1 [°]`).
    pub x_label: String,
    /// y-axis label with unit (e.g. `ω2 [rad/s]`).
    pub y_label: String,
    /// The curves.
    pub series: Vec<Series>,
}

/// A histogram: counts of samples in equal bins.
#[derive(Debug, Clone, PartialEq)]
pub struct Histogram {
    /// Title above the plot.
    pub title: String,
    /// x-axis label with unit.
    pub x_label: String,
    /// Left edge of the first bin.
    pub x0: f64,
    /// Bin width (> 0).
    pub bin_width: f64,
    /// Sample count per bin.
    pub counts: Vec<u64>,
    /// Vertical marker lines (e.g. spec limits, mean) with labels.
    pub markers: Vec<(f64, String)>,
}

/// Width of the plot frame, paper millimetres.
pub const PLOT_WIDTH: f64 = 160.0;
/// Height of the plot frame, paper millimetres.
pub const PLOT_HEIGHT: f64 = 100.0;
/// Cap height of axis labels and legend, paper mm (ISO 3098's 3.5 mm).
const TEXT_H: f64 = 3.5;
/// Cap height of tick numbers, paper mm (the 2.5 mm minimum).
const NUMBER_H: f64 = 2.5;
/// Cap height of the title, paper mm.
const TITLE_H: f64 = 5.0;
/// Tick mark length.
const TICK: f64 = 1.8;
/// Width of data curves (paper mm).
const CURVE_W: f64 = 0.45;
/// Most ticks wanted on an axis.
const MAX_TICKS: usize = 8;
/// Relative span under which a range counts as constant (all samples equal).
const FLAT_REL: f64 = 1e-12;
/// Colours of successive series.
const SERIES_COLORS: [Aci; 6] = [Aci::BLUE, Aci::RED, Aci::GREEN, Aci::MAGENTA, Aci::ORANGE, Aci::CYAN];

/// The ticks of one axis: the axis runs from `lo` to `hi`, with ticks every `step`
/// starting at `first`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ticks {
    /// Lower end of the axis.
    pub lo: f64,
    /// Upper end of the axis.
    pub hi: f64,
    /// Distance between ticks (> 0).
    pub step: f64,
    /// Value of the first tick (≥ `lo`).
    pub first: f64,
}

impl Ticks {
    /// Tick values from `first` to `hi`, each rounded to a multiple of `step`.
    pub fn values(&self) -> Vec<f64> {
        let n = ((self.hi - self.first) / self.step + 1e-9).floor().max(0.0) as usize;
        (0..=n).map(|i| snap(self.first + i as f64 * self.step, self.step)).collect()
    }

    /// Decimals needed to print the tick values exactly.
    pub fn decimals(&self) -> usize {
        decimals_for(self.step)
    }
}

/// Rounds `v` to the nearest multiple of `step` (removes float noise like 0.30000000000000004).
fn snap(v: f64, step: f64) -> f64 {
    let r = (v / step).round() * step;
    if r == 0.0 { 0.0 } else { r }
}

fn decimals_for(step: f64) -> usize {
    (0..10)
        .find(|&d| {
            let s = crate::geom::powi(10.0, d as i32) * step;
            (s - s.round()).abs() < 1e-6 * s.max(1.0)
        })
        .unwrap_or(10)
}

/// A "nice" tick step (1, 2, 2.5 or 5 × 10ᵏ; with `degrees`, also 15, 30, 45, 90, 180, 360)
/// so that `span / step` is at most `max_ticks`.
pub fn nice_step(span: f64, max_ticks: usize, degrees: bool) -> f64 {
    let max_ticks = max_ticks.max(2) as f64;
    let raw = span / max_ticks;
    if degrees && (10.0..=360.0).contains(&raw) {
        for s in [15.0, 30.0, 45.0, 60.0, 90.0, 180.0, 360.0] {
            if s >= raw {
                return s;
            }
        }
    }
    let mag = libm::pow(10f64, libm::log10(raw).floor());
    for m in [1.0, 2.0, 2.5, 5.0, 10.0] {
        if m * mag >= raw * (1.0 - 1e-12) {
            return m * mag;
        }
    }
    10.0 * mag
}

/// Ticks covering [`lo`, `hi`] (the finite data range; `lo ≤ hi`): the axis is widened to
/// the nearest ticks outside the data. A flat or tiny range is widened around its value.
/// Non-finite input gives the axis [0, 1].
pub fn nice_ticks(lo: f64, hi: f64, max_ticks: usize, degrees: bool) -> Ticks {
    let (mut lo, mut hi) = if lo.is_finite() && hi.is_finite() && lo <= hi { (lo, hi) } else { (0.0, 1.0) };
    let scale = lo.abs().max(hi.abs());
    if hi - lo <= FLAT_REL * scale || hi - lo < f64::MIN_POSITIVE * 1e3 {
        let pad = if scale > 0.0 { 0.1 * scale } else { 1.0 };
        lo -= pad;
        hi += pad;
    }
    let step = nice_step(hi - lo, max_ticks, degrees);
    // Tick indices just outside the data (a sample within 1e-9 steps of a tick sits on it,
    // also in the checks below: −1.2e-18 is 0).
    let mut ka = (lo / step + 1e-9).floor();
    let mut kb = (hi / step - 1e-9).ceil();
    if snap(ka * step, step) > lo + 1e-9 * step {
        ka -= 1.0;
    }
    if snap(kb * step, step) < hi - 1e-9 * step {
        kb += 1.0;
    }
    let (a, b) = (snap(ka * step, step), snap(kb * step, step));
    Ticks { lo: a, hi: b, step, first: a }
}

/// Ticks inside an exact range [`lo`, `hi`] (the axis is the data range itself): used for the
/// abscissa, where the data fill the axis (e.g. φ1 from 0° to 359°).
fn inner_ticks(lo: f64, hi: f64, max_ticks: usize, degrees: bool) -> Ticks {
    let t = nice_ticks(lo, hi, max_ticks, degrees);
    if !(lo.is_finite() && hi.is_finite()) || hi - lo <= FLAT_REL * lo.abs().max(hi.abs()) {
        return t;
    }
    let first = snap((lo / t.step - 1e-9).ceil() * t.step, t.step);
    Ticks { lo, hi, step: t.step, first }
}

/// Formats a tick value with `decimals` decimals ("-0" printed as "0", a negative one with
/// the minus sign −).
fn tick_label(v: f64, decimals: usize) -> String {
    let s = format!("{v:.decimals$}");
    if s.trim_start_matches('-').chars().all(|c| c == '0' || c == '.') {
        s.trim_start_matches('-').to_string()
    } else {
        super::sheet::typeset_minus(s)
    }
}

/// Drawing layers of a plot.
struct PlotLayers {
    frame: usize,
    grid: usize,
    text: usize,
    data: usize,
}

fn new_plot() -> (Drawing, PlotLayers) {
    let mut d = Drawing::new(DimStyle { text_height: TEXT_H, arrow_size: 2.5 });
    // The plot is drawn in paper millimetres: printed at 100 % it measures true.
    d.paper_mm_per_unit = Some(1.0);
    let frame = d.layer("PLOT_FRAME", Aci::BLACK, LineType::Continuous);
    let grid = d.layer("PLOT_GRID", Aci(254), LineType::Continuous);
    let text = d.layer("PLOT_TEXT", Aci::BLACK, LineType::Continuous);
    let data = d.layer("PLOT_DATA", Aci::BLUE, LineType::Continuous);
    (d, PlotLayers { frame, grid, text, data })
}

fn text(d: &mut Drawing, layer: usize, at: Point, h: f64, s: &str, (halign, valign): (HAlign, VAlign), rot: f64) {
    d.add(
        layer,
        Shape::Text {
            runs: crate::draw::Runs::flat(),
            at,
            height: h,
            value: s.to_string(),
            halign,
            valign,
            rotation: rot,
        },
    );
}

/// An axis label (`TEXT_H` high) drawn with its runs.
fn labelled(d: &mut Drawing, layer: usize, at: Point, label: Label, align: (HAlign, VAlign), rotation: f64) {
    let Label { text: value, runs } = label;
    let (halign, valign) = align;
    d.add(layer, Shape::Text { runs, at, height: TEXT_H, value, halign, valign, rotation });
}

/// The symbols whose axis label ([`axis_label`]) is a quantity with a subscript: angles,
/// angular rates, lengths, velocities, accelerations, forces and moments.
const QUANTITY_SYMBOLS: &str = "φψωεγsxyvaRMF";

/// An axis label `name [unit]` as a textbook writes it: a quantity's name (`φ1`, `vE`,
/// `|aE|`, `ω2`, `Me1`) with its index as a subscript ([`Label::quantity`]); a name marked
/// with `_` (`|R_O1|`, `γ_min`) with all that follows the `_` (the joint's name as the user
/// wrote it) as the subscript; anything else (`count`, `offset e`, `Δy = y(linkage) −
/// f(x)`, a chain's dimension) flat. The text stays as written.
fn axis_label(label: &str) -> Label {
    let name = label.rsplit_once(" [").map_or(label, |(n, _)| n);
    if name.contains(' ') {
        return Label::from(label);
    }
    let bare = name.trim_start_matches('|').trim_end_matches('|');
    if let Some(i) = name.find('_') {
        let end = name.trim_end_matches('|').len();
        if i + 1 < end {
            let runs = Runs(vec![
                Run { end: i, kind: RunKind::Base },
                Run { end: i + 1, kind: RunKind::Flat },
                Run { end, kind: RunKind::Sub },
            ]);
            return Label { text: label.to_string(), runs };
        }
        return Label::from(label);
    }
    let symbol = bare.chars().next();
    if bare.chars().count() < 2 || !symbol.is_some_and(|c| QUANTITY_SYMBOLS.contains(c)) {
        return Label::from(label);
    }
    Label { text: label.to_string(), runs: Label::quantity(name).runs }
}

/// Draws the frame, grid, ticks, numbers, labels and title for axes `xt` × `yt` (`xt`
/// `None`: the x axis runs over [0, `slots`] with no ticks, its categories drawn by the
/// caller); returns the map from data to paper coordinates.
fn axes(
    d: &mut Drawing,
    l: &PlotLayers,
    title: &str,
    x_label: &str,
    y_label: &str,
    xt: Result<&Ticks, f64>,
    yt: &Ticks,
) -> impl Fn(f64, f64) -> Point + use<> {
    let slots = Ticks { lo: 0.0, hi: xt.err().unwrap_or(1.0), step: 1.0, first: 0.0 };
    let (xt, x_ticks) = match xt {
        Ok(t) => (t, true),
        Err(_) => (&slots, false),
    };
    let map = data_to_paper(xt, yt);
    let (xd, yd) = (xt.decimals(), yt.decimals());
    for x in xt.values().into_iter().filter(|_| x_ticks) {
        let p = map(x, yt.lo);
        if p.x > 1e-9 && p.x < PLOT_WIDTH - 1e-9 {
            d.add(l.grid, Shape::Line { from: p, to: Point::new(p.x, PLOT_HEIGHT) });
        }
        d.add(l.frame, Shape::Line { from: p, to: Point::new(p.x, -TICK) });
        text(d, l.text, Point::new(p.x, -TICK - 1.0), NUMBER_H, &tick_label(x, xd), (HAlign::Center, VAlign::Top), 0.0);
    }
    let mut widest = 0.0f64;
    for y in yt.values() {
        let p = map(xt.lo, y);
        if p.y > 1e-9 && p.y < PLOT_HEIGHT - 1e-9 {
            d.add(l.grid, Shape::Line { from: p, to: Point::new(PLOT_WIDTH, p.y) });
        }
        d.add(l.frame, Shape::Line { from: p, to: Point::new(-TICK, p.y) });
        let s = tick_label(y, yd);
        widest = widest.max(text_width(&s, NUMBER_H));
        text(d, l.text, Point::new(-TICK - 1.0, p.y), NUMBER_H, &s, (HAlign::Right, VAlign::Middle), 0.0);
    }
    // A zero line when zero is inside the y range.
    if yt.lo < 0.0 && yt.hi > 0.0 {
        let p = map(xt.lo, 0.0);
        d.add(l.frame, Shape::Line { from: p, to: Point::new(PLOT_WIDTH, p.y) });
    }
    d.add(
        l.frame,
        Shape::Polyline {
            points: vec![
                Point::new(0.0, 0.0),
                Point::new(PLOT_WIDTH, 0.0),
                Point::new(PLOT_WIDTH, PLOT_HEIGHT),
                Point::new(0.0, PLOT_HEIGHT),
            ],
            closed: true,
            width: 0.3,
        },
    );
    let label_y = -TICK - 1.6 * NUMBER_H - TEXT_H - 1.0;
    let at = Point::new(PLOT_WIDTH / 2.0, label_y);
    labelled(d, l.text, at, axis_label(x_label), (HAlign::Center, VAlign::Top), 0.0);
    let label_x = -TICK - 1.0 - widest - 2.0 * TEXT_H;
    let at = Point::new(label_x, PLOT_HEIGHT / 2.0);
    labelled(d, l.text, at, axis_label(y_label), (HAlign::Center, VAlign::Baseline), std::f64::consts::FRAC_PI_2);
    text(
        d,
        l.text,
        Point::new(PLOT_WIDTH / 2.0, PLOT_HEIGHT + 4.0),
        TITLE_H,
        title,
        (HAlign::Center, VAlign::Baseline),
        0.0,
    );
    map
}

/// Finite range of `values`, or `None` when there is no finite value.
fn finite_range(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    values.filter(|v| v.is_finite()).fold(None, |acc, v| match acc {
        None => Some((v, v)),
        Some((a, b)) => Some((a.min(v), b.max(v))),
    })
}

/// Whether an axis label names degrees (then ticks fall on 15°, 30°, 45°, 90° …).
fn is_degrees(label: &str) -> bool {
    label.contains('°') || label.contains("deg")
}

/// A horizontal reference line across a diagram (a design limit), dashed, labelled at its
/// right end.
#[derive(Debug, Clone, PartialEq)]
pub struct Level {
    /// Its ordinate (data units); the y axis is widened to show it.
    pub y: f64,
    /// Its label (`limit 40°`); a `_` marks a subscript (`γ_min`: min drawn as one).
    pub label: String,
}

/// A marked sample of a diagram (an extreme): a small circle and its label.
#[derive(Debug, Clone, PartialEq)]
pub struct Mark {
    /// Abscissa (data units).
    pub x: f64,
    /// Ordinate (data units).
    pub y: f64,
    /// Its label (`γ_min = 23.07° at φ1 = 0°`); a `_` marks a subscript (`γ_min`: min
    /// drawn as one, the `_` kept where the text is read flat).
    pub label: String,
}

/// What a diagram marks besides its curves.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Marks {
    /// Reference lines.
    pub levels: Vec<Level>,
    /// Marked samples.
    pub points: Vec<Mark>,
}

/// Draws a line diagram: frame, grid, ticks with numbers, axis labels, title, one
/// polyline per finite run of each series, and a legend when there is more than one
/// series. Samples whose x or y is not finite are skipped and break the curve.
pub fn diagram(d: &Diagram) -> Drawing {
    diagram_marked(d, &Marks::default())
}

/// [`diagram`] with reference lines (dashed, on `PLOT_DATA` in dark grey, the y axis
/// widened to show them) and marked samples (two red circles and a label level with the
/// mark, an eighth of the frame towards its middle, with a red leader). Non-finite marks
/// are left out.
pub fn diagram_marked(d: &Diagram, marks: &Marks) -> Drawing {
    let (mut dr, l) = new_plot();
    let levels: Vec<&Level> = marks.levels.iter().filter(|v| v.y.is_finite()).collect();
    let (xt, yt) = diagram_ticks(d, &levels);
    let map = axes(&mut dr, &l, &d.title, &d.x_label, &d.y_label, Ok(&xt), &yt);
    for (i, s) in d.series.iter().enumerate() {
        let color = SERIES_COLORS[i % SERIES_COLORS.len()];
        let mut run: Vec<Point> = Vec::new();
        let flush = |run: &mut Vec<Point>, dr: &mut Drawing| {
            match run.len() {
                0 => {}
                1 => dr.add_colored(l.data, color, Shape::Circle { center: run[0], radius: CURVE_W }),
                _ => dr.add_colored(
                    l.data,
                    color,
                    Shape::Polyline { points: std::mem::take(run), closed: false, width: CURVE_W },
                ),
            }
            run.clear();
        };
        for (x, y) in s.x.iter().zip(&s.y) {
            if x.is_finite() && y.is_finite() {
                run.push(map(*x, *y));
            } else {
                flush(&mut run, &mut dr);
            }
        }
        flush(&mut run, &mut dr);
    }
    draw_marks(&mut dr, &l, &levels, marks, &map);
    if d.series.len() > 1 {
        for (i, s) in d.series.iter().enumerate() {
            let color = SERIES_COLORS[i % SERIES_COLORS.len()];
            let y = PLOT_HEIGHT - 5.0 - 5.0 * i as f64;
            let x = PLOT_WIDTH + 4.0;
            dr.add_colored(
                l.data,
                color,
                Shape::Polyline {
                    points: vec![Point::new(x, y), Point::new(x + 8.0, y)],
                    closed: false,
                    width: CURVE_W,
                },
            );
            text(&mut dr, l.text, Point::new(x + 10.0, y), TEXT_H, &s.label, (HAlign::Left, VAlign::Middle), 0.0);
        }
    }
    dr
}

/// The grid's lines broken under the text `t` (ISO 129-1: no line across a text).
fn break_grid(dr: &mut Drawing, l: &PlotLayers, t: &Shape) {
    if let Some(c) = crate::draw::text_corners(t) {
        let min = c.iter().fold(c[0], |m, q| Point::new(m.x.min(q.x), m.y.min(q.y)));
        let max = c.iter().fold(c[0], |m, q| Point::new(m.x.max(q.x), m.y.max(q.y)));
        crate::figure::shared::labels::break_around(dr, l.grid, &[TextBox { min, max }], 0.5);
    }
}

/// The plot's frame, for its labels to stay inside.
fn frame_box() -> TextBox {
    TextBox { min: Point::new(0.0, 0.0), max: Point::new(PLOT_WIDTH, PLOT_HEIGHT) }
}

/// The axes' ticks of a diagram: the abscissa over the data, the ordinate over the data and
/// the reference `levels`.
fn diagram_ticks(d: &Diagram, levels: &[&Level]) -> (Ticks, Ticks) {
    let finite_pairs = |s: &Series| -> Vec<(f64, f64)> {
        s.x.iter().zip(&s.y).filter(|(x, y)| x.is_finite() && y.is_finite()).map(|(x, y)| (*x, *y)).collect()
    };
    let all: Vec<(f64, f64)> = d.series.iter().flat_map(finite_pairs).collect();
    let (x0, x1) = finite_range(all.iter().map(|p| p.0)).unwrap_or((0.0, 1.0));
    let (y0, y1) = finite_range(all.iter().map(|p| p.1)).unwrap_or((0.0, 1.0));
    let (y0, y1) = levels.iter().fold((y0, y1), |(a, b), v| (a.min(v.y), b.max(v.y)));
    (inner_ticks(x0, x1, MAX_TICKS + 4, is_degrees(&d.x_label)), nice_ticks(y0, y1, MAX_TICKS, false))
}

/// Where [`diagram_marked`] draws each sample of the diagram's first series, on the plot's
/// paper (mm, y up): one entry per sample with a finite abscissa (the NaN that break a curve
/// between runs are left out), `None` where the value is not finite. The live page moves a
/// marker along it with the mechanism's position.
pub fn track(d: &Diagram, marks: &Marks) -> Vec<Option<Point>> {
    let levels: Vec<&Level> = marks.levels.iter().filter(|v| v.y.is_finite()).collect();
    let (xt, yt) = diagram_ticks(d, &levels);
    let map = data_to_paper(&xt, &yt);
    d.series
        .first()
        .map(|s| {
            s.x.iter()
                .zip(&s.y)
                .filter(|(x, _)| x.is_finite())
                .map(|(x, y)| y.is_finite().then(|| map(*x, *y)))
                .collect()
        })
        .unwrap_or_default()
}

/// Where [`diagram_marked`] draws the data point (`x`, `y`) of diagram `d` (with `marks`), on
/// the plot's paper (mm, y up): the map of [`track`] for any point, not only a sample's (a
/// report marks a position solved between the samples).
pub fn place(d: &Diagram, marks: &Marks, x: f64, y: f64) -> Point {
    let levels: Vec<&Level> = marks.levels.iter().filter(|v| v.y.is_finite()).collect();
    let (xt, yt) = diagram_ticks(d, &levels);
    data_to_paper(&xt, &yt)(x, y)
}

/// The map from data to the plot's paper coordinates for axes `xt` × `yt`.
fn data_to_paper(xt: &Ticks, yt: &Ticks) -> impl Fn(f64, f64) -> Point + use<> {
    let (xlo, xspan) = (xt.lo, (xt.hi - xt.lo).max(f64::MIN_POSITIVE));
    let (ylo, yspan) = (yt.lo, (yt.hi - yt.lo).max(f64::MIN_POSITIVE));
    move |x: f64, y: f64| Point::new((x - xlo) / xspan * PLOT_WIDTH, (y - ylo) / yspan * PLOT_HEIGHT)
}

/// The reference lines and marked samples of [`diagram_marked`].
fn draw_marks(dr: &mut Drawing, l: &PlotLayers, levels: &[&Level], marks: &Marks, map: &impl Fn(f64, f64) -> Point) {
    for v in levels {
        let y = map(0.0, v.y).y;
        dr.push(crate::draw::Entity {
            layer: l.data,
            color: Some(Aci::DARK_GREY),
            linetype: Some(LineType::Dashed),
            shape: Shape::Line { from: Point::new(0.0, y), to: Point::new(PLOT_WIDTH, y) },
        });
        // Above the line at its right end, else further left, else under it: clear of the
        // curves and the grid's numbers.
        let candidates = (0..8)
            .flat_map(|k| {
                let x = PLOT_WIDTH - 1.0 - k as f64 * PLOT_WIDTH / 8.0;
                [(y + 1.0, VAlign::Baseline), (y - 1.0, VAlign::Top)].map(|(y, valign)| Shape::Text {
                    runs: Runs::underscored(&v.label),
                    at: Point::new(x, y),
                    height: TEXT_H,
                    value: v.label.clone(),
                    halign: HAlign::Right,
                    valign,
                    rotation: 0.0,
                })
            })
            .collect();
        if let Some(t) = first_free(dr, candidates, Some(frame_box()), &[l.grid]) {
            break_grid(dr, l, &t);
            dr.add(l.text, t);
        }
    }
    let shown: Vec<&Mark> = marks.points.iter().filter(|m| m.x.is_finite() && m.y.is_finite()).collect();
    // Every mark's circles first, for no label or leader to cross another mark.
    let rings: Vec<TextBox> = shown
        .iter()
        .map(|m| {
            let p = map(m.x, m.y);
            dr.add_colored(l.data, Aci::RED, Shape::Circle { center: p, radius: 2.0 * CURVE_W });
            dr.add_colored(l.data, Aci::RED, Shape::Circle { center: p, radius: 4.0 * CURVE_W });
            let r = 4.0 * CURVE_W;
            TextBox { min: Point::new(p.x - r, p.y - r), max: Point::new(p.x + r, p.y + r) }
        })
        .collect();
    for (i, m) in shown.iter().enumerate() {
        let p = map(m.x, m.y);
        // At the mark's height, an eighth of the frame aside, with a leader: the curve leaves
        // an extreme upwards (a minimum) or downwards (a maximum), so the space level with
        // it is free once clear of the mark.
        let right = p.x < PLOT_WIDTH / 2.0;
        // Level with the mark an eighth of the frame aside, else higher or lower (the grid's
        // lines and the curve kept clear), with a red leader from the mark; on the other side
        // last (a curve too steep beside the mark for the label, a frame too narrow for it).
        let mut candidates: Vec<(Point, Shape)> = Vec::new();
        for side in if right { [1.0, -1.0] } else { [-1.0, 1.0] } {
            let halign = if side > 0.0 { HAlign::Left } else { HAlign::Right };
            for k in [0.0, 1.0, -1.0, 2.0, -2.0, 3.0, -3.0, 4.0, -4.0] {
                for far in [1.0, 1.5, 2.0] {
                    let at = Point::new(p.x + side * far * PLOT_WIDTH / 8.0, p.y + k * 1.6 * TEXT_H);
                    let t = Shape::Text {
                        runs: Runs::underscored(&m.label),
                        at,
                        height: TEXT_H,
                        value: m.label.clone(),
                        halign,
                        valign: VAlign::Middle,
                        rotation: 0.0,
                    };
                    candidates.push((at, t));
                }
            }
        }
        // A leader crosses no text already written (an earlier mark's label) and no other
        // mark.
        let written: Vec<TextBox> = dr
            .entities
            .iter()
            .filter_map(|e| crate::draw::text_corners(&e.shape))
            .map(|c| {
                let min = c.iter().fold(c[0], |m, q| Point::new(m.x.min(q.x), m.y.min(q.y)));
                let max = c.iter().fold(c[0], |m, q| Point::new(m.x.max(q.x), m.y.max(q.y)));
                TextBox { min, max }
            })
            .chain(rings.iter().enumerate().filter(|(j, _)| *j != i).map(|(_, r)| *r))
            .collect();
        let leader = |at: Point| {
            let side = if at.x > p.x { 1.0 } else { -1.0 };
            (p + (at - p).normalize() * (4.0 * CURVE_W), Point::new(at.x - side, at.y))
        };
        let clear: Vec<(Point, Shape)> = candidates
            .iter()
            .filter(|(at, _)| {
                let (a, b) = leader(*at);
                !written.iter().any(|w| w.crosses(a, b))
            })
            .cloned()
            .collect();
        let candidates = if clear.is_empty() { candidates } else { clear };
        let chosen = first_free(dr, candidates.iter().map(|c| c.1.clone()).collect(), Some(frame_box()), &[l.grid]);
        if let Some(t) = chosen {
            break_grid(dr, l, &t);
            let at = candidates.iter().find(|c| c.1 == t).map_or(p, |c| c.0);
            let (from, to) = leader(at);
            dr.add_colored(l.data, Aci::RED, Shape::Line { from, to });
            dr.add(l.text, t);
        }
    }
}

/// Draws a histogram: one bar per bin (outlined, light fill), ticks, title, and dashed
/// vertical marker lines with their labels.
pub fn histogram(h: &Histogram) -> Drawing {
    let (mut dr, l) = new_plot();
    let bw = if h.bin_width.is_finite() && h.bin_width > 0.0 { h.bin_width } else { 1.0 };
    let x_end = h.x0 + bw * h.counts.len() as f64;
    let markers = h.markers.iter().map(|m| m.0).filter(|v| v.is_finite());
    let (x0, x1) = finite_range([h.x0, x_end].into_iter().chain(markers)).unwrap_or((0.0, 1.0));
    let xt = nice_ticks(x0, x1, MAX_TICKS + 2, is_degrees(&h.x_label));
    let max_count = h.counts.iter().copied().max().unwrap_or(0) as f64;
    let yt = nice_ticks(0.0, max_count.max(1.0), MAX_TICKS, false);
    let yt = Ticks { step: yt.step.max(1.0), ..yt };
    let map = axes(&mut dr, &l, &h.title, &h.x_label, "count", Ok(&xt), &yt);
    let fill = dr.layer("PLOT_BARS", Aci(151), LineType::Continuous);
    for (i, &c) in h.counts.iter().enumerate() {
        if c == 0 {
            continue;
        }
        let a = h.x0 + bw * i as f64;
        let p0 = map(a, 0.0);
        let p1 = map(a + bw, c as f64);
        let corners =
            vec![Point::new(p0.x, p0.y), Point::new(p1.x, p0.y), Point::new(p1.x, p1.y), Point::new(p0.x, p1.y)];
        dr.add(fill, Shape::Filled { points: corners.clone() });
        dr.add_colored(l.data, Aci::BLUE, Shape::Polyline { points: corners, closed: true, width: 0.0 });
    }
    for (i, (x, label)) in h.markers.iter().enumerate() {
        if !x.is_finite() {
            continue;
        }
        let p = map(*x, yt.lo);
        dr.push(crate::draw::Entity {
            layer: l.data,
            color: Some(Aci::RED),
            linetype: Some(LineType::Dashed),
            shape: Shape::Line { from: p, to: Point::new(p.x, PLOT_HEIGHT) },
        });
        // Beside its line near the top, else lower, on either side: clear of the bars.
        let preferred = PLOT_HEIGHT - 3.0 - 4.5 * (i % 4) as f64;
        let candidates = (0..12)
            .flat_map(|k| {
                let y = preferred - 4.5 * k as f64;
                [(p.x + 1.0, HAlign::Left), (p.x - 1.0, HAlign::Right)].map(|(x, halign)| Shape::Text {
                    runs: crate::draw::Runs::flat(),
                    at: Point::new(x, y),
                    height: TEXT_H,
                    value: label.clone(),
                    halign,
                    valign: VAlign::Top,
                    rotation: 0.0,
                })
            })
            .collect();
        if let Some(t) = first_free(&dr, candidates, Some(frame_box()), &[l.grid]) {
            break_grid(&mut dr, &l, &t);
            dr.add(l.text, t);
        }
    }
    dr
}

/// A bar chart of named values (a Pareto chart: values sorted by the caller), with an
/// optional line over the bars on the same axis (the cumulative share).
#[derive(Debug, Clone, PartialEq)]
pub struct Bars {
    /// Title above the plot.
    pub title: String,
    /// y-axis label with unit.
    pub y_label: String,
    /// Each bar: its category label, its value (≥ 0) and a note written under the label.
    pub bars: Vec<(String, f64, String)>,
    /// A line through one value per bar, at the bars' middles, with its legend.
    pub line: Option<(String, Vec<f64>)>,
    /// The y axis reaches at least this (100 for percentages).
    pub y_max: f64,
}

/// Draws a bar chart: one filled bar per category (its label and note under the axis,
/// turned upright when the labels do not fit side by side), the optional line
/// with round markers, ticks, title and axis labels.
pub fn bars(b: &Bars) -> Drawing {
    let (mut dr, l) = new_plot();
    let n = b.bars.len().max(1);
    let top =
        b.bars.iter().map(|x| x.1).chain(b.line.iter().flat_map(|l| l.1.iter().copied())).filter(|v| v.is_finite());
    let y1 = top.fold(b.y_max, f64::max);
    let yt = nice_ticks(0.0, y1, MAX_TICKS, false);
    // The x axis is the bar slots: no numbers, the categories instead.
    let map = axes(&mut dr, &l, &b.title, "", &b.y_label, Err(n as f64), &yt);
    let slot = PLOT_WIDTH / n as f64;
    let fit = |s: &str| text_width(s, NUMBER_H) < 0.9 * slot;
    // A category that does not fit on one line breaks after its last '.' (a field path,
    // `rocker.` over `B[0]`) when both parts fit; else every category is turned upright.
    let lines = |s: &str| -> Vec<String> {
        match s.rfind('.') {
            Some(i) if !fit(s) && i + 1 < s.len() => vec![s[..=i].to_string(), s[i + 1..].to_string()],
            _ => vec![s.to_string()],
        }
    };
    let fits = b.bars.iter().all(|x| lines(&x.0).iter().all(|l| fit(l)) && fit(&x.2));
    let fill = dr.layer("PLOT_BARS", Aci(151), LineType::Continuous);
    for (i, (label, v, note)) in b.bars.iter().enumerate() {
        let (x0, x1) = (i as f64 + 0.2, i as f64 + 0.8);
        let v = if v.is_finite() { v.max(0.0) } else { 0.0 };
        let (p0, p1) = (map(x0, 0.0), map(x1, v));
        let corners = vec![p0, Point::new(p1.x, p0.y), p1, Point::new(p0.x, p1.y)];
        if v > 0.0 {
            dr.add(fill, Shape::Filled { points: corners.clone() });
        }
        dr.add_colored(l.data, Aci::BLUE, Shape::Polyline { points: corners, closed: true, width: 0.0 });
        let mid = 0.5 * (p0.x + p1.x);
        let below = Point::new(mid, -TICK - 1.0);
        // The category under its bar, its note under that (clear of the bars and the line).
        if fits {
            let mut at = below;
            for line in lines(label) {
                text(&mut dr, l.text, at, NUMBER_H, &line, (HAlign::Center, VAlign::Top), 0.0);
                at.y -= 1.6 * NUMBER_H;
            }
            text(&mut dr, l.text, at, NUMBER_H, note, (HAlign::Center, VAlign::Top), 0.0);
        } else {
            let both = if note.is_empty() { label.clone() } else { format!("{label} ({note})") };
            text(&mut dr, l.text, below, NUMBER_H, &both, (HAlign::Right, VAlign::Middle), std::f64::consts::FRAC_PI_2);
        }
    }
    if let Some((legend, ys)) = &b.line {
        let pts: Vec<Point> =
            ys.iter().enumerate().filter(|(_, y)| y.is_finite()).map(|(i, y)| map(i as f64 + 0.5, *y)).collect();
        for p in &pts {
            dr.add_colored(l.data, Aci::RED, Shape::Circle { center: *p, radius: 2.0 * CURVE_W });
        }
        if pts.len() >= 2 {
            dr.add_colored(l.data, Aci::RED, Shape::Polyline { points: pts, closed: false, width: CURVE_W });
        }
        let (x, y) = (PLOT_WIDTH + 4.0, PLOT_HEIGHT - 5.0);
        dr.add_colored(
            l.data,
            Aci::RED,
            Shape::Polyline { points: vec![Point::new(x, y), Point::new(x + 8.0, y)], closed: false, width: CURVE_W },
        );
        text(&mut dr, l.text, Point::new(x + 10.0, y), TEXT_H, legend, (HAlign::Left, VAlign::Middle), 0.0);
    }
    dr
}

#[cfg(test)]
#[allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the code under test calls"
)]
mod tests {
    use super::*;

    #[test]
    fn axis_labels_subscript_a_quantitys_index_and_leave_words_flat() {
        let subs = |label: &str| -> Vec<String> {
            let l = axis_label(label);
            assert_eq!(l.text, label, "the text stays as written");
            l.runs.split(&l.text).filter(|(_, k)| *k == RunKind::Sub).map(|(p, _)| p.to_string()).collect()
        };
        assert_eq!(subs("φ1 [°]"), ["1"]);
        assert_eq!(subs("|aE| [m/s²]"), ["E"]);
        assert_eq!(subs("Me1 [N·m]"), ["e1"]);
        assert_eq!(subs("|R_ram-guide| [N]"), ["ram-guide"]);
        assert_eq!(subs("γ_min [°]"), ["min"]);
        for flat in ["count", "x", "γ [°]", "offset e [mm]", "Δy = y(linkage) − f(x)", "gap [mm]", "Z [mm]"] {
            assert!(subs(flat).is_empty(), "{flat}");
        }
    }

    #[test]
    fn a_marked_diagram_shows_its_level_and_its_mark_inside_the_frame() {
        let d = Diagram {
            title: "γ".into(),
            x_label: "φ1 [°]".into(),
            y_label: "γ [°]".into(),
            series: vec![Series { label: "γ".into(), x: vec![0.0, 180.0, 359.0], y: vec![50.0, 70.0, 52.0] }],
        };
        let marks = Marks {
            levels: vec![Level { y: 40.0, label: "limit 40°".into() }],
            points: vec![Mark { x: 0.0, y: 50.0, label: "min".into() }],
        };
        let dr = diagram_marked(&d, &marks);
        // The dashed level lies inside the frame although every sample is above it.
        let level = dr
            .entities
            .iter()
            .find_map(|e| match e.shape {
                Shape::Line { from, to } if e.linetype == Some(LineType::Dashed) => Some((from, to)),
                _ => None,
            })
            .expect("a dashed level line");
        assert!(level.0.y >= 0.0 && level.0.y <= PLOT_HEIGHT && level.0.y == level.1.y);
        assert_eq!((level.0.x, level.1.x), (0.0, PLOT_WIDTH));
        let texts: Vec<&str> = dr
            .entities
            .iter()
            .filter_map(|e| match &e.shape {
                Shape::Text { value, .. } => Some(value.as_str()),
                _ => None,
            })
            .collect();
        assert!(texts.contains(&"limit 40°") && texts.contains(&"min"));
        // Without marks the diagram is the plain one.
        assert_eq!(diagram_marked(&d, &Marks::default()), diagram(&d));
    }

    fn is_nice(step: f64) -> bool {
        let mag = 10f64.powf(step.log10().floor());
        let m = step / mag;
        [1.0, 2.0, 2.5, 5.0, 10.0].iter().any(|n| (m - n).abs() < 1e-9)
    }

    #[test]
    fn data_a_rounding_off_a_tick_sit_on_it() {
        // x_B = −1.2e-18 m at the four-bar's extreme, 0.15999999999999998 for 0.16: the axis
        // ends on the tick, not one step further.
        let t = nice_ticks(-1.2e-18, 0.1, 8, false);
        assert_eq!((t.lo, t.hi), (0.0, 0.1));
        let t = nice_ticks(0.02, 0.15999999999999998 + 2e-17, 8, false);
        assert!((t.hi - 0.16).abs() < 1e-15, "{t:?}");
        // A sample a real fraction of a step past a tick still widens the axis.
        assert!(nice_ticks(-1e-4, 0.1, 8, false).lo < 0.0);
    }

    #[test]
    fn ticks_are_nice_numbers_covering_the_data() {
        for &(lo, hi) in &[(0.0, 1.0), (-3.7, 12.2), (0.013, 0.0171), (-1520.0, 880.0), (7.0, 7.000001), (-0.5, -0.2)] {
            let t = nice_ticks(lo, hi, 8, false);
            assert!(is_nice(t.step), "step {} for [{lo}, {hi}]", t.step);
            // Covering, a sample within 1e-9 steps of a tick counting as on it.
            let eps = 1e-9 * t.step;
            assert!(t.lo <= lo + eps && t.hi >= hi - eps, "{t:?} does not cover [{lo}, {hi}]");
            let v = t.values();
            assert!(v.len() >= 2 && v.len() <= 9 + 1, "{} ticks for [{lo}, {hi}]: {v:?}", v.len());
            // The axis ends on ticks and no more than one step beyond the data.
            assert!((t.lo - v[0]).abs() < 1e-9 * t.step && (t.hi - v[v.len() - 1]).abs() < 1e-9 * t.step);
            assert!(lo - t.lo < t.step && t.hi - hi < t.step);
            for w in v.windows(2) {
                // Float spacing of the values themselves bounds how equal the gaps can be.
                let noise = 1e-9 * t.step + 8.0 * f64::EPSILON * w[1].abs().max(w[0].abs());
                assert!(((w[1] - w[0]) - t.step).abs() < noise);
            }
            // Each tick is an integer multiple of the step.
            for x in &v {
                let r = x / t.step;
                assert!((r - r.round()).abs() < 1e-9 + 1e-12 * r.abs(), "tick {x} vs step {}", t.step);
            }
        }
        // span 15.9 over at most 8 intervals: raw step 1.99 → 2; the data lie in [-4, 14].
        let t = nice_ticks(-3.7, 12.2, 8, false);
        assert_eq!((t.step, t.lo, t.hi), (2.0, -4.0, 14.0));
        assert_eq!(nice_ticks(-3.7, 12.2, 4, false).values(), vec![-5.0, 0.0, 5.0, 10.0, 15.0]);
    }

    #[test]
    fn degree_axes_use_degree_steps() {
        let t = inner_ticks(0.0, 359.0, 12, true);
        assert_eq!(t.step, 30.0);
        assert_eq!((t.lo, t.hi), (0.0, 359.0));
        assert_eq!(t.values().last().copied(), Some(330.0));
    }

    #[test]
    fn constant_series_does_not_divide_by_zero() {
        for c in [0.0, 5.0, -2.5e-7] {
            let t = nice_ticks(c, c, 8, false);
            assert!(t.lo < c && t.hi > c && t.step > 0.0 && t.step.is_finite(), "{t:?}");
        }
        let d = diagram(&Diagram {
            title: "flat".into(),
            x_label: "φ1 [°]".into(),
            y_label: "y".into(),
            series: vec![Series { label: "c".into(), x: vec![0.0, 1.0, 2.0], y: vec![3.0; 3] }],
        });
        for e in &d.entities {
            if let Shape::Polyline { points, .. } = &e.shape {
                assert!(points.iter().all(|p| p.x.is_finite() && p.y.is_finite()));
            }
        }
        // A series with a single x value, too.
        let d = diagram(&Diagram {
            title: "point".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            series: vec![Series { label: "p".into(), x: vec![1.0], y: vec![1.0] }],
        });
        assert!(d.bounds().is_some_and(|b| b.min.x.is_finite() && b.max.y.is_finite()));
    }

    #[test]
    fn non_finite_values_break_the_curve() {
        let x: Vec<f64> = (0..10).map(f64::from).collect();
        let mut y: Vec<f64> = x.iter().map(|v| v * v).collect();
        y[4] = f64::NAN;
        y[7] = f64::INFINITY;
        let d = diagram(&Diagram {
            title: "t".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            series: vec![Series { label: "s".into(), x, y }],
        });
        let data = d.layers.iter().position(|l| l.name == "PLOT_DATA").unwrap();
        let runs: Vec<usize> = d
            .entities
            .iter()
            .filter(|e| e.layer == data)
            .filter_map(|e| match &e.shape {
                Shape::Polyline { points, .. } => Some(points.len()),
                _ => None,
            })
            .collect();
        assert_eq!(runs, vec![4, 2, 2]);
        // The infinite sample did not stretch the y axis: all points stay in the frame.
        for e in d.entities.iter().filter(|e| e.layer == data) {
            if let Shape::Polyline { points, .. } = &e.shape {
                assert!(points.iter().all(|p| p.y >= -1e-9 && p.y <= PLOT_HEIGHT + 1e-9));
            }
        }
    }

    #[test]
    fn tick_labels_have_just_enough_decimals() {
        let t = nice_ticks(0.0, 0.75, 8, false);
        assert_eq!(t.step, 0.1);
        assert_eq!(tick_label(0.30000000000000004, t.decimals()), "0.3");
        assert_eq!(tick_label(-0.0, 2), "0.00");
        assert_eq!(tick_label(-150.0, 0), "−150");
        assert_eq!(decimals_for(2.5), 1);
        assert_eq!(decimals_for(50.0), 0);
    }

    #[test]
    fn histogram_bars_have_the_counts_heights() {
        let h = Histogram {
            title: "h".into(),
            x_label: "Z [mm]".into(),
            x0: 10.0,
            bin_width: 0.5,
            counts: vec![1, 4, 2],
            markers: vec![(10.75, "mean".into())],
        };
        let d = histogram(&h);
        let bars = d.layers.iter().position(|l| l.name == "PLOT_BARS").unwrap();
        let heights: Vec<f64> = d
            .entities
            .iter()
            .filter(|e| e.layer == bars)
            .filter_map(|e| match &e.shape {
                Shape::Filled { points } => Some(points[2].y - points[0].y),
                _ => None,
            })
            .collect();
        assert_eq!(heights.len(), 3);
        assert!((heights[1] / heights[0] - 4.0).abs() < 1e-9 && (heights[2] / heights[0] - 2.0).abs() < 1e-9);
    }
}
