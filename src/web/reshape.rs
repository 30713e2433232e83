//! Reshaping by dragging (the page's edit mode): a pivot, a joint or a link's end dragged to
//! a new place changes the dimensions it carries, written into the scene's fields.
//!
//! - Four-bar: O1 and C are `o1` and `c`; the crank pin A sets the crank `l1 = |O1A|`; B
//!   sets `l_ab = |AB|` and `l_bc = |CB|`; M sets `l_bm = |BM|` and `alpha_deg`, the angle
//!   from ray B→A to ray B→M (counter-clockwise, degrees).
//! - Linkage: a ground point is `ground.points.X`. A body point moves with every point
//!   pinned to it (its revolute joints): each body keeps where its frame is at the position
//!   shown and takes the point's new body coordinates there; a body written in its link
//!   frame (its first point at the origin, its second on the x axis, as a drawn link is)
//!   stays so, its frame re-drawn through the moved points and its starting placement
//!   (`at`, `angle_deg`) turned with it. The driven body (the crank) keeps the direction
//!   its driver gives it: its pin sets its length (as the four-bar's A does), its pivot
//!   moves it whole. A one-point body (a slider block) moves its placement with the point.
//!
//! The geometry is that of the position on screen (the drive's state there), so the point
//! ends under the pointer at that position.

use std::collections::BTreeMap;

use super::edit::number;
use crate::figure::shared::animation::DriveState;
use crate::geom::{Point, Vector};

/// Decimals of an angle written by a drag, degrees.
const ANGLE_DECIMALS: usize = 2;

/// The points that can be dragged in edit mode at a position: the state's named points and,
/// for a linkage, its ground points (which the state does not list): (name, model point).
pub fn grips(table: &toml::Table, state: &DriveState) -> Vec<(String, Point)> {
    let mut out = state.points.clone();
    if kind(table) == "linkage" {
        for (name, p) in ground_points(table) {
            out.push((format!("ground.{name}"), p));
        }
    }
    out
}

/// The field changes (`--set` path, value) that put `point` at `target` in the position
/// `state` shows, coordinates and lengths written with `decimals` decimals (the page's grid).
/// A point that carries no dimension, or a kind whose picture is not dragged, is refused
/// with the reason.
pub fn changes(
    table: &toml::Table,
    state: &DriveState,
    point: &str,
    target: Point,
    decimals: usize,
) -> Result<Vec<(String, String)>, String> {
    match kind(table) {
        "fourbar" => fourbar(state, point, target, decimals),
        "linkage" => Linkage::new(table, state).changes(point, target, decimals),
        other => Err(format!("a {other} scene is reshaped through its fields (its picture has no points to drag)")),
    }
}

fn kind(table: &toml::Table) -> &str {
    table.get("kind").and_then(toml::Value::as_str).unwrap_or("")
}

fn at(state: &DriveState, name: &str) -> Result<Point, String> {
    state.points.iter().find(|(n, _)| n == name).map(|(_, p)| *p).ok_or_else(|| format!("no point `{name}`"))
}

fn pair(p: Point, decimals: usize) -> String {
    format!("[{}, {}]", number(p.x, decimals), number(p.y, decimals))
}

fn fourbar(state: &DriveState, point: &str, target: Point, decimals: usize) -> Result<Vec<(String, String)>, String> {
    let len = |p: &str| -> Result<String, String> { Ok(number((target - at(state, p)?).norm(), decimals)) };
    Ok(match point {
        "O1" => vec![("o1".into(), pair(target, decimals))],
        "C" => vec![("c".into(), pair(target, decimals))],
        "A" => vec![("l1".into(), len("O1")?)],
        "B" => vec![("l_ab".into(), len("A")?), ("l_bc".into(), len("C")?)],
        "M" => {
            let b = at(state, "B")?;
            let (ba, bm) = (at(state, "A")? - b, target - b);
            let alpha = libm::atan2(ba.x * bm.y - ba.y * bm.x, ba.dot(&bm)).to_degrees().rem_euclid(360.0);
            vec![("l_bm".into(), len("B")?), ("alpha_deg".into(), number(alpha, ANGLE_DECIMALS))]
        }
        other => return Err(format!("no point `{other}` in the four-bar; its points: O1, A, B, M, C")),
    })
}

