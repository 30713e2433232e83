//! The four-bar pipeline: solve the motion, draw every position (mechanism and the
//! polygons the scene's `outputs` ask for), and write the DXF with one layer per position,
//! one SVG frame per position, the HTML viewer, the diagrams, the CSV and the JSON summary.
//! The output formats are documented in docs/fourbar-output.md.

use rayon::prelude::*;
use serde_json::{Value, json};

use super::output::Output;
use super::{Outcome, RunOptions, solve_err};
use crate::Error;
use crate::draw::svg::{self, SvgOptions};
use crate::draw::{Drawing, raster, viewer};
use crate::figure::fourbar::{Layout, ModelUnits, Show, angle_text};
use crate::figure::plot::{self, Diagram, Series};
use crate::geom::{Point, Vector, deg};
use crate::report::{self, Csv};
use crate::scene::Units;
use crate::scene::fourbar::FourbarScene;
use crate::solve::fourbar::{Motion, Position, solve_motion};
use crate::solve::kinetostatics::Forces;

/// Width of the SVG frames and of the diagrams' PNG copies, pixels.
const FRAME_WIDTH_PX: u32 = 1000;
/// Width of the PNG copies of the diagrams, pixels.
const DIAGRAM_PNG_WIDTH_PX: u32 = 1000;
/// A jump of more than this many sweep steps between consecutive solved positions is a
/// gap (skipped angles): curves break there.
const GAP_STEPS: f64 = 1.5;

