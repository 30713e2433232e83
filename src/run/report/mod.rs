//! `mechdraw report`: the graph-analytical report a student hands in (issue 33), as pages
//! ([`crate::figure::report`]) of one PDF and the same pages as SVG, with the table of the
//! chosen positions' values and a JSON summary of what is where.
//!
//! The parts, in order (a kind has those that make sense for it):
//! 1. the title page; 2. the structural analysis; 3. the kinematic diagram; 4. the plan of
//!    positions; 5. the chosen positions, a set of pages each; 6. the diagrams over the
//!    cycle — for four-bar and linkage scenes;
//! - a triad's: the title page, its structure (class III, a structure of mobility 0), the
//!   pattern method's iterations as seed 000 draws them, its assembly modes;
//! - a chain's: the title page, seed 001's matrix N and the check, the dimensional
//!   functions, the stack-up with its histograms.
//!
//! Each kind's module gathers its parts ([`Part`]: a title, a page count, and the function
//! that draws its pages once their numbers are known); [`report`] numbers them, draws them in
//! parallel and hands back a [`Report`]. Nothing here writes a file ([`super::bytes`] does).

mod chain;
mod fourbar;
mod linkage;
mod motion;
mod triad;

use crate::par::prelude::*;

use super::positions::Positions;
use super::products::Page;
use crate::Error;
use crate::draw::Drawing;
use crate::figure::report::page::{PageTitle, ReportFrame};
use crate::figure::report::table::PaperTable;
use crate::figure::report::title::{self, TitlePage};
use crate::figure::shared::sheet::Paper;
use crate::report::Csv;
use crate::scene::{Loaded, Scene};

/// What the user asked of the report.
#[derive(Debug, Clone, PartialEq)]
pub struct ReportOptions {
    /// The paper, landscape.
    pub paper: Paper,
    /// The positions to analyse (`--positions`, as `mechdraw run` reads it: values of the
    /// motion's drive — crank angles in degrees for a four-bar, times in seconds for a
    /// linkage — or `every=Δ`); `None`: the report's choice (four evenly spaced and the dead
    /// positions), and twelve on the plan.
    pub positions: Option<Positions>,
}

impl Default for ReportOptions {
    fn default() -> Self {
        ReportOptions { paper: Paper::A4, positions: None }
    }
}

/// The report of one scene.
#[derive(Debug)]
pub struct Report {
    /// The scene's name: the stem of every file.
    pub name: String,
    /// The pages, in order (stems `01-title`, `02-structure`, …).
    pub pages: Vec<Page>,
    /// The parts: (title, first page).
    pub parts: Vec<(String, usize)>,
    /// The chosen positions' values (`<name>-report.csv`); empty for a triad or a chain.
    pub table: Option<Csv>,
    /// What is where (`<name>-report.json`).
    pub summary: serde_json::Value,
    /// Warnings (a dead position that could not be solved, …).
    pub warnings: Vec<String>,
}

/// What a page's drawing function is told: its number and the report's, and the contents.
#[derive(Debug, Clone, Copy)]
pub struct Numbers<'a> {
    /// The part's first page (from 1).
    pub first: usize,
    /// Pages in the report.
    pub total: usize,
    /// The report's parts: (title, first page).
    pub contents: &'a [(String, usize)],
}

/// One part of the report: its title, how many pages it has, and how it draws them.
pub struct Part<'a> {
    /// The title (`Structural analysis`), numbered in the contents.
    pub title: String,
    /// The stem of its pages' files (`structure`; several pages get `-1`, `-2`, …).
    pub stem: String,
    /// Its page count.
    pub pages: usize,
    /// Draws its pages (exactly `pages` of them) given their numbers.
    #[allow(clippy::type_complexity)]
    pub draw: Box<dyn Fn(Numbers<'_>) -> Result<Vec<Drawing>, Error> + Sync + 'a>,
}

/// The title page's part (every kind's first): `heading`, `subject` and the `data` table,
/// with the report's contents.
pub fn title_part<'a>(frame: Frame, heading: String, subject: String, data: PaperTable) -> Part<'a> {
    Part {
        title: "Title page".into(),
        stem: "title".into(),
        pages: 1,
        draw: Box::new(move |n: Numbers<'_>| {
            let t = TitlePage {
                heading: heading.clone(),
                subject: subject.clone(),
                data: data.clone(),
                contents: n.contents.to_vec(),
            };
            Ok(vec![title::page(&frame.frame, &frame.title("1  Title page", n.first, n.total), &t)])
        }),
    }
}

/// The frame and the title block's fixed texts, shared by every page.
#[derive(Debug, Clone)]
pub struct Frame {
    /// Where everything goes on a page.
    pub frame: ReportFrame,
    /// The scene's name.
    pub name: String,
    /// What it is (`four-bar`).
    pub subject: String,
    /// The scene file.
    pub file: String,
}

