//! The free-body figures of a chosen position (issue 33): each Assur group — the driver
//! with its crank, then every group in the solver's order — drawn apart at the position
//! with everything acting on it from outside the group: the inertia forces `Fi<n>` and
//! weights `G<n>` at the centroids, the loads by their names, the reactions of the joints
//! that tie it to the frame and to the other groups (named as its force polygon names them:
//! `RA`, `−RA`, `R32`), the driver's force or moment, and the couples — inertia moments
//! `Mi<n>` = −J·ε, torque loads, a driver's `Me<n>`, a prismatic joint's couple — as turning
//! arrows with their values. Every force is drawn to its group's printed force scale k_F
//! (N/mm), its tail at the point it acts at (or its tip, when from the point it would run
//! over a link of the group): a reaction measured × k_F is the vector of the run's CSV and
//! of the force polygon. Each panel has its k_l and k_F in its caption and a scale bar of
//! each. The joints inside a group (their reactions cancel in
//! it) are drawn without their forces.
//!
//! Units: forces N; couples N·m written in N·(the scene's length unit), as the tables.

use crate::draw::{Aci, Bounds, Drawing, Shape};
use crate::figure::linkage::forces::{body_forces, driver_name, reaction_names};
use crate::figure::report::page::{self, PageTitle, ReportFrame};
use crate::figure::report::sketch::{self, Marks, OnPaper, Sketch};
use crate::figure::report::structure::{group_caption, group_sketch};
use crate::figure::shared::clear_forces;
use crate::figure::shared::forces::{ForceArrow, NamedVector};
use crate::figure::shared::labels;
use crate::figure::shared::vocab::{self, Sizes, layer_of, layers, nice_scale};
use crate::geom::{Point, Vector};
use crate::solve::linkage::structure::{GroupStructure, Structure};
use crate::solve::linkage::{Anchor, Attach, DriverTarget, Dynamics, Forces, JointKind, LoadAction, Mechanism, State};

/// What the free-body page of one position shows.
#[derive(Debug, Clone)]
pub struct FreeBodyPage<'a> {
    /// The mechanism as drawn.
    pub sketch: &'a Sketch,
    /// The solver's mechanism.
    pub mechanism: &'a Mechanism,
    /// Its structure (the groups, in solving order).
    pub structure: &'a Structure,
    /// The position (x, y, φ per body, model units).
    pub q: &'a [f64],
    /// What acts on each group from outside it, one per group of `structure`.
    pub loads: Vec<GroupLoads>,
    /// Which position (`t = 0.25 s`).
    pub position: String,
    /// The length unit (`mm`, `m`).
    pub unit: &'a str,
    /// The couples' values times this are N·(`unit`) (1 / metres per unit for N·m).
    pub couple_factor: f64,
}

/// What acts on every group of `structure` from outside it at one sample of a linkage
/// ([`body_forces`], [`body_couples`], [`group_loads`]); couples in N·m.
pub fn linkage_loads(
    mech: &Mechanism,
    structure: &Structure,
    dynamics: &Dynamics,
    state: &State,
    f: &Forces,
) -> Vec<GroupLoads> {
    let forces = body_forces(mech, dynamics, state, f);
    let couples = body_couples(mech, dynamics, state, f);
    structure.groups.iter().map(|g| group_loads(mech, g, &forces, &couples)).collect()
}

/// A couple acting on a body: where it is drawn, its name, its value (N·m,
/// counter-clockwise positive).
#[derive(Debug, Clone, PartialEq)]
pub struct Couple {
    /// Where it is drawn (model units).
    pub at: Point,
    /// `Mi2`, `Me1`, a torque load's name, `M32`.
    pub name: String,
    /// N·m, counter-clockwise positive.
    pub value: f64,
    /// Whether the name is a quantity's symbol and its subscript (M_i2, M_e1, M_32), not a
    /// torque load's name as its user wrote it (drawn flat).
    pub quantity: bool,
}

