//! A four-bar scene's report: the four-bar solved as `mechdraw run` solves it (seed 003's
//! dyad, its kineto-statics), drawn in the report as a linkage of three bodies (crank 1,
//! coupler 2 with its point M, rocker 3) so that its structure is the Assur decomposition's
//! (the crank with the frame, the RRR dyad 2–3); its dead positions are the rocker's
//! extremes, in closed form (crank and coupler in line: |O1B| = l_AB ± l1), with the
//! working angle, the rocker's swing ψ and K = (180° + θ)/(180° − θ).

use super::Frame;
use super::motion::{self, At, Chosen, Cycle, Dead, DriveAxis, MotionReport};
use crate::Error;
use crate::figure::fourbar::sheet::FourbarSheets;
use crate::figure::fourbar::{ModelUnits, Show};
use crate::figure::linkage::LinkageFigure;
use crate::figure::report::diagrams::MarkedDiagram;
use crate::figure::report::freebody::{self, Couple, FreeBodyPage, GroupLoads};
use crate::figure::report::plan::PlanDimension;
use crate::figure::report::sketch::{DriverMark, LoadMark, Sketch};
use crate::figure::report::table::{Align, PaperTable};
use crate::figure::shared::forces::NamedVector;
use crate::figure::shared::labels::Label;
use crate::figure::shared::plot::{self, Marks};
use crate::figure::shared::sheet;
use crate::geom::{self, Point, Vector, deg};
use crate::report::Csv;
use crate::run::fourbar::{self as run, Quantity};
use crate::scene::Units;
use crate::scene::fourbar::FourbarScene;
use crate::solve::expr::Expr;
use crate::solve::fourbar::kinetostatics::{CrankRange, Dynamics as FourbarDynamics, Link, loads};
use crate::solve::fourbar::{Forces, Geometry, Kinematics, Motion, MotionSpec, Position, position, solve_motion};
use crate::solve::linkage::{Anchor, Attach, Body, Driver, DriverTarget, Joint, JointKind, Mechanism, Structure};

/// The coupler point M in the coupler's frame (A at the origin, B on +x).
fn m_local(g: &Geometry) -> Vector {
    let dir = std::f64::consts::PI + g.alpha;
    Vector::new(g.l_ab + g.l_bm * libm::cos(dir), g.l_bm * libm::sin(dir))
}

/// The four-bar as a linkage: crank O1A, coupler A–B–M, rocker CB; joints O1, A, B, C; the
/// crank turned by its angle.
pub fn mechanism(g: &Geometry, omega1: f64) -> Mechanism {
    let v = Vector::new;
    let body = |name: &str, points: Vec<(&str, Vector)>, at: Point| Body {
        name: name.into(),
        points: points.into_iter().map(|(n, p)| (n.to_string(), p)).collect(),
        at,
        angle: 0.0,
    };
    let anchor = |body: Attach, local: Vector| Anchor { body, local };
    let pin = |name: &str, a: Anchor, b: Anchor| Joint { name: name.into(), kind: JointKind::Revolute { a, b } };
    let (crank, coupler, rocker) = (Attach::Body(0), Attach::Body(1), Attach::Body(2));
    let law = Expr::parse(&format!("{omega1}*t")).or_else(|_| Expr::parse("t"));
    let drivers =
        law.map(|law| vec![Driver { name: "O1".into(), target: DriverTarget::BodyAngle(0), law }]).unwrap_or_default();
    Mechanism {
        bodies: vec![
            body("crank", vec![("O1", v(0.0, 0.0)), ("A", v(g.l1, 0.0))], g.o1),
            body("coupler", vec![("A", v(0.0, 0.0)), ("B", v(g.l_ab, 0.0)), ("M", m_local(g))], g.o1),
            body("rocker", vec![("C", v(0.0, 0.0)), ("B", v(g.l_bc, 0.0))], g.c),
        ],
        joints: vec![
            pin("O1", anchor(Attach::Ground, g.o1.coords), anchor(crank, v(0.0, 0.0))),
            pin("A", anchor(crank, v(g.l1, 0.0)), anchor(coupler, v(0.0, 0.0))),
            pin("B", anchor(coupler, v(g.l_ab, 0.0)), anchor(rocker, v(g.l_bc, 0.0))),
            pin("C", anchor(Attach::Ground, g.c.coords), anchor(rocker, v(0.0, 0.0))),
        ],
        drivers,
        length_scale: g.l1.max(g.l_ab).max(g.l_bc).max(g.ground()),
    }
}