pub(super) fn run(scene: &FourbarScene, file: &str, opts: &RunOptions) -> Result<Outcome, Error> {
    let spec = &scene.spec;
    let motion = solve_motion(spec).map_err(|e| solve_err(file)(e.into()))?;
    let units = match scene.units {
        Units::Si => ModelUnits::SI,
        Units::Mm => ModelUnits::MM,
    };
    let show = Show {
        velocity: spec.outputs.velocity,
        acceleration: spec.outputs.acceleration,
        forces: spec.outputs.forces && !motion.forces.is_empty(),
    };
    let forces = if show.forces { Some(motion.forces.as_slice()) } else { None };
    let layout = Layout::new(&spec.geometry, &motion.positions, forces, show, units);
    let table = Table::new(
        &motion,
        spec.outputs.velocity || spec.outputs.forces,
        spec.outputs.acceleration || spec.outputs.forces,
        show.forces,
        units,
    );
    let summary = summary(scene, &motion, &layout, &table);
    let mut warnings = motion.warnings();
    if motion.positions.is_empty() {
        warnings.push("no crank angle of the sweep could be assembled: nothing to draw".to_string());
    }
    let report = report_text(scene, &motion, &layout);

    let Some(dir) = &opts.out_dir else {
        return Ok(Outcome { summary, report, warnings, written: Vec::new() });
    };
    super::check_drawn(file, "phi1_deg.step", motion.positions.len(), "use a larger step")?;
    let mut out = Output::new(dir)?;
    let name = &scene.name;
    let step = spec.sweep.step_deg;
    let geom = &spec.geometry;
    let mut curve = runs(&motion.positions, step, |p| p.m);
    close_full_turn(&mut curve, &motion.positions, step);
    let base = layout.base(geom, &curve);
    let names = position_names(&motion.positions, spec.sweep.from_deg, step);

    // Each position drawn once (in parallel), for the DXF layer and the frame.
    let moving: Vec<Drawing> = motion
        .positions
        .par_iter()
        .enumerate()
        .map(|(i, p)| layout.moving(geom, p, motion.forces.get(i).filter(|_| show.forces)))
        .collect();
    let svg_opts = SvgOptions { width_px: FRAME_WIDTH_PX, window: Some(layout.window), ..SvgOptions::default() };

    // The DXF (every position on its own layer) is built on one core while the frames,
    // the viewer and the diagrams are built on the others; the frame files are staged
    // (written) while the diagrams and the viewer are built.
    let want_frames = !opts.no_frames;
    let out_ref = &out;
    let (dxf, (frames, staged, html, rendered)) = rayon::join(
        || {
            dxf_bytes(
                &layout.animation(&base, names.iter().map(String::as_str).zip(&moving)),
                name,
                &opts.dxf_for(scene.units),
            )
        },
        || {
            let frames = if want_frames {
                frame_svgs(&layout, &base, &moving, &motion.positions, &svg_opts, opts.progress)
            } else {
                Vec::new()
            };
            let frame_files: Vec<(std::path::PathBuf, &[u8])> = frames
                .iter()
                .zip(&names)
                .map(|(f, n)| (format!("frames/{name}/{}.svg", n.to_lowercase()).into(), f.svg.as_bytes()))
                .collect();
            let (staged, (rendered, html)) = rayon::join(
                || out_ref.stage(&frame_files),
                || {
                    let diagrams = diagrams(&motion, step, show.forces, &spec.outputs, units);
                    let rendered: Result<Vec<RenderedDiagram>, Error> = diagrams
                        .par_iter()
                        .map(|(file, d)| {
                            let s = svg::to_string(&plot::diagram(d), &SvgOptions::default());
                            let png = if opts.png { Some(raster::to_png(&s, DIAGRAM_PNG_WIDTH_PX)) } else { None };
                            png.transpose().map(|png| (file.clone(), s, png)).map_err(|e| Error::Export {
                                what: format!("diagrams/{name}/{file}.png"),
                                message: e.to_string(),
                            })
                        })
                        .collect();
                    let html = want_frames.then(|| {
                        let title = format!("{name}: four-bar, {} positions", frames.len());
                        viewer::html(&title, &frames)
                    });
                    (rendered, html)
                },
            );
            (frames, staged, html, rendered)
        },
    );
    out.write(format!("{name}.dxf"), dxf?)?;

    // The first position as the scene's picture.
    let picture = match (frames.first(), moving.first()) {
        (Some(f), _) => f.svg.clone(),
        (None, Some(first)) => svg::to_string(&layout.frame(&base, first), &svg_opts),
        (None, None) => svg::to_string(&base, &svg_opts),
    };
    out.write(format!("{name}.svg"), picture)?;
    out.write(format!("{name}.csv"), table.csv.to_bytes())?;
    let json_text = serde_json::to_string_pretty(&summary)
        .map_err(|e| Error::Export { what: format!("{name}.json"), message: e.to_string() })?;
    out.write(format!("{name}.json"), json_text)?;
    for (file, s, png) in rendered? {
        out.write(format!("diagrams/{name}/{file}.svg"), s)?;
        if let Some(png) = png {
            out.write(format!("diagrams/{name}/{file}.png"), png)?;
        }
    }
    out.record(staged?);
    if let Some(html) = html {
        out.write(format!("{name}.html"), html)?;
    }
    let written = out.commit()?;
    Ok(Outcome { summary, report, warnings, written })
}

/// A diagram's file stem, its SVG and (with `--png`) its PNG.
type RenderedDiagram = (String, String, Option<Vec<u8>>);

/// The DXF of the whole motion.
fn dxf_bytes(d: &Drawing, name: &str, opts: &crate::draw::dxf::DxfOptions) -> Result<Vec<u8>, Error> {
    crate::draw::dxf::to_bytes(d, opts)
        .map_err(|e| Error::Export { what: format!("{name}.dxf"), message: e.to_string() })
}

/// The SVG frames (in parallel), with the progress bar when asked for.
fn frame_svgs(
    layout: &Layout,
    base: &Drawing,
    moving: &[Drawing],
    positions: &[Position],
    svg_opts: &SvgOptions,
    progress: bool,
) -> Vec<viewer::Frame> {
    let bar = progress_bar(progress, moving.len());
    // The shared part is written once; each frame is its moving part appended to it.
    let base_svg = svg::to_string(base, svg_opts);
    let frames: Vec<viewer::Frame> = moving
        .par_iter()
        .zip(positions.par_iter())
        .map(|(m, p)| {
            let s = svg::splice(&base_svg, &svg::to_string(m, svg_opts))
                .unwrap_or_else(|| svg::to_string(&layout.frame(base, m), svg_opts));
            if let Some(b) = &bar {
                b.inc(1);
            }
            viewer::Frame { label: format!("φ1 = {}°", angle_text(deg(p.phi1))), svg: s }
        })
        .collect();
    if let Some(b) = &bar {
        b.finish_and_clear();
    }
    frames
}

