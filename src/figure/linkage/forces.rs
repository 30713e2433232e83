//! Force figures of any linkage (issue 15 §2), as [`ForcePolygon`]s for the shared
//! [`crate::figure::shared::forces::draw`] (the four-bar's dyad and crank polygons are drawn by the same
//! code): for each moving body, the polygon of everything acting on it — its inertia force
//! `Fi<n>` and weight `G<n>` (n the body's number, from 1; the ground is 0), the loads by
//! their names, a distance driver's force, and the reactions of its joints — chained from
//! its pole `f<n>`, the last reaction drawn as the resultant that closes it (seed 003's
//! Fig. 5: −R_A, F_i1, G1, closed by R_O). The reactions drawn on the mechanism at their
//! joints, and a table of magnitudes (every reaction's, the drivers' forces).
//!
//! Names: a joint with a short name (up to [`SHORT_NAME`] characters: `A`, `O1`) names
//! its reaction `R<name>` (`RA`, of the first body of the joint on the second, as
//! [`crate::solve::linkage`] reports it) and the opposite one, on the first body, `−RA`;
//! any other joint (`slide`, `ram-guide`) takes the textbook's numbers `R<i><j>`, the force
//! of body i on body j (`R32`), and `R<j><i>` for the opposite. A driver's force is
//! `Me<n>` (a moment on body n, N·m or N·mm) or `Fe<n>` (a force along a guide, N).
//!
//! Units: forces N; moments in N·(the scene's length unit), labelled so.

use crate::geom::{Point, Vector};
use crate::solve::linkage::{
    Applied, AppliedKind, Attach, DriverTarget, Dynamics, Forces, Group, GroupKind, JointKind, Mechanism, State,
    applied_forces,
};

use crate::figure::shared::forces::{ForcePolygon, Magnitude, NamedVector, Resultant};

/// Longest joint name used as is in a reaction's name (`RO1`); longer ones take the bodies'
/// numbers (`R32`).
pub const SHORT_NAME: usize = 3;

/// A vector shorter than this fraction of the largest in its polygon is left out of it (a
/// weight too small to draw); the polygon still closes to that fraction.
pub const NEGLIGIBLE_REL: f64 = 1e-9;

/// The number of a body for names (the ground 0, moving bodies from 1).
fn number(a: Attach) -> usize {
    match a {
        Attach::Ground => 0,
        Attach::Body(i) => i + 1,
    }
}

/// The two bodies of a joint: the one whose force is reported (first) and the one it acts
/// on (second), and the joint's point.
fn joint_bodies(kind: &JointKind) -> (Attach, Attach) {
    match *kind {
        JointKind::Revolute { a, b } => (a.body, b.body),
        JointKind::Prismatic { point, q1, .. } => (q1.body, point.body),
    }
}

/// The names of joint `j`'s reaction on its second body and of the opposite one.
pub fn reaction_names(mech: &Mechanism, j: usize) -> (String, String) {
    let joint = &mech.joints[j];
    let short = joint.name.chars().count() <= SHORT_NAME && joint.name.chars().all(|c| c.is_alphanumeric());
    if short {
        (format!("R{}", joint.name), format!("−R{}", joint.name))
    } else {
        let (a, b) = joint_bodies(&joint.kind);
        (format!("R{}{}", number(a), number(b)), format!("R{}{}", number(b), number(a)))
    }
}

/// Name of an applied force: `Fi<n>`, `G<n>`, the load's name, `Fe<n>`.
fn applied_name(dynamics: &Dynamics, a: &Applied) -> String {
    match a.kind {
        AppliedKind::Inertia => format!("Fi{}", a.body + 1),
        AppliedKind::Weight => format!("G{}", a.body + 1),
        AppliedKind::Load(l) => dynamics.loads[l].name.clone(),
        AppliedKind::Driver(_) => format!("Fe{}", a.body + 1),
    }
}

/// An applied force, named ([`applied_name`]): a load by the name its user gave it, drawn
/// as written; the others a quantity's symbol and subscript (F_i2, G_2, F_e1).
fn applied_vector(dynamics: &Dynamics, a: &Applied) -> NamedVector {
    let name = applied_name(dynamics, a);
    match a.kind {
        AppliedKind::Load(_) => NamedVector::as_written(&name, a.force),
        _ => NamedVector::new(&name, a.force),
    }
}

