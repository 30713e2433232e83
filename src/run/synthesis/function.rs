//! `task = "function"`: Freudenstein's function generator through three precision points,
//! the design as a `fourbar` scene, the function at the precision points by the analysis and
//! the structural error over the range charted.

use serde_json::json;

use super::check::{self, Row, TOL_FUNCTION};
use super::design::{self, FourbarDesign};
use super::{Context, Made, serr};
use crate::Error;
use crate::figure::shared::plot::{Diagram as Plot, Level, Mark, Marks, Series, diagram_marked};
use crate::figure::synthesis::{function as fig, len};
use crate::geom::{Side, wrap_pi};
use crate::run::products::Diagram;
use crate::solve::expr::Expr;
use crate::solve::fourbar::Geometry;
use crate::solve::synthesis::SynthesisError;
use crate::solve::synthesis::function::{Design, Requirement, synthesise};

/// Samples of x over the range for the structural error.
const ERROR_SAMPLES: usize = 201;

pub(super) fn made(cx: &Context, req: &Requirement, function: &Expr) -> Result<Made, Error> {
    let f = |x: f64| function.eval(x).value;
    let field = |e: &SynthesisError| match e {
        SynthesisError::PrecisionPointOutside { index, .. } => Some(format!("precision_x[{}]", index - 1)),
        _ => None,
    };
    let d = synthesise(req, &f).map_err(serr(cx.file, field))?;
    let crank_deg = |phi: f64| (phi + d.crank_turn).to_degrees();
    let (s0, s1) = (crank_deg(req.input.0), crank_deg(req.input.1));
    let (from, to) = (s0.min(s1), s0.max(s1));
    let omega = if s1 >= s0 { cx.scene.omega1.abs() } else { -cx.scene.omega1.abs() };
    let geometry = Geometry {
        o1: d.o1(),
        c: d.pivot_c(),
        l1: d.a,
        l_ab: d.b,
        l_bm: 0.5 * d.b,
        alpha: 0.0,
        l_bc: d.c,
        branch: d.sides[0],
    };
    let fd = FourbarDesign { geometry, omega1: omega, sweep_deg: (from, to, (to - from) / 180.0) };
    let what = format!(
        "y = {} on [{}, {}]: crank angle φ1 = {}° + φ, rocker angle φ3 = {}° + ψ (M is AB's middle)",
        function.source(),
        len(req.x_range.0),
        len(req.x_range.1),
        len(d.crank_turn.to_degrees()),
        len(d.rocker_turn.to_degrees())
    );
    let text = design::fourbar(&cx.design_name, cx.scene.units, &cx.header(&what), &fd);
    let parsed = cx.parse(&text)?;
    let g = check::fourbar_scene(&parsed).map_err(|e| cx.internal(e))?.spec.geometry;
    let span = (d.y_range.1 - d.y_range.0).abs();
    let mut rows = Vec::new();
    for j in 0..3 {
        let y = generated(&g, &d, req, d.x[j]).map_err(|e| cx.internal(e))?;
        rows.push(Row::new(format!("y(x{} = {})", j + 1, len(d.x[j])), d.y[j], y, TOL_FUNCTION * span));
    }
    let mut warnings = Vec::new();
    if d.sides.iter().any(|s| *s != d.sides[0]) {
        warnings.push(format!(
            "branch defect: B lies {} of A → C at the precision points: they are on different assembly modes, the linkage does not generate the function through all three",
            d.sides.iter().map(|s| if *s == Side::Left { "left" } else { "right" }).collect::<Vec<_>>().join(", ")
        ));
    }
    let (chart, gap) = error_chart(&g, &d, req, function);
    if let Some(x) = gap {
        warnings.push(format!(
            "the linkage cannot be assembled at x = {} inside the range: it passes a dead point, the function is not generated there",
            len(x)
        ));
    }
    let route = "fourbar solver: B by circle intersection at each precision point's crank angle, the rocker's angle mapped back to y".to_string();
    Ok(Made {
        picture: fig::construction(&d, req, function.source(), cx.units()),
        diagrams: vec![chart],
        design: text,
        check: check::Check { rows, route },
        summary: summary(req, &d, function),
        report: vec![
            format!("precision points x = {}, {}, {}", len(d.x[0]), len(d.x[1]), len(d.x[2])),
            format!("K1 = {}, K2 = {}, K3 = {}", d.k[0], d.k[1], d.k[2]),
            format!(
                "crank O1A = {}, coupler AB = {}, rocker CB = {}, ground O1C = {} {}; {}",
                len(d.a),
                len(d.b),
                len(d.c),
                len(d.d),
                cx.unit(),
                d.class.describe()
            ),
        ],
        warnings,
    })
}

