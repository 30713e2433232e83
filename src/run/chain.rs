//! The chain pipeline: analyse the graph, write the dimensional functions, stack up the
//! tolerances, draw the chain and the histograms, write the report, JSON and CSV.

use serde::Serialize;

use super::products::{self, Picture, Products};
use super::solve_err;
use crate::Error;
use crate::figure::chain::{self as fig, DependentMark};
use crate::report::Csv;
use crate::scene::chain::{ChainScene, Form};
use crate::solve::chain::graph::fmt_value;
use crate::solve::chain::{Analysis, Function, MonteCarlo, Stack, analyse, monte_carlo, stack};

/// Everything computed for one dependent dimension.
#[derive(Debug, Clone)]
pub struct DependentResult {
    /// Index in the scene's `dependent` list.
    pub index: usize,
    /// The dimensional function.
    pub function: Function,
    /// Analytic stack-up.
    pub stack: Stack,
    /// Monte Carlo, unless `samples = 0`.
    pub monte_carlo: Option<MonteCarlo>,
}

/// Analysis plus every dependent dimension's function and stack-up.
pub fn solve(scene: &ChainScene) -> Result<(Analysis, Vec<DependentResult>), crate::solve::chain::ChainError> {
    let analysis = analyse(&scene.chain);
    let s = &scene.stackup;
    let mut results = Vec::with_capacity(scene.chain.dependent.len());
    for (index, z) in scene.chain.dependent.iter().enumerate() {
        let function = analysis.function(&scene.chain, z)?;
        let st = stack(&function, &scene.chain.dimensions, s.mrss_factor, s.distribution);
        let mc = monte_carlo(&function, &scene.chain.dimensions, s.distribution, s.samples, s.seed, s.bins, z.spec);
        results.push(DependentResult { index, function, stack: st, monte_carlo: mc });
    }
    Ok((analysis, results))
}

pub(super) fn products(scene: &ChainScene, file: &str) -> Result<Products, Error> {
    let (analysis, results) = solve(scene).map_err(|e| solve_err(file)(e.into()))?;
    let units = scene.units.length();

    // Check: the seed's coincidence test and the graph's redundancy; the features.
    let labels = fig::feature_labels(&analysis, scene.chain.form);
    let (mut report, warnings) = dimensioning_report(scene, &analysis, &labels);
    stack_report(scene, &results, &mut report);
    let summary = summary(scene, &analysis, &results)?;

    let marks = dependent_marks(scene, &analysis, &results);
    let drawing = fig::chain(&scene.chain.dimensions, &analysis, &marks, &labels, units);
    let diagrams = histograms(scene, &results, units);
    let tables = vec![
        products::Table { suffix: String::new(), csv: dependent_csv(scene, &results) },
        products::Table { suffix: "-contributions".into(), csv: contributions_csv(scene, &results) },
    ];
    Ok(Products {
        name: scene.name.clone(),
        mm_per_unit: super::mm_per_unit(scene.units),
        picture: Picture::Still(drawing),
        positions: None,
        sheets: Vec::new(),
        pages: Vec::new(),
        diagrams,
        tables,
        texts: Vec::new(),
        summary,
        report,
        warnings,
        derived: Vec::new(),
        frame_scales: Vec::new(),
    })
}