/// What acts on each group of the four-bar (the crank with its driver; the dyad 2–3) from
/// outside it at position `p`, from the seed's route ([`Forces`]) and the applied loads
/// ([`loads`]): the reactions named as the force polygons name them (R_O and −R_A on the
/// crank; R_A and R_C on the dyad), the inertia forces and weights at the bars' centroids,
/// the external forces at their points, the couples in N·(length unit).
pub fn group_loads(
    g: &Geometry,
    p: &Position,
    kin: &Kinematics,
    f: &Forces,
    d: &FourbarDynamics,
    structure: &Structure,
) -> Vec<GroupLoads> {
    let l = loads(g, p, kin, d);
    let nv = |name: &str, v: Vector| NamedVector::new(name, v);
    let couple = |at: Point, name: &str, value: f64| Couple { at, name: name.into(), value, quantity: true };
    let phi1_deg = deg(p.phi1);
    let acting = |r: Option<CrankRange>| r.is_none_or(|r| r.contains_deg(phi1_deg));
    let mut crank = GroupLoads {
        forces: vec![
            (g.o1, nv("RO", f.r_o)),
            (p.a, nv("−RA", -f.r_a)),
            (l.g1_at, nv("Fi1", l.fi1)),
            (l.g1_at, nv("G1", l.w1)),
        ],
        couples: vec![couple(g.o1, "Me1", f.me1), couple(l.g1_at, "Mi1", l.mi1)],
    };
    let mut dyad = GroupLoads {
        forces: vec![
            (p.a, nv("RA", f.r_a)),
            (g.c, nv("RC", f.r_c)),
            (l.g21_at, nv("Fi21", l.fi21)),
            (l.g21_at, nv("G21", l.w21)),
            (l.g22_at, nv("Fi22", l.fi22)),
            (l.g22_at, nv("G22", l.w22)),
            (l.g3_at, nv("Fi3", l.fi3)),
            (l.g3_at, nv("G3", l.w3)),
        ],
        couples: vec![
            couple(l.g21_at, "Mi21", l.mi21),
            couple(l.g22_at, "Mi22", l.mi22),
            couple(l.g3_at, "Mi3", l.mi3),
        ],
    };
    for e in d.forces.iter().filter(|e| acting(e.range)) {
        dyad.forces.push((e.at.at(p), nv("F", e.value)));
    }
    for load in d.loads.iter().filter(|x| acting(x.range)) {
        let (start, _) = load.link.ends(g, p);
        let at = start + load.link.to_world(g, p, load.at);
        let (n, group) = match load.link {
            Link::Crank => (1, &mut crank),
            Link::Ab | Link::Bm => (2, &mut dyad),
            Link::Rocker => (3, &mut dyad),
        };
        if load.force != Vector::zeros() {
            group.forces.push((at, nv(&format!("F{n}"), load.force)));
        }
        if load.torque != 0.0 {
            group.couples.push(couple(at, &format!("M{n}"), load.torque / d.length_unit_m));
        }
    }
    structure.groups.iter().map(|s| if s.group.bodies == [0] { crank.clone() } else { dyad.clone() }).collect()
}

/// A position's coordinates as the linkage's (x, y, φ of crank, coupler, rocker).
pub fn coordinates(g: &Geometry, p: &Position) -> Vec<f64> {
    vec![g.o1.x, g.o1.y, p.phi1, p.a.x, p.a.y, p.phi2(), g.c.x, g.c.y, p.phi3()]
}

