//! The triad pipeline: every assembly mode (the main result), the seed's pattern method
//! and Newton–Raphson from a start; the drawing (the seed's Fig. 3) as SVG and DXF; the
//! JSON summary. Everything is solved before anything is written.

use serde_json::{Value, json};

use super::output::Output;
use super::{Outcome, RunOptions, solve_err};
use crate::Error;
use crate::draw::dxf;
use crate::draw::svg::{self, SvgOptions};
use crate::figure::triad::{TriadFigure, drawing};
use crate::geom::{Point, deg};
use crate::report::point;
use crate::scene::triad::{OrientationChoice, Sense, TriadScene};
use crate::solve::triad::pattern::construct;
use crate::solve::triad::{
    Configuration, NewtonOptions, NewtonSolution, Orientation, PatternOptions, PatternSolution, Triad, TriadError,
    all_modes, newton, pattern,
};

/// A pattern result is the same position as a mode when all vertices are this close
/// (relative to the triad's scale): far above the pattern's ε-induced error, far below the
/// distance between distinct modes.
const SAME_POSITION_REL: f64 = 1e-3;

/// Everything the triad pipeline computes.
#[derive(Debug, Clone)]
pub struct TriadResults {
    /// The triad's data.
    pub triad: Triad,
    /// Every assembly mode searched for.
    pub modes: Vec<Configuration>,
    /// The pattern method's result, or why it failed.
    pub pattern: Result<PatternSolution, TriadError>,
    /// The pattern's start triangle (A1, A2, A3), if A2 exists at the start angle.
    pub start: Option<[Point; 3]>,
    /// Newton's start angles (radians).
    pub newton_start: [f64; 3],
    /// Newton–Raphson's result, or why it failed.
    pub newton: Result<NewtonSolution, TriadError>,
    /// Index in `modes` of the position drawn as the mechanism.
    pub primary: usize,
    /// Warnings for the terminal.
    pub warnings: Vec<String>,
}

fn pattern_options(scene: &TriadScene) -> PatternOptions {
    let p = &scene.pattern;
    PatternOptions {
        phi1_start: p.phi1_start,
        step: p.step,
        tol: p.tol,
        max_iterations: p.max_iterations,
        a2: p.a2,
        orientation: match p.orientation {
            Sense::Ccw => Orientation::Ccw,
            Sense::Cw => Orientation::Cw,
        },
    }
}

fn max_vertex_distance(a: &[Point; 3], b: &[Point; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).norm()).fold(0.0, f64::max)
}

/// Solves the scene: all modes (an error when there is none), the pattern method and
/// Newton (their failures become warnings).
pub fn solve(scene: &TriadScene) -> Result<TriadResults, TriadError> {
    let triad = Triad::new(scene.o, scene.r, scene.l12, scene.l23, scene.l13)?;
    let choice = match scene.orientation {
        OrientationChoice::Both => None,
        OrientationChoice::Ccw => Some(Orientation::Ccw),
        OrientationChoice::Cw => Some(Orientation::Cw),
    };
    let modes = all_modes(&triad, choice)?;
    let popts = pattern_options(scene);
    let pattern = pattern(&triad, &popts);
    let start = construct(&triad, popts.phi1_start, popts.a2, popts.orientation);
    let newton_start = scene.newton.start.unwrap_or_else(|| match start {
        Some([a1, a2, a3]) => [a1 - triad.o[0], a2 - triad.o[1], a3 - triad.o[2]].map(crate::geom::angle_of),
        None => [popts.phi1_start; 3],
    });
    let newton = newton(&triad, &NewtonOptions { start: newton_start, max_iterations: scene.newton.max_iterations });
    let mut warnings = Vec::new();
    let scale = triad.scale();
    let nearest = |a: &[Point; 3]| {
        (0..modes.len())
            .min_by(|&i, &j| max_vertex_distance(&modes[i].a, a).total_cmp(&max_vertex_distance(&modes[j].a, a)))
    };
    let matched = match &pattern {
        Ok(p) => match nearest(&p.configuration.a) {
            Some(i) if max_vertex_distance(&modes[i].a, &p.configuration.a) <= SAME_POSITION_REL * scale => Some(i),
            _ => {
                warnings.push(format!(
                    "the pattern method's position (phi1 = {:.4}°) is not among the modes searched (orientation {}); drawing the mode nearest to its start",
                    deg(p.configuration.phi[0]),
                    match scene.orientation {
                        OrientationChoice::Both => "both",
                        OrientationChoice::Ccw => "ccw",
                        OrientationChoice::Cw => "cw",
                    }
                ));
                None
            }
        },
        Err(_) => {
            warnings.push("the pattern method failed (see the report); drawing the mode nearest to its start".into());
            None
        }
    };
    let primary = matched.unwrap_or_else(|| {
        // Nearest to the start triangle, else to the start angle phi1.
        let key = |c: &Configuration| match start {
            Some(a) => max_vertex_distance(&c.a, &a),
            None => crate::geom::wrap_pi(c.phi[0] - popts.phi1_start).abs() * scale,
        };
        (0..modes.len()).min_by(|&i, &j| key(&modes[i]).total_cmp(&key(&modes[j]))).unwrap_or(0)
    });
    if let Err(e) = &newton {
        warnings.push(e.to_string());
    }
    Ok(TriadResults { triad, modes, pattern, start, newton_start, newton, primary, warnings })
}

fn configuration_json(c: &Configuration) -> Value {
    let [p1, p2, p3] = c.phi_deg();
    json!({
        "phi1_deg": p1,
        "phi2_deg": p2,
        "phi3_deg": p3,
        "A1": point(c.a[0]),
        "A2": point(c.a[1]),
        "A3": point(c.a[2]),
        "orientation": c.orientation.name(),
        "residual": c.residual,
    })
}

