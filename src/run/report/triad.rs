//! A triad scene's report (seed 000): the title page; the structural analysis (the 6R
//! triad with its pivots fixed is a structure, M = 3·4 − 2·6 = 0: one class III Assur group
//! of order 3); the pattern method as the seed draws it (the start position dashed, the
//! solution solid, the angles dimensioned) with its iterations; every assembly mode.

use super::{Frame, Gathered, Part};
use crate::Error;
use crate::figure::linkage::LinkageFigure;
use crate::figure::report::compose::{self, Block};
use crate::figure::report::sketch::Sketch;
use crate::figure::report::structure::{self as structure_page, StructurePage};
use crate::figure::report::table::{Align, PaperTable};
use crate::figure::shared::labels::Label;
use crate::geom::{Vector, deg, rotate};
use crate::run::triad as run;
use crate::scene::triad::TriadScene;
use crate::solve::linkage::{Anchor, Attach, Body, Joint, JointKind, Mechanism, Structure};
use crate::solve::triad::{Configuration, Triad};

/// The triad as a linkage in configuration `c`: links O1A1, O2A2, O3A3 (bodies 1–3) and
/// the triangle A1A2A3 (body 4, its A3 on the side `c` puts it), its pivots on the frame;
/// with the coordinates of `c`.
fn mechanism(t: &Triad, c: &Configuration) -> (Mechanism, Vec<f64>) {
    let v = Vector::new;
    let turn = libm::atan2((c.a[1] - c.a[0]).y, (c.a[1] - c.a[0]).x);
    let a3 = rotate(c.a[2] - c.a[0], -turn);
    let link = |i: usize| Body {
        name: format!("link{}", i + 1),
        points: vec![(format!("O{}", i + 1), v(0.0, 0.0)), (format!("A{}", i + 1), v(t.r[i], 0.0))],
        at: t.o[i],
        angle: c.phi[i],
    };
    let triangle = Body {
        name: "triangle".into(),
        points: vec![("A1".into(), v(0.0, 0.0)), ("A2".into(), v(t.l12, 0.0)), ("A3".into(), a3)],
        at: c.a[0],
        angle: turn,
    };
    let anchor = |body: Attach, local: Vector| Anchor { body, local };
    let mut joints = Vec::new();
    for i in 0..3 {
        joints.push(Joint {
            name: format!("O{}", i + 1),
            kind: JointKind::Revolute {
                a: anchor(Attach::Ground, t.o[i].coords),
                b: anchor(Attach::Body(i), v(0.0, 0.0)),
            },
        });
    }
    let pins = [v(0.0, 0.0), v(t.l12, 0.0), a3];
    for (i, pin) in pins.iter().enumerate() {
        joints.push(Joint {
            name: format!("A{}", i + 1),
            kind: JointKind::Revolute { a: anchor(Attach::Body(i), v(t.r[i], 0.0)), b: anchor(Attach::Body(3), *pin) },
        });
    }
    let mech = Mechanism {
        bodies: vec![link(0), link(1), link(2), triangle],
        joints,
        drivers: Vec::new(),
        length_scale: t.scale(),
    };
    let q = mech.bodies.iter().flat_map(|b| [b.at.x, b.at.y, b.angle]).collect();
    (mech, q)
}

/// The triad's mechanism as drawn: its points named O1 … A3.
fn sketch(mech: &Mechanism) -> Sketch {
    let name_of = |a: Anchor| -> Option<&str> {
        match a.body {
            Attach::Ground => None,
            Attach::Body(b) => mech.bodies[b].points.iter().find(|(_, p)| *p == a.local).map(|(n, _)| n.as_str()),
        }
    };
    let figure = LinkageFigure::new(mech, name_of, Vec::new());
    Sketch { figure, names: mech.bodies.iter().map(|b| b.name.clone()).collect(), driver: None, loads: Vec::new() }
}

/// The title page's data.
fn data(scene: &TriadScene) -> PaperTable {
    let u = scene.units.length();
    let num = crate::report::number;
    let mut t = PaperTable::new(&["quantity", "value", "unit"], &[Align::Left, Align::Right, Align::Left]);
    for i in 0..3 {
        let o = scene.o[i];
        t.row(vec![format!("pivot O{}", i + 1), format!("({}, {})", num(o.x), num(o.y)), u.into()]);
    }
    // The quantities' names marked up with `_` before a subscript (R_1, l_12, φ_1: drawn
    // with their subscripts); the points' names flat (O1A1).
    let mut row = |q: &str, v: String, unit: &str| t.row(vec![Label::marked(q), v.into(), unit.into()]);
    for i in 0..3 {
        row(&format!("R_{} = O{}A{}", i + 1, i + 1, i + 1), num(scene.r[i]), u);
    }
    for (q, v) in [("l_12 = A1A2", scene.l12), ("l_23 = A2A3", scene.l23), ("l_13 = A1A3", scene.l13)] {
        row(q, num(v), u);
    }
    let p = &scene.pattern;
    row("pattern: start φ_1", num(deg(p.phi1_start)), "°");
    row("pattern: first step Δφ", num(deg(p.step)), "°");
    row("pattern: ε on |R_3 − A3O3|", num(p.tol), u);
    t
}