/// The couples on each moving body at one sample: the inertia moment −J·ε at the centroid,
/// torque loads, angle drivers' moments (at the driven body's pivot), prismatic joints'
/// couples (the guide's on the slider and the opposite), N·m.
pub fn body_couples(mech: &Mechanism, dynamics: &Dynamics, state: &State, f: &Forces) -> Vec<Vec<Couple>> {
    let mut out: Vec<Vec<Couple>> = vec![Vec::new(); mech.bodies.len()];
    for (i, body) in dynamics.bodies.iter().enumerate() {
        let eps = state.qdd.get(3 * i + 2).copied().unwrap_or(0.0);
        let m = -body.inertia * eps;
        if body.inertia != 0.0 && m != 0.0 {
            let at = state.point(Anchor { body: Attach::Body(i), local: body.centroid });
            out[i].push(Couple { at, name: format!("Mi{}", i + 1), value: m, quantity: true });
        }
    }
    for load in &dynamics.loads {
        if load.window.is_some_and(|w| !w.contains(state.t)) {
            continue;
        }
        if let LoadAction::Torque { body, torque } = &load.action
            && let Some(list) = out.get_mut(*body)
        {
            let at = body_point(mech, state, *body);
            list.push(Couple { at, name: load.name.clone(), value: torque.at(state.t), quantity: false });
        }
    }
    for (d, (driver, value)) in mech.drivers.iter().zip(&f.drivers).enumerate() {
        // φ_b − φ_a driven: +D on b, −D on a; a distance driver's force is a force.
        let on: Vec<(Attach, f64)> = match driver.target {
            DriverTarget::BodyAngle(i) => vec![(Attach::Body(i), 1.0)],
            DriverTarget::JointAngle(j) => match mech.joints[j].kind {
                JointKind::Revolute { a, b } => vec![(b.body, 1.0), (a.body, -1.0)],
                JointKind::Prismatic { .. } => Vec::new(),
            },
            DriverTarget::JointDistance(_) => Vec::new(),
        };
        for (body, sign) in on {
            if let Attach::Body(i) = body {
                let at = pivot_of(mech, state, i).unwrap_or_else(|| body_point(mech, state, i));
                out[i].push(Couple { at, name: driver_name(mech, d), value: sign * value, quantity: true });
            }
        }
    }
    for (j, joint) in mech.joints.iter().enumerate() {
        let JointKind::Prismatic { point, q1, .. } = joint.kind else { continue };
        let t = f.reactions[j].torque;
        if t == 0.0 {
            continue;
        }
        let (name, opposite) = reaction_names(mech, j);
        let at = state.point(point);
        for (body, name, value) in [(point.body, name, t), (q1.body, opposite, -t)] {
            if let Attach::Body(i) = body {
                out[i].push(Couple { at, name: couple_name(&name), value, quantity: true });
            }
        }
    }
    out
}

/// A reaction's couple named after it: `R32` → `M32`, `−RA` → `−MA`.
fn couple_name(reaction: &str) -> String {
    reaction.replacen('R', "M", 1)
}

/// The pivot of body `i` on the frame (a revolute joint to the ground), if any.
fn pivot_of(mech: &Mechanism, state: &State, i: usize) -> Option<Point> {
    mech.joints.iter().find_map(|j| match j.kind {
        JointKind::Revolute { a, b } if a.body == Attach::Body(i) && b.body == Attach::Ground => Some(state.point(a)),
        JointKind::Revolute { a, b } if b.body == Attach::Body(i) && a.body == Attach::Ground => Some(state.point(b)),
        _ => None,
    })
}

/// A point to draw a couple of body `i` at: its first point.
fn body_point(mech: &Mechanism, state: &State, i: usize) -> Point {
    let local = mech.bodies.get(i).and_then(|b| b.points.first()).map_or(Vector::zeros(), |(_, v)| *v);
    state.point(Anchor { body: Attach::Body(i), local })
}