/// The chain's check as the run reports it: the seed's coincidence test, the redundant
/// dimensions (each with the reference dimension to mark), the groups of features not tied
/// to the zero point, then the features by their `labels`; and the warnings among them.
fn dimensioning_report(scene: &ChainScene, analysis: &Analysis, labels: &[String]) -> (String, Vec<String>) {
    let dims = &scene.chain.dimensions;
    let units = scene.units.length();
    let mut warnings = Vec::new();
    let mut report = String::new();
    let n_red = analysis.redundant_count(dims.len());
    report.push_str(&format!(
        "chain {}: {}, {}, {}; {}\n",
        scene.name,
        crate::text::counted(analysis.features.len() as i64, "feature", "features"),
        crate::text::counted(dims.len() as i64, "dimension", "dimensions"),
        crate::text::counted(analysis.components as i64, "group of features", "groups of features"),
        crate::text::counted(n_red as i64, "redundant dimension", "redundant dimensions")
    ));
    let loop_text = |r: &crate::solve::chain::Redundant| {
        let f = Function { terms: r.path.clone(), nominal: r.path.iter().map(|t| t.coef * dims[t.dim].nominal).sum() };
        format!("{} = {}", dims[r.dim].name, f.names(dims))
    };
    for g in &analysis.coincident {
        let names: Vec<String> =
            g.iter().map(|&i| format!("{} ({})", dims[i].name, fmt_value(dims[i].nominal))).collect();
        report.push_str(&format!(
            "  seed's check: {} end at one point when every base is 0: over-dimensioned {}\n",
            names.join(", "),
            // p coinciding points (the zero point counts) are p − 1 redundant dimensions.
            crate::text::counted(
                (g.len() - 1 + usize::from(g.iter().any(|&i| analysis.node_of[dims[i].to] == analysis.node_of[0])))
                    as i64,
                "time",
                "times"
            )
        ));
    }
    for r in &analysis.redundant {
        let d = &dims[r.dim];
        let what = if r.contradiction {
            format!(
                "CONTRADICTION: the loop {} does not close: the others give {} but {} = {} ({:+} {units})",
                loop_text(r),
                fmt_value(d.nominal + r.residual),
                d.name,
                fmt_value(d.nominal),
                r.residual
            )
        } else {
            format!("redundant: {} ({}) repeats the loop {}", d.name, fmt_value(d.nominal), loop_text(r))
        };
        let fix = if r.contradiction { "correct the values, then mark" } else { "mark" };
        let line = format!("{what}; {fix} {} as a reference dimension \"(ref)\"", dims[r.suggest_ref].name);
        report.push_str(&format!("  {line}\n"));
        warnings.push(line);
    }
    if !analysis.untied.is_empty() {
        let line = format!(
            "under-dimensioned: these groups of features are not tied to the zero point {}: {}",
            analysis.features[0].name,
            analysis.untied_text()
        );
        report.push_str(&format!("  {line}\n"));
        warnings.push(line);
    }
    if n_red == 0 && analysis.untied.is_empty() {
        report.push_str("  dimensioning correct: no over- or under-dimensioning\n");
    }
    // Features by their labels (matrix form: F0 the zero point, then along the axis), each
    // with the dimension value it is known by in the matrix.
    let mut by_label: Vec<usize> = (0..analysis.features.len()).collect();
    if scene.chain.form == Form::Matrix {
        by_label.sort_by_key(|&i| labels[i].trim_start_matches('F').parse::<usize>().unwrap_or(usize::MAX));
    }
    report.push_str("  features: ");
    report.push_str(
        &by_label
            .iter()
            .map(|&i| {
                let f = &analysis.features[i];
                if labels[i] == f.name {
                    format!("{} at {}", f.name, fmt_value(f.x))
                } else {
                    format!("{} ({}) at {}", labels[i], f.name, fmt_value(f.x))
                }
            })
            .collect::<Vec<_>>()
            .join(", "),
    );
    report.push('\n');

    (report, warnings)
}