/// The four-bar's mechanism as the report draws it: names O1, A, B, M, C, the path of M,
/// ω1 with its sense, the coupler's loads.
fn sketch(scene: &FourbarScene, mech: &Mechanism) -> Sketch {
    let g = &scene.spec.geometry;
    let m = m_local(g);
    let name_of = |a: Anchor| -> Option<&'static str> {
        match a.body {
            Attach::Ground if a.local == g.o1.coords => Some("O1"),
            Attach::Ground => Some("C"),
            Attach::Body(0) if a.local == Vector::zeros() => Some("O1"),
            Attach::Body(0) => Some("A"),
            Attach::Body(1) if a.local == Vector::zeros() => Some("A"),
            Attach::Body(1) if a.local == m => Some("M"),
            Attach::Body(1) => Some("B"),
            Attach::Body(_) if a.local == Vector::zeros() => Some("C"),
            Attach::Body(_) => Some("B"),
        }
    };
    let units = match scene.units {
        Units::Si => ModelUnits::SI,
        Units::Mm => ModelUnits::MM,
    };
    let figure = LinkageFigure::new(mech, name_of, vec![Anchor { body: Attach::Body(1), local: m }]).with_units(units);
    let driver = Some(DriverMark {
        body: 0,
        pivot: Anchor { body: Attach::Body(0), local: Vector::zeros() },
        sense: if scene.spec.omega1 < 0.0 { -1.0 } else { 1.0 },
        symbol: "ω1".into(),
    });
    let local = |p: crate::solve::fourbar::ForcePoint| match p {
        crate::solve::fourbar::ForcePoint::A => Vector::zeros(),
        crate::solve::fourbar::ForcePoint::B => Vector::new(g.l_ab, 0.0),
        crate::solve::fourbar::ForcePoint::M => m,
    };
    let loads = scene
        .spec
        .dynamics
        .iter()
        .flat_map(|d| d.forces.iter())
        .map(|f| LoadMark {
            at: Anchor { body: Attach::Body(1), local: local(f.at) },
            direction: f.value,
            name: "F".into(),
        })
        .collect();
    Sketch { figure, names: mech.bodies.iter().map(|b| b.name.clone()).collect(), driver, loads }
}

/// The rocker's extremes: (crank angle, B) with crank and coupler stretched (|O1B| = l1 +
/// l_AB) and folded (|O1B| = l_AB − l1) on the scene's branch, when the four-bar reaches
/// them.
fn rocker_extremes(g: &Geometry) -> Vec<(f64, &'static str)> {
    let d = g.c - g.o1;
    let (dn, theta) = (d.norm(), geom::angle_of(d));
    let size = g.l1.max(g.l_ab).max(g.l_bc).max(dn);
    let mut out = Vec::new();
    for (sign, r, what) in
        [(1.0, g.l1 + g.l_ab, "crank and coupler stretched"), (-1.0, g.l_ab - g.l1, "crank and coupler folded")]
    {
        if r <= 0.0 {
            continue;
        }
        let cos = (dn * dn + r * r - g.l_bc * g.l_bc) / (2.0 * dn * r);
        if cos.abs() > 1.0 {
            continue;
        }
        let beta = libm::acos(cos);
        for b_dir in [theta + beta, theta - beta] {
            let u = Vector::new(libm::cos(b_dir), libm::sin(b_dir));
            let phi1 = geom::angle_of(u * sign);
            let Ok(p) = position(g, phi1, g.branch) else { continue };
            if (p.b - (g.o1 + u * r)).norm() <= 1e-9 * size {
                out.push((phi1, what));
                break;
            }
        }
    }
    out
}

/// An angle in degrees taken into [from, from + 360).
fn into_sweep(phi_deg: f64, from: f64) -> f64 {
    from + (phi_deg - from).rem_euclid(360.0)
}