fn progress_bar(on: bool, n: usize) -> Option<indicatif::ProgressBar> {
    if !on || n == 0 {
        return None;
    }
    let bar = indicatif::ProgressBar::new(n as u64);
    if let Ok(style) = indicatif::ProgressStyle::with_template("frames {bar:40.cyan/blue} {pos}/{len} {elapsed}") {
        bar.set_style(style);
    }
    Some(bar)
}

/// Layer (and frame file) names: `POS_ddd` with the crank angle in whole degrees when every
/// solved angle is a distinct whole degree in 0…999, else `POS_kkk` with the index of the
/// angle in the sweep (3 digits at least).
fn position_names(positions: &[Position], from_deg: f64, step_deg: f64) -> Vec<String> {
    let degs: Vec<f64> = positions.iter().map(|p| deg(p.phi1)).collect();
    let whole = degs.iter().all(|d| (d - d.round()).abs() < 1e-6 && d.round() >= 0.0 && d.round() <= 999.0);
    let mut seen = std::collections::HashSet::new();
    if whole && degs.iter().all(|d| seen.insert(d.round() as i64)) {
        return degs.iter().map(|d| format!("POS_{:03}", d.round() as i64)).collect();
    }
    degs.iter().map(|d| format!("POS_{:03}", ((d - from_deg) / step_deg).round().max(0.0) as i64)).collect()
}

/// Runs of consecutive positions (no skipped angle between them), mapped by `f`.
fn runs<T>(positions: &[Position], step_deg: f64, f: impl Fn(&Position) -> T) -> Vec<Vec<T>> {
    let mut out: Vec<Vec<T>> = Vec::new();
    let mut prev: Option<f64> = None;
    for p in positions {
        let d = deg(p.phi1);
        if prev.is_none_or(|q| d - q > GAP_STEPS * step_deg) {
            out.push(Vec::new());
        }
        if let Some(run) = out.last_mut() {
            run.push(f(p));
        }
        prev = Some(d);
    }
    out
}

/// When the solved positions cover a whole turn without a gap (the last angle one step
/// short of the first plus 360°), the coupler curve closes: its last run joins its first.
fn close_full_turn(curve: &mut [Vec<Point>], positions: &[Position], step_deg: f64) {
    let (Some(first), Some(last)) = (positions.first(), positions.last()) else { return };
    let wrap = deg(first.phi1) + 360.0 - deg(last.phi1);
    if (wrap - step_deg).abs() > 1e-6 * step_deg.max(1.0) || wrap > GAP_STEPS * step_deg {
        return;
    }
    if let Some(start) = curve.first().and_then(|r| r.first()).copied()
        && let Some(end_run) = curve.last_mut()
    {
        end_run.push(start);
    }
}

/// One named column of the table: its CSV name and the value at a position.
type Getter = Box<dyn Fn(&Position, Option<&Forces>) -> f64 + Sync>;

/// The per-position quantities, one column each: the CSV, and the source of the JSON
/// records and the diagrams (so the three always agree).
struct Table {
    csv: Csv,
}

