//! A component's tolerance band against the motion's abscissa (worst case, RSS and Monte
//! Carlo, the widest position marked), and the dimensions' contributions at one position
//! as a Pareto chart: the shared diagrams ([`crate::figure::shared::plot`]).

use crate::draw::Drawing;
use crate::figure::shared::plot::{self, Bars, Diagram, Mark, Marks, Series};

/// One component's bands over the positions, as deviations from nominal in the diagram's
/// unit.
#[derive(Debug, Clone, PartialEq)]
pub struct Bands {
    /// Title above the plot.
    pub title: String,
    /// Abscissa label with unit (`φ1 [°]`).
    pub x_label: String,
    /// Ordinate label with unit (`ΔM normal [mm]`).
    pub y_label: String,
    /// Abscissae.
    pub x: Vec<f64>,
    /// Linear mean shift (`None` at a dead point).
    pub shift: Vec<Option<f64>>,
    /// Worst-case half band.
    pub wc: Vec<Option<f64>>,
    /// RSS half band (3σ).
    pub rss: Vec<Option<f64>>,
    /// The Monte Carlo's 0.135 % and 99.865 % deviations.
    pub mc: Vec<Option<(f64, f64)>>,
    /// The widest position and its label.
    pub worst: Option<(usize, String)>,
}

/// The series `lo` then `hi` of one band, joined into one curve broken between them (one
/// colour and one legend entry for both edges).
fn edges(label: &str, x: &[f64], lo: impl Iterator<Item = f64>, hi: impl Iterator<Item = f64>) -> Series {
    let lo: Vec<f64> = lo.collect();
    let hi: Vec<f64> = hi.collect();
    let mut xs = x.to_vec();
    xs.push(f64::NAN);
    xs.extend_from_slice(x);
    let mut ys = lo;
    ys.push(f64::NAN);
    ys.extend(hi);
    Series { label: label.to_string(), x: xs, y: ys }
}

/// The band diagram: RSS ±3σ (blue), the Monte Carlo's 0.135 % and 99.865 % points (red)
/// and the worst case (green) about the linear mean shift, the widest position marked.
pub fn band_diagram(b: &Bands) -> Drawing {
    let nan = f64::NAN;
    let band = |v: &[Option<f64>], sign: f64| -> Vec<f64> {
        v.iter()
            .zip(&b.shift)
            .map(|(h, s)| match (h, s) {
                (Some(h), Some(s)) => s + sign * h,
                _ => nan,
            })
            .collect()
    };
    let series = vec![
        edges("RSS ±3σ", &b.x, band(&b.rss, -1.0).into_iter(), band(&b.rss, 1.0).into_iter()),
        edges(
            "Monte Carlo 0.135–99.865 %",
            &b.x,
            b.mc.iter().map(|m| m.map_or(nan, |m| m.0)),
            b.mc.iter().map(|m| m.map_or(nan, |m| m.1)),
        ),
        edges("worst case", &b.x, band(&b.wc, -1.0).into_iter(), band(&b.wc, 1.0).into_iter()),
    ];
    let d = Diagram { title: b.title.clone(), x_label: b.x_label.clone(), y_label: b.y_label.clone(), series };
    let points = b
        .worst
        .iter()
        .filter_map(|(k, label)| {
            let y = b.mc.get(*k).copied().flatten().map(|m| m.1).or_else(|| match (b.shift[*k], b.rss[*k]) {
                (Some(s), Some(r)) => Some(s + r),
                _ => None,
            })?;
            Some(Mark { x: b.x[*k], y, label: label.clone() })
        })
        .collect();
    plot::diagram_marked(&d, &Marks { levels: Vec::new(), points })
}

/// One dimension's share at a position.
#[derive(Debug, Clone, PartialEq)]
pub struct Contribution {
    /// The dimension (`l_ab`).
    pub dimension: String,
    /// Share of the variance, percent.
    pub pct_variance: f64,
    /// Share of the worst case, percent.
    pub pct_worst_case: f64,
}

/// The Pareto chart: the dimensions' shares of the variance as bars, largest first, with
/// their cumulative share as a line and each bar's worst-case share written above it.
pub fn pareto(title: &str, contributions: &[Contribution]) -> Drawing {
    let mut c: Vec<&Contribution> = contributions.iter().collect();
    c.sort_by(|a, b| b.pct_variance.total_cmp(&a.pct_variance).then(a.dimension.cmp(&b.dimension)));
    let mut sum = 0.0;
    let cumulative: Vec<f64> = c
        .iter()
        .map(|x| {
            sum += x.pct_variance;
            sum
        })
        .collect();
    plot::bars(&Bars {
        title: title.to_string(),
        y_label: "share of the variance [%]".to_string(),
        bars: c
            .iter()
            .map(|x| (x.dimension.clone(), x.pct_variance, format!("WC {:.0} %", x.pct_worst_case)))
            .collect(),
        line: Some(("cumulative".to_string(), cumulative)),
        y_max: 100.0,
    })
}