/// The title page's data.
fn data(scene: &FourbarScene) -> PaperTable {
    let s = &scene.spec;
    let g = &s.geometry;
    let u = scene.units.length();
    let num = crate::report::number;
    let mut t = PaperTable::new(&["quantity", "value", "unit"], &[Align::Left, Align::Right, Align::Left]);
    let pt = |p: Point| format!("({}, {})", num(p.x), num(p.y));
    // The quantities' names marked up with `_` before a subscript (l_1, ω_1, m_21: drawn
    // with their subscripts); the points' names flat (O1A).
    let row = |t: &mut PaperTable, q: &str, v: String, unit: &str| t.row(vec![Label::marked(q), v.into(), unit.into()]);
    for (q, v, unit) in [
        ("crank pivot O1", pt(g.o1), u),
        ("rocker pivot C", pt(g.c), u),
        ("crank O1A = l_1", num(g.l1), u),
        ("coupler AB", num(g.l_ab), u),
        ("coupler BM", num(g.l_bm), u),
        ("angle ABM α", num(deg(g.alpha)), "°"),
        ("rocker BC", num(g.l_bc), u),
        ("ground O1C", num(g.ground()), u),
        ("ω_1 (counter-clockwise +)", num(s.omega1), "rad/s"),
        ("ε_1", num(s.epsilon1), "rad/s²"),
    ] {
        row(&mut t, q, v, unit);
    }
    let sweep = format!("{} … {} step {}", num(s.sweep.from_deg), num(s.sweep.to_deg), num(s.sweep.step_deg));
    row(&mut t, "crank angles φ_1", sweep, "°");
    if let Some(d) = &s.dynamics {
        row(&mut t, "g", format!("({}, {})", num(d.gravity.x), num(d.gravity.y)), "m/s²");
        for (q, m) in [("m_1 crank", d.m1), ("m_21 bar AB", d.m21), ("m_22 bar BM", d.m22), ("m_3 rocker", d.m3)] {
            row(&mut t, q, num(m), "kg");
        }
        for f in &d.forces {
            let range =
                f.range.map_or(String::new(), |r| format!(" for φ_1 ∈ [{}°, {}°]", num(r.from_deg), num(r.to_deg)));
            row(&mut t, &format!("F at {:?}{range}", f.at), pt(Point::from(f.value)), "N");
        }
    }
    t
}

