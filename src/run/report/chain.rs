//! A dimensional chain's report (seed 001): the title page with the dimensions; seed 001's
//! matrix N (row B the bases, row W the signed dimensions), the same matrix with every base
//! made zero, and the check (the over-dimensioning found, the features' coordinates); the
//! part's dimensions as drawn; the dimensional functions of the dependent dimensions with
//! their stack-up (worst case, RSS, modified RSS, Monte Carlo); the stack-up's histograms.

use super::{Frame, Gathered, Part};
use crate::Error;
use crate::figure::report::compose::{self, Block};
use crate::figure::report::diagrams::{self, MarkedDiagram, PER_PAGE};
use crate::figure::report::table::{Align, PaperTable};
use crate::run::chain as run;
use crate::scene::chain::{ChainScene, value_label};
use crate::solve::chain::Form;

/// The title page's data: every dimension (base, value, tolerance), the dependent ones, the
/// stack-up's settings.
fn data(scene: &ChainScene) -> PaperTable {
    let u = scene.units.length();
    let c = &scene.chain;
    let num = crate::report::number;
    let mut t = PaperTable::new(
        &["dimension", "from", "to", "value", "tolerance", "unit"],
        &[Align::Left, Align::Left, Align::Left, Align::Right, Align::Right, Align::Left],
    );
    for d in &c.dimensions {
        t.row(vec![
            d.name.clone(),
            c.features[d.from].clone(),
            c.features[d.to].clone(),
            value_label(d.nominal),
            format!("+{} / {}", num(d.upper), num(d.lower)),
            u.into(),
        ]);
    }
    for z in &c.dependent {
        t.row(vec![z.name.clone(), "dependent".into(), z.label.clone(), String::new(), String::new(), u.into()]);
    }
    let s = &scene.stackup;
    t.row(vec![
        "stack-up".into(),
        format!("MRSS ×{}", num(s.mrss_factor)),
        s.distribution.name().into(),
        format!("{} samples", s.samples),
        format!("seed {}", s.seed),
        String::new(),
    ]);
    t
}

