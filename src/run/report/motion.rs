//! The report of a mechanism in motion (a four-bar or a linkage): the parts every such
//! report has, from what its kind's module gathers — the title page, the structural
//! analysis, the kinematic diagram, the plan of positions, the chosen positions' pages and
//! the diagrams — and the choice of positions (`--positions`, or four evenly spaced and
//! the dead positions; twelve on the plan).

use super::{Frame, Part};
use crate::Error;
use crate::draw::Drawing;
use crate::figure::report::diagrams::{self, MarkedDiagram, PER_PAGE};
use crate::figure::report::kinematic::{self, KinematicPage};
use crate::figure::report::plan::{self, PlanDimension, PlanPage};
use crate::figure::report::sketch::Sketch;
use crate::figure::report::structure::{self as structure_page, StructurePage};
use crate::figure::report::table::PaperTable;
use crate::geom::Point;
use crate::run::positions::Positions;
use crate::solve::linkage::{Anchor, Mechanism, Structure};

/// Positions on the plan when none are asked for.
pub const PLAN_POSITIONS: usize = 12;
/// Evenly spaced positions analysed when none are asked for (besides the dead positions).
pub const CHOSEN_POSITIONS: usize = 4;
/// A value asked for is the sample's when within this fraction of a step of it
/// (`--positions`' own tolerance).
pub use crate::run::positions::MATCH;

pub use crate::run::positions::DriveAxis;

/// A value of the drive as the messages and labels write it (`30°`, `0.25 s`).
pub fn text(axis: DriveAxis, v: f64) -> String {
    format!("{}{}", trimmed(v), axis.unit)
}

/// A number in at most 6 decimals, trailing zeros dropped.
pub fn trimmed(v: f64) -> String {
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.to_string() }
}

/// How the samples cover the drive's cycle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Cycle {
    /// The last sample repeats the first (a linkage over one turn: t = 0 … 1 s).
    Closes,
    /// The samples cover a whole turn without repeating (a four-bar's 0 … 359°).
    Whole,
    /// Less (or more) than one turn: the ends are both positions of the plan.
    Open,
}

/// `count` sample indices of `n` evenly spaced over the cycle.
pub fn evenly(n: usize, count: usize, cycle: Cycle) -> Vec<usize> {
    if n == 0 || count == 0 {
        return Vec::new();
    }
    let count = count.min(n);
    let mut out: Vec<usize> = match cycle {
        Cycle::Closes if n > 1 => (0..count).map(|i| (i * (n - 1) + count / 2) / count).collect(),
        Cycle::Whole | Cycle::Closes => (0..count).map(|i| (i * n + count / 2) / count).collect(),
        Cycle::Open if count == 1 => vec![0],
        Cycle::Open => (0..count).map(|i| (i * (n - 1) + (count - 1) / 2) / (count - 1)).collect(),
    };
    out.dedup();
    out
}

/// Where a chosen position is: a sample of the run, or an exact position the report solved
/// (a dead position), by index into the kind's extra positions.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum At {
    /// The run's sample.
    Sample(usize),
    /// The kind's extra position.
    Exact(usize),
}

/// A position the report analyses.
#[derive(Debug, Clone, PartialEq)]
pub struct Chosen {
    /// Where it is.
    pub at: At,
    /// The drive's value there.
    pub drive: f64,
    /// Its number on the plan and the diagrams (`1`, `2`, … ; `I`, `II` for dead positions).
    pub mark: String,
    /// Where it is (`φ1 = 30°`, `t = 0.25 s`).
    pub label: String,
    /// What it is besides (`dead position: the rocker's extreme, …`; on a sample that is a
    /// dead position, `dead position I: …`), or empty.
    pub note: String,
    /// Its pages' stem (`pos-030`, `dead-1`).
    pub stem: String,
}

/// A dead position the kind found: its drive value, its name, its coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct Dead {
    /// The drive's value (exact).
    pub drive: f64,
    /// What it is (`left extreme of the ram E`).
    pub what: String,
    /// The coordinates (x, y, φ per body).
    pub q: Vec<f64>,
}