/// What acts on one group from outside it: the forces with where they act, the couples.
#[derive(Debug, Clone, PartialEq)]
pub struct GroupLoads {
    /// Forces (model points, N).
    pub forces: Vec<(Point, NamedVector)>,
    /// Couples (N·m).
    pub couples: Vec<Couple>,
}

/// The forces and couples on group `g` from outside it: those of its bodies, less the
/// reactions of the joints between two of its bodies.
pub fn group_loads(
    mech: &Mechanism,
    g: &GroupStructure,
    forces: &[Vec<(Point, NamedVector)>],
    couples: &[Vec<Couple>],
) -> GroupLoads {
    let mine = |a: Attach| matches!(a, Attach::Body(i) if g.group.bodies.contains(&i));
    let mut inside: Vec<String> = Vec::new();
    for (j, joint) in mech.joints.iter().enumerate() {
        let (a, b) = match joint.kind {
            JointKind::Revolute { a, b } => (a.body, b.body),
            JointKind::Prismatic { point, q1, .. } => (q1.body, point.body),
        };
        if mine(a) && mine(b) {
            let (n, o) = reaction_names(mech, j);
            inside.extend([couple_name(&n), couple_name(&o), n, o]);
        }
    }
    let keep = |name: &str| !inside.iter().any(|x| x == name);
    GroupLoads {
        forces: g
            .group
            .bodies
            .iter()
            .filter_map(|&b| forces.get(b))
            .flatten()
            .filter(|(_, nv)| keep(&nv.name))
            .cloned()
            .collect(),
        couples: g
            .group
            .bodies
            .iter()
            .filter_map(|&b| couples.get(b))
            .flatten()
            .filter(|c| keep(&c.name))
            .cloned()
            .collect(),
    }
}

/// Share of a panel's smaller side the largest force of its group is drawn as.
pub const LARGEST_FORCE_SHARE: f64 = 0.3;

/// Room kept round the group for its forces when its k_l is chosen, as a share of the
/// largest force's length (each side; plus two letters): the forces that need more get a
/// coarser k_F rather than the group a coarser k_l (the slider-crank's dyad was drawn at
/// 10 mm/mm, 50 mm long, with a half share).
pub const ROOM_SHARE: f64 = 0.25;

/// A force below this fraction of its group's largest, or a couple below this fraction of
/// the page's largest, is left out (rounding noise: the inertia force of a slider at rest).
pub const NEGLIGIBLE_REL: f64 = 1e-9;

/// The free-body page of one position: a panel per group (its caption with its k_l and
/// k_F), the groups in solving order.
pub fn page(frame: &ReportFrame, title: &PageTitle, p: &FreeBodyPage) -> Drawing {
    let s = frame.sizes;
    let groups = &p.structure.groups;
    let n = groups.len().max(1);
    let cols = if n == 1 {
        1
    } else if n <= 4 {
        2
    } else {
        3
    };
    let cells = page::grid(frame.content, n, cols);
    let mut title = title.clone();
    title.cells = vec![p.position.clone(), "forces to k_F, couples by value".into()];
    let mut d = frame.page(&title);
    // A couple below NEGLIGIBLE_REL of the page's largest is rounding noise (an inertia
    // moment of 1e-15 N·mm where ε = 0): not drawn.
    let largest_couple = p.loads.iter().flat_map(|l| &l.couples).map(|c| c.value.abs()).fold(0.0, f64::max);
    for ((g, loads), cell) in groups.iter().zip(&p.loads).zip(&cells) {
        group_panel(&mut d, *cell, p, g, loads, NEGLIGIBLE_REL * largest_couple, s);
    }
    if let Some(spare) = cells.get(groups.len()) {
        let area = page::panel(&mut d, *spare, "How the figures are drawn", s);
        let l = page::sheet_layer(&mut d);
        page::lines(&mut d, l, area, &notes(p), 0.9 * s.text, s);
    }
    d
}