/// The dependent dimensions' table (nominal, mean, WC, RSS, MRSS, Monte Carlo) and each one's
/// equation, contributions, percentiles and spec, appended to `report`.
fn stack_report(scene: &ChainScene, results: &[DependentResult], report: &mut String) {
    let dims = &scene.chain.dimensions;
    if !results.is_empty() {
        report.push_str(&format!(
            "\n{:<6} {:<14} {:>10} {:>10} {:>9} {:>9} {:>9} {:>10} {:>9}\n",
            "Z", "between", "nominal", "mean", "WC ±", "RSS ±", "MRSS ±", "MC mean", "MC σ"
        ));
    }
    for r in results {
        let z = &scene.chain.dependent[r.index];
        let s = &r.stack;
        let (mcm, mcs) = r.monte_carlo.as_ref().map_or(("-".into(), "-".into()), |m| (fmt4(m.mean), fmt4(m.sigma)));
        report.push_str(&format!(
            "{:<6} {:<14} {:>10} {:>10} {:>9} {:>9} {:>9} {:>10} {:>9}\n",
            z.name,
            z.label,
            fmt4(s.nominal),
            fmt4(s.mean),
            fmt4(s.worst_case),
            fmt4(s.rss),
            fmt4(s.mrss),
            mcm,
            mcs
        ));
    }
    for r in results {
        let z = &scene.chain.dependent[r.index];
        report.push_str(&format!("  {}\n", r.function.equation(&z.name, dims)));
        let contrib: Vec<String> = r
            .stack
            .contributions
            .iter()
            .map(|c| format!("{} {:.1}% WC / {:.1}% var", dims[c.dim].name, c.pct_worst_case, c.pct_variance))
            .collect();
        if !contrib.is_empty() {
            report.push_str(&format!("    contributions: {}\n", contrib.join(", ")));
        }
        if let Some(m) = &r.monte_carlo {
            let p: Vec<String> = m.percentiles.iter().map(|(p, v)| format!("P{p} {}", fmt4(*v))).collect();
            report.push_str(&format!("    Monte Carlo ({}): {}\n", scene.stackup.distribution.name(), p.join(", ")));
            if let (Some(ppm), Some([lsl, usl])) = (m.out_of_spec_ppm, z.spec) {
                report.push_str(&format!(
                    "    spec [{}, {}]: {ppm:.1} ppm out of spec ({} ppm for a normal distribution), Cp {}, Cpk {}\n",
                    fmt_value(lsl),
                    fmt_value(usl),
                    m.out_of_spec_ppm_normal.map_or("-".into(), |p| format!("{p:.1}")),
                    m.cp.map_or("-".into(), fmt4),
                    m.cpk.map_or("-".into(), fmt4)
                ));
            }
        }
    }
}

/// Each dependent dimension's mark on the chain's drawing: between its features, its
/// nominal value, its worst-case band and (when it shifts) its mean.
fn dependent_marks(scene: &ChainScene, analysis: &Analysis, results: &[DependentResult]) -> Vec<DependentMark> {
    results
        .iter()
        .map(|r| {
            let z = &scene.chain.dependent[r.index];
            let (l, p) =
                (analysis.features[analysis.node_of[z.left]].x, analysis.features[analysis.node_of[z.right]].x);
            let tol =
                if r.stack.worst_case > 0.0 { format!(" ±{}", fmt_value(r.stack.worst_case)) } else { String::new() };
            let shift = r.stack.mean - r.stack.nominal;
            let text = if shift.abs() > 0.0 {
                format!("{} = {}{} (mean {})", z.name, fmt_value(r.stack.nominal), tol, fmt_value(r.stack.mean))
            } else {
                format!("{} = {}{}", z.name, fmt_value(r.stack.nominal), tol)
            };
            DependentMark { left_x: l, right_x: p, text }
        })
        .collect()
}

/// The Monte Carlo histogram of each dependent dimension that has one.
fn histograms(scene: &ChainScene, results: &[DependentResult], units: &str) -> Vec<products::Diagram> {
    results
        .iter()
        .filter_map(|r| {
            let z = &scene.chain.dependent[r.index];
            r.monte_carlo.as_ref().map(|m| products::Diagram {
                stem: format!("{}-histogram", z.name),
                drawing: fig::histogram(
                    &z.name,
                    &z.label,
                    units,
                    scene.stackup.distribution.name(),
                    m,
                    &r.stack,
                    z.spec,
                ),
                track: Vec::new(),
            })
        })
        .collect()
}

