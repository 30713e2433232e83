//! The structural analysis page: the mechanism drawn with its links numbered, then taken
//! apart into the driver (with the frame: a class I mechanism) and the Assur groups in the
//! order they are solved, each drawn apart with its joints and captioned with its class and
//! order; the mobility worked out, M = 3n − 2p₅ − p₄ with the counts, checked against what
//! the joints really leave (the rank of their equations) and against the drivers; the
//! structure's formula and the mechanism's class.

use crate::draw::{Bounds, Drawing};
use crate::figure::linkage::{BodyOutline, JointSymbol};
use crate::figure::report::page::{self, PageTitle, ReportFrame};
use crate::figure::report::sketch::{self, Marks, Sketch};
use crate::geom::Vector;
use crate::solve::linkage::structure::{GroupStructure, Structure, roman};
use crate::solve::linkage::{Attach, JointKind, Mechanism};

/// What the structural analysis page shows.
#[derive(Debug, Clone)]
pub struct StructurePage<'a> {
    /// The mechanism as drawn.
    pub sketch: &'a Sketch,
    /// The solver's mechanism (its joints' names and kinds).
    pub mechanism: &'a Mechanism,
    /// The structure.
    pub structure: &'a Structure,
    /// The position drawn.
    pub q: &'a [f64],
    /// Every position (the guides' lengths).
    pub motion: &'a [&'a [f64]],
    /// The length unit.
    pub unit: &'a str,
}

/// The link number of body `b` (1 …), or 0 for the frame.
fn number(a: Attach) -> usize {
    match a {
        Attach::Ground => 0,
        Attach::Body(b) => b + 1,
    }
}

/// The two links a joint connects, as numbers (`1–2`).
fn joint_links(kind: &JointKind) -> (usize, usize) {
    match *kind {
        JointKind::Revolute { a, b } => (number(a.body), number(b.body)),
        JointKind::Prismatic { point, q1, .. } => (number(q1.body), number(point.body)),
    }
}

/// A group's name as a course writes it: `I(0,1) driver` , `II(2,3) dyad RRR`.
pub fn group_caption(g: &GroupStructure) -> String {
    let mut numbers: Vec<usize> = g.group.bodies.iter().map(|&b| b + 1).collect();
    numbers.sort_unstable();
    let links: Vec<String> = numbers.iter().map(usize::to_string).collect();
    if g.is_driver() {
        return format!("I(0,{}) driver and frame", links.join(","));
    }
    if g.is_passive() {
        return format!("passive link ({}): not an Assur group", links.join(","));
    }
    let what = match g.group.kind {
        crate::solve::linkage::GroupKind::Dyad(k) => format!("dyad {}", k.name()),
        crate::solve::linkage::GroupKind::Triad => "triad 6R".to_string(),
        _ => "group".to_string(),
    };
    format!("{}({}) {what}, order {}", roman(g.class), links.join(","), g.order)
}