/// How far from `p` along `v` the box `b` reaches (0 when `p` is outside it), paper mm.
fn room_along(b: Bounds, p: Point, v: Vector) -> f64 {
    let n = v.norm();
    if n.is_nan() || n <= 0.0 || p.x < b.min.x || p.x > b.max.x || p.y < b.min.y || p.y > b.max.y {
        return 0.0;
    }
    let u = v / n;
    let along = |lo: f64, hi: f64, x: f64, d: f64| {
        if d > 0.0 {
            (hi - x) / d
        } else if d < 0.0 {
            (lo - x) / d
        } else {
            f64::INFINITY
        }
    };
    along(b.min.x, b.max.x, p.x, u.x).min(along(b.min.y, b.max.y, p.y, u.y))
}

/// What the spare panel says about the figures.
fn notes(p: &FreeBodyPage) -> Vec<String> {
    vec![
        format!("Position {}: each Assur group apart, as the solver takes them.", p.position),
        "Forces in N, drawn from (or onto) the point they act at to each panel's k_F (N per mm);".into(),
        "the lengths to the panel's k_l.".into(),
        "Red: the joints' reactions, the same vectors as in the group's force polygon".into(),
        "(RA: of the first body of joint A on the second, −RA the opposite; R32: of link 3 on 2).".into(),
        "Magenta: inertia forces Fi, weights G, loads by name.".into(),
        format!("Couples (N·{}): inertia moments Mi = −J·ε, the driver's Me, a slider's couple M;", p.unit),
        "their arrows show the sense, their values are written.".into(),
        "The reactions between two links of a group cancel in it and are not drawn.".into(),
    ]
}