/// The positions to analyse: those asked for (`--positions`, read as `mechdraw run` reads
/// it: a list, each a sample of the run within [`MATCH`] of a step, in the order given, or
/// `every=Δ`) or [`CHOSEN_POSITIONS`] evenly spaced; then the dead positions (unless
/// positions were asked for). Errors name `--positions`, what is wrong and what the run has.
pub fn choose(
    values: &[f64],
    axis: DriveAxis,
    cycle: Cycle,
    asked: Option<&Positions>,
    dead: &[Dead],
) -> Result<Vec<Chosen>, Error> {
    let bad = |message: String| Error::Option { option: "--positions".into(), message };
    let (Some(&first), Some(&last)) = (values.first(), values.last()) else {
        return Err(bad("the run has no position to analyse".into()));
    };
    let range = format!(
        "the run's {} goes from {} to {} in steps of {}",
        axis.name,
        text(axis, first),
        text(axis, last),
        text(axis, axis.step)
    );
    let sample = |k: usize, n: usize| Chosen {
        at: At::Sample(k),
        drive: values[k],
        mark: n.to_string(),
        label: format!("{} = {}", symbol(axis), text(axis, values[k])),
        note: String::new(),
        stem: format!("pos-{}", trimmed(values[k]).replace(['.', '-'], "_")),
    };
    let mut out = Vec::new();
    match asked {
        Some(Positions::List(list)) if list.is_empty() => {
            return Err(bad(format!("the list is empty: give positions such as {}", example(values, axis))));
        }
        Some(p) => {
            let tol = MATCH * axis.step;
            if let Positions::List(list) = p {
                let (lo, hi) = (first.min(last), first.max(last));
                for &v in list {
                    if !(v >= lo - tol && v <= hi + tol) {
                        return Err(bad(format!("{} = {} is outside the motion: {range}", axis.name, text(axis, v))));
                    }
                }
            }
            let picked = p.select(values, axis).map_err(bad)?;
            for (i, &k) in picked.iter().enumerate() {
                if picked[..i].contains(&k) {
                    return Err(bad(format!("{} is listed twice: give each position once", text(axis, values[k]))));
                }
                out.push(sample(k, i + 1));
            }
            if out.is_empty() {
                return Err(bad(format!("no position of the run is asked for: {range}")));
            }
        }
        None => {
            for (i, k) in evenly(values.len(), CHOSEN_POSITIONS, cycle).into_iter().enumerate() {
                out.push(sample(k, i + 1));
            }
            for (i, d) in dead.iter().enumerate() {
                let roman = crate::solve::linkage::structure::roman(i as u32 + 1);
                // A dead position on a chosen sample is that sample's page.
                if let Some(c) = out.iter_mut().find(|c| (c.drive - d.drive).abs() <= MATCH * axis.step) {
                    c.note = format!("dead position {roman}: {}", d.what);
                    continue;
                }
                out.push(Chosen {
                    at: At::Exact(i),
                    drive: d.drive,
                    mark: roman.clone(),
                    label: format!("{} = {}", symbol(axis), text(axis, (d.drive * 1e4).round() / 1e4)),
                    note: format!("dead position: {}", d.what),
                    stem: format!("dead-{}", i + 1),
                });
            }
        }
    }
    Ok(out)
}

/// The positions to analyse ([`choose`]) and the plan's: the samples asked for, or
/// [`PLAN_POSITIONS`] evenly spaced, numbered from the returned first number (1 for
/// positions asked for, else 0); each chosen sample on the plan marked with its number.
pub fn choose_with_plan(
    values: &[f64],
    axis: DriveAxis,
    cycle: Cycle,
    asked: Option<&Positions>,
    dead: &[Dead],
) -> Result<(Vec<Chosen>, Vec<usize>, usize), Error> {
    let mut chosen = choose(values, axis, cycle, asked, dead)?;
    let plan: Vec<usize> = match asked {
        Some(_) => chosen.iter().filter_map(|c| if let At::Sample(k) = c.at { Some(k) } else { None }).collect(),
        None => evenly(values.len(), PLAN_POSITIONS, cycle),
    };
    let base = usize::from(asked.is_some());
    for c in &mut chosen {
        if let At::Sample(k) = c.at
            && let Some(i) = plan.iter().position(|&p| p == k)
        {
            c.mark = (i + base).to_string();
        }
    }
    Ok((chosen, plan, base))
}