/// Where joint `j` acts at `state`.
fn joint_point(mech: &Mechanism, state: &State, j: usize) -> Point {
    match mech.joints[j].kind {
        JointKind::Revolute { b, .. } => state.point(b),
        JointKind::Prismatic { point, .. } => state.point(point),
    }
}

/// Every force on each moving body at one sample, named: (applied forces, then the
/// reactions of its joints), with where each acts.
pub fn body_forces(mech: &Mechanism, dynamics: &Dynamics, state: &State, f: &Forces) -> Vec<Vec<(Point, NamedVector)>> {
    let mut out: Vec<Vec<(Point, NamedVector)>> = vec![Vec::new(); mech.bodies.len()];
    for a in applied_forces(mech, dynamics, state, f) {
        out[a.body].push((a.at, applied_vector(dynamics, &a)));
    }
    for (j, joint) in mech.joints.iter().enumerate() {
        let (first, second) = joint_bodies(&joint.kind);
        let (name, opposite) = reaction_names(mech, j);
        let at = joint_point(mech, state, j);
        let r = f.reactions[j].force;
        if let Attach::Body(b) = second {
            out[b].push((at, NamedVector::new(&name, r)));
        }
        if let Attach::Body(a) = first {
            out[a].push((at, NamedVector::new(&opposite, -r)));
        }
    }
    out
}

/// The force polygon of one body from its forces ([`body_forces`]): the chain of every force
/// but the last reaction from the pole `f<n>`, which closes it as the resultant back to the
/// pole. Vectors negligible against the largest ([`NEGLIGIBLE_REL`]) are left out.
pub fn body_polygon(body: usize, forces: &[(Point, NamedVector)]) -> ForcePolygon {
    let largest = forces.iter().map(|(_, nv)| nv.v.norm()).fold(0.0, f64::max);
    let mut chain: Vec<NamedVector> =
        forces.iter().filter(|(_, nv)| nv.v.norm() > NEGLIGIBLE_REL * largest).map(|(_, nv)| nv.clone()).collect();
    let resultants = match chain.pop() {
        Some(last) => vec![Resultant { name: last.name, from: chain.len(), to: 0, name_at: 0.5 }],
        None => Vec::new(),
    };
    ForcePolygon { pole: format!("f{}", body + 1), chain, resultants, found: 0 }
}

/// How one Assur group (or the driven body) is drawn as a force figure, from its place in the
/// solving order: which joints' reactions are known when its turn comes in the
/// kineto-statics (those to groups solved after it in the kinematics: their reactions are
/// found first), which it finds (to the ground and to groups solved before it), which are
/// inside it, and its own drivers (whose force a distance driver's group finds).
#[derive(Debug, Clone, PartialEq)]
pub struct GroupFigure {
    /// `Crank 1 (driver)`, `Dyad 2–3 (RPR)`.
    pub caption: String,
    /// Its bodies, in the group's order.
    bodies: Vec<usize>,
    /// Joints whose reaction on the group is known: (joint, the group's body it acts on).
    known: Vec<(usize, usize)>,
    /// Joints whose reaction the group's figure finds: (joint, the group's body).
    found: Vec<(usize, usize)>,
    /// Joints between two of its bodies.
    inside: Vec<usize>,
    /// Its drivers.
    drivers: Vec<usize>,
}

/// The force figures of a linkage, one per group of the Assur decomposition in solving order
/// (seed 003: the dyad's Fig. 4, the crank's Fig. 5): see [`GroupFigure`], [`group_polygon`].
pub fn group_figures(mech: &Mechanism, groups: &[Group]) -> Vec<GroupFigure> {
    let mut group_of = vec![usize::MAX; mech.bodies.len()];
    for (g, group) in groups.iter().enumerate() {
        for &b in &group.bodies {
            group_of[b] = g;
        }
    }
    groups
        .iter()
        .enumerate()
        .map(|(g, group)| {
            let (mut known, mut found, mut inside) = (Vec::new(), Vec::new(), Vec::new());
            for (j, joint) in mech.joints.iter().enumerate() {
                let (a, b) = joint_bodies(&joint.kind);
                let mine = |x: Attach| matches!(x, Attach::Body(i) if group_of[i] == g);
                let other = |x: Attach| match x {
                    Attach::Ground => None,
                    Attach::Body(i) => Some(group_of[i]),
                };
                match (mine(a), mine(b)) {
                    (true, true) => inside.push(j),
                    (true, false) | (false, true) => {
                        let (here, there) = if mine(a) { (a, b) } else { (b, a) };
                        let Attach::Body(here) = here else { continue };
                        // Solved after this group in the kinematics: found before it.
                        if other(there).is_some_and(|o| o > g) { known.push((j, here)) } else { found.push((j, here)) }
                    }
                    (false, false) => {}
                }
            }
            GroupFigure {
                caption: group_caption(mech, group),
                bodies: group.bodies.clone(),
                known,
                found,
                inside,
                drivers: group.drivers.clone(),
            }
        })
        .collect()
}