/// The scene's ground points, in file order.
fn ground_points(table: &toml::Table) -> Vec<(String, Point)> {
    table
        .get("ground")
        .and_then(|g| g.get("points"))
        .and_then(toml::Value::as_table)
        .map(|t| t.iter().filter_map(|(n, v)| Some((n.clone(), coords(v)?))).collect())
        .unwrap_or_default()
}

/// `[x, y]` of numbers.
pub(super) fn coords(v: &toml::Value) -> Option<Point> {
    let a = v.as_array()?;
    let f = |x: &toml::Value| x.as_float().or_else(|| x.as_integer().map(|i| i as f64));
    Some(Point::new(f(a.first()?)?, f(a.get(1)?)?))
}

/// A body as the scene writes it: its index, name, points in body coordinates (file
/// order), starting placement.
struct Body {
    index: usize,
    name: String,
    points: Vec<(String, Point)>,
    at: Point,
    angle_deg: f64,
}

/// A linkage's bodies, joints and the state shown: what a drag of one point changes.
struct Linkage<'a> {
    bodies: Vec<Body>,
    /// Revolute joints: pairs of `body.point` names that coincide.
    pins: Vec<(String, String)>,
    ground: Vec<(String, Point)>,
    /// The bodies whose angle a driver sets.
    driven: Vec<String>,
    state: &'a DriveState,
}