/// The drive's symbol (`φ1`, `t`).
fn symbol(axis: DriveAxis) -> &'static str {
    axis.name.rsplit(' ').next().unwrap_or(axis.name)
}

/// An example list of positions of the run, for messages.
fn example(values: &[f64], axis: DriveAxis) -> String {
    evenly(values.len(), 3, Cycle::Whole).iter().map(|&k| trimmed(values[k])).collect::<Vec<_>>().join(",")
        + &format!(" ({})", axis.name)
}

/// What a motion report is made of, gathered by its kind.
pub struct MotionReport<'a> {
    /// The frame and the title block's texts.
    pub frame: Frame,
    /// The title page's heading, subject line and data.
    pub title: (String, String, PaperTable),
    /// The mechanism as drawn.
    pub sketch: Sketch,
    /// The solver's mechanism.
    pub mechanism: Mechanism,
    /// Its structure.
    pub structure: Structure,
    /// Every sample's coordinates.
    pub motion: Vec<Vec<f64>>,
    /// The positions of the plan: (number, coordinates).
    pub plan: Vec<(String, Vec<f64>)>,
    /// The dead positions: (name, coordinates) as the plan draws them.
    pub dead: Vec<(String, Vec<f64>)>,
    /// Where the plan numbers its positions.
    pub numbered: Option<Anchor>,
    /// The plan's dimensions and notes.
    pub dimensions: Vec<PlanDimension>,
    /// The plan's notes.
    pub notes: Vec<String>,
    /// The kinematic diagram's position label and lists.
    pub kinematic: (String, Vec<String>),
    /// The drafting scale the kinematic diagram and the position pages' mechanism share
    /// (the coarser of their own), when the kind holds one.
    pub drafting: Option<f64>,
    /// The length unit.
    pub unit: &'static str,
    /// The chosen positions.
    pub chosen: Vec<Chosen>,
    /// Pages per chosen position.
    pub position_pages: usize,
    /// Draws a chosen position's pages given its first page's number and the total.
    #[allow(clippy::type_complexity)]
    pub draw_position: Box<dyn Fn(&Chosen, usize, usize) -> Result<Vec<Drawing>, Error> + Sync + 'a>,
    /// The diagrams, each with the point of every chosen position on its paper.
    pub diagrams: Vec<MarkedDiagram>,
}

/// The parts of a motion report.
pub fn parts<'a>(r: &'a MotionReport<'a>) -> Vec<Part<'a>> {
    let f = &r.frame;
    let mut parts: Vec<Part<'a>> = Vec::new();
    parts.push(super::title_part(f.clone(), r.title.0.clone(), r.title.1.clone(), r.title.2.clone()));
    let q0: &[f64] = r.plan.first().map_or(&[][..], |(_, q)| q.as_slice());
    let refs: Vec<&[f64]> = r.motion.iter().map(Vec::as_slice).collect();
    let refs = std::sync::Arc::new(refs);
    {
        let refs = refs.clone();
        parts.push(Part {
            title: "Structural analysis".into(),
            stem: "structure".into(),
            pages: 1,
            draw: Box::new(move |n| {
                let p = StructurePage {
                    sketch: &r.sketch,
                    mechanism: &r.mechanism,
                    structure: &r.structure,
                    q: q0,
                    motion: &refs,
                    unit: r.unit,
                };
                Ok(vec![structure_page::page(&f.frame, &f.title("2  Structural analysis", n.first, n.total), &p)])
            }),
        });
    }
    {
        let refs = refs.clone();
        parts.push(Part {
            title: "Kinematic diagram".into(),
            stem: "kinematic".into(),
            pages: 1,
            draw: Box::new(move |n| {
                let p = KinematicPage {
                    sketch: &r.sketch,
                    q: q0,
                    motion: &refs,
                    position: r.kinematic.0.clone(),
                    unit: r.unit,
                    lists: r.kinematic.1.clone(),
                    held: r.drafting,
                };
                Ok(vec![kinematic::page(&f.frame, &f.title("3  Kinematic diagram", n.first, n.total), &p).0])
            }),
        });
    }
    {
        let refs = refs.clone();
        parts.push(Part {
            title: "Plan of positions".into(),
            stem: "plan".into(),
            pages: 1,
            draw: Box::new(move |n| {
                let p = PlanPage {
                    sketch: &r.sketch,
                    motion: &refs,
                    plan: r.plan.clone(),
                    dead: r.dead.clone(),
                    numbered: r.numbered,
                    dimensions: r.dimensions.clone(),
                    notes: r.notes.clone(),
                    unit: r.unit,
                };
                Ok(vec![plan::page(&f.frame, &f.title("4  Plan of positions", n.first, n.total), &p).0])
            }),
        });
    }
    for (i, c) in r.chosen.iter().enumerate() {
        parts.push(Part {
            title: if c.note.is_empty() {
                format!("Position {}: {}", c.mark, c.label)
            } else {
                format!("Position {}: {} ({})", c.mark, c.label, c.note)
            },
            stem: c.stem.clone(),
            pages: r.position_pages,
            draw: Box::new(move |n| {
                let _ = i;
                (r.draw_position)(c, n.first, n.total)
            }),
        });
    }
    let chunks: Vec<&[MarkedDiagram]> = r.diagrams.chunks(PER_PAGE).collect();
    if !chunks.is_empty() {
        let count = chunks.len();
        parts.push(Part {
            title: "Diagrams over the cycle".into(),
            stem: "diagrams".into(),
            pages: count,
            draw: Box::new(move |n| {
                Ok(chunks
                    .iter()
                    .enumerate()
                    .map(|(k, ds)| {
                        let part = format!("6  Diagrams over the cycle ({} of {count})", k + 1);
                        diagrams::page(&f.frame, &f.title(&part, n.first + k, n.total), ds).0
                    })
                    .collect())
            }),
        });
    }
    parts
}