fn fmt4(v: f64) -> String {
    fmt_value((v * 1e4).round() / 1e4)
}

/// A dimension named in a loop or a function, with its coefficient (+1 or −1).
#[derive(Debug, Serialize)]
struct TermRecord<'a> {
    dimension: &'a str,
    coef: f64,
}

/// A feature on the axis.
#[derive(Debug, Serialize)]
struct FeatureRecord<'a> {
    name: &'a str,
    /// The label on the drawing: `F0`… in the matrix form, the name in the named form.
    label: String,
    x: f64,
    aliases: &'a [String],
    tied: bool,
}

/// A dimension as the check sees it.
#[derive(Debug, Serialize)]
struct DimensionRecord<'a> {
    name: &'a str,
    from: &'a str,
    to: &'a str,
    nominal: f64,
    upper: f64,
    lower: f64,
    redundant: bool,
}

/// A redundant dimension and the loop it closes.
#[derive(Debug, Serialize)]
struct RedundantRecord<'a> {
    dimension: &'a str,
    nominal: f64,
    #[serde(rename = "loop")]
    loop_: String,
    path: Vec<TermRecord<'a>>,
    residual: f64,
    kind: &'static str,
    suggest_ref: &'a str,
}

/// The over-dimensioning check.
#[derive(Debug, Serialize)]
struct CheckRecord<'a> {
    features: usize,
    dimensions: usize,
    groups: usize,
    redundant_count: usize,
    contradictions: usize,
    coincident: Vec<Vec<&'a str>>,
    correct: bool,
}

/// A tolerance band around the mean.
#[derive(Debug, Serialize)]
struct Band {
    tol: f64,
    min: f64,
    max: f64,
}

impl Band {
    fn around(center: f64, tol: f64) -> Band {
        Band { tol, min: center - tol, max: center + tol }
    }
}

/// The modified RSS band with its factor.
#[derive(Debug, Serialize)]
struct MrssRecord {
    factor: f64,
    tol: f64,
    min: f64,
    max: f64,
}

/// A percentile of the Monte Carlo sample.
#[derive(Debug, Serialize)]
struct PercentileRecord {
    p: f64,
    value: f64,
}

/// The Monte Carlo stack-up of one dependent dimension.
#[derive(Debug, Serialize)]
struct MonteCarloRecord<'a> {
    distribution: &'a str,
    samples: u64,
    seed: u64,
    mean: f64,
    sigma: f64,
    min: f64,
    max: f64,
    percentiles: Vec<PercentileRecord>,
    out_of_spec_ppm: Option<f64>,
    out_of_spec_ppm_normal: Option<f64>,
    cp: Option<f64>,
    cpk: Option<f64>,
}

/// One independent dimension's share of a dependent one's tolerance.
#[derive(Debug, Serialize)]
struct ContributionRecord<'a> {
    dimension: &'a str,
    coef: f64,
    tol: f64,
    shift: f64,
    pct_worst_case: f64,
    pct_variance: f64,
}

/// A dependent dimension: its function and its stack-up.
#[derive(Debug, Serialize)]
struct DependentRecord<'a> {
    z: &'a str,
    between: &'a str,
    left: &'a str,
    right: &'a str,
    function: String,
    equation: String,
    terms: Vec<TermRecord<'a>>,
    nominal: f64,
    mean: f64,
    worst_case: Band,
    rss: Band,
    mrss: MrssRecord,
    sigma: f64,
    spec: Option<[f64; 2]>,
    monte_carlo: Option<MonteCarloRecord<'a>>,
    contributions: Vec<ContributionRecord<'a>>,
}

/// The chain's JSON summary (keys documented in docs/chain.md).
#[derive(Debug, Serialize)]
struct Summary<'a> {
    kind: &'static str,
    name: &'a str,
    units: &'static str,
    form: &'static str,
    features: Vec<FeatureRecord<'a>>,
    dimensions: Vec<DimensionRecord<'a>>,
    check: CheckRecord<'a>,
    redundant: Vec<RedundantRecord<'a>>,
    untied: Vec<Vec<&'a str>>,
    dependent: Vec<DependentRecord<'a>>,
}