/// The parts of a chain's report.
pub(super) fn gather<'a>(scene: &'a ChainScene, file: &str, frame: Frame) -> Result<Gathered<'a>, Error> {
    let products = run::products(scene, file)?;
    let (analysis, results) =
        run::solve(scene).map_err(|e| Error::Solve { file: file.to_string(), source: e.into() })?;
    let c = &scene.chain;
    let dims = &c.dimensions;
    let u = scene.units.length();
    // Matrix N as written, and with every base made zero (the coordinates of the ends).
    let mut header: Vec<String> = vec![String::new()];
    header.extend(dims.iter().map(|d| d.name.clone()));
    let align: Vec<Align> = std::iter::once(Align::Left).chain(dims.iter().map(|_| Align::Right)).collect();
    let header_refs: Vec<&str> = header.iter().map(String::as_str).collect();
    let mut matrix = PaperTable::new(&header_refs, &align);
    let base = |i: usize| c.features[dims[i].from].clone();
    let end_x = |i: usize| analysis.features[analysis.node_of[dims[i].to]].x;
    if c.form == Form::Matrix {
        matrix.row(std::iter::once("B".to_string()).chain((0..dims.len()).map(base)).collect());
        matrix.row(std::iter::once("W".to_string()).chain(dims.iter().map(|d| value_label(d.nominal))).collect());
        matrix.row(std::iter::once("B′".to_string()).chain(dims.iter().map(|_| "0".to_string())).collect());
        matrix.row(std::iter::once("W′".to_string()).chain((0..dims.len()).map(|i| value_label(end_x(i)))).collect());
    } else {
        matrix.row(std::iter::once("from".to_string()).chain((0..dims.len()).map(base)).collect());
        matrix.row(std::iter::once("value".to_string()).chain(dims.iter().map(|d| value_label(d.nominal))).collect());
        matrix.row(
            std::iter::once("x of the end".to_string()).chain((0..dims.len()).map(|i| value_label(end_x(i)))).collect(),
        );
    }
    // The run's report: its first block is the check, the rest the functions.
    let text = products.report.clone();
    let (check, functions) = text.split_once("\n\n").unwrap_or((text.as_str(), ""));
    let check_lines: Vec<String> = check.lines().map(|l| l.trim_end().to_string()).collect();
    let mut stack = PaperTable::new(
        &["Z", "between", "function", "nominal", "WC ±", "RSS ±", "MRSS ±", "MC mean", "MC σ"],
        &[
            Align::Left,
            Align::Left,
            Align::Left,
            Align::Right,
            Align::Right,
            Align::Right,
            Align::Right,
            Align::Right,
            Align::Right,
        ],
    );
    let num = crate::figure::shared::sheet::number;
    for r in &results {
        let z = &c.dependent[r.index];
        let st = &r.stack;
        let (mean, sigma) =
            r.monte_carlo.as_ref().map_or((String::new(), String::new()), |m| (num(m.mean), num(m.sigma)));
        stack.row(vec![
            z.name.clone(),
            z.label.clone(),
            r.function.names(dims),
            value_label(st.nominal),
            num(st.worst_case),
            num(st.rss),
            num(st.mrss),
            mean,
            sigma,
        ]);
    }
    let function_lines: Vec<String> =
        functions.lines().filter(|l| l.starts_with("  ")).map(|l| l.trim_end().to_string()).collect();
    let histograms: Vec<MarkedDiagram> =
        products.diagrams.iter().map(|d| MarkedDiagram { drawing: d.drawing.clone(), marks: Vec::new() }).collect();
    let picture = match &products.picture {
        super::super::products::Picture::Still(d) => d.clone(),
        super::super::products::Picture::Motion(a) => a.base.clone(),
    };
    let owned = std::sync::Arc::new((frame, matrix, check_lines, picture, stack, function_lines, histograms));
    let mut parts: Vec<Part<'a>> = Vec::new();
    parts.push(super::title_part(
        owned.0.clone(),
        "Dimensional chains in digital form".into(),
        format!("chain {} ({} dimensions; seed 001)", scene.name, scene.chain.dimensions.len()),
        data(scene),
    ));
    let o = owned.clone();
    parts.push(Part {
        title: "Matrix N and the check".into(),
        stem: "matrix".into(),
        pages: 1,
        draw: Box::new(move |n| {
            let (frame, matrix, check, ..) = &*o;
            let blocks = vec![
                (format!("Matrix N = [B; W] and, every base made zero, [B′; W′] ({u})"), Block::Table(matrix.clone())),
                ("The check: over- and under-dimensioning".to_string(), Block::Lines(check.clone())),
            ];
            Ok(vec![compose::text_page(
                &frame.frame,
                &frame.title("2  Matrix N and the check", n.first, n.total),
                &blocks,
                1,
            )])
        }),
    });
    let o = owned.clone();
    parts.push(Part {
        title: "The part's dimensions".into(),
        stem: "dimensions".into(),
        pages: 1,
        draw: Box::new(move |n| {
            let (frame, _, _, picture, ..) = &*o;
            let title = frame.title("3  The part's dimensions", n.first, n.total);
            Ok(vec![compose::figure_page(
                &frame.frame,
                &title,
                picture,
                "Independent dimensions (blue) and the dependent ones (red)",
                &[],
                1.0,
            )])
        }),
    });
    let o = owned.clone();
    parts.push(Part {
        title: "Dimensional functions and stack-up".into(),
        stem: "functions".into(),
        pages: 1,
        draw: Box::new(move |n| {
            let (frame, _, _, _, stack, lines, _) = &*o;
            let blocks = vec![
                (format!("Stack-up of the dependent dimensions ({u})"), Block::Table(stack.clone())),
                ("Dimensional functions, contributions, Monte Carlo".to_string(), Block::Lines(lines.clone())),
            ];
            Ok(vec![compose::text_page(
                &frame.frame,
                &frame.title("4  Dimensional functions and stack-up", n.first, n.total),
                &blocks,
                1,
            )])
        }),
    });
    let pages = owned.6.len().div_ceil(PER_PAGE);
    if pages > 0 {
        let o = owned.clone();
        parts.push(Part {
            title: "Histograms of the stack-up".into(),
            stem: "histograms".into(),
            pages,
            draw: Box::new(move |n| {
                let (frame, .., histograms) = &*o;
                Ok(histograms
                    .chunks(PER_PAGE)
                    .enumerate()
                    .map(|(k, ds)| {
                        let part = format!("5  Histograms of the stack-up ({} of {pages})", k + 1);
                        diagrams::page(&frame.frame, &frame.title(&part, n.first + k, n.total), ds).0
                    })
                    .collect())
            }),
        });
    }
    let summary = serde_json::json!({
        "kind": "chain",
        "redundant": analysis.redundant_count(dims.len()),
        "dependent": c.dependent.len(),
    });
    Ok(Gathered { parts, table: None, summary, warnings: products.warnings })
}
