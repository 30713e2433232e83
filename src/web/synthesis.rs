//! A synthesis scene's construction dragged (the page's edit mode on a still picture): the
//! lettered points that carry a requirement or a free choice, and the fields a drag of one
//! of them changes. The construction is solved again and redrawn; ψ, K and H, which no
//! point carries alone, change through their fields.
//!
//! The points are where the construction draws them (model units, the drawing's own frame:
//! the solvers' design frames, docs/synthesis.md), and a drag keeps what it does not change
//! fixed in that frame, so the point stays under the pointer:
//!
//! | task | point | changes |
//! |---|---|---|
//! | `crank-rocker` | C (O1 at the origin, C on +x) | `ground` = O1C (the free choice; `extreme_to_ground_deg` is dropped) |
//! | `slider-crank` | B1, B2 (the guide at y = −e) | `offset` e |
//! | `quick-return` | O1 (O3 at the origin, O1 on +y) | `ground` = O1O3, or `crank` = O1O3·sin(θ/2) when the crank is given |
//! | `quick-return` | E1, E2 (the ram's extremes) | `ram_height` |
//! | `motion` | P1, P2, P3 | `positions[i].at` |
//! | `motion` | the end of each position's line | `positions[i].angle_deg` |
//! | `motion` | A1, B1 | `a1`, `b1` |
//! | `function` | C (O1 at the origin) | `ground` |

use super::edit::{self, number};
use super::reshape::pair;
use crate::Error;
use crate::geom::{Point, Vector, angle_of};
use crate::scene::synthesis::{SynthesisScene, Task};
use crate::solve::synthesis::{self, crank_rocker, quick_return, slider_crank};

/// Decimals of an angle written by a drag, degrees.
const ANGLE_DECIMALS: usize = 2;

/// The name of the grip at the far end of position `i`'s line (0-based).
fn line_end(i: usize) -> String {
    format!("P{} line", i + 1)
}

/// The points of the construction a drag changes, (name, model point); empty when the
/// requirement cannot be met (the page then shows the message and keeps its picture).
pub fn grips(scene: &SynthesisScene) -> Vec<(String, Point)> {
    let named = |list: &[(&str, Point)]| list.iter().map(|(n, p)| (n.to_string(), *p)).collect();
    match &scene.task {
        Task::CrankRocker(r) => {
            crank_rocker::synthesise(r).map(|s| named(&[("C", s.design.pivot_c)])).unwrap_or_default()
        }
        Task::SliderCrank(r) => {
            slider_crank::synthesise(r).map(|s| named(&[("B1", s.design.b1), ("B2", s.design.b2)])).unwrap_or_default()
        }
        Task::QuickReturn(r) => quick_return::synthesise(r)
            .map(|d| named(&[("O1", d.o1), ("E1", d.e[0]), ("E2", d.e[1])]))
            .unwrap_or_default(),
        Task::Motion(r) => {
            let half = line_half(r.a1, r.b1);
            let mut out: Vec<(String, Point)> = Vec::new();
            for (i, p) in r.poses.iter().enumerate() {
                out.push((format!("P{}", i + 1), p.at));
                out.push((line_end(i), p.at + unit(p.angle) * half));
            }
            out.extend([("A1".to_string(), r.a1), ("B1".to_string(), r.b1)]);
            out
        }
        Task::Function { requirement, .. } => named(&[("C", Point::new(requirement.ground, 0.0))]),
    }
}

/// Half the drawn length of a position's line: 0.3·A1B1, as the construction draws it
/// (figure::synthesis::motion).
fn line_half(a1: Point, b1: Point) -> f64 {
    0.3 * (b1 - a1).norm()
}

fn unit(angle: f64) -> Vector {
    Vector::new(libm::cos(angle), libm::sin(angle))
}

/// The scene's text after `point` is dragged to `target` (model units), numbers written with
/// `decimals` decimals (the page's grid): the fields the point carries changed, every other
/// byte kept. A point the construction does not let a drag move is refused with the reason.
pub fn reshape(
    text: &str,
    file: &str,
    scene: &SynthesisScene,
    point: &str,
    target: Point,
    decimals: usize,
) -> Result<String, String> {
    let (set, drop) = changes(scene, point, target, decimals)?;
    let mut doc = edit::document(text, file).map_err(|e| e.to_string())?;
    for key in drop {
        doc.remove(key);
    }
    edit::set(&doc.to_string(), file, &set).map_err(|e: Error| e.to_string())
}

/// A drag's (`--set` path, value) changes and the top-level keys it drops.
type Changes = (Vec<(String, String)>, Vec<&'static str>);

/// The drag's changes.
fn changes(scene: &SynthesisScene, point: &str, target: Point, decimals: usize) -> Result<Changes, String> {
    let n = |v: f64| number(v, decimals);
    let one = |path: &str, v: String| vec![(path.to_string(), v)];
    let names = || grips(scene).into_iter().map(|(n, _)| n).collect::<Vec<_>>().join(", ");
    let refuse = || {
        Err(format!(
            "`{point}` carries nothing a drag changes in a {} synthesis; its points: {} (ψ, K and H change in their fields)",
            scene.task.name(),
            names()
        ))
    };
    let positive = |what: &str, v: f64| {
        if v > 0.0 { Ok(v) } else { Err(format!("{what} would be {} ≤ 0: drag the other way", n(v))) }
    };
    Ok(match (&scene.task, point) {
        (Task::CrankRocker(_), "C") => {
            (one("ground", n(positive("the ground O1C", target.x)?)), vec!["extreme_to_ground_deg"])
        }
        (Task::SliderCrank(_), "B1" | "B2") => (one("offset", n(positive("the offset e", -target.y)?)), vec![]),
        (Task::QuickReturn(r), "O1") => {
            let d = positive("the ground O1O3", target.y)?;
            match r.size {
                quick_return::Size::Ground(_) => (one("ground", n(d)), vec![]),
                quick_return::Size::Crank(_) => {
                    let theta = synthesis::excess_angle(r.time_ratio).map_err(|e| e.to_string())?;
                    (one("crank", n(d * libm::sin(theta / 2.0))), vec![])
                }
            }
        }
        (Task::QuickReturn(_), "E1" | "E2") => (one("ram_height", n(target.y)), vec![]),
        (Task::Motion(_), "A1") => (one("a1", pair(target, decimals)), vec![]),
        (Task::Motion(_), "B1") => (one("b1", pair(target, decimals)), vec![]),
        (Task::Motion(r), p) => {
            let i = (0..r.poses.len()).find(|&i| p == format!("P{}", i + 1) || p == line_end(i));
            let Some(i) = i else { return refuse() };
            if p == line_end(i) {
                let angle = angle_of(target - r.poses[i].at).to_degrees();
                let angle = if angle > 180.0 { angle - 360.0 } else { angle };
                (one(&format!("positions[{i}].angle_deg"), number(angle, ANGLE_DECIMALS)), vec![])
            } else {
                (one(&format!("positions[{i}].at"), pair(target, decimals)), vec![])
            }
        }
        (Task::Function { .. }, "C") => (one("ground", n(positive("the ground O1C", target.x)?)), vec![]),
        _ => return refuse(),
    })
}