/// The report of a four-bar scene.
pub(super) fn motion_report<'a>(
    scene: &'a FourbarScene,
    file: &str,
    opts: &super::ReportOptions,
    frame: Frame,
) -> Result<(MotionReport<'a>, Csv, serde_json::Value, Vec<String>), Error> {
    let spec = &scene.spec;
    let g = spec.geometry;
    let motion = solve_motion(spec).map_err(|e| Error::Solve { file: file.to_string(), source: e.into() })?;
    let mut warnings = motion.warnings();
    if motion.positions.is_empty() {
        return Err(Error::Option {
            option: "report".into(),
            message: format!("{file}: no crank angle of the sweep can be assembled: there is nothing to report"),
        });
    }
    let units = match scene.units {
        Units::Si => ModelUnits::SI,
        Units::Mm => ModelUnits::MM,
    };
    let show = Show {
        velocity: spec.outputs.velocity,
        acceleration: spec.outputs.acceleration,
        forces: spec.outputs.forces && !motion.forces.is_empty(),
        scales: crate::run::scale_choice(scene.frame_scales),
    };
    let mech = mechanism(&g, spec.omega1);
    let sk = sketch(scene, &mech);
    let step = spec.sweep.step_deg;
    let values: Vec<f64> = motion.positions.iter().map(|p| deg(p.phi1)).collect();
    let whole = motion.gaps.is_empty() && (values.len() as f64 * step - 360.0).abs() < 1e-6 * step;
    let cyc = if whole { Cycle::Whole } else { Cycle::Open };
    let (extra, dead, dead_warnings) = rocker_dead(spec, whole);
    warnings.extend(dead_warnings);
    let axis = DriveAxis { name: "crank angle φ1", unit: "°", step };
    let (chosen, plan_idx, base) = motion::choose_with_plan(&values, axis, cyc, opts.positions.as_ref(), &dead)?;
    let solved = Solved { motion, extra, show };
    let (mut dimensions, mut notes) = (Vec::new(), Vec::new());
    if let [(pa, _), (pb, _)] = solved.extra.as_slice() {
        (dimensions, notes) = swing_marks(spec, pa, pb, &dead);
    }
    notes.push(format!(
        "positions of the plan: {}",
        plan_idx
            .iter()
            .enumerate()
            .map(|(i, &k)| format!("{} φ1 = {}°", i + base, motion::trimmed(values[k])))
            .collect::<Vec<_>>()
            .join(", ")
    ));
    let positions = &solved.motion.positions;
    let plan: Vec<(String, Vec<f64>)> =
        plan_idx.iter().enumerate().map(|(i, &k)| ((i + base).to_string(), coordinates(&g, &positions[k]))).collect();
    let dead_drawn: Vec<(String, Vec<f64>)> = dead
        .iter()
        .enumerate()
        .map(|(i, d)| (crate::solve::linkage::structure::roman(i as u32 + 1), d.q.clone()))
        .collect();
    let structure = Structure::of(&mech, Some(&coordinates(&g, &positions[0])));
    let qs = run::reported(&spec.outputs, show.forces);
    // The diagrams and the chosen positions on them.
    let marked = solved.marked_diagrams(step, &qs, units, &chosen);
    // The chosen positions' table: the run's CSV columns.
    let picked = solved.picked(&chosen);
    let mut table = run::table(&picked, &qs, show.forces);
    table.prepend_column("position", &chosen.iter().map(|c| c.mark.clone()).collect::<Vec<_>>());
    // The printed sheet of each chosen position.
    let all_q: Vec<Vec<f64>> = positions.iter().map(|p| coordinates(&g, p)).collect();
    let sheets = position_sheets(scene, &frame, &solved, &qs, units);
    let free_bodies = show.forces && spec.dynamics.is_some();
    let per_position = sheets.per_position() + usize::from(free_bodies);
    let fb = (sk.clone(), mech.clone(), structure.clone(), frame.clone());
    let kinematic = format!("φ1 = {}°", motion::trimmed(values[plan_idx.first().copied().unwrap_or(0)]));
    let draw_position = position_drawer(scene, sheets, solved, qs, units, fb);
    let summary = serde_json::json!({
        "kind": "fourbar",
        "mobility": structure.mobility.formula,
        "mobility_at_placement": structure.mobility.actual,
        "groups": structure.groups.iter().map(|s| serde_json::json!({"kind": s.group.kind_name(), "class": s.class, "order": s.order})).collect::<Vec<_>>(),
        "positions": chosen.iter().map(|c| serde_json::json!({"mark": c.mark, "label": c.label, "note": c.note, "phi1_deg": c.drive})).collect::<Vec<_>>(),
    });
    let r = MotionReport {
        frame,
        title: (
            "Graph-analytical analysis of a four-bar linkage".into(),
            format!("four-bar {} ({:?}, seed 003)", scene.name, g.grashof()),
            data(scene),
        ),
        sketch: sk,
        mechanism: mech,
        structure,
        motion: all_q,
        plan,
        dead: dead_drawn,
        numbered: Some(Anchor { body: Attach::Body(0), local: Vector::new(g.l1, 0.0) }),
        dimensions,
        notes,
        kinematic: (kinematic, kinematic_lists(spec.omega1)),
        // The four-bar's sheets fit its motion in the same panel as the diagram's own fit
        // (both 0.0015 m/mm for the Chebyshev four-bar): not held.
        drafting: None,
        unit: scene.units.length(),
        chosen,
        position_pages: per_position,
        draw_position,
        diagrams: marked,
    };
    Ok((r, table, summary, warnings))
}