fn kin_of(p: &Position) -> crate::solve::fourbar::Kinematics {
    // Columns of kinematic quantities exist only when the motion has kinematics.
    p.kin.unwrap_or(crate::solve::fourbar::Kinematics {
        omega2: f64::NAN,
        omega3: f64::NAN,
        eps2: f64::NAN,
        eps3: f64::NAN,
        v_a: Vector::repeat(f64::NAN),
        v_b: Vector::repeat(f64::NAN),
        v_m: Vector::repeat(f64::NAN),
        v_ba: Vector::repeat(f64::NAN),
        a_a: Vector::repeat(f64::NAN),
        a_b: Vector::repeat(f64::NAN),
        a_m: Vector::repeat(f64::NAN),
        a_ba_n: Vector::repeat(f64::NAN),
        a_ba_t: Vector::repeat(f64::NAN),
        a_bc_n: Vector::repeat(f64::NAN),
        a_bc_t: Vector::repeat(f64::NAN),
        a_g1: Vector::repeat(f64::NAN),
        a_g21: Vector::repeat(f64::NAN),
        a_g22: Vector::repeat(f64::NAN),
        a_g3: Vector::repeat(f64::NAN),
    })
}

/// The columns, in CSV order.
fn columns(velocity: bool, acceleration: bool, forces: bool) -> Vec<(String, Getter)> {
    let mut c: Vec<(String, Getter)> = Vec::new();
    let mut col = |name: &str, g: Getter| c.push((name.to_string(), g));
    col("phi1_deg", Box::new(|p, _| deg(p.phi1)));
    for (n, f) in [("A", 0usize), ("B", 1), ("M", 2)] {
        let pt = move |p: &Position| -> Point { [p.a, p.b, p.m][f] };
        col(&format!("{n}_x"), Box::new(move |p, _| pt(p).x));
        col(&format!("{n}_y"), Box::new(move |p, _| pt(p).y));
    }
    col("phi2_deg", Box::new(|p, _| deg(p.phi2())));
    col("phi3_deg", Box::new(|p, _| deg(p.phi3())));
    col("transmission_deg", Box::new(|p, _| deg(p.transmission())));
    if velocity {
        col("omega2", Box::new(|p, _| kin_of(p).omega2));
        col("omega3", Box::new(|p, _| kin_of(p).omega3));
        type KV = fn(&crate::solve::fourbar::Kinematics) -> Vector;
        let vs: [(&str, KV); 4] = [("vA", |k| k.v_a), ("vB", |k| k.v_b), ("vM", |k| k.v_m), ("vBA", |k| k.v_ba)];
        for (n, f) in vs {
            col(&format!("{n}_x"), Box::new(move |p, _| f(&kin_of(p)).x));
            col(&format!("{n}_y"), Box::new(move |p, _| f(&kin_of(p)).y));
            col(&format!("{n}_mag"), Box::new(move |p, _| f(&kin_of(p)).norm()));
        }
    }
    if acceleration {
        col("eps2", Box::new(|p, _| kin_of(p).eps2));
        col("eps3", Box::new(|p, _| kin_of(p).eps3));
        type KV = fn(&crate::solve::fourbar::Kinematics) -> Vector;
        let acc: [(&str, KV); 11] = [
            ("aA", |k| k.a_a),
            ("aB", |k| k.a_b),
            ("aM", |k| k.a_m),
            ("aBA_n", |k| k.a_ba_n),
            ("aBA_t", |k| k.a_ba_t),
            ("aBC_n", |k| k.a_bc_n),
            ("aBC_t", |k| k.a_bc_t),
            ("aG1", |k| k.a_g1),
            ("aG21", |k| k.a_g21),
            ("aG22", |k| k.a_g22),
            ("aG3", |k| k.a_g3),
        ];
        for (n, f) in acc {
            col(&format!("{n}_x"), Box::new(move |p, _| f(&kin_of(p)).x));
            col(&format!("{n}_y"), Box::new(move |p, _| f(&kin_of(p)).y));
            if matches!(n, "aA" | "aB" | "aM") {
                col(&format!("{n}_mag"), Box::new(move |p, _| f(&kin_of(p)).norm()));
            }
        }
    }
    if forces {
        type FV = fn(&Forces) -> Vector;
        let fv: [(&str, FV); 17] = [
            ("R_A", |f| f.r_a),
            ("R_B", |f| f.r_b),
            ("R_C", |f| f.r_c),
            ("R_O", |f| f.r_o),
            ("R_An", |f| f.r_a_n),
            ("R_At", |f| f.r_a_t),
            ("R_Cn", |f| f.r_c_n),
            ("R_Ct", |f| f.r_c_t),
            ("Fi1", |f| f.fi1),
            ("Fi21", |f| f.fi21),
            ("Fi22", |f| f.fi22),
            ("Fi3", |f| f.fi3),
            ("F", |f| f.f_ext),
            ("G1", |f| f.g1),
            ("G21", |f| f.g21),
            ("G22", |f| f.g22),
            ("G3", |f| f.g3),
        ];
        for (n, g) in fv {
            col(&format!("{n}_x"), Box::new(move |_, f| f.map_or(f64::NAN, |f| g(f).x)));
            col(&format!("{n}_y"), Box::new(move |_, f| f.map_or(f64::NAN, |f| g(f).y)));
            if matches!(n, "R_A" | "R_B" | "R_C" | "R_O") {
                col(&format!("{n}_mag"), Box::new(move |_, f| f.map_or(f64::NAN, |f| g(f).norm())));
            }
        }
        type FS = fn(&Forces) -> f64;
        let fs: [(&str, FS); 5] =
            [("Mi1", |f| f.mi1), ("Mi21", |f| f.mi21), ("Mi22", |f| f.mi22), ("Mi3", |f| f.mi3), ("Me1", |f| f.me1)];
        for (n, g) in fs {
            col(n, Box::new(move |_, f| f.map_or(f64::NAN, g)));
        }
    }
    c
}

