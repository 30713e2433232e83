//! The triad pipeline: every assembly mode (the main result), the seed's pattern method
//! and Newton–Raphson from a start; the drawing (the seed's Fig. 3) as SVG and DXF; the
//! JSON summary. Everything is solved before anything is written.

use serde::Serialize;

use super::products::{self, Picture, Products, Sheet};
use super::solve_err;
use crate::Error;
use crate::figure::shared::labels::Label;
use crate::figure::shared::vocab::ModelUnits;
use crate::figure::triad::{ModesSheet, TriadFigure, drawing, modes_sheet, orientation_text};
use crate::geom::{Point, deg};
use crate::scene::Units;
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
    /// Index in `modes` of the position the pattern method reached (`None`: it failed, or
    /// reached a position outside the modes searched).
    pub reached: Option<usize>,
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
    let drawing = match scene.mode {
        Some(m) => format!("drawing mode {m}, as the scene's `mode` asks"),
        None => "drawing the mode nearest to its start".to_string(),
    };
    let matched = match &pattern {
        Ok(p) => match nearest(&p.configuration.a) {
            Some(i) if max_vertex_distance(&modes[i].a, &p.configuration.a) <= SAME_POSITION_REL * scale => Some(i),
            _ => {
                warnings.push(format!(
                    "the pattern method's position (phi1 = {:.4}°) is not among the modes searched (orientation {}); {drawing}",
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
            warnings.push(format!("the pattern method failed (see the report); {drawing}"));
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
    let primary = match scene.mode {
        Some(m) if (1..=modes.len()).contains(&m) => m - 1,
        Some(m) => return Err(TriadError::NoSuchMode { mode: m, count: modes.len() }),
        None => primary,
    };
    if let Err(e) = &newton {
        warnings.push(e.to_string());
    }
    Ok(TriadResults { triad, modes, pattern, start, newton_start, newton, primary, reached: matched, warnings })
}

/// Where a configuration puts the triad: its angles, its vertices and their orientation.
#[derive(Debug, Serialize)]
struct PlacementRecord {
    phi1_deg: f64,
    phi2_deg: f64,
    phi3_deg: f64,
    #[serde(rename = "A1")]
    a1: [f64; 2],
    #[serde(rename = "A2")]
    a2: [f64; 2],
    #[serde(rename = "A3")]
    a3: [f64; 2],
    orientation: &'static str,
}

impl PlacementRecord {
    fn of(c: &Configuration) -> PlacementRecord {
        let [phi1_deg, phi2_deg, phi3_deg] = c.phi_deg();
        let p = |i: usize| [c.a[i].x, c.a[i].y];
        PlacementRecord {
            phi1_deg,
            phi2_deg,
            phi3_deg,
            a1: p(0),
            a2: p(1),
            a3: p(2),
            orientation: c.orientation.name(),
        }
    }
}

/// A configuration of the triad in the JSON summary.
#[derive(Debug, Serialize)]
struct ConfigurationRecord {
    #[serde(flatten)]
    placement: PlacementRecord,
    /// Relative residual of the six constraint equations.
    residual: f64,
}

impl ConfigurationRecord {
    fn of(c: &Configuration) -> ConfigurationRecord {
        ConfigurationRecord { placement: PlacementRecord::of(c), residual: c.residual }
    }
}

/// The pattern method's result: its position, or why it failed.
#[derive(Debug, Serialize)]
#[serde(untagged)]
enum PatternRecord {
    Solved {
        #[serde(flatten)]
        placement: PlacementRecord,
        /// |R3 − O3A3|, scene units (the method's own measure).
        residual: f64,
        /// Relative residual of the six constraint equations.
        relative_residual: f64,
        iterations: usize,
        evaluations: usize,
        phi1_start_deg: f64,
    },
    Failed {
        error: String,
        phi1_start_deg: f64,
    },
}

/// Newton–Raphson's result: its position, or why it failed.
#[derive(Debug, Serialize)]
#[serde(untagged)]
enum NewtonRecord {
    Solved {
        #[serde(flatten)]
        configuration: ConfigurationRecord,
        iterations: usize,
        start_deg: [f64; 3],
    },
    Failed {
        error: String,
        start_deg: [f64; 3],
    },
}

/// How many assembly modes of each orientation.
#[derive(Debug, Serialize)]
struct ModeCount {
    ccw: usize,
    cw: usize,
    collinear: usize,
    total: usize,
}

/// The triad's JSON summary (docs/triad.md).
#[derive(Debug, Serialize)]
struct Summary<'a> {
    kind: &'static str,
    name: &'a str,
    units: &'static str,
    pattern: PatternRecord,
    newton: NewtonRecord,
    solutions: Vec<ConfigurationRecord>,
    modes: ModeCount,
    primary: usize,
}

/// The JSON summary of the results.
pub fn summary(scene: &TriadScene, r: &TriadResults) -> Result<serde_json::Value, Error> {
    let phi1_start_deg = deg(scene.pattern.phi1_start);
    let pattern = match &r.pattern {
        Ok(p) => PatternRecord::Solved {
            placement: PlacementRecord::of(&p.configuration),
            residual: p.residual,
            relative_residual: p.configuration.residual,
            iterations: p.iterations,
            evaluations: p.evaluations,
            phi1_start_deg,
        },
        Err(e) => PatternRecord::Failed { error: e.to_string(), phi1_start_deg },
    };
    let start_deg = r.newton_start.map(deg);
    let newton = match &r.newton {
        Ok(n) => NewtonRecord::Solved {
            configuration: ConfigurationRecord::of(&n.configuration),
            iterations: n.iterations,
            start_deg,
        },
        Err(e) => NewtonRecord::Failed { error: e.to_string(), start_deg },
    };
    let count = |o: Orientation| r.modes.iter().filter(|c| c.orientation == o).count();
    let s = Summary {
        kind: "triad",
        name: &scene.name,
        units: scene.units.length(),
        pattern,
        newton,
        solutions: r.modes.iter().map(ConfigurationRecord::of).collect(),
        modes: ModeCount {
            ccw: count(Orientation::Ccw),
            cw: count(Orientation::Cw),
            collinear: count(Orientation::Collinear),
            total: r.modes.len(),
        },
        primary: r.primary,
    };
    products::summary_value(&s, &scene.name)
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

/// The model's length unit, for the drawing.
fn model_units(scene: &TriadScene) -> ModelUnits {
    match scene.units {
        Units::Mm => ModelUnits::MM,
        Units::Si => ModelUnits::SI,
    }
}

/// The seed's Fig. 3 of the results: the drawn mode alone with the pattern method's start.
pub fn figure(scene: &TriadScene, r: &TriadResults) -> crate::draw::Drawing {
    let mut caption = Vec::new();
    let start_deg = deg(scene.pattern.phi1_start);
    let n = r.modes.len();
    // The pattern method's run, then what is drawn solid and why; marked up with `_` before
    // a subscript (φ_1: Label::marked).
    let pattern = match &r.pattern {
        Ok(p) => format!(
            "Pattern method: φ_1 = {start_deg:.2}° (dashed, red) → {:.2}°{}",
            deg(p.configuration.phi[0]),
            match r.reached {
                Some(_) => format!(" in {} iterations", p.iterations),
                None => ", not among the modes searched".to_string(),
            }
        ),
        Err(_) => format!("Pattern method failed from φ_1 = {start_deg:.2}°"),
    };
    let drawn = r.primary + 1;
    match (scene.mode, r.reached, &r.pattern) {
        (Some(m), Some(i), _) => {
            caption.push(format!("{pattern} (mode {}).", i + 1));
            caption.push(format!("Solid: mode {m} of {n}, chosen by the scene's mode = {m}."));
        }
        (Some(m), None, _) => {
            caption.push(format!("{pattern}."));
            caption.push(format!("Solid: mode {m} of {n}, chosen by the scene's mode = {m}."));
        }
        (None, Some(_), _) => caption.push(format!("{pattern} (solid: mode {drawn} of {n}).")),
        (None, None, Ok(_)) => {
            caption.push(format!("{pattern}; drawn: mode {drawn} of {n}, the nearest to the start."))
        }
        (None, None, Err(_)) => caption.push(format!("{pattern}; drawn: mode {drawn} of {n}.")),
    }
    if r.modes.len() > 1 {
        caption.push(format!("All {} assembly modes are drawn on the modes sheet.", r.modes.len()));
    }
    let caption: Vec<Label> = caption.iter().map(|line| Label::marked(line)).collect();
    drawing(&TriadFigure {
        triad: &r.triad,
        exact: &r.modes[r.primary],
        approximate: r.start,
        units: model_units(scene),
        caption: &caption,
    })
}

/// Every assembly mode as small multiples, the drawn one marked.
pub fn modes_figure(scene: &TriadScene, r: &TriadResults) -> crate::draw::Drawing {
    let by_sense: Vec<String> = [Orientation::Ccw, Orientation::Cw, Orientation::Collinear]
        .into_iter()
        .map(|o| (o, r.modes.iter().filter(|c| c.orientation == o).count()))
        .filter(|(_, n)| *n > 0)
        .map(|(o, n)| format!("{n} {}", orientation_text(o)))
        .collect();
    // The scene's name as the user wrote it; φ_1, φ_2, φ_3 with their subscripts.
    // Three short lines, so that the title fits a page turned either way.
    let title = [
        Label::from(scene.name.as_str()).then(&format!(": {} assembly modes ({})", r.modes.len(), by_sense.join(", "))),
        Label::from(format!("The sense is that of A1 → A2 → A3. Fig. 3 draws mode {}.", r.primary + 1).as_str()),
        Label::marked("φ_1, φ_2, φ_3: directions O1 → A1, O2 → A2, O3 → A3 from +x."),
    ];
    modes_sheet(&ModesSheet {
        triad: &r.triad,
        modes: &r.modes,
        drawn: r.primary,
        title: &title,
        units: model_units(scene),
    })
}

pub(super) fn products(scene: &TriadScene, file: &str) -> Result<Products, Error> {
    let results = solve(scene).map_err(|e| solve_err(file)(e.into()))?;
    let mut extras = products::Extras {
        sheets: vec![Sheet { suffix: "modes".into(), drawing: modes_figure(scene, &results) }],
        summary: summary(scene, &results)?,
        report: report(scene, &results),
        ..Default::default()
    };
    let mut warnings = results.warnings.clone();
    if let Some(study) = super::tolerance::triad(scene, &results.triad, &results.modes, None) {
        warnings.extend(study.add_to(&mut extras));
    }
    Ok(Products {
        name: scene.name.clone(),
        mm_per_unit: super::mm_per_unit(scene.units),
        picture: Picture::Still(figure(scene, &results)),
        positions: None,
        sheets: extras.sheets,
        pages: Vec::new(),
        diagrams: extras.diagrams,
        tables: extras.tables,
        texts: Vec::new(),
        summary: extras.summary,
        report: extras.report,
        warnings,
        derived: Vec::new(),
        frame_scales: Vec::new(),
    })
}