/// A position solved exactly (a rocker's extreme) with its forces.
type Exact = (Position, Option<Forces>);

/// The run's motion, the rocker's extremes solved exactly, and whether forces are shown.
struct Solved {
    motion: Motion,
    extra: Vec<Exact>,
    show: Show,
}

impl Solved {
    /// The position and (shown) forces of a chosen position.
    fn at(&self, a: At) -> (&Position, Option<&Forces>) {
        let show = self.show.forces;
        match a {
            At::Sample(k) => (&self.motion.positions[k], if show { self.motion.forces.get(k) } else { None }),
            At::Exact(i) => (&self.extra[i].0, self.extra[i].1.as_ref().filter(|_| show)),
        }
    }

    /// The chosen positions as a motion of their own (for the table of their values).
    fn picked(&self, chosen: &[Chosen]) -> Motion {
        Motion {
            positions: chosen.iter().map(|c| *self.at(c.at).0).collect(),
            forces: if self.show.forces {
                chosen.iter().filter_map(|c| self.at(c.at).1.copied()).collect()
            } else {
                Vec::new()
            },
            gaps: Vec::new(),
            dead_points: Vec::new(),
            grashof: self.motion.grashof,
        }
    }

    /// The run's diagrams, each with the point of every chosen position on its paper (γ's
    /// with its least value and the 40° limit marked).
    fn marked_diagrams(&self, step: f64, qs: &[Quantity], units: ModelUnits, chosen: &[Chosen]) -> Vec<MarkedDiagram> {
        let (motion, forces) = (&self.motion, self.show.forces);
        let diagrams = run::diagrams(motion, step, qs, forces, units);
        let gamma_marks = crate::run::fourbar_teaching::gamma_marks(crate::solve::fourbar::transmission::gamma_min(
            &motion.positions,
        ));
        diagrams
            .iter()
            .map(|(stem, d)| {
                let marks = if stem == "gamma_deg" { gamma_marks.clone() } else { Marks::default() };
                let points = motion::marks(chosen, |c| {
                    let (p, f) = self.at(c.at);
                    let one = Motion {
                        positions: vec![*p],
                        forces: f.into_iter().copied().collect(),
                        gaps: Vec::new(),
                        dead_points: Vec::new(),
                        grashof: motion.grashof,
                    };
                    let ds = run::diagrams(&one, step, qs, forces, units);
                    let s = ds.iter().find(|(s, _)| s == stem)?.1.series.first()?.clone();
                    let (x, y) = (*s.x.first()?, *s.y.first()?);
                    (x.is_finite() && y.is_finite()).then(|| plot::place(d, &marks, x, y))
                });
                let drawing =
                    if marks == Marks::default() { plot::diagram(d) } else { plot::diagram_marked(d, &marks) };
                MarkedDiagram { drawing, marks: points }
            })
            .collect()
    }
}

/// The rocker's extremes (the dead positions), solved exactly where the sweep reaches them:
/// each position with its forces, its dead position, and a warning for one that cannot be.
fn rocker_dead(spec: &MotionSpec, whole: bool) -> (Vec<Exact>, Vec<Dead>, Vec<String>) {
    let g = spec.geometry;
    let (mut extra, mut dead, mut warnings) = (Vec::new(), Vec::new(), Vec::new());
    for (phi1, what) in &rocker_extremes(&g) {
        let d = into_sweep(deg(*phi1), spec.sweep.from_deg);
        if d > spec.sweep.to_deg + 1e-9 && !whole {
            continue;
        }
        match run::solve_at(spec, g.branch, d) {
            Ok((p, f)) => {
                dead.push(Dead { drive: d, what: format!("rocker's extreme, {what}"), q: coordinates(&g, &p) });
                extra.push((p, f));
            }
            Err(e) => warnings.push(format!("the rocker's extreme ({what}) is left out of the report: {e}")),
        }
    }
    (extra, dead, warnings)
}

