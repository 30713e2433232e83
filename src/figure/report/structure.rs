//! The structural analysis page: the mechanism drawn with its links numbered, then taken
//! apart into the driver (with the frame: a class I mechanism) and the Assur groups in the
//! order they are solved, each drawn apart with its joints and captioned with its class and
//! order; the mobility worked out, M = 3n − 2p₅ − p₄ with the counts, checked against what
//! the joints really leave (the rank of their equations) and against the drivers; the
//! structure's formula and the mechanism's class.

use crate::draw::{Bounds, Drawing};
use crate::figure::linkage::{BodyOutline, JointSymbol};
use crate::figure::report::page::{self, PageTitle, ReportFrame};
use crate::figure::report::sketch::{self, Marks, OnPaper, Sketch};
use crate::figure::shared::vocab::{self, Sizes};
use crate::geom::{Point, Vector};
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

/// Height of the mobility's lines, in letter heights.
const TEXT_SIZE: f64 = 0.8;

/// Where the structure page puts its panels and each drawing ([`layout`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// The mechanism's panel and its placement.
    pub mechanism: (Bounds, OnPaper),
    /// The panel of the mobility's working.
    pub text: Bounds,
    /// Each group's panel and its placement, in solving order, all at one k_l.
    pub groups: Vec<(Bounds, OnPaper)>,
}

/// The structure page's layout, of three: the mechanism in the left column beside the
/// title block, the mobility's working under it and the groups in the column over the title
/// block; the mechanism the whole left column, the working under the groups; or the
/// mechanism across the page, the groups under it beside the working over the title block.
/// The working's panel is as tall as its lines need at its width; the groups are stacked
/// or side by side, each panel sized to its group at the groups' one scale. Of the three,
/// the one drawing the mechanism largest of those that draw the groups at most
/// [`GROUPS_SMALLER`] times smaller than it (the first when none does). Every drawing at
/// the finest drafting scale its panel holds ([`sketch::fit`]); the groups at the finest
/// one at which all of them fit.
pub fn layout(frame: &ReportFrame, p: &StructurePage) -> Layout {
    let s = frame.sizes;
    let (left, right) = frame.tall_left();
    let mut text = mobility_lines(p);
    text.extend(group_lines(p));
    let unit_box = (Vector::zeros(), Vector::new(1.0, 1.0));
    let mech_extent = p.sketch.extent_with_guides(p.q, p.motion, s).unwrap_or(unit_box);
    let groups: Vec<(Vector, Vector)> = p
        .structure
        .groups
        .iter()
        .map(|g| group_sketch(p.sketch, p.mechanism, g).extent_with_guides(p.q, p.motion, s).unwrap_or(unit_box))
        .collect();
    let captions: Vec<f64> =
        p.structure.groups.iter().map(|g| crate::draw::parts::text_width(&group_caption(g), s.text)).collect();
    let fit_mechanism =
        |panel: Bounds| sketch::fit(mech_extent.0, mech_extent.1, page::panel_area(panel, true, s), sketch::room(s));
    let mut candidates: Vec<(Layout, f64, Vec<Bounds>)> = Vec::new();
    // The mechanism in the left column, the text under it or under the groups.
    for text_right in [false, true] {
        let (column, region) = if text_right { (right, left) } else { (left, right) };
        // Under the mechanism it always goes (every line, the mechanism keeping the rest);
        // under the groups only when it leaves them room.
        let th = text_height(&text, column.width(), s);
        if text_right && th > MOST_TEXT * column.height() {
            continue;
        }
        let th = th.min(ALL_TEXT * column.height());
        let text_panel = Bounds { max: Point::new(column.max.x, column.min.y + th), ..column };
        let rest = Bounds { min: Point::new(column.min.x, column.min.y + th), ..column };
        let (mech_panel, group_region) = if text_right { (region, rest) } else { (rest, region) };
        let (k, cells) = arrange(group_region, &groups, &captions, s);
        candidates.push((
            Layout { mechanism: (mech_panel, fit_mechanism(mech_panel)), text: text_panel, groups: Vec::new() },
            k,
            cells,
        ));
    }
    // A wide mechanism (a slider-crank's long guide) across the page, the groups under it
    // beside the text over the title block.
    let th = text_height(&text, right.width(), s);
    if th <= MOST_TEXT * right.height() {
        let split = right.min.y + th;
        let mech_panel = Bounds { min: Point::new(left.min.x, split), max: right.max };
        let text_panel = Bounds { max: Point::new(right.max.x, split), ..right };
        let group_region = Bounds { max: Point::new(left.max.x, split), ..left };
        let (k, cells) = arrange(group_region, &groups, &captions, s);
        candidates.push((
            Layout { mechanism: (mech_panel, fit_mechanism(mech_panel)), text: text_panel, groups: Vec::new() },
            k,
            cells,
        ));
    }
    // The mechanism as large as the groups let it be: the finest scale of those that draw
    // the groups at most GROUPS_SMALLER times smaller (the groups' finer scale on a tie);
    // when none does, the mechanism over its text.
    let ok = |c: &&(Layout, f64, Vec<Bounds>)| c.1 <= GROUPS_SMALLER * c.0.mechanism.1.k_l;
    let best = candidates
        .iter()
        .enumerate()
        .filter(|(_, c)| ok(c))
        .min_by(|(_, a), (_, b)| {
            (a.0.mechanism.1.k_l, a.1).partial_cmp(&(b.0.mechanism.1.k_l, b.1)).unwrap_or(std::cmp::Ordering::Equal)
        })
        .map_or(0, |(i, _)| i);
    let (mut chosen, k, cells) = candidates.swap_remove(best);
    chosen.groups = groups
        .iter()
        .zip(cells)
        .map(|((lo, hi), cell)| {
            (
                cell,
                OnPaper {
                    k_l: k,
                    origin: crate::figure::shared::sheet::centre(*lo, *hi, k, page::panel_area(cell, true, s)),
                },
            )
        })
        .collect();
    chosen
}