/// A finite value, or `None` (JSON `null`).
fn finite(v: Option<f64>) -> Option<f64> {
    v.filter(|x| x.is_finite())
}

/// The JSON summary (keys documented in docs/chain.md).
fn summary(scene: &ChainScene, a: &Analysis, results: &[DependentResult]) -> Result<serde_json::Value, Error> {
    let dims = &scene.chain.dimensions;
    let fname = |f: usize| a.features[a.node_of[f]].name.as_str();
    let terms = |ts: &[crate::solve::chain::graph::Term]| -> Vec<TermRecord<'_>> {
        ts.iter().map(|t| TermRecord { dimension: &dims[t.dim].name, coef: t.coef }).collect()
    };
    let labels = fig::feature_labels(a, scene.chain.form);
    let features = a
        .features
        .iter()
        .zip(labels)
        .map(|(f, label)| FeatureRecord { name: &f.name, label, x: f.x, aliases: &f.aliases, tied: f.tied })
        .collect();
    let dimensions = dims
        .iter()
        .enumerate()
        .map(|(i, d)| DimensionRecord {
            name: &d.name,
            from: fname(d.from),
            to: fname(d.to),
            nominal: d.nominal,
            upper: d.upper,
            lower: d.lower,
            redundant: !a.in_tree[i],
        })
        .collect();
    let redundant = a
        .redundant
        .iter()
        .map(|r| {
            let f = Function { terms: r.path.clone(), nominal: 0.0 };
            RedundantRecord {
                dimension: &dims[r.dim].name,
                nominal: dims[r.dim].nominal,
                loop_: format!("{} = {}", dims[r.dim].name, f.names(dims)),
                path: terms(&r.path),
                residual: r.residual,
                kind: if r.contradiction { "contradiction" } else { "repeat" },
                suggest_ref: &dims[r.suggest_ref].name,
            }
        })
        .collect();
    let dependent = results
        .iter()
        .map(|r| {
            let z = &scene.chain.dependent[r.index];
            let s = &r.stack;
            let monte_carlo = r.monte_carlo.as_ref().map(|m| MonteCarloRecord {
                distribution: scene.stackup.distribution.name(),
                samples: m.samples,
                seed: scene.stackup.seed,
                mean: m.mean,
                sigma: m.sigma,
                min: m.min,
                max: m.max,
                percentiles: m.percentiles.iter().map(|&(p, value)| PercentileRecord { p, value }).collect(),
                out_of_spec_ppm: finite(m.out_of_spec_ppm),
                out_of_spec_ppm_normal: finite(m.out_of_spec_ppm_normal),
                cp: finite(m.cp),
                cpk: finite(m.cpk),
            });
            DependentRecord {
                z: &z.name,
                between: &z.label,
                left: fname(z.left),
                right: fname(z.right),
                function: r.function.names(dims),
                equation: r.function.equation(&z.name, dims),
                terms: terms(&r.function.terms),
                nominal: s.nominal,
                mean: s.mean,
                worst_case: Band::around(s.mean, s.worst_case),
                rss: Band::around(s.mean, s.rss),
                mrss: MrssRecord { factor: s.mrss_factor, tol: s.mrss, min: s.mean - s.mrss, max: s.mean + s.mrss },
                sigma: s.sigma,
                spec: z.spec,
                monte_carlo,
                contributions: s
                    .contributions
                    .iter()
                    .map(|c| ContributionRecord {
                        dimension: &dims[c.dim].name,
                        coef: c.coef,
                        tol: c.half,
                        shift: c.shift,
                        pct_worst_case: c.pct_worst_case,
                        pct_variance: c.pct_variance,
                    })
                    .collect(),
            }
        })
        .collect();
    let s = Summary {
        kind: "chain",
        name: &scene.name,
        units: scene.units.length(),
        form: match scene.chain.form {
            Form::Matrix => "matrix",
            Form::Named => "named",
        },
        features,
        dimensions,
        check: CheckRecord {
            features: a.features.len(),
            dimensions: dims.len(),
            groups: a.components,
            redundant_count: a.redundant_count(dims.len()),
            contradictions: a.redundant.iter().filter(|r| r.contradiction).count(),
            coincident: a.coincident.iter().map(|g| g.iter().map(|&i| dims[i].name.as_str()).collect()).collect(),
            correct: a.redundant.is_empty() && a.untied.is_empty(),
        },
        redundant,
        untied: a.untied.iter().map(|g| g.iter().map(|&i| a.features[i].name.as_str()).collect()).collect(),
        dependent,
    };
    products::summary_value(&s, &scene.name)
}