/// The JSON summary (keys documented in docs/triad.md).
pub fn summary(scene: &TriadScene, r: &TriadResults) -> Value {
    let pattern = match &r.pattern {
        Ok(p) => {
            let mut v = configuration_json(&p.configuration);
            v["iterations"] = json!(p.iterations);
            v["residual"] = json!(p.residual);
            v["evaluations"] = json!(p.evaluations);
            v["relative_residual"] = json!(p.configuration.residual);
            v["phi1_start_deg"] = json!(deg(scene.pattern.phi1_start));
            v
        }
        Err(e) => json!({ "error": e.to_string(), "phi1_start_deg": deg(scene.pattern.phi1_start) }),
    };
    let newton = match &r.newton {
        Ok(n) => {
            let mut v = configuration_json(&n.configuration);
            v["iterations"] = json!(n.iterations);
            v["start_deg"] = json!(r.newton_start.map(deg));
            v
        }
        Err(e) => json!({ "error": e.to_string(), "start_deg": r.newton_start.map(deg) }),
    };
    let count = |o: Orientation| r.modes.iter().filter(|c| c.orientation == o).count();
    json!({
        "kind": "triad",
        "name": scene.name,
        "units": scene.units.length(),
        "pattern": pattern,
        "newton": newton,
        "solutions": r.modes.iter().map(configuration_json).collect::<Vec<_>>(),
        "modes": {
            "ccw": count(Orientation::Ccw),
            "cw": count(Orientation::Cw),
            "collinear": count(Orientation::Collinear),
            "total": r.modes.len(),
        },
        "primary": r.primary,
    })
}

fn report(scene: &TriadScene, r: &TriadResults) -> String {
    let u = scene.units.length();
    let mut s = String::new();
    match &r.pattern {
        Ok(p) => s.push_str(&format!(
            "pattern method: phi1 = {:.2}° → {:.4}° in {} iterations (|R3 − O3A3| = {:.2e} {u})\n",
            deg(scene.pattern.phi1_start),
            deg(p.configuration.phi[0]),
            p.iterations,
            p.residual
        )),
        Err(e) => s.push_str(&format!("{e}\n")),
    }
    if let Ok(n) = &r.newton {
        let [a, b, c] = n.configuration.phi_deg();
        s.push_str(&format!(
            "Newton–Raphson: phi = ({a:.4}°, {b:.4}°, {c:.4}°) in {} iterations ({})\n",
            n.iterations, n.configuration.orientation
        ));
    }
    s.push_str(&format!("{} assembly modes:\n", r.modes.len()));
    for (i, c) in r.modes.iter().enumerate() {
        let [a, b, cc] = c.phi_deg();
        let mark = if i == r.primary { "  (drawn)" } else { "" };
        s.push_str(&format!(
            "  {:>2} {:<9} phi1 = {a:>9.4}°  phi2 = {b:>9.4}°  phi3 = {cc:>9.4}°  residual {:.1e}{mark}\n",
            i + 1,
            c.orientation.name(),
            c.residual
        ));
    }
    s
}

/// The drawing of the results.
pub fn figure(scene: &TriadScene, r: &TriadResults) -> crate::draw::Drawing {
    let others: Vec<(usize, Configuration)> =
        r.modes.iter().enumerate().filter(|(i, _)| *i != r.primary).map(|(i, c)| (i + 1, *c)).collect();
    let mut caption = Vec::new();
    match &r.pattern {
        Ok(p) => caption.push(format!(
            "Pattern method: φ1 = {:.2}° (dashed, red) → {:.2}° in {} iterations (solid: mode {}).",
            deg(scene.pattern.phi1_start),
            deg(p.configuration.phi[0]),
            p.iterations,
            r.primary + 1
        )),
        Err(_) => caption.push(format!(
            "Pattern method failed from φ1 = {:.2}°; drawn: mode {}.",
            deg(scene.pattern.phi1_start),
            r.primary + 1
        )),
    }
    if !others.is_empty() {
        caption.push(format!("Other assembly modes (grey), numbered as in the report: {} in all.", r.modes.len()));
    }
    drawing(&TriadFigure {
        triad: &r.triad,
        exact: &r.modes[r.primary],
        approximate: r.start,
        others: &others,
        caption: &caption,
    })
}

pub(super) fn run(scene: &TriadScene, file: &str, opts: &RunOptions) -> Result<Outcome, Error> {
    let results = solve(scene).map_err(|e| solve_err(file)(e.into()))?;
    let summary = summary(scene, &results);
    let report = report(scene, &results);
    let mut written = Vec::new();
    if let Some(dir) = &opts.out_dir {
        let d = figure(scene, &results);
        let svg_text = svg::to_string(&d, &SvgOptions::default());
        let dxf_bytes = dxf::to_bytes(&d, &opts.dxf_for(scene.units))
            .map_err(|e| Error::Export { what: format!("{}.dxf", scene.name), message: e.to_string() })?;
        let json_text = serde_json::to_string_pretty(&summary)
            .map_err(|e| Error::Export { what: "the JSON summary".into(), message: e.to_string() })?;
        let mut out = Output::new(dir)?;
        out.write(format!("{}.dxf", scene.name), dxf_bytes)?;
        out.write(format!("{}.svg", scene.name), svg_text)?;
        out.write(format!("{}.json", scene.name), json_text + "\n")?;
        written = out.commit()?;
    }
    Ok(Outcome { summary, report, warnings: results.warnings, written })
}