/// A group's caption: `Crank 1 (driver)`, `Dyad 2–3 (RPR)`, `Triad 2–5`, `Group 2–4 (general)`
/// (bodies numbered from 1 in the scene's order).
fn group_caption(mech: &Mechanism, group: &Group) -> String {
    let numbers: Vec<String> = group.bodies.iter().map(|b| (b + 1).to_string()).collect();
    let list = numbers.join("–");
    match group.kind {
        GroupKind::Driven(_) => match group.bodies.first() {
            Some(&b) => format!("{} (driver)", caption(mech, b)),
            None => "Driver".to_string(),
        },
        GroupKind::Dyad(k) => format!("Dyad {list} ({})", k.name()),
        GroupKind::Triad => format!("Triad {list}"),
        GroupKind::General => format!("Group {list} (general)"),
    }
}

/// The force of joint `j` on body `body` (one of its two bodies) with its name
/// ([`reaction_names`]).
fn reaction_on(mech: &Mechanism, f: &Forces, j: usize, body: usize) -> NamedVector {
    let (first, _) = joint_bodies(&mech.joints[j].kind);
    let (name, opposite) = reaction_names(mech, j);
    let r = f.reactions[j].force;
    if first == Attach::Body(body) { NamedVector::new(&opposite, -r) } else { NamedVector::new(&name, r) }
}

/// The force polygon of one group at one sample (seed 003, Figs. 4 and 5, for any group):
/// from the pole `f<n>` (n its first body's number) the known forces body by body — inertia
/// forces, weights, loads and the reactions of the groups found before it — then the
/// reactions it finds, body by body backwards (and a distance driver's balancing force), the
/// last closing the figure at the pole; drawn in red ([`ForcePolygon::found`]). The
/// reaction between its first bodies and the others, where one joint joins them, is drawn
/// across it as a resultant (the seed's R_B: from the end of the first body's known forces
/// to where the found reactions meet). Vectors negligible against the largest
/// ([`NEGLIGIBLE_REL`]) are left out.
pub fn group_polygon(
    mech: &Mechanism,
    fig: &GroupFigure,
    dynamics: &Dynamics,
    state: &State,
    f: &Forces,
) -> ForcePolygon {
    let applied = applied_forces(mech, dynamics, state, f);
    let own = |a: &Applied| matches!(a.kind, AppliedKind::Driver(d) if fig.drivers.contains(&d));
    let per_body = |b: usize, found: bool| -> Vec<NamedVector> {
        let mut out: Vec<NamedVector> =
            applied.iter().filter(|a| a.body == b && own(a) == found).map(|a| applied_vector(dynamics, a)).collect();
        let joints = if found { &fig.found } else { &fig.known };
        out.extend(joints.iter().filter(|(_, on)| *on == b).map(|&(j, _)| reaction_on(mech, f, j, b)));
        out
    };
    let known: Vec<Vec<NamedVector>> = fig.bodies.iter().map(|&b| per_body(b, false)).collect();
    let found: Vec<Vec<NamedVector>> = fig.bodies.iter().map(|&b| per_body(b, true)).collect();
    let largest = known.iter().chain(&found).flatten().map(|nv| nv.v.norm()).fold(0.0, f64::max);
    let keep = |v: &Vec<NamedVector>| -> Vec<NamedVector> {
        v.iter().filter(|nv| nv.v.norm() > NEGLIGIBLE_REL * largest).cloned().collect()
    };
    let (known, found): (Vec<_>, Vec<_>) = (known.iter().map(keep).collect(), found.iter().map(keep).collect());
    // Vertex after the known forces of the first k + 1 bodies, and where the found reactions
    // of body k start (they run backwards, body n's first).
    let n = fig.bodies.len();
    let after_known: Vec<usize> = known
        .iter()
        .scan(0, |acc, v| {
            *acc += v.len();
            Some(*acc)
        })
        .collect();
    let total_known = after_known.last().copied().unwrap_or(0);
    let found_start = |k: usize| total_known + found[k + 1..].iter().map(Vec::len).sum::<usize>();
    let mut resultants = Vec::new();
    for (k, &end_known) in after_known.iter().enumerate().take(n.saturating_sub(1)) {
        let front = &fig.bodies[..=k];
        let between: Vec<usize> = fig
            .inside
            .iter()
            .copied()
            .filter(|&j| {
                let (a, b) = joint_bodies(&mech.joints[j].kind);
                let in_front = |x: Attach| matches!(x, Attach::Body(i) if front.contains(&i));
                in_front(a) != in_front(b)
            })
            .collect();
        if let [j] = between[..] {
            // The force of the others on the front bodies.
            let on = fig.bodies[..=k]
                .iter()
                .copied()
                .find(|&b| {
                    let (a, c) = joint_bodies(&mech.joints[j].kind);
                    a == Attach::Body(b) || c == Attach::Body(b)
                })
                .unwrap_or(fig.bodies[0]);
            let name = reaction_on(mech, f, j, on).name;
            resultants.push(Resultant { name, from: end_known, to: found_start(k), name_at: 0.5 });
        }
    }
    let found_count = found.iter().map(Vec::len).sum();
    let chain: Vec<NamedVector> = known.into_iter().flatten().chain(found.into_iter().rev().flatten()).collect();
    ForcePolygon {
        pole: format!("f{}", fig.bodies.first().map_or(0, |b| b + 1)),
        chain,
        resultants,
        found: found_count,
    }
}