impl Table {
    fn new(motion: &Motion, velocity: bool, acceleration: bool, forces: bool, _units: ModelUnits) -> Table {
        let cols = columns(velocity, acceleration, forces);
        let mut csv = Csv::new(cols.iter().map(|(n, _)| n.clone()));
        for (i, p) in motion.positions.iter().enumerate() {
            let f = if forces { motion.forces.get(i) } else { None };
            csv.row(cols.iter().map(|(_, g)| g(p, f)));
        }
        Table { csv }
    }
}

/// The JSON record of one position (design.md §4 names; points and vectors as [x, y]).
fn position_record(p: &Position, f: Option<&Forces>, velocity: bool, acceleration: bool) -> Value {
    let mut r = json!({
        "phi1_deg": deg(p.phi1),
        "A": report::point(p.a),
        "B": report::point(p.b),
        "M": report::point(p.m),
        "phi2_deg": deg(p.phi2()),
        "phi3_deg": deg(p.phi3()),
        "transmission_deg": deg(p.transmission()),
    });
    let obj = r.as_object_mut().expect("json! object");
    if let Some(k) = &p.kin {
        if velocity {
            obj.insert("omega2".into(), json!(k.omega2));
            obj.insert("omega3".into(), json!(k.omega3));
            obj.insert("vA".into(), report::vector(k.v_a));
            obj.insert("vB".into(), report::vector(k.v_b));
            obj.insert("vM".into(), report::vector(k.v_m));
            obj.insert("vBA".into(), report::vector(k.v_ba));
        }
        if acceleration {
            obj.insert("eps2".into(), json!(k.eps2));
            obj.insert("eps3".into(), json!(k.eps3));
            obj.insert("aA".into(), report::vector(k.a_a));
            obj.insert("aB".into(), report::vector(k.a_b));
            obj.insert("aM".into(), report::vector(k.a_m));
        }
    }
    if let Some(f) = f {
        for (n, v) in [("R_A", f.r_a), ("R_B", f.r_b), ("R_C", f.r_c), ("R_O", f.r_o)] {
            obj.insert(n.into(), report::vector(v));
            obj.insert(format!("{n}_mag"), json!(v.norm()));
        }
        obj.insert("Me1".into(), json!(f.me1));
    }
    r
}