/// The largest share of its column the mobility's working may take beside the groups or
/// under a wide mechanism.
const MOST_TEXT: f64 = 0.6;

/// The largest share of the left column the mobility's working takes under the mechanism.
const ALL_TEXT: f64 = 0.85;

/// How many times smaller than the mechanism the groups may be drawn before the layout
/// gives them the room of its mobility's working ([`layout`]).
pub const GROUPS_SMALLER: f64 = 2.0;

/// The height of a panel holding `lines` at [`TEXT_SIZE`] in `width` mm (wrapped as
/// [`page::lines`] wraps them), its title band and margins included.
fn text_height(lines: &[String], width: f64, s: Sizes) -> f64 {
    let h = TEXT_SIZE * s.text;
    let probe = Bounds { min: Point::origin(), max: Point::new(width, 1000.0) };
    let inner = page::panel_area(probe, true, s);
    let n: usize = lines.iter().map(|l| page::wrap(l, h, inner.width()).len()).sum();
    // A hair more than the lines, so that their count fits after rounding.
    (n as f64 + 0.1) * page::LINE_SPACING * h + (probe.height() - inner.height())
}

/// The groups' panels in `region`, stacked or side by side (the one drawing them larger),
/// each as tall (stacked) or wide (side by side) as its group's extent (`extents`, model
/// units) at the groups' one scale needs, the region's spare shared in proportion; with
/// that scale: the finest drafting scale at which every group fits its panel leaving
/// [`sketch::room`] around it. A panel narrower than its caption (`captions`, mm) is not
/// an arrangement.
fn arrange(region: Bounds, extents: &[(Vector, Vector)], captions: &[f64], s: Sizes) -> (f64, Vec<Bounds>) {
    let n = extents.len();
    if n == 0 {
        return (1.0, Vec::new());
    }
    let probe = Bounds { min: Point::origin(), max: Point::new(1000.0, 1000.0) };
    let inner = page::panel_area(probe, true, s);
    let room = sketch::room(s);
    // What a panel takes besides its drawing, mm.
    let fixed = Vector::new(probe.width() - inner.width(), probe.height() - inner.height()) + 2.0 * room;
    let sizes: Vec<Vector> = extents.iter().map(|(lo, hi)| hi - lo).collect();
    let arrangement = |stacked: bool| -> Option<(f64, Vec<Bounds>)> {
        // Along: the direction the panels follow each other; across: the other.
        let split = |v: Vector| if stacked { (v.y, v.x) } else { (v.x, v.y) };
        let (length, breadth) = along_across(region, stacked);
        let (fix_along, fix_across) = if stacked { (fixed.y, fixed.x) } else { (fixed.x, fixed.y) };
        let free_along = length - n as f64 * fix_along;
        let free_across = breadth - fix_across;
        if free_along <= 0.0 || free_across <= 0.0 {
            return None;
        }
        let total: f64 = sizes.iter().map(|v| split(*v).0).sum();
        let raw = sizes.iter().map(|v| split(*v).1 / free_across).fold(total / free_along, f64::max);
        let k = vocab::drafting_scale(raw);
        // Each panel's share of the free length: its group's, or equal for groups of none.
        let shares: Vec<f64> =
            if total > 0.0 { sizes.iter().map(|v| split(*v).0 / total).collect() } else { vec![1.0 / n as f64; n] };
        let mut cells = Vec::with_capacity(n);
        let mut at = if stacked { region.max.y } else { region.min.x };
        for share in shares {
            let len = fix_along + share * free_along;
            let cell = if stacked {
                Bounds { min: Point::new(region.min.x, at - len), max: Point::new(region.max.x, at) }
            } else {
                Bounds { min: Point::new(at, region.min.y), max: Point::new(at + len, region.max.y) }
            };
            at = if stacked { at - len } else { at + len };
            cells.push(cell);
        }
        let captions_fit = cells.iter().zip(captions).all(|(c, w)| *w + 1.2 * s.text <= c.width());
        captions_fit.then_some((k, cells))
    };
    let fallback = || (vocab::drafting_scale(1.0), page::grid(region, n, 1));
    match (arrangement(true), arrangement(false)) {
        (Some(a), Some(b)) => {
            if b.0 < a.0 {
                b
            } else {
                a
            }
        }
        (Some(a), None) | (None, Some(a)) => a,
        (None, None) => fallback(),
    }
}