/// Which force figures a linkage's frames and sheets draw: one per Assur group in solving
/// order ([`group_figures`], the default), or one per moving body ([`body_polygon`], the
/// scene's `[polygons] force_figures = "bodies"`).
#[derive(Debug, Clone, PartialEq)]
pub enum ForceFigures {
    /// One figure per group.
    Groups(Vec<GroupFigure>),
    /// One figure per moving body.
    Bodies,
}

impl ForceFigures {
    /// The figures of `mech`: per body, or per group of its Assur decomposition.
    pub fn new(mech: &Mechanism, per_body: bool) -> ForceFigures {
        if per_body {
            ForceFigures::Bodies
        } else {
            ForceFigures::Groups(group_figures(mech, &crate::solve::linkage::decompose(mech)))
        }
    }

    /// Each figure's caption, in drawing order.
    pub fn captions(&self, mech: &Mechanism) -> Vec<String> {
        match self {
            ForceFigures::Groups(g) => g.iter().map(|g| g.caption.clone()).collect(),
            ForceFigures::Bodies => (0..mech.bodies.len()).map(|b| caption(mech, b)).collect(),
        }
    }

    /// Each figure's polygon at one sample, in drawing order.
    pub fn polygons(&self, mech: &Mechanism, dynamics: &Dynamics, state: &State, f: &Forces) -> Vec<ForcePolygon> {
        match self {
            ForceFigures::Groups(g) => g.iter().map(|g| group_polygon(mech, g, dynamics, state, f)).collect(),
            ForceFigures::Bodies => {
                body_forces(mech, dynamics, state, f).iter().enumerate().map(|(b, bf)| body_polygon(b, bf)).collect()
            }
        }
    }
}

/// The caption of body `body`'s polygon: `Crank 1`.
pub fn caption(mech: &Mechanism, body: usize) -> String {
    let name = &mech.bodies[body].name;
    let mut c = name.chars();
    let cap = c.next().map(|f| f.to_uppercase().chain(c).collect::<String>()).unwrap_or_default();
    format!("{cap} {}", body + 1)
}

/// The forces drawn on the mechanism: each joint's reaction (on its second body) at the
/// joint, and each load where it acts while it acts.
pub fn on_mechanism(mech: &Mechanism, dynamics: &Dynamics, state: &State, f: &Forces) -> Vec<(Point, NamedVector)> {
    let mut out: Vec<(Point, NamedVector)> = (0..mech.joints.len())
        .map(|j| (joint_point(mech, state, j), NamedVector::new(&reaction_names(mech, j).0, f.reactions[j].force)))
        .collect();
    for a in applied_forces(mech, dynamics, state, f) {
        if let AppliedKind::Load(_) = a.kind {
            out.push((a.at, applied_vector(dynamics, &a)));
        }
    }
    out
}