/// The points of the chosen positions on a diagram: for each, where `place` puts it, with
/// its mark.
pub fn marks(chosen: &[Chosen], place: impl Fn(&Chosen) -> Option<Point>) -> Vec<(Point, String)> {
    chosen.iter().filter_map(|c| place(c).map(|p| (p, c.mark.clone()))).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const DEG: DriveAxis = DriveAxis { name: "crank angle φ1", unit: "°", step: 1.0 };

    #[test]
    fn evenly_spaced_positions_cover_the_cycle() {
        assert_eq!(evenly(360, 12, Cycle::Whole), (0..12).map(|i| 30 * i).collect::<Vec<_>>());
        assert_eq!(evenly(361, 4, Cycle::Closes), vec![0, 90, 180, 270]);
        assert_eq!(evenly(101, 3, Cycle::Open), vec![0, 50, 100]);
        assert_eq!(evenly(2, 12, Cycle::Whole), vec![0, 1]);
    }

    #[test]
    fn positions_asked_for_are_samples_inside_the_motion_once_each() {
        let values: Vec<f64> = (0..360).map(f64::from).collect();
        let c = choose(&values, DEG, Cycle::Whole, Some(&Positions::List(vec![90.0, 0.0])), &[]).unwrap();
        assert_eq!(c.iter().map(|c| c.at).collect::<Vec<_>>(), vec![At::Sample(90), At::Sample(0)]);
        assert_eq!(c[0].label, "φ1 = 90°");
        let msg = |asked: &[f64]| {
            choose(&values, DEG, Cycle::Whole, Some(&Positions::List(asked.to_vec())), &[]).unwrap_err().to_string()
        };
        let e = msg(&[400.0]);
        assert!(
            e.contains("--positions")
                && e.contains("400°")
                && e.contains("outside the motion")
                && e.contains("from 0° to 359°"),
            "{e}"
        );
        assert!(msg(&[30.0, 30.0000000001]).contains("listed twice"));
        assert!(msg(&[]).contains("empty"));
        let e = msg(&[45.5]);
        assert!(e.contains("nearest is 45°") || e.contains("nearest is 46°"), "{e}");
        // The default: four evenly spaced, then the dead positions.
        let dead = [Dead { drive: 33.5, what: "x".into(), q: vec![] }];
        let c = choose(&values, DEG, Cycle::Whole, None, &dead).unwrap();
        assert_eq!(c.len(), 5);
        assert_eq!((c[4].at, c[4].mark.as_str()), (At::Exact(0), "I"));
    }
}