fn summary(scene: &FourbarScene, motion: &Motion, layout: &Layout, _table: &Table) -> Value {
    let spec = &scene.spec;
    let o = &spec.outputs;
    let forces = layout.show.forces;
    let positions: Vec<Value> = motion
        .positions
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let f = if forces { motion.forces.get(i) } else { None };
            position_record(p, f, o.velocity || o.forces, o.acceleration || o.forces)
        })
        .collect();
    let mut outputs = vec!["position"];
    if o.velocity {
        outputs.push("velocity");
    }
    if o.acceleration {
        outputs.push("acceleration");
    }
    if o.forces {
        outputs.push("forces");
    }
    let len = layout.units.length;
    let scale = |s: Option<(crate::figure::fourbar::Scale, Point)>, unit: String| {
        s.map(|(s, _)| json!({ "value": s.per_mm, "unit": unit })).unwrap_or(Value::Null)
    };
    json!({
        "kind": "fourbar",
        "name": scene.name,
        "units": len,
        "omega1": spec.omega1,
        "sweep": { "from_deg": spec.sweep.from_deg, "to_deg": spec.sweep.to_deg, "step_deg": spec.sweep.step_deg },
        "outputs": outputs,
        "grashof": motion.grashof,
        "solved": motion.positions.len(),
        "gaps": motion.gaps,
        "dead_points": motion.dead_points,
        "scales": {
            "k_v": scale(layout.velocity, format!("({len}/s)/mm")),
            "k_a": scale(layout.acceleration, format!("({len}/s²)/mm")),
            "k_f": scale(layout.forces, "N/mm".to_string()),
        },
        "positions": positions,
    })
}

fn report_text(scene: &FourbarScene, motion: &Motion, layout: &Layout) -> String {
    let mut s = format!("{}: four-bar, {} positions solved", scene.name, motion.positions.len());
    let skipped: usize = motion.gaps.iter().map(|g| g.skipped).sum();
    if skipped > 0 {
        s.push_str(&format!(", {skipped} skipped"));
    }
    for (n, sc, u) in [
        ("k_v", layout.velocity, format!("({}/s)/mm", layout.units.length)),
        ("k_a", layout.acceleration, format!("({}/s²)/mm", layout.units.length)),
        ("k_f", layout.forces, "N/mm".to_string()),
    ] {
        if let Some((sc, _)) = sc {
            s.push_str(&format!("; {n} = {} {u}", crate::figure::fourbar::scale_text(sc.per_mm)));
        }
    }
    s.push('\n');
    s
}