/// The table of magnitudes: every reaction's |R| (N) and, at a prismatic joint, its couple
/// `M<…>`; each driver's force `Me<n>` (signed, in `moment_unit`) or `Fe<n>` (N).
/// `moment_per_nm` converts N·m to `moment_unit` (1000 for N·mm).
pub fn magnitudes(mech: &Mechanism, f: &Forces, moment_unit: &str, moment_per_nm: f64) -> Vec<Magnitude> {
    let row = |name: String, value: f64, unit: &str| Magnitude::new(&name, value, unit);
    let mut rows = Vec::new();
    for (j, joint) in mech.joints.iter().enumerate() {
        let name = reaction_names(mech, j).0;
        rows.push(row(name.clone(), f.reactions[j].force.norm(), "N"));
        if let JointKind::Prismatic { .. } = joint.kind {
            let couple = name.replacen('R', "M", 1);
            rows.push(row(couple, f.reactions[j].torque * moment_per_nm, moment_unit));
        }
    }
    for (d, value) in f.drivers.iter().enumerate() {
        let name = driver_name(mech, d);
        if name.starts_with("Me") {
            rows.push(row(name, value * moment_per_nm, moment_unit));
        } else {
            rows.push(row(name, *value, "N"));
        }
    }
    rows
}

/// The name of driver `d`'s force, as the table, the diagrams and the sheets write it: `Me<n>`
/// for an angular driver (the balancing moment on body n, seed 003's Me1), `Fe<n>` for a
/// distance driver (the balancing force on body n).
pub fn driver_name(mech: &Mechanism, d: usize) -> String {
    let Some(driver) = mech.drivers.get(d) else { return String::new() };
    let (kind, body) = match driver.target {
        DriverTarget::BodyAngle(i) => ("Me", Attach::Body(i)),
        DriverTarget::JointAngle(j) | DriverTarget::JointDistance(j) => {
            let (a, b) = joint_bodies(&mech.joints[j].kind);
            let kind = if matches!(driver.target, DriverTarget::JointAngle(_)) { "Me" } else { "Fe" };
            (kind, if b == Attach::Ground { a } else { b })
        }
    };
    format!("{kind}{}", number(body))
}

/// The table's rows of the forces applied to the bodies at one sample (`Fi2`, `G2`, each
/// load by its name; a distance driver's force is in [`magnitudes`]): |F|, N, in the order
/// the solver lists them.
pub fn applied_magnitudes(mech: &Mechanism, dynamics: &Dynamics, state: &State, f: &Forces) -> Vec<Magnitude> {
    applied_forces(mech, dynamics, state, f)
        .iter()
        .filter(|a| !matches!(a.kind, AppliedKind::Driver(_)))
        .map(|a| {
            let v = applied_vector(dynamics, a);
            Magnitude { quantity: v.quantity, ..Magnitude::new(&v.name, a.force.norm(), "N") }
        })
        .collect()
}

/// The sum of the forces on a body ([`body_forces`]), N: zero when its polygon closes
/// (the closing side drawn by [`body_polygon`] is then its last reaction).
pub fn closure(forces: &[(Point, NamedVector)]) -> Vector {
    forces.iter().map(|(_, nv)| nv.v).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A body with three forces that balance: the last closes the chain.
    #[test]
    fn the_last_reaction_closes_the_polygon() {
        let forces = vec![
            (Point::origin(), NamedVector::new("G1", Vector::new(0.0, -10.0))),
            (Point::origin(), NamedVector::new("RA", Vector::new(4.0, 6.0))),
            (Point::origin(), NamedVector::new("−RO", Vector::new(-4.0, 4.0))),
        ];
        let poly = body_polygon(0, &forces);
        assert_eq!(poly.pole, "f1");
        assert_eq!(poly.chain.len(), 2);
        assert_eq!(poly.resultant("−RO"), Some(Vector::new(-4.0, 4.0)));
        assert!(closure(&forces).norm() < 1e-15);
        // Unbalanced, the closing side is not the force.
        let mut off = forces.clone();
        off[0].1.v.y = -11.0;
        assert!((closure(&off) - Vector::new(0.0, -1.0)).norm() < 1e-15);
        assert_ne!(body_polygon(0, &off).resultant("−RO"), Some(Vector::new(-4.0, 4.0)));
    }
}