/// The lines of the mobility's working.
pub fn mobility_lines(p: &StructurePage) -> Vec<String> {
    let st = p.structure;
    let m = &st.mobility;
    let mech = p.mechanism;
    let links: Vec<String> = mech.bodies.iter().enumerate().map(|(i, b)| format!("{} {}", i + 1, b.name)).collect();
    let named = |prismatic: bool| -> Vec<String> {
        mech.joints
            .iter()
            .filter(|j| matches!(j.kind, JointKind::Prismatic { .. }) == prismatic)
            .map(|j| {
                let (a, b) = joint_links(&j.kind);
                format!("{} ({a}–{b})", j.name)
            })
            .collect()
    };
    let mut out = vec![
        format!("n = {} moving links: {}", m.links, links.join(", ")),
        format!("p₅ = {} lower pairs: {} revolute, {} prismatic", m.lower(), m.revolute, m.prismatic),
    ];
    for (kind, list) in [("revolute", named(false)), ("prismatic", named(true))] {
        if !list.is_empty() {
            out.push(format!("   {kind}: {}", list.join(", ")));
        }
    }
    out.push("p₄ = 0 higher pairs".to_string());
    out.push(format!("{} (Chebyshev–Grübler)", m.worked()));
    match m.actual {
        Some(a) if a == m.formula => out.push(format!(
            "At this position the joints leave {} (3n − rank Φq = {} − {}): as the formula says.",
            crate::text::counted(a, "degree of freedom", "degrees of freedom"),
            3 * m.links,
            3 * m.links as i64 - a
        )),
        Some(a) => out.push(format!(
            "At this position the joints leave {} (3n − rank Φq = {} − {}), not {}: {} repeat others (a \
             redundant, passive constraint); the formula counts them, the motion does not.",
            crate::text::counted(a, "degree of freedom", "degrees of freedom"),
            3 * m.links,
            3 * m.links as i64 - a,
            m.formula,
            crate::text::counted(m.redundant() as i64, "joint equation", "joint equations"),
        )),
        None => {}
    }
    if m.redundant() > 0 {
        out.push(
            "The solver takes the joints' equations as independent: with a repeated one it has no motion to solve, so \
             this report stops at the structure and the kinematic diagram (no plan of positions, no velocity, \
             acceleration or force pages: the reactions of a redundant link are statically indeterminate). Remove the \
             passive link and its joints to analyse the motion."
                .to_string(),
        );
    }
    let effective = m.actual.unwrap_or(m.formula);
    let drivers = crate::text::counted(st.drivers as i64, "driver", "drivers");
    out.push(if effective == 0 && st.drivers == 0 {
        "M = 0: with its outer pairs on the frame it is a structure, an Assur group on its own; a driver moving \
         one of its outer pairs makes it part of a mechanism."
            .to_string()
    } else if effective == st.drivers as i64 {
        format!("{}: M = {effective} = the number of drivers, the motion is determined.", drivers)
    } else {
        format!("{} for M = {effective}: the motion is not determined by the drivers.", drivers)
    });
    out.push(format!("Structure: {}; a class {} mechanism.", st.formula(|b| b + 1), roman(st.class())));
    out
}

/// The groups' table lines: each group's links, pairs, class and order.
fn group_lines(p: &StructurePage) -> Vec<String> {
    let mech = p.mechanism;
    p.structure
        .groups
        .iter()
        .map(|g| {
            let pair = |j: &usize| {
                let (a, b) = joint_links(&mech.joints[*j].kind);
                format!("{} ({a}–{b})", mech.joints[*j].name)
            };
            let outer: Vec<String> = g.outer.iter().map(pair).collect();
            let inner: Vec<String> = g.inner.iter().map(pair).collect();
            let mut line = format!("{}: outer pairs {}", group_caption(g), outer.join(", "));
            if !inner.is_empty() {
                line.push_str(&format!("; inner {}", inner.join(", ")));
            }
            let w = 3 * g.group.bodies.len() as i64 - 2 * g.group.joints.len() as i64;
            line.push_str(&format!(
                "; W = 3·{} − 2·{} = {}",
                g.group.bodies.len(),
                g.group.joints.len(),
                if w < 0 { format!("−{}", -w) } else { w.to_string() }
            ));
            if g.is_passive() {
                line.push_str(&format!(
                    ": {} more than its coordinates",
                    crate::text::counted(-w, "joint equation", "joint equations")
                ));
            }
            line
        })
        .collect()
}

/// The sketch of one group alone: its bodies and its joints (the others' outlines left out).
pub fn group_sketch(sketch: &Sketch, mech: &Mechanism, g: &GroupStructure) -> Sketch {
    let bodies = sketch
        .figure
        .bodies
        .iter()
        .enumerate()
        .map(|(i, b)| if g.group.bodies.contains(&i) { b.clone() } else { BodyOutline { points: Vec::new() } })
        .collect();
    let joints: Vec<JointSymbol> = (0..mech.joints.len())
        .filter(|j| g.group.joints.contains(j))
        .filter_map(|j| sketch.figure.joints.get(j).cloned())
        .collect();
    let mut figure = sketch.figure.clone();
    figure.bodies = bodies;
    figure.joints = joints;
    figure.traced = Vec::new();
    Sketch { figure, names: sketch.names.clone(), driver: None, loads: Vec::new() }
}