/// The parts of a triad's report.
pub(super) fn gather<'a>(scene: &'a TriadScene, file: &str, frame: Frame) -> Result<Gathered<'a>, Error> {
    let results = run::solve(scene).map_err(|e| Error::Solve { file: file.to_string(), source: e.into() })?;
    let primary = results.modes[results.primary];
    let (mech, q) = mechanism(&results.triad, &primary);
    let structure = Structure::of(&mech, Some(&q));
    let fig = run::figure(scene, &results);
    let unit = scene.units.length();
    let mut iterations = PaperTable::new(
        &[Label::from("step"), Label::marked("φ_1 [°]"), Label::marked(&format!("|R_3 − A3O3| [{unit}]"))],
        &[Align::Left, Align::Right, Align::Right],
    );
    let mut result_lines = Vec::new();
    match &results.pattern {
        Ok(p) => {
            for (k, (phi, r)) in p.history.iter().enumerate() {
                iterations.row(vec![
                    if k == 0 { "start".into() } else { k.to_string() },
                    format!("{:.6}", deg(*phi)),
                    crate::figure::report::page::scientific(*r, 4),
                ]);
            }
            let [a, b, c] = p.configuration.phi_deg();
            result_lines.push(format!("φ1 = {a:.4}°, φ2 = {b:.4}°, φ3 = {c:.4}° in {} secant updates", p.iterations));
            result_lines.push(format!(
                "({} constructions I–IV; |R3 − A3O3| = {} {unit} < ε)",
                p.evaluations,
                crate::figure::report::page::scientific(p.residual, 3)
            ));
            result_lines.push("The seed: from φ1 = 90° it converges to φ1 = 75.77°.".into());
        }
        Err(e) => result_lines.push(format!("The pattern method failed: {e}")),
    }
    if let Ok(n) = &results.newton {
        let [a, b, c] = n.configuration.phi_deg();
        result_lines.push(format!("Newton–Raphson, the independent route: φ = ({a:.4}°, {b:.4}°, {c:.4}°)"));
    }
    let modes: Vec<(String, Mechanism, Vec<f64>)> = results
        .modes
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let [a, b, cc] = c.phi_deg();
            let (m, q) = mechanism(&results.triad, c);
            (format!("Mode {} · {} · φ1 {:.2}° φ2 {:.2}° φ3 {:.2}°", i + 1, c.orientation.name(), a, b, cc), m, q)
        })
        .collect();
    let owned = std::sync::Arc::new((frame, mech, q, structure, fig, iterations, result_lines, modes));
    let mut parts: Vec<Part<'a>> = Vec::new();
    parts.push(super::title_part(
        owned.0.clone(),
        "The 6R triad by the pattern method".into(),
        format!("triad {} (seed 000)", scene.name),
        data(scene),
    ));
    let o = owned.clone();
    parts.push(Part {
        title: "Structural analysis".into(),
        stem: "structure".into(),
        pages: 1,
        draw: Box::new(move |n| {
            let (frame, mech, q, structure, ..) = &*o;
            let sk = sketch(mech);
            let motion = [q.as_slice()];
            let p = StructurePage { sketch: &sk, mechanism: mech, structure, q, motion: &motion, unit };
            Ok(vec![structure_page::page(&frame.frame, &frame.title("2  Structural analysis", n.first, n.total), &p)])
        }),
    });
    let o = owned.clone();
    parts.push(Part {
        title: "The pattern method".into(),
        stem: "pattern".into(),
        pages: 1,
        draw: Box::new(move |n| {
            let (frame, _, _, _, fig, iterations, lines, _) = &*o;
            let blocks = vec![
                ("Iterations (eq. 2: the secant on φ1)".to_string(), Block::Table(iterations.clone())),
                ("Result".to_string(), Block::Lines(lines.clone())),
            ];
            let title = frame.title("3  The pattern method", n.first, n.total);
            Ok(vec![compose::figure_page(
                &frame.frame,
                &title,
                fig,
                "The pattern method (seed 000, Fig. 3)",
                &blocks,
                0.72,
            )])
        }),
    });
    let o = owned.clone();
    parts.push(Part {
        title: "Assembly modes".into(),
        stem: "modes".into(),
        pages: 1,
        draw: Box::new(move |n| {
            let (frame, .., modes) = &*o;
            let sketches: Vec<Sketch> = modes.iter().map(|(_, m, _)| sketch(m)).collect();
            let positions: Vec<(String, &Sketch, Vec<f64>)> =
                modes.iter().zip(&sketches).map(|((c, _, q), s)| (c.clone(), s, q.clone())).collect();
            let title = frame.title("4  Assembly modes", n.first, n.total);
            Ok(vec![compose::positions_page(&frame.frame, &title, &positions, unit)])
        }),
    });
    let summary = serde_json::json!({
        "kind": "triad",
        "mobility": owned.3.mobility.formula,
        "groups": owned.3.groups.iter().map(|g| serde_json::json!({"kind": g.group.kind_name(), "class": g.class, "order": g.order})).collect::<Vec<_>>(),
        "modes": results.modes.len(),
    });
    Ok(Gathered { parts, table: None, summary, warnings: results.warnings.clone() })
}