impl<'a> Linkage<'a> {
    fn new(table: &toml::Table, state: &'a DriveState) -> Linkage<'a> {
        let list = |key: &str| table.get(key).and_then(toml::Value::as_array).cloned().unwrap_or_default();
        let bodies = list("body")
            .iter()
            .enumerate()
            .filter_map(|(index, b)| {
                let points =
                    b.get("points")?.as_table()?.iter().filter_map(|(n, v)| Some((n.clone(), coords(v)?))).collect();
                Some(Body {
                    index,
                    name: b.get("name")?.as_str()?.to_string(),
                    points,
                    at: b.get("at").and_then(coords).unwrap_or(Point::origin()),
                    angle_deg: b
                        .get("angle_deg")
                        .and_then(|a| a.as_float().or(a.as_integer().map(|i| i as f64)))
                        .unwrap_or(0.0),
                })
            })
            .collect();
        let pins = list("joint")
            .iter()
            .filter_map(|j| {
                let r = j.get("revolute")?.as_array()?;
                Some((r.first()?.as_str()?.to_string(), r.get(1)?.as_str()?.to_string()))
            })
            .collect();
        let joints = list("joint");
        let driven = list("driver")
            .iter()
            .filter_map(|d| {
                if let Some(b) = d.get("body").and_then(toml::Value::as_str) {
                    return Some(b.to_string());
                }
                let name = d.get("joint")?.as_str()?;
                let j = joints.iter().find(|j| j.get("name").and_then(toml::Value::as_str) == Some(name))?;
                // Across a revolute the second body turns relative to the first.
                let second = j.get("revolute")?.as_array()?.get(1)?.as_str()?;
                Some(second.split('.').next()?.to_string())
            })
            .collect();
        Linkage { bodies, pins, ground: ground_points(table), driven, state }
    }

    /// Every `body.point` pinned to `name`, itself included (the revolute joints' closure).
    fn pinned(&self, name: &str) -> Vec<String> {
        let mut group = vec![name.to_string()];
        let mut i = 0;
        while i < group.len() {
            for (a, b) in &self.pins {
                for (x, y) in [(a, b), (b, a)] {
                    if *x == group[i] && !group.contains(y) {
                        group.push(y.clone());
                    }
                }
            }
            i += 1;
        }
        group
    }

    fn changes(&self, point: &str, target: Point, decimals: usize) -> Result<Vec<(String, String)>, String> {
        let known = self.state.points.iter().any(|(n, _)| n == point)
            || point.strip_prefix("ground.").is_some_and(|g| self.ground.iter().any(|(n, _)| n == g));
        if !known {
            return Err(format!("no point `{point}` in the linkage"));
        }
        let mut out = Vec::new();
        let mut moved: BTreeMap<usize, Vec<String>> = BTreeMap::new();
        for name in self.pinned(point) {
            let Some((owner, p)) = name.split_once('.') else { continue };
            if owner == "ground" {
                out.push((format!("ground.points.{p}"), pair(target, decimals)));
            } else if let Some(b) = self.bodies.iter().find(|b| b.name == owner) {
                moved.entry(b.index).or_default().push(p.to_string());
            }
        }
        for (index, names) in moved {
            let body = self.bodies.iter().find(|b| b.index == index).ok_or("no body")?;
            out.extend(self.reshape(body, &names, target, decimals)?);
        }
        Ok(out)
    }

    /// The body's changes when its points `names` go to `target`.
    fn reshape(
        &self,
        b: &Body,
        names: &[String],
        target: Point,
        decimals: usize,
    ) -> Result<Vec<(String, String)>, String> {
        let world = |n: &str| at(self.state, &format!("{}.{n}", b.name));
        let key = |n: &str| format!("body[{}].points.{n}", b.index);
        if b.points.len() == 1 {
            // A block: its placement moves with its point.
            let shift = target - world(&b.points[0].0)?;
            return Ok(vec![(format!("body[{}].at", b.index), pair(b.at + shift, decimals))]);
        }
        // Where the body is at the position shown: its frame from two of its points.
        let (p0, p1) = (&b.points[0], &b.points[1]);
        let (w0, w1) = (world(&p0.0)?, world(&p1.0)?);
        let (l, w) = (p1.1 - p0.1, w1 - w0);
        let turn = libm::atan2(w.y, w.x) - libm::atan2(l.y, l.x);
        let to_body = |q: Point| -> Point { p0.1 + rotate(q - w0, -turn) };
        let new_world: Vec<(String, Point)> = b
            .points
            .iter()
            .map(|(n, _)| Ok((n.clone(), if names.contains(n) { target } else { world(n)? })))
            .collect::<Result<_, String>>()?;
        let canonical = p0.1 == Point::origin() && p1.1.y == 0.0 && p1.1.x > 0.0;
        if self.driven.contains(&b.name) {
            // The driver sets its direction: its pivot moves it whole, its pin on the axis
            // sets its length, another point takes its body coordinates.
            return Ok(names
                .iter()
                .filter(|n| **n != p0.0)
                .map(|n| {
                    let local =
                        if canonical && *n == p1.0 { Point::new((target - w0).norm(), 0.0) } else { to_body(target) };
                    (key(n), pair(local, decimals))
                })
                .collect());
        }
        if !canonical {
            // The frame stays; the moved points take their body coordinates there.
            return Ok(names.iter().map(|n| (key(n), pair(to_body(target), decimals))).collect());
        }
        // A link frame: re-drawn through its (moved) first two points.
        let (n0, n1) = (new_world[0].1, new_world[1].1);
        let axis = n1 - n0;
        if axis.norm() == 0.0 {
            return Err(format!("{}'s first two points would coincide", b.name));
        }
        let phi = libm::atan2(axis.y, axis.x);
        let mut out = Vec::new();
        for (i, (n, q)) in new_world.iter().enumerate() {
            let local = match i {
                0 => Point::origin(),
                1 => Point::new(axis.norm(), 0.0),
                _ => Point::origin() + rotate(*q - n0, -phi),
            };
            let old = b.points[i].1;
            let size = axis.norm().max(f64::MIN_POSITIVE);
            if (local - old).norm() > 1e-9 * size {
                out.push((key(n), pair(local, decimals)));
            }
        }
        // The starting placement follows the frame: the new origin and axis seen in the old
        // frame, put where the old frame starts.
        let (o_old, x_old) = (to_body(n0), to_body(n1));
        let delta = libm::atan2((x_old - o_old).y, (x_old - o_old).x);
        if (o_old - Point::origin()).norm() > 0.0 || delta != 0.0 {
            let a0 = b.angle_deg.to_radians();
            out.push((format!("body[{}].at", b.index), pair(b.at + rotate(o_old.coords, a0), decimals)));
            out.push((
                format!("body[{}].angle_deg", b.index),
                number(b.angle_deg + delta.to_degrees(), ANGLE_DECIMALS),
            ));
        }
        Ok(out)
    }
}

/// `v` turned by `a` radians counter-clockwise.
fn rotate(v: Vector, a: f64) -> Vector {
    let (s, c) = (libm::sin(a), libm::cos(a));
    Vector::new(c * v.x - s * v.y, s * v.x + c * v.y)
}

#[cfg(test)]
#[allow(
    clippy::disallowed_methods,
    reason = "expected values and test data from std's math: independent of the libm the code under test calls"
)]
mod tests {
    use super::*;
    use crate::web::Session;