/// The plan's dimensions and notes between the rocker's extremes `pa`, `pb`: the rocker's
/// swing ψ, the crank's working angle, K.
fn swing_marks(spec: &MotionSpec, pa: &Position, pb: &Position, dead: &[Dead]) -> (Vec<PlanDimension>, Vec<String>) {
    let g = spec.geometry;
    let sense = if spec.omega1 < 0.0 { -1.0 } else { 1.0 };
    let fwd = (sense * (pb.phi1 - pa.phi1)).rem_euclid(std::f64::consts::TAU);
    let (work, ret) = if fwd >= std::f64::consts::PI {
        (fwd, std::f64::consts::TAU - fwd)
    } else {
        (std::f64::consts::TAU - fwd, fwd)
    };
    let theta = deg(work) - 180.0;
    let k = work / ret;
    let swing = deg((pa.phi3() - pb.phi3()).abs());
    let swing = if swing > 180.0 { 360.0 - swing } else { swing };
    let mut dimensions = Vec::new();
    let (first, second) = if sense * libm::sin(pb.phi3() - pa.phi3()) > 0.0 { (pa.b, pb.b) } else { (pb.b, pa.b) };
    dimensions.push(PlanDimension::Angle {
        vertex: g.c,
        first,
        second,
        text: format!("ψ = {}°", sheet::number(swing)),
    });
    let (first, second) = if (sense > 0.0) == (fwd >= std::f64::consts::PI) { (pa.a, pb.a) } else { (pb.a, pa.a) };
    dimensions.push(PlanDimension::Angle {
        vertex: g.o1,
        first,
        second,
        text: format!("{}°", sheet::number(deg(work))),
    });
    let notes = vec![
        format!("rocker swing ψ = {}°", sheet::number(swing)),
        format!(
            "crank angles of the extremes: I φ1 = {}°, II φ1 = {}°",
            sheet::number(dead[0].drive),
            sheet::number(dead[1].drive)
        ),
        format!("working stroke {}°, return {}° of crank angle", sheet::number(deg(work)), sheet::number(deg(ret))),
        format!("θ = {}°: K = (180° + θ)/(180° − θ) = {}", sheet::number(theta), sheet::number(k)),
    ];
    (dimensions, notes)
}

/// The kinematic diagram's lists: links, joints, the crank's ω1 and the load.
fn kinematic_lists(omega1: f64) -> Vec<String> {
    vec![
        "0 the frame (O1, C)".to_string(),
        "1 crank O1A".into(),
        "2 coupler ABM (one rigid link)".into(),
        "3 rocker CB".into(),
        "O1: revolute 0–1, A: revolute 1–2".into(),
        "B: revolute 2–3, C: revolute 3–0".into(),
        format!(
            "ω1 = {} rad/s, {}",
            sheet::number(omega1.abs()),
            if omega1 < 0.0 { "clockwise" } else { "counter-clockwise" }
        ),
        "F: the load on the coupler (arrow not to scale)".into(),
    ]
}

/// The printed sheets of the chosen positions, as `run --sheets` lays them out (the table's
/// rows as the first position's).
fn position_sheets(
    scene: &FourbarScene,
    frame: &Frame,
    solved: &Solved,
    qs: &[Quantity],
    units: ModelUnits,
) -> FourbarSheets {
    let (spec, motion, show) = (&scene.spec, &solved.motion, solved.show);
    let step = spec.sweep.step_deg;
    let mut curve = run::runs(&motion.positions, step, |p| p.m);
    run::close_full_turn(&mut curve, &motion.positions, step);
    let rows = motion.positions.first().map_or(0, |p| {
        run::sheet_table(p, if show.forces { motion.forces.first() } else { None }, qs, units).rows.len()
    });
    let (external, loads) =
        spec.dynamics.as_ref().map_or((&[][..], &[][..]), |d| (d.forces.as_slice(), d.loads.as_slice()));
    let g = &spec.geometry;
    FourbarSheets::new(frame.frame.paper, &scene.name, spec.omega1, g, &motion.positions, &curve, show, units, rows)
        .with_loads(external, loads)
}