/// The y the analysed linkage generates at `x`: its rocker angle at the crank angle of x,
/// mapped back by the output's linear map (the turn nearest the required ψ).
fn generated(g: &Geometry, d: &Design, req: &Requirement, x: f64) -> Result<f64, String> {
    let phi = d.phi_of(req, x);
    let phi3 = check::output_angle(g, phi + d.crank_turn)?;
    let want = req.output.0 + (x - req.x_range.0) / (req.x_range.1 - req.x_range.0) * (req.output.1 - req.output.0);
    let psi = want + wrap_pi(phi3 - d.rocker_turn - want);
    Ok(d.y_of_psi(req, psi))
}

/// The structural error y_generated − f(x) over the range, the precision points marked; and
/// the first x where the linkage cannot be assembled, if any.
fn error_chart(g: &Geometry, d: &Design, req: &Requirement, function: &Expr) -> (Diagram, Option<f64>) {
    let (x0, x1) = req.x_range;
    let mut gap = None;
    let (xs, es): (Vec<f64>, Vec<f64>) = (0..ERROR_SAMPLES)
        .map(|k| {
            let x = x0 + (x1 - x0) * k as f64 / (ERROR_SAMPLES - 1) as f64;
            let e = match generated(g, d, req, x) {
                Ok(y) => y - function.eval(x).value,
                Err(_) => {
                    gap.get_or_insert(x);
                    f64::NAN
                }
            };
            (x, e)
        })
        .unzip();
    let plot = Plot {
        title: format!("Structural error of the generator of y = {}", function.source()),
        x_label: "x".into(),
        y_label: "Δy = y(linkage) − f(x)".into(),
        series: vec![Series { label: "Δy".into(), x: xs, y: es }],
    };
    let marks = Marks {
        levels: vec![Level { y: 0.0, label: String::new() }],
        points: (0..3).map(|j| Mark { x: d.x[j], y: 0.0, label: format!("x{}", j + 1) }).collect(),
    };
    (Diagram { stem: "structural-error".into(), drawing: diagram_marked(&plot, &marks), track: Vec::new() }, gap)
}

fn summary(req: &Requirement, d: &Design, function: &Expr) -> serde_json::Value {
    json!({
        "requirement": {
            "function": function.source(),
            "x_range": [req.x_range.0, req.x_range.1],
            "input_deg": [req.input.0.to_degrees(), req.input.1.to_degrees()],
            "output_deg": [req.output.0.to_degrees(), req.output.1.to_degrees()],
            "ground": req.ground,
            "precision_x": req.precision,
        },
        "construction": {
            "precision_x": d.x, "precision_y": d.y,
            "phi_deg": d.phi.map(f64::to_degrees), "psi_deg": d.psi.map(f64::to_degrees),
            "k": d.k,
        },
        "design": {
            "crank": d.a, "coupler": d.b, "rocker": d.c, "ground": d.d,
            "crank_turn_deg": d.crank_turn.to_degrees(), "rocker_turn_deg": d.rocker_turn.to_degrees(),
            "sides": d.sides,
        },
        "quality": {
            "class": d.class,
            "defects": if d.sides.iter().any(|s| *s != d.sides[0]) { vec!["branch"] } else { vec![] },
        },
    })
}