/// The length of `region` along which panels follow each other (its height when
/// `stacked`, else its width) and its breadth across.
fn along_across(region: Bounds, stacked: bool) -> (f64, f64) {
    if stacked { (region.height(), region.width()) } else { (region.width(), region.height()) }
}

/// The structural analysis page (its title block's cells: the mechanism's and the groups'
/// k_l): the mechanism numbered, the mobility's working, the groups apart ([`layout`]).
pub fn page(frame: &ReportFrame, title: &PageTitle, p: &StructurePage) -> Drawing {
    let s = frame.sizes;
    let lay = layout(frame, p);
    let (mech_panel, at) = lay.mechanism;
    let k_l = lay.groups.first().map_or(at.k_l, |(_, g)| g.k_l);
    let mut title = title.clone();
    title.cells = vec![
        format!("k_l = {} {}/mm", page::plain(at.k_l), p.unit),
        format!("groups: k_l = {} {}/mm", page::plain(k_l), p.unit),
    ];
    let mut d = frame.open_page(&title);
    let area = page::panel(
        &mut d,
        mech_panel,
        &format!("The mechanism, links numbered · k_l = {} {}/mm", page::plain(at.k_l), p.unit),
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
    let area = page::panel(&mut d, lay.text, "Mobility and groups", s);
    let l = page::sheet_layer(&mut d);
    let mut text = mobility_lines(p);
    text.extend(group_lines(p));
    page::lines(&mut d, l, area, &text, TEXT_SIZE * s.text, s);
    // The groups apart, at one scale: in each caption where every caption has room for it,
    // else in the title block only ("groups: k_l = …").
    let scale = format!(" · k_l = {} {}/mm", page::plain(k_l), p.unit);
    let with_scale = p.structure.groups.iter().zip(&lay.groups).all(|(g, (cell, _))| {
        crate::draw::parts::text_width(&format!("{}{scale}", group_caption(g)), s.text) + 1.2 * s.text <= cell.width()
    });
    for (g, (cell, at)) in p.structure.groups.iter().zip(lay.groups) {
        let gs = group_sketch(p.sketch, p.mechanism, g);
        let caption = if with_scale { format!("{}{scale}", group_caption(g)) } else { group_caption(g) };
        let area = page::panel(&mut d, cell, &caption, s);
        sketch::draw(
            &mut d,
            &gs,
            p.q,
            p.motion,
            sketch::Frame { at, sizes: s, area },
            Marks { numbers: true, ..Marks::default() },
        );
    }
    d
}