/// What draws a chosen position's pages given its first page's number and the total: its
/// sheets, then (with forces) its groups' free-body figures (`fb`: the sketch, the
/// mechanism, the structure and the frame they are drawn with).
#[allow(clippy::type_complexity)]
fn position_drawer<'a>(
    scene: &'a FourbarScene,
    sheets: FourbarSheets,
    solved: Solved,
    qs: Vec<Quantity>,
    units: ModelUnits,
    fb: (Sketch, Mechanism, Structure, Frame),
) -> Box<dyn Fn(&Chosen, usize, usize) -> Result<Vec<crate::draw::Drawing>, Error> + Sync + 'a> {
    let (g, dynamics) = (scene.spec.geometry, scene.spec.dynamics.clone());
    let free_bodies = solved.show.forces && dynamics.is_some();
    let unit = scene.units.length();
    Box::new(move |c: &Chosen, first: usize, total: usize| -> Result<Vec<crate::draw::Drawing>, Error> {
        let (p, f) = solved.at(c.at);
        let table = run::sheet_table(p, f, &qs, units);
        let mut out: Vec<crate::draw::Drawing> =
            sheets.pages(&g, p, f, &table, (first, total)).pages.into_iter().map(|(_, d)| d).collect();
        if let (true, Some(f), Some(dynamics), Some(kin)) = (free_bodies, f, dynamics.as_ref(), p.kin.as_ref()) {
            let (sketch, mech, structure, frame) = &fb;
            let q = coordinates(&g, p);
            let page = FreeBodyPage {
                sketch,
                mechanism: mech,
                structure,
                q: &q,
                loads: group_loads(&g, p, kin, f, dynamics, structure),
                position: c.label.clone(),
                unit,
                couple_factor: 1.0,
            };
            let part = format!("5  Position {}: free-body figures of the groups", c.mark);
            out.push(freebody::page(&frame.frame, &frame.title(&part, first + out.len(), total), &page));
        }
        Ok(out)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each group's free body (the crank with R_O, −R_A, Me1; the dyad with R_A, R_C) is in
    /// equilibrium with the inertia forces and moments, the weights and the loads: ΣF = 0
    /// and ΣM about the origin = 0, to 1e-9 of the largest term (d'Alembert), at every 30°.
    #[test]
    fn the_four_bars_free_bodies_are_in_equilibrium() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("templates/fourbar-chebyshev.toml");
        let loaded = crate::scene::load(&path, &[]).unwrap();
        let crate::scene::Scene::Fourbar(scene) = &loaded.scene else { panic!("a four-bar") };
        let spec = &scene.spec;
        let g = spec.geometry;
        let motion = solve_motion(spec).unwrap();
        let d = spec.dynamics.as_ref().unwrap();
        let mech = mechanism(&g, spec.omega1);
        let structure = Structure::of(&mech, Some(&coordinates(&g, &motion.positions[0])));
        let mut checked = 0;
        for (p, f) in motion.positions.iter().zip(&motion.forces).step_by(30) {
            for loads in group_loads(&g, p, p.kin.as_ref().unwrap(), f, d, &structure) {
                let (mut sf, mut sm, mut scale) = (Vector::zeros(), 0.0, 0.0f64);
                for (at, nv) in &loads.forces {
                    let m = at.x * nv.v.y - at.y * nv.v.x;
                    sf += nv.v;
                    sm += m;
                    scale = scale.max(nv.v.norm()).max(m.abs());
                }
                for c in &loads.couples {
                    sm += c.value;
                    scale = scale.max(c.value.abs());
                }
                assert!(
                    sf.norm() <= 1e-9 * scale && sm.abs() <= 1e-9 * scale,
                    "φ1 = {}: ΣF = {sf:?}, ΣM = {sm}",
                    p.phi1
                );
                checked += 1;
            }
        }
        assert!(checked >= 24, "{checked}");
    }
}