/// Share of the left column's height the mechanism's panel takes (the mobility's working
/// below it).
const MECHANISM_SHARE: f64 = 0.5;

/// The structural analysis page (its title block's cells: the mechanism's and the groups'
/// k_l): the mechanism numbered (left, above the mobility's
/// working), the groups apart (right), all at one k_l when the groups' panels hold them at
/// the mechanism's, else every group at the one scale that fits them all.
pub fn page(frame: &ReportFrame, title: &PageTitle, p: &StructurePage) -> Drawing {
    let s = frame.sizes;
    let mut title = title.clone();
    let c = frame.content;
    let [left, right] = match page::columns(c, 2, 0.0).as_slice() {
        [a, b] => [*a, *b],
        _ => [c, c],
    };
    let split = left.max.y - MECHANISM_SHARE * left.height();
    let mech_panel = Bounds { min: crate::geom::Point::new(left.min.x, split), ..left };
    let text_panel = Bounds { max: crate::geom::Point::new(left.max.x, split), ..left };
    // The mechanism's scale, and the groups' (the coarser of it and what their panels need).
    let probe = page::panel_area(mech_panel, true, s);
    let (lo, hi) = p.sketch.extent_with_guides(p.q, p.motion, s).unwrap_or((Vector::zeros(), Vector::new(1.0, 1.0)));
    let at = sketch::fit(lo, hi, probe, sketch::room(s));
    let n = p.structure.groups.len().max(1);
    let cols = if n <= 2 { 1 } else { 2 };
    let cells = page::grid(right, n, cols);
    let sketches: Vec<Sketch> = p.structure.groups.iter().map(|g| group_sketch(p.sketch, p.mechanism, g)).collect();
    let k_l = sketches.iter().zip(&cells).fold(at.k_l, |k, (gs, cell)| {
        let (lo, hi) = gs.extent(&[p.q]).unwrap_or((Vector::zeros(), Vector::new(1.0, 1.0)));
        k.max(sketch::fit(lo, hi, page::panel_area(*cell, true, s), sketch::room(s)).k_l)
    });
    title.cells = vec![
        format!("k_l = {} {}/mm", page::plain(at.k_l), p.unit),
        format!("groups: k_l = {} {}/mm", page::plain(k_l), p.unit),
    ];
    let mut d = frame.page(&title);
    let area = page::panel(
        &mut d,
        mech_panel,
        &format!("The mechanism, links numbered   k_l = {} {}/mm", page::plain(at.k_l), p.unit),
        s,
    );
    sketch::draw(
        &mut d,
        p.sketch,
        p.q,
        p.motion,
        sketch::Frame { at, sizes: s, area },
        Marks { numbers: true, ..Marks::default() },
    );
    // The mobility.
    let area = page::panel(&mut d, text_panel, "Mobility and groups", s);
    let l = page::sheet_layer(&mut d);
    let mut text = mobility_lines(p);
    text.extend(group_lines(p));
    page::lines(&mut d, l, area, &text, 0.8 * s.text, s);
    // The groups apart, at one scale.
    for ((g, gs), cell) in p.structure.groups.iter().zip(&sketches).zip(cells) {
        let probe = page::panel_area(cell, true, s);
        let (lo, hi) = gs.extent(&[p.q]).unwrap_or((Vector::zeros(), Vector::new(1.0, 1.0)));
        let at = sketch::OnPaper { k_l, origin: crate::figure::shared::sheet::centre(lo, hi, k_l, probe) };
        // Two columns of groups leave no room for the scale in each caption: it is the
        // title block's ("groups: k_l = …"), the same for every group.
        let caption = if cols == 1 {
            format!("{}   k_l = {} {}/mm", group_caption(g), page::plain(k_l), p.unit)
        } else {
            group_caption(g)
        };
        let area = page::panel(&mut d, cell, &caption, s);
        sketch::draw(
            &mut d,
            gs,
            p.q,
            p.motion,
            sketch::Frame { at, sizes: s, area },
            Marks { numbers: true, ..Marks::default() },
        );
    }
    d
}