    fn session(name: &str) -> (Session, toml::Table) {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("templates").join(name);
        let text = std::fs::read_to_string(path).unwrap();
        (Session::new(&text, name).unwrap(), text.parse().unwrap())
    }

    #[test]
    fn dragging_the_four_bars_b_sets_both_links_it_joins() {
        let (s, t) = session("fourbar-chebyshev.toml");
        let st = s.points(90).unwrap();
        let ch = changes(&t, &st, "B", Point::new(0.05, 0.12), 4).unwrap();
        let a = at(&st, "A").unwrap();
        let expect_ab = number((Point::new(0.05, 0.12) - a).norm(), 4);
        assert_eq!(ch, vec![("l_ab".into(), expect_ab), ("l_bc".into(), number((0.03f64).hypot(0.12), 4))]);
        assert_eq!(
            changes(&t, &st, "C", Point::new(0.09, 0.005), 4).unwrap(),
            vec![("c".into(), "[0.09, 0.005]".into())]
        );
        // M straight on from B along AB: alpha 180°.
        let b = at(&st, "B").unwrap();
        let m = b + (b - a);
        let ch = changes(&t, &st, "M", m, 4).unwrap();
        assert_eq!(ch[1], ("alpha_deg".to_string(), "180.0".to_string()));
    }

    #[test]
    fn a_coupler_point_dragged_lands_under_the_pointer() {
        let (mut s, t) = session("fourbar-linkage.toml");
        let k = 40;
        let st = s.points(k).unwrap();
        let m = at(&st, "coupler.M").unwrap();
        let target = Point::new(m.x + 0.01, m.y - 0.02);
        let ch = changes(&t, &st, "coupler.M", target, 7).unwrap();
        assert!(ch.iter().all(|(p, _)| p == "body[1].points.M"), "{ch:?}");
        s.set_many(&ch).unwrap();
        let after = s.points(k).unwrap();
        assert!((at(&after, "coupler.M").unwrap() - target).norm() < 1e-7, "M under the pointer");
        for n in ["coupler.A", "coupler.B", "rocker.B"] {
            assert!((at(&after, n).unwrap() - at(&st, n).unwrap()).norm() < 1e-9, "{n} stays");
        }
    }

    #[test]
    fn a_crank_pin_dragged_sets_the_cranks_length_and_the_rod_follows() {
        let (mut s, t) = session("slider-crank.toml");
        let k = 30;
        let st = s.points(k).unwrap();
        let (o, a) = (at(&st, "crank.O").unwrap(), at(&st, "crank.A").unwrap());
        let target = a + (a - o) * 0.1 + Vector::new(0.0, 3.0);
        let ch = changes(&t, &st, "crank.A", target, 3).unwrap();
        let length = number((target - o).norm(), 3);
        assert!(ch.contains(&("body[0].points.A".to_string(), format!("[{length}, 0.0]"))), "{ch:?}");
        s.set_many(&ch).unwrap();
        let after = s.points(k).unwrap();
        let (o2, a2) = (at(&after, "crank.O").unwrap(), at(&after, "crank.A").unwrap());
        assert!(((a2 - o2).norm() - length.parse::<f64>().unwrap()).abs() < 1e-9);
        assert!((at(&after, "rod.A").unwrap() - a2).norm() < 1e-9, "the rod stays pinned");
        // The driver's direction is kept.
        let dir = |p: Point, q: Point| libm::atan2(q.y - p.y, q.x - p.x);
        assert!((dir(o2, a2) - dir(o, a)).abs() < 1e-9);
    }
}