/// `<name>.csv`: one row per dependent dimension.
pub fn dependent_csv(scene: &ChainScene, results: &[DependentResult]) -> Csv {
    let mut csv = Csv::new([
        "z",
        "between",
        "function",
        "nominal",
        "mean",
        "wc_tol",
        "wc_min",
        "wc_max",
        "rss_tol",
        "mrss_tol",
        "sigma",
        "mc_mean",
        "mc_sigma",
        "mc_p0.135",
        "mc_p50",
        "mc_p99.865",
        "lsl",
        "usl",
        "ppm",
        "ppm_normal",
        "cp",
        "cpk",
    ]);
    let num = |v: Option<f64>| v.filter(|x| x.is_finite()).map_or(String::new(), |x| format!("{x}"));
    for r in results {
        let z = &scene.chain.dependent[r.index];
        let s = &r.stack;
        let m = r.monte_carlo.as_ref();
        let pct = |p: f64| m.and_then(|m| m.percentiles.iter().find(|(q, _)| *q == p).map(|(_, v)| *v));
        csv.row_text([
            z.name.clone(),
            z.label.clone(),
            r.function.names(&scene.chain.dimensions),
            num(Some(s.nominal)),
            num(Some(s.mean)),
            num(Some(s.worst_case)),
            num(Some(s.mean - s.worst_case)),
            num(Some(s.mean + s.worst_case)),
            num(Some(s.rss)),
            num(Some(s.mrss)),
            num(Some(s.sigma)),
            num(m.map(|m| m.mean)),
            num(m.map(|m| m.sigma)),
            num(pct(0.135)),
            num(pct(50.0)),
            num(pct(99.865)),
            num(z.spec.map(|s| s[0])),
            num(z.spec.map(|s| s[1])),
            num(m.and_then(|m| m.out_of_spec_ppm)),
            num(m.and_then(|m| m.out_of_spec_ppm_normal)),
            num(m.and_then(|m| m.cp)),
            num(m.and_then(|m| m.cpk)),
        ]);
    }
    csv
}

/// `<name>-contributions.csv`: one row per (dependent, independent dimension) pair.
pub fn contributions_csv(scene: &ChainScene, results: &[DependentResult]) -> Csv {
    let mut csv = Csv::new([
        "z",
        "dimension",
        "coef",
        "nominal",
        "upper",
        "lower",
        "tol",
        "shift",
        "pct_worst_case",
        "pct_variance",
    ]);
    for r in results {
        let z = &scene.chain.dependent[r.index];
        for c in &r.stack.contributions {
            let d = &scene.chain.dimensions[c.dim];
            csv.row_text([
                z.name.clone(),
                d.name.clone(),
                format!("{}", c.coef),
                format!("{}", d.nominal),
                format!("{}", d.upper),
                format!("{}", d.lower),
                format!("{}", c.half),
                format!("{}", c.shift),
                format!("{}", c.pct_worst_case),
                format!("{}", c.pct_variance),
            ]);
        }
    }
    csv
}