/// The diagrams (file stem, diagram) the scene's outputs ask for: angles always; angular
/// velocities and |vM| with velocities; angular accelerations and |aM| with accelerations;
/// |R_A|, |R_B|, |R_C|, |R_O| and Me1 with forces.
fn diagrams(
    motion: &Motion,
    step_deg: f64,
    forces: bool,
    o: &crate::solve::fourbar::Outputs,
    units: ModelUnits,
) -> Vec<(String, Diagram)> {
    let len = units.length;
    let moment = if len == "m" { "N·m".to_string() } else { format!("N·{len}") };
    let velocity = o.velocity || o.forces;
    let acceleration = o.acceleration || o.forces;
    type Q = Box<dyn Fn(&Position, Option<&Forces>) -> f64>;
    let mut list: Vec<(&str, String, String, Q)> = vec![
        ("phi2", "Coupler angle φ2".into(), "φ2 [°]".into(), Box::new(|p, _| deg(p.phi2()))),
        ("phi3", "Rocker angle φ3".into(), "φ3 [°]".into(), Box::new(|p, _| deg(p.phi3()))),
    ];
    if velocity {
        list.push((
            "omega2",
            "Angular velocity of the coupler ω2".into(),
            "ω2 [rad/s]".into(),
            Box::new(|p, _| kin_of(p).omega2),
        ));
        list.push((
            "omega3",
            "Angular velocity of the rocker ω3".into(),
            "ω3 [rad/s]".into(),
            Box::new(|p, _| kin_of(p).omega3),
        ));
        list.push((
            "vM",
            "Speed of the coupler point M".into(),
            format!("|vM| [{len}/s]"),
            Box::new(|p, _| kin_of(p).v_m.norm()),
        ));
    }
    if acceleration {
        list.push((
            "eps2",
            "Angular acceleration of the coupler ε2".into(),
            "ε2 [rad/s²]".into(),
            Box::new(|p, _| kin_of(p).eps2),
        ));
        list.push((
            "eps3",
            "Angular acceleration of the rocker ε3".into(),
            "ε3 [rad/s²]".into(),
            Box::new(|p, _| kin_of(p).eps3),
        ));
        list.push((
            "aM",
            "Acceleration of the coupler point M".into(),
            format!("|aM| [{len}/s²]"),
            Box::new(|p, _| kin_of(p).a_m.norm()),
        ));
    }
    if forces {
        let mag = |g: fn(&Forces) -> Vector| -> Q { Box::new(move |_, f| f.map_or(f64::NAN, |f| g(f).norm())) };
        list.push(("R_A", "Reaction in A (link 1 on link 2)".into(), "|R_A| [N]".into(), mag(|f| f.r_a)));
        list.push(("R_B", "Reaction in B (link 3 on link 2)".into(), "|R_B| [N]".into(), mag(|f| f.r_b)));
        list.push(("R_C", "Reaction in C (ground on link 3)".into(), "|R_C| [N]".into(), mag(|f| f.r_c)));
        list.push(("R_O", "Reaction in O1 (ground on link 1)".into(), "|R_O| [N]".into(), mag(|f| f.r_o)));
        list.push((
            "Me1",
            "Balancing moment on the crank (CCW positive)".into(),
            format!("Me1 [{moment}]"),
            Box::new(|_, f| f.map_or(f64::NAN, |f| f.me1)),
        ));
    }
    list.into_iter()
        .map(|(file, title, y_label, q)| {
            // NaN between runs breaks the curve over skipped angles.
            let mut x = Vec::with_capacity(motion.positions.len() + 4);
            let mut y = Vec::with_capacity(motion.positions.len() + 4);
            let mut prev: Option<f64> = None;
            for (i, p) in motion.positions.iter().enumerate() {
                let d = deg(p.phi1);
                if prev.is_some_and(|q| d - q > GAP_STEPS * step_deg) {
                    x.push(f64::NAN);
                    y.push(f64::NAN);
                }
                x.push(d);
                y.push(q(p, if forces { motion.forces.get(i) } else { None }));
                prev = Some(d);
            }
            let series = vec![Series { label: file.to_string(), x, y }];
            (file.to_string(), Diagram { title, x_label: "φ1 [°]".into(), y_label, series })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    #[test]
    fn spliced_frames_are_the_svg_writers_output_for_the_whole_frame() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("templates/fourbar-chebyshev.toml");
        let over: Vec<crate::scene::Override> = vec!["phi1_deg.step=45".parse().unwrap()];
        let loaded = crate::scene::load(&path, &over).unwrap();
        let Scene::Fourbar(scene) = &loaded.scene else { panic!("not a four-bar") };
        let motion = solve_motion(&scene.spec).unwrap();
        let show = Show { velocity: true, acceleration: true, forces: true };
        let geom = &scene.spec.geometry;
        let layout = Layout::new(geom, &motion.positions, Some(&motion.forces), show, ModelUnits::SI);
        let base = layout.base(geom, &runs(&motion.positions, 45.0, |p| p.m));
        let opts = SvgOptions { window: Some(layout.window), ..SvgOptions::default() };
        let base_svg = svg::to_string(&base, &opts);
        for (p, f) in motion.positions.iter().zip(&motion.forces) {
            let m = layout.moving(geom, p, Some(f));
            let whole = svg::to_string(&layout.frame(&base, &m), &opts);
            assert_eq!(svg::splice(&base_svg, &svg::to_string(&m, &opts)).as_deref(), Some(whole.as_str()));
        }
        // Different windows: no splice.
        let other = SvgOptions { width_px: 10, ..opts };
        assert!(svg::splice(&base_svg, &svg::to_string(&base, &other)).is_none());
    }
}