impl Frame {
    /// The title block of page `page` (from 1) of `total`, for part `part`.
    pub fn title(&self, part: &str, page: usize, total: usize) -> PageTitle {
        PageTitle {
            name: self.name.clone(),
            subject: self.subject.clone(),
            part: part.to_string(),
            file: self.file.clone(),
            cells: Vec::new(),
            page: (page, total),
        }
    }
}

/// The report of `loaded`.
pub fn report(loaded: &Loaded, opts: &ReportOptions) -> Result<Report, Error> {
    let file = loaded.path.display().to_string();
    let frame = |subject: &str| Frame {
        frame: ReportFrame::new(opts.paper),
        name: loaded.scene.name().to_string(),
        subject: subject.to_string(),
        file: file.clone(),
    };
    if opts.positions.is_some() && matches!(loaded.scene, Scene::Triad(_) | Scene::Chain(_)) {
        return Err(Error::Option {
            option: "--positions".into(),
            message: format!(
                "a {} scene has no motion to choose positions of: {file} is reported whole (leave out --positions)",
                loaded.scene.kind()
            ),
        });
    }
    // Before solving: a mistyped step is refused at once, as `mechdraw run` refuses it.
    super::check_positions(&loaded.scene, &file)?;
    let name = loaded.scene.name();
    match &loaded.scene {
        Scene::Fourbar(s) => {
            let (r, table, summary, warnings) = fourbar::motion_report(s, &file, opts, frame("four-bar"))?;
            assemble(name, opts.paper, Gathered { parts: motion::parts(&r), table: Some(table), summary, warnings })
        }
        Scene::Linkage(s) if linkage::is_redundant(s) => {
            assemble(name, opts.paper, linkage::structure_report(s, &file, opts, frame("linkage"))?)
        }
        Scene::Linkage(s) => {
            let (r, table, summary, warnings) = linkage::motion_report(s, &file, opts, frame("linkage"))?;
            assemble(name, opts.paper, Gathered { parts: motion::parts(&r), table: Some(table), summary, warnings })
        }
        Scene::Triad(s) => assemble(name, opts.paper, triad::gather(s, &file, frame("triad"))?),
        Scene::Chain(s) => assemble(name, opts.paper, chain::gather(s, &file, frame("dimensional chain"))?),
        // A synthesis's analysis is its design's: the report is the design scene's.
        Scene::Synthesis(_) => Err(Error::Option {
            option: "report".into(),
            message: format!(
                "{file} is a synthesis scene: `mechdraw run {file}` writes the mechanism it designs as {name}-design.toml; report that scene (mechdraw report {name}-design.toml)"
            ),
        }),
    }
}

/// What a kind's module gathers: the parts, the table of the chosen positions, the summary's
/// kind-specific part, warnings.
pub struct Gathered<'a> {
    /// The parts in order.
    pub parts: Vec<Part<'a>>,
    /// The chosen positions' values.
    pub table: Option<Csv>,
    /// The kind's part of the summary (positions, structure …).
    pub summary: serde_json::Value,
    /// Warnings.
    pub warnings: Vec<String>,
}

/// Numbers the parts, draws their pages in parallel, names them.
fn assemble(name: &str, paper: Paper, g: Gathered<'_>) -> Result<Report, Error> {
    let mut contents = Vec::with_capacity(g.parts.len());
    let mut next = 1;
    for p in &g.parts {
        contents.push((p.title.clone(), next));
        next += p.pages;
    }
    let total = next - 1;
    let drawn: Vec<Vec<Drawing>> = g
        .parts
        .par_iter()
        .zip(&contents)
        .map(|(p, (_, first))| {
            let pages = (p.draw)(Numbers { first: *first, total, contents: &contents })?;
            if pages.len() != p.pages {
                return Err(Error::Export {
                    what: format!("{name}-report.pdf"),
                    message: format!("part {} drew {} pages, not {}", p.title, pages.len(), p.pages),
                });
            }
            Ok(pages)
        })
        .collect::<Result<_, Error>>()?;
    let mut pages = Vec::with_capacity(total);
    for ((p, (_, first)), drawings) in g.parts.iter().zip(&contents).zip(drawn) {
        let many = drawings.len() > 1;
        for (k, drawing) in drawings.into_iter().enumerate() {
            let number = first + k;
            let stem =
                if many { format!("{number:02}-{}-{}", p.stem, k + 1) } else { format!("{number:02}-{}", p.stem) };
            pages.push(Page {
                stem,
                drawing,
                window: paper.bounds(),
                hairline_mm: crate::figure::report::page::HAIRLINE_MM,
            });
        }
    }
    let summary = serde_json::json!({
        "name": name,
        "pages": total,
        "parts": contents.iter().map(|(t, first)| serde_json::json!({"title": t, "first_page": first})).collect::<Vec<_>>(),
        "kind": g.summary,
    });
    Ok(Report { name: name.to_string(), pages, parts: contents, table: g.table, summary, warnings: g.warnings })
}