/// One group's panel.
fn group_panel(
    d: &mut Drawing,
    cell: Bounds,
    p: &FreeBodyPage,
    g: &GroupStructure,
    loads: &GroupLoads,
    least_couple: f64,
    s: Sizes,
) {
    let gs = group_sketch(p.sketch, p.mechanism, g);
    let q = p.q;
    let probe = page::panel_area(cell, true, s);
    let (lo, hi) = gs.extent(&[q]).unwrap_or((Vector::zeros(), Vector::new(1.0, 1.0)));
    // The group in the panel's middle, the arrows round it.
    let side = probe.width().min(probe.height());
    let reach = LARGEST_FORCE_SHARE * side;
    let room = Vector::new(ROOM_SHARE * reach + 2.0 * s.text, ROOM_SHARE * reach + 2.0 * s.text);
    let at: OnPaper = sketch::fit(lo, hi, probe, room);
    let largest = loads.forces.iter().map(|(_, nv)| nv.v.norm()).fold(0.0, f64::max);
    // The largest force `reach` long, and every arrow's tip (with its name) inside the panel.
    let margin = 3.0 * s.text;
    let inside = Bounds { min: probe.min + Vector::new(margin, margin), max: probe.max - Vector::new(margin, margin) };
    let need = loads.forces.iter().fold(largest / reach.max(1e-9), |k, (point, nv)| {
        let room = room_along(inside, at.point(*point), nv.v);
        if room > 0.0 { k.max(nv.v.norm() / room) } else { k }
    });
    let k_f = nice_scale(need);
    let caption =
        format!("{}   k_l = {} {}/mm, k_F = {} N/mm", group_caption(g), page::plain(at.k_l), p.unit, page::plain(k_f));
    let area = page::panel(d, cell, &caption, s);
    let start = d.entities.len();
    sketch::draw(d, &gs, q, &[q], sketch::Frame { at, sizes: s, area }, Marks { numbers: true, ..Marks::default() });
    let frc = layer_of(d, layers::FORCES);
    // The forces to k_F, clear of the group's links, guides and joints' symbols.
    let mut arrows: Vec<ForceArrow> = loads
        .forces
        .iter()
        .filter(|(_, nv)| nv.v.norm() > NEGLIGIBLE_REL * largest && !nv.v.norm().is_nan())
        .map(|(point, nv)| {
            let from = at.point(*point);
            ForceArrow { at: from, force: nv.clone(), arrow: (from, from + nv.v / k_f) }
        })
        .collect();
    clear_of_group(&mut arrows, &gs, q, (at, inside), s);
    // (from, to, name, colour, with a leader)
    let mut names: Vec<(Point, Point, labels::Label, Option<Aci>, bool)> = Vec::new();
    for a in &arrows {
        let (nv, (from, to)) = (&a.force, a.arrow);
        let reaction = nv.name.starts_with('R') || nv.name.starts_with("−R");
        let color = reaction.then_some(Aci::RED);
        match color {
            Some(c) => d.add_colored(frc, c, Shape::Arrow { from, to, head: s.head }),
            None => d.add(frc, Shape::Arrow { from, to, head: s.head }),
        }
        names.push((from, to, nv.label(), color, false));
    }
    let per_nm = p.couple_factor;
    // A couple of 0 (the crank's inertia moment at constant speed) or at rounding level is
    // not drawn.
    for (k, c) in loads.couples.iter().filter(|c| c.value.abs() > least_couple && c.value.is_finite()).enumerate() {
        let centre = at.point(c.at);
        let r = 2.5 * s.joint + k as f64 * 0.8 * s.joint;
        let sweep = 1.4 * c.value.signum();
        let from = 0.9 + 0.7 * k as f64;
        let mid = vocab::turn_arrow(d, frc, centre, r, from, sweep, s);
        let text = format!("{} = {} N·{}", c.name, crate::figure::shared::sheet::number(c.value * per_nm), p.unit);
        // M_i2 = … with the name's subscript (its runs lie within the name, the text's start).
        let runs = if c.quantity { labels::Label::quantity(&c.name).runs } else { crate::draw::Runs::flat() };
        names.push((centre, mid, labels::Label { text, runs }, None, true));
    }
    let mut letters = labels::Polygon::of_names();
    sketch::avoid(d, start, &mut letters);
    sketch::keep_inside(&mut letters, area);
    for (from, to, name, color, leader) in names {
        if leader {
            letters.name_with_leader(to, name, s.text, to - from, color);
        } else {
            letters.letter(to, name, s.text, to - from, color);
        }
    }
    let l = layer_of(d, layers::FORCES);
    letters.draw(d, l);
    // The scale bars: the forces' and, over it, the lengths'.
    let dims = layer_of(d, layers::DIMENSIONS);
    let value = vocab::bar_value(k_f);
    vocab::scale_bar(
        d,
        dims,
        Point::new(area.min.x + s.text, area.min.y + 0.5 * s.text),
        value / k_f,
        &format!("{} N", page::plain(value)),
        s,
    );
    let value = vocab::bar_value(at.k_l);
    vocab::scale_bar(
        d,
        dims,
        Point::new(area.min.x + s.text, area.min.y + 0.5 * s.text + LENGTH_BAR_RISE * s.text),
        value / at.k_l,
        &format!("{} {}", page::plain(value), p.unit),
        s,
    );
}

/// The length scale bar stands this many letter heights over the force scale bar.
const LENGTH_BAR_RISE: f64 = 1.6;

/// Places the group's forces ([`clear_forces::place`]) clear of its links, its ground
/// guides and its joints' symbols as the panel draws them at `at`, inside the panel's
/// drawing area `inside` where it can.
fn clear_of_group(arrows: &mut [ForceArrow], gs: &Sketch, q: &[f64], (at, inside): (OnPaper, Bounds), s: Sizes) {
    let paper_fig = gs.figure.on_paper(at.origin, at.k_l);
    let paper_q = crate::figure::linkage::on_paper(q, at.origin, at.k_l);
    let mut strokes = crate::figure::linkage::frame::links_of(&paper_fig, &paper_q);
    for (a, b) in crate::figure::linkage::guide_spans(&paper_fig, &[&paper_q], &s).into_iter().flatten() {
        strokes.extend(clear_forces::guide_strokes(a, b, s));
    }
    let symbols = crate::figure::linkage::sheet::symbols(&paper_fig, &paper_q, s);
    clear_forces::place(arrows, &strokes, &symbols, Some((inside.min, inside.max)), s);
}
